# SPDX-License-Identifier: BSD-3-Clause
"""Barrel (cylindrical) cams against independent truth: the groove walls against a brute-force
envelope of the roller's positions (written here from the roller's axis alone), the pressure angle
against the closed form tan(alpha) = h' / rho of a translating follower, the swing arm's against the
normal of the sampled pitch curve, a stiffly driven carriage's contact force and drive torque against
the rigid-body balance, and the reach from the config and the command line."""

import math
import pickle

import camfollower as cf
import numpy as np
import pytest
from camfollower.config import config_from_dict

DEG = math.pi / 180.0
EXAMPLE = "examples/barrel_cam.toml"


def program(lift=0.04, law=None):
    """Dwell, rise over 130 deg, dwell, return: a transfer motion."""
    dwell, move = cf.MotionLaw.dwell(), law or cf.MotionLaw.modified_sine()
    return cf.MotionProgram(
        [
            cf.Segment(dwell, 0, 40 * DEG, 0, 0),
            cf.Segment(move, 40 * DEG, 170 * DEG, 0, lift),
            cf.Segment(dwell, 170 * DEG, 220 * DEG, lift, lift),
            cf.Segment(move, 220 * DEG, 350 * DEG, lift, 0),
            cf.Segment(dwell, 350 * DEG, 360 * DEG, 0, 0),
        ]
    )


def arm_program():
    return program(lift=20 * DEG)


def translating():
    return cf.BarrelRoller(cylinder_radius=0.06, groove_depth=0.016, roller_radius=0.01)


def swing_arm():
    # The arm is 10 deg below the perpendicular to the cam axis at zero lift and swings through it.
    L, b = 0.12, 10 * DEG
    return cf.BarrelArmRoller(0.06, 0.016, 0.01, pivot=(-L * math.cos(b), L * math.sin(b)), arm_length=L)


def axis_path(follower, prog, theta):
    """The roller's axis at cam angles theta: its offset across the station and its height (m),
    from the follower's definition (a carriage on the axis, or an arm about its pivot)."""
    h = np.asarray(prog.evaluate(theta)["h"])
    if isinstance(follower, cf.BarrelRoller):
        return np.zeros_like(h), h
    px, py = follower.pivot
    phi = follower.start_angle + (1 if follower.turn == "counter_clockwise" else -1) * h
    return px + follower.arm_length * np.cos(phi), py + follower.arm_length * np.sin(phi)


def gap(follower, prog, rho, beta, z, theta, section):
    """Distance from the cam point (rho, beta, z) to the roller's surface at cam angles theta (> 0:
    outside the roller). The roller's axis is parallel to the station's radial line, the roller on
    the station's side of the cam axis; its radius at distance t from the cam axis is a + b t."""
    a, b = section
    cx, cy = axis_path(follower, prog, theta)
    psi = theta - beta  # the point's angle from the station, in the ground
    d = np.hypot(rho * np.sin(psi) + cx, z - cy) - (a + b * rho * np.cos(psi))
    return np.where(np.cos(psi) > 0, d, np.inf)  # the roller reaches out from the cam axis, on its side only


@pytest.mark.parametrize("make", [translating, swing_arm], ids=["carriage", "swing arm"])
@pytest.mark.parametrize("roller", ["cylindrical", "tapered"])
def test_groove_walls_are_the_envelope_of_the_rollers_positions(make, roller):
    follower = make()
    prog = arm_program() if isinstance(follower, cf.BarrelArmRoller) else program()
    clearance = 2e-4
    g = cf.export.groove_points(follower, prog, points=360, clearance=clearance, roller=roller)
    r, rho_p = follower.roller_radius, follower.cylinder_radius - follower.groove_depth / 2
    assert g["radii"] == pytest.approx([follower.cylinder_radius, rho_p, follower.cylinder_radius - 0.016])

    def section(extra):
        return (extra, r / rho_p) if roller == "tapered" else (r + extra, 0.0)

    worst_touch = worst_cut = 0.0
    for k in range(0, 360, 9):
        theta_k = g["theta"][k]
        near = theta_k + np.linspace(-0.25, 0.25, 50001)  # steps of 1e-5 rad
        everywhere = np.linspace(0, 2 * math.pi, 20001)
        for i, rho in enumerate(g["radii"]):
            for flank, extra in (("lift", 0.0), ("back", clearance)):
                beta, z = g[f"{flank}_angle"][i][k], g[f"{flank}_z"][i][k]
                local = gap(follower, prog, rho, beta, z, near, section(extra))
                # The roller at theta_k touches the wall point, and no roller position cuts into it.
                worst_touch = max(worst_touch, abs(gap(follower, prog, rho, beta, z, theta_k, section(extra))))
                worst_cut = max(
                    worst_cut, -min(local.min(), gap(follower, prog, rho, beta, z, everywhere, section(extra)).min())
                )
    print(f"{type(follower).__name__} {roller}: |gap at theta| {worst_touch:.2g} m, deepest cut {worst_cut:.2g} m")
    assert worst_touch < 1e-12
    assert worst_cut < 1e-9


