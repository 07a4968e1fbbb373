# SPDX-License-Identifier: BSD-3-Clause
"""User-defined motion through the bindings: lift tables as splines, polynomial segments, laws from
callables, continuity, smoothness. Independent truth: closed-form laws written out here, finite
differences of the spline's own lift, scipy's make_interp_spline (an independent B-spline code),
numpy's polynomial solvers."""

import math
import pickle

import camfollower as cf
import numpy as np
import pytest
from scipy.interpolate import make_interp_spline

DEG = math.pi / 180.0


def smooth(t):
    """h = a (1 - cos t) + b sin 2t and its derivatives."""
    a, b = 0.004, 0.001
    return (
        a * (1 - np.cos(t)) + b * np.sin(2 * t),
        a * np.sin(t) + 2 * b * np.cos(2 * t),
        a * np.cos(t) - 4 * b * np.sin(2 * t),
        -a * np.sin(t) - 8 * b * np.cos(2 * t),
    )


def cycloidal(theta, a, beta, lift):
    """Cycloidal rise by `lift` over [a, a + beta]: h and its derivatives, closed form."""
    x = (theta - a) / beta
    w = 2 * np.pi
    return (
        lift * (x - np.sin(w * x) / w),
        lift * (1 - np.cos(w * x)) / beta,
        lift * w * np.sin(w * x) / beta**2,
        lift * w**2 * np.cos(w * x) / beta**3,
    )


def test_from_callable_segment_matches_the_closed_form_law():
    a, beta, lift = 30 * DEG, 120 * DEG, 0.01
    jerk_end = lift * (2 * np.pi) ** 2 / beta**3  # the cycloid's end jerk, not zero
    seg = cf.motion.from_callable(
        lambda t: cycloidal(t, a, beta, lift)[0],
        a,
        a + beta,
        points=121,
        start_derivatives=[0, 0, jerk_end],
        end_derivatives=[0, 0, jerk_end],
    )
    assert isinstance(seg, cf.Segment)
    assert seg.law.name == "spline(degree=5, points=121)"
    theta = np.linspace(a, a + beta, 997)
    got = seg.lift_at(theta)
    want = cycloidal(theta, a, beta, lift)
    for key, w, tol in zip(("h", "dh", "d2h", "d3h"), want, (1e-9, 1e-7, 1e-5, 1e-3)):
        assert np.max(np.abs(got[key] - w)) < tol * np.max(np.abs(w)), key
    # Inside a program between dwells.
    prog = cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.dwell(), 0, a, 0, 0),
            seg,
            cf.Segment(cf.MotionLaw.cycloidal(), a + beta, 2 * np.pi, lift, 0),
        ]
    )
    assert prog.continuity().continuous_through == 2  # jerk jumps into the dwells, as the cycloid's does


def test_from_callable_scalar_and_periodic():
    calls = []

    def scalar_only(t):
        calls.append(t)
        return 0.004 * (1 - math.cos(t)) + 0.001 * math.sin(2 * t)  # math: refuses arrays

    prog = cf.motion.from_callable(scalar_only, periodic=True, points=90)
    assert isinstance(prog, cf.MotionProgram)
    assert sum(isinstance(c, float) for c in calls) == 90  # one scalar call per sample after the array try
    theta = np.linspace(0, 2 * np.pi, 1001)
    got = prog.evaluate(theta)
    want = smooth(theta)
    assert np.max(np.abs(got["h"] - want[0])) < 1e-9
    assert np.max(np.abs(got["d2h"] - want[2])) < 1e-5 * 0.008
    # A periodic program need not start at 0.
    shifted = cf.motion.from_callable(lambda t: smooth(t)[0], 1.0, 1.0 + 2 * np.pi, periodic=True, points=90)
    assert np.max(np.abs(shifted.evaluate(theta)["h"] - want[0])) < 1e-9


