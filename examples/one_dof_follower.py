# SPDX-License-Identifier: BSD-3-Clause
"""A 1-DOF follower on a rigid cam: mass, rod stiffness (the contact), return spring.

The follower (mass m) rides a flat face on a rigid cam through its rod (stiffness k, a linear contact
that can only push) and is held down by a preloaded return spring (k_s). In contact it is an undamped
oscillator with f_n = sqrt((k + k_s) / m) / 2 pi driven by the lift. After a cycloidal rise of duration
T_r it keeps a residual vibration whose amplitude, relative to the rise L_eff = L k / (k + k_s) it
follows statically, is the textbook closed form

    A / L_eff = |sin(pi tau)| / (pi tau |tau^2 - 1|),   tau = T_r f_n.

Run it: python examples/one_dof_follower.py
"""

import camfollower as cf
import numpy as np

MASS, ROD, SPRING, PRELOAD = 0.5, 2.0e6, 2.0e4, 3000.0  # kg, N/m, N/m, N (enough to keep contact)
LIFT, RISE = 0.001, np.radians(90.0)  # m, rad of cam angle


def program():
    law = cf.MotionLaw.cycloidal()
    return cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.dwell(), 0.0, np.radians(30), 0.0, 0.0),
            cf.Segment(law, np.radians(30), np.radians(30) + RISE, 0.0, LIFT),
            cf.Segment(cf.MotionLaw.dwell(), np.radians(30) + RISE, np.radians(240), LIFT, LIFT),
            cf.Segment(law, np.radians(240), 2 * np.pi, LIFT, 0.0),
        ]
    )


def natural_frequency():
    return np.sqrt((ROD + SPRING) / MASS) / (2 * np.pi)


def follower(tau):
    """The mechanism whose rise lasts tau natural periods."""
    b = cf.MechanismBuilder()
    b.add_dof("y", MASS, direction=(0, 1, 0))
    b.add_spring("return_spring", "y", "ground", stiffness=SPRING, preload=PRELOAD)
    b.add_contact("cam", program(), cf.TranslatingFlat(base_radius=0.040), follower_dof="y", stiffness=ROD)
    rise_time = tau / natural_frequency()
    b.camshaft_speed_rpm = RISE / rise_time * 60 / (2 * np.pi)
    return b.build()


# Run up to the middle of the top dwell (200 deg) and record only the dwell after the rise has ended
# (from 120 deg on; the row at its very start is left out).
RUN = dict(revolutions=200 / 360, record_last_revolutions=(80 - 1e-6) / 360)


def amplitude_of(mech, r):
    """Residual vibration amplitude of a run of `mech` on the dwell, relative to L_eff."""
    assert not r.contact_loss["cam"], "the follower must stay on the cam"
    wn = 2 * np.pi * natural_frequency()
    y_static = mech.static_equilibrium(np.radians(150))[0]
    z, v = r.q[:, 0] - y_static, r.v[:, 0]
    amplitude = np.sqrt(z**2 + (v / wn) ** 2)
    return float(np.mean(amplitude)) / (LIFT * ROD / (ROD + SPRING))


def residual_amplitude(tau, steps_per_period=4000):
    """Simulated residual vibration amplitude after the rise, relative to L_eff."""
    mech = follower(tau)
    r = cf.simulate(mech, time_step=1 / natural_frequency() / steps_per_period, **RUN)
    return amplitude_of(mech, r)


def residual_amplitudes(taus, steps_per_period=4000):
    """residual_amplitude for every tau at once: the runs share the step, so simulate_many runs them
    together on the machine's cores (each exactly as simulate runs it alone)."""
    mechs = [follower(tau) for tau in taus]
    runs = cf.simulate_many(mechs, time_step=1 / natural_frequency() / steps_per_period, **RUN)
    return [amplitude_of(m, r) for m, r in zip(mechs, runs)]


def closed_form(tau):
    return abs(np.sin(np.pi * tau)) / (np.pi * tau * abs(tau**2 - 1))


if __name__ == "__main__":
    print(f"f_n = {natural_frequency():.1f} Hz")
    print(f"{'tau':>6} {'simulated A/L':>14} {'closed form':>12} {'difference':>11}")
    taus = (0.75, 1.5, 2.5, 3.3, 5.5, 8.0)
    for tau, a in zip(taus, residual_amplitudes(taus)):
        e = closed_form(tau)
        print(f"{tau:6.2f} {a:14.7f} {e:12.7f} {a - e:11.1e}")
