# SPDX-License-Identifier: BSD-3-Clause
"""The third hardening round's classes in the model, the solver and the bindings: a model's size is
bounded before it costs minutes, long compiled phases stop on request, every role of an element names
a DOF of its own and every element a name of its own, a recording that would hold nothing is refused by
the option's name, motion inputs that overflow are refused at construction, argument mismatches are
short errors naming the call, and an instance whose __init__ never ran raises instead of crashing."""

import math
import subprocess
import sys
import textwrap
import time

import camfollower as cf
import numpy as np
import pytest

PROGRAM = cf.MotionProgram.paper_default()


def one_dof():
    b = cf.MechanismBuilder()
    b.add_dof("f", 0.5)
    b.add_dof("g", 0.2)
    b.add_spring("spring", "f", "ground", stiffness=2e4, preload=300.0)
    b.add_spring("mount", "g", "ground", stiffness=1e7)
    return b


def shaft_builder(elements: int, length: float = 0.5):
    b = cf.MechanismBuilder()
    b.add_shaft("s", length=length, outer_diameter=0.03, max_element_length=length / elements, stations=[0.0, length])
    b.add_bearing("b0", "s", 0.0, stiffness=1e8)
    b.add_bearing("b1", "s", length, stiffness=1e8)
    b.add_drive("drive", "s", 0.0, stiffness=1e4)
    return b


# --- item 1: the model's size is bounded before it is built ---


@pytest.mark.parametrize("element", [1e-6, 20e-6])
def test_a_shaft_mesh_absurd_for_its_section_is_refused_at_once(element):
    b = cf.MechanismBuilder()
    start = time.monotonic()
    with pytest.raises(ValueError, match=r"shaft 's' max_element_length = .* radius of gyration .*um written for mm"):
        b.add_shaft("s", length=0.05, outer_diameter=0.03, max_element_length=element)
    assert time.monotonic() - start < 5.0


def test_a_config_with_a_micrometre_mesh_is_refused_at_once(tmp_path):
    text = (cf.__file__ and open(_example("camshaft.toml")).read()).replace(
        'max_element_length = "12 mm"', 'max_element_length = "20 um"'
    )
    config = tmp_path / "camshaft.toml"
    config.write_text(text)
    start = time.monotonic()
    with pytest.raises(ValueError, match=r"camshaft.toml:\d+.*max_element_length"):
        cf.load_config(config)
    assert time.monotonic() - start < 5.0


def test_a_shaft_is_limited_in_elements_and_a_mechanism_in_dofs():
    with pytest.raises(ValueError, match=r"would make about 1000 elements \(limit 500 per shaft"):
        shaft_builder(1000, length=1.0)
    b = shaft_builder(400)  # 401 nodes x 5 DOFs
    b.add_shaft("t", length=0.5, outer_diameter=0.03, max_element_length=0.5 / 400, stations=[0.0, 0.5])
    start = time.monotonic()
    with pytest.raises(ValueError, match=r"the mechanism has 4010 DOFs, more than the 3000"):
        b.build()
    assert time.monotonic() - start < 5.0


# --- item 2: long phases stop on request; the cheap refusal comes first ---


def test_a_run_with_much_work_between_output_steps_is_cancelled_promptly():
    mech = cf.presets.paper()
    calls = []

    def stop(done, planned):
        calls.append(done)
        return False

    start = time.monotonic()
    # 5e-3 s in steps of at most 1e-10 s: 5e7 integration steps (half a minute) in 25 output steps.
    r = cf.simulate(
        mech,
        method="dormand_prince",
        tolerance=1e-6,
        max_step=1e-10,
        duration=5e-3,
        time_step=2e-4,
        progress=stop,
        progress_interval=0.05,
    )
    assert time.monotonic() - start < 5.0
    assert r.stats["cancelled"] and calls
    assert r.rows < 6


