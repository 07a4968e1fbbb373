// SPDX-License-Identifier: BSD-3-Clause
// Oscillating (swinging-arm) roller follower. The arm turns about the fixed pivot P (ground frame);
// the roller centre is C = P + L u(phi), u(phi) = (cos phi, sin phi), phi = phi0 + sigma s(theta),
// with s the program's lift in rad and sigma = +1 (counter-clockwise lift) or -1 (clockwise).
//
// phi0 puts the roller on the base pitch circle, |P + L u(phi0)| = r_b + r_r, at the root where the
// lifting rotation moves the roller away from the cam: d|C|/dphi = L P . J u / |C| has the sign of
// sigma. With |C|^2 = |P|^2 + L^2 + 2 L P . u, the root has P . u = (r^2 - |P|^2 - L^2) / (2L),
// which exists (transversally) only for | |P| - r | < L < |P| + r.
//
// Normal and curvature: roller_pitch.hpp with C' = sigma L s' J u, C'' = sigma L s'' J u - L s'^2 u.
// The roller centre's lifting velocity per unit s is sigma L J u: pressure angle from v = sigma J u,
// lever = n . (sigma L J u) = L cos alpha (the contact point is on the line through C along n, so
// its velocity has the same normal component as the centre's).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <string>

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

class OscillatingRoller {
public:
    // Its name in configs, messages and exports; its lift is the arm's rotation (rad).
    static constexpr const char* type_name = "oscillating_roller";
    static constexpr bool translating = false;
    static constexpr const char* description =
        "Oscillating (swing-arm) roller follower: pivot (x, y) in m in the ground frame, arm length (m); its lift "
        "program is the arm rotation in rad.";
    static constexpr std::array parameters{
        common_parameter::base_radius,
        common_parameter::roller_radius,
        common_parameter::pivot,
        required_parameter("arm_length", ParameterKind::length, "pivot to roller centre L (m, > 0)"),
        common_parameter::turn,
    };

    // base_radius r_b (m, > 0), roller_radius r_r (m, > 0), pivot P (m, ground frame, outside the
    // base circle), arm_length L (m, > 0, with | |P| - (r_b + r_r) | < L < |P| + r_b + r_r),
    // turn: the arm's lifting sense.
    OscillatingRoller(double base_radius, double roller_radius, const Eigen::Vector2d& pivot, double arm_length,
                      ArmTurn turn = ArmTurn::counter_clockwise)
        : base_radius_(base_radius),
          roller_radius_(roller_radius),
          pivot_(pivot),
          arm_length_(arm_length),
          turn_(turn),
          sigma_(turn_sign(turn)) {
        detail::require_length(base_radius, "base_radius");
        detail::require_length(roller_radius, "roller_radius");
        detail::require_length(arm_length, "arm_length");
        if (!(std::isfinite(pivot.x()) && std::isfinite(pivot.y()) && pivot.norm() <= detail::max_part_length))
            detail::fail("pivot must be finite and within ", detail::max_part_length, " m of the cam centre, got (",
                         pivot.x(), ", ", pivot.y(), ")");
        const double d = pivot.norm(), r = base_radius + roller_radius;
        if (!(d > base_radius))
            detail::fail("pivot must lie outside the base circle: |pivot| = ", d,
                         " m must be > base_radius = ", base_radius, " m");
        if (!(std::abs(d - r) < arm_length && arm_length < d + r))
            detail::fail("arm_length = ", arm_length,
                         " m cannot put the roller on the base pitch circle (radius base_radius + "
                         "roller_radius = ",
                         r, " m) from the pivot at |pivot| = ", d, " m: arm_length must lie in (", std::abs(d - r),
                         ", ", d + r, ") m");
        const double projection = (r * r - d * d - arm_length * arm_length) / (2.0 * arm_length);
        phi0_ = detail::arm_angle_with_projection(pivot, std::clamp(projection, -d, d), sigma_);
    }

    auto parameter_values() const { return std::make_tuple(base_radius_, roller_radius_, pivot_, arm_length_, turn_); }
    double base_radius() const { return base_radius_; }
    double roller_radius() const { return roller_radius_; }
    const Eigen::Vector2d& pivot() const { return pivot_; }
    double arm_length() const { return arm_length_; }
    ArmTurn turn() const { return turn_; }
    double follower_radius() const { return roller_radius_; }
    // phi0: arm angle (rad, ground frame) with the roller on the base circle.
    double start_angle() const { return phi0_; }
    double arm_angle(const FollowerMotion& m) const { return phi0_ + sigma_ * m.h; }

    // Roller centre and its theta-derivatives, ground frame.
    RollerPath roller_path(const FollowerMotion& m) const {
        const Eigen::Vector2d u = planar::unit(arm_angle(m)), Ju = planar::perp(u);
        const double L = arm_length_;
        return {pivot_ + L * u, sigma_ * L * m.dh * Ju, sigma_ * L * m.d2h * Ju - L * m.dh * m.dh * u};
    }

    // theta is not needed: the arm's position follows from the lift alone.
    ContactGeometry contact(double /*theta*/, const FollowerMotion& m) const {
        const Eigen::Vector2d u = planar::unit(arm_angle(m));
        const RollerNormal rn = roller_normal(roller_path(m));
        const Eigen::Vector2d v = sigma_ * planar::perp(u);  // lifting direction of the centre
        const double cos_a = v.dot(rn.normal), sin_a = planar::cross(v, rn.normal);
        // d(v . n)/d theta with dv/d theta = sigma J (sigma s' J u) = -s' u.
        const double dcos_a = -m.dh * u.dot(rn.normal) + v.dot(rn.dnormal);
        return {rn.normal, rn.dnormal, arm_length_ * cos_a, arm_length_ * dcos_a, m.h, m.dh, cos_a, sin_a};
    }

    FollowerProfilePoint profile(double theta, const FollowerMotion& m) const {
        const RollerPath path = roller_path(m);
        const Eigen::Vector2d n = roller_normal(path).normal;
        const Eigen::Vector2d v = sigma_ * planar::perp(planar::unit(arm_angle(m)));
        const Eigen::Vector2d contact_point = path.centre - roller_radius_ * n;
        const double kappa = roller_pitch_curvature(path);
        return {theta,
                planar::to_cam_frame(theta, contact_point),
                planar::to_cam_frame(theta, path.centre),
                contact_point,
                roller_surface_radius(kappa, roller_radius_),
                roller_effective_radius(kappa, roller_radius_),
                std::atan2(planar::cross(v, n), v.dot(n))};
    }

    // Signed curvature of the pitch curve (roller-centre path in the cam frame), 1/m, > 0 convex.
    double pitch_curvature(const FollowerMotion& m) const { return roller_pitch_curvature(roller_path(m)); }

private:
    double base_radius_, roller_radius_;
    Eigen::Vector2d pivot_;
    double arm_length_;
    ArmTurn turn_;
    double sigma_;
    double phi0_ = 0.0;
};

}  // namespace camfollower
