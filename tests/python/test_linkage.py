# SPDX-License-Identifier: BSD-3-Clause
"""A cam-driven linkage (swing arm - coupler - slider, and a four-bar) against independent truth: the
closed-form offset slider-crank and four-bar position, the output's SVAJ against finite differences,
the backward solution reproducing a wanted output, and the dynamics of the jointed bodies (stiff pin
joints) against the rigid linkage's one-DOF Lagrange equation written out here and integrated by
scipy, with the energy kept without damping."""

import math

import camfollower as cf
import numpy as np
import pytest
from scipy.integrate import solve_ivp

DEG = math.pi / 180.0
R, L, E, PHI0 = 0.10, 0.30, 0.05, 60 * DEG  # arm, coupler (m), slider line offset (m), arm angle at rest


def slider_crank(**kw):
    args = dict(
        arm_length=R,
        arm_angle=PHI0,
        coupler_length=L,
        coupler_mass=0.4,
        coupler_inertia=0.4 * L**2 / 12,
        output="slider",
        output_origin=(0.0, E),
        output_direction=0.0,
        joint_stiffness=1e9,
    )
    args.update(kw)
    return cf.CouplerLinkage("link", "arm", "slide", **args)


def four_bar(**kw):
    args = dict(
        arm_length=0.08,
        arm_angle=100 * DEG,
        coupler_length=0.25,
        coupler_mass=0.3,
        coupler_inertia=0.3 * 0.25**2 / 12,
        output="rocker",
        output_origin=(0.22, 0.02),
        output_length=0.12,
        joint_stiffness=1e9,
    )
    args.update(kw)
    return cf.CouplerLinkage("link", "arm", "rocker", **args)


def slider_x(phi):
    """The offset slider-crank's pin position along the line (closed form)."""
    return R * np.cos(phi) + np.sqrt(L**2 - (R * np.sin(phi) - E) ** 2)


def rocker_angle(phi, pivot=(0.22, 0.02), r2=0.12, length=0.25, r1=0.08):
    """The four-bar's output angle by intersecting two circles, branch to the left of the pin-to-pivot line."""
    ax, ay = r1 * np.cos(phi), r1 * np.sin(phi)
    dx, dy = pivot[0] - ax, pivot[1] - ay
    d = np.hypot(dx, dy)
    a = (length**2 - r2**2 + d**2) / (2 * d)
    h = np.sqrt(length**2 - a**2)
    bx, by = ax + (a * dx - h * dy) / d, ay + (a * dy + h * dx) / d
    return np.arctan2(by - pivot[1], bx - pivot[0])


def test_the_output_is_the_closed_form_slider_crank_and_four_bar():
    q = np.linspace(-0.6, 0.6, 41)
    np.testing.assert_allclose(slider_crank().output_at(q), slider_x(PHI0 + q) - slider_x(PHI0), rtol=0, atol=1e-15)
    bar = four_bar()
    psi = rocker_angle(100 * DEG + q)
    np.testing.assert_allclose(bar.output_at(q), psi - psi[20], rtol=0, atol=1e-14)
    # The other branch: the pin behind the perpendicular's foot.
    other = slider_crank(branch=-1)
    back = R * np.cos(PHI0 + q) - np.sqrt(L**2 - (R * np.sin(PHI0 + q) - E) ** 2)
    np.testing.assert_allclose(other.output_at(q), back - back[20], rtol=0, atol=1e-15)


def lift_program():
    dwell, law = cf.MotionLaw.dwell(), cf.MotionLaw.modified_sine()
    return cf.MotionProgram(
        [
            cf.Segment(dwell, 0, 30 * DEG, 0, 0),
            cf.Segment(law, 30 * DEG, 150 * DEG, 0, 25 * DEG),
            cf.Segment(dwell, 150 * DEG, 210 * DEG, 25 * DEG, 25 * DEG),
            cf.Segment(law, 210 * DEG, 330 * DEG, 25 * DEG, 0),
            cf.Segment(dwell, 330 * DEG, 360 * DEG, 0, 0),
        ]
    )


