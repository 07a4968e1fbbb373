# SPDX-License-Identifier: BSD-3-Clause
"""Monte-Carlo tolerance studies: what a design's tolerances cost in contact margin, accelerations and
residual vibration.

Each toleranced parameter gets a distribution of its deviation from the nominal value
(:class:`Normal`, :class:`Uniform`, :class:`TruncatedNormal`; absolute in SI units, or ``relative``
to the nominal). Case ``i`` of a study with seed ``s`` draws its values from
``numpy.random.default_rng([s, i])``: any case can be rerun alone, and a study's cases do not depend on
how many there are or on which executor ran them. Every case is solved for its periodic steady state
by shooting from its own static equilibrium (about 18 revolutions per case for the paper's mechanism;
starting from the nominal orbit does not save revolutions: a few micrometres of eccentricity move the
orbit by more than the contact deflection).

A model is described by a picklable builder, ``build(values: dict) -> Mechanism`` with
``build.nominal(name)``: :class:`PaperCase` (the paper's mechanism: every ``Parameters`` name, the cam's
``eccentricity`` and a profile ``waviness`` amplitude, the guide clearance, the damping ratio) or
:class:`ConfigCase` (any numeric value of a config file by its key path, e.g.
``"contact.0.follower.offset"`` or ``"preset.parameters.contact_stiffness"``).

A roller radius is a tolerance against the machined cam: the cam is cut once, for the nominal roller,
and a roller of another radius rolls on that cam and follows the lift its centre takes there
(:func:`roller_on_fixed_cam`), not the design lift (``roller_tolerance="fixed_cam"``, the default of
both builders). ``roller_tolerance="regenerated_cam"`` keeps the design lift for every roller, as if
each cam were cut again for its roller.

Out-of-range values are refused before anything runs: the model is built at each bounded
distribution's ends (for a normal distribution at +-4 standard deviations); a bound the model rejects
stops the study with the model's message naming the parameter (use a TruncatedNormal to stay inside
a valid range). Results: :class:`MonteCarloResult` (rows, a pandas DataFrame, Parquet, summary
statistics, sensitivities, plots).
"""

from __future__ import annotations

import copy
import dataclasses
import functools
import math
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple

import numpy as np

from . import _core, _text
from .executors import check_executor, run_cases
from .response import ACCURACY_OF, check_accuracy, check_accuracy_of, steady_response

#: Metrics of each case kept in the table (from camfollower.response.steady_response).
METRICS = (
    "min_force_N",
    "min_force_angle_deg",
    "max_force_N",
    "contact_lost",
    "lost_fraction",
    "max_abs_acceleration",
    "dwell_residual",
    "converged",
    "revolutions",
    "iterations",
    "accuracy",
    "steps_per_revolution",
)


def _finite(name: str, v) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise ValueError(f"{name} must be a finite number, got {_echo(v)}")
    return float(v)


def _flag(name: str, v) -> None:
    # `relative = "no"` would be truthy: a flag is a bool or nothing.
    if not isinstance(v, bool):
        raise ValueError(f"{name} must be True or False, got {_echo(v)}")


def _echo(v) -> str:
    text = "".join(c if c.isprintable() else "?" for c in repr(v))
    return text if len(text) <= 60 else text[:60] + "..."


@dataclass(frozen=True)
class Normal:
    """Deviation ~ N(mean, std^2); ``relative``: as a fraction of the nominal value."""

    std: float
    mean: float = 0.0
    relative: bool = False

    def __post_init__(self):
        if _finite("Normal std", self.std) < 0:
            raise ValueError(f"Normal std must be >= 0 (a spread), got {self.std}")
        _finite("Normal mean", self.mean)
        _flag("Normal relative", self.relative)

    def sample(self, rng) -> float:
        return self.mean + self.std * rng.standard_normal()

    def extremes(self) -> Tuple[float, float]:
        return self.mean - 4 * self.std, self.mean + 4 * self.std


@dataclass(frozen=True)
class Uniform:
    """Deviation ~ U(low, high); ``relative``: as a fraction of the nominal value."""

    low: float
    high: float
    relative: bool = False

    def __post_init__(self):
        if _finite("Uniform high", self.high) < _finite("Uniform low", self.low):
            raise ValueError(f"Uniform needs low <= high (a non-negative spread), got low {self.low}, high {self.high}")
        _flag("Uniform relative", self.relative)

    def sample(self, rng) -> float:
        return self.low + (self.high - self.low) * rng.random()

    def extremes(self) -> Tuple[float, float]:
        return self.low, self.high


