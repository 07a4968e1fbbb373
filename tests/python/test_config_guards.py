# SPDX-License-Identifier: BSD-3-Clause
"""Config guards (docs/config.md): a bare-number length far off the scale of its contact is refused at
its key with a hint ("did you mean "25 mm"?"), and a mechanism that is not force-closed is warned
about, checked against the closed-form rigid contact force of one follower mass on a preloaded spring."""

import json
import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from camfollower import cli
from camfollower.config import ForceClosureWarning, config_from_dict, force_closure, load_config

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"

# ---- implausible lengths ------------------------------------------------------------------------

# A translating roller on a 40 mm cam lifting 12 mm; {h}, {start_h}, {follower}, {contact_extra},
# {program_extra} are replaced per test.
ROLLER = """\
[camshaft]
speed = 600

[program.feed]
start_h = {start_h}
segments = [
  {{ law = "dwell", end = "40 deg" }},
  {{ law = "modified_sine", end = "150 deg", h = {h} }},
  {{ law = "dwell", end = "200 deg" }},
  {{ law = "polynomial", end = "320 deg", h = {back}, interior_theta = ["250 deg"], interior_h = [{interior_h}] }},
  {{ law = "dwell", end = "360 deg" }},
]
{program_extra}
[[dof]]
name = "carrier"
mass = "250 g"

[[spring]]
name = "return_spring"
a = "carrier"
stiffness = "20 N/mm"
preload = "300 N"

[[contact]]
name = "cam"
program = "feed"
follower = {follower}
follower_dof = "carrier"
stiffness = 1e9
{contact_extra}
"""

NOMINAL = dict(
    start_h=0,
    back=0,
    h='"12 mm"',
    interior_h='"6 mm"',
    program_extra="",
    contact_extra="",
    follower='{ type = "translating_roller", base_radius = "40 mm", roller_radius = "10 mm", offset = "5 mm" }',
)


def write(tmp_path, **changes):
    text = ROLLER.format(**{**NOMINAL, **changes})
    path = tmp_path / "c.toml"
    path.write_text(text)
    return path, text


def line_of(text, needle):
    """The 1-based line of `needle` in the config text (found here, not by the reader)."""
    (n,) = [i + 1 for i, line in enumerate(text.splitlines()) if needle in line]
    return n


def test_the_issue_case_a_bare_25_meant_as_mm_is_refused_with_the_hint(tmp_path):
    path, text = write(tmp_path, h="25")
    with pytest.raises(ValueError) as e:
        load_config(path)
    line = line_of(text, "h = 25 }")
    assert str(e.value).startswith(
        f"{path}:{line}: program.feed.segments[1].h: the lift 25 m is more than 10 x the "
        "base radius 0.04 m of contact 'cam'"
    )
    assert 'did you mean "25 mm"?' in str(e.value)


def test_the_same_lifts_with_units_or_plausible_bare_numbers_load(tmp_path):
    for h in ('"25 mm"', "0.025", '"25.0 mm"'):
        path, _ = write(tmp_path, h=h)
        assert load_config(path).programs["feed"].max_lift() == pytest.approx(
            float(h.strip('"').split()[0]) * (1e-3 if "mm" in h else 1.0)
        )


@pytest.mark.parametrize("name", sorted(p.stem for p in EXAMPLES.glob("*.toml")))
def test_every_example_loads_and_is_force_closed_at_its_speed(name):
    with warnings.catch_warnings():
        warnings.simplefilter("error", ForceClosureWarning)
        case = load_config(EXAMPLES / f"{name}.toml")
    assert case.warnings == ()