@pytest.mark.parametrize("make", [slider_crank, four_bar])
def test_the_output_svaj_is_the_derivative_of_the_output(make):
    link, program = make(), lift_program()
    theta = np.linspace(0.05, 2 * math.pi - 0.05, 97)
    svaj = link.svaj(program, theta)
    s = lambda x: link.output_at(program.evaluate(x)["h"])  # noqa: E731
    np.testing.assert_allclose(svaj["s"], s(theta), rtol=0, atol=1e-15)
    h = 1e-4
    for key, f in (
        ("ds", lambda x: (s(x + h) - s(x - h)) / (2 * h)),
        ("d2s", lambda x: (s(x + h) - 2 * s(x) + s(x - h)) / h**2),
    ):
        ref = f(theta)
        np.testing.assert_allclose(svaj[key], ref, rtol=0, atol=2e-6 * np.abs(ref).max())
    d2 = lambda x: link.svaj(program, x)["d2s"]  # noqa: E731
    jerk = (d2(theta + h) - d2(theta - h)) / (2 * h)
    np.testing.assert_allclose(svaj["d3s"], jerk, rtol=0, atol=1e-5 * np.abs(jerk).max())


def test_the_backward_solution_reproduces_the_wanted_output():
    # The slide shall move 40 mm by a cycloidal rise and return: the arm's lift follows from the
    # inverse linkage kinematics, as a lift table fitted by a quintic spline.
    link = slider_crank()
    dwell, cyc = cf.MotionLaw.dwell(), cf.MotionLaw.cycloidal()
    wanted = cf.MotionProgram(
        [
            cf.Segment(dwell, 0, 20 * DEG, 0, 0),
            cf.Segment(cyc, 20 * DEG, 160 * DEG, 0, -0.04),
            cf.Segment(dwell, 160 * DEG, 200 * DEG, -0.04, -0.04),
            cf.Segment(cyc, 200 * DEG, 340 * DEG, -0.04, 0),
            cf.Segment(dwell, 340 * DEG, 360 * DEG, 0, 0),
        ]
    )
    lift = link.backward(wanted, points=3600)
    theta = np.linspace(0, 2 * math.pi, 7919, endpoint=False) + 1e-4  # off the table's nodes
    got = link.output_at(lift.evaluate(theta)["h"])
    err = np.abs(got - wanted.evaluate(theta)["h"]).max()
    print(f"backward solution: output error {err:.2e} m over a 40 mm stroke")
    assert err < 1e-9
    assert np.abs(lift.evaluate(theta)["h"]).max() > 0.2  # the arm turns by more than 10 deg


class RigidSliderCrank:
    """The rigid linkage as one DOF, the arm's displacement q (phi = PHI0 + q): kinetic energy
    M(phi) q'^2 / 2 with M = J_arm + m_s x'^2 + m_c |c'|^2 + J_c beta'^2 (x the slide, c the coupler's
    centre, beta its angle, all closed-form in phi), the springs' potential V; Lagrange:
    M q'' + M' q'^2 / 2 + V' = 0, M' by a complex step (exact to rounding: every expression is analytic)."""

    J_ARM, M_SLIDE, M_C = 2e-3, 1.5, 0.4
    J_C = 0.4 * L**2 / 12
    K_ARM, K_SLIDE = 30.0, 4e3  # N m/rad to ground on the arm, N/m on the slide

    @staticmethod
    def rates(phi):
        """x', c_x', c_y', beta' per radian of arm angle."""
        s, c = np.sin(phi), np.cos(phi)
        S = np.sqrt(L**2 - (R * s - E) ** 2)
        dS = -(R * s - E) * R * c / S
        dx = -R * s + dS
        dbeta = (-S * R * c - (E - R * s) * dS) / L**2
        return dx, 0.5 * (-R * s + dx), 0.5 * R * c, dbeta

    def inertia(self, phi):
        dx, dcx, dcy, dbeta = self.rates(phi)
        return self.J_ARM + self.M_SLIDE * dx**2 + self.M_C * (dcx**2 + dcy**2) + self.J_C * dbeta**2

    def rhs(self, t, y):
        q, v = y
        phi = PHI0 + q
        dM = self.inertia(phi + 1e-30j).imag / 1e-30
        dV = self.K_ARM * q + self.K_SLIDE * (slider_x(phi) - slider_x(PHI0)) * self.rates(phi)[0]
        return [v, -(0.5 * dM * v * v + dV) / self.inertia(phi)]


