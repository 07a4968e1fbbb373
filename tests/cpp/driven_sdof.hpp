// SPDX-License-Identifier: BSD-3-Clause
// A test problem with a closed form: a damped single-DOF oscillator driven by F sin(W t) from rest.
#pragma once

#include <algorithm>
#include <cmath>

#include "camfollower/constants.hpp"
#include "linear_system_instances.hpp"
#include "run.hpp"

// Damped SDOF driven by F sin(W t) from rest at x = 0: the closed form is the steady response plus
// the free response that cancels its initial displacement and velocity.
struct DrivenSdof {
    double m = 2.0, k = 800.0, c = 4.0, F = 3.0, W = 13.0;
    LinearSystem<1> system() const {
        LinearSystem<1> s;
        s.M(0, 0) = m, s.K(0, 0) = k, s.C(0, 0) = c;
        const double f = F, w = W;
        s.external = [f, w](double t) { return Eigen::Matrix<double, 1, 1>(f * std::sin(w * t)); };
        return s;
    }
    double exact(double t) const {
        const double w = std::sqrt(k / m), zeta = c / (2 * std::sqrt(k * m)), wd = w * std::sqrt(1 - zeta * zeta);
        // Steady: X sin(W t - phi)
        const double den = (k - m * W * W) * (k - m * W * W) + (c * W) * (c * W);
        const double A = F * (k - m * W * W) / den, B = -F * c * W / den;  // x_p = A sin + B cos
        const double x0 = -B, v0 = -A * W;                                 // free part's start
        const double free =
            std::exp(-zeta * w * t) * (x0 * std::cos(wd * t) + (v0 + zeta * w * x0) / wd * std::sin(wd * t));
        return A * std::sin(W * t) + B * std::cos(W * t) + free;
    }
    double period() const { return 2 * camfollower::pi / std::sqrt(k / m); }
};

// The largest |x - exact| over the recorded rows of a run with settings `s`.
inline double max_error(const DrivenSdof& sdof, const camfollower::SolverSettings& s, double duration) {
    const auto r = run(sdof.system(), s, duration);
    double err = 0.0;
    for (std::size_t i = 0; i < r.rows; ++i) err = std::max(err, std::abs(r.q[i] - sdof.exact(r.t[i])));
    return err;
}
