# SPDX-License-Identifier: BSD-3-Clause
"""simulate(): integrate any camfollower system (Newmark-beta / HHT-alpha, Fox-Goodwin, Dormand-Prince
5(4) and 8(5,3)); simulate_many(): many systems at once on C++ threads."""

from __future__ import annotations

import dataclasses
import math
import numbers
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Callable, List, Optional, Sequence, Tuple

from . import _core
from ._core import SolverSettings
from .results import Result


@dataclass(frozen=True)
class RunOptions:
    """What a run records and how long it runs (the solver's settings: :class:`SolverSettings`),
    immutable; ``replace(**changes)`` returns a copy with fields changed.

    Give ``duration`` (s) or ``revolutions`` (of the camshaft, for systems with a ``period``). One row
    is recorded every ``decimation`` steps, from ``record_from`` (s) or over the
    ``record_last_revolutions`` on; ``max_output_bytes`` bounds the recording. ``progress_interval``:
    seconds between progress calls. ``settle`` and ``settle_*``: settle on the periodic response first
    (:func:`simulate`).
    """

    duration: Optional[float] = None
    revolutions: Optional[float] = None
    decimation: int = 1
    record_from: Optional[float] = None
    record_last_revolutions: Optional[float] = None
    max_output_bytes: float = 4.0 * 1024**3
    progress_interval: float = 0.2
    settle: bool = False
    settle_tolerance: float = 1e-4
    settle_dofs: Optional[Tuple[str, ...]] = None
    settle_min_revolutions: int = 2
    settle_max_revolutions: int = 200

    def replace(self, **changes) -> "RunOptions":
        unknown = sorted(set(changes) - _OPTION_FIELDS)
        if unknown:
            raise TypeError(f"RunOptions has no field(s) {unknown}; its fields: {sorted(_OPTION_FIELDS)}")
        return dataclasses.replace(self, **changes)


_OPTION_FIELDS = frozenset(f.name for f in dataclasses.fields(RunOptions))
# The method names as attributes (METHOD.fox_goodwin), from the C++ method table: modules that pick a
# method name it through this, not a string of their own.
METHOD = SimpleNamespace(**{name: name for name in _core.METHODS})
_SETTINGS_FIELDS = frozenset(_core.SolverSettings.FIELDS)


def settings_and_options(settings=None, options=None, **overrides) -> Tuple[SolverSettings, RunOptions]:
    """The :class:`SolverSettings` and :class:`RunOptions` of a run: ``settings`` and ``options``
    (None: the defaults) with ``overrides`` (fields of either) applied. Raises TypeError for a keyword
    that is a field of neither."""
    unknown = sorted(set(overrides) - _SETTINGS_FIELDS - _OPTION_FIELDS)
    if unknown:
        raise TypeError(
            f"unexpected keyword argument(s) {unknown}; the solver settings are {sorted(_SETTINGS_FIELDS)}, "
            f"the run options {sorted(_OPTION_FIELDS)}"
        )
    solver = {k: v for k, v in overrides.items() if k in _SETTINGS_FIELDS}
    run = {k: v for k, v in overrides.items() if k in _OPTION_FIELDS}
    return _changed(settings, SolverSettings, solver, "settings"), _changed(options, RunOptions, run, "options")


def _changed(value, kind, changes: dict, what: str):
    """``value`` (an instance of ``kind``, or None for its defaults) with ``changes`` applied."""
    if value is None:
        return kind(**changes)
    if not isinstance(value, kind):
        raise TypeError(f"{what} must be a camfollower.{kind.__name__} or None, got {type(value).__name__}")
    return value.replace(**changes) if changes else value


