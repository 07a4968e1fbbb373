# SPDX-License-Identifier: BSD-3-Clause
"""Profile errors (a cam's manufacturing error as a lift error e(theta)) from Python: the components
against their formulas and finite differences, the table fit against known trigonometric polynomials,
pickling, ValueError messages, the undercut check, and a simulated follower that traces a waviness."""

import pickle

import camfollower as cf
import numpy as np
import pytest

DEG = np.pi / 180


def central_differences(evaluate, keys, theta, h):
    """d/dtheta of keys[0..2] by central differences, compared by the caller with keys[1..3]."""
    plus, minus = evaluate(theta + h), evaluate(theta - h)
    return [(plus[k] - minus[k]) / (2 * h) for k in keys[:3]]


def check_derivatives(evaluate, keys, theta, h, scales, rel=1e-6):
    exact = evaluate(theta)
    for fd, key, scale in zip(central_differences(evaluate, keys, theta, h), keys[1:], scales):
        assert np.abs(fd - exact[key]).max() <= rel * scale, key


def test_waviness_and_dent_follow_their_formulas():
    t = np.linspace(-1.0, 7.0, 401)
    w = cf.ProfileError.waviness(12e-6, 7, phase=0.4)
    np.testing.assert_allclose(w.evaluate(t)["e"], 12e-6 * np.cos(7 * t + 0.4), rtol=0, atol=1e-17)
    assert isinstance(w.evaluate(0.3)["e"], float)

    centre, width, depth = 2.0, 6 * DEG, 30e-6
    d = cf.ProfileError.dent(centre, width, depth)
    x = (t - centre) / (width / 2)
    expected = np.where(np.abs(x) < 1, -depth * (1 - x**2) ** 4, 0.0)
    np.testing.assert_allclose(d.evaluate(t)["e"], expected, rtol=0, atol=1e-12 * depth)
    assert d.evaluate(centre)["e"] == -depth
    assert d.features() == pytest.approx([centre - width / 2, centre, centre + width / 2])
    assert w.features() == []


@pytest.mark.parametrize(
    "error, h, scales",
    [
        (cf.ProfileError.waviness(12e-6, 7, phase=0.4), 1e-5, (12e-6 * 49, 12e-6 * 343, 12e-6 * 2401)),
        (cf.ProfileError.dent(2.0, 6 * DEG, 30e-6), 1e-6, (30e-6 * 8 * 365, 30e-6 * 48 * 7000, 30e-6 * 400 * 1.3e5)),
        (cf.ProfileError.fourier(1e-6, [2e-6, -1e-6, 3e-7], [0.0, 1e-6, 2e-6]), 1e-5, (2e-5, 8e-5, 3e-4)),
    ],
)
def test_derivatives_match_finite_differences(error, h, scales):
    theta = np.array([0.3, 1.96, 1.99, 2.0, 2.04, 4.1, 5.9])
    check_derivatives(error.evaluate, ("e", "de", "d2e", "d3e"), theta, h, scales)


def test_a_program_with_an_error_is_the_design_lift_plus_e():
    design = cf.MotionProgram.paper_default()
    error = cf.ProfileError.waviness(20e-6, 12) + cf.ProfileError.dent(np.radians(100), np.radians(4), 5e-6)
    program = design.with_profile_error(error)
    assert design.profile_error is None
    assert program.profile_error.components == error.components
    t = np.linspace(0, 2 * np.pi, 2001)
    for key, ekey in zip(("h", "dh", "d2h", "d3h"), ("e", "de", "d2e", "d3e")):
        np.testing.assert_array_equal(program.evaluate(t)[key], design.evaluate(t)[key] + error.evaluate(t)[ekey])
    check_derivatives(
        program.evaluate, ("h", "dh", "d2h", "d3h"), np.array([0.1, 1.7, 1.745, 2.6, 5.9]), 1e-6, (0.02, 0.2, 5.0)
    )
    # Crests of 12 waves sit on the top dwell's ends, a trough in the bottom dwell.
    assert program.max_lift() == pytest.approx(0.010 + 20e-6, abs=1e-13)
    assert program.min_lift() == pytest.approx(-20e-6, abs=1e-13)
    assert program.with_profile_error(cf.ProfileError()).profile_error is None


