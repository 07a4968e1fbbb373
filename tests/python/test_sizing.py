# SPDX-License-Identifier: BSD-3-Clause
"""Sizing helpers against a brute-force search over the same geometry checks."""

import math

import camfollower as cf
import numpy as np
import pytest
from camfollower import sizing

PROGRAM = cf.MotionProgram.paper_default()


def feasible(rb, rr, e, alpha_max, rho_min):
    try:
        f = cf.TranslatingRoller(rb, rr, e)
        f.check(PROGRAM)
    except ValueError:
        return False
    return abs(f.max_pressure_angle(PROGRAM)[1]) <= alpha_max and f.min_surface_radius(PROGRAM)[1] >= rho_min


def test_smallest_base_radius_for_a_given_offset_equals_a_brute_force_scan():
    alpha, rho = math.radians(25), 0.008
    s = sizing.smallest_base_radius(
        PROGRAM, max_pressure_angle=alpha, min_surface_radius=rho, roller_radius=0.0125, offset=0.01
    )
    grid = np.arange(0.001, 0.06, 0.0002)
    first = next(rb for rb in grid if feasible(rb, 0.0125, 0.01, alpha, rho))
    assert s.base_radius == pytest.approx(first, abs=0.0002)
    assert not feasible(s.base_radius - 0.0003, 0.0125, 0.01, alpha, rho)
    assert abs(s.max_pressure_angle) <= alpha + 1e-9
    # At 25 deg and 8 mm the pressure angle binds: the tightest radius is then well above 8 mm.
    assert s.binding == "pressure angle" and s.min_surface_radius > rho


def test_best_offset_beats_every_offset_on_a_grid():
    alpha, rho = math.radians(20), 0.008
    s = sizing.smallest_base_radius(
        PROGRAM, max_pressure_angle=alpha, min_surface_radius=rho, roller_radius=0.0125, offset=None, tolerance=1e-5
    )
    offsets = np.arange(-0.02, 0.0201, 0.001)
    grid = np.arange(0.005, 0.05, 0.0005)
    best = min(next((rb for rb in grid if feasible(rb, 0.0125, e, alpha, rho)), math.inf) for e in offsets)
    # The optimizer's radius is no worse than the best grid point (up to the grid spacing).
    assert s.base_radius <= best + 1e-4
    assert feasible(s.base_radius + 1e-5, 0.0125, s.offset, alpha, rho)


def test_flat_face_sized_by_its_radius_of_curvature():
    rho = 0.012
    s = sizing.smallest_base_radius(PROGRAM, "translating_flat", min_surface_radius=rho)
    grid = np.arange(0.001, 0.05, 0.0002)

    def ok(rb):
        f = cf.TranslatingFlat(rb)
        try:
            f.check(PROGRAM)
        except ValueError:
            return False
        return f.min_surface_radius(PROGRAM)[1] >= rho

    assert s.base_radius == pytest.approx(next(rb for rb in grid if ok(rb)), abs=0.0002)
    assert s.binding == "radius of curvature"


def test_roller_size_check_margin_is_the_surface_radius():
    r = sizing.roller_size_check(PROGRAM, 0.04, 0.0125, 0.01)
    f = cf.TranslatingRoller(0.04, 0.0125, 0.01)
    assert r["ok"] and r["margin"] == pytest.approx(f.min_surface_radius(PROGRAM)[1])
    assert r["min_pitch_radius"] == pytest.approx(r["margin"] + 0.0125)


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(max_pressure_angle=2.0, roller_radius=0.01), "max_pressure_angle must be < pi/2"),
        (dict(max_pressure_angle=0.5), "roller_radius must be finite and > 0"),
        (dict(max_pressure_angle=0.5, roller_radius=0.01, min_surface_radius=-1), "min_surface_radius"),
        (dict(max_pressure_angle=0.01, roller_radius=0.01, upper=0.02), "no base radius up to upper"),
    ],
)
def test_bad_sizing_input(kwargs, message):
    with pytest.raises(ValueError, match=message):
        sizing.smallest_base_radius(PROGRAM, **kwargs)


# ---- oscillating followers (lift = arm rotation, rad) ------------------------------------------------

ANGULAR = cf.MotionProgram.paper_default(math.radians(15))


