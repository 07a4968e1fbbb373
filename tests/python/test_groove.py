# SPDX-License-Identifier: BSD-3-Clause
"""A grooved cam (form closure: the roller between two flanks) against independent truth: the same
equations written out here in NumPy and integrated with scipy's solve_ivp, the rigid-flank impact
oscillator solved in closed form up to root finding (where the load leaves the inner flank, the free
flight across the clearance, the strike on the outer flank and its impact velocity), and the flank
that carries the load in the rigid check from the sign of the inertia load."""

import math
import pickle

import camfollower as cf
import numpy as np
import pytest
from camfollower.analysis import groove_statistics
from camfollower.config import config_from_dict, force_closure
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

DEG = math.pi / 180.0


class GroovedFollower:
    """A translating roller follower (mass M, zero offset) in a face groove of clearance C, no spring: a
    light load P (gravity-like) holds it on the inner flank at rest. Through the second half of the rise
    and the first of the return the cam decelerates the follower faster than P can: the load passes
    to the outer flank, and the roller crosses the groove and strikes it."""

    M, P = 0.3, 3.0  # kg, N (towards the cam)
    # Both flanks: N/m (exponent 1); Hunt-Crossley chi, s/m: restitution ~0.5 at the ~5 cm/s strikes.
    K, CHI = 1e8, 10.0
    C = 50e-6  # m
    RB, RR = 0.030, 0.008  # m
    LIFT, RISE_START, RISE = 0.006, 20 * DEG, 90 * DEG
    RETURN_START, RETURN = 200 * DEG, 160 * DEG
    RPM = 1000.0

    def __init__(self):
        self.omega = self.RPM * math.pi / 30.0
        self.period = 2 * math.pi / self.omega
        self.s0 = self.RB + self.RR

    def program(self):
        dwell, cyc = cf.MotionLaw.dwell(), cf.MotionLaw.cycloidal()
        a, b, L = self.RISE_START, self.RISE_START + self.RISE, self.LIFT
        return cf.MotionProgram(
            [
                cf.Segment(dwell, 0, a, 0, 0),
                cf.Segment(cyc, a, b, 0, L),
                cf.Segment(dwell, b, self.RETURN_START, L, L),
                cf.Segment(cyc, self.RETURN_START, 2 * math.pi, L, 0),
            ]
        )

    def builder(self, groove=None):
        m = cf.MechanismBuilder()
        m.add_dof("w", self.M, direction=(0, 1, 0))
        m.add_load("w", -self.P)
        m.add_contact(
            "cam",
            self.program(),
            cf.TranslatingRoller(self.RB, self.RR, 0.0),
            follower_dof="w",
            stiffness=self.K,
            damping_factor=self.CHI,
            groove=cf.Groove(self.C) if groove is None else groove,
        )
        m.camshaft_speed_rpm = self.RPM
        return m

    # --- the model written out again: cycloidal lift and its derivatives in theta ---
    def lift(self, theta):
        theta = np.mod(theta, 2 * math.pi)
        h, dh, ddh = np.zeros_like(theta), np.zeros_like(theta), np.zeros_like(theta)
        L = self.LIFT
        for start, span, sign, base in (
            (self.RISE_START, self.RISE, 1.0, 0.0),
            (self.RETURN_START, self.RETURN, -1.0, L),
        ):
            x = (theta - start) / span
            inside = (x >= 0) & (x <= 1)
            xs = np.clip(x, 0, 1)
            h = np.where(inside, base + sign * L * (xs - np.sin(2 * np.pi * xs) / (2 * np.pi)), h)
            dh = np.where(inside, sign * L / span * (1 - np.cos(2 * np.pi * xs)), dh)
            ddh = np.where(inside, sign * 2 * np.pi * L / span**2 * np.sin(2 * np.pi * xs), ddh)
        h = np.where((theta > self.RISE_START + self.RISE) & (theta < self.RETURN_START), L, h)
        return h, dh, ddh

    def geometry(self, t):
        """cos(alpha), its time rate, the lift and its time rate; alpha = atan(h' / (s0 + h))."""
        h, dh, ddh = self.lift(self.omega * np.asarray(t, dtype=float))
        R = self.s0 + h
        alpha = np.arctan2(dh, R)
        dalpha = (ddh * R - dh**2) / (R**2 + dh**2)  # per rad
        return np.cos(alpha), -np.sin(alpha) * dalpha * self.omega, h, dh * self.omega

    def flanks(self, t, w, v):
        c, c_dot, h, h_dot = self.geometry(t)
        delta = c * (h - w)
        delta_dot = c_dot * (h - w) + c * (h_dot - v)
        inner = np.where(delta > 0, self.K * delta * np.maximum(1 + self.CHI * delta_dot, 0.0), 0.0)
        d_out = -delta - self.C
        outer = np.where(d_out > 0, self.K * d_out * np.maximum(1 - self.CHI * delta_dot, 0.0), 0.0)
        return inner, outer, c, delta, delta_dot

    def rhs(self, t, y):
        w, v = y
        inner, outer, c, _, _ = self.flanks(t, w, v)
        return [v, (c * (inner - outer) - self.P) / self.M]


