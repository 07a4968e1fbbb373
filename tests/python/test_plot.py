# SPDX-License-Identifier: BSD-3-Clause
"""camfollower.plot: the drawn data are the quantities they claim to be."""

import math

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

import camfollower as cf  # noqa: E402
from camfollower import plot  # noqa: E402

PROGRAM = cf.MotionProgram.paper_default()


def test_svaj_at_speed_shows_the_rigid_follower_motion():
    fig = plot.svaj(PROGRAM, rpm=750)
    lift, vel, acc, jerk = (ax.lines[0] for ax in fig.axes)
    deg = lift.get_xdata()
    assert deg[0] == 0 and deg[-1] == pytest.approx(360)
    assert np.max(lift.get_ydata()) == pytest.approx(10.0)  # mm: the 10 mm rise
    # Modified trapezoid: peak acceleration 4.888 h / beta^2 (Norton's coefficient), beta = 150 deg.
    w, beta = 750 * 2 * math.pi / 60, math.radians(150)
    assert np.max(np.abs(acc.get_ydata())) == pytest.approx(4.888 * 0.010 / beta**2 * w**2, rel=1e-3)
    # Each curve is the time derivative of the one above (finite differences of the drawn data).
    dt = np.radians(np.diff(deg)) / w
    mid = 0.5 * (vel.get_ydata()[1:] + vel.get_ydata()[:-1])
    assert np.max(np.abs(np.diff(1e-3 * lift.get_ydata()) / dt - mid)) < 1e-3 * np.max(np.abs(mid))


def test_profile_draws_the_base_circle_on_the_dwell():
    f = cf.TranslatingRoller(0.04, 0.0125, 0.0)  # in-line: on both dwells the contact is radial
    fig = plot.profile(f, PROGRAM, theta=math.radians(90))
    surface = fig.axes[0].lines[0]
    x, y = surface.get_xdata(), surface.get_ydata()
    r = np.hypot(x, y)  # mm
    n = len(x)
    dwell = slice(0, int(n * 25 / 360))  # 0-25 deg of the 0-30 deg dwell
    assert np.allclose(r[dwell], 40.0, atol=1e-9)
    assert r.max() == pytest.approx(50.0, abs=1e-6)  # base radius + lift, on the upper dwell


def test_contact_force_shades_every_loss_interval():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        m = cf.presets.paper(eccentricity=cf.CamEccentricity(10e-6, formulation="paper_force_both"))
    r = cf.simulate(m, revolutions=1, time_step=m.period / 8192)
    assert r.contact_loss["cam"], "this literal case loses contact"
    fig = plot.contact_force(r)
    assert len(fig.axes[0].patches) == len(r.contact_loss["cam"])


def test_spectrum_peaks_at_the_signal_frequency():
    t = np.arange(8192) / 8192.0
    fig = plot.spectrum(np.sin(2 * np.pi * 100 * t), 8192.0, fmax=500, natural_frequencies=[250])
    line = fig.axes[0].lines[0]
    assert line.get_xdata()[np.argmax(line.get_ydata())] == pytest.approx(100.0)


def test_pressure_angle_plot_matches_the_follower():
    f = cf.TranslatingRoller(0.04, 0.0125, 0.01)
    fig = plot.pressure_angle_and_curvature(f, PROGRAM)
    theta, alpha = f.max_pressure_angle(PROGRAM)
    assert np.max(np.abs(fig.axes[0].lines[0].get_ydata())) == pytest.approx(abs(math.degrees(alpha)), rel=1e-3)


def test_bad_plot_input():
    with pytest.raises(ValueError, match="rpm must be finite and > 0"):
        plot.svaj(PROGRAM, rpm=-1)
    with pytest.raises(ValueError, match=r"points must be an integer in \[8, 10000000\]"):
        plot.svaj(PROGRAM, points=3)


def test_an_undercut_cam_is_drawn_and_flagged():
    # A 20 mm roller on a 10 mm base circle under a 20 mm rise in 60 deg undercuts near the nose: the
    # mechanism refuses it, the plot draws it with the reason in the title.
    d, mt, dw = math.radians, cf.MotionLaw.modified_trapezoid(), cf.MotionLaw.dwell()
    steep = cf.MotionProgram([cf.Segment(dw, 0, d(90), 0, 0), cf.Segment(mt, d(90), d(150), 0, 0.02),
                              cf.Segment(dw, d(150), d(210), 0.02, 0.02), cf.Segment(mt, d(210), d(270), 0.02, 0),
                              cf.Segment(dw, d(270), 2 * math.pi, 0, 0)])
    f = cf.TranslatingRoller(0.01, 0.02, 0.0)
    with pytest.raises(ValueError, match="undercuts"):
        f.check(steep)
    fig = plot.profile(f, steep)
    assert "NOT FOLLOWABLE" in fig.axes[0].get_title()
    assert len(fig.axes[0].lines[0].get_xdata()) > 100
