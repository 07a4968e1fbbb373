# SPDX-License-Identifier: BSD-3-Clause
"""Hardening: output files that cannot be damaged, parameters that say what they accept, and the
other ways an adversarial user found to get a wrong answer silently or an unhelpful error."""

import json
import math
import os
import re
import stat
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest
from camfollower import _files

ROOT = Path(__file__).resolve().parents[2]

# --- output files: one writer, refusing what it must not replace -----------------------------------


def _writers(tmp_path):
    """Every public way the package writes a file, as f(path)."""
    result = cf.simulate(cf.presets.paper(), duration=1e-3, time_step=1e-5)
    follower, program = cf.TranslatingRoller(0.03, 0.01, 0.0), cf.MotionProgram.paper_default()
    return {
        "write_bytes": lambda p: _files.write_bytes(p, b"new"),
        "Result.save": lambda p: result.save(p),
        "export.write_csv": lambda p: cf.export.write_csv(p, follower, program, points=64),
    }


def _target(tmp_path, name):
    return tmp_path / (name + (".npz" if name == "Result.save" else ".csv"))


@pytest.mark.parametrize("writer", ["write_bytes", "Result.save", "export.write_csv"])
def test_writers_refuse_a_fifo_a_symlink_and_a_read_only_file(tmp_path, writer):
    write = _writers(tmp_path)[writer]
    target = _target(tmp_path, writer)

    os.mkfifo(target)
    with pytest.raises(ValueError, match="not a regular file"):
        write(target)
    assert stat.S_ISFIFO(os.lstat(target).st_mode)
    target.unlink()

    real = tmp_path / "real.bin"
    real.write_bytes(b"keep")
    target.symlink_to(real)
    with pytest.raises(ValueError, match="symbolic link"):
        write(target)
    assert target.is_symlink() and real.read_bytes() == b"keep"
    target.unlink()

    target.write_bytes(b"protected")
    target.chmod(0o444)  # refused even for root, who could write it
    with pytest.raises(ValueError, match="read-only"):
        write(target)
    assert target.read_bytes() == b"protected"
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([target.name, "real.bin"])  # no temporaries


def test_writer_refuses_a_device_and_names_the_parameter():
    with pytest.raises(
        ValueError, match=r"path: '/dev/null' exists and is not a regular file \(a FIFO, socket or device\)"
    ):
        _files.write_bytes("/dev/null", b"x")


def test_writer_refuses_a_nul_in_the_path(tmp_path):
    with pytest.raises(ValueError, match="NUL"):
        _files.write_bytes(str(tmp_path / "a\0b.csv"), b"x")
    assert not list(tmp_path.iterdir())  # nothing written at the truncated name "a"


def test_writer_never_replaces_an_input_file(tmp_path):
    config = tmp_path / "case.toml"
    config.write_text("[camshaft]\n")
    alias = tmp_path / "sub" / ".." / "case.toml"
    (tmp_path / "sub").mkdir()
    with pytest.raises(ValueError, match="is the input file .* itself"):
        _files.write_bytes(alias, b"x", protect=[config])
    assert config.read_text() == "[camshaft]\n"


def test_temporary_names_are_unique_and_leave_other_files_alone(tmp_path):
    bystander = tmp_path / ".out.csv.tmp"  # what a fixed temporary name would have clobbered
    bystander.write_text("someone else's")
    for k in range(3):
        _files.write_bytes(tmp_path / "out.csv", f"run {k}".encode())
    assert (tmp_path / "out.csv").read_text() == "run 2"
    assert bystander.read_text() == "someone else's"
    assert sorted(p.name for p in tmp_path.iterdir()) == [".out.csv.tmp", "out.csv"]


def test_a_failed_write_leaves_no_temporary_and_names_it(tmp_path):
    """A file-size limit makes write() fail half way: the target keeps its old content, the partial
    temporary is removed, and the message names the temporary as well as the target."""
    target = tmp_path / "big.bin"
    target.write_bytes(b"old")
    code = textwrap.dedent(f"""
        import resource, signal
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))
        from camfollower import _files
        try:
            _files.write_bytes({str(target)!r}, b"x" * 100000)
        except ValueError as e:
            print(e)
    """)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert (
        "writing the temporary" in out.stdout and "big.bin.tmp." in out.stdout and "'" + str(target) + "'" in out.stdout
    )
    assert target.read_bytes() == b"old"
    assert [p.name for p in tmp_path.iterdir()] == ["big.bin"]


def test_output_folder_removes_a_previous_summary_first(tmp_path):
    (tmp_path / "summary.json").write_text("{}")
    _files.output_folder(tmp_path)
    assert not (tmp_path / "summary.json").exists()
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(ValueError, match="--out: .* exists and is not a directory"):
        _files.output_folder(blocker)


