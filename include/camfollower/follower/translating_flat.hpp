// SPDX-License-Identifier: BSD-3-Clause
// Translating flat-faced follower: a straight face, inclined by the face angle g, moving along the
// axis x = e (ground frame, y along the axis). The face line is {X : n . X = p(theta)} with the
// constant unit normal n = (-sin g, cos g) and the support distance p = r_b + cos g * h(theta)
// (tangent to the base circle at h = 0; a lift h moves the line by h along y, i.e. by cos g * h
// along n).
//
// In the cam frame the face normal turns at d psi / d theta = -1, so the envelope of the face lines
// (the cam surface) touches the face at X = p n - p' J n = p n + p' t, t = (cos g, sin g) the face
// direction, and has the radius of curvature rho = p + p'' = r_b + cos g (h + h'') (support-function
// formula). For g = 0: X = (h', r_b + h) and rho = r_b + h + h'', the textbook results. rho <= 0 is a
// cusp: the face cannot generate that profile.
//
// The contact point's velocity per unit lift is (0, 1): pressure angle = g, lever = cos g, both
// constant. The offset does not change the contact; it only moves the axis, and so where on the face
// the contact lies (face_position).
#pragma once

#include <array>
#include <cmath>
#include <tuple>
#include <string>
#include <limits>

#include <Eigen/Core>

#include "camfollower/error.hpp"
#include "camfollower/follower/contact_geometry.hpp"
#include "camfollower/follower/parameters.hpp"
#include "camfollower/follower/plane.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/motion/laws.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

class TranslatingFlat {
public:
    // Its name in configs, messages and exports; its lift is a length (m).
    static constexpr const char* type_name = "translating_flat";
    static constexpr bool translating = true;
    static constexpr const char* description =
        "Translating flat-faced follower: face angle (rad) from the normal to the axis, offset (m).";
    static constexpr std::array parameters{
        common_parameter::base_radius,
        optional_parameter("face_angle", ParameterKind::angle,
                           "face angle g from the normal to the axis (rad, |g| < pi/2)", 0.0),
        optional_parameter("offset", ParameterKind::length, "lateral position e of the axis (m)", 0.0),
    };

    // base_radius r_b (m, > 0); face_angle g (rad, |g| < pi/2; > 0 tilts the face normal towards -x);
    // offset e (m, finite): lateral position of the follower axis.
    explicit TranslatingFlat(double base_radius, double face_angle = 0.0, double offset = 0.0)
        : base_radius_(base_radius), face_angle_(face_angle), offset_(offset) {
        detail::require_length(base_radius, "base_radius");
        if (!(std::isfinite(face_angle) && std::abs(face_angle) < 0.5 * pi))
            detail::fail("face_angle must satisfy |face_angle| < pi/2 rad (90 deg), got ", face_angle, " rad (",
                         radians_to_degrees(face_angle), " deg)");
        detail::require_offset(offset, "offset");
        cos_g_ = std::cos(face_angle);
        sin_g_ = std::sin(face_angle);
    }

    auto parameter_values() const { return std::make_tuple(base_radius_, face_angle_, offset_); }
    double base_radius() const { return base_radius_; }
    double face_angle() const { return face_angle_; }
    double offset() const { return offset_; }
    double follower_radius() const { return std::numeric_limits<double>::infinity(); }

    Eigen::Vector2d face_normal() const { return {-sin_g_, cos_g_}; }
    Eigen::Vector2d face_direction() const { return {cos_g_, sin_g_}; }  // -J n

    ContactGeometry contact(double /*theta*/, const FollowerMotion& m) const {
        return {face_normal(), Eigen::Vector2d::Zero(), cos_g_, 0.0, m.h, m.dh, cos_g_, sin_g_};
    }

    FollowerProfilePoint profile(double theta, const FollowerMotion& m) const {
        const double p = base_radius_ + cos_g_ * m.h;
        const Eigen::Vector2d contact_point = p * face_normal() + cos_g_ * m.dh * face_direction();
        const double rho = p + cos_g_ * m.d2h;
        return {theta,
                planar::to_cam_frame(theta, contact_point),
                planar::to_cam_frame(theta, axis_point(m)),
                contact_point,
                rho,
                rho,
                face_angle_};
    }

    // Where the follower axis crosses the face (ground frame, m): the face's reference point.
    Eigen::Vector2d axis_point(const FollowerMotion& m) const {
        // On the base circle the face {n . X = r_b} meets x = e at y = (r_b + e sin g) / cos g.
        return {offset_, (base_radius_ + offset_ * sin_g_) / cos_g_ + m.h};
    }

    // Signed distance of the contact from the axis along the face direction t (m): how wide the face
    // must be. For g = 0 it is h' - e.
    double face_position(const FollowerMotion& m) const {
        const Eigen::Vector2d contact_point =
            (base_radius_ + cos_g_ * m.h) * face_normal() + cos_g_ * m.dh * face_direction();
        return (contact_point - axis_point(m)).dot(face_direction());
    }

private:
    double base_radius_, face_angle_, offset_;
    double cos_g_ = 1.0, sin_g_ = 0.0;
};

}  // namespace camfollower
