// SPDX-License-Identifier: BSD-3-Clause
// Manufacturing defects of the paper (section 1.3), both off by default.
//
// Camshaft eccentricity (eqs 6-11): the cam's geometric centre turns around the bearing axis at
// radius `eccentricity`, at eccentricity (cos phi, sin phi) in (x, y), phi = omega t + phase (the
// cam turns counter-clockwise in (x, y), paper eq 5). Its vertical component is taken as the
// transmission error along the line of action, de_c(t) = eccentricity sin phi, added to the contact
// penetration (for n = 1 the paper's force K_h de_c; the exact projection on the normal would be
// eccentricity sin(phi - alpha)); its horizontal component moves the cam centre towards the follower
// axis, e* = e - eccentricity cos phi, which re-evaluates the pressure angle alpha* (eqs 9-11).
//
// Follower backlash (eqs 12-18): a guide clearance `backlash`. The rod rides at e' = e + backlash
// during rises and e'' = e - backlash during returns; dwells keep the side of the last rise or
// return. The side enters the geometry (alpha', alpha'') and, as a horizontal displacement of the
// roller support, the guide spring K_rb (x3). The switch ramps over `backlash_switch_width` (rad of
// cam angle) from the start of the segment that changes side (C1 smoothstep); 0 is the literal hard
// switch.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "camfollower/error.hpp"
#include "camfollower/contact/paper_backlash.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

struct Defects {
    double eccentricity = 0.0;          // m
    double eccentricity_phase = 0.0;    // zeta, rad
    double backlash = 0.0;              // m
    double backlash_switch_width = 0.0; // rad

    bool any() const { return eccentricity != 0.0 || backlash != 0.0; }

    void validate() const {
        detail::require_non_negative(eccentricity, "eccentricity", "(m)");
        detail::require_finite(eccentricity_phase, "eccentricity_phase");
        detail::require_non_negative(backlash, "backlash", "(m)");
        detail::require_in_range(backlash_switch_width, 0.0, pi, "backlash_switch_width (rad)");
    }
};

}  // namespace camfollower
