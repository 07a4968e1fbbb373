// Manufacturing defects of the paper (section 1.3), both off by default.
//
// Camshaft eccentricity (eqs 6-11): the cam's geometric centre turns around the bearing axis at
// radius `eccentricity`. Its component along the line of action is the transmission error
// de_c(t) = eccentricity sin(omega t + phase), added to the contact penetration (for n = 1 this is
// the paper's force K_h de_c); its horizontal component de_x(t) = eccentricity cos(omega t + phase)
// perturbs the offset, e* = e + de_x, which re-evaluates the pressure angle alpha* (eqs 9-11).
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
