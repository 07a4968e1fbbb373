# SPDX-License-Identifier: BSD-3-Clause
"""The paper's study, run as ``camfollower study`` (or ``python -m camfollower.study``).

The paper's cam at 750 rpm, for the paper's offset follower (e = 10 mm) and an in-line one (e = 0):
healthy, camshaft eccentricity and guide clearance, each in two formulations side by side:

- ``paper``: the paper's literal reading: its element dampers (lateral modes at ~1e-5 of critical),
  eccentricity as the force K_h epsilon sin(theta) of its eq 6, backlash as an imposed switch of the
  rod's side at the start of each rise and return (the preset's ``paper_backlash``);
- ``physical``: the defects from their mechanisms: dashpots on every element (3 % on the lowest
  modes), the cam's centre displaced (exact contact geometry), the rod in a guide with a radial gap
  (wall contacts).

Every case first runs until its periodic steady state (the follower acceleration's change between
revolutions below a tolerance, or it reports that it never settles), then the analysed revolutions.
Sensitivity bands over what the paper does not give: camshaft mass and contact exponent.

Writes to the output folder (default ``out/``): figures, the data behind each under ``data/``, the
cam surface ``cam_surface.csv`` and ``summary.json`` (written last: its presence marks a complete run).
"""

from __future__ import annotations

import argparse
import io
import math
import os
import sys
import time
import warnings
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from . import (
    CamEccentricity,
    MotionProgram,
    Parameters,
    TranslatingRoller,
    _files,
    export,
    presets,
    simulate,
    simulate_many,
)
from . import analysis as an

FOLLOWERS = {"offset": 0.010, "inline": 0.0}  # follower axis offset e, m
FORMULATIONS = ("paper", "physical")
DEFECTS = ("healthy", "eccentricity", "clearance")


@dataclass(frozen=True)
class StudyConfig:
    rpm: float = 750.0
    eccentricity: float = 10e-6  # m, cam centre from the bearing axis
    clearance: float = 10e-6  # m, radial: the rod crosses 2 x this between the walls
    backlash_switch_width_deg: float = 10.0  # paper formulation: cam angle over which the imposed switch ramps
    damping_ratio: float = presets.REALISTIC_DAMPING_RATIO  # physical formulation
    analysed_revolutions: int = 8  # after settling; spectral resolution = shaft frequency / this
    steps_per_revolution: int = 32768
    settle_tolerance: float = 1e-5  # relative change of the follower acceleration per revolution
    max_revolutions: int = 150  # to settle
    camshaft_masses: tuple = (0.5, 1.1, 2.0, 5.0)  # kg, sensitivity band (paper: 1.1)
    contact_exponents: tuple = (1.0, 10.0 / 9.0, 1.5)  # sensitivity band (paper: 1)

    def validate(self) -> None:
        def positive(name, v):
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise ValueError(f"{name} must be finite and > 0, got {v}")

        positive("rpm", self.rpm)
        positive("eccentricity", self.eccentricity)
        positive("clearance", self.clearance)
        if not (0 <= self.backlash_switch_width_deg <= 180):
            raise ValueError(f"backlash switch width must be in [0, 180] deg, got {self.backlash_switch_width_deg}")
        if not (0 < self.damping_ratio < 1):
            raise ValueError(f"damping ratio must be in (0, 1), got {self.damping_ratio}")
        if self.analysed_revolutions < 2:
            raise ValueError(f"analysed revolutions must be >= 2, got {self.analysed_revolutions}")
        if self.steps_per_revolution < 1000:
            raise ValueError(f"steps per revolution must be >= 1000, got {self.steps_per_revolution}")
        if not (0 < self.settle_tolerance < 1):
            raise ValueError(f"settle tolerance must be in (0, 1), got {self.settle_tolerance}")
        if self.max_revolutions < 2:
            raise ValueError(f"max revolutions must be >= 2, got {self.max_revolutions}")


@dataclass
class CaseResult:
    key: str  # follower/formulation/defect
    model: object
    program: MotionProgram
    omega: float
    period: float
    theta: np.ndarray
    follower_disp: np.ndarray
    follower_acc: np.ndarray
    theory_acc: np.ndarray
    shaft_acc: np.ndarray
    contact_force: np.ndarray
    contact_stiffness_vertical: np.ndarray
    pressure_angle: np.ndarray
    rod_lateral: np.ndarray
    shaft_spectrum: an.Spectrum
    stiffness_spectrum: an.Spectrum
    settle: dict
    contact_loss_time: float
    clearance: dict | None
    stats: dict


