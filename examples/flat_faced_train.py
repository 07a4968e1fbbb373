# SPDX-License-Identifier: BSD-3-Clause
"""A flat-faced tappet held on its cam by a valve spring with its own mass: spring surge, in its simplest form.

The tappet (DOF "follower", mass m_f, moving along +y, away from the cam) rides a flat face on the
cam (TranslatingFlat, face angle 0): the contact acts as a linear spring k_c, which can only push,
from the rigid cam to the tappet. The valve spring (stiffness k_s, mass m_s) is cut at its middle:
half its mass, m_m = m_s / 2, sits there (DOF "spring_mid"), and the two halves are springs of 2 k_s
each, tappet to middle and middle to ground, so that in series they give k_s. The spring is fitted
compressed: both halves carry the same preload P (N), so the middle is balanced at zero deflection
and the tappet is pressed onto the cam by P. Gravity acts along -y. All in SI units (m, kg, N, s,
rad); the camshaft turns at a constant speed (rpm).

Quasi-static (slow camshaft) the middle moves half as far as the tappet, and the contact force is

    F(theta) = [P + k_s h + (m_f + m_m / 2) g + (m_f + m_m / 4) omega^2 h''] / (1 + k_s / k_c),

with h(theta) the lift and h'' = d2h/dtheta2. The inertia term grows with omega^2: where h'' < 0
(the deceleration at the top of the rise and the start of the return) it subtracts from the
spring force, and the tappet leaves the cam once it exceeds it. Bounds on that speed follow from
F_spring_min = m |h''|_max omega^2: with the smallest holding force (P and the weight
W = (m_f + m_m / 2) g) and the largest mass (m_f + m_m) it cannot be lower (quasi-statically), and
with the largest holding force (P + k_s L + W) and the smallest mass (m_f) it cannot be higher.
Each run starts at rest on the base circle. Nothing is damped, so a second revolution also carries
the vibration left by the first.

Run it: python examples/flat_faced_train.py
"""

import camfollower as cf
import numpy as np

TAPPET_MASS, SPRING_MASS = 0.1, 0.04  # kg: m_f and the spring's own mass m_s
MID_MASS = SPRING_MASS / 2  # kg: m_m, half the spring lumped at its middle
SPRING, PRELOAD = 3.0e4, 250.0  # N/m (k_s, the whole spring), N (P)
CONTACT = 2.0e8  # N/m: the cam/tappet contact (linear)
GRAVITY = 9.81  # m/s^2, along -y
BASE_RADIUS, LIFT = 0.020, 0.008  # m
RPM = 1500.0  # operating camshaft speed
TIME_STEP = 1e-6  # s: about 140 steps per period of the contact mode (7.1 kHz)


def program():
    """Dwell, cycloidal rise of 8 mm over 120 deg, dwell, cycloidal return over 120 deg, dwell."""
    rise, dwell, d = cf.MotionLaw.cycloidal(), cf.MotionLaw.dwell(), np.radians
    return cf.MotionProgram(
        [
            cf.Segment(dwell, 0.0, d(60), 0.0, 0.0),
            cf.Segment(rise, d(60), d(180), 0.0, LIFT),
            cf.Segment(dwell, d(180), d(200), LIFT, LIFT),
            cf.Segment(rise, d(200), d(320), LIFT, 0.0),
            cf.Segment(dwell, d(320), 2 * np.pi, 0.0, 0.0),
        ]
    )


def follower():
    return cf.TranslatingFlat(base_radius=BASE_RADIUS, face_angle=0.0)


