# SPDX-License-Identifier: BSD-3-Clause
"""The paper's literal backlash (its eqs 12-18) as a named option of the paper preset: the rod's side
imposed by the program, the offset e +- b in the contact geometry, K_rb anchored on the displaced rod."""

import math
import pickle

import camfollower as cf
import numpy as np
import pytest

B = 1e-4  # m
WIDTH = math.radians(10.0)


def side(theta, width=WIDTH):
    """The imposed side written again from the paper's rule: +1 from each rise on, -1 from each return on
    (the paper cam: rise 30-180 deg, return 210-360 deg), ramped by a C1 smoothstep over ``width``."""
    theta = np.mod(theta, 2 * np.pi)

    def ramp(since, start, end):
        x = np.clip(since / width, 0.0, 1.0) if width > 0 else (since >= 0).astype(float)
        return start + (end - start) * x * x * (3 - 2 * x)

    rise, ret = math.radians(30), math.radians(210)
    after_rise = (theta >= rise) & (theta < ret)
    return np.where(after_rise, ramp(theta - rise, -1.0, 1.0), ramp(np.mod(theta - ret, 2 * np.pi), 1.0, -1.0))


def test_pressure_angle_follows_the_imposed_offset():
    """Over a revolution the contact's pressure angle is atan((h' - e') / (s0' + h)) (paper eq 4) at
    e' = e + b s(theta), s0' = sqrt((r_b + r_r)^2 - e'^2), written here from the paper's rule."""
    m = cf.presets.paper(paper_backlash=B, paper_backlash_switch_width=WIDTH)
    r = cf.simulate(m, revolutions=1, time_step=m.period / 3600)
    theta = np.asarray(r["theta"])
    p = cf.Parameters()
    e = p.offset + B * side(theta)
    s0 = np.sqrt((p.base_radius + p.roller_radius) ** 2 - e**2)
    k = cf.MotionProgram.paper_default().evaluate(theta)
    expected = np.arctan((np.asarray(k["dh"]) - e) / (s0 + np.asarray(k["h"])))
    np.testing.assert_allclose(r["cam.pressure_angle"], expected, rtol=0, atol=1e-12)
    # The healthy preset's differs by the offset's share: about b / (s0 + h) rad.
    healthy = cf.simulate(cf.presets.paper(), revolutions=1, time_step=m.period / 3600)
    assert np.max(np.abs(np.asarray(healthy["cam.pressure_angle"]) - expected)) > 0.5 * B / 0.05


def test_the_rod_rides_on_the_imposed_side_and_the_option_survives_pickle_and_config(tmp_path):
    m = cf.presets.paper(paper_backlash=B, paper_backlash_switch_width=WIDTH)
    (contact,) = m.builder().contacts
    assert contact["paper_backlash"] == (B, WIDTH, "x3", cf.Parameters().guide_stiffness)
    # On the dwells the rod x3 sits near +b (after the rise) and -b (after the return): the guide spring
    # is anchored there, and the roller pin and bearing springs in series hold it back by only a little.
    for theta_deg, s in ((195.0, 1.0), (15.0, -1.0)):
        x3 = m.static_equilibrium(math.radians(theta_deg))[6]
        assert x3 == pytest.approx(s * B, rel=0.3), theta_deg
    back = pickle.loads(pickle.dumps(m))
    path = tmp_path / "backlash.toml"
    path.write_text(
        '[preset]\nname = "paper"\npaper_backlash = "0.1 mm"\npaper_backlash_switch_width = "10 deg"\n'
        '[camshaft]\nspeed = "750 rpm"\n'
    )
    from_config = cf.load_config(path).mechanism
    runs = [cf.simulate(x, revolutions=0.25, time_step=m.period / 3600) for x in (m, back, from_config)]
    for other in runs[1:]:
        np.testing.assert_allclose(other.q, runs[0].q, rtol=0, atol=1e-15)


@pytest.mark.parametrize(
    "options, message",
    [
        (dict(paper_backlash=1e-4, guide_clearance=1e-4), "two models of the same guide clearance"),
        (dict(paper_backlash=-1e-4), "paper_backlash must be finite and >= 0"),
        (dict(paper_backlash_switch_width=0.1), "paper_backlash_switch_width needs a paper_backlash > 0"),
        (dict(paper_backlash=1e-4, paper_backlash_switch_width=4.0), r"paper_backlash_switch_width \(rad\) must be in"),
        (dict(paper_backlash=0.05), "paper backlash 0.05 m with \\|offset\\| = 0.01 m make the offset reach"),
    ],
)
def test_bad_paper_backlash_is_refused_by_name(options, message):
    with pytest.raises(ValueError, match=message):
        cf.presets.paper(**options)