def test_a_killed_study_leaves_no_summary_and_no_hidden_folders(tmp_path):
    """summary.json marks a complete run: the old one goes at the start, and nothing is staged."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "summary.json").write_text('{"from": "an earlier run"}')
    proc = subprocess.Popen(
        [sys.executable, "-m", "camfollower.study", "--out", str(out), "--no-figures"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        deadline = time.monotonic() + 60
        while (out / "summary.json").exists() and time.monotonic() < deadline:
            time.sleep(0.05)
        time.sleep(0.5)
        assert proc.poll() is None, "the study ended before it could be killed"
    finally:
        proc.kill()
        proc.wait(timeout=30)
    assert not (out / "summary.json").exists()
    assert not [p.name for p in out.rglob(".*")]


# --- parameters: every listed name readable and settable, numbers checked by name -------------------


def test_every_listed_parameter_round_trips_through_get_and_replace():
    p = cf.Parameters()
    assert set(p.to_dict()) == set(cf.Parameters.names())
    for name in cf.Parameters.names():
        value = p.get(name)
        assert p.replace(**{name: value}).get(name) == value
    q = p.replace(contact_damping="hunt_crossley")
    assert q.get("contact_damping") == "hunt_crossley" == q.contact_damping
    # The model reaches the preset's contact: chi = 3 (1 - c_e) / (2 v_ref) (Hunt-Crossley) or
    # 3 (1 - c_e^2) / (4 v_ref) (Lankarani-Nikravesh), docs/model.md.
    q = q.replace(restitution=0.8, reference_speed=2.0)
    (contact,) = cf.presets.paper(q).builder().contacts
    assert contact["damping_factor"] == pytest.approx(3 * (1 - 0.8) / (2 * 2.0), rel=1e-14)
    (contact,) = cf.presets.paper(q.replace(contact_damping="lankarani_nikravesh")).builder().contacts
    assert contact["damping_factor"] == pytest.approx(3 * (1 - 0.8**2) / (4 * 2.0), rel=1e-14)


@pytest.mark.parametrize(
    "make",
    [
        lambda v: cf.Parameters(contact_stiffness=v),
        lambda v: cf.Parameters().replace(contact_stiffness=v),
    ],
)
@pytest.mark.parametrize("value", ["1e8", b"1e8", True, None, [1e8]])
def test_a_non_number_is_a_type_error_naming_the_parameter(make, value):
    with pytest.raises(TypeError, match=r"contact_stiffness must be a number, got \w+"):
        make(value)


def test_numpy_scalars_are_numbers():
    assert cf.Parameters(contact_stiffness=np.float32(2e8)).contact_stiffness == pytest.approx(2e8)
    assert cf.Parameters(camshaft_speed_rpm=np.int64(900)).camshaft_speed_rpm == 900.0


def test_contact_damping_names_its_choices():
    with pytest.raises(
        ValueError, match="contact_damping must be 'none', 'hunt_crossley' or 'lankarani_nikravesh', got 'xnonex'"
    ):
        cf.Parameters(contact_damping="xnonex")
    with pytest.raises(TypeError, match="contact_damping must be"):
        cf.Parameters(contact_damping=0.5)


def test_an_overflowing_speed_names_the_speed_and_its_range():
    with pytest.raises(
        ValueError, match=r"camshaft_speed_rpm must be in \[9.5\d*e-06, 954\d+\.?\d*\] rpm, got 1e\+308"
    ):
        cf.presets.paper(cf.Parameters(camshaft_speed_rpm=1e308))
    with pytest.raises(ValueError, match="camshaft_speed_rpm must be in"):
        cf.presets.paper().with_camshaft_speed_rpm(1e308)
    with pytest.raises(ValueError, match=r"camshaft_speed_rpm must be in .* got 4.94\d*e-324"):  # infinite period
        cf.presets.paper(cf.Parameters(camshaft_speed_rpm=5e-324))


@pytest.mark.parametrize("stiffness,exponent", [(10.0, 1.5), (1.0, 1.0), (1e13, 1.0), (1e14, 1.5)])
def test_preload_calibration_holds_from_soft_to_rigid_contacts(stiffness, exponent):
    """Without gravity the follower chain at rest is held along its axis by the contact alone (the
    guide takes the lateral part), so the contact force's axial component F cos(pressure angle) at
    the static equilibrium equals the spring force, which calibration sets to K_rs delta_rs."""
    p = cf.Parameters(contact_stiffness=stiffness, contact_exponent=exponent, gravity=0.0)
    model = cf.presets.paper(p)
    q0 = np.array(model.initial_state)
    assert np.all(np.isfinite(q0))
    target = p.spring_stiffness * p.spring_preload_deflection
    # The contact force at the initial state as the run records it (first row: t = 0, at rest) ...
    r = cf.simulate(model, duration=1e-6, time_step=1e-6)
    assert r["t"][0] == 0.0
    force, alpha = r["cam.force"][0], r["cam.pressure_angle"][0]
    assert force * math.cos(alpha) == pytest.approx(target, rel=1e-6)
    # ... and from the paper's contact written out (docs/model.md): on the dwell h = h' = 0, so
    # alpha = atan(-e / s0) and delta = cos(alpha) (y1 - y2) - sin(alpha) (x1 - x2), F = K_h delta^n.
    y1, y2, x1, x2 = q0[0], q0[1], q0[4], q0[5]
    s0 = math.sqrt((p.base_radius + p.roller_radius) ** 2 - p.offset**2)
    a = math.atan(-p.offset / s0)
    assert alpha == pytest.approx(a, rel=1e-12)
    delta = math.cos(a) * (y1 - y2) - math.sin(a) * (x1 - x2)
    assert stiffness * delta**exponent * math.cos(a) == pytest.approx(target, rel=1e-6)


def _run_from(model, q, v):
    return cf.simulate(model, duration=1e-5, time_step=1e-6, initial_state=(q, v))


def test_non_finite_or_huge_initial_states_are_refused_naming_the_dof():
    model = cf.presets.paper()
    q, v = np.array(model.initial_state), np.zeros(7)
    for value in (np.nan, 1e300, -2e3):
        bad = q.copy()
        bad[1] = value
        with pytest.raises(ValueError, match=r"initial q\[1\] \(y2\) must be in \[-1000, 1000\]"):
            _run_from(model, bad, v)
    v[4] = np.inf
    with pytest.raises(ValueError, match=r"initial v\[4\] \(x1\) must be finite"):
        _run_from(model, q, v)
    # A start far off but within the bounds runs.
    near = q.copy()
    near[6] += 1e-7
    assert _run_from(model, near, np.zeros(7)).rows > 0


def test_runs_beyond_ten_billion_steps_are_refused_at_once():
    start = time.monotonic()
    with pytest.raises(ValueError, match=r"steps is too many \(limit 1e\+?10\)"):
        cf.simulate(cf.presets.paper(), duration=9.9e6, time_step=1e-6, decimation=10**12)
    assert time.monotonic() - start < 10.0


@pytest.mark.parametrize(
    "name,value,error",
    [
        ("decimation", 1.5, TypeError),
        ("decimation", True, TypeError),
        ("max_iterations", "25", TypeError),
        ("time_step", "3e-6", TypeError),
        ("settle_max_revolutions", 10**30, ValueError),
        ("linear_solver", 1, TypeError),
    ],
)
def test_simulate_names_a_bad_argument(name, value, error):
    with pytest.raises(error, match=name):
        cf.simulate(cf.presets.paper(), duration=1e-3, **{name: value})


def test_point_counts_are_bounded_before_any_memory_is_taken(tmp_path):
    follower, program = cf.TranslatingRoller(0.03, 0.01, 0.0), cf.MotionProgram.paper_default()
    limit = cf._core.MAX_POINTS
    with pytest.raises(ValueError, match=rf"points must be an integer in \[3, {limit}\]"):
        cf.export.profile_points(follower, program, points=10**12)
    with pytest.raises(ValueError, match="points must be an integer in"):
        cf.export.write_csv(tmp_path / "a.csv", follower, program, points=limit + 1)
    with pytest.raises(ValueError, match="points must be an integer in"):  # the core's own bound
        cf._core.write_cam_csv(str(tmp_path / "b.csv"), follower, program, 10**12, None, "mm")
    with pytest.raises(ValueError, match="points must be an integer in"):
        cf.motion.from_callable(lambda t: 0.0 * t, 0.0, 1.0, points=10**12)
    assert not list(tmp_path.iterdir())


def test_segments_spanning_less_than_a_microradian_are_refused():
    dw, cyc = cf.MotionLaw.dwell(), cf.MotionLaw.cycloidal()
    r0, r1 = math.pi - 9e-10, math.pi - 5e-10
    with pytest.raises(ValueError, match=r"segment spans .* at least 1e-06 rad"):
        cf.MotionProgram(
            [
                cf.Segment(dw, 0, math.pi, 0, 0),
                cf.Segment(cyc, r0, r1, 0, 1e-3),
                cf.Segment(dw, r1, 2 * math.pi - 0.5, 1e-3, 1e-3),
                cf.Segment(cyc, 2 * math.pi - 0.5, 2 * math.pi, 1e-3, 0),
            ]
        )
    with pytest.raises(ValueError, match=r"h_start/h_end must be in \[-1000, 1000\] m"):
        cf.MotionProgram([cf.Segment(cyc, 0, math.pi, 0, 1e154), cf.Segment(cyc, math.pi, 2 * math.pi, 1e154, 0)])


# --- analysis and study helpers: ValueError naming the argument, never IndexError or NaN ----------


def test_analysis_helpers_name_bad_arguments():
    from camfollower import analysis as an

    model = cf.presets.paper()
    cases = [
        (lambda: an.Spectrum(np.array([1.0]), np.array([1.0])), "frequency must be a 1-D array of at least 2"),
        (lambda: an.Spectrum(np.arange(3.0), np.arange(4.0)), "same length"),
        (lambda: an.last_revolutions({"t": [0.0]}, 0.1, 1), r"result\['t'\] must be a 1-D array of at least 2"),
        (lambda: an.last_revolutions({"t": [0.0, 1e-3, 2e-3]}, 1e308, 1), "one period"),
        (lambda: an.last_revolutions({"t": [0.0, 1e-3, 2e-3]}, 0.0, 1), "period must be finite and > 0"),
        (lambda: an.last_revolutions({"t": [0.0, 1e-3, 2e-3]}, 1e-3, 0), "revolutions must be an integer >= 1"),
        (lambda: an.theoretical_follower_acceleration("x", 0.0), "model must be a Mechanism"),
        (lambda: an.phase_statistics(model, [0.0, 1.0], [1.0]), "same length"),
        (lambda: an.phase_statistics(model, [], []), "theta must be a 1-D array of at least 1"),
        (lambda: an.phase_statistics(model, [0.1, 0.2], [1.0, 2.0]), "no sample of theta falls in the"),
        (lambda: an.contact_loss_intervals([0.0, 1.0], [True]), "same length"),
        (lambda: an.find_peaks(an.spectrum(np.ones(16), 100.0), count=0), "count must be an integer >= 1"),
        (lambda: an.sidebands(an.spectrum(np.ones(16), 100.0), 10.0, -1.0), "spacing must be finite and > 0"),
        (lambda: an.spectrum(np.ones(16), "fast"), "sample_rate must be a number"),
    ]
    for call, message in cases:
        with pytest.raises(ValueError, match=message):
            call()
    assert an.contact_loss_intervals([], []) == []
    theta = np.linspace(0, 2 * math.pi, 721)[:-1]
    stats = an.phase_statistics(model, theta, np.ones_like(theta))
    assert sum(s["samples"] for s in stats) == theta.size and all(s["peak"] == 1.0 for s in stats)
    huge = an.phase_statistics(model, theta, np.full_like(theta, -1e200))  # x^2 would overflow
    assert all(s["rms"] == pytest.approx(1e200) for s in huge)


def test_speed_helpers_name_bad_arguments():
    from camfollower import speed as sp

    m = cf.presets.paper()
    with pytest.raises(ValueError, match="speeds must be a sequence of camshaft speeds"):
        sp.margin_curve(m, 5)
    with pytest.raises(ValueError, match="speed_range must be a sequence"):
        sp.jump_speed(m, 5)
    with pytest.raises(ValueError, match="speeds must hold numbers"):
        sp.margin_curve(m, ["fast"])
    with pytest.raises(ValueError, match="sweep must be a speed_sweep"):
        sp.plot_waterfall({})


def test_study_tables_echo_short_printable_values_with_file_and_line(tmp_path):
    from camfollower.studies import montecarlo_settings, sweep_settings

    config = tmp_path / "case.toml"
    huge = "x" * 10_000_000
    config.write_text(f'[camshaft]\nspeed = "750 rpm"\n\n[sweep]\nrpm = ["{huge}"]\n')
    with pytest.raises(ValueError) as e:
        sweep_settings({"rpm": [huge]}, path=config)
    message = str(e.value)
    assert message.startswith(f"{config}:5: sweep.rpm[0]: must be a camshaft speed") and len(message) < 400
    with pytest.raises(ValueError) as e:
        sweep_settings({"rpm": [500.0], "bad\x1b[2Jkey" * 1000: 1}, path=None)
    assert "\x1b" not in str(e.value) and len(str(e.value)) < 600
    with pytest.raises(ValueError, match="not both"):
        sweep_settings({"rpm": [500.0], "count": 3})
    config.write_text(
        "[montecarlo]\ncases = 10\n\n[[montecarlo.tolerance]]\nparameter = \"a\"\n"
        "distribution = \"normal\"\nstd = 0.1\n\n[[montecarlo.tolerance]]\nparameter = \"b\"\n"
        "distribution = \"gamma\"\n"
    )
    with pytest.raises(ValueError, match=rf"^{config}:11: montecarlo.tolerance\[1\].distribution: must be one of"):
        montecarlo_settings(
            {
                "cases": 10,
                "tolerance": [
                    {"parameter": "a", "distribution": "normal", "std": 0.1},
                    {"parameter": "b", "distribution": "gamma"},
                ],
            },
            path=config,
        )


def test_a_run_reports_its_step_against_the_shortest_natural_period():
    """highest_mode_hz from the stepper's tangent at the start equals the modal analysis' highest
    frequency (a separate code path), and a coarse step shows as few steps per shortest period."""
    model = cf.presets.paper()
    highest = float(np.max(model.modal_analysis(0.0)["frequencies_hz"]))
    fine = cf.simulate(model, duration=2e-4, time_step=1e-6)
    assert fine.stats["highest_mode_hz"] == pytest.approx(highest, rel=1e-6)
    assert fine.stats["steps_per_shortest_period"] == pytest.approx(1.0 / (highest * 1e-6), rel=1e-6)
    coarse = cf.simulate(model, duration=model.period, time_step=model.period / 12)
    assert coarse.stats["steps_per_shortest_period"] < 0.1


def test_a_step_longer_than_the_run_or_a_twelfth_of_a_revolution_is_refused():
    model = cf.presets.paper()
    with pytest.raises(ValueError, match=r"time_step = 0.001 s is longer than the duration 0.0001 s"):
        cf.simulate(model, duration=1e-4, time_step=1e-3)
    with pytest.raises(ValueError, match="cannot resolve the cam's motion: it must be <="):
        cf.simulate(model, revolutions=2, time_step=model.period)


def test_no_error_message_carries_control_characters_or_megabytes():
    """Every message is sanitized where it is raised (detail::fail): a looked-up name is echoed with
    its control characters as '?' and cut at 1,000 bytes."""
    name = "\x07\x1b[2J" + "x" * 5_000_000
    builder = cf.MechanismBuilder()
    builder.add_dof("tappet", 0.1, [0, 1, 0])
    for call in (
        lambda: cf.Parameters().get(name),
        lambda: (builder.add_spring("spring", "tappet", name, stiffness=1e5), builder.build()),
        lambda: cf.simulate(cf.presets.paper(), duration=1e-4, linear_solver=name),
    ):
        with pytest.raises(ValueError) as e:
            call()
        text = str(e.value)
        assert "\x1b" not in text and "\x07" not in text and len(text) < 2000, text[:200]
        assert "?" in text and "bytes)" in text


def test_geometry_beyond_a_kilometre_is_refused():
    with pytest.raises(ValueError, match=r"base_radius must be finite and > 0 \(m\), in \[1e-06, 1000\] m"):
        cf.TranslatingRoller(5.6e102, 0.125, 0.0)
    with pytest.raises(ValueError, match="sample_rate = .* gives no usable frequency axis"):
        from camfollower import analysis

        analysis.spectrum(np.zeros(8), 2.2250738585072014e-308)


def test_an_output_cap_beyond_memory_is_capped_and_named_not_a_memory_error():
    with pytest.raises(ValueError, match=r"max_output_bytes = 1e\+300 B was capped at this machine's memory"):
        cf.simulate(cf.presets.paper(), duration=4e3, time_step=1e-6, max_output_bytes=1e300)


def test_a_config_speed_outside_the_models_range_names_the_file_and_line(tmp_path):
    text = (ROOT / "examples" / "swing_arm.toml").read_text()
    assert 'speed = "' in text
    lines = text.splitlines()
    k = next(i for i, line in enumerate(lines) if line.strip().startswith("speed ="))
    lines[k] = 'speed = "1e-320 rpm"'
    path = tmp_path / "slow.toml"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(
        ValueError, match=rf"slow.toml:{k + 1}: camshaft.speed: must be in \[9.5\d*e-06, 954\d*\.?\d*\] rpm"
    ):
        cf.load_config(path)


def test_a_spectrum_that_would_overflow_is_refused():
    from camfollower import analysis

    with pytest.raises(ValueError, match=r"signal: values up to 1.\d*e\+308 overflow the spectrum"):
        analysis.spectrum([0.0] * 6 + [1.6079056208947341e308, 0.0], 1.0)


def test_a_config_whose_mechanism_cannot_be_solved_names_the_file(tmp_path):
    """A contact of 1e300 N/m^n: its gap's rounding exceeds the static deflection, so the equilibrium
    cannot be found; the RuntimeError says which file (found by the long fuzz profile)."""
    text = (ROOT / "examples" / "oscillating_flat.toml").read_text()
    assert "stiffness = 1e8" in text
    path = tmp_path / "rigid.toml"
    path.write_text(text.replace("stiffness = 1e8", "stiffness = 1e300"))
    with pytest.raises(RuntimeError, match=r"rigid.toml: static equilibrium at theta = 0 deg did not converge"):
        cf.load_config(path)


def test_a_preset_whose_calibration_cannot_converge_names_the_file_and_table(tmp_path):
    """The paper preset calibrates its spring preload at build: a denormal preload deflection was a
    RuntimeError without the file (long fuzz profile); now the deflection is bounded like every
    length, and a preset that cannot be built says which file and table."""
    text = (ROOT / "examples" / "paper_studies.toml").read_text()
    lines = text.splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("spring_preload_deflection ="))
    lines[k] = "spring_preload_deflection = 1e-320"
    path = tmp_path / "denormal.toml"
    path.write_text("\n".join(lines) + "\n")
    # Located at the parameter's own line since the model's messages are matched to their keys.
    with pytest.raises(
        ValueError,
        match=rf"denormal.toml:{k + 1}: preset.parameters.spring_preload_deflection: must be "
        r"finite and > 0 \(m\), in \[1e-06, 1000\] m, got (1e-320|9.99\d*e-321)",
    ):
        cf.load_config(path)
    # A contact no double can balance (1e25 N/m): whichever check stops it, the message is located.
    lines[k] = "spring_preload_deflection = 0.013"
    c = next(i for i, line in enumerate(lines) if line.startswith("contact_stiffness ="))
    lines[c] = "contact_stiffness = 1e25"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises((ValueError, RuntimeError), match=r"denormal.toml:\d+: preset: static equilibrium"):
        cf.load_config(path)


# --- the command line (python -m camfollower): its output folder, its JSON, its arguments ------------


def _strict_json(path):
    """A summary parsed as RFC 8259 JSON: NaN, Infinity and -Infinity are not JSON."""

    def refuse(constant):
        raise ValueError(f"{path.name}: {constant} is not JSON")

    return json.loads(path.read_text(), parse_constant=refuse)


def _small_studies_config(folder: Path, name: str = "studies.toml") -> Path:
    """paper_studies.toml cut to one sweep speed (no jump) and two Monte-Carlo cases, coarse steps."""
    text = (ROOT / "examples" / "paper_studies.toml").read_text()
    start, end = text.index("[sweep]"), text.index("[montecarlo]")
    text = text[:start] + "[sweep]\nrpm = [700]\nsteps_per_revolution = 512\n\n" + text[end:]
    text = text.replace("cases = 200", "cases = 2\nsteps_per_revolution = 512")
    path = folder / name
    path.write_text(text)
    return path


@pytest.mark.parametrize("link", ["itself", "symlink", "hardlink", "summary_symlink"])
def test_the_output_folder_never_removes_the_runs_config(tmp_path, link):
    """output_folder removes an old summary.json; never when that is the config, or either links to
    the other (same device and inode)."""
    out = tmp_path / "out"
    out.mkdir()
    text = "[camshaft]\nspeed = \"600 rpm\"\n"
    if link == "summary_symlink":
        config = tmp_path / "case.toml"
        config.write_text(text)
        (out / "summary.json").symlink_to(config)
    else:
        (out / "summary.json").write_text(text)
        config = {
            "itself": out / "summary.json",
            "symlink": tmp_path / "case.toml",
            "hardlink": tmp_path / "case.toml",
        }[link]
        if link == "symlink":
            config.symlink_to(out / "summary.json")
        elif link == "hardlink":
            os.link(out / "summary.json", config)
    with pytest.raises(ValueError, match=r"--out: '.*summary.json' is the input file '.*' \(or a link to it\)"):
        _files.output_folder(out, protect=[config])
    assert config.read_text() == text
    (tmp_path / "other.toml").write_text(text)  # an unrelated input: the old summary goes as before
    _files.output_folder(out, protect=[tmp_path / "other.toml"])
    assert not (out / "summary.json").exists() and not (out / "summary.json").is_symlink()


@pytest.mark.parametrize("command", ["figures", "camshaft", "sweep", "montecarlo"])
def test_no_command_deletes_its_config_as_an_old_summary(tmp_path, capsys, command):
    from camfollower import cli

    out = tmp_path / "out"
    out.mkdir()
    config = _small_studies_config(out, "summary.json")
    text = config.read_text()
    assert (
        cli.main(
            [command, str(config), "-o", str(out)] + (["--no-progress"] if command in ("sweep", "montecarlo") else [])
        )
        == 1
    )
    err = capsys.readouterr().err
    assert err.startswith("camfollower: error: --out: ") and "is the input file" in err and str(config) in err
    assert config.read_text() == text
    assert sorted(p.name for p in out.iterdir()) == ["summary.json"]  # refused before anything ran


def test_an_output_folder_whose_name_is_not_utf8_is_refused_before_the_run(tmp_path):
    """argv bytes that are not UTF-8 arrive surrogate-escaped: the core's writer cannot take them, and
    pybind11's TypeError printed the whole run.csv after the run. Refused up front, naming --out."""
    out = os.fsencode(tmp_path) + b"/out\xff"
    config = ROOT / "examples" / "translating_roller.toml"
    t0 = time.perf_counter()
    run = subprocess.run(
        [sys.executable, "-m", "camfollower", "figures", str(config), "-o", out], capture_output=True, timeout=120
    )
    err = run.stderr.decode("utf-8", "replace")
    assert run.returncode == 2, err  # refused with the arguments: a usage error
    assert err.startswith("camfollower: error: --out: ") and "not valid UTF-8" in err and "out\\xff" in err
    assert "Traceback" not in err and len(err) < 1000
    assert not os.path.exists(out) and time.perf_counter() - t0 < 30  # no run, no folder