# One case per length kind the rule claims: (changes to the nominal config, the key path, the value in
# the message, the limit's words, the hint, the changes that follow the hint). Each value is a
# millimetre (or micrometre) figure written as a bare number.
KINDS = [
    (
        "lift h",
        dict(h="25"),
        "program.feed.segments[1].h",
        "the lift 25 m",
        "10 x the base radius 0.04 m",
        '"25 mm"',
        dict(h='"25 mm"'),
    ),
    (
        "lift start_h",
        dict(start_h="3", back="3"),
        "program.feed.start_h",
        "the lift 3 m",
        "10 x the base radius",
        '"3 mm"',
        dict(start_h='"3 mm"', back='"3 mm"'),
    ),
    (
        "lift interior_h",
        dict(interior_h="6"),
        "program.feed.segments[3].interior_h[0]",
        "the lift 6 m",
        "10 x the base radius",
        '"6 mm"',
        dict(interior_h='"6 mm"'),
    ),
    (
        "base_radius absolute",
        dict(follower='{ type = "translating_roller", base_radius = 40, roller_radius = "10 mm" }'),
        "contact[0].follower.base_radius",
        "the base radius 40 m",
        "1 m",
        '"40 mm"',
        dict(follower='{ type = "translating_roller", base_radius = "40 mm", roller_radius = "10 mm" }'),
    ),
    (
        "base_radius vs roller",
        dict(follower='{ type = "translating_roller", base_radius = 0.9, roller_radius = "6 mm" }'),
        "contact[0].follower.base_radius",
        "the base radius 0.9 m",
        "100 x the roller radius 0.006 m",
        '"0.9 mm"',
        None,
    ),
    (
        "roller_radius",
        dict(follower='{ type = "translating_roller", base_radius = "40 mm", roller_radius = 10 }'),
        "contact[0].follower.roller_radius",
        "the roller radius 10 m",
        "10 x the base radius 0.04 m",
        '"10 mm"',
        dict(follower='{ type = "translating_roller", base_radius = "40 mm", roller_radius = "10 mm" }'),
    ),
    (
        "offset",
        dict(follower='{ type = "translating_flat", base_radius = "40 mm", offset = 5 }'),
        "contact[0].follower.offset",
        "the offset 5 m",
        "10 x the base radius",
        '"5 mm"',
        dict(follower='{ type = "translating_flat", base_radius = "40 mm", offset = "5 mm" }'),
    ),
    (
        "eccentricity radius",
        dict(contact_extra='eccentricity = { radius = 0.01 }'),
        "contact[0].eccentricity.radius",
        "the eccentricity radius 0.01 m",
        "a tenth of the base radius 0.04 m",
        '"0.01 mm"',
        dict(contact_extra='eccentricity = { radius = "0.01 mm" }'),
    ),
    (
        "waviness amplitude",
        dict(program_extra='[program.feed.error]\nwaviness = [{ amplitude = 5, order = 3 }]\n'),
        "program.feed.error.waviness[0].amplitude",
        "the waviness amplitude 5 m",
        "a tenth of the base radius",
        '"5 um"',
        dict(program_extra='[program.feed.error]\nwaviness = [{ amplitude = "5 um", order = 3 }]\n'),
    ),
    (
        "dent depth",
        dict(program_extra='[program.feed.error]\ndent = [{ centre = "100 deg", width = "4 deg", depth = 20 }]\n'),
        "program.feed.error.dent[0].depth",
        "the dent depth 20 m",
        "a tenth of the base radius",
        '"20 um"',
        dict(program_extra='[program.feed.error]\ndent = [{ centre = "100 deg", width = "4 deg", depth = "20 um" }]\n'),
    ),
]


@pytest.mark.parametrize("kind, changes, key, value, limit, hint, fixed", KINDS, ids=[k[0] for k in KINDS])
def test_each_length_kind_is_refused_at_its_key_with_a_hint(tmp_path, kind, changes, key, value, limit, hint, fixed):
    path, text = write(tmp_path, **changes)
    with pytest.raises(ValueError) as e:
        load_config(path)
    message = str(e.value)
    m = re.match(
        rf"{re.escape(str(path))}:(\d+): {re.escape(key)}: {re.escape(value)} is more than "
        rf"{re.escape(limit)}.*: did you mean {re.escape(hint)}\?",
        message,
    )
    assert m, message
    # The line is the key's own.
    assert key.split(".")[-1].split("[")[0] in text.splitlines()[int(m.group(1)) - 1]
    # Written as the hint says, it loads.
    if fixed is not None:
        load_config(write(tmp_path, **{**changes, **fixed})[0])


