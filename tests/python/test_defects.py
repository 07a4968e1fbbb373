# SPDX-License-Identifier: BSD-3-Clause
"""The defects (guide clearance with walls and friction, eccentric cam, settling, the paper's literal
eccentricity force) against independent second methods: the same equations written here in NumPy and
integrated with scipy's solve_ivp, closed-form geometry of a displaced circle, root finding on that
exact geometry, and re-computations of the reported quantities from the raw histories.

Newmark's average-acceleration rule is second order for a smooth response; where a force has a kink
(a wall or a contact closing) its per-step velocity error is bounded by J dt^2 / 8 instead (J: jump of
d(acceleration)/dt), which the tolerances below add up explicitly."""

import math
import pickle
import warnings

import camfollower as cf
import numpy as np
import pytest
from camfollower.analysis import clearance_statistics
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

DEG = math.pi / 180.0


# --- 1. a rod in a guide with clearance: walls (Hertz, damped), Coulomb friction on the sliding DOF ---


class Rod:
    """Lateral DOF x (rod in its guide, radial clearance C) and axial DOF w (the rod's sliding
    coordinate, a follower on a cam, held down by a preloaded spring). The cam's contact force has a
    lateral component F sin(alpha): on the dwell (offset e > 0, alpha < 0) it seats the rod on the +C
    wall; in the middle of the rise (R' > e, alpha > 0) it throws the rod across to the -C wall, and
    back. Friction mu N tanh(w' / v_slip) acts on w while the rod touches a wall."""

    MX, MW = 0.2, 0.3  # kg
    KS, P = 1e3, 1200.0  # axial spring N/m, preload N (keeps the cam contact closed)
    KC = 1e8  # cam contact, N/m, exponent 1, undamped
    KW, CHI, MU, VS, C = 2.5e8, 0.5, 0.2, 1e-3, 50e-6  # wall N/m, s/m, -, m/s; clearance m
    RB, RR, E = 0.030, 0.008, 0.005  # m
    LIFT, RISE_START, RISE = 0.006, 20 * DEG, 90 * DEG
    RPM, PHASE = 3000.0, 15 * DEG  # t = 0 is 5 deg before the rise
    T = 4e-3  # s: two impacts, one on each wall

    def __init__(self):
        self.omega = self.RPM * 2 * math.pi / 60
        self.s0 = math.sqrt((self.RB + self.RR) ** 2 - self.E**2)

    def builder(self, friction=None):
        friction = self.MU if friction is None else friction
        dwell, cyc = cf.MotionLaw.dwell(), cf.MotionLaw.cycloidal()
        a, b, L = self.RISE_START, self.RISE_START + self.RISE, self.LIFT
        program = cf.MotionProgram(
            [
                cf.Segment(dwell, 0, a, 0, 0),
                cf.Segment(cyc, a, b, 0, L),
                cf.Segment(dwell, b, 200 * DEG, L, L),
                cf.Segment(cyc, 200 * DEG, 2 * math.pi, L, 0),
            ]
        )
        m = cf.MechanismBuilder()
        m.add_dof("x", self.MX, direction=(1, 0, 0))
        m.add_dof("w", self.MW, direction=(0, 1, 0))
        m.add_spring("axial", "w", "ground", stiffness=self.KS, preload=self.P)
        m.add_contact(
            "cam",
            program,
            cf.TranslatingRoller(self.RB, self.RR, self.E),
            follower_dof="w",
            lateral="x",
            stiffness=self.KC,
            phase=self.PHASE,
        )
        m.add_clearance(
            "guide",
            [("x", 1.0)],
            clearance=self.C,
            stiffness=self.KW,
            exponent=1,
            damping_factor=self.CHI,
            friction=friction,
            sliding_dof="w" if friction else "",
            slip_velocity=self.VS,
        )
        m.camshaft_speed_rpm = self.RPM
        return m

    # The model written out again (vectorized over t): cycloidal lift, roller pressure angle
    # alpha = atan((R' - e) / R), linearized contact delta = sin(alpha) x + cos(alpha) (h - w).
    def lift(self, t):
        x = np.clip((self.omega * np.asarray(t) + self.PHASE - self.RISE_START) / self.RISE, 0.0, 1.0)
        h = self.LIFT * (x - np.sin(2 * np.pi * x) / (2 * np.pi))
        dh = self.LIFT / self.RISE * (1 - np.cos(2 * np.pi * x))
        return h, dh

    def forces(self, t, x, w, vx, vw):
        h, dh = self.lift(t)
        alpha = np.arctan2(dh - self.E, self.s0 + h)
        cam = self.KC * np.maximum(np.sin(alpha) * x + np.cos(alpha) * (h - w), 0.0)
        side = np.sign(x)
        depth = np.abs(x) - self.C
        wall = np.where(depth > 0, self.KW * depth * np.maximum(1 + self.CHI * side * vx, 0.0), 0.0)
        friction = -self.MU * wall * np.tanh(vw / self.VS)
        return cam, alpha, wall, side, friction

    def rhs(self, t, y):
        x, w, vx, vw = y
        cam, alpha, wall, side, friction = self.forces(t, x, w, vx, vw)
        return [
            vx,
            vw,
            (-cam * np.sin(alpha) - side * wall) / self.MX,
            (cam * np.cos(alpha) - self.P - self.KS * w + friction) / self.MW,
        ]


