# SPDX-License-Identifier: BSD-3-Clause
"""Sizing a disk cam: the smallest base circle (and the best offset) for a lift program.

A cam grows with its base circle: the pressure angle falls and the surface's radii of curvature grow
as the base radius r_b grows (for a fixed lift), so the smallest r_b that meets both limits is found
by bisection on r_b, each candidate checked over the whole revolution by the follower's own sampled
searches (``max_pressure_angle``, ``min_surface_radius``, ``check``: undercut, cusp, 90 deg). For a
translating roller the offset that minimizes the largest |pressure angle| is found for each r_b by
golden-section search (the largest |alpha| over the revolution is unimodal in the offset: it trades
the rise's peak against the return's).

Oscillating followers (lift in rad) have a pivot instead of an offset; the pivot is put at (d, 0) (its
direction round the cam only turns the cam). An oscillating roller is sized for a given arm length
L and a given pressure angle a0 on the base circle, which fixes the pivot distance d as r_b changes
(a0 = 0: the arm at right angles to the cam radius through the roller); a0 = None picks the best a0
(pivot distance) per r_b, as for the offset. An oscillating flat face is sized for a given ratio
d / r_b (the cam then scales with r_b).

All lengths in m, angles in rad. Results say which limit binds and at which cam angle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Union

from . import _text
from ._core import ArmTurn, MotionProgram, OscillatingFlat, OscillatingRoller, TranslatingFlat, TranslatingRoller


@dataclass(frozen=True)
class Sizing:
    base_radius: float  # m
    offset: float  # m (translating followers; 0 for oscillating ones)
    max_pressure_angle: float  # rad, signed, the largest |alpha| over the revolution
    max_pressure_angle_at: float  # rad, cam angle
    min_surface_radius: float  # m, smallest convex radius of curvature of the cam surface
    min_surface_radius_at: float  # rad
    binding: str  # "pressure angle" or "radius of curvature": the limit that sets base_radius
    # Oscillating followers (None for translating ones): the pivot sits at (pivot_distance, 0).
    pivot_distance: Optional[float] = None  # m, |P|
    arm_length: Optional[float] = None  # m (oscillating roller)
    dwell_pressure_angle: Optional[float] = None  # rad, the pressure angle on the base circle (oscillating roller)

    def __repr__(self) -> str:  # SI values to 6 significant digits, not the float's last bits
        fields = {k: getattr(self, k) for k in self.__dataclass_fields__ if getattr(self, k) is not None}
        return f"Sizing({_text.values(fields)})"


KINDS = ("translating_roller", "translating_flat", "oscillating_roller", "oscillating_flat")


@dataclass(frozen=True)
class _Design:
    """The fixed part of a design: everything but the base radius and the free variable."""

    kind: str
    roller_radius: Optional[float]
    arm_length: Optional[float]
    face_offset: float
    turn: str

    def pivot_distance(self, base_radius: float, variable: float) -> float:
        """|P| for the oscillating followers. Roller: the variable is the dwell pressure angle a0, and
        on the base circle sin a0 = sigma (d^2 - r^2 - L^2) / (2 L r) (r = r_b + r_r; docs/sizing.md),
        so d^2 = L^2 + r^2 + 2 sigma L r sin a0. Flat face: the variable is the ratio d / r_b."""
        if self.kind == "oscillating_roller":
            r, L = base_radius + self.roller_radius, self.arm_length
            sigma = 1.0 if self.turn == "counter_clockwise" else -1.0
            return math.sqrt(max(L * L + r * r + 2.0 * sigma * L * r * math.sin(variable), 0.0))
        return variable * base_radius

    def follower(self, base_radius: float, variable: float):
        """The follower for base radius r_b and the free variable: the offset (translating), the dwell
        pressure angle (oscillating roller) or the pivot distance ratio (oscillating flat face)."""
        if self.kind == "translating_roller":
            return TranslatingRoller(base_radius, self.roller_radius, variable)
        if self.kind == "translating_flat":
            return TranslatingFlat(base_radius, 0.0, variable)
        pivot = (self.pivot_distance(base_radius, variable), 0.0)
        if self.kind == "oscillating_roller":
            return OscillatingRoller(base_radius, self.roller_radius, pivot, self.arm_length, self.turn)
        return OscillatingFlat(base_radius, pivot, self.face_offset, self.turn)


def _evaluate(program: MotionProgram, design: _Design, base_radius: float, variable: float):
    """(|alpha| max, its theta, alpha, rho min, its theta) for one geometry, None if not followable."""
    try:
        f = design.follower(base_radius, variable)
        f.check(program)
    except ValueError:
        return None
    ta, alpha = f.max_pressure_angle(program)
    tr, rho = f.min_surface_radius(program)
    return abs(alpha), ta, alpha, rho, tr


def _golden(cost, lo: float, hi: float, tolerance: float) -> float:
    """Minimizer of a unimodal cost on [lo, hi] to `tolerance` (golden section)."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    a, b = hi - g * (hi - lo), lo + g * (hi - lo)
    fa, fb = cost(a), cost(b)
    while hi - lo > tolerance:
        if fa <= fb:
            hi, b, fb = b, a, fa
            a = hi - g * (hi - lo)
            fa = cost(a)
        else:
            lo, a, fa = a, b, fb
            b = lo + g * (hi - lo)
            fb = cost(b)
    return 0.5 * (lo + hi)


