# SPDX-License-Identifier: BSD-3-Clause
"""What the studies, results and the command line print: significant digits, not rounding noise
(349.99999999999994 rpm, an event at 8.2e-294 s), and a line, not every evaluation. The files (CSV,
JSON, NPZ) keep full precision."""

import math
import re

import numpy as np
import pytest
from camfollower import periodic, sizing, speed, study
from camfollower import tolerance as tol
from camfollower.results import Result

NOISE = re.compile(r"\d\.\d{9,}|\d{7,}\.\d|e-[1-9]\d\d")  # 10+ significant digits, or a time of 1e-100 s


def _row(rpm):
    return {
        "rpm": rpm,
        "min_force_N": 12.345678901234,
        "min_force_angle_deg": 121.12345678901,
        "contact_lost": False,
        "harmonics": list(np.linspace(1.0, 1e-6, 64)),
    }


def test_jump_speed_prints_the_answer_in_one_short_line():
    evaluations = [_row(r) for r in np.linspace(1000.0000000001, 1329.0999999999999, 14)]
    j = speed.JumpSpeed(
        rpm=1329.0999999999999,
        angle_deg=121.12345678901,
        bracket=(1328.1000000000001, 1329.0999999999999),
        min_force_below_N=0.40000000000000002,
        evaluations=evaluations,
    )
    text = repr(j)
    assert len(text) < 200 and "harmonics" not in text and not NOISE.search(text)
    assert text == (
        "JumpSpeed(rpm=1329.1, angle_deg=121.1, bracket=(1328.1, 1329.1), min_force_below_N=0.4, "
        "windows=0, warnings=0, evaluations=14)"
    )
    assert str(j) == (
        "jump speed 1329.1 rpm (bracket 1328.1 to 1329.1 rpm): the follower leaves the cam at 121.1 deg; "
        "min contact force just below 0.4 N; 14 evaluations"
    )
    assert j.evaluations == evaluations  # the data stay whole


def test_study_results_print_significant_digits():
    s = speed.SpringSize(
        rate=14000.000000000002,
        preload=181.99999999999997,
        min_force_N=5.0000000000000009,
        min_force_angle_deg=123.40000000000001,
        max_spring_force_N=321.99999999999994,
        evaluations=7,
    )
    assert repr(s) == (
        "SpringSize(rate=14000, preload=182, min_force_N=5, min_force_angle_deg=123.4, "
        "max_spring_force_N=322, evaluations=7)"
    )
    z = sizing.Sizing(
        base_radius=0.037200000000000004,
        offset=0.0,
        max_pressure_angle=0.52359877559829882,
        max_pressure_angle_at=1.2,
        min_surface_radius=0.0080000000000000002,
        min_surface_radius_at=2.5,
        binding="pressure angle",
    )
    assert repr(z) == (
        "Sizing(base_radius=0.0372, offset=0, max_pressure_angle=0.523599, max_pressure_angle_at=1.2, "
        "min_surface_radius=0.008, min_surface_radius_at=2.5, binding='pressure angle')"
    )
    case = tol.PaperCase(contact_stiffness=190000000.00000003)
    assert "contact_stiffness=1.9e+08" in repr(case) and not NOISE.search(repr(case))


def test_monte_carlo_result_prints_a_line_not_its_rows():
    rows = [
        {
            "case": i,
            "seed": i,
            "preset.x": 1.0 + i * 1e-3,
            "min_force_N": 10.0 + i / 3,
            "contact_lost": i % 50 == 0,
            "ok": i != 7,
            "error": "",
        }
        for i in range(200)
    ]
    r = tol.MonteCarloResult(rows=rows, nominal=rows[0], parameters=["preset.x"], seed=2026)
    text = repr(r)
    assert text == (
        "MonteCarloResult(200 cases, 1 failed, 4 lost contact, min_force_N 10 to 76.33; seed 2026; "
        "parameters: preset.x)"
    )


