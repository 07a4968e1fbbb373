# SPDX-License-Identifier: BSD-3-Clause
"""Monte-Carlo studies that measure what they say: a roller-radius tolerance against the cam cut for the
nominal roller (checked against brute force on the sampled cam surface and the closed form of a circular
cam), sensitivities in the metric's units (checked on rows with a known linear law and against the
paper model's spring rate over the cosine of the pressure angle), and ``montecarlo --rpm``."""

import copy
import json
import math
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest
from camfollower import cli
from camfollower import tolerance as tol
from camfollower.config import load_config
from camfollower.response import steady_response

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
TWO_PI = 2 * math.pi


# --- independent truths -------------------------------------------------------------------------------


def _surface(follower, program, points=400_000):
    """The cam surface (cam frame) the follower cuts with the program, densely sampled."""
    p = follower.profile(program, np.linspace(0.0, TWO_PI, points, endpoint=False))
    return p["surface_x"], p["surface_y"]


def _ground(theta, x, y):
    c, s = math.cos(theta), math.sin(theta)
    return c * x - s * y, s * x + c * y


def brute_translating(surface, theta, radius, base_radius, offset):
    """Lift of a roller of `radius` on the follower's line x = offset: the highest centre at which the
    circle touches a sampled surface point (the lowest the circle can sit without cutting into the cam),
    measured from where the same roller sits on the base circle."""
    sx, sy = surface
    out = []
    for a in theta:
        qx, qy = _ground(a, sx, sy)
        near = (np.abs(qx - offset) < radius) & (qy > 0.0)
        out.append(np.max(qy[near] + np.sqrt(radius**2 - (qx[near] - offset) ** 2)))
    return np.array(out) - math.sqrt((base_radius + radius) ** 2 - offset**2)


def brute_oscillating(surface, theta, radius, follower, program):
    """Arm rotation of a roller of `radius` on the arm: for each sampled surface point the arm angles at
    which the circle passes through it bound an interval the centre may not enter; the arm rests at the
    largest such bound (in the lifting sense) near its nominal angle."""
    sx, sy = surface
    px, py = np.asarray(follower.pivot, dtype=float).reshape(2)
    arm = follower.arm_length
    sigma = 1.0 if follower.turn == "counter_clockwise" else -1.0
    start = cf.OscillatingRoller(follower.base_radius, radius, [px, py], arm, follower.turn).start_angle
    nominal = follower.start_angle + sigma * program.evaluate(np.asarray(theta))["h"]
    out = []
    for a, phi_n in zip(theta, nominal):
        qx, qy = _ground(a, sx, sy)
        dx, dy = qx - px, qy - py
        d = np.hypot(dx, dy)
        cos_gamma = (arm**2 + d**2 - radius**2) / (2 * arm * d)
        ok = np.abs(cos_gamma) < 1.0
        beta, gamma = np.arctan2(dy[ok], dx[ok]), np.arccos(cos_gamma[ok])
        rel = [((beta + g - phi_n + math.pi) % TWO_PI - math.pi) for g in (gamma, -gamma)]
        near = (np.abs(rel[0]) < 0.3) & (np.abs(rel[1]) < 0.3)
        bound = np.maximum(sigma * rel[0][near], sigma * rel[1][near])
        out.append(np.max(bound) + sigma * (phi_n - start))
    return np.array(out)


def circle_cam_translating(theta, radius, disk_radius, ecc, offset):
    """Centre height of a roller of `radius` on the line x = offset touching a circular disk of
    `disk_radius` whose centre sits `ecc` from the cam axis at angle theta - pi/2 (the cam turning
    counter-clockwise): (offset - ecc cos)^2 + (y - ecc sin)^2 = (disk_radius + radius)^2."""
    c, s = np.cos(theta - math.pi / 2), np.sin(theta - math.pi / 2)
    return ecc * s + np.sqrt((disk_radius + radius) ** 2 - (offset - ecc * c) ** 2)


def circle_cam_arm(theta, radius, disk_radius, ecc, pivot, arm, near):
    """Arm angle of a roller of `radius` on an arm of length `arm` about `pivot` touching the same disk:
    the intersection of the circle of the arm and the circle of radius disk_radius + radius about the
    disk centre, the one nearer the angle `near`."""
    dx, dy = ecc * np.cos(theta - math.pi / 2) - pivot[0], ecc * np.sin(theta - math.pi / 2) - pivot[1]
    d = np.hypot(dx, dy)
    gamma = np.arccos((arm**2 + d**2 - (disk_radius + radius) ** 2) / (2 * arm * d))
    beta = np.arctan2(dy, dx)
    roots = np.stack([beta + gamma, beta - gamma])
    pick = np.argmin(np.abs((roots - near + math.pi) % TWO_PI - math.pi), axis=0)
    return np.choose(pick, roots)


