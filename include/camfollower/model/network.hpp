// SPDX-License-Identifier: BSD-3-Clause
// A lumped mass-spring-damper network with N DOFs, assembled once into fixed-size M, C, K.
// Topology is data: masses per DOF, linear spring-dampers between two DOFs or a DOF and ground.
// Nonlinear elements (the cam contact) live in the model and act through rank-one tangents.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "camfollower/error.hpp"

namespace camfollower {

inline constexpr int ground = -1;

struct SpringDamper {
    int i;            // DOF index
    int j;            // DOF index or `ground`
    double stiffness; // N/m
    double damping;   // N s/m
    std::string name;
};

template <int N>
class LumpedNetwork {
public:
    using Matrix = Eigen::Matrix<double, N, N>;

    void set_mass(int dof, double mass, const std::string& name) {
        check_dof(dof, "dof");
        detail::require_positive(mass, ("mass of " + name).c_str(), "(kg)");
        masses_[dof] = mass;
        names_[dof] = name;
    }

    void connect(int i, int j, double stiffness, double damping, const std::string& name) {
        check_dof(i, "i");
        if (j != ground) check_dof(j, "j");
        if (i == j) detail::fail("element '", name, "' connects DOF ", i, " to itself");
        detail::require_non_negative(stiffness, ("stiffness of " + name).c_str(), "(N/m)");
        detail::require_non_negative(damping, ("damping of " + name).c_str(), "(N s/m)");
        elements_.push_back({i, j, stiffness, damping, name});
    }

    const std::vector<SpringDamper>& elements() const { return elements_; }
    const std::array<std::string, N>& dof_names() const { return names_; }

    Matrix mass_matrix() const {
        for (int k = 0; k < N; ++k)
            if (!(masses_[k] > 0.0)) detail::fail("DOF ", k, " has no positive mass");
        Matrix M = Matrix::Zero();
        for (int k = 0; k < N; ++k) M(k, k) = masses_[k];
        return M;
    }
    Matrix stiffness_matrix() const { return assemble(&SpringDamper::stiffness); }
    Matrix damping_matrix() const { return assemble(&SpringDamper::damping); }

private:
    static void check_dof(int dof, const char* what) {
        if (dof < 0 || dof >= N) detail::fail(what, " must be a DOF index in [0, ", N - 1, "], got ", dof);
    }

    Matrix assemble(double SpringDamper::*value) const {
        Matrix A = Matrix::Zero();
        for (const SpringDamper& e : elements_) {
            const double v = e.*value;
            A(e.i, e.i) += v;
            if (e.j != ground) {
                A(e.j, e.j) += v;
                A(e.i, e.j) -= v;
                A(e.j, e.i) -= v;
            }
        }
        return A;
    }

    std::array<double, N> masses_{};
    std::array<std::string, N> names_{};
    std::vector<SpringDamper> elements_;
};

}  // namespace camfollower
