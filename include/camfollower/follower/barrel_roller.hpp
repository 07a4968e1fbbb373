// SPDX-License-Identifier: BSD-3-Clause
// Barrel (cylindrical) cams: a groove cut into a cylinder of radius R that turns about its own axis,
// and a roller whose axis is radial, running in the groove to depth d. Two followers:
//   BarrelRoller     the roller's carriage slides parallel to the cam axis (its lift in m);
//   BarrelArmRoller  the roller sits on a swing arm whose pivot axis is radial (parallel to the
//                    roller's), so the arm swings in the plane tangent to the cylinder (lift in rad).
//
// Dynamics in the developed pitch cylinder, radius rho = R - d/2 (the roller's mid-length), where the
// cam surface is a plane sliding past the follower at rho theta':
// - Developed ground frame: x across the follower's station, against the surface's motion; y along the
//   cam axis, the translating follower's lifting direction. Developed cam frame: X_cam = X + (rho theta, 0),
//   so the follower runs along the groove in +x as theta grows.
// - Roller centre C(theta) (ground): the pitch curve is C + (rho theta, 0), tangent T = C' + (rho, 0),
//   second derivative A = C''. The normal from the lifting flank to the roller is J T / |T|:
//   N = (0, rho) + J C', N' = J C''; curvature (> 0 convex, as for disk cams) -(T x A) / |T|^3.
// - Translating roller: C = (0, h), so tan(alpha) = h' / rho and lever = cos(alpha) (the closed form of
//   cylindrical cams). Swing arm: C = P + L u(phi0 + sigma h), lever = L cos(alpha), as the disk cam's.
// The cam's displacements (cam_x, cam_y of a contact) are along x (tangential at the station) and y
// (axial). The exact 3D groove walls along the whole depth, for a cylindrical and the ideal tapered
// roller, are in geometry/barrel_groove.hpp; at the pitch radius they agree with this developed model to
// second order in (roller radius / rho).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <type_traits>

#include <Eigen/Core>

#include "camfollower/error.hpp"
#include "camfollower/follower/arm_turn.hpp"
#include "camfollower/follower/contact_geometry.hpp"
#include "camfollower/follower/parameters.hpp"
#include "camfollower/follower/plane.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/follower/roller_pitch.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

namespace barrel_parameter {
inline constexpr FollowerParameter cylinder_radius =
    required_parameter("cylinder_radius", ParameterKind::length, "outer radius R of the barrel cam (m, > 0)");
inline constexpr FollowerParameter groove_depth = required_parameter(
    "groove_depth", ParameterKind::length, "depth d of the groove (m, 0 < d < R); the pitch radius is R - d/2");
}  // namespace barrel_parameter

namespace detail {

// The barrel's size, shared by both followers: R, d and the roller, validated once.
struct BarrelSize {
    double cylinder_radius, groove_depth, roller_radius;

    BarrelSize(double R, double d, double r) : cylinder_radius(R), groove_depth(d), roller_radius(r) {
        require_length(R, "cylinder_radius");
        require_length(d, "groove_depth");
        require_length(r, "roller_radius");
        if (!(d < R))
            fail("groove_depth = ", d, " m must be below cylinder_radius = ", R,
                 " m (the groove is cut into the cylinder's surface)");
    }
    double pitch_radius() const { return cylinder_radius - 0.5 * groove_depth; }
    double inner_radius() const { return cylinder_radius - groove_depth; }
};

// Normal, curvature and profile point of a roller whose centre runs along C(theta) over a developed
// cam surface at radius rho (see the file comment).
inline RollerNormal developed_roller_normal(const RollerPath& path, double rho) {
    const Eigen::Vector2d N = Eigen::Vector2d(0.0, rho) + planar::perp(path.dcentre);
    const Eigen::Vector2d dN = planar::perp(path.d2centre);
    const double length = N.norm();
    const Eigen::Vector2d n = N / length;
    return {n, (dN - n * n.dot(dN)) / length};
}
inline double developed_pitch_curvature(const RollerPath& path, double rho) {
    const Eigen::Vector2d T = path.dcentre + Eigen::Vector2d(rho, 0.0);
    const double speed = T.norm();
    return -planar::cross(T, path.d2centre) / (speed * speed * speed);
}
inline Eigen::Vector2d to_developed_cam_frame(double theta, double rho, const Eigen::Vector2d& ground) {
    return ground + Eigen::Vector2d(rho * theta, 0.0);
}
inline FollowerProfilePoint developed_profile(double theta, double rho, double roller_radius, const RollerPath& path,
                                              const Eigen::Vector2d& lifting_direction) {
    const Eigen::Vector2d n = developed_roller_normal(path, rho).normal;
    const Eigen::Vector2d contact_point = path.centre - roller_radius * n;
    const double kappa = developed_pitch_curvature(path, rho);
    return {theta,
            to_developed_cam_frame(theta, rho, contact_point),
            to_developed_cam_frame(theta, rho, path.centre),
            contact_point,
            roller_surface_radius(kappa, roller_radius),
            roller_effective_radius(kappa, roller_radius),
            std::atan2(planar::cross(lifting_direction, n), lifting_direction.dot(n))};
}

}  // namespace detail