@pytest.fixture(scope="module")
def rod_run():
    rod = Rod()
    mech = rod.builder().build()
    y0 = np.concatenate([mech.initial_state, mech.initial_velocity])
    # Radau at rtol 1e-10; max_step 2 us << the ~90 us wall contacts, so none is stepped over (a DOP853
    # run at rtol 1e-12 agrees with it to ~1e-12 m).
    ref = solve_ivp(
        rod.rhs,
        (0, rod.T),
        y0,
        method="Radau",
        rtol=1e-10,
        atol=[1e-15, 1e-15, 1e-11, 1e-11],
        max_step=2e-6,
        dense_output=True,
    )
    assert ref.status == 0
    dt = 2e-7
    return rod, mech, ref, cf.simulate(mech, duration=rod.T, time_step=dt)


def test_rod_starts_in_the_static_equilibrium_of_the_independent_equations(rod_run):
    rod, mech, ref, _ = rod_run
    assert mech.clearance_names == ["guide"]
    np.testing.assert_array_equal(mech.initial_velocity, [0.0, 0.0])  # on the dwell
    x0 = mech.initial_state[0]
    assert rod.C < x0 < rod.C + 2e-6  # seated on the +C wall by the dwell's lateral force
    accelerations = rod.rhs(0.0, [*mech.initial_state, 0.0, 0.0])[2:]
    # Every force is at least ~1e2 N on ~0.2 kg: 1e-7 m/s^2 is ~1e-10 of the force scale.
    assert np.abs(accelerations).max() < 1e-7, accelerations