@dataclass(frozen=True)
class TruncatedNormal:
    """Deviation ~ N(mean, std^2) restricted to [low, high] (redrawn until inside); ``relative``: as a
    fraction of the nominal value. The interval must hold at least 1e-3 of the probability."""

    std: float
    low: float
    high: float
    mean: float = 0.0
    relative: bool = False

    def __post_init__(self):
        if _finite("TruncatedNormal std", self.std) <= 0:
            raise ValueError(f"TruncatedNormal std must be > 0, got {self.std}")
        if _finite("TruncatedNormal high", self.high) <= _finite("TruncatedNormal low", self.low):
            raise ValueError(f"TruncatedNormal needs low < high, got low {self.low}, high {self.high}")
        _finite("TruncatedNormal mean", self.mean)
        _flag("TruncatedNormal relative", self.relative)
        cdf = lambda x: 0.5 * (1 + math.erf((x - self.mean) / (self.std * math.sqrt(2))))  # noqa: E731
        if cdf(self.high) - cdf(self.low) < 1e-3:
            raise ValueError(
                f"TruncatedNormal [{self.low}, {self.high}] holds less than 1e-3 of N({self.mean}, "
                f"{self.std}^2): widen the interval or move the mean"
            )

    def sample(self, rng) -> float:
        while True:
            x = self.mean + self.std * rng.standard_normal()
            if self.low <= x <= self.high:
                return x

    def extremes(self) -> Tuple[float, float]:
        return self.low, self.high


DISTRIBUTIONS = {"normal": Normal, "uniform": Uniform, "truncated_normal": TruncatedNormal}


def distribution(spec: Mapping[str, Any]):
    """A distribution from a dict (config files): {"distribution": "normal", "std": ..., ...}."""
    spec = dict(spec)
    kind = spec.pop("distribution", None)
    if not isinstance(kind, str) or kind not in DISTRIBUTIONS:  # a dict or list is unhashable: no `in` first
        raise ValueError(f"distribution must be one of {list(DISTRIBUTIONS)}, got {_echo(kind)}")
    cls = DISTRIBUTIONS[kind]
    fields = [f.name for f in dataclasses.fields(cls)]
    for key in spec:
        if key not in fields:
            raise ValueError(f"{kind} distribution: unknown key {_echo(key)}; known: {', '.join(fields)}")
    for f in dataclasses.fields(cls):
        if f.name not in spec and f.default is dataclasses.MISSING:
            raise ValueError(f"{kind} distribution: the key {f.name!r} is required")
    return cls(**spec)


_TWO_PI = 2.0 * math.pi

#: Builders' ways of tolerancing a roller radius: "fixed_cam" (the roller rolls on the cam cut for the
#: nominal roller) or "regenerated_cam" (the cam is cut again for each roller: the design lift for all).
ROLLER_TOLERANCES = ("fixed_cam", "regenerated_cam")

#: Spacing (rad, along the cam) of the lift table :func:`roller_on_fixed_cam` samples: 0.1 deg.
FIXED_CAM_STEP = math.radians(0.1)


def _roller_tolerance(value) -> str:
    if not isinstance(value, str) or value not in ROLLER_TOLERANCES:
        raise ValueError(f"roller_tolerance must be one of {', '.join(ROLLER_TOLERANCES)}, got {_echo(value)}")
    return value


def _wrap(x):
    return (np.asarray(x) + math.pi) % _TWO_PI - math.pi