def _derivatives(f, theta, eta=2e-3):
    """h, h', h'' of a smooth closed form by 5-point central differences (truncation ~eta^4 h^(6)/90, rounding
    ~1e-17 m / eta^2: both below 1e-11 here)."""
    v = [f(theta + k * eta) for k in (-2, -1, 0, 1, 2)]
    return (
        v[2],
        (v[0] - 8 * v[1] + 8 * v[3] - v[4]) / (12 * eta),
        (-v[0] + 16 * v[1] - 30 * v[2] + 16 * v[3] - v[4]) / (12 * eta**2),
    )


# --- the roller on a fixed cam --------------------------------------------------------------------------

PAPER = cf.MotionProgram.paper_default()
ARM_PROGRAM = cf.MotionProgram.paper_default(0.25)  # 0.25 rad of arm rotation
DWELLS = [(0.0, 30.0), (180.0, 210.0)]


def _on_dwell(theta_deg, margin=0.5):
    return np.any([(a + margin < theta_deg) & (theta_deg < b - margin) for a, b in DWELLS], axis=0)


def test_the_same_roller_follows_the_design_lift():
    for f, program in (
        (cf.TranslatingRoller(0.03, 0.008, 0.01), PAPER),
        (cf.OscillatingRoller(0.03, 0.008, [0.06, 0.05], 0.06), ARM_PROGRAM),
    ):
        g, q = tol.roller_on_fixed_cam(f, program, f.roller_radius)
        assert g is f and q is program
        # a radius one part in 1e12 off goes through the whole construction: the lift and its
        # derivatives are the design's
        g, q = tol.roller_on_fixed_cam(f, program, f.roller_radius * (1 + 1e-12))
        assert g.roller_radius == pytest.approx(f.roller_radius, rel=1e-11) and type(g) is type(f)
        theta = np.linspace(0.0, TWO_PI, 7201)[:-1]
        a, b = q.evaluate(theta), program.evaluate(theta)
        scale = np.abs(b["h"]).max()
        assert np.abs(a["h"] - b["h"]).max() < 1e-11 * scale
        assert np.abs(a["dh"] - b["dh"]).max() < 1e-8 * np.abs(b["dh"]).max()
        # h'' of the B-spline pieces against the law's: apart from the law's jerk steps (x = 1/8, 3/8, ...)
        # where an interpolating quintic rounds the corner over a few table points
        steps = np.radians(
            [a_ + (b_ - a_) * x for a_, b_ in ((30, 180), (210, 360)) for x in (1 / 8, 3 / 8, 5 / 8, 7 / 8)]
        )
        away = np.min(np.abs(theta[:, None] - steps[None, :]), axis=1) > np.radians(1.0)
        assert np.abs(a["d2h"] - b["d2h"])[away].max() < 1e-6 * np.abs(b["d2h"]).max()


