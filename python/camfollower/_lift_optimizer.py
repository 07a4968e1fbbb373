# SPDX-License-Identifier: BSD-3-Clause
"""The lift synthesis on the flexible model: a trust-region Gauss-Newton loop whose subproblems
scipy's SLSQP solves.

Why this and not SLSQP on the simulation directly: the samples the objective squares are nearly
linear in the station lifts (exactly so for a linear mechanism), so one finite-difference Jacobian
(n + 1 periodic steady states, run together on threads) gives a model of the objective that is
nearly exact over a wide step, and the kinematic limits are exactly linear (acceleration, jerk) or
cheap to linearize afresh (pressure angle, curvature). SLSQP minimizes that model under the
linearized limits inside a trust region at no simulation cost; the candidate is then simulated, and
accepted only when it really improves (or, from an infeasible start, reduces the worst violation).
SLSQP on the simulation itself would spend a steady state per line-search point and build its
curvature from gradients over many iterations.
"""

from __future__ import annotations

import math
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional

import numpy as np

from ._lift_space import LiftSpace
from ._synthesis_dynamics import Dynamics, with_program

_RPM = math.pi / 30.0
#: Finite-difference step of the station lifts (fraction of the segment's lift).
FD_STEP = 1e-4
#: Constraint violation (relative to its limit) still counted as feasible: a hundredth of a per cent.
FEASIBLE = 1e-4
#: Trust region on the station lifts (fractions of the segment's lift).
START_RADIUS, MAX_RADIUS, MIN_RADIUS = 0.05, 1.0, 1e-7
#: The least convex radius of curvature of the cam surface when none is asked (m).
DEFAULT_MIN_RADIUS = 0.5e-3


@dataclass
class Limits:
    """The kinematic and contact limits; None = not imposed. SI units (rad for angles)."""

    max_acceleration: Optional[float] = None  # m/s^2 or rad/s^2, rigid follower at the design speed
    max_jerk: Optional[float] = None  # m/s^3 or rad/s^3, at the design speed
    max_pressure_angle: Optional[float] = None  # rad
    min_radius: Optional[float] = None  # m, the cam surface's least convex radius of curvature
    min_force: Optional[float] = None  # N, the contact force at every speed of the band
    max_output_acceleration: Optional[float] = None  # the output's peak |acceleration| at the design speed
    max_stress: Optional[float] = None  # Pa, the Hertz pressure at every sample of every speed

    def named(self) -> Dict[str, float]:
        return {k: v for k, v in self.__dict__.items() if v is not None}


@dataclass
class _Point:
    p: np.ndarray
    samples: list  # one Sample per speed
    objective: float  # the model's measure: mean or worst of the speeds' (mean square | peak) / scale
    violation: float  # worst relative violation of a limit (0 when feasible)
    worst: str  # which limit that is
    kinematics: Dict[str, np.ndarray] = field(default_factory=dict)


