# SPDX-License-Identifier: BSD-3-Clause
"""A variable camshaft speed against independent truth: a stiffly held follower's acceleration against
the rigid kinematics h'' theta'^2 + h' theta'' through a run-up, the drive torque's work against the
energy the mechanism stores (no damping), the periodic steady state of a modulated speed, and the
speed program's reach from Python and the config."""

import math
import pickle

import camfollower as cf
import numpy as np
import pytest
from camfollower.config import config_from_dict

DEG = math.pi / 180.0
RPM = math.pi / 30.0  # rad/s per rpm


def program(lift=0.008):
    """Rise and return by the 4-5-6-7 polynomial: its jerk has no step, so a stiffly held follower
    barely rings and its acceleration shows the kinematics."""
    dwell, cyc = cf.MotionLaw.dwell(), cf.MotionLaw.polynomial_4567()
    return cf.MotionProgram(
        [
            cf.Segment(dwell, 0, 30 * DEG, 0, 0),
            cf.Segment(cyc, 30 * DEG, 150 * DEG, 0, lift),
            cf.Segment(dwell, 150 * DEG, 200 * DEG, lift, lift),
            cf.Segment(cyc, 200 * DEG, 360 * DEG, lift, 0),
        ]
    )


def follower(mass=0.2, stiffness=1e8, damping_factor=0.0, spring=2e4, load=150.0):
    """A translating roller follower held by a spring (no preload) and a constant load towards the cam."""
    b = cf.MechanismBuilder()
    b.add_dof("w", mass, direction=(0, 1, 0))
    b.add_spring("spring", "w", stiffness=spring)
    b.add_load("w", -load)
    b.add_contact(
        "cam",
        program(),
        cf.TranslatingRoller(0.03, 0.008, 0.0),
        follower_dof="w",
        stiffness=stiffness,
        exponent=1.0,
        damping_factor=damping_factor,
    )
    return b


def run_up(b, to_rpm=600.0, duration=0.25, shape="linear", start=0.0):
    b.speed_program = cf.SpeedProgram(0.0, [cf.SpeedRamp(start, duration, to_rpm * RPM, shape)])
    return b


@pytest.mark.parametrize("shape", ["linear", "smooth"])
def test_a_stiff_follower_moves_with_the_rigid_kinematics_of_a_run_up(shape):
    # 0 -> 300 rpm, the ramp from the first dwell to the second (3 rad in either shape): the rise passes
    # while the camshaft accelerates, and no step of theta'' meets a moving follower (the linear ramp's
    # steps fall in the dwells). The follower's ground acceleration is h'' theta'^2 + h' theta'' up to
    # the contact's compliance.
    top = 300 * RPM
    mech = run_up(follower(damping_factor=2e-3), to_rpm=300.0, duration=2 * 3.0 / top, shape=shape).build()
    r = cf.simulate(mech, duration=0.3, method="dop853", tolerance=1e-9, time_step=2e-5)
    drive = mech.speed_program.evaluate(r.t)
    np.testing.assert_allclose(r["theta"], drive["angle"], rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(r["drive.speed"], drive["speed"], rtol=1e-13, atol=1e-13)
    m = program().evaluate(drive["angle"])
    rigid = m["d2h"] * drive["speed"] ** 2 + m["dh"] * drive["acceleration"]
    # Without the h' theta'' term the check must fail: it is a sizeable part of the acceleration.
    missing = np.abs(m["dh"] * drive["acceleration"]).max()
    err = np.abs(r.a[:, 0] - rigid).max()
    print(
        f"{shape} run-up: |a - rigid| {err:.3g} m/s^2, peak rigid {np.abs(rigid).max():.3g}, h' theta'' {missing:.3g}"
    )
    assert missing > 0.05 * np.abs(rigid).max()
    assert err < 0.01 * missing
    np.testing.assert_allclose(r.q[:, 0], m["h"], rtol=0, atol=4e-6)  # the contact deflects by up to 3.1 um


def test_the_drive_torque_does_the_work_the_mechanism_stores():
    # No damping anywhere: the work of the drive torque, integral of drive.power dt, equals the change
    # of kinetic energy, spring and load potential and the contact's elastic energy K delta^2 / 2.
    b = run_up(follower(stiffness=5e7), duration=0.2, shape="smooth")
    mech = b.build()
    r = cf.simulate(mech, duration=0.22, method="dop853", tolerance=1e-10, time_step=5e-6)
    w, v, delta = r.q[:, 0], r.v[:, 0], r["cam.penetration"]
    energy = 0.5 * 0.2 * v**2 + 0.5 * 2e4 * w**2 + 150.0 * w + 0.5 * 5e7 * np.maximum(delta, 0.0) ** 2
    power = r["drive.power"]
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(r.t))])
    stored = energy - energy[0]
    scale = np.abs(stored).max()
    print(f"work {work[-1]:.6g} J, stored {stored[-1]:.6g} J, largest gap {np.abs(work - stored).max():.3g} J")
    assert scale > 0.1  # the follower rises 8 mm against 150 N and a spring
    np.testing.assert_allclose(work, stored, rtol=0, atol=2e-4 * scale)
    # The torque is the power over the speed (a rigid camshaft).
    moving = r["drive.speed"] > 1.0
    np.testing.assert_allclose(r["drive.torque"][moving] * r["drive.speed"][moving], power[moving], rtol=1e-12)


