# SPDX-License-Identifier: BSD-3-Clause
"""`camfollower synthesize` and the [synthesis] table: the files it writes, the program table loading
back to the same mechanism (simulated afresh: the same residuals), the electronic cam table matching
the program, and bad input named at its key or option."""

import json
import math

import camfollower as cf
import numpy as np
import pytest
from camfollower import cli, ecam, synthesis

CONFIG = """
[camshaft]
speed = "600 rpm"

[program.lift]
segments = [
  { law = "dwell", end = "40 deg", h = 0 },
  { law = "cycloidal", end = "160 deg", h = "20 mm" },
  { law = "dwell", end = "200 deg" },
  { law = "cycloidal", end = "320 deg", h = 0 },
  { law = "dwell", end = "360 deg" },
]

[[dof]]
name = "y"
mass = "0.5 kg"
direction = [0, 1, 0]

[[spring]]
name = "return"
a = "y"
stiffness = "10 N/mm"
damping = 5.0
preload = 150

[[contact]]
name = "cam"
program = "lift"
follower = { type = "translating_flat", base_radius = "30 mm" }
follower_dof = "y"
stiffness = 2e5
"""
SYNTHESIS = """
[synthesis]
nodes = 6
continuity = 4
max_iterations = 6
"""


def write(tmp_path, text):
    path = tmp_path / "one_mass.toml"
    path.write_text(text)
    return path


def test_synthesize_writes_a_program_that_loads_back_to_the_same_residuals(tmp_path, capsys):
    config = write(tmp_path, CONFIG + SYNTHESIS)
    out = tmp_path / "out"
    assert cli.main(["synthesize", str(config), "-o", str(out)]) == 0
    printed = capsys.readouterr().out
    summary = json.loads((out / "summary.json").read_text())
    assert sorted(summary["files"]) == sorted(
        ["program.toml", "ecam_table.csv", "verification.csv", "before_after.png", "summary.json"]
    )
    before, after = summary["verification"]["config"][0], summary["verification"]["synthesized"][0]
    assert after["residual"] < before["residual"] / 100  # 3.7e-4 m -> ~1e-9 m
    assert "600 rpm: residual vibration" in printed
    # program.toml pasted into the config, the contact pointed at it, as its header says: the same
    # program, the same residual.
    pasted = tmp_path / "pasted.toml"
    pasted.write_text(
        CONFIG.replace('program = "lift"', 'program = "synthesized"') + (out / "program.toml").read_text()
    )
    again = cf.load_config(pasted).mechanism
    check = synthesis.verify(again, again.builder().contacts[0]["program"], [600.0])[0]
    assert check["residual"] == pytest.approx(after["residual"], rel=1e-9)
    # The servo table holds that program's lift (mm against deg).
    program = again.builder().contacts[0]["program"]
    table = ecam.read_table_csv(out / "ecam_table.csv")
    theta = np.asarray(table["theta"])
    assert np.max(np.abs(np.asarray(table["h"]) - np.asarray(program.evaluate(theta % (2 * math.pi))["h"]))) < 1e-9
    rows = (out / "verification.csv").read_text().splitlines()
    assert rows[0].startswith("lift,rpm,residual,residual_error") and len(rows) == 3


@pytest.mark.parametrize(
    "table, message",
    [
        ("[synthesis]\nnodez = 6\n", r"synthesis\.nodez|nodez"),
        ('[synthesis]\nobjective = "jerk"\n', r"synthesis\.objective: must be one of residual, follower_error"),
        (
            '[synthesis]\noutput = "slide"\n',
            r"synthesis\.output: must name a DOF of the mechanism, got slide; its DOFs: y",
        ),
        ("[synthesis]\nnodes = 2\n", r"synthesis\.nodes: must be an integer in \[3, 40\]"),
        ("[synthesis]\nband = 0.2\nrpm = [600, 500]\n", r"synthesis\.rpm: give rpm .* or band, not both"),
        (
            "[synthesis]\nmax_pressure_angle_deg = 95\n",
            r"synthesis\.max_pressure_angle_deg: must be a number in \[0, 90\]",
        ),
        ("[synthesis]\nmax_acceleration = 1.0\nnodes = 6\ncontinuity = 4\n", r"max_acceleration: no lift can move"),
        (
            "[synthesis]\nmax_stress = 2e8\n",
            r"synthesis\.max_stress: max_stress \(Pa\) and roller_width \(m\) go together",
        ),
    ],
)
def test_bad_synthesis_tables_are_named(tmp_path, capsys, table, message):
    config = write(tmp_path, CONFIG + table)
    assert cli.main(["synthesize", str(config), "-o", str(tmp_path / "out")]) == 1
    err = capsys.readouterr().err
    assert err.startswith("camfollower: error: ")
    assert __import__("re").search(message, err), err
    assert not (tmp_path / "out" / "summary.json").exists()


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--band", "1.5"], "--band: 1.5 is not a fraction"),
        (["--band", "0.2", "--rpm", "600"], "give --rpm"),
        (["--rpm", "-5"], "--rpm"),
        (["--workers", "0"], "--workers"),
    ],
)
def test_bad_synthesize_options_are_usage_errors(tmp_path, capsys, argv, message):
    config = write(tmp_path, CONFIG)
    assert cli.main(["synthesize", str(config), "-o", str(tmp_path / "out"), *argv]) == 2
    assert message in capsys.readouterr().err


def test_the_indexing_examples_synthesis_table_reads_as_documented():
    from pathlib import Path

    from camfollower.studies import synthesis_settings

    case = cf.load_config(Path(__file__).resolve().parents[2] / "examples" / "indexing_cam.toml")
    m = case.mechanism
    st = synthesis_settings(case.data["synthesis"], path=case.path, contacts=m.contact_names, dofs=list(m.dof_names))
    assert st["output"] == "slide" and st["band"] == 0.2 and st["nodes"] == 16
    assert st["start"] == "polynomial_4567"
    assert (st["max_acceleration"], st["max_output_acceleration"]) == (27.9, 30.0)
