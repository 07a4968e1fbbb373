# SPDX-License-Identifier: BSD-3-Clause
"""Speed studies on the periodic steady state: margin curve, jump speed, spring sizing, speed sweeps
(waterfall of the contact force's shaft orders, resonances marked) and motion-law comparisons.

Every study takes the mechanism at one speed (it is rebuilt at each speed with
``Mechanism.with_camshaft_speed_rpm``) and an ``executor`` as in :mod:`camfollower.executors`
("serial", a process pool by default, any concurrent.futures.Executor, a Dask client or scheduler
address). Speeds in rpm of the camshaft, forces in N.
"""

from __future__ import annotations

import functools
import math
import numbers
import warnings
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import _core
from ._text import g
from .executors import run_cases
from .response import (
    ACCURACY_OF,
    HARMONICS,
    STUDY_ACCURACY,
    check_accuracy,
    check_accuracy_of,
    contact_of,
    steady_response,
)


def _at_speed(system, rpm: float, options: Dict[str, Any]) -> Dict[str, Any]:
    return steady_response(system.with_camshaft_speed_rpm(float(rpm)), **options)


# The model's own limits, stated in the core.
_MIN_RPM, _MAX_RPM = _core.MIN_CAMSHAFT_SPEED * 30.0 / math.pi, _core.MAX_CAMSHAFT_SPEED * 30.0 / math.pi


def _check_speeds(speeds, name: str = "speeds") -> List[float]:
    if isinstance(speeds, (str, bytes)) or not hasattr(speeds, "__iter__"):
        raise ValueError(f"{name} must be a sequence of camshaft speeds (rpm), got {type(speeds).__name__}")
    out = []
    for s in speeds:
        if isinstance(s, bool) or not isinstance(s, numbers.Real):
            raise ValueError(f"{name} must hold numbers (rpm), got {type(s).__name__}")
        out.append(float(s))
    if not out:
        raise ValueError(f"{name}: give at least one camshaft speed (rpm)")
    bad = [s for s in out if not (math.isfinite(s) and _MIN_RPM <= s <= _MAX_RPM)]
    if bad:
        raise ValueError(
            f"{name} must be finite camshaft speeds in [{_MIN_RPM:.6g}, {_MAX_RPM:.6g}] rpm, got {bad[:3]}"
        )
    return out


def _rows(outcomes, speeds) -> List[Dict[str, Any]]:
    rows = []
    for o, rpm in zip(outcomes, speeds):
        if o.ok:
            rows.append(o.value)
        else:
            rows.append({"rpm": rpm, "converged": False, "method": "failed", "error": o.error})
    return rows


def margin_curve(
    system,
    speeds: Sequence[float],
    *,
    contact: Optional[str] = None,
    accuracy: Optional[float] = None,
    steps_per_revolution: Optional[int] = None,
    fallback: Optional[str] = "transient",
    executor=None,
    workers: Optional[int] = None,
    progress: bool = True,
    accuracy_of: str = ACCURACY_OF[0],
) -> List[Dict[str, Any]]:
    """The periodic steady state at each speed (one :func:`camfollower.response.steady_response` row
    per speed, in order): minimum contact force (the margin) and where, contact loss, accelerations,
    harmonics, each at ``accuracy`` (steady_response: default 1e-3 of the peak force and acceleration;
    ``steps_per_revolution`` to fix the step instead; ``accuracy_of="force"``: of the force alone). Speeds whose response is not periodic fall back to
    the transient route (``fallback``); a speed that fails altogether gives a row with ``error``. Only
    these speeds are run: :func:`margin_scan` chooses the speeds from the model's resonances."""
    speeds = _check_speeds(speeds)
    if accuracy is not None:
        check_accuracy(accuracy)
    options = dict(contact=contact, accuracy=accuracy, steps_per_revolution=steps_per_revolution, fallback=fallback)
    fn = functools.partial(_at_speed, system, options={**options, "accuracy_of": check_accuracy_of(accuracy_of)})
    return _rows(run_cases(fn, speeds, executor=executor, workers=workers, progress=progress, desc="speeds"), speeds)


class StudyWarning(UserWarning):
    """A study's answer needs the designer's attention: a margin that dips with speed, several loss
    windows, coexisting steady states, a scan coarser than the model's resonances."""


@dataclass(frozen=True)
class LossWindow:
    """A speed range whose periodic steady state loses contact: from ``start_rpm`` (the lowest losing
    speed found; the contact holds ``tolerance`` below it) to ``end_rpm`` (the highest; nan when the
    contact is still lost at the range's end), the cam angle ``angle_deg`` where the follower leaves
    (where the force is smallest just below ``start_rpm``)."""

    start_rpm: float
    end_rpm: float
    angle_deg: float

    def __str__(self) -> str:
        end = "the range's end" if math.isnan(self.end_rpm) else f"{g(self.end_rpm)} rpm"
        return f"{g(self.start_rpm)} rpm to {end} (leaves at {g(self.angle_deg, 4)} deg)"


