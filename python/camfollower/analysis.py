# SPDX-License-Identifier: BSD-3-Clause
"""Post-processing of simulation results: spectra, sidebands, per-phase statistics, contact loss.

All inputs and outputs are NumPy arrays in SI units. A result is the dict returned by
:func:`camfollower.simulate`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "Spectrum",
    "spectrum",
    "last_revolutions",
    "sidebands",
    "theoretical_follower_acceleration",
    "phase_statistics",
    "contact_loss_intervals",
    "find_peaks",
]


@dataclass(frozen=True)
class Spectrum:
    frequency: np.ndarray  # Hz
    amplitude: np.ndarray  # single-sided amplitude, same unit as the signal

    @property
    def resolution(self) -> float:
        return float(self.frequency[1] - self.frequency[0])

    def at(self, f: float) -> float:
        """Amplitude of the bin nearest to f (Hz); ValueError outside the spectrum's range."""
        lo, hi = self.frequency[0], self.frequency[-1]
        if not (lo - 0.5 * self.resolution <= f <= hi + 0.5 * self.resolution):
            raise ValueError(f"frequency {f} Hz is outside this spectrum's range [{lo}, {hi}] Hz")
        return float(self.amplitude[int(round((f - lo) / self.resolution))])

    def band(self, lo: float, hi: float) -> "Spectrum":
        keep = (self.frequency >= lo) & (self.frequency <= hi)
        return Spectrum(self.frequency[keep], self.amplitude[keep])


def spectrum(signal, sample_rate: float, window: str = "hann", detrend: bool = True) -> Spectrum:
    """Single-sided amplitude spectrum: a sinusoid of amplitude A at a bin frequency reads A.

    Feed whole revolutions (see :func:`last_revolutions`) so that the resolution
    sample_rate / len(signal) divides the shaft frequency and its harmonics fall on bins.
    window: "hann" (amplitude-corrected) or "rect".
    """
    x = np.asarray(signal, dtype=float)
    if x.ndim != 1 or x.size < 8:
        raise ValueError(f"signal must be a 1-D array of at least 8 samples, got shape {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError("signal must be finite")
    if not (math.isfinite(sample_rate) and sample_rate > 0):
        raise ValueError(f"sample_rate must be finite and > 0 (Hz), got {sample_rate}")
    if detrend:
        x = x - x.mean()
    if window == "hann":
        w = np.hanning(x.size + 1)[:-1]  # periodic Hann: exact for whole periods
    elif window == "rect":
        w = np.ones(x.size)
    else:
        raise ValueError(f"window must be 'hann' or 'rect', got {window!r}")
    amplitude = np.abs(np.fft.rfft(x * w)) * 2.0 / w.sum()
    amplitude[0] /= 2.0  # DC and (even length) Nyquist have no mirror image
    if x.size % 2 == 0:
        amplitude[-1] /= 2.0
    frequency = np.fft.rfftfreq(x.size, d=1.0 / sample_rate)
    return Spectrum(frequency, amplitude)


def last_revolutions(result: dict, period: float, revolutions: int) -> slice:
    """Slice of the rows covering the last `revolutions` whole revolutions of a result."""
    t = np.asarray(result["t"])
    dt = float(t[1] - t[0])
    per_rev = period / dt
    if abs(per_rev - round(per_rev)) > 1e-6 * per_rev:
        raise ValueError(
            f"the sampling interval {dt} s does not divide the period {period} s: "
            "use time_step = period / integer (and a decimation that divides it)")
    n = int(round(per_rev)) * revolutions
    if n > t.size - 1:
        raise ValueError(f"revolutions={revolutions} needs {n} rows, the result has {t.size - 1} after t = 0")
    return slice(t.size - n, t.size)


def find_peaks(spec: Spectrum, count: int = 5, lo: float = 0.0, hi: float = math.inf) -> list[tuple[float, float]]:
    """The `count` largest local maxima (frequency, amplitude) in [lo, hi] Hz, largest first."""
    a = spec.amplitude
    idx = np.flatnonzero((a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:])) + 1
    idx = idx[(spec.frequency[idx] >= lo) & (spec.frequency[idx] <= hi)]
    idx = idx[np.argsort(a[idx])[::-1][:count]]
    return [(float(spec.frequency[i]), float(a[i])) for i in idx]


def sidebands(spec: Spectrum, carrier: float, spacing: float, orders: int = 3) -> dict:
    """Amplitudes at carrier + k * spacing for k = -orders..orders and the modulation ratio
    (root-sum-square of the sidebands over the carrier)."""
    if spacing <= 0 or orders < 1:
        raise ValueError("spacing must be > 0 (Hz) and orders >= 1")
    levels = {k: spec.at(carrier + k * spacing) for k in range(-orders, orders + 1)}
    side = math.sqrt(sum(v * v for k, v in levels.items() if k != 0))
    return {"carrier_hz": carrier, "spacing_hz": spacing, "levels": levels,
            "modulation_ratio": side / levels[0] if levels[0] > 0 else math.inf}


def theoretical_follower_acceleration(model, theta) -> np.ndarray:
    """Rigid-follower acceleration omega^2 d2h/dtheta2 at cam angles theta (constant speed)."""
    return model.omega**2 * np.asarray(model.cam.program.evaluate(np.asarray(theta))["d2h"])


def phase_statistics(model, theta, signal) -> list[dict]:
    """Peak |x| and RMS of a signal over each segment of the motion program (dwell, rise, ...)."""
    theta = np.mod(np.asarray(theta), 2 * math.pi)
    x = np.asarray(signal)
    stats = []
    for seg in model.cam.program.segments:
        inside = (theta >= seg.theta_start) & (theta < seg.theta_end)
        kind = "dwell" if seg.h_end == seg.h_start else ("rise" if seg.h_end > seg.h_start else "return")
        name = f"{kind} {math.degrees(seg.theta_start):.0f}-{math.degrees(seg.theta_end):.0f} deg"
        if not inside.any():
            stats.append({"phase": name, "peak": math.nan, "rms": math.nan})
            continue
        stats.append({"phase": name, "peak": float(np.max(np.abs(x[inside]))),
                      "rms": float(np.sqrt(np.mean(x[inside] ** 2)))})
    return stats


def contact_loss_intervals(t, in_contact) -> list[tuple[float, float]]:
    """[start, end) times where in_contact is False, from sampled flags."""
    t = np.asarray(t)
    lost = ~np.asarray(in_contact, dtype=bool)
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
    return {"free_flight_time_per_revolution_s": float(np.count_nonzero(side == 0) * dt / revolutions),
            "impacts_per_revolution": float(np.count_nonzero(arrivals) / revolutions),
            "wall_changes_per_revolution": float(wall_changes / revolutions),
            "peak_seat_force_N": float(force.max()),
            "mean_seat_force_N": float(force.mean())}
