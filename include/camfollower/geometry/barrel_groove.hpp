// SPDX-License-Identifier: BSD-3-Clause
// A barrel cam's groove for manufacturing and checking: the exact walls along the whole depth for a
// cylindrical roller and for the ideal tapered roller (its cone's apex on the cam axis, so it rolls
// without slip at every radius), the pressure angle along the groove at each radius, and a 4-axis
// machining path. Followers and the developed model: follower/barrel_roller.hpp.
//
// 3D frames. The cam axis is z (the developed y, the lifting direction); the follower's station is the
// radial line x3 at cam angle 0 of the ground; the cam turns counter-clockwise about z as theta grows,
// so its surface at the station moves in +y3 (the developed x = -y3). At cam angle theta the roller's
// axis is the line parallel to x3 through (y3, z) = (-C_x, C_y), C the roller centre of the developed
// model (follower/barrel_roller.hpp): through the cam axis for the translating roller.
// A point of the cam at radius rho, at the ground angle psi from the station and height z, lies at
// w = (rho sin(psi) + C_x, z - C_y) from the roller's axis (y3, z components) and t = rho cos(psi)
// along it. The roller's radius at t is a + b t: cylindrical a = r, b = 0; tapered a = 0, b = r / rho_p
// (r at the pitch radius); the opposite flank's roller is larger by the groove clearance c.
// The wall is the envelope of the roller's positions: at each theta, the point of the circle
// (radius rho) that satisfies
//   F = |w|^2 - (a + b t)^2 = 0   and   G = dF/dtheta (cam point fixed: dpsi/dtheta = 1) = 0,
// solved by Newton from the developed model's contact point. Its position on the cam is the angle
// beta = theta - psi (the roller's station is at beta = theta) and the height z.
// Machining: a cutter shaped as the roller, larger by c/2, its axis where the roller's is, shifted by
// c/2 along the developed normal (the groove's centre line): the rotary axis at theta, the cross slide
// at the axis's offset across the station, the axial slide at its height, plunged to the groove depth.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "camfollower/contact/groove.hpp"
#include "camfollower/detail/atomic_file.hpp"
#include "camfollower/error.hpp"
#include "camfollower/follower/barrel_roller.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/motion/program.hpp"
#include "camfollower/units.hpp"