def test_rod_in_a_guide_with_friction_matches_solve_ivp(rod_run):
    rod, mech, ref, r = rod_run
    dt = r.time_step
    y = ref.sol(r.t)
    cam, _, wall, _, friction = rod.forces(r.t, *y)
    # The reference's wall events, with the penetration rate there: lift-off from the +C seat, then
    # an impact on the -C wall and one on the +C wall (onset and separation each).
    fine = np.linspace(0, rod.T, 400001)
    yf = ref.sol(fine)
    touching = np.abs(yf[0]) > rod.C
    kinks = np.nonzero(touching[1:] != touching[:-1])[0]
    assert touching[0] and len(kinks) == 5
    assert np.sign(yf[0][kinks[1] + 1]) == -1 and np.sign(yf[0][kinks[3] + 1]) == 1
    # Per kink the trapezoidal velocity error is at most J dt^2 / 8, J = k |u'| (1 + chi |u'|) / m;
    # it then carries on as a displacement error growing over the rest of the run. Factor 2: the
    # impacts' own dynamics reshape these errors (measured: 2.6e-9 m against a bound of 1.0e-8 m).
    rate = np.abs(yf[2][kinks])
    dv = rod.KW * rate * (1 + rod.CHI * rate) / rod.MX * dt**2 / 8
    tol_v = 2 * dv.sum()
    tol_x = 2 * float(np.sum(dv * (rod.T - fine[kinks]))) + 1e-10  # + the smooth part (~1e-11 at 2e-7 s)
    err_x = np.abs(r.q[:, 0] - y[0]).max()
    err_w = np.abs(r.q[:, 1] - y[1]).max()
    # Wall force: k (1 + chi u') on the displacement error, k delta chi on the rate error.
    peak_rate, peak_depth = np.abs(yf[2]).max(), (np.abs(yf[0]) - rod.C).max()
    tol_wall = rod.KW * (1 + rod.CHI * peak_rate) * tol_x + rod.KW * peak_depth * rod.CHI * tol_v
    err_wall = np.abs(r["guide.force"] - wall).max()
    # Friction mu N on w: mu m_x / m_w ~ 0.13 of the impulse error on x reaches w, and the cam couples
    # them through sin(alpha) ~ 0.1: tol_x covers w.
    print(
        f"rod vs solve_ivp at dt = {dt:.0e} s: x {err_x:.2e} m (tol {tol_x:.2e}), w {err_w:.2e} m, "
        f"wall force {err_wall:.3f} N of {wall.max():.0f} N peak (tol {tol_wall:.2f})"
    )
    assert err_x <= tol_x
    assert err_w <= tol_x
    assert err_wall <= tol_wall
    np.testing.assert_array_equal(r["guide.side"], np.where(np.abs(r.q[:, 0]) > rod.C, np.sign(r.q[:, 0]), 0))
    np.testing.assert_allclose(r["guide.gap"], r.q[:, 0], rtol=0, atol=0)
    np.testing.assert_allclose(r["guide.friction"], friction, rtol=0, atol=rod.MU * tol_wall + 1e-9)
    np.testing.assert_allclose(r["cam.force"], cam, rtol=0, atol=rod.KC * 2 * tol_x)
    assert r["cam.in_contact"].all()
    # The motion is not trivial: across the whole gap, wall forces of kN, sliding at m/s.
    assert np.ptp(y[0]) > 2 * rod.C and wall.max() > 1e3 and np.abs(y[3]).max() > 1.0

    # The clearance statistics from the recorded rows against the reference's events.
    stats = clearance_statistics(r, "guide", rod.T + dt)  # one "revolution": the whole run
    free_time = np.count_nonzero(~(np.abs(y[0]) > rod.C)) * dt
    assert stats["impacts_per_revolution"] == pytest.approx(2.0)
    assert stats["wall_changes_per_revolution"] == pytest.approx(2.0)
    assert stats["free_flight_time_per_revolution_s"] == pytest.approx(free_time, abs=4 * dt)
    assert stats["peak_seat_force_N"] == pytest.approx(wall.max(), abs=tol_wall)


def test_the_rod_comparison_can_fail(rod_run):
    # The same mechanism without the guide's friction (a model error of mu N on w) misses by far.
    rod, _, ref, _ = rod_run
    r = cf.simulate(rod.builder(friction=0.0).build(), duration=rod.T, time_step=4e-7)
    assert np.abs(r.q[:, 1] - ref.sol(r.t)[1]).max() > 1e-6


# --- 2. eccentric circular cam against the exact geometry of a displaced circle ---