def test_paths_that_are_not_utf8_are_value_errors_without_the_content(tmp_path):
    """The same for the library: an output path with undecodable bytes is a ValueError naming the
    parameter, never a TypeError that echoes the file's content."""
    secret = "content that must not be echoed"
    with pytest.raises(ValueError, match=r"^path: the name .*out\\xff.csv' is not valid UTF-8") as e:
        _files.write_bytes(os.fsdecode(os.fsencode(tmp_path) + b"/out\xff.csv"), secret.encode() * 1000)
    assert secret not in str(e.value) and len(str(e.value)) < 1000
    with pytest.raises(ValueError, match=r"^--out: the name .* is not valid UTF-8"):
        _files.output_folder(os.fsdecode(os.fsencode(tmp_path) + b"/out\xff"))


def test_a_config_path_that_is_not_utf8_is_a_value_error_without_its_content(tmp_path):
    """load_config passed the surrogate-escaped name to the core, whose pybind11 TypeError echoed the
    whole config text."""
    name = os.fsdecode(os.fsencode(tmp_path) + b"/case\xff.toml")
    secret = "a line of the config that must not be echoed"
    Path(name).write_text(f"# {secret}\n" + (ROOT / "examples" / "translating_roller.toml").read_text())
    with pytest.raises(ValueError, match=r"config path .*case\\xff.toml' is not valid UTF-8") as e:
        cf.load_config(name)
    assert secret not in str(e.value) and len(str(e.value)) < 1000