def test_table_reproduces_a_trigonometric_polynomial_and_smooths_to_its_projection():
    def poly(t, harmonics):
        return 2e-6 + sum(a * np.cos(k * t) + b * np.sin(k * t) for k, a, b in harmonics)

    low = [(1, 5e-6, -1e-6), (2, -2e-6, 3e-6), (3, 1e-6, 0.0)]
    high = [(5, 2e-6, 1e-6)]
    fine = np.linspace(0, 2 * np.pi, 997)
    # 11 equally spaced points carry harmonics up to 5 exactly.
    theta = 0.2 + 2 * np.pi * np.arange(11) / 11
    fit = cf.ProfileError.table(theta, poly(theta, low + high))
    np.testing.assert_allclose(fit.evaluate(fine)["e"], poly(fine, low + high), rtol=0, atol=1e-17)
    # Unequally spaced: least squares with zero residual.
    rng = np.random.default_rng(3)
    theta = np.sort(2 * np.pi * (np.arange(17) + 0.5 + 0.4 * rng.uniform(-1, 1, 17)) / 17)
    fit = cf.ProfileError.table(theta, poly(theta, low + high), max_harmonic=6)
    np.testing.assert_allclose(fit.evaluate(fine)["e"], poly(fine, low + high), rtol=0, atol=1e-17)
    # max_harmonic 3 on 24 equally spaced points: harmonic 5 is orthogonal to 1..3 there.
    theta = 2 * np.pi * np.arange(24) / 24
    fit = cf.ProfileError.table(theta, poly(theta, low + high), max_harmonic=3)
    np.testing.assert_allclose(fit.evaluate(fine)["e"], poly(fine, low), rtol=0, atol=1e-17)
    assert fit.components[0]["kind"] == "fourier" and len(fit.components[0]["cos"]) == 3


def test_components_combine_and_read_back():
    w, d = cf.ProfileError.waviness(5e-6, 3), cf.ProfileError.dent(1.0, 0.2, 2e-5)
    both = w + d
    assert len(both) == 2 and bool(both) and not cf.ProfileError()
    assert [c["kind"] for c in both.components] == ["waviness", "dent"]
    assert both.components[1] == {"kind": "dent", "centre": 1.0, "width": 0.2, "depth": 2e-5}
    t = np.linspace(0, 2 * np.pi, 50)
    np.testing.assert_allclose(both.evaluate(t)["e"], w.evaluate(t)["e"] + d.evaluate(t)["e"], rtol=0, atol=1e-20)
    assert "waviness(amplitude=5e-06, order=3" in repr(both)