def test_an_offset_the_model_refuses_gets_the_hint_after_the_models_message(tmp_path):
    # A roller's offset must stay within the base and roller radii: the model says so first (as before),
    # and the hint follows when the offset is a bare number far too large.
    path, text = write(
        tmp_path, follower='{ type = "translating_roller", base_radius = "40 mm", roller_radius = "10 mm", offset = 5 }'
    )
    with pytest.raises(ValueError) as e:
        load_config(path)
    line = line_of(text, "offset = 5 }")
    assert str(e.value).startswith(
        f"{path}:{line}: contact[0].follower.offset: must satisfy |offset| < base_radius + roller_radius"
    )
    assert str(e.value).endswith(
        '; the offset 5 m is more than 10 x the base radius 0.04 m of contact \'cam\': did you mean '
        '"5 mm"? (a bare number is metres; write "5 m" if you mean it)'
    )
    # Within the radii but written with a unit: no hint, the model's message alone.
    path, _ = write(
        tmp_path,
        follower='{ type = "translating_roller", base_radius = "40 mm", roller_radius = "10 mm", offset = "5 m" }',
    )
    with pytest.raises(ValueError, match=r"must satisfy \|offset\| < base_radius \+ roller_radius = 0\.05 m, got 5 m$"):
        load_config(path)


# The oscillating followers' lengths, on a swing arm (arm angle lift: not a length, never compared).
SWING = """\
[camshaft]
speed = 600
[program.swing]
segments = [{{ law = "cycloidal", end = "150 deg", h = "15 deg" }}, {{ law = "dwell", end = "210 deg" }},
            {{ law = "cycloidal", end = "300 deg", h = 0 }}, {{ law = "dwell", end = "360 deg" }}]
[[dof]]
name = "arm"
mass = "2e-3 kg m^2"
[[spring]]
name = "return_spring"
a = "arm"
stiffness = "40 N m/rad"
preload = 3.0
[[contact]]
name = "cam"
program = "swing"
follower = {follower}
follower_dof = "arm"
stiffness = 1e8
"""

OSCILLATING = [
    (
        "arm_length",
        '{ type = "oscillating_roller", base_radius = "30 mm", roller_radius = "8 mm", '
        'pivot = ["60 mm", "50 mm"], arm_length = 60 }',
        "contact[0].follower.arm_length",
        "the arm length 60 m",
        "100 x the base radius 0.03 m",
        '"60 mm"',
    ),
    (
        "pivot",
        '{ type = "oscillating_roller", base_radius = "30 mm", roller_radius = "8 mm", pivot = [60, 50], '
        'arm_length = "60 mm" }',
        "contact[0].follower.pivot",
        "the pivot's distance from the cam centre 78.10249676 m",
        "100 x the base radius 0.03 m",
        '["60 mm", "50 mm"]',
    ),
    (
        "base_radius vs pivot",
        '{ type = "oscillating_roller", base_radius = 30, roller_radius = "8 mm", '
        'pivot = ["60 mm", "50 mm"], arm_length = "60 mm" }',
        "contact[0].follower.base_radius",
        "the base radius 30 m",
        "1 m",
        '"30 mm"',
    ),
    (
        "face_offset",
        '{ type = "oscillating_flat", base_radius = "35 mm", pivot = ["0 mm", "80 mm"], face_offset = 6 }',
        "contact[0].follower.face_offset",
        "the face offset 6 m",
        "10 x the base radius 0.035 m",
        '"6 mm"',
    ),
]


@pytest.mark.parametrize("kind, follower, key, value, limit, hint", OSCILLATING, ids=[k[0] for k in OSCILLATING])
def test_each_oscillating_follower_length_is_refused_with_a_hint(tmp_path, kind, follower, key, value, limit, hint):
    path = tmp_path / "swing.toml"
    path.write_text(SWING.format(follower=follower))
    with pytest.raises(
        ValueError,
        match=rf"^{re.escape(str(path))}:\d+: {re.escape(key)}: {re.escape(value)} is more "
        rf"than {re.escape(limit)}.*did you mean {re.escape(hint)}\?",
    ):
        load_config(path)


def test_base_radius_against_the_arm_and_pivot_below_one_metre(tmp_path):
    # 0.9 m passes the 1 m bound but not 10 x the 60 mm arm (nor 10 x the pivot's 78 mm distance).
    path = tmp_path / "swing.toml"
    path.write_text(
        SWING.format(
            follower='{ type = "oscillating_roller", base_radius = 0.9, roller_radius = "10 mm", '
            'pivot = ["60 mm", "50 mm"], arm_length = "60 mm" }'
        )
    )
    with pytest.raises(
        ValueError,
        match=r"contact\[0\]\.follower\.base_radius: the base radius 0\.9 m is more than "
        r"10 x the arm length 0\.06 m of contact 'cam'.*\"0\.9 mm\"",
    ):
        load_config(path)