def _on_fixed_cam(follower, design, radius: float, t):
    """Where a roller of ``radius`` sits when it touches the cam surface point that the cam's own roller
    touches at cam angle ``t`` (rad, array), with the same normal: the cam angle theta(t) at which that
    happens and the roller's lift s(t) there (m, or rad for an arm). Closed form: the new roller's centre
    is the surface point moved ``radius`` along the normal (cam frame); theta turns it onto the follower's
    path (a line, or the arm's circle about its pivot)."""
    p = follower.profile(design, t)
    r = follower.roller_radius
    sx, sy = p["surface_x"], p["surface_y"]
    x = sx + radius * (p["reference_x"] - sx) / r
    y = sy + radius * (p["reference_y"] - sy) / r
    rho2, psi = x * x + y * y, np.arctan2(y, x)
    if isinstance(follower, _core.TranslatingRoller):
        e = follower.offset
        height = np.sqrt(rho2 - e * e)  # the centre at (e, height) in the ground frame
        theta = np.arctan2(height, e) - psi
        lift = height - math.sqrt((follower.base_radius + radius) ** 2 - e * e)
    else:  # OscillatingRoller: the centre at distance |X| from the cam axis and arm_length from the pivot
        pivot = np.asarray(follower.pivot, dtype=float).reshape(2)
        arm, d = follower.arm_length, float(np.hypot(pivot[0], pivot[1]))
        ux, uy = pivot / d
        c, s = np.cos(t), np.sin(t)
        gx, gy = c * p["reference_x"] - s * p["reference_y"], s * p["reference_x"] + c * p["reference_y"]
        side = np.where(ux * gy - uy * gx >= 0.0, 1.0, -1.0)  # the cam roller's side of the line axis-pivot
        along = (rho2 - arm * arm + d * d) / (2.0 * d)
        across2 = rho2 - along * along
        if np.any(across2 < 0.0):
            k = int(np.argmax(across2 < 0.0))
            raise ValueError(
                f"roller_radius: a roller of {radius:.6g} m cannot touch the cam at "
                f"{math.degrees(float(t[k])):.4g} deg on an arm of {arm:.6g} m"
            )
        across = side * np.sqrt(across2)
        cx, cy = along * ux - across * uy, along * uy + across * ux
        theta = np.arctan2(cy, cx) - psi
        sigma = 1.0 if follower.turn == "counter_clockwise" else -1.0
        start = _core.OscillatingRoller(follower.base_radius, radius, pivot, arm, follower.turn).start_angle
        lift = sigma * _wrap(np.arctan2(cy - pivot[1], cx - pivot[0]) - start)
    return t + _wrap(theta - t), lift


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _end_derivatives(follower, segment, radius: float, t: float) -> List[float]:
    """ds/dtheta and d2s/dtheta2 of the new roller's lift where it touches the surface point of cam
    parameter ``t`` (rad), from ``segment``'s own lift and its first three derivatives there (one-sided
    at its ends): the chain rule through the closed form of :func:`_on_fixed_cam`, in the frame turned by
    t, where the cam's roller has its centre at C(t) and normal n(t), the new one at G = C + (radius - r) n."""
    theta = min(max(t, segment.theta_start), segment.theta_end)
    v = segment.lift_at(np.array([theta]))
    h, h1, h2, h3 = (float(v[k][0]) for k in ("h", "dh", "d2h", "d3h"))

    def J(a):
        return np.array([-a[1], a[0]])

    if isinstance(follower, _core.TranslatingRoller):
        e = follower.offset
        s0 = math.sqrt((follower.base_radius + follower.roller_radius) ** 2 - e * e)
        C, C1, C2, C3 = (np.array(x, dtype=float) for x in ((e, s0 + h), (0.0, h1), (0.0, h2), (0.0, h3)))
    else:
        pivot, arm = np.asarray(follower.pivot, dtype=float).reshape(2), follower.arm_length
        sigma = 1.0 if follower.turn == "counter_clockwise" else -1.0
        phi = follower.start_angle + sigma * h
        u = np.array([math.cos(phi), math.sin(phi)])
        C = pivot + arm * u
        C1 = sigma * arm * h1 * J(u)
        C2 = sigma * arm * h2 * J(u) - arm * h1 * h1 * u
        C3 = sigma * arm * (h3 - h1**3) * J(u) - 3.0 * arm * h1 * h2 * u
    N, N1, N2 = C + J(C1), C1 + J(C2), C2 + J(C3)
    m = math.hypot(*N)
    a, b = N @ N1, N1 @ N1 + N @ N2
    n1 = N1 / m - N * a / m**3
    n2 = N2 / m - 2.0 * N1 * a / m**3 - N * b / m**3 + 3.0 * N * a * a / m**5
    d = radius - follower.roller_radius
    G, G1, G2 = C + d * N / m, C1 + d * n1, C2 + d * n2
    r2 = G @ G
    rho = math.sqrt(r2)
    rho1 = (G @ G1) / rho
    rho2 = (G1 @ G1 + G @ G2) / rho - (G @ G1) ** 2 / rho**3
    ang1 = _cross(G, G1) / r2
    ang2 = _cross(G, G2) / r2 - 2.0 * _cross(G, G1) * (G @ G1) / r2**2
    if isinstance(follower, _core.TranslatingRoller):
        # the centre at (e, Y), Y = sqrt(rho^2 - e^2); theta - t = atan2(Y, e) - angle(G)
        Y = math.sqrt(r2 - e * e)
        Y1 = rho * rho1 / Y
        Y2 = (rho1**2 + rho * rho2) / Y - (rho * rho1) ** 2 / Y**3
        beta1 = e * Y1 / r2
        beta2 = e * Y2 / r2 - 2.0 * e * Y1 * rho * rho1 / r2**2
        th1, th2, s1, s2 = 1.0 + beta1 - ang1, beta2 - ang2, Y1, Y2
    else:
        # the centre Q = A p + side B Jp, rho from the axis and arm from the pivot; theta - t = angle(Q) - angle(G)
        dist = math.hypot(*pivot)
        p = pivot / dist
        A = (r2 - arm * arm + dist * dist) / (2.0 * dist)
        A1, A2 = rho * rho1 / dist, (rho1**2 + rho * rho2) / dist
        B = math.sqrt(r2 - A * A)
        B1 = (rho * rho1 - A * A1) / B
        B2 = (rho1**2 + rho * rho2 - A1**2 - A * A2) / B - (rho * rho1 - A * A1) ** 2 / B**3
        side = 1.0 if _cross(p, C) >= 0.0 else -1.0
        Q, Q1, Q2 = (x * p + side * y * J(p) for x, y in ((A, B), (A1, B1), (A2, B2)))
        gam1 = _cross(Q, Q1) / r2
        gam2 = _cross(Q, Q2) / r2 - 2.0 * _cross(Q, Q1) * (Q @ Q1) / r2**2
        R = Q - pivot  # |R| = arm, so R . Q' = 0: the arm angle's rates are R x Q' / arm^2 and R x Q'' / arm^2
        th1, th2 = 1.0 + gam1 - ang1, gam2 - ang2
        s1, s2 = sigma * _cross(R, Q1) / arm**2, sigma * _cross(R, Q2) / arm**2
    return [s1 / th1, (s2 * th1 - s1 * th2) / th1**3]


