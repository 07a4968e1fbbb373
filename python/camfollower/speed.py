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
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import _core
from ._text import g
from .executors import run_cases
from .response import STUDY_STEPS_PER_REVOLUTION, steady_response


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
        raise ValueError(f"{name} must be finite camshaft speeds in [{_MIN_RPM:.6g}, {_MAX_RPM:.6g}] rpm, got {bad[:3]}")
    return out


def _rows(outcomes, speeds) -> List[Dict[str, Any]]:
    rows = []
    for o, rpm in zip(outcomes, speeds):
        if o.ok:
            rows.append(o.value)
        else:
            rows.append({"rpm": rpm, "converged": False, "method": "failed", "error": o.error})
    return rows


def margin_curve(system, speeds: Sequence[float], *, contact: Optional[str] = None,
                 steps_per_revolution: int = STUDY_STEPS_PER_REVOLUTION, fallback: Optional[str] = "transient",
                 executor=None, workers: Optional[int] = None, progress: bool = True) -> List[Dict[str, Any]]:
    """The periodic steady state at each speed (one :func:`camfollower.response.steady_response` row
    per speed, in order): minimum contact force (the margin) and where, contact loss, accelerations,
    harmonics. Speeds whose response is not periodic fall back to the transient route (``fallback``);
    a speed that fails altogether gives a row with ``error``."""
    speeds = _check_speeds(speeds)
    fn = functools.partial(_at_speed, system, options=dict(contact=contact, steps_per_revolution=steps_per_revolution,
                                                           fallback=fallback))
    return _rows(run_cases(fn, speeds, executor=executor, workers=workers, progress=progress, desc="speeds"), speeds)


@dataclass(frozen=True)
class JumpSpeed:
    """The camshaft speed at which the follower first leaves the cam (rpm, within ``tolerance``), the
    cam angle where it leaves (deg: where the contact force is smallest just below the jump speed),
    and every speed evaluated on the way (``evaluations``: steady_response rows, in the order run)."""

    rpm: float
    angle_deg: float
    bracket: Tuple[float, float]
    min_force_below_N: float
    evaluations: List[Dict[str, Any]] = field(default_factory=list)

    def __repr__(self) -> str:  # the answer, not every evaluation's 64 harmonics
        return (f"JumpSpeed(rpm={g(self.rpm)}, angle_deg={g(self.angle_deg, 4)}, "
                f"bracket=({g(self.bracket[0])}, {g(self.bracket[1])}), "
                f"min_force_below_N={g(self.min_force_below_N, 4)}, evaluations={len(self.evaluations)})")

    def __str__(self) -> str:
        return (f"jump speed {g(self.rpm)} rpm (bracket {g(self.bracket[0])} to {g(self.bracket[1])} rpm): the "
                f"follower leaves the cam at {g(self.angle_deg, 4)} deg; min contact force just below "
                f"{g(self.min_force_below_N, 4)} N; {len(self.evaluations)} evaluations")


def jump_speed(system, bracket: Tuple[float, float], *, contact: Optional[str] = None, tolerance: float = 1e-3,
               steps_per_revolution: int = STUDY_STEPS_PER_REVOLUTION, max_evaluations: int = 40) -> JumpSpeed:
    """The jump speed by bisection on contact loss in the periodic steady state between
    ``bracket = (lo, hi)`` rpm: the contact must hold all round at ``lo`` and be lost somewhere at
    ``hi`` (else ValueError saying what each end showed). Bisection stops when the bracket is
    narrower than ``tolerance`` relative; the answer is the bracket's upper end (the lowest speed
    seen to lose contact)."""
    speeds = _check_speeds(bracket, "bracket")
    lo, hi = speeds if len(speeds) == 2 else (None, None)
    if lo is None or not lo < hi:
        raise ValueError(f"bracket must be two increasing speeds (lo, hi) in rpm, got {bracket!r}")
    if not (0.0 < tolerance < 0.5):
        raise ValueError(f"tolerance must be in (0, 0.5) (relative), got {tolerance}")
    options = dict(contact=contact, steps_per_revolution=steps_per_revolution, fallback="transient", multipliers=False)
    evals: List[Dict[str, Any]] = []

    def lost(rpm):
        row = _at_speed(system, rpm, options)
        evals.append(row)
        return row["contact_lost"], row

    lost_lo, row_lo = lost(lo)
    lost_hi, row_hi = lost(hi)
    if lost_lo or not lost_hi:
        raise ValueError(
            f"bracket ({lo:g}, {hi:g}) rpm does not bracket the jump: the contact is "
            f"{'lost' if lost_lo else 'kept'} at {lo:g} rpm (min force {row_lo['min_force_N']:.4g} N) and "
            f"{'lost' if lost_hi else 'kept'} at {hi:g} rpm (min force {row_hi['min_force_N']:.4g} N); "
            "it must be kept at the lower speed and lost at the higher")
    below = row_lo
    while (hi - lo) > tolerance * hi:
        if len(evals) >= max_evaluations:
            raise RuntimeError(f"jump_speed: {max_evaluations} evaluations without narrowing ({lo:g}, {hi:g}) rpm "
                               f"to {tolerance:g} relative")
        mid = 0.5 * (lo + hi)
        is_lost, row = lost(mid)
        if is_lost:
            hi = mid
        else:
            lo, below = mid, row
    return JumpSpeed(rpm=hi, angle_deg=below["min_force_angle_deg"], bracket=(lo, hi),
                     min_force_below_N=below["min_force_N"], evaluations=evals)


