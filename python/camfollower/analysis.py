# SPDX-License-Identifier: BSD-3-Clause
"""Post-processing of simulation results: spectra, sidebands, per-phase statistics, contact loss.

All inputs and outputs are NumPy arrays in SI units. A result is the dict returned by
:func:`camfollower.simulate`.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from . import _core

__all__ = [
    "Spectrum",
    "spectrum",
    "last_revolutions",
    "sidebands",
    "theoretical_follower_acceleration",
    "phase_statistics",
    "contact_loss_intervals",
    "find_peaks",
    "groove_statistics",
]


def _series(values, name: str, min_size: int = 1) -> np.ndarray:
    """A 1-D array of finite floats of at least `min_size` samples, or ValueError naming it."""
    try:
        x = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a 1-D array of numbers, got {type(values).__name__}") from None
    if x.ndim != 1 or x.size < min_size:
        raise ValueError(f"{name} must be a 1-D array of at least {min_size} samples, got shape {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError(f"{name} must be finite (it holds NaN or inf)")
    return x


def _real(value, name: str, unit: str, *, positive: bool = False, infinite: bool = False) -> float:
    """A real number (not a bool or str), finite unless `infinite`, > 0 if `positive`."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{name} must be a number ({unit}), got {type(value).__name__}")
    x = float(value)
    if math.isnan(x) or (not infinite and math.isinf(x)) or (positive and not x > 0):
        raise ValueError(
            f"{name} must be {'finite and ' if not infinite else ''}{'> 0 ' if positive else ''}({unit}), got {value!r}"
        )
    return x


def _count(value, name: str, minimum: int) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum:
        raise ValueError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


@dataclass(frozen=True)
class Spectrum:
    frequency: np.ndarray  # Hz, equally spaced, increasing
    amplitude: np.ndarray  # single-sided amplitude, same unit as the signal

    def __post_init__(self):
        f = _series(self.frequency, "frequency", 2)
        a = _series(self.amplitude, "amplitude", 2)
        if f.shape != a.shape:
            raise ValueError(f"frequency and amplitude must have the same length, got {f.size} and {a.size}")
        if not np.all(np.diff(f) > 0):
            raise ValueError("frequency must be increasing")
        object.__setattr__(self, "frequency", f)
        object.__setattr__(self, "amplitude", a)

    @property
    def resolution(self) -> float:
        return float(self.frequency[1] - self.frequency[0])

    def at(self, f: float) -> float:
        """Amplitude of the bin nearest to f (Hz); ValueError outside the spectrum's range."""
        f = _real(f, "f", "Hz")
        lo, hi = self.frequency[0], self.frequency[-1]
        if not (lo - 0.5 * self.resolution <= f <= hi + 0.5 * self.resolution):
            raise ValueError(f"frequency {f} Hz is outside this spectrum's range [{lo}, {hi}] Hz")
        return float(self.amplitude[int(round((f - lo) / self.resolution))])

    def band(self, lo: float, hi: float) -> "Spectrum":
        """The bins in [lo, hi] Hz (at least two)."""
        lo, hi = _real(lo, "lo", "Hz", infinite=True), _real(hi, "hi", "Hz", infinite=True)
        keep = (self.frequency >= lo) & (self.frequency <= hi)
        if np.count_nonzero(keep) < 2:
            raise ValueError(
                f"the band [{lo}, {hi}] Hz holds fewer than two bins of this spectrum "
                f"({self.frequency[0]} to {self.frequency[-1]} Hz)"
            )
        return Spectrum(self.frequency[keep], self.amplitude[keep])