def test_periodic_orbit_prints_its_facts_not_its_matrices():
    n = 7
    orbit = periodic.PeriodicOrbit(
        q=np.zeros(n),
        v=np.zeros(n),
        period=0.080000000000000002,
        converged=True,
        mismatch=3.2e-11,
        iterations=3,
        monodromies=1,
        revolutions=5.0,
        multipliers=np.array([0.93000000000000005 + 0j]),
        monodromy=np.eye(2 * n),
        monodromy_at_orbit=True,
        history=(1e-3, 1e-7, 3.2e-11),
        dof_names=tuple("abcdefg"),
    )
    assert repr(orbit) == (
        "PeriodicOrbit(method='shooting', converged=True, period=0.08 s, mismatch=3.2e-11, "
        "iterations=3, revolutions=5, spectral_radius=0.93, 7 DOFs)"
    )


def _result(events):
    t = np.linspace(0.0, 0.1, 11)
    data = np.vstack([t, t, t, t])
    return Result(
        ["t", "q.y", "v.y", "a.y"],
        ["y"],
        data,
        {"time_step": 1e-4, "decimation": 100},
        {"cam": [(0.0, 8.2e-294)]},
        None,
        events,
    )


def test_result_and_its_events_print_times_to_the_picosecond(tmp_path):
    r = _result([(8.2e-294, "cam.contact", "lost"), (0.050000000000000003, "cam.contact", "made")])
    assert repr(r.events) == (
        "[Event(time=0, name='cam.contact', kind='lost'), Event(time=0.05, name='cam.contact', kind='made')]"
    )
    text = repr(r)
    assert "t = 0 to 0.1 s" in text and "2 contact events" in text and "contact lost 0 s" in text
    assert not NOISE.search(text)
    # Still plain tuples with the full values: compared, unpacked, saved and loaded as before.
    assert r.events[0] == (8.2e-294, "cam.contact", "lost")
    t, name, kind = r.events[1]
    assert (t, name, kind) == (0.05, "cam.contact", "made") and r.events[0].time == 8.2e-294
    back = Result.load(r.save(tmp_path / "r.npz"))
    assert back.events == r.events and repr(back.events) == repr(r.events)


def test_the_command_line_prints_no_rounding_noise(monkeypatch, capsys, tmp_path):
    from camfollower import cli

    summary = {
        "contacts": {
            "cam": {
                "min_force_N": 176.04,
                "max_force_N": 340.9,
                "contact_lost_s": 8.2e-294,
                "max_abs_acceleration": 47.78,
                "max_abs_rigid_acceleration": 43.99,
            }
        },
        "files": ["run.csv", "summary.json"],
    }
    monkeypatch.setattr(cli, "figures", lambda config, out: summary)
    config = tmp_path / "c.toml"
    config.write_text("")
    assert cli.main(["figures", str(config), "-o", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    assert "contact lost 0 s" in out and not NOISE.search(out)


def test_the_paper_study_table_prints_no_rounding_noise(capsys):
    case = {
        "settle": {"settled": True, "revolutions": 3, "change": 1e-5},
        "contact_force_range_N": (180.0, 340.0),
        "peak_follower_acceleration_m_s2": 47.0,
        "dwell_deviation_peak_m_s2": 0.5,
        "rise_deviation_rms_m_s2": 0.2,
        "return_deviation_rms_m_s2": 0.3,
        "contact_loss_time_per_revolution_s": 8.2e-294,
        "shaft_acceleration_sidebands": {"defect_modulation": 0.01},
    }
    summary = {
        "rpm": 750.0,
        "kinematics": {
            "max_pressure_angle_rise_deg": 20.0,
            "max_pressure_angle_return_deg": -21.0,
            "max_theoretical_follower_acceleration_m_s2": 43.993,
        },
        "natural_frequencies_hz_dwell": [868.0],
        "cases": {"offset/paper/healthy": case},
        "carrier_hz": 12.5,
        "sensitivity": [],
    }
    study.print_summary(summary)
    out = capsys.readouterr().out
    assert " 0.0e+00 " in out and not NOISE.search(out)


@pytest.mark.parametrize("x, text", [(349.99999999999994, "350"), (8.2e-294, "8.2e-294"), (1e-7, "1e-07"), (3, "3")])
def test_significant_digits_keep_real_small_numbers(x, text):
    from camfollower import _text

    assert _text.g(x) == text  # only a time is rounded to the picosecond
    assert _text.seconds(8.2e-294) == "0" and _text.seconds(-1e-20) == "0" and _text.seconds(1.5e-9) == "1.5e-09"
    assert math.isnan(float(_text.seconds(float("nan"))))