def run_jointed(stiffness, w0=8.0, duration=0.25):
    """The slider-crank as jointed bodies (arm, slide, coupler; springs to ground) swinging freely from
    q = 0 with the arm at w0 rad/s and the rest at the rigid linkage's velocities."""
    model = RigidSliderCrank()
    b = cf.MechanismBuilder()
    b.add_dof("arm", model.J_ARM)
    b.add_dof("slide", model.M_SLIDE)
    b.add_spring("arm_spring", "arm", stiffness=model.K_ARM)
    b.add_spring("slide_spring", "slide", stiffness=model.K_SLIDE)
    b.add_linkage(slider_crank(coupler_mass=model.M_C, coupler_inertia=model.J_C, joint_stiffness=stiffness))
    mech = b.build()

    def rigid(q):  # arm, slide, coupler centre and angle of the rigid linkage at arm displacement q
        phi = PHI0 + q
        ax, ay, bx = R * math.cos(phi), R * math.sin(phi), slider_x(phi)
        return np.array([q, bx, 0.5 * (ax + bx), 0.5 * (ay + E), math.atan2(E - ay, bx - ax)])

    h = 1e-7
    v0 = w0 * (rigid(h) - rigid(-h)) / (2 * h)
    r = cf.simulate(
        mech, duration=duration, method="dop853", tolerance=1e-9, time_step=5e-4, initial_state=(np.zeros(5), v0)
    )
    return model, mech, r