def spectrum(signal, sample_rate: float, window: str = "hann", detrend: bool = True) -> Spectrum:
    """Single-sided amplitude spectrum: a sinusoid of amplitude A at a bin frequency reads A.

    Feed whole revolutions (see :func:`last_revolutions`) so that the resolution
    sample_rate / len(signal) divides the shaft frequency and its harmonics fall on bins.
    window: "hann" (amplitude-corrected) or "rect".
    """
    x = _series(signal, "signal", 8)
    sample_rate = _real(sample_rate, "sample_rate", "Hz", positive=True)
    if detrend:
        x = x - x.mean()
    if window == "hann":
        w = np.hanning(x.size + 1)[:-1]  # periodic Hann: exact for whole periods
    elif window == "rect":
        w = np.ones(x.size)
    else:
        raise ValueError(f"window must be 'hann' or 'rect', got {window!r}")
    with np.errstate(over="ignore", invalid="ignore"):
        amplitude = np.abs(np.fft.rfft(x * w)) * 2.0 / w.sum()
    if not np.all(np.isfinite(amplitude)):
        raise ValueError(f"signal: values up to {np.max(np.abs(x)):.3g} overflow the spectrum; scale the signal")
    amplitude[0] /= 2.0  # DC and (even length) Nyquist have no mirror image
    if x.size % 2 == 0:
        amplitude[-1] /= 2.0
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        frequency = np.fft.rfftfreq(x.size, d=1.0 / sample_rate)
    if not (np.all(np.isfinite(frequency)) and np.all(np.diff(frequency) > 0)):
        raise ValueError(
            f"sample_rate = {sample_rate} Hz gives no usable frequency axis for {x.size} samples "
            "(the bin spacing overflows or underflows)"
        )
    return Spectrum(frequency, amplitude)


def last_revolutions(result: dict, period: float, revolutions: int) -> slice:
    """Slice of the rows covering the last `revolutions` whole revolutions of a result."""
    t = _series(result["t"], "result['t']", 2)
    period = _real(period, "period", "s", positive=True)
    revolutions = _count(revolutions, "revolutions", 1)
    dt = float(t[1] - t[0])
    if not dt > 0:
        raise ValueError(f"result['t'] must increase, got t[0] = {t[0]} s, t[1] = {t[1]} s")
    per_rev = period / dt
    if per_rev > t.size:
        raise ValueError(f"one period ({period} s) is longer than the whole result ({t.size} rows of {dt} s)")
    if abs(per_rev - round(per_rev)) > 1e-6 * per_rev:
        raise ValueError(
            f"the sampling interval {dt} s does not divide the period {period} s: "
            "use time_step = period / integer (and a decimation that divides it)"
        )
    n = int(round(per_rev)) * revolutions
    if n > t.size - 1:
        raise ValueError(f"revolutions={revolutions} needs {n} rows, the result has {t.size - 1} after t = 0")
    return slice(t.size - n, t.size)


def find_peaks(spec: Spectrum, count: int = 5, lo: float = 0.0, hi: float = math.inf) -> list[tuple[float, float]]:
    """The `count` largest local maxima (frequency, amplitude) in [lo, hi] Hz, largest first."""
    count = _count(count, "count", 1)
    lo, hi = _real(lo, "lo", "Hz", infinite=True), _real(hi, "hi", "Hz", infinite=True)
    a = spec.amplitude
    idx = np.flatnonzero((a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:])) + 1
    idx = idx[(spec.frequency[idx] >= lo) & (spec.frequency[idx] <= hi)]
    idx = idx[np.argsort(a[idx])[::-1][:count]]
    return [(float(spec.frequency[i]), float(a[i])) for i in idx]


def sidebands(spec: Spectrum, carrier: float, spacing: float, orders: int = 3) -> dict:
    """Amplitudes at carrier + k * spacing for k = -orders..orders and the modulation ratio
    (root-sum-square of the sidebands over the carrier)."""
    carrier = _real(carrier, "carrier", "Hz")
    spacing = _real(spacing, "spacing", "Hz", positive=True)
    orders = _count(orders, "orders", 1)
    levels = {k: spec.at(carrier + k * spacing) for k in range(-orders, orders + 1)}
    side = math.sqrt(sum(v * v for k, v in levels.items() if k != 0))
    return {
        "carrier_hz": carrier,
        "spacing_hz": spacing,
        "levels": levels,
        "modulation_ratio": side / levels[0] if levels[0] > 0 else math.inf,
    }


def theoretical_follower_acceleration(model, theta, contact: str | None = None) -> np.ndarray:
    """Rigid-follower acceleration omega^2 d2h/dtheta2 at cam angles theta (constant speed), of the cam
    of ``contact`` on a Mechanism (the name may be left out when it has one contact); m/s^2, or rad/s^2
    for an oscillating follower."""
    program, omega = _program_and_speed(model, contact)
    theta = np.asarray(theta, dtype=float)
    if not np.all(np.isfinite(theta)):
        raise ValueError("theta must be finite (rad)")
    return omega**2 * np.asarray(program.evaluate(np.asarray(theta))["d2h"])


