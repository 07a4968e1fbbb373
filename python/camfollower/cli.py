# SPDX-License-Identifier: BSD-3-Clause
"""The ``camfollower`` command (installed by ``pip install``; also ``python -m camfollower``): one
front door for every verb, each working on a config file (docs/config.md).

- ``kinematics [CONFIG] [--rpm RPM]``: per contact, the largest pressure angle, the smallest convex
  cam-surface radius, the lift range and the rigid follower's peak velocity and acceleration;
- ``modes [CONFIG] [--theta DEG] [--count N]``: natural frequencies, contacts linearized at a cam angle
  (without CONFIG both describe the paper's mechanism);
- ``run CONFIG [-o FILE]``: simulate the case, every recorded channel as CSV;
- ``export CONFIG -o FILE [--contact NAME] [--unit mm] [--cutter-radius R] [--points N] [--roller R]``:
  the cam surface (and cutter-centre path) for manufacturing, CSV, or DXF when FILE ends in ``.dxf``
  (a barrel cam: its groove walls and 4-axis machining path); ``--ecam table|segments|twincat``: the
  lift program for a servo drive instead (camfollower.ecam);
- ``figures``, ``camshaft``, ``sweep``, ``montecarlo CONFIG [-o DIR]``: the recorded channels, figures
  and ``summary.json`` of a run, a camshaft at several speeds, a speed sweep with the jump speed, a
  Monte-Carlo tolerance study;
- ``synthesize CONFIG [-o DIR] [--rpm ...] [--band F]``: a lift designed for the flexible mechanism
  (camfollower.synthesis, the config's [synthesis] table);
- ``design [CONFIG] [--port N] [--no-browser]``: the design page on 127.0.0.1 (camfollower.design): edit
  the cam and mechanism in the browser, the flexible response redrawn at each edit;
- ``study [--out DIR] ...``: the paper's study (healthy / eccentricity / clearance) on its default case.

``-o`` names what the verb writes: the file for the verbs that write one (``run``, ``export``), the
folder for the others (default ``./out``). Every file is written to a temporary name and renamed (the
library's atomic writer), so a failed run leaves no half-written file; the config is never
overwritten or removed. Every command-line argument is checked before anything runs; an error is one
line ``camfollower: error: ...`` (exit status 1; 2 for a command line that cannot be read). The C++
program ``camfollower`` (built with ``-DCAMFOLLOWER_BUILD_CLI=ON`` for C++-only installs) offers
``kinematics``, ``modes``, ``run`` and ``export`` with the same names and options.
"""

from __future__ import annotations

import argparse
import io
import math
import os
import re
import sys
import warnings
from pathlib import Path

import numpy as np

from . import _files, _text
from .config import ForceClosureWarning, force_closure, load_config
from .executors import _check_scheduler
from .response import STUDY_ACCURACY
from .speed import _MAX_RPM, _MIN_RPM


def _write(config: str, path: Path, content: bytes) -> None:
    """The package's one atomic writer (camfollower._files), never over the config file."""
    _files.write_bytes(path, content, protect=[config])


def _save(config: str, fig, path: Path) -> None:
    _files.save_figure(fig, path, protect=[config])


def _load(config: str):
    """load_config, its force-closure warnings left to _closure (printed as the commands' own lines)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ForceClosureWarning)
        return load_config(config)


def _closure(case, rpm=None) -> list:
    """The case's force-closure warnings at `rpm` (default: the config's speed), each printed on stderr
    as ``camfollower: warning: ...``; the summary's ``warnings`` list (docs/config.md, "Force closure")."""
    found = list(case.warnings) if rpm is None else list(case.force_closure(rpm)["warnings"])
    for w in found:
        print(f"camfollower: warning: {_message(w)}", file=sys.stderr)
    return found


def _folder(config: str, out: str) -> Path:
    """The output folder, its old summary.json removed unless that is the config (or links to it)."""
    return _files.output_folder(out, "--out", protect=[config])


def _speeds(values, option: str, engine: bool = False) -> list:
    """Speeds (rpm) given as `option`, each finite and within the model's camshaft speeds (an engine
    turns twice as fast as its camshaft)."""
    factor = 2.0 if engine else 1.0
    lo, hi = factor * _MIN_RPM, factor * _MAX_RPM
    for v in values:
        if not (math.isfinite(v) and lo <= v <= hi):
            raise ValueError(
                f"{option}: {v:g} is not {'an engine' if engine else 'a camshaft'} speed in [{lo:.6g}, {hi:.6g}] rpm"
            )
    return [float(v) for v in values]


def _integer(value, option: str, lo: int, hi: int) -> None:
    if not lo <= value <= hi:
        raise ValueError(f"{option}: {value} is not in [{lo}, {hi}]")


_MAX_REVOLUTIONS = 1e6  # camshaft revolutions per speed: far beyond any study, far below the step cap