class EccentricCircle:
    """A base circle (one 360 deg dwell) whose centre sits at u = eps (cos(theta + zeta),
    sin(theta + zeta)); translating roller with offset e; one follower DOF y (the roller centre at
    (e, s0 + y), s0 = sqrt(Rp^2 - e^2), Rp = r_b + r_r) on a preloaded return spring. Exact contact:
    delta = Rp - |(e, s0 + y) - u| (distance-based, no linearization), force along the actual normal.
    camfollower linearizes delta in y about the exact kinematic configuration: the two differ by
    O(delta^2 tan(alpha)^2 / Rp) ~ 1e-10 m here."""

    M, KS, P = 0.5, 2e4, 300.0
    RB, RR, E = 0.040, 0.0125, 0.010
    KC, EXPONENT, CHI = 1e10, 1.5, 0.05  # N/m^1.5 (delta ~ 10 um), s/m
    EPS, ZETA = 0.2e-3, 0.4
    RPM = 3000.0  # run-out at 50 Hz; inertia M eps omega^2 ~ 10 N

    def __init__(self):
        self.omega = self.RPM * 2 * math.pi / 60
        self.rp = self.RB + self.RR
        self.s0 = math.sqrt(self.rp**2 - self.E**2)

    def build(self, zeta=None):
        zeta = self.ZETA if zeta is None else zeta
        b = cf.MechanismBuilder()
        b.add_dof("y", self.M, direction=(0, 1, 0))
        b.add_spring("spring", "y", "ground", stiffness=self.KS, preload=self.P)
        program = cf.MotionProgram([cf.Segment(cf.MotionLaw.dwell(), 0.0, 2 * math.pi, 0.0, 0.0)])
        b.add_contact(
            "cam",
            program,
            cf.TranslatingRoller(self.RB, self.RR, self.E),
            follower_dof="y",
            stiffness=self.KC,
            exponent=self.EXPONENT,
            damping_factor=self.CHI,
            eccentricity=cf.CamEccentricity(self.EPS, zeta),
        )
        b.camshaft_speed_rpm = self.RPM
        return b.build()

    def centre(self, t):
        a = self.omega * np.asarray(t) + self.ZETA
        return (
            self.EPS * np.cos(a),
            self.EPS * np.sin(a),
            -self.EPS * self.omega * np.sin(a),
            self.EPS * self.omega * np.cos(a),
        )

    def contact(self, t, y, v, moving=True):
        """Force magnitude, normal's y component and penetration (vectorized)."""
        ux, uy, dux, duy = self.centre(t)
        dx, dy = self.E - ux, self.s0 + y - uy
        dist = np.hypot(dx, dy)
        delta = self.rp - dist
        rate = -(dx * -dux + dy * (v - duy)) / dist if moving else 0.0
        force = np.where(
            delta > 0, self.KC * np.maximum(delta, 0) ** self.EXPONENT * np.maximum(1 + self.CHI * rate, 0.0), 0.0
        )
        return force, dy / dist, delta

    def rhs(self, t, s):
        y, v = s
        force, ny, _ = self.contact(t, y, v)
        return [v, (force * ny - self.P - self.KS * y) / self.M]

    def kinematic_lift(self, theta):
        """Roller-centre height above s0 touching the displaced pitch circle, and d/dtheta."""
        ux, uy = self.EPS * math.cos(theta + self.ZETA), self.EPS * math.sin(theta + self.ZETA)
        dux, duy = -uy, ux
        root = math.sqrt(self.rp**2 - (self.E - ux) ** 2)
        return uy + root - self.s0, duy + (self.E - ux) * dux / root

    def static(self, theta):
        """Exact static equilibrium (at rest, no contact damping) by root finding."""
        t = theta / self.omega
        top = self.kinematic_lift(theta)[0]

        def residual(y):
            force, ny, _ = self.contact(t, y, 0.0, moving=False)
            return float(force * ny - self.P - self.KS * y)

        return brentq(residual, top - 1e-3, top, xtol=1e-18, rtol=1e-15)


@pytest.fixture(scope="module")
def eccentric():
    cam = EccentricCircle()
    return cam, cam.build()


def test_eccentric_start_is_the_quasi_static_state_of_the_exact_geometry(eccentric):
    cam, mech = eccentric
    q0, v0 = mech.initial_state[0], mech.initial_velocity[0]
    # Kinematics of the displaced circle: the roller follows y_kin(theta) less the contact deflection,
    # which changes with the spring force (k_s / k_contact ~ 4e-4): 1e-3 relative.
    kinematic_rate = cam.omega * cam.kinematic_lift(0.0)[1]
    assert v0 == pytest.approx(kinematic_rate, rel=1e-3)
    assert abs(v0 / kinematic_rate - 1) > 1e-5  # the compliance is there: not the rigid kinematics
    # The exact static equilibrium: position, and its rate by central differences in theta.
    exact = cam.static(0.0)
    # The linearization's offset, to leading order: with z = y_kin - y, the exact penetration is
    # c z - s^2 z^2 / (2 Rp) and the exact normal's y component c - s^2 z / Rp (c, s: cos, sin of the
    # pressure angle), so the linearized force is high by (1 + n / 2) s^2 z / (c Rp) relative, and
    # the linearized equilibrium sits higher by that / n of z: (1 + n / 2) / n z^2 s^2 / (c Rp).
    z = cam.kinematic_lift(0.0)[0] - exact  # ~1e-5 m
    s = (cam.E - cam.EPS * math.cos(cam.ZETA)) / cam.rp
    c = math.sqrt(1 - s * s)
    n = cam.EXPONENT
    offset = (1 + n / 2) / n * z * z * s * s / (c * cam.rp)  # ~8e-11 m
    h = 1e-4
    exact_rate = cam.omega * (cam.static(h) - cam.static(-h)) / (2 * h)
    print(
        f"eccentric start: q0 - exact {q0 - exact:.3e} m (predicted linearization offset {offset:.3e}); "
        f"v0 {v0:.9f}, exact static rate {exact_rate:.9f}, kinematic {kinematic_rate:.9f} m/s"
    )
    assert q0 - exact == pytest.approx(offset, rel=5e-3)  # next order: z / Rp ~ 2e-4, k_s / k_contact ~ 4e-4
    assert v0 == pytest.approx(exact_rate, rel=1e-5)  # the linearization: O(delta tan^2 / Rp) ~ 7e-6


