# SPDX-License-Identifier: BSD-3-Clause
"""Flexible camshafts from Python and from config files: the builder against a config describing the
same shaft, the sparse backend against the dense one, pickling, the valve-train preset, the lowest
modes against the full solver, the camshaft study command, and bad input."""

import json
import math
import pickle
import subprocess
import sys
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest
from camfollower.camshaft import camshaft_study
from camfollower.config import load_config

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def two_cam_shaft(contact_damping=0.0, max_element_length=0.012):
    """The shaft of examples/camshaft.toml, built in Python."""
    program = load_config(EXAMPLES / "camshaft.toml").programs["valve"]
    b = cf.MechanismBuilder()
    b.set_gravity([0, 0, 9.81])
    # In the config reader's order: DOFs, the shaft, bearings, drive, spring chains, contacts.
    for k in (1, 2):
        b.add_dof(f"valve{k}", 0.085, [0, 0, 1])
    b.add_shaft(
        "camshaft",
        length=0.176,
        outer_diameter=0.026,
        inner_diameter=0.012,
        max_element_length=max_element_length,
        stations=[0.0, 0.088, 0.176, 0.044, 0.132],
        damping=5e-6,
    )
    for name, x in (("front", 0.0), ("middle", 0.088), ("rear", 0.176)):
        b.add_bearing(name, "camshaft", x, stiffness=2e8, damping=400)
    b.add_drive("drive", "camshaft", 0.0, stiffness=6000, damping=1.5)
    b.add_mass(b.shaft_dof("camshaft", 0.0, "rx"), 1.5e-3)
    for k in (1, 2):
        b.add_spring_chain(
            f"spring{k}",
            f"valve{k}",
            stiffness=4.5e4,
            mass=0.045,
            elements=6,
            damping=2.5,
            preload=280,
            direction=[0, 0, 1],
        )
    law = cf.LineContact.palmgren_law(0.012)
    for k, (x, phase) in enumerate(((0.044, 0.0), (0.132, math.pi)), start=1):
        b.mount_cam(
            f"cam{k}",
            program,
            cf.TranslatingRoller(0.018, 0.009, 0.0),
            follower_dof=f"valve{k}",
            shaft="camshaft",
            at=x,
            stiffness=law["stiffness"],
            exponent=law["exponent"],
            damping_factor=contact_damping,
            phase=phase,
            width=0.016,
            cam_mass=0.09,
            cam_inertia=1.8e-5,
        )
    b.camshaft_speed_rpm = 2000
    return b


def test_the_config_and_the_python_builder_describe_the_same_camshaft():
    case = load_config(EXAMPLES / "camshaft.toml")
    m, mine = case.mechanism, two_cam_shaft().build()
    assert m.dof_names == mine.dof_names
    assert "camshaft.0.rx" in m.dof_names and "spring1.5" in m.dof_names
    np.testing.assert_allclose(m.mass, mine.mass, rtol=0, atol=1e-15)
    np.testing.assert_allclose(m.stiffness, mine.stiffness, rtol=1e-15, atol=1e-6)
    np.testing.assert_allclose(m.initial_state, mine.initial_state, rtol=1e-12, atol=1e-15)


def test_sparse_and_dense_backends_agree_and_say_which_ran():
    m = two_cam_shaft(contact_damping=1e-5, max_element_length=0.005).build()
    assert m.size > 100
    runs = {
        solver: cf.simulate(m, revolutions=0.1, time_step=2e-5, linear_solver=solver)
        for solver in ("auto", "low_rank", "klu")
    }
    assert runs["auto"].stats["backend"] == "sparse"
    assert runs["low_rank"].stats["backend"] == "dense"
    assert runs["klu"].stats["backend"] == "sparse"
    q = np.asarray(runs["low_rank"].q)
    for solver in ("auto", "klu"):
        assert np.abs(np.asarray(runs[solver].q) - q).max() <= 1e-9 * np.abs(q).max()
    # Each cam's angle carries the shaft's twist; its moment is recorded.
    twist = np.asarray(runs["auto"]["cam1.cam_angle"]) - m.omega * np.asarray(runs["auto"].t)
    assert 0 < np.abs(twist).max() < math.radians(1.0)
    assert np.isfinite(runs["auto"]["cam1.cam_torque"]).all()


def test_sparse_and_dense_backends_agree_under_a_tolerance():
    # Newmark under a tolerance on the sparse backend: the same levels, the same steps, the same run.
    m = two_cam_shaft(contact_damping=1e-5, max_element_length=0.005).build()
    runs = {
        solver: cf.simulate(m, revolutions=0.1, time_step=1e-4, linear_solver=solver, tolerance=1e-5)
        for solver in ("auto", "low_rank")
    }
    assert runs["auto"].stats["backend"] == "sparse" and runs["low_rank"].stats["backend"] == "dense"
    assert runs["auto"].stats["steps"] == runs["low_rank"].stats["steps"] > 0
    q = np.asarray(runs["low_rank"].q)
    assert np.abs(np.asarray(runs["auto"].q) - q).max() <= 1e-9 * np.abs(q).max()


