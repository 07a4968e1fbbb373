# SPDX-License-Identifier: BSD-3-Clause
"""The integration methods (docs/solvers.md): Dormand-Prince 5(4) and 8(5,3) against an independent solution
of the same equations (the NumPy model integrated by scipy), Fox-Goodwin, the settings each method
accepts, the config's [solver] scheme."""
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import camfollower as cf
from camfollower.reference import NumpyCamFollower

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def model():
    return cf.CamFollowerModel()


@pytest.fixture(scope="module")
def reference(model):
    """The 7-DOF equations written again in NumPy, integrated by scipy's DOP853 at rtol 1e-12."""
    ref = NumpyCamFollower(model)
    sol = solve_ivp(ref.rhs, (0, model.period), ref.initial(), method="DOP853", rtol=1e-12, atol=1e-15,
                    dense_output=True)
    assert sol.status == 0
    return ref, sol


def force_error(model, reference, result):
    ref, sol = reference
    z = sol.sol(result["t"])
    forces = np.array([ref.kh * max(ref.contact(t, zi[:7])[1], 0.0) for t, zi in zip(result["t"], z.T)])
    return np.max(np.abs(result["contact_force"] - forces)) / np.max(forces)


# (method, force evaluations per step, tolerance, bounds of the contact force's error relative to its peak:
# above half the tolerance, the comparison resolves it; the reference's own floor is ~4e-9). DOP853 at
# 1e-8 is measured at 4e-8, Dormand-Prince at 5.9e-7.
@pytest.mark.parametrize("method, per_step, tolerance, low, high", [
    ("dormand_prince", 6, 1e-5, 0.5e-5, 2e-3), ("dormand_prince", 6, 1e-7, 0.5e-7, 2e-5),
    ("dop853", 12, 1e-7, 0.5e-7, 2e-5), ("dop853", 12, 1e-8, 0.5e-8, 2e-7)])
def test_explicit_contact_force_against_scipy_on_independent_equations(model, reference, method, per_step, tolerance,
                                                                       low, high):
    r = cf.simulate(model, revolutions=1, time_step=model.period / 512, method=method, tolerance=tolerance)
    assert r.stats["method"] == method
    assert r.stats["newton_iterations"] == 0
    assert r.stats["evaluations"] >= per_step * r.stats["steps"]
    assert len(r["t"]) == 513 and r["t"][-1] == pytest.approx(model.period, rel=1e-12)
    err = force_error(model, reference, r)
    print(f"{method} tolerance {tolerance:g}: contact force error {err:.2e} of the peak, {r.stats['steps']} steps")
    assert low < err < high


# Radau IIA: implicit, so Newton iterations (three force evaluations each, and one at the solution per
# step); its global error is 10-20x the tolerance on this model (measured 1.7e-6 at 1e-7, 1.3e-7 at 1e-8).
@pytest.mark.parametrize("tolerance", [1e-7, 1e-8])
def test_radau_contact_force_against_scipy_on_independent_equations(model, reference, tolerance):
    r = cf.simulate(model, revolutions=1, time_step=model.period / 512, method="radau", tolerance=tolerance)
    assert (r.stats["method"], r.stats["requested_method"]) == ("radau", "radau")
    assert r.stats["newton_iterations"] >= r.stats["steps"] > 0
    assert r.stats["evaluations"] >= 4 * r.stats["steps"]
    assert len(r["t"]) == 513 and r["t"][-1] == pytest.approx(model.period, rel=1e-12)
    err = force_error(model, reference, r)
    print(f"radau tolerance {tolerance:g}: contact force error {err:.2e} of the peak, {r.stats['steps']} steps")
    assert 0.5 * tolerance < err < 200 * tolerance


