# SPDX-License-Identifier: BSD-3-Clause
"""camfollower.plot: the drawn data are the quantities they claim to be."""

import math
import re
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import camfollower as cf  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from camfollower import plot  # noqa: E402

PROGRAM = cf.MotionProgram.paper_default()
ROOT = Path(__file__).resolve().parents[2]


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
    steep = cf.MotionProgram(
        [
            cf.Segment(dw, 0, d(90), 0, 0),
            cf.Segment(mt, d(90), d(150), 0, 0.02),
            cf.Segment(dw, d(150), d(210), 0.02, 0.02),
            cf.Segment(mt, d(210), d(270), 0.02, 0),
            cf.Segment(dw, d(270), 2 * math.pi, 0, 0),
        ]
    )
    f = cf.TranslatingRoller(0.01, 0.02, 0.0)
    with pytest.raises(ValueError, match="undercuts"):
        f.check(steep)
    fig = plot.profile(f, steep)
    assert "NOT FOLLOWABLE" in fig.axes[0].get_title()
    assert len(fig.axes[0].lines[0].get_xdata()) > 100


# --- figures fit for a design review (issue 32, part 6): checked on the drawn artists ---


def _valve_cam():
    """A 9 mm rise and return over 70 deg each (4-5-6-7 polynomials) on an 18 mm base circle: the
    surface radius passes through infinity on both flanks (convex to concave and back)."""
    d, law, dw = math.radians, cf.MotionLaw.polynomial_4567(), cf.MotionLaw.dwell()
    program = cf.MotionProgram(
        [
            cf.Segment(dw, 0, d(110), 0, 0),
            cf.Segment(law, d(110), d(180), 0, 0.009),
            cf.Segment(law, d(180), d(250), 0.009, 0),
            cf.Segment(dw, d(250), 2 * math.pi, 0, 0),
        ]
    )
    return cf.TranslatingRoller(0.018, 0.012, 0.0), program


def test_curvature_beyond_the_display_limit_is_a_gap_with_the_limit_marked():
    follower, program = _valve_cam()
    limit_mm = 1e3 * 10 * follower.base_radius
    theta = np.linspace(0, 2 * math.pi, 3601)
    rho = 1e3 * np.asarray(follower.profile(program, theta)["surface_radius"])
    beyond = np.abs(rho) > limit_mm
    assert beyond.any() and (rho > limit_mm).any() and (rho < -limit_mm).any()  # the case shows both signs
    ax = plot.pressure_angle_and_curvature(follower, program).axes[1]
    curve = ax.lines[0]
    y = np.asarray(curve.get_ydata(), dtype=float)
    # No plateau at the limit that reads as a value: beyond it the curve has a gap, elsewhere the radius.
    assert np.all(np.isnan(y[beyond]))
    assert np.allclose(y[~beyond], rho[~beyond])
    assert np.all(np.abs(y[~beyond]) <= limit_mm)
    # The limit is drawn explicitly on both sides, and says what it is.
    marks = [ln for ln in ax.lines[1:] if np.allclose(np.abs(ln.get_ydata()), limit_mm)]
    assert {np.sign(ln.get_ydata()[0]) for ln in marks} == {1.0, -1.0}
    assert any(f"{limit_mm:g} mm" in t.get_text() and "gap" in t.get_text() for t in ax.get_legend().get_texts())
    assert "(mm)" in ax.get_ylabel() and ax.get_xlim() == (0, 360)


def test_svaj_of_an_arm_rotation_is_in_degrees_and_radians_per_second():
    d, cyc, dw = math.radians, cf.MotionLaw.cycloidal(), cf.MotionLaw.dwell()
    swing = cf.MotionProgram(
        [
            cf.Segment(dw, 0, d(60), 0, 0),
            cf.Segment(cyc, d(60), d(150), 0, d(15)),
            cf.Segment(dw, d(150), d(210), d(15), d(15)),
            cf.Segment(cyc, d(210), d(300), d(15), 0),
            cf.Segment(dw, d(300), 2 * math.pi, 0, 0),
        ]
    )
    fig = plot.svaj(swing, rpm=600, angular=True)
    lift, vel, acc, jerk = fig.axes
    assert np.max(lift.lines[0].get_ydata()) == pytest.approx(15.0)  # deg, not 261.8 "mm"
    assert "deg" in lift.get_ylabel() and "mm" not in lift.get_ylabel()
    assert [a.get_ylabel() for a in (vel, acc, jerk)] == ["velocity (rad/s)", "acceleration (rad/s²)", "jerk (rad/s³)"]
    # Cycloidal: peak velocity 2 h / beta (per rad of cam angle) times omega.
    w = 600 * 2 * math.pi / 60
    assert np.max(vel.lines[0].get_ydata()) == pytest.approx(2 * d(15) / d(90) * w, rel=1e-4)


