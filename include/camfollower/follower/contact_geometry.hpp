// SPDX-License-Identifier: BSD-3-Clause
// What every follower type gives the dynamic model at one cam angle: the contact normal, the lever
// of the follower's own coordinate, and the nominal follower motion, with their cam-angle rates.
//
// Frames and conventions (shared by every follower type):
// - Ground frame: origin at the cam's (undisplaced) centre, fixed in space. For translating followers
//   y points along the follower axis (away from the cam) and x across it, towards the side of the
//   offset. The cam turns counter-clockwise in this frame as theta increases.
// - Cam frame: the ground frame turned with the cam, X_cam = Rot(-theta) X_ground (equal at theta = 0).
// - The follower's coordinate s is the program's lift: m for translating followers (along the axis),
//   rad for oscillating ones (arm rotation in the lifting sense). Its nominal value is s(theta).
// - Linearized penetration of a contact pair (the paper's form, exact to first order about the
//   nominal kinematic configuration):
//       delta = n . (u_cam - u_lateral) + lever * (s(theta) - q_follower)
//   with n the unit normal from cam to follower, lever = d delta / d(-q_follower) = n . (velocity of
//   the follower's contact point per unit lift), u_cam the cam centre's displacement and u_lateral a
//   translation of the follower across its axis (translating followers).
// - Pressure angle: the angle from the follower contact point's lifting direction to the normal,
//   alpha = atan2(v x n, v . n); for the translating roller alpha = atan((R' - e) / R).
//   v is the lifting direction of the follower's contact point, except for the oscillating roller,
//   where it is the roller centre's (sigma J u): the centre lies on the normal line, so lever =
//   L cos alpha with that choice (the usual textbook definition).
// Implementations (one header each): follower/translating_roller.hpp, translating_flat.hpp,
// oscillating_roller.hpp, oscillating_flat.hpp; the arm's lifting sense ArmTurn is in
// follower/arm_turn.hpp, the cam-frame profile point and the sampled checks in follower/profile.hpp.
#pragma once

#include <cmath>

#include <Eigen/Core>

namespace camfollower {

struct ContactGeometry {
    Eigen::Vector2d normal;       // unit, cam -> follower, ground frame
    Eigen::Vector2d dnormal;      // d normal / d theta, 1/rad
    double lever;                 // m per unit of s (translating: cos alpha; oscillating: moment arm, m)
    double dlever;                // d lever / d theta, per rad
    double lift;                  // s(theta): m (translating) or rad (oscillating)
    double dlift;                 // ds / d theta
    double cos_alpha, sin_alpha;  // pressure angle

    double pressure_angle() const { return std::atan2(sin_alpha, cos_alpha); }
};

}  // namespace camfollower