def test_a_command_line_error_is_one_bounded_printable_message():
    from camfollower import cli

    text = cli._message(ValueError("\x1b[2J" + "x" * 1_000_000))
    assert text.startswith("?[2Jx") and len(text) < 2100 and "\x1b" not in text


def test_every_summary_the_commands_write_is_strict_json(tmp_path, capsys):
    """sweep wrote first_loss_angle_deg = NaN (contact kept): not JSON. Every summary is parsed here
    by a strict parser; a non-finite number is null."""
    from camfollower import cli

    config = _small_studies_config(tmp_path)
    assert cli.main(["sweep", str(config), "--workers", "1", "--no-progress", "-o", str(tmp_path / "sweep")]) == 0
    sweep = _strict_json(tmp_path / "sweep" / "summary.json")
    assert sweep["speeds"][0]["contact_lost"] is False and sweep["speeds"][0]["first_loss_angle_deg"] is None
    assert cli.main(["montecarlo", str(config), "--workers", "1", "--no-progress", "-o", str(tmp_path / "mc")]) == 0
    assert _strict_json(tmp_path / "mc" / "summary.json")["cases"] == 2
    assert cli.main(["figures", str(ROOT / "examples" / "translating_roller.toml"), "-o", str(tmp_path / "fig")]) == 0
    assert _strict_json(tmp_path / "fig" / "summary.json")["contacts"]["cam"]["contact_lost_s"] == 0.0
    assert "error" not in capsys.readouterr().err


