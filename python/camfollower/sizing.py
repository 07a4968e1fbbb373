"""Sizing a disk cam: the smallest base circle (and the best offset) for a lift program.

A cam grows with its base circle: the pressure angle falls and the surface's radii of curvature grow
as the base radius r_b grows (for a fixed lift), so the smallest r_b that meets both limits is found
by bisection on r_b, each candidate checked over the whole revolution by the follower's own sampled
searches (``max_pressure_angle``, ``min_surface_radius``, ``check``: undercut, cusp, 90 deg). For a
translating roller the offset that minimizes the largest |pressure angle| is found for each r_b by
golden-section search (the largest |alpha| over the revolution is unimodal in the offset: it trades
the rise's peak against the return's).

All lengths in m, angles in rad. Results say which limit binds and at which cam angle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

from ._core import MotionProgram, TranslatingFlat, TranslatingRoller


@dataclass(frozen=True)
class Sizing:
    base_radius: float  # m
    offset: float  # m (translating followers)
    max_pressure_angle: float  # rad, signed, the largest |alpha| over the revolution
    max_pressure_angle_at: float  # rad, cam angle
    min_surface_radius: float  # m, smallest convex radius of curvature of the cam surface
    min_surface_radius_at: float  # rad
    binding: str  # "pressure angle" or "radius of curvature": the limit that sets base_radius


def _follower(kind: str, base_radius: float, roller_radius: Optional[float], offset: float):
    if kind == "translating_roller":
        return TranslatingRoller(base_radius, roller_radius, offset)
    if kind == "translating_flat":
        return TranslatingFlat(base_radius, 0.0, offset)
    raise ValueError(f"follower must be 'translating_roller' or 'translating_flat', got {kind!r}")


def _evaluate(program: MotionProgram, kind: str, base_radius: float, roller_radius, offset: float):
    """(|alpha| max, its theta, alpha, rho min, its theta, followable?) for one geometry."""
    try:
        f = _follower(kind, base_radius, roller_radius, offset)
        f.check(program)
    except ValueError:
        return None
    ta, alpha = f.max_pressure_angle(program)
    tr, rho = f.min_surface_radius(program)
    return abs(alpha), ta, alpha, rho, tr


def _best_offset(program, kind, base_radius, roller_radius, tolerance):
    """Offset in (-(r_b + r_r), r_b + r_r) minimizing the largest |pressure angle| (golden section)."""
    limit = 0.95 * (base_radius + roller_radius)
    lo, hi = -limit, limit
    g = (math.sqrt(5.0) - 1.0) / 2.0

    def cost(e):
        r = _evaluate(program, kind, base_radius, roller_radius, e)
        return math.inf if r is None else r[0]

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


def smallest_base_radius(program: MotionProgram, follower: str = "translating_roller", *,
                         max_pressure_angle: float = math.radians(30.0), min_surface_radius: float = 0.0,
                         roller_radius: Optional[float] = None, offset: Optional[float] = 0.0,
                         upper: float = 1.0, tolerance: float = 1e-6) -> Sizing:
    """Smallest base radius (m) for which the cam is followable (no undercut, no cusp), its largest
    |pressure angle| is at most ``max_pressure_angle`` (rad; translating roller only: a flat face's
    pressure angle is its face angle) and its smallest convex surface radius of curvature is at least
    ``min_surface_radius`` (m). ``offset=None`` also picks, for each candidate, the offset that
    minimizes the pressure angle (translating roller). Searched in (0, ``upper``] to ``tolerance`` (m).
    Raises ValueError when even ``upper`` does not meet the limits."""
    for name, v in (("max_pressure_angle", max_pressure_angle), ("upper", upper), ("tolerance", tolerance)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"{name} must be finite and > 0, got {v!r}")
    if not (max_pressure_angle < math.pi / 2):
        raise ValueError(f"max_pressure_angle must be < pi/2 rad (90 deg), got {max_pressure_angle}")
    if not (math.isfinite(min_surface_radius) and min_surface_radius >= 0):
        raise ValueError(f"min_surface_radius must be finite and >= 0 m, got {min_surface_radius!r}")
    if follower == "translating_roller":
        if roller_radius is None or not (math.isfinite(roller_radius) and roller_radius > 0):
            raise ValueError(f"roller_radius must be finite and > 0 m for a translating roller, got {roller_radius!r}")
    elif offset is None:
        raise ValueError("offset=None (best offset) applies to the translating roller only")

    def measure(rb):
        e = _best_offset(program, follower, rb, roller_radius, tolerance) if offset is None else offset
        if follower == "translating_roller" and abs(e) >= rb + roller_radius:
            return None, e
        return _evaluate(program, follower, rb, roller_radius, e), e

    def ok(rb):
        r, e = measure(rb)
        if r is None:
            return False, e, r
        alpha_ok = follower != "translating_roller" or r[0] <= max_pressure_angle
        return alpha_ok and r[3] >= min_surface_radius, e, r

    good, e_up, r_up = ok(upper)
    if not good:
        raise ValueError(f"no base radius up to upper = {upper} m meets the limits (max_pressure_angle = "
                         f"{math.degrees(max_pressure_angle):.3g} deg, min_surface_radius = {min_surface_radius} m)")
    lo, hi = 0.0, upper
    while hi - lo > tolerance:
        mid = 0.5 * (lo + hi)
        if ok(mid)[0]:
            hi = mid
        else:
            lo = mid
    _, e, r = ok(hi)
    # Which limit binds: the one that fails just below the answer.
    below, _ = measure(max(hi - 2 * tolerance, tolerance))
    if below is None or below[3] < min_surface_radius:
        binding = "radius of curvature"
    else:
        binding = "pressure angle"
    return Sizing(base_radius=hi, offset=e, max_pressure_angle=r[2], max_pressure_angle_at=r[1],
                  min_surface_radius=r[3], min_surface_radius_at=r[4], binding=binding)


def roller_size_check(program: MotionProgram, base_radius: float, roller_radius: float, offset: float = 0.0) -> dict:
    """Does a roller of ``roller_radius`` (m) trace the cam without undercut? Returns ``ok``, the
    smallest convex pitch-curve radius of curvature (m) with its cam angle, and the ``margin`` (m)
    by which it exceeds the roller radius (<= 0: undercut)."""
    f = TranslatingRoller(base_radius, roller_radius, offset)
    theta, rho_surface = f.min_surface_radius(program)
    pitch = rho_surface + roller_radius  # the pitch curve is the surface offset by the roller
    return {"ok": bool(rho_surface > 0), "min_pitch_radius": pitch, "at": theta, "margin": rho_surface}


__all__ = ["Sizing", "smallest_base_radius", "roller_size_check"]
