// SPDX-License-Identifier: BSD-3-Clause
// A linear N-DOF test system, M q'' + C q' + K q = p(t), written against the system contract with only
// the members a linear system needs (no workspace, no tangent, no contact).
#pragma once

#include <functional>

#include <Eigen/Core>

template <int N>
struct LinearSystem {
    using Vector = Eigen::Matrix<double, N, 1>;
    using Matrix = Eigen::Matrix<double, N, N>;

    Matrix M = Matrix::Identity(), C = Matrix::Zero(), K = Matrix::Identity();
    Vector q0 = Vector::Zero();
    std::function<Vector(double)> external = [](double) { return Vector::Zero(); };

    int size() const { return N; }
    const Matrix& mass() const { return M; }
    const Matrix& damping() const { return C; }
    const Matrix& stiffness() const { return K; }
    void load(double t, Vector& p) const { p = external(t); }
    Vector initial_displacement() const { return q0; }
};
