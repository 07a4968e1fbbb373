# SPDX-License-Identifier: BSD-3-Clause
"""The open mechanism core from Python: builder, immutable picklable mechanisms, typed results, the
paper preset against the paper's Table 2 assembled in NumPy, and the examples against closed forms."""

import pickle
import runpy
import time
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def one_dof():
    return runpy.run_path(str(EXAMPLES / "one_dof_follower.py"))


@pytest.mark.parametrize("tau", [0.75, 1.5, 2.5, 3.3, 5.5, 8.0])
def test_one_dof_residual_vibration_matches_the_closed_form(one_dof, tau):
    simulated, exact = one_dof["residual_amplitude"](tau), one_dof["closed_form"](tau)
    print(f"tau {tau}: A/L simulated {simulated:.7f}, closed form {exact:.7f}")
    assert abs(simulated - exact) < 1e-5


def test_one_dof_residual_vibrations_at_once_are_those_one_by_one(one_dof):
    taus = [0.75, 2.5, 8.0]
    together = one_dof["residual_amplitudes"](taus)
    assert together == [one_dof["residual_amplitude"](tau) for tau in taus]  # bit for bit
    for tau, a in zip(taus, together):
        assert abs(a - one_dof["closed_form"](tau)) < 1e-5


def test_the_residual_vibration_check_can_fail(one_dof):
    # A coarse step shifts the discrete natural frequency: the same comparison then misses.
    simulated = one_dof["residual_amplitude"](2.5, steps_per_period=20)
    assert abs(simulated - one_dof["closed_form"](2.5)) > 1e-5


def paper_table_2():
    """M, C, K of the paper's 7-DOF model assembled here from Table 2 (docs/model.md), q = (y1, y2, y3,
    y4, x1, x2, x3); the camshaft mass places the contact-free bearing mode at Table 3's 2447 Hz."""
    dofs = ["y1", "y2", "y3", "y4", "x1", "x2", "x3"]
    m_c = 2.6e8 / (2 * np.pi * 2447.0) ** 2
    M = np.diag([m_c, 0.07, 0.34, 1.36, m_c, 0.07, 0.34])
    K, C = np.zeros((7, 7)), np.zeros((7, 7))

    def spring(matrix, a, b, value):
        i = dofs.index(a)
        matrix[i, i] += value
        if b is not None:
            j = dofs.index(b)
            matrix[j, j] += value
            matrix[i, j] -= value
            matrix[j, i] -= value

    for a, b, k in [
        ("y1", None, 2.6e8),  # K_vs, camshaft bearing
        ("x1", None, 2.6e8),  # K_hs
        ("y2", "y3", 1.7e8),  # K_vc, roller pin
        ("x2", "x3", 2.5e8),  # K_hc
        ("x3", None, 2.5e8),  # K_rb, rod guide
        ("y3", "y4", 2.5e8),  # K_f, follower rod
        ("y4", None, 1.4e4),  # K_rs, return spring
    ]:
        spring(K, a, b, k)
    for a, b, c in [("y1", None, 750.0), ("x1", None, 750.0), ("y3", "y4", 0.08)]:  # C_vs, C_hs, C_f
        spring(C, a, b, c)
    return dofs, M, C, K


def contact_direction(theta, offset=0.010):
    """d delta / dq of the cam-roller contact (docs/model.md): delta = cos a (y1 - y2 + h) - sin a (x1 - x2),
    a = atan((R' - e) / R), R = s0 + h (paper eqs 2, 4); and the lift h at theta."""
    s0 = np.sqrt((0.030 + 0.008) ** 2 - offset**2)
    m = cf.MotionProgram.paper_default().evaluate(theta)
    a = np.arctan((m["dh"] - offset) / (s0 + m["h"]))
    c, s = np.cos(a), np.sin(a)
    return np.array([c, -c, 0.0, 0.0, -s, s, 0.0]), float(m["h"])