# Search range of an oscillating roller's dwell pressure angle (rad) when it is optimized ("best").
DWELL_PRESSURE_ANGLE_RANGE = (-math.radians(75.0), math.radians(75.0))


def _best_variable(program, design: _Design, base_radius: float, tolerance: float) -> float:
    """The free variable minimizing the largest |pressure angle| at this base radius (golden section):
    the offset in (-(r_b + r_r), r_b + r_r) of a translating roller, or the dwell pressure angle in
    DWELL_PRESSURE_ANGLE_RANGE of an oscillating roller (which moves the pivot). Either trades the
    rise's peak against the return's, so the cost is unimodal."""

    def cost(v):
        r = _evaluate(program, design, base_radius, v)
        return math.inf if r is None else r[0]

    if design.kind == "translating_roller":
        limit = 0.95 * (base_radius + design.roller_radius)
        return _golden(cost, -limit, limit, tolerance)
    return _golden(cost, *DWELL_PRESSURE_ANGLE_RANGE, 1e-5)


def _positive(name: str, v, unit: str) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
        raise ValueError(f"{name} must be finite and > 0 {unit}, got {v!r}")
    return float(v)


_TURNS = {
    "counter_clockwise": "counter_clockwise",
    "ccw": "counter_clockwise",
    "clockwise": "clockwise",
    "cw": "clockwise",
}


def _turn(turn) -> str:
    """An arm's turn as the followers take it: the ArmTurn enum or its name; returned as the name."""
    if isinstance(turn, ArmTurn):
        return turn.name
    if not isinstance(turn, str):
        raise TypeError(
            f"turn must be an ArmTurn or one of 'counter_clockwise', 'clockwise', got {type(turn).__name__}"
        )
    if turn not in _TURNS:
        raise ValueError(f"turn must be 'counter_clockwise' or 'clockwise' (or an ArmTurn), got {turn!r}")
    return _TURNS[turn]