@dataclass(frozen=True)
class SpringSize:
    """A spring that keeps ``margin_N`` of contact force up to ``rpm``: its ``rate`` (N/m) and the
    smallest ``preload`` (N, at the follower's lowest position) that does it, with the resulting
    minimum force and where it occurs, and the spring's largest force over the revolution (N)."""

    rate: float
    preload: float
    min_force_N: float
    min_force_angle_deg: float
    max_spring_force_N: float
    evaluations: int

    def __repr__(self) -> str:
        return (f"SpringSize(rate={g(self.rate)}, preload={g(self.preload)}, min_force_N={g(self.min_force_N, 4)}, "
                f"min_force_angle_deg={g(self.min_force_angle_deg, 4)}, max_spring_force_N={g(self.max_spring_force_N)}, "
                f"evaluations={self.evaluations})")


def size_spring(build: Callable[[float, float], Any], rpm: float, margin: float, rates: Sequence[float], *,
                contact: Optional[str] = None, preload_guess: float = 100.0,
                steps_per_revolution: int = STUDY_STEPS_PER_REVOLUTION, tolerance: float = 1e-3,
                max_evaluations: int = 30) -> List[SpringSize]:
    """For each spring ``rate`` (N/m), the smallest preload (N) whose periodic response at ``rpm``
    keeps at least ``margin`` N of contact force all round (secant steps on the preload: the minimum
    force is nearly affine in it). ``build(rate, preload)`` returns the mechanism (at any speed; it is
    run at ``rpm``). The spring's largest force is preload + rate x the largest lift (the program's).
    Raises ValueError for a margin < 0 or rates <= 0, RuntimeError when no preload up to 1e6 N does."""
    if not (math.isfinite(margin) and margin >= 0.0):
        raise ValueError(f"margin must be a finite force >= 0 N, got {margin}")
    rates = [float(k) for k in rates]
    if not rates or any(not (math.isfinite(k) and k > 0) for k in rates):
        raise ValueError(f"rates must be finite spring rates > 0 N/m, got {rates}")
    if not (math.isfinite(preload_guess) and preload_guess > 0):
        raise ValueError(f"preload_guess must be a finite force > 0 N, got {preload_guess}")
    rpm = _check_speeds([rpm])[0]
    out = []
    for k in rates:
        count = 0

        def margin_at(p):
            nonlocal count
            count += 1
            mech = build(k, p).with_camshaft_speed_rpm(rpm)
            row = steady_response(mech, contact=contact, steps_per_revolution=steps_per_revolution,
                                  fallback="transient", multipliers=False)
            # With contact lost the minimum force is 0 whatever the shortfall: extrapolate from the
            # lost fraction so the secant still sees a slope.
            short = row["min_force_N"] - margin - (row["lost_fraction"] * p if row["contact_lost"] else 0.0)
            return short, row, mech

        p0, p1 = preload_guess, 2.0 * preload_guess
        f0, row0, _ = margin_at(p0)
        f1, row1, mech = margin_at(p1)
        while abs(p1 - p0) > tolerance * abs(p1) or f1 < 0.0:
            if count >= max_evaluations:
                raise RuntimeError(f"size_spring: no preload found for rate {k:g} N/m in {max_evaluations} evaluations "
                                   f"(last {p1:g} N, margin shortfall {f1:.4g} N)")
            slope = (f1 - f0) / (p1 - p0) if p1 != p0 else 1.0
            step = -f1 / slope if slope > 0 else p1
            p_next = min(max(p1 + step, 0.5 * p1), 4.0 * p1 + 1.0)
            if p_next > 1e6:
                raise RuntimeError(f"size_spring: rate {k:g} N/m needs a preload above 1e6 N for {margin:g} N at {rpm:g} rpm")
            if f1 >= 0.0 and abs(p_next - p1) <= tolerance * p1:
                break
            p0, f0 = p1, f1
            p1 = p_next
            f1, row1, mech = margin_at(p1)
        lift = max(float(np.max(np.asarray(c["program"].evaluate(np.linspace(0, 2 * math.pi, 4097))["h"])))
                   for c in mech.builder().__getstate__()["contacts"])
        out.append(SpringSize(rate=k, preload=p1, min_force_N=row1["min_force_N"],
                              min_force_angle_deg=row1["min_force_angle_deg"], max_spring_force_N=p1 + k * lift,
                              evaluations=count))
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
            spectrum[:len(r["harmonics"]), j] = r["harmonics"]
    try:
        natural = [float(f) for f in system.modal_analysis(0.0)["frequencies_hz"]]
    except (AttributeError, RuntimeError, ValueError):
        natural = []
    lo, hi = min(r["rpm"] for r in rows), max(r["rpm"] for r in rows)
    resonances = [(k, f, 60.0 * f / k) for f in natural for k in range(1, width + 1) if lo <= 60.0 * f / k <= hi]
    return {"rows": rows, "orders": list(range(1, width + 1)), "spectrum": spectrum, "natural_hz": natural,
            "resonances": resonances}


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

    missing = [k for k in ("rows", "spectrum", "orders", "natural_hz", "resonances")
               if not isinstance(sweep, dict) or k not in sweep]
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
            ax.annotate(f"mode {f:.4g} Hz", (0.0, f), xycoords=("axes fraction", "data"), xytext=(3, -3),
                        textcoords="offset points", ha="left", va="top", fontsize=7, color="tab:red")
        res = sweep["resonances"]
        if res:
            ax.plot([r for _, _, r in res], [f for _, f, _ in res], "|", color="tab:red", ms=6, mew=0.8,
                    label="shaft order × mode crossing")
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
            ax.plot(r, f, "o", mfc="none", mec="tab:red", ms=9, label="labelled resonance" if len(placed) == 1 else None)
            ax.plot(line, k * line / 60.0, color="0.5", lw=0.5)
            ax.annotate(f"{k}×", (r, f), xytext=(0, 7), textcoords="offset points", ha="center", fontsize=7,
                        color="tab:red")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="upper left", fontsize=7)
    ax.set_xlabel("camshaft speed (rpm)")
    ax.set_ylabel("frequency (Hz)")
    ax.set_title("Contact force shaft orders of the periodic response; resonances circled")
    return fig