def test_pickling_round_trips_errors_and_programs():
    error = (
        cf.ProfileError.waviness(5e-6, 3, phase=0.2)
        + cf.ProfileError.dent(1.0, 0.2, 2e-5)
        + cf.ProfileError.table(np.linspace(0, 2 * np.pi, 9, endpoint=False), np.arange(9) * 1e-7)
    )
    copy = pickle.loads(pickle.dumps(error))
    assert copy.components == error.components
    program = cf.MotionProgram.paper_default().with_profile_error(error)
    again = pickle.loads(pickle.dumps(program))
    t = np.linspace(0, 2 * np.pi, 500)
    np.testing.assert_array_equal(again.evaluate(t)["h"], program.evaluate(t)["h"])
    assert again.max_lift() == program.max_lift()
    # A design program pickles with None, and the state from before profile errors still loads.
    design = cf.MotionProgram.paper_default()
    assert design.__getstate__()[1] is None
    old = cf.MotionProgram.__new__(cf.MotionProgram)
    old.__setstate__((design.segments,))
    assert old.profile_error is None
    np.testing.assert_array_equal(old.evaluate(t)["h"], design.evaluate(t)["h"])


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: cf.ProfileError.dent(1.0, 0.0, 1e-5), r"dent width must be in \[1e-06 rad, 180 deg\], got 0"),
        (lambda: cf.ProfileError.dent(1.0, 3.5, 1e-5), r"dent width must be in \[1e-06 rad, 180 deg\]"),
        (lambda: cf.ProfileError.dent(float("nan"), 0.1, 1e-5), r"dent centre"),
        (lambda: cf.ProfileError.dent(1.0, 0.1, float("inf")), r"dent depth"),
        (lambda: cf.ProfileError.waviness(1e-6, 0), r"waviness order must be an integer >= 1"),
        (lambda: cf.ProfileError.waviness(float("nan"), 2), r"waviness amplitude"),
        (
            lambda: cf.ProfileError.table([0.0, 1.0, 1.0, 2.0], [0, 0, 0, 0]),
            r"theta must be strictly increasing in \[0, 360\) deg; point 2",
        ),
        (lambda: cf.ProfileError.table([0.0, 1.0, 7.0], [0, 0, 0]), r"point 2 is at 401\.07"),
        (lambda: cf.ProfileError.table([0.0, 1.0, 2.0], [0, float("nan"), 0]), r"point 1 must be finite"),
        (lambda: cf.ProfileError.table([0.0, 1.0], [0, 0]), r"at least 3 points"),
        (lambda: cf.ProfileError.table([0.0, 1.0, 2.0], [0, 0]), r"same length, got 3 and 2"),
        (
            lambda: cf.ProfileError.table(np.arange(6.0), np.zeros(6), max_harmonic=3),
            r"max_harmonic must be in \[1, 2\]",
        ),
        (lambda: cf.ProfileError.fourier(0.0, [1e-6], []), r"same length"),
    ],
)
def test_bad_input_names_the_parameter(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_the_undercut_check_sees_a_narrow_dent():
    roller = cf.TranslatingRoller(0.040, 0.0125, 0.0)
    healthy = cf.MotionProgram.paper_default()
    roller.check(healthy)
    # 0.2 mm deep over 3 deg: the flanks of the dent bend the pitch curve to a ~2 mm radius (< 12.5 mm).
    dented = healthy.with_profile_error(cf.ProfileError.dent(np.radians(15), np.radians(3), 0.2e-3))
    with pytest.raises(ValueError, match=r"undercuts at theta = 1[456]\.\d+ deg"):
        roller.check(dented)
    b = cf.MechanismBuilder()
    b.add_dof("y", 0.5, direction=(0, 1, 0))
    b.add_spring("spring", "y", "ground", stiffness=2e4, preload=300.0)
    b.add_contact("cam", dented, roller, follower_dof="y", stiffness=1e8)
    with pytest.raises(ValueError, match=r"contact 'cam'.*undercuts"):
        b.build()


MASS, ROD, SPRING, PRELOAD = 0.5, 2.0e6, 2.0e4, 3000.0  # the 1-DOF follower of examples/one_dof_follower.py
AMPLITUDE, ORDER = 20e-6, 10


def one_dof(program, rpm):
    b = cf.MechanismBuilder()
    b.add_dof("y", MASS, direction=(0, 1, 0))
    b.add_spring("return_spring", "y", "ground", stiffness=SPRING, preload=PRELOAD)
    b.add_contact("cam", program, cf.TranslatingFlat(base_radius=0.040), follower_dof="y", stiffness=ROD)
    b.camshaft_speed_rpm = rpm
    return b.build()


def test_a_simulated_follower_traces_the_waviness():
    # At 60 rpm the waviness excites 10 Hz, far below f_n = 320 Hz: the follower follows
    # quasi-statically, and the rod (ROD) in series with the spring (SPRING) passes
    # ROD / (ROD + SPRING) of any lift change to the follower.
    lift, rise = 0.001, np.radians(90)
    design = cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.dwell(), 0.0, np.radians(30), 0.0, 0.0),
            cf.Segment(cf.MotionLaw.cycloidal(), np.radians(30), np.radians(30) + rise, 0.0, lift),
            cf.Segment(cf.MotionLaw.dwell(), np.radians(30) + rise, np.radians(240), lift, lift),
            cf.Segment(cf.MotionLaw.cycloidal(), np.radians(240), 2 * np.pi, lift, 0.0),
        ]
    )
    wavy = design.with_profile_error(cf.ProfileError.waviness(AMPLITUDE, ORDER))
    runs = [cf.simulate(one_dof(p, 60.0), revolutions=1, time_step=2e-5, decimation=10) for p in (design, wavy)]
    for r in runs:
        assert not r.contact_loss["cam"]
    theta = runs[1]["cam.cam_angle"]
    difference = runs[1].q[:, 0] - runs[0].q[:, 0]
    # Least-squares amplitude and phase of the difference at the waviness order.
    basis = np.column_stack([np.cos(ORDER * theta), np.sin(ORDER * theta), np.ones_like(theta)])
    (a, b, _), *_ = np.linalg.lstsq(basis, difference, rcond=None)
    static_share = ROD / (ROD + SPRING)
    print(f"traced amplitude {np.hypot(a, b):.4e} m, expected {static_share * AMPLITUDE:.4e} m")
    assert np.hypot(a, b) == pytest.approx(static_share * AMPLITUDE, rel=0.02)
    assert abs(b) < 0.02 * abs(a)  # in phase with e = A cos(k theta)
    # And point by point: the follower displacement minus its design-lift displacement is the waviness.
    np.testing.assert_allclose(
        difference, static_share * AMPLITUDE * np.cos(ORDER * theta), rtol=0, atol=0.02 * AMPLITUDE
    )