def test_paper_preset_is_the_paper_model_of_table_2():
    scipy_linalg = pytest.importorskip("scipy.linalg")
    preset = cf.presets.paper()
    dofs, M, C, K = paper_table_2()
    assert preset.dof_names == dofs
    np.testing.assert_allclose(preset.mass, M, rtol=1e-15, atol=0)
    np.testing.assert_allclose(preset.stiffness, K, rtol=1e-15, atol=0)
    np.testing.assert_allclose(preset.damping, C, rtol=1e-15, atol=0)
    (contact,) = preset.builder().contacts
    assert contact["stiffness"] == 1.9e8 and contact["exponent"] == 1.0  # K_h, linear law
    # The static equilibrium on the dwell, (K + K_h g g^T) q = -P e_y4, with the preload P calibrated so
    # that the return spring then carries K_rs delta_rs = 14e3 N/m * 13 mm = 182 N (docs/model.md).
    (rs,) = [s for s in preset.builder().springs if s["name"] == "K_rs"]
    g, h = contact_direction(0.0)
    assert h == 0.0
    load = np.zeros(7)
    load[3] = -rs["preload"]
    q0 = np.linalg.solve(K + 1.9e8 * np.outer(g, g), load)
    np.testing.assert_allclose(preset.initial_state, q0, rtol=0, atol=1e-12 * np.abs(q0).max())
    assert rs["preload"] + 1.4e4 * q0[3] == pytest.approx(1.4e4 * 0.013, rel=1e-9)
    # Natural frequencies, contact linearized along g at the equilibrium, against scipy's eigh.
    for theta in (0.0, np.radians(100), np.radians(290)):
        g, _ = contact_direction(theta)
        omega2 = scipy_linalg.eigh(K + 1.9e8 * np.outer(g, g), M, eigvals_only=True)
        np.testing.assert_allclose(
            preset.modal_analysis(theta)["frequencies_hz"], np.sqrt(omega2) / (2 * np.pi), rtol=1e-10
        )
    table = [867.9, 2447.0, 2747.5, 3893.3, 5318.7, 10403.4, 12013.2]  # docs/model.md, theta = 0
    np.testing.assert_allclose(preset.modal_analysis(0.0)["frequencies_hz"], table, rtol=0, atol=0.05)


def builder_1dof(speed_rpm=750.0):
    b = cf.MechanismBuilder()
    b.add_dof("y", 0.5, direction=(0, 1, 0))
    b.add_spring("spring", "y", "ground", stiffness=2e4, preload=300.0)
    b.add_contact(
        "cam", cf.MotionProgram.paper_default(), cf.TranslatingRoller(0.03, 0.008, 0.0), follower_dof="y", stiffness=1e8
    )
    b.camshaft_speed_rpm = speed_rpm
    return b


def test_mechanisms_are_immutable_and_changed_copies_are_new_objects():
    mech = builder_1dof().build()
    with pytest.raises(AttributeError):
        mech.camshaft_speed_rpm = 3000
    faster = mech.with_camshaft_speed_rpm(3000)
    assert mech.camshaft_speed_rpm == pytest.approx(750) and faster.camshaft_speed_rpm == pytest.approx(3000)
    assert faster.period == pytest.approx(mech.period / 4)
    b = mech.builder()
    b.add_load("y", -10.0)
    assert mech.initial_state[0] != b.build().initial_state[0]  # the original did not change


def test_mechanisms_and_results_pickle_and_give_identical_runs(tmp_path):
    mech = cf.presets.paper()
    copy = pickle.loads(pickle.dumps(mech))
    np.testing.assert_array_equal(copy.initial_state, mech.initial_state)
    r1 = cf.simulate(mech, duration=2e-3, decimation=10)
    r2 = cf.simulate(copy, duration=2e-3, decimation=10)
    np.testing.assert_array_equal(r1.q, r2.q)
    r3 = pickle.loads(pickle.dumps(r1))
    np.testing.assert_array_equal(r3.q, r1.q)
    path = r1.save(tmp_path / "run.npz")
    r4 = cf.Result.load(path)
    assert r4.channels == r1.channels and r4.stats == r1.stats and r4.contact_loss == r1.contact_loss
    np.testing.assert_array_equal(r4["cam.force"], r1["cam.force"])
    assert not list(tmp_path.glob(".*tmp"))  # no temporary left behind
    with pytest.raises(ValueError, match="npz"):
        r1.save(tmp_path / "run.csv")


def test_result_channels_are_named_views():
    mech = cf.presets.paper()
    r = cf.simulate(mech, duration=1e-3, time_step=1e-5, decimation=10)
    assert r.q.shape == (11, 7) and r.dof_names == mech.dof_names
    assert r.q.base is not None and not r.q.flags.writeable
    assert "cam.pressure_angle" in r.channels and r["cam.in_contact"].dtype == bool
    with pytest.raises(KeyError, match="recorded channels"):
        r.channel("nope")