def parameters(cfg: StudyConfig, follower: str, **overrides) -> Parameters:
    return Parameters(camshaft_speed_rpm=cfg.rpm).replace(offset=FOLLOWERS[follower], **overrides)


def build(cfg: StudyConfig, follower: str, formulation: str, defect: str, p: Parameters | None = None):
    """The model of one case (see the module docstring)."""
    p = p or parameters(cfg, follower)
    if formulation == "paper":
        if defect == "clearance":
            return presets.paper(
                p,
                paper_backlash=cfg.clearance,
                paper_backlash_switch_width=math.radians(cfg.backlash_switch_width_deg),
            )
        ecc = CamEccentricity(cfg.eccentricity, formulation="paper_force_both") if defect == "eccentricity" else None
        with warnings.catch_warnings():  # the literal force exceeds the preload: reported in the summary
            warnings.simplefilter("ignore", UserWarning)
            return presets.paper(p, eccentricity=ecc)
    ecc = CamEccentricity(cfg.eccentricity) if defect == "eccentricity" else None
    clearance = cfg.clearance if defect == "clearance" else 0.0
    return presets.paper_damped(p, eccentricity=ecc, guide_clearance=clearance, damping_ratio=cfg.damping_ratio)


def _run_options(cfg: StudyConfig, model) -> dict:
    """simulate()'s options for a case: settle on the follower, then record the analysed revolutions."""
    return dict(
        revolutions=cfg.analysed_revolutions,
        time_step=model.period / cfg.steps_per_revolution,
        settle=True,
        settle_dofs=["y4"],
        settle_tolerance=cfg.settle_tolerance,
        settle_max_revolutions=cfg.max_revolutions,
    )


def _case_result(cfg: StudyConfig, key: str, model, r) -> CaseResult:
    """A case's figures from its run."""
    program = MotionProgram.paper_default()
    n = cfg.steps_per_revolution
    w = slice(-cfg.analysed_revolutions * n, None)  # whole revolutions (the first row is the settled start)
    theta = np.asarray(r["theta"])[w]
    a4 = np.asarray(r["a.y4"])[w]
    omega = 2 * math.pi / model.period
    theory = omega**2 * np.asarray(program.evaluate(theta)["d2h"])
    a1 = np.asarray(r["a.y1"])[w]
    force = np.asarray(r["cam.force"])[w]
    pressure_angle = np.asarray(r["cam.pressure_angle"])[w]
    k_vertical = np.asarray(r["cam.stiffness"])[w] * np.cos(pressure_angle) ** 2
    in_contact = np.asarray(r["cam.in_contact"])[w].astype(bool)
    lost = an.contact_loss_intervals(np.asarray(r["t"])[w], in_contact)
    sample_rate = n / model.period
    guide = an.clearance_statistics(r, "guide", model.period) if "guide.side" in r else None
    return CaseResult(
        key=key,
        model=model,
        program=program,
        omega=omega,
        period=model.period,
        theta=theta,
        follower_disp=np.asarray(r["q.y4"])[w],
        follower_acc=a4,
        theory_acc=theory,
        shaft_acc=a1,
        contact_force=force,
        contact_stiffness_vertical=k_vertical,
        pressure_angle=pressure_angle,
        rod_lateral=np.asarray(r["q.x3"])[w],
        shaft_spectrum=an.spectrum(a1, sample_rate),
        stiffness_spectrum=an.spectrum(k_vertical, sample_rate),
        settle=dict(r.settle),
        contact_loss_time=float(sum(b - a for a, b in lost)) / cfg.analysed_revolutions,
        clearance=guide,
        stats=dict(r.stats),
    )


def run_case(cfg: StudyConfig, follower: str, formulation: str, defect: str, p: Parameters | None = None) -> CaseResult:
    model = build(cfg, follower, formulation, defect, p)
    r = simulate(model, **_run_options(cfg, model))
    return _case_result(cfg, f"{follower}/{formulation}/{defect}", model, r)


def deviation_figures(case: CaseResult) -> dict:
    """Dwell peak and rise / return RMS of the follower acceleration's deviation from omega^2 h''."""
    st = an.phase_statistics(case.program, case.theta, case.follower_acc - case.theory_acc)
    return {
        "dwell_peak": max(s["peak"] for s in st if s["phase"].startswith("dwell")),
        "rise_rms": max(s["rms"] for s in st if s["phase"].startswith("rise")),
        "return_rms": max(s["rms"] for s in st if s["phase"].startswith("return")),
    }


