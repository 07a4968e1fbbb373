# SPDX-License-Identifier: BSD-3-Clause
"""A camshaft at several speeds: what each valve, spring, bearing and the drive see.

``camshaft_study(config_or_mechanism, rpm=[...])`` simulates a mechanism with a flexible camshaft
(docs/camshaft.md) at each camshaft speed and reduces every run to per-cam figures:

* lift error: the follower's displacement minus the cam's lift at its nominal angle (omega t +
  phase), less its value on the base circle (the static contact and spring deflection), largest |.|;
* contact force: peak, smallest while lifting (the margin against jump), time without contact;
* shaft twist at the cam: peak-to-peak of cam angle - (omega t + phase);
* valve-spring surge (a spring chain ``add_spring_chain`` from the follower): peak-to-peak of the
  middle coil's departure from the straight line between the spring's ends, and its main frequency;

and per bearing (a pair of springs "<name>.y", "<name>.z" to ground) its largest radial load, and for
the drive (a spring from a shaft's twist to ground) the torque it delivers to the shaft, mean and
peak-to-peak.
"""

from __future__ import annotations

import math
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np

from ._core import Mechanism, MechanismBuilder


def _spring_chains(builder: MechanismBuilder) -> Dict[str, List[str]]:
    """{follower DOF: [interior DOFs of the spring chain starting there, in order]}."""
    dofs = {d["name"] for d in builder.dofs if "name" in d}
    chains: Dict[str, List[str]] = {}
    for s in builder.springs:
        if s["name"].endswith(".s1"):
            chain = s["name"][:-3]
            interior = []
            while f"{chain}.{len(interior) + 1}" in dofs:
                interior.append(f"{chain}.{len(interior) + 1}")
            if interior:
                chains[s["a"]] = interior
    return chains


def _bearings(builder: MechanismBuilder) -> Dict[str, tuple]:
    springs = {s["name"]: s for s in builder.springs}
    out = {}
    for name, s in springs.items():
        if name.endswith(".y") and name[:-2] + ".z" in springs and s["b"] == "ground":
            out[name[:-2]] = (s, springs[name[:-2] + ".z"])
    return out


def _drives(builder: MechanismBuilder) -> List[dict]:
    return [s for s in builder.springs if s["a"].endswith(".rx") and s["b"] == "ground" and s["stiffness"] > 0]


def _drive_torque(s: dict, result) -> np.ndarray:
    """Torque a drive spring delivers to the shaft (N m, positive driving it forward): -(k rx + c rx')."""
    return -(s["stiffness"] * np.asarray(result[f"q.{s['a']}"]) + s["damping"] * np.asarray(result[f"v.{s['a']}"]))


def _main_frequency(x: np.ndarray, sample_rate: float) -> float:
    if len(x) < 8:
        return float("nan")
    spectrum = np.abs(np.fft.rfft((x - x.mean()) * np.hanning(len(x))))
    spectrum[0] = 0.0
    return float(np.argmax(spectrum) * sample_rate / len(x))


def run_summary(mechanism: Mechanism, result) -> Dict[str, Any]:
    """The per-cam, per-bearing and drive figures of one run (see the module's description)."""
    builder = mechanism.builder()
    omega = mechanism.omega
    t = np.asarray(result.t)
    chains = _spring_chains(builder)
    sample_rate = 1.0 / (result.time_step * result.decimation)
    cams = {}
    for c in builder.contacts:
        name, dof = c["name"], c["follower_dof"]
        nominal = omega * t + c["phase"]
        lift = np.asarray(c["program"].evaluate(np.mod(nominal, 2 * math.pi))["h"])
        q = np.asarray(result[f"q.{dof}"])
        error = q - lift
        dwell = lift <= 1e-9 * max(1.0, np.abs(lift).max())
        base = float(np.median(error[dwell])) if dwell.any() else 0.0
        force = np.asarray(result[f"{name}.force"])
        lifting = ~dwell
        twist = np.asarray(result[f"{name}.cam_angle"]) - nominal
        lost = sum(b - a for a, b in result.contact_loss.get(name, []))
        entry = {
            "lift_error_mm": 1e3 * float(np.abs(error - base).max()),
            "max_force_N": float(force.max()),
            "min_force_lifting_N": float(force[lifting].min()) if lifting.any() else float(force.min()),
            "contact_lost_s": float(lost),
            "twist_peak_to_peak_deg": float(np.degrees(twist.max() - twist.min())),
        }
        if dof in chains:
            interior = chains[dof]
            n = len(interior) + 1
            k = n // 2
            middle = np.asarray(result[f"q.{interior[k - 1]}"])
            departure = middle - (1.0 - k / n) * q
            entry["surge_peak_to_peak_mm"] = 1e3 * float(departure.max() - departure.min())
            entry["surge_main_frequency_Hz"] = _main_frequency(departure, sample_rate)
        cams[name] = entry
    bearings = {}
    for name, (sy, sz) in _bearings(builder).items():
        fy = sy["stiffness"] * np.asarray(result[f"q.{sy['a']}"]) + sy["damping"] * np.asarray(result[f"v.{sy['a']}"])
        fz = sz["stiffness"] * np.asarray(result[f"q.{sz['a']}"]) + sz["damping"] * np.asarray(result[f"v.{sz['a']}"])
        bearings[name] = {"max_load_N": float(np.hypot(fy, fz).max())}
    drives = {}
    for s in _drives(builder):
        torque = _drive_torque(s, result)
        drives[s["name"]] = {
            "mean_torque_Nm": float(torque.mean()),
            "torque_peak_to_peak_Nm": float(torque.max() - torque.min()),
        }
    return {
        "camshaft_speed_rpm": mechanism.camshaft_speed_rpm,
        "cams": cams,
        "bearings": bearings,
        "drives": drives,
        "newton_iterations_per_step": result.stats["mean_iterations"],
        "backend": result.stats.get("backend", ""),
    }


