# SPDX-License-Identifier: BSD-3-Clause
"""Manufacturing export (camfollower.export): CSV and DXF round trips against independent truth."""

import math
import os
import stat
import sys

import camfollower as cf
import numpy as np
import pytest
from camfollower import export

PAPER = cf.MotionProgram.paper_default()
RB, RR, E = 0.030, 0.008, 0.010


def roller():
    return cf.TranslatingRoller(RB, RR, E)


def pitch_curve_mm(theta):
    """Roller centre in the cam frame from its definition: Rot(-theta) (e, s0 + h(theta)), in mm."""
    R = math.sqrt((RB + RR) ** 2 - E**2) + PAPER.evaluate(theta)["h"]
    c, s = np.cos(theta), np.sin(theta)
    return 1e3 * (c * E + s * R), 1e3 * (-s * E + c * R)


def read_csv(path):
    lines = open(path).read().splitlines()
    comments = [ln for ln in lines if ln.startswith("#")]
    data = np.loadtxt(path, delimiter=",", skiprows=len(comments) + 1)
    return comments, lines[len(comments)], data


def test_csv_round_trip_and_the_cutter_path_of_a_roller_sized_cutter_is_the_pitch_curve(tmp_path):
    path = tmp_path / "cam.csv"
    export.write_csv(path, roller(), PAPER, points=720, cutter_radius=RR)
    comments, columns, data = read_csv(path)
    assert columns == "theta_rad,surface_x_mm,surface_y_mm,cutter_x_mm,cutter_y_mm"
    assert data.shape == (720, 5)
    np.testing.assert_allclose(data[:, 0], 2 * np.pi * np.arange(720) / 720, rtol=1e-15, atol=0)
    px, py = pitch_curve_mm(data[:, 0])
    assert np.max(np.hypot(data[:, 3] - px, data[:, 4] - py)) < 1e-12
    # The rows are exactly what profile_points gives (17 significant digits).
    p = export.profile_points(roller(), PAPER, points=720, cutter_radius=RR)
    for k, key in enumerate(["theta", "surface_x", "surface_y", "cutter_x", "cutter_y"]):
        assert np.array_equal(data[:, k], p[key])
    text = "\n".join(comments)
    assert "# units: lengths in mm" in text
    assert "the cam turns counter-clockwise viewed from +z" in text
    assert "zero reference: at theta = 0" in text
    assert "translating_roller: base_radius = 30 mm, roller_radius = 8 mm, offset = 10 mm" in text
    assert "cutter radius: 8 mm" in text and "points: 720" in text
    # What the header claims: rows run clockwise (negative shoelace area) ...
    x, y = data[:, 1], data[:, 2]
    assert 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y) < 0
    # ... and the surface is the roller circle's inner side: |surface - centre| = r_r.
    assert np.allclose(np.hypot(x - px, y - py), 1e3 * RR, rtol=0, atol=1e-9)
    assert os.listdir(tmp_path) == ["cam.csv"]


def test_units_scale_the_points():
    f = cf.OscillatingFlat(0.03, (0.0, 0.08), 0.005)
    program = cf.MotionProgram.paper_default(math.radians(15))
    m = export.profile_points(f, program, points=100, cutter_radius=0.005, unit="m")
    mm = export.profile_points(f, program, points=100, cutter_radius=0.005, unit="mm")
    inch = export.profile_points(f, program, points=100, cutter_radius=0.005, unit="inch")
    um = export.profile_points(f, program, points=100, cutter_radius=0.005, unit="um")
    for key in ("surface_x", "surface_y", "cutter_x", "cutter_y"):
        np.testing.assert_allclose(mm[key], 1000 * m[key], rtol=1e-14, atol=1e-14)
        np.testing.assert_allclose(inch[key] * 25.4, mm[key], rtol=1e-14, atol=1e-12)
        np.testing.assert_allclose(um[key], 1e6 * m[key], rtol=1e-14, atol=1e-9)
    # The cutter path sits one cutter radius out along the unit normal.
    d = np.hypot(m["cutter_x"] - m["surface_x"], m["cutter_y"] - m["surface_y"])
    np.testing.assert_allclose(d, 0.005, rtol=1e-12)
    assert "cutter_x" not in export.profile_points(f, program, points=10)