def test_recording_window_and_progress_and_cancellation():
    mech = cf.presets.paper()
    full = cf.simulate(mech, revolutions=1, decimation=64)
    last = cf.simulate(mech, revolutions=1, decimation=64, record_last_revolutions=0.25)
    assert last.t[0] >= 0.75 * mech.period - 64 * 3e-6 and last.t[-1] == pytest.approx(full.t[-1])
    np.testing.assert_array_equal(last.q, full.q[-last.rows :])
    calls = []
    stopped = cf.simulate(
        mech, revolutions=1, progress=lambda done, total: calls.append(done) or len(calls) < 2, progress_interval=1e-6
    )
    assert stopped.stats["cancelled"] and len(calls) == 2 and stopped.rows < full.rows * 64


def test_ctrl_c_stops_a_long_run_quickly(ctrl_c):
    mech = cf.presets.paper()
    start = ctrl_c(0.5)
    with pytest.raises(KeyboardInterrupt):
        cf.simulate(mech, revolutions=2000, decimation=1000)  # ~3 min if not stopped
    assert time.monotonic() - start < 1.5


@pytest.mark.parametrize(
    "change, message",
    [
        (lambda b: b.add_spring("s", "nope", "ground", stiffness=1.0), "not defined"),
        (lambda b: b.add_spring("s", "y", "y", stiffness=1.0), "to itself"),
        (lambda b: b.add_dof("z", -1.0), "mass of DOF 'z'"),
        (lambda b: b.set_modal_damping([-0.1]), "modal damping ratio"),
        (
            lambda b: b.add_contact(
                "cam2",
                cf.MotionProgram.paper_default(),
                cf.TranslatingRoller(0.03, 0.008),
                follower_dof="w",
                stiffness=1e8,
            ),
            "not defined",
        ),
    ],
)
def test_bad_descriptions_name_the_element(change, message):
    b = builder_1dof()
    with pytest.raises(ValueError, match=message):
        change(b)
        b.build()


def test_a_cusped_cam_is_refused_with_the_angle():
    # 20 mm in 60 deg: on a 30 mm base circle the flat face would need a surface radius r_b + h + h'' < 0.
    mt, dwell, d = cf.MotionLaw.modified_trapezoid(), cf.MotionLaw.dwell(), np.radians
    fast = cf.MotionProgram(
        [
            cf.Segment(dwell, 0, d(30), 0, 0),
            cf.Segment(mt, d(30), d(90), 0, 0.02),
            cf.Segment(dwell, d(90), d(180), 0.02, 0.02),
            cf.Segment(mt, d(180), 2 * np.pi, 0.02, 0),
        ]
    )
    b = cf.MechanismBuilder()
    b.add_dof("y", 0.5)
    b.add_spring("spring", "y", "ground", stiffness=2e4, preload=300.0)
    b.add_contact("cam", fast, cf.TranslatingFlat(0.03), follower_dof="y", stiffness=1e8)
    with pytest.raises(ValueError, match=r"contact 'cam'.*cusp at theta = 67\.\d+ deg"):
        b.build()


def test_a_follower_not_held_in_place_is_reported():
    b = cf.MechanismBuilder()
    b.add_dof("y", 0.5)
    b.add_dof("free", 0.1, direction=(0, 1, 0))  # falls under gravity: nothing holds it
    b.set_gravity((0, -9.81, 0))
    b.add_contact("cam", cf.MotionProgram.paper_default(), cf.TranslatingFlat(0.03), follower_dof="y", stiffness=1e8)
    with pytest.raises(ValueError, match="not held in place"):
        b.build()


def test_model_parameters_cannot_be_changed_behind_the_models_back():
    p = cf.Parameters()
    model = cf.presets.paper(p)
    with pytest.raises(AttributeError):
        p.camshaft_speed_rpm = 3000  # the card is immutable: no silently ignored assignment
    with pytest.raises(AttributeError):
        model.camshaft_speed_rpm = 3000
    faster = cf.presets.paper(p.replace(camshaft_speed_rpm=3000))
    assert faster.period == pytest.approx(model.period / 4)
    assert p.camshaft_speed_rpm == 750 and model.camshaft_speed_rpm == pytest.approx(750)
    b = model.builder()  # a copy: changing it leaves the model alone
    b.camshaft_speed_rpm = 3000
    assert model.camshaft_speed_rpm == pytest.approx(750)
    q = cf.Parameters().replace(contact_stiffness=2e8)
    assert q.contact_stiffness == 2e8 and cf.Parameters().contact_stiffness == 1.9e8
    assert cf.presets.paper(q).builder().contacts[0]["stiffness"] == 2e8
    assert model.builder().contacts[0]["stiffness"] == 1.9e8
    with pytest.raises(ValueError, match="roller_mass must be finite and > 0"):
        cf.Parameters().replace(roller_mass=-1.0)
    with pytest.raises(ValueError, match="unknown parameter 'stiffnes'"):
        p.replace(stiffnes=1.0)