def check_arguments(args: argparse.Namespace) -> None:
    """Every command-line argument, checked before the config is read or anything runs; ValueError
    naming the option as typed on the command line and what it accepts."""
    if args.config is not None:
        _files.check_name(args.config, "config")
    if getattr(args, "out", None) is not None:
        _files.check_name(args.out, "--out")
        if not args.out:
            raise ValueError("--out: must name a folder, got an empty string")
    if getattr(args, "contact", None) is not None and not args.contact:
        raise ValueError("--contact: must name a contact of the config, got an empty string")
    if getattr(args, "output", None) is not None:
        _files.check_name(args.output, "-o/--output")
        if not args.output:
            raise ValueError("-o/--output: must name a file, got an empty string")
    if args.command == "kinematics" and args.rpm is not None:
        _speeds([args.rpm], "--rpm")
    if args.command == "modes":
        if not (math.isfinite(args.theta) and abs(args.theta) <= 1e6):
            raise ValueError(f"--theta: {args.theta:g} is not a cam angle in [-1e6, 1e6] deg")
        if args.count is not None:
            _integer(args.count, "--count", 1, 100_000)
    if args.command == "export":
        from . import _core

        units = _core.length_units()
        if args.unit not in units:
            raise ValueError(f"--unit: {args.unit!r} is not one of {', '.join(units)}")
        most = _core.MAX_PART_LENGTH / units[args.unit]
        if not (math.isfinite(args.cutter_radius) and 0.0 <= args.cutter_radius <= most):
            raise ValueError(f"--cutter-radius: {args.cutter_radius:g} is not a radius in [0, {most:g}] {args.unit}")
        _integer(args.points, "--points", 8, _core.MAX_POINTS)
    if args.command == "camshaft":
        if args.rpm and args.engine_rpm:
            raise ValueError("give --rpm (camshaft) or --engine-rpm (twice the camshaft's), not both")
        _speeds(args.rpm or [], "--rpm")
        _speeds(args.engine_rpm or [], "--engine-rpm", engine=True)
        if not (math.isfinite(args.revolutions) and 0 < args.revolutions <= _MAX_REVOLUTIONS):
            raise ValueError(
                f"--revolutions: {args.revolutions:g} is not a number of camshaft revolutions in "
                f"(0, {_MAX_REVOLUTIONS:g}]"
            )
    if args.command == "sweep":
        _speeds(args.rpm or [], "--rpm")
        if args.jump:
            lo, hi = _speeds(args.jump, "--jump")
            if not lo < hi:
                raise ValueError(f"--jump: LO {lo:g} must be below HI {hi:g} rpm")
    if args.command == "design":
        _integer(args.port, "--port", 0, 65535)
    if args.command == "synthesize":
        _speeds(args.rpm or [], "--rpm")
        if args.rpm and args.band is not None:
            raise ValueError("give --rpm (the speeds, design first) or --band (around the config's speed), not both")
        if args.band is not None and not (math.isfinite(args.band) and 0.0 <= args.band < 1.0):
            raise ValueError(f"--band: {args.band:g} is not a fraction of the design speed in [0, 1)")
        if args.workers is not None:
            _integer(args.workers, "--workers", 1, 64)
    if args.command in ("sweep", "montecarlo"):
        if args.workers is not None:
            _integer(args.workers, "--workers", 1, 1 << 20)
        if args.scheduler is not None:
            if not args.scheduler.strip():
                raise ValueError("--scheduler: give a Dask scheduler address (tcp://host:8786) or dask:N")
            _check_scheduler(args.scheduler, "--scheduler")
            if args.workers is not None:
                raise ValueError("give --workers (a local process pool) or --scheduler (a Dask scheduler), not both")
    if args.command == "montecarlo":
        if args.rpm is not None:
            _speeds([args.rpm], "--rpm")
        if args.cases is not None:
            _integer(args.cases, "--cases", 1, 10_000_000)
        if args.seed is not None:
            _integer(args.seed, "--seed", 0, 2**63 - 1)


def _groove_clearance(contact: dict) -> float:
    """A contact's groove clearance (m), 0 without a groove."""
    return contact["groove"].clearance if contact.get("groove") is not None else 0.0


def figures(config: str, out: str) -> dict:
    """Run the case in `config` and write its CSV, figures and summary into `out`; return the summary."""
    import matplotlib

    matplotlib.use("Agg")
    from . import export, plot

    case = _load(config)
    closure = _closure(case)
    folder = _folder(config, out)
    m = case.mechanism
    rpm = m.camshaft_speed_rpm
    result = case.run()
    _write(config, folder / "run.csv", _recording_csv(result))
    written = ["run.csv"]
    contacts = case.builder.contacts
    summary = {
        "config": str(case.path),
        "camshaft_speed_rpm": rpm,
        "rows": result.rows,
        "drive": {
            "peak_torque_N_m": float(np.abs(result["drive.torque"]).max()),
            "peak_power_W": float(np.abs(result["drive.power"]).max()),
        },
        "time_step_s": result.time_step,
        "contacts": {},
    }
    omega = m.omega
    for c in contacts:
        name, program, follower, dof = c["name"], c["program"], c["follower"], c["follower_dof"]
        angular = not follower.translating  # the lift is the arm's rotation (rad)
        for fig, file in (
            (plot.svaj(program, rpm=rpm, angular=angular), f"svaj_{name}.png"),
            (
                (plot.groove(follower, program, clearance=_groove_clearance(c)), f"groove_{name}.png")
                if export.is_barrel(follower)
                else (plot.profile(follower, program), f"profile_{name}.png")
            ),
            (plot.pressure_angle_and_curvature(follower, program), f"pressure_angle_curvature_{name}.png"),
            (
                plot.acceleration(
                    result,
                    program,
                    omega,
                    dof,
                    phase=c["phase"],
                    unit="rad/s²" if angular else "m/s²",
                    speed_program=m.speed_program,
                ),
                f"acceleration_{name}.png",
            ),
            (plot.contact_force(result, name), f"contact_force_{name}.png"),
        ):
            _save(config, fig, folder / file)
            written.append(file)
        force = np.asarray(result[f"{name}.force"])
        sample_rate = 1.0 / (result.time_step * result.decimation)
        fmax = min(0.5 * sample_rate, 20000.0)
        naturals = list(m.modal_analysis(0.0)["frequencies_hz"])
        _save(
            config,
            plot.spectrum(
                force - force.mean(),
                sample_rate,
                fmax=fmax,
                natural_frequencies=naturals,
                quantity=f"{name} contact force",
                unit="N",
            ),
            folder / f"spectrum_{name}.png",
        )
        written.append(f"spectrum_{name}.png")
        lost = sum(b - a for a, b in result.contact_loss.get(name, []))
        theta = np.linspace(0.0, 2 * math.pi, 7201)
        rigid = omega**2 * np.asarray(program.evaluate(theta)["d2h"])
        summary["contacts"][name] = {
            "follower": type(follower).__name__,
            "max_force_N": float(force.max()),
            "min_force_N": float(force.min()),
            "contact_lost_s": float(lost),
            "contact_events": sum(1 for _, event, _ in result.events if event == f"{name}.contact"),
            "max_abs_acceleration": float(np.abs(np.asarray(result[f"a.{dof}"])).max()),
            "max_abs_rigid_acceleration": float(np.abs(rigid).max()),
            "max_abs_pressure_angle_deg": float(np.degrees(abs(follower.max_pressure_angle(program)[1]))),
            "min_convex_surface_radius_mm": float(1e3 * follower.min_surface_radius(program)[1]),
        }
    summary["files"] = written + ["summary.json"]
    summary["warnings"] = closure
    _write(config, folder / "summary.json", _files.json_text(summary).encode())
    return summary


