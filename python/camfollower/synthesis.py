# SPDX-License-Identifier: BSD-3-Clause
"""Designing the cam lift for the follower's dynamics: the classical compensation first.

**Polydyne** (Stoddart, 1953): a follower train of stiffness ``k`` between the cam and an output of
mass ``m``, held by a return spring ``k_s`` with viscous damping ``c`` to the frame. Its output y
obeys m y'' + c y' + k_s y = k (x - y) (time derivatives; the preload only sets the static
deflection, which the datum absorbs), so the output follows a wanted motion y(theta) exactly at the
camshaft speed omega when the cam lifts

    x(theta) = y + (m omega^2 y'' + c omega y' + k_s y) / k       (theta-derivatives).

That demands two derivatives of y beyond those the cam needs: a cam with continuous acceleration
(x in C2) needs a wanted motion whose fourth derivative is continuous (y in C4); a jump in y''''
becomes a jump in the cam's acceleration of m omega^2 / k times it. :func:`polydyne` refuses a
wanted motion that is not C4, naming the boundary. Off the design speed the compensation is wrong by
(omega_design^2 - omega^2) m y'' / k, and the output rings.

The lift is returned as a periodic B-spline program (``MotionProgram.from_table``, degree 7: C6)
through the compensated lift at ``points`` equally spaced cam angles, a normal program: checks,
exports, configs and simulations take it. Lifts in m (translating followers) or rad (arms: then
``mass`` is an inertia in kg m^2 and the stiffnesses are in N m/rad).
"""

from __future__ import annotations

import math
import numbers
import time
from dataclasses import dataclass, field
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import _core
from ._core import MotionProgram
from ._lift_optimizer import Limits, Optimizer, not_periodic
from ._lift_space import LiftSpace, degree_for
from ._synthesis_dynamics import SHOOTING_TOLERANCE, Dynamics, check_objective, with_program
from .periodic import periodic_steady_state
from .response import contact_of, scheme_at, scheme_settings, steady_response

_RPM = math.pi / 30.0  # rad/s per rpm


def _positive(value, name: str, unit: str, allow_zero: bool = False) -> float:
    ok = (
        not isinstance(value, bool)
        and isinstance(value, numbers.Real)
        and math.isfinite(value)
        and (value >= 0 if allow_zero else value > 0)
    )
    if not ok:
        raise ValueError(f"{name} must be a finite number {'>=' if allow_zero else '>'} 0 ({unit}), got {value!r}")
    return float(value)


def snap_jumps(program: MotionProgram, step: float = 1e-4) -> list:
    """The jumps of the fourth theta-derivative y'''' at each segment boundary (m/rad^4 or 1/rad^3),
    as (boundary angle in rad, jump), from one-sided differences of y''' over ``step`` rad: a jump
    the differences see to within O(step) of the derivatives beyond it."""
    jumps = []
    for boundary in program.continuity().boundaries:
        theta = boundary.theta
        left = program.evaluate(np.array([theta - 2 * step, theta - step]) % (2 * math.pi))["d3h"]
        right = program.evaluate(np.array([theta + step, theta + 2 * step]) % (2 * math.pi))["d3h"]
        at = boundary.right[3]
        before = (3 * boundary.left[3] - 4 * left[1] + left[0]) / (2 * step)  # second-order one-sided
        after = (-3 * at + 4 * right[0] - right[1]) / (2 * step)
        jumps.append((theta, after - before))
    return jumps


