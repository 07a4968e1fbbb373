# SPDX-License-Identifier: BSD-3-Clause
"""Electronic cam tables (camfollower.ecam): the table columns against closed-form laws written out
here, unit scaling against hand conversion, the round trips (table, segment list, TwinCAT CNC file)
with their measured accuracy, the documented controller layout, and the refusals."""

import math
import os
from pathlib import Path

import camfollower as cf
import numpy as np
import pytest
from camfollower import ecam

L = cf.MotionLaw
H = 0.012  # m: the cycloidal program's lift
RISE = (math.pi / 3, math.pi)  # rad: 60 .. 180 deg
RETURN = (4 * math.pi / 3, 2 * math.pi)  # rad: 240 .. 360 deg


def cycloidal_program():
    return cf.MotionProgram(
        [
            cf.Segment(L.dwell(), 0.0, RISE[0], 0.0, 0.0),
            cf.Segment(L.cycloidal(), RISE[0], RISE[1], 0.0, H),
            cf.Segment(L.dwell(), RISE[1], RETURN[0], H, H),
            cf.Segment(L.cycloidal(), RETURN[0], RETURN[1], H, 0.0),
        ]
    )


def cycloid_closed_form(theta):
    """h, h', h'' (m, m/rad, m/rad^2) of cycloidal_program from the law itself:
    S = x - sin(2 pi x) / (2 pi), S' = 1 - cos(2 pi x), S'' = 2 pi sin(2 pi x); a return is H (1 - S)."""
    theta = np.asarray(theta, dtype=float)
    h, v, a = np.zeros_like(theta), np.zeros_like(theta), np.zeros_like(theta)
    for (t0, t1), sign, base in ((RISE, 1.0, 0.0), (RETURN, -1.0, H)):
        beta = t1 - t0
        inside = (theta >= t0) & (theta <= t1)
        x = (theta[inside] - t0) / beta
        h[inside] = base + sign * H * (x - np.sin(2 * np.pi * x) / (2 * np.pi))
        v[inside] = sign * H / beta * (1 - np.cos(2 * np.pi * x))
        a[inside] = sign * H / beta**2 * 2 * np.pi * np.sin(2 * np.pi * x)
    h[(theta > RISE[1]) & (theta < RETURN[0])] = H
    return h, v, a


def load(path):
    """The CSV as plain numbers, without the module's reader: comment lines, the column line, rows."""
    lines = open(path).read().splitlines()
    comments = [ln for ln in lines if ln.startswith("#")]
    data = np.loadtxt(path, delimiter=",", skiprows=len(comments) + 1, ndmin=2)
    return comments, lines[len(comments)], data


# ---------------------------------------------------------------------------------------------------
# The equidistant table


def test_table_columns_are_the_cycloid_in_master_units(tmp_path):
    path = tmp_path / "cam.csv"
    ecam.write_table_csv(path, cycloidal_program(), points=360, master_unit="deg", slave_unit="mm")
    comments, columns, data = load(path)
    assert columns == "master_deg,slave_mm,slave_velocity_mm_per_deg,slave_acceleration_mm_per_deg2"
    assert data.shape == (361, 4)  # closed: the row at 360 deg repeats the first
    assert np.array_equal(data[:, 0], np.arange(361.0))
    theta = np.radians(data[:, 0])
    h, v, a = cycloid_closed_form(theta % (2 * np.pi))
    per_deg = math.pi / 180
    np.testing.assert_allclose(data[:, 1], 1e3 * h, rtol=0, atol=1e-12 * 12)
    np.testing.assert_allclose(data[:, 2], 1e3 * v * per_deg, rtol=0, atol=1e-12 * np.max(np.abs(data[:, 2])))
    np.testing.assert_allclose(data[:, 3], 1e3 * a * per_deg**2, rtol=0, atol=1e-12 * np.max(np.abs(data[:, 3])))
    # The peak velocity of a cycloid is 2 H / beta: 2 * 12 mm / 120 deg = 0.2 mm/deg at 120 deg.
    assert data[120, 2] == pytest.approx(0.2, rel=1e-12)
    assert np.array_equal(data[-1, 1:], data[0, 1:])
    text = "\n".join(comments)
    for fact in (
        "# master_unit: deg",
        "# master_period: 360.0",
        "# points: 360",
        "# closed: yes (361 rows",
        "# slave_unit: mm (1 mm = 0.001 m)",
        "d(slave)/d(master) in mm/deg: a derivative with respect to the master position, not time",
        "d2(slave)/d(master)2 in mm/deg^2",
        "theta = 2 pi master / master_period",
    ):
        assert fact in text, fact
    assert os.listdir(tmp_path) == ["cam.csv"]  # written atomically: no temporary left


