// SPDX-License-Identifier: BSD-3-Clause
// The linear structure of a mechanism as data: named DOFs with masses, spring-dampers between two DOFs
// or a DOF and ground (with an optional preload), constant loads, gravity and global damping models.
// Assembled through triplets into M, C, K, so that a sparse backend can take the same triplets.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "camfollower/error.hpp"

namespace camfollower {

inline const std::string ground_name = "ground";

struct DofSpec {
    std::string name;
    double mass;                // kg (translation) or kg m^2 (rotation)
    Eigen::Vector3d direction;  // unit direction of a translation in space (gravity); zero: none
};

// Force on DOF a: -(preload + stiffness (q_a - q_b) + damping (v_a - v_b)); on b the opposite.
struct SpringSpec {
    std::string name;
    std::string a, b;  // DOF names; b may be "ground"
    double stiffness;  // N/m (N m/rad)
    double damping;    // N s/m
    double preload;    // N: force at zero deflection, pushing a towards negative q_a
};

struct LoadSpec {
    std::string dof;
    double force;  // N (N m), constant, along +q
};

class NetworkSpec {
public:
    void add_dof(const std::string& name, double mass, const Eigen::Vector3d& direction = Eigen::Vector3d::Zero()) {
        if (name.empty() || name == ground_name) detail::fail("DOF name must be non-empty and not '", ground_name, "'");
        for (const DofSpec& d : dofs_)
            if (d.name == name) detail::fail("DOF '", name, "' is defined twice");
        detail::require_positive(mass, ("mass of DOF '" + name + "'").c_str(), "(kg or kg m^2)");
        if (!direction.allFinite()) detail::fail("direction of DOF '", name, "' must be finite");
        const double norm = direction.norm();
        if (norm != 0.0 && std::abs(norm - 1.0) > 1e-9)
            detail::fail("direction of DOF '", name, "' must be a unit vector (or zero: no gravity), got norm ", norm);
        dofs_.push_back({name, mass, direction});
    }

    void add_spring(const std::string& name, const std::string& a, const std::string& b, double stiffness,
                    double damping = 0.0, double preload = 0.0) {
        check_element(name, a, b);
        detail::require_non_negative(stiffness, ("stiffness of '" + name + "'").c_str(), "(N/m)");
        detail::require_non_negative(damping, ("damping of '" + name + "'").c_str(), "(N s/m)");
        detail::require_finite(preload, ("preload of '" + name + "'").c_str());
        springs_.push_back({name, a, b, stiffness, damping, preload});
    }

    void add_load(const std::string& dof, double force) {
        if (dof == ground_name) detail::fail("a load acts on a DOF, not on '", ground_name, "'");
        detail::require_finite(force, ("load on '" + dof + "'").c_str());
        loads_.push_back({dof, force});
    }

    void set_gravity(const Eigen::Vector3d& g) {
        if (!g.allFinite()) detail::fail("gravity must be finite (m/s^2)");
        gravity_ = g;
    }
    // C += alpha M + beta K.
    void set_rayleigh_damping(double alpha, double beta) {
        detail::require_non_negative(alpha, "rayleigh alpha", "(1/s)");
        detail::require_non_negative(beta, "rayleigh beta", "(s)");
        rayleigh_alpha_ = alpha, rayleigh_beta_ = beta;
    }
    // C += M Phi diag(2 zeta_i omega_i) Phi^T M over the modes of the structure linearized with its
    // contacts at the initial equilibrium: one ratio for every mode, or one per mode (ascending).
    void set_modal_damping(const std::vector<double>& ratios) {
        for (std::size_t i = 0; i < ratios.size(); ++i)
            detail::require_non_negative(ratios[i], detail::concat("modal damping ratio [", i, "]").c_str());
        modal_ratios_ = ratios;
    }

    const std::vector<DofSpec>& dofs() const { return dofs_; }
    const std::vector<SpringSpec>& springs() const { return springs_; }
    const std::vector<LoadSpec>& loads() const { return loads_; }
    const Eigen::Vector3d& gravity() const { return gravity_; }
    double rayleigh_alpha() const { return rayleigh_alpha_; }
    double rayleigh_beta() const { return rayleigh_beta_; }
    const std::vector<double>& modal_ratios() const { return modal_ratios_; }
    int size() const { return int(dofs_.size()); }

    // Index of a DOF by name; ground is -1. `who` names the element for the error message.
    int index(const std::string& name, const std::string& who) const {
        if (name == ground_name) return -1;
        for (std::size_t k = 0; k < dofs_.size(); ++k)
            if (dofs_[k].name == name) return int(k);
        std::string known;
        for (const DofSpec& d : dofs_) known += (known.empty() ? "" : ", ") + d.name;
        detail::fail(who, " refers to DOF '", name, "', which is not defined (defined: ", known.empty() ? "none" : known,
                     ", or '", ground_name, "')");
    }

    // Triplets of M (diagonal), C and K from the elements (global damping models are added by the
    // mechanism, which knows the contacts).
    using Triplets = std::vector<Eigen::Triplet<double>>;
    void assemble(Triplets& M, Triplets& C, Triplets& K) const {
        for (std::size_t k = 0; k < dofs_.size(); ++k) M.emplace_back(int(k), int(k), dofs_[k].mass);
        for (const SpringSpec& s : springs_) {
            const int i = index(s.a, "spring '" + s.name + "'"), j = index(s.b, "spring '" + s.name + "'");
            for (auto [list, value] : {std::pair{&K, s.stiffness}, std::pair{&C, s.damping}}) {
                if (value == 0.0) continue;
                list->emplace_back(i, i, value);
                if (j >= 0) {
                    list->emplace_back(j, j, value);
                    list->emplace_back(i, j, -value);
                    list->emplace_back(j, i, -value);
                }
            }
        }
    }

    // Constant generalized loads: applied loads, gravity along each DOF's direction, spring preloads.
    Eigen::VectorXd constant_load() const {
        Eigen::VectorXd p = Eigen::VectorXd::Zero(size());
        for (const LoadSpec& l : loads_) p[index(l.dof, "load")] += l.force;
        for (std::size_t k = 0; k < dofs_.size(); ++k) p[Eigen::Index(k)] += dofs_[k].mass * gravity_.dot(dofs_[k].direction);
        for (const SpringSpec& s : springs_) {
            const int i = index(s.a, "spring '" + s.name + "'"), j = index(s.b, "spring '" + s.name + "'");
            p[i] -= s.preload;
            if (j >= 0) p[j] += s.preload;
        }
        return p;
    }

private:
    void check_element(const std::string& name, const std::string& a, const std::string& b) const {
        if (name.empty()) detail::fail("element name must be non-empty");
        for (const SpringSpec& s : springs_)
            if (s.name == name) detail::fail("element '", name, "' is defined twice");
        if (a == b) detail::fail("element '", name, "' connects DOF '", a, "' to itself");
        if (a == ground_name) detail::fail("element '", name, "': the first end must be a DOF, '", ground_name, "' may only be the second");
    }

    std::vector<DofSpec> dofs_;
    std::vector<SpringSpec> springs_;
    std::vector<LoadSpec> loads_;
    Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
    double rayleigh_alpha_ = 0.0, rayleigh_beta_ = 0.0;
    std::vector<double> modal_ratios_;
};

}  // namespace camfollower