class Optimizer:
    def __init__(
        self, space: LiftSpace, dynamics: Dynamics, follower, limits: Limits, robust: str, workers: int, budget: int
    ):
        self.space, self.dyn, self.follower, self.limits = space, dynamics, follower, limits
        self.robust, self.workers, self.budget = robust, workers, budget
        self.omega = dynamics.speeds[0] * _RPM  # the design speed comes first
        self.grid = space.grid(600)
        self.roller = float(getattr(follower, "roller_radius", 0.0))
        self.flat = not hasattr(follower, "roller_radius")
        # No undercut: the surface's convex radius of curvature stays above min_radius (default
        # DEFAULT_MIN_RADIUS: a cusp or a roller that no longer fits is a limit of every cam).
        self.min_radius = DEFAULT_MIN_RADIUS if limits.min_radius is None else limits.min_radius
        self.history: List[Dict[str, Any]] = []

    # -- evaluations -------------------------------------------------------------------------------
    def _run_all(self, jobs):
        """jobs: (p, speed index, guess orbit, multipliers) -> Samples, on ``workers`` threads."""

        def one(job):
            p, i, guess, multipliers = job
            return self.dyn.run(self.space.program(p), i, guess, multipliers)

        if self.workers == 1 or len(jobs) == 1:
            return [one(j) for j in jobs]
        with ThreadPoolExecutor(self.workers) as pool:
            return list(pool.map(one, jobs))

    def _measures(self, samples) -> np.ndarray:
        if self.dyn.measure == "rms":
            return np.array([np.mean(s.values**2) for s in samples])
        return np.array([np.max(np.abs(s.values)) for s in samples])

    def _combine(self, per_speed: np.ndarray) -> float:
        return float(np.max(per_speed) if self.robust == "worst" else np.mean(per_speed))

    def _kinematic_groups(self, p):
        """Limits as g >= 0 (each scaled by its limit): {name: (values, matrix)} linearized at p."""
        lim, w = self.limits, self.omega
        groups = {}
        need_basis = lim.max_acceleration is not None or lim.max_jerk is not None
        if need_basis:
            base, mats = self.space.kinematic_basis(p, self.grid)
            for name, key, power in (("max_acceleration", "d2h", 2), ("max_jerk", "d3h", 3)):
                limit = getattr(lim, name)
                if limit is not None:
                    v, m = base[key] * w**power / limit, mats[key] * w**power / limit
                    groups[name] = (np.concatenate([1 - v, 1 + v]), np.vstack([-m, m]))
        # The undercut limit always holds; the pressure angle's when asked.
        base = self._geometry(p)
        mats = {k: np.empty((len(self.grid), len(p))) for k in base}
        for j in range(len(p)):
            e = p.copy()
            e[j] += FD_STEP
            moved = self._geometry(e)
            for k in base:
                mats[k][:, j] = (moved[k] - base[k]) / FD_STEP
        if lim.max_pressure_angle is not None:
            v, m = base["alpha"] / lim.max_pressure_angle, mats["alpha"] / lim.max_pressure_angle
            groups["max_pressure_angle"] = (np.concatenate([1 - v, 1 + v]), np.vstack([-m, m]))
        if self.flat:  # a flat face: the surface's radius itself, smooth in the lift, must stay above
            groups["min_radius"] = (base["radius"] / self.min_radius - 1.0, mats["radius"] / self.min_radius)
        else:  # a roller: its centre's path may turn concave, never tighter than the roller convex
            reach = self.roller + self.min_radius
            groups["min_radius"] = (1 - base["kappa"] * reach, -mats["kappa"] * reach)
        return groups

    def _geometry(self, p) -> Dict[str, np.ndarray]:
        """Pressure angle, the surface's radius of curvature (a flat face's: R_b + h + h'', smooth) and
        the signed curvature of a roller centre's path (smooth where the surface's radius jumps through
        infinity)."""
        prof = self.follower.profile(self.space.program(p), self.grid)
        radius = np.asarray(prof["surface_radius"], dtype=float)
        pitch = radius + self.roller
        with np.errstate(divide="ignore"):
            kappa = np.where(pitch == 0.0, np.inf, 1.0 / pitch)
        return {"alpha": np.asarray(prof["pressure_angle"], dtype=float), "kappa": kappa, "radius": radius}

    def _dynamic_groups(self, samples) -> Dict[str, np.ndarray]:
        """The limits on the simulated response, g >= 0 (scaled): the contact force at every speed, the
        output's peak acceleration at the design speed (the first)."""
        groups = {}
        if self.limits.min_force is not None:
            scale = max(abs(self.limits.min_force), 1.0)
            groups["min_force"] = np.array([(s.min_force - self.limits.min_force) / scale for s in samples])
        if self.limits.max_output_acceleration is not None:
            # Every sample, not the peak: each is smooth in the lift, the peak jumps between samples.
            a = samples[0].acceleration / self.limits.max_output_acceleration
            groups["max_output_acceleration"] = np.concatenate([1.0 - a, 1.0 + a])
        if self.limits.max_stress is not None:
            groups["max_stress"] = np.concatenate([1.0 - s.stress / self.limits.max_stress for s in samples])
        return groups

    def _dynamic_jacobians(self, jac_force, jac_acceleration, jac_stress) -> Dict[str, np.ndarray]:
        out = {}
        if self.limits.min_force is not None:
            out["min_force"] = jac_force / max(abs(self.limits.min_force), 1.0)
        if self.limits.max_output_acceleration is not None:
            m = jac_acceleration / self.limits.max_output_acceleration
            out["max_output_acceleration"] = np.vstack([-m, m])
        if self.limits.max_stress is not None:
            out["max_stress"] = -np.vstack(jac_stress) / self.limits.max_stress
        return out

    def _point(self, p, samples, scale) -> _Point:
        groups = self._kinematic_groups(p)
        violation, worst = 0.0, ""
        for name, (g, _) in groups.items():
            if g.size and -g.min() > violation:
                violation, worst = float(-g.min()), name
        for name, g in self._dynamic_groups(samples).items():
            if -g.min() > violation:
                violation, worst = float(-g.min()), name
        return _Point(p, samples, self._combine(self._measures(samples)) / scale, violation, worst, groups)

    def _jacobians(self, point: _Point) -> List[np.ndarray]:
        jobs = []
        for j in range(len(point.p)):
            e = point.p.copy()
            e[j] += FD_STEP
            jobs += [(e, i, s.orbit, False) for i, s in enumerate(point.samples)]
        moved = self._run_all(jobs)
        n = len(point.samples)
        jac_values = [np.empty((len(s.values), len(point.p))) for s in point.samples]
        jac_force = np.empty((n, len(point.p)))
        jac_acceleration = np.empty((len(point.samples[0].acceleration), len(point.p)))
        stressed = self.limits.max_stress is not None
        jac_stress = [np.empty((len(s.stress), len(point.p))) for s in point.samples] if stressed else []
        for k, m in enumerate(moved):
            j, i = divmod(k, n)
            jac_values[i][:, j] = (m.values - point.samples[i].values) / FD_STEP
            jac_force[i, j] = (m.min_force - point.samples[i].min_force) / FD_STEP
            if i == 0:
                jac_acceleration[:, j] = (m.acceleration - point.samples[0].acceleration) / FD_STEP
            if stressed:
                jac_stress[i][:, j] = (m.stress - point.samples[i].stress) / FD_STEP
        return jac_values, self._dynamic_jacobians(jac_force, jac_acceleration, jac_stress)

    # -- the model step ----------------------------------------------------------------------------
    def _subproblem(
        self, point: _Point, jac, radius: float, scale: float, weighted: bool = False, relax: Optional[float] = None
    ):
        """SLSQP on the Gauss-Newton model inside the trust region, from a feasible point: (step, model
        objective, status). ``weighted``: the worst case of rms measures as their average weighted by
        the current ones (no quadratic constraints: the fallback when SLSQP fails on the epigraph);
        ``relax``: every limit relaxed by this (the least violation a restoring step can reach)."""
        jac_values, jac_dynamic = jac
        n, speeds = len(point.p), len(point.samples)
        cur = max(point.objective, 1e-300)  # model normalized to 1 at the current point
        norm = scale * cur
        r = [s.values for s in point.samples]
        rms = self.dyn.measure == "rms"
        # The unknown is u = step / sigma, sigma the step that moves the objective by its current size
        # (capped by the trust radius): near the optimum that step is 1e-8 of the lift, and SLSQP fails
        # on a model whose curvature is 1e15 in the raw step.
        if rms:
            influence = max(float(np.max(np.sum(J**2, axis=0))) / len(ri) for J, ri in zip(jac_values, r))
            sigma = math.sqrt(norm / influence) if influence > 0 else radius
        else:
            influence = max(float(np.max(np.abs(J))) for J in jac_values)
            sigma = norm / influence if influence > 0 else radius
        sigma = min(sigma, radius)
        jac_values = [J * sigma for J in jac_values]
        cons = []
        linear = [(g, m * sigma) for g, m in point.kinematics.values()]
        linear += [(g, jac_dynamic[name] * sigma) for name, g in self._dynamic_groups(point.samples).items()]
        if rms:
            # mean square per speed: c_i + 2 b_i.u + u.Q_i.u, over scale * cur
            quad = [
                (J.T @ J / len(ri) / norm, J.T @ ri / len(ri) / norm, ri @ ri / len(ri) / norm)
                for J, ri in zip(jac_values, r)
            ]
            if self.robust == "average" or weighted:
                w = np.array([cc for _, _, cc in quad]) if weighted else np.ones(speeds)
                w = w / w.sum()
                Q = sum(wi * q for wi, (q, _, _) in zip(w, quad))
                b = sum(wi * bb for wi, (_, bb, _) in zip(w, quad))
                c = sum(wi * cc for wi, (_, _, cc) in zip(w, quad))
                fun = lambda z: c + 2 * b @ z + z @ Q @ z  # noqa: E731
                jac_fun = lambda z: 2 * b + 2 * Q @ z  # noqa: E731
                extra = 0
            else:
                extra = 1
                fun, jac_fun = _last, _last_grad
                for q, bb, cc in quad:
                    cons.append(
                        {
                            "type": "ineq",
                            "fun": lambda z, q=q, bb=bb, cc=cc: z[-1] - (cc + 2 * bb @ z[:n] + z[:n] @ q @ z[:n]),
                            "jac": lambda z, q=q, bb=bb: np.concatenate([-(2 * bb + 2 * q @ z[:n]), [1.0]]),
                        }
                    )
        else:
            extra = 1 if self.robust == "worst" else speeds
            for i, (J, ri) in enumerate(zip(jac_values, r)):
                col = -1 if extra == 1 else n + i
                A = np.vstack([-J, J]) / norm
                a0 = np.concatenate([-ri, ri]) / norm
                T = np.zeros((len(a0), extra))
                T[:, col] = 1.0
                cons.append(
                    {
                        "type": "ineq",
                        "fun": lambda z, A=A, a0=a0, T=T: a0 + A @ z[:n] + T @ z[n:],
                        "jac": lambda z, A=A, T=T: np.hstack([A, T]),
                    }
                )
            fun = lambda z: float(np.mean(z[n:]))  # noqa: E731
            jac_fun = lambda z: np.concatenate([np.zeros(n), np.full(extra, 1.0 / extra)])  # noqa: E731
        # A limit violated within FEASIBLE is only kept from getting worse: the step 0 stays feasible.
        for g, m in linear:
            g = g - np.minimum(g, 0.0) if relax is None else g + relax
            cons.append({"type": "ineq", "fun": lambda z, g=g, m=m: g + m @ z[:n], "jac": lambda z, m=m: _pad(m, z)})
        z0 = np.zeros(n + extra)
        if extra:
            z0[n:] = 1.0  # the current point's normalized measure
        bounds = [(-radius / sigma, radius / sigma)] * n + [(None, None)] * extra
        res = _scipy_optimize().minimize(
            fun,
            z0,
            jac=jac_fun,
            method="SLSQP",
            bounds=bounds,
            constraints=cons,
            options={"maxiter": 1000, "ftol": 1e-12},
        )
        u = np.clip(res.x[:n], -radius / sigma, radius / sigma)
        if rms:
            each = [cc + 2 * bb @ u + u @ q @ u for q, bb, cc in quad]
            model = max(each) if self.robust == "worst" else float(np.mean(each))
        else:
            model = float(fun(res.x))
        return u * sigma, model * cur, res

    def _restore(self, point: _Point, jac, radius: float, scale: float):
        """From an infeasible point, the step within the trust region that minimizes the largest
        linearized violation (a linear program, HiGHS): (step, model objective, status)."""
        linear = [(g, m) for g, m in point.kinematics.values()]
        linear += [(g, jac[1][name]) for name, g in self._dynamic_groups(point.samples).items()]
        n = len(point.p)
        G = np.vstack([m for _, m in linear])
        g = np.concatenate([v for v, _ in linear])
        # minimize t subject to g + G s + t >= 0, |s| <= radius, t >= 0
        res = _scipy_optimize().linprog(
            np.concatenate([np.zeros(n), [1.0]]),
            A_ub=np.hstack([-G, -np.ones((len(g), 1))]),
            b_ub=g,
            bounds=[(-radius, radius)] * n + [(0.0, None)],
            method="highs",
        )
        if res.status != 0:
            return np.zeros(n), point.objective, _Failed(res.message)
        # Then the best objective among the steps that reach (about) that violation.
        least = float(res.x[-1]) * (1.0 + 1e-6) + 1e-12
        step, model, fit = self._subproblem(point, jac, radius, scale, relax=least)
        if fit.status in (0, 9):
            return step, model, fit
        return res.x[:n], point.objective, _Failed("", 0)

    # -- the loop ----------------------------------------------------------------------------------
    def run(self, p0: np.ndarray, max_iterations: int, tolerance: float, target: float) -> Dict[str, Any]:
        t0 = time.perf_counter()
        samples = []
        for i, rpm in enumerate(self.dyn.speeds):
            try:
                samples.append(self._run_all([(p0, i, None, True)])[0])
            except RuntimeError as e:
                raise ValueError(not_periodic(rpm, e)) from None
        scale = self._combine(self._measures(samples))
        if not scale > 0.0:
            raise ValueError(
                "the start lift's objective is already zero: nothing to reduce (check output and objective)"
            )
        start = self._point(p0, samples, scale)
        point, radius = start, START_RADIUS
        converged, message = False, ""
        jac = self._jacobians(point)
        self._log(0, point, radius, True, math.nan)
        for iteration in range(1, max_iterations + 1):
            if self.dyn.evaluations + len(self.dyn.speeds) > self.budget:
                message = f"stopped at the evaluation budget ({self.budget} periodic steady states)"
                break
            restoring = point.violation > FEASIBLE
            if restoring:  # feasibility first: the step that most reduces the worst violation
                step, model, res = self._restore(point, jac, radius, scale)
            else:
                step, model, res = self._subproblem(point, jac, radius, scale)
                if res.status not in (0, 9) and self.robust == "worst" and self.dyn.measure == "rms":
                    step, model, res = self._subproblem(point, jac, radius, scale, weighted=True)
            if res.status not in (0, 9):  # 9: the iteration limit, its last iterate is still a fair step
                radius /= 4.0
                self._log(iteration, point, radius, False, math.nan, f"model step failed: {res.message}")
                if radius < MIN_RADIUS:
                    message = f"the trust region collapsed: the model step failed ({res.message})"
                    break
                continue
            candidate_p = point.p + step
            try:
                samples = self._run_all([(candidate_p, i, s.orbit, False) for i, s in enumerate(point.samples)])
            except (RuntimeError, ValueError) as e:  # not periodic, or a cam the library refuses
                radius /= 4.0
                self._log(iteration, point, radius, False, math.nan, f"candidate refused: {e}")
                if radius < MIN_RADIUS:
                    message = "the trust region collapsed: candidates near the lift are not periodic"
                    break
                continue
            cand = self._point(candidate_p, samples, scale)
            if restoring:
                accept = cand.violation < point.violation
            else:
                accept = cand.violation <= FEASIBLE and cand.objective < point.objective
            predicted = point.objective - model
            actual = point.objective - cand.objective
            ratio = actual / predicted if predicted > 0 else 0.0
            self._log(iteration, cand, radius, accept, ratio)
            if not accept and not restoring and predicted <= tolerance * point.objective:
                converged = True  # the model expects less than the tolerance from any step it can take
                message = f"converged: the model expects less than {tolerance:g} of the objective from a step"
                break
            if not accept:
                radius /= 4.0
                if radius < MIN_RADIUS:
                    message = "the trust region collapsed: no step of the model improves the simulated objective"
                    break
                continue
            small = not restoring and actual <= tolerance * point.objective
            point = cand
            if restoring:
                pass  # a restoring step is judged by the violation, not by the model's objective
            elif ratio > 0.75 and np.max(np.abs(step)) > 0.8 * radius:
                radius = min(2.0 * radius, MAX_RADIUS)
            elif ratio < 0.25:
                radius /= 2.0
            reached = target**2 if self.dyn.measure == "rms" else target  # rms objectives are mean squares
            if point.violation <= FEASIBLE and point.objective <= reached:
                converged = True
                message = f"converged: the objective is below target = {target:g} of the start's"
                break
            if small or (
                not restoring and point.violation <= FEASIBLE and predicted <= 0.1 * tolerance * point.objective
            ):
                converged = True
                message = f"converged: the last step improved the objective by less than {tolerance:g} of it"
                break
            if (
                iteration < max_iterations
                and self.dyn.evaluations + (len(point.p) + 1) * len(self.dyn.speeds) <= self.budget
            ):
                jac = self._jacobians(point)
            else:
                message = "stopped at the iteration or evaluation budget"
                break
        else:
            message = f"stopped after max_iterations = {max_iterations} without converging"
        if point.violation > FEASIBLE:
            message += f"; the best lift found still violates {point.worst} by {point.violation:.3g} of its limit"
        return {
            "start": start,
            "best": point,
            "scale": scale,
            "converged": converged and point.violation <= FEASIBLE,
            "message": message,
            "wall_time": time.perf_counter() - t0,
        }

    def _log(self, iteration, point, radius, accepted, ratio, note=""):
        self.history.append(
            {
                "iteration": iteration,
                "objective": point.objective,
                "violation": point.violation,
                "trust_radius": radius,
                "accepted": bool(accepted),
                "ratio": ratio,
                "evaluations": self.dyn.evaluations,
                "note": note,
            }
        )


def _scipy_optimize():
    """scipy.optimize (SLSQP, linprog), imported when a synthesis runs (the 'synthesis' extra)."""
    try:
        from scipy import optimize
    except ImportError:
        raise ImportError(
            "camfollower.synthesis.synthesize needs scipy (SLSQP): pip install 'camfollower[synthesis]'"
        ) from None
    return optimize


def not_periodic(rpm: float, error: Exception) -> str:
    """The message for a start lift whose steady state at ``rpm`` is not periodic."""
    return (
        f"speeds_rpm: at {rpm:g} rpm the start lift's response is not periodic: the follower may leave the cam "
        f"there (is the jump speed inside the band?); narrow the band, stiffen the return spring or start from "
        f"a gentler lift. {error}"
    )


@dataclass
class _Failed:
    """An optimizer outcome in scipy's terms (message, status: 0 success)."""

    message: str
    status: int = 2


def _pad(m, z):
    extra = len(z) - m.shape[1]
    return np.hstack([m, np.zeros((m.shape[0], extra))]) if extra else m


def _last(z):
    return float(z[-1])


def _last_grad(z):
    g = np.zeros_like(z)
    g[-1] = 1.0
    return g


__all__ = ["Limits", "Optimizer", "not_periodic", "with_program"]
