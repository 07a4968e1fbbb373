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

import numpy as np

from . import _core
from ._core import MotionProgram

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
    if isinstance(speed_rpm, bool) or not isinstance(speed_rpm, numbers.Real) or not math.isfinite(speed_rpm):
        raise ValueError(f"speed_rpm must be a finite number (rpm), got {speed_rpm!r}")
    omega = float(speed_rpm) * _RPM
    if not _core.MIN_CAMSHAFT_SPEED <= omega <= _core.MAX_CAMSHAFT_SPEED:
        raise ValueError(
            f"speed_rpm must be in [{_core.MIN_CAMSHAFT_SPEED / _RPM:g}, {_core.MAX_CAMSHAFT_SPEED / _RPM:g}] rpm, "
            f"got {speed_rpm!r}"
        )
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


__all__ = ["polydyne", "snap_jumps"]