def test_spline_derivatives_are_the_derivatives_of_its_own_lift():
    rng = np.random.default_rng(3)
    theta = np.sort(rng.uniform(0, 2 * np.pi, 40))
    h = 0.005 * np.sin(theta) + 0.0002 * rng.standard_normal(40)
    prog = cf.MotionProgram.from_table(theta, h)
    t = np.linspace(0.1, 6.0, 50)
    e = 1e-5
    mid, lo, hi = prog.evaluate(t), prog.evaluate(t - e), prog.evaluate(t + e)
    for d, f in (("dh", "h"), ("d2h", "dh"), ("d3h", "d2h")):
        fd = (hi[f] - lo[f]) / (2 * e)
        assert np.allclose(mid[d], fd, rtol=1e-5, atol=1e-8 * np.max(np.abs(mid[d]))), d


@pytest.mark.parametrize("uniform", [True, False])
def test_periodic_interpolation_equals_scipy_make_interp_spline(uniform):
    """Same space (periodic quintic, knots at the table points) and same conditions: the same spline."""
    n = 25
    if uniform:
        theta = 2 * np.pi * np.arange(n) / n
    else:
        theta = np.sort(np.random.default_rng(7).uniform(0, 2 * np.pi, n))
    h = smooth(theta)[0] + 1e-4 * np.cos(5 * theta)
    ours = cf.MotionProgram.from_table(theta, h, degree=5)
    ref = make_interp_spline(np.append(theta, theta[0] + 2 * np.pi), np.append(h, h[0]), k=5, bc_type="periodic")
    t = np.linspace(theta[0], theta[0] + 2 * np.pi, 777)
    got = ours.evaluate(t)
    for k, key in enumerate(("h", "dh", "d2h", "d3h")):
        want = ref(t, nu=k)
        assert np.max(np.abs(got[key] - want)) < 1e-9 * np.max(np.abs(want)), key


def test_polynomial_segment_equals_an_independent_solve():
    a, b = 0.5, 2.0
    start, end = [0.001, 0.002, -0.003], [0.008, 0.0, 0.001, 0.02]
    interior = [(1.0, 0.004), (1.6, 0.007)]
    seg = cf.Segment.polynomial(a, b, start, end, interior)
    n = len(start) + len(end) + len(interior)
    # Monomials in u = theta - a, rows for each derivative condition, numpy's dense solve.
    rows, rhs = [], []
    for u0, conds in ((0.0, start), (b - a, end)):
        for r, v in enumerate(conds):
            rows.append([math.perm(k, r) * u0 ** (k - r) if k >= r else 0.0 for k in range(n)])
            rhs.append(v)
    for t0, v in interior:
        rows.append([(t0 - a) ** k for k in range(n)])
        rhs.append(v)
    coef = np.linalg.solve(np.array(rows), np.array(rhs))
    poly = np.polynomial.Polynomial(coef)
    t = np.linspace(a, b, 301)
    got = seg.lift_at(t)
    for k, key in enumerate(("h", "dh", "d2h", "d3h")):
        want = poly.deriv(k)(t - a) if k else poly(t - a)
        assert np.max(np.abs(got[key] - want)) < 1e-9 * max(1e-3, np.max(np.abs(want))), key
    assert seg.law.name == f"polynomial(degree={n - 1})"


def test_polynomial_through_points_equals_numpy_polyfit():
    pts = [(0.3, 0.002), (0.5, 0.0035), (0.9, 0.001)]
    seg = cf.Segment.polynomial(0.0, 1.2, [0.0], [0.004], pts)
    x = np.array([0.0] + [p[0] for p in pts] + [1.2])
    y = np.array([0.0] + [p[1] for p in pts] + [0.004])
    fit = np.polyfit(x, y, 4)
    t = np.linspace(0, 1.2, 50)
    assert np.allclose(seg.lift_at(t)["h"], np.polyval(fit, t), rtol=0, atol=1e-12)


