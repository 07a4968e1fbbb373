# SPDX-License-Identifier: BSD-3-Clause
"""The paper's cam (a TranslatingRoller on a MotionProgram) through the bindings: arrays out, paper
eqs 2-5 re-derived in NumPy, CSV export, and ValueError for bad input."""

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


def paper_follower():
    """The paper's cam and follower (Tables 1-2): base circle 30 mm, roller 8 mm, offset 10 mm."""
    return cf.TranslatingRoller(0.030, 0.008, 0.010), cf.MotionProgram.paper_default()


def test_profile_matches_paper_equations_written_in_numpy():
    follower, program = paper_follower()
    theta = np.linspace(0, 2 * np.pi, 2001)
    p = follower.profile(program, theta)
    h = program.evaluate(theta)
    rb, rr, e = 0.030, 0.008, 0.010
    R = np.sqrt((rb + rr) ** 2 - e**2) + h["h"]  # eq 2
    alpha = np.arctan((h["dh"] - e) / R)  # eq 4 with I12I24 = dR/dtheta
    x = R * np.cos(theta) - e * np.sin(theta) - rr * np.cos(theta - alpha)  # eq 5
    y = R * np.sin(theta) + e * np.cos(theta) - rr * np.sin(theta - alpha)
    np.testing.assert_allclose(p["pressure_angle"], alpha, rtol=0, atol=1e-15)
    # The follower types' cam frame has x across the follower axis and y along it (docs/followers.md):
    # the paper's eq 5 (x along the axis) is its mirror image, x <-> y.
    np.testing.assert_allclose(p["surface_x"], y, rtol=0, atol=1e-16)
    np.testing.assert_allclose(p["surface_y"], x, rtol=0, atol=1e-16)
    # Ground frame: roller centre (e, R), normal from cam to roller (e - R', R)/|.| = (-sin a, cos a).
    np.testing.assert_allclose(p["contact_x"], e + rr * np.sin(alpha), rtol=0, atol=1e-16)
    np.testing.assert_allclose(p["contact_y"], R - rr * np.cos(alpha), rtol=0, atol=1e-16)
    for k in range(0, theta.size, 20):
        c = follower.contact(program, theta[k])
        normal = np.array([e - h["dh"][k], R[k]]) / np.hypot(e - h["dh"][k], R[k])
        np.testing.assert_allclose(c["normal"], normal, rtol=0, atol=1e-15)
        assert np.hypot(*c["normal"]) == pytest.approx(1.0, abs=1e-15)
        assert c["lever"] == pytest.approx(np.cos(alpha[k]), abs=1e-15)


def test_perturbed_offset_changes_the_base_pitch_height():
    # A perturbed offset (the paper's backlash, e* = e +- delta) is another follower: the roller centre
    # on the base circle sits at (e*, s0*) in the ground frame, s0* = sqrt((r_b + r_r)^2 - e*^2) (eq 2).
    program = cf.MotionProgram.paper_default()
    de, theta = 10e-6, 0.2  # on the first dwell
    for e_star in (0.010 + de, 0.010 - de):
        p = cf.TranslatingRoller(0.030, 0.008, e_star).profile(program, theta)
        x, y = p["reference_x"], p["reference_y"]  # roller centre, cam frame: Rot(-theta) (e*, R)
        ground = (x * np.cos(theta) - y * np.sin(theta), x * np.sin(theta) + y * np.cos(theta))
        assert ground[0] == pytest.approx(e_star, rel=1e-14)
        assert ground[1] == pytest.approx(np.sqrt(0.038**2 - e_star**2), rel=1e-15)


def test_theoretical_follower_acceleration_at_750_rpm():
    # Modified trapezoid: peak h'' = h_max * Ca / beta^2, Ca = 8 pi / (pi + 2), beta = 150 deg.
    omega = 750 * 2 * np.pi / 60
    theta = np.linspace(0, 2 * np.pi, 400001)
    amax = omega**2 * np.max(np.abs(cf.MotionProgram.paper_default().evaluate(theta)["d2h"]))
    expected = omega**2 * 0.010 * (8 * np.pi / (np.pi + 2)) / (150 * DEG) ** 2
    assert amax == pytest.approx(expected, rel=1e-9)


