// SPDX-License-Identifier: BSD-3-Clause
// What the adaptive methods (Dormand-Prince, DOP853, Radau IIA, Newmark under error control) measure a
// step's error estimate (e_q, e_v) against, in one place:
//   - the mixed displacement/velocity norm sqrt(mean((e_i / (tol (|y_i| + y_ref)))^2)), q_ref the
//     largest |q| of the run so far, v_ref the largest |v| but at least q_ref omega_ref (omega_ref:
//     2 pi / period for a camshaft-driven system, else its lowest natural frequency), so that
//     components near zero (a dwell starting at rest) do not demand absolute accuracy;
//   - the force-weighted error |K_t e_q + C_t e_v|_inf, K_t and C_t the stiffness and damping with the
//     contacts' tangent: the error in the forces (and, through M^-1, the accelerations) a step leaves
//     behind. A stiff contact turns nanometres into newtons; the mixed norm alone lets the contact
//     force drift far beyond the tolerance.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "camfollower/core/system.hpp"

namespace camfollower {

struct ErrorScales {
    double q_ref = 0.0, v_ref = 0.0, omega_ref = 0.0;

    // At the start state (q, v); rate: omega_ref (reference_rate in solver/newmark.hpp).
    template <class Vector>
    void start(double rate, const Vector& q, const Vector& v) {
        omega_ref = rate;
        q_ref = q.cwiseAbs().maxCoeff();
        v_ref = std::max(v.cwiseAbs().maxCoeff(), omega_ref * q_ref);
    }
    // Raises q_ref to at least `q` (and v_ref with it).
    void floor_displacement(double q) {
        q_ref = std::max(q_ref, q);
        v_ref = std::max(v_ref, omega_ref * q_ref);
    }
    // After an accepted step at (q, v).
    template <class Vector>
    void update(const Vector& q, const Vector& v) {
        q_ref = std::max(q_ref, q.cwiseAbs().maxCoeff());
        v_ref = std::max({v_ref, v.cwiseAbs().maxCoeff(), omega_ref * q_ref});
    }
    // The mixed norm of (eq, ev) in units of `tolerance`, for a step from (q0, v0) to (q1, v1).
    template <class Vector>
    double mixed(double tolerance, const Vector& eq, const Vector& ev, const Vector& q0, const Vector& v0,
                 const Vector& q1, const Vector& v1) const {
        double sum = 0.0;
        const auto n = eq.size();
        for (Eigen::Index i = 0; i < n; ++i) {
            const double sq = tolerance * (std::max(std::abs(q0[i]), std::abs(q1[i])) + q_ref + 1e-12);
            const double sv = tolerance * (std::max(std::abs(v0[i]), std::abs(v1[i])) + v_ref + 1e-12);
            sum += (eq[i] / sq) * (eq[i] / sq) + (ev[i] / sv) * (ev[i] / sv);
        }
        return std::sqrt(sum / double(2 * n));
    }
};

// |K e_q + C e_v + U_q V_q^T e_q + U_v V_v^T e_v|_inf: the force error of (eq, ev), the contacts'
// tangent given as its displacement part uvq and velocity part uvv (tangent(..., 1, 0, uvq) and
// tangent(..., 0, 1, uvv)); `scratch` a vector of the system's size.
template <class System, class Vector>
double force_error(const System& system, const LowRank<Vector>& uvq, const LowRank<Vector>& uvv, const Vector& eq,
                   const Vector& ev, Vector& scratch) {
    scratch.noalias() = system.stiffness() * eq;
    scratch.noalias() += system.damping() * ev;
    for (int r = 0; r < uvq.rank; ++r) scratch += uvq.U.col(r) * uvq.V.col(r).dot(eq);
    for (int r = 0; r < uvv.rank; ++r) scratch += uvv.U.col(r) * uvv.V.col(r).dot(ev);
    return scratch.cwiseAbs().maxCoeff();
}

}  // namespace camfollower