@pytest.fixture(scope="module")
def groove_run():
    g = GroovedFollower()
    mech = g.builder().build()
    y0 = [mech.initial_state[0], mech.initial_velocity[0]]
    ref = solve_ivp(
        g.rhs, (0, g.period), y0, method="Radau", rtol=1e-11, atol=[1e-15, 1e-11], max_step=2e-6, dense_output=True
    )
    assert ref.status == 0
    r = cf.simulate(mech, duration=g.period, method="dop853", tolerance=1e-10, time_step=2e-6)
    return g, mech, ref, r


def test_grooved_follower_matches_the_independent_equations(groove_run):
    g, mech, ref, r = groove_run
    assert {e.name for e in r.events} == {"cam.contact", "cam.outer_contact"}
    # At rest on the dwell the inner flank carries the load: delta = P / K.
    assert mech.initial_state[0] == pytest.approx(-g.P / g.K, rel=1e-9)
    w_ref = ref.sol(r.t)[0]
    inner, outer, _, delta, delta_dot = g.flanks(r.t, *ref.sol(r.t))
    err = np.abs(r.q[:, 0] - w_ref).max()
    print(f"groove vs solve_ivp: w {err:.2e} m over a {g.C:.0e} m clearance; outer peak {outer.max():.1f} N")
    assert err < 2e-9
    np.testing.assert_allclose(r["cam.outer_penetration"], -delta - g.C, rtol=0, atol=4e-9)
    np.testing.assert_allclose(r["cam.penetration_rate"], delta_dot, rtol=0, atol=2e-4 * np.abs(delta_dot).max())
    force_tol = g.K * 4e-9 * (1 + g.CHI * np.abs(delta_dot).max())
    np.testing.assert_allclose(r["cam.force"], inner, rtol=0, atol=force_tol)
    np.testing.assert_allclose(r["cam.outer_force"], outer, rtol=0, atol=force_tol)
    # Not trivial: the roller crosses the groove and the outer flank carries tens of N.
    assert outer.max() > 20.0 and r["cam.outer_in_contact"].any() and not r["cam.in_contact"].all()

    # The strikes: where the reference's flank penetrations rise through zero, with its impact
    # velocity there. A strike's time is resolved to the displacement error over the closing speed; a
    # strike slower than 2 mm/s (a graze at the end of a bounce sequence) may fall between the two
    # methods' resolutions, so both lists are compared above that speed.
    fine = np.linspace(0, g.period, 600001)
    _, _, _, d_in, _ = g.flanks(fine, *ref.sol(fine))
    ref_strikes = []
    for flank, depth in (("inner", d_in), ("outer", -d_in - g.C)):
        on = depth > 0
        for k in np.nonzero(~on[:-1] & on[1:])[0]:
            t = brentq(lambda x: _depth(g, ref, x, flank)[0], fine[k], fine[k + 1], xtol=1e-14)
            ref_strikes.append((t, flank, _depth(g, ref, t, flank)[1]))
    stats = groove_statistics(r, "cam", g.period)
    assert len(stats["strikes"]) >= 4 and len(ref_strikes) >= 4
    slowest = 2e-3  # m/s

    def matched(strike, others):
        t, flank, v = strike
        tol_t = 4e-9 / abs(v) + 1e-9
        return any(f == flank and abs(u - t) < tol_t and abs(w - v) < 5e-3 * abs(v) + 2e-5 for u, f, w in others)

    for strike in ref_strikes:
        assert strike[2] < slowest or matched(strike, stats["strikes"]), strike
    for strike in stats["strikes"]:
        assert strike[2] < slowest or matched(strike, ref_strikes), strike
    print("strikes (ms, flank, m/s):", [(round(t * 1e3, 4), f, round(v, 4)) for t, f, v in stats["strikes"]])


