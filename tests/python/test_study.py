"""The main job end to end on a short case, and its handling of bad output folders and options."""

import json

import pytest

from camfollower import study


def test_study_writes_figures_data_and_summary(tmp_path):
    out = tmp_path / "out"
    assert study.main(["--out", str(out), "--revolutions", "6", "--analysed-revolutions", "2"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["cases"]) == {"healthy", "eccentricity", "backlash"}
    for n in range(6, 16):
        assert len(list(out.glob(f"fig{n:02d}_*.png"))) == 1
        assert len(list((out / "data").glob(f"fig{n:02d}_*.csv"))) == 1
    assert (out / "kinematics.png").stat().st_size > 10000
    assert summary["spectral_resolution_hz"] == pytest.approx(6.25)
    assert not list(out.glob(".camfollower-study-*"))  # no staging left behind
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
        (["--eccentricity", "nan"], "eccentricity must be finite and >= 0"),
        (["--backlash=-1e-6"], "backlash must be finite and >= 0"),
        (["--revolutions", "3", "--analysed-revolutions", "3"], "analysed revolutions"),
        (["--backlash-switch-width", "400"], "switch width"),
    ],
)
def test_bad_study_options(tmp_path, capsys, args, message):
    with pytest.raises(SystemExit):
        study.main(["--out", str(tmp_path)] + args)
    assert message in capsys.readouterr().err
