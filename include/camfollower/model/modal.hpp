// SPDX-License-Identifier: BSD-3-Clause
// Undamped modal analysis of a model linearized about its quasi-static equilibrium at a cam angle:
// K_t phi = omega^2 M phi (generalized symmetric eigenproblem), K_t = K + k_c g g^T in contact.
#pragma once

#include <Eigen/Eigenvalues>

#include "camfollower/model/cam_follower_model.hpp"

namespace camfollower {

struct ModalResult {
    using Vector = CamFollowerModel::Vector;
    using Matrix = CamFollowerModel::Matrix;
    Vector frequencies_hz;  // ascending
    Matrix mode_shapes;     // columns, mass-normalized (phi^T M phi = I)
    Matrix tangent_stiffness;
    double contact_stiffness;  // dF/d delta used, N/m (0 without contact)
};

inline ModalResult modal_analysis(const CamFollowerModel& model, double theta, bool with_contact = true) {
    detail::require_finite(theta, "theta");
    ModalResult r;
    r.tangent_stiffness = model.stiffness_matrix();
    r.contact_stiffness = 0.0;
    if (with_contact) {
        const CamFollowerModel::Vector q = model.static_equilibrium(theta);
        const auto c = model.at_time(theta / model.omega());
        r.contact_stiffness = model.contact_stiffness_at(theta, q);
        r.tangent_stiffness += r.contact_stiffness * c.g * c.g.transpose();
    }
    const Eigen::GeneralizedSelfAdjointEigenSolver<ModalResult::Matrix> solver(r.tangent_stiffness,
                                                                              model.mass_matrix());
    if (solver.info() != Eigen::Success) detail::fail("modal analysis failed: eigen solver did not converge");
    r.frequencies_hz = solver.eigenvalues().cwiseMax(0.0).cwiseSqrt() / two_pi;
    r.mode_shapes = solver.eigenvectors();
    return r;
}

}  // namespace camfollower
