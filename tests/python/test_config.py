# SPDX-License-Identifier: BSD-3-Clause
"""Config files in Python (camfollower.load_config): the same cases as the command line, checked
against mechanisms built by hand in Python, the lift table's own data, and the error messages."""

import json
import math
import runpy
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import camfollower as cf
from camfollower.config import config_from_dict, load_config

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
CONFIGS = ["eccentricity", "flat_faced_table", "translating_roller", "swing_arm", "oscillating_flat"]


@pytest.mark.parametrize("name", CONFIGS)
def test_every_example_config_loads_and_names_its_parts(name):
    case = load_config(EXAMPLES / f"{name}.toml")
    assert case.mechanism.contact_names == ["cam"]
    assert case.data["camshaft"]["speed"]  # the tomllib dict is kept
    kw = case.simulate_kwargs()
    assert kw["time_step"] > 0 and kw["decimation"] >= 1


def test_swing_arm_config_is_the_python_example_built_by_hand():
    # examples/swing_arm_follower.py builds the same mechanism with MechanismBuilder: same matrices,
    # same contact force history.
    arm = runpy.run_path(str(EXAMPLES / "swing_arm_follower.py"))
    by_hand = arm["mechanism"]()
    case = load_config(EXAMPLES / "swing_arm.toml")
    np.testing.assert_array_equal(case.mechanism.mass, by_hand.mass)
    np.testing.assert_array_equal(case.mechanism.stiffness, by_hand.stiffness)
    a = case.run(revolutions=0.5, decimation=50)
    b = cf.simulate(by_hand, revolutions=0.5, time_step=arm["TIME_STEP"], decimation=50)
    assert a.rows == b.rows > 50
    np.testing.assert_allclose(a["cam.force"], b["cam.force"], rtol=0, atol=1e-9 * np.abs(b["cam.force"]).max())


def test_table_lift_passes_through_the_measured_points():
    # The interpolating spline reproduces the data file's own numbers (read here with numpy).
    case = load_config(EXAMPLES / "flat_faced_table.toml")
    data = np.loadtxt(EXAMPLES / "data" / "tappet_lift.csv", delimiter=",", comments="#", skiprows=3)
    theta, h = np.radians(data[:, 0]), 1e-3 * data[:, 1]
    lift = case.programs["measured"].evaluate(theta)["h"]
    np.testing.assert_allclose(lift, h, rtol=0, atol=1e-12)


def test_a_dict_builds_the_same_case_as_the_file():
    case = load_config(EXAMPLES / "translating_roller.toml")
    again = config_from_dict(case.data, base_dir=EXAMPLES)
    np.testing.assert_array_equal(again.mechanism.stiffness, case.mechanism.stiffness)
    changed = dict(case.data, camshaft={"speed": "300 rpm"})
    assert config_from_dict(changed).mechanism.camshaft_speed_rpm == pytest.approx(300.0, rel=1e-15)


@pytest.mark.parametrize("text, message", [
    ("[camshaft]\nspeed = 600\n[preset]\nname = \"paper\"\n[preset.parameters]\noffset = \"10 kg\"\n",
     "bad.toml:6: preset.parameters.offset: unit 'kg'"),
    ("[camshaft]\nspeed = 600\n[preset]\nname = \"paper\"\nnmae = 1\n", "bad.toml:5: preset.nmae: unknown key"),
    ("[camshaft]\nspeed = 600\nspeed = 700\n", "TOML syntax"),
    ("[camshaft]\nspeed = \"600 rpm\n", "TOML syntax"),
    ("[camshaft]\nspeed = 600\n[preset]\nname = \"paper\"\n[output]\ndecimation = 1e300\n",
     "output.decimation: must be a whole number"),
])
def test_errors_name_file_line_and_key(tmp_path, text, message):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match=None) as e:
        load_config(path)
    assert message in str(e.value)


def test_files_that_are_not_configs(tmp_path):
    with pytest.raises(ValueError, match="is a directory"):
        load_config(tmp_path)
    (tmp_path / "empty.toml").write_text("")
    with pytest.raises(ValueError, match="is empty"):
        load_config(tmp_path / "empty.toml")
    with pytest.raises(ValueError, match="NUL"):
        load_config("a\0b.toml")
    with pytest.raises(ValueError, match="No such file"):
        load_config(tmp_path / "missing.toml")
    with pytest.raises(ValueError, match="must be a dict"):
        config_from_dict([("camshaft", 1)])
    with pytest.raises(ValueError, match="camshaft.speed: must be finite"):
        config_from_dict({"camshaft": {"speed": math.nan}, "preset": {"name": "paper"}})


def test_figures_from_a_config_in_one_command(tmp_path):
    out = tmp_path / "figs"
    run = subprocess.run([sys.executable, "-m", "camfollower", "figures", str(EXAMPLES / "flat_faced_table.toml"),
                          "-o", str(out)], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr
    summary = json.loads((out / "summary.json").read_text())
    for f in summary["files"]:
        assert (out / f).stat().st_size > 0
    cam = summary["contacts"]["cam"]
    # The tappet follows the cam (no loss at 1500 rpm with 250 N preload): its peak acceleration is the
    # rigid one within the contact's small vibration.
    assert cam["contact_lost_s"] == 0.0
    assert cam["max_abs_acceleration"] == pytest.approx(cam["max_abs_rigid_acceleration"], rel=0.05)
    # A flat face has a zero pressure angle by construction (face normal along the axis).
    assert cam["max_abs_pressure_angle_deg"] == pytest.approx(0.0, abs=1e-9)
    # An output folder that is a file is refused, nothing written.
    (tmp_path / "file").write_text("x")
    bad = subprocess.run([sys.executable, "-m", "camfollower", "figures", str(EXAMPLES / "swing_arm.toml"), "-o",
                          str(tmp_path / "file")], capture_output=True, text=True, timeout=300)
    assert bad.returncode == 1 and "not a directory" in bad.stderr