def test_table_with_a_speed_adds_time_and_per_second_columns(tmp_path):
    path = tmp_path / "cam.csv"
    ecam.write_table_csv(path, cycloidal_program(), points=72, speed_rpm=120.0, closed=False)
    comments, columns, data = load(path)
    assert columns.endswith(",time_s,slave_velocity_mm_per_s,slave_acceleration_mm_per_s2")
    assert data.shape == (72, 7)
    omega = 120.0 * 2 * math.pi / 60  # rad/s
    theta = 2 * np.pi * np.arange(72) / 72
    h, v, a = cycloid_closed_form(theta)
    np.testing.assert_allclose(data[:, 4], theta / omega, rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(data[:, 5], 1e3 * v * omega, rtol=0, atol=1e-11 * np.max(np.abs(data[:, 5])))
    np.testing.assert_allclose(data[:, 6], 1e3 * a * omega**2, rtol=0, atol=1e-11 * np.max(np.abs(data[:, 6])))
    assert "one master cycle takes 0.5 s" in "\n".join(comments)
    back = ecam.read_table_csv(path)
    assert back["speed_rpm"] == 120.0 and back["closed"] is False
    assert np.array_equal(back["time"], data[:, 4])


def test_units_scale_as_converted_by_hand(tmp_path):
    prog = cycloidal_program()
    ecam.write_table_csv(tmp_path / "si.csv", prog, points=48, master_unit="rad", slave_unit="m")
    ecam.write_table_csv(tmp_path / "mm.csv", prog, points=48, master_unit="deg", slave_unit="mm")
    ecam.write_table_csv(tmp_path / "belt.csv", prog, points=48, master_unit="mm", master_period=250.0, slave_unit="um")
    _, cols_si, si = load(tmp_path / "si.csv")
    _, _, mm = load(tmp_path / "mm.csv")
    _, cols_belt, belt = load(tmp_path / "belt.csv")
    assert cols_si == "master_rad,slave_m,slave_velocity_m_per_rad,slave_acceleration_m_per_rad2"
    assert cols_belt == "master_mm,slave_um,slave_velocity_um_per_mm,slave_acceleration_um_per_mm2"
    # A rad master defaults to one turn, 2 pi; the rows are the same cam angles.
    np.testing.assert_allclose(si[:, 0], 2 * np.pi * np.arange(49) / 48, rtol=1e-15, atol=0)
    np.testing.assert_allclose(mm[:, 0], np.degrees(si[:, 0]), rtol=1e-14, atol=1e-13)
    np.testing.assert_allclose(belt[:, 0], 250.0 * np.arange(49) / 48, rtol=1e-15, atol=0)
    # Slave: 1 m = 1000 mm = 1e6 um; d/d(deg) = pi / 180 d/d(rad); d/d(mm of belt) = 2 pi / 250 d/d(rad).
    for data, length, per_master in ((mm, 1e3, math.pi / 180), (belt, 1e6, 2 * math.pi / 250.0)):
        np.testing.assert_allclose(data[:, 1], length * si[:, 1], rtol=1e-14, atol=1e-18)
        np.testing.assert_allclose(data[:, 2], length * per_master * si[:, 2], rtol=1e-13, atol=1e-18)
        np.testing.assert_allclose(data[:, 3], length * per_master**2 * si[:, 3], rtol=1e-13, atol=1e-18)


def test_an_oscillating_slave_in_degrees(tmp_path):
    arm = cf.MotionProgram(
        [cf.Segment(L.cycloidal(), 0.0, math.pi, 0.0, 0.3), cf.Segment(L.cycloidal(), math.pi, 2 * math.pi, 0.3, 0.0)]
    )
    path = tmp_path / "arm.csv"
    ecam.write_table_csv(path, arm, points=36, slave_unit="deg", rotary=True)
    comments, columns, data = load(path)
    assert columns == "master_deg,slave_deg,slave_velocity_deg_per_deg,slave_acceleration_deg_per_deg2"
    lift = arm.evaluate(np.radians(data[:-1, 0]))
    np.testing.assert_allclose(data[:-1, 1], np.degrees(lift["h"]), rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(data[:-1, 2], lift["dh"], rtol=1e-13, atol=1e-15)  # deg/deg = rad/rad
    assert "# slave_kind: rotary" in "\n".join(comments)
    assert ecam.read_table_csv(path)["rotary"] is True


def test_table_round_trip_through_a_degree_5_spline(tmp_path):
    # Measured (docs/ecam.md): 4.2e-8 of the lift for the paper's program, 5.2e-8 for the cycloids,
    # 360 points, degree 5; asserted with a margin of about 2.
    theta = np.linspace(0, 2 * np.pi, 20001)[:-1]
    for prog, lift in ((cf.MotionProgram.paper_default(), 0.01), (cycloidal_program(), H)):
        path = tmp_path / "cam.csv"
        ecam.write_table_csv(path, prog, points=360)
        back = ecam.program_from_table_csv(path)
        assert len(back.segments) == 1 and back.segments[0].law.is_custom
        a, b = prog.evaluate(theta), back.evaluate(theta)
        assert np.max(np.abs(a["h"] - b["h"])) < 1e-7 * lift
        assert np.max(np.abs(a["dh"] - b["dh"])) < 3e-5 * np.max(np.abs(a["dh"]))
        # Degree 3 is closer still for catalogue laws whose jerk jumps on table points (5.6e-9 measured).
        cubic = ecam.program_from_table_csv(path, degree=3).evaluate(theta)
        assert np.max(np.abs(a["h"] - cubic["h"])) < 1.5e-8 * lift
    table = ecam.read_table_csv(path)
    assert (table["points"], table["master_period"], table["master_unit"], table["slave_unit"]) == (
        360,
        360.0,
        "deg",
        "mm",
    )
    np.testing.assert_allclose(table["h"][:360], cycloid_closed_form(table["theta"][:360])[0], rtol=0, atol=1e-15)


def test_read_table_csv_refuses_a_file_that_is_not_such_a_table(tmp_path):
    path = tmp_path / "cam.csv"
    ecam.write_table_csv(path, cycloidal_program(), points=12)
    text = path.read_text()
    (tmp_path / "short.csv").write_text(text.rsplit("\n", 2)[0] + "\n")  # one row missing
    with pytest.raises(ValueError, match=r"the header says 13 rows \(points 12, closed: True\), got 12"):
        ecam.read_table_csv(tmp_path / "short.csv")
    (tmp_path / "other.csv").write_text("a,b\n1,2\n")
    with pytest.raises(ValueError, match="is not a camfollower electronic cam table"):
        ecam.read_table_csv(tmp_path / "other.csv")


# ---------------------------------------------------------------------------------------------------
# The segment list


def catalogue_program():
    d = math.radians
    laws = [
        (L.dwell(), 0, 20, 0.0, 0.0),
        (L.cycloidal(), 20, 60, 0.0, 0.004),
        (L.simple_harmonic(), 60, 100, 0.004, 0.010),
        (L.dwell(), 100, 130, 0.010, 0.010),
        (L.constant_acceleration(), 130, 170, 0.010, 0.007),
        (L.modified_sine(), 170, 210, 0.007, 0.012),
        (L.modified_trapezoid(), 210, 250, 0.012, 0.005),
        (L.polynomial_345(), 250, 290, 0.005, 0.008),
        (L.polynomial_4567(), 290, 320, 0.008, 0.003),
        (L.sine_constant_cosine(0.2, 0.3, 0.5), 320, 360, 0.003, 0.0),
    ]
    return cf.MotionProgram([cf.Segment(law, d(a), d(b), h0, h1) for law, a, b, h0, h1 in laws])


@pytest.mark.parametrize(
    "units",
    [
        dict(),
        dict(master_unit="rad", slave_unit="m"),
        dict(master_unit="mm", master_period=250.0, slave_unit="um"),
    ],
)
def test_segment_list_round_trip_is_exact(tmp_path, units):
    prog = catalogue_program()
    path = tmp_path / "segments.csv"
    ecam.write_segment_list(path, prog, **units)
    back = ecam.read_segment_list(path)
    assert len(back.segments) == len(prog.segments)
    for s, r in zip(prog.segments, back.segments):
        assert r.law.name == s.law.name and not r.law.is_custom
        assert (r.law.b, r.law.c, r.law.d) == (s.law.b, s.law.c, s.law.d)
        for attr in ("theta_start", "theta_end", "h_start", "h_end"):
            assert abs(getattr(r, attr) - getattr(s, attr)) <= 1e-12 * max(1.0, abs(getattr(s, attr))), attr
    theta = np.linspace(0, 2 * np.pi, 5001)
    a, b = prog.evaluate(theta), back.evaluate(theta)
    for key, scale in (("h", 0.012), ("dh", 1.0), ("d2h", 1.0)):
        assert np.max(np.abs(a[key] - b[key])) <= 1e-12 * max(scale, np.max(np.abs(a[key])))


def test_segment_list_rows_name_the_laws_and_their_boundary_rates(tmp_path):
    path = tmp_path / "segments.csv"
    ecam.write_segment_list(path, catalogue_program())
    lines = open(path).read().splitlines()
    body = [ln for ln in lines if not ln.startswith("#")]
    assert body[0].startswith("segment,master_start_deg,master_end_deg,slave_start_mm,slave_end_mm,law,b,c,d,")
    rows = [r.split(",") for r in body[1:]]
    assert [r[5] for r in rows] == [
        "dwell",
        "cycloidal",
        "simple_harmonic",
        "dwell",
        "constant_acceleration",
        "modified_sine",
        "modified_trapezoid",
        "polynomial_345",
        "polynomial_4567",
        "sine_constant_cosine",
    ]
    assert rows[9][6:9] == ["0.2", "0.3", "0.5"] and rows[6][6:9] == ["", "", ""]
    assert rows[1][1:5] == ["20.0", "60.0", "0.0", "4.0"]
    # Harmonic rise (6 mm over 40 deg): S = (1 - cos pi x) / 2, S'' = pi^2 / 2 cos pi x at x = 0.
    assert float(rows[2][11]) == pytest.approx(6.0 * math.pi**2 / 2 / 40.0**2, rel=1e-9)
    assert float(rows[2][9]) == pytest.approx(0.0, abs=1e-15)
    # Constant acceleration fall (3 mm over 40 deg): S = 2 x^2 on the first half, S'' = 4.
    assert float(rows[4][11]) == pytest.approx(-3.0 * 4 / 40.0**2, rel=1e-9)
    # Cycloid: S' = 1 - cos(2 pi x) = 0 at both ends.
    assert float(rows[1][9]) == 0.0 and abs(float(rows[1][10])) < 1e-15


def test_segment_list_refuses_a_spline_or_polynomial_segment_naming_it(tmp_path):
    poly = cf.Segment.polynomial(math.pi / 2, math.pi, [0.0, 0.0, 0.0], [0.01, 0.0, 0.0])
    prog = cf.MotionProgram(
        [
            cf.Segment(L.dwell(), 0.0, math.pi / 2, 0.0, 0.0),
            poly,
            cf.Segment(L.cycloidal(), math.pi, 2 * math.pi, 0.01, 0.0),
        ]
    )
    with pytest.raises(
        ValueError, match=r"program\.segments\[1\] \(segment 2 of 3\) has the law 'polynomial\(degree=5\)'"
    ):
        ecam.write_segment_list(tmp_path / "s.csv", prog)
    table = cf.MotionProgram.from_table(np.linspace(0, 2 * np.pi, 36, endpoint=False), np.zeros(36))
    with pytest.raises(ValueError, match=r"program\.segments\[0\] .* 'periodic spline"):
        ecam.write_segment_list(tmp_path / "s.csv", table)
    dented = catalogue_program().with_profile_error(cf.ProfileError.waviness(1e-6, 5))
    with pytest.raises(ValueError, match="carries a manufacturing \\(profile\\) error"):
        ecam.write_segment_list(tmp_path / "s.csv", dented)
    assert not list(tmp_path.iterdir())


def test_read_segment_list_names_a_bad_row(tmp_path):
    path = tmp_path / "segments.csv"
    ecam.write_segment_list(path, cf.MotionProgram.paper_default())
    text = path.read_text()
    (tmp_path / "bad.csv").write_text(text.replace("modified_trapezoid", "rast", 1))
    with pytest.raises(ValueError, match=r"row 2: unknown law 'rast'; the catalogue laws are dwell, "):
        ecam.read_segment_list(tmp_path / "bad.csv")


# ---------------------------------------------------------------------------------------------------
# The TwinCAT CNC / ISG MC platform cam table


def test_twincat_cnc_table_has_the_documented_layout(tmp_path):
    path = tmp_path / "cam.txt"
    ecam.write_twincat_cnc_table(path, cycloidal_program(), points=36, name="Cycloid_12mm", table_id=402)
    lines = [ln for ln in open(path).read().splitlines() if not ln.startswith("#")]
    assert lines[:6] == [
        "Tablename = Cycloid_12mm",
        "Tabletype = 3 # 3 = TABLE_ONE_COLUMN_REAL64",
        "Table-ID = 402 # Table-ID",
        "Functiontype = 1 # 1 = LINEAR",
        "Lines = 36",
        "Begintable",
    ]
    assert lines[-1] == "EndTable" and len(lines) == 6 + 36 + 1
    # Line k is the slave at master k * 10 deg, in 1E-4 mm with 4 decimals and a decimal comma.
    values = np.array([float(v.replace(",", ".")) for v in lines[6:-1]])
    h = cycloid_closed_form(2 * np.pi * np.arange(36) / 36)[0]
    np.testing.assert_allclose(values, h * 1e7, rtol=0, atol=0.5e-4 + 1e-9)
    assert lines[6 + 12] == "60000,0000"  # 120 deg: half the 12 mm rise
    assert "," in lines[6 + 8] and "." not in "".join(lines[6:-1])


def test_twincat_cnc_round_trip(tmp_path):
    # Measured (docs/ecam.md), 360 lines, degree 5: 4.2e-8 of the lift with 4 decimals; 5.5e-6 with whole
    # numbers of 1E-4 mm (the 0.05 um rounding, amplified a little by the spline).
    theta = np.linspace(0, 2 * np.pi, 20001)[:-1]
    prog = cf.MotionProgram.paper_default()
    exact = prog.evaluate(theta)["h"]
    ecam.write_twincat_cnc_table(tmp_path / "c4.txt", prog, points=360)
    ecam.write_twincat_cnc_table(tmp_path / "c0.txt", prog, points=360, decimals=0)
    four = ecam.program_from_twincat_cnc_table(tmp_path / "c4.txt").evaluate(theta)["h"]
    whole = ecam.program_from_twincat_cnc_table(tmp_path / "c0.txt").evaluate(theta)["h"]
    assert np.max(np.abs(four - exact)) < 1e-7 * 0.01
    assert np.max(np.abs(whole - exact)) < 1.2e-5 * 0.01
    table = ecam.read_twincat_cnc_table(tmp_path / "c0.txt")
    assert (table["name"], table["table_type"], table["table_id"], table["function_type"]) == ("camfollower", 3, 1, 1)
    assert np.array_equal(table["values"], np.round(prog.evaluate(table["theta"])["h"] * 1e7))
    assert table["master_deg"][1] == 1.0


def test_read_twincat_cnc_table_follows_the_interpreters_rules(tmp_path):
    # Written the way Beckhoff's examples are: comments with '#' and ';' first on a line, a commented-out
    # keyword, text after the last token, tabs, decimal commas, "Function type" spelt with a blank.
    degrees = 10.0 * np.arange(36)
    values = 3600000.0 * np.sin(np.radians(degrees))
    data = [f"{v:.4f}".replace(".", ",") for v in values]
    data[3] += "   valid comment"
    text = "\n".join(
        [
            "; a comment line",
            "Tablename = Sinus_360",
            "Tabletype = 3 # 3 = TABLE_ONE_COLUMN_REAL64",
            "Table-ID\t= 402 # Table-ID",
            "Function type = 5",
            "Lines = 36",
            "#Begintable !!! comment with '#' !!!",
            "Begintable",
            *data,
            "EndTable",
        ]
    )
    path = tmp_path / "sinus.txt"
    path.write_text(text + "\n")
    table = ecam.read_twincat_cnc_table(path)
    assert (table["name"], table["table_id"], table["function_type"], table["lines"]) == ("Sinus_360", 402, 5, 36)
    np.testing.assert_allclose(table["values"], values, rtol=0, atol=5e-5)
    np.testing.assert_allclose(table["h"], values * 1e-7, rtol=0, atol=5e-12)
    path.write_text(text.replace("Lines = 36", "Lines = 35") + "\n")
    with pytest.raises(ValueError, match="Lines = 35 but the table holds 36 values"):
        ecam.read_twincat_cnc_table(path)
    path.write_text(text.replace("Tabletype = 3", "Tabletype = 7") + "\n")
    with pytest.raises(ValueError, match=r"Tabletype 7 \(TABLE_TWO_COLUMNS_SGN32\) is not read here"):
        ecam.read_twincat_cnc_table(path)


# ---------------------------------------------------------------------------------------------------
# Refusals


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(points=7), r"points must be an integer in \[8, 1000000\], got 7"),
        (dict(points=1_000_001), r"points must be an integer in \[8, 1000000\], got 1000001"),
        (dict(points=360.0), r"points must be an integer in \[8, 1000000\], got 360.0"),
        (dict(points=True), r"points must be an integer in \[8, 1000000\], got True"),
        (dict(master_period=0.0), r"master_period must be a finite number > 0 \(deg of master travel"),
        (dict(master_period=-360.0), r"master_period must be a finite number > 0"),
        (dict(master_period=math.nan), r"master_period must be a finite number > 0"),
        (dict(master_unit="turns"), r"master_unit must be one of 'deg', 'rad', 'm', 'mm', 'um', got 'turns'"),
        (dict(master_unit="mm"), r"master_period is required for a linear master \(master_unit='mm'\)"),
        (
            dict(slave_unit="deg"),
            r"slave_unit must be one of 'm', 'mm', 'um' for a translating follower \(rotary=False\), got 'deg'",
        ),
        (
            dict(slave_unit="mm", rotary=True),
            r"slave_unit must be one of 'rad', 'deg' for an oscillating follower \(rotary=True\), got 'mm'",
        ),
        (dict(slave_unit="inch"), r"slave_unit must be one of 'm', 'mm', 'um'"),
        (dict(speed_rpm=-5.0), r"speed_rpm must be None or a number in \["),
    ],
)
def test_bad_table_arguments_are_refused_naming_the_parameter(tmp_path, kwargs, message):
    with pytest.raises(ValueError, match=message):
        ecam.write_table_csv(tmp_path / "cam.csv", cycloidal_program(), **kwargs)
    assert not list(tmp_path.iterdir())


