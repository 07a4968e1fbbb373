# SPDX-License-Identifier: BSD-3-Clause
"""What a designer reads off one periodic steady state: contact margin, where it is smallest, contact
loss, accelerations, residual vibration in the dwells and the contact force's harmonics, at a stated
accuracy.

:func:`steady_response` finds the periodic orbit (camfollower.periodic), records its revolution and
measures it; every study (speed sweeps, jump speed, spring sizing, Monte-Carlo) is built on it. The
orbit is found at a step that halves until the contact force and the follower's acceleration change by
less than the accuracy asked (docs/studies.md, "Accuracy of the studies").
"""

from __future__ import annotations

import math
import numbers
import warnings
from typing import Any, Dict, Optional, Sequence

import numpy as np

from . import _core
from .periodic import PeriodicOrbit, periodic_steady_state
from .simulation import METHOD

#: The studies' default accuracy: estimated error of the contact force and of the follower's
#: acceleration over the revolution, relative to their peaks.
STUDY_ACCURACY = 1e-3
#: What the studies' accuracy covers (steady_response's ``accuracy_of``): the contact force and the
#: follower's acceleration (the default), or the contact force alone (margins and jump speeds: what
#: they read). The first is the default.
ACCURACY_OF = ("force_and_acceleration", "force")
#: Steps per revolution the studies start from; halved steps from there until the accuracy holds.
STUDY_STEPS_PER_REVOLUTION = 4096
#: The finest step the accuracy search takes (steps per revolution).
MAX_STUDY_STEPS_PER_REVOLUTION = 1 << 18
#: Contact-force harmonics (shaft orders) kept per speed.
HARMONICS = 64
#: The schemes are second order at least: halving the step divides the error by 4 or more, so the
#: finer of two solutions is off by at most about their difference / (2^2 - 1).
_RICHARDSON = 3.0
#: Fox-Goodwin (Newmark gamma = 1/2, beta = 1/12) is stable below dt = sqrt(6) / omega_max; the studies
#: keep half of that, for contacts that stiffen under load.
_FOX_GOODWIN_MARGIN = 0.5


#: The label of the studies' scheme within Fox-Goodwin's stability margin (study_scheme).
MATCHED_FOX_GOODWIN = "fox_goodwin_matched"


def matched_beta(omega_dt: float) -> float:
    """Newmark's beta (gamma = 1/2) whose discrete undamped oscillation at omega dt has the exact
    period: cos(omega dt) = 1 - (omega dt)^2 / (2 (1 + beta (omega dt)^2)). It is 1/12 + (omega dt)^2
    / 240 + O((omega dt)^4): Fox-Goodwin's beta plus a term of second order in the step, so every
    other mode keeps Fox-Goodwin's fourth-order period error."""
    w2 = omega_dt * omega_dt
    if w2 < 1e-4:  # the closed form loses digits to cancellation: its series
        return 1.0 / 12.0 + w2 / 240.0 + w2 * w2 / 6048.0
    return (w2 / (2.0 * (1.0 - math.cos(omega_dt))) - 1.0) / w2


_AVERAGE_ACCELERATION = {"name": METHOD.newmark, "method": METHOD.newmark, "gamma": 0.5, "beta": 0.25}