def test_spectrum_axes_name_the_quantity_and_its_unit():
    t = np.arange(8192) / 8192.0
    fig = plot.spectrum(
        3.0 * np.sin(2 * np.pi * 100 * t),
        8192.0,
        fmax=500,
        natural_frequencies=[250, 900],
        quantity="cam contact force",
        unit="N",
    )
    ax = fig.axes[0]
    assert ax.get_xlabel() == "frequency (Hz)"
    assert ax.get_ylabel() == "cam contact force amplitude (N)"
    assert "cam contact force" in ax.get_title()
    line = ax.lines[0]
    assert np.max(line.get_ydata()) == pytest.approx(3.0, rel=1e-3)  # the unit holds: amplitude 3 N reads 3
    marks = [ln for ln in ax.lines[1:] if ln.get_xdata()[0] == ln.get_xdata()[1]]
    assert [ln.get_xdata()[0] for ln in marks] == [250]  # 900 Hz lies beyond the band shown
    assert "natural frequencies" in [t.get_text() for t in ax.get_legend().get_texts()]


def test_per_revolution_folds_any_revolution_and_breaks_the_line_at_the_wrap():
    # A periodic orbit recorded on the third revolution, rows at both t = 0 and t = T.
    theta = np.linspace(4 * math.pi + 1.0, 6 * math.pi + 1.0, 361)
    y = np.sin(theta)
    x, yy = plot.per_revolution(theta, y)
    finite = np.isfinite(x)
    assert np.all((x[finite] >= 0) & (x[finite] <= 360))
    assert np.isnan(x).sum() == 1  # one wrap
    i = int(np.flatnonzero(np.isnan(x))[0])
    assert x[i - 1] == 360 and x[i + 1] == 0  # closed at the edges...
    assert yy[i - 1] == pytest.approx(math.sin(2 * math.pi), abs=1e-3) == yy[i + 1]  # ...at the value there
    for seg in (slice(0, i), slice(i + 1, None)):  # no segment runs back across the plot
        assert np.all(np.diff(x[seg]) > 0)
    assert np.allclose(yy[finite], np.sin(np.radians(x[finite])), atol=1e-4)  # edges: interpolated


def _no_line_across(x, step):
    """Every drawn segment (between NaNs) runs forward (a wrap edge may repeat a sample) in steps of at
    most `step` degrees."""
    x = np.asarray(x, dtype=float)
    cuts = np.flatnonzero(np.isnan(x))
    segments = np.split(x, cuts)
    return all(
        np.all((np.diff(seg[np.isfinite(seg)]) >= 0) & (np.diff(seg[np.isfinite(seg)]) <= step)) for seg in segments
    )


def _config(tmp_path, phase_deg=90):
    """A translating roller run for 3 revolutions, the last recorded, its contact at a phase."""
    text = (ROOT / "examples" / "translating_roller.toml").read_text()
    text = text.replace('follower_dof = "carrier"', f'follower_dof = "carrier"\nphase = "{phase_deg} deg"')
    text = text.replace("revolutions = 2\nsteps_per_revolution = 20000", "revolutions = 3\nsteps_per_revolution = 4000")
    text = text.replace("decimation = 10", "decimation = 4\nrecord_last_revolutions = 1")
    path = tmp_path / "roller.toml"
    path.write_text(text)
    return path


def test_figures_acceleration_is_one_revolution_of_the_cams_own_angle(tmp_path, monkeypatch):
    from camfollower import cli

    drawn = {}
    monkeypatch.setattr(cli, "_save", lambda config, fig, path: drawn.__setitem__(path.name, fig))
    cli.figures(str(_config(tmp_path)), str(tmp_path / "out"))
    ax = drawn["acceleration_cam.png"].axes[0]
    assert ax.get_xlim() == (0, 360)
    simulated, rigid = ax.lines[0], ax.lines[1]
    x, a = np.asarray(simulated.get_xdata()), np.asarray(simulated.get_ydata())
    finite = np.isfinite(x)
    assert np.all((x[finite] >= 0) & (x[finite] <= 360))  # the third revolution, drawn as 0-360 deg
    assert _no_line_across(x, 1.0)  # no wrap line back across the plot
    # The follower rides the cam at its phase: the simulated curve lies on the rigid one (dwells and
    # peaks at the same cam angles), which a plot against the shaft angle alone would shift by 90 deg.
    on_rigid = np.interp(x[finite], rigid.get_xdata(), rigid.get_ydata())
    peak = np.max(np.abs(rigid.get_ydata()))
    assert np.max(np.abs(a[finite] - on_rigid)) < 0.15 * peak
    assert "m/s²" in ax.get_ylabel()
    spectrum = drawn["spectrum_cam.png"].axes[0]
    assert spectrum.get_ylabel() == "cam contact force amplitude (N)" and spectrum.get_xlabel() == "frequency (Hz)"