def test_the_drive_torque_of_a_constant_speed_matches_the_virtual_work_of_the_contact():
    # At constant speed the torque is F d delta / d theta; for a translating roller with no offset,
    # delta = cos(alpha) (h - w), so d delta / d theta at fixed w is cos(alpha) h' + (h - w) d cos(alpha) / d theta.
    b = follower(damping_factor=1e-3)
    b.camshaft_speed_rpm = 300.0
    mech = b.build()
    r = cf.simulate(mech, revolutions=1, method="dop853", tolerance=1e-9, time_step=1e-4)
    theta = r["theta"]
    m = program().evaluate(theta)
    h, dh, ddh = m["h"], m["dh"], m["d2h"]
    R = 0.038 + h
    alpha = np.arctan2(dh, R)
    dalpha = (ddh * R - dh**2) / (R**2 + dh**2)
    arm = np.cos(alpha) * dh - np.sin(alpha) * dalpha * (h - r.q[:, 0])
    np.testing.assert_allclose(r["drive.torque"], r["cam.force"] * arm, rtol=1e-9, atol=1e-9)
    assert r["drive.torque"].max() > 1.0 and r["drive.torque"].min() < -1.0  # drives the rise, driven on the return


def test_a_modulated_speed_has_a_periodic_steady_state_and_a_run_up_has_none():
    b = follower(damping_factor=5e-3)
    b.speed_program = cf.SpeedProgram(500 * RPM, [], cf.SpeedModulation(0.15, 2, 0.3))
    mech = b.build()
    assert mech.periodic and mech.camshaft_speed_rpm == pytest.approx(500.0)
    settings = cf.SolverSettings(method="dop853", tolerance=1e-10, time_step=1e-4)
    orbit = cf.periodic_steady_state(mech, settings)
    assert orbit.converged
    # The orbit closes: one more revolution from its state returns to it.
    r = cf.simulate(mech, settings, duration=mech.period, initial_state=(orbit.q, orbit.v))
    assert abs(r.q[-1, 0] - orbit.q[0]) < 1e-8 * (1 + abs(orbit.q[0]))
    assert np.ptp(r["drive.speed"]) == pytest.approx(2 * 0.15 * 500 * RPM, rel=1e-3)

    up = run_up(follower()).build()
    assert not up.periodic
    with pytest.raises(ValueError, match="repeats every revolution"):
        cf.periodic_steady_state(up, time_step=1e-4)
    with pytest.raises(ValueError, match="repeats every revolution"):
        cf.simulate(up, revolutions=1, time_step=1e-4, settle=True)


def test_the_speed_program_pickles_scales_and_refuses_bad_input():
    p = cf.SpeedProgram(
        10.0, [cf.SpeedRamp(0.1, 0.4, 60.0), cf.SpeedRamp(1.0, 0.2, 0.0, "linear")], cf.SpeedModulation(0.1, 3, 0.2)
    )
    assert (
        eval(repr(p), {k: getattr(cf, k) for k in ("SpeedProgram", "SpeedRamp", "SpeedModulation")}).ramps[1].shape
        == "linear"
    )
    q = pickle.loads(pickle.dumps(p))
    t = np.linspace(0, 1.5, 31)
    np.testing.assert_array_equal(q.evaluate(t)["angle"], p.evaluate(t)["angle"])
    assert p.nominal_speed == 60.0 and not p.periodic

    b = run_up(follower())
    assert b.camshaft_speed_rpm == pytest.approx(600.0)
    mech = b.build()
    twice = mech.with_camshaft_speed_rpm(1200.0)
    np.testing.assert_allclose(twice.speed_program.evaluate(t)["speed"], 2 * mech.speed_program.evaluate(t)["speed"])
    again = pickle.loads(pickle.dumps(mech))
    np.testing.assert_array_equal(again.speed_program.evaluate(t)["angle"], mech.speed_program.evaluate(t)["angle"])
    b.speed_program = None
    assert b.build().speed_program.constant_speed

    with pytest.raises(ValueError, match="ramp 1 to_speed.*reversing"):
        cf.SpeedProgram(0.0, [cf.SpeedRamp(0, 1, -5.0)])
    with pytest.raises(ValueError, match="amplitude must be in"):
        cf.SpeedModulation(1.0, 1) and cf.SpeedProgram(10.0, [], cf.SpeedModulation(1.0, 1))
    with pytest.raises(ValueError, match="shape must be 'smooth' or 'linear'"):
        cf.SpeedRamp(0, 1, 5.0, "cubic")
    with pytest.raises(ValueError, match="never reached"):
        cf.SpeedProgram(0.0, [cf.SpeedRamp(0, 0.1, 10.0), cf.SpeedRamp(0.2, 0.1, 0.0)]).time_at_angle(100.0)