class BarrelRoller {
public:
    static constexpr const char* type_name = "barrel_roller";
    static constexpr bool translating = true;
    static constexpr bool barrel = true;
    static constexpr const char* description =
        "Barrel (cylindrical) cam with a translating roller follower: the roller's axis is radial and its carriage "
        "slides parallel to the cam axis; lift in m along the axis.";
    static constexpr std::array parameters{
        barrel_parameter::cylinder_radius,
        barrel_parameter::groove_depth,
        common_parameter::roller_radius,
    };

    // cylinder_radius R (m, > 0), groove_depth d (m, 0 < d < R), roller_radius r_r (m, > 0).
    BarrelRoller(double cylinder_radius, double groove_depth, double roller_radius)
        : size_(cylinder_radius, groove_depth, roller_radius), rho_(size_.pitch_radius()) {}

    auto parameter_values() const {
        return std::make_tuple(size_.cylinder_radius, size_.groove_depth, size_.roller_radius);
    }
    double cylinder_radius() const { return size_.cylinder_radius; }
    double groove_depth() const { return size_.groove_depth; }
    double roller_radius() const { return size_.roller_radius; }
    double follower_radius() const { return size_.roller_radius; }
    // rho = R - d/2: the radius of the developed cylinder the dynamics use, m.
    double pitch_radius() const { return rho_; }
    double inner_radius() const { return size_.inner_radius(); }
    // The same follower seen on the developed cylinder of radius rho (m) by a roller section of
    // roller_radius (m): the groove's checks at its bottom and top (geometry/barrel_groove.hpp).
    BarrelRoller at_pitch_radius(double rho, double roller_radius) const {
        BarrelRoller f = *this;
        f.rho_ = rho;
        f.size_.roller_radius = roller_radius;
        return f;
    }

    RollerPath roller_path(const FollowerMotion& m) const { return {{0.0, m.h}, {0.0, m.dh}, {0.0, m.d2h}}; }
    // The lifting direction of the roller centre per unit lift (developed ground frame).
    Eigen::Vector2d lifting_direction(const FollowerMotion&) const { return {0.0, 1.0}; }

    // n = (-sin a, cos a) with tan a = h'/rho; lever = cos a.
    ContactGeometry contact(double /*theta*/, const FollowerMotion& m) const {
        const RollerNormal rn = detail::developed_roller_normal(roller_path(m), pitch_radius());
        const double c = rn.normal.y(), s = -rn.normal.x();
        return {rn.normal, rn.dnormal, c, rn.dnormal.y(), m.h, m.dh, c, s};
    }

    FollowerProfilePoint profile(double theta, const FollowerMotion& m) const {
        return detail::developed_profile(theta, pitch_radius(), size_.roller_radius, roller_path(m), {0.0, 1.0});
    }
    double pitch_curvature(const FollowerMotion& m) const {
        return detail::developed_pitch_curvature(roller_path(m), pitch_radius());
    }

private:
    detail::BarrelSize size_;
    double rho_;  // the developed cylinder's radius: R - d/2, or another depth's (at_pitch_radius)
};

class BarrelArmRoller {
public:
    static constexpr const char* type_name = "barrel_arm_roller";
    static constexpr bool translating = false;
    static constexpr bool barrel = true;
    static constexpr const char* description =
        "Barrel (cylindrical) cam with a swing-arm roller follower: the arm's pivot axis is radial, so the arm swings "
        "in the plane tangent to the cylinder; pivot (x across the station, y along the cam axis) in m; lift in rad.";
    static constexpr std::array parameters{
        barrel_parameter::cylinder_radius,
        barrel_parameter::groove_depth,
        common_parameter::roller_radius,
        required_parameter("pivot", ParameterKind::point,
                           "arm pivot (m): x across the follower's station (against the surface's motion), y along "
                           "the cam axis; |x| <= arm_length"),
        required_parameter("arm_length", ParameterKind::length, "pivot to roller centre L (m, > 0)"),
        common_parameter::turn,
    };

