# SPDX-License-Identifier: BSD-3-Clause
"""Property-based tests (hypothesis) over the Python API: motion programs, followers, mechanisms,
flexible shafts and simulate, fed anything a user could pass (negative, zero, tiny, huge, NaN, inf).

The oracle: the call either returns finite results or raises ValueError whose message names the
argument or element at fault; never a crash, a hang, a silent NaN or another exception type.
Profiles: the default ("ci") runs a few hundred examples per property; ``--hypothesis-profile=long``
runs 10,000 per property (over 100,000 in all).
"""

import math
import warnings

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
import camfollower as cf  # noqa: E402
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

# Numbers a user might pass: ordinary magnitudes, extremes, and non-finite values.
anything = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-1.0, max_value=1.0),
    st.sampled_from([0.0, -0.0, 1e-300, -1e-300, 1e300, 5e-324, 1e-9, 1e9]),
)
length = st.one_of(st.floats(min_value=1e-4, max_value=0.2), anything)
LAWS = [
    "cycloidal",
    "simple_harmonic",
    "polynomial_345",
    "polynomial_4567",
    "modified_sine",
    "modified_trapezoid",
    "constant_acceleration",
]


def raises_naming(call, *names):
    """Run call(); a ValueError (bad input) or RuntimeError (a model that cannot be solved) must name
    one of `names` (the argument or element at fault)."""
    try:
        return call()
    except (ValueError, RuntimeError) as e:
        text = str(e)
        assert text and any(n in text for n in names), f"error does not name {names}: {text}"
        return None


def finite(x):
    return np.all(np.isfinite(np.asarray(x, dtype=float)))


@given(law=st.sampled_from(LAWS), rise=anything, lift=anything, theta=st.lists(anything, min_size=1, max_size=8))
def test_motion_program_is_finite_or_refused(law, rise, lift, theta):
    """Dwell, rise over `rise` rad, dwell, return: refused or finite at any finite angle."""

    def build():
        a = rise
        return cf.MotionProgram(
            [
                cf.Segment(cf.MotionLaw.dwell(), 0.0, 1.0, 0.0, 0.0),
                cf.Segment(getattr(cf.MotionLaw, law)(), 1.0, 1.0 + a, 0.0, lift),
                cf.Segment(cf.MotionLaw.dwell(), 1.0 + a, 4.0, lift, lift),
                cf.Segment(getattr(cf.MotionLaw, law)(), 4.0, 2 * math.pi, lift, 0.0),
            ]
        )

    program = raises_naming(build, "theta", "segment", "rise", "lift", "h_", "span", "angle", "finite")
    if program is None:
        return
    angles = np.array([t for t in theta if math.isfinite(t)])
    if angles.size:
        values = program.evaluate(angles)
        for key in ("h", "dh", "d2h", "d3h"):
            assert finite(values[key]), key
    bad = [t for t in theta if not math.isfinite(t)]
    if bad:
        raises_naming(lambda: program.evaluate(np.array(bad)), "theta")


@given(
    base=length,
    roller=length,
    offset=st.one_of(st.floats(min_value=-0.05, max_value=0.05), anything),
    lift=st.one_of(st.floats(min_value=1e-4, max_value=0.05), anything),
)
def test_translating_roller_geometry_is_checked_or_refused(base, roller, offset, lift):
    follower = raises_naming(
        lambda: cf.TranslatingRoller(base, roller, offset), "base_radius", "roller_radius", "offset"
    )
    program = raises_naming(lambda: cf.MotionProgram.paper_default(lift), "rise", "lift", "total_rise", "h")
    if follower is None or program is None:
        return
    ok = raises_naming(lambda: follower.check(program) or True, "theta", "undercut", "pressure angle", "cusp", "radius")
    if ok:
        theta, alpha = follower.max_pressure_angle(program)
        assert math.isfinite(alpha) and abs(alpha) < math.pi / 2
        theta, radius = follower.min_surface_radius(program)
        assert math.isfinite(radius) and radius > 0


@given(mass=anything, stiffness=anything, damping=anything, preload=anything)
def test_mechanism_parts_are_validated_by_name(mass, stiffness, damping, preload):
    b = cf.MechanismBuilder()
    if raises_naming(lambda: b.add_dof("tappet", mass, [0, 1, 0]) or True, "tappet") is None:
        return
    if (
        raises_naming(
            lambda: b.add_spring("spring", "tappet", stiffness=stiffness, damping=damping, preload=preload) or True,
            "spring",
        )
        is None
    ):
        return
    b.add_contact(
        "cam", cf.MotionProgram.paper_default(), cf.TranslatingRoller(0.03, 0.008), follower_dof="tappet", stiffness=2e8
    )
    m = raises_naming(b.build, "static equilibrium", "spring", "tappet", "contact")
    if m is not None:
        assert finite(m.initial_state)