def camshaft(config: str, out: str, rpm=None, engine_rpm=None, revolutions: float = 2.0) -> dict:
    """A flexible camshaft at several speeds (camfollower.camshaft): summary.csv (one row per speed and
    cam), study.png (the figures against speed), traces_<rpm>rpm.png per speed, summary.json last."""
    import matplotlib

    matplotlib.use("Agg")
    from .camshaft import camshaft_study, plot_study, plot_traces

    if rpm and engine_rpm:
        raise ValueError("give --rpm (camshaft) or --engine-rpm (twice the camshaft's), not both")
    # Checked as given, before the halving: a bad engine speed is named as the engine speed.
    speeds = (
        _speeds(rpm, "--rpm")
        if rpm
        else [0.5 * e for e in _speeds(engine_rpm, "--engine-rpm", engine=True)]
        if engine_rpm
        else None
    )
    case = _load(config)
    closure = _closure(case, max(speeds) if speeds else None)
    folder = _folder(config, out)
    summaries, results = camshaft_study(case, speeds, revolutions=revolutions)
    written = []
    rows = [
        "camshaft_rpm,cam,lift_error_mm,max_force_N,min_force_lifting_N,contact_lost_s,twist_peak_to_peak_deg,"
        "surge_peak_to_peak_mm,surge_main_frequency_Hz"
    ]
    for s in summaries:
        for cam, c in s["cams"].items():
            rows.append(
                ",".join(
                    [f"{s['camshaft_speed_rpm']:.6g}", cam]
                    + [
                        f"{c.get(k, float('nan')):.6g}"
                        for k in (
                            "lift_error_mm",
                            "max_force_N",
                            "min_force_lifting_N",
                            "contact_lost_s",
                            "twist_peak_to_peak_deg",
                            "surge_peak_to_peak_mm",
                            "surge_main_frequency_Hz",
                        )
                    ]
                )
            )
    _write(config, folder / "summary.csv", ("\n".join(rows) + "\n").encode())
    written.append("summary.csv")
    _save(config, plot_study(summaries, engine=bool(engine_rpm)), folder / "study.png")
    written.append("study.png")
    for s, r in zip(summaries, results):
        m = case.mechanism.with_camshaft_speed_rpm(s["camshaft_speed_rpm"])
        file = f"traces_{s['camshaft_speed_rpm']:g}rpm.png"
        _save(config, plot_traces(m, r), folder / file)
        written.append(file)
    summary = {"config": str(case.path), "speeds": summaries, "files": written + ["summary.json"]}
    summary["warnings"] = closure
    _write(config, folder / "summary.json", _files.json_text(summary).encode())
    return summary


# The paper's mechanism at 750 rpm: what kinematics and modes describe without a config (as the C++ program).
_PAPER_CASE = {"camshaft": {"speed": 750}, "preset": {"name": "paper"}}


def _case_or_paper(config):
    from .config import config_from_dict

    return _load(config) if config else config_from_dict(_PAPER_CASE)


def _origin(case) -> str:
    return str(case.path) if case.path else "<paper preset>"


def _peak(program, key: str):
    """(|value|, theta) of the largest |d/dtheta| derivative `key` of the lift over a revolution: a
    0.01 deg grid with the segment boundaries, then golden-section search between the best sample's
    neighbours (sizing's, as the C++ program's maximize_piecewise)."""
    from .sizing import _golden

    theta = np.union1d(np.linspace(0.0, 2 * math.pi, 36001), [s.theta_start for s in program.segments])
    values = np.abs(np.asarray(program.evaluate(theta)[key]))
    k = int(np.argmax(values))
    best = (float(values[k]), float(theta[k]))

    def f(t):
        return float(np.abs(np.asarray(program.evaluate(np.array([t]))[key]))[0])

    lo, hi = float(theta[max(k - 1, 0)]), float(theta[min(k + 1, len(theta) - 1)])
    t = _golden(lambda x: -f(x), lo, hi, 1e-9 * (hi - lo))
    return max(best, (f(t), t))


def _spans(intervals) -> str:
    """Cam-angle intervals (deg) as the C++ command prints them: "30.0-89.5, 270.5-330.0", or "no"."""
    return ", ".join(f"{a:.1f}-{b:.1f}" for a, b in intervals) or "no"


def kinematics(config, rpm=None) -> list:
    """Print the kinematic checks of every contact of `config` (the paper preset without one) at `rpm`
    (default: the config's); return them as dicts (SI units, angles in degrees)."""
    case = _case_or_paper(config)
    rpm = rpm or case.mechanism.camshaft_speed_rpm
    omega = rpm * 2 * math.pi / 60.0
    print(f"{_origin(case)} at {rpm:.6g} rpm")
    rows = []
    closure = force_closure(case.builder, rpm)["contacts"]
    for i, c in enumerate(case.builder.contacts):
        # The check reports no contact when it could not run (a static equilibrium not found).
        closed = closure[i] if i < len(closure) else None
        follower, program = c["follower"], c["program"]
        translating = follower.translating
        alpha_at, alpha = follower.max_pressure_angle(program)
        rho_at, rho = follower.min_surface_radius(program)
        velocity, velocity_at = _peak(program, "dh")
        acceleration, acceleration_at = _peak(program, "d2h")
        row = {
            "contact": c["name"],
            "follower": type(follower).__name__,
            "max_abs_pressure_angle_deg": abs(math.degrees(alpha)),
            "at_deg": math.degrees(alpha_at),
            "min_convex_surface_radius_m": rho,
            "radius_at_deg": math.degrees(rho_at),
            "lift_min": program.min_lift(),
            "lift_max": program.max_lift(),
            "max_abs_velocity": omega * velocity,
            "velocity_at_deg": math.degrees(velocity_at),
            "max_abs_acceleration": omega**2 * acceleration,
            "acceleration_at_deg": math.degrees(acceleration_at),
        }
        rows.append(row)
        # Lengths in mm, arm angles in degrees, as the C++ program prints them.
        lift_unit, lift_scale = ("mm", 1e3) if translating else ("deg", 180.0 / math.pi)
        rate = "m/s" if translating else "rad/s"
        print(f"contact '{c['name']}': {re.sub(r'(?<!^)(?=[A-Z])', '_', row['follower']).lower()} follower")
        print(
            f"  max |pressure angle|:                {row['max_abs_pressure_angle_deg']:.4f} deg at theta = "
            f"{row['at_deg']:.3f} deg"
        )
        print(f"  min convex cam-surface radius:       {1e3 * rho:.4f} mm at theta = {row['radius_at_deg']:.3f} deg")
        print(
            f"  lift range:                          {lift_scale * row['lift_min']:.6g} to "
            f"{lift_scale * row['lift_max']:.6g} {lift_unit}"
        )
        print(
            f"  max |follower velocity| (rigid):     {row['max_abs_velocity']:.6g} {rate} at theta = "
            f"{row['velocity_at_deg']:.3f} deg"
        )
        print(
            f"  max |follower acceleration| (rigid): {row['max_abs_acceleration']:.6g} {rate}^2 at theta = "
            f"{row['acceleration_at_deg']:.3f} deg"
        )
        if c["groove"] is not None and closed:  # where the rigid check puts the roller on the outer flank (as C++)
            row["groove_clearance"] = c["groove"].clearance
            row["outer_flank_deg"] = closed["outer_flank_deg"]
            row["flank_changes"] = closed["flank_changes"]
            print(
                f"  groove clearance {1e3 * c['groove'].clearance:.6g} mm: outer flank carries the roller (rigid) "
                f"over {_spans(closed['outer_flank_deg'])} deg, {closed['flank_changes']} flank changes per revolution"
            )
        if closed and "conjugate" in closed:  # conjugate cams: where the rigid check puts the load on the other cam
            row["conjugate"] = closed["conjugate"]
            row["other_cam_deg"] = closed["other_cam_deg"]
            row["flank_changes"] = closed["flank_changes"]
            print(
                f"  conjugate to '{closed['conjugate']}', which carries the load (rigid) over "
                f"{_spans(closed['other_cam_deg'])} deg, "
                f"{closed['flank_changes']} changes of cam per revolution"
            )
    return rows


