# SPDX-License-Identifier: BSD-3-Clause
"""What a designer reads off one periodic steady state: contact margin, where it is smallest, contact
loss, accelerations, residual vibration in the dwells and the contact force's harmonics.

:func:`steady_response` finds the periodic orbit (camfollower.periodic), records its revolution and
measures it; every study (speed sweeps, jump speed, spring sizing, Monte-Carlo) is built on it.
"""

from __future__ import annotations

import math
from typing import Any, Dict, Optional

import numpy as np

from .periodic import PeriodicOrbit, periodic_steady_state

#: Steps per revolution of the studies' default scheme (the time step is period / this).
STUDY_STEPS_PER_REVOLUTION = 4096
#: Contact-force harmonics (shaft orders) kept per speed.
HARMONICS = 64


def contact_of(system, contact: Optional[str]) -> Dict[str, Any]:
    """The named contact's (default: the first) program, follower DOF and name."""
    names = list(getattr(system, "contact_names", []))
    if not names:
        raise ValueError(f"{type(system).__name__} has no cam contact to study (build a Mechanism with add_contact)")
    name = names[0] if contact is None else contact
    if name not in names:
        raise ValueError(f"contact: unknown contact {name!r}; the mechanism's contacts are {names}")
    for c in system.builder().__getstate__()["contacts"]:
        if c["name"] == name:
            return {"name": name, "program": c["program"], "dof": c["follower_dof"]}
    raise ValueError(f"contact {name!r} not found in the mechanism's description")  # pragma: no cover


def _dwells(program):
    for seg in program.segments:
        if seg.h_end == seg.h_start and seg.theta_end > seg.theta_start:
            yield seg


def steady_response(system, *, contact: Optional[str] = None, steps_per_revolution: int = STUDY_STEPS_PER_REVOLUTION,
                    guess: Optional[PeriodicOrbit] = None, multipliers: bool = True, fallback: Optional[str] = None,
                    tolerance: float = 1e-9, harmonics: int = HARMONICS, keep_orbit: bool = False) -> Dict[str, Any]:
    """The periodic steady state of ``system`` at its own camshaft speed, measured on ``contact``.

    Returns a flat dict (one table row): ``rpm``; the orbit's ``converged``, ``method``, ``revolutions``
    (cost), ``iterations``, ``spectral_radius`` (nan without a monodromy at the orbit: ``multipliers``
    False), ``instability``; ``min_force_N`` and the cam angle ``min_force_angle_deg`` where it occurs
    (the margin against contact loss, and where the follower would leave first), ``max_force_N``,
    ``contact_lost`` (any instant without contact), ``lost_fraction`` of the revolution and
    ``first_loss_angle_deg``; ``max_abs_acceleration`` of the follower DOF and the rigid follower's
    ``rigid_max_abs_acceleration`` (m/s^2 or rad/s^2); ``dwell_residual`` (the largest peak-to-peak
    follower displacement over a dwell: the residual vibration, m or rad) with ``dwell_residual_at_deg``
    (the dwell's start) and per dwell (``dwells``: start, end, peak-to-peak displacement and largest
    |acceleration|); ``harmonics``: contact-force amplitude (N) of shaft orders 1..``harmonics``
    (a list). ``keep_orbit`` adds the PeriodicOrbit as ``orbit``.
    """
    if not (isinstance(steps_per_revolution, int) and 64 <= steps_per_revolution <= 1 << 22):
        raise ValueError(f"steps_per_revolution must be an integer in [64, 4194304], got {steps_per_revolution!r}")
    c = contact_of(system, contact)
    period = system.period
    orbit = periodic_steady_state(system, time_step=period / steps_per_revolution, guess=guess, multipliers=multipliers,
                                  fallback=fallback, tolerance=tolerance, warmup_revolutions=0 if guess else 1)
    r = orbit.record(system)
    name, dof = c["name"], c["dof"]
    force = np.asarray(r[f"{name}.force"])[1:]  # one revolution: rows 1..N (row 0 repeats row N)
    theta = np.mod(np.asarray(r["theta"])[1:], 2 * math.pi)
    touching = np.asarray(r[f"{name}.in_contact"])[1:] > 0.5
    q = np.asarray(r[f"q.{dof}"])[1:]
    a = np.asarray(r[f"a.{dof}"])[1:]
    k = int(np.argmin(force))
    lost = ~touching
    row: Dict[str, Any] = {
        "rpm": float(system.camshaft_speed_rpm), "converged": orbit.converged, "method": orbit.method,
        "revolutions": orbit.revolutions, "iterations": orbit.iterations,
        "spectral_radius": orbit.spectral_radius if orbit.monodromy_at_orbit else math.nan,
        "instability": orbit.instability() if orbit.monodromy_at_orbit else "unknown",
        "min_force_N": float(force[k]), "min_force_angle_deg": math.degrees(float(theta[k])),
        "max_force_N": float(force.max()), "contact_lost": bool(lost.any()),
        "lost_fraction": float(lost.mean()),
        "first_loss_angle_deg": math.degrees(float(theta[np.argmax(lost)])) if lost.any() else math.nan,
        "max_abs_acceleration": float(np.abs(a).max()),
        "rigid_max_abs_acceleration": float(system.omega ** 2 * np.abs(
            np.asarray(c["program"].evaluate(np.linspace(0, 2 * math.pi, 4097))["d2h"])).max()),
    }
    dwells = []
    for seg in _dwells(c["program"]):
        inside = (theta >= seg.theta_start) & (theta < seg.theta_end)
        if inside.sum() > 1:
            dwells.append({"start_deg": math.degrees(seg.theta_start), "end_deg": math.degrees(seg.theta_end),
                           "peak_to_peak": float(np.ptp(q[inside])), "max_abs_acceleration": float(np.abs(a[inside]).max())})
    worst = max(dwells, key=lambda d: d["peak_to_peak"], default=None)
    row["dwell_residual"] = worst["peak_to_peak"] if worst else 0.0
    row["dwell_residual_at_deg"] = worst["start_deg"] if worst else math.nan
    row["dwells"] = dwells
    spectrum = np.abs(np.fft.rfft(force)) * 2.0 / force.size
    row["harmonics"] = [float(x) for x in spectrum[1:harmonics + 1]]
    if keep_orbit:
        row["orbit"] = orbit
    return row


__all__ = ["STUDY_STEPS_PER_REVOLUTION", "contact_of", "steady_response"]
