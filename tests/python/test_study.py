# SPDX-License-Identifier: BSD-3-Clause
"""The main job end to end on a short case, and its handling of bad output folders and options."""

import json

import pytest
from camfollower import study


def test_study_writes_figures_data_and_summary(tmp_path):
    out = tmp_path / "out"
    assert (
        study.main(
            [
                "--out",
                str(out),
                "--max-revolutions",
                "4",
                "--analysed-revolutions",
                "2",
                "--steps-per-revolution",
                "4096",
            ]
        )
        == 0
    )
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["cases"]) == {
        f"{f}/{m}/{d}"
        for f in ("offset", "inline")
        for m in ("paper", "physical")
        for d in ("healthy", "eccentricity", "clearance")
    }
    for case in summary["cases"].values():  # every case states whether and how it settled
        assert set(case["settle"]) == {"settled", "revolutions", "change", "change_absolute", "tolerance"}
        assert 2 <= case["settle"]["revolutions"] <= 4
    assert "guide_clearance" in summary["cases"]["inline/physical/clearance"]
    assert len(summary["sensitivity"]) == 12
    for n in range(6, 20):
        assert len(list(out.glob(f"fig{n:02d}_*.png"))) == 1
        assert len(list((out / "data").glob(f"fig{n:02d}_*.csv"))) == 1
    assert (out / "kinematics.png").stat().st_size > 10000
    assert summary["spectral_resolution_hz"] == pytest.approx(6.25)
    assert not [p.name for p in out.rglob(".*")]  # no temporaries or staging folders left behind
    k = summary["kinematics"]
    assert k["max_theoretical_follower_acceleration_m_s2"] == pytest.approx(43.993, abs=1e-3)


def test_unwritable_output_folder_is_a_clear_error(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    with pytest.raises(SystemExit) as e:
        study.main(["--out", str(blocker / "out")])
    assert e.value.code == 2
    assert "--out: cannot write to" in capsys.readouterr().err


@pytest.mark.parametrize(
    "args,message",
    [
        (["--rpm", "-5"], "rpm must be finite and > 0"),
        (["--eccentricity", "nan"], "eccentricity must be finite and > 0"),
        (["--clearance=-1e-6"], "clearance must be finite and > 0"),
        (["--analysed-revolutions", "1"], "analysed revolutions"),
        (["--damping-ratio", "1.5"], "damping ratio"),
        (["--backlash-switch-width", "400"], "switch width"),
    ],
)
def test_bad_study_options(tmp_path, capsys, args, message):
    with pytest.raises(SystemExit):
        study.main(["--out", str(tmp_path)] + args)
    assert message in capsys.readouterr().err


def test_kinematics_summary_against_the_papers_pressure_angle():
    """The rise's and the return's largest pressure angle against alpha = atan((h' - e) / (s0 + h))
    (paper eq 4) written here, every 0.0005 deg; the tightest surface radius is the base circle."""
    import math

    import camfollower as cf
    import numpy as np

    program = cf.MotionProgram.paper_default()
    e, rb, rr = 0.010, 0.030, 0.008
    k = study.kinematics_summary(cf.TranslatingRoller(rb, rr, e), program, 750.0)
    theta = np.linspace(0, 2 * math.pi, 720001)
    m = program.evaluate(theta)
    alpha = np.arctan((np.asarray(m["dh"]) - e) / (math.sqrt((rb + rr) ** 2 - e**2) + np.asarray(m["h"])))
    rise = (theta >= math.radians(30)) & (theta <= math.radians(180))
    ret = theta >= math.radians(210)
    for key, inside in (("rise", rise), ("return", ret)):
        i = np.flatnonzero(inside)[np.argmax(np.abs(alpha[inside]))]
        assert k[f"max_pressure_angle_{key}_deg"] == pytest.approx(math.degrees(alpha[i]), abs=1e-6), key
        assert k[f"max_pressure_angle_{key}_at_deg"] == pytest.approx(math.degrees(theta[i]), abs=2e-3), key
    assert k["min_surface_radius_m"] == pytest.approx(rb, rel=1e-12)