def study_scheme(system, steps: int) -> Dict[str, Any]:
    """The time-stepping scheme of the studies at ``steps`` per revolution, as ``name`` (the label the
    rows show), ``method``, ``gamma`` and ``beta`` (scheme_settings() gives the solver settings).

    Within half of Fox-Goodwin's stability limit sqrt(6) / omega_max for the system's highest mode (at
    cam angle 0): Fox-Goodwin **period-matched** to that mode (``fox_goodwin_matched``: Newmark with
    gamma = 1/2 and beta = matched_beta(omega_max dt), slightly above 1/12). Fox-Goodwin's fourth-order
    phase keeps the lightly damped fast modes that ring through a whole revolution in phase, where
    the average-acceleration rule's period error would need ~50x the steps; matching the highest
    mode's period removes the largest of the phase errors that remain (``matched_hz``). Beyond the
    margin, or beyond the processed velocity's limit with the model's damping (Mechanism.step_limit),
    Newmark's average acceleration (unconditionally stable). A model large enough for the
    sparse backend (linear_solver 'auto') gets average acceleration: that backend does not process
    the velocity, and the trapezoidal one is second order through the dampers."""
    average = dict(_AVERAGE_ACCELERATION)
    if len(getattr(system, "dof_names", ())) >= _core.SPARSE_BACKEND_THRESHOLD:
        return average
    try:
        omega_max = 2.0 * math.pi * float(np.max(system.modal_analysis(0.0)["frequencies_hz"]))
    except (AttributeError, RuntimeError, ValueError):
        omega_max = math.inf
    dt = system.period / steps
    omega_dt = dt * omega_max
    if omega_dt <= _FOX_GOODWIN_MARGIN * math.sqrt(6.0) and _damping_allows(system, dt, matched_beta(omega_dt)):
        return {
            "name": MATCHED_FOX_GOODWIN,
            "method": METHOD.newmark,
            "gamma": 0.5,
            "beta": matched_beta(omega_dt),
            "matched_hz": omega_max / (2.0 * math.pi),
        }
    return average


def _damping_allows(system, dt: float, beta: float) -> bool:
    """The processed velocity of the matched scheme is stable at dt with the system's damping
    (Mechanism.step_limit; a heavily damped mode, such as a shaft's stiffness-proportional damping,
    lowers the limit far below sqrt(6) / omega_max)."""
    step_limit = getattr(system, "step_limit", None)
    return step_limit is None or dt <= step_limit(beta)["step"]


def scheme_at(system, steps: int, name: str) -> Dict[str, Any]:
    """The studies' scheme ``name`` (a row's ``scheme``) at ``steps`` per revolution, for a finer orbit
    of the same family: the period-matched Fox-Goodwin's beta depends on the step, average
    acceleration's does not."""
    return study_scheme(system, steps) if name == MATCHED_FOX_GOODWIN else dict(_AVERAGE_ACCELERATION)


def scheme_settings(scheme: Dict[str, Any]) -> Dict[str, Any]:
    """The solver settings (method, gamma, beta) of a study_scheme()."""
    return {"method": scheme["method"], "gamma": scheme["gamma"], "beta": scheme["beta"]}


def _fox_goodwin_steps(system, steps: int, finest: int) -> int:
    """The first of steps, 2 steps, 4 steps, ... at which Fox-Goodwin is within its margin (else steps)."""
    n = steps
    while n <= finest:
        if study_scheme(system, n)["name"] == MATCHED_FOX_GOODWIN:
            return n
        n *= 2
    return steps


def contact_of(system, contact: Optional[str]) -> Dict[str, Any]:
    """The named contact's (default: the first) program, follower DOF, name, phase and whether it is
    grooved (form-closed)."""
    names = list(getattr(system, "contact_names", []))
    if not names:
        raise ValueError(f"{type(system).__name__} has no cam contact to study (build a Mechanism with add_contact)")
    name = names[0] if contact is None else contact
    if name not in names:
        raise ValueError(f"contact: unknown contact {name!r}; the mechanism's contacts are {names}")
    for c in system.builder().contacts:
        if c["name"] == name:
            return {
                "name": name,
                "program": c["program"],
                "dof": c["follower_dof"],
                "phase": float(c["phase"]),
                "grooved": c.get("groove") is not None,
            }
    raise ValueError(f"contact {name!r} not found in the mechanism's description")  # pragma: no cover


def _quasi_static(system, dof: str, theta: np.ndarray) -> np.ndarray:
    """The DOF's quasi-static position at the shaft angles `theta`: the mechanism's static equilibrium
    (springs, preloads, loads against the cam as it is: eccentricity and profile errors included) on a
    0.5 deg grid, interpolated periodically (Mechanism.quasi_static_path, as the lift synthesis's). A
    dwell's residual vibration is measured from it, so a defect's own motion of the follower (an
    eccentric cam lifts it once per revolution) is not counted as vibration."""
    names = list(system.dof_names)
    if dof not in names:
        return np.zeros_like(theta)
    try:
        return np.asarray(system.quasi_static_path(dof, np.asarray(theta, dtype=float)))
    except (RuntimeError, ValueError) as e:  # no static equilibrium somewhere (a follower not held on)
        warnings.warn(f"dwell residual of {dof!r} measured as the raw peak-to-peak: {e}", RuntimeWarning, stacklevel=3)
        return np.zeros_like(theta)


