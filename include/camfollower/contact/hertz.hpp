// SPDX-License-Identifier: BSD-3-Clause
// Unilateral Hertzian contact law F = K <delta>^n (1 + chi delta_dot), with its exact tangent.
// n = 1 (paper, K in N/m), 3/2 (point contact), 10/9 (line contact); chi = 0 without damping,
// Hunt-Crossley / Lankarani-Nikravesh otherwise (CamFollowerParameters::contact_damping_factor).
// Separated (delta <= 0): no force, no stiffness. The damped force is clamped at zero (no pull).
#pragma once

#include <cmath>

namespace camfollower {

struct ContactResponse {
    double force;      // N, >= 0
    double stiffness;  // dF/d delta, N/m
    double damping;    // dF/d delta_dot, N s/m
    bool in_contact;   // delta > 0
    double delta;      // the penetration it was evaluated at, m
};

struct HertzContact {
    double stiffness = 1.9e8;     // K, N/m^n
    double exponent = 1.0;        // n >= 1
    double damping_factor = 0.0;  // chi, s/m

    ContactResponse operator()(double delta, double delta_dot) const {
        if (!(delta > 0.0)) return {0.0, 0.0, 0.0, false, delta};
        // delta^n and n delta^(n-1); pow only off the paper's linear law.
        const double dn = exponent == 1.0 ? delta : std::pow(delta, exponent);
        const double elastic = stiffness * dn;
        const double k_elastic = exponent == 1.0 ? stiffness : exponent * elastic / delta;
        const double factor = 1.0 + damping_factor * delta_dot;
        if (factor <= 0.0) return {0.0, 0.0, 0.0, true, delta};  // separating faster than the law can pull
        return {elastic * factor, k_elastic * factor, elastic * damping_factor, true, delta};
    }
};

}  // namespace camfollower