def test_ctrl_c_stops_an_adaptive_run_within_an_output_interval(ctrl_c):
    start = ctrl_c(0.5)
    with pytest.raises(KeyboardInterrupt):  # 1e7 integration steps in two output intervals: 15 s if not stopped
        cf.simulate(cf.presets.paper(), method="dop853", tolerance=1e-6, max_step=1e-10, duration=1e-3, time_step=5e-4)
    assert time.monotonic() - start < 5.0


def test_a_fixed_step_beyond_the_stability_limit_is_refused_before_the_factorizations():
    b = shaft_builder(180)  # 905 DOFs: the dense levels' factorizations would take tens of seconds
    m = b.build()
    start = time.monotonic()
    with pytest.raises(ValueError, match=r"time_step = .* exceeds the stability limit"):
        cf.simulate(m, method="fox_goodwin", linear_solver="low_rank", time_step=1e-4, duration=1e-3)
    assert time.monotonic() - start < 5.0


def test_the_dense_backend_is_bounded_in_size():
    m = shaft_builder(220).build()  # 1105 DOFs
    with pytest.raises(ValueError, match=r"linear_solver 'low_rank' \(dense\) is limited to 1000 DOFs.*'sparse'"):
        cf.simulate(m, linear_solver="low_rank", time_step=1e-6, duration=1e-5)


# --- item 3 (and 18): roles and names ---


@pytest.mark.parametrize(
    "roles, named",
    [
        (dict(lateral="f"), "lateral and follower_dof both name DOF 'f'"),
        (dict(cam_y="f"), "follower_dof and cam_y both name DOF 'f'"),
        (dict(cam_x="f"), "follower_dof and cam_x both name DOF 'f'"),
        (dict(cam_x="g", cam_y="g"), "cam_y and cam_x both name DOF 'g'"),
        (dict(cam_y="g", cam_twist="g"), "cam_twist and cam_y both name DOF 'g'"),
        (dict(lateral="g", cam_twist="g"), "cam_twist and lateral both name DOF 'g'"),
    ],
)
def test_each_role_of_a_contact_needs_a_dof_of_its_own(roles, named):
    b = one_dof()
    with pytest.raises(ValueError, match=rf"contact 'cam': {named}"):
        b.add_contact("cam", PROGRAM, cf.TranslatingRoller(0.03, 0.008), follower_dof="f", stiffness=1e8, **roles)


def test_each_role_of_a_contact_in_a_config_needs_a_dof_of_its_own(tmp_path):
    text = open(_example("translating_roller.toml")).read()
    follower = next(line.split("=")[1].strip() for line in text.splitlines() if line.startswith("follower_dof"))
    config = tmp_path / "case.toml"
    config.write_text(text.replace(f"follower_dof = {follower}", f"follower_dof = {follower}\nlateral = {follower}", 1))
    with pytest.raises(ValueError, match=r"case.toml.*lateral and follower_dof both name DOF"):
        cf.load_config(config)


def test_a_clearance_slides_along_a_dof_of_its_own():
    b = one_dof()
    with pytest.raises(ValueError, match=r"clearance 'guide': sliding_dof 'g' is also a DOF of the gap"):
        b.add_clearance("guide", [("g", 1.0)], clearance=1e-4, stiffness=1e8, friction=0.1, sliding_dof="g")


@pytest.mark.parametrize(
    "first, second, message",
    [
        ("contact", "clearance", "clearance 'cam': the name is taken by contact 'cam'"),
        ("clearance", "contact", "contact 'cam': the name is taken by clearance 'cam'"),
        ("contact", "spring", "element 'cam': the name is taken by contact 'cam'"),
        ("spring", "contact", "contact 'cam': the name is taken by element 'cam'"),
    ],
)
def test_one_name_one_element_whatever_its_kind(first, second, message):
    b = one_dof()
    add = {
        "contact": lambda: b.add_contact(
            "cam", PROGRAM, cf.TranslatingRoller(0.03, 0.008), follower_dof="f", stiffness=1e8
        ),
        "clearance": lambda: b.add_clearance("cam", [("g", 1.0)], clearance=1e-4, stiffness=1e8),
        "spring": lambda: b.add_spring("cam", "g", "f", stiffness=1e3),
    }
    add[first]()
    with pytest.raises(ValueError, match=message):
        add[second]()