def roller_on_fixed_cam(follower, program, roller_radius: float, *, step: float = FIXED_CAM_STEP):
    """The follower with a roller of ``roller_radius`` (m) and the lift it follows on the cam cut for
    ``follower``'s own roller and ``program``: ``(follower, program)``, to put in a contact in their place.

    The cam is the surface ``follower`` generates with ``program`` (a TranslatingRoller or
    OscillatingRoller). The other roller's centre stays ``roller_radius`` from that surface, along its
    normal: on a dwell (a circular arc about the cam axis) the lift stays constant (the same level for a
    centred translating roller; an offset or an arm moves the level slightly), on a rise or return it
    differs. The lift is computed in closed form per surface point and made a program of the same
    pieces: each dwell a dwell, each other segment a quintic B-spline table (``step`` rad apart along
    the cam, 0.1 deg) with its end slope and curvature; the pieces start and end where the new roller
    meets the old segment ends (a few hundredths of a degree from them for 0.1 mm). A profile error the
    program carries is kept as it is (as measured with the nominal roller). The same radius gives back
    ``follower`` and ``program``. The lift is measured from the new roller's own rest on the base circle
    (which moves by about the radius difference): a spring set against fixed geometry rather than at
    assembly would change its preload by that shift, which this does not model.

    A roller larger than a concave flank's radius cannot follow it (it would bridge the hollow) and a
    radius outside (0, 1 m] is refused: ValueError naming ``roller_radius``.
    """
    if not isinstance(follower, (_core.TranslatingRoller, _core.OscillatingRoller)):
        raise ValueError(
            f"roller_on_fixed_cam needs a TranslatingRoller or OscillatingRoller follower, got "
            f"{type(follower).__name__}"
        )
    radius = _finite("roller_radius", roller_radius)
    if not 0.0 < radius <= 1.0:
        raise ValueError(f"roller_radius must be in (0, 1] m, got {roller_radius!r}")
    if not (isinstance(step, float) and 1e-5 <= step <= math.radians(5.0)):
        raise ValueError(f"step must be in [1e-5, {math.radians(5.0):.6g}] rad, got {_echo(step)}")
    if radius == follower.roller_radius:
        return follower, program
    if isinstance(follower, _core.TranslatingRoller):
        new = _core.TranslatingRoller(follower.base_radius, radius, follower.offset)
    else:
        new = _core.OscillatingRoller(
            follower.base_radius, radius, np.asarray(follower.pivot).reshape(2), follower.arm_length, follower.turn
        )
    error = program.profile_error
    design = program.with_profile_error(_core.ProfileError()) if error else program
    # A concave flank of radius below the roller's: the roller cannot reach its bottom.
    t = np.linspace(0.0, _TWO_PI, int(math.ceil(_TWO_PI / step)) * 4, endpoint=False)
    surface = np.asarray(follower.profile(design, t)["surface_radius"])
    hollow = (surface < 0.0) & (-surface <= radius)
    if hollow.any():
        k = int(np.argmax(hollow))
        raise ValueError(
            f"roller_radius: a roller of {radius:.6g} m does not fit the cam's concave flank of radius "
            f"{-surface[k]:.6g} m at {math.degrees(t[k]):.4g} deg (the cam was cut for "
            f"{follower.roller_radius:.6g} m): it would bridge the hollow"
        )

    def path(t):
        return _on_fixed_cam(follower, design, radius, np.atleast_1d(np.asarray(t, dtype=float)))

    segments = design.segments
    bounds = [seg.theta_start for seg in segments] + [_TWO_PI]
    dwell = [seg.law.name == "dwell" for seg in segments]
    t0 = 0.0  # the surface point the new roller touches at cam angle 0 (a fixed point of t -> t - theta(t))
    for _ in range(100):
        move = float(path(t0)[0][0])
        t0 -= move
        if abs(move) < 1e-15:
            break
    # Pieces [ta, tb] of cam parameter between the segment ends, over one turn from t0 (cam angle 0 to
    # 2 pi), each with its segment j, that segment's turn (a multiple of 2 pi) and whether it is a dwell.
    cuts = sorted({b + k * _TWO_PI for b in bounds for k in (-1, 0, 1) if t0 < b + k * _TWO_PI < t0 + _TWO_PI})
    edges = np.array([t0, *cuts, t0 + _TWO_PI])
    theta_e, lift_e = path(edges)
    theta_e[0], theta_e[-1] = 0.0, _TWO_PI
    pieces = []
    for i in range(len(edges) - 1):
        mid = 0.5 * (edges[i] + edges[i + 1])
        turn = math.floor(mid / _TWO_PI) * _TWO_PI
        j = int(np.searchsorted(bounds, mid - turn, side="right")) - 1
        pieces.append([edges[i], edges[i + 1], theta_e[i], theta_e[i + 1], lift_e[i], lift_e[i + 1], j, turn])
    # A boundary moved to within 2e-6 rad of another (or of 0): the sliver joins its neighbour.
    while len(pieces) > 1:
        k = next((i for i, q in enumerate(pieces) if q[3] - q[2] < 2e-6), None)
        if k is None:
            break
        n = k + 1 if k + 1 < len(pieces) else k - 1
        a, b = min(k, n), max(k, n)
        pieces[a : b + 1] = [
            [
                pieces[a][0],
                pieces[b][1],
                pieces[a][2],
                pieces[b][3],
                pieces[a][4],
                pieces[b][5],
                pieces[n][6],
                pieces[n][7],
            ]
        ]
    for i, q in enumerate(pieces):  # a dwell is level (its ends differ by rounding): the next piece starts there
        if dwell[q[6]]:
            q[5] = q[4]
            if i + 1 < len(pieces):
                pieces[i + 1][4] = q[4]
    out = []
    for ta, tb, tha, thb, sa, sb, j, turn in pieces:
        if dwell[j]:
            out.append(_core.Segment(_core.MotionLaw.dwell(), tha, thb, sa, sa))
            continue
        tg = np.linspace(ta, tb, max(16, int(math.ceil((tb - ta) / step))) + 1)
        thg, sg = path(tg)
        if np.any(np.diff(thg) <= 0.0):
            k = int(np.argmax(np.diff(thg) <= 0.0))
            raise ValueError(
                f"roller_radius: a roller of {radius:.6g} m does not follow the cam cut for "
                f"{follower.roller_radius:.6g} m near {math.degrees(thg[k]):.4g} deg"
            )
        thg[0], thg[-1], sg[0], sg[-1] = tha, thb, sa, sb
        out.append(
            _core.Segment.from_table(
                thg,
                sg,
                5,
                0.0,
                _end_derivatives(follower, segments[j], radius, ta - turn),
                _end_derivatives(follower, segments[j], radius, tb - turn),
            )
        )
    result = _core.MotionProgram(out)
    return new, (result.with_profile_error(error) if error else result)


