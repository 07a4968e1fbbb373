// SPDX-License-Identifier: BSD-3-Clause
// Contact normal and pitch-curve curvature of any roller follower, from its centre's path C(theta)
// in the ground frame and the theta-derivatives of that path.
//
// The pitch curve in the cam frame is Rot(-theta) C, so (J = +90 deg turn, Rot commutes with J)
//   tangent         T = Rot(-theta) (C' - J C)
//   second deriv.   A = Rot(-theta) (C'' - 2 J C' - C)
// The cam turns counter-clockwise, so the follower runs round the cam clockwise: the outward normal
// (cam -> roller) is J T, turned back to the ground frame N = C + J C'. The curve is convex where it
// turns clockwise, so the signed curvature (> 0 convex) is -(T x A) / |T|^3 (rotation keeps x).
#pragma once

#include <cmath>
#include <limits>

#include <Eigen/Core>

#include "camfollower/follower/plane.hpp"

namespace camfollower {

struct RollerPath {
    Eigen::Vector2d centre;    // C, ground frame, m
    Eigen::Vector2d dcentre;   // dC/dtheta, m/rad
    Eigen::Vector2d d2centre;  // d2C/dtheta2, m/rad^2
};

struct RollerNormal {
    Eigen::Vector2d normal;   // unit, cam -> roller, ground frame
    Eigen::Vector2d dnormal;  // d normal / d theta, 1/rad
};

// n = N/|N| with N = C + J C'; dn = (I - n n^T) N' / |N| with N' = C' + J C''.
inline RollerNormal roller_normal(const RollerPath& path) {
    const Eigen::Vector2d N = path.centre + planar::perp(path.dcentre);
    const Eigen::Vector2d dN = path.dcentre + planar::perp(path.d2centre);
    const double length = N.norm();
    const Eigen::Vector2d n = N / length;
    return {n, (dN - n * n.dot(dN)) / length};
}

// Signed curvature of the pitch curve, 1/m, > 0 where convex.
inline double roller_pitch_curvature(const RollerPath& path) {
    const Eigen::Vector2d T = path.dcentre - planar::perp(path.centre);
    const Eigen::Vector2d A = path.d2centre - 2.0 * planar::perp(path.dcentre) - path.centre;
    const double speed = T.norm();
    return -planar::cross(T, A) / (speed * speed * speed);
}

// Cam surface radius of curvature (signed, +inf at a pitch-curve inflection) and the effective
// contact radius 1/(1/rho_surface + 1/r_r) = r_r (1 - r_r kappa), finite everywhere.
inline double roller_surface_radius(double pitch_curvature, double roller_radius) {
    return pitch_curvature == 0.0 ? std::numeric_limits<double>::infinity() : 1.0 / pitch_curvature - roller_radius;
}
inline double roller_effective_radius(double pitch_curvature, double roller_radius) {
    return roller_radius * (1.0 - roller_radius * pitch_curvature);
}

}  // namespace camfollower
