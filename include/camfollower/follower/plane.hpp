// SPDX-License-Identifier: BSD-3-Clause
// Plane-vector helpers shared by the follower types: the quarter turn J, the scalar cross product,
// rotations and the change from the ground frame to the cam frame (X_cam = Rot(-theta) X_ground).
#pragma once

#include <cmath>

#include <Eigen/Core>

namespace camfollower::planar {

// J v: v turned by +90 deg, J(x, y) = (-y, x).
inline Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

// a x b (z component): positive when b lies counter-clockwise of a.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Unit vector at `angle` rad from the x axis.
inline Eigen::Vector2d unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

// Rot(angle) v.
inline Eigen::Vector2d rotate(double angle, const Eigen::Vector2d& v) {
    const double c = std::cos(angle), s = std::sin(angle);
    return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// The cam turns counter-clockwise by theta, so a ground point seen from the cam turns back by theta.
inline Eigen::Vector2d to_cam_frame(double theta, const Eigen::Vector2d& ground) { return rotate(-theta, ground); }

}  // namespace camfollower::planar
