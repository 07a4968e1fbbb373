// SPDX-License-Identifier: BSD-3-Clause
// A uniform shaft of n equal Timoshenko elements along x, assembled into global stiffness and mass
// (sparse through triplets, dense as a convenience), with bearings as spring supports to ground and
// boundary conditions by removing DOFs.
//
// Global DOF numbering is node-major: DOF 6 node + d, d as in timoshenko_beam.hpp
// (u_x, u_y, u_z, theta_x, theta_y, theta_z). Node 0 is at x = 0, node n at x = length.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "camfollower/error.hpp"
#include "camfollower/structure/beam_section.hpp"
#include "camfollower/structure/timoshenko_beam.hpp"

namespace camfollower {

inline constexpr int shaft_dofs_per_node = 6;

enum class ShaftDof : int { axial = 0, lateral_y = 1, lateral_z = 2, torsion = 3, rotation_y = 4, rotation_z = 5 };

inline int shaft_dof(int node, ShaftDof dof) { return shaft_dofs_per_node * node + static_cast<int>(dof); }

// A bearing (or any linear support) from one node to ground, stiffness per DOF direction.
struct ShaftSupport {
    int node;
    double kx, ky, kz;     // N/m
    double ktx, kty, ktz;  // N m/rad
};

class UniformShaft {
public:
    UniformShaft(const BeamSection& section, double length, int element_count)
        : section_(section), length_(length), element_count_(element_count) {
        section_.validate();
        detail::require_positive(length, "shaft length", "(m)");
        if (element_count < 1) detail::fail("element_count must be >= 1, got ", element_count);
    }

    // Adds to whatever is already at the node; zero means no support in that direction.
    void add_support(int node, double kx, double ky, double kz, double ktx, double kty, double ktz) {
        if (node < 0 || node > element_count_)
            detail::fail("support node must be in [0, ", element_count_, "], got ", node);
        detail::require_non_negative(kx, "support kx", "(N/m)");
        detail::require_non_negative(ky, "support ky", "(N/m)");
        detail::require_non_negative(kz, "support kz", "(N/m)");
        detail::require_non_negative(ktx, "support ktx", "(N m/rad)");
        detail::require_non_negative(kty, "support kty", "(N m/rad)");
        detail::require_non_negative(ktz, "support ktz", "(N m/rad)");
        supports_.push_back({node, kx, ky, kz, ktx, kty, ktz});
    }

    const BeamSection& section() const { return section_; }
    double length() const { return length_; }
    int element_count() const { return element_count_; }
    int node_count() const { return element_count_ + 1; }
    int dof_count() const { return shaft_dofs_per_node * node_count(); }
    double element_length() const { return length_ / element_count_; }
    double node_position(int node) const { return length_ * node / element_count_; }
    const std::vector<ShaftSupport>& supports() const { return supports_; }

    Eigen::SparseMatrix<double> stiffness_sparse() const {
        std::vector<Eigen::Triplet<double>> triplets =
            element_triplets(timoshenko_stiffness(section_, element_length()));
        for (const ShaftSupport& s : supports_) {
            const double k[6] = {s.kx, s.ky, s.kz, s.ktx, s.kty, s.ktz};
            for (int d = 0; d < shaft_dofs_per_node; ++d)
                if (k[d] != 0.0)
                    triplets.emplace_back(shaft_dofs_per_node * s.node + d, shaft_dofs_per_node * s.node + d, k[d]);
        }
        return to_sparse(triplets);
    }

    Eigen::SparseMatrix<double> mass_sparse() const {
        return to_sparse(element_triplets(timoshenko_mass(section_, element_length())));
    }

    Eigen::MatrixXd stiffness() const { return Eigen::MatrixXd(stiffness_sparse()); }
    Eigen::MatrixXd mass() const { return Eigen::MatrixXd(mass_sparse()); }

private:
    std::vector<Eigen::Triplet<double>> element_triplets(const BeamMatrix& element) const {
        std::vector<Eigen::Triplet<double>> triplets;
        triplets.reserve(static_cast<std::size_t>(element_count_) * 144 + 6 * supports_.size());
        for (int e = 0; e < element_count_; ++e) {
            const int first = shaft_dofs_per_node * e;  // element e joins nodes e and e + 1
            for (int i = 0; i < 12; ++i)
                for (int j = 0; j < 12; ++j)
                    if (element(i, j) != 0.0) triplets.emplace_back(first + i, first + j, element(i, j));
        }
        return triplets;
    }

