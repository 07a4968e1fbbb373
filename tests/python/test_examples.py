# SPDX-License-Identifier: BSD-3-Clause
"""The flat-faced train and swing-arm examples against closed forms worked out here, from the masses,
stiffnesses and geometry the examples set (not from the library's own contact geometry)."""

import runpy
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def train():
    return runpy.run_path(str(EXAMPLES / "flat_faced_train.py"))


@pytest.fixture(scope="module")
def arm():
    return runpy.run_path(str(EXAMPLES / "swing_arm_follower.py"))


# --- flat-faced tappet with a massive valve spring ---


@pytest.mark.parametrize("theta_deg", [0.0, 120.0, 190.0])
def test_train_natural_frequencies_are_those_of_the_two_mass_chain(train, theta_deg):
    # Tappet m_f on the contact k_c (to the rigid cam) and on the upper half 2 k_s; the middle m_m on
    # both halves. A linear contact: the same frequencies at any cam angle.
    m_f, m_m, k_s, k_c = train["TAPPET_MASS"], train["MID_MASS"], train["SPRING"], train["CONTACT"]
    M = np.diag([m_f, m_m])
    K = np.array([[k_c + 2 * k_s, -2 * k_s], [-2 * k_s, 4 * k_s]])
    exact = np.sqrt(scipy.linalg.eigh(K, M, eigvals_only=True)) / (2 * np.pi)
    code = train["mechanism"]().modal_analysis(np.radians(theta_deg))["frequencies_hz"]
    print(
        f"theta {theta_deg} deg: code {code} Hz, two-mass chain {exact} Hz, "
        f"relative difference {np.abs(code / exact - 1).max():.1e}"
    )
    np.testing.assert_allclose(code, exact, rtol=1e-10, atol=0)


def test_train_contact_force_is_the_static_closed_form_at_low_speed(train):
    # Tappet: F = P + 2 k_s (y_f - y_m) + m_f g + m_f a_f. Middle: m_m a_m = 2 k_s (y_f - 2 y_m) - m_m g,
    # so y_m = y_f / 2 - m_m (g + a_f / 2) / (4 k_s) when slow and 2 k_s (y_f - y_m) = k_s y_f +
    # m_m g / 2 + m_m a_f / 4. Contact: y_f = h - F / k_c, a_f = omega^2 h'' (F'' / k_c is 1e-9 of it).
    m_f, m_m, k_s, k_c = train["TAPPET_MASS"], train["MID_MASS"], train["SPRING"], train["CONTACT"]
    P, g, rpm = train["PRELOAD"], train["GRAVITY"], 10.0
    r = train["run"](rpm, time_step=1e-4)
    m = train["program"]().evaluate(r["theta"])
    omega = rpm * 2 * np.pi / 60

    def closed_form(weight_mass, inertia_mass):
        return (P + k_s * m["h"] + weight_mass * g + inertia_mass * omega**2 * m["d2h"]) / (1 + k_s / k_c)

    force = r["cam.force"]
    error = np.abs(force / closed_form(m_f + m_m / 2, m_f + m_m / 4) - 1).max()
    # What the comparison resolves: the inertia term, and where the spring's weight goes.
    without_inertia = np.abs(force / closed_form(m_f + m_m / 2, 0.0) - 1).max()
    whole_spring_weight = np.abs(force / closed_form(m_f + m_m, m_f + m_m / 4) - 1).max()
    print(
        f"{rpm} rpm, {r.rows} samples, F {force.min():.4f} .. {force.max():.4f} N: largest relative "
        f"difference {error:.2e} (without the inertia term {without_inertia:.2e}, with all of the middle's "
        f"weight on the tappet {whole_spring_weight:.2e})"
    )
    assert not r.contact_loss["cam"]
    assert error < 1e-6
    assert without_inertia > 1e-6 and whole_spring_weight > 1e-6


