"""The paper's study, run as ``python -m camfollower.study`` (or ``camfollower-study``).

Three cases at 750 rpm on the paper's cam and 7-DOF model: healthy, 10 um camshaft eccentricity and
10 um follower backlash. Each is simulated from static equilibrium for several revolutions; the last
whole revolutions (transient gone) are analysed. Writes to the output folder (default ``out/``):
figures ``fig06``-``fig15`` and ``kinematics.png``, the data behind each figure under ``data/``, the
cam surface ``cam_surface.csv`` and ``summary.json`` (written last: its presence marks a complete run).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import CamFollowerModel, Defects, DiskCam, Parameters, simulate
from . import analysis as an

SHAFT = 0  # y1: camshaft bearing, vertical
FOLLOWER = 3  # y4


@dataclass
class StudyConfig:
    rpm: float = 750.0
    eccentricity: float = 10e-6  # m
    eccentricity_phase: float = 0.0  # rad
    backlash: float = 10e-6  # m
    backlash_switch_width_deg: float = 10.0
    revolutions: int = 20  # simulated per case
    analysed_revolutions: int = 8  # the last ones; spectral resolution = shaft frequency / this
    steps_per_revolution: int = 32768
    sensitivity_widths_deg: tuple = (0.0, 2.0, 10.0, 30.0)

    def validate(self) -> None:
        def positive(name, v):
            if not (math.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be finite and > 0, got {v}")

        positive("rpm", self.rpm)
        for name in ("eccentricity", "backlash"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise ValueError(f"{name} must be finite and >= 0 (m), got {v}")
        if not (0 <= self.backlash_switch_width_deg <= 180):
            raise ValueError(f"backlash switch width must be in [0, 180] deg, got {self.backlash_switch_width_deg}")
        if not (2 <= self.analysed_revolutions < self.revolutions):
            raise ValueError("analysed revolutions must be >= 2 and fewer than the simulated revolutions, "
                             f"got {self.analysed_revolutions} of {self.revolutions}")
        if self.steps_per_revolution < 1000:
            raise ValueError(f"steps per revolution must be >= 1000, got {self.steps_per_revolution}")


@dataclass
class CaseResult:
    name: str
    model: CamFollowerModel
    theta: np.ndarray  # analysed window
    follower_acc: np.ndarray
    theory_acc: np.ndarray
    shaft_acc: np.ndarray
    contact_force: np.ndarray
    contact_stiffness_vertical: np.ndarray
    in_contact: np.ndarray
    shaft_spectrum: an.Spectrum
    stiffness_spectrum: an.Spectrum
    stats: dict
    summary: dict = field(default_factory=dict)


def run_case(name: str, defects: Defects, cfg: StudyConfig) -> CaseResult:
    model = CamFollowerModel(Parameters(camshaft_speed_rpm=cfg.rpm), defects=defects)
    n = cfg.steps_per_revolution
    r = simulate(model, revolutions=cfg.revolutions, time_step=model.period / n)
    w = an.last_revolutions(r, model.period, cfg.analysed_revolutions)
    theta = r["theta"][w]
    a4 = r["a"][w, FOLLOWER]
    theory = an.theoretical_follower_acceleration(model, theta)
    a1 = r["a"][w, SHAFT]
    # The paper's "Hertzian stiffness": the contact stiffness seen along the follower axis.
    k_vertical = r["contact_stiffness"][w] * np.cos(r["pressure_angle"][w]) ** 2
    sample_rate = n / model.period
    rev_a = r["a"][-2 * n:-n, FOLLOWER]
    rev_b = r["a"][-n:, FOLLOWER]
    lost = an.contact_loss_intervals(r["t"][w], r["in_contact"][w])
    return CaseResult(
        name=name, model=model, theta=theta, follower_acc=a4, theory_acc=theory, shaft_acc=a1,
        contact_force=r["contact_force"][w], contact_stiffness_vertical=k_vertical, in_contact=r["in_contact"][w],
        shaft_spectrum=an.spectrum(a1, sample_rate), stiffness_spectrum=an.spectrum(k_vertical, sample_rate),
        stats={**r["stats"],
               "periodicity_follower_acc": float(np.max(np.abs(rev_a - rev_b))),
               "contact_loss_time_s": float(sum(b - a for a, b in lost)) / cfg.analysed_revolutions,
               "contact_loss_intervals": len(lost)})


def summarize(case: CaseResult, carrier: float, cfg: StudyConfig) -> dict:
    m = case.model
    dev = case.follower_acc - case.theory_acc
    return {
        "defects": {"eccentricity_m": m.defects.eccentricity, "backlash_m": m.defects.backlash,
                    "backlash_switch_width_deg": math.degrees(m.defects.backlash_switch_width)},
        "period_s": m.period,
        "newton_iterations_per_step": case.stats["mean_iterations"],
        "revolution_to_revolution_change_of_follower_acceleration_m_s2": case.stats["periodicity_follower_acc"],
        "follower_acceleration_m_s2": an.phase_statistics(m, case.theta, case.follower_acc),
        "follower_acceleration_minus_theory_m_s2": an.phase_statistics(m, case.theta, dev),
        "contact_force_N": an.phase_statistics(m, case.theta, case.contact_force),
        "contact_force_range_N": [float(case.contact_force.min()), float(case.contact_force.max())],
        "contact_loss_time_per_revolution_s": case.stats["contact_loss_time_s"],
        "shaft_acceleration_rms_m_s2": float(np.sqrt(np.mean(case.shaft_acc**2))),
        "shaft_acceleration_spectral_peaks": [{"frequency_hz": f, "amplitude_m_s2": a}
                                              for f, a in an.find_peaks(case.shaft_spectrum, 6, lo=50.0)],
        "shaft_acceleration_sidebands": an.sidebands(case.shaft_spectrum, carrier, cfg.rpm / 60.0, orders=3),
        "vertical_contact_stiffness_spectral_peaks": [
            {"frequency_hz": f, "amplitude_N_m": a} for f, a in an.find_peaks(case.stiffness_spectrum, 5, lo=1.0)],
    }


def defect_modulation(levels: dict, healthy_levels: dict) -> float:
    """What a defect adds around the carrier: RSS of the changes of the +-k x shaft-frequency lines
    against the healthy case, over the healthy carrier. 0 = no added modulation."""
    added = math.sqrt(sum((levels[k] - healthy_levels[k]) ** 2 for k in levels if k != 0))
    return added / healthy_levels[0]


def backlash_sensitivity(cfg: StudyConfig) -> list[dict]:
    """Peak follower acceleration, contact force and contact loss against the switch width."""
    out = []
    short = StudyConfig(**{**cfg.__dict__, "revolutions": 12, "analysed_revolutions": 2})
    for width in cfg.sensitivity_widths_deg:
        c = run_case("backlash", Defects(backlash=cfg.backlash, backlash_switch_width=math.radians(width)), short)
        out.append({"switch_width_deg": width,
                    "peak_follower_acceleration_m_s2": float(np.max(np.abs(c.follower_acc))),
                    "peak_contact_force_N": float(np.max(c.contact_force)),
                    "contact_loss_time_per_revolution_s": c.stats["contact_loss_time_s"]})
    return out


class Progress:
    """A one-line text progress bar on stderr."""

    def __init__(self, total: int):
        self.total, self.done, self.start = total, 0, time.perf_counter()

    def step(self, label: str) -> None:
        self.done += 1
        filled = int(30 * self.done / self.total)
        line = (f"[{'#' * filled}{'.' * (30 - filled)}] {self.done}/{self.total} "
                f"{time.perf_counter() - self.start:5.1f} s  {label:<40s}")
        # Redraw in place on a terminal; one line per step in a log.
        tty = sys.stderr.isatty()
        sys.stderr.write(("\r" + line) if tty else (line.rstrip() + "\n"))
        if tty and self.done == self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def write_csv(path: Path, header: list[str], columns) -> None:
    np.savetxt(path, np.column_stack(columns), delimiter=",", header=",".join(header), comments="", fmt="%.9g")


def make_figures(cases: dict, carrier: float, modal: dict, cfg: StudyConfig, folder: Path, progress: Progress):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = folder / "data"
    data.mkdir(exist_ok=True)
    h = cases["healthy"]
    n = cfg.steps_per_revolution
    one = slice(h.theta.size - n, h.theta.size)  # last revolution
    deg = np.degrees(np.mod(h.theta[one], 2 * np.pi))
    every = 4  # decimation of the time plots and their data

    def save(fig, name):
        fig.tight_layout()
        fig.savefig(folder / f"{name}.png", dpi=110)
        plt.close(fig)
        progress.step(name)

    def time_figure(name, title, ylabel, series, csv_header):
        fig, ax = plt.subplots(figsize=(9, 4.5))
        for label, y, style in series:
            ax.plot(deg[::every], y[one][::every], style, lw=0.8, label=label)
        ax.set_xlabel("cam angle θ (deg)"), ax.set_ylabel(ylabel), ax.set_xlim(0, 360)
        for b in (30, 180, 210):
            ax.axvline(b, color="0.7", lw=0.6)
        ax.set_title(title), ax.legend(loc="best"), ax.grid(alpha=0.3)
        write_csv(data / f"{name}.csv", ["theta_deg"] + csv_header, [deg[::every]] + [y[one][::every] for _, y, _ in series])
        save(fig, name)

    def spectrum_figure(name, title, spectra, fmax, zoom=None):
        fig, axes = plt.subplots(1, 2 if zoom else 1, figsize=(11 if zoom else 9, 4.5), squeeze=False)
        ax = axes[0, 0]
        for label, s, style in spectra:
            b = s.band(0, fmax)
            ax.plot(b.frequency, b.amplitude, style, lw=0.8, label=label)
        for f in modal["frequencies_hz"]:
            if f < fmax:
                ax.axvline(f, color="tab:red", lw=0.5, ls=":")
        ax.axvline(0.4 * modal["frequencies_hz"][0], color="tab:green", lw=0.5, ls="--", label="2/5 f01")
        ax.set_xlabel("frequency (Hz)"), ax.set_ylabel("amplitude (m/s²)"), ax.set_title(title)
        ax.legend(loc="best"), ax.grid(alpha=0.3)
        if zoom:
            az = axes[0, 1]
            for label, s, style in spectra:
                b = s.band(*zoom)
                az.plot(b.frequency, b.amplitude, style, marker=".", lw=0.8, label=label)
            az.axvline(carrier, color="0.5", lw=0.5)
            az.set_xlabel("frequency (Hz)"), az.set_title(f"around the carrier {carrier:.1f} Hz (±12.5 Hz lines)")
            az.grid(alpha=0.3), az.legend(loc="best")
        cols, header = [spectra[0][1].band(0, fmax).frequency], ["frequency_hz"]
        for label, s, _ in spectra:
            cols.append(s.band(0, fmax).amplitude)
            header.append(f"amplitude_{label.replace(' ', '_')}")
        write_csv(data / f"{name}.csv", header, cols)
        save(fig, name)

    fmax = 6000.0
    zoom = (carrier - 60, carrier + 60)
    time_figure("fig06_follower_acceleration", "Follower acceleration over one period (healthy)", "ÿ4 (m/s²)",
                [("dynamic", h.follower_acc, "-"), ("theoretical ω²h''", h.theory_acc, "k--")],
                ["dynamic_m_s2", "theoretical_m_s2"])
    time_figure("fig07_contact_force", "Cam-roller contact force (healthy)", "contact force (N)",
                [("healthy", h.contact_force, "-")], ["contact_force_N"])
    spectrum_figure("fig08_bearing_spectrum", "Camshaft bearing acceleration ÿ1 (healthy)",
                    [("healthy", h.shaft_spectrum, "-")], fmax)
    fig, ax = plt.subplots(figsize=(9, 4.5))
    ks = h.stiffness_spectrum.band(1.0, 400)
    ax.semilogy(ks.frequency, ks.amplitude, ".-", lw=0.8)
    ax.set_xlabel("frequency (Hz)"), ax.set_ylabel("amplitude (N/m)")
    ax.set_title("Spectrum of the contact stiffness along the follower axis, K_h cos²α")
    ax.grid(alpha=0.3)
    write_csv(data / "fig09_contact_stiffness_spectrum.csv", ["frequency_hz", "amplitude_N_m"], [ks.frequency, ks.amplitude])
    save(fig, "fig09_contact_stiffness_spectrum")
    for key, (fa, ff, fs) in {"eccentricity": (10, 11, 12), "backlash": (13, 14, 15)}.items():
        d = cases[key]
        time_figure(f"fig{fa}_{key}_follower_acceleration", f"Follower acceleration: {key} vs healthy", "ÿ4 (m/s²)",
                    [(key, d.follower_acc, "-"), ("healthy", h.follower_acc, "-"), ("theoretical", h.theory_acc, "k--")],
                    [f"{key}_m_s2", "healthy_m_s2", "theoretical_m_s2"])
        time_figure(f"fig{ff}_{key}_contact_force", f"Contact force: {key} vs healthy", "contact force (N)",
                    [(key, d.contact_force, "-"), ("healthy", h.contact_force, "-")], [f"{key}_N", "healthy_N"])
        spectrum_figure(f"fig{fs}_{key}_bearing_spectrum", f"Camshaft bearing acceleration ÿ1: {key} vs healthy",
                        [(key, d.shaft_spectrum, "-"), ("healthy", h.shaft_spectrum, "-")], fmax, zoom)


def plot_kinematics(cam: DiskCam, rpm: float, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    omega = rpm * 2 * math.pi / 60
    theta = np.linspace(0, 2 * math.pi, 3601)
    p = cam.profile(theta)
    h = cam.program.evaluate(theta)
    deg = np.degrees(theta)
    fig = plt.figure(figsize=(11, 7))
    ax = [fig.add_subplot(2, 3, i) for i in (1, 2, 4, 5)] + [fig.add_subplot(1, 3, 3)]
    ax[0].plot(deg, 1e3 * h["h"]), ax[0].set_ylabel("lift h (mm)")
    ax[1].plot(deg, omega * h["dh"]), ax[1].set_ylabel("follower velocity (m/s)")
    ax[2].plot(deg, omega**2 * h["d2h"]), ax[2].set_ylabel("follower acceleration (m/s²)")
    ax[3].plot(deg, np.degrees(p["pressure_angle"])), ax[3].set_ylabel("pressure angle (deg)")
    for a in ax[:4]:
        a.set_xlabel("cam angle θ (deg)"), a.set_xlim(0, 360), a.grid(alpha=0.3)
    ax[4].plot(1e3 * p["surface_x"], 1e3 * p["surface_y"], label="cam surface")
    ax[4].plot(1e3 * p["pitch_x"], 1e3 * p["pitch_y"], "--", label="pitch curve")
    ax[4].set_aspect("equal"), ax[4].set_xlabel("x (mm)"), ax[4].set_ylabel("y (mm)"), ax[4].legend()
    fig.suptitle(f"Paper cam kinematics at {rpm:g} rpm (modified trapezoid, e = {1e3 * cam.offset:g} mm)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def kinematics_summary(cam: DiskCam, rpm: float) -> dict:
    """Pressure-angle extremes, tightest cam-surface radius and peak follower acceleration."""
    omega = rpm * 2 * math.pi / 60
    theta = np.linspace(0, 2 * math.pi, 360001)
    d2h = cam.program.evaluate(theta)["d2h"]
    k = int(np.argmax(np.abs(d2h)))
    t_rise, a_rise = cam.max_pressure_angle_rise()
    t_ret, a_ret = cam.max_pressure_angle_return()
    t_rho, rho = cam.min_surface_radius()
    return {
        "max_pressure_angle_rise_deg": math.degrees(a_rise),
        "max_pressure_angle_rise_at_deg": math.degrees(t_rise),
        "max_pressure_angle_return_deg": math.degrees(a_ret),
        "max_pressure_angle_return_at_deg": math.degrees(t_ret),
        "min_surface_radius_m": rho,
        "min_surface_radius_at_deg": math.degrees(t_rho),
        "max_theoretical_follower_acceleration_m_s2": float(omega**2 * abs(d2h[k])),
        "max_theoretical_follower_acceleration_at_deg": math.degrees(theta[k]),
    }


def run_study(cfg: StudyConfig, out: Path, figures: bool = True) -> dict:
    """Run the three cases, write figures, data and summary.json into `out`; return the summary."""
    cfg.validate()
    progress = Progress(6 + (10 if figures else 0))
    defects = {
        "healthy": Defects(),
        "eccentricity": Defects(eccentricity=cfg.eccentricity, eccentricity_phase=cfg.eccentricity_phase),
        "backlash": Defects(backlash=cfg.backlash, backlash_switch_width=math.radians(cfg.backlash_switch_width_deg)),
    }
    cases = {}
    for name, d in defects.items():
        cases[name] = run_case(name, d, cfg)
        progress.step(f"simulated {name} ({cfg.revolutions} revolutions)")
    model = cases["healthy"].model
    modal = model.modal_analysis(0.0)
    # Carrier: the strongest line of the healthy camshaft-bearing spectrum.
    carrier = an.find_peaks(cases["healthy"].shaft_spectrum, 1, lo=50.0)[0][0]
    summary = {
        "rpm": cfg.rpm,
        "shaft_frequency_hz": cfg.rpm / 60.0,
        "time_step_s": model.period / cfg.steps_per_revolution,
        "simulated_revolutions": cfg.revolutions,
        "analysed_revolutions": cfg.analysed_revolutions,
        "spectral_resolution_hz": cfg.rpm / 60.0 / cfg.analysed_revolutions,
        "kinematics": kinematics_summary(model.cam, cfg.rpm),
        "natural_frequencies_hz_dwell": [float(f) for f in modal["frequencies_hz"]],
        "paper_table3_hz": [2447, 2447, 5711, 12777, 13990, 17009, 17009],
        "carrier_hz": carrier,
        "cases": {name: summarize(c, carrier, cfg) for name, c in cases.items()},
    }
    healthy_lines = summary["cases"]["healthy"]["shaft_acceleration_sidebands"]["levels"]
    for name in ("eccentricity", "backlash"):
        sb = summary["cases"][name]["shaft_acceleration_sidebands"]
        sb["defect_modulation"] = defect_modulation(sb["levels"], healthy_lines)
    progress.step("analysed")
    summary["backlash_switch_width_sensitivity"] = backlash_sensitivity(cfg)
    progress.step("backlash switch-width sensitivity")

    # Stage everything, then move into place; summary.json last marks a complete run.
    out.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=".camfollower-study-", dir=out))
    try:
        if figures:
            plot_kinematics(model.cam, cfg.rpm, stage / "kinematics.png")
            make_figures(cases, carrier, modal, cfg, stage, progress)
        model.cam.write_surface_csv(str(stage / "cam_surface.csv"))
        (stage / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
        (out / "summary.json").unlink(missing_ok=True)
        for item in sorted(stage.rglob("*"), key=lambda p: p.name == "summary.json"):
            if item.is_file():
                target = out / item.relative_to(stage)
                target.parent.mkdir(parents=True, exist_ok=True)
                os.replace(item, target)
    finally:
        shutil.rmtree(stage, ignore_errors=True)
    progress.step("written")
    return summary


def print_summary(summary: dict) -> None:
    k = summary["kinematics"]
    print(f"\npaper cam at {summary['rpm']:g} rpm: max |pressure angle| rise {abs(k['max_pressure_angle_rise_deg']):.2f} deg "
          f"at {k['max_pressure_angle_rise_at_deg']:.1f} deg, return {abs(k['max_pressure_angle_return_deg']):.2f} deg at "
          f"{k['max_pressure_angle_return_at_deg']:.1f} deg; min surface radius {1e3 * k['min_surface_radius_m']:.2f} mm; "
          f"peak theoretical follower acceleration {k['max_theoretical_follower_acceleration_m_s2']:.2f} m/s^2")
    print("natural frequencies on the dwell (Hz): " + ", ".join(f"{f:.0f}" for f in summary["natural_frequencies_hz_dwell"])
          + "   (paper Table 3: " + ", ".join(str(f) for f in summary["paper_table3_hz"]) + ")")
    print(f"\n{'case':13s} {'peak a4':>9s} {'dwell dev':>10s} {'rise dev':>9s} {'return dev':>10s} {'Fc min':>8s} "
          f"{'Fc max':>8s} {'loss/rev':>9s} {'a1 rms':>8s} {'added mod.':>10s}")
    for name, c in summary["cases"].items():
        dev = c["follower_acceleration_minus_theory_m_s2"]
        dwell = max(p["peak"] for p in dev if p["phase"].startswith("dwell"))
        rise = max(p["rms"] for p in dev if p["phase"].startswith("rise"))
        ret = max(p["rms"] for p in dev if p["phase"].startswith("return"))
        peak = max(p["peak"] for p in c["follower_acceleration_m_s2"])
        lo, hi = c["contact_force_range_N"]
        print(f"{name:13s} {peak:9.2f} {dwell:10.3f} {rise:9.3f} {ret:10.3f} {lo:8.1f} {hi:8.1f} "
              f"{c['contact_loss_time_per_revolution_s']:9.2e} {c['shaft_acceleration_rms_m_s2']:8.3f} "
              f"{c['shaft_acceleration_sidebands'].get('defect_modulation', 0.0):10.4f}")
    print("  (m/s^2 and N; dwell dev = peak |a4 - theory| on the dwells, rise/return dev = its RMS; added mod. =\n"
          f"   RSS of the changes of the +-1..3 x 12.5 Hz lines around the {summary['carrier_hz']:.1f} Hz carrier of the\n"
          "   camshaft-bearing acceleration, relative to the healthy carrier)")
    print("backlash switch-width sensitivity: " + "; ".join(
        f"{s['switch_width_deg']:g} deg: peak a4 {s['peak_follower_acceleration_m_s2']:.0f} m/s^2, "
        f"peak Fc {s['peak_contact_force_N']:.0f} N, contact lost {1e3 * s['contact_loss_time_per_revolution_s']:.2f} ms/rev"
        for s in summary["backlash_switch_width_sensitivity"]))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="camfollower-study", description=__doc__.splitlines()[0])
    d = StudyConfig()
    parser.add_argument("--out", default="out", help="output folder (created if missing); default: out")
    parser.add_argument("--rpm", type=float, default=d.rpm, help=f"camshaft speed (rpm); default {d.rpm:g}")
    parser.add_argument("--eccentricity", type=float, default=d.eccentricity, help="camshaft eccentricity (m); default 10e-6")
    parser.add_argument("--backlash", type=float, default=d.backlash, help="follower backlash (m); default 10e-6")
    parser.add_argument("--backlash-switch-width", type=float, default=d.backlash_switch_width_deg,
                        help=f"cam angle over which the rod crosses the clearance (deg); default {d.backlash_switch_width_deg:g}")
    parser.add_argument("--revolutions", type=int, default=d.revolutions, help=f"simulated revolutions; default {d.revolutions}")
    parser.add_argument("--analysed-revolutions", type=int, default=d.analysed_revolutions,
                        help=f"last revolutions analysed; default {d.analysed_revolutions}")
    parser.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    args = parser.parse_args(argv)
    cfg = StudyConfig(rpm=args.rpm, eccentricity=args.eccentricity, backlash=args.backlash,
                      backlash_switch_width_deg=args.backlash_switch_width, revolutions=args.revolutions,
                      analysed_revolutions=args.analysed_revolutions)
    out = Path(args.out)
    try:
        cfg.validate()
        out.mkdir(parents=True, exist_ok=True)
        if not os.access(out, os.W_OK):
            raise PermissionError(f"'{out}' is not writable")
    except ValueError as e:
        parser.error(str(e))
    except OSError as e:
        parser.error(f"--out: cannot write to '{out}': {e}")
    summary = run_study(cfg, out, figures=not args.no_figures)
    print_summary(summary)
    print(f"\nwrote figures, data/ and summary.json to {out}/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