@dataclass(frozen=True)
class JumpSpeed:
    """The lowest camshaft speed in the range scanned whose periodic steady state loses contact (rpm,
    within ``tolerance``), the cam angle where the follower leaves (deg: where the contact force is
    smallest just below the jump speed), the final ``bracket`` (kept, lost) and the margin there;
    every loss window in the range (``windows``), the margin curve the scan measured (``margin``:
    steady_response rows sorted by speed), the scan's ``resolution_rpm`` (its largest spacing below
    the jump), the ``accuracy`` of the margin just below the jump and the scan's (``scan_accuracy``,
    the worst below the jump; relative, see steady_response), ``warnings`` (also issued as
    :class:`StudyWarning`) and every evaluation in the order run (``evaluations``)."""

    rpm: float
    angle_deg: float
    bracket: Tuple[float, float]
    min_force_below_N: float
    evaluations: List[Dict[str, Any]] = field(default_factory=list)
    windows: List[LossWindow] = field(default_factory=list)
    margin: List[Dict[str, Any]] = field(default_factory=list)
    resolution_rpm: float = math.nan
    accuracy: float = math.nan
    scan_accuracy: float = math.nan
    warnings: List[str] = field(default_factory=list)

    def __repr__(self) -> str:  # the answer, not every evaluation's 64 harmonics
        return (
            f"JumpSpeed(rpm={g(self.rpm)}, angle_deg={g(self.angle_deg, 4)}, "
            f"bracket=({g(self.bracket[0])}, {g(self.bracket[1])}), "
            f"min_force_below_N={g(self.min_force_below_N, 4)}, windows={len(self.windows)}, "
            f"warnings={len(self.warnings)}, evaluations={len(self.evaluations)})"
        )

    def __str__(self) -> str:
        text = (
            f"jump speed {g(self.rpm)} rpm (bracket {g(self.bracket[0])} to {g(self.bracket[1])} rpm): the "
            f"follower leaves the cam at {g(self.angle_deg, 4)} deg; min contact force just below "
            f"{g(self.min_force_below_N, 4)} N; {len(self.evaluations)} evaluations"
        )
        if len(self.windows) > 1:
            text += "; contact lost " + ", ".join(str(w) for w in self.windows)
        return text + "".join(f"\nwarning: {w}" for w in self.warnings)

    def summary(self) -> Dict[str, Any]:
        """JSON-ready facts (no per-speed harmonics)."""
        keep = ("rpm", "min_force_N", "min_force_angle_deg", "contact_lost", "accuracy", "steps_per_revolution")
        return {
            "rpm": self.rpm,
            "angle_deg": self.angle_deg,
            "bracket": list(self.bracket),
            "min_force_below_N": self.min_force_below_N,
            "resolution_rpm": self.resolution_rpm,
            "accuracy": self.accuracy,
            "scan_accuracy": self.scan_accuracy,
            "evaluations": len(self.evaluations),
            "windows": [
                {"start_rpm": w.start_rpm, "end_rpm": w.end_rpm, "angle_deg": w.angle_deg} for w in self.windows
            ],
            "margin": [{k: r.get(k) for k in keep} for r in self.margin],
            "warnings": list(self.warnings),
        }


def resonance_speeds(
    system, lo: float, hi: float, *, contact: Optional[str] = None, max_order: int = HARMONICS, threshold: float = 1e-3
) -> List[Tuple[int, float, float]]:
    """Where a shaft order of the cam's excitation meets a natural frequency of the mechanism inside
    (lo, hi) rpm: (order k, mode Hz, rpm = 60 f / k), sorted by speed. Orders 1 to the last one at
    which the rigid follower's acceleration has a harmonic of at least ``threshold`` of its largest
    (at most ``max_order``); modes are the mechanism's at cam angle 0, contacts linearized."""
    c = contact_of(system, contact)
    d2h = np.asarray(c["program"].evaluate(np.linspace(0, 2 * math.pi, 4096, endpoint=False))["d2h"])
    amp = np.abs(np.fft.rfft(d2h))[1 : max_order + 1]
    # Every order up to the last significant one: a symmetric lift cancels some orders in the rigid
    # excitation, but the flexible, nonlinear mechanism excites them again.
    significant = np.nonzero(amp >= threshold * amp.max())[0] if amp.size and amp.max() > 0 else []
    orders = list(range(1, int(significant[-1]) + 2)) if len(significant) else []
    try:
        natural = [float(f) for f in system.modal_analysis(0.0)["frequencies_hz"]]
    except (AttributeError, RuntimeError, ValueError):
        natural = []
    out = [(k, f, 60.0 * f / k) for f in natural for k in orders if lo < 60.0 * f / k < hi]
    return sorted(out, key=lambda x: x[2])


def _scan_grid(lo: float, hi: float, resonances, resolution: Optional[float]) -> Tuple[List[float], float]:
    """The first scan: every resonance speed and the midpoints between them, filled to at most
    ``resolution`` rpm apart (default: a 16th of the range, or half the closest spacing of two
    resonances of one mode, if finer), and the resolution used."""
    if resolution is None:
        resolution = (hi - lo) / 16.0
        by_mode: Dict[float, List[float]] = {}
        for _, f, r in resonances:
            by_mode.setdefault(f, []).append(r)
        gaps = [b - a for rs in by_mode.values() for a, b in zip(sorted(rs), sorted(rs)[1:])]
        if gaps:
            resolution = max(min(resolution, 0.5 * min(gaps)), (hi - lo) / 400.0)
    points = {lo, hi, *(r for _, _, r in resonances)}
    ordered = sorted(points)
    points.update(0.5 * (a + b) for a, b in zip(ordered, ordered[1:]))
    ordered = sorted(points)
    filled = []
    for a, b in zip(ordered, ordered[1:]):
        n = max(1, math.ceil((b - a) / resolution - 1e-9))
        filled.extend(a + (b - a) * i / n for i in range(n))
    filled.append(hi)
    merged = [filled[0]]
    for x in filled[1:]:  # resonances closer than a 1000th of the range are one point
        if x - merged[-1] > 1e-3 * (hi - lo):
            merged.append(x)
    merged[-1] = hi
    return merged, resolution