@pytest.mark.parametrize("factor, refused", [(1.0, False), (1.0 + 1e-6, True)])
def test_the_limits_are_inclusive(tmp_path, factor, refused):
    # A roller of exactly 10 base radii (2^-5 m: exact in binary) passes the guard; a hair more does not.
    rb = 2.0**-5
    follower = f'{{ type = "translating_roller", base_radius = {rb!r}, roller_radius = {10 * rb * factor!r} }}'
    path, _ = write(tmp_path, follower=follower, h='"5 mm"', interior_h='"2 mm"')
    if refused:
        with pytest.raises(ValueError, match=r"roller_radius: the roller radius .* is more than 10 x the base radius"):
            load_config(path)
    else:
        load_config(path)


def test_the_presets_lengths_are_checked_too(tmp_path):
    path = tmp_path / "p.toml"
    base = (
        '[camshaft]\nspeed = 750\n[program.p]\nsegments = [{ law = "cycloidal", end = "180 deg", h = H },'
        ' { law = "cycloidal", end = "360 deg", h = 0 }]\n[preset]\nname = "paper"\nprogram = "p"\n'
    )
    path.write_text(base.replace("H", "20"))
    with pytest.raises(
        ValueError,
        match=r"p\.toml:4: program\.p\.segments\[0\]\.h: the lift 20 m is more than 10 x the "
        r"base radius .* of the paper preset's cam.*\"20 mm\"",
    ):
        load_config(path)
    path.write_text(base.replace("H", '"20 mm"') + "[preset.parameters]\nroller_radius = 12\n")
    with pytest.raises(ValueError, match=r"preset\.parameters\.roller_radius: the roller radius 12 m .*\"12 mm\""):
        load_config(path)
    path.write_text("[camshaft]\nspeed = 2000\n[preset]\nname = \"valve_train\"\n[preset.parameters]\nlift = 9\n")
    with pytest.raises(
        ValueError,
        match=r"p\.toml:6: preset\.parameters\.lift: the lift 9 m is more than 10 x the base "
        r"radius 0\.018 m of the valve-train preset's cams.*\"9 mm\"",
    ):
        load_config(path)


# ---- force closure ------------------------------------------------------------------------------

# One flat-faced follower (the contact force acts along its axis: lever 1) of mass M on a spring of
# rate K and preload P, lifted H by a cycloidal rise over BETA and a slower cycloidal return over
# BACK (so that the rise's deceleration is where contact goes first, at one angle).
M, K, P, H, BETA, BACK = 0.25, 2.0e4, 60.0, 0.010, math.radians(120.0), math.radians(150.0)


def one_mass(rpm, spring=True):
    data = {
        "camshaft": {"speed": rpm},
        "program": {
            "c": {
                "segments": [
                    {"law": "cycloidal", "end": BETA, "h": H},
                    {"law": "cycloidal", "end": BETA + BACK, "h": 0},
                    {"law": "dwell", "end": 2 * math.pi},
                ]
            }
        },
        "dof": [{"name": "f", "mass": M}],
        "contact": [
            {
                "name": "cam",
                "program": "c",
                "follower_dof": "f",
                "stiffness": 1e10,
                "follower": {"type": "translating_flat", "base_radius": 0.05},
            }
        ],
    }
    if spring:
        data["spring"] = [{"name": "s", "a": "f", "stiffness": K, "preload": P}]
    return data


def closed_form(omega):
    """The rigid contact force P + K h + M omega^2 h'' of the cycloidal rise and return (written out
    here from the law, not taken from the library), on a fine grid of the revolution."""
    theta = np.linspace(0.0, 2 * math.pi, 200001)
    rise, back = theta <= BETA, (theta > BETA) & (theta <= BETA + BACK)
    u = np.where(rise, theta / BETA, np.clip((theta - BETA) / BACK, 0.0, 1.0))
    wave = np.sin(2 * math.pi * u) / (2 * math.pi)
    h = np.where(rise, H * (u - wave), np.where(back, H * (1 - u + wave), 0.0))
    d2h = np.where(
        rise,
        H * 2 * math.pi / BETA**2 * np.sin(2 * math.pi * u),
        np.where(back, -H * 2 * math.pi / BACK**2 * np.sin(2 * math.pi * u), 0.0),
    )
    return theta, P + K * h + M * omega**2 * d2h, P + K * h, d2h