def oscillating_ok(f, alpha_max, rho_min):
    """The follower's own checks: followable, |alpha| <= alpha_max, convex radius >= rho_min."""
    try:
        f.check(ANGULAR)
    except ValueError:
        return False
    return abs(f.max_pressure_angle(ANGULAR)[1]) <= alpha_max and f.min_surface_radius(ANGULAR)[1] >= rho_min


def perpendicular_arm_roller(rb, rr, L, turn="counter_clockwise"):
    """Pivot where the arm is at right angles to the cam radius through the roller on the base circle
    (Pythagoras): the design sizing calls dwell_pressure_angle = 0."""
    return cf.OscillatingRoller(rb, rr, (math.hypot(L, rb + rr), 0.0), L, turn)


@pytest.mark.parametrize("turn", ["counter_clockwise", "clockwise"])
def test_oscillating_roller_with_a_perpendicular_arm_equals_a_brute_force_scan(turn):
    alpha, rho, rr, L = math.radians(25), 0.005, 0.01, 0.1
    s = sizing.smallest_base_radius(
        ANGULAR,
        "oscillating_roller",
        max_pressure_angle=alpha,
        min_surface_radius=rho,
        roller_radius=rr,
        arm_length=L,
        turn=turn,
    )
    grid = np.arange(0.002, 0.08, 0.0002)
    first = next(rb for rb in grid if oscillating_ok(perpendicular_arm_roller(rb, rr, L, turn), alpha, rho))
    assert s.base_radius == pytest.approx(first, abs=0.0002)
    assert not oscillating_ok(perpendicular_arm_roller(s.base_radius - 0.0003, rr, L, turn), alpha, rho)
    assert s.pivot_distance == pytest.approx(math.hypot(L, s.base_radius + rr), rel=1e-12)
    assert s.arm_length == L and s.dwell_pressure_angle == 0.0 and s.offset == 0.0
    f = perpendicular_arm_roller(s.base_radius, rr, L, turn)
    # Reported extremes are the follower's own, with the angle where each occurs.
    assert (s.max_pressure_angle_at, s.max_pressure_angle) == pytest.approx(f.max_pressure_angle(ANGULAR))
    assert (s.min_surface_radius_at, s.min_surface_radius) == pytest.approx(f.min_surface_radius(ANGULAR))
    assert s.binding == "pressure angle" and abs(s.max_pressure_angle) == pytest.approx(alpha, abs=1e-4)
    # On the first dwell (base circle) the pressure angle of a perpendicular arm is zero.
    assert f.profile(ANGULAR, math.radians(10))["pressure_angle"] == pytest.approx(0.0, abs=1e-12)


def test_oscillating_roller_dwell_pressure_angle_sets_the_pivot():
    a0 = math.radians(8)
    s = sizing.smallest_base_radius(
        ANGULAR,
        "oscillating_roller",
        max_pressure_angle=math.radians(30),
        min_surface_radius=0.004,
        roller_radius=0.01,
        arm_length=0.08,
        dwell_pressure_angle=a0,
        turn="clockwise",
    )
    f = cf.OscillatingRoller(s.base_radius, 0.01, (s.pivot_distance, 0.0), 0.08, "clockwise")
    assert f.profile(ANGULAR, math.radians(10))["pressure_angle"] == pytest.approx(a0, abs=1e-12)


def test_oscillating_roller_best_pivot_beats_every_pivot_distance_on_a_grid():
    alpha, rho, rr, L = math.radians(25), 0.005, 0.01, 0.1
    s = sizing.smallest_base_radius(
        ANGULAR,
        "oscillating_roller",
        max_pressure_angle=alpha,
        min_surface_radius=rho,
        roller_radius=rr,
        arm_length=L,
        dwell_pressure_angle=None,
        tolerance=1e-5,
    )

    def any_pivot_works(rb):
        r = rb + rr
        for d in np.linspace(abs(L - r), L + r, 60)[1:-1]:
            if d > rb and oscillating_ok(cf.OscillatingRoller(rb, rr, (d, 0.0), L), alpha, rho):
                return True
        return False

    best = next(rb for rb in np.arange(0.010, 0.04, 0.0005) if any_pivot_works(rb))
    assert s.base_radius <= best + 1e-4
    # ... and the optimizer's own design is feasible, better than the perpendicular arm.
    f = cf.OscillatingRoller(s.base_radius + 1e-5, rr, (s.pivot_distance, 0.0), L)
    assert oscillating_ok(f, alpha + 1e-4, rho)
    assert (
        s.base_radius
        < sizing.smallest_base_radius(
            ANGULAR,
            "oscillating_roller",
            max_pressure_angle=alpha,
            min_surface_radius=rho,
            roller_radius=rr,
            arm_length=L,
        ).base_radius
    )


