# SPDX-License-Identifier: BSD-3-Clause
"""An experiment for the structure-exploiting integrator (docs/benchmarks.md, "Exponential
integrators on the paper preset"): how accurate are exponential Runge-Kutta methods, which integrate a
linear part exactly, against Fox-Goodwin at the same step? Written in NumPy on the independent
reference model (camfollower.reference), so it measures accuracy per step, not cost.

One revolution of the paper preset at 750 rpm from static equilibrium; errors in the contact force and
in the accelerations of y2 (the roller, on the contact) and y4 (the follower's top), relative to their
peaks on 2048 rows, against DOP853 at rtol 1e-12. Two choices of the linear part:

- ``constant``: M, C, K and the contact stiffness along the direction at zero pressure angle; the rest
  (the contact's rotation with the pressure angle, the lift) is the remainder (Cox-Matthews ETDRK4);
- ``moving``: the same, re-linearized at every step's middle with the contact's current direction
  (an expm per step: far too slow as written; it shows what a cheaper propagator could reach).

    .venv/bin/python bench/exponential_experiment.py [--steps 4096 8192]
"""

from __future__ import annotations

import argparse
import sys

import camfollower as cf
import numpy as np
import scipy.linalg as sl
from camfollower.reference import NumpyCamFollower
from scipy.integrate import solve_ivp

ROWS = 2048


class Experiment:
    def __init__(self, rpm: float = 750.0):
        self.mechanism = cf.presets.paper().with_camshaft_speed_rpm(rpm)
        self.ref = NumpyCamFollower(self.mechanism)
        self.period = self.ref.period

    def linear_part(self, g):
        """First-order matrix of M q'' + C q' + (K + k g g^T) q."""
        r = self.ref
        a = np.zeros((14, 14))
        a[:7, 7:] = np.eye(7)
        a[7:, :7] = -r.Minv @ (r.K + r.kh * np.outer(g, g))
        a[7:, 7:] = -r.Minv @ r.C
        return a

    def remainder(self, t, z, g_linear):
        """The true right-hand side less the linear part with contact direction g_linear."""
        r = self.ref
        q = z[:7]
        g, delta = r.contact(t, q)
        force = r.kh * delta if delta > 0 else 0.0
        return np.concatenate([np.zeros(7), r.Minv @ (r.external - force * g + r.kh * (g_linear @ q) * g_linear)])

    def measured(self, t, z):
        g, delta = self.ref.contact(t, z[:7])
        return (self.ref.kh * delta if delta > 0 else 0.0), self.ref.rhs(t, z)[7:]

    def etdrk4(self, steps: int, moving: bool):
        h = self.period / steps
        z, t, every, out = self.ref.initial(), 0.0, steps // ROWS, []
        g_linear = np.array([1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0])  # zero pressure angle
        coefficients = _etdrk4_coefficients(self.linear_part(g_linear), h)
        for k in range(steps):
            if moving:
                g_linear = self.ref.contact(t + h / 2, z[:7])[0]
                coefficients = _etdrk4_coefficients(self.linear_part(g_linear), h)
            e, e_half, q1, f1, f2, f3 = coefficients
            n_u = self.remainder(t, z, g_linear)
            a = e_half @ z + h / 2 * q1 @ n_u
            n_a = self.remainder(t + h / 2, a, g_linear)
            b = e_half @ z + h / 2 * q1 @ n_a
            n_b = self.remainder(t + h / 2, b, g_linear)
            c = e_half @ a + h / 2 * q1 @ (2 * n_b - n_u)
            n_c = self.remainder(t + h, c, g_linear)
            z = e @ z + h * (f1 @ n_u + 2 * f2 @ (n_a + n_b) + f3 @ n_c)
            t = (k + 1) * h
            if (k + 1) % every == 0:
                out.append(self.measured(t, z))
        return _columns(out)

    def fox_goodwin(self, steps: int):
        r = cf.simulate(
            self.mechanism, revolutions=1, time_step=self.period / steps, method="fox_goodwin", decimation=steps // ROWS
        )
        acc = np.column_stack([np.asarray(r[f"a.{d}"])[1:] for d in self.mechanism.dof_names])
        return np.asarray(r["cam.force"])[1:], acc

    def reference(self):
        ts = np.arange(1, ROWS + 1) * self.period / ROWS
        sol = solve_ivp(
            self.ref.rhs, (0, self.period), self.ref.initial(), method="DOP853", rtol=1e-12, atol=1e-15, t_eval=ts
        )
        return _columns([self.measured(t, z) for t, z in zip(ts, sol.y.T)])


def _phis(ha):
    """exp(hA), phi1, phi2, phi3 of hA from one exponential of the augmented block matrix."""
    d = ha.shape[0]
    b = np.zeros((4 * d, 4 * d))
    b[:d, :d] = ha
    for k in range(3):
        b[d * k : d * (k + 1), d * (k + 1) : d * (k + 2)] = np.eye(d)
    e = sl.expm(b)
    return [e[:d, d * k : d * (k + 1)] for k in range(4)]


def _etdrk4_coefficients(a, h):
    e, p1, p2, p3 = _phis(h * a)
    e_half, q1, _, _ = _phis(h / 2 * a)
    return e, e_half, q1, p1 - 3 * p2 + 4 * p3, p2 - 2 * p3, -p2 + 4 * p3


def _columns(rows):
    return np.array([r[0] for r in rows]), np.array([r[1] for r in rows])


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, nargs="+", default=[2048, 4096, 8192])
    args = parser.parse_args(argv)
    x = Experiment()
    force_ref, acc_ref = x.reference()

    def errors(force, acc):
        e = [np.abs(force - force_ref).max() / np.abs(force_ref).max()]
        e += [np.abs(acc[:, j] - acc_ref[:, j]).max() / np.abs(acc_ref[:, j]).max() for j in (1, 3)]
        return " / ".join(f"{v:.1e}" for v in e)

    print("| steps per revolution | Fox-Goodwin | ETDRK4, constant linear part | ETDRK4, moving linear part |")
    print("|---|---|---|---|")
    for steps in args.steps:
        try:
            fg = errors(*x.fox_goodwin(steps))
        except ValueError:
            fg = "beyond its stability limit"
        print(f"| {steps} | {fg} | {errors(*x.etdrk4(steps, False))} | {errors(*x.etdrk4(steps, True))} |", flush=True)
    print("(errors: contact force / acceleration of y2 / of y4, relative to their peaks)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