def test_pressure_angle_is_the_closed_form_and_the_exact_wall_tends_to_it():
    prog = program()
    theta = np.linspace(0, 2 * math.pi, 721)
    dh = np.asarray(prog.evaluate(theta)["dh"])
    f = translating()
    rho_p = 0.052
    alpha = np.array([f.contact(prog, t)["pressure_angle"] for t in theta])
    np.testing.assert_allclose(alpha, np.arctan(dh / rho_p), rtol=0, atol=1e-14)
    np.testing.assert_allclose(np.asarray(f.profile(prog, theta)["pressure_angle"]), alpha, rtol=0, atol=1e-14)
    assert math.degrees(abs(f.max_pressure_angle(prog)[1])) > 30  # a steep groove: the check means something
    # The exact walls: with a thin roller the pressure angle at each radius is atan(h' / radius); with a
    # real one it differs at second order in (roller radius / radius).
    for r, tolerance in ((1e-5, 1e-7), (0.01, 0.02)):
        thin = cf.BarrelRoller(0.06, 0.016, r)
        g = cf.export.groove_points(thin, prog, points=720)
        for i, radius in enumerate(g["radii"]):
            closed = np.arctan(dh[:-1] / radius)
            err = np.abs(g["pressure_angle"][i] - closed).max()
            assert err < tolerance, (r, radius, err)
    # The bottom of the groove is steeper than the top.
    assert np.abs(g["pressure_angle"][2]).max() > np.abs(g["pressure_angle"][0]).max() + 2 * DEG


def developed_pitch_curve(follower, prog, theta):
    """The roller centre in the developed cam frame: (x + rho theta, y) with the pitch radius rho."""
    cx, cy = axis_path(follower, prog, theta)
    return cx + (follower.cylinder_radius - follower.groove_depth / 2) * theta, cy


def test_swing_arm_normal_is_normal_to_the_pitch_curve_and_the_lever_is_its_moment():
    f, prog = swing_arm(), arm_program()
    eps = 1e-6
    for t in np.linspace(0.05, 2 * math.pi - 0.05, 97):
        c = f.contact(prog, t)
        x, y = developed_pitch_curve(f, prog, np.array([t - eps, t + eps]))
        tangent = np.array([x[1] - x[0], y[1] - y[0]])
        tangent /= np.linalg.norm(tangent)
        n = np.asarray(c["normal"]).ravel()
        assert abs(n @ tangent) < 1e-8
        # lever = d(penetration)/d(-lift): the roller centre's velocity per unit arm rotation along n.
        cx, cy = axis_path(f, prog, np.array([t]))
        h = prog.evaluate(t)["h"]
        px, py = f.pivot
        dcentre = np.array([-(cy[0] - py), cx[0] - px])  # d C / d phi = J (C - P), counter-clockwise arm
        assert c["lever"] == pytest.approx(n @ dcentre, abs=1e-12)
        assert np.isfinite(h)
    # Its pressure angle: between the normal and the roller centre's lifting direction.
    p = f.profile(prog, np.array([1.0]))
    c = f.contact(prog, 1.0)
    assert p["pressure_angle"][0] == pytest.approx(c["pressure_angle"], abs=1e-14)