def _program_and_speed(model, contact: str | None):
    """The motion program of a Mechanism's contact and the camshaft speed (rad/s)."""
    if isinstance(model, _core.Mechanism):
        contacts = model.builder().contacts
        names = [c["name"] for c in contacts]
        if contact is None:
            if len(contacts) != 1:
                raise ValueError(f"contact: name one of the mechanism's contacts {names}")
            return contacts[0]["program"], model.omega
        for c in contacts:
            if c["name"] == contact:
                return c["program"], model.omega
        raise ValueError(f"contact: no contact named {contact!r}; the mechanism has {names}")
    raise ValueError(f"model must be a Mechanism, got {type(model).__name__}")


def phase_statistics(model, theta, signal, contact: str | None = None) -> list[dict]:
    """Peak |x| and RMS of a signal over each segment of the motion program (dwell, rise, ...), with
    the number of samples in it. ``model``: a Mechanism (with ``contact``, the cam whose segments are
    meant; it may be left out when the mechanism has one contact) or the MotionProgram itself. A
    segment the samples do not reach is refused (ValueError), not reported as NaN: sample a whole
    revolution."""
    program = model if isinstance(model, _core.MotionProgram) else _program_and_speed(model, contact)[0]
    theta = np.mod(_series(theta, "theta"), 2 * math.pi)
    x = _series(signal, "signal")
    if x.shape != theta.shape:
        raise ValueError(f"theta and signal must have the same length, got {theta.size} and {x.size}")
    stats = []
    for seg in program.segments:
        inside = (theta >= seg.theta_start) & (theta < seg.theta_end)
        kind = "dwell" if seg.h_end == seg.h_start else ("rise" if seg.h_end > seg.h_start else "return")
        name = f"{kind} {math.degrees(seg.theta_start):.0f}-{math.degrees(seg.theta_end):.0f} deg"
        if not inside.any():
            raise ValueError(f"no sample of theta falls in the {name} phase: give at least one revolution")
        peak = float(np.max(np.abs(x[inside])))
        scaled = x[inside] / peak if peak > 0 else x[inside]  # no overflow of x^2 for |x| > 1e154
        stats.append(
            {
                "phase": name,
                "samples": int(np.count_nonzero(inside)),
                "peak": peak,
                "rms": (peak if peak > 0 else 1.0) * float(np.sqrt(np.mean(scaled**2))),
            }
        )
    return stats


def contact_loss_intervals(t, in_contact) -> list[tuple[float, float]]:
    """[start, end) times where in_contact is False, from sampled flags (none for no samples)."""
    t = _series(t, "t", 0)
    flags = np.asarray(in_contact)
    if flags.shape != t.shape:
        raise ValueError(f"t and in_contact must have the same length, got {t.size} and {flags.size}")
    if t.size == 0:
        return []
    lost = ~flags.astype(bool)
    edges = np.diff(lost.astype(np.int8))
    starts = list(np.flatnonzero(edges == 1) + 1)
    ends = list(np.flatnonzero(edges == -1) + 1)
    if lost[0]:
        starts.insert(0, 0)
    if lost[-1]:
        ends.append(t.size - 1)
    return [(float(t[a]), float(t[b])) for a, b in zip(starts, ends)]


def clearance_statistics(result, name: str, period: float) -> dict:
    """What a clearance did over a recorded run, per revolution of ``period`` (s): the free-flight
    time (s, rod touching neither wall), impacts (a free rod meeting a wall, or a jump from one wall
    to the other between two rows), wall changes (arrivals on the other wall than the last one), and
    the peak and mean seat force (N). Counted from the recorded rows of ``<name>.side`` and
    ``<name>.force``: record every step (decimation 1) or short impacts may be missed."""
    period = _real(period, "period", "s", positive=True)
    side = np.asarray(result[f"{name}.side"], dtype=float)
    force = np.asarray(result[f"{name}.force"], dtype=float)
    t = np.asarray(result["t"], dtype=float)
    if t.size < 2:
        raise ValueError(f"clearance '{name}': need at least two recorded rows, got {t.size}")
    dt = float(t[1] - t[0])
    revolutions = (t[-1] - t[0] + dt) / period
    if not revolutions > 0:
        raise ValueError(f"period must be > 0 s, got {period}")
    arrivals = (side[1:] != 0) & (side[1:] != side[:-1])
    seated = side[side != 0]
    wall_changes = int(np.count_nonzero(seated[1:] != seated[:-1])) if seated.size else 0
    return {
        "free_flight_time_per_revolution_s": float(np.count_nonzero(side == 0) * dt / revolutions),
        "impacts_per_revolution": float(np.count_nonzero(arrivals) / revolutions),
        "wall_changes_per_revolution": float(wall_changes / revolutions),
        "peak_seat_force_N": float(force.max()),
        "mean_seat_force_N": float(force.mean()),
    }


