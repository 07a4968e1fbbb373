# SPDX-License-Identifier: BSD-3-Clause
"""User-defined cam motion beyond the built-in laws.

- ``from_callable``: sample a lift function h(theta) (m, theta in rad) into a B-spline, as one segment of
  a program or as a whole periodic program.
- ``smoothness``: the program's smoothness report (peaks of |h'|, |h''|, |h'''| and where they occur,
  spline-fit residuals, where a table's noise shows up in the jerk), also in m/s, m/s^2, m/s^3 at a
  camshaft speed.

The building blocks live on the compiled classes: ``MotionProgram.from_table`` (a periodic lift table),
``Segment.from_table`` (a table as one segment), ``Segment.polynomial`` (a polynomial from boundary
conditions), ``MotionProgram.continuity`` / ``require_continuity``. See docs/motion.md.

>>> import numpy as np, camfollower as cf
>>> seg = cf.motion.from_callable(lambda t: 0.01 * (t - 0.5) / 2.0, 0.5, 2.5, points=5, degree=3,
...                               start_derivatives=[0.005], end_derivatives=[0.005])
>>> round(float(seg.lift_at(1.5)["h"]), 12)
0.005
"""

from __future__ import annotations

import math
import numbers
from typing import Callable, Optional, Sequence

import numpy as np

from . import _core
from ._core import MotionProgram, Segment

__all__ = ["from_callable", "smoothness"]

TWO_PI = 2.0 * math.pi


def _sample(f: Callable, theta: np.ndarray) -> np.ndarray:
    """f at every theta: one vectorized call when f takes arrays, else one call per angle."""
    try:
        with np.errstate(all="ignore"):
            h = np.asarray(f(theta), dtype=float)
        if h.shape == theta.shape:
            return h
    except (TypeError, ValueError):
        pass
    return np.array([float(f(float(t))) for t in theta])


def from_callable(
    f: Callable,
    theta_start: float = 0.0,
    theta_end: float = TWO_PI,
    *,
    points: int = 361,
    degree: int = 5,
    smoothing: float = 0.0,
    periodic: bool = False,
    start_derivatives: Sequence[float] = (),
    end_derivatives: Sequence[float] = (),
):
    """Sample a lift function ``f(theta) -> h`` (rad -> m; vectorized or scalar) into a B-spline.

    ``periodic=False`` (default): a ``Segment`` spanning [theta_start, theta_end] from ``points`` equally
    spaced samples, both ends included (``Segment.from_table``). Its end values are f's; its end
    derivatives h', h'', ... (m/rad^k) are ``start_derivatives`` / ``end_derivatives``, by default zeros
    up to ``degree - 1`` (the segment joins dwells): pass f's own derivatives if it does not.

    ``periodic=True``: a whole ``MotionProgram`` (``MotionProgram.from_table``): theta_end - theta_start
    must be one revolution; ``points`` samples per revolution, the end (= the start) not repeated.

    ``degree``: odd spline degree 1, 3, 5 (default, C4) or 7. ``smoothing``: the penalty weight lambda
    (rad^degree) of a smoothing spline; 0 interpolates the samples. Raises ValueError naming the bad
    parameter.
    """
    if not callable(f):
        raise ValueError(f"f must be callable h(theta) -> m, got {type(f).__name__}")
    theta_start, theta_end = float(theta_start), float(theta_end)
    if not (math.isfinite(theta_start) and math.isfinite(theta_end) and theta_end > theta_start):
        raise ValueError(
            f"theta_end must be > theta_start (both finite, rad), got theta_start = {theta_start}, "
            f"theta_end = {theta_end}"
        )
    if isinstance(points, bool) or not isinstance(points, numbers.Integral) or not 2 <= points <= _core.MAX_POINTS:
        raise ValueError(f"points must be an integer in [2, {_core.MAX_POINTS}], got {points!r}")
    points = int(points)
    if periodic:
        if abs(theta_end - theta_start - TWO_PI) > 1e-9:
            raise ValueError(
                "theta_end - theta_start must be one revolution (2 pi rad) for a periodic program, got "
                f"{theta_end - theta_start} rad"
            )
        if points < degree + 1:
            raise ValueError(f"points must be >= degree + 1 = {degree + 1} for a periodic spline, got {points}")
        theta = theta_start + TWO_PI * np.arange(points) / points
    else:
        if points < 2:
            raise ValueError(f"points must be >= 2 for a segment, got {points}")
        theta = np.linspace(theta_start, theta_end, points)
    h = _sample(f, theta)
    bad = ~np.isfinite(h)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"f must return a finite lift (m): f({theta[i]!r}) = {h[i]!r}")
    if not periodic:
        return Segment.from_table(
            theta,
            h,
            degree=degree,
            smoothing=smoothing,
            start_derivatives=list(start_derivatives),
            end_derivatives=list(end_derivatives),
        )
    wrapped = np.mod(theta, TWO_PI)
    wrapped[wrapped >= TWO_PI] = 0.0
    order = np.argsort(wrapped)
    return MotionProgram.from_table(wrapped[order], h[order], degree=degree, smoothing=smoothing)


def smoothness(program: MotionProgram, rpm: Optional[float] = None, excursions: int = 5) -> dict:
    """The program's smoothness report (``MotionProgram.smoothness``), per radian, plus physical units.

    Keys: ``velocity``, ``acceleration``, ``jerk``: ``{"value": peak |h'|, |h''|, |h'''| (m/rad^k),
    "theta": where (rad)}``; ``table_points``; ``residual``: ``{"max", "rms" (m), "theta_of_max"}`` of
    the program's spline tables (0 when interpolating); ``jerk_roughness`` (RMS local jerk excursion /
    peak |h'''|: below 0.01 for a smooth lift, 0.1-0.5 when a table's noise dominates);
    ``jerk_excursions``: the largest local jerk excursions ``[{"theta", "excursion" (m/rad^3)}]`` —
    where the noise shows up.

    With ``rpm`` (camshaft speed, > 0) a key ``at_speed`` adds ``omega`` (rad/s) and the peaks as a
    follower moves at that constant speed: ``velocity`` (m/s), ``acceleration`` (m/s^2), ``jerk``
    (m/s^3), and ``jerk_excursions`` in m/s^3.
    """
    report = program.smoothness(excursions)
    if rpm is None:
        return report
    rpm = float(rpm)
    if not (math.isfinite(rpm) and rpm > 0.0):
        raise ValueError(f"rpm must be finite and > 0 (camshaft speed, rev/min), got {rpm}")
    omega = rpm * TWO_PI / 60.0
    report["at_speed"] = {
        "rpm": rpm,
        "omega": omega,
        "velocity": report["velocity"]["value"] * omega,
        "acceleration": report["acceleration"]["value"] * omega**2,
        "jerk": report["jerk"]["value"] * omega**3,
        "jerk_excursions": [e["excursion"] * omega**3 for e in report["jerk_excursions"]],
    }
    return report