def test_the_json_writer_is_strict_and_fails_loudly_on_what_it_cannot_write():
    text = _files.json_text(
        {
            "nan": math.nan,
            "inf": [np.float32("inf"), -math.inf],
            "n": np.int64(3),
            "a": np.array([1.5, np.nan]),
            "ok": np.bool_(True),
            7: (1, 2.5),
        }
    )
    assert json.loads(text, parse_constant=lambda c: pytest.fail(c)) == {
        "nan": None,
        "inf": [None, None],
        "n": 3,
        "a": [1.5, None],
        "ok": True,
        "7": [1, 2.5],
    }
    with pytest.raises(TypeError, match="not JSON serializable"):
        _files.json_text({"x": object()})


def test_a_saved_result_holds_strict_json_and_reads_back_nan(tmp_path):
    result = cf.simulate(cf.presets.paper(), duration=1e-3, time_step=1e-5)
    result.settle = {"settled": False, "revolutions": 3, "change": math.nan, "history": [math.inf, 0.5]}
    path = result.save(tmp_path / "r.npz")
    with np.load(path) as z:
        for key in ("settle", "events", "stats_text"):
            json.loads(str(z[key]), parse_constant=lambda c: pytest.fail(f"{key}: {c}"))
    back = cf.Result.load(path).settle
    assert back["settled"] is False and math.isnan(back["change"]) and math.isnan(back["history"][0])
    assert back["history"][1] == 0.5


