// SPDX-License-Identifier: BSD-3-Clause
// Root of a scalar function by secant steps from x0 and x1 = x0 - f(x0) (good for a nearly affine f
// of slope ~1, such as a preload calibrated against the spring force it produces).
#pragma once

#include <cmath>

namespace camfollower::detail {

struct SecantRoot {
    double x;         // the root found
    double residual;  // f(x)
};

template <class F>
SecantRoot secant_root(const F& f, double x0, double tolerance, int max_iterations = 50) {
    double f0 = f(x0);
    double x1 = x0 - f0, f1 = f(x1);
    for (int it = 0; it < max_iterations && std::abs(f1) > tolerance; ++it) {
        const double x2 = f1 == f0 ? x1 : x1 - f1 * (x1 - x0) / (f1 - f0);
        x0 = x1, f0 = f1;
        x1 = x2, f1 = f(x1);
    }
    return {x1, f1};
}

}  // namespace camfollower::detail