def test_train_holds_at_its_speed_and_separates_between_the_closed_form_bounds(train):
    m_f, m_m, k_s, P = train["TAPPET_MASS"], train["MID_MASS"], train["SPRING"], train["PRELOAD"]
    weight = (m_f + m_m / 2) * train["GRAVITY"]
    r = train["run"](train["RPM"], revolutions=3)  # undamped: later revolutions carry the first's vibration
    print(
        f"{train['RPM']:.0f} rpm, 3 revolutions: smallest contact force {r['cam.force'].min():.3f} N, "
        f"losses {r.contact_loss['cam']}"
    )
    assert not r.contact_loss["cam"] and r["cam.force"].min() > 0.5 * P

    # F_spring_min = m |h''|max omega^2. Lower: the least holding force (P + weight, at h = 0) and the
    # largest mass (m_f + m_m); upper: the largest (P + k_s L + weight) and the smallest (m_f).
    theta = np.linspace(0, 2 * np.pi, 360001)
    m = train["program"]().evaluate(theta)
    h2_max = np.abs(m["d2h"]).max()
    to_rpm = 60 / (2 * np.pi)
    lower = np.sqrt((P + weight) / ((m_f + m_m) * h2_max)) * to_rpm
    upper = np.sqrt((P + k_s * train["LIFT"] + weight) / (m_f * h2_max)) * to_rpm
    # For reference, the quasi-static speed at which the closed form of the previous test reaches zero.
    braking = m["d2h"] < 0
    quasi_static = np.sqrt(np.min((P + k_s * m["h"][braking] + weight) / ((m_f + m_m / 4) * -m["d2h"][braking])))
    holds, loses, runs = train["separation_speed"](holds=train["RPM"], loses=2 * upper, resolution=10.0)
    print(
        f"first loss of contact (first revolution from rest) between {holds:.1f} and {loses:.1f} rpm "
        f"({runs} runs); bounds {lower:.1f} .. {upper:.1f} rpm; quasi-static closed form "
        f"{quasi_static * to_rpm:.1f} rpm"
    )
    assert lower < holds < loses < upper
    assert loses - holds <= 10.0


# --- swing-arm roller follower ---