def plot_margin(rows: Sequence[Dict[str, Any]], jump: Optional[JumpSpeed] = None, ax=None):
    """The margin curve: minimum contact force against speed, contact loss marked, the jump speed
    (if given) as a vertical line inside the axes. Returns the figure."""
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
        ax.axvline(jump.rpm, color="tab:red", ls="--", label=f"jump {jump.rpm:.0f} rpm at {jump.angle_deg:.0f} deg")
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


def compare_programs(build: Callable[[Any], Any], programs: Dict[str, Any], rpm: float, *, contact: Optional[str] = None,
                     steps_per_revolution: int = STUDY_STEPS_PER_REVOLUTION, executor=None,
                     workers: Optional[int] = None, progress: bool = True) -> List[Dict[str, Any]]:
    """Motion laws side by side: ``build(program)`` returns the mechanism for a MotionProgram; one
    steady_response row per named program at ``rpm`` (with ``program``: its name): margin, peak
    accelerations against the rigid follower's, residual vibration in the dwells."""
    if not programs:
        raise ValueError("programs: give at least one named MotionProgram")
    speed = _check_speeds([rpm])[0]
    items = list(programs.items())
    fn = functools.partial(_program_case, build, speed, dict(contact=contact, steps_per_revolution=steps_per_revolution,
                                                             fallback="transient"))
    out = run_cases(fn, items, executor=executor, workers=workers, progress=progress, desc="programs")
    return [o.value if o.ok else {"program": name, "error": o.error} for o, (name, _) in zip(out, items)]


__all__ = ["JumpSpeed", "SpringSize", "compare_programs", "jump_speed", "margin_curve", "plot_margin", "plot_waterfall",
           "size_spring", "speed_sweep"]