def test_eccentric_circular_cam_matches_solve_ivp_on_the_exact_geometry(eccentric):
    cam, mech = eccentric
    T = 2 * mech.period
    y0 = [mech.initial_state[0], mech.initial_velocity[0]]
    ref = solve_ivp(cam.rhs, (0, T), y0, method="LSODA", rtol=1e-11, atol=[1e-16, 1e-12], dense_output=True)
    assert ref.status == 0
    r = cf.simulate(mech, duration=T, time_step=1e-6)
    y = ref.sol(r.t)
    force, _, _ = cam.contact(r.t, y[0], y[1])
    err_y = np.abs(r.q[:, 0] - y[0]).max()
    err_f = np.abs(r["cam.force"] - force).max()
    print(
        f"eccentric cam vs solve_ivp, 2 revolutions at dt = 1e-6 s: y {err_y:.2e} m of {np.ptp(y[0]):.2e} m "
        f"run-out, force {err_f:.4f} N of {force.min():.1f}..{force.max():.1f} N"
    )
    # Tolerance: the start is quasi-static in velocity, not in acceleration, so a free vibration of
    # about M eps omega^2 / k_contact ~ 2e-7 m rings at f_c ~ 1.5 kHz (little damped); Newmark's
    # period error (omega_c dt)^2 / 12 ~ 8e-6 accumulates over 60 cycles to ~3e-3 rad of phase:
    # ~6e-10 m, x k_contact ~ 0.03 N. The linearization adds O(delta^2 tan^2 / Rp) ~ 1e-10 m.
    assert err_y <= 1e-9
    assert err_f <= 0.05
    assert np.ptp(y[0]) > 1.9 * cam.EPS and np.ptp(force) > 10.0  # run-out followed, dynamics matter
    assert r["cam.in_contact"].all()


def test_eccentric_cam_converges_at_second_order_to_its_linearized_equations(eccentric):
    # The remaining difference above is the linearization: written out here (delta = n_y (y_kin - y),
    # force n_y F, n the exact normal of the kinematic configuration), the error falls by 4 per halving.
    cam, mech = eccentric
    T = 2 * mech.period

    def kinematics(t):
        th = cam.omega * t
        ux, uy = cam.EPS * math.cos(th + cam.ZETA), cam.EPS * math.sin(th + cam.ZETA)
        root = math.sqrt(cam.rp**2 - (cam.E - ux) ** 2)
        return uy + root - cam.s0, root / cam.rp

    def linearized(t, s, h=1e-9):
        y, v = s
        lift, ny = kinematics(t)
        (l1, n1), (l2, n2) = kinematics(t + h), kinematics(t - h)
        delta = ny * (lift - y)
        rate = (n1 - n2) / (2 * h) * (lift - y) + ny * ((l1 - l2) / (2 * h) - v)
        force = cam.KC * max(delta, 0.0) ** cam.EXPONENT * max(1 + cam.CHI * rate, 0.0)
        return [v, (force * ny - cam.P - cam.KS * y) / cam.M]

    y0 = [mech.initial_state[0], mech.initial_velocity[0]]
    ref = solve_ivp(linearized, (0, T), y0, method="LSODA", rtol=1e-11, atol=[1e-16, 1e-12], dense_output=True)
    errors = []
    for dt in (1e-6, 5e-7):
        r = cf.simulate(mech, duration=T, time_step=dt, decimation=int(round(1e-6 / dt)))
        errors.append(np.abs(r.q[:, 0] - ref.sol(r.t)[0]).max())
    print(f"eccentric cam vs its linearized equations: {errors[0]:.2e} m at 1e-6 s, {errors[1]:.2e} m at 5e-7 s")
    assert errors[0] <= 5e-10
    assert 3.5 <= errors[0] / errors[1] <= 4.5


