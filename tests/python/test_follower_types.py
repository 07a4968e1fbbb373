# SPDX-License-Identifier: BSD-3-Clause
"""Every follower type from its one parameter description (include/camfollower/follower/parameters.hpp):
the Python class, its keywords and defaults, its properties, pickling and repr, and the config's keys are
all generated from that description. Each is checked here for every type the config reader accepts, with
values and defaults written out independently of the description."""

import copy
import math
import pickle
import re

import camfollower as cf
import numpy as np
import pytest
from camfollower.config import config_from_dict
from camfollower.export import is_barrel, write_csv, write_groove_csv

# Every parameter given, in SI (the Python API), and the same values as a config writes them.
GIVEN = {
    "translating_roller": dict(base_radius=0.04, roller_radius=0.012, offset=0.005),
    "translating_flat": dict(base_radius=0.04, face_angle=0.1, offset=0.003),
    "oscillating_roller": dict(
        base_radius=0.04, roller_radius=0.01, pivot=(0.1, 0.05), arm_length=0.08, turn="clockwise"
    ),
    "oscillating_flat": dict(base_radius=0.04, pivot=(0.12, 0.0), face_offset=0.004, turn="clockwise"),
    "barrel_roller": dict(cylinder_radius=0.06, groove_depth=0.016, roller_radius=0.01),
    "barrel_arm_roller": dict(
        cylinder_radius=0.06,
        groove_depth=0.016,
        roller_radius=0.01,
        pivot=(-0.1, 0.02),
        arm_length=0.12,
        turn="counter_clockwise",
    ),
}
IN_CONFIG = {
    "translating_roller": dict(base_radius="40 mm", roller_radius="12 mm", offset="5 mm"),
    "translating_flat": dict(base_radius="40 mm", face_angle="0.1 rad", offset="3 mm"),
    "oscillating_roller": dict(
        base_radius="40 mm", roller_radius="10 mm", pivot=["100 mm", "50 mm"], arm_length="80 mm", turn="clockwise"
    ),
    "oscillating_flat": dict(base_radius="40 mm", pivot=["120 mm", "0 mm"], face_offset="4 mm", turn="clockwise"),
    "barrel_roller": dict(cylinder_radius="60 mm", groove_depth="16 mm", roller_radius="10 mm"),
    "barrel_arm_roller": dict(
        cylinder_radius="60 mm",
        groove_depth="16 mm",
        roller_radius="10 mm",
        pivot=["-100 mm", "20 mm"],
        arm_length="120 mm",
        turn="counter_clockwise",
    ),
}
# The optional parameters and their documented defaults (docs/config.md, the docstrings).
DEFAULTS = {
    "translating_roller": dict(offset=0.0),
    "translating_flat": dict(face_angle=0.0, offset=0.0),
    "oscillating_roller": dict(turn="counter_clockwise"),
    "oscillating_flat": dict(face_offset=0.0, turn="counter_clockwise"),
    "barrel_roller": dict(),
    "barrel_arm_roller": dict(turn="counter_clockwise"),
}
TYPES = sorted(GIVEN)


def class_of(type_name):
    return getattr(cf, "".join(part.capitalize() for part in type_name.split("_")))


def parameters_of(follower, names):
    return {name: getattr(follower, name) for name in names}


def same(a, b):
    """Parameter dicts equal: numbers exactly, points element by element, turns by name."""
    assert a.keys() == b.keys()
    for k in a:
        if isinstance(a[k], str) or isinstance(b[k], str):
            assert a[k] == b[k], k
        else:
            np.testing.assert_array_equal(np.asarray(a[k], float), np.asarray(b[k], float), err_msg=k)


def config(follower, type_name):
    translating = class_of(type_name).translating
    lift = "5 mm" if translating else "5 deg"
    mass, stiffness, preload = ("0.2 kg", "20 N/mm", "30 N") if translating else ("2e-4 kg m^2", 20.0, 3.0)
    return {
        "camshaft": {"speed": "600 rpm"},
        "program": {
            "p": {
                "segments": [
                    {"law": "dwell", "end": "60 deg"},
                    {"law": "cycloidal", "end": "150 deg", "h": lift},
                    {"law": "dwell", "end": "210 deg", "h": lift},
                    {"law": "cycloidal", "end": "300 deg", "h": 0},
                    {"law": "dwell", "end": "360 deg", "h": 0},
                ]
            }
        },
        "dof": [{"name": "f", "mass": mass}],
        "spring": [{"name": "s", "a": "f", "stiffness": stiffness, "preload": preload}],
        "contact": [{"name": "cam", "program": "p", "follower": follower, "follower_dof": "f", "stiffness": 1e8}],
    }