def test_bad_program_and_controller_arguments_are_refused(tmp_path):
    for writer in (ecam.write_table_csv, ecam.write_segment_list, ecam.write_twincat_cnc_table):
        with pytest.raises(ValueError, match="program must be a camfollower.MotionProgram, got list"):
            writer(tmp_path / "x", [cf.Segment(L.dwell(), 0.0, 2 * math.pi, 0.0, 0.0)])
    prog = cycloidal_program()
    for kwargs, message in (
        (dict(name="two words"), r"name must be 1 to 30 printable ASCII characters without blanks"),
        (dict(name="x" * 31), r"name must be 1 to 30"),
        (dict(function_type=5), r"function_type must be 0 \(STEP_DIRECT\), 1 \(LINEAR\) or 2 \(POLYNOM_3\)"),
        (dict(table_id=0), r"table_id must be an integer in \[1, "),
        (dict(decimals=10), r"decimals must be an integer in \[0, 9\], got 10"),
        (dict(decimal_separator=";"), r"decimal_separator must be ',' or '.'"),
        (dict(points=4), r"points must be an integer in \[8, 1000000\], got 4"),
    ):
        with pytest.raises(ValueError, match=message):
            ecam.write_twincat_cnc_table(tmp_path / "c.txt", prog, **kwargs)
    with pytest.raises(ValueError, match="is not a regular file"):
        ecam.write_table_csv(tmp_path, prog)  # a directory: the atomic writer refuses it
    assert not list(tmp_path.iterdir())