def modes(config, theta_deg: float = 0.0, count=None) -> list:
    """Print the natural frequencies of `config`'s mechanism (the paper preset without one), contacts
    linearized at the static equilibrium at camshaft angle `theta_deg`; all of a small model, the
    lowest `count` (default 20) of one above 200 DOFs. Return (frequency in Hz, DOF moving most)."""
    case = _case_or_paper(config)
    m = case.mechanism
    n = len(m.dof_names)
    wanted = min(count or (20 if n > 200 else n), n)
    frequencies, shapes = m.lowest_modes(math.radians(theta_deg), wanted)
    part = f" (lowest {len(frequencies)} of {n})" if len(frequencies) < n else ""
    print(
        f"{_origin(case)}: natural frequencies (Hz), contacts linearized at the static equilibrium, "
        f"theta = {theta_deg:g} deg{part}"
    )
    out = []
    for k, f in enumerate(np.asarray(frequencies).ravel()):
        dof = m.dof_names[int(np.argmax(np.abs(np.asarray(shapes)[:, k])))]
        print(f"mode {k + 1:<3d} {f:14.2f}   largest motion: {dof}")
        out.append((float(f), dof))
    return out


def _recording_csv(result) -> bytes:
    names = result.channels
    data = np.column_stack([np.asarray(result[n]) for n in names])
    table = io.StringIO()
    np.savetxt(table, data, delimiter=",", header=",".join(names), comments="", fmt="%.12g")
    return table.getvalue().encode()


def run(config: str, output=None) -> dict:
    """Simulate the case in `config` and write every recorded channel as CSV to `output` (default: the
    config's ``[output] file``, relative to the working directory); return what was done."""
    case = _load(config)
    closure = _closure(case)
    target = output or case.output.get("file")
    if not target:
        raise ValueError(f"{config}: no output file: set [output] file or give -o FILE")
    path = Path(target)  # relative to the working directory (docs/config.md), as in the C++ program
    _files.check_name(str(path), "-o/--output" if output else "[output] file")
    _files.check_target(path, protect=[config])
    result = case.run()
    _write(config, path, _recording_csv(result))
    lost = {name: float(sum(b - a for a, b in spans)) for name, spans in result.contact_loss.items()}
    summary = {
        "rows": result.rows,
        "channels": len(result.channels),
        "method": result.stats["method"],
        "steps": result.stats["steps"],
        "contact_lost_s": lost,
        "events": len(result.events),
        "file": str(path),
        "warnings": closure,
    }
    losses = "".join(f", '{k}' lost contact {_text.g(v, 4)} s" for k, v in lost.items() if v > 0.0)
    print(
        f"{summary['rows']} rows, {summary['channels']} channels ({summary['method']}: {summary['steps']} steps)"
        f"{losses}, {summary['events']} contact losses and re-contacts located -> {path}"
    )
    if "method_choice" in result.stats:
        print(f"method auto took {result.stats['method_choice']}")
    if "velocity_choice" in result.stats:
        print(result.stats["velocity_choice"])
    return summary


def export(
    config: str,
    output: str,
    contact=None,
    unit: str = "mm",
    cutter_radius: float = 0.0,
    points: int = 3600,
    roller: str = "cylindrical",
    ecam=None,
) -> dict:
    """Write the cam of `contact` (default: the first) in `config` for manufacturing: CSV, or DXF when
    `output` ends in ``.dxf``; `cutter_radius` in `unit` (0: no cutter path). A barrel cam's groove
    instead, for a `roller` "cylindrical" or "tapered" (its cutter is shaped as the roller). With
    `ecam` ("table", "segments" or "twincat") the contact's lift program for a servo drive instead
    (camfollower.ecam; the slave in `unit`, deg for an arm)."""
    from . import _core
    from . import export as ex

    units = _core.length_units()
    if unit not in units:
        raise ValueError(f"--unit must be one of {', '.join(units)}, got {unit!r}")
    case = _load(config)
    contacts = case.builder.contacts
    names = [c["name"] for c in contacts]
    name = contact or (names[0] if names else None)
    if name not in names:
        raise ValueError(f"--contact: no contact named {name!r}; the config defines: {', '.join(names) or 'none'}")
    c = contacts[names.index(name)]
    _files.check_name(output, "-o/--output")
    cutter = cutter_radius * units[unit] if cutter_radius else None
    dxf = output.lower().endswith(".dxf")
    _files.check_target(output, protect=[config])
    if ecam is not None:
        return _export_ecam(output, name, c, ecam, unit, cutter, points)
    if ex.is_barrel(c["follower"]):
        # A barrel cam: its groove, cut by a cutter shaped as the roller (the contact's groove sets the width).
        if cutter:
            raise ValueError(
                f"--cutter-radius: contact '{name}' is a barrel cam, cut by a cutter shaped as its roller (the "
                "machining path in the file); leave --cutter-radius out"
            )
        clearance = _groove_clearance(c)
        (ex.write_groove_dxf if dxf else ex.write_groove_csv)(
            output, c["follower"], c["program"], points=points, clearance=clearance, roller=roller, unit=unit
        )
        print(
            f"contact '{name}': {points} cam angles of the barrel cam's groove and machining path in {unit} -> {output}"
        )
        return {"contact": name, "points": points, "unit": unit, "file": output, "format": "dxf" if dxf else "csv"}
    (ex.write_dxf if dxf else ex.write_csv)(
        output,
        c["follower"],
        c["program"],
        points=points,
        cutter_radius=cutter,
        unit=unit,
        frame_angle=c["frame_angle"],
    )
    print(
        f"contact '{name}': {points} points of the cam surface{' and the cutter-centre path' if cutter else ''} "
        f"in {unit} -> {output}"
    )
    return {"contact": name, "points": points, "unit": unit, "file": output, "format": "dxf" if dxf else "csv"}


