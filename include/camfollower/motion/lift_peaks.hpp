// SPDX-License-Identifier: BSD-3-Clause
// Peaks of |h'|, |h''|, |h'''| of a lift that is smooth between given breaks: a grid over every piece
// finds the bracket, golden-section refinement (detail::maximize) the peak inside it.
#pragma once

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "camfollower/detail/extremum.hpp"
#include "camfollower/motion/follower_motion.hpp"

namespace camfollower {

// Largest |d^k h / dtheta^k| (m/rad^k) and the angle where it occurs (rad).
struct LiftPeak {
    double value = 0.0;
    double theta = 0.0;
};

struct LiftPeaks {
    LiftPeak velocity;      // |h'|, m/rad
    LiftPeak acceleration;  // |h''|, m/rad^2
    LiftPeak jerk;          // |h'''|, m/rad^3
};

namespace detail {

// f(theta) -> FollowerMotion, smooth inside each piece [breaks[i], breaks[i + 1]] (ascending).
template <class F>
LiftPeaks find_lift_peaks(const F& f, const std::vector<double>& breaks, std::size_t samples_per_piece) {
    struct Best {
        double value = -1.0, theta = 0.0, step = 0.0;
    };
    Best best[3];
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
        const double a = breaks[i], b = breaks[i + 1];
        const double step = (b - a) / static_cast<double>(samples_per_piece);
        for (std::size_t k = 0; k <= samples_per_piece; ++k) {
            const double theta = k == samples_per_piece ? b : a + step * static_cast<double>(k);
            const FollowerMotion m = f(theta);
            const double v[3] = {std::abs(m.dh), std::abs(m.d2h), std::abs(m.d3h)};
            for (int q = 0; q < 3; ++q)
                if (v[q] > best[q].value) best[q] = {v[q], theta, step};
        }
    }
    LiftPeak out[3];
    for (int q = 0; q < 3; ++q) {
        const Best& s = best[q];
        if (!(s.value > 0.0)) {
            out[q] = {0.0, s.theta};
            continue;
        }
        const auto magnitude = [&](double theta) {
            const FollowerMotion m = f(theta);
            return std::abs(q == 0 ? m.dh : q == 1 ? m.d2h : m.d3h);
        };
        // The bracket may reach into the neighbouring piece: a peak on a break is sampled from both sides.
        const double lo = std::fmax(breaks.front(), s.theta - s.step), hi = std::fmin(breaks.back(), s.theta + s.step);
        const Extremum e = hi > lo ? maximize(magnitude, lo, hi, 4) : Extremum{s.theta, s.value};
        out[q] = e.value >= s.value ? LiftPeak{e.value, e.x} : LiftPeak{s.value, s.theta};
    }
    return {out[0], out[1], out[2]};
}

// Lowest and highest h of f over the pieces (m): grid, then golden refinement around each extreme.
template <class F>
std::pair<double, double> find_lift_range(const F& f, const std::vector<double>& breaks,
                                          std::size_t samples_per_piece) {
    double low = f(breaks.front()).h, high = low, at_low = breaks.front(), at_high = breaks.front();
    double low_step = 0.0, high_step = 0.0;
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
        const double a = breaks[i], b = breaks[i + 1];
        const double step = (b - a) / static_cast<double>(samples_per_piece);
        for (std::size_t k = 0; k <= samples_per_piece; ++k) {
            const double theta = k == samples_per_piece ? b : a + step * static_cast<double>(k);
            const double h = f(theta).h;
            if (h < low) low = h, at_low = theta, low_step = step;
            if (h > high) high = h, at_high = theta, high_step = step;
        }
    }
    const auto refine = [&](double at, double step, double sign) {
        const double lo = std::fmax(breaks.front(), at - step), hi = std::fmin(breaks.back(), at + step);
        if (!(hi > lo)) return sign * f(at).h;
        return maximize([&](double t) { return sign * f(t).h; }, lo, hi, 4).value;
    };
    low = std::fmin(low, -refine(at_low, low_step, -1.0));
    high = std::fmax(high, refine(at_high, high_step, 1.0));
    return {low, high};
}

}  // namespace detail
}  // namespace camfollower
