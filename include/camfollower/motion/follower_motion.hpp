// SPDX-License-Identifier: BSD-3-Clause
// The follower lift and its cam-angle derivatives at one theta: the value every motion description
// (program, spline, polynomial) hands out.
#pragma once

namespace camfollower {

// Lift and its cam-angle derivatives at one theta.
struct FollowerMotion {
    double h;    // m
    double dh;   // m/rad
    double d2h;  // m/rad^2
    double d3h;  // m/rad^3
};

}  // namespace camfollower
