"""Sizing helpers against a brute-force search over the same geometry checks."""

import math

import numpy as np
import pytest

import camfollower as cf
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
    s = sizing.smallest_base_radius(PROGRAM, max_pressure_angle=alpha, min_surface_radius=rho, roller_radius=0.0125,
                                    offset=0.01)
    grid = np.arange(0.001, 0.06, 0.0002)
    first = next(rb for rb in grid if feasible(rb, 0.0125, 0.01, alpha, rho))
    assert s.base_radius == pytest.approx(first, abs=0.0002)
    assert not feasible(s.base_radius - 0.0003, 0.0125, 0.01, alpha, rho)
    assert abs(s.max_pressure_angle) <= alpha + 1e-9
    # At 25 deg and 8 mm the pressure angle binds: the tightest radius is then well above 8 mm.
    assert s.binding == "pressure angle" and s.min_surface_radius > rho


def test_best_offset_beats_every_offset_on_a_grid():
    alpha, rho = math.radians(20), 0.008
    s = sizing.smallest_base_radius(PROGRAM, max_pressure_angle=alpha, min_surface_radius=rho, roller_radius=0.0125,
                                    offset=None, tolerance=1e-5)
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


@pytest.mark.parametrize("kwargs,message", [
    (dict(max_pressure_angle=2.0, roller_radius=0.01), "max_pressure_angle must be < pi/2"),
    (dict(max_pressure_angle=0.5), "roller_radius must be finite and > 0"),
    (dict(max_pressure_angle=0.5, roller_radius=0.01, min_surface_radius=-1), "min_surface_radius"),
    (dict(max_pressure_angle=0.01, roller_radius=0.01, upper=0.02), "no base radius up to upper"),
])
def test_bad_sizing_input(kwargs, message):
    with pytest.raises(ValueError, match=message):
        sizing.smallest_base_radius(PROGRAM, **kwargs)
