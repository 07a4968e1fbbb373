# SPDX-License-Identifier: BSD-3-Clause
"""Conjugate cams (include/camfollower/contact/conjugate.hpp): two cams on one shaft holding one follower
both ways. Checked against independent truth: the return cam's surface, placed on the shaft and turned
with it, touches a roller carried rigidly with the lift roller (brute-force distance, translating and
bell-crank pairs); the dynamics against the follower's equation of motion between two cams written out
here and integrated by scipy; the rigid check's load sharing against the sign of m omega^2 h''."""

import math
import pickle
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest
from camfollower.config import force_closure, load_config
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

PROGRAM = cf.MotionProgram.paper_default(0.010)  # 10 mm rise 30-180 deg, return 210-360 deg


def swing_program(lift_deg=15.0):
    d, law = math.radians, cf.MotionLaw
    return cf.MotionProgram(
        [
            cf.Segment(law.dwell(), 0.0, d(60), 0.0, 0.0),
            cf.Segment(law.cycloidal(), d(60), d(150), 0.0, d(lift_deg)),
            cf.Segment(law.dwell(), d(150), d(210), d(lift_deg), d(lift_deg)),
            cf.Segment(law.cycloidal(), d(210), d(300), d(lift_deg), 0.0),
            cf.Segment(law.dwell(), d(300), 2 * math.pi, 0.0, 0.0),
        ]
    )