def carriage(stiffness=2e9, spring=2e4, preload=300.0, mass=2.0):
    """A carriage on a barrel cam, held against the lifting flank by a preloaded spring."""
    b = cf.MechanismBuilder()
    b.add_dof("w", mass, direction=(1, 0, 0))
    b.add_spring("spring", "w", stiffness=spring, preload=preload)
    b.add_contact(
        "cam",
        program(law=cf.MotionLaw.polynomial_4567()),
        translating(),
        follower_dof="w",
        stiffness=stiffness,
        exponent=1.0,
        damping_factor=2e-3,
    )
    b.camshaft_speed_rpm = 120.0
    return b


def test_contact_force_and_drive_torque_follow_the_rigid_balance():
    b = carriage()
    mech = b.build()
    omega = 120 * math.pi / 30
    r = cf.simulate(mech, revolutions=2, method="dop853", tolerance=1e-9, time_step=2 * math.pi / omega / 2000)
    keep = r.t > 2 * math.pi / omega  # the second revolution
    m = b.contacts[0]["program"].evaluate(r["theta"][keep])
    h, dh, d2h = (np.asarray(m[k]) for k in ("h", "dh", "d2h"))
    # Along the axis: F cos(alpha) = m a + k h + preload, the pressure angle atan(h' / rho) at rho = 52 mm.
    axial = 2.0 * omega**2 * d2h + 2e4 * h + 300.0
    cos_alpha = 0.052 / np.hypot(0.052, dh)
    force = np.asarray(r["cam.force"])[keep]
    err = np.abs(force - axial / cos_alpha).max() / np.abs(axial / cos_alpha).max()
    print(f"barrel carriage: |F - rigid| / peak {err:.2g}; peak 1/cos(alpha) {1 / cos_alpha.min():.3f}")
    assert 1 / cos_alpha.min() > 1.15  # the pressure angle is a sizeable part of the force
    assert err < 2e-3
    # The drive torque: the contact force's tangential part at the pitch radius, F sin(alpha) rho.
    torque = np.asarray(r["drive.torque"])[keep]
    rigid_torque = force * np.sin(np.arctan(dh / 0.052)) * 0.052
    assert np.abs(torque - rigid_torque).max() < 2e-3 * np.abs(rigid_torque).max()


def test_barrel_followers_pickle_and_refuse_bad_geometry():
    for f in (translating(), swing_arm()):
        back = pickle.loads(pickle.dumps(f))
        assert repr(back) == repr(f)
    assert cf.BarrelRoller.translating and not cf.BarrelArmRoller.translating
    with pytest.raises(ValueError, match="groove_depth = 0.07 m must be below cylinder_radius = 0.06 m"):
        cf.BarrelRoller(0.06, 0.07, 0.01)
    with pytest.raises(ValueError, match="roller_radius"):
        cf.BarrelRoller(0.06, 0.01, -0.01)
    with pytest.raises(ValueError, match=r"\|pivot x\| must not exceed arm_length = 0.1 m"):
        cf.BarrelArmRoller(0.06, 0.016, 0.01, pivot=(-0.2, 0.0), arm_length=0.1)
    with pytest.raises(ValueError, match="pivot x = 0.1 m is on the wrong side for turn = counter_clockwise"):
        cf.BarrelArmRoller(0.06, 0.016, 0.01, pivot=(0.1, 0.0), arm_length=0.12)
    cf.BarrelArmRoller(0.06, 0.016, 0.01, pivot=(0.1, 0.0), arm_length=0.12, turn="clockwise")  # that side's turn
    with pytest.raises(ValueError, match="pivot x must not be 0"):
        cf.BarrelArmRoller(0.06, 0.016, 0.01, pivot=(0.0, 0.0), arm_length=0.1)
    # A steep groove on a thin cylinder jams at the bottom: the message names the radius.
    steep = cf.BarrelRoller(0.03, 0.02, 0.005)
    with pytest.raises(ValueError, match=r"barrel groove at its bottom \(radius 0.01 m\): the cam profile undercuts"):
        cf.export.groove_points(steep, program(lift=0.08))
    with pytest.raises(ValueError, match="roller must be one of cylindrical, tapered"):
        cf.export.groove_points(translating(), program(), roller="conical")
    with pytest.raises(ValueError, match="barrel cam's groove, which has no disk outline"):
        cf.export.profile_points(translating(), program())
    with pytest.raises(ValueError, match="needs BarrelRoller or BarrelArmRoller, got translating_roller"):
        cf.export.groove_points(cf.TranslatingRoller(0.03, 0.01), program())