def test_the_jointed_bodies_move_as_the_rigid_linkage_and_keep_their_energy():
    model, mech, r = run_jointed(1e9)
    assert mech.dof_names == ["arm", "slide", "link.x", "link.y", "link.angle"]
    np.testing.assert_allclose(mech.initial_state, 0.0, atol=1e-15)  # assembled, unloaded at q = 0
    ref = solve_ivp(model.rhs, (0, 0.25), [0.0, 8.0], method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    q_ref = ref.sol(r.t)[0]
    arm_err = np.abs(r.q[:, 0] - q_ref).max()
    slide_err = np.abs(r.q[:, 1] - (slider_x(PHI0 + q_ref) - slider_x(PHI0))).max()
    print(
        f"jointed (1e9 N/m) vs rigid linkage: arm {arm_err:.2e} rad of {np.abs(q_ref).max():.3f}, slide {slide_err:.2e} m"
    )
    assert np.abs(q_ref).max() > 0.1
    assert arm_err < 2e-5 * np.abs(q_ref).max() and slide_err < 2e-7
    assert 0 < r["link.input.stretch"].max() < 1e-7  # stiff joints: the linkage holds together
    # The joints' compliance is the whole difference: ten times stiffer, ten times closer.
    _, _, soft = run_jointed(1e8)
    soft_err = np.abs(soft.q[:, 0] - q_ref).max()
    assert 7 < soft_err / arm_err < 13
    # No damping: kinetic + spring + joint energy stays what it was.
    M = np.diag([model.J_ARM, model.M_SLIDE, model.M_C, model.M_C, model.J_C])
    kinetic = 0.5 * np.einsum("ij,jk,ik->i", r.v, M, r.v)
    joints = 0.5 * 1e9 * (r["link.input.stretch"] ** 2 + r["link.output.stretch"] ** 2)
    energy = kinetic + 0.5 * model.K_ARM * r.q[:, 0] ** 2 + 0.5 * model.K_SLIDE * r.q[:, 1] ** 2 + joints
    print(f"energy {energy[0]:.6g} J, drift {np.abs(energy - energy[0]).max():.2e} J")
    assert np.abs(energy - energy[0]).max() < 1e-7 * energy[0]


def test_bad_linkages_are_refused_naming_the_value():
    with pytest.raises(ValueError, match="cannot reach the slider's line"):
        slider_crank(output_origin=(0.0, 0.5)).output_at(0.0)
    with pytest.raises(ValueError, match="four-bar cannot close"):
        four_bar(output_length=0.005)
    with pytest.raises(ValueError, match="branch must be"):
        slider_crank(branch=0)
    with pytest.raises(ValueError, match="coupler_mass"):
        slider_crank(coupler_mass=0.0)
    with pytest.raises(ValueError, match="joint_stiffness"):
        slider_crank(joint_stiffness=-1.0)
    with pytest.raises(ValueError, match="coupler_length must be in"):
        slider_crank(coupler_length=float("nan"))
    # Over the lift, the linkage must close at every angle: a lift that swings the arm past it is refused.
    short = slider_crank(coupler_length=0.07, output_origin=(0.0, 0.15), arm_turn="clockwise")
    assert abs(short.output_at(0.1)) < 0.02  # it closes there
    with pytest.raises(ValueError, match="cannot reach the slider's line at arm displacement 0.3 rad"):
        short.output_at(np.array([0.0, 0.3]))
    b = cf.MechanismBuilder()
    b.add_dof("arm", 1e-3)
    b.add_dof("slide", 1.0)
    b.add_spring("s", "arm", stiffness=10.0, preload=-1.0)
    b.add_linkage(short)
    swing = cf.MotionProgram(
        [
            cf.Segment(cf.MotionLaw.cycloidal(), 0, math.pi, 0, 0.3),
            cf.Segment(cf.MotionLaw.cycloidal(), math.pi, 2 * math.pi, 0.3, 0),
        ]
    )
    b.add_contact("cam", swing, cf.OscillatingRoller(0.05, 0.01, (0.2, 0.0), 0.15), follower_dof="arm", stiffness=1e8)
    with pytest.raises(ValueError, match=r"linkage 'link'.*cannot reach.*contact 'cam' turns the arm there"):
        b.build()
    with pytest.raises(ValueError, match="defined twice|is taken"):
        b.add_linkage(short)


def linkage_config(**changes):
    link = {
        "name": "link",
        "arm_dof": "arm",
        "arm_length": "100 mm",
        "arm_angle": "60 deg",
        "coupler": {"length": "300 mm", "mass": "0.4 kg", "inertia": "3e-3 kg m^2"},
        "output": {"type": "slider", "dof": "slide", "origin": ["0 mm", "50 mm"]},
        "joint_stiffness": "1 N/um",
    }
    link.update(changes)
    return {
        "camshaft": {"speed": "100 rpm"},
        "program": {
            "swing": {
                "segments": [
                    {"law": "cycloidal", "end": "180 deg", "h": "10 deg"},
                    {"law": "cycloidal", "end": "360 deg", "h": 0},
                ]
            }
        },
        "dof": [{"name": "arm", "mass": "1e-3 kg m^2"}, {"name": "slide", "mass": "1 kg"}],
        "spring": [{"name": "s", "a": "arm", "stiffness": "100 N m/rad", "preload": "5 N m"}],
        "contact": [
            {
                "name": "cam",
                "program": "swing",
                "follower_dof": "arm",
                "stiffness": 1e8,
                "follower": {
                    "type": "oscillating_roller",
                    "base_radius": "40 mm",
                    "roller_radius": "10 mm",
                    "pivot": ["120 mm", "0 mm"],
                    "arm_length": "100 mm",
                },
            }
        ],
        "linkage": [link],
    }


def test_the_config_reads_a_linkage_and_names_bad_keys():
    from camfollower.config import config_from_dict

    case = config_from_dict(linkage_config())
    (link,) = case.builder.linkages
    assert (link.arm_length, link.arm_angle, link.coupler_length, link.output) == (
        pytest.approx(0.1),
        pytest.approx(60 * DEG),
        pytest.approx(0.3),
        "slider",
    )
    q = np.linspace(-0.2, 0.2, 9)
    np.testing.assert_allclose(link.output_at(q), slider_crank().output_at(q), rtol=0, atol=1e-15)
    assert case.mechanism.dof_names == ["arm", "slide", "link.x", "link.y", "link.angle"]
    for bad, where in (
        (
            {"coupler": {"length": "300 mm", "mass": "0.4 kg"}},
            r"linkage\[0\]\.coupler: the key 'inertia' is required",
        ),
        ({"output": {"type": "piston", "dof": "slide", "origin": [0, 0.05]}}, "output.type"),
        ({"output": {"type": "slider", "dof": "slide", "origin": [0, 0.05], "branch": 0}}, "output.branch"),
        ({"arm_dof": "nowhere"}, "arm_dof"),
        ({"joint_stiffnes": "1 N/um"}, "joint_stiffnes"),
        ({"coupler_length": "1 m"}, "coupler_length"),
    ):
        with pytest.raises(ValueError, match=where):
            config_from_dict(linkage_config(**bad))
    # A coupler too short for the slider's line is refused with the linkage named.
    with pytest.raises(ValueError, match="linkage 'link'.*cannot reach the slider's line"):
        config_from_dict(linkage_config(output={"type": "slider", "dof": "slide", "origin": ["0 mm", "500 mm"]}))