def _is_lost(row: Dict[str, Any]) -> bool:
    return bool(row.get("contact_lost", False))


class _Scan:
    """Periodic steady states by speed (rpm -> steady_response row), run in batches on an executor,
    with the evaluation budget and the order they were run in."""

    def __init__(self, system, options, executor, workers, progress, max_evaluations, what):
        self.system, self.options, self.executor, self.workers, self.progress = (
            system,
            options,
            executor,
            workers,
            progress,
        )
        self.max_evaluations, self.what = max_evaluations, what
        self.rows: Dict[float, Dict[str, Any]] = {}
        self.evaluations: List[Dict[str, Any]] = []

    def run(self, batch: Sequence[float]) -> None:
        batch = [x for x in dict.fromkeys(batch) if x not in self.rows]
        if len(self.evaluations) + len(batch) > self.max_evaluations:
            raise RuntimeError(
                f"{self.what} needs more than max_evaluations = {self.max_evaluations} periodic steady "
                "states; narrow the speed range or coarsen tolerance"
            )
        fn = functools.partial(_at_speed, self.system, options=self.options)
        outcomes = run_cases(
            fn, batch, executor=self.executor, workers=self.workers, progress=self.progress, desc="speeds"
        )
        for o, x in zip(outcomes, batch):
            if not o.ok:
                raise RuntimeError(f"{self.what}: the periodic steady state at {x:g} rpm failed: {o.error}")
            self.rows[x] = o.value
            self.evaluations.append(o.value)

    def sorted(self) -> List[float]:
        return sorted(self.rows)


def _refine_dips(scan: _Scan, tolerance: float) -> None:
    """Refine the dips of the margin among speeds that keep contact (midpoints and the parabola's
    vertex) that could hide a loss — deeper than the margin left at their bottom, or with less margin
    left than 5 times its error — until they lose contact or their neighbours are within
    ``tolerance`` (relative)."""
    for _ in range(12):
        xs, rows, new = scan.sorted(), scan.rows, []
        for i in range(1, len(xs) - 1):
            a, b, c = (rows[x] for x in xs[i - 1 : i + 2])
            if any(map(_is_lost, (a, b, c))) or not (
                b["min_force_N"] < a["min_force_N"] and b["min_force_N"] <= c["min_force_N"]
            ):
                continue
            depth = max(a["min_force_N"], c["min_force_N"]) - b["min_force_N"]
            if b["min_force_N"] > max(depth, 5.0 * b.get("force_error_N", 0.0)):
                continue
            x0, x1, x2 = xs[i - 1 : i + 2]
            if min(x1 - x0, x2 - x1) <= tolerance * x1:
                continue
            new += [0.5 * (x0 + x1), 0.5 * (x1 + x2)]
            vertex = _parabola_vertex(x0, x1, x2, a["min_force_N"], b["min_force_N"], c["min_force_N"])
            if vertex is not None and abs(vertex - x1) > tolerance * x1:
                new.append(vertex)
        if not new:
            return
        scan.run(new)


def _check_range(speed_range, tolerance, resolution, accuracy) -> Tuple[float, float]:
    speeds = _check_speeds(speed_range, "speed_range")
    lo, hi = speeds if len(speeds) == 2 else (None, None)
    if lo is None or not lo < hi:
        raise ValueError(f"speed_range must be two increasing speeds (lo, hi) in rpm, got {speed_range!r}")
    if isinstance(tolerance, bool) or not isinstance(tolerance, numbers.Real) or not 1e-6 <= tolerance < 0.5:
        raise ValueError(f"tolerance must be in [1e-06, 0.5) (relative), got {tolerance!r}")
    if resolution is not None and (
        isinstance(resolution, bool) or not isinstance(resolution, numbers.Real) or not 0.0 < resolution <= hi - lo
    ):
        raise ValueError(f"resolution must be a speed step in (0, {hi - lo:g}] rpm, got {resolution!r}")
    if accuracy is not None:
        check_accuracy(accuracy)
    return lo, hi


#: The accuracy the margin scan runs at (the edges of loss windows are then found at the accuracy asked).
SCAN_ACCURACY = 1e-2


def _scan_accuracy(accuracy: Optional[float], steps_per_revolution: Optional[int]) -> Optional[float]:
    if steps_per_revolution is not None and accuracy is None:
        return None
    return max(STUDY_ACCURACY if accuracy is None else accuracy, SCAN_ACCURACY)


def _scan_options(contact, accuracy, steps_per_revolution, accuracy_of) -> Dict[str, Any]:
    return dict(
        contact=contact,
        accuracy=accuracy,
        accuracy_of=accuracy_of,
        steps_per_revolution=steps_per_revolution,
        fallback="transient",
        multipliers=False,
        keep_orbit=True,
        stop_at_loss=True,
    )


def _scan_range(
    system,
    lo,
    hi,
    *,
    contact,
    tolerance,
    accuracy,
    accuracy_of,
    steps_per_revolution,
    resolution,
    max_evaluations,
    executor,
    workers,
    progress,
    what,
) -> Tuple[_Scan, float, List[str]]:
    """The margin scan of (lo, hi): the resonance grid, then its dips refined; (scan, resolution used,
    warnings)."""
    c = contact_of(system, contact)
    if c["grooved"]:
        raise ValueError(
            f"contact {c['name']!r} is grooved (form-closed): it has no contact margin or jump speed to scan; its "
            "roller changes flank where the load reverses (see camfollower.config.force_closure's outer_flank_deg "
            "and analysis.groove_statistics)"
        )
    scan = _Scan(
        system,
        _scan_options(contact, _scan_accuracy(accuracy, steps_per_revolution), steps_per_revolution, accuracy_of),
        executor,
        workers,
        progress,
        max_evaluations,
        what,
    )
    resonances = resonance_speeds(system, lo, hi, contact=contact)
    grid, used = _scan_grid(lo, hi, resonances, resolution)
    warned = []
    if resolution is not None and resonances:
        needed = _scan_grid(lo, hi, resonances, None)[1]
        if resolution > 1.5 * needed:
            warned.append(
                f"resolution {resolution:g} rpm is coarser than the model's resonances need "
                f"({needed:.4g} rpm: shaft orders meet its modes that close together); a loss window "
                "between scan points can be missed"
            )
    scan.run(grid)
    _refine_dips(scan, tolerance)
    return scan, used, warned