def test_radau_takes_fewer_steps_where_damping_makes_the_model_stiff():
    """The realistically damped preset (3 % in every element): its high modes are overdamped, the
    explicit methods' steps are bounded by stability there (stiff_steps), Radau's by accuracy only."""
    m = cf.presets.paper_damped()
    T = m.period
    ref = cf.simulate(m, revolutions=1, time_step=T / 512, method="dop853", tolerance=1e-11)
    explicit = cf.simulate(m, revolutions=1, time_step=T / 512, method="dop853", tolerance=1e-7)
    r = cf.simulate(m, revolutions=1, time_step=T / 512, method="radau", tolerance=1e-7)
    peak = np.max(np.abs(ref["cam.force"]))
    err = np.max(np.abs(r["cam.force"] - ref["cam.force"])) / peak
    print(f"radau: {r.stats['steps']} steps, force error {err:.1e}; dop853: {explicit.stats['steps']} steps, "
          f"{explicit.stats['stiff_steps']} stiff")
    assert explicit.stats["stiff_steps"] > 0 and r.stats["stiff_steps"] == 0
    assert 1e-10 < err < 1e-6  # measured 5e-8: two methods, and Radau within its usual 10-20x the tolerance
    assert r.stats["steps"] < 0.6 * explicit.stats["steps"]


def test_radau_refuses_the_sparse_backend(model):
    with pytest.raises(ValueError, match="linear_solver 'sparse' or 'klu' applies to Newmark; radau runs on the dense "
                                         "backend only"):
        cf.simulate(cf.presets.valve_train(), revolutions=0.01, method="radau", linear_solver="sparse")


def test_dormand_prince_converges_to_newmark_at_fine_steps(model):
    """Two methods, one model: the force histories approach each other as both are refined."""
    dp = cf.simulate(model, revolutions=1, time_step=model.period / 256, method="dormand_prince", tolerance=1e-9)
    nm = cf.simulate(model, revolutions=1, time_step=model.period / 65536, decimation=256)
    assert np.array_equal(dp["t"].shape, nm["t"].shape)
    np.testing.assert_allclose(dp["t"], nm["t"], rtol=0, atol=1e-12)
    diff = np.max(np.abs(dp["contact_force"] - nm["contact_force"])) / np.max(np.abs(nm["contact_force"]))
    assert diff < 2e-4


def test_fox_goodwin_is_newmark_with_beta_one_twelfth(model):
    fg = cf.simulate(model, revolutions=0.25, time_step=model.period / 16384, method="fox_goodwin")
    nm = cf.simulate(model, revolutions=0.25, time_step=model.period / 16384, gamma=0.5, beta=1 / 12)
    assert fg.stats["method"] == "fox_goodwin" and nm.stats["method"] == "fox_goodwin"
    np.testing.assert_array_equal(fg["contact_force"], nm["contact_force"])
    with pytest.raises(ValueError, match=r"exceeds the stability limit"):
        cf.simulate(model, revolutions=0.25, time_step=model.period / 1024, method="fox_goodwin")


@pytest.mark.parametrize("kwargs, message", [
    (dict(method="rk4"), r"method must be 'newmark', 'fox_goodwin', 'dormand_prince', 'dop853', 'radau' or 'auto', got 'rk4'"),
    (dict(tolerance=1e-6), r"tolerance applies to methods 'dormand_prince', 'dop853' and 'radau' only"),
    (dict(max_step=1e-5, method="fox_goodwin"), r"max_step applies to methods 'dormand_prince', 'dop853' and 'radau' only"),
    (dict(method="dormand_prince", beta=0.3), r"gamma, beta and hht_alpha apply to method 'newmark' only"),
    (dict(method="dormand_prince", tolerance=0.0), r"tolerance must be in \[1e-13, 0.1\], got 0"),
    (dict(method="dormand_prince", tolerance=float("nan")), r"tolerance must be in \[1e-13, 0.1\], got nan"),
    (dict(method="dormand_prince", max_step=-1.0), r"max_step must be 0 \(unbounded\) or finite and >= 1e-12 s"),
    (dict(method="dormand_prince", max_step=1e-13), r"max_step must be 0 \(unbounded\) or finite and >= 1e-12 s"),
    (dict(method="dop853", tolerance=0.0), r"tolerance must be in \[1e-13, 0.1\], got 0"),
    (dict(method="dop853", tolerance=-1e-6), r"tolerance must be in \[1e-13, 0.1\], got -1e-06"),
    (dict(method="dop853", tolerance=float("inf")), r"tolerance must be in \[1e-13, 0.1\], got inf"),
    (dict(method="dop853", max_step=-1.0), r"max_step must be 0 \(unbounded\) or finite and >= 1e-12 s"),
    (dict(method="dop853", hht_alpha=-0.05), r"gamma, beta and hht_alpha apply to method 'newmark' only"),
])
def test_method_settings_are_checked_by_name(model, kwargs, message):
    with pytest.raises(ValueError, match=message):
        cf.simulate(model, revolutions=0.1, **kwargs)