def J(v):
    """+90 deg turn of 2-vectors (last axis)."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def arm_geometry(arm, s, ds):
    """Lever L cos(alpha) (m per rad) and alpha (rad) at arm rotation s (rad) and ds/dtheta, from the
    pivot, arm and radii alone. The roller centre C = P + L u(phi0 + s), |C| = r_b + r_r at s = 0 on the
    root where turning counter-clockwise moves the roller away from the cam. In the cam frame the
    centre runs along Rot(-theta) C, with tangent Rot(-theta)(C' - J C); the contact normal is normal
    to it: n ~ J (C' - J C) = C + J C'. On a dwell (C' = 0) n points from the cam centre to C."""
    P, L = np.asarray(arm["PIVOT"], float), arm["ARM_LENGTH"]
    R = arm["BASE_RADIUS"] + arm["ROLLER_RADIUS"]
    # |P + L u|^2 = R^2  <=>  P.u = (R^2 - |P|^2 - L^2) / (2 L) = |P| cos(phi - angle of P)
    c = (R**2 - P @ P - L**2) / (2 * L)
    beta, gap = np.arctan2(P[1], P[0]), np.arccos(c / np.linalg.norm(P))
    roots = [beta + gap, beta - gap]
    lifting = [phi for phi in roots if P @ J(np.array([np.cos(phi), np.sin(phi)])) > 0]  # d|C|^2/dphi = 2 L P.Ju
    assert len(lifting) == 1
    phi = lifting[0] + np.asarray(s, float)
    u = np.stack([np.cos(phi), np.sin(phi)], axis=-1)
    C = P + L * u
    assert np.allclose(np.linalg.norm(C[np.asarray(s) == 0.0], axis=-1), R, rtol=1e-14, atol=0)
    dC = L * np.asarray(ds, float)[..., None] * J(u)
    N = C + J(dC)
    n = N / np.linalg.norm(N, axis=-1, keepdims=True)
    v = J(u)  # direction of the roller centre as the arm lifts
    cos_a, sin_a = np.sum(n * v, axis=-1), v[..., 0] * n[..., 1] - v[..., 1] * n[..., 0]
    return L * cos_a, np.arctan2(sin_a, cos_a)


DWELLS = [("base", 30.0), ("top", 180.0), ("base, after the return", 330.0)]


@pytest.mark.parametrize("name, theta_deg", DWELLS)
def test_swing_arm_static_balance_on_a_dwell(arm, name, theta_deg):
    theta = np.radians(theta_deg)
    s = arm["program"]().evaluate(theta)["h"]
    q, force = arm["rest_on_cam"](theta)
    q_code = arm["mechanism"]().static_equilibrium(theta)[0]
    lever, alpha = arm_geometry(arm, s, 0.0)
    torque = arm["PRELOAD_TORQUE"] + arm["TORSION"] * q
    print(
        f"{name} dwell, theta {theta_deg} deg: s {s:.6f} rad, q {q:.9f} rad, alpha {np.degrees(alpha):.4f} deg, "
        f"L cos(alpha) {lever:.9f} m; F {force:.6f} N, F L cos(alpha) {force * lever:.12f} N m, "
        f"T0 + k_t q {torque:.12f} N m, relative difference {abs(force * lever / torque - 1):.1e}"
    )
    assert q == pytest.approx(q_code, rel=1e-15, abs=0)
    assert force * lever == pytest.approx(torque, rel=1e-9, abs=0)


def test_swing_arm_tracks_the_lift_quasi_statically(arm):
    # At rest: k_c lever^2 (s - q) = T0 + k_t q, so s - q = (T0 + k_t s) / (k_c lever^2 + k_t). The
    # arm's inertia, J omega^2 s'' at 1 rpm, is below 1e-6 of the spring torque.
    r = arm["run"](1.0, time_step=1e-3, decimation=5)
    m = arm["program"]().evaluate(r["theta"])
    lever, _ = arm_geometry(arm, m["h"], m["dh"])
    predicted = (arm["PRELOAD_TORQUE"] + arm["TORSION"] * m["h"]) / (arm["CONTACT"] * lever**2 + arm["TORSION"])
    lag = m["h"] - r.q[:, 0]
    error = np.abs(lag - predicted)
    tolerance = 1e-9 + 1e-3 * predicted
    print(
        f"1 rpm, {r.rows} samples: s - q from {lag.min():.6e} to {lag.max():.6e} rad; largest |difference| "
        f"{error.max():.2e} rad, relative {np.max(error / predicted):.2e}, "
        f"of the tolerance {np.max(error / tolerance):.2e}"
    )
    assert not r.contact_loss["cam"]
    assert np.all(error <= tolerance)


@pytest.mark.parametrize("name, theta_deg", DWELLS)
def test_swing_arm_natural_frequency_on_a_dwell(arm, name, theta_deg):
    theta = np.radians(theta_deg)
    lever, _ = arm_geometry(arm, arm["program"]().evaluate(theta)["h"], 0.0)
    exact = np.sqrt((arm["TORSION"] + arm["CONTACT"] * lever**2) / arm["INERTIA"]) / (2 * np.pi)
    code = arm["mechanism"]().modal_analysis(theta)["frequencies_hz"][0]
    print(
        f"{name} dwell, theta {theta_deg} deg: code {code:.9f} Hz, closed form {exact:.9f} Hz, "
        f"relative difference {abs(code / exact - 1):.1e}"
    )
    assert code == pytest.approx(exact, rel=1e-9, abs=0)


# --- the rod in its guide clearance ---


@pytest.fixture(scope="module")
def guide():
    return runpy.run_path(str(EXAMPLES / "guide_clearance.py"))


def test_guide_rod_follows_the_lateral_load(guide):
    """The contact pushes the roller across the axis by F sin(alpha): with the offset follower alpha
    stays negative all revolution (one wall, no impacts); in-line, alpha has the sign of h' (positive
    on the rise, negative on the return), so the rod sits on opposite walls and must cross."""
    m, r = guide["run"](0.010)
    s = guide["analysis"].clearance_statistics(r, "guide", m.period)
    assert s["impacts_per_revolution"] == 0 and s["wall_changes_per_revolution"] == 0
    alpha = r["cam.pressure_angle"]
    assert np.all(alpha < 0)
    m, r = guide["run"](0.0)
    s = guide["analysis"].clearance_statistics(r, "guide", m.period)
    assert s["wall_changes_per_revolution"] >= 1 and s["impacts_per_revolution"] > 2
    rise, ret = guide["rod_side"](r, 100, 170), guide["rod_side"](r, 250, 330)
    assert rise * ret < 0 and min(abs(rise), abs(ret)) > 0.8 * guide["CLEARANCE"]