def summarize(case: CaseResult, carrier: float) -> dict:
    dev = deviation_figures(case)
    out = {
        "settle": {k: case.settle[k] for k in ("settled", "revolutions", "change", "change_absolute", "tolerance")},
        "newton_iterations_per_step": case.stats["mean_iterations"],
        "peak_follower_acceleration_m_s2": float(np.max(np.abs(case.follower_acc))),
        "follower_acceleration_minus_theory_m_s2": an.phase_statistics(
            case.program, case.theta, case.follower_acc - case.theory_acc
        ),
        "dwell_deviation_peak_m_s2": dev["dwell_peak"],
        "rise_deviation_rms_m_s2": dev["rise_rms"],
        "return_deviation_rms_m_s2": dev["return_rms"],
        "contact_force_range_N": [float(case.contact_force.min()), float(case.contact_force.max())],
        "contact_loss_time_per_revolution_s": case.contact_loss_time,
        "shaft_acceleration_rms_m_s2": float(np.sqrt(np.mean(case.shaft_acc**2))),
        "shaft_acceleration_spectral_peaks": [
            {"frequency_hz": f, "amplitude_m_s2": a} for f, a in an.find_peaks(case.shaft_spectrum, 6, lo=50.0)
        ],
        "shaft_acceleration_sidebands": an.sidebands(
            case.shaft_spectrum, carrier, case.omega / (2 * math.pi), orders=3
        ),
    }
    if case.clearance is not None:
        out["guide_clearance"] = case.clearance
    model_warnings = getattr(case.model, "warnings", [])
    if model_warnings:
        out["model_warnings"] = list(model_warnings)
    return out


def defect_modulation(levels: dict, healthy_levels: dict) -> float:
    """What a defect adds around the carrier: RSS of the changes of the +-k x shaft-frequency lines
    against the healthy case, over the healthy carrier. 0 = no added modulation."""
    added = math.sqrt(sum((levels[k] - healthy_levels[k]) ** 2 for k in levels if k != 0))
    return added / healthy_levels[0]


def run_cases(cfg: StudyConfig, progress=None) -> dict:
    """Every follower x formulation x defect case, keyed follower/formulation/defect, run together on
    C++ threads (simulate_many; each case as simulate() runs it alone)."""
    keys, models = [], []
    for follower in FOLLOWERS:
        for formulation in FORMULATIONS:
            for defect in DEFECTS:
                keys.append(f"{follower}/{formulation}/{defect}")
                models.append(build(cfg, follower, formulation, defect))
    periods = {m.period for m in models}
    if len(periods) != 1:
        raise ValueError(f"the study's cases must share one camshaft speed, got periods {sorted(periods)} s")
    cases = {}
    for key, model, r in zip(keys, models, simulate_many(models, **_run_options(cfg, models[0]))):
        c = cases[key] = _case_result(cfg, key, model, r)
        if progress:
            progress.step(f"{c.key}: settled={c.settle['settled']} ({c.settle['revolutions']} rev)")
    return cases


def matched_contact_stiffness(p: Parameters, exponent: float, force: float) -> float:
    """K_n of K delta^n with the same tangent stiffness as the paper's linear law where it carries
    `force` (N): n K_n delta^(n-1) = K_1 at K_n delta^n = force, so delta = n force / K_1."""
    delta = exponent * force / p.get("contact_stiffness")
    return force / delta**exponent


def sensitivity(cfg: StudyConfig, progress=None) -> list[dict]:
    """Rise vs return deviation of the healthy offset follower (physical formulation) over camshaft
    mass and contact exponent (neither is given by the paper)."""
    out = []
    base = parameters(cfg, "offset")
    force = base.get("spring_stiffness") * base.get("spring_preload_deflection")  # the spring force on the dwell
    short = replace(cfg, analysed_revolutions=2)
    for exponent in cfg.contact_exponents:
        for mass in cfg.camshaft_masses:
            p = base.replace(
                camshaft_mass=mass,
                contact_exponent=exponent,
                contact_stiffness=matched_contact_stiffness(base, exponent, force),
            )
            c = run_case(short, "offset", "physical", "healthy", p)
            dev = deviation_figures(c)
            out.append(
                {
                    "contact_exponent": exponent,
                    "camshaft_mass_kg": mass,
                    "contact_stiffness": p.get("contact_stiffness"),
                    "rise_deviation_rms_m_s2": dev["rise_rms"],
                    "return_deviation_rms_m_s2": dev["return_rms"],
                    "dwell_deviation_peak_m_s2": dev["dwell_peak"],
                    "settled": c.settle["settled"],
                }
            )
            if progress:
                progress.step(f"sensitivity n={exponent:.3g} m1={mass:g} kg")
    return out