def _depth(g, ref, t, flank):
    """The reference's penetration of `flank` at t and its rate (the closing speed)."""
    w, v = ref.sol(t)
    _, _, _, delta, rate = g.flanks(np.array([t]), np.array([w]), np.array([v]))
    return (float(delta[0]), float(rate[0])) if flank == "inner" else (float(-delta[0] - g.C), float(-rate[0]))


def test_first_flank_change_against_the_rigid_flank_closed_form(groove_run):
    """Rigid flanks: the inner flank carries the follower while the cam's push M h'' w^2 + P is > 0.
    Where it falls to zero (past mid-rise) the follower leaves it and flies under -P alone, at the
    lift's rate there; the groove decelerates faster and its outer flank, at h + C / cos(alpha) in
    the follower's coordinate, meets it. Stiff flanks (deflections ~P/K = 3e-8 m against C = 5e-5 m)
    approach this to a small fraction of the flight."""
    g, mech, ref, r = groove_run
    push = lambda th: g.M * g.lift(np.array([th]))[2][0] * g.omega**2 + g.P  # noqa: E731
    mid = g.RISE_START + g.RISE / 2
    theta1 = brentq(push, mid, g.RISE_START + 0.75 * g.RISE)  # the push is least at three quarters
    t1 = theta1 / g.omega
    h1, dh1, _ = (x[0] for x in g.lift(np.array([theta1])))
    v1 = dh1 * g.omega

    def gap(t):  # outer flank position minus the flying follower's, in w
        c, _, h, _ = (x[0] for x in g.geometry(np.array([t])))
        w = h1 + v1 * (t - t1) - 0.5 * g.P / g.M * (t - t1) ** 2
        return h + g.C / c - w

    t2 = brentq(gap, t1 + 1e-7, t1 + 0.1 * g.period, xtol=1e-14)
    c2, c2_dot, h2, h2_dot = (x[0] for x in g.geometry(np.array([t2])))
    flank_speed = h2_dot - g.C * c2_dot / c2**2  # d/dt (h + C / cos alpha)
    impact = (v1 - g.P / g.M * (t2 - t1)) - flank_speed  # the follower closing on the outer flank
    stats = groove_statistics(r, "cam", g.period)
    first = next(s for s in stats["strikes"] if s[1] == "outer")
    flight = t2 - t1
    print(
        f"rigid flanks: leaves at {theta1 / DEG:.3f} deg, strikes at {t2 * g.omega / DEG:.3f} deg at {impact:.4f} m/s; "
        f"model: {first[0] * g.omega / DEG:.3f} deg at {first[2]:.4f} m/s"
    )
    assert first[0] == pytest.approx(t2, abs=0.01 * flight)
    assert first[2] == pytest.approx(impact, rel=0.02)
    assert impact > 0.01  # a real impact, not a graze