def margin_scan(
    system,
    speed_range: Tuple[float, float],
    *,
    contact: Optional[str] = None,
    tolerance: float = 1e-3,
    accuracy: Optional[float] = None,
    steps_per_revolution: Optional[int] = None,
    resolution: Optional[float] = None,
    max_evaluations: int = 400,
    executor="serial",
    workers: Optional[int] = None,
    progress: bool = False,
    accuracy_of: str = ACCURACY_OF[0],
) -> List[Dict[str, Any]]:
    """The margin curve over ``speed_range = (lo, hi)`` rpm at the speeds the model needs: every
    resonance speed (:func:`resonance_speeds`), the midpoints between them, at most ``resolution`` rpm
    apart (default from the resonances' spacing), and every dip of the minimum contact force refined to
    ``tolerance`` (relative) or until it loses contact. steady_response rows sorted by speed (the same
    scan :func:`jump_speed` and :func:`size_spring` run). ``accuracy_of="force"``: the accuracy of the
    contact force alone, all a margin reads (steady_response)."""
    lo, hi = _check_range(speed_range, tolerance, resolution, accuracy)
    scan, _, warned = _scan_range(
        system,
        lo,
        hi,
        contact=contact,
        tolerance=tolerance,
        accuracy=accuracy,
        accuracy_of=check_accuracy_of(accuracy_of),
        steps_per_revolution=steps_per_revolution,
        resolution=resolution,
        max_evaluations=max_evaluations,
        executor=executor,
        workers=workers,
        progress=progress,
        what=f"the margin scan of ({lo:g}, {hi:g}) rpm",
    )
    for w in warned:
        warnings.warn(w, StudyWarning, stacklevel=2)
    return [{k: v for k, v in scan.rows[x].items() if k != "orbit"} for x in scan.sorted()]