    Eigen::SparseMatrix<double> to_sparse(const std::vector<Eigen::Triplet<double>>& triplets) const {
        Eigen::SparseMatrix<double> matrix(dof_count(), dof_count());
        matrix.setFromTriplets(triplets.begin(), triplets.end());  // sums the shared-node entries
        return matrix;
    }

    BeamSection section_;
    double length_;
    int element_count_;
    std::vector<ShaftSupport> supports_;
};

// The DOFs that remain after removing `fixed_dofs` (any order, duplicates allowed), ascending.
inline std::vector<int> kept_dofs(int dof_count, const std::vector<int>& fixed_dofs) {
    std::vector<bool> fixed(static_cast<std::size_t>(dof_count), false);
    for (int d : fixed_dofs) {
        if (d < 0 || d >= dof_count) detail::fail("fixed DOF must be in [0, ", dof_count - 1, "], got ", d);
        fixed[static_cast<std::size_t>(d)] = true;
    }
    std::vector<int> kept;
    for (int d = 0; d < dof_count; ++d)
        if (!fixed[static_cast<std::size_t>(d)]) kept.push_back(d);
    return kept;
}

// Homogeneous Dirichlet conditions: the rows and columns of fixed DOFs are removed.
inline Eigen::MatrixXd remove_dofs(const Eigen::MatrixXd& matrix, const std::vector<int>& fixed_dofs) {
    if (matrix.rows() != matrix.cols())
        detail::fail("remove_dofs needs a square matrix, got ", matrix.rows(), " x ", matrix.cols());
    const std::vector<int> kept = kept_dofs(static_cast<int>(matrix.rows()), fixed_dofs);
    const int n = static_cast<int>(kept.size());
    Eigen::MatrixXd reduced(n, n);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) reduced(i, j) = matrix(kept[i], kept[j]);
    return reduced;
}

inline Eigen::SparseMatrix<double> remove_dofs(const Eigen::SparseMatrix<double>& matrix,
                                               const std::vector<int>& fixed_dofs) {
    if (matrix.rows() != matrix.cols())
        detail::fail("remove_dofs needs a square matrix, got ", matrix.rows(), " x ", matrix.cols());
    const std::vector<int> kept = kept_dofs(static_cast<int>(matrix.rows()), fixed_dofs);
    std::vector<int> new_index(static_cast<std::size_t>(matrix.rows()), -1);
    for (std::size_t i = 0; i < kept.size(); ++i) new_index[static_cast<std::size_t>(kept[i])] = static_cast<int>(i);
    std::vector<Eigen::Triplet<double>> triplets;
    for (int col = 0; col < matrix.outerSize(); ++col)
        for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, col); it; ++it) {
            const int r = new_index[static_cast<std::size_t>(it.row())],
                      c = new_index[static_cast<std::size_t>(it.col())];
            if (r >= 0 && c >= 0) triplets.emplace_back(r, c, it.value());
        }
    const int n = static_cast<int>(kept.size());
    Eigen::SparseMatrix<double> reduced(n, n);
    reduced.setFromTriplets(triplets.begin(), triplets.end());
    return reduced;
}

// A load (or displacement) vector restricted to the kept DOFs.
inline Eigen::VectorXd remove_dofs(const Eigen::VectorXd& vector, const std::vector<int>& fixed_dofs) {
    const std::vector<int> kept = kept_dofs(static_cast<int>(vector.size()), fixed_dofs);
    Eigen::VectorXd reduced(static_cast<Eigen::Index>(kept.size()));
    for (std::size_t i = 0; i < kept.size(); ++i) reduced(static_cast<Eigen::Index>(i)) = vector(kept[i]);
    return reduced;
}

}  // namespace camfollower
