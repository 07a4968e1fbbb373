# SPDX-License-Identifier: BSD-3-Clause
"""DiskCam and MotionProgram through the bindings: arrays out, paper eqs 2-5 re-derived in NumPy,
CSV export, and ValueError for bad input."""

import camfollower as cf
import numpy as np
import pytest

DEG = np.pi / 180


def test_program_from_segments_and_paper_default_agree():
    mt, dw = cf.MotionLaw.modified_trapezoid(), cf.MotionLaw.dwell()
    prog = cf.MotionProgram(
        [
            cf.Segment(dw, 0, 30 * DEG, 0, 0),
            cf.Segment(mt, 30 * DEG, 180 * DEG, 0, 0.01),
            cf.Segment(dw, 180 * DEG, 210 * DEG, 0.01, 0.01),
            cf.Segment(mt, 210 * DEG, 360 * DEG, 0.01, 0),
        ]
    )
    theta = np.linspace(-1, 8, 1001)
    a, b = prog.evaluate(theta), cf.MotionProgram.paper_default().evaluate(theta)
    for key in ("h", "dh", "d2h", "d3h"):
        np.testing.assert_array_equal(a[key], b[key])


def test_profile_matches_paper_equations_written_in_numpy():
    cam = cf.DiskCam()
    theta = np.linspace(0, 2 * np.pi, 2001)
    p = cam.profile(theta)
    h = cam.program.evaluate(theta)
    rb, rr, e = 0.030, 0.008, 0.010
    R = np.sqrt((rb + rr) ** 2 - e**2) + h["h"]  # eq 2
    alpha = np.arctan((h["dh"] - e) / R)  # eq 4 with I12I24 = dR/dtheta
    x = R * np.cos(theta) - e * np.sin(theta) - rr * np.cos(theta - alpha)  # eq 5
    y = R * np.sin(theta) + e * np.cos(theta) - rr * np.sin(theta - alpha)
    np.testing.assert_allclose(p["pressure_angle"], alpha, rtol=0, atol=1e-15)
    np.testing.assert_allclose(p["surface_x"], x, rtol=0, atol=1e-16)
    np.testing.assert_allclose(p["surface_y"], y, rtol=0, atol=1e-16)
    np.testing.assert_allclose(np.hypot(p["normal_x"], p["normal_y"]), 1.0, atol=1e-15)


def test_perturbed_offset_changes_the_base_pitch_height():
    cam = cf.DiskCam()
    de = 10e-6
    for e_star in (0.010 + de, 0.010 - de):
        R = cam.profile(0.2, offset=e_star)["R"]
        assert R == pytest.approx(np.sqrt(0.038**2 - e_star**2), rel=1e-15)


def test_theoretical_follower_acceleration_at_750_rpm():
    # Modified trapezoid: peak h'' = h_max * Ca / beta^2, Ca = 8 pi / (pi + 2), beta = 150 deg.
    omega = 750 * 2 * np.pi / 60
    theta = np.linspace(0, 2 * np.pi, 400001)
    amax = omega**2 * np.max(np.abs(cf.MotionProgram.paper_default().evaluate(theta)["d2h"]))
    expected = omega**2 * 0.010 * (8 * np.pi / (np.pi + 2)) / (150 * DEG) ** 2
    assert amax == pytest.approx(expected, rel=1e-9)


def test_extremes_are_returned_as_theta_value_pairs():
    cam = cf.DiskCam()
    t_rise, a_rise = cam.max_pressure_angle_rise()
    t_ret, a_ret = cam.max_pressure_angle_return()
    assert 30 * DEG <= t_rise <= 180 * DEG and 210 * DEG <= t_ret <= 360 * DEG
    assert abs(a_ret) > abs(a_rise)
    _, rho = cam.min_surface_radius()
    assert rho == pytest.approx(0.030, rel=1e-12)


def test_surface_csv_is_closed(tmp_path):
    path = tmp_path / "cam.csv"
    cf.DiskCam().write_surface_csv(str(path), points=720)
    data = np.loadtxt(path, delimiter=",", skiprows=1)
    assert data.shape == (721, 3)
    np.testing.assert_allclose(data[0, 1:], data[-1, 1:], atol=1e-15)
    assert [p.name for p in tmp_path.iterdir()] == ["cam.csv"]  # no temporary left behind
    with pytest.raises(ValueError, match="path: cannot create a temporary file in"):
        cf.DiskCam().write_surface_csv(str(tmp_path / "missing" / "cam.csv"))


@pytest.mark.parametrize(
    "kwargs,message",
    [
        (dict(offset=0.038), r"\|offset\| < base_radius \+ roller_radius"),
        (dict(roller_radius=0.0), "roller_radius must be finite and > 0"),
        (dict(base_radius=float("nan")), "base_radius"),
    ],
)
def test_bad_geometry_raises_value_error(kwargs, message):
    with pytest.raises(ValueError, match=message):
        cf.DiskCam(**kwargs)


def test_undercut_and_bad_programs_raise_value_error():
    cyc = cf.MotionLaw.cycloidal()
    steep = cf.MotionProgram([cf.Segment(cyc, 0, 40 * DEG, 0, 0.04), cf.Segment(cyc, 40 * DEG, 2 * np.pi, 0.04, 0)])
    with pytest.raises(ValueError, match="undercuts"):
        cf.DiskCam(steep, base_radius=0.010, roller_radius=0.012, offset=0.0)
    with pytest.raises(ValueError, match=r"segments\[1\].theta_start.*gap"):
        cf.MotionProgram([cf.Segment(cyc, 0, 1.0, 0, 0.01), cf.Segment(cyc, 1.1, 2 * np.pi, 0.01, 0)])
    with pytest.raises(ValueError, match=r"segment spans 0 rad .*must be at least"):
        cf.MotionProgram([cf.Segment(cyc, 0, 0, 0, 0.0), cf.Segment(cf.MotionLaw.dwell(), 0, 2 * np.pi, 0, 0)])
    with pytest.raises(ValueError, match="theta must be finite"):
        cf.MotionProgram.paper_default().evaluate(np.array([0.0, np.inf]))