def groove_statistics(result, contact: str, period: float) -> dict:
    """What the roller of a grooved cam did over a run, per revolution of ``period`` (s).

    From the run's located events on ``<contact>.contact`` (inner flank) and ``<contact>.outer_contact``
    (outer flank), exact to the stepper's event location whatever the output interval: ``strikes``, a
    list of ``(time in s, "inner" | "outer", impact velocity in m/s)`` for every flank the roller meets
    after a flight (velocities from the ``<contact>.penetration_rate`` channel interpolated at the event:
    record finely, e.g. every step, for accurate velocities); ``impacts_per_revolution`` (all strikes,
    re-strikes after a bounce included); ``flank_changes_per_revolution`` (strikes on the other flank
    than the one last touched); ``free_flight_time_per_revolution_s`` (touching neither flank);
    ``max_impact_velocity_m_s``; ``peak_inner_force_N`` and ``peak_outer_force_N``. Over the recorded
    rows' span only (a run recorded from ``record_from`` is counted from there)."""
    period = _real(period, "period", "s", positive=True)
    channels = result.channels
    for suffix in ("in_contact", "outer_in_contact", "penetration_rate"):
        if f"{contact}.{suffix}" not in channels:
            grooved = sorted({c.rsplit(".", 1)[0] for c in channels if c.endswith(".outer_in_contact")})
            raise ValueError(f"'{contact}' is not a grooved contact of this run; its grooved contacts: {grooved}")
    t = np.asarray(result["t"], dtype=float)
    if t.size < 2:
        raise ValueError(f"groove '{contact}': need at least two recorded rows, got {t.size}")
    rate = np.asarray(result[f"{contact}.penetration_rate"], dtype=float)
    t_end = float(t[-1])
    revolutions = (t_end - float(t[0])) / period  # the run spans [t0, t_end]; the events are instants in it
    touching = {
        "inner": bool(result[f"{contact}.in_contact"][0]),
        "outer": bool(result[f"{contact}.outer_in_contact"][0]),
    }
    flank_of = {f"{contact}.contact": "inner", f"{contact}.outer_contact": "outer"}
    last = "inner" if touching["inner"] else "outer" if touching["outer"] else None
    strikes, changes, free, since = [], 0, 0.0, float(t[0])
    for event in result.events:
        flank = flank_of.get(event.name)
        if flank is None or not t[0] < event.time <= t_end:  # only the recorded span's (record_from)
            continue
        free_before = not (touching["inner"] or touching["outer"])
        if free_before:
            free += event.time - since
        touching[flank] = event.kind == "made"
        if not (touching["inner"] or touching["outer"]):
            since = event.time
        if event.kind != "made":
            continue
        velocity = float(np.interp(event.time, t, rate)) * (1.0 if flank == "inner" else -1.0)
        strikes.append((float(event.time), flank, velocity))
        changes += last is not None and flank != last
        last = flank
    if not (touching["inner"] or touching["outer"]):
        free += t_end - since
    return {
        "strikes": strikes,
        "impacts_per_revolution": len(strikes) / revolutions,
        "flank_changes_per_revolution": changes / revolutions,
        "free_flight_time_per_revolution_s": free / revolutions,
        "max_impact_velocity_m_s": max((v for _, _, v in strikes), default=0.0),
        "peak_inner_force_N": float(np.max(result[f"{contact}.force"])),
        "peak_outer_force_N": float(np.max(result[f"{contact}.outer_force"])),
    }
