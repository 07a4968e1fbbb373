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
#include "camfollower/core/ground.hpp"
#include "camfollower/structure/shaft_spec.hpp"
#include "camfollower/structure/timoshenko_beam.hpp"

namespace camfollower {

struct DofSpec {
    std::string name;
    double mass;                // kg (translation) or kg m^2 (rotation); 0 on a shaft's DOFs (the beam has it)
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

// A lumped mass (kg) or inertia (kg m^2) added to a DOF: a cam's or flywheel's on a shaft node, a
// spring's end share on the DOF it is attached to.
struct PointMassSpec {
    std::string dof;
    double mass;
};

// A shaft in the network: its spec, its node positions and where its DOFs start in the DOF list.
struct ShaftEntry {
    ShaftSpec spec;
    std::vector<double> nodes;  // x of each node, m
    int first_dof = 0;
    int dofs_per_node() const { return spec.axial ? 6 : 5; }
    // Global index of DOF d (0..5: ux, uy, uz, rx, ry, rz) of node k; -1 for an unmodelled axial DOF.
    int index(int node, int d) const {
        if (!spec.axial && d == 0) return -1;
        return first_dof + node * dofs_per_node() + (spec.axial ? d : d - 1);
    }
};

class NetworkSpec {
public:
    void add_dof(const std::string& name, double mass, const Eigen::Vector3d& direction = Eigen::Vector3d::Zero()) {
        detail::require_name(name, "DOF");
        if (name == ground_name) detail::fail("DOF name must not be '", ground_name, "' (the fixed frame)");
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
        detail::require_force(preload, ("preload of '" + name + "'").c_str());
        springs_.push_back({name, a, b, stiffness, damping, preload});
    }

    // A flexible shaft (structure/shaft_spec.hpp): its node DOFs join the DOF list as
    // "<shaft>.<node>.<ux|uy|uz|rx|ry|rz>" (shaft_dof_name()).
    void add_shaft(const ShaftSpec& shaft) {
        shaft.validate();
        for (const ShaftEntry& s : shafts_)
            if (s.spec.name == shaft.name) detail::fail("shaft '", shaft.name, "' is defined twice");
        ShaftEntry entry{shaft, shaft.node_positions(), size()};
        for (std::size_t k = 0; k < entry.nodes.size(); ++k)
            for (int d = shaft.axial ? 0 : 1; d < 6; ++d) {
                const std::string name = shaft_dof_name(shaft.name, int(k), d);
                for (const DofSpec& o : dofs_)
                    if (o.name == name) detail::fail("DOF '", name, "' of shaft '", shaft.name, "' is already defined");
                Eigen::Vector3d direction = Eigen::Vector3d::Zero();
                if (d < 3) direction[d] = 1.0;
                dofs_.push_back({name, 0.0, direction});
            }
        shafts_.push_back(std::move(entry));
    }
    const ShaftEntry& shaft(const std::string& name) const {
        for (const ShaftEntry& s : shafts_)
            if (s.spec.name == name) return s;
        detail::fail("no shaft named '", name, "'");
    }
    // Name of DOF d (0..5: ux, uy, uz, rx, ry, rz) of the shaft's node at station x.
    std::string shaft_dof_at(const std::string& shaft_name, double x, int d) const {
        const ShaftEntry& s = shaft(shaft_name);
        if (!s.spec.axial && d == 0) detail::fail("shaft '", shaft_name, "' has no axial DOF (set axial = true)");
        return shaft_dof_name(shaft_name, s.spec.node_at(x), d);
    }

    void add_mass(const std::string& dof, double mass) {
        if (dof == ground_name) detail::fail("a point mass sits on a DOF, not on '", ground_name, "'");
        detail::require_positive(mass, ("point mass on '" + dof + "'").c_str(), "(kg or kg m^2)");
        (void)index(dof, "point mass");
        masses_.push_back({dof, mass});
    }

    // A helical spring with its own mass, as a chain of `elements` equal spring-dampers between a and
    // b with elements - 1 interior masses ("<name>.1", ...), so that it surges: the distributed
    // spring's natural frequencies f_j = (j / 2) sqrt(stiffness / mass) with both ends held. Each
    // element has stiffness and damping `elements` times the spring's and the same preload; each end
    // gets half an interior mass. `direction` is the interior masses' direction (gravity).
    void add_spring_chain(const std::string& name, const std::string& a, const std::string& b, double stiffness,
                          double mass, int elements, double damping = 0.0, double preload = 0.0,
                          const Eigen::Vector3d& direction = Eigen::Vector3d::Zero()) {
        check_element(name, a, b);
        (void)index(a, "spring chain '" + name + "'"), (void)index(b, "spring chain '" + name + "'");
        detail::require_positive(stiffness, ("stiffness of '" + name + "'").c_str(), "(N/m)");
        detail::require_positive(mass, ("mass of '" + name + "'").c_str(), "(kg)");
        if (elements < 1 || elements > 1000)
            detail::fail("elements of spring chain '", name, "' must be in [1, 1000], got ", elements);
        const double n = elements, m = mass / n;
        for (int k = 1; k < elements; ++k) add_dof(name + "." + std::to_string(k), m, direction);
        for (int k = 1; k <= elements; ++k) {
            const std::string from = k == 1 ? a : name + "." + std::to_string(k - 1);
            const std::string to = k == elements ? b : name + "." + std::to_string(k);
            add_spring(elements == 1 ? name : name + ".s" + std::to_string(k), from, to, n * stiffness, n * damping,
                       preload);
        }
        add_mass(a, 0.5 * m);
        if (b != ground_name) add_mass(b, 0.5 * m);
    }