def rotation(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def surface_distance(follower, program, shaft_to_ground, point, guess):
    """Distance (m) from a ground-frame point to a cam's surface, the cam turned into the ground frame by
    the rotation `shaft_to_ground`; minimised over the profile's parameter near `guess` (rad)."""

    def distance(psi):
        p = follower.profile(program, psi)
        return float(np.linalg.norm(shaft_to_ground @ np.array([p["surface_x"], p["surface_y"]]) - point))

    samples = np.linspace(guess - 0.6, guess + 0.6, 241)
    best = samples[int(np.argmin([distance(s) for s in samples]))]
    r = minimize_scalar(distance, bounds=(best - 0.01, best + 0.01), method="bounded", options={"xatol": 1e-12})
    return r.fun


def test_the_translating_return_cam_touches_a_roller_carried_with_the_lift_roller(tmp_path):
    lift = cf.TranslatingRoller(0.040, 0.010, 0.005)
    back = cf.TranslatingRoller(0.050, 0.012, -0.005)  # on the lift roller's axis: offset -e in its turned frame
    b = cf.MechanismBuilder()
    b.add_dof("f", 0.5)
    assert b.add_conjugate_cams("cams", PROGRAM, lift, back, follower_dof="f", stiffness=1e9) is None  # no crank
    ret = b.contacts[1]
    assert ret["name"] == "cams.return" and ret["frame_angle"] == pytest.approx(math.pi)
    s0 = math.sqrt(0.050**2 - 0.005**2)
    worst = 0.0
    for theta in np.radians(np.arange(0.0, 360.0, 7.5)):
        # The lift roller's centre from its definition (axis x = e, pitch height + lift); the return
        # roller rides 'distance' below it on the same axis: the rigid follower.
        h = PROGRAM.evaluate(theta)["h"]
        centre = np.array([0.005, s0 + h])
        distance = s0 + math.sqrt(0.062**2 - 0.005**2) + PROGRAM.max_lift()
        roller = centre - np.array([0.0, distance])
        # The return cam: its body turned by the shaft (theta + phase) and by its frame (pi).
        to_ground = rotation(theta + ret["phase"] + ret["frame_angle"])
        gap = surface_distance(back, ret["program"], to_ground, roller, theta) - 0.012
        worst = max(worst, abs(gap))
    print(f"translating conjugate: |roller-to-surface distance - r| <= {worst:.2e} m")
    assert worst < 1e-10
    # Its drawing states its mounting: the file's zero-angle point turned by the stated angle touches the
    # return roller written out above (at theta = 0).
    path = tmp_path / "return.csv"
    cf.export.write_csv(path, back, ret["program"], points=360, unit="m", frame_angle=ret["frame_angle"])
    lines = path.read_text().splitlines()
    (note,) = [x for x in lines if x.startswith("# mounting:")]
    angle = math.radians(float(note.split("turned by ")[1].split(" deg")[0]))
    assert angle == pytest.approx(math.pi, abs=1e-12)
    first = np.array([float(v) for v in lines[[x.startswith("#") for x in lines].index(False) + 1].split(",")[1:3]])
    roller0 = np.array([0.005, s0 + PROGRAM.evaluate(0.0)["h"]]) - np.array([0.0, distance])
    (back_at_zero,) = [rotation(angle) @ first]
    assert np.linalg.norm(back_at_zero - roller0) == pytest.approx(0.012, abs=1e-12)


def test_the_bell_crank_return_arm_touches_its_cam_at_a_fixed_angle_to_the_lift_arm():
    program = swing_program()
    pivot = (0.090, 0.060)
    lift = cf.OscillatingRoller(0.040, 0.010, pivot, 0.080, "counter_clockwise")
    back = cf.OscillatingRoller(0.045, 0.010, pivot, 0.085, "clockwise")
    b = cf.MechanismBuilder()
    b.add_dof("arm", 1e-3)
    crank_angle = b.add_conjugate_cams("bell", program, lift, back, follower_dof="arm", stiffness=1e8)
    ret = b.contacts[1]
    assert ret["frame_angle"] == 0.0 and ret["follower_ratio"] == -1.0
    # The return arm's angle at rest, from its own cam: the roller centre (reference point) at theta = 0.
    p0 = back.profile(ret["program"], 0.0)
    c0 = np.array([p0["reference_x"], p0["reference_y"]]) - np.asarray(pivot)  # cam frame = ground at 0
    crank = math.atan2(c0[1], c0[0]) - lift.start_angle  # fixed on the bell crank
    assert crank_angle == pytest.approx(crank, abs=1e-12)  # what add_conjugate_cams tells the designer
    worst = 0.0
    for theta in np.radians(np.arange(0.0, 360.0, 7.5)):
        arm = lift.start_angle + program.evaluate(theta)["h"] + crank  # the lift arm's angle, then the crank's
        roller = np.asarray(pivot) + 0.085 * np.array([math.cos(arm), math.sin(arm)])
        gap = surface_distance(back, ret["program"], rotation(theta), roller, theta) - 0.010
        worst = max(worst, abs(gap))
    print(f"bell-crank conjugate: |roller-to-surface distance - r| <= {worst:.2e} m")
    assert worst < 1e-10


class TwoCams:
    """A follower of mass M between a lift cam and a return cam (translating rollers), written out here:
    delta_lift = cos(a) (h - q), delta_return = cos(b) (q - h - B) (B < 0: interference), tan a =
    (h' - e) / (s0 + h) (offset e, pitch height s0) and likewise for the return roller with h_r = H - h,
    forces K delta (1 + CHI delta') >= 0, M q'' = F_lift cos(a) - F_return cos(b)."""

    M, K, CHI, B, RPM = 0.5, 1e8, 0.05, -20e-6, 1000.0
    E, E_R = 0.005, -0.005

    def __init__(self):
        self.omega = self.RPM * math.pi / 30.0
        self.s0 = math.sqrt(0.050**2 - self.E**2)
        self.s0_r = math.sqrt(0.062**2 - self.E_R**2)
        self.H = PROGRAM.max_lift()

    def builder(self):
        b = cf.MechanismBuilder()
        b.add_dof("f", self.M)
        b.add_conjugate_cams(
            "cams",
            PROGRAM,
            cf.TranslatingRoller(0.040, 0.010, self.E),
            cf.TranslatingRoller(0.050, 0.012, self.E_R),
            follower_dof="f",
            stiffness=self.K,
            damping_factor=self.CHI,
            backlash=self.B,
        )
        b.camshaft_speed_rpm = self.RPM
        return b

    def deltas(self, t, q):
        """Both penetrations and the cosines of both pressure angles at time t, follower at q."""
        m = PROGRAM.evaluate(self.omega * t)
        ca = 1.0 / math.hypot(1.0, (m["dh"] - self.E) / (self.s0 + m["h"]))
        cb = 1.0 / math.hypot(1.0, (-m["dh"] - self.E_R) / (self.s0_r + self.H - m["h"]))
        return ca * (m["h"] - q), cb * (q - m["h"] - self.B), ca, cb

    def forces(self, t, q, v):
        d_lift, d_ret, ca, cb = self.deltas(t, q)
        # The penetrations' time rates by a central difference along the motion (q + v dt).
        dt = 1e-7
        lo, hi = self.deltas(t - dt, q - dt * v), self.deltas(t + dt, q + dt * v)
        r_lift, r_ret = (hi[0] - lo[0]) / (2 * dt), (hi[1] - lo[1]) / (2 * dt)
        f_lift = self.K * d_lift * max(1 + self.CHI * r_lift, 0.0) if d_lift > 0 else 0.0
        f_ret = self.K * d_ret * max(1 + self.CHI * r_ret, 0.0) if d_ret > 0 else 0.0
        return f_lift, f_ret, ca, cb

    def rhs(self, t, y):
        f_lift, f_ret, ca, cb = self.forces(t, *y)
        return [y[1], (f_lift * ca - f_ret * cb) / self.M]


@pytest.fixture(scope="module")
def two_cams_run():
    model = TwoCams()
    mech = model.builder().build()
    period = 60.0 / model.RPM
    y0 = [mech.initial_state[0], mech.initial_velocity[0]]
    ref = solve_ivp(
        model.rhs, (0, period), y0, method="Radau", rtol=1e-10, atol=[1e-14, 1e-10], max_step=2e-5, dense_output=True
    )
    assert ref.status == 0
    r = cf.simulate(mech, duration=period, method="dop853", tolerance=1e-10, time_step=5e-6)
    return model, mech, ref, r


def test_the_follower_between_two_cams_matches_the_equations_written_out(two_cams_run):
    model, mech, ref, r = two_cams_run
    q_ref = ref.sol(r.t)[0]
    err = np.abs(r.q[:, 0] - q_ref).max()
    forces = np.array([model.forces(t, *ref.sol(t))[:2] for t in r.t])
    f_err = np.abs(np.column_stack([r["cams.lift.force"], r["cams.return.force"]]) - forces).max()
    print(f"two cams vs solve_ivp: q {err:.2e} m, forces {f_err:.3g} N of {forces.max():.0f} N")
    assert err < 1e-11
    assert f_err < 1e-6 * forces.max()
    # Both contacts stay pressed by the interference (about K |B| / 2 each), never lost.
    assert r["cams.lift.in_contact"].all() and r["cams.return.in_contact"].all()
    assert 0.3 * model.K * abs(model.B) < np.median(r["cams.lift.force"]) < 0.7 * model.K * abs(model.B)


def test_the_rigid_check_puts_the_load_on_the_cam_the_acceleration_asks_for():
    model = TwoCams()
    report = force_closure(model.builder(), 600.0)
    assert report["warnings"] == []  # form-closed: never warned about
    lift, ret = report["contacts"]
    assert lift["conjugate"] == "cams.return" and ret["conjugate"] == "cams.lift"
    # The return cam carries where the follower decelerates (h'' < 0), the lift cam where h'' > 0 (at
    # rest in the dwells, h'' = 0, neither: both carry the preload only).
    grid = np.radians(np.arange(0.0, 360.0, 0.5))
    d2h = np.array([PROGRAM.evaluate(t)["d2h"] for t in grid])

    def inside(intervals, deg):
        return any(a <= deg <= b if a <= b else deg >= a or deg <= b for a, b in intervals)

    for deg, a in zip(np.degrees(grid), d2h):
        if abs(a) < 1e-3 * np.abs(d2h).max():
            continue
        assert inside(lift["other_cam_deg"], deg) == (a < 0), deg
        assert inside(ret["other_cam_deg"], deg) == (a > 0), deg
    signs = np.sign(d2h[np.abs(d2h) > 1e-3 * np.abs(d2h).max()])
    changes = int(np.sum(signs != np.roll(signs, -1)))  # around the revolution
    assert lift["flank_changes"] == ret["flank_changes"] == changes == 2  # cyclic: + - - +


def test_the_return_program_is_the_complement_of_the_lift_program():
    back = PROGRAM.complement(0.010)
    for theta in np.linspace(0.0, 2 * math.pi, 97):
        a, b = PROGRAM.evaluate(theta), back.evaluate(theta)
        assert a["h"] + b["h"] == pytest.approx(0.010, abs=1e-17)
        for k in ("dh", "d2h", "d3h"):
            assert b[k] == pytest.approx(-a[k], abs=1e-15)
    table = cf.MotionProgram.from_table(
        np.linspace(0, 2 * math.pi, 37)[:-1], 0.005 * (1 - np.cos(np.linspace(0, 2 * math.pi, 37)[:-1]))
    )
    with pytest.raises(ValueError, match="only built-in laws are mirrored"):
        table.complement(0.01)


def test_a_return_program_given_must_be_conjugate():
    b = cf.MechanismBuilder()
    b.add_dof("f", 0.5)
    args = (cf.TranslatingRoller(0.04, 0.01), cf.TranslatingRoller(0.05, 0.01))
    b.add_conjugate_cams(
        "ok", PROGRAM, *args, follower_dof="f", stiffness=1e9, return_program=PROGRAM.complement(0.012)
    )
    assert b.contacts[1]["follower_offset"] == pytest.approx(0.012)
    with pytest.raises(ValueError, match=r"conjugate cams 'bad': the return program is not conjugate"):
        b.add_conjugate_cams("bad", PROGRAM, *args, follower_dof="f", stiffness=1e9, return_program=PROGRAM)


@pytest.mark.parametrize(
    "change, message",
    [
        (dict(return_follower=cf.OscillatingRoller(0.04, 0.01, (0.09, 0.06), 0.08)), "both be translating or both"),
        (dict(backlash=0.02), "backlash must be finite and smaller than the stroke"),
        (dict(backlash=float("nan")), "backlash must be finite"),
    ],
)
def test_bad_translating_pairs_are_refused_by_name(change, message):
    b = cf.MechanismBuilder()
    b.add_dof("f", 0.5)
    kw = dict(follower_dof="f", stiffness=1e9)
    back = change.pop("return_follower", cf.TranslatingRoller(0.05, 0.01))
    with pytest.raises(ValueError, match=message):
        b.add_conjugate_cams("cams", PROGRAM, cf.TranslatingRoller(0.04, 0.01), back, **kw, **change)


def test_bad_bell_cranks_are_refused_by_name():
    b = cf.MechanismBuilder()
    b.add_dof("arm", 1e-3)
    lift = cf.OscillatingRoller(0.040, 0.010, (0.090, 0.060), 0.080)
    kw = dict(follower_dof="arm", stiffness=1e8)
    with pytest.raises(ValueError, match="opposite sense"):
        b.add_conjugate_cams("c", swing_program(), lift, cf.OscillatingRoller(0.045, 0.01, (0.09, 0.06), 0.085), **kw)
    with pytest.raises(ValueError, match="one pivot"):
        other = cf.OscillatingRoller(0.045, 0.01, (0.09, 0.07), 0.085, "clockwise")
        b.add_conjugate_cams("c", swing_program(), lift, other, **kw)


def test_a_pair_map_refuses_what_it_does_not_model():
    b = cf.MechanismBuilder()
    b.add_dof("f", 0.5)
    f = cf.TranslatingRoller(0.04, 0.01)
    with pytest.raises(ValueError, match="follower_ratio must be finite"):
        b.add_contact("c", PROGRAM, f, follower_dof="f", stiffness=1e9, follower_ratio=0.0)
        b.build()
    b = cf.MechanismBuilder()
    b.add_dof("f", 0.5)
    b.add_spring("s", "f", stiffness=1e4, preload=100.0)
    b.add_contact(
        "c", PROGRAM, f, follower_dof="f", stiffness=1e9, frame_angle=0.5, eccentricity=cf.CamEccentricity(1e-4)
    )
    with pytest.raises(ValueError, match=r"an eccentric cam .*frame_angle 0"):
        b.build()


def test_the_example_config_loads_pickles_and_runs_alike():
    case = load_config(Path(__file__).resolve().parents[2] / "examples" / "conjugate_cams.toml")
    names = [c["name"] for c in case.builder.contacts]
    assert names == ["cams.lift", "cams.return"]
    assert case.warnings == ()
    twin = pickle.loads(pickle.dumps(case.mechanism))
    a = cf.simulate(case.mechanism, revolutions=1, time_step=1e-5)
    b = cf.simulate(twin, revolutions=1, time_step=1e-5)
    np.testing.assert_array_equal(a["cams.return.force"], b["cams.return.force"])
    assert a["cams.return.force"].max() > 0 and a["cams.lift.force"].max() > 0


def test_the_example_script_draws_both_cams(tmp_path):
    """examples/conjugate_cams.py runs and draws; the interference keeps both cams loaded all round."""
    import runpy

    script = Path(__file__).resolve().parents[2] / "examples" / "conjugate_cams.py"
    summary = runpy.run_path(str(script))["main"](str(tmp_path / "conjugate.png"))
    assert (tmp_path / "conjugate.png").stat().st_size > 20_000
    assert summary["min_lift_force_N"] > 0.0 and summary["min_return_force_N"] > 0.0