class Progress:
    """A one-line text progress bar on stderr."""

    def __init__(self, total: int):
        self.total, self.done, self.start = total, 0, time.perf_counter()

    def step(self, label: str) -> None:
        self.done += 1
        filled = int(30 * self.done / self.total)
        line = (
            f"[{'#' * filled}{'.' * (30 - filled)}] {self.done}/{self.total} "
            f"{time.perf_counter() - self.start:5.1f} s  {label:<40s}"
        )
        # Redraw in place on a terminal; one line per step in a log.
        tty = sys.stderr.isatty()
        sys.stderr.write(("\r" + line) if tty else (line.rstrip() + "\n"))
        if tty and self.done == self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def write_csv(path: Path, header: list[str], columns) -> None:
    table = io.StringIO()
    np.savetxt(table, np.column_stack(columns), delimiter=",", header=",".join(header), comments="", fmt="%.9g")
    _files.write_text(path, table.getvalue())


def plot_kinematics(follower: TranslatingRoller, program: MotionProgram, rpm: float, path: Path) -> None:
    """SVAJ at the study's speed, pressure angle and surface curvature, and the cam profile, drawn by
    camfollower.plot for the study's follower."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from . import plot as cfplot

    fig = plt.figure(figsize=(14, 8))
    grid = fig.add_gridspec(4, 3)
    svaj_axes = [fig.add_subplot(grid[0, 0])]
    svaj_axes += [fig.add_subplot(grid[i, 0], sharex=svaj_axes[0]) for i in (1, 2, 3)]
    geometry_axes = [fig.add_subplot(grid[0:2, 1])]
    geometry_axes.append(fig.add_subplot(grid[2:4, 1], sharex=geometry_axes[0]))
    cfplot.svaj(program, rpm=rpm, axes=svaj_axes)
    cfplot.pressure_angle_and_curvature(follower, program, axes=geometry_axes)
    cfplot.profile(follower, program, ax=fig.add_subplot(grid[:, 2]))
    fig.suptitle(f"Paper cam kinematics at {rpm:g} rpm (modified trapezoid, e = {1e3 * follower.offset:g} mm)")
    fig.tight_layout()
    _files.save_figure(fig, path)


def kinematics_summary(follower: TranslatingRoller, program: MotionProgram, rpm: float) -> dict:
    """Pressure-angle extremes on the rises and on the returns (largest magnitude, sampled every
    0.001 deg, segment ends included), the tightest cam-surface radius and the peak follower
    acceleration."""
    omega = rpm * 2 * math.pi / 60
    theta = np.linspace(0, 2 * math.pi, 360001)
    d2h = program.evaluate(theta)["d2h"]
    k = int(np.argmax(np.abs(d2h)))
    alpha = np.asarray(follower.profile(program, theta)["pressure_angle"])

    def extreme(direction: float):
        inside = np.zeros(theta.size, dtype=bool)
        for seg in program.segments:
            if np.sign(seg.h_end - seg.h_start) == direction:
                inside |= (theta >= seg.theta_start) & (theta <= seg.theta_end)
        i = np.flatnonzero(inside)[int(np.argmax(np.abs(alpha[inside])))]
        return float(theta[i]), float(alpha[i])

    t_rise, a_rise = extreme(1.0)
    t_ret, a_ret = extreme(-1.0)
    t_rho, rho = follower.min_surface_radius(program)
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


def make_figures(cases: dict, carrier: float, modal: dict, bands: list, cfg: StudyConfig, folder: Path, progress):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from . import plot as cfplot

    data = folder / "data"
    data.mkdir(exist_ok=True)
    n = cfg.steps_per_revolution
    every = 4  # decimation of the time plots and their data

    def last_rev(c, x):
        return x[c.theta.size - n :][::every]

    def deg(c):
        return np.degrees(np.mod(last_rev(c, c.theta), 2 * math.pi))

    def fold(c, y):  # (deg, y) to plot: the line broken where the angle wraps (camfollower.plot)
        return cfplot.per_revolution(last_rev(c, c.theta), y)

    def save(fig, name):
        fig.tight_layout()
        _files.save_figure(fig, folder / f"{name}.png")
        progress.step(name)

    def time_panels(name, title, ylabel, panels, signal):
        """One panel per formulation; each a list of (label, case, style); the theory on acceleration."""
        fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.5), squeeze=False)
        header, cols = ["theta_deg"], [deg(panels[0][1][0][1])]
        for ax, (panel_title, series) in zip(axes[0], panels):
            for label, c, style in series:
                y = last_rev(c, signal(c))
                ax.plot(*fold(c, y), style, lw=0.8, label=label)
                header.append(f"{c.key.replace('/', '_')}")
                cols.append(y)
            if signal(series[0][1]) is series[0][1].follower_acc:
                c = series[0][1]
                ax.plot(*fold(c, last_rev(c, c.theory_acc)), "k--", lw=0.8, label="theoretical ω²h''")
            ax.set_xlabel("cam angle θ (deg)"), ax.set_ylabel(ylabel), ax.set_xlim(0, 360)
            for b in (30, 180, 210):
                ax.axvline(b, color="0.7", lw=0.6)
            ax.set_title(panel_title, fontsize=10), ax.legend(loc="best", fontsize=8), ax.grid(alpha=0.3)
        fig.suptitle(title)
        write_csv(data / f"{name}.csv", header, cols)
        save(fig, name)

    def spectrum_panels(name, title, panels, fmax=6000.0):
        fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.5), squeeze=False)
        header, cols = ["frequency_hz"], [panels[0][1][0][1].shaft_spectrum.band(0, fmax).frequency]
        for ax, (panel_title, series) in zip(axes[0], panels):
            for label, c, style in series:
                b = c.shaft_spectrum.band(0, fmax)
                ax.semilogy(b.frequency, b.amplitude, style, lw=0.8, label=label)
                header.append(c.key.replace("/", "_"))
                cols.append(b.amplitude)
            for f in modal["frequencies_hz"]:
                if f < fmax:
                    ax.axvline(f, color="tab:red", lw=0.5, ls=":")
            ax.axvline(0.4 * modal["frequencies_hz"][0], color="tab:green", lw=0.5, ls="--", label="2/5 f01")
            ax.set_xlabel("frequency (Hz)"), ax.set_ylabel("ÿ1 amplitude (m/s²)")
            ax.set_title(panel_title, fontsize=10), ax.legend(loc="best", fontsize=8), ax.grid(alpha=0.3)
        fig.suptitle(title)
        write_csv(data / f"{name}.csv", header, cols)
        save(fig, name)

    c = cases
    acc = lambda x: x.follower_acc  # noqa: E731
    force = lambda x: x.contact_force  # noqa: E731
    both = [
        ("paper formulation (paper's dampers)", [("healthy", c["offset/paper/healthy"], "-")]),
        ("physical formulation (3 % damping)", [("healthy", c["offset/physical/healthy"], "-")]),
    ]
    time_panels(
        "fig06_follower_acceleration",
        "Follower acceleration ÿ4 over one period, offset follower, healthy",
        "ÿ4 (m/s²)",
        both,
        acc,
    )
    time_panels(
        "fig07_contact_force", "Cam-roller contact force, offset follower, healthy", "contact force (N)", both, force
    )
    spectrum_panels("fig08_bearing_spectrum", "Camshaft bearing acceleration ÿ1, offset follower, healthy", both)
    fig, ax = plt.subplots(figsize=(9, 4.5))
    cols, header = [], []
    for label, key in (("paper", "offset/paper/healthy"), ("physical", "offset/physical/healthy")):
        ks = c[key].stiffness_spectrum.band(1.0, 400)
        ax.semilogy(ks.frequency, ks.amplitude, ".-", lw=0.8, label=label)
        cols += [ks.frequency, ks.amplitude] if not cols else [ks.amplitude]
        header += ["frequency_hz", f"amplitude_{label}_N_m"] if not header else [f"amplitude_{label}_N_m"]
    ax.set_xlabel("frequency (Hz)"), ax.set_ylabel("amplitude (N/m)"), ax.legend(), ax.grid(alpha=0.3)
    ax.set_title("Spectrum of the contact stiffness along the follower axis, K_h cos²α (offset, healthy)")
    write_csv(data / "fig09_contact_stiffness_spectrum.csv", header, cols)
    save(fig, "fig09_contact_stiffness_spectrum")

    for defect, (fa, ff, fs) in {"eccentricity": (10, 11, 12), "clearance": (13, 14, 15)}.items():
        literal = "K_h ε sin θ force (eq 6)" if defect == "eccentricity" else "imposed side switch"
        physical = "displaced cam centre" if defect == "eccentricity" else "gap with wall contacts"
        panels = [
            (
                f"paper formulation: {literal}",
                [(defect, c[f"offset/paper/{defect}"], "-"), ("healthy", c["offset/paper/healthy"], "-")],
            ),
            (
                f"physical formulation: {physical}",
                [(defect, c[f"offset/physical/{defect}"], "-"), ("healthy", c["offset/physical/healthy"], "-")],
            ),
        ]
        time_panels(
            f"fig{fa}_{defect}_follower_acceleration",
            f"Follower acceleration: {defect} vs healthy (offset)",
            "ÿ4 (m/s²)",
            panels,
            acc,
        )
        time_panels(
            f"fig{ff}_{defect}_contact_force",
            f"Contact force: {defect} vs healthy (offset)",
            "contact force (N)",
            panels,
            force,
        )
        spectrum_panels(
            f"fig{fs}_{defect}_bearing_spectrum", f"Bearing acceleration ÿ1: {defect} vs healthy (offset)", panels
        )

    # In-line follower: the lateral load reverses, so the rod crosses its clearance.
    panels = [
        (
            "paper formulation: imposed side switch",
            [("clearance", c["inline/paper/clearance"], "-"), ("healthy", c["inline/paper/healthy"], "-")],
        ),
        (
            "physical formulation: gap with wall contacts",
            [("clearance", c["inline/physical/clearance"], "-"), ("healthy", c["inline/physical/healthy"], "-")],
        ),
    ]
    time_panels(
        "fig16_inline_clearance_follower_acceleration",
        "In-line follower (e = 0): follower acceleration with guide clearance",
        "ÿ4 (m/s²)",
        panels,
        acc,
    )
    fig, ax = plt.subplots(figsize=(9, 4.5))
    header, cols = ["theta_deg"], [deg(c["inline/physical/clearance"])]
    for key in ("inline/physical/clearance", "offset/physical/clearance"):
        y = 1e6 * last_rev(c[key], c[key].rod_lateral)
        ax.plot(*fold(c[key], y), lw=0.8, label=key.split("/")[0])
        header.append(f"{key.split('/')[0]}_x3_um")
        cols.append(y)
    for wall in (-cfg.clearance, cfg.clearance):
        ax.axhline(1e6 * wall, color="k", lw=0.6, ls="--")
    ax.set_xlabel("cam angle θ (deg)"), ax.set_ylabel("rod lateral position x3 (µm)"), ax.set_xlim(0, 360)
    ax.set_title(f"The rod in its guide (walls at ±{1e6 * cfg.clearance:g} µm), physical formulation")
    ax.legend(), ax.grid(alpha=0.3)
    write_csv(data / "fig17_rod_in_guide.csv", header, cols)
    save(fig, "fig17_rod_in_guide")

    fig, ax = plt.subplots(figsize=(9, 4.5))
    rows = []
    for key, case in c.items():
        h = case.settle["history"]
        ax.semilogy(np.arange(2, len(h) + 2), h, lw=0.8, ls="-" if "physical" in key else "--", label=key)
        rows += [(key, i + 2, v) for i, v in enumerate(h)]
    ax.axhline(cfg.settle_tolerance, color="k", lw=0.6)
    ax.set_xlabel("revolution"), ax.set_ylabel("max |Δÿ4| / max |ÿ4| vs the previous revolution")
    (
        ax.set_title("Settling to the periodic response (black: tolerance)"),
        ax.legend(fontsize=6, ncol=2),
        ax.grid(alpha=0.3),
    )
    _files.write_text(
        data / "fig18_settling.csv", "case,revolution,change\n" + "".join(f"{k},{i},{v:.9g}\n" for k, i, v in rows)
    )
    save(fig, "fig18_settling")

    fig, ax = plt.subplots(figsize=(9, 4.5))
    for exponent in cfg.contact_exponents:
        sel = [b for b in bands if b["contact_exponent"] == exponent]
        m = [b["camshaft_mass_kg"] for b in sel]
        ax.plot(m, [b["rise_deviation_rms_m_s2"] for b in sel], "o-", label=f"rise, n = {exponent:.3g}")
        ax.plot(m, [b["return_deviation_rms_m_s2"] for b in sel], "s--", label=f"return, n = {exponent:.3g}")
    ax.set_xscale("log"), ax.set_xlabel("camshaft mass (kg)"), ax.set_ylabel("RMS of ÿ4 − ω²h'' (m/s²)")
    ax.set_title("Rise vs return vibration over what the paper does not give (offset, physical, healthy)")
    ax.legend(fontsize=8), ax.grid(alpha=0.3)
    keys = list(bands[0])
    _files.write_text(
        data / "fig19_sensitivity.csv",
        ",".join(keys)
        + "\n"
        + "".join(
            ",".join(f"{b[k]:.9g}" if isinstance(b[k], float) else str(b[k]) for k in keys) + "\n" for b in bands
        ),
    )
    save(fig, "fig19_sensitivity")


FIGURES = 14  # make_figures' progress steps


def run_study(cfg: StudyConfig, out: Path, figures: bool = True) -> dict:
    """Run every case and the sensitivity bands, write figures, data and summary.json into `out`."""
    cfg.validate()
    # Every file goes atomically into place (camfollower._files); summary.json, removed now and
    # written last, marks a complete run.
    out = _files.output_folder(out)
    bands_count = len(cfg.camshaft_masses) * len(cfg.contact_exponents)
    progress = Progress(
        len(FOLLOWERS) * len(FORMULATIONS) * len(DEFECTS) + bands_count + 1 + (FIGURES if figures else 0)
    )
    cases = run_cases(cfg, progress)
    bands = sensitivity(cfg, progress)
    healthy = cases["offset/physical/healthy"]
    modal = healthy.model.modal_analysis(0.0)
    carrier = an.find_peaks(healthy.shaft_spectrum, 1, lo=50.0)[0][0]
    g = parameters(cfg, "offset")
    roller, program = TranslatingRoller(g.base_radius, g.roller_radius, g.offset), MotionProgram.paper_default()
    summary = {
        "rpm": cfg.rpm,
        "shaft_frequency_hz": cfg.rpm / 60.0,
        "time_step_s": healthy.period / cfg.steps_per_revolution,
        "analysed_revolutions": cfg.analysed_revolutions,
        "settle_tolerance": cfg.settle_tolerance,
        "max_revolutions_to_settle": cfg.max_revolutions,
        "spectral_resolution_hz": cfg.rpm / 60.0 / cfg.analysed_revolutions,
        "eccentricity_m": cfg.eccentricity,
        "clearance_m": cfg.clearance,
        "damping_ratio_physical": cfg.damping_ratio,
        "kinematics": kinematics_summary(roller, program, cfg.rpm),
        "natural_frequencies_hz_dwell": [float(f) for f in modal["frequencies_hz"]],
        "paper_table3_hz": [2447, 2447, 5711, 12777, 13990, 17009, 17009],
        "carrier_hz": carrier,
        "cases": {key: summarize(c, carrier) for key, c in cases.items()},
        "sensitivity": bands,
    }
    for key, c in summary["cases"].items():
        follower, formulation, defect = key.split("/")
        if defect != "healthy":
            lines = summary["cases"][f"{follower}/{formulation}/healthy"]["shaft_acceleration_sidebands"]["levels"]
            c["shaft_acceleration_sidebands"]["defect_modulation"] = defect_modulation(
                c["shaft_acceleration_sidebands"]["levels"], lines
            )
    progress.step("analysed")

    if figures:
        plot_kinematics(roller, program, cfg.rpm, out / "kinematics.png")
        make_figures(cases, carrier, modal, bands, cfg, out, progress)
    export.write_csv(out / "cam_surface.csv", roller, program)
    _files.write_text(out / "summary.json", _files.json_text(summary))
    return summary


def print_summary(summary: dict) -> None:
    k = summary["kinematics"]
    print(
        f"\npaper cam at {summary['rpm']:g} rpm (offset follower): max |pressure angle| rise "
        f"{abs(k['max_pressure_angle_rise_deg']):.2f} deg, return {abs(k['max_pressure_angle_return_deg']):.2f} deg; "
        f"peak theoretical follower acceleration {k['max_theoretical_follower_acceleration_m_s2']:.2f} m/s^2"
    )
    print(
        "natural frequencies on the dwell (Hz): "
        + ", ".join(f"{f:.0f}" for f in summary["natural_frequencies_hz_dwell"])
    )
    print(
        f"\n{'case':30s} {'settled':>8s} {'revs':>5s} {'change':>8s} {'peak a4':>9s} {'dwell':>7s} {'rise':>6s} "
        f"{'return':>6s} {'Fc min':>7s} {'Fc max':>8s} {'loss/rev':>8s} {'mod.':>7s} {'impacts':>7s}"
    )
    for key, c in summary["cases"].items():
        s = c["settle"]
        lo, hi = c["contact_force_range_N"]
        impacts = c.get("guide_clearance", {}).get("impacts_per_revolution", float("nan"))
        print(
            f"{key:30s} {str(s['settled']):>8s} {s['revolutions']:5d} {s['change']:8.1e} "
            f"{c['peak_follower_acceleration_m_s2']:9.1f} {c['dwell_deviation_peak_m_s2']:7.2f} "
            f"{c['rise_deviation_rms_m_s2']:6.2f} {c['return_deviation_rms_m_s2']:6.2f} {lo:7.1f} {hi:8.1f} "
            f"{round(c['contact_loss_time_per_revolution_s'], 12) + 0.0:8.1e} "  # rounding noise of 0 s: 0
            f"{c['shaft_acceleration_sidebands'].get('defect_modulation', 0.0):7.4f} {impacts:7.1f}"
        )
    print(
        "  (m/s^2 and N; settled/revs/change: periodic steady state reached, revolutions to reach it, last relative\n"
        "   change of a4; dwell = peak |a4 - omega^2 h''| on the dwells, rise/return = its RMS; mod. = added\n"
        f"   modulation of the camshaft-bearing acceleration around {summary['carrier_hz']:.1f} Hz; impacts per revolution of the rod on its guide walls)"
    )
    print("sensitivity (offset, physical, healthy): rise / return RMS deviation (m/s^2)")
    for b in summary["sensitivity"]:
        print(
            f"  n = {b['contact_exponent']:.3g}, camshaft {b['camshaft_mass_kg']:g} kg: "
            f"{b['rise_deviation_rms_m_s2']:.2f} / {b['return_deviation_rms_m_s2']:.2f}"
        )


def main(argv: list[str] | None = None, prog: str = "camfollower study") -> int:
    parser = argparse.ArgumentParser(prog=prog, description=__doc__.splitlines()[0].replace("``", ""))
    d = StudyConfig()
    parser.add_argument("-o", "--out", default="out", help="output folder (created if missing); default: out")
    parser.add_argument("--rpm", type=float, default=d.rpm, help=f"camshaft speed (rpm); default {d.rpm:g}")
    parser.add_argument(
        "--eccentricity", type=float, default=d.eccentricity, help="cam centre offset (m); default 10e-6"
    )
    parser.add_argument(
        "--clearance", type=float, default=d.clearance, help="radial guide clearance (m); default 10e-6"
    )
    parser.add_argument(
        "--backlash-switch-width",
        type=float,
        default=d.backlash_switch_width_deg,
        help=f"paper formulation: cam angle of the imposed side switch (deg); default {d.backlash_switch_width_deg:g}",
    )
    parser.add_argument(
        "--damping-ratio",
        type=float,
        default=d.damping_ratio,
        help=f"physical formulation: modal damping of the lowest modes; default {d.damping_ratio:g}",
    )
    parser.add_argument(
        "--analysed-revolutions",
        type=int,
        default=d.analysed_revolutions,
        help=f"revolutions analysed after settling; default {d.analysed_revolutions}",
    )
    parser.add_argument(
        "--max-revolutions",
        type=int,
        default=d.max_revolutions,
        help=f"at most this many revolutions to settle; default {d.max_revolutions}",
    )
    parser.add_argument(
        "--steps-per-revolution",
        type=int,
        default=d.steps_per_revolution,
        help=f"time steps per revolution; default {d.steps_per_revolution}",
    )
    parser.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    args = parser.parse_args(argv)
    cfg = StudyConfig(
        rpm=args.rpm,
        eccentricity=args.eccentricity,
        clearance=args.clearance,
        backlash_switch_width_deg=args.backlash_switch_width,
        damping_ratio=args.damping_ratio,
        analysed_revolutions=args.analysed_revolutions,
        max_revolutions=args.max_revolutions,
        steps_per_revolution=args.steps_per_revolution,
    )
    out = Path(args.out)
    try:
        cfg.validate()
        _files.check_name(args.out, "--out")
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