    void add_load(const std::string& dof, double force) {
        if (dof == ground_name) detail::fail("a load acts on a DOF, not on '", ground_name, "'");
        detail::require_force(force, ("load on '" + dof + "'").c_str());
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
    const std::vector<PointMassSpec>& masses() const { return masses_; }
    const std::vector<ShaftEntry>& shafts() const { return shafts_; }
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
        for (std::size_t k = 0; k < dofs_.size() && k < 24; ++k) known += (known.empty() ? "" : ", ") + dofs_[k].name;
        if (dofs_.size() > 24) known += ", ... (" + std::to_string(dofs_.size()) + " in all)";
        detail::fail(who, " refers to DOF '", name,
                     "', which is not defined (defined: ", known.empty() ? "none" : known, ", or '", ground_name, "')");
    }

    // Triplets of M, C and K from the elements (global damping models are added by the mechanism,
    // which knows the contacts).
    using Triplets = std::vector<Eigen::Triplet<double>>;
    void assemble(Triplets& M, Triplets& C, Triplets& K) const {
        for (std::size_t k = 0; k < dofs_.size(); ++k)
            if (dofs_[k].mass != 0.0) M.emplace_back(int(k), int(k), dofs_[k].mass);
        for (const PointMassSpec& m : masses_) {
            const int i = index(m.dof, "point mass");
            M.emplace_back(i, i, m.mass);
        }
        for (const ShaftEntry& s : shafts_)
            for_each_shaft_element(s, [&](const int* map, const BeamMatrix& k, const BeamMatrix& m) {
                for (int a = 0; a < 12; ++a)
                    for (int b = 0; b < 12; ++b) {
                        if (map[a] < 0 || map[b] < 0) continue;
                        if (k(a, b) != 0.0) K.emplace_back(map[a], map[b], k(a, b));
                        if (m(a, b) != 0.0) M.emplace_back(map[a], map[b], m(a, b));
                        if (k(a, b) != 0.0 && s.spec.damping > 0.0)
                            C.emplace_back(map[a], map[b], s.spec.damping * k(a, b));
                    }
            });
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
        for (std::size_t k = 0; k < dofs_.size(); ++k)
            p[Eigen::Index(k)] += dofs_[k].mass * gravity_.dot(dofs_[k].direction);
        for (const PointMassSpec& m : masses_) {
            const int i = index(m.dof, "point mass");
            p[i] += m.mass * gravity_.dot(dofs_[std::size_t(i)].direction);
        }
        // A shaft's weight as its consistent load: M times the rigid translation along gravity.
        for (const ShaftEntry& s : shafts_)
            for_each_shaft_element(s, [&](const int* map, const BeamMatrix&, const BeamMatrix& m) {
                Eigen::Matrix<double, 12, 1> g = Eigen::Matrix<double, 12, 1>::Zero();
                for (int node = 0; node < 2; ++node) g.segment<3>(6 * node) = gravity_;
                const Eigen::Matrix<double, 12, 1> load = m * g;
                for (int a = 0; a < 12; ++a)
                    if (map[a] >= 0) p[map[a]] += load[a];
            });
        for (const SpringSpec& s : springs_) {
            const int i = index(s.a, "spring '" + s.name + "'"), j = index(s.b, "spring '" + s.name + "'");
            p[i] -= s.preload;
            if (j >= 0) p[j] += s.preload;
        }
        return p;
    }

private:
    // f(map, k, m) for every element of a shaft: map[12] the global index of each element DOF (-1: not
    // modelled), k and m the element's stiffness and consistent mass.
    template <class F>
    static void for_each_shaft_element(const ShaftEntry& s, F&& f) {
        for (std::size_t e = 0; e + 1 < s.nodes.size(); ++e) {
            const double length = s.nodes[e + 1] - s.nodes[e];
            int map[12];
            for (int a = 0; a < 12; ++a) map[a] = s.index(int(e) + a / 6, a % 6);
            f(map, timoshenko_stiffness(s.spec.section, length), timoshenko_mass(s.spec.section, length));
        }
    }

    void check_element(const std::string& name, const std::string& a, const std::string& b) const {
        detail::require_name(name, "element");
        for (const SpringSpec& s : springs_)
            if (s.name == name) detail::fail("element '", name, "' is defined twice");
        if (a == b) detail::fail("element '", name, "' connects DOF '", a, "' to itself");
        if (a == ground_name)
            detail::fail("element '", name, "': the first end must be a DOF, '", ground_name,
                         "' may only be the second");
    }

    std::vector<DofSpec> dofs_;
    std::vector<SpringSpec> springs_;
    std::vector<LoadSpec> loads_;
    std::vector<PointMassSpec> masses_;
    std::vector<ShaftEntry> shafts_;
    Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();
    double rayleigh_alpha_ = 0.0, rayleigh_beta_ = 0.0;
    std::vector<double> modal_ratios_;
};

}  // namespace camfollower