def test_every_type_the_config_accepts_is_checked_here():
    with pytest.raises(ValueError) as e:
        config_from_dict(config({"type": "nonsense", "base_radius": "40 mm"}, "translating_roller"))
    listed = re.findall(r'"([a-z_]+)"', str(e.value).split("must be one of", 1)[1].split("got")[0])
    assert sorted(listed) == TYPES, str(e.value)


@pytest.mark.parametrize("type_name", TYPES)
def test_keywords_properties_repr_and_pickle(type_name):
    cls = class_of(type_name)
    given = GIVEN[type_name]
    follower = cls(**given)
    same(parameters_of(follower, given), given)
    # Positionally, in the documented order, the same follower.
    same(parameters_of(cls(*given.values()), given), given)
    # The repr reads back as the same follower; a pickle and a copy are the same follower.
    back = eval(repr(follower), {cls.__name__: cls})
    assert repr(back) == repr(follower)
    same(parameters_of(back, given), given)
    for twin in (pickle.loads(pickle.dumps(follower)), copy.deepcopy(follower)):
        same(parameters_of(twin, given), given)
    assert cls.__doc__ and "follower" in cls.__doc__.lower()


@pytest.mark.parametrize("type_name", TYPES)
def test_omitted_optional_parameters_take_their_documented_defaults(type_name):
    cls = class_of(type_name)
    required = {k: v for k, v in GIVEN[type_name].items() if k not in DEFAULTS[type_name]}
    same(parameters_of(cls(**required), DEFAULTS[type_name]), DEFAULTS[type_name])
    for name in required:  # and every required one is required
        with pytest.raises(TypeError):
            cls(**{k: v for k, v in required.items() if k != name})


@pytest.mark.parametrize("type_name", TYPES)
def test_the_config_builds_the_same_follower_from_its_keys(type_name):
    case = config_from_dict(config({"type": type_name, **IN_CONFIG[type_name]}, type_name))
    follower = case.builder.contacts[0]["follower"]
    assert type(follower) is class_of(type_name)
    given = GIVEN[type_name]
    read = parameters_of(follower, given)
    for k, v in given.items():
        if isinstance(v, str):
            assert read[k] == v
        else:
            np.testing.assert_allclose(read[k], v, rtol=1e-15, atol=0, err_msg=k)
    # Only the optional keys left out: the defaults.
    required = {k: v for k, v in IN_CONFIG[type_name].items() if k not in DEFAULTS[type_name]}
    case = config_from_dict(config({"type": type_name, **required}, type_name))
    same(parameters_of(case.builder.contacts[0]["follower"], DEFAULTS[type_name]), DEFAULTS[type_name])


@pytest.mark.parametrize("type_name", TYPES)
def test_another_types_key_and_a_misspelt_key_are_refused_at_the_key(type_name):
    foreign = next(
        key for other in TYPES for key in IN_CONFIG[other] if other != type_name and key not in IN_CONFIG[type_name]
    )
    value = IN_CONFIG[next(o for o in TYPES if foreign in IN_CONFIG[o])][foreign]
    follower = {"type": type_name, **IN_CONFIG[type_name], foreign: value}
    with pytest.raises(ValueError, match=rf"contact\[0\]\.follower\.{foreign}: is not used in this configuration"):
        config_from_dict(config(follower, type_name))
    follower = {"type": type_name, **IN_CONFIG[type_name], "base_raduis": "40 mm"}
    with pytest.raises(ValueError, match=r"follower\.base_raduis: unknown key; known here: type, base_radius, ") as e:
        config_from_dict(config(follower, type_name))
    assert all(name in str(e.value) for name in GIVEN[type_name])  # every type's keys are listed


@pytest.mark.parametrize("type_name", TYPES)
def test_the_exports_header_names_every_parameter_in_order_with_its_unit(type_name, tmp_path):
    case = config_from_dict(config({"type": type_name, **IN_CONFIG[type_name]}, type_name))
    follower = case.builder.contacts[0]["follower"]
    # A barrel cam's file is its groove's.
    (write_groove_csv if is_barrel(follower) else write_csv)(
        tmp_path / "cam.csv", follower, case.programs["p"], points=360
    )
    lines = (tmp_path / "cam.csv").read_text().splitlines()
    (line,) = [x for x in lines if x.startswith("#") and f"{type_name}: " in x]
    words = dict(part.split(" = ") for part in line.split(f"{type_name}: ", 1)[1].split(", ") if " = " in part)
    assert list(words) == list(GIVEN[type_name])  # every parameter, in order (a point's y shares its comma)
    for name, written in IN_CONFIG[type_name].items():
        if name == "face_angle":
            assert words[name] == f"{math.degrees(0.1):.10g} deg"
        elif name == "turn":
            assert words[name] == written
        elif name != "pivot":
            assert words[name] == written  # lengths in mm, as the config wrote them
