# SPDX-License-Identifier: BSD-3-Clause
"""The paper's 7-DOF equations written again in NumPy, as a user would for scipy.integrate.solve_ivp.

A second, independent route to the paper preset: the reference of the solver tests and the
scipy/Exudyn comparison in ``bench/``. Only M, C, K, the return spring's preload, the cam lift
h(theta) and the follower's geometry come from camfollower; the contact geometry and force are
re-derived here from the paper's equations (eqs 2 and 4). Linear contact law (n = 1), no defects, no
contact damping, no gravity.

>>> import camfollower as cf
>>> from camfollower.reference import NumpyCamFollower
>>> ref = NumpyCamFollower(cf.presets.paper())
>>> z0 = ref.initial()                       # static equilibrium, at rest
>>> bool(abs(ref.rhs(0.0, z0)).max() < 1e-6)  # it is an equilibrium
True
"""

import numpy as np

from . import _core

# The paper preset's DOFs and roles: y1 camshaft, y2 roller, y3 rod, y4 follower top; x1, x2, x3 across.
_DOFS = ["y1", "y2", "y3", "y4", "x1", "x2", "x3"]
_ROLES = {"cam_x": "x1", "cam_y": "y1", "follower_dof": "y2", "lateral": "x2", "cam_twist": "ground"}


class NumpyCamFollower:
    """State z = (q, v), 14 entries; rhs(t, z) and jacobian(t, z) for scipy.integrate.solve_ivp.
    ``mechanism``: the paper preset (camfollower.presets.paper), healthy."""

    def __init__(self, mechanism):
        if not isinstance(mechanism, _core.Mechanism) or list(mechanism.dof_names) != _DOFS:
            raise ValueError("the NumPy reference covers the paper preset (camfollower.presets.paper) only")
        b = mechanism.builder()
        (c,) = b.contacts
        follower = c["follower"]
        if (
            not isinstance(follower, _core.TranslatingRoller)
            or any(c[k] != v for k, v in _ROLES.items())
            or c["exponent"] != 1.0
            or c["damping_factor"] != 0.0
            or c["eccentricity"].radius != 0.0
            or c["paper_backlash"][0] != 0.0
            or b.clearances
            or b.loads
            or np.any(np.asarray(b.__getstate__()["gravity"]) != 0.0)
        ):
            raise ValueError(
                "the NumPy reference covers the linear undamped contact law, without gravity or defects, only"
            )
        self.M = np.array(mechanism.mass)
        self.C = np.array(mechanism.damping)
        self.K = np.array(mechanism.stiffness)
        self.Minv = np.diag(1.0 / np.diag(self.M))
        self.external = np.zeros(7)
        for s in b.springs:  # a preload pushes a towards negative q_a, b the other way (structure/network.hpp)
            if s["preload"]:
                self.external[_DOFS.index(s["a"])] -= s["preload"]
                if s["b"] != "ground":
                    self.external[_DOFS.index(s["b"])] += s["preload"]
        self.omega = mechanism.omega
        self.period = mechanism.period
        self.kh = c["stiffness"]
        self.e = follower.offset
        self.s0 = np.sqrt((follower.base_radius + follower.roller_radius) ** 2 - self.e**2)  # paper eq 2
        self.program = c["program"]
        self.q0 = np.array(mechanism.initial_state)

    def contact(self, t, q):
        """Contact direction g (d delta / dq) and penetration delta at time t."""
        m = self.program.evaluate(self.omega * t)
        R = self.s0 + m["h"]
        p = m["dh"] - self.e  # R' - e, paper eq 4
        norm = np.hypot(R, p)
        c, s = R / norm, p / norm
        g = np.array([c, -c, 0.0, 0.0, -s, s, 0.0])
        delta = g @ q + m["h"] * c
        return g, delta

    def rhs(self, t, z):
        q, v = z[:7], z[7:]
        g, delta = self.contact(t, q)
        force = self.kh * delta if delta > 0 else 0.0
        a = self.Minv @ (self.external - self.C @ v - self.K @ q - force * g)
        return np.concatenate([v, a])

    def jacobian(self, t, z):
        g, delta = self.contact(t, z[:7])
        kt = self.K + (self.kh * np.outer(g, g) if delta > 0 else 0.0)
        J = np.zeros((14, 14))
        J[:7, 7:] = np.eye(7)
        J[7:, :7] = -self.Minv @ kt
        J[7:, 7:] = -self.Minv @ self.C
        return J

    def initial(self):
        return np.concatenate([self.q0, np.zeros(7)])