def _dwells(program):
    for seg in program.segments:
        if seg.h_end == seg.h_start and seg.theta_end > seg.theta_start:
            yield seg


def check_accuracy(accuracy, name: str = "accuracy") -> float:
    """An accuracy (relative error of force and acceleration) the studies can reach: in [1e-6, 0.1]."""
    if isinstance(accuracy, bool) or not isinstance(accuracy, numbers.Real) or not 1e-6 <= float(accuracy) <= 0.1:
        raise ValueError(
            f"{name} must be a relative error in [1e-06, 0.1] of the peak contact force and follower "
            f"acceleration (e.g. 1e-3), got {accuracy!r}"
        )
    return float(accuracy)


def check_accuracy_of(accuracy_of, name: str = "accuracy_of") -> str:
    """What a study's accuracy covers: one of ACCURACY_OF."""
    if accuracy_of not in ACCURACY_OF:
        raise ValueError(
            f"{name} must be {' or '.join(repr(a) for a in ACCURACY_OF)} (the channels the accuracy estimate "
            f"covers), got {accuracy_of!r}"
        )
    return str(accuracy_of)


def _check_steps(steps, name: str) -> int:
    if isinstance(steps, bool) or not isinstance(steps, numbers.Integral) or not 64 <= steps <= 1 << 22:
        raise ValueError(f"{name} must be an integer in [64, 4194304], got {steps!r}")
    return int(steps)


def _measured(system, orbit: PeriodicOrbit, name: str, dof: str):
    """(contact force, follower acceleration, the recording) over one revolution: rows 1..N (row 0
    repeats row N)."""
    r = orbit.record(system)
    return np.asarray(r[f"{name}.force"])[1:], np.asarray(r[f"a.{dof}"])[1:], r


def _change(fine: np.ndarray, coarse: np.ndarray) -> float:
    """Largest change between two recordings of a channel on the coarse grid, relative to its peak."""
    peak = float(np.max(np.abs(fine)))
    if peak == 0.0:
        return 0.0
    return float(np.max(np.abs(fine[1::2] - coarse))) / peak