def _export_ecam(output, name, contact, kind, unit, cutter, points) -> dict:
    """The contact's lift program as an electronic cam file (export --ecam)."""
    from . import ecam

    if cutter:
        raise ValueError("--cutter-radius: an electronic cam table holds the lift, not the cam's outline; leave it out")
    rotary = not getattr(contact["follower"], "translating", True)
    slave = "deg" if rotary else unit
    if not rotary and unit not in ecam.LENGTH_UNITS:
        raise ValueError(
            f"--unit: an electronic cam table's slave unit is one of {', '.join(ecam.LENGTH_UNITS)}, got {unit!r}"
        )
    program = contact["program"]
    if kind == "table":
        ecam.write_table_csv(output, program, points=points, slave_unit=slave, rotary=rotary)
    elif kind == "segments":
        ecam.write_segment_list(output, program, slave_unit=slave, rotary=rotary)
    else:
        ecam.write_twincat_cnc_table(output, program, points=points, rotary=rotary)
    what = {"table": f"{points} master positions", "segments": "the segment list", "twincat": f"{points} lines"}
    print(f"contact '{name}': the lift program as an electronic cam ({kind}: {what[kind]}) -> {output}")
    return {"contact": name, "file": output, "format": f"ecam-{kind}"}


def _csv(rows, columns) -> bytes:
    import csv

    buffer = io.StringIO()
    w = csv.DictWriter(buffer, fieldnames=columns, extrasaction="ignore", lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in r.items() if k in columns})
    return buffer.getvalue().encode()


def _executor(args):
    if args.scheduler and args.workers:
        raise ValueError("give --workers (a local process pool) or --scheduler (a Dask scheduler), not both")
    if args.scheduler:
        return args.scheduler
    return "serial" if args.workers == 1 else None


def sweep(config: str, out: str, *, rpm=None, jump=None, executor=None, workers=None, progress=True) -> dict:
    """The config's mechanism over a speed range (camfollower.speed): sweep.csv (one row per speed),
    spectrum.csv (contact-force shaft orders per speed), margin.png, waterfall.png, summary.json last."""
    import matplotlib

    matplotlib.use("Agg")
    from . import speed as sp
    from .studies import sweep_settings

    case = _load(config)
    st = sweep_settings(
        case.data.get("sweep", {}), rpm=rpm, jump=jump, path=case.path, contacts=case.mechanism.contact_names
    )
    closure = _closure(case, max(st["rpm"]))
    folder = _folder(config, out)
    m = case.mechanism
    accuracy = dict(
        accuracy=st["accuracy"], accuracy_of=st["accuracy_of"], steps_per_revolution=st["steps_per_revolution"]
    )
    result = sp.speed_sweep(
        m, st["rpm"], contact=st["contact"], executor=executor, workers=workers, progress=progress, **accuracy
    )
    jump_result = None
    if st["jump"] is not None:
        with warnings.catch_warnings():  # said once, in the summary and on stderr below
            warnings.simplefilter("ignore", sp.StudyWarning)
            jump_result = sp.jump_speed(
                m, tuple(st["jump"]), contact=st["contact"], executor=executor, workers=workers, **accuracy
            )
        for w in jump_result.warnings:
            print(f"warning: {w}", file=sys.stderr)
    columns = [
        "rpm",
        "method",
        "converged",
        "revolutions",
        "min_force_N",
        "min_force_angle_deg",
        "max_force_N",
        "contact_lost",
        "lost_fraction",
        "first_loss_angle_deg",
        "max_abs_acceleration",
        "rigid_max_abs_acceleration",
        "dwell_residual",
        "dwell_residual_at_deg",
        "spectral_radius",
        "instability",
        "steps_per_revolution",
        "accuracy",
        "accuracy_reached",
        "force_error_N",
        "error",
    ]
    _write(config, folder / "sweep.csv", _csv(result["rows"], columns))
    spec_rows = [
        {"rpm": r["rpm"], **{f"order_{k}": float(result["spectrum"][k - 1, j]) for k in result["orders"]}}
        for j, r in enumerate(result["rows"])
    ]
    _write(config, folder / "spectrum.csv", _csv(spec_rows, ["rpm"] + [f"order_{k}" for k in result["orders"]]))
    # The margin figure shows the jump scan's speeds too: the dips between the sweep's speeds.
    margin_rows = sorted(result["rows"] + (jump_result.margin if jump_result else []), key=lambda r: r["rpm"])
    _save(config, sp.plot_margin(margin_rows, jump_result), folder / "margin.png")
    _save(config, sp.plot_waterfall(result), folder / "waterfall.png")
    reached = [r["accuracy"] for r in result["rows"] if "accuracy" in r]
    summary = {
        "config": str(case.path),
        "contact": st["contact"] or m.contact_names[0],
        "accuracy_target": st["accuracy"]
        if st["accuracy"] is not None
        else (None if st["steps_per_revolution"] else STUDY_ACCURACY),
        "accuracy_of": st["accuracy_of"],
        "steps_per_revolution": st["steps_per_revolution"],
        "accuracy": max(reached, default=None),
        "speeds": [{k: r.get(k) for k in columns if k in r} for r in result["rows"]],
        "natural_frequencies_hz": result["natural_hz"],
        "resonances": [{"order": k, "mode_hz": f, "rpm": r} for k, f, r in result["resonances"]],
        "files": ["sweep.csv", "spectrum.csv", "margin.png", "waterfall.png", "summary.json"],
    }
    if jump_result is not None:
        summary["jump"] = jump_result.summary()
    summary["warnings"] = closure
    _write(config, folder / "summary.json", _files.json_text(summary).encode())
    return summary


