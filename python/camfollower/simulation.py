"""simulate(): integrate any camfollower system with Newmark-beta / HHT-alpha and Newton-Raphson."""

from __future__ import annotations

import math
from typing import Callable, Optional

from . import _core
from .results import Result


def simulate(system, *, duration: Optional[float] = None, revolutions: Optional[float] = None,
             time_step: float = 3e-6, decimation: int = 1, record_from: Optional[float] = None,
             record_last_revolutions: Optional[float] = None, gamma: Optional[float] = None,
             beta: Optional[float] = None, hht_alpha: float = 0.0, linear_solver: str = "low_rank",
             residual_tolerance: float = 1e-10, increment_tolerance: float = 1e-10, max_iterations: int = 25,
             max_halvings: int = 6, max_output_bytes: float = 4.0 * 1024 ** 3,
             progress: Optional[Callable[[int, int], Optional[bool]]] = None,
             progress_interval: float = 0.2) -> Result:
    """Integrate ``system`` from its initial state (static equilibrium, at rest) and return a Result.

    Give ``duration`` (s) or ``revolutions`` (of the camshaft, for systems with a ``period``). One row
    is recorded every ``decimation`` steps, from ``record_from`` (s) or over the
    ``record_last_revolutions`` on. ``gamma``/``beta`` default to 1/2, 1/4 (average acceleration) or,
    with ``hht_alpha`` < 0, to HHT's 1/2 - alpha and (1 - alpha)^2 / 4; beta < 1/4 is only
    conditionally stable and a step beyond its limit is refused. ``linear_solver``: "low_rank"
    (Sherman-Morrison / Woodbury on the contact rank) or "dense_lu".

    ``system`` is a Mechanism (camfollower.MechanismBuilder, camfollower.presets) or a CamFollowerModel.
    ``progress(steps_done, steps_planned)`` is called about every ``progress_interval`` seconds;
    returning False stops the run (the Result then holds what was recorded, ``stats["cancelled"]``
    is True). Ctrl-C stops a run within about a second with KeyboardInterrupt. The GIL is released
    while the run integrates.

    Raises ValueError for bad input and RuntimeError when Newton fails after ``max_halvings``.
    """
    if (duration is None) == (revolutions is None):
        raise ValueError("give exactly one of duration (s) or revolutions")
    if revolutions is not None or record_last_revolutions is not None:
        period = getattr(system, "period", None)
        if period is None:
            raise ValueError(f"{type(system).__name__} has no camshaft period: give duration and record_from in s")
    if revolutions is not None:
        if not (isinstance(revolutions, (int, float)) and math.isfinite(revolutions) and revolutions > 0):
            raise ValueError(f"revolutions must be finite and > 0, got {revolutions!r}")
        duration = revolutions * period
    if record_from is not None and record_last_revolutions is not None:
        raise ValueError("give at most one of record_from (s) or record_last_revolutions")
    start = float("-inf")
    if record_from is not None:
        start = float(record_from)
    elif record_last_revolutions is not None:
        if not (math.isfinite(record_last_revolutions) and record_last_revolutions > 0):
            raise ValueError(f"record_last_revolutions must be finite and > 0, got {record_last_revolutions!r}")
        start = duration - record_last_revolutions * period
    raw = _core._run(system, float(duration), time_step, decimation, gamma, beta, hht_alpha, linear_solver,
                     residual_tolerance, increment_tolerance, max_iterations, max_halvings, start,
                     max_output_bytes, progress, progress_interval)
    return Result(raw["names"], raw["dofs"], raw["data"], raw["stats"], raw["contact_loss"])