def test_the_eccentric_comparison_can_fail(eccentric):
    # The eccentricity's direction off by 1 deg moves the follower by ~eps * 0.017 = 3.5e-6 m.
    cam, mech = eccentric
    r = cf.simulate(cam.build(zeta=cam.ZETA + DEG), duration=mech.period / 4, time_step=1e-6, decimation=1000)
    exact = [cam.static(cam.omega * t) for t in r.t]
    assert np.abs(r.q[:, 0] - exact).max() > 1e-6


# --- 3. settling on the periodic response ---


def settle_run(mech, **options):
    return cf.simulate(mech, revolutions=1, time_step=mech.period / 8192, settle=True, **options)


@pytest.fixture(scope="module")
def settled():
    return {
        "damped": settle_run(cf.presets.paper_damped()),
        "paper": settle_run(cf.presets.paper()),
        "eccentric": settle_run(cf.presets.paper_damped(eccentricity=cf.CamEccentricity(10e-6, 0.4))),
    }


def test_realistic_damping_settles_in_a_few_revolutions_the_paper_dampers_take_many(settled):
    d, p = settled["damped"].settle, settled["paper"].settle
    message = (
        f"paper_damped settled in {d['revolutions']} revolutions (change {d['change']:.2e}), the paper's "
        f"own dampers in {p['revolutions']} (change {p['change']:.2e})"
    )
    print(message)
    assert d["settled"] and d["change"] <= d["tolerance"] == 1e-4, message
    assert d["revolutions"] <= 8, message
    assert p["settled"] and p["change"] <= p["tolerance"], message
    assert p["revolutions"] >= 5 * d["revolutions"], message
    assert d["dofs"] == ["y2"] and len(d["history"]) == d["revolutions"] - 1 and d["history"][-1] == d["change"]


def test_the_settle_change_recomputed_from_a_plain_run():
    # Run the same revolutions without settle and recompute the reported change from the recorded
    # accelerations: max |a_k - a_(k-1)| / max |a_k| over the last two settling revolutions.
    mech = cf.presets.paper_damped()
    report = settle_run(mech).settle
    k, steps = report["revolutions"], 8192
    plain = cf.simulate(
        mech,
        revolutions=k + 1,
        time_step=mech.period / steps,
        record_from=(k - 2) * mech.period + 0.5 * mech.period / steps,
    )
    a = plain.a[:, plain.dof_names.index("y2")]
    assert a.size == 3 * steps
    previous, last, after = a[:steps], a[steps : 2 * steps], a[2 * steps :]
    change = np.abs(last - previous).max() / np.abs(last).max()
    assert change == pytest.approx(report["change"], rel=1e-9)
    # After settling the response repeats: the next revolution changes as little again.
    assert np.abs(after - last).max() / np.abs(after).max() <= report["tolerance"]


def test_an_exact_eccentric_cam_settles_like_the_healthy_mechanism(settled):
    d, e = settled["damped"].settle, settled["eccentric"].settle
    print(
        f"eccentric paper_damped: {e['revolutions']} revolutions, change {e['change']:.2e} "
        f"(healthy {d['revolutions']}, {d['change']:.2e})"
    )
    assert e["settled"] and e["revolutions"] <= d["revolutions"] + 2
    assert e["change"] <= 3 * d["change"]


def test_results_keep_the_settle_report_through_files_and_pickle(settled, tmp_path):
    r = settled["damped"]
    loaded = cf.Result.load(r.save(tmp_path / "settled.npz"))
    assert loaded.settle == r.settle
    assert pickle.loads(pickle.dumps(r)).settle == r.settle
    assert cf.Result.load(cf.simulate(cf.presets.paper(), duration=1e-4).save(tmp_path / "plain.npz")).settle is None


# --- 4. the paper's literal eccentricity force ---


def test_the_literal_force_warns_when_it_exceeds_the_static_contact_force():
    p = cf.Parameters()
    # Independent of the code: on the dwell the spring force K_rs delta_rs is carried by the contact
    # along its normal, so F = K_rs delta_rs / cos(alpha_0), alpha_0 = atan(-e / s0).
    s0 = math.sqrt((p.base_radius + p.roller_radius) ** 2 - p.offset**2)
    static_force = p.spring_stiffness * p.spring_preload_deflection / math.cos(math.atan(p.offset / s0))
    with pytest.warns(UserWarning, match=r"static contact force") as record:
        literal = cf.presets.paper(eccentricity=cf.CamEccentricity(10e-6, formulation="paper_force_both"))
    message = str(record[0].message)
    assert "1900 N" in message
    assert float(message.split("static contact force ")[1].split(" N")[0]) == pytest.approx(static_force, rel=1e-6)
    assert literal.warnings == [message]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        exact = cf.presets.paper(eccentricity=cf.CamEccentricity(10e-6))
        small = cf.presets.paper(eccentricity=cf.CamEccentricity(0.5e-6, formulation="paper_force_both"))
    assert exact.warnings == [] and small.warnings == []