def montecarlo(
    config: str, out: str, *, cases=None, seed=None, rpm=None, executor=None, workers=None, progress=True
) -> dict:
    """A Monte-Carlo tolerance study of the config's mechanism (camfollower.tolerance) with the
    tolerances of its [montecarlo] table, at camshaft speed ``rpm`` (default: the table's ``rpm``, else
    the config's): cases.csv (and cases.parquet with pyarrow), histogram.png, summary.json last
    (speed, statistics, sensitivities in the metrics' units, failed cases)."""
    import matplotlib

    matplotlib.use("Agg")
    from . import tolerance as tol
    from .studies import montecarlo_settings

    case = _load(config)
    data = {k: v for k, v in case.data.items() if k not in ("sweep", "montecarlo")}
    # Given the model, the table's check sets its speed and roller tolerance and covers each tolerance's
    # value and range, located at its block.
    st = montecarlo_settings(
        case.data.get("montecarlo"),
        cases=cases,
        seed=seed,
        rpm=rpm,
        path=case.path,
        build=tol.ConfigCase(data, case.path.parent if case.path else "."),
        contacts=case.mechanism.contact_names,
    )
    closure = _closure(case, st["rpm"])  # at the study's speed
    folder = _folder(config, out)
    result = tol.monte_carlo(
        st["build"],
        st["tolerances"],
        cases=st["cases"],
        seed=st["seed"],
        contact=st["contact"],
        accuracy=st["accuracy"],
        accuracy_of=st["accuracy_of"],
        steps_per_revolution=st["steps_per_revolution"],
        executor=executor,
        workers=workers,
        progress=progress,
    )
    columns = ["case", "seed"] + result.parameters + list(result.metrics) + ["ok", "error"]
    _write(config, folder / "cases.csv", _csv(result.rows, columns))
    files = ["cases.csv"]
    try:
        result.to_parquet(folder / "cases.parquet", protect=[config])
        files.append("cases.parquet")
    except ImportError:
        pass
    speed = st["rpm"] if st["rpm"] is not None else case.mechanism.camshaft_speed_rpm
    summary = {
        "config": str(case.path),
        "camshaft_speed_rpm": speed,
        "roller_tolerance": st["roller_tolerance"],
        **result.summary(),
        "parameters": result.parameters,
    }
    ok = [r for r in result.rows if r["ok"]]
    if len(ok) >= len(result.parameters) + 2:
        summary["sensitivities"] = {
            m: result.sensitivities(m) for m in ("min_force_N", "max_abs_acceleration", "dwell_residual")
        }
        _save(config, result.plot("min_force_N"), folder / "histogram.png")
        files.append("histogram.png")
    summary["failed_cases"] = [
        {k: r[k] for k in ["case", "seed"] + result.parameters + ["error"]} for r in result.failed()
    ]
    summary["files"] = files + ["summary.json"]
    summary["warnings"] = closure
    _write(config, folder / "summary.json", _files.json_text(summary).encode())
    return summary


def _message(error: BaseException, limit: int = 2000) -> str:
    """An error as printable text of at most `limit` characters: whatever raised it, the message never
    carries a whole file's content or a terminal control sequence."""
    text = "".join(c if c.isprintable() or c == "\n" else "?" for c in str(error))
    return text if len(text) <= limit else text[:limit] + f"... ({len(text)} characters)"


def _add_executor_options(p) -> None:
    p.add_argument("--workers", type=int, help="local worker processes (default: one per CPU; 1 runs in this process)")
    p.add_argument(
        "--scheduler",
        help="a Dask scheduler address, tcp://host:8786 (or dask:N for a local cluster "
        "of N processes); needs the 'dask' extra",
    )
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def synthesize(config: str, out: str, *, rpm=None, band=None, workers=None) -> dict:
    """Redesign the lift of the config's contact for its flexible mechanism (camfollower.synthesis,
    the config's [synthesis] table; ``rpm`` (design speed first) or ``band`` override its speeds):
    program.toml (the new program as a config table), ecam_table.csv (an equidistant master/slave
    table), verification.csv (the config's own lift and the new one simulated afresh at every speed),
    before_after.png, summary.json last."""
    import matplotlib

    matplotlib.use("Agg")
    from . import ecam, synthesis
    from .config import program_toml
    from .studies import synthesis_settings

    case = _load(config)
    m = case.mechanism
    settings = synthesis_settings(
        case.data.get("synthesis"), path=case.path, contacts=m.contact_names, dofs=list(m.dof_names)
    )
    if rpm:
        settings.pop("band", None)
        settings["speeds_rpm"] = list(rpm)
    elif band is not None:
        settings.pop("speeds_rpm", None)
        settings["band"] = band
    start = settings.pop("start", "program")
    contact = settings["contact"] or m.contact_names[0]
    own = next(c for c in m.builder().contacts if c["name"] == contact)
    if start != "program":
        settings["start"] = synthesis.with_laws(own["program"], start)
    folder = _folder(config, out)
    result = synthesis.synthesize(m, workers=workers or 2, **settings)
    speeds = sorted(result.speeds_rpm)  # the design speed first in the result; in order here
    before = synthesis.verify(m, own["program"], speeds, contact=contact, output=result.output)
    after = synthesis.verify(m, result.program, speeds, contact=contact, output=result.output)
    rotary = not getattr(own["follower"], "translating", True)
    written = []
    header = (
        f"# The lift camfollower synthesize designed for {case.path.name if case.path else 'the config'}'s contact "
        f"{contact!r}.\n# To use it: paste this table into the config and set that contact's program = \"synthesized\".\n"
    )
    _write(
        config, folder / "program.toml", (header + program_toml(result.program, "synthesized", rotary=rotary)).encode()
    )
    written.append("program.toml")
    ecam.write_table_csv(folder / "ecam_table.csv", result.program, rotary=rotary, slave_unit="deg" if rotary else "mm")
    written.append("ecam_table.csv")
    rows = [{"lift": "config", **r} for r in before] + [{"lift": "synthesized", **r} for r in after]
    columns = [
        "lift",
        "rpm",
        "residual",
        "residual_error",
        "residual_rms",
        "max_abs_acceleration",
        "rigid_max_abs_acceleration",
        "min_force_N",
        "contact_lost",
        "accuracy",
        "steps_per_revolution",
    ]
    _write(config, folder / "verification.csv", _csv(rows, columns))
    written.append("verification.csv")
    output_dof = next(d for d in m.builder().dofs if d["name"] == result.output)
    turns = not np.any(np.asarray(output_dof["direction"]))  # a rotational DOF has no direction
    figure = _before_after(own["program"], result, before, after, rotary, "rad" if turns else "m")
    _save(config, figure, folder / "before_after.png")
    written.append("before_after.png")
    summary = {
        "config": str(case.path),
        "synthesis": result.summary(),
        "verification": {"config": before, "synthesized": after},
        "files": written + ["summary.json"],
    }
    _write(config, folder / "summary.json", _files.json_text(summary).encode())
    return summary


def _before_after(program, result, before, after, rotary: bool, output_unit: str):
    """Cam acceleration and the output's residual vibration against speed, the config's lift and the
    synthesized one."""
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 4.5))
    theta = np.linspace(0.0, 2.0 * math.pi, 2001)
    omega = result.speeds_rpm[0] * math.pi / 30.0
    for label, p, style in (("config's lift", program, "--"), ("synthesized", result.program, "-")):
        ax.plot(np.degrees(theta), np.asarray(p.evaluate(theta)["d2h"]) * omega**2, style, label=label)
    ax.set_xlabel("cam angle (deg)")
    ax.set_ylabel(f"rigid follower acceleration at {result.speeds_rpm[0]:g} rpm ({'rad' if rotary else 'm'}/s$^2$)")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 45))
    ax.grid(True, alpha=0.3)
    ax.legend()
    ax.set_title("cam acceleration")
    order = np.argsort([r["rpm"] for r in before])
    for label, rows, style in (("config's lift", before, "--o"), ("synthesized", after, "-o")):
        bx.semilogy(
            [rows[i]["rpm"] for i in order], [max(rows[i]["residual"], 1e-16) for i in order], style, label=label
        )
    bx.set_xlabel("camshaft speed (rpm)")
    bx.set_ylabel(f"residual vibration of {result.output}, peak-to-peak ({output_unit})")
    bx.grid(True, which="both", alpha=0.3)
    bx.legend()
    n = len(result.speeds_rpm)
    where = f"{result.robust} over {n} speeds" if n > 1 else f"at {result.speeds_rpm[0]:g} rpm"
    bx.set_title(f"objective: {result.objective.replace('_', ' ')} ({result.measure}, {where})")
    fig.tight_layout()
    return fig