def critical_rpm():
    theta, _, static, d2h = closed_form(0.0)
    decel = d2h < 0
    omega = np.sqrt(np.min(static[decel] / (-M * d2h[decel])))
    return omega * 30 / math.pi


def test_the_rigid_check_loses_contact_just_above_the_closed_form_speed_and_not_below():
    rpm_c = critical_rpm()
    assert 1000 < rpm_c < 5000  # a real speed, not an edge of the model's range
    below = force_closure(config_from_dict(one_mass(0.99 * rpm_c)))
    assert below["warnings"] == []
    above = force_closure(config_from_dict(one_mass(1.01 * rpm_c)))
    (message,) = above["warnings"]
    assert message.startswith(f"contact 'cam' is not force-closed at {1.01 * rpm_c:.0f} rpm: in the rigid check")
    (c,) = above["contacts"]
    assert c["rigid_limit_rpm"] == pytest.approx(rpm_c, rel=2e-4)
    # The force and its angle: the closed form's minimum at that speed.
    theta, force, _, _ = closed_form(1.01 * rpm_c * math.pi / 30)
    # To the 0.5 deg grid's error: about (0.5 deg)^2 / 12 x (2 pi / BETA)^2 = 6e-5 of the peak inertia
    # force (244 N) in the second difference, and as much again between grid points.
    inertia = M * (1.01 * rpm_c * math.pi / 30) ** 2 * H * 2 * math.pi / BETA**2
    assert 200 < inertia < 300
    assert c["rigid_min_force_N"] == pytest.approx(force.min(), abs=2e-4 * inertia)
    assert c["rigid_min_angle_deg"] == pytest.approx(math.degrees(theta[force.argmin()]), abs=0.5)
    assert f"falls to {c['rigid_min_force_N']:.4g} N at cam angle {c['rigid_min_angle_deg']:.1f} deg" in message
    # Where it is negative: the closed form's interval, to the grid's 0.5 deg.
    ((lo, hi),) = c["rigid_loss_deg"]
    lost = np.degrees(theta[force < 0])
    assert lo == pytest.approx(lost.min(), abs=0.6) and hi == pytest.approx(lost.max(), abs=0.6)
    # At rest the spring holds it: P + K h, smallest on the base circle, less the contact's own
    # deflection F / 1e10 N/m against the spring (P / (1 + K / 1e10)).
    assert c["static_min_force_N"] == pytest.approx(P / (1 + K / 1e10), rel=1e-9)


def test_the_rigid_check_at_another_speed_scales_like_the_closed_form():
    # force_closure(rpm=...) of a case built at another speed: the same answer as building it there.
    rpm_c = critical_rpm()
    here = force_closure(config_from_dict(one_mass(300.0)), rpm=1.05 * rpm_c)
    there = force_closure(config_from_dict(one_mass(1.05 * rpm_c)))
    assert here["contacts"][0]["rigid_min_force_N"] == pytest.approx(
        there["contacts"][0]["rigid_min_force_N"], rel=1e-9
    )
    assert len(here["warnings"]) == 1
    # ... and that answer is the closed form's smallest force at that speed (to the check's grid).
    omega = 1.05 * rpm_c * math.pi / 30
    expected = np.min(closed_form(omega)[1])
    assert here["contacts"][0]["rigid_min_force_N"] == pytest.approx(expected, rel=1e-3, abs=1e-3 * P)


@pytest.mark.parametrize("rpm", [1.0, 60.0, 600.0, 6000.0])
def test_no_spring_at_all_warns_at_any_speed(rpm):
    r = force_closure(config_from_dict(one_mass(rpm, spring=False)))
    (message,) = r["warnings"]
    assert message.startswith("contact 'cam' is not force-closed: at rest its contact force is <= 0 (0 N at cam angle")
    assert "over the whole revolution" in message and "add a return spring" in message
    assert r["contacts"][0]["rigid_limit_rpm"] == 0.0


