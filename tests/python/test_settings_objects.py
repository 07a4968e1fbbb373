# SPDX-License-Identifier: BSD-3-Clause
"""Typed solver settings and run options: camfollower.SolverSettings is the C++ SolverSettings (its
field names and defaults), immutable and picklable; RunOptions the run's length and recording;
simulate(system, settings, options, **overrides) runs the same as the keywords alone; the config
produces the same objects."""

import pickle

import camfollower as cf
import numpy as np
import pytest


def test_defaults_are_the_cpp_ones():
    s = cf.SolverSettings()
    assert (s.method, s.time_step, s.tolerance, s.max_step) == ("newmark", 3e-6, None, 0.0)
    assert (s.gamma, s.beta, s.linear_solver) == (0.5, 0.25, "auto")
    assert (s.residual_tolerance, s.increment_tolerance, s.max_iterations, s.max_halvings) == (1e-10, 1e-10, 25, 6)
    assert not s.adaptive
    assert cf.SolverSettings("fox_goodwin").beta == pytest.approx(1 / 12)  # as the method steps
    assert cf.SolverSettings("hht").hht_alpha == -0.05
    assert set(cf.SolverSettings.FIELDS) >= {"method", "time_step", "tolerance", "gamma", "hht_alpha"}


def test_repr_pickle_equality_and_hash():
    s = cf.SolverSettings("dop853", time_step=1e-5, tolerance=1e-8, max_step=2e-5)
    assert repr(s) == "SolverSettings(method='dop853', time_step=1e-05, tolerance=1e-08, max_step=2e-05)"
    t = pickle.loads(pickle.dumps(s))
    assert t == s and hash(t) == hash(s) and t is not s
    assert s != cf.SolverSettings("dop853", time_step=1e-5, tolerance=1e-7, max_step=2e-5)
    assert len({s, t, cf.SolverSettings()}) == 2
    n = cf.SolverSettings(gamma=0.6, beta=0.3025)
    assert pickle.loads(pickle.dumps(n)).fields() == {
        "method": "newmark",
        "time_step": 3e-6,
        "gamma": 0.6,
        "beta": 0.3025,
    }


def test_replace_changes_fields_and_drops_parameters_of_another_method():
    n = cf.SolverSettings(gamma=0.6, beta=0.3025, time_step=1e-5)
    d = n.replace(method="dop853", tolerance=1e-7)
    assert (d.method, d.time_step, d.tolerance) == ("dop853", 1e-5, 1e-7)
    assert n.method == "newmark" and n.tolerance is None  # unchanged: immutable
    with pytest.raises(
        ValueError, match=r"gamma and beta apply to method 'newmark' only, got them with method 'dop853'"
    ):
        n.replace(method="dop853", gamma=0.6)
    with pytest.raises(ValueError, match=r"tolerance must be in \[1e-13, 0.1\], got 0"):
        n.replace(tolerance=0.0)


def test_bad_keywords_are_named():
    with pytest.raises(TypeError, match=r"unexpected keyword 'tolerence'; its fields: method, time_step, tolerance"):
        cf.SolverSettings(tolerence=1e-6)
    with pytest.raises(TypeError, match="tolerance must be a number, got str"):
        cf.SolverSettings("dop853", tolerance="1e-6")
    with pytest.raises(TypeError, match="max_halvings must be an integer, got float"):
        cf.SolverSettings(max_halvings=3.0)
    with pytest.raises(TypeError, match="method must be a str, got int"):
        cf.SolverSettings(5)
    with pytest.raises(ValueError, match="method must be 'newmark', 'fox_goodwin', 'hht'"):
        cf.SolverSettings("rk4")
    with pytest.raises(TypeError, match=r"unexpected keyword argument\(s\) \['revolution'\]"):
        cf.simulate(cf.presets.paper(), revolution=1)
    with pytest.raises(TypeError, match="settings must be a camfollower.SolverSettings or None, got dict"):
        cf.simulate(cf.presets.paper(), {"method": "dop853"}, revolutions=0.01)
    with pytest.raises(TypeError, match=r"RunOptions has no field\(s\) \['method'\]"):
        cf.RunOptions().replace(method="dop853")