def config(**camshaft):
    return {
        "camshaft": {"speed": "600 rpm", **camshaft},
        "program": {
            "lift": {
                "segments": [
                    {"law": "dwell", "end": "30 deg"},
                    {"law": "cycloidal", "end": "150 deg", "h": "8 mm"},
                    {"law": "dwell", "end": "200 deg", "h": "8 mm"},
                    {"law": "cycloidal", "end": "360 deg", "h": 0},
                ]
            }
        },
        "dof": [{"name": "w", "mass": "0.2 kg"}],
        "spring": [{"name": "s", "a": "w", "stiffness": "20 N/mm", "preload": "150 N"}],
        "contact": [
            {
                "name": "cam",
                "program": "lift",
                "follower_dof": "w",
                "stiffness": 1e8,
                "follower": {"type": "translating_roller", "base_radius": "30 mm", "roller_radius": "8 mm"},
            }
        ],
    }


def test_the_config_reads_run_up_run_down_and_modulation():
    c = config_from_dict(
        config(
            run_up={"from": "60 rpm", "duration": "0.5 s", "start": "0.1 s"},
            run_down={"start": "2 s", "duration": "300 ms", "shape": "linear"},
        )
    )
    p = c.mechanism.speed_program
    assert p.initial_speed == pytest.approx(60 * RPM)
    assert [(r.start, r.duration, r.to_speed, r.shape) for r in p.ramps] == [
        (0.1, 0.5, pytest.approx(600 * RPM), "smooth"),
        (2.0, pytest.approx(0.3), 0.0, "linear"),
    ]
    c = config_from_dict(config(modulation={"amplitude": 0.1, "harmonic": 2, "phase": "90 deg"}))
    mod = c.mechanism.speed_program.modulation
    assert (mod.amplitude, mod.harmonic, mod.phase) == (0.1, 2, pytest.approx(math.pi / 2))
    assert config_from_dict(config()).mechanism.speed_program.constant_speed

    for bad, where in (
        ({"run_up": {"from": "700 rpm", "duration": "1 s"}}, "camshaft.run_up.from"),
        ({"run_up": {"duration": "0 s"}}, "camshaft.run_up.duration"),
        ({"run_up": {"duration": "1 s"}, "run_down": {"start": "0.5 s", "duration": "1 s"}}, "camshaft.run_down.start"),
        ({"run_down": {"start": "1 s", "duration": "1 s", "to": "-5 rpm"}}, "camshaft.run_down.to"),
        ({"modulation": {"amplitude": 1.0}}, "camshaft.modulation.amplitude"),
        ({"modulation": {"amplitude": 0.1, "harmonic": 0}}, "camshaft.modulation.harmonic"),
        ({"run_up": {"duration": "1 s", "shape": "cubic"}}, "camshaft.run_up.shape"),
        ({"run_up": {"duration": "1 s", "to": "600 rpm"}}, "camshaft.run_up.to"),
    ):
        with pytest.raises(ValueError, match=where.replace(".", r"\.")):
            config_from_dict(config(**bad))


def test_the_run_up_example_draws_the_drive(tmp_path):
    """examples/run_up.py runs and draws: the camshaft reaches 600 rpm at 0.4 s and the grooved roller
    first crosses to the outer flank on the way up."""
    import runpy
    from pathlib import Path

    script = Path(__file__).resolve().parents[2] / "examples" / "run_up.py"
    namespace = runpy.run_path(str(script))
    summary = namespace["main"](str(tmp_path / "run_up.png"))
    assert (tmp_path / "run_up.png").stat().st_size > 20_000
    case, mech, r = namespace["run"]()
    assert mech.camshaft_speed_rpm == pytest.approx(600.0) and not mech.periodic
    at = np.searchsorted(r.t, 0.4)
    assert r["drive.speed"][at] == pytest.approx(600 * RPM, rel=1e-9)
    first_outer = r.t[np.argmax(r["cam.outer_in_contact"] > 0)]
    assert 0.0 < first_outer < 0.4
    assert summary["peak_torque_N_m"] > 0.0 and summary["outer_flank_peak_N"] > 0.0