# -- the command line: camfollower export --ecam ---------------------------------------------------------
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.mark.parametrize("kind", ["table", "segments", "twincat"])
def test_export_writes_the_configs_lift_program_for_a_servo_drive(tmp_path, capsys, kind):
    from camfollower import cli

    config = EXAMPLES / "indexing_cam.toml"
    out = tmp_path / f"index.{kind}"
    assert cli.main(["export", str(config), "-o", str(out), "--ecam", kind, "--points", "720"]) == 0
    assert f"({kind}:" in capsys.readouterr().out
    program = cf.load_config(config).mechanism.builder().contacts[0]["program"]
    theta = np.linspace(0.0, 2 * np.pi, 1001)[:-1]
    want = np.asarray(program.evaluate(theta)["h"])
    if kind == "segments":
        again = ecam.read_segment_list(out)
        tolerance = 1e-12 * 0.015
    elif kind == "table":
        again = ecam.program_from_table_csv(out)
        tolerance = 1e-6 * 0.015
    else:
        again = ecam.program_from_twincat_cnc_table(out)
        tolerance = 1e-6 * 0.015
    assert np.max(np.abs(np.asarray(again.evaluate(theta)["h"]) - want)) < tolerance


def test_export_of_an_arm_writes_degrees_and_refuses_a_cutter(tmp_path, capsys):
    from camfollower import cli

    config = EXAMPLES / "swing_arm.toml"
    out = tmp_path / "arm.csv"
    assert cli.main(["export", str(config), "-o", str(out), "--ecam", "table"]) == 0
    table = ecam.read_table_csv(out)
    assert table["slave_unit"] == "deg" and table["rotary"]
    program = cf.load_config(config).mechanism.builder().contacts[0]["program"]
    assert np.max(np.abs(table["h"] - np.asarray(program.evaluate(table["theta"] % (2 * np.pi))["h"]))) < 1e-12
    capsys.readouterr()
    assert cli.main(["export", str(config), "-o", str(out), "--ecam", "table", "--cutter-radius", "5"]) == 1
    assert "--cutter-radius: an electronic cam table holds the lift" in capsys.readouterr().err