# --- item 14: a recording that would hold nothing ---


@pytest.mark.parametrize(
    "options, named",
    [
        (
            dict(revolutions=1, record_last_revolutions=1e-300),
            "record_last_revolutions = 1e-300 .* fewer than two rows",
        ),
        (dict(revolutions=1, record_last_revolutions=3), "record_last_revolutions = 3 is longer than the run"),
        (
            dict(duration=0.01, record_from=0.02),
            r"record_from = 0.02 s: the recording window starts after the run ends",
        ),
        (dict(duration=0.01, decimation=10**6), "decimation = 1000000 steps .* a single row"),
    ],
)
def test_a_recording_window_without_rows_is_refused_by_the_option(options, named):
    with pytest.raises(ValueError, match=named):
        cf.simulate(cf.presets.paper(), time_step=1e-5, **options)


@pytest.mark.parametrize(
    "line, named",
    [
        ("record_last_revolutions = 1e-300", r"case.toml:\d+: output.record_last_revolutions: .* fewer than two rows"),
        (
            "record_last_revolutions = 3",
            r"case.toml:\d+: output.record_last_revolutions: .* longer than the run \(2 revolutions",
        ),
        (
            "decimation = 1000000",
            r"case.toml:\d+: output.decimation: decimation = 1000000 steps is longer than the run",
        ),
    ],
)
def test_a_config_recording_without_rows_is_refused_by_its_key(tmp_path, line, named):
    text = open(_example("translating_roller.toml")).read().replace("decimation = 10", line, 1)
    config = tmp_path / "case.toml"
    config.write_text(text)
    with pytest.raises(ValueError, match=named):
        cf.load_config(config)


# --- item 17: motion inputs that overflow ---


@pytest.mark.parametrize(
    "make, named",
    [
        (lambda: cf.ProfileError.dent(1.0, 5e-324, 1e-5), r"dent width must be in \[1e-06 rad"),
        (
            lambda: cf.MotionLaw.sine_constant_cosine(1e-310, 0.5, 0.5 - 1e-310),
            "b .sine fraction. must be 0 or at least",
        ),
        (
            lambda: cf.Segment(cf.MotionLaw.cycloidal(), 1.0, 1.0, 0.0, 0.01),
            "span theta_end - theta_start must be at least",
        ),
        (
            lambda: cf.Segment(cf.MotionLaw.cycloidal(), 1.0, 0.5, 0.0, 0.01),
            "span theta_end - theta_start must be at least",
        ),
        (
            lambda: cf.Segment(cf.MotionLaw.cycloidal(), math.nan, 1.0, 0.0, 0.01),
            "theta_start/theta_end must be finite",
        ),
        (lambda: cf.Segment(cf.MotionLaw.dwell(), 0.0, 1.0, 0.0, 0.01), "a dwell must have h_end == h_start"),
        (lambda: cf.Segment(cf.MotionLaw.cycloidal(), 0.0, 1.0, 0.0, math.inf), "h_start/h_end must be in"),
        (
            lambda: cf.Segment.polynomial(0.0, 1e-300, [0.0, 0.0], [0.01, 0.0]),
            "polynomial segment: theta_end - theta_start",
        ),
        (
            lambda: cf.Segment(cf.MotionLaw.cycloidal(), 0.0, 1.0, 0.0, 0.01).lift_at(math.nan),
            r"theta = nan rad is outside",
        ),
        (lambda: cf.Segment(cf.MotionLaw.cycloidal(), 0.0, 1.0, 0.0, 0.01).lift_at(2.0), r"theta = 2 rad is outside"),
    ],
)
def test_motion_inputs_that_would_overflow_are_refused_at_construction(make, named):
    with pytest.raises(ValueError, match=named):
        make()


