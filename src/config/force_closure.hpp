// SPDX-License-Identifier: BSD-3-Clause
// Force closure: is every follower held on its cam, at rest and at the camshaft's speed? Two checks
// per contact over one revolution (docs/config.md, "Force closure"):
//
//  - at rest: the contact force of the quasi-static equilibrium q_s(theta) (springs, preloads, loads,
//    gravity; Mechanism::static_equilibrium) must stay > 0; where it is <= 0 nothing presses the
//    follower onto the cam (a return spring left out, or one without preload);
//  - rigid: the mechanism following the cam along that quasi-static path at the speed omega, the
//    contacts held closed (no penetration change), the force each contact must carry is
//        F_i(theta) = F_s,i(theta) + omega dF_1,i(theta) + omega^2 dF_2,i(theta),
//    with [K_t G; G^T 0] [dq; dF] = -[M q_s'' omega^2 + C q_s' omega; 0] (G: the contacts' gradients
//    d delta / d q, K_t the tangent stiffness, q_s' and q_s'' central differences in theta). For one
//    follower mass m on a spring of rate k and preload P this is P + k h + c omega h' + m omega^2 h''.
//    Where it is < 0 the follower leaves the cam even without vibration. The dynamic response (the
//    jump speed of camfollower.speed) loses contact at lower speeds still: this check finds the
//    mechanisms that cannot work, it does not clear the others.
//  A grooved cam holds its roller either way: the rigid check then says which flank carries it where
//  (outer where F < 0) and how often the load changes flank. Conjugate cams (two contacts on one
//  follower DOF pushing it in opposite senses, follower_ratio of opposite signs) likewise: the rigid
//  check holds the lift cam's contact only (both together are one constraint) and its force, where
//  < 0, is carried by the return cam.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "camfollower/model/mechanism.hpp"
#include "camfollower/precompiled.hpp"  // the mechanisms and simulate() for them, compiled once

namespace camfollower::config {

struct ContactClosure {
    std::string contact;
    double static_min_force = 0.0;  // N, the smallest contact force at rest over the revolution
    double static_min_angle = 0.0;  // rad, the contact's cam angle (shaft angle + phase) where it is
    std::vector<std::pair<double, double>> static_open;  // cam-angle intervals (rad) where it is <= 0
    double rigid_min_force = 0.0;  // N, the rigid check's smallest contact force at the checked speed
    double rigid_min_angle = 0.0;  // rad, cam angle
    std::vector<std::pair<double, double>> rigid_loss;  // cam-angle intervals (rad) where it is < 0
    // The lowest camshaft speed at which the rigid check loses this contact: 0 when it is not pressed at
    // rest, infinity when no speed the model takes loses it.
    double rigid_limit_rpm = std::numeric_limits<double>::infinity();
    // A grooved cam (form-closed: no warnings): the cam-angle intervals (rad) where the rigid check's
    // force is < 0, i.e. the outer flank carries the roller, and how often the load changes flank per
    // revolution (at each change the roller crosses the groove clearance and strikes the other flank).
    bool grooved = false;
    std::vector<std::pair<double, double>> outer_flank;
    int flank_changes = 0;
    // One of conjugate cams (form-closed: no warnings): the other cam's contact, the cam-angle intervals
    // (rad) where the rigid check puts the load on the other cam, and how often per revolution the load
    // passes from one cam to the other (flank_changes; a dwell where the net force vanishes and both
    // carry only their preload is not a change).
    std::string conjugate;
    std::vector<std::pair<double, double>> other_cam;
};

struct ForceClosure {
    double rpm = 0.0;  // the speed checked
    int angles = 0;    // cam angles per revolution of the grid
    std::vector<ContactClosure> contacts;
    std::vector<std::string> warnings;  // one per contact that is not force-closed, naming it, the angles and the force
};

// The checks of the mechanism `b` at camshaft speed `rpm` (<= 0: the builder's own). A static
// equilibrium that cannot be found at some angle ends the check with a warning saying so.
ForceClosure check_force_closure(const MechanismBuilder& b, double rpm = 0.0);

}  // namespace camfollower::config