_MISSING = "no-such-config.toml"  # an argument checked first is refused before the config is read


@pytest.mark.parametrize(
    "argv, message",
    [
        (["camshaft", _MISSING, "--engine-rpm", "-1"], r"--engine-rpm: -1 is not an engine speed in \[.*\] rpm"),
        (["camshaft", _MISSING, "--rpm", "nan"], r"--rpm: nan is not a camshaft speed in \[.*\] rpm"),
        (["camshaft", _MISSING, "--rpm", "1000", "--engine-rpm", "2000"], "give --rpm .* or --engine-rpm .*, not both"),
        (
            ["camshaft", _MISSING, "--revolutions", "0"],
            r"--revolutions: 0 is not a number of camshaft revolutions in \(0, ",
        ),
        (["camshaft", _MISSING, "--revolutions", "inf"], r"--revolutions: inf is not"),
        (["sweep", _MISSING, "--jump", "2000", "1000"], "--jump: LO 2000 must be below HI 1000 rpm"),
        (["sweep", _MISSING, "--jump", "nan", "1000"], r"--jump: nan is not a camshaft speed in \["),
        (["sweep", _MISSING, "--rpm", "1e308"], r"--rpm: 1e\+308 is not a camshaft speed in \["),
        (["sweep", _MISSING, "--workers", "0"], r"--workers: 0 is not in \[1, "),
        (["sweep", _MISSING, "--scheduler", " "], "--scheduler: give a Dask scheduler address"),
        (
            ["montecarlo", _MISSING, "--workers", "2", "--scheduler", "dask:2"],
            "give --workers .* or --scheduler .*, not both",
        ),
        (["montecarlo", _MISSING, "--cases", "0"], r"--cases: 0 is not in \[1, 10000000\]"),
        (["montecarlo", _MISSING, "--seed", "-1"], r"--seed: -1 is not in \[0, "),
        (["figures", _MISSING, "-o", "a\0b"], "--out: the path contains a NUL character"),
    ],
)
def test_every_command_line_argument_is_checked_before_anything_runs(tmp_path, capsys, monkeypatch, argv, message):
    from camfollower import cli

    monkeypatch.chdir(tmp_path)
    assert cli.main(argv) == 2  # a usage error, as in the C++ program
    err = capsys.readouterr().err
    assert re.match("camfollower: error: " + message, err) and err.count("\n") == 1, err
    assert not (tmp_path / "out").exists()