def test_a_barrel_cam_on_a_shaft_needs_its_axial_dofs():
    b = cf.MechanismBuilder()
    b.add_dof("w", 1.0, direction=(1, 0, 0))
    b.add_shaft("shaft", length=0.3, outer_diameter=0.03, stations=[0.15])
    with pytest.raises(ValueError, match=r"needs its axial DOFs \(axial = true\)"):
        b.mount_cam("cam", program(), translating(), follower_dof="w", shaft="shaft", at=0.15, stiffness=1e9)
    # With them, the cam's displacements are the node's u_y (across the station) and u_x (axial).
    b.add_shaft("axial", length=0.3, outer_diameter=0.03, stations=[0.15], axial=True)
    b.mount_cam("cam", program(), translating(), follower_dof="w", shaft="axial", at=0.15, stiffness=1e9)
    c = b.contacts[0]
    assert (c["cam_x"], c["cam_y"]) == (b.shaft_dof("axial", 0.15, "uy"), b.shaft_dof("axial", 0.15, "ux"))


def test_the_example_runs_and_exports_its_groove(tmp_path, capsys):
    case = cf.load_config(EXAMPLE)
    c = case.builder.contacts[0]
    assert isinstance(c["follower"], cf.BarrelRoller) and c["groove"].clearance == pytest.approx(5e-5)
    r = case.run()
    force = np.asarray(r["cam.force"])
    assert force.max() > 0 and np.isfinite(r["drive.torque"]).all()
    from camfollower import cli

    out = tmp_path / "groove.csv"
    assert cli.main(["export", EXAMPLE, "-o", str(out), "--points", "720"]) == 0
    lines = out.read_text().splitlines()
    header = next(line for line in lines if not line.startswith("#"))
    assert header.startswith("theta_deg,centre_angle_deg,centre_z_mm,lift_top_angle_deg")
    data = np.loadtxt(out, delimiter=",", skiprows=lines.index(header) + 1)
    assert data.shape == (720, 3 + 15 + 3)
    columns = header.split(",")
    z = data[:, columns.index("centre_z_mm")]
    assert z.max() == pytest.approx(50.0, abs=1e-9)  # the carriage's stroke, mm
    width = data[:, columns.index("back_top_z_mm")] - data[:, columns.index("lift_top_z_mm")]
    assert width[0] == pytest.approx(20.05, abs=1e-9)  # in a dwell: the roller's diameter + clearance
    np.testing.assert_allclose(data[:, columns.index("cutter_plunge_mm")], 16.0, rtol=1e-15)
    dxf = tmp_path / "groove.dxf"
    assert cli.main(["export", EXAMPLE, "-o", str(dxf), "--points", "720", "--roller", "tapered"]) == 0
    ezdxf = pytest.importorskip("ezdxf")
    layers = {e.dxf.layer for e in ezdxf.readfile(dxf).modelspace()}
    assert layers == {"GROOVE_TOP", "GROOVE_BOTTOM", "PITCH_CURVE"}
    assert cli.main(["export", EXAMPLE, "-o", str(tmp_path / "x.csv"), "--cutter-radius", "5"]) == 1
    assert "is a barrel cam, cut by a cutter shaped as its roller" in capsys.readouterr().err


def test_the_config_names_a_bad_barrel_parameter():
    base = {
        "camshaft": {"speed": "200 rpm"},
        "program": {
            "p": {
                "segments": [
                    {"law": "cycloidal", "end": "180 deg", "h": "40 mm"},
                    {"law": "cycloidal", "end": "360 deg", "h": 0},
                ]
            }
        },
        "dof": [{"name": "w", "mass": "1 kg"}],
        "contact": [
            {
                "name": "cam",
                "program": "p",
                "follower": {
                    "type": "barrel_roller",
                    "cylinder_radius": "60 mm",
                    "groove_depth": "80 mm",
                    "roller_radius": "10 mm",
                },
                "follower_dof": "w",
                "stiffness": "1e9 N/m",
                "exponent": 1,
            }
        ],
    }
    with pytest.raises(ValueError, match="groove_depth = 0.08 m must be below cylinder_radius"):
        config_from_dict(base)