namespace camfollower {

enum class BarrelRollerShape { cylindrical, tapered };

inline const char* barrel_roller_shape_name(BarrelRollerShape s) {
    return s == BarrelRollerShape::tapered ? "tapered" : "cylindrical";
}
inline BarrelRollerShape barrel_roller_shape_from(const std::string& name) {
    if (name == "cylindrical") return BarrelRollerShape::cylindrical;
    if (name == "tapered") return BarrelRollerShape::tapered;
    detail::fail("roller shape must be 'cylindrical' or 'tapered', got '", detail::printable(name), "'");
}

// One wall point at one radius: where it is on the cam and the pressure angle there.
struct BarrelWallPoint {
    double angle;           // beta, rad: position round the cam (the roller's station is at beta = theta)
    double axial;           // z, m: height along the cam axis
    double pressure_angle;  // rad: between the wall's normal (projected on the tangent plane) and the lift
};

// The groove at `theta.size()` cam angles, on each of `radii`.
struct BarrelGroove {
    BarrelRollerShape shape = BarrelRollerShape::cylindrical;
    double clearance = 0.0;                          // m: groove width minus the roller's diameter
    std::vector<double> radii;                       // m: outer, pitch, bottom
    std::vector<double> theta;                       // rad, 2 pi k / n
    std::vector<Eigen::Vector2d> centre;             // (beta, z) of the roller centre at the pitch radius
    std::vector<std::vector<BarrelWallPoint>> lift;  // [radius][k]: the flank that lifts the roller
    std::vector<std::vector<BarrelWallPoint>> back;  // [radius][k]: the opposite flank (clearance c away)
    // Machining, per cam angle: the cutter axis's offset across the station (m, developed x), its
    // height (m) and its plunge below the cylinder's surface (m, the groove depth).
    std::vector<Eigen::Vector3d> cutter;
};

namespace detail {

struct BarrelRollerSection {
    double a, b;  // roller radius a + b t at distance t from the cam axis along the roller's axis, m
};

// The wall point at radius rho touching the roller section `roller` whose axis runs along `path`,
// on side `side` (-1: the lifting flank, against the developed normal n; +1 the opposite one).
inline Eigen::Vector2d barrel_wall_point(const RollerPath& path, const Eigen::Vector2d& n, double rho,
                                         BarrelRollerSection roller, double side, double theta) {
    const double r0 = roller.a + roller.b * rho;
    const Eigen::Vector2d guess = path.centre + side * r0 * n;  // developed (x, y)
    double psi = std::asin(std::clamp(-guess.x() / rho, -1.0, 1.0)), z = guess.y();
    const double Cx = path.centre.x(), Cy = path.centre.y(), dCx = path.dcentre.x(), dCy = path.dcentre.y();
    double residual = 0.0;
    for (int iteration = 0; iteration < 60; ++iteration) {
        const double s = std::sin(psi), c = std::cos(psi);
        const double wx = rho * s + Cx, wz = z - Cy, t = rho * c, radius = roller.a + roller.b * t;
        const double F = wx * wx + wz * wz - radius * radius;
        const double G = 2.0 * wx * (rho * c + dCx) - 2.0 * wz * dCy + 2.0 * radius * roller.b * rho * s;
        const double F_psi = 2.0 * wx * rho * c + 2.0 * radius * roller.b * rho * s;
        const double F_z = 2.0 * wz;
        const double G_psi = 2.0 * rho * c * (rho * c + dCx) - 2.0 * wx * rho * s +
                             2.0 * roller.b * rho * (-roller.b * rho * s * s + radius * c);
        const double G_z = -2.0 * dCy;
        const double det = F_psi * G_z - F_z * G_psi;
        const double dpsi = (F * G_z - F_z * G) / det, dz = (F_psi * G - F * G_psi) / det;
        psi -= dpsi, z -= dz;
        residual = std::abs(dpsi) * rho + std::abs(dz);
        if (!std::isfinite(residual)) break;
        if (residual <= 1e-14 * (rho + std::abs(z))) {
            const Eigen::Vector2d from_axis(-(rho * std::sin(psi) + Cx), z - Cy);  // developed (x, y)
            if (from_axis.dot(n) * side <= 0.0) break;                             // the wrong side: no wall
            return {theta - psi, z};
        }
    }
    fail("the barrel groove's wall has no point at radius ", rho, " m at theta = ", radians_to_degrees(theta),
         " deg (last correction ", residual,
         " m): the roller cannot cut a wall there (undercut; enlarge the cylinder or soften the motion law)");
}

}  // namespace detail

// The groove of `follower` (BarrelRoller or BarrelArmRoller) running `program`, at `points` cam
// angles, with a groove clearance (m, >= 0) and a roller shape. Checks first that the roller can trace
// the groove at its top, pitch and bottom radii (no undercut, pressure angle below 90 deg; the
// opposite flank's concave radius above the roller's plus the clearance), naming the radius.
template <class F>
BarrelGroove barrel_groove(const F& follower, const MotionProgram& program, std::size_t points = 3600,
                           double clearance = 0.0, BarrelRollerShape shape = BarrelRollerShape::cylindrical) {
    static_assert(is_barrel_follower<F>::value, "barrel_groove needs a barrel cam's follower");
    detail::require_point_count(points, 3, "points");
    detail::require_non_negative(clearance, "groove clearance", "(m)");
    const double r = follower.roller_radius(), rho_p = follower.pitch_radius();
    if (clearance > 0.0) Groove{clearance, {}}.validate("barrel cam", r);
    BarrelGroove out;
    out.shape = shape, out.clearance = clearance;
    out.radii = {follower.cylinder_radius(), rho_p, follower.inner_radius()};
    const auto section_at = [&](double extra) {
        return shape == BarrelRollerShape::tapered ? detail::BarrelRollerSection{extra, r / rho_p}
                                                   : detail::BarrelRollerSection{r + extra, 0.0};
    };
    const detail::BarrelRollerSection lifting = section_at(0.0), opposite = section_at(clearance);
    static const char* const where[3] = {"top", "pitch", "bottom"};
    for (std::size_t i = 0; i < out.radii.size(); ++i) {
        const double rho = out.radii[i], r_here = lifting.a + lifting.b * rho;
        const F here = follower.at_pitch_radius(rho, r_here);
        const std::string who = detail::concat("barrel groove at its ", where[i], " (radius ", rho, " m)");
        try {
            check_undercut(program, here);
            const auto curvature = [&](double theta) { return here.pitch_curvature(program.evaluate(theta)); };
            check_outer_flank(program, curvature, opposite.a + opposite.b * rho, who);
        } catch (const std::invalid_argument& e) {
            const std::string message = e.what();
            detail::fail(message.rfind(who, 0) == 0 ? message : who + ": " + message);
        }
    }
    out.lift.assign(out.radii.size(), {});
    out.back.assign(out.radii.size(), {});
    for (std::size_t k = 0; k < points; ++k) {
        const double theta = two_pi * static_cast<double>(k) / static_cast<double>(points);
        const FollowerMotion m = program.evaluate(theta);
        const RollerPath path = follower.roller_path(m);
        const Eigen::Vector2d n_p = detail::developed_roller_normal(path, rho_p).normal;
        out.theta.push_back(theta);
        out.centre.emplace_back(theta + path.centre.x() / rho_p, path.centre.y());
        const Eigen::Vector2d axis = path.centre + 0.5 * clearance * n_p;
        out.cutter.emplace_back(axis.x(), axis.y(), follower.groove_depth());
        const Eigen::Vector2d v = follower.lifting_direction(m);
        for (std::size_t i = 0; i < out.radii.size(); ++i) {
            const double rho = out.radii[i];
            const Eigen::Vector2d n = detail::developed_roller_normal(path, rho).normal;
            for (const double side : {-1.0, 1.0}) {
                const Eigen::Vector2d p =
                    detail::barrel_wall_point(path, n, rho, side < 0.0 ? lifting : opposite, side, theta);
                // The lifting flank's normal towards the roller, developed: from the point to the axis
                // (on the opposite flank, from the axis to the point: the direction it would lift in).
                const double psi = theta - p.x();
                const Eigen::Vector2d from_axis(-(rho * std::sin(psi) + path.centre.x()), p.y() - path.centre.y());
                const Eigen::Vector2d normal = side * from_axis.normalized();
                const BarrelWallPoint w{p.x(), p.y(), std::atan2(planar::cross(v, normal), v.dot(normal))};
                (side < 0.0 ? out.lift : out.back)[i].push_back(w);
            }
        }
    }
    return out;
}

// The groove as CSV (lengths in `unit`, angles in deg): "# " notes, then one row per cam angle with the
// roller centre, both flanks and the pressure angle at the top, pitch and bottom radii, and the
// machining path.
template <class F>
std::string barrel_groove_csv(const F& follower, const BarrelGroove& g, LengthUnit unit = LengthUnit::mm) {
    const char* u = length_unit_name(unit);
    const auto L = [&](double metres) { return metres_to(unit, metres); };
    std::ostringstream out;
    out.precision(17);
    out << "# camfollower barrel cam groove for manufacturing\n"
        << "# units: lengths in " << u << ", angles in deg\n"
        << "# follower: " << describe_follower(follower, unit) << "\n"
        << "# roller: " << barrel_roller_shape_name(g.shape) << ", groove clearance " << L(g.clearance) << " " << u
        << " (groove width = roller diameter + clearance)\n"
        << "# frame: z along the cam axis (the follower's lift); angle = position round the cam, measured in the cam "
           "so that the roller's station is at angle = theta (the cam turns the other way); the cam turns "
           "counter-clockwise about +z as theta grows\n"
        << "# radii: top " << L(g.radii[0]) << ", pitch " << L(g.radii[1]) << ", bottom " << L(g.radii[2]) << " " << u
        << "; lift flank = the wall that pushes the roller in its lifting direction, back flank = the opposite wall\n"
        << "# pressure angle: between the lift flank's normal (in the cylinder's tangent plane) and the roller's "
           "lifting direction\n"
        << "# machining (4 axes): rotary = theta, cross = the cutter axis's offset across the station (positive "
           "against the surface's motion), axial = its height, plunge = depth below the surface; cutter = the "
           "roller's shape enlarged by half the clearance\n"
        << "# points: " << g.theta.size() << " (theta_k = 360 k / " << g.theta.size() << " deg)\n";
    out << "theta_deg,centre_angle_deg,centre_z_" << u;
    static const char* const where[3] = {"top", "pitch", "bottom"};
    for (const char* w : where)
        out << ",lift_" << w << "_angle_deg,lift_" << w << "_z_" << u << ",back_" << w << "_angle_deg,back_" << w
            << "_z_" << u << ",pressure_angle_" << w << "_deg";
    out << ",cutter_cross_" << u << ",cutter_axial_" << u << ",cutter_plunge_" << u << '\n';
    for (std::size_t k = 0; k < g.theta.size(); ++k) {
        out << radians_to_degrees(g.theta[k]) << ',' << radians_to_degrees(g.centre[k].x()) << ','
            << L(g.centre[k].y());
        for (std::size_t i = 0; i < g.radii.size(); ++i) {
            const BarrelWallPoint &a = g.lift[i][k], &b = g.back[i][k];
            out << ',' << radians_to_degrees(a.angle) << ',' << L(a.axial) << ',' << radians_to_degrees(b.angle) << ','
                << L(b.axial) << ',' << radians_to_degrees(a.pressure_angle);
        }
        out << ',' << L(g.cutter[k].x()) << ',' << L(g.cutter[k].y()) << ',' << L(g.cutter[k].z()) << '\n';
    }
    return out.str();
}

template <class F>
void write_barrel_groove_csv(const std::string& path, const F& follower, const MotionProgram& program,
                             std::size_t points = 3600, double clearance = 0.0,
                             BarrelRollerShape shape = BarrelRollerShape::cylindrical,
                             LengthUnit unit = LengthUnit::mm) {
    length_unit_spec(unit);
    const BarrelGroove g = barrel_groove(follower, program, points, clearance, shape);
    detail::write_file_atomically(path, barrel_groove_csv(follower, g, unit));
}

}  // namespace camfollower
