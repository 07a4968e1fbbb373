# SPDX-License-Identifier: BSD-3-Clause
"""One front door (camfollower.cli, docs/config.md "Command line"): the ``camfollower`` command that
``pip install`` puts next to the interpreter offers every verb; kinematics, modes, run and export give
what the library's own functions give (and, where the C++ program is built, what it prints), with
the option checks of the C++ program."""

import json
import math
import re
import subprocess
import sys
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest
from camfollower import export as ex
from camfollower.config import load_config

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
COMMAND = Path(sys.executable).parent / "camfollower"
CPP = next(
    (
        p
        for p in (ROOT / "build-sanitize" / "src" / "camfollower", ROOT / "build" / "src" / "camfollower")
        if p.exists()
    ),
    None,
)
VERBS = ["kinematics", "modes", "run", "export", "study", "figures", "camshaft", "sweep", "montecarlo"]


def command(*args, cwd=None):
    return subprocess.run([str(COMMAND), *map(str, args)], capture_output=True, text=True, timeout=600, cwd=cwd)


NUMBER = r"(?<![\w.])-?\d+(?:\.\d+)?(?:e[+-]?\d+)?(?![\w.])"


def numbers(text):
    return [float(x) for x in re.findall(NUMBER, text)]


def test_pip_installs_one_command_with_every_verb():
    assert COMMAND.exists(), "pip install puts the camfollower command next to the interpreter"
    r = command("--help")
    assert r.returncode == 0
    for verb in VERBS:
        assert verb in r.stdout
    study = command("study", "--help")
    assert study.returncode == 0 and study.stdout.startswith("usage: camfollower study")


@pytest.mark.parametrize("config", [None, "swing_arm.toml", "flat_faced_table.toml"])
def test_kinematics_prints_the_library_figures(config, capsys):
    """Pressure angle and curvature as the follower's own functions give them; the rigid peaks against
    a 1e6-point evaluation of the lift's derivatives (a second method)."""
    from camfollower import cli

    rows = cli.kinematics(str(EXAMPLES / config) if config else None)
    out = capsys.readouterr().out
    case = load_config(EXAMPLES / config) if config else None
    m = case.mechanism if case else cf.presets.paper()
    contacts = m.builder().__getstate__()["contacts"]
    assert [r["contact"] for r in rows] == [c["name"] for c in contacts]
    omega = m.omega
    theta = np.linspace(0.0, 2 * math.pi, 1_000_001)
    for row, c in zip(rows, contacts):
        f, program = c["follower"], c["program"]
        assert row["max_abs_pressure_angle_deg"] == pytest.approx(abs(math.degrees(f.max_pressure_angle(program)[1])))
        assert row["min_convex_surface_radius_m"] == pytest.approx(f.min_surface_radius(program)[1])
        d = program.evaluate(theta)
        assert row["max_abs_velocity"] == pytest.approx(omega * np.abs(d["dh"]).max(), rel=1e-6)
        assert row["max_abs_acceleration"] == pytest.approx(omega**2 * np.abs(d["d2h"]).max(), rel=1e-6)
        assert f"contact '{c['name']}'" in out
    assert "max |pressure angle|" in out and "lift range" in out


@pytest.mark.skipif(CPP is None, reason="the C++ program is built by scripts/test.sh")
@pytest.mark.parametrize(
    "args",
    [
        ["kinematics"],
        ["kinematics", EXAMPLES / "swing_arm.toml", "--rpm", "300"],
        ["modes"],
        ["modes", EXAMPLES / "translating_roller.toml", "--theta", "90"],
    ],
)
def test_the_python_and_the_cpp_command_print_the_same(args):
    """Same verbs, same lines, numbers within 1e-4 (the rigid peaks are found by two methods)."""
    py = command(*args)
    cpp = subprocess.run([str(CPP), *map(str, args)], capture_output=True, text=True, timeout=600)
    assert py.returncode == cpp.returncode == 0, (py.stderr, cpp.stderr)
    py_lines, cpp_lines = py.stdout.splitlines(), cpp.stdout.splitlines()
    assert len(py_lines) == len(cpp_lines)
    for a, b in zip(py_lines, cpp_lines):
        assert re.sub(NUMBER, "#", a) == re.sub(NUMBER, "#", b), (a, b)
        assert numbers(a) == pytest.approx(numbers(b), rel=1e-4, abs=2e-3), (a, b)


def test_modes_are_the_mechanisms_and_name_the_dof_moving_most(capsys):
    from camfollower import cli

    out = cli.modes(str(EXAMPLES / "translating_roller.toml"), theta_deg=90.0)
    m = load_config(EXAMPLES / "translating_roller.toml").mechanism
    # scipy's generalized symmetric solver on the mechanism's own tangent stiffness and mass
    import scipy.linalg

    kt = np.asarray(m.modal_analysis(math.radians(90.0))["tangent_stiffness"])
    values, shapes = scipy.linalg.eigh(kt, np.asarray(m.mass))
    assert [f for f, _ in out] == pytest.approx(list(np.sqrt(np.maximum(values, 0)) / (2 * np.pi)), rel=1e-9)
    assert [d for _, d in out] == [m.dof_names[int(np.argmax(np.abs(shapes[:, k])))] for k in range(len(out))]
    assert len(out) == len(m.dof_names) and "lowest" not in capsys.readouterr().out
    assert len(cli.modes(str(EXAMPLES / "translating_roller.toml"), count=1)) == 1
    assert f"(lowest 1 of {len(m.dof_names)})" in capsys.readouterr().out