def test_the_literal_force_against_the_exact_eccentricity():
    # Orders of magnitude. The exact defect moves the cam surface by at most ~eps (1 + tan alpha)
    # along the follower, far below the first mode (12.5 Hz against kHz): the train follows it
    # quasi-statically, the return spring's force changes by K_rs eps (1 + tan alpha) ~ 0.18 N and
    # the train's inertia by m eps omega^2 ~ 0.11 N. The paper's literal force instead pushes the
    # roller off the cam with K_h eps sin(theta + zeta): the contact force changes by ~K_h eps
    # (the soft spring cannot take it up), and above the static contact force it opens the contact,
    # whose impacts then far exceed K_h eps.
    p = cf.Parameters()
    healthy = cf.simulate(cf.presets.paper(), revolutions=1, decimation=10)

    def deviation(eps, formulation):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            mech = cf.presets.paper(eccentricity=cf.CamEccentricity(eps, formulation=formulation))
        r = cf.simulate(mech, revolutions=1, decimation=10)
        return np.abs(r["cam.force"] - healthy["cam.force"]).max(), r.contact_loss["cam"]

    eps = 10e-6
    k_eps = p.contact_stiffness * eps  # 1900 N
    exact, exact_loss = deviation(eps, "exact")
    literal, literal_loss = deviation(eps, "paper_force_both")
    small, small_loss = deviation(0.5e-6, "paper_force_both")
    print(
        f"force deviation from healthy: exact {exact:.3f} N, literal {literal:.0f} N (K_h eps = {k_eps:.0f} N), "
        f"literal at 0.5 um {small:.1f} N (K_h eps = {p.contact_stiffness * 0.5e-6:.0f} N)"
    )
    assert exact <= 1e-3 * k_eps and not exact_loss
    assert literal >= k_eps and literal_loss
    assert small == pytest.approx(p.contact_stiffness * 0.5e-6, rel=0.25) and not small_loss


# --- 5. pickling a mechanism with eccentricity and clearances ---


def defective_builder():
    """A follower (y) on an eccentric cam; its rod laterally (x) and tilting (phi, about z = 0.02 m) in
    a two-bushing guide with friction on y."""
    b = cf.MechanismBuilder()
    b.add_dof("y", 0.5, direction=(0, 1, 0))
    b.add_dof("x", 0.3, direction=(1, 0, 0))
    b.add_dof("phi", 2e-4)
    b.add_spring("spring", "y", "ground", stiffness=2e4, preload=300.0)
    b.add_contact(
        "cam",
        cf.MotionProgram.paper_default(),
        cf.TranslatingRoller(0.04, 0.0125, 0.01),
        follower_dof="y",
        lateral="x",
        stiffness=1e8,
        eccentricity=cf.CamEccentricity(20e-6, 0.3, unbalance_mass=0.0),
    )
    b.add_guide(
        "guide",
        "x",
        clearance=20e-6,
        length=0.08,
        bushings=[0.0, 0.08],
        tilt_dof="phi",
        tilt_reference=0.02,
        stiffness=2.5e8,
        damping_factor=0.3,
        friction=0.15,
        sliding_dof="y",
    )
    b.camshaft_speed_rpm = 1500
    return b