def test_345_and_4567_from_conditions_equal_the_built_in_laws():
    for conds, law in ((3, cf.MotionLaw.polynomial_345()), (4, cf.MotionLaw.polynomial_4567())):
        seg = cf.Segment.polynomial(0.2, 1.7, [0.0] * conds, [0.01] + [0.0] * (conds - 1))
        x = np.linspace(0, 1, 101)
        assert np.allclose(seg.law.evaluate(x)["S"], law.evaluate(x)["S"], rtol=0, atol=1e-12)
        assert seg.law.peaks().acceleration == pytest.approx(law.peaks().acceleration, rel=1e-9)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda: cf.MotionProgram.from_table([0, 1, 2, 7], [0, 1e-3, 2e-3, 0]), r"theta\[3\]"),
        (lambda: cf.MotionProgram.from_table(np.arange(12) * 0.5, np.zeros(12), degree=4), "degree"),
        (lambda: cf.MotionProgram.from_table(np.arange(12) * 0.5, np.zeros(12), smoothing=-1), "smoothing"),
        (lambda: cf.MotionProgram.from_table([0, 1, 2, 3], [0, 1e-3, 2e-3, 0]), "theta: a periodic spline"),
        (lambda: cf.Segment.from_table([0, 1, 1, 2], [0, 1, 2, 3]), "theta must be strictly increasing"),
        (lambda: cf.Segment.from_table([0, 1, 2], [0, np.nan, 2]), r"h\[1\] must be finite"),
        (lambda: cf.Segment.from_table([0, 1, 2], [0, 1, 2], start_derivatives=[0] * 5), "start_derivatives"),
        (lambda: cf.Segment.polynomial(1.0, 2.0, [0], [0], [(2.5, 0.0)]), r"interior\[0\]"),
        (
            lambda: cf.Segment.polynomial(1.0, 1.0, [0], [0]),
            "theta_end - theta_start must be finite and at least 1e-06",
        ),
        (lambda: cf.Segment.polynomial(1.0, 2.0, [], [0]), "start must hold"),
        (lambda: cf.Segment.polynomial(1.0, 2.0, [0] * 20, [1e-3] + [0] * 19), "ill-conditioned"),
        (lambda: cf.motion.from_callable(np.sin, 0, 1, points=1), "points"),
        (lambda: cf.motion.from_callable(np.sin, 0, 1, periodic=True), "one revolution"),
        (lambda: cf.motion.from_callable(lambda t: np.log(t - 0.5), 0, 1), "f must return a finite lift"),
        (lambda: cf.motion.smoothness(cf.MotionProgram.paper_default(), rpm=-1), "rpm"),
    ],
)
def test_bad_input_raises_value_error_naming_the_parameter(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_program_checks_a_custom_segment_against_its_law():
    seg = cf.Segment.polynomial(0.5, 2.0, [0.0, 0, 0], [0.004, 0, 0])
    with pytest.raises(ValueError, match=r"segment: its polynomial.*law spans 85.9.* deg but the segment spans 114.5"):
        cf.Segment(seg.law, 0.5, 2.5, 0.0, 0.004)  # refused when made, not only in a MotionProgram


def test_continuity_and_require_continuity():
    prog = cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.dwell(), 0, 30 * DEG, 0, 0),
            cf.Segment(cf.MotionLaw.constant_acceleration(), 30 * DEG, 180 * DEG, 0, 0.01),
            cf.Segment(cf.MotionLaw.dwell(), 180 * DEG, 210 * DEG, 0.01, 0.01),
            cf.Segment(cf.MotionLaw.cycloidal(), 210 * DEG, 2 * np.pi, 0.01, 0),
        ]
    )
    report = prog.continuity()
    assert len(report) == 4
    assert report.continuous_through == 1
    b = report[0]
    assert (b.left_segment, b.right_segment) == (0, 1)
    assert b.continuous_through == 1
    assert b.jump[2] == pytest.approx(4 * 0.01 / (150 * DEG) ** 2, rel=1e-12)
    assert report[-1].right_segment == 0 and report[-1].continuous_through == 2  # cycloid into the dwell
    prog.require_continuity(1)
    with pytest.raises(ValueError, match=r"segments\[0\].*segments\[1\].*30 deg.*h'' \(acceleration"):
        prog.require_continuity(2)