def camshaft_study(
    case: Union["Config", Mechanism],  # noqa: F821
    rpm: Optional[Sequence[float]] = None,
    *,
    revolutions: float = 2.0,
    record_last_revolutions: float = 1.0,
    **simulate_options,
):
    """Simulate `case` (a Config from load_config, or a Mechanism) at each camshaft speed in `rpm`
    (default: its own) for `revolutions`, recording the last `record_last_revolutions`; return
    (summaries, results): one run_summary() per speed and the Results. A Config's solver settings
    apply unless `simulate_options` override them."""
    from .simulation import simulate

    if isinstance(case, Mechanism):
        base, options = case, {}
    else:
        base, options = case.mechanism, case.simulate_kwargs()
    for key in ("revolutions", "duration", "record_last_revolutions", "record_from"):
        options.pop(key, None)
    options.update(simulate_options)
    speeds = list(rpm) if rpm is not None else [base.camshaft_speed_rpm]
    if not speeds:
        raise ValueError("rpm: give at least one camshaft speed")
    for speed in speeds:  # all of them before the first run
        if not (math.isfinite(speed) and speed > 0):
            raise ValueError(f"rpm: camshaft speeds must be finite and > 0, got {speed}")
    summaries, results = [], []
    for speed in speeds:
        m = base if speed == base.camshaft_speed_rpm else base.with_camshaft_speed_rpm(float(speed))
        result = simulate(m, revolutions=revolutions, record_last_revolutions=record_last_revolutions, **options)
        summaries.append(run_summary(m, result))
        results.append(result)
    return summaries, results


def plot_study(summaries: Sequence[Dict[str, Any]], engine: bool = False):
    """One figure, six panels against speed: lift error, smallest contact force while lifting, twist,
    surge per cam; largest load per bearing; drive torque fluctuation."""
    import matplotlib.pyplot as plt

    factor = 2.0 if engine else 1.0
    speed = np.array([s["camshaft_speed_rpm"] for s in summaries]) * factor
    fig, axes = plt.subplots(2, 3, figsize=(13, 7), constrained_layout=True)
    panels = [
        ("lift_error_mm", "lift error (mm)"),
        ("min_force_lifting_N", "min contact force lifting (N)"),
        ("twist_peak_to_peak_deg", "shaft twist at cam, p-p (deg)"),
        ("surge_peak_to_peak_mm", "spring surge, p-p (mm)"),
    ]
    cams = list(summaries[0]["cams"])
    for ax, (key, label) in zip(axes.flat, panels):
        for cam in cams:
            values = [s["cams"][cam].get(key, np.nan) for s in summaries]
            ax.plot(speed, values, marker="o", label=cam)
        ax.set_ylabel(label)
        if key == "min_force_lifting_N":
            ax.axhline(0.0, color="k", lw=0.8)
    axes.flat[0].legend(fontsize=7, ncol=2)
    ax = axes.flat[4]
    for b in summaries[0]["bearings"]:
        ax.plot(speed, [s["bearings"][b]["max_load_N"] for s in summaries], marker="s", label=b)
    ax.set_ylabel("largest bearing load (N)")
    if summaries[0]["bearings"]:
        ax.legend(fontsize=7)
    ax = axes.flat[5]
    for d in summaries[0]["drives"]:
        ax.plot(speed, [s["drives"][d]["torque_peak_to_peak_Nm"] for s in summaries], marker="^", label=f"{d} p-p")
        ax.plot(speed, [s["drives"][d]["mean_torque_Nm"] for s in summaries], ls="--", label=f"{d} mean")
    ax.set_ylabel("drive torque (N m)")
    if summaries[0]["drives"]:
        ax.legend(fontsize=7)
    for ax in axes.flat:
        ax.set_xlabel("engine speed (rpm)" if engine else "camshaft speed (rpm)")
        ax.grid(True, alpha=0.3)
    return fig


def plot_traces(mechanism: Mechanism, result):
    """Contact force of every cam and the drive torque against the camshaft angle, folded onto one
    revolution (0-360°, whatever revolutions were recorded; the lines broken where the angle wraps)."""
    import matplotlib.pyplot as plt

    from .plot import per_revolution

    builder = mechanism.builder()
    theta = np.asarray(result["theta"])
    fig, (a, b) = plt.subplots(2, 1, figsize=(10, 7), sharex=True, constrained_layout=True)
    for c in builder.contacts:
        a.plot(*per_revolution(theta, np.asarray(result[f"{c['name']}.force"])), lw=0.8, label=c["name"])
    a.set_ylabel("contact force (N)")
    a.legend(fontsize=7, ncol=4, loc="best")
    drives = _drives(builder)
    for s in drives:
        b.plot(*per_revolution(theta, _drive_torque(s, result)), lw=0.8, label=s["name"])
    if drives:
        b.legend(fontsize=7, loc="best")
    b.set_ylabel("drive torque (N m)")
    b.set_xlabel("camshaft angle (deg, per revolution)")
    b.set_xlim(0, 360)
    for ax in (a, b):
        ax.grid(True, alpha=0.3)
    fig.suptitle(f"{mechanism.camshaft_speed_rpm:.6g} rpm camshaft")
    return fig


__all__ = ["camshaft_study", "run_summary", "plot_study", "plot_traces"]