@given(
    length_=anything,
    outer=length,
    inner=st.one_of(st.just(0.0), length),
    element=anything,
    stations=st.lists(anything, max_size=4),
)
def test_shaft_description_is_validated_by_name(length_, outer, inner, element, stations):
    b = cf.MechanismBuilder()
    done = raises_naming(
        lambda: (
            b.add_shaft(
                "s",
                length=length_,
                outer_diameter=outer,
                inner_diameter=inner,
                max_element_length=element,
                stations=stations,
            )
            or True
        ),
        "shaft 's'",
        "diameter",
        "youngs_modulus",
        "density",
    )
    if done:
        names = b.dof_names
        assert names and all(n.startswith("s.") for n in names)
        assert len(names) < 5 * 10**6


PRESET = cf.presets.paper()


@given(time_step=anything, duration=anything)
def test_simulate_runs_or_refuses_its_step_and_duration(time_step, duration):
    def run():
        # Bounded work: at most 1,000 steps are accepted for the check.
        if (
            math.isfinite(time_step)
            and math.isfinite(duration)
            and time_step > 0
            and duration > 0
            and duration / time_step > 1000
        ):
            return None
        return cf.simulate(PRESET, duration=duration, time_step=time_step, decimation=1)

    result = raises_naming(run, "time_step", "duration", "steps", "stability")
    if result is not None:
        assert finite(result.q) and finite(result["cam.force"])


@given(
    tolerance=st.one_of(st.floats(min_value=1e-13, max_value=0.1), anything),
    max_step=st.one_of(st.just(None), anything),
    time_step=st.one_of(st.just(1e-4), anything),
)
def test_dormand_prince_runs_or_refuses_its_settings(tolerance, max_step, time_step):
    """The explicit method over 2 ms of the paper preset: its tolerance, step bound and output interval
    are honoured or refused by name; a run that is accepted is finite."""
    duration = 2e-3

    def run():
        # Bounded work: at most 1,000 output rows and 1e5 bounded steps are accepted for the check.
        if math.isfinite(time_step) and time_step > 0 and duration / time_step > 1000:
            return None
        if max_step is not None and math.isfinite(max_step) and max_step > 0 and duration / max_step > 1e5:
            return None
        return cf.simulate(
            PRESET,
            duration=duration,
            time_step=time_step,
            method="dormand_prince",
            tolerance=tolerance,
            max_step=max_step,
        )

    result = raises_naming(run, "tolerance", "max_step", "time_step", "duration", "Dormand-Prince")
    if result is not None:
        assert finite(result.q) and finite(result["cam.force"])
        assert result.stats["method"] == "dormand_prince"


def _follower(kind, base, size, offset):
    if kind == "translating_flat":
        return cf.TranslatingFlat(base, 0.0, offset)
    if kind == "oscillating_roller":
        return cf.OscillatingRoller(base, size, [0.12, 0.0], 0.11 + offset)
    if kind == "oscillating_flat":
        return cf.OscillatingFlat(base, [0.12, 0.05], offset)
    return cf.TranslatingRoller(base, size, offset)


@given(
    kind=st.sampled_from(["translating_flat", "oscillating_roller", "oscillating_flat", "translating_roller"]),
    base=length,
    size=length,
    offset=st.one_of(st.floats(min_value=-0.02, max_value=0.02), anything),
    lift=st.one_of(st.floats(min_value=1e-4, max_value=0.05), anything),
)
def test_every_follower_type_is_checked_or_refused(kind, base, size, offset, lift):
    """Every follower type: built and checked against a program of any lift, or refused naming the
    part; what is accepted has finite, meaningful geometry."""
    names = (
        "base_radius",
        "roller_radius",
        "offset",
        "face",
        "arm",
        "pivot",
        "undercut",
        "theta",
        "cusp",
        "pressure angle",
        "radius",
        "lift",
        "h_",
    )
    follower = raises_naming(lambda: _follower(kind, base, size, offset), *names)
    program = raises_naming(lambda: cf.MotionProgram.paper_default(lift), "rise", "lift", "total_rise", "h")
    if follower is None or program is None:
        return
    if raises_naming(lambda: follower.check(program) or True, *names):
        theta, alpha = follower.max_pressure_angle(program)
        assert math.isfinite(alpha) and abs(alpha) < math.pi / 2
        theta, radius = follower.min_surface_radius(program)
        assert math.isfinite(radius)