def test_smoothness_in_physical_units_at_750_rpm():
    omega = 750 * 2 * np.pi / 60
    beta = 150 * DEG
    truth = 0.010 * (8 * np.pi / (np.pi + 2)) / beta**2 * omega**2  # modified trapezoid peak, m/s^2
    r = cf.motion.smoothness(cf.MotionProgram.paper_default(), rpm=750)
    assert r["at_speed"]["acceleration"] == pytest.approx(truth, rel=1e-9)
    assert r["at_speed"]["velocity"] == pytest.approx(0.010 * 2 / beta * omega, rel=1e-9)
    assert r["table_points"] == 0
    # A 73-point table of the same program (every 5 deg) as a quintic spline: near the truth.
    theta = np.arange(72) * 5 * DEG
    table = cf.MotionProgram.from_table(theta, cf.MotionProgram.paper_default().evaluate(theta)["h"])
    t = cf.motion.smoothness(table, rpm=750)
    assert t["at_speed"]["acceleration"] == pytest.approx(truth, rel=0.1)
    assert t["table_points"] == 72 and t["residual"]["max"] < 1e-12


def test_smoothing_reduces_noise_in_the_jerk():
    rng = np.random.default_rng(1)
    n, sigma = 360, 10e-6
    theta = 2 * np.pi * np.arange(n) / n
    h = smooth(theta)[0] + sigma * rng.standard_normal(n)
    lam = 1.0 / (2 * np.pi / n * 6.0**6)
    rough = cf.motion.smoothness(cf.MotionProgram.from_table(theta, h))
    fine = cf.motion.smoothness(cf.MotionProgram.from_table(theta, h, smoothing=lam))
    assert rough["jerk"]["value"] > 10 * fine["jerk"]["value"]
    assert 0.6 * sigma < fine["residual"]["rms"] < 1.4 * sigma
    assert rough["jerk_roughness"] > 0.1 > 0.01 > fine["jerk_roughness"]
    assert len(rough["jerk_excursions"]) == 5


def test_pickling_round_trips_custom_laws():
    theta = 2 * np.pi * np.arange(30) / 30
    periodic = cf.MotionProgram.from_table(theta, smooth(theta)[0], smoothing=1e-6)
    seg = cf.Segment.from_table(
        np.linspace(0.5, 2.0, 11),
        0.004 * np.linspace(0, 1, 11) ** 2,
        degree=3,
        start_derivatives=[0.0],
        end_derivatives=[0.0053],
    )
    poly = cf.Segment.polynomial(2.0, 3.0, [0.004, 0, 0], [0.0, 0, 0], [(2.5, 0.003)])
    prog = cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.dwell(), 0, 0.5, 0, 0),
            seg,
            poly,
            cf.Segment(cf.MotionLaw.dwell(), 3.0, 2 * np.pi, 0, 0),
        ]
    )
    t = np.linspace(0, 2 * np.pi, 333)
    for p in (periodic, prog):
        q = pickle.loads(pickle.dumps(p))
        assert [s.law.name for s in q.segments] == [s.law.name for s in p.segments]
        for key in ("h", "dh", "d2h", "d3h"):
            assert np.array_equal(q.evaluate(t)[key], p.evaluate(t)[key])
    law = pickle.loads(pickle.dumps(poly.law))
    assert law.definition["interior"] == [(2.5, 0.003)]
    assert pickle.loads(pickle.dumps(cf.MotionLaw.modified_sine())).name == cf.MotionLaw.modified_sine().name


def test_custom_law_introspection():
    seg = cf.Segment.polynomial(1.0, 2.0, [0.0, 0, 0, 0], [0.01, 0, 0, 0])
    assert seg.law.is_custom and not cf.MotionLaw.cycloidal().is_custom
    assert seg.law.has_zero_end_acceleration()
    peaks = seg.law.lift_peaks()
    assert peaks["acceleration"]["value"] == pytest.approx(0.01 * cf.MotionLaw.polynomial_4567().peaks().acceleration)
    assert peaks["velocity"]["theta"] == pytest.approx(0.5)  # offset from the segment start: mid-rise
    assert seg.law.evaluate_lift(1.0)["h"] == pytest.approx(0.01)
    assert cf.MotionLaw.cycloidal().definition is None
