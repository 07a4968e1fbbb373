# SPDX-License-Identifier: BSD-3-Clause
"""One vocabulary of integration methods: the C++ table (solver/settings.hpp) is what Python, the config,
the error messages and the docs list, and each name runs as itself."""

import re
from pathlib import Path

import camfollower as cf
import pytest

ROOT = Path(__file__).resolve().parents[2]
NAMES = ("newmark", "fox_goodwin", "hht", "dormand_prince", "dop853", "radau", "auto")


def test_python_reads_the_table_in_its_order():
    assert tuple(cf.METHODS) == NAMES
    for name, traits in cf.METHODS.items():
        assert traits["summary"], name
    assert [cf.METHODS[n]["order"] for n in ("dormand_prince", "dop853", "radau")] == [5, 8, 5]


def test_docs_list_every_method_and_no_other():
    text = (ROOT / "docs" / "solvers.md").read_text()
    table = text[text.index("| method | kind |") : text.index("## Choosing")]
    listed = {m.group(1) for m in re.finditer(r"^\| `(\w+)`", table, re.M)}
    assert listed == set(NAMES)
    scheme_row = next(line for line in (ROOT / "docs" / "config.md").read_text().splitlines() if "| `scheme` |" in line)
    for name in NAMES:
        assert f'"{name}"' in scheme_row, name


def test_an_unknown_name_is_refused_with_the_list():
    m = cf.presets.paper()
    listed = ", ".join(f"'{n}'" for n in NAMES[:-1]) + f" or '{NAMES[-1]}'"
    with pytest.raises(ValueError, match=re.escape(f"method must be {listed}, got 'rk4'")):
        cf.simulate(m, revolutions=0.01, method="rk4")
    with pytest.raises(ValueError, match=re.escape(f"method must be {listed}, got 'rk4'")):
        cf.periodic_steady_state(m, time_step=m.period / 1024, method="rk4")
    with pytest.raises(ValueError, match=r'scheme: must be one of "average_acceleration", "newmark", "fox_goodwin", '):
        cf.config_from_dict(
            {"camshaft": {"speed": "750 rpm"}, "preset": {"name": "paper"}, "solver": {"scheme": "rk4"}}
        )


@pytest.mark.parametrize("name", NAMES)
def test_each_name_runs_as_itself(name):
    m = cf.presets.paper()
    r = cf.simulate(m, revolutions=0.02, time_step=m.period / 8192, method=name)
    assert r.stats["requested_method"] == name
    if name == "auto":
        assert r.stats["method"] == "fox_goodwin"  # T/8192 is within its stability limit on the preset
    else:
        assert r.stats["method"] == name
    # The Runge-Kutta methods run under their default tolerance, the Newmark family at fixed steps.
    if name in ("dormand_prince", "dop853", "radau"):
        assert r.stats["evaluations"] > 0
    else:
        assert r.stats["steps"] == round(0.02 * 8192)


def test_the_config_names_the_same_methods():
    for name in NAMES:
        solver = {"scheme": name, **({"gamma": 0.5, "beta": 0.25} if name == "newmark" else {})}
        cfg = cf.config_from_dict({"camshaft": {"speed": "750 rpm"}, "preset": {"name": "paper"}, "solver": solver})
        assert cfg.simulate_kwargs()["method"] == name
    # average_acceleration: the config's name for newmark at gamma 1/2, beta 1/4.
    kw = cf.config_from_dict(
        {"camshaft": {"speed": "750 rpm"}, "preset": {"name": "paper"}, "solver": {}}
    ).simulate_kwargs()
    assert kw["method"] == "newmark" and "gamma" not in kw  # the defaults, 1/2 and 1/4
    kw = cf.config_from_dict(
        {
            "camshaft": {"speed": "750 rpm"},
            "preset": {"name": "paper"},
            "solver": {"scheme": "newmark", "gamma": 0.6, "beta": 0.3025},
        }
    ).simulate_kwargs()
    assert (kw["gamma"], kw["beta"]) == (0.6, 0.3025)
    # A config's run with another method: the config's Newmark parameters do not follow it.
    cfg = cf.config_from_dict(
        {"camshaft": {"speed": "750 rpm"}, "preset": {"name": "paper"}, "solver": {"scheme": "average_acceleration"}}
    )
    assert cfg.run(method="dop853", revolutions=0.01).stats["method"] == "dop853"
    kw = cf.config_from_dict(
        {"camshaft": {"speed": "750 rpm"}, "preset": {"name": "paper"}, "solver": {"scheme": "hht"}}
    ).simulate_kwargs()
    assert kw["hht_alpha"] == -0.05 and "gamma" not in kw
    kw = cf.config_from_dict(
        {"camshaft": {"speed": "750 rpm"}, "preset": {"name": "paper"}, "solver": {"scheme": "dop853"}}
    ).simulate_kwargs()
    assert kw["tolerance"] == cf._core.RUNGE_KUTTA_DEFAULT_TOLERANCE == 1e-6


def test_the_config_refuses_parameters_of_another_method():
    base = {"camshaft": {"speed": "750 rpm"}, "preset": {"name": "paper"}}
    for scheme in ("fox_goodwin", "average_acceleration", "dop853"):
        with pytest.raises(
            ValueError, match=rf'solver.gamma: applies only with scheme = "newmark" \("{scheme}" sets its own\)'
        ):
            cf.config_from_dict({**base, "solver": {"scheme": scheme, "gamma": 0.6}})
    with pytest.raises(ValueError, match=r'solver.hht_alpha: applies only with scheme = "hht"'):
        cf.config_from_dict({**base, "solver": {"scheme": "newmark", "gamma": 0.5, "beta": 0.25, "hht_alpha": -0.1}})