def test_run_writes_every_channel_of_the_configs_run(tmp_path):
    target = tmp_path / "run.csv"
    r = command("run", EXAMPLES / "swing_arm.toml", "-o", target)
    assert r.returncode == 0, r.stderr
    assert f"-> {target}" in r.stdout
    header = target.read_text().splitlines()[0].split(",")
    data = np.loadtxt(target, delimiter=",", skiprows=1)
    result = load_config(EXAMPLES / "swing_arm.toml").run()
    assert header == list(result.channels)
    np.testing.assert_allclose(data[:, header.index("cam.force")], result["cam.force"], rtol=1e-11)


@pytest.mark.parametrize(
    "args, status, message",
    [
        (["run", EXAMPLES / "swing_arm.toml", "-o", ""], 2, "-o/--output: must name a file"),
        (["figures", EXAMPLES / "swing_arm.toml", "-o", ""], 2, "--out: must name a folder"),
        (["modes", "--theta", "nan"], 2, "--theta: nan is not a cam angle"),
        (["modes", "--count", "0"], 2, "--count"),
        (["modes", "--count", "2.5"], 2, "argument --count: invalid int value"),
        (["kinematics", "--rpm", "-5"], 2, "--rpm"),
        (["kinematics", "--rpm", "fast"], 2, "argument --rpm: invalid float value"),
        (["kinematics", EXAMPLES / "swing_arm.toml", "--bogus"], 2, "unrecognized arguments: --bogus"),
        (["export", EXAMPLES / "swing_arm.toml", "-o", "x.csv", "--unit", "furlong"], 2, "--unit: 'furlong' is not"),
        (["export", EXAMPLES / "swing_arm.toml", "-o", "x.csv", "--cutter-radius", "2e6"], 2, "--cutter-radius"),
        (["export", EXAMPLES / "swing_arm.toml", "-o", "x.csv", "--points", "3"], 2, "--points"),
        (["export", EXAMPLES / "swing_arm.toml", "-o", "x.csv", "--contact", ""], 2, "--contact: must name a contact"),
        # Found once the config is read: the run failed (1).
        (["run", EXAMPLES / "swing_arm.toml", "-o", EXAMPLES / "swing_arm.toml"], 1, "is the input file"),
        (["export", EXAMPLES / "swing_arm.toml", "-o", "x.csv", "--contact", "nope"], 1, "no contact named 'nope'"),
    ],
)
def test_bad_arguments_are_one_line_naming_the_option(tmp_path, args, status, message):
    """A usage error (an argument unreadable or out of its range) exits with 2, a config or run that
    fails with 1, as the C++ program does; each is one line."""
    r = command(*args, cwd=tmp_path)
    assert r.returncode == status, (r.stdout, r.stderr)
    assert r.stderr.startswith("camfollower: error: ") and message in r.stderr and r.stderr.count("\n") == 1
    assert not list(tmp_path.iterdir())


def test_run_writes_the_configs_output_file_relative_to_the_working_directory(tmp_path):
    """As docs/config.md says and the C++ program does (never next to the config in the sources)."""
    config = tmp_path / "cfg" / "swing_arm.toml"
    config.parent.mkdir()
    config.write_text((EXAMPLES / "swing_arm.toml").read_text())
    name = load_config(config).output["file"]
    work = tmp_path / "work"
    work.mkdir()
    r = command("run", config, cwd=work)
    assert r.returncode == 0, r.stderr
    assert (work / name).is_file() and not (config.parent / name).exists()


def test_a_closed_pipe_is_not_an_error_message():
    """camfollower modes CONFIG | head -1: no traceback and no 'Broken pipe' line."""
    p = subprocess.run(
        f"'{COMMAND}' modes '{EXAMPLES / 'valve_train.toml'}' | head -1",
        shell=True,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert p.stdout.count("\n") == 1 and "natural frequencies" in p.stdout
    assert p.stderr == ""


def test_export_writes_the_libraries_csv_and_a_dxf_with_the_cutter_in_the_unit(tmp_path):
    case = load_config(EXAMPLES / "swing_arm.toml")
    c = case.builder.__getstate__()["contacts"][0]
    r = command("export", EXAMPLES / "swing_arm.toml", "-o", tmp_path / "cam.csv", "--cutter-radius", "5")
    assert r.returncode == 0, r.stderr
    ex.write_csv(tmp_path / "direct.csv", c["follower"], c["program"], cutter_radius=0.005)
    assert (tmp_path / "cam.csv").read_bytes() == (tmp_path / "direct.csv").read_bytes()
    r = command(
        "export",
        EXAMPLES / "swing_arm.toml",
        "-o",
        tmp_path / "cam.dxf",
        "--unit",
        "inch",
        "--cutter-radius",
        "0.2",
        "--points",
        "720",
    )
    assert r.returncode == 0, r.stderr
    ezdxf = pytest.importorskip("ezdxf")
    doc = ezdxf.readfile(tmp_path / "cam.dxf")
    layers = {e.dxf.layer: e for e in doc.modelspace().query("LWPOLYLINE")}
    surface = np.array([p[:2] for p in layers["CAM_SURFACE"].get_points()])
    cutter = np.array([p[:2] for p in layers["CUTTER_PATH"].get_points()])
    assert len(surface) == len(cutter) == 720
    # The cutter centre runs 0.2 inch off the surface (in the file's unit).
    gaps = np.min(np.linalg.norm(cutter[:, None, :] - surface[None, :, :], axis=2), axis=1)
    assert np.median(gaps) == pytest.approx(0.2, rel=1e-3)


def test_figures_summary_still_written_through_the_command(tmp_path):
    r = command("figures", EXAMPLES / "swing_arm.toml", "-o", tmp_path / "out")
    assert r.returncode == 0, r.stderr
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert "run.csv" in summary["files"]