def _fixed_cam(actual, cam):
    """``actual`` (a Mechanism) with every roller whose radius differs from the one in ``cam`` (the same
    mechanism built with the nominal rollers) running on ``cam``'s cam: its contact's program replaced
    by the lift it follows there."""
    state, cam_state = actual.__getstate__(), cam.__getstate__()
    changed = False
    for c, nominal in zip(state["contacts"], cam_state["contacts"]):
        f, g = c["follower"], nominal["follower"]
        if (
            isinstance(f, (_core.TranslatingRoller, _core.OscillatingRoller))
            and type(f) is type(g)
            and f.roller_radius != g.roller_radius
        ):
            c["program"] = roller_on_fixed_cam(g, nominal["program"], f.roller_radius)[1]
            changed = True
    if not changed:
        return actual
    out = type(actual).__new__(type(actual))
    out.__setstate__(state)
    return out


def _is_roller_radius(name: str) -> bool:
    return name.rsplit(".", 1)[-1] == "roller_radius"


class PaperCase:
    """Builder of the paper's mechanism (presets.paper) from named values: every ``Parameters`` name,
    ``eccentricity`` (m, the cam centre's offset; exact geometry), ``waviness`` (m, amplitude of a
    profile error of ``waviness_order`` waves per revolution), ``guide_clearance`` (m, radial) and
    ``element_damping_ratio``. ``fixed`` values apply to every case (e.g. camshaft_speed_rpm).

    ``roller_radius`` against ``roller_tolerance="fixed_cam"`` (default): the cam is the one cut for the
    nominal roller (``fixed`` or the Table 2 value), and a roller of another radius follows the lift it
    takes on that cam (:func:`roller_on_fixed_cam`); ``"regenerated_cam"``: the design lift whatever the
    roller (a cam cut again for each)."""

    EXTRA = {"eccentricity": 0.0, "waviness": 0.0, "guide_clearance": 0.0, "element_damping_ratio": 0.0}

    def __init__(self, waviness_order: int = 10, *, roller_tolerance: str = "fixed_cam", **fixed):
        self.waviness_order = int(waviness_order)
        self.roller_tolerance = _roller_tolerance(roller_tolerance)
        self.fixed = dict(fixed)
        for k in self.fixed:
            self._check(k)

    def _check(self, name: str) -> None:
        if name not in self.EXTRA and name not in _core.Parameters.names():
            raise ValueError(
                f"PaperCase: unknown parameter {name!r}; known: {_core.Parameters.names() + list(self.EXTRA)}"
            )

    def nominal(self, name: str) -> float:
        self._check(name)
        if name == "contact_damping":
            raise ValueError(
                "PaperCase: contact_damping is a model choice, not a number to scatter; "
                "fix it with PaperCase(contact_damping=...)"
            )
        if name in self.fixed:
            return float(self.fixed[name])
        return self.EXTRA[name] if name in self.EXTRA else _core.Parameters().get(name)

    def _build(self, values: Mapping[str, float]):
        from . import presets

        v = {**self.fixed, **values}
        extra = {k: v.pop(k) for k in list(v) if k in self.EXTRA}
        program = _core.MotionProgram.paper_default()
        if extra.get("waviness", 0.0):
            program = program.with_profile_error(_core.ProfileError.waviness(extra["waviness"], self.waviness_order))
        ecc = _core.CamEccentricity(extra["eccentricity"]) if extra.get("eccentricity", 0.0) else None
        return presets.paper(
            _core.Parameters(**v),
            program,
            eccentricity=ecc,
            guide_clearance=extra.get("guide_clearance", 0.0),
            element_damping_ratio=extra.get("element_damping_ratio", 0.0),
        )

    def __call__(self, values: Mapping[str, float]):
        m = self._build(values)
        if self.roller_tolerance == "fixed_cam" and "roller_radius" in values:
            m = _fixed_cam(m, self._build({**values, "roller_radius": self.nominal("roller_radius")}))
        return m

    def __repr__(self) -> str:
        fixed = "".join(f", {k}={_text.g(v)}" for k, v in self.fixed.items())
        mode = "" if self.roller_tolerance == "fixed_cam" else f", roller_tolerance={self.roller_tolerance!r}"
        return f"PaperCase(waviness_order={self.waviness_order}{mode}{fixed})"