def test_objects_and_keywords_run_the_same():
    m = cf.presets.paper()
    kw = dict(method="dop853", time_step=m.period / 2048, tolerance=1e-7)
    by_keywords = cf.simulate(m, revolutions=0.1, **kw)
    settings = cf.SolverSettings(**kw)
    options = cf.RunOptions(revolutions=0.1)
    by_objects = cf.simulate(m, settings, options)
    np.testing.assert_array_equal(by_keywords["cam.force"], by_objects["cam.force"])
    # Overrides on top of the objects win; the objects stay as they were.
    looser = cf.simulate(m, settings, options, tolerance=1e-5)
    assert looser.stats["evaluations"] < by_objects.stats["evaluations"]
    assert settings.tolerance == 1e-7
    many = cf.simulate_many([m, m], settings, options)
    np.testing.assert_array_equal(many[1]["cam.force"], by_objects["cam.force"])
    orbit = cf.periodic_steady_state(m, cf.SolverSettings("fox_goodwin", time_step=m.period / 4096))
    assert cf.SolverSettings(**orbit.scheme) == cf.SolverSettings("fox_goodwin", time_step=m.period / 4096)


def test_a_runge_kutta_method_without_a_tolerance_runs_under_the_default_one():
    m = cf.presets.paper()
    s = cf.SolverSettings("dop853", time_step=m.period / 2048)
    assert s.tolerance is None  # kept as asked
    a = cf.simulate(m, s, revolutions=0.05)
    b = cf.simulate(m, s.replace(tolerance=cf._core.RUNGE_KUTTA_DEFAULT_TOLERANCE), revolutions=0.05)
    np.testing.assert_array_equal(a["cam.force"], b["cam.force"])


def test_the_config_produces_the_same_objects():
    cfg = cf.config_from_dict(
        {
            "camshaft": {"speed": "750 rpm"},
            "preset": {"name": "paper"},
            "solver": {"scheme": "dop853", "tolerance": 1e-7, "steps_per_revolution": 2048},
        }
    )
    m = cfg.mechanism
    assert cfg.settings == cf.SolverSettings("dop853", tolerance=1e-7, time_step=m.period / 2048)
    assert cfg.options.revolutions == 1.0 and cfg.options.decimation == 1
    r = cfg.run(revolutions=0.05)
    s = cf.simulate(m, cfg.settings, cfg.options, revolutions=0.05)
    np.testing.assert_array_equal(r["cam.force"], s["cam.force"])


def test_numpy_integers_and_comparisons_with_other_types():
    assert cf.SolverSettings(max_halvings=np.int64(8), max_iterations=np.int32(30)).max_halvings == 8
    assert (cf.SolverSettings() == None) is False  # noqa: E711 (the operator, not identity)
    assert cf.SolverSettings() != "newmark"
    with pytest.raises(ValueError, match=r"max_halvings must be an integer in \[-1e6, 1e6\]"):
        cf.SolverSettings(max_halvings=2**70)


def test_an_orbit_pickled_before_the_settings_objects_still_records():
    from camfollower.periodic import _settings_of

    legacy = {
        "time_step": 1e-5,
        "gamma": 0.5,
        "beta": 0.25,
        "hht_alpha": 0.0,
        "linear_solver": "auto",
        "residual_tolerance": 1e-10,
        "increment_tolerance": 1e-10,
        "max_iterations": 25,
        "max_halvings": 6,
    }
    assert _settings_of(legacy) == cf.SolverSettings(time_step=1e-5)
    fox = {**legacy, "method": "fox_goodwin"}
    assert _settings_of(fox) == cf.SolverSettings("fox_goodwin", time_step=1e-5)