NUMERIC = [n for n in cf.Parameters.names() if n != "contact_damping"]


def paper_from_card(values, damping):
    """The paper preset on a parameter card: built with finite matrices and preload, or refused naming
    the parameter (or what the calibration could not do)."""
    names = tuple(values) + ("contact_damping", "static equilibrium", "calibration", "offset", "radius")

    def build():
        return cf.presets.paper(parameters=cf.Parameters(contact_damping=damping, **values))

    model = raises_naming(build, *names)
    if model is not None:
        (spring,) = [s for s in model.builder().springs if s["name"] == "K_rs"]
        assert finite(model.initial_state) and finite(model.stiffness) and math.isfinite(spring["preload"])


@given(
    values=st.dictionaries(st.sampled_from(NUMERIC), anything, min_size=1, max_size=3),
    damping=st.sampled_from(["none", "hunt_crossley", "lankarani_nikravesh", "viscous"]),
)
def test_parameters_build_a_model_or_are_refused_by_name(values, damping):
    paper_from_card(values, damping)


@pytest.mark.parametrize(
    "values",
    [
        {"contact_stiffness": 1e-9},  # a preload of -1.2e14 N
        {"roller_pin_stiffness_vertical": 1e-9},  # -2.1e14 N
        {"rod_stiffness": 1e-9},  # 2.5e15 N
        {"bearing_stiffness_vertical": 1e-9},  # -6.1e13 N
        {"spring_stiffness": 1e12},  # 1.3e10 N
        {"spring_stiffness": 1923794551.0},  # the spring about as stiff as the chain under it
    ],
)
def test_a_spring_that_cannot_be_balanced_is_refused_by_name(values):
    paper_from_card(values, "none")


@pytest.mark.parametrize(
    "values",
    [
        {"guide_stiffness": 1e-9},  # through the pressure angle the contact loads the lateral parts too
        {"roller_pin_stiffness_horizontal": 1e-9},
        {"bearing_stiffness_horizontal": 1e-9},
    ],
)
def test_a_too_soft_lateral_part_is_refused_by_name(values):
    paper_from_card(values, "none")


@pytest.mark.parametrize("damping", ["hunt_crossley", "lankarani_nikravesh"])
def test_an_overflowing_contact_damping_is_refused_by_name(damping):
    paper_from_card({"restitution": 0.0, "reference_speed": 5e-324}, damping)


@given(
    eccentricity=anything,
    phase=anything,
    formulation=st.sampled_from(["exact", "paper_force_both"]),
    backlash=anything,
    width=anything,
)
def test_defects_are_validated_by_name(eccentricity, phase, formulation, backlash, width):
    """The paper preset's defects, from their mechanisms or the paper's literal readings: built, or
    refused naming the defect."""
    ecc = raises_naming(lambda: cf.CamEccentricity(eccentricity, phase, formulation), "eccentricity", "phase")
    if ecc is None:
        return
    names = ("eccentric", "paper_backlash", "paper backlash", "switch", "static equilibrium", "pressure angle")

    def build():
        with warnings.catch_warnings():  # the paper's literal force may exceed the preload: a warning
            warnings.simplefilter("ignore", UserWarning)
            return cf.presets.paper(eccentricity=ecc, paper_backlash=backlash, paper_backlash_switch_width=width)

    model = raises_naming(build, *names)
    if model is not None:
        assert finite(model.initial_state)


@given(signal=st.lists(anything, max_size=40), rate=anything, count=st.integers(-2, 5))
def test_analysis_is_finite_or_refused_by_name(signal, rate, count):
    from camfollower import analysis as an

    spec = raises_naming(lambda: an.spectrum(signal, rate), "signal", "sample_rate")
    if spec is not None:
        assert finite(spec.amplitude) and finite(spec.frequency)
        peaks = raises_naming(lambda: an.find_peaks(spec, count), "count")
        assert peaks is None or all(math.isfinite(f) and math.isfinite(a) for f, a in peaks)
    t = np.arange(len(signal), dtype=float)
    flags = [x > 0 if math.isfinite(x) else False for x in signal]
    intervals = an.contact_loss_intervals(t, flags)
    assert all(a <= b for a, b in intervals)
    theta = np.linspace(0.0, 2 * math.pi, len(signal), endpoint=False)
    stats = raises_naming(lambda: an.phase_statistics(PRESET_MODEL, theta, signal), "theta", "signal", "phase")
    if stats is not None:
        assert all(math.isfinite(s["peak"]) and math.isfinite(s["rms"]) for s in stats)


