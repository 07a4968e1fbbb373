// SPDX-License-Identifier: BSD-3-Clause
// Oscillating flat-faced follower: a straight face on an arm turning about the fixed pivot P. The
// face is the line {X : m(phi) . X = m(phi) . P + f}, m(phi) = (cos phi, sin phi) its unit normal
// pointing away from the cam, f the face offset (signed distance of the face from the pivot along
// m), phi = phi0 + sigma s(theta) (s in rad; sigma = +1 counter-clockwise lift, -1 clockwise).
//
// Support distance of the face from the cam centre: p = m . P + f, p' = sigma s' (J m . P).
// phi0 solves m(phi0) . P + f = r_b with sign(J m . P) = sigma, so lifting pushes the face out.
//
// In the cam frame the normal's angle is psi = phi - theta, w = d psi / d theta = sigma s' - 1, so
// (support-function envelope, p as a function of psi):
//   contact point     X = p m + (p'/w) J m
//   radius of curv.   rho = p + d2p/dpsi2 = p + (p'' w - p' w') / w^3      (> 0 convex)
// w = 0 (the face turning with the cam) is singular: X and rho are not finite there.
//
// Taking X as a point of the face, dX/ds = sigma J (X - P). With F = P + f m (the foot of the
// perpendicular from the pivot) X - P = f m + a J m, a = (J m . P) / w (since p'/w - J m . P =
// (J m . P) / w), hence
//   lever = n . dX/ds = sigma m . J (X - P) = -sigma a,   pressure angle from v = J(X - P)/|X - P|:
//   cos alpha = -sigma a / |X - P|,   sin alpha = -sigma f / |X - P|.
// So the pressure angle is identically 0 when the face passes through the pivot (f = 0), and not 0
// on a dwell otherwise. lever <= 0 means |alpha| >= 90 deg: check_undercut refuses it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <string>
#include <limits>

#include <Eigen/Core>

#include "camfollower/error.hpp"
#include "camfollower/follower/arm_turn.hpp"
#include "camfollower/follower/contact_geometry.hpp"
#include "camfollower/follower/parameters.hpp"
#include "camfollower/follower/plane.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

class OscillatingFlat {
public:
    // Its name in configs, messages and exports; its lift is the arm's rotation (rad).
    static constexpr const char* type_name = "oscillating_flat";
    static constexpr bool translating = false;
    static constexpr const char* description =
        "Oscillating flat-faced follower: pivot (x, y) in m, face offset from the pivot (m); its lift program is "
        "the arm rotation in rad.";
    static constexpr std::array parameters{
        common_parameter::base_radius,
        common_parameter::pivot,
        optional_parameter("face_offset", ParameterKind::length,
                           "distance f of the face from the pivot (m, |r_b - f| < |P|)", 0.0),
        common_parameter::turn,
    };

    // base_radius r_b (m, > 0), pivot P (m, ground frame, outside the base circle), face_offset f (m,
    // |r_b - f| < |P| so the face can touch the base circle), turn: the arm's lifting sense.
    OscillatingFlat(double base_radius, const Eigen::Vector2d& pivot, double face_offset = 0.0,
                    ArmTurn turn = ArmTurn::counter_clockwise)
        : base_radius_(base_radius), pivot_(pivot), face_offset_(face_offset), turn_(turn), sigma_(turn_sign(turn)) {
        detail::require_length(base_radius, "base_radius");
        if (!(std::isfinite(pivot.x()) && std::isfinite(pivot.y()) && pivot.norm() <= detail::max_part_length))
            detail::fail("pivot must be finite and within ", detail::max_part_length, " m of the cam centre, got (",
                         pivot.x(), ", ", pivot.y(), ")");
        detail::require_offset(face_offset, "face_offset");
        const double d = pivot.norm();
        if (!(d > base_radius))
            detail::fail("pivot must lie outside the base circle: |pivot| = ", d,
                         " m must be > base_radius = ", base_radius, " m");
        const double projection = base_radius - face_offset;  // m(phi0) . P
        if (!(std::abs(projection) < d))
            detail::fail("face_offset = ", face_offset,
                         " m: the face cannot touch the base circle from the pivot at |pivot| = ", d,
                         " m; face_offset must lie in (", base_radius - d, ", ", base_radius + d,
                         ") m (|base_radius - face_offset| < |pivot|)");
        phi0_ = detail::arm_angle_with_projection(pivot, std::clamp(projection, -d, d), sigma_);
    }

    auto parameter_values() const { return std::make_tuple(base_radius_, pivot_, face_offset_, turn_); }
    double base_radius() const { return base_radius_; }
    const Eigen::Vector2d& pivot() const { return pivot_; }
    double face_offset() const { return face_offset_; }
    ArmTurn turn() const { return turn_; }
    double follower_radius() const { return std::numeric_limits<double>::infinity(); }
    // phi0: angle of the face normal (rad, ground frame) with the face on the base circle.
    double start_angle() const { return phi0_; }
    double arm_angle(const FollowerMotion& m) const { return phi0_ + sigma_ * m.h; }

    ContactGeometry contact(double /*theta*/, const FollowerMotion& m) const {
        const Eigen::Vector2d n = planar::unit(arm_angle(m)), Jn = planar::perp(n);
        const double nP = n.dot(pivot_), JnP = Jn.dot(pivot_);
        const double w = sigma_ * m.dh - 1.0;
        const double a = JnP / w;  // contact position along J n from the pivot's foot
        // d(J n . P)/d theta = sigma s' (J J n) . P = -sigma s' n . P; w' = sigma s''.
        const double da = (-sigma_ * m.dh * nP * w - JnP * sigma_ * m.d2h) / (w * w);
        const Eigen::Vector2d arm = face_offset_ * n + a * Jn;  // X - P
        const Eigen::Vector2d v = sigma_ * planar::perp(arm) / arm.norm();
        return {n, sigma_ * m.dh * Jn, -sigma_ * a, -sigma_ * da, m.h, m.dh, v.dot(n), planar::cross(v, n)};
    }

    FollowerProfilePoint profile(double theta, const FollowerMotion& m) const {
        const Eigen::Vector2d n = planar::unit(arm_angle(m)), Jn = planar::perp(n);
        const double nP = n.dot(pivot_), JnP = Jn.dot(pivot_);
        const double p = nP + face_offset_;
        const double dp = sigma_ * m.dh * JnP;
        const double d2p = sigma_ * m.d2h * JnP - m.dh * m.dh * nP;
        const double w = sigma_ * m.dh - 1.0, dw = sigma_ * m.d2h;
        const Eigen::Vector2d contact_point = p * n + (dp / w) * Jn;
        const double rho = p + (d2p * w - dp * dw) / (w * w * w);
        const Eigen::Vector2d foot = pivot_ + face_offset_ * n;
        const Eigen::Vector2d v = sigma_ * planar::perp(contact_point - pivot_);
        return {
            theta, planar::to_cam_frame(theta, contact_point), planar::to_cam_frame(theta, foot), contact_point, rho,
            rho,   std::atan2(planar::cross(v, n), v.dot(n))};
    }

    // Signed distance (m) along J m from the pivot's foot F = P + f m to the contact: how long the
    // face must be.
    double face_position(const FollowerMotion& m) const {
        const Eigen::Vector2d n = planar::unit(arm_angle(m));
        return planar::perp(n).dot(pivot_) / (sigma_ * m.dh - 1.0);
    }

private:
    double base_radius_;
    Eigen::Vector2d pivot_;
    double face_offset_;
    ArmTurn turn_;
    double sigma_;
    double phi0_ = 0.0;
};

}  // namespace camfollower