def test_every_motion_value_that_is_built_is_finite():
    law = cf.MotionLaw.sine_constant_cosine(1e-6, 0.5, 0.5 - 1e-6)
    segment = cf.Segment(law, 0.0, 1e-6, 0.0, 1e-3)  # the smallest span and fraction allowed
    values = segment.lift_at(np.linspace(0.0, 1e-6, 101))
    assert all(np.all(np.isfinite(np.asarray(v))) for v in values.values())


# --- item 18: argument mismatches are short and name the call ---


def test_argument_mismatches_name_the_call_and_stay_short():
    theta = np.linspace(0.0, 1.0, 2000)
    with pytest.raises(TypeError) as e:
        cf.Segment.from_table(theta, np.sin(theta), degree="five")
    text = str(e.value)
    assert text.startswith("Segment.from_table(): the arguments") and "degree=str 'five'" in text
    assert len(text) < 600 and "0.0005" not in text  # no array printed
    with pytest.raises(TypeError, match=r"with_camshaft_speed_rpm\(\): the arguments \(int of 1329 bits"):
        cf.presets.paper().with_camshaft_speed_rpm(10**400)
    with pytest.raises(TypeError, match=r"^system must be a camfollower Mechanism .* got str$"):
        cf.simulate("x", duration=1.0)


@pytest.mark.parametrize("answer", ["yes", 1, [True]])
def test_a_progress_callback_must_answer_with_a_bool(answer):
    with pytest.raises(
        TypeError,
        match=rf"progress\(steps_done, steps_planned\) must return None, True or False, "
        rf"got {type(answer).__name__}",
    ):
        cf.simulate(cf.presets.paper(), revolutions=3, progress=lambda done, planned: answer, progress_interval=1e-9)


def test_a_progress_callback_may_answer_with_numpys_bool():
    r = cf.simulate(
        cf.presets.paper(), revolutions=0.2, progress=lambda done, planned: np.bool_(True), progress_interval=1e-9
    )
    assert not r.stats["cancelled"]


# --- item 20: an instance whose __init__ never ran ---


def test_instances_without_init_raise_instead_of_crashing():
    """Every public method and property of every compiled class, on an instance made by __new__ alone:
    each raises (ValueError naming the uninitialized instance, or TypeError for the arguments), and the
    interpreter survives (a subprocess: a crash would be a signal, not an exception)."""
    script = textwrap.dedent("""
        import inspect, camfollower as cf
        from camfollower import _core
        tried = 0
        for name, cls in vars(_core).items():
            if name.startswith("_") or not inspect.isclass(cls) or hasattr(cls, "__members__"):  # not the enums
                continue
            if not hasattr(cls, "__init__") or cls.__init__ is object.__init__:
                continue
            try:
                obj = cls.__new__(cls)
            except TypeError:
                continue
            for attr in dir(cls):
                static = inspect.getattr_static(cls, attr)  # class-level members need no instance
                if attr.startswith("_") or isinstance(static, staticmethod) or "static" in type(static).__name__:
                    continue
                if not callable(static) and not isinstance(static, property):  # class data (translating, ...)
                    continue
                tried += 1
                try:
                    value = getattr(obj, attr)
                    if callable(value):
                        value()
                except (ValueError, TypeError) as e:
                    assert "uninitialized" in str(e) or "argument" in str(e) or "must" in str(e), (name, attr, str(e))
                    continue
                raise AssertionError(f"{name}.{attr} on an uninitialized instance returned instead of raising")
        print("tried", tried)
    """)
    r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-3000:]
    assert int(r.stdout.split()[-1]) > 50


def _example(name):
    from pathlib import Path

    return Path(__file__).resolve().parents[2] / "examples" / name
