# SPDX-License-Identifier: BSD-3-Clause
"""A swing-arm (oscillating) roller follower on a disk cam, held on it by a torsional spring.

The cam centre is the origin of the ground frame and the cam turns counter-clockwise. The arm turns
about a fixed pivot P = (0.06, 0.05) m; its roller (radius r_r = 8 mm) at the arm length L = 60 mm
from the pivot rolls on the cam (base radius r_b = 30 mm). The one DOF, "arm", is the arm's rotation
(rad, counter-clockwise = lifting) from its angle on the base circle; its "mass" is the arm's moment
of inertia about the pivot J (kg m^2). A torsional return spring to ground (k_t, N m/rad) with a
preload torque T0 (N m) turns it back onto the cam. The lift program is the arm rotation s(theta)
in rad: a 15 deg cycloidal rise over 90 deg of cam, a dwell, the same return, and dwells.

The contact is a linear spring k_c (N/m) along the contact normal n: the penetration is
delta = lever (s(theta) - q) with lever = L cos(alpha) (m per rad), alpha the pressure angle between
n and the roller centre's direction of motion, and the contact force F = k_c delta (N) turns the arm
with the torque F lever. Hence, at rest,

    F L cos(alpha) = T0 + k_t q,      s - q = (T0 + k_t s) / (k_c lever^2 + k_t),

and the arm on the cam is an oscillator with f_n = sqrt((k_t + k_c lever^2) / J) / 2 pi. On a dwell
the cam surface is an arc about the cam centre, so n points from the cam centre to the roller centre.
SI units: m, kg, kg m^2, N, N m, rad, s; camshaft speed in rpm.

Run it: python examples/swing_arm_follower.py
"""

import camfollower as cf
import numpy as np

INERTIA = 2.0e-4  # kg m^2: J of the arm about its pivot
TORSION, PRELOAD_TORQUE = 20.0, 3.0  # N m/rad (k_t), N m (T0)
CONTACT = 1.0e8  # N/m: roller/cam contact (linear)
BASE_RADIUS, ROLLER_RADIUS = 0.030, 0.008  # m
PIVOT, ARM_LENGTH = (0.06, 0.05), 0.060  # m (ground frame), m
SWING = np.radians(15.0)  # rad: the arm's total rotation
RPM = 600.0  # operating camshaft speed
TIME_STEP = 2e-6  # s: about 75 steps per period of the arm on the cam (6.6 kHz)


def program():
    rise, dwell, d = cf.MotionLaw.cycloidal(), cf.MotionLaw.dwell(), np.radians
    return cf.MotionProgram(
        [
            cf.Segment(dwell, 0.0, d(60), 0.0, 0.0),
            cf.Segment(rise, d(60), d(150), 0.0, SWING),
            cf.Segment(dwell, d(150), d(210), SWING, SWING),
            cf.Segment(rise, d(210), d(300), SWING, 0.0),
            cf.Segment(dwell, d(300), 2 * np.pi, 0.0, 0.0),
        ]
    )


def follower():
    return cf.OscillatingRoller(
        base_radius=BASE_RADIUS, roller_radius=ROLLER_RADIUS, pivot=PIVOT, arm_length=ARM_LENGTH
    )


def mechanism(rpm=RPM, phase=0.0):
    """phase (rad): the cam's angle at t = 0, so that the run starts at rest at that cam angle."""
    b = cf.MechanismBuilder()
    b.add_dof("arm", INERTIA)  # a rotation: no direction, no gravity
    b.add_spring("return_spring", "arm", "ground", stiffness=TORSION, preload=PRELOAD_TORQUE)
    b.add_contact("cam", program(), follower(), follower_dof="arm", stiffness=CONTACT, phase=phase)
    b.camshaft_speed_rpm = rpm
    return b.build()


def run(rpm=RPM, revolutions=1.0, time_step=TIME_STEP, **options):
    """One run from rest on the base circle (the static equilibrium at theta = 0)."""
    return cf.simulate(mechanism(rpm), revolutions=revolutions, time_step=time_step, **options)


def rest_on_cam(theta):
    """(arm angle q in rad, contact force F in N) at rest at cam angle theta (rad): the static
    equilibrium, and the force the contact law gives there (the first row of a run started there)."""
    mech = mechanism(phase=theta)
    r = cf.simulate(mech, duration=TIME_STEP, time_step=TIME_STEP)
    return float(mech.initial_state[0]), float(r["cam.force"][0])


if __name__ == "__main__":
    follower().check(program())
    theta_a, alpha_max = follower().max_pressure_angle(program())
    print(
        f"arm on the base circle at {np.degrees(follower().start_angle):.2f} deg; "
        f"largest pressure angle {np.degrees(alpha_max):.2f} deg at theta = {np.degrees(theta_a):.1f} deg"
    )
    print(
        f"{'dwell':>8} {'s (deg)':>8} {'q (deg)':>10} {'F (N)':>9} {'F lever (N m)':>14} "
        f"{'T0 + k_t q':>11} {'f_n (Hz)':>9}"
    )
    for name, theta in (("base", np.radians(30)), ("top", np.radians(180))):
        q, force = rest_on_cam(theta)
        lever = follower().contact(program(), theta)["lever"]
        f_n = mechanism().modal_analysis(theta)["frequencies_hz"][0]
        s = program().evaluate(theta)["h"]
        print(
            f"{name:>8} {np.degrees(s):8.3f} {np.degrees(q):10.5f} {force:9.3f} {force * lever:14.6f} "
            f"{PRELOAD_TORQUE + TORSION * q:11.6f} {f_n:9.1f}"
        )
    for rpm in (1.0, RPM):
        r = run(rpm, time_step=1e-3 if rpm < 10 else TIME_STEP)  # slow: nothing to resolve but the lift
        lag = program().evaluate(r["theta"])["h"] - r.q[:, 0]
        print(
            f"{rpm:6.0f} rpm: contact force {r['cam.force'].min():.2f} .. {r['cam.force'].max():.2f} N, "
            f"s - q {lag.min():.3e} .. {lag.max():.3e} rad, contact lost: {bool(r.contact_loss['cam'])}"
        )