@pytest.mark.parametrize("offset", [0.01, 0.0])
@pytest.mark.parametrize("delta", [1e-4, -1e-4])
def test_a_translating_roller_of_another_radius_against_brute_force(offset, delta):
    f = cf.TranslatingRoller(0.03, 0.008, offset)
    radius = 0.008 + delta
    g, q = tol.roller_on_fixed_cam(f, PAPER, radius)
    assert g.roller_radius == radius and g.offset == offset and g.base_radius == 0.03
    theta = np.radians(np.arange(0.0, 360.0, 1.5))
    truth = brute_translating(_surface(f, PAPER), theta, radius, 0.03, offset)
    lift = q.evaluate(theta)["h"]
    # the brute force's own error: surface points 0.6 um apart miss the tangent point by ~(0.6 um)^2 / (8 rho),
    # 1e-11 m (observed 7e-12 m)
    assert np.abs(lift - truth).max() < 5e-11
    # the rise and return differ measurably from the design lift (brute force says the same) ...
    design = PAPER.evaluate(theta)["h"]
    moving = ~_on_dwell(np.degrees(theta), margin=-1.0)
    assert np.abs(truth - design)[moving].max() > 1e-6
    assert np.abs(lift - design)[moving].max() == pytest.approx(np.abs(truth - design)[moving].max(), rel=1e-3)
    # ... the dwells stay dwells: constant, at the level of distance geometry. On the base circle
    # (radius r_b) the centre sits r_b + r' from the axis (lift 0); on the top dwell the surface is a
    # circle of radius R_s = |C_top| - r about the axis, so the centre is at R_s + r' and the lift is
    # sqrt((R_s + r')^2 - e^2) - sqrt((r_b + r')^2 - e^2): exactly h for a centred roller.
    top_surface = math.hypot(offset, math.sqrt(0.038**2 - offset**2) + 0.01) - 0.008
    top = math.sqrt((top_surface + radius) ** 2 - offset**2) - math.sqrt((0.03 + radius) ** 2 - offset**2)
    dwell = _on_dwell(np.degrees(theta))
    levels = np.where(np.degrees(theta[dwell]) < 90, 0.0, top)
    assert np.abs(lift[dwell] - levels).max() < 1e-15
    if offset == 0.0:
        assert top == pytest.approx(0.01, abs=1e-15)
    else:
        assert abs(top - 0.01) > 1e-7  # an offset roller's top dwell moves (-14 nm per um of radius)
    assert [s.law.name for s in q.segments if s.law.name == "dwell"] and q.segments[0].theta_start == 0.0


@pytest.mark.parametrize("turn", ["counter_clockwise", "clockwise"])
@pytest.mark.parametrize("delta", [5e-4, -5e-4])
def test_an_oscillating_roller_of_another_radius_against_brute_force(turn, delta):
    f = cf.OscillatingRoller(0.03, 0.008, [0.06, 0.05], 0.06, turn=turn)
    radius = 0.008 + delta
    g, q = tol.roller_on_fixed_cam(f, ARM_PROGRAM, radius)
    assert g.roller_radius == radius and g.turn == turn and g.arm_length == 0.06
    theta = np.radians(np.arange(0.0, 360.0, 2.0))
    truth = brute_oscillating(_surface(f, ARM_PROGRAM), theta, radius, f, ARM_PROGRAM)
    lift = q.evaluate(theta)["h"]
    # rad: the sampled surface's ~1e-11 m over the 0.06 m arm (observed 1.4e-10)
    assert np.abs(lift - truth).max() < 1e-9
    design = ARM_PROGRAM.evaluate(theta)["h"]
    assert np.abs(truth - design).max() > 1e-4  # the arm turns differently (rad)
    dwell = _on_dwell(np.degrees(theta))
    for lo in (True, False):  # each dwell at one level
        part = lift[dwell & ((np.degrees(theta) < 90) == lo)]
        assert np.ptp(part) < 1e-14


def test_circular_cam_closed_form():
    """An eccentric circular disk (radius 35 mm, centre 4 mm off the axis) is the cam of any roller: its
    centre stays disk radius + roller radius from the disk centre. The design lift is made for a 10 mm
    roller (as a periodic table of the closed form, 0.125 deg apart: the new roller's curvature depends
    on the surface's, i.e. on the table's third derivative; at 0.25 deg the table's own error showed,
    2.4e-7 of the peak h'' of the arm); a 9 mm and a 12 mm roller then follow the closed form of their
    own radius, lift, slope and curvature."""
    disk, ecc, offset, r = 0.035, 0.004, 0.005, 0.010
    base = disk - ecc
    grid = np.linspace(0.0, TWO_PI, 2880, endpoint=False)
    s0 = math.sqrt((base + r) ** 2 - offset**2)
    program = cf.MotionProgram.from_table(grid, circle_cam_translating(grid, r, disk, ecc, offset) - s0)
    f = cf.TranslatingRoller(base, r, offset)
    theta = np.linspace(0.0, TWO_PI, 721)[:-1]
    for radius in (0.009, 0.012):
        q = tol.roller_on_fixed_cam(f, program, radius)[1]
        s0r = math.sqrt((base + radius) ** 2 - offset**2)
        h, dh, d2h = _derivatives(
            lambda t, r_=radius, s_=s0r: circle_cam_translating(t, r_, disk, ecc, offset) - s_, theta
        )
        ev = q.evaluate(theta)
        assert np.abs(ev["h"] - h).max() < 1e-12
        assert np.abs(ev["dh"] - dh).max() < 1e-10
        assert np.abs(ev["d2h"] - d2h).max() < 1e-8 * np.abs(d2h).max()
    # the same disk under an oscillating roller: its arm angle from the intersection of two circles
    pivot, arm = np.array([0.07, 0.04]), 0.07
    fo = cf.OscillatingRoller(base, r, pivot, arm)
    start = fo.start_angle
    nominal = circle_cam_arm(grid, r, disk, ecc, pivot, arm, start)
    arm_program = cf.MotionProgram.from_table(grid, nominal - start)
    for radius in (0.009, 0.012):
        q = tol.roller_on_fixed_cam(fo, arm_program, radius)[1]
        start_r = cf.OscillatingRoller(base, radius, pivot, arm).start_angle
        h, dh, d2h = _derivatives(
            lambda t, r_=radius, s_=start_r: circle_cam_arm(t, r_, disk, ecc, pivot, arm, start) - s_, theta
        )
        ev = q.evaluate(theta)
        assert np.abs(ev["h"] - h).max() < 1e-11
        assert np.abs(ev["dh"] - dh).max() < 1e-9
        assert np.abs(ev["d2h"] - d2h).max() < 1e-7 * np.abs(d2h).max()


