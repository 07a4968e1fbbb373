// SPDX-License-Identifier: BSD-3-Clause
// A point of a link in the plane of a linkage, as a function of the mechanism's DOFs: on the ground,
// on a link turning about a fixed pivot (a swing arm, a rocker), on a slider along a fixed line, or on
// a free planar body (a coupler: two translations and a rotation). Positions are in the linkage's
// own plane frame (m); each DOF is a displacement from the reference configuration the builder
// assembled, so q = 0 is that configuration.
//
//   ground     p = point
//   rotating   p = pivot + r (cos(a0 + s q), sin(a0 + s q))                 s = +-1: the DOF's sense
//   sliding    p = origin + q u,  u = (cos gamma, sin gamma)
//   planar     p = c0 + (q_x, q_y) + R(b0 + q_b) l                          l: the point in the body frame
//
// The Jacobian d p / d q has at most three columns; the only second derivatives are those of a
// rotation, d2 p / d q_rot^2 = -(p - centre of rotation).
#pragma once

#include <array>
#include <cmath>
#include <string>

#include <Eigen/Core>

#include "camfollower/error.hpp"

namespace camfollower {

struct PlanarPoint {
    enum class Kind { ground, rotating, sliding, planar };
    Kind kind = Kind::ground;
    // The DOFs by name: rotating and sliding use dofs[0]; planar (x, y, rotation); "ground": unused.
    std::array<std::string, 3> dofs{"ground", "ground", "ground"};
    Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // ground: the point; rotating: the pivot;
                                                       // sliding: the point at q = 0; planar: c0
    double radius = 0.0;                               // rotating: the point's distance from the pivot, m
    double angle = 0.0;                                // rotating: a0; sliding: gamma; planar: b0 (rad)
    double sense = 1.0;                                // rotating: +1 counter-clockwise with q, -1 clockwise
    Eigen::Vector2d local = Eigen::Vector2d::Zero();   // planar: the point in the body frame, m

    static PlanarPoint fixed(const Eigen::Vector2d& p) { return {Kind::ground, {}, p, 0.0, 0.0, 1.0, {}}; }
    static PlanarPoint on_rotating(const std::string& dof, const Eigen::Vector2d& pivot, double radius, double angle,
                                   double sense = 1.0) {
        return {Kind::rotating, {dof, "ground", "ground"}, pivot, radius, angle, sense, {}};
    }
    static PlanarPoint on_slider(const std::string& dof, const Eigen::Vector2d& at_rest, double direction) {
        return {Kind::sliding, {dof, "ground", "ground"}, at_rest, 0.0, direction, 1.0, {}};
    }
    static PlanarPoint on_body(const std::array<std::string, 3>& dofs, const Eigen::Vector2d& centre, double angle,
                               const Eigen::Vector2d& local) {
        return {Kind::planar, dofs, centre, 0.0, angle, 1.0, local};
    }

    // How many DOFs this point moves with (0 to 3).
    int dof_count() const {
        switch (kind) {
            case Kind::ground: return 0;
            case Kind::rotating:
            case Kind::sliding: return 1;
            case Kind::planar: return 3;
        }
        return 0;
    }
    // The DOF whose second derivative is not zero (rotating: 0, planar: 2), -1 for none.
    int rotation_slot() const { return kind == Kind::rotating ? 0 : kind == Kind::planar ? 2 : -1; }

    void validate(const std::string& who) const {
        for (int i = 0; i < 2; ++i)
            if (!std::isfinite(origin[i])) detail::fail(who, ": position must be finite");
        if (!std::isfinite(angle)) detail::fail(who, ": angle must be finite");
        if (kind == Kind::rotating) {
            if (!(std::isfinite(radius) && radius > 0.0 && radius <= detail::max_part_length))
                detail::fail(who, ": radius must be in (0, ", detail::max_part_length, "] m, got ", radius, " m");
            if (!(sense == 1.0 || sense == -1.0)) detail::fail(who, ": sense must be +1 or -1, got ", sense);
        }
        if (kind == Kind::planar && !(local.allFinite() && local.norm() <= detail::max_part_length))
            detail::fail(who, ": the point on the body must be finite and within ", detail::max_part_length, " m");
    }

    // Position (m) at the displacements x[0..dof_count()) of this point's DOFs, its Jacobian columns
    // d p / d x_i, and the rotation's second derivative d2 p / d x_rot^2.
    struct Value {
        Eigen::Vector2d p;
        std::array<Eigen::Vector2d, 3> dp;
        Eigen::Vector2d d2p_rotation;
    };
    Value at(const std::array<double, 3>& x) const {
        Value v{origin,
                {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()},
                Eigen::Vector2d::Zero()};
        switch (kind) {
            case Kind::ground: break;
            case Kind::rotating: {
                const double a = angle + sense * x[0];
                const Eigen::Vector2d arm = radius * Eigen::Vector2d(std::cos(a), std::sin(a));
                v.p = origin + arm;
                v.dp[0] = sense * Eigen::Vector2d(-arm.y(), arm.x());
                v.d2p_rotation = -arm;
                break;
            }
            case Kind::sliding: {
                const Eigen::Vector2d u(std::cos(angle), std::sin(angle));
                v.p = origin + x[0] * u;
                v.dp[0] = u;
                break;
            }
            case Kind::planar: {
                const double b = angle + x[2], c = std::cos(b), s = std::sin(b);
                const Eigen::Vector2d r(c * local.x() - s * local.y(), s * local.x() + c * local.y());
                v.p = origin + Eigen::Vector2d(x[0], x[1]) + r;
                v.dp[0] = Eigen::Vector2d(1.0, 0.0);
                v.dp[1] = Eigen::Vector2d(0.0, 1.0);
                v.dp[2] = Eigen::Vector2d(-r.y(), r.x());
                v.d2p_rotation = -r;
                break;
            }
        }
        return v;
    }
};

}  // namespace camfollower