def polydyne(
    desired: MotionProgram,
    *,
    mass: float,
    stiffness: float,
    speed_rpm: float,
    return_stiffness: float = 0.0,
    damping: float = 0.0,
    points: int = 3600,
) -> MotionProgram:
    """The cam lift that makes a one-mass follower's output move exactly as ``desired`` at
    ``speed_rpm``: x = y + (m omega^2 y'' + c omega y' + k_s y) / k (module docstring). ``mass`` (kg,
    or kg m^2), ``stiffness`` k of the follower train (N/m or N m/rad, > 0), ``return_stiffness`` k_s
    and ``damping`` c (N s/m or N m s/rad, to the frame; >= 0), ``points`` cam angles of the fitted
    table (>= 360). Raises ValueError naming the parameter, or the boundary where ``desired`` is not
    C4 (its fourth derivative jumps: the cam's acceleration would step there)."""
    if not isinstance(desired, MotionProgram):
        raise ValueError(f"desired must be a MotionProgram, got {type(desired).__name__}")
    m = _positive(mass, "mass", "kg, or kg m^2 for an arm")
    k = _positive(stiffness, "stiffness", "N/m, or N m/rad for an arm")
    ks = _positive(return_stiffness, "return_stiffness", "N/m, or N m/rad", allow_zero=True)
    c = _positive(damping, "damping", "N s/m, or N m s/rad", allow_zero=True)
    omega = _speed(speed_rpm, "speed_rpm") * _RPM
    if isinstance(points, bool) or not isinstance(points, numbers.Integral) or not 360 <= points <= _core.MAX_POINTS:
        raise ValueError(f"points must be an integer in [360, {_core.MAX_POINTS}], got {points!r}")
    try:
        desired.require_continuity(3)
    except ValueError as e:
        raise ValueError(
            f"desired: polydyne needs a motion continuous through its fourth derivative (C4); {e}"
        ) from None
    scale = max(abs(desired.max_lift()), abs(desired.min_lift()), 1e-300)
    for theta, jump in snap_jumps(desired):
        # The differences' own error is O(step) times y''''' ~ lift; a real jump is O(lift) per rad^4.
        if abs(jump) > 1e-3 * scale:
            raise ValueError(
                f"desired: polydyne needs a motion continuous through its fourth derivative (C4), but y'''' jumps "
                f"by {jump:.6g} per rad^4 at {math.degrees(theta):.6g} deg: the cam's acceleration would step by "
                f"{m * omega**2 / k * jump:.6g} there (use a law whose fourth derivative is continuous, e.g. "
                "Segment.polynomial with zero derivatives through the fourth at its ends)"
            )
    theta = 2 * math.pi * np.arange(points) / points
    y = desired.evaluate(theta)
    x = (
        np.asarray(y["h"])
        + (m * omega**2 * np.asarray(y["d2h"]) + c * omega * np.asarray(y["dh"]) + ks * np.asarray(y["h"])) / k
    )
    return MotionProgram.from_table(theta, x, degree=7)


# -- synthesis on the flexible model ------------------------------------------------------------------

#: The catalogue laws the synthesis is compared with (docs/synthesis.md).
CATALOGUE = ("cycloidal", "modified_sine", "modified_trapezoid", "polynomial_4567")
#: Robust combinations of the band's speeds.
ROBUST = ("worst", "average")


@dataclass
class SynthesisResult:
    """What :func:`synthesize` found. ``program`` is a normal MotionProgram (the redesigned segments are
    splines through the station lifts); ``system`` the mechanism with it at the design speed.
    ``objective_start`` / ``objective_final``: the objective's measure (rms or peak, m, rad or m/s^2)
    at each speed of ``speeds_rpm`` as the optimizer measured it (at ``steps_per_revolution``);
    :func:`verify` measures programs afresh at a stated accuracy. ``evaluations``: periodic steady
    states computed (each a shooting of the whole mechanism), ``revolutions`` their simulated
    revolutions, ``wall_time`` in s. ``limits``: per limit, its value and the start and final
    programs' (``None`` where a limit was not imposed is left out). ``history``: per iteration the
    normalized objective, the worst limit violation, the trust radius, whether the step was taken."""

    program: MotionProgram
    start_program: MotionProgram
    system: Any
    contact: str
    output: str
    objective: str
    measure: str
    robust: str
    speeds_rpm: Tuple[float, ...]
    converged: bool
    message: str
    iterations: int
    evaluations: int
    revolutions: float
    wall_time: float
    steps_per_revolution: int
    objective_start: Tuple[float, ...]
    objective_final: Tuple[float, ...]
    limits: Dict[str, Dict[str, float]]
    kinematics: Dict[str, Dict[str, float]]
    stations: Dict[int, List[float]]
    history: List[Dict[str, Any]] = field(repr=False)

    @property
    def improvement(self) -> float:
        """Start objective / final objective, combined over the speeds as optimized."""
        combine = max if self.robust == "worst" else (lambda v: sum(v) / len(v))
        final = combine(self.objective_final)
        return combine(self.objective_start) / final if final > 0 else math.inf

    def summary(self) -> Dict[str, Any]:
        """JSON-ready facts (no programs or orbits)."""
        out = {k: getattr(self, k) for k in _SUMMARY_FIELDS}
        out["improvement"] = self.improvement
        out["stations"] = {str(k): v for k, v in self.stations.items()}
        return out