def test_flank_changes_and_the_rigid_check(groove_run):
    g, mech, _, r = groove_run
    # The rigid check: the outer flank carries the roller where M h'' w^2 + P < 0 (zero offset: the
    # normal force is that over cos alpha, the same sign).
    theta = np.linspace(0, 2 * math.pi, 3601)[:-1]
    outer = g.M * g.lift(theta)[2] * g.omega**2 + g.P < 0
    changes = int(np.count_nonzero(outer != np.roll(outer, 1)))
    assert changes == 4  # off and back on the outer flank in the rise and in the return
    closure = force_closure(g.builder())
    (c,) = closure["contacts"]
    assert closure["warnings"] == []  # form-closed: never "not force-closed"
    assert c["grooved"] and c["flank_changes"] == changes
    edges = np.array(c["outer_flank_deg"]).ravel()
    ref_edges = np.sort(theta[outer != np.roll(outer, 1)] / DEG)
    assert np.abs(np.sort(edges) - ref_edges).max() < 1.0  # the check's grid is coarser than this one
    # The run: each half-revolution where the outer flank carries is reached by a strike on it, and
    # left by one on the inner flank (bounces add strikes on the same flank, not changes).
    stats = groove_statistics(r, "cam", g.period)
    assert stats["flank_changes_per_revolution"] == pytest.approx(changes)
    assert stats["impacts_per_revolution"] >= changes
    assert stats["free_flight_time_per_revolution_s"] > 0
    assert stats["peak_outer_force_N"] == pytest.approx(np.max(r["cam.outer_force"]))


def test_the_groove_through_config_pickle_and_bad_input():
    g = GroovedFollower()
    doc = {
        "camshaft": {"speed": "1000 rpm"},
        "dof": [{"name": "w", "mass": "0.3 kg", "direction": [0, 1, 0]}],
        "load": [{"dof": "w", "force": "-3 N"}],
        "program": {
            "feed": {
                "segments": [
                    {"law": "dwell", "end": "20 deg"},
                    {"law": "cycloidal", "end": "110 deg", "h": "6 mm"},
                    {"law": "dwell", "end": "200 deg", "h": "6 mm"},
                    {"law": "cycloidal", "end": "360 deg", "h": 0},
                ]
            }
        },
        "contact": [
            {
                "name": "cam",
                "program": "feed",
                "follower_dof": "w",
                "stiffness": 1e8,
                "damping_factor": "0.3 s/m",
                "follower": {"type": "translating_roller", "base_radius": "30 mm", "roller_radius": "8 mm"},
                "groove": {"clearance": "0.05 mm"},
            }
        ],
    }
    cfg = config_from_dict(doc)
    (spec,) = cfg.builder.contacts
    assert spec["groove"].clearance == pytest.approx(g.C)
    assert spec["groove"].stiffness is None  # the contact's law on both flanks
    a = cfg.builder.build()
    b = g.builder().build()
    np.testing.assert_allclose(a.initial_state, b.initial_state, rtol=1e-12)
    assert pickle.loads(pickle.dumps(g.builder())).contacts[0]["groove"].clearance == g.C
    own = cf.Groove(g.C, stiffness=3e8, exponent=1.0, damping_factor=0.1)
    assert pickle.loads(pickle.dumps(own)).stiffness == 3e8
    short = cf.simulate(g.builder(own).build(), duration=1e-4, time_step=1e-5)
    assert short.channels[-4:] == [
        "cam.penetration_rate",
        "cam.outer_force",
        "cam.outer_penetration",
        "cam.outer_in_contact",
    ]

    with pytest.raises(
        ValueError, match=r"groove clearance 0.05 m must be below the roller radius 0.008 m.*did you mean mm"
    ):
        g.builder(cf.Groove(0.05)).build()
    for bad in (0.0, -1e-5, math.nan, math.inf):
        with pytest.raises(ValueError, match="Groove: groove clearance must be finite and > 0"):
            cf.Groove(bad)
    with pytest.raises(ValueError, match="give its stiffness too"):
        cf.Groove(1e-5, exponent=1.5)
    m = cf.MechanismBuilder()
    m.add_dof("w", 0.3)
    m.add_load("w", -3.0)
    with pytest.raises(ValueError, match="a groove holds a roller; translating_flat has none"):
        m.add_contact(
            "cam", g.program(), cf.TranslatingFlat(0.03), follower_dof="w", stiffness=1e8, groove=cf.Groove(5e-5)
        )
        m.build()
    doc["contact"][0]["groove"] = {"clearance": "0.05 mm", "stifness": "1e8 N/m"}
    with pytest.raises(ValueError, match="stifness"):
        config_from_dict(doc)


