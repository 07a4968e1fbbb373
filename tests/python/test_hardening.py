# SPDX-License-Identifier: BSD-3-Clause
"""Hardening: output files that cannot be damaged, parameters that say what they accept, and the
other ways an adversarial user found to get a wrong answer silently or an unhelpful error."""

import math
import os
import stat
import subprocess
import sys
import textwrap
import time

from pathlib import Path

import numpy as np
import pytest

import camfollower as cf
from camfollower import _files

ROOT = Path(__file__).resolve().parents[2]

# --- output files: one writer, refusing what it must not replace -----------------------------------


def _writers(tmp_path):
    """Every public way the package writes a file, as f(path)."""
    result = cf.simulate(cf.CamFollowerModel(), duration=1e-3, time_step=1e-5)
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
    with pytest.raises(ValueError, match=r"path: '/dev/null' exists and is not a regular file \(a FIFO, socket or device\)"):
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
    assert "writing the temporary" in out.stdout and "big.bin.tmp." in out.stdout and "'" + str(target) + "'" in out.stdout
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
    proc = subprocess.Popen([sys.executable, "-m", "camfollower.study", "--out", str(out), "--no-figures"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
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
    assert cf.CamFollowerModel(q).parameters.contact_damping == "hunt_crossley"
    model = cf.CamFollowerModel().with_parameters(contact_damping="lankarani_nikravesh")
    assert model.parameters.contact_damping == "lankarani_nikravesh"


@pytest.mark.parametrize("make", [
    lambda v: cf.Parameters(contact_stiffness=v),
    lambda v: cf.Parameters().replace(contact_stiffness=v),
    lambda v: cf.CamFollowerModel().with_parameters(contact_stiffness=v),
])
@pytest.mark.parametrize("value", ["1e8", b"1e8", True, None, [1e8]])
def test_a_non_number_is_a_type_error_naming_the_parameter(make, value):
    with pytest.raises(TypeError, match=r"contact_stiffness must be a number, got \w+"):
        make(value)


def test_numpy_scalars_are_numbers():
    assert cf.Parameters(contact_stiffness=np.float32(2e8)).contact_stiffness == pytest.approx(2e8)
    assert cf.Parameters(camshaft_speed_rpm=np.int64(900)).camshaft_speed_rpm == 900.0


def test_contact_damping_names_its_choices():
    with pytest.raises(ValueError, match="contact_damping must be 'none', 'hunt_crossley' or 'lankarani_nikravesh', got 'xnonex'"):
        cf.Parameters(contact_damping="xnonex")
    with pytest.raises(TypeError, match="contact_damping must be"):
        cf.Parameters(contact_damping=0.5)


def test_an_overflowing_speed_names_the_speed_and_its_range():
    with pytest.raises(ValueError, match=r"camshaft_speed_rpm must be in \[9.5\d*e-06, 954\d+\.?\d*\] rpm, got 1e\+308"):
        cf.CamFollowerModel(cf.Parameters(camshaft_speed_rpm=1e308))
    with pytest.raises(ValueError, match="camshaft_speed_rpm must be in"):
        cf.presets.paper().with_camshaft_speed_rpm(1e308)
    with pytest.raises(ValueError, match=r"camshaft_speed_rpm must be in .* got 4.94\d*e-324"):  # infinite period
        cf.CamFollowerModel(cf.Parameters(camshaft_speed_rpm=5e-324))


@pytest.mark.parametrize("stiffness,exponent", [(10.0, 1.5), (1.0, 1.0), (1e13, 1.0), (1e14, 1.5)])
def test_preload_calibration_holds_from_soft_to_rigid_contacts(stiffness, exponent):
    """Without gravity the follower chain at rest is held along its axis by the contact alone (the
    guide takes the lateral part), so the contact force's axial component F cos(pressure angle) at
    the static equilibrium equals the spring force, which calibration sets to K_rs delta_rs."""
    p = cf.Parameters(contact_stiffness=stiffness, contact_exponent=exponent, gravity=0.0)
    model = cf.CamFollowerModel(p)
    q0 = model.initial_state
    assert np.all(np.isfinite(q0))
    c = model.contact(0.0, q0, np.zeros(7))
    target = p.spring_stiffness * p.spring_preload_deflection
    assert c["force"] * math.cos(c["pressure_angle"]) == pytest.approx(target, rel=1e-6)


def test_contact_refuses_non_finite_states():
    model = cf.CamFollowerModel()
    q, v = model.initial_state, np.zeros(7)
    bad = q.copy()
    bad[1] = np.nan
    with pytest.raises(ValueError, match=r"q\[1\] \(y2\) must be in"):
        model.contact(0.0, bad, v)
    bad[1] = 1e300
    with pytest.raises(ValueError, match=r"q\[1\]"):
        model.contact(0.0, bad, v)
    v[4] = np.inf
    with pytest.raises(ValueError, match=r"v\[4\] \(x1\) must be finite"):
        model.contact(0.0, q, v)


def test_runs_beyond_ten_billion_steps_are_refused_at_once():
    start = time.monotonic()
    with pytest.raises(ValueError, match=r"steps is too many \(limit 1e\+?10\)"):
        cf.simulate(cf.CamFollowerModel(), duration=9.9e6, time_step=1e-6, decimation=10**12)
    assert time.monotonic() - start < 10.0


@pytest.mark.parametrize("name,value,error", [
    ("decimation", 1.5, TypeError), ("decimation", True, TypeError), ("max_iterations", "25", TypeError),
    ("time_step", "3e-6", TypeError), ("settle_max_revolutions", 10**30, ValueError), ("linear_solver", 1, TypeError),
])
def test_simulate_names_a_bad_argument(name, value, error):
    with pytest.raises(error, match=name):
        cf.simulate(cf.CamFollowerModel(), duration=1e-3, **{name: value})


def test_point_counts_are_bounded_before_any_memory_is_taken(tmp_path):
    follower, program = cf.TranslatingRoller(0.03, 0.01, 0.0), cf.MotionProgram.paper_default()
    limit = cf._core.MAX_POINTS
    with pytest.raises(ValueError, match=rf"points must be an integer in \[3, {limit}\]"):
        cf.export.profile_points(follower, program, points=10**12)
    with pytest.raises(ValueError, match="points must be an integer in"):
        cf.export.write_csv(tmp_path / "a.csv", follower, program, points=limit + 1)
    with pytest.raises(ValueError, match="points must be an integer in"):
        cf.DiskCam().write_surface_csv(str(tmp_path / "b.csv"), 10**12)
    with pytest.raises(ValueError, match="points must be an integer in"):
        cf.motion.from_callable(lambda t: 0.0 * t, 0.0, 1.0, points=10**12)
    assert not list(tmp_path.iterdir())


def test_segments_spanning_less_than_a_microradian_are_refused():
    dw, cyc = cf.MotionLaw.dwell(), cf.MotionLaw.cycloidal()
    r0, r1 = math.pi - 9e-10, math.pi - 5e-10
    with pytest.raises(ValueError, match=r"segments\[1\] spans .* at least 1e-06 rad"):
        cf.MotionProgram([cf.Segment(dw, 0, math.pi, 0, 0), cf.Segment(cyc, r0, r1, 0, 1e-3),
                          cf.Segment(dw, r1, 2 * math.pi - 0.5, 1e-3, 1e-3),
                          cf.Segment(cyc, 2 * math.pi - 0.5, 2 * math.pi, 1e-3, 0)])
    with pytest.raises(ValueError, match=r"h_start/h_end must be in \[-1000, 1000\] m"):
        cf.MotionProgram([cf.Segment(cyc, 0, math.pi, 0, 1e154), cf.Segment(cyc, math.pi, 2 * math.pi, 1e154, 0)])


# --- analysis and study helpers: ValueError naming the argument, never IndexError or NaN ----------


def test_analysis_helpers_name_bad_arguments():
    from camfollower import analysis as an
    model = cf.CamFollowerModel()
    cases = [
        (lambda: an.Spectrum(np.array([1.0]), np.array([1.0])), "frequency must be a 1-D array of at least 2"),
        (lambda: an.Spectrum(np.arange(3.0), np.arange(4.0)), "same length"),
        (lambda: an.last_revolutions({"t": [0.0]}, 0.1, 1), r"result\['t'\] must be a 1-D array of at least 2"),
        (lambda: an.last_revolutions({"t": [0.0, 1e-3, 2e-3]}, 1e308, 1), "one period"),
        (lambda: an.last_revolutions({"t": [0.0, 1e-3, 2e-3]}, 0.0, 1), "period must be finite and > 0"),
        (lambda: an.last_revolutions({"t": [0.0, 1e-3, 2e-3]}, 1e-3, 0), "revolutions must be an integer >= 1"),
        (lambda: an.theoretical_follower_acceleration("x", 0.0), "model must be a CamFollowerModel"),
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
    with pytest.raises(ValueError, match="bracket must be a sequence"):
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
    config.write_text("[montecarlo]\ncases = 10\n\n[[montecarlo.tolerance]]\nparameter = \"a\"\n"
                      "distribution = \"normal\"\nstd = 0.1\n\n[[montecarlo.tolerance]]\nparameter = \"b\"\n"
                      "distribution = \"gamma\"\n")
    with pytest.raises(ValueError, match=rf"^{config}:11: montecarlo.tolerance\[1\].distribution: must be one of"):
        montecarlo_settings({"cases": 10, "tolerance": [{"parameter": "a", "distribution": "normal", "std": 0.1},
                                                         {"parameter": "b", "distribution": "gamma"}]}, path=config)


def test_a_run_reports_its_step_against_the_shortest_natural_period():
    """highest_mode_hz from the stepper's tangent at the start equals the modal analysis' highest
    frequency (a separate code path), and a coarse step shows as few steps per shortest period."""
    model = cf.CamFollowerModel()
    highest = float(np.max(model.modal_analysis(0.0)["frequencies_hz"]))
    fine = cf.simulate(model, duration=2e-4, time_step=1e-6)
    assert fine.stats["highest_mode_hz"] == pytest.approx(highest, rel=1e-6)
    assert fine.stats["steps_per_shortest_period"] == pytest.approx(1.0 / (highest * 1e-6), rel=1e-6)
    coarse = cf.simulate(model, duration=model.period, time_step=model.period / 12)
    assert coarse.stats["steps_per_shortest_period"] < 0.1


def test_a_step_longer_than_the_run_or_a_twelfth_of_a_revolution_is_refused():
    model = cf.CamFollowerModel()
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
    for call in (lambda: cf.Parameters().get(name),
                 lambda: (builder.add_spring("spring", "tappet", name, stiffness=1e5), builder.build()),
                 lambda: cf.simulate(cf.CamFollowerModel(), duration=1e-4, linear_solver=name)):
        with pytest.raises(ValueError) as e:
            call()
        text = str(e.value)
        assert "\x1b" not in text and "\x07" not in text and len(text) < 2000, text[:200]
        assert "?" in text and "bytes)" in text


def test_geometry_beyond_a_kilometre_is_refused():
    with pytest.raises(ValueError, match=r"base_radius must be finite and > 0 \(m\), in \[1e-06, 1000\] m"):
        cf.DiskCam(cf.MotionProgram.paper_default(), 5.6e102, 0.125, 0.0)
    with pytest.raises(ValueError, match="sample_rate = .* gives no usable frequency axis"):
        from camfollower import analysis
        analysis.spectrum(np.zeros(8), 2.2250738585072014e-308)


def test_an_output_cap_beyond_memory_is_capped_and_named_not_a_memory_error():
    with pytest.raises(ValueError, match=r"max_output_bytes = 1e\+300 B was capped at this machine's memory"):
        cf.simulate(cf.CamFollowerModel(), duration=4e3, time_step=1e-6, max_output_bytes=1e300)


def test_a_config_speed_outside_the_models_range_names_the_file_and_line(tmp_path):
    text = (ROOT / "examples" / "swing_arm.toml").read_text()
    assert 'speed = "' in text
    lines = text.splitlines()
    k = next(i for i, line in enumerate(lines) if line.strip().startswith("speed ="))
    lines[k] = 'speed = "1e-320 rpm"'
    path = tmp_path / "slow.toml"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(ValueError, match=rf"slow.toml:{k + 1}: camshaft.speed: must be in \[9.5\d*e-06, 954\d*\.?\d*\] rpm"):
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
    with pytest.raises(ValueError, match=r"denormal.toml:\d+: preset(.parameters)?: spring_preload_deflection must be "
                                         r"finite and > 0 \(m\), in \[1e-06, 1000\] m, got (1e-320|9.99\d*e-321)"):
        cf.load_config(path)
    # A contact no double can balance (1e25 N/m): whichever check stops it, the message is located.
    lines[k] = "spring_preload_deflection = 0.013"
    c = next(i for i, line in enumerate(lines) if line.startswith("contact_stiffness ="))
    lines[c] = "contact_stiffness = 1e25"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises((ValueError, RuntimeError), match=r"denormal.toml:\d+: preset: static equilibrium"):
        cf.load_config(path)