def test_extremes_are_returned_as_theta_value_pairs():
    follower, program = paper_follower()
    t_max, a_max = follower.max_pressure_angle(program)
    # Brute force on eq 4 at 0.001 deg: the largest |alpha| is on the return (23.13 deg at 290.5 deg).
    theta = np.linspace(0, 2 * np.pi, 360001)
    h = program.evaluate(theta)
    alpha = np.arctan((h["dh"] - 0.010) / (np.sqrt(0.038**2 - 0.010**2) + h["h"]))
    k = np.argmax(np.abs(alpha))
    assert 210 * DEG <= t_max <= 360 * DEG and abs(t_max - theta[k]) < 0.01 * DEG
    assert a_max == pytest.approx(alpha[k], rel=1e-9)
    rise = (theta >= 30 * DEG) & (theta <= 180 * DEG)
    assert abs(a_max) > np.max(np.abs(alpha[rise]))  # the rise's extreme is smaller
    _, rho = follower.min_surface_radius(program)
    assert rho == pytest.approx(0.030, rel=1e-12)


def test_surface_csv_is_closed(tmp_path):
    follower, program = paper_follower()
    path = tmp_path / "cam.csv"
    cf.export.write_csv(path, follower, program, points=720, unit="m")
    lines = path.read_text().splitlines()
    header = next(i for i, line in enumerate(lines) if not line.startswith("#"))
    assert lines[header] == "theta_rad,surface_x_m,surface_y_m"
    data = np.loadtxt(lines[header + 1 :], delimiter=",")
    assert data.shape == (720, 3)  # theta_k = 2 pi k / 720; the last row joins the first
    np.testing.assert_allclose(data[:, 0], 2 * np.pi * np.arange(720) / 720, rtol=0, atol=1e-15)
    surface = follower.profile(program, data[:, 0])
    np.testing.assert_allclose(data[:, 1], surface["surface_x"], rtol=0, atol=1e-16)
    np.testing.assert_allclose(data[:, 2], surface["surface_y"], rtol=0, atol=1e-16)
    closing = follower.profile(program, 2 * np.pi)  # one turn later: the first point again
    np.testing.assert_allclose([closing["surface_x"], closing["surface_y"]], data[0, 1:], rtol=0, atol=1e-15)
    assert [p.name for p in tmp_path.iterdir()] == ["cam.csv"]  # no temporary left behind
    with pytest.raises(ValueError, match="path: cannot create a temporary file in"):
        cf.export.write_csv(tmp_path / "missing" / "cam.csv", follower, program)


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
        cf.TranslatingRoller(**{"base_radius": 0.030, "roller_radius": 0.008, "offset": 0.010, **kwargs})


def test_undercut_and_bad_programs_raise_value_error():
    cyc = cf.MotionLaw.cycloidal()
    steep = cf.MotionProgram([cf.Segment(cyc, 0, 40 * DEG, 0, 0.04), cf.Segment(cyc, 40 * DEG, 2 * np.pi, 0.04, 0)])
    with pytest.raises(ValueError, match="undercuts"):
        cf.TranslatingRoller(base_radius=0.010, roller_radius=0.012, offset=0.0).check(steep)
    with pytest.raises(ValueError, match=r"segments\[1\].theta_start.*gap"):
        cf.MotionProgram([cf.Segment(cyc, 0, 1.0, 0, 0.01), cf.Segment(cyc, 1.1, 2 * np.pi, 0.01, 0)])
    with pytest.raises(ValueError, match=r"segment spans 0 rad .*must be at least"):
        cf.MotionProgram([cf.Segment(cyc, 0, 0, 0, 0.0), cf.Segment(cf.MotionLaw.dwell(), 0, 2 * np.pi, 0, 0)])
    with pytest.raises(ValueError, match="theta must be finite"):
        cf.MotionProgram.paper_default().evaluate(np.array([0.0, np.inf]))