def test_dxf_read_back(tmp_path):
    ezdxf = pytest.importorskip("ezdxf")
    path = tmp_path / "cam.dxf"
    f = cf.OscillatingRoller(0.03, 0.01, (0.08, 0.02), 0.07, "clockwise")
    program = cf.MotionProgram.paper_default(math.radians(15))
    export.write_dxf(path, f, program, points=1000, cutter_radius=0.012)
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4  # millimetres
    names = {layer.dxf.name for layer in doc.layers}
    assert {"CAM_SURFACE", "CUTTER_PATH", "REFERENCE"} <= names
    msp = doc.modelspace()
    surface = msp.query('LWPOLYLINE[layer=="CAM_SURFACE"]')
    cutter = msp.query('LWPOLYLINE[layer=="CUTTER_PATH"]')
    assert len(surface) == 1 and len(cutter) == 1
    assert surface[0].closed and cutter[0].closed
    s = np.array(surface[0].get_points("xy"))
    c = np.array(cutter[0].get_points("xy"))
    assert s.shape == (1000, 2) and c.shape == (1000, 2)
    p = export.profile_points(f, program, points=1000, cutter_radius=0.012)
    np.testing.assert_allclose(s[:, 0], p["surface_x"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(c[:, 1], p["cutter_y"], rtol=0, atol=1e-9)
    texts = {t.dxf.text for t in msp.query('TEXT[layer=="REFERENCE"]')}
    assert {"THETA = 0", "CCW"} <= texts
    notes = [v for _, v in doc.header.custom_vars]
    assert any("counter-clockwise viewed from +z" in v for v in notes)
    assert any(v.startswith("follower: oscillating_roller") for v in notes)
    assert os.listdir(tmp_path) == ["cam.dxf"]
    # Inches, no cutter: $INSUNITS 1, no cutter layer entity.
    export.write_dxf(path, cf.TranslatingFlat(0.03), PAPER, points=50, unit="inch")
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 1
    assert len(doc.modelspace().query('LWPOLYLINE[layer=="CUTTER_PATH"]')) == 0
    pts = np.array(doc.modelspace().query('LWPOLYLINE[layer=="CAM_SURFACE"]')[0].get_points("xy"))
    assert len(pts) == 50
    # On the first dwell the flat face touches the base circle straight up: (0, r_b) in inches.
    np.testing.assert_allclose(pts[0], [0.0, 0.03 / 0.0254], atol=1e-12)


def test_missing_ezdxf_names_the_extra(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    with pytest.raises(ImportError, match=r"pip install camfollower\[dxf\]"):
        export.write_dxf(tmp_path / "x.dxf", roller(), PAPER, points=10)
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("writer", ["write_csv", "write_dxf"])
def test_refused_targets_leave_nothing_behind(tmp_path, writer):
    if writer == "write_dxf":
        pytest.importorskip("ezdxf")
    write = getattr(export, writer)
    (tmp_path / "folder").mkdir()
    with pytest.raises(ValueError, match="not a regular file.*directory"):
        write(tmp_path / "folder", roller(), PAPER, points=36)
    os.mkfifo(tmp_path / "pipe")
    with pytest.raises(ValueError, match="FIFO"):
        write(tmp_path / "pipe", roller(), PAPER, points=36)
    assert stat.S_ISFIFO(os.lstat(tmp_path / "pipe").st_mode)
    with pytest.raises(ValueError, match="cannot create a temporary file"):
        write(tmp_path / "missing" / "cam.out", roller(), PAPER, points=36)
    # A refused cutter keeps an existing file as it was.
    target = tmp_path / "cam.out"
    target.write_text("old\n")
    with pytest.raises(ValueError, match="cutter_radius"):
        write(target, cf.TranslatingRoller(0.02, 0.005, 0.0), FAST, points=36, cutter_radius=0.05)
    assert target.read_text() == "old\n"
    assert sorted(os.listdir(tmp_path)) == ["cam.out", "folder", "pipe"]


# A fast cycloidal rise on a small cam: its surface is concave where the rise starts.
deg = math.pi / 180
FAST = cf.MotionProgram(
    [
        cf.Segment(cf.MotionLaw.dwell(), 0, 60 * deg, 0, 0),
        cf.Segment(cf.MotionLaw.cycloidal(), 60 * deg, 120 * deg, 0, 0.01),
        cf.Segment(cf.MotionLaw.dwell(), 120 * deg, 200 * deg, 0.01, 0.01),
        cf.Segment(cf.MotionLaw.cycloidal(), 200 * deg, 2 * math.pi, 0.01, 0),
    ]
)


def test_too_large_cutter_is_refused_at_the_tightest_concave_spot():
    f = cf.TranslatingRoller(0.02, 0.005, 0.0)
    # Truth: the smallest concave radius by three-point circles through a dense surface.
    p = export.profile_points(f, FAST, points=36000, unit="m")
    x, y = p["surface_x"], p["surface_y"]
    a = np.column_stack([np.roll(x, 1), np.roll(y, 1)])
    b = np.column_stack([x, y])
    c = np.column_stack([np.roll(x, -1), np.roll(y, -1)])
    ab, bc, ac = b - a, c - b, c - a
    cross = ab[:, 0] * ac[:, 1] - ab[:, 1] * ac[:, 0]
    r = -np.linalg.norm(ab, axis=1) * np.linalg.norm(bc, axis=1) * np.linalg.norm(ac, axis=1) / (2 * cross)
    concave = np.where(r < 0, -r, np.inf)
    k = int(np.argmin(concave))
    tightest, at = concave[k], math.degrees(p["theta"][k])
    export.profile_points(f, FAST, points=36, cutter_radius=0.99 * tightest)
    with pytest.raises(ValueError, match="cutter_radius") as info:
        export.profile_points(f, FAST, points=36, cutter_radius=1.01 * tightest)
    message = str(info.value)
    assert "concave" in message
    assert float(message.split("theta = ")[1].split(" deg")[0]) == pytest.approx(at, abs=0.05)


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(points=2), r"points must be an integer in \[3, 10000000\]"),
        (dict(points=-5), r"points must be an integer in \[3, 10000000\]"),
        (dict(points=10.5), r"points must be an integer in \[3, 10000000\]"),
        (dict(cutter_radius=-0.001), "cutter_radius must be None or a finite number >= 0"),
        (dict(cutter_radius=float("nan")), "cutter_radius"),
        (dict(unit="cm"), "unit must be one of m, mm, um, inch"),
    ],
)
def test_bad_input_names_the_parameter(tmp_path, kwargs, message):
    for call in (
        lambda: export.profile_points(roller(), PAPER, **kwargs),
        lambda: export.write_csv(tmp_path / "x.csv", roller(), PAPER, **kwargs),
    ):
        with pytest.raises(ValueError, match=message):
            call()
    assert os.listdir(tmp_path) == []


def test_bad_follower_and_core_checks():
    with pytest.raises(
        ValueError,
        match=r"follower must be one of TranslatingRoller, TranslatingFlat, OscillatingRoller, OscillatingFlat, BarrelRoller, BarrelArmRoller; got <class 'str'>",
    ):
        export.profile_points("roller", PAPER, points=10)
    with pytest.raises(ValueError, match=r"points must be an integer in \[3, 10000000\]"):
        cf._core.cam_outline(roller(), PAPER, -1)  # the core checks too