def test_a_roller_too_large_for_a_concave_flank_and_bad_input_are_refused():
    # a 10 mm rise over 40 deg on a 40 mm base circle: the start of the rise is concave
    program = cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.dwell(), 0.0, math.radians(100), 0.0, 0.0),
            cf.Segment(cf.MotionLaw.cycloidal(), math.radians(100), math.radians(140), 0.0, 0.01),
            cf.Segment(cf.MotionLaw.dwell(), math.radians(140), math.radians(220), 0.01, 0.01),
            cf.Segment(cf.MotionLaw.cycloidal(), math.radians(220), TWO_PI, 0.01, 0.0),
        ]
    )
    f = cf.TranslatingRoller(0.04, 0.008, 0.0)
    radius = f.profile(program, np.linspace(0, TWO_PI, 100_000))["surface_radius"]
    hollow = -radius[radius < 0].max()  # the tightest concave radius of the cam's surface
    assert 0.008 < hollow < 0.05
    tol.roller_on_fixed_cam(f, program, 0.99 * hollow)
    with pytest.raises(ValueError, match="roller_radius.*does not fit the cam's concave flank"):
        tol.roller_on_fixed_cam(f, program, 1.01 * hollow)
    for bad in (0.0, -0.001, math.nan, 2.0, "8 mm"):
        with pytest.raises(ValueError, match="roller_radius"):
            tol.roller_on_fixed_cam(f, program, bad)
    with pytest.raises(ValueError, match="TranslatingRoller or OscillatingRoller"):
        tol.roller_on_fixed_cam(cf.TranslatingFlat(0.04), program, 0.008)
    with pytest.raises(ValueError, match="roller_tolerance must be one of fixed_cam, regenerated_cam"):
        tol.PaperCase(roller_tolerance="regenerate")


def _contact_program(m):
    return m.__getstate__()["contacts"][0]["program"]


