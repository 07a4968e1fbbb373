// SPDX-License-Identifier: BSD-3-Clause
// Translating roller follower with offset (paper section 1.2, eqs 2-5): the roller centre runs along
// the axis x = e at height R(theta) = s0 + h(theta), s0 = sqrt((r_b + r_r)^2 - e^2).
//
// Ground frame (contact_geometry.hpp): C = (e, R), n = (e - R', R)/|.| = (-sin a, cos a),
// a = atan((R' - e)/R) (paper eq 4, I12I24 = dR/dtheta), lever = n . (0, 1) = cos a. A positive
// offset lowers the pressure angle on the rise (R' > 0) and raises its magnitude on the return.
// Pitch-curve curvature (positive where convex):
//   kappa = (R^2 + (R' - e)(2R' - e) - R R'') / (R^2 + (R' - e)^2)^(3/2); surface radius
//   rho_s = 1/kappa - r_r. A convex stretch with 1/kappa <= r_r undercuts (the roller cannot follow).
// profile() draws the cam in the frame X_cam = Rot(-theta) X_ground.
#pragma once

#include <array>
#include <cmath>
#include <tuple>
#include <string>

#include <Eigen/Core>

#include "camfollower/error.hpp"
#include "camfollower/follower/contact_geometry.hpp"
#include "camfollower/follower/parameters.hpp"
#include "camfollower/follower/plane.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/follower/roller_pitch.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

// What the contact needs at one cam angle: cheap, no trigonometry beyond the motion law.
struct ContactKinematics {
    double h, dh, d2h;            // lift and its theta-derivatives
    double R, dR, d2R;            // roller-centre distance along the axis and theta-derivatives
    double cos_alpha, sin_alpha;  // pressure angle
    double dalpha;                // d alpha / d theta

    double pressure_angle() const { return std::atan2(sin_alpha, cos_alpha); }
    // Unit normal from cam to roller, follower frame (x lateral, y axial).
    Eigen::Vector2d normal() const { return {-sin_alpha, cos_alpha}; }
};

class TranslatingRoller {
public:
    // Its name in configs, messages and exports; its lift is a length (m).
    static constexpr const char* type_name = "translating_roller";
    static constexpr bool translating = true;
    static constexpr const char* description = "Translating roller follower with offset (m): the paper's follower.";
    static constexpr std::array parameters{
        common_parameter::base_radius,
        common_parameter::roller_radius,
        optional_parameter("offset", ParameterKind::length, "lateral offset e of the axis (m, |e| < r_b + r_r)", 0.0),
    };

    // base_radius r_b (m, > 0), roller_radius r_r (m, > 0), offset e (m, |e| < r_b + r_r: the axis
    // must cut the base pitch circle).
    TranslatingRoller(double base_radius, double roller_radius, double offset = 0.0)
        : base_radius_(base_radius), roller_radius_(roller_radius), offset_(offset) {
        detail::require_length(base_radius, "base_radius");
        detail::require_length(roller_radius, "roller_radius");
        const double rp = base_radius + roller_radius;
        if (!(std::isfinite(offset) && std::abs(offset) < rp))
            detail::fail("offset must satisfy |offset| < base_radius + roller_radius = ", rp, " m, got ", offset, " m");
        pitch_base_ = std::sqrt(rp * rp - offset * offset);
    }

    auto parameter_values() const { return std::make_tuple(base_radius_, roller_radius_, offset_); }
    double base_radius() const { return base_radius_; }
    double roller_radius() const { return roller_radius_; }
    double offset() const { return offset_; }
    double follower_radius() const { return roller_radius_; }
    // s0: roller-centre height on the base circle, m.
    double pitch_base() const { return pitch_base_; }

    ContactKinematics kinematics(const FollowerMotion& m) const { return kinematics_from(m, pitch_base_, offset_); }

    // The same at any offset and s0 (the paper's perturbed offset e*, eqs 8-18, and its backlash).
    static ContactKinematics kinematics_from(const FollowerMotion& m, double s0, double offset) {
        const double R = s0 + m.h, dR = m.dh, d2R = m.d2h;
        const double p = dR - offset;  // R' - e
        const double norm2 = R * R + p * p;
        const double inv = 1.0 / std::sqrt(norm2);
        // d/dtheta atan(p / R) = (p' R - p R') / (R^2 + p^2), p' = R''
        return {m.h, m.dh, m.d2h, R, dR, d2R, R * inv, p * inv, (d2R * R - p * dR) / norm2};
    }

    // Pitch-curve curvature kappa (1/m, > 0 convex) from the kinematics at offset e.
    static double curvature(const ContactKinematics& k, double offset) {
        const double p = k.dR - offset;
        const double norm2 = k.R * k.R + p * p;
        return (k.R * k.R + p * (2.0 * k.dR - offset) - k.R * k.d2R) / (norm2 * std::sqrt(norm2));
    }

    // theta is not needed: a translating follower's contact depends on the lift only.
    ContactGeometry contact(double /*theta*/, const FollowerMotion& m) const {
        const ContactKinematics k = kinematics(m);
        const double c = k.cos_alpha, s = k.sin_alpha;
        return {k.normal(), Eigen::Vector2d(-c, -s) * k.dalpha, c, -s * k.dalpha, m.h, m.dh, c, s};
    }

    FollowerProfilePoint profile(double theta, const FollowerMotion& m) const {
        const ContactKinematics k = kinematics(m);
        const Eigen::Vector2d centre(offset_, k.R);
        const Eigen::Vector2d contact_point = centre - roller_radius_ * k.normal();
        const double kappa = curvature(k, offset_);
        return {theta,
                planar::to_cam_frame(theta, contact_point),
                planar::to_cam_frame(theta, centre),
                contact_point,
                roller_surface_radius(kappa, roller_radius_),
                roller_effective_radius(kappa, roller_radius_),
                k.pressure_angle()};
    }

    // Signed curvature of the pitch curve (roller-centre path in the cam frame), 1/m, > 0 convex.
    double pitch_curvature(const FollowerMotion& m) const { return curvature(kinematics(m), offset_); }

private:
    double base_radius_, roller_radius_, offset_;
    double pitch_base_;
};

}  // namespace camfollower
