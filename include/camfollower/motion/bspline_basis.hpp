// SPDX-License-Identifier: BSD-3-Clause
// B-spline basis functions and their derivatives on an arbitrary knot vector (Piegl & Tiller, "The
// NURBS Book", algorithms A2.1 and A2.3), on the stack: degrees up to max_spline_degree.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace camfollower::detail {

inline constexpr int max_spline_degree = 7;
inline constexpr std::size_t spline_order_capacity = max_spline_degree + 1;

// derivative[k][j]: k-th derivative of basis function span - degree + j at x (k <= derivatives).
using BasisDerivatives = std::array<std::array<double, spline_order_capacity>, spline_order_capacity>;

// Index i in [degree, basis_count - 1] with knots[i] <= x < knots[i + 1] (the last non-empty span
// for x at or beyond the right end).
inline std::size_t find_knot_span(const std::vector<double>& knots, int degree, std::size_t basis_count, double x) {
    const auto first = knots.begin() + degree + 1, last = knots.begin() + static_cast<std::ptrdiff_t>(basis_count);
    const auto it = std::upper_bound(first, last, x);
    return static_cast<std::size_t>(it - knots.begin()) - 1;
}

// The non-zero basis functions of span `span` and their first `derivatives` derivatives at x. The
// formulas are the span's polynomial pieces, so x may also sit on the span's right end.
inline BasisDerivatives basis_derivatives(const std::vector<double>& knots, std::size_t span, double x, int degree,
                                          int derivatives) {
    const int p = degree;
    std::array<std::array<double, spline_order_capacity>, spline_order_capacity> ndu{};
    std::array<double, spline_order_capacity> left{}, right{};
    ndu[0][0] = 1.0;
    for (int j = 1; j <= p; ++j) {
        left[j] = x - knots[span + 1 - j];
        right[j] = knots[span + j] - x;
        double saved = 0.0;
        for (int r = 0; r < j; ++r) {
            ndu[j][r] = right[r + 1] + left[j - r];  // knot differences: > 0 on a non-empty span
            const double temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    BasisDerivatives out{};
    for (int j = 0; j <= p; ++j) out[0][j] = ndu[j][p];
    const int n = std::min(derivatives, p);
    std::array<std::array<double, spline_order_capacity>, 2> a{};
    for (int r = 0; r <= p; ++r) {
        int s1 = 0, s2 = 1;
        a[0][0] = 1.0;
        for (int k = 1; k <= n; ++k) {
            double d = 0.0;
            const int rk = r - k, pk = p - k;
            if (r >= k) {
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            const int j1 = rk >= -1 ? 1 : -rk;
            const int j2 = r - 1 <= pk ? k - 1 : p - r;
            for (int j = j1; j <= j2; ++j) {
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
                d += a[s2][j] * ndu[rk + j][pk];
            }
            if (r <= pk) {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            out[k][r] = d;
            std::swap(s1, s2);
        }
    }
    double factor = p;
    for (int k = 1; k <= n; ++k) {
        for (int j = 0; j <= p; ++j) out[k][j] *= factor;
        factor *= p - k;
    }
    return out;
}

}  // namespace camfollower::detail
