// SPDX-License-Identifier: BSD-3-Clause
// The paper's literal follower backlash (Tounsi et al., its eqs 12-18), a named formulation beside the
// guide clearance modelled from its mechanism (contact/clearance.hpp, where the rod crosses the gap
// when the lateral load reverses). Here the rod's side is imposed by the cam program instead:
// - the rod rides at e + b during rises and at e - b during returns; dwells keep the side of the last
//   rise or return; the switch ramps over switch_width (rad of cam angle) from the start of the segment
//   that changes side (C1 smoothstep; 0 is the literal hard switch);
// - the contact geometry follows the offset e' = e + b s(theta) (the pressure angle alpha'), with the
//   offset's rate in the terms' time derivatives;
// - the guide's spring is anchored on the displaced rod: a load guide_stiffness b s(theta) along
//   +guide_dof (the rod's lateral DOF at the guide).
// Defined for a translating roller follower on a rigid camshaft; kept to reproduce the paper.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "camfollower/core/ground.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/program.hpp"

namespace camfollower {

struct PaperBacklash {
    double backlash = 0.0;                // b, m (0: off)
    double switch_width = 0.0;            // rad of cam angle
    std::string guide_dof = ground_name;  // the rod's lateral DOF at the guide
    double guide_stiffness = 0.0;         // K_rb, N/m: the load K_rb b s on guide_dof

    bool any() const { return backlash != 0.0; }
    void validate(const std::string& who) const {
        detail::require_non_negative(backlash, (who + " paper backlash").c_str(), "(m)");
        detail::require_in_range(switch_width, 0.0, pi, (who + " paper backlash switch_width (rad)").c_str());
        detail::require_non_negative(guide_stiffness, (who + " paper backlash guide_stiffness").c_str(), "(N/m)");
        if (guide_stiffness > 0.0 && guide_dof == ground_name)
            detail::fail(who,
                         ": the paper backlash's guide_stiffness loads guide_dof, which must be a DOF, not ground");
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
                detail::fail("backlash_switch_width = ", radians_to_degrees(width), " deg must not exceed the ",
                             radians_to_degrees(spacing), " deg between two switches of the rod's side");
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