def test_a_max_step_that_would_take_beyond_ten_billion_steps_is_refused(model):
    with pytest.raises(ValueError, match=r"duration / max_step = 8e\+10 steps is too many \(limit 1e10\)"):
        cf.simulate(model, revolutions=1, method="dormand_prince", max_step=1e-12)


def test_method_must_be_a_string(model):
    with pytest.raises(TypeError, match="method must be a str, got int"):
        cf.simulate(model, revolutions=0.1, method=5)
    with pytest.raises(TypeError, match="tolerance must be a number, got str"):
        cf.simulate(model, revolutions=0.1, method="dormand_prince", tolerance="1e-6")


@pytest.mark.parametrize("scheme", ["dormand_prince", "dop853", "radau"])
def test_config_scheme_explicit_reaches_simulate(tmp_path, scheme):
    text = (ROOT / "examples" / "translating_roller.toml").read_text()
    assert "[solver]" in text
    lines = [line for line in text.splitlines() if not line.startswith("scheme")]
    k = lines.index("[solver]")
    lines.insert(k + 1, f'scheme = "{scheme}"\ntolerance = 1e-7')
    path = tmp_path / "dp.toml"
    path.write_text("\n".join(lines) + "\n")
    cfg = cf.load_config(path)
    kw = cfg.simulate_kwargs()
    assert kw["method"] == scheme and kw["tolerance"] == 1e-7
    assert "gamma" not in kw
    r = cfg.run(revolutions=0.2)
    assert r.stats["method"] == scheme

    bad = list(lines)
    bad[k + 1] = 'tolerance = 1e-7'
    path.write_text("\n".join(bad) + "\n")
    with pytest.raises(ValueError, match=rf"dp.toml:{k + 2}: solver.tolerance: applies only with scheme = "
                                         r"\"dormand_prince\", \"dop853\" or \"radau\""):
        cf.load_config(path)


def test_auto_takes_fox_goodwin_within_its_stability_limit_else_average_acceleration():
    m = cf.presets.paper()
    limit = 0.9 * np.sqrt(6.0) / (2 * np.pi * cf.simulate(m, duration=m.period / 64, time_step=m.period / 4096)
                                  .stats["highest_mode_hz"])
    for dt, chosen in ((0.98 * limit, "fox_goodwin"), (1.02 * limit, "newmark")):
        r = cf.simulate(m, duration=200 * dt, time_step=dt, method="auto")
        assert (r.stats["method"], r.stats["requested_method"]) == (chosen, "auto")
        direct = cf.simulate(m, duration=200 * dt, time_step=dt, method=chosen)
        assert direct.stats["requested_method"] == chosen
        np.testing.assert_array_equal(r["cam.force"], direct["cam.force"])
    with pytest.raises(ValueError, match="gamma, beta and hht_alpha apply to method 'newmark' only"):
        cf.simulate(m, revolutions=0.1, method="auto", hht_alpha=-0.05)
    with pytest.raises(ValueError, match="tolerance applies to methods 'dormand_prince', 'dop853' and 'radau' only"):
        cf.simulate(m, revolutions=0.1, method="auto", tolerance=1e-6)


def test_config_scheme_auto_reaches_simulate():
    cfg = cf.load_config(ROOT / "examples" / "translating_roller.toml")  # the example asks for scheme = "auto"
    assert cfg.simulate_kwargs()["method"] == "auto"
    r = cfg.run(revolutions=0.2)
    # Its highest mode (6.5 kHz) allows Fox-Goodwin up to 0.9 sqrt(6) / omega = 54 us; the step is 5 us.
    assert (r.stats["requested_method"], r.stats["method"]) == ("auto", "fox_goodwin")