def test_builders_put_the_roller_on_the_nominal_cam_unless_told_otherwise():
    fixed, regenerated = tol.PaperCase(), tol.PaperCase(roller_tolerance="regenerated_cam")
    assert "regenerated_cam" in repr(regenerated) and "roller_tolerance" not in repr(fixed)
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    design = PAPER.evaluate(theta)["h"]
    lift = _contact_program(fixed({"roller_radius": 0.0081})).evaluate(theta)["h"]
    expected = tol.roller_on_fixed_cam(cf.TranslatingRoller(0.03, 0.008, 0.01), PAPER, 0.0081)[1].evaluate(theta)["h"]
    assert np.array_equal(lift, expected) and np.abs(lift - design).max() > 1e-6
    assert np.array_equal(_contact_program(regenerated({"roller_radius": 0.0081})).evaluate(theta)["h"], design)
    assert np.array_equal(_contact_program(fixed({"roller_radius": 0.008})).evaluate(theta)["h"], design)
    # the nominal roller given as a fixed value is the one the cam was cut for
    cut_for_9 = tol.PaperCase(roller_radius=0.009)
    assert np.array_equal(_contact_program(cut_for_9({"roller_radius": 0.009})).evaluate(theta)["h"], design)
    # a config: the swing arm's roller radius by key path, its cam the config's
    data = copy.deepcopy(load_config(EXAMPLES / "swing_arm.toml").data)
    data["contact"][0]["follower"]["roller_radius"] = 0.008
    name = "contact.0.follower.roller_radius"
    case = load_config(EXAMPLES / "swing_arm.toml")
    f, program = case.builder.__getstate__()["contacts"][0]["follower"], case.programs[data["contact"][0]["program"]]
    build = tol.ConfigCase(data, EXAMPLES)
    expected = tol.roller_on_fixed_cam(f, program, 0.0085)[1].evaluate(theta)["h"]
    assert np.array_equal(_contact_program(build({name: 0.0085})).evaluate(theta)["h"], expected)
    regenerated = build.with_options(roller_tolerance="regenerated_cam")
    assert np.array_equal(
        _contact_program(regenerated({name: 0.0085})).evaluate(theta)["h"], program.evaluate(theta)["h"]
    )
    # the study runs; its cases differ from the regenerated-cam study's (same draws)
    tols = {"roller_radius": tol.Uniform(-1e-4, 1e-4)}
    a = tol.monte_carlo(tol.PaperCase(), tols, cases=3, seed=2, executor="serial", progress=False)
    b = tol.monte_carlo(
        tol.PaperCase(roller_tolerance="regenerated_cam"), tols, cases=3, seed=2, executor="serial", progress=False
    )
    assert all(r["ok"] for r in a.rows + b.rows)
    assert [r["roller_radius"] for r in a.rows] == [r["roller_radius"] for r in b.rows]
    assert all(abs(x["min_force_N"] - y["min_force_N"]) > 1e-4 for x, y in zip(a.rows, b.rows))
    assert a.nominal["min_force_N"] == b.nominal["min_force_N"]


# --- sensitivities in the metric's units ---------------------------------------------------------------


def test_sensitivities_recover_the_slopes_of_a_known_linear_law():
    """y = 3e4 a - 0.5 b + 2 c (+ noise): a is a length of 10 um spread (effect 0.3 N per std), b a
    stiffness-like number of 20 spread (-10 N per std), c a 0.07 spread (0.14 N per std); d never varies."""
    rng = np.random.default_rng(7)
    n = 3000
    a, b, c = rng.normal(0.0, 1e-5, n), rng.normal(100.0, 20.0, n), rng.normal(0.0, 0.07, n)
    y = 150.0 + 3e4 * a - 0.5 * b + 2.0 * c + rng.normal(0.0, 1e-3, n)
    rows = [
        {"case": i, "seed": 7, "a": a[i], "b": b[i], "c": c[i], "d": 1.0, "min_force_N": y[i], "ok": True, "error": ""}
        for i in range(n)
    ]
    r = tol.MonteCarloResult(
        rows=rows, nominal={"min_force_N": 100.0}, parameters=["a", "b", "c", "d"], metrics=["min_force_N"]
    )
    s = r.sensitivities("min_force_N")
    assert [d["parameter"] for d in s] == ["b", "a", "c", "d"]  # by the absolute effect of one std
    by = {d["parameter"]: d for d in s}
    for name, slope, x in (("a", 3e4, a), ("b", -0.5, b), ("c", 2.0, c)):
        assert by[name]["slope"] == pytest.approx(slope, rel=2e-3)
        assert by[name]["parameter_std"] == pytest.approx(np.std(x, ddof=1), rel=1e-12)
        assert by[name]["effect_of_one_std"] == pytest.approx(by[name]["slope"] * np.std(x, ddof=1), rel=1e-12)
    assert by["a"]["effect_of_one_std"] == pytest.approx(0.3, rel=0.05)
    assert by["c"]["effect_of_one_std"] == pytest.approx(0.14, rel=0.05)
    assert math.isnan(by["d"]["slope"]) and by["d"]["effect_of_one_std"] == 0.0 and by["d"]["parameter_std"] == 0.0


def test_sensitivity_of_the_margin_to_the_spring_preload_is_the_rate_over_cos_alpha():
    """The paper's mechanism is linear while in contact: more spring deflection adds k_s per metre to the
    force along the follower axis, and the contact normal, inclined at the pressure angle alpha, carries
    it as k_s / cos(alpha) at the angle of the smallest force."""
    r = tol.monte_carlo(
        tol.PaperCase(),
        {"spring_preload_deflection": tol.Normal(0.3e-3)},
        cases=6,
        seed=3,
        executor="serial",
        progress=False,
    )
    theta = math.radians(r.nominal["min_force_angle_deg"])
    alpha = cf.TranslatingRoller(0.03, 0.008, 0.01).profile(PAPER, np.array([theta]))["pressure_angle"][0]
    s = r.sensitivities("min_force_N")[0]
    assert s["slope"] == pytest.approx(cf.Parameters().get("spring_stiffness") / math.cos(alpha), rel=1e-4)