class _Parser(argparse.ArgumentParser):
    """argparse with the command's one-line errors: a command line that cannot be read is a usage
    error (exit status 2), as in the C++ program."""

    def error(self, message):
        print(f"camfollower: error: {_message(message)} (see: {self.prog} --help)", file=sys.stderr)
        raise SystemExit(2)


def main(argv=None) -> int:
    try:
        return _main(argv)
    except BrokenPipeError:  # the reader went away (| head): no traceback and no message
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 1


def _main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    if argv[:1] == ["study"]:  # the paper's study has its own options (camfollower study --help)
        from . import study

        return study.main(argv[1:], prog="camfollower study")
    parser = _Parser(
        prog="camfollower",
        description="camfollower: dynamics of flexible cam-follower "
        "mechanisms; every verb works on a config file (docs/config.md). -o is the file "
        "for run and export, the folder for the others.",
        epilog="exit status: 0 done, 1 the config or the run failed, 2 a command-line (usage) error; every "
        "error is one line 'camfollower: error: ...'",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    k = sub.add_parser(
        "kinematics",
        help="per contact: largest pressure angle, smallest cam-surface radius, lift "
        "range, rigid velocity and acceleration",
    )
    k.add_argument("config", nargs="?", help="config file (default: the paper's mechanism)")
    k.add_argument("--rpm", type=float, help="camshaft speed for the velocity and acceleration (default: the config's)")
    md = sub.add_parser("modes", help="natural frequencies of the mechanism, contacts linearized at a cam angle")
    md.add_argument("config", nargs="?", help="config file (default: the paper's mechanism)")
    md.add_argument("--theta", type=float, default=0.0, help="camshaft angle of the linearization, deg (default 0)")
    md.add_argument("--count", type=int, help="how many of the lowest modes (default: all; 20 above 200 DOFs)")
    r = sub.add_parser("run", help="simulate the case the config describes; every recorded channel as CSV")
    r.add_argument("config", help="config file (docs/config.md)")
    r.add_argument("-o", "--output", help="CSV file (default: the config's [output] file)")
    e = sub.add_parser(
        "export",
        help="the cam surface (and cutter-centre path) of one contact for manufacturing: CSV, or DXF for a .dxf file",
    )
    e.add_argument("config", help="config file (docs/config.md)")
    e.add_argument("-o", "--output", required=True, help="CSV or DXF file")
    e.add_argument("--contact", help="contact whose cam to export (default: the first)")
    e.add_argument("--unit", default="mm", help="length unit of the file: m, mm, um or inch (default mm)")
    e.add_argument(
        "--cutter-radius",
        type=float,
        default=0.0,
        help="radius of the milling cutter or grinding wheel, in --unit (default 0: no cutter path)",
    )
    e.add_argument("--points", type=int, default=3600, help="points round the cam (default 3600)")
    e.add_argument(
        "--roller",
        choices=("cylindrical", "tapered"),
        default="cylindrical",
        help="a barrel cam's roller: cylindrical or the ideal tapered one (its groove walls; default cylindrical)",
    )
    e.add_argument(
        "--ecam",
        choices=("table", "segments", "twincat"),
        help="the lift program for a servo drive instead (docs/ecam.md): an equidistant master/slave table, "
        "a VDI 2143-style segment list, or a TwinCAT CNC cam table",
    )
    sub.add_parser(
        "study",
        help="the paper's study (healthy / eccentricity / clearance) -> ./out; "
        "camfollower study --help for its options",
    )
    f = sub.add_parser("figures", help="simulate a config; write run.csv, figures and summary.json")
    f.add_argument("config", help="config file (docs/config.md)")
    f.add_argument("-o", "--out", default="out", help="output folder (default: ./out)")
    c = sub.add_parser(
        "camshaft", help="a flexible camshaft at several speeds: summary.csv, study.png, traces, summary.json"
    )
    c.add_argument("config", help="config file with a flexible camshaft (docs/camshaft.md)")
    c.add_argument("--rpm", type=float, nargs="+", help="camshaft speeds (default: the config's)")
    c.add_argument("--engine-rpm", type=float, nargs="+", help="engine speeds (the camshaft turns at half)")
    c.add_argument(
        "--revolutions", type=float, default=2.0, help="camshaft revolutions per speed; the last is recorded"
    )
    c.add_argument("-o", "--out", default="out", help="output folder (default: ./out)")
    s = sub.add_parser("sweep", help="periodic steady state over a speed range: margin curve, waterfall, jump speed")
    s.add_argument("config", help="config file (docs/config.md; optional [sweep] table, docs/studies.md)")
    s.add_argument("--rpm", type=float, nargs="+", help="camshaft speeds (default: the config's [sweep])")
    s.add_argument(
        "--jump", type=float, nargs=2, metavar=("LO", "HI"), help="find the jump speed between LO and HI rpm"
    )
    _add_executor_options(s)
    s.add_argument("-o", "--out", default="out", help="output folder (default: ./out)")
    mc = sub.add_parser("montecarlo", help="Monte-Carlo tolerance study from the config's [montecarlo] table")
    mc.add_argument("config", help="config file with a [montecarlo] table (docs/studies.md)")
    mc.add_argument("--cases", type=int, help="number of cases (default: the config's)")
    mc.add_argument("--seed", type=int, help="study seed (default: the config's)")
    mc.add_argument(
        "--rpm", type=float, help="camshaft speed of every case (default: the table's rpm, else the config's)"
    )
    _add_executor_options(mc)
    mc.add_argument("-o", "--out", default="out", help="output folder (default: ./out)")
    sy = sub.add_parser(
        "synthesize",
        help="redesign the lift for the flexible mechanism from the config's [synthesis] table: new program, "
        "verification, figures",
    )
    sy.add_argument("config", help="config file (optional [synthesis] table, docs/synthesis.md)")
    sy.add_argument("--rpm", type=float, nargs="+", help="speeds to design for, the design speed first (rpm)")
    sy.add_argument("--band", type=float, help="design over +/- this fraction of the config's speed (e.g. 0.2)")
    sy.add_argument("--workers", type=int, help="threads for the finite differences (default 2)")
    sy.add_argument("-o", "--out", default="out", help="output folder (default: ./out)")
    dz = sub.add_parser(
        "design",
        help="the design page: edit the cam and mechanism in the browser, with the flexible response live",
    )
    dz.add_argument("config", nargs="?", help="config file to start from (default: the paper's mechanism)")
    dz.add_argument("--port", type=int, default=0, help="port on 127.0.0.1 (default: a free one)")
    dz.add_argument("--no-browser", action="store_true", help="print the address, do not open a browser")
    args = parser.parse_args(argv)
    try:
        check_arguments(args)
    except (ValueError, TypeError) as e:  # an argument out of its range: a usage error, as in the C++ program
        print(f"camfollower: error: {_message(e)}", file=sys.stderr)
        return 2
    try:
        if args.command == "design":
            from .design import serve

            serve(args.config, port=args.port, open_browser=not args.no_browser)
            return 0
        if args.command == "kinematics":
            kinematics(args.config, args.rpm)
            return 0
        if args.command == "modes":
            modes(args.config, args.theta, args.count)
            return 0
        if args.command == "run":
            run(args.config, args.output)
            return 0
        if args.command == "export":
            export(
                args.config,
                args.output,
                args.contact,
                args.unit,
                args.cutter_radius,
                args.points,
                args.roller,
                args.ecam,
            )
            return 0
        if args.command == "camshaft":
            study = camshaft(args.config, args.out, args.rpm, args.engine_rpm, args.revolutions)
        elif args.command == "sweep":
            result = sweep(
                args.config,
                args.out,
                rpm=args.rpm,
                jump=args.jump,
                executor=_executor(args),
                workers=args.workers,
                progress=not args.no_progress,
            )
        elif args.command == "synthesize":
            result = synthesize(args.config, args.out, rpm=args.rpm, band=args.band, workers=args.workers)
        elif args.command == "montecarlo":
            result = montecarlo(
                args.config,
                args.out,
                cases=args.cases,
                seed=args.seed,
                rpm=args.rpm,
                executor=_executor(args),
                workers=args.workers,
                progress=not args.no_progress,
            )
        else:
            summary = figures(args.config, args.out)
    except BrokenPipeError:
        raise  # main: the reader went away
    except (ValueError, TypeError, RuntimeError, OSError, ImportError) as e:
        print(f"camfollower: error: {_message(e)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("camfollower: cancelled", file=sys.stderr)
        return 130
    if args.command == "sweep":
        for r in result["speeds"]:
            print(
                f"{r['rpm']:g} rpm: min contact force {r.get('min_force_N', float('nan')):.2f} N at "
                f"{r.get('min_force_angle_deg', float('nan')):.1f} deg, contact {'LOST' if r.get('contact_lost') else 'kept'} "
                f"({r.get('method')})"
            )
        if "jump" in result:
            j = result["jump"]
            print(
                f"jump speed {j['rpm']:.1f} rpm (bracket {j['bracket'][0]:.1f}-{j['bracket'][1]:.1f}): the follower "
                f"first leaves the cam at {j['angle_deg']:.1f} deg"
            )
            for w in j["windows"]:
                lost_on = w["end_rpm"] is None or not math.isfinite(w["end_rpm"])
                end = "the range's end" if lost_on else f"{w['end_rpm']:.1f} rpm"
                print(f"  contact lost from {w['start_rpm']:.1f} rpm to {end} (leaves at {w['angle_deg']:.1f} deg)")
        print(f"{len(result['files'])} files -> {args.out}")
        return 0
    if args.command == "synthesize":
        r = result["synthesis"]
        print(
            f"{r['objective']} ({r['measure']}) of {r['output']}: {'converged' if r['converged'] else 'NOT converged'} "
            f"in {r['iterations']} iterations, {r['evaluations']} periodic steady states, {r['wall_time']:.1f} s "
            f"({r['message']})"
        )
        for b, a in zip(result["verification"]["config"], result["verification"]["synthesized"]):
            print(
                f"  {_text.g(a['rpm'], 6)} rpm: residual vibration {b['residual']:.3g} -> {a['residual']:.3g}, "
                f"max |a| {b['max_abs_acceleration']:.4g} -> {a['max_abs_acceleration']:.4g}, min contact force "
                f"{b['min_force_N']:.1f} -> {a['min_force_N']:.1f} N"
            )
        print(f"{len(result['files'])} files -> {args.out}")
        return 0
    if args.command == "montecarlo":
        f = result["metrics"].get("min_force_N", {})
        print(
            f"{result['cases']} cases at {_text.g(result['camshaft_speed_rpm'], 6)} rpm, {result['failed']} failed, "
            f"{result['contact_lost']} lost contact; min contact force {f.get('mean', float('nan')):.2f} +- "
            f"{f.get('std', float('nan')):.2f} N (5 % {f.get('p5', float('nan')):.2f} N, nominal "
            f"{f.get('nominal', float('nan')):.2f} N)"
        )
        for s_ in result.get("sensitivities", {}).get("min_force_N", [])[:3]:
            print(
                f"  {s_['parameter']}: {s_['effect_of_one_std']:+.3g} N per std of {_text.g(s_['parameter_std'], 3)} "
                f"(slope {_text.g(s_['slope'], 4)} N per unit), standardized {s_['standardized_coefficient']:+.2f}, "
                f"correlation {s_['correlation']:+.2f}"
            )
        print(f"{len(result['files'])} files -> {args.out}")
        return 0
    if args.command == "camshaft":
        for s in study["speeds"]:
            cams = s["cams"].values()
            drive = "; ".join(
                f"{n} torque {d['mean_torque_Nm']:.2f} N m mean, {d['torque_peak_to_peak_Nm']:.2f} p-p"
                for n, d in s["drives"].items()
            )
            print(
                f"{s['camshaft_speed_rpm']:g} rpm: lift error <= {max(c['lift_error_mm'] for c in cams):.3f} mm, "
                f"min contact force lifting {min(c['min_force_lifting_N'] for c in cams):.1f} N, "
                f"twist <= {max(c['twist_peak_to_peak_deg'] for c in cams):.3f} deg p-p, "
                f"surge <= {max(c.get('surge_peak_to_peak_mm', 0.0) for c in cams):.4f} mm p-p; {drive}"
            )
        print(f"{len(study['files'])} files -> {args.out}")
        return 0
    for name, c in summary["contacts"].items():
        print(
            f"{name}: force {c['min_force_N']:.1f} to {c['max_force_N']:.1f} N, contact lost "
            f"{_text.seconds(c['contact_lost_s'], 3)} s, "
            f"max |a| {c['max_abs_acceleration']:.4g} (rigid {c['max_abs_rigid_acceleration']:.4g})"
        )
    print(f"{len(summary['files'])} files -> {args.out}")
    return 0