def test_a_follower_held_only_by_gravity_finds_its_equilibrium_and_edge_cases_of_the_review():
    b = cf.MechanismBuilder()
    b.add_dof("y", 0.5, direction=(0, 1, 0))
    b.set_gravity((0, -9.81, 0))
    b.add_contact("cam", cf.MotionProgram.paper_default(), cf.TranslatingFlat(0.03), follower_dof="y", stiffness=1e8)
    mech = b.build()
    assert mech.initial_state[0] == pytest.approx(-0.5 * 9.81 / 1e8, rel=1e-9)  # weight / contact stiffness
    with pytest.raises(ValueError, match="not on 'ground'"):
        b.add_load("ground", 1.0)
    with pytest.raises(ValueError, match="record_from = inf s: the recording window starts after the run ends"):
        cf.simulate(mech, duration=1e-4, time_step=1e-5, record_from=float("inf"))  # nothing to record: refused
    lifted = builder_1dof()
    lifted.add_load("y", 400.0)  # lifts the follower off the cam: contact open from the start
    r = cf.simulate(lifted.build(), duration=1e-4, time_step=1e-5)
    assert r.contact_loss["cam"] == [(0.0, pytest.approx(1e-4))]
    clash = cf.MechanismBuilder()
    clash.add_dof("force", 0.5)
    clash.add_spring("k", "force", "ground", stiffness=1e4, preload=100.0)
    clash.add_contact(
        "q", cf.MotionProgram.paper_default(), cf.TranslatingFlat(0.03), follower_dof="force", stiffness=1e8
    )
    with pytest.raises(ValueError, match="both named 'q.force'"):
        cf.simulate(clash.build(), duration=1e-4)


def test_rayleigh_and_modal_damping_against_their_definitions():
    m, k, kc = 0.5, 2e4, 1e8  # the contact (n = 1) adds kc to the stiffness in contact
    b = builder_1dof()
    b.set_rayleigh_damping(3.0, 2e-6)
    mech = b.build()
    np.testing.assert_allclose(mech.damping, [[3.0 * m + 2e-6 * k]], rtol=1e-14)  # alpha M + beta K
    b = builder_1dof()
    b.set_modal_damping([0.05])
    mech = b.build()
    # One DOF: C = 2 zeta omega m with omega from K + contact stiffness at the initial equilibrium.
    np.testing.assert_allclose(mech.damping, [[2 * 0.05 * np.sqrt((k + kc) / m) * m]], rtol=1e-12)
    with pytest.raises(ValueError, match="one ratio or one per mode"):
        b = builder_1dof()
        b.set_modal_damping([0.05, 0.02])
        b.build()


def test_the_builder_reads_back_what_was_added():
    """The builder's read accessors give each element as it was added, in order (values typed in here)."""
    b = cf.MechanismBuilder()
    b.add_dof("x", 0.2, direction=(1, 0, 0))
    b.add_dof("w", 0.3, direction=(0, 1, 0))
    b.add_mass("w", 0.05)
    b.add_spring("axial", "w", "ground", stiffness=2.5e4, damping=3.0, preload=40.0)
    b.add_load("x", -1.5)
    program = cf.MotionProgram.paper_default()
    b.add_contact("cam", program, cf.TranslatingRoller(0.04, 0.01), follower_dof="w", lateral="x", stiffness=3e8)
    b.add_clearance("guide", [("x", 1.0)], clearance=2e-5, stiffness=1e8)
    assert [d["name"] for d in b.dofs] == ["x", "w"]
    assert b.dofs[1]["mass"] == 0.3 and list(b.dofs[0]["direction"]) == [1, 0, 0]
    assert b.masses == [("w", 0.05)]
    (s,) = b.springs
    assert (s["name"], s["a"], s["b"], s["stiffness"], s["damping"], s["preload"]) == (
        "axial",
        "w",
        "ground",
        2.5e4,
        3.0,
        40.0,
    )
    assert b.loads == [{"dof": "x", "force": -1.5}]
    (c,) = b.contacts
    assert (c["name"], c["follower_dof"], c["lateral"], c["stiffness"]) == ("cam", "w", "x", 3e8)
    assert c["follower"].base_radius == 0.04 and c["follower"].roller_radius == 0.01
    (g,) = b.clearances
    assert (g["name"], g["gap"], g["clearance"], g["stiffness"]) == ("guide", [("x", 1.0)], 2e-5, 1e8)
    # Copies: changing what was read does not change the builder.
    b.contacts[0]["stiffness"] = 1.0
    assert b.contacts[0]["stiffness"] == 3e8
