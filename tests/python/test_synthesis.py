# SPDX-License-Identifier: BSD-3-Clause
"""Polydyne compensation against independent truth: the one-mass follower's equation of motion
m y'' + c y' + k_s y = k (x - y), driven by the synthesized cam lift x and integrated by scipy at tight
tolerance, moves the output as wanted at the design speed (and not off it, nor with the uncompensated
cam); a wanted motion that is not C4 is refused where its fourth derivative jumps."""

import math

import camfollower as cf
import numpy as np
import pytest
from camfollower import synthesis
from scipy.integrate import solve_ivp

DEG = math.pi / 180.0
M, K, KS, C = 0.5, 2e5, 1e4, 5.0  # kg, N/m, N/m, N s/m: natural frequency 103 Hz
LIFT = 0.02


def c4_program():
    """Dwell, rise, dwell, return; each move a degree-9 polynomial with zero derivatives through the
    fourth at its ends, so the program is C4."""
    zero = [0.0, 0.0, 0.0, 0.0]
    return cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.dwell(), 0, 40 * DEG, 0, 0),
            cf.Segment.polynomial(40 * DEG, 160 * DEG, [0.0, *zero], [LIFT, *zero]),
            cf.Segment(cf.MotionLaw.dwell(), 160 * DEG, 200 * DEG, LIFT, LIFT),
            cf.Segment.polynomial(200 * DEG, 320 * DEG, [LIFT, *zero], [0.0, *zero]),
            cf.Segment(cf.MotionLaw.dwell(), 320 * DEG, 360 * DEG, 0, 0),
        ]
    )


def output_error(cam, desired, rpm, revolutions=1):
    """Largest |y - desired| (m) of the one-mass follower driven by `cam` at `rpm`, integrated by
    scipy's DOP853 from rest in the first dwell (written out here, sharing nothing with synthesis)."""
    omega = rpm * math.pi / 30

    def rhs(t, s):
        x = cam.evaluate(omega * t % (2 * math.pi))["h"]
        return [s[1], (K * (x - s[0]) - KS * s[0] - C * s[1]) / M]

    period = 2 * math.pi / omega
    t = np.linspace(0, revolutions * period, 4001)
    sol = solve_ivp(
        rhs, (0, t[-1]), [0.0, 0.0], method="DOP853", rtol=1e-11, atol=1e-14, t_eval=t, max_step=period / 2000
    )
    assert sol.success
    return np.abs(sol.y[0] - np.asarray(desired.evaluate(omega * t % (2 * math.pi))["h"])).max()


def test_the_compensated_cam_moves_the_output_as_wanted_at_the_design_speed_only():
    desired = c4_program()
    cam = synthesis.polydyne(desired, mass=M, stiffness=K, return_stiffness=KS, damping=C, speed_rpm=600)
    assert isinstance(cam, cf.MotionProgram)
    design = output_error(cam, desired, 600)
    plain = output_error(desired, desired, 600)  # the wanted motion cut as the cam: no compensation
    off = [output_error(cam, desired, rpm) for rpm in (480, 720)]  # +-20 %
    print(f"polydyne at 600 rpm: |y - wanted| {design:.3g} m; uncompensated {plain:.3g} m; at 480/720 rpm {off}")
    assert design < 1e-7 * LIFT
    assert plain > 1e4 * design  # the check fails without the compensation
    assert min(off) > 100 * design
    # The compensation is the closed form at the table's points: the lift grows by (m w^2 y'' + k_s y) / k.
    theta = np.linspace(0, 2 * math.pi, 721)[:-1]
    y, x = desired.evaluate(theta), cam.evaluate(theta)
    w = 600 * math.pi / 30
    written = (
        np.asarray(y["h"])
        + (M * w**2 * np.asarray(y["d2h"]) + C * w * np.asarray(y["dh"]) + KS * np.asarray(y["h"])) / K
    )
    np.testing.assert_allclose(x["h"], written, rtol=0, atol=1e-9 * LIFT)


def test_a_motion_that_is_not_c4_is_refused_where_it_jumps():
    cycloidal = cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.dwell(), 0, 40 * DEG, 0, 0),
            cf.Segment(cf.MotionLaw.cycloidal(), 40 * DEG, 160 * DEG, 0, LIFT),
            cf.Segment(cf.MotionLaw.dwell(), 160 * DEG, 200 * DEG, LIFT, LIFT),
            cf.Segment(cf.MotionLaw.cycloidal(), 200 * DEG, 320 * DEG, LIFT, 0),
            cf.Segment(cf.MotionLaw.dwell(), 320 * DEG, 360 * DEG, 0, 0),
        ]
    )
    # Cycloidal motion has continuous acceleration but its jerk jumps at the ends: refused at C3.
    with pytest.raises(ValueError, match=r"continuous through its fourth derivative \(C4\).*40 deg"):
        synthesis.polydyne(cycloidal, mass=M, stiffness=K, speed_rpm=600)
    # A 4-5-6-7 polynomial has continuous jerk but its fourth derivative jumps at its ends.
    law = cf.MotionLaw.polynomial_4567()
    c3 = cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.dwell(), 0, 40 * DEG, 0, 0),
            cf.Segment(law, 40 * DEG, 160 * DEG, 0, LIFT),
            cf.Segment(cf.MotionLaw.dwell(), 160 * DEG, 200 * DEG, LIFT, LIFT),
            cf.Segment(law, 200 * DEG, 320 * DEG, LIFT, 0),
            cf.Segment(cf.MotionLaw.dwell(), 320 * DEG, 360 * DEG, 0, 0),
        ]
    )
    with pytest.raises(ValueError, match=r"y'''' jumps by .* at 40 deg: the cam's acceleration would step"):
        synthesis.polydyne(c3, mass=M, stiffness=K, speed_rpm=600)
    # The jump it reports is the law's: 840 H / beta^4 for 4-5-6-7 (h'''' = 840 H / beta^4 at its start).
    beta = 120 * DEG
    (theta, jump), *_ = synthesis.snap_jumps(c3)
    assert theta == pytest.approx(40 * DEG)
    assert jump == pytest.approx(840 * LIFT / beta**4, rel=1e-4)
    assert all(abs(j) < 1e-6 for _, j in synthesis.snap_jumps(c4_program()))


@pytest.mark.parametrize(
    "change, message",
    [
        (dict(mass=0.0), r"mass must be a finite number > 0 \(kg"),
        (dict(stiffness=-1.0), r"stiffness must be a finite number > 0"),
        (dict(return_stiffness=float("nan")), r"return_stiffness must be a finite number >= 0"),
        (dict(damping=-0.1), r"damping must be a finite number >= 0"),
        (dict(speed_rpm=1e9), r"speed_rpm must be in \["),
        (dict(points=100), r"points must be an integer in \[360, "),
    ],
)
def test_bad_parameters_are_named(change, message):
    kw = {**dict(mass=M, stiffness=K, speed_rpm=600.0), **change}
    with pytest.raises(ValueError, match=message):
        synthesis.polydyne(c4_program(), **kw)