_SUMMARY_FIELDS = (
    "contact",
    "output",
    "objective",
    "measure",
    "robust",
    "speeds_rpm",
    "converged",
    "message",
    "iterations",
    "evaluations",
    "revolutions",
    "wall_time",
    "steps_per_revolution",
    "objective_start",
    "objective_final",
    "limits",
    "kinematics",
    "history",
)


def _speed(value, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number (rpm), got {value!r}")
    lo, hi = _core.MIN_CAMSHAFT_SPEED / _RPM, _core.MAX_CAMSHAFT_SPEED / _RPM
    if not lo <= value <= hi:
        raise ValueError(f"{name} must be in [{lo:g}, {hi:g}] rpm, got {value!r}")
    return float(value)


def band_speeds(design_rpm: float, band: float = 0.0, count: int = 5) -> List[float]:
    """The design speed first, then ``count`` speeds spread evenly over design * (1 -/+ band)."""
    design = _speed(design_rpm, "speed")
    if isinstance(band, bool) or not isinstance(band, numbers.Real) or not 0.0 <= band < 1.0:
        raise ValueError(f"band must be a fraction of the design speed in [0, 1) (0.2: +/-20 %), got {band!r}")
    if band == 0.0:
        return [design]
    if isinstance(count, bool) or not isinstance(count, numbers.Integral) or not 2 <= count <= 21:
        raise ValueError(f"band_speeds must be an integer in [2, 21], got {count!r}")
    others = [design * f for f in np.linspace(1.0 - band, 1.0 + band, count)]
    return [design] + [s for s in others if abs(s - design) > 1e-9 * design]


def _kinematics(program, follower, omega: float, space: LiftSpace) -> Dict[str, float]:
    """Peak rigid acceleration and jerk at the design speed, the largest |pressure angle| and the least
    convex radius of curvature over the redesigned segments."""
    theta = space.grid(1200)
    k = program.evaluate(theta)
    prof = follower.profile(program, theta)
    radius = np.asarray(prof["surface_radius"], dtype=float)
    convex = radius[radius > 0]
    return {
        "max_acceleration": float(np.max(np.abs(k["d2h"]))) * omega**2,
        "max_jerk": float(np.max(np.abs(k["d3h"]))) * omega**3,
        "max_pressure_angle": float(np.max(np.abs(prof["pressure_angle"]))),
        "min_radius": float(np.min(convex)) if convex.size else math.inf,
    }


def _check_reachable(space: LiftSpace, follower, limits: Limits, omega: float) -> None:
    """Refuse limits no lift in any space can meet, naming the limit and the segment."""
    for i in space.segments:
        seg = space.base.segments[i]
        rise, span = abs(seg.h_end - seg.h_start), seg.theta_end - seg.theta_start
        where = f"segment {i} ({math.degrees(seg.theta_start):.4g}-{math.degrees(seg.theta_end):.4g} deg)"
        if limits.max_acceleration is not None:
            least = 4.0 * rise / span**2 * omega**2  # constant acceleration's peak: the least of any lift
            if limits.max_acceleration < least:
                raise ValueError(
                    f"max_acceleration: no lift can move {rise:.6g} in {math.degrees(span):.6g} deg ({where}) with a "
                    f"peak below {least:.6g} (4 h / beta^2 omega^2, constant acceleration's) at the design speed; "
                    f"the limit is {limits.max_acceleration:.6g}: raise it or lengthen the segment"
                )
        if limits.max_pressure_angle is not None and isinstance(follower, _core.TranslatingRoller):
            reach = math.sqrt(max((follower.base_radius + follower.roller_radius) ** 2 - follower.offset**2, 0.0))
            top = max(abs(seg.h_start), abs(seg.h_end))
            least = math.atan(max(rise / span - abs(follower.offset), 0.0) / (reach + top))
            if limits.max_pressure_angle < least:
                raise ValueError(
                    f"max_pressure_angle: at a base radius of {follower.base_radius:.6g} m no lift can move "
                    f"{rise:.6g} m in {math.degrees(span):.6g} deg ({where}) below {math.degrees(least):.4g} deg "
                    f"(its mean slope); the limit is {math.degrees(limits.max_pressure_angle):.4g} deg: enlarge "
                    "the base circle, lengthen the segment or raise the limit"
                )


def _limits(
    max_acceleration, max_jerk, max_pressure_angle, min_radius, min_force, max_output_acceleration, max_stress
) -> Limits:
    def check(value, name, unit, low=0.0, high=math.inf):
        if value is None:
            return None
        if isinstance(value, bool) or not isinstance(value, numbers.Real) or not (low < value < high):
            raise ValueError(f"{name} must be a number in ({low:g}, {high:g}) {unit} or None, got {value!r}")
        return float(value)

    if min_force is not None and (
        isinstance(min_force, bool) or not isinstance(min_force, numbers.Real) or not math.isfinite(min_force)
    ):
        raise ValueError(f"min_force must be a finite number (N) or None, got {min_force!r}")
    return Limits(
        max_acceleration=check(max_acceleration, "max_acceleration", "m/s^2 (rad/s^2 for an arm)"),
        max_jerk=check(max_jerk, "max_jerk", "m/s^3 (rad/s^3 for an arm)"),
        max_pressure_angle=check(max_pressure_angle, "max_pressure_angle", "rad", 0.0, math.pi / 2),
        min_radius=check(min_radius, "min_radius", "m"),
        min_force=None if min_force is None else float(min_force),
        max_output_acceleration=check(max_output_acceleration, "max_output_acceleration", "m/s^2 (rad/s^2 for an arm)"),
        max_stress=check(max_stress, "max_stress", "Pa"),
    )


def synthesize(
    system,
    *,
    contact: Optional[str] = None,
    output: Optional[str] = None,
    objective: str = "residual",
    measure: str = "rms",
    speeds_rpm: Optional[Sequence[float]] = None,
    band: float = 0.0,
    band_speeds_count: int = 5,
    robust: str = "worst",
    segments: Optional[Sequence[int]] = None,
    nodes: int = 8,
    continuity: int = 6,
    start: Optional[MotionProgram] = None,
    max_acceleration: Optional[float] = None,
    max_jerk: Optional[float] = None,
    max_pressure_angle: Optional[float] = None,
    min_radius: Optional[float] = None,
    min_force: Optional[float] = None,
    max_output_acceleration: Optional[float] = None,
    max_stress: Optional[float] = None,
    line_contact: Optional[_core.LineContact] = None,
    accuracy: float = 1e-4,
    steps_per_revolution: Optional[int] = None,
    max_iterations: int = 12,
    max_evaluations: int = 600,
    tolerance: float = 1e-3,
    target: float = 1e-6,
    workers: int = 2,
) -> SynthesisResult:
    """Redesign the rises and returns of ``contact``'s program (default: the first contact) so that
    the flexible mechanism's ``output`` DOF (default: the contact's follower DOF) moves as the
    objective asks, at one speed or over a band, under kinematic and contact limits.

    **Unknowns.** Each redesigned segment (``segments``: indices into the program, default every
    rise and return) becomes a spline through its lift at ``nodes`` equally spaced stations, of the
    degree that joins its neighbours with ``continuity`` continuous derivatives (2, 4 or 6: degree 3,
    5, 7); the end lifts and angles stay. The start is the program's own lift at the stations, or
    ``start``'s (e.g. a :func:`polydyne` lift).

    **Objective** on the periodic steady state: ``"residual"`` (the output less its quasi-static
    path, in the dwells), ``"follower_error"`` (the same over the whole revolution) or
    ``"acceleration"`` (the output's); ``measure`` ``"rms"`` or ``"peak"``; over ``speeds_rpm`` (default:
    the system's speed, and with ``band`` = 0.2 ``band_speeds_count`` speeds over +/-20 % of it), the
    ``robust`` combination ``"worst"`` (the largest) or ``"average"``.

    **Limits** (None: not imposed): ``max_acceleration`` and ``max_jerk`` of the rigid follower at
    the design speed (m/s^2, m/s^3; rad/s^2, rad/s^3 for an arm), ``max_pressure_angle`` (rad) and the
    cam surface's least convex radius of curvature ``min_radius`` (m) over the redesigned segments,
    the contact force's least value ``min_force`` (N) at every speed (no jump), the output's peak
    |acceleration| in the flexible response at the design speed ``max_output_acceleration`` (m/s^2,
    rad/s^2: the rigid peak plus what the mechanism's vibration adds), the Hertz pressure ``max_stress``
    (Pa) of the contact force at every sample of every speed, for the roller ``line_contact`` (a
    LineContact: width, materials). A limit no lift can
    meet is refused before any simulation, naming it.

    **Method and cost.** Trust-region Gauss-Newton: a finite-difference Jacobian of the objective's
    samples (one steady state per station and speed, on ``workers`` threads, warm-started from the
    current orbit), SLSQP on the model under the linearized limits, the candidate simulated and
    accepted only if it improves. The step is fixed at ``steps_per_revolution`` (default: the one
    the studies' accuracy search picks for the start lift at the fastest speed, ``accuracy``).
    Stops when a step improves the objective by less than ``tolerance`` of it or the objective is
    below ``target`` times the start's (``converged``; rms objectives compare mean squares), or at
    ``max_iterations`` / ``max_evaluations`` steady states (not converged: ``message`` says why and
    the best feasible program found is returned).
    """
    t0 = time.perf_counter()
    if robust not in ROBUST:
        raise ValueError(f"robust must be one of {list(ROBUST)}, got {robust!r}")
    if isinstance(continuity, bool) or not isinstance(continuity, numbers.Integral):
        raise ValueError(f"continuity must be an integer 2..6, got {continuity!r}")
    degree = degree_for(int(continuity))
    for name, value, low, high in (
        ("max_iterations", max_iterations, 1, 100),
        ("max_evaluations", max_evaluations, 2, 100000),
        ("workers", workers, 1, 64),
    ):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) or not low <= value <= high:
            raise ValueError(f"{name} must be an integer in [{low}, {high}], got {value!r}")
    if isinstance(tolerance, bool) or not isinstance(tolerance, numbers.Real) or not 1e-8 <= tolerance <= 0.5:
        raise ValueError(f"tolerance must be a relative improvement in [1e-08, 0.5], got {tolerance!r}")
    if isinstance(target, bool) or not isinstance(target, numbers.Real) or not 0.0 <= target < 1.0:
        raise ValueError(f"target must be a fraction of the start's objective in [0, 1), got {target!r}")
    c, _ = check_objective(system, contact, output, objective, measure)
    follower = next(x["follower"] for x in system.builder().contacts if x["name"] == c["name"])
    space = LiftSpace(c["program"], segments, nodes, degree)
    design = float(system.camshaft_speed_rpm)
    speeds = band_speeds(design, band, band_speeds_count) if speeds_rpm is None else _speed_list(speeds_rpm)
    limits = _limits(
        max_acceleration, max_jerk, max_pressure_angle, min_radius, min_force, max_output_acceleration, max_stress
    )
    if (limits.max_stress is None) != (line_contact is None):
        raise ValueError(
            "max_stress and line_contact go together: the Hertz pressure needs the roller's width and materials "
            "(a camfollower.LineContact)"
        )
    if line_contact is not None and not isinstance(line_contact, _core.LineContact):
        raise ValueError(f"line_contact must be a camfollower.LineContact, got {type(line_contact).__name__}")
    if limits.min_force is not None and c["grooved"]:
        raise ValueError(f"min_force: contact {c['name']!r} is grooved (form-closed): it has no contact margin to keep")
    omega = speeds[0] * _RPM
    _check_reachable(space, follower, limits, omega)
    if start is not None and not isinstance(start, MotionProgram):
        raise ValueError(f"start must be a MotionProgram or None, got {type(start).__name__}")
    p0 = space.start(start)
    try:
        first = with_program(system, c["name"], space.program(p0))
    except ValueError as e:
        raise ValueError(
            f"the start lift through {nodes} stations per segment (degree {degree}: continuity {continuity}) is "
            f"refused: {e}. More nodes, a lower continuity or a start closer to a feasible lift may help"
        ) from None
    if steps_per_revolution is None:
        fastest = first.with_camshaft_speed_rpm(max(speeds))
        try:
            steps_per_revolution = steady_response(
                fastest, contact=c["name"], accuracy=accuracy, multipliers=False, harmonics=1
            )["steps_per_revolution"]
        except RuntimeError as e:
            raise ValueError(not_periodic(max(speeds), e)) from None
    dynamics = Dynamics(system, c["name"], output, objective, measure, speeds, steps_per_revolution, line_contact)
    optimizer = Optimizer(space, dynamics, follower, limits, robust, int(workers), int(max_evaluations))
    out = optimizer.run(p0, int(max_iterations), float(tolerance), float(target))
    best, first = out["best"], out["start"]
    program, start_program = space.program(best.p), space.program(first.p)
    measure_of = dynamics.measure_of
    start_kin = _kinematics(start_program, follower, omega, space)
    final_kin = _kinematics(program, follower, omega, space)
    named = limits.named()
    limit_rows = {
        k: {"limit": v, "start": start_kin.get(k, math.nan), "final": final_kin.get(k, math.nan)}
        for k, v in named.items()
        if k not in ("min_force", "max_output_acceleration", "max_stress")
    }
    if limits.min_force is not None:
        limit_rows["min_force"] = {
            "limit": limits.min_force,
            "start": min(s.min_force for s in first.samples),
            "final": min(s.min_force for s in best.samples),
        }
    if limits.max_stress is not None:
        limit_rows["max_stress"] = {
            "limit": limits.max_stress,
            "start": max(float(np.max(s.stress)) for s in first.samples),
            "final": max(float(np.max(s.stress)) for s in best.samples),
        }
    if limits.max_output_acceleration is not None:
        limit_rows["max_output_acceleration"] = {
            "limit": limits.max_output_acceleration,
            "start": first.samples[0].peak_acceleration,
            "final": best.samples[0].peak_acceleration,
        }
    return SynthesisResult(
        program=program,
        start_program=start_program,
        system=with_program(system, c["name"], program),
        contact=c["name"],
        output=dynamics.output,
        objective=objective,
        measure=measure,
        robust=robust,
        speeds_rpm=tuple(speeds),
        converged=bool(out["converged"]),
        message=out["message"],
        iterations=max(h["iteration"] for h in optimizer.history),
        evaluations=dynamics.evaluations,
        revolutions=dynamics.revolutions,
        wall_time=time.perf_counter() - t0,
        steps_per_revolution=int(steps_per_revolution),
        objective_start=tuple(measure_of(s.values) for s in first.samples),
        objective_final=tuple(measure_of(s.values) for s in best.samples),
        limits=limit_rows,
        kinematics={"start": start_kin, "final": final_kin},
        stations={i: list(space.stations(i)) for i in space.segments},
        history=optimizer.history,
    )