def mechanism(rpm=RPM):
    b = cf.MechanismBuilder()
    b.add_dof("follower", TAPPET_MASS, direction=(0, 1, 0))
    b.add_dof("spring_mid", MID_MASS, direction=(0, 1, 0))
    # Force on the first DOF: -(P + 2 k_s (q_a - q_b)). The same preload in both halves: the spring
    # is compressed as a whole, so the middle is in balance and P presses the tappet onto the cam.
    b.add_spring("spring_top", "follower", "spring_mid", stiffness=2 * SPRING, preload=PRELOAD)
    b.add_spring("spring_bottom", "spring_mid", "ground", stiffness=2 * SPRING, preload=PRELOAD)
    b.set_gravity((0.0, -GRAVITY, 0.0))
    b.add_contact("cam", program(), follower(), follower_dof="follower", stiffness=CONTACT)
    b.camshaft_speed_rpm = rpm
    return b.build()


def run(rpm=RPM, revolutions=1.0, time_step=TIME_STEP, **options):
    """One run from rest on the base circle (the static equilibrium at theta = 0)."""
    return cf.simulate(mechanism(rpm), revolutions=revolutions, time_step=time_step, **options)


def loses_contact(rpm, revolutions=1.0):
    return bool(run(rpm, revolutions)["contact_loss"]["cam"])


def separation_speed(holds=RPM, loses=12000.0, resolution=10.0):
    """The lowest camshaft speed (rpm) at which the tappet leaves the cam in its first revolution,
    by bisection between a speed where it holds and one where it does not. Returns (holds, loses, runs)."""
    if loses_contact(holds) or not loses_contact(loses):
        raise ValueError(f"the bracket ({holds}, {loses}) rpm does not straddle the separation speed")
    runs = 2
    while loses - holds > resolution:
        middle = 0.5 * (holds + loses)
        holds, loses = (holds, middle) if loses_contact(middle) else (middle, loses)
        runs += 1
    return holds, loses, runs


def quasi_static_force(theta, rpm):
    """The closed form above (N), at cam angle theta (rad)."""
    m = program().evaluate(theta)
    omega = rpm * 2 * np.pi / 60
    return (
        PRELOAD
        + SPRING * m["h"]
        + (TAPPET_MASS + MID_MASS / 2) * GRAVITY
        + (TAPPET_MASS + MID_MASS / 4) * omega**2 * m["d2h"]
    ) / (1 + SPRING / CONTACT)


def separation_bounds():
    """(lower, upper) camshaft speeds (rpm) from F_spring_min = m |h''|_max omega^2."""
    h2_max = np.abs(program().evaluate(np.linspace(0, 2 * np.pi, 72001))["d2h"]).max()
    weight = (TAPPET_MASS + MID_MASS / 2) * GRAVITY
    lower = np.sqrt((PRELOAD + weight) / ((TAPPET_MASS + MID_MASS) * h2_max))
    upper = np.sqrt((PRELOAD + SPRING * LIFT + weight) / (TAPPET_MASS * h2_max))
    return lower * 60 / (2 * np.pi), upper * 60 / (2 * np.pi)


if __name__ == "__main__":
    follower().check(program())
    f = mechanism().modal_analysis(0.0)["frequencies_hz"]
    print(f"on the cam: surge mode {f[0]:.1f} Hz, tappet on its contact {f[1]:.1f} Hz")
    theta = np.linspace(0, 2 * np.pi, 7201)
    print(f"{'rpm':>6} {'min F simulated (N)':>20} {'min F quasi-static (N)':>23} {'contact lost':>13}")
    for rpm in (10, RPM, 3000, 4500, 5500, 6000):
        r = run(rpm, time_step=1e-4 if rpm < 100 else TIME_STEP)  # slow: nothing to resolve but the lift
        print(
            f"{rpm:6.0f} {r['cam.force'].min():20.3f} {quasi_static_force(theta, rpm).min():23.3f} "
            f"{str(bool(r.contact_loss['cam'])):>13}"
        )
    lower, upper = separation_bounds()
    holds, loses, runs = separation_speed()
    print(
        f"separation (first revolution from rest): between {holds:.0f} and {loses:.0f} rpm ({runs} runs); "
        f"bounds from F_spring_min = m |h''|max omega^2: {lower:.0f} .. {upper:.0f} rpm"
    )
