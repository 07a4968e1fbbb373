// SPDX-License-Identifier: BSD-3-Clause
// Translating roller follower with offset: the roller centre runs along the axis x = e at height
// R(theta) = s0 + h(theta), s0 = sqrt((r_b + r_r)^2 - e^2). The kinematics are DiskCam's (paper
// eqs 2-5), reused so that both give bit-identical normals and pressure angles.
//
// Ground frame (contact_geometry.hpp): C = (e, R), n = (e - R', R)/|.| = (-sin a, cos a),
// a = atan((R' - e)/R), lever = n . (0, 1) = cos a.
// Note: DiskCam::profile draws the cam in a mirrored cam frame (axial, lateral) turned by +theta;
// profile() here uses X_cam = Rot(-theta) X_ground, the x <-> y mirror image of DiskCam's points.
// Radii of curvature and pressure angles do not depend on that choice.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "camfollower/error.hpp"
#include "camfollower/follower/contact_geometry.hpp"
#include "camfollower/follower/plane.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/follower/roller_pitch.hpp"
#include "camfollower/geometry/disk_cam.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

class TranslatingRoller {
public:
    // base_radius r_b (m, > 0), roller_radius r_r (m, > 0), offset e (m, |e| < r_b + r_r: the axis
    // must cut the base pitch circle).
    TranslatingRoller(double base_radius, double roller_radius, double offset)
        : base_radius_(base_radius), roller_radius_(roller_radius), offset_(offset) {
        detail::require_length(base_radius, "base_radius");
        detail::require_length(roller_radius, "roller_radius");
        const double rp = base_radius + roller_radius;
        if (!(std::isfinite(offset) && std::abs(offset) < rp))
            detail::fail("offset must satisfy |offset| < base_radius + roller_radius = ", rp,
                         " m, got ", offset, " m");
        pitch_base_ = std::sqrt(rp * rp - offset * offset);
    }

    double base_radius() const { return base_radius_; }
    double roller_radius() const { return roller_radius_; }
    double offset() const { return offset_; }
    double follower_radius() const { return roller_radius_; }
    // s0: roller-centre height on the base circle, m.
    double pitch_base() const { return pitch_base_; }

    // The same numbers as DiskCam::kinematics_from(m, s0, e), in the follower-generic form.
    ContactKinematics kinematics(const FollowerMotion& m) const {
        return DiskCam::kinematics_from(m, pitch_base_, offset_);
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
        const double kappa = DiskCam::curvature(k, offset_);
        return {theta,
                planar::to_cam_frame(theta, contact_point),
                planar::to_cam_frame(theta, centre),
                contact_point,
                roller_surface_radius(kappa, roller_radius_),
                roller_effective_radius(kappa, roller_radius_),
                k.pressure_angle()};
    }

    // Signed curvature of the pitch curve (roller-centre path in the cam frame), 1/m, > 0 convex.
    double pitch_curvature(const FollowerMotion& m) const {
        return DiskCam::curvature(kinematics(m), offset_);
    }

private:
    double base_radius_, roller_radius_, offset_;
    double pitch_base_;
};

}  // namespace camfollower