# --- montecarlo --rpm ----------------------------------------------------------------------------------


def test_montecarlo_runs_at_the_speed_given_on_the_command_line(tmp_path, capsys):
    cfg = EXAMPLES / "paper_studies.toml"
    out = tmp_path / "mc"
    assert (
        cli.main(
            ["montecarlo", str(cfg), "--cases", "6", "--workers", "1", "--no-progress", "--rpm", "900", "-o", str(out)]
        )
        == 0
    )
    printed = capsys.readouterr().out
    summary = json.loads((out / "summary.json").read_text())
    assert summary["camshaft_speed_rpm"] == 900.0 and "6 cases at 900 rpm" in printed
    # the study is the one of the same config written for 900 rpm (not its own 750 rpm): same cases
    at_900 = tmp_path / "at_900.toml"
    at_900.write_text(cfg.read_text().replace('speed = "750 rpm"', 'speed = "900 rpm"'))
    assert (
        cli.main(
            ["montecarlo", str(at_900), "--cases", "6", "--workers", "1", "--no-progress", "-o", str(tmp_path / "900")]
        )
        == 0
    )
    assert (
        cli.main(
            ["montecarlo", str(cfg), "--cases", "3", "--workers", "1", "--no-progress", "-o", str(tmp_path / "750")]
        )
        == 0
    )
    capsys.readouterr()
    other = json.loads((tmp_path / "900" / "summary.json").read_text())
    own = json.loads((tmp_path / "750" / "summary.json").read_text())
    assert other["camshaft_speed_rpm"] == 900.0 and own["camshaft_speed_rpm"] == 750.0
    assert summary["metrics"] == other["metrics"]
    assert (out / "cases.csv").read_text() == (tmp_path / "900" / "cases.csv").read_text()
    assert abs(summary["metrics"]["min_force_N"]["nominal"] - own["metrics"]["min_force_N"]["nominal"]) > 1.0
    # and its nominal is the steady state of the config's mechanism turned to 900 rpm
    m = load_config(cfg).mechanism.with_camshaft_speed_rpm(900.0)
    assert summary["metrics"]["min_force_N"]["nominal"] == pytest.approx(
        steady_response(m, fallback="transient")["min_force_N"], rel=1e-9
    )
    assert "N per std of" in printed and summary["sensitivities"]["min_force_N"][0]["effect_of_one_std"] is not None
    # the table's rpm, overridden by --rpm
    with_rpm = tmp_path / "rpm.toml"
    with_rpm.write_text(cfg.read_text().replace("cases = 200", "cases = 200\nrpm = 1000"))
    assert (
        cli.main(
            ["montecarlo", str(with_rpm), "--cases", "2", "--workers", "1", "--no-progress", "-o", str(tmp_path / "t")]
        )
        == 0
    )
    assert json.loads((tmp_path / "t" / "summary.json").read_text())["camshaft_speed_rpm"] == 1000.0
    capsys.readouterr()
    # bad speeds: one line naming --rpm (or the table's key, at its line) and the range
    for bad in ("nan", "0", "-5", "1e9", "inf"):
        assert cli.main(["montecarlo", str(cfg), "--rpm", bad, "-o", str(tmp_path / "x")]) == 2  # usage error
        err = capsys.readouterr().err
        assert err.startswith("camfollower: error: --rpm:") and "rpm" in err.split("--rpm")[1]
    bad_table = tmp_path / "bad.toml"
    bad_table.write_text(cfg.read_text().replace("cases = 200", "cases = 200\nrpm = -3"))
    assert cli.main(["montecarlo", str(bad_table), "-o", str(tmp_path / "x")]) == 1
    line = cfg.read_text().splitlines().index("cases = 200") + 2  # the line after it
    assert f"bad.toml:{line}: montecarlo.rpm: must be a camshaft speed in" in capsys.readouterr().err
    mode = tmp_path / "mode.toml"
    mode.write_text(cfg.read_text().replace("cases = 200", 'cases = 200\nroller_tolerance = "regenerate"'))
    assert cli.main(["montecarlo", str(mode), "-o", str(tmp_path / "x")]) == 1
    assert "montecarlo.roller_tolerance: must be one of fixed_cam, regenerated_cam" in capsys.readouterr().err
