// SPDX-License-Identifier: BSD-3-Clause
// The variational equations of the Newmark family: the derivatives of the stepped state with respect
// to the state (q0, v0) a run started from, carried through every accepted step, so that one
// revolution gives shooting's monodromy d(q, v)(T) / d(q, v)(0) instead of 2n perturbed revolutions.
//
// With F_q, F_v the nonlinear force's tangent at the step's end and G = (K + F_q) dq + (C + F_v) dv,
// one step of HHT-alpha (alpha = 0: Newmark) differentiated (each of dq, dv, da an n x 2n matrix):
//   P = dq + dt dv + dt^2 (1/2 - beta) da,   W = dv + dt (1 - gamma) da               (predictors)
//   [M + (1 + alpha)(gamma dt (C + F_v) + beta dt^2 (K + F_q))] da1
//       = -(1 + alpha)((K + F_q) P + (C + F_v) W) + alpha G0
//   dq1 = P + beta dt^2 da1,   dv1 = W + gamma dt da1,   G1 = (alpha G0 - M da1) / (1 + alpha).
// The matrix on the left is beta dt^2 times the step's Newton matrix (the backend solves it), and
// the last line is the differentiated equation of motion, so G costs no product of its own. At the
// start a0 = -M^-1 (C v0 + K q0 + f0): da0 = -M^-1 G0. The scheme is differentiated as it is (its
// own phase errors included): the monodromy is that of the discrete map shooting solves.
// Contact losses between steps and path memory (elements with hysteresis) are not differentiated:
// the Jacobian is then approximate, which costs Newton's iterations, not the orbit's accuracy (and
// where it stalls them, shooting's automatic choice goes over to differences: solver/shooting.hpp).
// A processed velocity (NewmarkParameters::processed) adds the jerk's and the last acceleration's
// derivatives (dj, da_prev) to the predictors, as its step adds them to the velocity; a step of
// another length than the last solves with the equal-step Newton matrix (approximate, as above).
#pragma once

#include <Eigen/Core>

namespace camfollower {

// Fixed-size blocks for a fixed-size model (7 x 14 for the paper preset: Eigen multiplies them without
// its general matrix-product machinery), dynamic otherwise.
template <class Vector>
struct StepSensitivity {
    static constexpr int rows = Vector::RowsAtCompileTime;
    static constexpr int cols = rows == Eigen::Dynamic ? Eigen::Dynamic : 2 * rows;
    using Block = Eigen::Matrix<double, rows, cols>;
    Block dq, dv, da, g;                                   // n x 2n: d(q, v, a) / d(q0, v0) and G (above)
    Block dj, da_prev;                                     // a processed velocity's jerk and last acceleration
    Block p, w, r;                                         // scratch
    Eigen::Matrix<double, Eigen::Dynamic, cols> low_rank;  // rank x 2n scratch of the tangent's V^T X

    void resize(int n, int rank_capacity) {
        for (Block* m : {&dq, &dv, &da, &g, &dj, &da_prev, &p, &w, &r}) m->resize(n, 2 * n);
        low_rank.resize(rank_capacity, 2 * n);
    }
    // d(q, v) / d(q0, v0): the monodromy after one revolution, 2n x 2n.
    Eigen::MatrixXd state_jacobian() const {
        Eigen::MatrixXd j(2 * dq.rows(), dq.cols());
        j << dq, dv;
        return j;
    }
};

}  // namespace camfollower