class ConfigCase:
    """Builder of a config file's mechanism with values replaced by key path: "a.b.0.c" is
    ``data["a"]["b"][0]["c"]`` (lists by index). The nominal value must be a plain number (SI) in
    the config.

    A ``...roller_radius`` (a contact's follower, a preset's parameter) is toleranced against
    ``roller_tolerance`` as in :class:`PaperCase` ("fixed_cam" by default: the cam is the config's, cut for
    its roller). ``camshaft_speed_rpm``: every case at that camshaft speed (rpm) instead of the config's."""

    def __init__(
        self,
        data: Mapping[str, Any],
        base_dir: os.PathLike | str = ".",
        *,
        roller_tolerance: str = "fixed_cam",
        camshaft_speed_rpm: Optional[float] = None,
    ):
        self.data = copy.deepcopy(dict(data))
        self.base_dir = os.fspath(base_dir)
        self.roller_tolerance = _roller_tolerance(roller_tolerance)
        if camshaft_speed_rpm is not None:
            from .speed import _MAX_RPM, _MIN_RPM

            rpm = _finite("camshaft_speed_rpm", camshaft_speed_rpm)
            if not _MIN_RPM <= rpm <= _MAX_RPM:
                raise ValueError(
                    f"camshaft_speed_rpm must be a camshaft speed in [{_MIN_RPM:.6g}, {_MAX_RPM:.6g}] "
                    f"rpm, got {_echo(camshaft_speed_rpm)}"
                )
            camshaft_speed_rpm = rpm
        self.camshaft_speed_rpm = camshaft_speed_rpm

    @classmethod
    def from_file(cls, path: os.PathLike | str, **options) -> "ConfigCase":
        from .config import load_config

        case = load_config(path)
        return cls(case.data, os.path.dirname(os.path.abspath(os.fspath(path))), **options)

    def with_options(self, **options) -> "ConfigCase":
        """A copy with other ``roller_tolerance`` / ``camshaft_speed_rpm``."""
        return ConfigCase(
            self.data,
            self.base_dir,
            **{"roller_tolerance": self.roller_tolerance, "camshaft_speed_rpm": self.camshaft_speed_rpm, **options},
        )

    def _slot(self, data, path: str):
        parts = path.split(".")
        node = data
        for i, p in enumerate(parts[:-1]):
            try:
                node = node[int(p)] if isinstance(node, list) else node[p]
            except (KeyError, IndexError, ValueError, TypeError):
                raise ValueError(f"parameter {path!r}: no {'.'.join(parts[: i + 1])!r} in the config") from None
        last = parts[-1]
        if isinstance(node, list):
            try:
                last = int(last)
                node[last]
            except (ValueError, IndexError):
                raise ValueError(f"parameter {path!r}: no element {parts[-1]!r} in the config's list") from None
        elif not isinstance(node, dict) or last not in node:
            raise ValueError(f"parameter {path!r}: the config has no such value (give its nominal value in the file)")
        return node, last

    def nominal(self, name: str) -> float:
        if self.camshaft_speed_rpm is not None and name.split(".")[0] == "camshaft":
            raise ValueError(
                f"parameter {name!r}: the study runs at {self.camshaft_speed_rpm:g} rpm "
                "(camshaft_speed_rpm, --rpm): a tolerance on the config's speed would not reach the model"
            )
        node, key = self._slot(self.data, name)
        v = node[key]
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise ValueError(
                f"parameter {name!r}: its nominal value {v!r} must be a plain number in SI units to be toleranced"
            )
        return float(v)

    def _build(self, values: Mapping[str, float]):
        from .config import config_from_dict

        data = copy.deepcopy(self.data)
        for name, value in values.items():
            node, key = self._slot(data, name)
            node[key] = float(value)
        return config_from_dict(data, self.base_dir).mechanism

    def __call__(self, values: Mapping[str, float]):
        m = self._build(values)
        rollers = [n for n in values if _is_roller_radius(n)]
        if self.roller_tolerance == "fixed_cam" and rollers:
            m = _fixed_cam(m, self._build({**values, **{n: self.nominal(n) for n in rollers}}))
        return m if self.camshaft_speed_rpm is None else m.with_camshaft_speed_rpm(self.camshaft_speed_rpm)


def _draw(tolerances: Mapping[str, Any], nominal: Mapping[str, float], seed: int, case: int) -> Dict[str, float]:
    rng = np.random.default_rng([seed, case])
    out = {}
    for name, dist in tolerances.items():
        d = dist.sample(rng)
        out[name] = nominal[name] * (1.0 + d) if dist.relative else nominal[name] + d
    return out


def _mc_case(build, options: Dict[str, Any], values: Dict[str, float]) -> Dict[str, Any]:
    row = steady_response(build(values), **options)
    return {k: row[k] for k in METRICS}