    // At zero lift the roller centre is on the station (x = 0), on the side of the pivot from which the
    // lifting rotation carries it towards and past the pivot's axial level: pivot = (-L cos b, L sin b)
    // starts the arm b below the perpendicular to the cam axis, at y = 0.
    BarrelArmRoller(double cylinder_radius, double groove_depth, double roller_radius, const Eigen::Vector2d& pivot,
                    double arm_length, ArmTurn turn = ArmTurn::counter_clockwise)
        : size_(cylinder_radius, groove_depth, roller_radius),
          pivot_(pivot),
          arm_length_(arm_length),
          turn_(turn),
          sigma_(turn_sign(turn)),
          rho_(size_.pitch_radius()) {
        detail::require_length(arm_length, "arm_length");
        if (!(std::isfinite(pivot.x()) && std::isfinite(pivot.y()) && pivot.norm() <= detail::max_part_length))
            detail::fail("pivot must be finite and within ", detail::max_part_length, " m of the station, got (",
                         pivot.x(), ", ", pivot.y(), ")");
        if (!(std::abs(pivot.x()) <= arm_length))
            detail::fail("pivot x = ", pivot.x(),
                         " m cannot reach the follower's station: |pivot x| must not exceed "
                         "arm_length = ",
                         arm_length, " m");
        if (pivot.x() == 0.0)
            detail::fail(
                "pivot x must not be 0: an arm along the cam axis moves the roller across the groove, not "
                "along the axis (put the pivot beside the station, e.g. x = -arm_length)");
        const double lifting = -sigma_ * pivot.x();  // sign of the roller's axial velocity at zero lift
        if (!(lifting > 0.0))
            detail::fail("pivot x = ", pivot.x(), " m is on the wrong side for turn = ", arm_turn_name(turn),
                         ": the lifting rotation would move the roller against +y (the lift); put the pivot at x ",
                         sigma_ > 0.0 ? "< 0" : "> 0", " or turn the other way");
        // The roller on the station (C_x = 0), below the pivot's level in the lifting sense.
        const double c = -pivot.x() / arm_length, s = std::sqrt(std::max(0.0, 1.0 - c * c));
        phi0_ = std::atan2(-s, c);
    }

    auto parameter_values() const {
        return std::make_tuple(size_.cylinder_radius, size_.groove_depth, size_.roller_radius, pivot_, arm_length_,
                               turn_);
    }
    double cylinder_radius() const { return size_.cylinder_radius; }
    double groove_depth() const { return size_.groove_depth; }
    double roller_radius() const { return size_.roller_radius; }
    double follower_radius() const { return size_.roller_radius; }
    const Eigen::Vector2d& pivot() const { return pivot_; }
    double arm_length() const { return arm_length_; }
    ArmTurn turn() const { return turn_; }
    double pitch_radius() const { return rho_; }
    double inner_radius() const { return size_.inner_radius(); }
    // phi0: the arm's angle (rad, developed ground frame) at zero lift.
    double start_angle() const { return phi0_; }
    double arm_angle(const FollowerMotion& m) const { return phi0_ + sigma_ * m.h; }
    BarrelArmRoller at_pitch_radius(double rho, double roller_radius) const {
        BarrelArmRoller f = *this;
        f.rho_ = rho;
        f.size_.roller_radius = roller_radius;
        return f;
    }

    RollerPath roller_path(const FollowerMotion& m) const {
        const Eigen::Vector2d u = planar::unit(arm_angle(m)), Ju = planar::perp(u);
        const double L = arm_length_;
        return {pivot_ + L * u, sigma_ * L * m.dh * Ju, sigma_ * L * m.d2h * Ju - L * m.dh * m.dh * u};
    }
    Eigen::Vector2d lifting_direction(const FollowerMotion& m) const {
        return sigma_ * planar::perp(planar::unit(arm_angle(m)));
    }

    ContactGeometry contact(double /*theta*/, const FollowerMotion& m) const {
        const Eigen::Vector2d u = planar::unit(arm_angle(m));
        const RollerNormal rn = detail::developed_roller_normal(roller_path(m), pitch_radius());
        const Eigen::Vector2d v = sigma_ * planar::perp(u);
        const double cos_a = v.dot(rn.normal), sin_a = planar::cross(v, rn.normal);
        const double dcos_a = -m.dh * u.dot(rn.normal) + v.dot(rn.dnormal);  // dv/dtheta = -s' u
        return {rn.normal, rn.dnormal, arm_length_ * cos_a, arm_length_ * dcos_a, m.h, m.dh, cos_a, sin_a};
    }

    FollowerProfilePoint profile(double theta, const FollowerMotion& m) const {
        return detail::developed_profile(theta, pitch_radius(), size_.roller_radius, roller_path(m),
                                         lifting_direction(m));
    }
    double pitch_curvature(const FollowerMotion& m) const {
        return detail::developed_pitch_curvature(roller_path(m), pitch_radius());
    }

private:
    detail::BarrelSize size_;
    Eigen::Vector2d pivot_;
    double arm_length_;
    ArmTurn turn_;
    double sigma_;
    double rho_;
    double phi0_ = 0.0;
};

// Is F a barrel cam's follower (its profile is the developed groove, not a disk's outline)?
template <class F, class = void>
struct is_barrel_follower : std::false_type {};
template <class F>
struct is_barrel_follower<F, std::void_t<decltype(F::barrel)>> : std::bool_constant<F::barrel> {};

}  // namespace camfollower