def test_a_spring_without_preload_warns_where_the_follower_rests_on_the_base_circle():
    data = one_mass(300.0)
    data["spring"][0]["preload"] = 0.0
    (c,) = force_closure(config_from_dict(data))["contacts"]
    # P = 0: the force K h is zero exactly on the dwell, from BETA + BACK = 270 deg round to 0.
    ((lo, hi),) = c["static_open_deg"]
    assert lo == pytest.approx(270.0, abs=0.6) and hi == pytest.approx(0.0, abs=0.6)


def test_the_paper_preset_at_its_speed_does_not_warn(tmp_path):
    path = tmp_path / "paper.toml"
    path.write_text('[camshaft]\nspeed = 750\n[preset]\nname = "paper"\n')
    with warnings.catch_warnings():
        warnings.simplefilter("error", ForceClosureWarning)
        case = load_config(path)
    (c,) = case.force_closure()["contacts"]
    assert c["static_min_force_N"] > 100 and c["rigid_min_force_N"] > 0 and c["rigid_limit_rpm"] > 750


def test_load_config_warns_with_its_category_and_names_the_file(tmp_path):
    path = tmp_path / "loose.toml"
    path.write_text(_toml(one_mass(600.0, spring=False)))
    with pytest.warns(ForceClosureWarning, match=rf"^{re.escape(str(path))}: contact 'cam' is not force-closed"):
        case = load_config(path)
    assert len(case.warnings) == 1


def _toml(data):
    """A flat enough dict as TOML text (the few shapes one_mass makes)."""

    def value(v):
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, dict):
            return "{ " + ", ".join(f"{k} = {value(x)}" for k, x in v.items()) + " }"
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(float(v))

    out = [f"[camshaft]\nspeed = {value(data['camshaft']['speed'])}"]
    for name, p in data["program"].items():
        out.append(f"[program.{name}]\nsegments = {value(p['segments'])}")
    for kind in ("dof", "spring", "contact"):
        for block in data.get(kind, []):
            out.append(f"[[{kind}]]\n" + "\n".join(f"{k} = {value(v)}" for k, v in block.items()))
    return "\n".join(out) + "\n"


def test_the_figures_command_prints_the_warning_and_lists_it_in_the_summary(tmp_path, capsys):
    path = tmp_path / "loose.toml"
    data = one_mass(1.2 * critical_rpm())
    path.write_text(_toml(data) + "[solver]\nsteps_per_revolution = 2048\n")
    assert cli.main(["figures", str(path), "-o", str(tmp_path / "out")]) == 0
    err = capsys.readouterr().err
    (line,) = [x for x in err.splitlines() if x.startswith("camfollower: warning: ")]
    assert "contact 'cam' is not force-closed at" in line
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["warnings"] == [line.removeprefix("camfollower: warning: ")]


def test_the_figures_summary_of_a_force_closed_case_has_an_empty_list(tmp_path, capsys):
    path = tmp_path / "tight.toml"
    path.write_text(_toml(one_mass(0.5 * critical_rpm())) + "[solver]\nsteps_per_revolution = 2048\n")
    assert cli.main(["figures", str(path), "-o", str(tmp_path / "out")]) == 0
    assert "warning" not in capsys.readouterr().err
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["warnings"] == []


# ---- rotations and translations -----------------------------------------------------------------

SWING_ARM = (EXAMPLES / "swing_arm.toml").read_text()


@pytest.mark.parametrize(
    "old, new, key, at, words",
    [
        # The arm of an oscillating follower turns: its "mass" is an inertia. Its torsional spring says
        # so first (without units there, the contact does: below).
        (
            'mass = "2e-4 kg m^2"',
            'mass = "0.2 kg"',
            "spring[0].stiffness",
            'stiffness = "20 N m/rad"',
            "(or, if 'arm' turns, its mass in kg m^2)",
        ),
        # A torsional spring's rate, damping and preload in a translation's units.
        ('stiffness = "20 N m/rad"', 'stiffness = "20 N/mm"', "spring[0].stiffness", "20 N/mm", "write it in N m/rad"),
        ("preload = 3.0", 'preload = "3 N"', "spring[0].preload", '"3 N"', "write it in N m or N mm (a moment)"),
        ("preload = 3.0", 'preload = 3.0\ndamping = "2 N s/m"', "spring[0].damping", "2 N s/m", "in N m s/rad"),
    ],
)
def test_a_unit_of_the_other_motion_is_refused_at_its_key(tmp_path, old, new, key, at, words):
    path = tmp_path / "arm.toml"
    path.write_text(SWING_ARM.replace(old, new))
    with pytest.raises(ValueError) as e:
        load_config(path)
    line = line_of(path.read_text(), at)
    assert str(e.value).startswith(f"{path}:{line}: {key}: ") and words in str(e.value), str(e.value)