def jump_speed(
    system,
    speed_range: Tuple[float, float],
    *,
    contact: Optional[str] = None,
    tolerance: float = 1e-3,
    accuracy: Optional[float] = None,
    steps_per_revolution: Optional[int] = None,
    resolution: Optional[float] = None,
    max_evaluations: int = 400,
    executor="serial",
    workers: Optional[int] = None,
    progress: bool = False,
    accuracy_of: str = ACCURACY_OF[0],
) -> JumpSpeed:
    """The jump speed: the lowest camshaft speed in ``speed_range = (lo, hi)`` rpm whose periodic steady
    state loses contact, found whatever the range.

    The minimum contact force need not fall steadily with speed: a shaft order meeting a natural
    frequency makes it dip, and contact can be lost in a window below the speed where it is lost for
    good. So the margin is scanned first (:func:`margin_scan`): at every resonance speed of the model
    (:func:`resonance_speeds`), between them, and at most ``resolution`` rpm apart (default from the
    resonances' spacing; a coarser one given is warned about); every dip of the margin is refined
    (midpoints and parabolic steps) until it loses contact or is resolved to ``tolerance``. Then each
    run of losing speeds is bisected at both ends to ``tolerance`` (relative): ``windows``. Warnings
    (``warnings``, :class:`StudyWarning`): a margin that dips on the way (non-monotonic), several loss
    windows, and coexisting steady states (the orbit found coming down from the first losing speed
    still losing contact where the one from rest keeps it: the answer then depends on how the speed is
    reached).

    Every speed is a :func:`camfollower.response.steady_response` at ``accuracy`` (default 1e-3 of
    the peak force and acceleration; ``accuracy_of="force"``: of the force alone, all the search reads;
    ``steps_per_revolution`` to fix the step instead). ValueError when
    the contact is already lost at ``lo`` or nowhere in the range (with the smallest margin and where).
    ``executor``/``workers`` run the scan's speeds as :func:`margin_curve` does (default serial).
    """
    lo, hi = _check_range(speed_range, tolerance, resolution, accuracy)
    scan, used, warned = _scan_range(
        system,
        lo,
        hi,
        contact=contact,
        tolerance=tolerance,
        accuracy=accuracy,
        accuracy_of=check_accuracy_of(accuracy_of),
        steps_per_revolution=steps_per_revolution,
        resolution=resolution,
        max_evaluations=max_evaluations,
        executor=executor,
        workers=workers,
        progress=progress,
        what=f"jump_speed over ({lo:g}, {hi:g}) rpm",
    )
    coarse = scan.rows
    fine = _Scan(
        system,
        _scan_options(contact, accuracy, steps_per_revolution, accuracy_of),
        executor,
        workers,
        progress,
        max_evaluations,
        scan.what,
    )
    rows = fine.rows

    def lost_at(x: float) -> bool:
        fine.run([x])
        return _is_lost(rows[x])

    xs = scan.sorted()
    runs, i = [], 0
    while i < len(xs):
        if _is_lost(coarse[xs[i]]):
            j = i
            while j + 1 < len(xs) and _is_lost(coarse[xs[j + 1]]):
                j += 1
            runs.append((i, j))
            i = j + 1
        else:
            i += 1

    def edge(k: int, step: int) -> Optional[Tuple[float, float]]:
        """The edge between scan speed k (contact kept) and its neighbour k + step (lost), at the
        accuracy asked: both ends confirmed (moving outwards or inwards when the finer answer
        differs), then bisected to the tolerance. None when the window closes at that accuracy."""
        while lost_at(xs[k]):
            k -= step
            if not 0 <= k < len(xs):  # (lo is kept: only an upper edge runs off, at the range's end)
                return None
        m = k + step
        while 0 <= m < len(xs) and not lost_at(xs[m]):
            if not _is_lost(coarse[xs[m]]):
                return None
            k, m = m, m + step
        if not 0 <= m < len(xs):
            return None
        kept_x, lost_x = xs[k], xs[m]
        while abs(lost_x - kept_x) > tolerance * max(kept_x, lost_x):
            mid = 0.5 * (kept_x + lost_x)
            kept_x, lost_x = (kept_x, mid) if lost_at(mid) else (mid, lost_x)
        return kept_x, lost_x

    if lost_at(lo):
        r = rows[lo]
        raise ValueError(
            f"speed_range: the contact is already lost at the lower speed {lo:g} rpm (min force "
            f"{r['min_force_N']:.4g} N, first loss at {r['first_loss_angle_deg']:.4g} deg): the first "
            "loss is below the range; lower it"
        )
    windows, first_bracket = [], None
    for i, j in runs:
        low = edge(i - 1, +1)
        if low is None:
            continue
        if first_bracket is None:
            first_bracket = low
        high = edge(j + 1, -1) if j + 1 < len(xs) else None
        windows.append(
            LossWindow(
                start_rpm=low[1], end_rpm=high[1] if high else math.nan, angle_deg=rows[low[0]]["min_force_angle_deg"]
            )
        )
    if first_bracket is None:
        merged = {**coarse, **rows}
        k = min(merged, key=lambda x: merged[x]["min_force_N"])
        r = merged[k]
        raise ValueError(
            f"speed_range: no contact loss between {lo:g} and {hi:g} rpm ({len(merged)} speeds scanned, "
            f"resolution {used:.4g} rpm); the smallest margin is {r['min_force_N']:.4g} N at {k:.6g} rpm, "
            f"at {r['min_force_angle_deg']:.4g} deg of cam angle: raise the upper speed"
        )
    kept, lost = first_bracket
    below = rows[kept]
    # Coexisting states: come down from the first losing speed to the kept one, from the losing orbit.
    down = steady_response(
        system.with_camshaft_speed_rpm(kept),
        guess=rows[lost].get("orbit"),
        **{k: v for k, v in fine.options.items() if k != "keep_orbit"},
    )
    fine.evaluations.append(down)
    rows = {**coarse, **rows}  # the margin curve: the scan's speeds, at the accuracy asked where it was rerun
    if _is_lost(down):
        warned.append(
            f"coexisting steady states at {kept:.6g} rpm: coming down from {lost:.6g} rpm the follower "
            f"keeps losing contact (min force {down['min_force_N']:.4g} N) where the state reached from "
            f"rest keeps it ({below['min_force_N']:.4g} N): the jump depends on how the speed is reached"
        )
    xs = sorted(rows)
    dips = [
        x
        for a, x, b in zip(xs, xs[1:], xs[2:])
        if x < kept
        and not _is_lost(rows[x])
        and rows[x]["min_force_N"] < rows[a]["min_force_N"]
        and rows[x]["min_force_N"] < rows[b]["min_force_N"]
    ]
    if dips:
        shown = ", ".join(f"{x:.5g} rpm ({rows[x]['min_force_N']:.4g} N)" for x in dips[:6])
        more = f" and {len(dips) - 6} more" if len(dips) > 6 else ""
        warned.append(
            f"the margin is not monotonic in speed: below the jump it dips at {shown}{more} "
            "(shaft orders meeting natural frequencies)"
        )
    if len(windows) > 1:
        warned.append(
            f"contact is lost in {len(windows)} windows: "
            + "; ".join(str(w) for w in windows)
            + " — it holds again between them"
        )
    for w in warned:
        warnings.warn(w, StudyWarning, stacklevel=2)
    gaps = [b - a for a, b in zip(xs, xs[1:]) if b <= kept]
    evaluations = scan.evaluations + fine.evaluations
    for r in evaluations:
        r.pop("orbit", None)
    return JumpSpeed(
        rpm=lost,
        angle_deg=below["min_force_angle_deg"],
        bracket=(kept, lost),
        min_force_below_N=below["min_force_N"],
        evaluations=evaluations,
        windows=windows,
        margin=[rows[x] for x in xs],
        resolution_rpm=max(gaps, default=lost - kept),
        accuracy=fine.rows[kept]["accuracy"],
        scan_accuracy=max((coarse[x]["accuracy"] for x in coarse if x <= kept), default=math.nan),
        warnings=warned,
    )


def _parabola_vertex(x0, x1, x2, y0, y1, y2) -> Optional[float]:
    """The minimum of the parabola through three points, if it lies between the outer two."""
    d = (x0 - x1) * (x0 - x2) * (x1 - x2)
    a = (x2 * (y1 - y0) + x1 * (y0 - y2) + x0 * (y2 - y1)) / d
    b = (x2 * x2 * (y0 - y1) + x1 * x1 * (y2 - y0) + x0 * x0 * (y1 - y2)) / d
    if not a > 0:
        return None
    v = -b / (2 * a)
    return v if x0 < v < x2 else None