def simulate(
    system,
    settings: Optional[SolverSettings] = None,
    options: Optional[RunOptions] = None,
    *,
    initial_state=None,
    progress: Optional[Callable[[int, int], Optional[bool]]] = None,
    **overrides,
) -> Result:
    """Integrate ``system`` from its initial state (static equilibrium, at rest) and return a Result.

    ``settings`` (:class:`SolverSettings`: the method and its step, tolerance, ...) and ``options``
    (:class:`RunOptions`: duration, recording, settling), each None for the defaults; ``overrides``:
    any of their fields by name, e.g. ``simulate(m, revolutions=1, method="dop853",
    tolerance=1e-8)`` (the config's ``Config.settings`` and ``Config.options`` are the same objects).

    Give ``duration`` (s) or ``revolutions`` (of the camshaft, for systems with a ``period``). One row
    is recorded every ``decimation`` steps, from ``record_from`` (s) or over the
    ``record_last_revolutions`` on. ``gamma``/``beta`` (method "newmark" only) default to 1/2, 1/4
    (average acceleration); beta < 1/4 is only conditionally stable and a step beyond its limit is
    refused. ``hht_alpha`` (method "hht" only, in [-1/3, 0], default -0.05). ``linear_solver``: "auto" (dense
    below 100 DOFs, sparse above), "low_rank" (dense: Sherman-Morrison / Woodbury on the contact
    rank), "dense_lu", "sparse" (SuiteSparse: CHOLMOD when symmetric positive definite, else KLU) or
    "klu"; ``stats["backend"]`` says which ran.

    ``method`` (the names: ``camfollower.METHODS``): "newmark" (the default: Newmark with ``gamma``,
    ``beta``, fixed step ``time_step``), "hht" (HHT-alpha with ``hht_alpha``: Newmark that damps the
    highest modes; no ``tolerance``), "fox_goodwin" (Newmark with gamma = 1/2, beta = 1/12, its velocity processed to
    fourth order, damping included; stable below dt = sqrt(6) / omega_max undamped, lower with damping
    (Mechanism.step_limit), refused beyond it; docs/solvers.md); both given a
    ``tolerance`` adapt their steps: ``time_step`` becomes the output interval, integrated in steps of
    time_step / 2^k (k <= ``max_halvings``, within fox_goodwin's stability limit and ``max_step``)
    chosen by an error estimate measured like the Runge-Kutta methods' below: for fox_goodwin
    Numerov's phase lag per radian of the cam, which keeps a revolution's error near the tolerance
    whatever the output interval (0.001 to 0.65 times it on the paper preset); for newmark Zienkiewicz
    & Xie's local error per step, which on a ringing mode adds up to hundreds or thousands of times
    the tolerance (docs/solvers.md, "Error control across output intervals"),
    "dormand_prince" (explicit Runge-Kutta 5(4) with adaptive steps: each step's error, in
    displacements and velocities and in the forces it leaves, below ``tolerance`` (relative, default
    1e-6; steps no longer than ``max_step`` s if given); ``time_step`` is then the output interval, the
    rows filled by dense output; the global error is typically a few tens of times the tolerance),
    "dop853" (explicit Runge-Kutta 8(5,3), Hairer's DOP853, with the same error control, ``tolerance``
    and ``max_step``: half the steps of dormand_prince at twice the force evaluations each, several
    times more accurate at the same tolerance, 7th-order dense output; for errors of 1e-8 and runs with
    contact losses, not for very stiff contacts at tight tolerances), "radau" (implicit Radau IIA of
    order 5, L-stable, with the same error control, ``tolerance`` and ``max_step``, simplified Newton
    on the stages (``newton_iterations``): for models stiff at the accuracy wanted, where the explicit
    methods report ``stiff_steps``; dense backend only) or "auto": without ``tolerance``, fox_goodwin
    when ``time_step`` is within its stability limit at the start (damping included), with a 10 % margin, else
    average-acceleration newmark; with ``tolerance`` (and optionally ``max_step``), radau when the
    model's fastest modes, linearized at the start, are damped (a mode at damping ratio 0.3 or more at
    least half as fast as the fastest ringing one) or, at tolerances of 1e-7 and looser, when the
    fastest mode rings alone, 3 or more times faster than the next (a stiff contact), else
    fox_goodwin at tolerances of 1e-5 and looser (``max_halvings`` raised to at least 12) and dop853
    below (above 200 DOFs: dop853); never newmark under a tolerance.
    ``stats`` reports ``method`` (the one that ran), ``requested_method``, ``method_choice`` (with
    "auto": what it took and why, in words), ``velocity_choice`` (fox_goodwin, or newmark with gamma =
    1/2 and beta < 1/4, that kept the trapezoidal velocity: on the sparse backend, or at a step beyond
    the processed velocity's damped stability limit; why, in words), ``evaluations``,
    ``rejected_steps`` and ``stiff_steps`` (steps bounded by stability rather than accuracy: an
    implicit method would be cheaper there).

    ``system`` is a Mechanism (camfollower.MechanismBuilder, camfollower.presets, a config's ``.mechanism``).
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
    settings, options = settings_and_options(settings, options, **overrides)
    args, settle_dofs = _run_arguments(system, settings, options, initial_state=initial_state, progress=progress)
    return _result(
        _capped(lambda: _core._run(system, settings, progress=progress, **args), args, options.max_output_bytes),
        settle_dofs,
    )


def simulate_many(
    systems: Sequence,
    settings: Optional[SolverSettings] = None,
    options: Optional[RunOptions] = None,
    *,
    threads: Optional[int] = None,
    errors: str = "raise",
    progress: Optional[Callable[[int, int], Optional[bool]]] = None,
    **overrides,
) -> List[Optional[Result]]:
    """Run :func:`simulate` on every system of ``systems`` at once, on ``threads`` C++ threads (default:
    one per CPU core) with the GIL released, and return their Results in the systems' order.

    ``settings``, ``options`` and ``overrides`` as for :func:`simulate` (but no ``initial_state``),
    the same for every case (``revolutions`` count each system's own period). ``max_output_bytes``
    bounds the recordings of all cases together (each case gets an equal share): record what a study
    needs (``decimation``, ``record_last_revolutions``).

    ``errors``: "raise" (default) raises the first failed case's error (ValueError, RuntimeError, ...),
    prefixed with ``systems[i]``, once every case has run; "return" puts each failed case's exception
    in the list in place of its Result. ``progress(cases_done, cases)`` is called about every
    ``progress_interval`` seconds; returning False stops the call: the cases running stop (their
    Results have ``stats["cancelled"]``) and those not started are None. Ctrl-C stops every case and
    raises KeyboardInterrupt. Systems are immutable, so one system may appear many times.
    """
    systems = list(systems)
    if "initial_state" in overrides:
        raise TypeError("simulate_many() takes no initial_state: every case starts from its own static equilibrium")
    settings, options = settings_and_options(settings, options, **overrides)
    if progress is not None and not callable(progress):
        raise TypeError(
            f"progress must be a callable progress(cases_done, cases) or None, got {type(progress).__name__}"
        )
    if threads is not None and (
        isinstance(threads, bool) or not isinstance(threads, numbers.Integral) or not 1 <= threads <= 1024
    ):
        raise ValueError(f"threads must be an integer in [1, 1024] (None: one per CPU core), got {threads!r}")
    if errors not in ("raise", "return"):
        raise ValueError(f"errors must be 'raise' or 'return', got {errors!r}")
    if not systems:
        return []
    cases, shared, dofs = [], None, []
    for i, system in enumerate(systems):
        try:
            args, settle_dofs = _run_arguments(system, settings, options)
        except (TypeError, ValueError) as e:
            raise type(e)(f"systems[{i}]: {e}") from None
        cases.append(
            (
                system,
                args.pop("duration"),
                args.pop("record_from"),
                args.pop("settle_period", None),
                args.pop("settle_dofs", []),
            )
        )
        dofs.append(settle_dofs)
        for name in ("q0", "v0", "settle_tolerance", "settle_min_revolutions", "settle_max_revolutions"):
            args.pop(name, None)
        shared = args
    shared["max_output_bytes"] /= len(systems)
    raw = _core._run_many(
        cases,
        settings,
        threads=threads or 0,
        progress=progress,
        settle_tolerance=options.settle_tolerance,
        settle_min_revolutions=options.settle_min_revolutions,
        settle_max_revolutions=options.settle_max_revolutions,
        **shared,
    )
    out: List[Optional[Result]] = []
    for i, r in enumerate(raw):
        if isinstance(r, tuple):
            kind, message = r
            error = {"ValueError": ValueError, "MemoryError": MemoryError}.get(kind, RuntimeError)(
                f"systems[{i}]: {message}"
            )
            if errors == "raise":
                raise error
            out.append(error)
        else:
            out.append(None if r is None else _result(r, dofs[i]))
    return out


def _result(raw, settle_dofs) -> Result:
    stats = dict(raw["stats"])
    report = stats.pop("settle", None)
    if report is not None:
        report["dofs"] = list(settle_dofs)
    return Result(raw["names"], raw["dofs"], raw["data"], stats, raw["contact_loss"], report, raw["events"])


def _run_arguments(system, settings: SolverSettings, o: RunOptions, *, initial_state=None, progress=None):
    """simulate()'s arguments checked and turned into _core._run's (but for system and progress), and the
    watched DOFs' names (None without settle)."""
    if not isinstance(system, _core.Mechanism):
        raise TypeError(
            f"system must be a camfollower Mechanism (MechanismBuilder.build(), camfollower.presets, "
            f"a config's .mechanism), got {type(system).__name__}"
        )
    if progress is not None and not callable(progress):
        raise TypeError(
            f"progress must be a callable progress(steps_done, steps_planned) or None, got {type(progress).__name__}"
        )
    duration, revolutions, decimation = o.duration, o.revolutions, o.decimation
    record_from, record_last_revolutions = o.record_from, o.record_last_revolutions
    max_output_bytes, progress_interval = o.max_output_bytes, o.progress_interval
    settle, settle_tolerance, settle_dofs = o.settle, o.settle_tolerance, o.settle_dofs
    settle_min_revolutions, settle_max_revolutions = o.settle_min_revolutions, o.settle_max_revolutions
    time_step = settings.time_step
    # Numbers and counts checked here by name (pybind11 would say "incompatible function arguments");
    # the solver's settings were checked by SolverSettings.
    for name, value in (
        ("max_output_bytes", max_output_bytes),
        ("progress_interval", progress_interval),
        ("settle_tolerance", settle_tolerance),
        ("duration", duration),
        ("revolutions", revolutions),
        ("record_from", record_from),
        ("record_last_revolutions", record_last_revolutions),
    ):
        if value is not None and (isinstance(value, bool) or not isinstance(value, numbers.Real)):
            raise TypeError(f"{name} must be a number, got {type(value).__name__}")
    for name, value in (
        ("decimation", decimation),
        ("settle_min_revolutions", settle_min_revolutions),
        ("settle_max_revolutions", settle_max_revolutions),
    ):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise TypeError(f"{name} must be an integer, got {type(value).__name__} {value!r}")
        if not 0 <= value <= 2**53:
            raise ValueError(f"{name} must be in [0, 2^53], got {value}")
    if not isinstance(settle, bool):
        raise TypeError(f"settle must be a bool, got {type(settle).__name__}")
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
        window = record_last_revolutions * period
        if window > duration * (1 + 1e-12):
            raise ValueError(
                f"record_last_revolutions = {record_last_revolutions:g} is longer than the run "
                f"({duration / period:g} revolutions)"
            )
        if isinstance(time_step, numbers.Real) and window < 2 * decimation * time_step:
            raise ValueError(
                f"record_last_revolutions = {record_last_revolutions:g} ({window:g} s) holds fewer than two "
                f"rows at decimation {decimation} x time_step {time_step:g} s; record a longer window"
            )
        start = duration - window
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
        settle_args = dict(
            settle_period=float(period),
            settle_dofs=[names.index(d) for d in settle_dofs],
            settle_tolerance=settle_tolerance,
            settle_min_revolutions=settle_min_revolutions,
            settle_max_revolutions=settle_max_revolutions,
        )
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
    args = dict(
        duration=float(duration),
        decimation=decimation,
        record_from=start,
        max_output_bytes=cap,
        progress_interval=progress_interval,
        **settle_args,
        q0=q0,
        v0=v0,
    )
    return args, (list(settle_dofs) if settle else None)


def _capped(call, args, max_output_bytes):
    """call(), naming this machine's memory when it capped max_output_bytes and the run hit the cap."""
    try:
        return call()
    except ValueError as e:
        cap = args["max_output_bytes"]
        if cap < max_output_bytes and "max_output_bytes" in str(e):
            raise ValueError(
                f"{e} (max_output_bytes = {max_output_bytes:g} B was capped at this machine's memory, "
                f"{_physical_memory() / 2**30:.3g} GiB)"
            ) from None
        raise


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