def test_mechanisms_with_defects_pickle_and_rebuild_bit_identically():
    mech = defective_builder().build()
    assert mech.clearance_names == ["guide.bushing1", "guide.bushing2"]
    copies = [
        pickle.loads(pickle.dumps(mech)),
        mech.builder().build(),
        pickle.loads(pickle.dumps(mech.builder())).build(),
    ]
    runs = [cf.simulate(m, duration=300 * 2e-6, time_step=2e-6) for m in [mech] + copies]
    for m, r in zip(copies, runs[1:]):
        assert repr(m.builder().__getstate__()["contacts"][0]["eccentricity"]) == repr(cf.CamEccentricity(20e-6, 0.3))
        assert m.clearance_names == mech.clearance_names
        np.testing.assert_array_equal(m.initial_state, mech.initial_state)
        np.testing.assert_array_equal(m.initial_velocity, mech.initial_velocity)
        assert r.channels == runs[0].channels
        for name in r.channels:
            np.testing.assert_array_equal(r[name], runs[0][name], err_msg=name)
    # Each bushing's gap is the rod's lateral displacement there: x + (z - 0.02) phi.
    r = runs[0]
    x, phi = r.q[:, 1], r.q[:, 2]
    np.testing.assert_allclose(r["guide.bushing1.gap"], x - 0.02 * phi, rtol=0, atol=1e-18)
    np.testing.assert_allclose(r["guide.bushing2.gap"], x + 0.06 * phi, rtol=0, atol=1e-18)
    assert r.rows == 301 and r["guide.bushing1.side"].any()


# --- 6. bad input names the parameter ---


def _builder():
    b = cf.MechanismBuilder()
    b.add_dof("x", 0.2, direction=(1, 0, 0))
    b.add_dof("w", 0.3, direction=(0, 1, 0))
    return b


@pytest.mark.parametrize(
    "change, message",
    [
        (lambda b: b.add_clearance("g", [("x", 1.0)], clearance=0.0, stiffness=1e8), "clearance 'g' clearance"),
        (lambda b: b.add_clearance("g", [("x", 1.0)], clearance=-1e-5, stiffness=1e8), "clearance 'g' clearance"),
        (
            lambda b: b.add_clearance("g", [("x", 1.0)], clearance=float("nan"), stiffness=1e8),
            "clearance 'g' clearance",
        ),
        (
            lambda b: b.add_clearance("g", [("x", 1.0)], clearance=1e-5, stiffness=1e8, friction=-0.1, sliding_dof="w"),
            "friction coefficient",
        ),
        (lambda b: b.add_clearance("g", [("x", 1.0)], clearance=1e-5, stiffness=1e8, friction=0.1), "sliding DOF"),
        (
            lambda b: b.add_clearance(
                "g", [("x", 1.0)], clearance=1e-5, stiffness=1e8, friction=0.1, sliding_dof="w", slip_velocity=0.0
            ),
            "slip velocity",
        ),
        (lambda b: b.add_clearance("g", [("x", 1.0), ("x", 2.0)], clearance=1e-5, stiffness=1e8), "appears twice"),
        (
            lambda b: (
                b.add_clearance("g", [("x", 1.0)], clearance=1e-5, stiffness=1e8, friction=0.1, sliding_dof="v"),
                b.build(),
            ),
            "sliding_dof refers to DOF 'v'",
        ),
        (
            lambda b: b.add_guide("guide", "x", clearance=1e-5, length=0.1, bushings=[0.12], stiffness=1e8),
            r"bushing position 0.12 m must lie in the guide",
        ),
        (
            lambda b: b.add_guide("guide", "x", clearance=1e-5, length=0.1, bushings=[-0.01], stiffness=1e8),
            r"bushing position -0.01 m",
        ),
        (
            lambda b: b.add_guide("guide", "x", clearance=1e-5, length=0.1, bushings=[0.0, 0.1], stiffness=1e8),
            "tilt_dof",
        ),
        (lambda b: cf.CamEccentricity(1e-5, formulation="paper"), "eccentricity formulation"),
        (lambda b: cf.CamEccentricity(-1e-5), "eccentricity radius"),
        (lambda b: cf.presets.paper(element_damping_ratio=1.0), "element_damping_ratio"),
        (lambda b: cf.presets.paper_damped(damping_ratio=1.0), "element_damping_ratio"),
    ],
)
def test_bad_defect_input_names_the_parameter(change, message):
    with pytest.raises(ValueError, match=message):
        change(_builder())


def test_bad_settle_input_names_the_parameter():
    mech = cf.presets.paper_damped()
    with pytest.raises(ValueError, match="time step must divide the period"):
        cf.simulate(mech, revolutions=1, time_step=7e-6, settle=True)
    with pytest.raises(ValueError, match=r"settle_dofs: unknown DOF\(s\) \['y9'\]"):
        cf.simulate(mech, revolutions=1, time_step=mech.period / 8192, settle=True, settle_dofs=["y9"])