def test_a_torsional_preload_in_newton_metres_is_taken_as_a_moment(tmp_path):
    """The preload of a spring on a turning DOF may be written as a moment (it could not be before)."""
    path = tmp_path / "arm.toml"
    path.write_text(SWING_ARM.replace("preload = 3.0", 'preload = "3000 N mm"'))
    spring = load_config(path).builder.__getstate__()["springs"][0]
    assert spring["preload"] == pytest.approx(3.0)


def test_a_follower_dof_of_the_other_motion_is_refused_at_the_contact(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(SWING_ARM.replace('mass = "2e-4 kg m^2"', 'mass = "0.2 kg"').replace('"20 N m/rad"', "20"))
    with pytest.raises(ValueError) as e:
        load_config(path)
    line = line_of(path.read_text(), 'follower_dof = "arm"')
    assert str(e.value).startswith(
        f"{path}:{line}: contact[0].follower_dof: DOF 'arm' is an oscillating follower's arm angle (rad), so it "
        "turns, but its mass is written in units of a DOF that translates: write its moment of inertia in kg m^2"
    )


def test_a_translating_follower_on_an_inertia_and_a_spring_joining_both_motions_are_refused(tmp_path):
    text = (
        ROLLER.format(**NOMINAL)
        .replace('mass = "250 g"', 'mass = "250 kg mm^2"')
        .replace('stiffness = "20 N/mm"', "stiffness = 20000")
        .replace('preload = "300 N"', "preload = 300")
    )
    path = tmp_path / "c.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match=r"contact\[0\]\.follower_dof: DOF 'carrier' is a translating follower's lift"):
        load_config(path)
    text = (
        ROLLER.format(**NOMINAL)
        + '\n[[dof]]\nname = "arm"\nmass = "1 kg m^2"\n\n[[spring]]\nname = "link"\na = "arm"\nb = "carrier"\nstiffness = 1e5\n'
    )
    path.write_text(text)
    with pytest.raises(
        ValueError, match=r"spring\[1\]\.b: joins DOF 'arm', which turns .* and DOF 'carrier', which translates"
    ):
        load_config(path)


def test_bare_numbers_state_no_motion_and_load_as_before(tmp_path):
    path = tmp_path / "arm.toml"
    path.write_text(
        SWING_ARM.replace('mass = "2e-4 kg m^2"', "mass = 2e-4").replace('stiffness = "20 N m/rad"', "stiffness = 20")
    )
    assert load_config(path).builder.__getstate__()["springs"][0]["stiffness"] == pytest.approx(20.0)


def test_a_bare_arm_angle_beyond_a_quarter_turn_is_taken_for_degrees(tmp_path):
    """An oscillating follower's lift is an arm angle, radians when bare: "h = 15" on the swing arm is a
    15 rad (860 deg) swing, refused at its key with the degrees it means; with a unit, or a plausible
    bare radian value, it loads."""
    base = (EXAMPLES / "swing_arm.toml").read_text()
    assert 'h = "15 deg" }' in base
    path = tmp_path / "arm.toml"
    path.write_text(base.replace('h = "15 deg" }', "h = 15 }"))  # the rise and the dwell after it
    with pytest.raises(ValueError) as e:
        load_config(path)
    line = [i + 1 for i, t in enumerate(path.read_text().splitlines()) if "h = 15 }" in t][0]
    assert str(e.value).startswith(f"{path}:{line}: program.swing.segments[1].h: the arm's lift 15 rad of contact ")
    assert 'did you mean "15 deg"? (a bare number is radians; write "15 rad" if you mean it)' in str(e.value)
    for h, rad in (("0.2617993877991494", 0.2617993877991494), ('"15 deg"', math.radians(15.0))):
        path.write_text(base.replace('h = "15 deg" }', f"h = {h} }}"))
        assert load_config(path).programs["swing"].max_lift() == pytest.approx(rad)