def steady_response(
    system,
    *,
    contact: Optional[str] = None,
    accuracy: Optional[float] = None,
    steps_per_revolution: Optional[int] = None,
    guess: Optional[PeriodicOrbit] = None,
    multipliers: bool = True,
    fallback: Optional[str] = None,
    tolerance: float = 1e-9,
    harmonics: int = HARMONICS,
    channels: Sequence[str] = (),
    keep_orbit: bool = False,
    max_steps_per_revolution: int = MAX_STUDY_STEPS_PER_REVOLUTION,
    stop_at_loss: bool = False,
    accuracy_of: str = ACCURACY_OF[0],
) -> Dict[str, Any]:
    """The periodic steady state of ``system`` at its own camshaft speed, measured on ``contact``.

    **Accuracy.** The orbit is found with the studies' scheme (study_scheme: period-matched
    Fox-Goodwin where it is stable with margin, else average acceleration) at
    ``steps_per_revolution`` (default 4096, or the first halving within Fox-Goodwin's margin) and
    again at half the step, and so on, until the contact force and the follower's acceleration of
    the finer orbit are within ``accuracy`` (default 1e-3) of their peaks: the estimate
    is the largest change between the last two orbits divided by 3 (the method is second order). Each
    finer orbit starts from the coarser one. The row says what it reached: ``accuracy`` (the estimate),
    ``accuracy_target``, ``accuracy_reached`` (False when ``max_steps_per_revolution`` came first: the
    row is then the finest orbit computed) and ``steps_per_revolution`` (of the orbit reported).
    ``steps_per_revolution`` alone (no ``accuracy``): that step, its accuracy estimated from an orbit at
    twice the step. ``accuracy_of="force"`` makes the estimate (and so the search) cover the contact
    force alone: a margin curve or a jump search reads nothing else, and the follower's acceleration,
    whose fast ringing needs the finer steps, is then only as accurate as the step leaves it (the row
    says ``accuracy_of``).

    Returns a flat dict (one table row): ``rpm``; the orbit's ``converged``, ``method``, ``revolutions``
    and ``steps`` (the cost: revolutions and time steps of every orbit computed), ``iterations``,
    ``spectral_radius`` (nan without a monodromy at the orbit: ``multipliers`` False),
    ``instability``; ``min_force_N`` and the cam angle ``min_force_angle_deg`` where it occurs (the
    margin against contact loss, and where the follower would leave first), ``max_force_N``,
    ``force_error_N`` (the accuracy estimate in N), ``contact_lost`` (any instant without contact),
    ``lost_fraction`` of the revolution and ``first_loss_angle_deg``; ``max_abs_acceleration`` of the
    follower DOF and the rigid follower's ``rigid_max_abs_acceleration`` (m/s^2 or rad/s^2);
    ``dwell_residual`` (the residual vibration: the largest peak-to-peak over a dwell of the follower
    displacement less its quasi-static path, the static equilibrium on the cam as it is, so that an
    eccentric cam's or a profile error's own lift is not counted; m or rad) with
    ``dwell_residual_at_deg`` (the dwell's start, in the contact's cam angle) and per dwell (``dwells``:
    start, end, that peak-to-peak and the largest |acceleration|); ``harmonics``: contact-force
    amplitude (N) of shaft orders 1..``harmonics`` (a list). ``channels``: any recorded channels of the
    result (``"q.slide"``, ``"a.slide"``, ``"spring.force"``, ...) measured the same way, as
    ``row["channels"][name]``: ``min``, ``min_angle_deg``, ``max``, ``dwell_residual`` (largest
    peak-to-peak over a dwell; a displacement ``q.<dof>`` less its quasi-static path, as the
    follower's) and ``dwell_residual_at_deg``. ``keep_orbit`` adds the PeriodicOrbit
    as ``orbit``. ``stop_at_loss``: end the search at the first step whose response loses contact
    without settling to a periodic state, after at most 12 shooting iterations and 60 transient
    revolutions (a jump scan only needs to know that contact is lost).
    """
    if accuracy is None:
        target = STUDY_ACCURACY if steps_per_revolution is None else None
    else:
        target = check_accuracy(accuracy)
    start = _check_steps(
        STUDY_STEPS_PER_REVOLUTION if steps_per_revolution is None else steps_per_revolution, "steps_per_revolution"
    )
    finest = _check_steps(max_steps_per_revolution, "max_steps_per_revolution")
    if finest < start:
        raise ValueError(f"max_steps_per_revolution ({finest}) must be >= steps_per_revolution ({start})")
    if isinstance(channels, str) or not all(isinstance(c, str) for c in channels):
        raise ValueError(f"channels must be a list of channel names, got {channels!r}")
    with_acceleration = check_accuracy_of(accuracy_of) == "force_and_acceleration"
    c = contact_of(system, contact)
    period = system.period
    name, dof = c["name"], c["dof"]
    cost = {"revolutions": 0.0, "steps": 0}
    # Knowing that contact is lost takes less search than the periodic state itself.
    search = dict(max_shooting_iterations=12, transient_max_revolutions=60) if stop_at_loss else {}
    if target is not None:
        start = _fox_goodwin_steps(system, start, finest)
    scheme = study_scheme(system, start if target is not None else start // 2)

    def orbit_at(steps: int, seed: Optional[PeriodicOrbit], with_multipliers: bool) -> PeriodicOrbit:
        if seed is not None and not seed.converged and seed is not guess:
            # A coarser orbit that never settled (contact loss, or a transient that diverged at the
            # coarse step) is no start for a finer one: start from rest, as without a seed.
            seed = guess
        o = periodic_steady_state(
            system,
            time_step=period / steps,
            guess=seed,
            multipliers=with_multipliers,
            fallback=fallback,
            tolerance=tolerance,
            warmup_revolutions=0 if seed else 1,
            **scheme_settings(scheme_at(system, steps, scheme["name"])),
            **search,
        )
        cost["revolutions"] += o.revolutions + 1.0  # + the recorded revolution
        cost["steps"] += int(round((o.revolutions + 1.0) * steps))
        return o

    if target is None:  # a fixed step: its accuracy from the orbit at twice the step
        coarse_steps, steps = start // 2, start
        if coarse_steps * 2 != start:
            raise ValueError(f"steps_per_revolution must be even to estimate its accuracy, got {start}")
        coarse = orbit_at(coarse_steps, guess, False)
        orbit = orbit_at(steps, coarse, multipliers)
    else:
        steps = start
        coarse = None
        orbit = orbit_at(steps, guess, False)
    force, acc, rec = _measured(system, orbit, name, dof)
    # The coarser orbit's force and acceleration (each orbit is recorded once).
    coarse_measured = _measured(system, coarse, name, dof)[:2] if coarse is not None else None
    estimate, previous = math.inf, math.inf
    stalls = 0  # refinements in a row whose change did not halve
    while True:
        if coarse is not None:
            f_c, a_c = coarse_measured
            change = _change(force, f_c)
            if with_acceleration:
                change = max(change, _change(acc, a_c))
            previous, estimate = estimate, change / _RICHARDSON
        if target is None or estimate <= target or 2 * steps > finest:
            break
        if stop_at_loss and not orbit.converged and float(np.min(force)) <= 0.0:
            break
        # Refining no longer pays: the change did not halve twice running between converged orbits
        # (impacts: once is not enough, a smooth response can stall for one halving before its order
        # shows: the paper preset from rest at 600 rpm, 2.7e-3 then 2.0e-3 then 1.9e-4), or the
        # transient route settles no better at a finer step (no periodic response: chatter).
        settled = orbit.converged and (coarse is None or coarse.converged)
        stalls = stalls + 1 if settled and estimate > 0.5 * previous else 0
        if stalls >= 2:
            break
        if (
            not orbit.converged
            and coarse is not None
            and not coarse.converged
            and not orbit.mismatch <= 0.25 * coarse.mismatch
        ):
            break
        coarse, coarse_measured, steps = orbit, (force, acc), 2 * steps
        orbit = orbit_at(steps, coarse, False)
        force, acc, rec = _measured(system, orbit, name, dof)
    if multipliers and not orbit.monodromy_at_orbit and orbit.method == "shooting":
        orbit = orbit_at(steps, orbit, True)  # the multipliers of the orbit reported
    reached = target is None or estimate <= target
    return _row(
        system,
        c,
        orbit,
        rec,
        force,
        acc,
        harmonics,
        channels,
        keep_orbit,
        cost,
        {
            "accuracy": estimate,
            "accuracy_target": target if target is not None else math.nan,
            "accuracy_reached": reached,
            "accuracy_of": accuracy_of,
            "steps_per_revolution": steps,
            "scheme": scheme["name"],
        },
    )


def _row(system, c, orbit, r, force, a, harmonics, channels, keep_orbit, cost, accuracy) -> Dict[str, Any]:
    name = c["name"]
    theta = np.mod(np.asarray(r["theta"])[1:], 2 * math.pi)
    cam_theta = np.mod(theta + c["phase"], 2 * math.pi)  # the contact's own cam angle: its dwells
    touching = np.asarray(r[f"{name}.in_contact"])[1:] > 0.5
    q = np.asarray(r[f"q.{c['dof']}"])[1:]
    k = int(np.argmin(force))
    lost = ~touching
    row: Dict[str, Any] = {
        "rpm": float(system.camshaft_speed_rpm),
        "converged": orbit.converged,
        "method": orbit.method,
        "revolutions": cost["revolutions"],
        "steps": cost["steps"],
        "iterations": orbit.iterations,
        "spectral_radius": orbit.spectral_radius if orbit.monodromy_at_orbit else math.nan,
        "instability": orbit.instability() if orbit.monodromy_at_orbit else "unknown",
        "min_force_N": float(force[k]),
        "min_force_angle_deg": math.degrees(float(theta[k])),
        "max_force_N": float(force.max()),
        "force_error_N": accuracy["accuracy"] * float(np.max(np.abs(force))),
        "contact_lost": bool(lost.any()),
        "lost_fraction": float(lost.mean()),
        "first_loss_angle_deg": math.degrees(float(theta[np.argmax(lost)])) if lost.any() else math.nan,
        "max_abs_acceleration": float(np.abs(a).max()),
        "rigid_max_abs_acceleration": float(
            system.omega**2 * np.abs(np.asarray(c["program"].evaluate(np.linspace(0, 2 * math.pi, 4097))["d2h"])).max()
        ),
        **accuracy,
    }
    dwells = []
    vibration = q - _quasi_static(system, c["dof"], theta) if any(_dwells(c["program"])) else q
    for seg in _dwells(c["program"]):
        inside = (cam_theta >= seg.theta_start) & (cam_theta < seg.theta_end)
        if inside.sum() > 1:
            dwells.append(
                {
                    "start_deg": math.degrees(seg.theta_start),
                    "end_deg": math.degrees(seg.theta_end),
                    "peak_to_peak": float(np.ptp(vibration[inside])),
                    "max_abs_acceleration": float(np.abs(a[inside]).max()),
                }
            )
    worst = max(dwells, key=lambda d: d["peak_to_peak"], default=None)
    row["dwell_residual"] = worst["peak_to_peak"] if worst else 0.0
    row["dwell_residual_at_deg"] = worst["start_deg"] if worst else math.nan
    row["dwells"] = dwells
    if channels:
        row["channels"] = {ch: _channel_measures(system, r, ch, theta, cam_theta, c["program"]) for ch in channels}
    spectrum = np.abs(np.fft.rfft(force)) * 2.0 / force.size
    row["harmonics"] = [float(x) for x in spectrum[1 : harmonics + 1]]
    if keep_orbit:
        row["orbit"] = orbit
    return row


def _channel_measures(system, r, channel: str, theta: np.ndarray, cam_theta: np.ndarray, program) -> Dict[str, Any]:
    try:
        x = np.asarray(r[channel], dtype=float)
    except KeyError:
        raise ValueError(f"channels: no channel {channel!r} in the result; recorded: {', '.join(r.channels)}") from None
    if x.ndim != 1:
        raise ValueError(f"channels: {channel!r} is not a single channel (give e.g. 'q.<dof>')")
    x = x[1:]
    k = int(np.argmin(x))
    worst, at = 0.0, math.nan
    # A displacement's residual vibration is measured from its quasi-static path (as the follower's).
    moving = x - _quasi_static(system, channel[2:], theta) if channel.startswith("q.") and any(_dwells(program)) else x
    for seg in _dwells(program):
        inside = (cam_theta >= seg.theta_start) & (cam_theta < seg.theta_end)
        if inside.sum() > 1 and float(np.ptp(moving[inside])) > worst:
            worst, at = float(np.ptp(moving[inside])), math.degrees(seg.theta_start)
    return {
        "min": float(x[k]),
        "min_angle_deg": math.degrees(float(theta[k])),
        "max": float(x.max()),
        "dwell_residual": worst,
        "dwell_residual_at_deg": at,
    }


__all__ = [
    "ACCURACY_OF",
    "HARMONICS",
    "MATCHED_FOX_GOODWIN",
    "MAX_STUDY_STEPS_PER_REVOLUTION",
    "STUDY_ACCURACY",
    "STUDY_STEPS_PER_REVOLUTION",
    "check_accuracy",
    "check_accuracy_of",
    "contact_of",
    "matched_beta",
    "scheme_at",
    "scheme_settings",
    "steady_response",
    "study_scheme",
]