@dataclass
class MonteCarloResult:
    """A Monte-Carlo study's outcome: ``rows`` (one dict per case: ``case``, ``seed``, the parameter
    values, the metrics, ``ok`` and ``error``), the ``nominal`` case's row, the toleranced
    ``parameters`` and the ``metrics``."""

    rows: List[Dict[str, Any]]
    nominal: Dict[str, Any]
    parameters: List[str]
    metrics: List[str] = field(default_factory=lambda: list(METRICS))
    seed: int = 0

    @property
    def table(self):
        """The rows as a pandas DataFrame (optional extra: pip install 'camfollower[study]')."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("MonteCarloResult.table needs pandas: pip install 'camfollower[study]'") from None
        return pd.DataFrame(self.rows)

    def failed(self) -> List[Dict[str, Any]]:
        return [r for r in self.rows if not r["ok"]]

    def __repr__(self) -> str:  # a line, not every row
        ok = [r for r in self.rows if r["ok"]]
        lost = sum(bool(r.get("contact_lost")) for r in ok)
        forces = [
            r["min_force_N"] for r in ok if isinstance(r.get("min_force_N"), float) and math.isfinite(r["min_force_N"])
        ]
        spread = f", min_force_N {_text.g(min(forces), 4)} to {_text.g(max(forces), 4)}" if forces else ""
        return (
            f"MonteCarloResult({len(self.rows)} cases, {len(self.rows) - len(ok)} failed, {lost} lost contact"
            f"{spread}; seed {self.seed}; parameters: {', '.join(self.parameters)})"
        )

    def _matrix(self, names: Sequence[str]) -> np.ndarray:
        ok = [r for r in self.rows if r["ok"]]
        return np.array([[float(r[n]) for n in names] for r in ok], dtype=float).reshape(len(ok), len(names))

    def summary(self) -> Dict[str, Any]:
        """Per metric: mean, std, min, 5/50/95 % percentiles, max and the nominal value; counts of cases,
        failures and cases that lost contact."""
        numeric = [m for m in self.metrics if m not in ("converged", "contact_lost")]
        X = self._matrix(numeric)
        out: Dict[str, Any] = {
            "cases": len(self.rows),
            "failed": len(self.failed()),
            "contact_lost": int(sum(bool(r.get("contact_lost")) for r in self.rows if r["ok"])),
            "seed": self.seed,
            "metrics": {},
        }
        for j, m in enumerate(numeric):
            x = X[:, j] if X.size else np.zeros(0)
            x = x[np.isfinite(x)]
            if x.size == 0:
                continue
            p5, p50, p95 = np.percentile(x, [5, 50, 95])
            out["metrics"][m] = {
                "mean": float(x.mean()),
                "std": float(x.std(ddof=1)) if x.size > 1 else 0.0,
                "min": float(x.min()),
                "p5": float(p5),
                "p50": float(p50),
                "p95": float(p95),
                "max": float(x.max()),
                "nominal": float(self.nominal[m]),
            }
        return out

    def sensitivities(self, metric: str = "min_force_N") -> List[Dict[str, Any]]:
        """How each parameter drives ``metric``, by linear least squares over the successful cases (all
        parameters at once), one dict per parameter:

        - ``effect_of_one_std``: the change of the metric (its own units: N for the forces, m/s^2 or
          rad/s^2, m or rad) that one standard deviation of the parameter (over the cases) brings,
          ``slope * parameter_std``;
        - ``slope``: the metric's change per unit of the parameter (SI: N per m for a force against a
          length; per N/m against a stiffness), nan for a parameter that did not vary;
        - ``parameter_std``: the parameter's standard deviation over the cases (SI);
        - ``standardized_coefficient``: the same fit on standardized values (the metric's change in
          standard deviations per standard deviation of the parameter) and ``correlation`` (Pearson).

        Ranked by the absolute effect of one standard deviation, largest first: read it against what the
        design can spare (a 0.1 N effect on a 180 N margin is noise, whatever its rank)."""
        if metric not in self.metrics:
            raise ValueError(f"metric must be one of {self.metrics}, got {metric!r}")
        X = self._matrix(list(self.parameters) + [metric])
        X = X[np.all(np.isfinite(X), axis=1)]
        if X.shape[0] < len(self.parameters) + 2:
            raise ValueError(
                f"sensitivities need at least {len(self.parameters) + 2} successful cases, got {X.shape[0]}"
            )
        sd = X.std(axis=0, ddof=1)
        Z = np.divide(X - X.mean(axis=0), sd, out=np.zeros_like(X), where=sd > 0)
        coef = np.linalg.lstsq(Z[:, :-1], Z[:, -1], rcond=None)[0]
        out = []
        for j, p in enumerate(self.parameters):
            r = float(np.corrcoef(X[:, j], X[:, -1])[0, 1]) if sd[j] > 0 and sd[-1] > 0 else 0.0
            effect = float(coef[j] * sd[-1])
            out.append(
                {
                    "parameter": p,
                    "effect_of_one_std": effect,
                    "slope": effect / float(sd[j]) if sd[j] > 0 else math.nan,
                    "parameter_std": float(sd[j]),
                    "standardized_coefficient": float(coef[j]),
                    "correlation": r,
                }
            )
        return sorted(out, key=lambda d: -abs(d["effect_of_one_std"]))

    def to_parquet(self, path: os.PathLike | str, *, protect=()) -> None:
        """Write the table as Parquet (pyarrow), atomically (camfollower._files; never over `protect`)."""
        import io

        from . import _files

        buf = io.BytesIO()
        self.table.to_parquet(buf, index=False)
        _files.write_bytes(path, buf.getvalue(), protect=protect)

    def plot(self, metric: str = "min_force_N"):
        """Histogram of ``metric`` (nominal marked) and its scatter against the most influential
        parameter. Returns the figure."""
        import matplotlib.pyplot as plt

        fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
        x = self._matrix([metric])[:, 0]
        a.hist(x[np.isfinite(x)], bins=max(10, int(math.sqrt(max(len(x), 1)))), color="tab:blue", alpha=0.8)
        a.axvline(self.nominal[metric], color="tab:red", label="nominal")
        a.set_xlabel(metric)
        a.set_ylabel("cases")
        a.legend()
        first = self.sensitivities(metric)[0]
        top = first["parameter"]
        X = self._matrix([top, metric])
        b.plot(X[:, 0], X[:, 1], ".", ms=3)
        b.set_xlabel(top)
        b.set_ylabel(metric)
        b.set_title(f"most influential: {top} ({_text.g(first['effect_of_one_std'], 3)} per std)")
        fig.tight_layout()
        return fig


def _check_ranges(build, tolerances, nominal) -> None:
    for name, dist in tolerances.items():
        for end in dist.extremes():
            value = nominal[name] * (1.0 + end) if dist.relative else nominal[name] + end
            try:
                build({name: value})
            except ValueError as e:
                kind = type(dist).__name__
                raise ValueError(
                    f"tolerance on {name!r}: the {kind} reaches {value:.6g} (nominal {nominal[name]:.6g}), "
                    f"which the model refuses: {e}. Narrow it or use a TruncatedNormal inside the valid "
                    "range"
                ) from None


def monte_carlo(
    build: Callable[[Mapping[str, float]], Any],
    tolerances: Mapping[str, Any],
    *,
    cases: int = 100,
    seed: int = 0,
    contact: Optional[str] = None,
    accuracy: Optional[float] = None,
    steps_per_revolution: Optional[int] = None,
    executor=None,
    workers: Optional[int] = None,
    progress: bool = True,
    accuracy_of: str = ACCURACY_OF[0],
) -> MonteCarloResult:
    """``cases`` random variants of the model ``build`` describes (module docstring), each solved to
    its periodic steady state and measured (:data:`METRICS`), on ``executor`` (camfollower.executors).

    ``tolerances``: {parameter: Normal | Uniform | TruncatedNormal}. The nominal model is solved first
    (its row is ``nominal``). Each case at ``accuracy`` (steady_response: default 1e-3 of the peak force
    and acceleration, ``accuracy_of="force"`` of the force alone; ``steps_per_revolution`` to fix the
    step instead); each row says the ``accuracy`` it reached. A case that fails (non-periodic response after the transient
    fallback, a model error, a crashed worker) is kept as a row with ``ok`` False, its values, seed and
    the error.
    """
    if not tolerances:
        raise ValueError("tolerances: give at least one {parameter: distribution}")
    for name, d in tolerances.items():
        if not isinstance(d, (Normal, Uniform, TruncatedNormal)):
            raise TypeError(
                f"tolerance on {name!r} must be a Normal, Uniform or TruncatedNormal, got {type(d).__name__}"
            )
    if isinstance(cases, bool) or not isinstance(cases, int) or not 1 <= cases <= 10_000_000:
        raise ValueError(f"cases must be an integer in [1, 1e7], got {cases!r}")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
    check_executor(executor, workers)  # before the nominal model is solved
    nominal = {name: build.nominal(name) for name in tolerances}
    _check_ranges(build, tolerances, nominal)
    if accuracy is not None:
        check_accuracy(accuracy)
    options = dict(
        contact=contact,
        accuracy=accuracy,
        accuracy_of=check_accuracy_of(accuracy_of),
        steps_per_revolution=steps_per_revolution,
        fallback="transient",
        multipliers=False,
    )
    nominal_row = steady_response(build({}), **{**options, "multipliers": True})
    values = [_draw(tolerances, nominal, seed, i) for i in range(cases)]
    fn = functools.partial(_mc_case, build, options)
    outcomes = run_cases(fn, values, executor=executor, workers=workers, progress=progress, desc="Monte-Carlo")
    rows = []
    for i, (o, v) in enumerate(zip(outcomes, values)):
        row = {"case": i, "seed": seed, **v}
        if o.ok:
            row.update(o.value, ok=True, error="")
        else:
            row.update({m: math.nan for m in METRICS}, ok=False, error=o.error)
        rows.append(row)
    return MonteCarloResult(
        rows=rows, nominal={k: nominal_row[k] for k in METRICS}, parameters=list(tolerances), seed=seed
    )


__all__ = [
    "ConfigCase",
    "DISTRIBUTIONS",
    "FIXED_CAM_STEP",
    "METRICS",
    "MonteCarloResult",
    "Normal",
    "PaperCase",
    "ROLLER_TOLERANCES",
    "TruncatedNormal",
    "Uniform",
    "distribution",
    "monte_carlo",
    "roller_on_fixed_cam",
]
