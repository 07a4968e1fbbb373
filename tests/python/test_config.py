# SPDX-License-Identifier: BSD-3-Clause
"""Config files in Python (camfollower.load_config): the same cases as the command line, checked
against mechanisms built by hand in Python, the lift table's own data, and the error messages."""

import datetime
import json
import math
import runpy
import subprocess
import sys
import time
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest
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


@pytest.mark.parametrize(
    "text, message",
    [
        (
            "[camshaft]\nspeed = 600\n[preset]\nname = \"paper\"\n[preset.parameters]\noffset = \"10 kg\"\n",
            "bad.toml:6: preset.parameters.offset: unit 'kg'",
        ),
        ("[camshaft]\nspeed = 600\n[preset]\nname = \"paper\"\nnmae = 1\n", "bad.toml:5: preset.nmae: unknown key"),
        ("[camshaft]\nspeed = 600\nspeed = 700\n", "TOML syntax"),
        ("[camshaft]\nspeed = \"600 rpm\n", "TOML syntax"),
        (
            "[camshaft]\nspeed = 600\n[preset]\nname = \"paper\"\n[output]\ndecimation = 1e300\n",
            "output.decimation: must be a whole number",
        ),
    ],
)
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
    run = subprocess.run(
        [sys.executable, "-m", "camfollower", "figures", str(EXAMPLES / "flat_faced_table.toml"), "-o", str(out)],
        capture_output=True,
        text=True,
        timeout=300,
    )
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
    bad = subprocess.run(
        [
            sys.executable,
            "-m",
            "camfollower",
            "figures",
            str(EXAMPLES / "swing_arm.toml"),
            "-o",
            str(tmp_path / "file"),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert bad.returncode == 1 and "not a directory" in bad.stderr


# --- hardening, third round (issue 33): one reader for files and dicts, every error located ---------

ROOT = EXAMPLES.parent


def _line_of(text: str, needle: str, occurrence: int = 0) -> int:
    """The 1-based line of the `occurrence`-th line containing `needle` (the test's own count)."""
    return [i + 1 for i, line in enumerate(text.splitlines()) if needle in line][occurrence]


def test_a_cyclic_or_deep_dict_is_refused_naming_the_key_path_and_the_limit():
    # Run apart: before the fix the recursive conversion overflowed the C stack (a segfault).
    script = r"""
import json, camfollower as cf
base = {"camshaft": {"speed": 600}, "preset": {"name": "paper"}}
cyclic = dict(base); cyclic["x"] = cyclic
deep = dict(base); node = deep
for _ in range(30000):
    node["y"] = {}; node = node["y"]
lst = []; lst.append(lst); listy = dict(base, z=lst)
deep_list = dict(base, w=[]); node = deep_list["w"]
for _ in range(30000):
    node.append([]); node = node[0]
laughs = {"v": 1.0}
for _ in range(40):  # 2**40 values by shared sub-dicts, 41 levels deep
    laughs = {"a": laughs, "b": laughs}
laughs = dict(base, l=laughs)
out = {}
for name, data in [("cyclic", cyclic), ("deep", deep), ("listy", listy), ("deep_list", deep_list), ("laughs", laughs)]:
    try:
        cf.config_from_dict(data)
        out[name] = "accepted"
    except Exception as e:
        out[name] = [type(e).__name__, str(e)]
print(json.dumps(out))
"""
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr[-2000:]
    out = json.loads(run.stdout)
    for name, key in [("cyclic", "x.x.x"), ("deep", "y.y.y"), ("listy", "z[0][0]"), ("deep_list", "w[0][0]")]:
        kind, message = out[name]
        assert kind == "ValueError", out[name]
        assert message.startswith(f"<dict>: {key} ... (60 more) ... ") and "nested deeper than 64 levels" in message, (
            message
        )
        assert len(message) < 300, message
    kind, message = out["laughs"]
    assert (
        kind == "ValueError" and message.startswith("<dict>: l.a.a ... (") and "appears more than 1000 times" in message
    )


@pytest.mark.parametrize(
    "value, message",
    [
        ({1: 2}, "keys must be strings (TOML keys), got int 1"),
        (2**64, "does not fit in 64 bits"),
        ("\ud800", "must be valid Unicode text"),
        (None, "must be a str, bool, int, float, list, dict or a date/time, got NoneType"),
    ],
)
def test_a_dict_value_toml_cannot_hold_is_a_value_error_naming_its_key(value, message):
    data = {"camshaft": {"speed": 600}, "preset": {"name": "paper"}, "solver": {"odd": [1, value]}}
    with pytest.raises(ValueError) as e:
        config_from_dict(data)
    assert str(e.value).startswith("<dict>: solver.odd[1]") and message in str(e.value), str(e.value)


def test_the_data_of_a_file_round_trips_through_a_dict_dates_included(tmp_path):
    text = (EXAMPLES / "translating_roller.toml").read_text()
    path = tmp_path / "c.toml"
    path.write_text(text + '\n[output.extra]\nwhen = 1979-05-27T07:32:00-08:00\nday = 1979-05-27\nat = 07:32:00\n')
    with pytest.raises(ValueError, match=r"c.toml:\d+: output.extra: unknown key"):
        load_config(path)
    data = cf._core._parse_toml(path.read_bytes(), str(path))
    extra = data["output"]["extra"]
    assert extra["when"] == datetime.datetime(
        1979, 5, 27, 7, 32, tzinfo=datetime.timezone(datetime.timedelta(hours=-8))
    )
    assert extra["day"] == datetime.date(1979, 5, 27) and extra["at"] == datetime.time(7, 32)
    # Tables in the file's order, as tomllib gave them.
    assert list(data) == ["camshaft", "program", "dof", "spring", "contact", "solver", "output"]
    with pytest.raises(ValueError, match=r"^<dict>: output.extra: unknown key"):
        config_from_dict(data, base_dir=tmp_path)


def _located(tmp_path, text, needle, key, message, occurrence=0):
    path = tmp_path / "c.toml"
    path.write_text(text)
    with pytest.raises(ValueError) as e:
        load_config(path)
    expected = f"{path}:{_line_of(text, needle, occurrence)}: {key}: {message}"
    assert str(e.value).startswith(expected), (str(e.value), expected)


def test_model_builder_errors_name_the_line_and_the_key_they_concern(tmp_path):
    """The builders' messages name their parameter; the reader locates them at that key's line (it
    gave the table's line and path, or for the mechanism's final checks the file alone)."""
    base = (EXAMPLES / "translating_roller.toml").read_text()
    assert 'mass = "0.25 kg"' in base and 'stiffness = "40 N/um"' in base
    _located(
        tmp_path,
        base.replace('mass = "0.25 kg"', 'mass = "-0.25 kg"'),
        'mass = "-0.25 kg"',
        "dof[0].mass",
        "mass of DOF 'carrier' must be finite and > 0",
    )
    _located(
        tmp_path,
        base.replace('stiffness = "40 N/um"', 'stiffness = "-40 N/um"'),
        'stiffness = "-40',
        "spring[0].stiffness",
        "stiffness of 'rod' must be finite and >= 0",
    )
    _located(
        tmp_path,
        base.replace('offset = "5 mm"', 'offset = "60 mm"'),
        'offset = "60 mm"',
        "contact[0].follower.offset",
        "must satisfy |offset| < base_radius + roller_radius",
    )
    # Checked only when the whole mechanism is built: before, "c.toml: clearance 'gap' sliding_dof ...".
    clearance = (
        '\n[[clearance]]\nname = "gap"\ngap_dofs = ["slide"]\ngap_coefficients = [1]\nclearance = 0.001\n'
        'stiffness = 1e6\nfriction = 0.1\nsliding_dof = "nope"\n'
    )
    _located(
        tmp_path,
        base + clearance,
        'sliding_dof = "nope"',
        "clearance[0].sliding_dof",
        "clearance 'gap' sliding_dof refers to DOF 'nope'",
    )
    _located(
        tmp_path,
        base + clearance.replace("stiffness = 1e6", "stiffness = -1e6").replace('"nope"', '"carrier"'),
        "stiffness = -1e6",
        "clearance[0].stiffness",
        "clearance 'gap' wall stiffness must be finite and > 0",
    )
    _located(
        tmp_path,
        base + "\n[damping]\nmodal_ratios = [0.1, 0.2, 0.3]\n",
        "modal_ratios",
        "damping.modal_ratios",
        "give one ratio or one per mode (2), got 3",
    )
    # A preset's parameters are checked together; the message is located at the one it names.
    preset = '[camshaft]\nspeed = 600\n[preset]\nname = "paper"\n[preset.parameters]\nfollower_mass = 1\noffset = 0.5\n'
    _located(
        tmp_path,
        preset,
        "offset = 0.5",
        "preset.parameters.offset",
        "must satisfy |offset| < base_radius + roller_radius",
    )


def _settings_error(tmp_path, table_text, call, kind=ValueError):
    path = tmp_path / "study.toml"
    path.write_text((EXAMPLES / "paper_studies.toml").read_text().split("[sweep]")[0] + table_text)
    case = load_config(path)
    with pytest.raises(kind) as e:
        call(case, path)
    return path, str(e.value)


MC = '[montecarlo]\ncases = 4\n\n[[montecarlo.tolerance]]\nparameter = "preset.parameters.contact_stiffness"\n'


@pytest.mark.parametrize(
    "block, needle, key, message",
    [
        (
            "distribution = {}\nstd = 0.1\n",
            "distribution =",
            "distribution",
            "must be one of normal, uniform, truncated_normal (a string), got a table",
        ),
        (
            'distribution = ["normal"]\nstd = 0.1\n',
            "distribution =",
            "distribution",
            "must be one of normal, uniform, truncated_normal (a string), got an array",
        ),
        ('distribution = "normal"\nstd = "5 %"\n', "std =", "std", "Normal std must be a finite number, got '5 %'"),
        (
            'distribution = "normal"\nstd = 0.1\nrelative = "yes"\n',
            "relative =",
            "relative",
            "Normal relative must be True or False, got 'yes'",
        ),
        (
            'distribution = "normal"\nsdt = 0.1\n',
            "sdt =",
            "sdt",
            "unknown key; known here: parameter, distribution, std",
        ),
        ('distribution = "uniform"\nlow = 0.1\nhigh = -0.1\n', "low =", "low", "Uniform needs low <= high"),
        ('distribution = "normal"\nstd = -1\n', "std =", "std", "Normal std must be >= 0"),
    ],
)
def test_a_tolerance_block_names_the_key_its_line_and_the_type_it_needs(tmp_path, block, needle, key, message):
    from camfollower.studies import montecarlo_settings

    path, text = _settings_error(
        tmp_path, MC + block, lambda case, p: montecarlo_settings(case.data["montecarlo"], path=p)
    )
    assert text.startswith(f"{path}:{_line_of(path.read_text(), needle)}: montecarlo.tolerance[0].{key}: {message}"), (
        text
    )


def test_a_tolerance_the_model_refuses_or_a_missing_contact_names_its_line(tmp_path):
    from camfollower.studies import montecarlo_settings, sweep_settings
    from camfollower.tolerance import ConfigCase

    nominal = MC.replace("contact_stiffness", "follower_mass") + 'distribution = "normal"\nstd = 2.0\n'
    absent = MC.replace("contact_stiffness", "no_such_value") + 'distribution = "normal"\nstd = 0.1\n'
    for block, message in [(nominal, "the Normal reaches"), (absent, "the config has no such value")]:
        path, text = _settings_error(
            tmp_path,
            block,
            lambda case, p: montecarlo_settings(
                case.data["montecarlo"],
                path=p,
                build=ConfigCase(case.data, p.parent),
                contacts=case.mechanism.contact_names,
            ),
        )
        line = _line_of(path.read_text(), "parameter =")
        assert text.startswith(f"{path}:{line}: montecarlo.tolerance[0].parameter: ") and message in text, text
    path, text = _settings_error(
        tmp_path,
        '[sweep]\nrpm = [600]\ncontact = "lever"\n',
        lambda case, p: sweep_settings(case.data["sweep"], path=p, contacts=case.mechanism.contact_names),
    )
    assert text.startswith(
        f"{path}:{_line_of(path.read_text(), 'contact =')}: sweep.contact: no contact named lever; "
        "the mechanism's contacts: cam"
    ), text


def test_the_montecarlo_command_reports_a_bad_block_in_one_line(tmp_path):
    path = tmp_path / "study.toml"
    path.write_text((EXAMPLES / "paper_studies.toml").read_text().split("[sweep]")[0] + MC + "distribution = {}\n")
    run = subprocess.run(
        [sys.executable, "-m", "camfollower", "montecarlo", str(path), "-o", str(tmp_path / "out")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert run.returncode == 1 and "Traceback" not in run.stderr, run.stderr
    assert run.stderr.startswith(
        f"camfollower: error: {path}:{_line_of(path.read_text(), 'distribution =')}: "
        "montecarlo.tolerance[0].distribution: must be one of"
    ), run.stderr


def test_deep_nesting_and_long_dotted_keys_are_refused_at_once_with_file_and_line(tmp_path):
    path = tmp_path / "c.toml"
    tail = '[camshaft]\nspeed = 600\n[preset]\nname = "paper"\n'
    cases = [
        ("x = " + "[" * 5000 + "]" * 5000 + "\n", r"c.toml:1:\d+: TOML syntax: .*nested value depth"),
        (
            "x = " + "[" * 100 + "]" * 100 + "\n",
            r"c.toml:1: x\[0\]\[0\] \.\.\. \(60 more\) \.\.\. \[0\]\[0\]: nested deeper",
        ),
        (
            ".".join(["k"] * 10_000) + " = 1\n",
            r"c.toml:1: k\.k\.k \.\.\. \(60 more\) \.\.\. k\.k: nested deeper than 64",
        ),
    ]
    for head, message in cases:
        path.write_text(head + tail)
        start = time.perf_counter()
        with pytest.raises(ValueError, match=message):
            load_config(path)
        assert time.perf_counter() - start < 2.0  # tomllib: a RecursionError; 15 s for the dotted key


CLI = next(
    (
        p
        for p in (ROOT / "build-sanitize" / "src" / "camfollower", ROOT / "build" / "src" / "camfollower")
        if p.exists()
    ),
    None,
)


def test_a_byte_order_mark_reads_the_same_in_python_and_on_the_command_line(tmp_path):
    """What Windows editors write: accepted by both readers (toml++ skips it), the same case."""
    text = (EXAMPLES / "translating_roller.toml").read_bytes()
    (tmp_path / "plain.toml").write_bytes(text)
    (tmp_path / "bom.toml").write_bytes(b"\xef\xbb\xbf" + text)
    plain, bom = load_config(tmp_path / "plain.toml"), load_config(tmp_path / "bom.toml")
    assert bom.data == plain.data
    np.testing.assert_array_equal(bom.mechanism.stiffness, plain.mechanism.stiffness)
    if CLI is not None:
        runs = [
            subprocess.run([str(CLI), "kinematics", str(tmp_path / name)], capture_output=True, text=True, timeout=120)
            for name in ("plain.toml", "bom.toml")
        ]
        assert runs[0].returncode == runs[1].returncode == 0, runs[1].stderr
        assert runs[0].stdout.replace("plain.toml", "") == runs[1].stdout.replace("bom.toml", "")
    # A second mark is text, refused by both with the same message.
    (tmp_path / "two.toml").write_bytes(b"\xef\xbb\xbf" * 2 + text)
    with pytest.raises(ValueError, match=r"two.toml:1:1: TOML syntax") as e:
        load_config(tmp_path / "two.toml")
    if CLI is not None:
        run = subprocess.run(
            [str(CLI), "kinematics", str(tmp_path / "two.toml")], capture_output=True, text=True, timeout=120
        )
        assert run.returncode == 1 and run.stderr.strip() == f"camfollower: error: {e.value}"


def test_a_study_table_says_what_its_accuracy_covers(tmp_path):
    from camfollower.studies import montecarlo_settings, sweep_settings

    sweep = lambda case, p: sweep_settings(case.data["sweep"], path=p)  # noqa: E731
    path, text = _settings_error(tmp_path, '[sweep]\nrpm = [600]\naccuracy_of = "forces"\n', sweep)
    assert text.startswith(f"{path}:{_line_of(path.read_text(), 'accuracy_of =')}: sweep.accuracy_of: must be "), text
    assert "'force_and_acceleration' or 'force'" in text and "got 'forces'" in text
    path.write_text(path.read_text().replace('"forces"', '"force"'))
    assert sweep_settings(load_config(path).data["sweep"], path=path)["accuracy_of"] == "force"
    path.write_text(path.read_text().replace('accuracy_of = "force"\n', ""))
    assert sweep_settings(load_config(path).data["sweep"], path=path)["accuracy_of"] == "force_and_acceleration"
    block = MC + 'distribution = "normal"\nstd = 0.1\n'
    mc = lambda case, p: montecarlo_settings(case.data["montecarlo"], path=p)  # noqa: E731
    path, text = _settings_error(tmp_path, block.replace("cases = 4\n", "cases = 4\naccuracy_of = 1\n"), mc)
    assert "montecarlo.accuracy_of: must be 'force_and_acceleration' or 'force'" in text and "got 1" in text