def test_study_settings_check_a_whole_bracket_and_the_overrides_before_any_run(monkeypatch):
    from camfollower import camshaft as cs
    from camfollower import simulation
    from camfollower.studies import montecarlo_settings, sweep_settings

    with pytest.raises(ValueError, match=r"^sweep.jump: the low speed 2000 must be below the high speed 1000 rpm"):
        sweep_settings({"rpm": [700], "jump": [2000, 1000]})
    with pytest.raises(ValueError, match=r"^--jump: must be a camshaft speed"):
        sweep_settings({"rpm": [700], "jump": [1000, 2000]}, jump=[math.nan, 1000])
    table = {"tolerance": [{"parameter": "a", "distribution": "normal", "std": 0.1}]}
    for kw, name in (({"cases": 0}, "--cases"), ({"seed": -1}, "--seed"), ({"cases": 2.5}, "--cases")):
        with pytest.raises(ValueError, match=f"^{name}: must be an integer in"):
            montecarlo_settings(table, **kw)
    monkeypatch.setattr(simulation, "simulate", lambda *a, **k: pytest.fail("a speed ran before all were checked"))
    with pytest.raises(ValueError, match="rpm: camshaft speeds must be finite and > 0, got nan"):
        cs.camshaft_study(cf.load_config(ROOT / "examples" / "camshaft.toml"), [1000.0, math.nan])