def test_oscillating_flat_face_sized_by_its_radius_of_curvature():
    rho = 0.01
    s = sizing.smallest_base_radius(ANGULAR, "oscillating_flat", min_surface_radius=rho, pivot_distance_ratio=2.5)
    grid = np.arange(0.002, 0.05, 0.0002)
    first = next(rb for rb in grid if oscillating_ok(cf.OscillatingFlat(rb, (2.5 * rb, 0.0)), math.pi / 2, rho))
    assert s.base_radius == pytest.approx(first, abs=0.0002)
    assert s.binding == "radius of curvature"
    assert s.pivot_distance == pytest.approx(2.5 * s.base_radius)
    assert s.min_surface_radius >= rho and abs(s.max_pressure_angle) < 1e-9  # face through the pivot


@pytest.mark.parametrize(
    "follower,kwargs,message",
    [
        ("oscillating_roller", dict(roller_radius=0.01), "arm_length must be finite and > 0"),
        ("oscillating_roller", dict(arm_length=0.1), "roller_radius must be finite and > 0"),
        (
            "oscillating_roller",
            dict(roller_radius=0.01, arm_length=0.1, dwell_pressure_angle=2.0),
            "dwell_pressure_angle",
        ),
        ("oscillating_roller", dict(roller_radius=0.01, arm_length=0.1, turn="up"), "turn must be"),
        ("oscillating_flat", dict(pivot_distance_ratio=1.0), "pivot_distance_ratio"),
        ("oscillating_flat", dict(pivot_distance_ratio=None), "pivot_distance_ratio=None"),
        ("oscillating_flat", dict(face_offset=math.nan), "face_offset"),
        ("swinging", dict(), "follower must be one of"),
    ],
)
def test_bad_oscillating_sizing_input(follower, kwargs, message):
    with pytest.raises(ValueError, match=message):
        sizing.smallest_base_radius(ANGULAR, follower, **kwargs)


@pytest.mark.parametrize(
    "make",
    [
        lambda turn: cf.OscillatingRoller(0.03, 0.008, [0.06, 0.05], 0.06, turn=turn),
        lambda turn: cf.OscillatingFlat(0.03, [0.06, 0.05], 0.0, turn),
    ],
)
def test_a_turn_is_the_arm_turn_enum_or_its_name(make):
    theta = np.linspace(0, 2 * math.pi, 73)
    for enum, names in (
        (cf.ArmTurn.clockwise, ("clockwise", "cw")),
        (cf.ArmTurn.counter_clockwise, ("counter_clockwise", "ccw")),
    ):
        by_enum = make(enum)
        assert by_enum.turn == enum.name
        for name in names:
            by_name = make(name)
            assert by_name.turn == enum.name
            assert np.array_equal(
                by_enum.profile(ANGULAR, theta)["surface_x"], by_name.profile(ANGULAR, theta)["surface_x"]
            )
    # The two senses are different cams.
    assert not np.allclose(
        make(cf.ArmTurn.clockwise).profile(ANGULAR, theta)["surface_x"],
        make(cf.ArmTurn.counter_clockwise).profile(ANGULAR, theta)["surface_x"],
    )
    with pytest.raises(TypeError, match="turn must be an ArmTurn or one of 'counter_clockwise', 'clockwise', got int"):
        make(1)
    with pytest.raises(ValueError, match="turn must be 'counter_clockwise' or 'clockwise', got 'up'"):
        make("up")


def test_sizing_takes_the_arm_turn_enum_as_the_followers_do():
    kwargs = dict(roller_radius=0.01, arm_length=0.1)
    for enum in (cf.ArmTurn.clockwise, cf.ArmTurn.counter_clockwise):
        assert sizing.smallest_base_radius(
            ANGULAR, "oscillating_roller", turn=enum, **kwargs
        ) == sizing.smallest_base_radius(ANGULAR, "oscillating_roller", turn=enum.name, **kwargs)
    with pytest.raises(TypeError, match="turn must be an ArmTurn"):
        sizing.smallest_base_radius(ANGULAR, "oscillating_roller", turn=0, **kwargs)