PRESET_MODEL = cf.presets.paper()


ROLE_DOFS = st.sampled_from(["ground", "f", "g", "h"])


@given(cam_x=ROLE_DOFS, cam_y=ROLE_DOFS, follower=ROLE_DOFS, lateral=ROLE_DOFS)
def test_contact_roles_are_distinct_dofs_or_refused_naming_them(cam_x, cam_y, follower, lateral):
    """Any assignment of DOFs to a contact's roles: two roles on one DOF (or the follower on ground) are
    refused when the contact is added, naming the roles; distinct roles build a finite model."""
    b = cf.MechanismBuilder()
    for name, mass in (("f", 0.5), ("g", 2.0), ("h", 2.0)):
        b.add_dof(name, mass)
    b.add_spring("kf", "f", "ground", stiffness=2e4, preload=300.0)
    b.add_spring("kg", "g", "ground", stiffness=1e8)
    b.add_spring("kh", "h", "ground", stiffness=1e8)
    roles = {"cam_x": cam_x, "cam_y": cam_y, "follower_dof": follower, "lateral": lateral}
    used = [d for d in roles.values() if d != "ground"]
    clash = len(used) != len(set(used)) or follower == "ground"
    try:
        b.add_contact(
            "cam",
            cf.MotionProgram.paper_default(),
            cf.TranslatingRoller(0.03, 0.008),
            stiffness=1e8,
            cam_x=cam_x,
            cam_y=cam_y,
            follower_dof=follower,
            lateral=lateral,
        )
    except ValueError as e:
        assert clash, str(e)
        assert "contact 'cam'" in str(e) and ("both name DOF" in str(e) or "follower_dof must be a DOF" in str(e))
        return
    assert not clash
    m = raises_naming(b.build, "static equilibrium", "contact 'cam'")
    assert m is None or finite(m.initial_state)


@given(
    length_=st.floats(min_value=0.01, max_value=2.0),
    elements=st.integers(1, 3000),
    outer=st.floats(min_value=0.005, max_value=0.1),
    shafts=st.integers(1, 3),
)
@settings(deadline=None, max_examples=40)
def test_model_size_is_bounded_before_it_is_built(length_, elements, outer, shafts):
    """Shafts of any mesh: refused by name at once (too many elements, a mesh finer than the section
    allows, too many DOFs), or built within the DOF bound."""
    import time

    b = cf.MechanismBuilder()
    start = time.monotonic()
    for k in range(shafts):
        added = raises_naming(
            lambda: (
                b.add_shaft(
                    f"s{k}",
                    length=length_,
                    outer_diameter=outer,
                    max_element_length=length_ / elements,
                    stations=[0.0, length_],
                )
                or True
            ),
            "max_element_length",
        )
        if added is None:
            assert time.monotonic() - start < 5.0
            return
        b.add_bearing(f"b{k}", f"s{k}", 0.0, stiffness=1e8)
        b.add_bearing(f"c{k}", f"s{k}", length_, stiffness=1e8)
        b.add_drive(f"d{k}", f"s{k}", 0.0, stiffness=1e4)
    m = raises_naming(b.build, "DOFs, more than the 3000")
    assert m is None or m.size <= 3000
    assert time.monotonic() - start < 10.0


@given(b_=anything, c=anything, width=anything, span=anything)
def test_motion_parameters_build_finite_laws_or_are_refused(b_, c, width, span):
    law = raises_naming(lambda: cf.MotionLaw.sine_constant_cosine(b_, c, 1.0 - b_ - c), "fraction", "b + c + d")
    if law is not None:
        segment = raises_naming(lambda: cf.Segment(law, 0.0, span, 0.0, 0.01), "span", "theta")
        if segment is not None:
            values = segment.lift_at(np.linspace(0.0, span, 9))
            assert all(finite(v) for v in values.values())
    dent = raises_naming(lambda: cf.ProfileError.dent(1.0, width, 1e-5), "dent width")
    if dent is not None:
        program = cf.MotionProgram.paper_default().with_profile_error(dent)
        assert all(finite(v) for v in program.evaluate(np.linspace(0.0, 2 * math.pi, 721)).values())
