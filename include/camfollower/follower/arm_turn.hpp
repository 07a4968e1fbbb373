// SPDX-License-Identifier: BSD-3-Clause
// The lifting sense of an oscillating follower's arm, and the arm's starting angle on the base
// circle (shared by the oscillating roller and the oscillating flat face).
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "camfollower/error.hpp"

namespace camfollower {

// Which way the arm turns (in the ground frame) when the follower lifts. The cam itself always turns
// counter-clockwise; a clockwise arm is the usual "trailing" arrangement on the rise.
enum class ArmTurn { counter_clockwise, clockwise };

// sigma = +1 (counter-clockwise) or -1 (clockwise): phi = phi0 + sigma s(theta).
inline double turn_sign(ArmTurn turn) {
    switch (turn) {
        case ArmTurn::counter_clockwise: return 1.0;
        case ArmTurn::clockwise: return -1.0;
    }
    detail::fail("turn must be ArmTurn::counter_clockwise or ArmTurn::clockwise");
}

namespace detail {

// The angle phi with P . u(phi) = projection (u = (cos phi, sin phi)) at which P . J u(phi) has the
// sign of sigma: of the two roots phi = beta -+ gamma (beta the angle of P, cos gamma =
// projection / |P|), P . J u = -|P| sin(phi - beta) picks phi = beta - sigma gamma. The caller has
// checked |projection| < |P| (a transversal root, so P . J u != 0 there).
inline double arm_angle_with_projection(const Eigen::Vector2d& P, double projection, double sigma) {
    const double beta = std::atan2(P.y(), P.x());
    const double gamma = std::acos(projection / P.norm());
    return beta - sigma * gamma;
}

}  // namespace detail
}  // namespace camfollower