def test_the_grooved_follower_has_a_periodic_orbit_and_a_long_transient_shows_what_it_does():
    """Shooting on the grooved follower (strikes and bounces every revolution) finds a periodic orbit:
    one revolution from it returns to it. Impact oscillators bifurcate: here the transient settles on
    an orbit of two revolutions instead (the shooting's orbit is unstable, its spectral radius > 1 with
    Fox-Goodwin) - the periodic steady state is what the transient shows, so both are checked."""
    g = GroovedFollower()
    mech = g.builder().build()
    dt = g.period / 30000
    orbit = cf.periodic_steady_state(mech, time_step=dt, method="fox_goodwin", tolerance=1e-6)
    assert orbit.converged
    again = orbit.record(mech, revolutions=1)
    assert abs(again.q[-1, 0] - orbit.q[0]) <= 1e-6 * orbit.q_scale
    assert abs(again.v[-1, 0] - orbit.v[0]) <= 1e-6 * orbit.v_scale
    assert groove_statistics(again, "cam", g.period)["flank_changes_per_revolution"] == pytest.approx(4.0)
    # The transient: states at whole revolutions, after 20 of them, repeat every second revolution.
    r = cf.simulate(mech, revolutions=26, time_step=dt, method="fox_goodwin")
    at = [int(np.argmin(np.abs(r.t - k * g.period))) for k in range(20, 27)]
    w, v = r.q[at, 0], r.v[at, 0]
    print(
        f"orbit ({orbit.q[0]:.5e} m, {orbit.v[0]:.5e} m/s), spectral radius {orbit.spectral_radius:.3g}; "
        f"transient at revolutions 20-26: w {w} m, v {v} m/s"
    )
    assert np.abs(w[2:] - w[:-2]).max() < 1e-6 * orbit.q_scale
    assert np.abs(v[2:] - v[:-2]).max() < 1e-6 * orbit.v_scale


def test_the_example_grooved_cam_reports_where_the_outer_flank_carries(capsys):
    """examples/grooved_cam.toml: carrier and slide (1.4 kg on a stiff rod) under gravity. Rigidly,
    the outer flank carries them where the cam decelerates them faster than gravity, h'' w^2 < -g."""
    from pathlib import Path

    from camfollower import cli

    example = Path(__file__).resolve().parents[2] / "examples" / "grooved_cam.toml"
    (row,) = cli.kinematics(str(example))
    out = capsys.readouterr().out
    assert "groove clearance 0.04 mm: outer flank carries the roller (rigid) over" in out
    program = cf.load_config(example).builder.contacts[0]["program"]
    omega = 600 * math.pi / 30
    theta = np.linspace(0, 2 * math.pi, 7201)[:-1]
    outer = np.asarray(program.evaluate(theta)["d2h"]) * omega**2 < -9.81
    edges = np.sort(theta[outer != np.roll(outer, 1)] / DEG)
    assert row["flank_changes"] == len(edges) == 4
    assert np.abs(np.sort(np.ravel(row["outer_flank_deg"])) - edges).max() < 1.0
    assert row["groove_clearance"] == pytest.approx(40e-6)


def test_the_example_script_draws_the_flanks(tmp_path):
    """examples/grooved_cam.py runs and draws; its strikes agree with its located events."""
    import runpy
    from pathlib import Path

    script = Path(__file__).resolve().parents[2] / "examples" / "grooved_cam.py"
    stats = runpy.run_path(str(script))["main"](str(tmp_path / "grooved.png"))
    assert (tmp_path / "grooved.png").stat().st_size > 20_000
    assert stats["flank_changes_per_revolution"] >= 4 and stats["max_impact_velocity_m_s"] > 0.0
    assert all(flank in ("inner", "outer") and v > -1e-3 for _, flank, v in stats["strikes"])  # closing (a graze ~0)


def test_speed_studies_refuse_a_grooved_contact_with_a_reason():
    """A grooved follower cannot jump: the speed scans say so instead of reporting the inner flank's
    expected load reversals as contact loss."""
    from camfollower import speed

    mech = GroovedFollower().builder().build()
    for study in (speed.jump_speed, speed.margin_scan):
        with pytest.raises(ValueError, match=r"contact 'cam' is grooved \(form-closed\): it has no contact margin"):
            study(mech, (500, 1500))
