// SPDX-License-Identifier: BSD-3-Clause
// Locating the maximum of a smooth scalar function on an interval: dense sampling to find the
// right bracket, then golden-section refinement (the value converges quadratically, so ~1e-15).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace camfollower::detail {

struct Extremum {
    double x;
    double value;
};

// The bracket [x_best - h, x_best + h] of the best of the samples a + k h (k = 0 .. n) refined by
// golden section; the refined point, the best sample or an end of [a, b], whichever is largest.
template <class F>
Extremum refine_maximum(const F& f, double a, double b, double h, std::size_t best) {
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

template <class F>
Extremum maximize(const F& f, double a, double b, std::size_t samples = 400) {
    const double h = (b - a) / static_cast<double>(samples);
    std::size_t best = 0;
    double best_value = f(a);
    for (std::size_t k = 1; k <= samples; ++k) {
        const double v = f(a + h * static_cast<double>(k));
        if (v > best_value) best_value = v, best = k;
    }
    return refine_maximum(f, a, b, h, best);
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
Extremum maximize_piecewise(const F& f, const std::vector<double>& breaks, std::size_t samples, double max_step) {
    Extremum best{breaks.front(), -std::numeric_limits<double>::infinity()};
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
        const double a = breaks[i], b = breaks[i + 1];
        const Extremum e = maximize(f, a, b, samples_for(b - a, samples, max_step));
        if (e.value > best.value) best = e;
    }
    return best;
}

// The largest value of each of N functions over the pieces, from one shared sampling pass: g(x)
// returns all N at x (std::array<double, N>: e.g. N quantities of one cam profile point, computed
// once). Each function is refined as maximize_piecewise would, but only in the pieces that can hold
// its maximum: those whose best sample is within twice the drop to its neighbouring samples of the
// best sample overall (a smooth maximum between samples exceeds the nearest one by less than that).
// Same result as N maximize_piecewise calls, at about 1/N of the evaluations. Allocates (checks at
// model construction, not the time loop).
template <std::size_t N, class G>
std::array<Extremum, N> maximize_piecewise_together(const G& g, const std::vector<double>& breaks, std::size_t samples,
                                                    double max_step) {
    struct Candidate {
        std::size_t best = 0;
        double value = -std::numeric_limits<double>::infinity(), slack = 0.0;
    };
    struct Piece {
        double a, b, h;
        std::array<Candidate, N> best;
    };
    std::vector<Piece> pieces;
    std::vector<std::array<double, N>> values;
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
        const double a = breaks[i], b = breaks[i + 1];
        const std::size_t n = samples_for(b - a, samples, max_step);
        Piece piece{a, b, (b - a) / static_cast<double>(n), {}};
        values.resize(n + 1);
        for (std::size_t k = 0; k <= n; ++k) values[k] = g(k == 0 ? a : a + piece.h * static_cast<double>(k));
        for (std::size_t j = 0; j < N; ++j) {
            Candidate& c = piece.best[j];
            for (std::size_t k = 0; k <= n; ++k)
                if (k == 0 || values[k][j] > c.value) c.value = values[k][j], c.best = k;
            if (c.best > 0) c.slack = std::fmax(c.slack, 2.0 * std::fabs(c.value - values[c.best - 1][j]));
            if (c.best < n) c.slack = std::fmax(c.slack, 2.0 * std::fabs(c.value - values[c.best + 1][j]));
        }
        pieces.push_back(piece);
    }
    std::array<Extremum, N> out;
    for (std::size_t j = 0; j < N; ++j) {
        double sampled = -std::numeric_limits<double>::infinity();
        for (const Piece& p : pieces) sampled = std::fmax(sampled, p.best[j].value);
        out[j] = {breaks.front(), -std::numeric_limits<double>::infinity()};
        const auto f = [&](double x) { return g(x)[j]; };
        for (const Piece& p : pieces) {
            const Candidate& c = p.best[j];
            if (!(c.value + c.slack >= sampled)) continue;  // cannot beat the best sample
            const Extremum e = refine_maximum(f, p.a, p.b, p.h, c.best);
            if (e.value > out[j].value) out[j] = e;
        }
    }
    return out;
}

}  // namespace camfollower::detail
