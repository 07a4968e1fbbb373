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

// The rod's side in the guide, s(theta) in [-1, 1] (+1: e + backlash), and ds/dtheta.
class BacklashSide {
public:
    BacklashSide() = default;
    BacklashSide(const MotionProgram& program, double width) : width_(width) {
        const auto& segs = program.segments();
        // Side of each moving segment; dwells inherit cyclically from the last moving one.
        std::vector<double> side(segs.size(), 0.0);
        for (std::size_t i = 0; i < segs.size(); ++i)
            if (segs[i].lift() != 0.0) side[i] = segs[i].lift() > 0.0 ? 1.0 : -1.0;
        if (std::none_of(side.begin(), side.end(), [](double s) { return s != 0.0; })) return;
        for (std::size_t pass = 0; pass < 2; ++pass)
            for (std::size_t i = 0; i < segs.size(); ++i)
                if (side[i] == 0.0 || (pass == 1 && segs[i].lift() == 0.0))
                    side[i] = side[(i + segs.size() - 1) % segs.size()];
        for (std::size_t i = 0; i < segs.size(); ++i) {
            const double before = side[(i + segs.size() - 1) % segs.size()];
            if (side[i] != before) switches_.push_back({segs[i].theta_start, before, side[i]});
        }
        if (switches_.empty()) constant_ = side[0];
        // Each ramp must end before the next switch starts.
        for (std::size_t i = 0; i < switches_.size(); ++i) {
            const double next = switches_[(i + 1) % switches_.size()].theta;
            const double gap = MotionProgram::wrap(next - switches_[i].theta);
            const double spacing = gap == 0.0 ? two_pi : gap;
            if (width > spacing)
                detail::fail("backlash_switch_width = ", radians_to_degrees(width),
                             " deg must not exceed the ", radians_to_degrees(spacing),
                             " deg between two switches of the rod's side");
        }
    }

    struct Value {
        double side, dside;  // dside: per rad of cam angle
    };

    Value at(double theta) const {
        if (switches_.empty()) return {constant_, 0.0};
        const double t = MotionProgram::wrap(theta);
        // The last switch at or before t (cyclically).
        const Switch* last = &switches_.back();
        for (const Switch& s : switches_)
            if (s.theta <= t) last = &s;
        if (width_ == 0.0) return {last->to, 0.0};
        const double since = MotionProgram::wrap(t - last->theta);
        if (since >= width_) return {last->to, 0.0};
        const double x = since / width_;
        const double step = x * x * (3.0 - 2.0 * x), dstep = 6.0 * x * (1.0 - x) / width_;
        return {last->from + (last->to - last->from) * step, (last->to - last->from) * dstep};
    }

private:
    struct Switch {
        double theta, from, to;
    };
    std::vector<Switch> switches_;
    double constant_ = 0.0;
    double width_ = 0.0;
};

}  // namespace camfollower