# --- the C++ command line (src/main.cpp, CLI11): numeric options, usage errors, exit status -----------

_CPP_CLI = next(
    (
        p
        for p in (ROOT / "build-sanitize" / "src" / "camfollower", ROOT / "build" / "src" / "camfollower")
        if p.exists()
    ),
    ROOT / "build-sanitize" / "src" / "camfollower",
)


def _cpp_cli(*args, cwd=None):
    return subprocess.run([str(_CPP_CLI), *map(str, args)], capture_output=True, text=True, timeout=120, cwd=cwd)


@pytest.mark.skipif(not _CPP_CLI.exists(), reason="the command line is built by scripts/test.sh (ctest)")
@pytest.mark.parametrize(
    "args, message",
    [
        (["kinematics", "--rpm", "nan"], r"--rpm: nan is not a camshaft speed in \[9.5493e-06, 954930\] rpm"),
        (["kinematics", "--rpm", "1e308"], r"--rpm: 1e\+308 is not a camshaft speed in \[9.5493e-06, 954930\] rpm"),
        (["kinematics", "--rpm", "-5"], r"--rpm: -5 is not a camshaft speed in \["),
        (["modes", "--theta", "inf"], r"--theta: inf is not a cam angle in \[-1000000, 1000000\] deg"),
        (["modes", "--count", "0"], r"--count: 0 is not a number of modes in \[1, 100000\]"),
        (
            ["export", "{flat}", "-o", "{tmp}/cam.csv", "--cutter-radius", "nan"],
            r"--cutter-radius: nan is not a radius >= 0",
        ),
        (
            ["export", "{flat}", "-o", "{tmp}/cam.csv", "--cutter-radius", "-1"],
            r"--cutter-radius: -1 is not a radius >= 0",
        ),
        (
            ["export", "{flat}", "-o", "{tmp}/cam.csv", "--cutter-radius", "2e6"],
            r"--cutter-radius: 2000000 is not a radius in \[0, 1000000\] mm",
        ),
        (
            ["export", "{flat}", "-o", "{tmp}/cam.csv", "--points", "-5"],
            r"--points: -5 is not a number of points in \[8, 10000000\]",
        ),
        (["run", "{flat}", "-o", ""], r"-o/--output: must name a file, got an empty string"),
        (["export", "{flat}", "-o", ""], r"-o/--output: must name a file, got an empty string"),
        (["export", "{flat}", "-o", "{tmp}/cam.DXF"], r"-o/--output: this program writes the cam as CSV; for DXF"),
        (["run"], r"config is required"),
        (["run", "{flat}", "--bogus"], r"The following argument"),
        (["kinematics", "--rpm", "fast"], r"(Could not convert|--rpm).*fast"),
        ([], r"A subcommand is required"),
    ],
)
def test_cpp_command_line_errors_are_named_usage_errors(tmp_path, args, message):
    """NaN passed CLI11's range checks (--cutter-radius nan silently wrote no cutter path), 1e308 rpm
    was taken, -o "" wrote the config's own output file, and parse errors went out without the
    prefix, with CLI11's exit codes (105, 106, 109) and DBL_MAX in 309 digits."""
    flat = ROOT / "examples" / "flat_faced_table.toml"
    r = _cpp_cli(*[a.format(flat=flat, tmp=tmp_path) for a in args], cwd=tmp_path)
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert re.match("camfollower: error: " + message, r.stderr) and r.stderr.count("\n") == 1, r.stderr
    assert len(r.stderr) < 300 and not list(tmp_path.iterdir())  # nothing written, not even the default file


@pytest.mark.skipif(not _CPP_CLI.exists(), reason="the command line is built by scripts/test.sh (ctest)")
def test_cpp_command_line_help_and_run_errors_keep_their_status(tmp_path):
    help_ = _cpp_cli("--help")
    assert (
        help_.returncode == 0
        and "Exit status: 0 done, 1 the config or the run failed, 2 a command-line" in help_.stdout
    )
    assert _cpp_cli("run", "--help").returncode == 0
    bad = tmp_path / "bad.toml"
    bad.write_text("[camshaft]\nspeed = \"fast\"\n")
    r = _cpp_cli("run", bad, "-o", tmp_path / "x.csv")
    assert r.returncode == 1 and r.stderr.startswith("camfollower: error: ") and "bad.toml" in r.stderr
    ok = _cpp_cli("kinematics", ROOT / "examples" / "flat_faced_table.toml", "--rpm", "954929")
    assert ok.returncode == 0 and "at 954929 rpm" in ok.stdout


@pytest.mark.parametrize("radius", [5.4861240687936856e303, 1e300, 1001.0, math.inf, math.nan])
def test_an_absurd_eccentricity_radius_is_refused_by_name(radius):
    # Found by the property test: a radius near the largest double overflowed the pitch-curve geometry,
    # and the refusal named theta ("theta must be finite, got inf") instead of the radius.
    with pytest.raises(ValueError, match=r"eccentricity radius must be in \[0, 1000\] m, got "):
        cf.presets.paper(eccentricity=cf.CamEccentricity(radius=radius, formulation="exact"), paper_backlash=0.0)