@dataclass(frozen=True)
class SpringSize:
    """A spring that keeps ``margin_N`` of contact force up to ``rpm``: its ``rate`` (N/m) and the
    smallest ``preload`` (N, at the follower's lowest position) that does it, with the resulting
    minimum force, where it occurs and at which speed (``critical_rpm``: ``rpm``, or the speed of the
    scanned range where the margin is least), and the spring's largest force over the revolution (N)."""

    rate: float
    preload: float
    min_force_N: float
    min_force_angle_deg: float
    max_spring_force_N: float
    evaluations: int
    critical_rpm: float = math.nan

    def __repr__(self) -> str:
        at = "" if math.isnan(self.critical_rpm) else f"critical_rpm={g(self.critical_rpm)}, "
        return (
            f"SpringSize(rate={g(self.rate)}, preload={g(self.preload)}, min_force_N={g(self.min_force_N, 4)}, "
            f"min_force_angle_deg={g(self.min_force_angle_deg, 4)}, {at}"
            f"max_spring_force_N={g(self.max_spring_force_N)}, evaluations={self.evaluations})"
        )


def size_spring(
    build: Callable[[float, float], Any],
    rpm: float,
    margin: float,
    rates: Sequence[float],
    *,
    contact: Optional[str] = None,
    preload_guess: float = 100.0,
    accuracy: Optional[float] = None,
    steps_per_revolution: Optional[int] = None,
    tolerance: float = 1e-3,
    speed_range: Optional[Tuple[float, float]] = None,
    max_evaluations: int = 30,
    accuracy_of: str = ACCURACY_OF[0],
) -> List[SpringSize]:
    """For each spring ``rate`` (N/m), the smallest preload (N) whose periodic response keeps at least
    ``margin`` N of contact force all round at ``rpm`` — and, given ``speed_range = (lo, rpm)``, at
    every speed of that range (secant steps on the preload: the minimum force is nearly affine in it).
    With a range, the margin is scanned as :func:`jump_speed` scans it (resonance dips refined) for the
    spring found, and the spring is sized again at the speed where the margin is least, until the
    whole range keeps it. ``build(rate, preload)`` returns the mechanism (at any speed). The spring's
    largest force is preload + rate x the largest lift (the program's). Each response at ``accuracy``
    (steady_response; ``accuracy_of="force"``: of the force alone, all the sizing reads). Raises ValueError for a margin < 0, rates <= 0 or a range not ending at ``rpm``,
    RuntimeError when no preload up to 1e6 N does."""
    if not (math.isfinite(margin) and margin >= 0.0):
        raise ValueError(f"margin must be a finite force >= 0 N, got {margin}")
    rates = [float(k) for k in rates]
    if not rates or any(not (math.isfinite(k) and k > 0) for k in rates):
        raise ValueError(f"rates must be finite spring rates > 0 N/m, got {rates}")
    if not (math.isfinite(preload_guess) and preload_guess > 0):
        raise ValueError(f"preload_guess must be a finite force > 0 N, got {preload_guess}")
    rpm = _check_speeds([rpm])[0]
    check_accuracy_of(accuracy_of)
    if speed_range is not None:
        lo, hi = _check_range(speed_range, tolerance, None, accuracy)
        if hi != rpm:
            raise ValueError(
                f"speed_range must end at rpm = {rpm:g} (the margin is kept up to it), got {speed_range!r}"
            )
    out = []
    for k in rates:
        count = 0

        def margin_at(p, at_rpm):
            nonlocal count
            count += 1
            mech = build(k, p).with_camshaft_speed_rpm(at_rpm)
            row = steady_response(
                mech,
                contact=contact,
                accuracy=accuracy,
                accuracy_of=accuracy_of,
                steps_per_revolution=steps_per_revolution,
                fallback="transient",
                multipliers=False,
            )
            # With contact lost the minimum force is 0 whatever the shortfall: extrapolate from the
            # lost fraction so the secant still sees a slope.
            short = row["min_force_N"] - margin - (row["lost_fraction"] * p if row["contact_lost"] else 0.0)
            return short, row, mech

        def size_at(at_rpm, p0):
            p1 = 2.0 * p0
            f0, _, _ = margin_at(p0, at_rpm)
            f1, row1, mech = margin_at(p1, at_rpm)
            while abs(p1 - p0) > tolerance * abs(p1) or f1 < 0.0:
                if count >= max_evaluations:
                    raise RuntimeError(
                        f"size_spring: no preload found for rate {k:g} N/m in {max_evaluations} "
                        f"evaluations (last {p1:g} N, margin shortfall {f1:.4g} N at {at_rpm:g} rpm)"
                    )
                slope = (f1 - f0) / (p1 - p0) if p1 != p0 else 1.0
                step = -f1 / slope if slope > 0 else p1
                p_next = min(max(p1 + step, 0.5 * p1), 4.0 * p1 + 1.0)
                if p_next > 1e6:
                    raise RuntimeError(
                        f"size_spring: rate {k:g} N/m needs a preload above 1e6 N for {margin:g} N at {at_rpm:g} rpm"
                    )
                if f1 >= 0.0 and abs(p_next - p1) <= tolerance * p1:
                    break
                p0, f0 = p1, f1
                p1 = p_next
                f1, row1, mech = margin_at(p1, at_rpm)
            return p1, row1, mech

        critical = rpm
        p, row, mech = size_at(rpm, preload_guess)
        for _ in range(4 if speed_range is not None else 0):
            rows = margin_scan(
                build(k, p),
                (lo, rpm),
                contact=contact,
                tolerance=tolerance,
                accuracy=accuracy,
                accuracy_of=accuracy_of,
                steps_per_revolution=steps_per_revolution,
            )
            count += len(rows)
            worst = min(rows, key=lambda r: r["min_force_N"] - (r["lost_fraction"] * p if r["contact_lost"] else 0.0))
            if worst["min_force_N"] >= margin - max(worst.get("force_error_N", 0.0), tolerance * margin):
                row = worst
                critical = worst["rpm"]
                break
            critical = worst["rpm"]
            p, row, mech = size_at(critical, p)
        lift = max(
            float(np.max(np.asarray(c["program"].evaluate(np.linspace(0, 2 * math.pi, 4097))["h"])))
            for c in mech.builder().contacts
        )
        out.append(
            SpringSize(
                rate=k,
                preload=p,
                min_force_N=row["min_force_N"],
                min_force_angle_deg=row["min_force_angle_deg"],
                max_spring_force_N=p + k * lift,
                evaluations=count,
                critical_rpm=critical,
            )
        )
    return out