def test_a_camshaft_mechanism_pickles_to_the_same_model():
    m = two_cam_shaft().build()
    back = pickle.loads(pickle.dumps(m))
    assert back.dof_names == m.dof_names
    np.testing.assert_array_equal(back.mass, m.mass)
    np.testing.assert_array_equal(back.stiffness, m.stiffness)
    np.testing.assert_array_equal(back.initial_state, m.initial_state)


def test_valve_train_preset_and_its_lowest_modes():
    m = cf.presets.valve_train(engine_speed_rpm=5000, cylinders=3, firing_order=[1, 3, 2])
    assert m.contact_names == ["c1v1", "c1v2", "c2v1", "c2v2", "c3v1", "c3v2"]
    assert m.camshaft_speed_rpm == pytest.approx(2500)
    freqs, shapes = m.lowest_modes(0.0, 8)
    full = m.modal_analysis(0.0)["frequencies_hz"]
    np.testing.assert_allclose(freqs, full[:8], rtol=1e-8)
    np.testing.assert_allclose(np.einsum("ik,ij,jk->k", shapes, m.mass, shapes), 1.0, rtol=1e-8)
    with pytest.raises(ValueError, match="unknown valve-train parameter 'bore'"):
        cf.presets.valve_train(bore=0.08)
    with pytest.raises(ValueError, match="firing_order must list each cylinder 1..4 once"):
        cf.presets.valve_train(firing_order=[1, 2, 2, 4])
    assert cf.presets.VALVE_TRAIN_PARAMETERS["spring_stiffness"] == "N/m"


def test_bad_camshaft_input_names_the_part():
    b = cf.MechanismBuilder()
    b.add_shaft("s", length=0.3, outer_diameter=0.025, stations=[0.1])
    with pytest.raises(ValueError, match="shaft 's' has no node at x = 0.2 m"):
        b.add_bearing("b", "s", 0.2, stiffness=1e8)
    with pytest.raises(ValueError, match="inner diameter must be < outer diameter"):
        b.add_shaft("t", length=0.3, outer_diameter=0.025, inner_diameter=0.03)
    with pytest.raises(ValueError, match="elements of spring chain 'k' must be in \\[1, 1000\\]"):
        b.add_dof("v", 0.1)
        b.add_spring_chain("k", "v", stiffness=1e4, mass=0.01, elements=0)
    with pytest.raises(ValueError, match="dof must be one of"):
        b.shaft_dof("s", 0.1, "twist")


def test_config_camshaft_blocks_refuse_misplaced_keys(tmp_path):
    text = (EXAMPLES / "camshaft.toml").read_text()
    bad = text.replace('follower_dof = "valve1"', 'follower_dof = "valve1"\ncam_x = "camshaft.1.uy"', 1)
    path = tmp_path / "bad.toml"
    path.write_text(bad)
    with pytest.raises(ValueError, match="cam_x: is the shaft's node DOF for a cam mounted on a shaft"):
        load_config(path)
    far = text.replace('at = "132 mm"', 'at = "300 mm"')
    path.write_text(far)
    with pytest.raises(ValueError, match="outside the shaft"):
        load_config(path)


def test_camshaft_study_command_writes_its_table_figures_and_summary(tmp_path):
    out = tmp_path / "study"
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "camfollower",
            "camshaft",
            str(EXAMPLES / "camshaft.toml"),
            "--rpm",
            "1000",
            "2500",
            "--revolutions",
            "1",
            "-o",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stderr
    assert "1000 rpm: lift error" in done.stdout and "drive torque" in done.stdout
    summary = json.loads((out / "summary.json").read_text())
    assert [s["camshaft_speed_rpm"] for s in summary["speeds"]] == pytest.approx([1000, 2500], rel=1e-12)
    assert {"summary.csv", "study.png", "traces_1000rpm.png", "traces_2500rpm.png"} <= set(summary["files"])
    slow, fast = (s["cams"]["cam1"] for s in summary["speeds"])
    # Faster: larger inertia loads (the valve's acceleration grows as the speed squared), so a larger
    # peak contact force and a larger lift error; the force never drops below the spring's preload
    # region at these speeds.
    assert fast["max_force_N"] > slow["max_force_N"]
    assert fast["lift_error_mm"] > slow["lift_error_mm"]
    assert fast["min_force_lifting_N"] > 100.0 and fast["contact_lost_s"] == 0.0
    assert 0 < slow["twist_peak_to_peak_deg"] < 1.0
    assert len((out / "summary.csv").read_text().splitlines()) == 1 + 2 * 2


def test_camshaft_study_api_on_a_mechanism():
    summaries, results = camshaft_study(
        two_cam_shaft(max_element_length=0.005).build(),
        [1500.0],
        revolutions=0.5,
        record_last_revolutions=0.25,
        time_step=2e-5,
    )
    s = summaries[0]
    assert s["backend"] == "sparse"
    assert set(s["cams"]) == {"cam1", "cam2"} and set(s["bearings"]) == {"front", "middle", "rear"}
    assert s["drives"]["drive"]["torque_peak_to_peak_Nm"] > 0
    with pytest.raises(ValueError, match="rpm: camshaft speeds must be finite and > 0"):
        camshaft_study(two_cam_shaft().build(), [-5.0])
