# SPDX-License-Identifier: BSD-3-Clause
"""The 7-DOF equations written again in NumPy, as a user would for scipy.integrate.solve_ivp.

A second, independent route to the same model: the reference of the solver tests and the
scipy/Exudyn comparison in ``bench/``. Only M, C, K, the spring preload and the cam lift h(theta)
come from camfollower; the contact geometry and force are re-derived here from the paper's equations
(eqs 2 and 4). Linear contact law (n = 1), no defects, no contact damping.

>>> import camfollower as cf
>>> from camfollower.reference import NumpyCamFollower
>>> ref = NumpyCamFollower(cf.CamFollowerModel())
>>> z0 = ref.initial()                       # static equilibrium, at rest
>>> bool(abs(ref.rhs(0.0, z0)).max() < 1e-6)  # it is an equilibrium
True
"""

import numpy as np


class NumpyCamFollower:
    """State z = (q, v), 14 entries; rhs(t, z) and jacobian(t, z) for scipy.integrate.solve_ivp."""

    def __init__(self, model):
        p = model.parameters
        if (
            p.contact_exponent != 1.0
            or p.gravity != 0.0
            or p.to_dict()["contact_damping"] != "none"
            or model.defects.eccentricity
            or model.defects.backlash
        ):
            raise ValueError(
                "the NumPy reference covers the linear undamped contact law, without gravity or defects, only"
            )
        p = model.parameters
        self.M = np.array(model.mass_matrix)
        self.C = np.array(model.damping_matrix)
        self.K = np.array(model.stiffness_matrix)
        self.Minv = np.diag(1.0 / np.diag(self.M))
        self.external = np.zeros(7)
        self.external[3] = -model.spring_preload
        self.omega = model.omega
        self.kh = p.contact_stiffness
        self.e = p.offset
        self.s0 = np.sqrt((p.base_radius + p.roller_radius) ** 2 - p.offset**2)  # paper eq 2
        self.program = model.cam.program
        self.q0 = np.array(model.initial_state)

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