def speed_sweep(system, speeds: Sequence[float], **options) -> Dict[str, Any]:
    """A speed sweep: :func:`margin_curve` rows plus, for the waterfall, the contact force's
    harmonics as an array ``orders x speeds`` (``spectrum``, N) with ``orders`` (1, 2, ...), and the
    mechanism's natural frequencies on the dwell (``natural_hz``) for marking resonances: shaft order
    k resonates with mode j where k x rpm / 60 = f_j (``resonances``: (order, mode Hz, rpm) inside the
    swept range)."""
    rows = margin_curve(system, speeds, **options)
    good = [r for r in rows if "harmonics" in r]
    width = max((len(r["harmonics"]) for r in good), default=0)
    spectrum = np.full((width, len(rows)), np.nan)
    for j, r in enumerate(rows):
        if "harmonics" in r:
            spectrum[: len(r["harmonics"]), j] = r["harmonics"]
    try:
        natural = [float(f) for f in system.modal_analysis(0.0)["frequencies_hz"]]
    except (AttributeError, RuntimeError, ValueError):
        natural = []
    lo, hi = min(r["rpm"] for r in rows), max(r["rpm"] for r in rows)
    resonances = [(k, f, 60.0 * f / k) for f in natural for k in range(1, width + 1) if lo <= 60.0 * f / k <= hi]
    return {
        "rows": rows,
        "orders": list(range(1, width + 1)),
        "spectrum": spectrum,
        "natural_hz": natural,
        "resonances": resonances,
    }


def _resonance_strength(sweep: Dict[str, Any], rpm: np.ndarray, spec: np.ndarray) -> List[float]:
    """Each resonance's harmonic amplitude (N), interpolated at its crossing speed (NaN: not computed)."""
    out = []
    for k, _, r in sweep["resonances"]:
        row = spec[k - 1] if 0 < k <= spec.shape[0] else np.full(rpm.size, np.nan)
        good = np.isfinite(row)
        out.append(float(np.interp(r, rpm[good], row[good])) if good.sum() >= 1 else float("nan"))
    return out


def plot_waterfall(sweep: Dict[str, Any], *, labels: int = 12, ax=None):
    """Campbell-style waterfall of a :func:`speed_sweep`: contact-force harmonic amplitude (colour, dB
    re 1 N) at frequency k x rpm / 60 against camshaft speed, the natural frequencies as dashed lines,
    and every crossing of a shaft order k with a mode (a resonance: k x rpm / 60 = f) marked. At most
    ``labels`` of them, the strongest harmonics first, are circled with their order's line and label
    "k×", and only where the label does not overlap another: a long run of high orders crossing one
    mode stays readable. Returns the figure."""
    import matplotlib.pyplot as plt

    missing = [
        k
        for k in ("rows", "spectrum", "orders", "natural_hz", "resonances")
        if not isinstance(sweep, dict) or k not in sweep
    ]
    if missing:
        raise ValueError(f"sweep must be a speed_sweep() result; missing {missing}")
    rows = sweep["rows"]
    rpm = np.array([r["rpm"] for r in rows], dtype=float)
    spec = np.asarray(sweep["spectrum"], dtype=float)
    fig = ax.figure if ax is not None else plt.figure(figsize=(9, 6))
    ax = ax or fig.add_subplot(111)
    orders = np.asarray(sweep["orders"])
    if spec.size:
        R, K = np.meshgrid(rpm, orders)
        F = K * R / 60.0
        amp = 20 * np.log10(np.maximum(spec, 1e-6))
        sc = ax.scatter(R.ravel(), F.ravel(), c=amp.ravel(), s=8, cmap="viridis", vmin=np.nanmax(amp) - 80)
        fig.colorbar(sc, ax=ax, label="contact force harmonic (dB re 1 N)")
        fmax = float(np.nanmax(F))
        span = float(rpm.max() - rpm.min()) or 1.0
        ax.set_xlim(rpm.min() - 0.03 * span, rpm.max() + 0.03 * span)
        ax.set_ylim(0, 1.05 * fmax)
        for i, f in enumerate(f for f in sweep["natural_hz"] if f <= fmax):
            ax.axhline(f, color="tab:red", lw=0.8, ls="--", label="natural frequency (dwell)" if i == 0 else None)
            ax.annotate(
                f"mode {f:.4g} Hz",
                (0.0, f),
                xycoords=("axes fraction", "data"),
                xytext=(3, -3),
                textcoords="offset points",
                ha="left",
                va="top",
                fontsize=7,
                color="tab:red",
            )
        res = sweep["resonances"]
        if res:
            ax.plot(
                [r for _, _, r in res],
                [f for _, f, _ in res],
                "|",
                color="tab:red",
                ms=6,
                mew=0.8,
                label="shaft order × mode crossing",
            )
        # Label the strongest crossings first; skip one whose label would touch a label already placed
        # (in display space, with the axes' final limits).
        fig.canvas.draw_idle()
        to_px = ax.transData.transform
        placed: List[Tuple[float, float]] = []
        strength = _resonance_strength(sweep, rpm, spec)
        order = sorted(range(len(res)), key=lambda i: -(strength[i] if np.isfinite(strength[i]) else -np.inf))
        line = np.array([rpm.min(), rpm.max()])
        gap_x, gap_y = 30.0 * fig.dpi / 100.0, 14.0 * fig.dpi / 100.0  # a label's size, in pixels
        for i in order:
            if len(placed) >= labels:
                break
            k, f, r = res[i]
            x, y = to_px((r, f))
            if any(abs(x - px) < gap_x and abs(y - py) < gap_y for px, py in placed):
                continue
            placed.append((x, y))
            ax.plot(
                r, f, "o", mfc="none", mec="tab:red", ms=9, label="labelled resonance" if len(placed) == 1 else None
            )
            ax.plot(line, k * line / 60.0, color="0.5", lw=0.5)
            ax.annotate(
                f"{k}×", (r, f), xytext=(0, 7), textcoords="offset points", ha="center", fontsize=7, color="tab:red"
            )
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper left", fontsize=7)
    ax.set_xlabel("camshaft speed (rpm)")
    ax.set_ylabel("frequency (Hz)")
    ax.set_title("Contact force shaft orders of the periodic response; resonances circled")
    return fig


