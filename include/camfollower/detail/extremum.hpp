// SPDX-License-Identifier: BSD-3-Clause
// Locating the maximum of a smooth scalar function on an interval: dense sampling to find the
// right bracket, then golden-section refinement (the value converges quadratically, so ~1e-15).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace camfollower::detail {

struct Extremum {
    double x;
    double value;
};

template <class F>
Extremum maximize(const F& f, double a, double b, std::size_t samples = 400) {
    const double h = (b - a) / static_cast<double>(samples);
    std::size_t best = 0;
    double best_value = f(a);
    for (std::size_t k = 1; k <= samples; ++k) {
        const double v = f(a + h * static_cast<double>(k));
        if (v > best_value) best_value = v, best = k;
    }
    double lo = a + h * (static_cast<double>(best) - 1.0), hi = a + h * (static_cast<double>(best) + 1.0);
    lo = std::fmax(lo, a);
    hi = std::fmin(hi, b);
    const double r = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
    double f1 = f(x1), f2 = f(x2);
    for (int it = 0; it < 200 && hi - lo > 1e-15 * (1.0 + std::fabs(lo)); ++it) {
        if (f1 < f2) {
            lo = x1, x1 = x2, f1 = f2;
            x2 = lo + r * (hi - lo), f2 = f(x2);
        } else {
            hi = x2, x2 = x1, f2 = f1;
            x1 = hi - r * (hi - lo), f1 = f(x1);
        }
    }
    Extremum e{0.5 * (lo + hi), f(0.5 * (lo + hi))};
    // Bracket ends (a kink or an interval end) can beat the interior point.
    for (double x : {a + h * static_cast<double>(best), a, b}) {
        const double v = f(x);
        if (v > e.value) e = {x, v};
    }
    return e;
}

// Samples for a piece of length span: `samples`, or more so that no step exceeds max_step (a narrow
// feature, e.g. a dent in the cam, must not fall between two samples).
inline std::size_t samples_for(double span, std::size_t samples, double max_step) {
    if (!(max_step > 0.0 && std::isfinite(max_step))) return samples;
    return std::max(samples, static_cast<std::size_t>(std::ceil(span / max_step)));
}

// Largest f over consecutive pieces [breaks[i], breaks[i + 1]]: f is smooth inside each piece, kinks
// and narrow features sit on the breaks. Ties keep the earliest piece.
template <class F>
Extremum maximize_piecewise(const F& f, const std::vector<double>& breaks, std::size_t samples,
                            double max_step) {
    Extremum best{breaks.front(), -std::numeric_limits<double>::infinity()};
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
        const double a = breaks[i], b = breaks[i + 1];
        const Extremum e = maximize(f, a, b, samples_for(b - a, samples, max_step));
        if (e.value > best.value) best = e;
    }
    return best;
}

}  // namespace camfollower::detail