def _speed_list(speeds) -> List[float]:
    try:
        values = list(speeds)
    except TypeError:
        raise ValueError(f"speeds_rpm must be a list of speeds (rpm), got {speeds!r}") from None
    if not values:
        raise ValueError("speeds_rpm must hold at least one speed (rpm)")
    return [_speed(v, f"speeds_rpm[{i}]") for i, v in enumerate(values)]


def with_laws(program: MotionProgram, law: str) -> MotionProgram:
    """``program`` with every rise and return replaced by the catalogue law ``law`` (the same angles and
    lifts): the designs a synthesis is compared with."""
    if law not in CATALOGUE and not hasattr(_core.MotionLaw, law):
        raise ValueError(f"law must be a catalogue law such as {list(CATALOGUE)}, got {law!r}")
    made = getattr(_core.MotionLaw, law)()
    return MotionProgram(
        [
            s if s.h_end == s.h_start else _core.Segment(made, s.theta_start, s.theta_end, s.h_start, s.h_end)
            for s in program.segments
        ]
    )


def verify(
    system,
    program: MotionProgram,
    speeds_rpm: Sequence[float],
    *,
    contact: Optional[str] = None,
    output: Optional[str] = None,
    accuracy: float = 1e-4,
) -> List[Dict[str, Any]]:
    """``program`` in ``system`` simulated afresh at each speed (a new periodic steady state at
    ``accuracy``, nothing reused from an optimizer): per speed ``rpm``, ``residual`` (the output's
    largest peak-to-peak over a dwell, less its quasi-static path; m or rad) from the orbit at twice
    the steps the accuracy search settled on, ``residual_error`` (its change from that step: a lift
    tuned at one step can be quieter in that discrete model than in the mechanism), ``residual_rms``
    (its rms over the dwells), ``max_abs_acceleration`` of the output and the rigid follower's
    ``rigid_max_abs_acceleration`` (contact's follower), ``min_force_N``, ``contact_lost``,
    ``accuracy`` reached and ``steps_per_revolution``."""
    c = contact_of(system, contact)
    dof = c["dof"] if output is None else output
    if dof not in list(system.dof_names):
        raise ValueError(f"output: unknown DOF {dof!r}; the mechanism's DOFs are {list(system.dof_names)}")
    base = with_program(system, c["name"], program)
    rows = []
    for rpm in _speed_list(speeds_rpm):
        s = base.with_camshaft_speed_rpm(rpm)
        row = steady_response(
            s,
            contact=c["name"],
            accuracy=accuracy,
            multipliers=False,
            harmonics=1,
            keep_orbit=True,
            channels=[],
            fallback="transient",  # a design that loses contact is reported, not refused
            tolerance=SHOOTING_TOLERANCE,
        )
        # The residual again at twice the steps, from this orbit: a lift tuned at one step can be quieter
        # in that discrete model than in the mechanism; the difference is the residual's accuracy.
        steps = int(row["steps_per_revolution"])
        periodic = row["method"] == "shooting" and row["converged"]
        coarse = _reduce(s, c, dof, row["orbit"])
        reduced = coarse
        if periodic:
            finer = periodic_steady_state(
                s,
                time_step=s.period / (2 * steps),
                guess=row["orbit"],
                multipliers=False,
                **scheme_settings(scheme_at(s, 2 * steps, row["scheme"])),
                tolerance=SHOOTING_TOLERANCE,
            )
            reduced, steps = _reduce(s, c, dof, finer), 2 * steps
        rows.append(
            {
                "rpm": rpm,
                "residual": float(reduced["dwell_peak_to_peak"]),
                "residual_error": abs(float(reduced["dwell_peak_to_peak"]) - float(coarse["dwell_peak_to_peak"]))
                if periodic
                else math.nan,
                "residual_rms": float(reduced["dwell_rms"]),
                "max_abs_acceleration": float(reduced["peak_acceleration"]),
                "rigid_max_abs_acceleration": row["rigid_max_abs_acceleration"],
                "min_force_N": row["min_force_N"],
                "contact_lost": row["contact_lost"],
                "periodic": periodic,
                "accuracy": row["accuracy"],
                "steps_per_revolution": steps,
            }
        )
    return rows


def _reduce(system, c, dof: str, orbit) -> Dict[str, Any]:
    """One recorded revolution of ``orbit`` reduced by the library (synthesis/lift_samples.hpp), in the
    system's own program's dwells."""
    record = orbit.record(system)
    return _core._lift_samples(
        system,
        c["name"],
        dof,
        "follower_error",
        np.asarray(record["theta"])[1:],
        np.asarray(record[f"q.{dof}"])[1:],
        np.asarray(record[f"a.{dof}"])[1:],
        np.asarray(record[f"{c['name']}.force"])[1:],
        c["program"],
    )


__all__ = [
    "CATALOGUE",
    "SynthesisResult",
    "band_speeds",
    "polydyne",
    "snap_jumps",
    "synthesize",
    "verify",
    "with_laws",
]