def plot_margin(rows: Sequence[Dict[str, Any]], jump: Optional[JumpSpeed] = None, ax=None):
    """The margin curve: minimum contact force against speed, contact loss marked, the jump speed
    (if given: the first loss) as a vertical line inside the axes and its loss windows shaded. Returns
    the figure."""
    import matplotlib.pyplot as plt

    fig = ax.figure if ax is not None else plt.figure(figsize=(7, 4.5))
    ax = ax or fig.add_subplot(111)
    ok = [r for r in rows if "min_force_N" in r]
    rpm = np.array([r["rpm"] for r in ok])
    f = np.array([r["min_force_N"] for r in ok])
    lost = np.array([r["contact_lost"] for r in ok], dtype=bool)
    ax.plot(rpm, f, "o-", label="minimum contact force")
    if lost.any():
        ax.plot(rpm[lost], f[lost], "x", color="tab:red", ms=9, label="contact lost")
    speeds = list(rpm)
    if jump is not None:
        for i, w in enumerate(jump.windows):
            end = w.end_rpm if math.isfinite(w.end_rpm) else max(speeds + [w.start_rpm])
            ax.axvspan(
                w.start_rpm,
                max(end, w.start_rpm),
                color="tab:red",
                alpha=0.12,
                lw=0,
                label="contact lost (windows)" if i == 0 else None,
            )
        ax.axvline(
            jump.rpm, color="tab:red", ls="--", label=f"first loss {jump.rpm:.0f} rpm at {jump.angle_deg:.0f} deg"
        )
        speeds.append(jump.rpm)
    if speeds:  # the jump line off the last speed stays inside, clear of the frame
        lo, hi = min(speeds), max(speeds)
        pad = 0.04 * (hi - lo) if hi > lo else 0.05 * hi
        ax.set_xlim(lo - pad, hi + pad)
    ax.axhline(0.0, color="0.5", lw=0.6)
    ax.set_xlabel("camshaft speed (rpm)")
    ax.set_ylabel("minimum contact force (N)")
    ax.set_title("Margin against jump: smallest contact force per revolution")
    ax.grid(alpha=0.3)
    ax.legend()
    return fig


def _program_case(build, speed, options, item):
    name, program = item
    row = steady_response(build(program).with_camshaft_speed_rpm(speed), **options)
    row["program"] = name
    return row


def compare_programs(
    build: Callable[[Any], Any],
    programs: Dict[str, Any],
    rpm: float,
    *,
    contact: Optional[str] = None,
    accuracy: Optional[float] = None,
    steps_per_revolution: Optional[int] = None,
    executor=None,
    workers: Optional[int] = None,
    progress: bool = True,
    accuracy_of: str = ACCURACY_OF[0],
) -> List[Dict[str, Any]]:
    """Motion laws side by side: ``build(program)`` returns the mechanism for a MotionProgram; one
    steady_response row per named program at ``rpm`` (with ``program``: its name): margin, peak
    accelerations against the rigid follower's, residual vibration in the dwells."""
    if not programs:
        raise ValueError("programs: give at least one named MotionProgram")
    speed = _check_speeds([rpm])[0]
    items = list(programs.items())
    fn = functools.partial(
        _program_case,
        build,
        speed,
        dict(
            contact=contact,
            accuracy=accuracy,
            accuracy_of=check_accuracy_of(accuracy_of),
            steps_per_revolution=steps_per_revolution,
            fallback="transient",
        ),
    )
    out = run_cases(fn, items, executor=executor, workers=workers, progress=progress, desc="programs")
    return [o.value if o.ok else {"program": name, "error": o.error} for o, (name, _) in zip(out, items)]


__all__ = [
    "JumpSpeed",
    "LossWindow",
    "SpringSize",
    "StudyWarning",
    "compare_programs",
    "jump_speed",
    "margin_curve",
    "margin_scan",
    "plot_margin",
    "plot_waterfall",
    "resonance_speeds",
    "size_spring",
    "speed_sweep",
]
