# SPDX-License-Identifier: BSD-3-Clause
"""simulate(): integrate any camfollower system with Newmark-beta / HHT-alpha and Newton-Raphson."""

from __future__ import annotations

import math
import numbers
from typing import Callable, Optional, Sequence

from . import _core
from .results import Result


def simulate(system, *, duration: Optional[float] = None, revolutions: Optional[float] = None,
             time_step: float = 3e-6, decimation: int = 1, record_from: Optional[float] = None,
             record_last_revolutions: Optional[float] = None, gamma: Optional[float] = None,
             beta: Optional[float] = None, hht_alpha: float = 0.0, linear_solver: str = "auto",
             residual_tolerance: float = 1e-10, increment_tolerance: float = 1e-10, max_iterations: int = 25,
             max_halvings: int = 6, max_output_bytes: float = 4.0 * 1024 ** 3,
             progress: Optional[Callable[[int, int], Optional[bool]]] = None,
             progress_interval: float = 0.2, settle: bool = False, settle_tolerance: float = 1e-4,
             settle_dofs: Optional[Sequence[str]] = None, settle_min_revolutions: int = 2,
             settle_max_revolutions: int = 200, initial_state=None, method: str = "newmark",
             tolerance: Optional[float] = None, max_step: Optional[float] = None) -> Result:
    """Integrate ``system`` from its initial state (static equilibrium, at rest) and return a Result.

    Give ``duration`` (s) or ``revolutions`` (of the camshaft, for systems with a ``period``). One row
    is recorded every ``decimation`` steps, from ``record_from`` (s) or over the
    ``record_last_revolutions`` on. ``gamma``/``beta`` default to 1/2, 1/4 (average acceleration) or,
    with ``hht_alpha`` < 0, to HHT's 1/2 - alpha and (1 - alpha)^2 / 4; beta < 1/4 is only
    conditionally stable and a step beyond its limit is refused. ``linear_solver``: "auto" (dense
    below 100 DOFs, sparse above), "low_rank" (dense: Sherman-Morrison / Woodbury on the contact
    rank), "dense_lu", "sparse" (SuiteSparse: CHOLMOD when symmetric positive definite, else KLU) or
    "klu"; ``stats["backend"]`` says which ran.

    ``method``: "newmark" (the default: Newmark/HHT with ``gamma``, ``beta``, ``hht_alpha``, fixed step
    ``time_step``), "fox_goodwin" (Newmark with gamma = 1/2, beta = 1/12: fourth-order phase on
    undamped linear modes, stable below dt = sqrt(6) / omega_max, refused beyond it) or
    "dormand_prince" (explicit Runge-Kutta 5(4) with adaptive steps: each step's error, in
    displacements and velocities and in the forces it leaves, below ``tolerance`` (relative, default
    1e-6; steps no longer than ``max_step`` s if given); ``time_step`` is then the output interval, the
    rows filled by dense output). The global error is typically a few tens of times the tolerance;
    ``stats`` reports ``method``, ``evaluations``, ``rejected_steps`` and ``stiff_steps`` (steps bounded
    by stability rather than accuracy: an implicit method would be cheaper there).

    ``system`` is a Mechanism (camfollower.MechanismBuilder, camfollower.presets) or a CamFollowerModel.
    ``progress(steps_done, steps_planned)`` is called about every ``progress_interval`` seconds;
    returning False stops the run (the Result then holds what was recorded, ``stats["cancelled"]``
    is True). Ctrl-C stops a run within about a second with KeyboardInterrupt. The GIL is released
    while the run integrates.

    ``settle=True`` (systems with a ``period``) first runs whole revolutions until the largest change of
    the watched accelerations between two successive revolutions, relative to their peak, is at most
    ``settle_tolerance`` (the periodic steady state), or ``settle_max_revolutions`` have run; then
    ``duration``/``revolutions`` and ``record_from``/``record_last_revolutions`` count from the settled
    state (recorded times stay absolute) and ``result.settle`` reports it (``settled`` False: the
    response never became periodic: chaos, chatter or an undamped mode). Watched: ``settle_dofs`` (names),
    by default each contact's follower DOF (every DOF for systems without contacts). The time step must
    divide the period.

    ``initial_state``: ``(q, v)`` arrays (one entry per DOF, SI) to start from at t = 0 instead of the
    system's static equilibrium at rest, e.g. a :class:`camfollower.periodic.PeriodicOrbit` (its state).

    Raises ValueError for bad input and RuntimeError when Newton fails after ``max_halvings``.
    """
    # Numbers and counts checked here by name (pybind11 would say "incompatible function arguments").
    for name, value in (("time_step", time_step), ("hht_alpha", hht_alpha), ("residual_tolerance", residual_tolerance),
                        ("increment_tolerance", increment_tolerance), ("max_output_bytes", max_output_bytes),
                        ("progress_interval", progress_interval), ("settle_tolerance", settle_tolerance),
                        ("duration", duration), ("revolutions", revolutions), ("record_from", record_from),
                        ("record_last_revolutions", record_last_revolutions), ("gamma", gamma), ("beta", beta),
                        ("tolerance", tolerance), ("max_step", max_step)):
        if value is not None and (isinstance(value, bool) or not isinstance(value, numbers.Real)):
            raise TypeError(f"{name} must be a number, got {type(value).__name__}")
    for name, value in (("decimation", decimation), ("max_iterations", max_iterations), ("max_halvings", max_halvings),
                        ("settle_min_revolutions", settle_min_revolutions),
                        ("settle_max_revolutions", settle_max_revolutions)):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise TypeError(f"{name} must be an integer, got {type(value).__name__} {value!r}")
        if not 0 <= value <= 2**53:
            raise ValueError(f"{name} must be in [0, 2^53], got {value}")
    for name, value in (("linear_solver", linear_solver), ("method", method)):
        if not isinstance(value, str):
            raise TypeError(f"{name} must be a str, got {type(value).__name__}")
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
    settle_args = {}
    if settle:
        period = getattr(system, "period", None)
        if period is None:
            raise ValueError(f"settle needs a periodic system: {type(system).__name__} has no camshaft period")
        names = list(getattr(system, "dof_names", []))
        if settle_dofs is None:
            settle_dofs = list(dict.fromkeys(getattr(system, "follower_dofs", []))) or names
        unknown = [d for d in settle_dofs if d not in names]
        if unknown:
            raise ValueError(f"settle_dofs: unknown DOF(s) {unknown}; the system's DOFs are {names}")
        settle_args = dict(settle_period=float(period), settle_dofs=[names.index(d) for d in settle_dofs],
                           settle_tolerance=settle_tolerance, settle_min_revolutions=settle_min_revolutions,
                           settle_max_revolutions=settle_max_revolutions)
    q0 = v0 = None
    if initial_state is not None:
        if hasattr(initial_state, "q") and hasattr(initial_state, "v"):
            initial_state = (initial_state.q, initial_state.v)
        try:
            q0, v0 = initial_state
        except (TypeError, ValueError):
            raise ValueError("initial_state must be a pair (q, v) of arrays or a PeriodicOrbit") from None
        q0, v0 = _vector("initial_state q", q0), _vector("initial_state v", v0)
    # The output cap never exceeds this machine's memory: a run needing more is refused by name
    # (ValueError), not left to fail with a MemoryError half way through allocating.
    memory = _physical_memory()
    cap = min(float(max_output_bytes), memory) if memory else float(max_output_bytes)
    try:
        raw = _core._run(system, float(duration), time_step, decimation, gamma, beta, hht_alpha, linear_solver,
                         residual_tolerance, increment_tolerance, max_iterations, max_halvings, start,
                         cap, progress, progress_interval, **settle_args, q0=q0, v0=v0, method=method,
                         tolerance=tolerance, max_step=max_step)
    except ValueError as e:
        if cap < max_output_bytes and "max_output_bytes" in str(e):
            raise ValueError(f"{e} (max_output_bytes = {max_output_bytes:g} B was capped at this machine's memory, "
                             f"{memory / 2**30:.3g} GiB)") from None
        raise
    stats = dict(raw["stats"])
    report = stats.pop("settle", None)
    if report is not None:
        report["dofs"] = list(settle_dofs)
    return Result(raw["names"], raw["dofs"], raw["data"], stats, raw["contact_loss"], report)


def _physical_memory() -> float:
    """Bytes of physical memory (0 if the platform does not say)."""
    import os

    try:
        return float(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (AttributeError, ValueError, OSError):
        return 0.0


def _vector(name: str, x):
    import numpy as np

    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an array of numbers") from None
    if a.ndim != 1:
        raise ValueError(f"{name} must be one-dimensional (one entry per DOF), got shape {a.shape}")
    return a