def smallest_base_radius(
    program: MotionProgram,
    follower: str = "translating_roller",
    *,
    max_pressure_angle: float = math.radians(30.0),
    min_surface_radius: float = 0.0,
    roller_radius: Optional[float] = None,
    offset: Optional[float] = 0.0,
    arm_length: Optional[float] = None,
    dwell_pressure_angle: Optional[float] = 0.0,
    pivot_distance_ratio: Optional[float] = 2.0,
    face_offset: float = 0.0,
    turn: Union[str, ArmTurn] = "counter_clockwise",
    upper: float = 1.0,
    tolerance: float = 1e-6,
) -> Sizing:
    """Smallest base radius (m) for which the cam is followable (no undercut, no cusp, |alpha| < 90
    deg), its largest |pressure angle| is at most ``max_pressure_angle`` (rad; not for the translating
    flat face, whose pressure angle is its face angle) and its smallest convex surface radius of
    curvature is at least ``min_surface_radius`` (m). Searched in (0, ``upper``] to ``tolerance`` (m).

    ``follower`` and its free design variable (``None`` picks, for each candidate base radius, the
    value that suits the cam best; see docs/sizing.md):

    - ``"translating_roller"``: ``roller_radius`` (m), ``offset`` (m, or None: the offset minimizing
      the largest |alpha|);
    - ``"translating_flat"``: ``offset`` (m; it does not change the cam);
    - ``"oscillating_roller"``: ``roller_radius`` and ``arm_length`` (m), ``turn`` (an ``ArmTurn`` or its
      name, as for the followers), and
      ``dwell_pressure_angle`` a0 (rad, default 0), the pressure angle on the base circle, which sets
      the pivot distance d = sqrt(L^2 + r^2 + 2 sigma L r sin a0) (r = r_b + r_r; a0 = 0 puts the arm
      at right angles to the cam radius through the roller), or None: the a0 minimizing the largest
      |alpha|. The lift program is the arm rotation (rad);
    - ``"oscillating_flat"``: ``pivot_distance_ratio`` d / r_b (> 1, default 2; no "best": the radii
      only grow as the pivot nears the cam), ``face_offset`` (m), ``turn``. Lift in rad.

    The pivot is put at (d, 0): where it sits round the cam only turns the cam. Raises ValueError when
    even ``upper`` does not meet the limits."""
    for name, v in (("max_pressure_angle", max_pressure_angle), ("upper", upper), ("tolerance", tolerance)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be finite and > 0, got {v!r}")
    if not (max_pressure_angle < math.pi / 2):
        raise ValueError(f"max_pressure_angle must be < pi/2 rad (90 deg), got {max_pressure_angle}")
    if not (math.isfinite(min_surface_radius) and min_surface_radius >= 0):
        raise ValueError(f"min_surface_radius must be finite and >= 0 m, got {min_surface_radius!r}")
    if follower not in KINDS:
        raise ValueError(f"follower must be one of {', '.join(repr(k) for k in KINDS)}, got {follower!r}")
    if follower.endswith("roller"):
        if roller_radius is None or not (math.isfinite(roller_radius) and roller_radius > 0):
            raise ValueError(
                f"roller_radius must be finite and > 0 m for a {follower.replace('_', ' ')}, got {roller_radius!r}"
            )
    if follower.startswith("translating"):
        if offset is None and follower != "translating_roller":
            raise ValueError("offset=None (best offset) applies to the translating roller only")
        variable = offset
    else:
        turn = _turn(turn)
        if follower == "oscillating_roller":
            arm_length = _positive("arm_length", arm_length, "m for an oscillating roller")
            if dwell_pressure_angle is not None and not (
                math.isfinite(dwell_pressure_angle) and abs(dwell_pressure_angle) < math.pi / 2
            ):
                raise ValueError(
                    f"dwell_pressure_angle must be None or finite with |value| < pi/2 rad, got {dwell_pressure_angle!r}"
                )
            variable = dwell_pressure_angle
        else:
            if pivot_distance_ratio is None:
                raise ValueError(
                    "pivot_distance_ratio=None (best) is not offered for the oscillating flat face: its "
                    "smallest surface radius only grows as the pivot approaches the cam, so the 'best' "
                    "pivot would touch the base circle; choose the ratio from the layout"
                )
            if not (
                isinstance(pivot_distance_ratio, (int, float))
                and math.isfinite(pivot_distance_ratio)
                and pivot_distance_ratio > 1
            ):
                raise ValueError(
                    f"pivot_distance_ratio (|pivot| / base_radius) must be finite and > 1, got {pivot_distance_ratio!r}"
                )
            if not math.isfinite(face_offset):
                raise ValueError(f"face_offset must be finite (m), got {face_offset!r}")
            variable = pivot_distance_ratio
    design = _Design(follower, roller_radius, arm_length, float(face_offset), turn)

    def measure(rb):
        v = _best_variable(program, design, rb, tolerance) if variable is None else variable
        if follower == "translating_roller" and abs(v) >= rb + roller_radius:
            return None, v
        return _evaluate(program, design, rb, v), v

    def ok(rb):
        r, v = measure(rb)
        if r is None:
            return False, v, r
        alpha_ok = follower == "translating_flat" or r[0] <= max_pressure_angle
        return alpha_ok and r[3] >= min_surface_radius, v, r

    good, _, _ = ok(upper)
    if not good:
        raise ValueError(
            f"no base radius up to upper = {upper} m meets the limits (max_pressure_angle = "
            f"{math.degrees(max_pressure_angle):.3g} deg, min_surface_radius = {min_surface_radius} m)"
        )
    lo, hi = 0.0, upper
    while hi - lo > tolerance:
        mid = 0.5 * (lo + hi)
        if ok(mid)[0]:
            hi = mid
        else:
            lo = mid
    _, v, r = ok(hi)
    # Which limit binds: the one that fails just below the answer.
    below, _ = measure(max(hi - 2 * tolerance, tolerance))
    if below is None or below[3] < min_surface_radius:
        binding = "radius of curvature"
    else:
        binding = "pressure angle"
    extra = {}
    if follower.startswith("oscillating"):
        extra = dict(pivot_distance=design.pivot_distance(hi, v))
        if follower == "oscillating_roller":
            extra.update(arm_length=arm_length, dwell_pressure_angle=v)
    return Sizing(
        base_radius=hi,
        offset=v if follower.startswith("translating") else 0.0,
        max_pressure_angle=r[2],
        max_pressure_angle_at=r[1],
        min_surface_radius=r[3],
        min_surface_radius_at=r[4],
        binding=binding,
        **extra,
    )


def roller_size_check(program: MotionProgram, base_radius: float, roller_radius: float, offset: float = 0.0) -> dict:
    """Does a roller of ``roller_radius`` (m) trace the cam without undercut? Returns ``ok``, the
    smallest convex pitch-curve radius of curvature (m) with its cam angle, and the ``margin`` (m)
    by which it exceeds the roller radius (<= 0: undercut)."""
    f = TranslatingRoller(base_radius, roller_radius, offset)
    theta, rho_surface = f.min_surface_radius(program)
    pitch = rho_surface + roller_radius  # the pitch curve is the surface offset by the roller
    return {"ok": bool(rho_surface > 0), "min_pitch_radius": pitch, "at": theta, "margin": rho_surface}


__all__ = ["Sizing", "smallest_base_radius", "roller_size_check"]