def test_camshaft_traces_are_drawn_over_one_revolution():
    from camfollower.camshaft import plot_traces

    case = cf.load_config(ROOT / "examples" / "camshaft.toml")
    m = case.mechanism
    state = m.builder().__getstate__()
    theta = np.linspace(2 * math.pi, 4 * math.pi, 721)  # the second revolution, both ends recorded
    result = {"theta": theta}
    for c in state["contacts"]:
        result[f"{c['name']}.force"] = 300 + 100 * np.cos(theta + c["phase"])
    for d in state["dofs"]:
        if "name" in d:
            result[f"q.{d['name']}"] = np.zeros_like(theta)
            result[f"v.{d['name']}"] = np.zeros_like(theta)
    for dof in [d for d in (s["a"] for s in state["springs"]) if d.endswith(".rx")]:
        result[f"q.{dof}"] = 1e-3 * np.sin(theta)
        result[f"v.{dof}"] = np.zeros_like(theta)
    fig = plot_traces(m, result)
    for ax in fig.axes:
        assert ax.get_xlim() == (0, 360)
        for line in ax.lines:
            x = np.asarray(line.get_xdata(), dtype=float)
            finite = np.isfinite(x)
            assert np.all((x[finite] >= 0) & (x[finite] <= 360))
            assert _no_line_across(x, 1.0)
    assert "per revolution" in fig.axes[-1].get_xlabel()


def _sweep_with_many_crossings():
    """A sweep like the paper mechanism's: 500-1300 rpm, 64 shaft orders, one mode at 868 Hz that 23
    orders cross within the range (every 20-30 rpm), the harmonics falling with the order."""
    from camfollower import speed

    rpm = np.arange(500.0, 1301.0, 50.0)
    orders = list(range(1, 65))
    spectrum = np.array([[50.0 / k**2 * (1 + 0.1 * np.sin(r / 97)) for r in rpm] for k in orders])
    natural = [868.0]
    resonances = [(k, f, 60 * f / k) for f in natural for k in orders if rpm[0] <= 60 * f / k <= rpm[-1]]
    rows = [{"rpm": r, "min_force_N": 100.0, "contact_lost": False} for r in rpm]
    return speed, {
        "rows": rows,
        "orders": orders,
        "spectrum": spectrum,
        "natural_hz": natural,
        "resonances": resonances,
    }


def test_waterfall_labels_are_readable_and_name_the_strongest_resonances():
    speed, sweep = _sweep_with_many_crossings()
    assert len(sweep["resonances"]) > 20
    fig = speed.plot_waterfall(sweep, labels=12)
    ax = fig.axes[0]
    fig.canvas.draw()
    labels = [t for t in ax.texts if re.fullmatch(r"\d+[x×]", t.get_text())]
    assert 1 <= len(labels) <= 12
    boxes = [t.get_window_extent() for t in labels]
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            assert not boxes[i].overlaps(boxes[j]), (labels[i].get_text(), labels[j].get_text())
    # The lowest crossing order carries the largest harmonic here: it is labelled, at its resonance.
    lowest = min(k for k, _, _ in sweep["resonances"])
    text = next(t for t in labels if int(t.get_text()[:-1]) == lowest)
    k, f, r = next(x for x in sweep["resonances"] if x[0] == lowest)
    assert text.xy == pytest.approx((r, f))
    # Every crossing is marked, labelled or not; axes say what they show.
    crossings = next(ln for ln in ax.lines if ln.get_marker() == "|")
    assert len(crossings.get_xdata()) == len(sweep["resonances"])
    assert ax.get_xlabel() == "camshaft speed (rpm)" and ax.get_ylabel() == "frequency (Hz)"
    assert fig.axes[1].get_ylabel() == "contact force harmonic (dB re 1 N)"


def test_margin_plot_keeps_the_jump_line_inside_the_axes():
    from camfollower import speed

    rows = [{"rpm": r, "min_force_N": 200.0 - 0.15 * r, "contact_lost": False} for r in range(500, 1301, 100)]
    jump = speed.JumpSpeed(rpm=1329.1, angle_deg=121.1, bracket=(1328.1, 1329.1), min_force_below_N=1.0)
    ax = speed.plot_margin(rows, jump).axes[0]
    lo, hi = ax.get_xlim()
    assert lo < 500 and hi - 1329.1 > 0.02 * (hi - lo)  # clear of the frame, not on it
    assert "jump" in ax.get_title().lower() or "margin" in ax.get_title().lower()
    assert ax.get_ylabel() == "minimum contact force (N)" and ax.get_xlabel() == "camshaft speed (rpm)"
