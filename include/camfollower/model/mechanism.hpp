// SPDX-License-Identifier: BSD-3-Clause
// A cam mechanism built from a runtime description (model/mechanism_builder.hpp): the linear structure
// (structure/network.hpp) and its nonlinear elements (model/element_set.hpp: cam-follower contact
// pairs, clearances) on one camshaft turning at a constant speed or by a speed program
// (motion/speed_program.hpp); with flexible shafts (structure/shaft_spec.hpp) a cam's angle adds the
// shaft's twist at the cam, a state, and a speed change loads the twists with the shafts' inertia. Mechanism<N> is
// immutable and implements the system contract (core/system.hpp); N is the DOF count when known at
// compile time (fixed-size Eigen, the fast path), Eigen::Dynamic otherwise.
//
//   M q'' + C q' + K q + sum_i F_i(delta_i, delta_i') g_i(t) = p
//
// p: constant loads, gravity, spring preloads. Displacements are measured from the unloaded
// configuration in which every follower touches its cam's base circle; follower coordinates carry
// the lift.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "camfollower/core/system.hpp"
#include "camfollower/detail/precompiled_use.hpp"
#include "camfollower/error.hpp"
#include "camfollower/model/element_set.hpp"
#include "camfollower/model/elements/clearance_element.hpp"
#include "camfollower/model/elements/contact_element.hpp"
#include "camfollower/model/elements/pin_joint_element.hpp"
#include "camfollower/model/mechanism_builder.hpp"
#include "camfollower/structure/network.hpp"

namespace camfollower {

// Every element kind a Mechanism holds, in the order of their channels and events.
using MechanismElements = ElementSet<ContactElement, ClearanceElement, PinJointElement>;

template <int N = Eigen::Dynamic>
class Mechanism {
public:
    using Vector = Eigen::Matrix<double, N, 1>;
    using Matrix = Eigen::Matrix<double, N, N>;

    struct Workspace {
        double t = 0.0;
        // One State per element: time-only terms, the responses of the last force() call (reused by
        // tangent(), event_values() and accepted(), which the stepper calls at the same q, v:
        // core/system.hpp) and path memory (contact-loss intervals).
        mutable MechanismElements::States states;
        double drive_acceleration = 0.0;  // the camshaft's angular acceleration at t, rad/s^2 (shafts only)
        template <class E>
        std::vector<typename E::State>& of() const {
            return std::get<std::vector<typename E::State>>(states);
        }
        const ContactElement::State& contact(std::size_t i) const { return of<ContactElement>().at(i); }
        const ClearanceElement::State& clearance(std::size_t i) const { return of<ClearanceElement>().at(i); }
    };

    explicit Mechanism(MechanismBuilder description);

    // Dense assembly and O(n^3) solves at build: this many DOFs build in about a second.
    static constexpr int max_dofs = 3000;

    // --- the system contract ---
    int size() const { return n_; }
    const Matrix& mass() const { return M_; }
    const Matrix& damping() const { return C_; }
    const Matrix& stiffness() const { return K_; }
    const Vector& initial_displacement() const { return initial_; }
    // The quasi-static velocity at the start: the static equilibrium's rate as the cam turns (zero on
    // a dwell of a true cam; the run-out rate of an eccentric one), so a run starts without a kick.
    const Vector& initial_velocity() const { return initial_velocity_; }
    int max_rank() const { return max_rank_; }

    Workspace workspace() const;
    void prepare(double t, Workspace& w) const {
        w.t = t;
        if (rotation_loaded_) w.drive_acceleration = drive_.at(t).acceleration;
        elements_.for_each(w.states, [&](const auto& e, auto& s) { e.prepare(t, s); });
    }
    void force(const Workspace& w, const Vector& q, const Vector& v, Vector& f) const {
        f = -load_;
        // Twists are measured from the rigid rotation: its acceleration loads them with M e theta''.
        if (rotation_loaded_) f.noalias() += w.drive_acceleration * rotation_inertia_;
        elements_.for_each(w.states, [&](const auto& e, auto& s) { e.add_force(w.t, q, v, s, f); });
    }
    void tangent(const Workspace& w, const Vector&, const Vector& v, double cq, double cv, LowRank<Vector>& uv) const {
        DenseColumns sink{uv};
        tangent_columns(w, v, cq, cv, sink);
    }
    // The same tangent with each column pair stored on its few DOFs (the sparse backend).
    void tangent(const Workspace& w, const Vector&, const Vector& v, double cq, double cv, SparseLowRank& uv) const {
        tangent_columns(w, v, cq, cv, uv);
    }
    // The DOFs each tangent column pair can touch: the sparse backend's fill pattern.
    std::vector<std::vector<int>> tangent_pattern() const;
    const Eigen::SparseMatrix<double>& sparse_mass() const { return M_sparse_; }
    const Eigen::SparseMatrix<double>& sparse_damping() const { return C_sparse_; }
    const Eigen::SparseMatrix<double>& sparse_stiffness() const { return K_sparse_; }
    void accepted(Workspace& w, const Vector&, const Vector&) const {
        elements_.for_each(w.states, [&](const auto& e, auto& s) { e.accepted(w.t, s); });
    }
    void event_located(Workspace& w, int index, double time, int direction) const {
        elements_.event_located(w.states, index, time, direction);
    }
    std::vector<std::string> dof_names() const;
    // "theta" (the drive's angle, rad), "drive.speed" (rad/s), "drive.torque" (N m: the torque the
    // cams take from the camshaft, sum of (F - F_outer) d delta / d theta over the contacts) and
    // "drive.power" (W: each cam's torque times its speed, summed), then each element's channels
    // (model/elements/: a contact's <name>.force, .penetration, ...; a clearance's <name>.force,
    // .side, .gap, .friction; a pin joint's <name>.force, .stretch).
    std::vector<std::string> channel_names() const;
    // Switching functions (solver/events.hpp): per contact <name>.contact, its penetration (m); per
    // clearance <name>.wall, |u| - c (m): > 0 while touching.
    std::vector<std::string> event_names() const;
    // (force() at the same q, v computed them: its responses are reused)
    CAMFOLLOWER_FORCE_INLINE void event_values(const Workspace& w, const Vector&, const Vector&, double* g) const {
        elements_.for_each(w.states, [&](const auto& e, const auto& s) { g = e.event_values(s, g); });
    }
    void observe(const Workspace& w, const Vector& q, const Vector& v, double* out) const {
        const DriveState d = drive_.at(w.t);
        double* drive = out;  // theta, drive.speed, then drive.torque and drive.power from the contacts
        out += 4;
        ContactElement::DriveLoad load;
        elements_.for_each(w.states, [&](const auto& e, const auto& s) {
            if constexpr (std::is_same_v<std::decay_t<decltype(e)>, ContactElement>)
                out = e.observe(w.t, s, q, v, out, &load);
            else out = e.observe(w.t, s, q, v, out);
        });
        drive[0] = d.angle, drive[1] = d.rate, drive[2] = load.torque, drive[3] = load.power;
    }

    // --- queries ---
    // The description it was built from: copy, change and build again for a changed mechanism.
    const MechanismBuilder& description() const { return spec_; }
    const MechanismElements& elements() const { return elements_; }
    const std::vector<ContactElement>& contacts() const { return elements_.template of<ContactElement>(); }
    const std::vector<ClearanceElement>& clearances() const { return elements_.template of<ClearanceElement>(); }
    // What the model's user should know about its formulation (e.g. the paper's literal eccentricity
    // force exceeding the static contact force). Python turns each into a UserWarning.
    const std::vector<std::string>& warnings() const { return warnings_; }
    std::size_t contact_index(const std::string& name) const;
    // Contact force of contact i at rest at camshaft angle theta and displacement q, N.
    double static_contact_force(double theta, const Vector& q, std::size_t i) const;
    // The nominal camshaft speed (rad/s; with a speed program its highest base speed) and the period of
    // a revolution at it (s).
    double omega() const { return spec_.camshaft_speed; }
    double period() const { return two_pi / spec_.camshaft_speed; }
    // The camshaft's rotation; periodic(): it repeats every period (no speed ramps).
    const SpeedProgram& drive() const { return drive_; }
    bool periodic() const { return drive_.periodic(); }
    const Vector& constant_load() const { return load_; }
    int dof_index(const std::string& name) const { return spec_.structure.index(name, "dof_index"); }

    // Contact-loss intervals of contact i up to t_end (a loss still open at t_end ends there).
    static std::vector<std::pair<double, double>> contact_loss(const Workspace& w, std::size_t i, double t_end) {
        return ContactElement::losses_until(w.contact(i), t_end);
    }

    // Quasi-static equilibrium at camshaft angle theta, at rest: K q + sum F_i(delta_i, 0) g_i = p (the
    // contact laws at zero penetration rate: a static state has no impact damping). Newton from the
    // contact-free deflection (or zero when the structure alone is singular) on the exact tangent,
    // with an all-contacts-closed step where that tangent is singular.
    Vector static_equilibrium(double theta) const;

    // Tangent stiffness K + sum k_i g_i g_i^T at rest at camshaft angle theta and displacement q
    // (for modal analysis about a static equilibrium).
    Matrix tangent_stiffness(double theta, const Vector& q) const;

private:
    // A workspace with the time-only terms prepared at camshaft angle theta (static analyses).
    Workspace workspace_at(double theta) const;

    // r = K q + sum F_i(delta_i, 0) g_i - p and its Jacobian.
    void static_residual(const Workspace& w, const Vector& q, Vector& r, Matrix& Kt) const;

    // d q_static / dt at (theta, q): Kt dq/dt = -(d r / dt at fixed q), the time-only terms' rates.
    Vector quasi_static_velocity(double theta, const Vector& q) const;

    // Writes a dense LowRank's columns through the column-sink interface of tangent_columns().
    struct DenseColumns {
        LowRank<Vector>& uv;
        void start_column() {
            uv.U.col(uv.rank).setZero();
            uv.V.col(uv.rank).setZero();
            ++uv.rank;
        }
        void add(int dof, double u, double v) {
            uv.U(dof, uv.rank - 1) += u;
            uv.V(dof, uv.rank - 1) += v;
        }
    };

    // cq df/dq + cv df/dv = sum of u v^T column pairs, written to sink.start_column() / sink.add(dof,
    // u, v) (entries of one column add up).
    template <class Sink>
    void tangent_columns(const Workspace& w, const Vector& v, double cq, double cv, Sink& sink) const {
        elements_.for_each(w.states, [&](const auto& e, const auto& s) { e.add_tangent(s, v, cq, cv, sink); });
    }

    // x = A^-1 b for a static analysis: dense full-pivoting LU up to dense_static_limit DOFs, sparse LU
    // above. False when A is singular; x is then the direction that is not held (a null vector).
    static constexpr int dense_static_limit = 200;
    bool solve_static(const Matrix& A, const Vector& b, Vector& x) const;
    // The DOFs that dominate a direction not held in place (at least a tenth of its largest entry).
    std::string unconstrained_dofs(const Vector& direction) const;

    Matrix dense(const NetworkSpec::Triplets& t) const;

    void add_modal_damping(const std::vector<double>& ratios);

    // A linkage whose arm a cam drives must close at every lift of that cam's program (720 angles).
    void check_linkages_close() const {
        for (const CouplerLinkage& l : spec_.linkages)
            for (const ContactElement& c : contacts()) {
                const ContactPairSpec& p = c.spec();
                if (p.follower_dof != l.arm_dof) continue;
                for (int i = 0; i < 720; ++i) {
                    const double theta = two_pi * i / 720.0;
                    const double q = (p.program.evaluate(theta).h - p.follower_offset) / p.follower_ratio;
                    try {
                        (void)l.output_at(q);
                    } catch (const std::invalid_argument& e) {
                        detail::fail(e.what(), "; the cam of contact '", p.name,
                                     "' turns the arm there at theta = ", radians_to_degrees(theta), " deg");
                    }
                }
            }
    }

    MechanismBuilder spec_;
    int n_ = 0;
    Matrix M_, C_, K_;
    Eigen::SparseMatrix<double> M_sparse_, C_sparse_, K_sparse_;
    Vector load_, initial_, initial_velocity_;
    MechanismElements elements_;
    SpeedProgram drive_ = SpeedProgram::constant(1.0);
    Vector rotation_inertia_;       // M e, e = 1 on every shaft twist (the rigid rotation's inertia)
    bool rotation_loaded_ = false;  // a variable speed and shafts that twist
    int max_rank_ = 0;
    std::vector<std::string> warnings_;
};

// Out of the class body: with camfollower::precompiled these are compiled once, for Mechanism<> and
// the paper preset (camfollower/precompiled.hpp), not in every unit that builds a mechanism.

template <int N>
Mechanism<N>::Mechanism(MechanismBuilder description) : spec_(std::move(description)) {
    const NetworkSpec& net = spec_.structure;
    n_ = net.size();
    if (n_ == 0) detail::fail("a mechanism needs at least one DOF");
    if (n_ > max_dofs)
        detail::fail("the mechanism has ", n_, " DOFs, more than the ", max_dofs,
                     " a Mechanism assembles (dense n x n "
                     "matrices: ",
                     24.0 * double(n_) * double(n_) / 1e9,
                     " GB for M, C and K alone); coarsen the shafts' "
                     "meshes (max_element_length) or split the model");
    if (N != Eigen::Dynamic && n_ != N) detail::fail("Mechanism<", N, "> built from a description with ", n_, " DOFs");
    drive_ = spec_.drive();
    NetworkSpec::Triplets tm, tc, tk;
    net.assemble(tm, tc, tk);
    M_ = dense(tm), C_ = dense(tc), K_ = dense(tk);
    const Eigen::VectorXd p = net.constant_load();
    load_ = p;
    elements_ = MechanismElements::build(spec_, net, drive_);
    Vector rigid_rotation = Vector::Zero(n_);
    for (const ShaftEntry& shaft : net.shafts())
        for (std::size_t k = 0; k < shaft.nodes.size(); ++k) rigid_rotation[shaft.index(int(k), 3)] = 1.0;
    rotation_inertia_ = M_ * rigid_rotation;
    rotation_loaded_ = !drive_.is_constant() && !rotation_inertia_.isZero(0.0);
    elements_.for_each([&](const auto& e) { max_rank_ += e.max_rank(); });
    if (net.rayleigh_alpha() != 0.0 || net.rayleigh_beta() != 0.0)
        C_ += net.rayleigh_alpha() * M_ + net.rayleigh_beta() * K_;
    initial_ = static_equilibrium(0.0);
    if (!net.modal_ratios().empty()) add_modal_damping(net.modal_ratios());
    M_sparse_ = M_.sparseView(), C_sparse_ = C_.sparseView(), K_sparse_ = K_.sparseView();
    initial_velocity_ = quasi_static_velocity(0.0, initial_);
    check_linkages_close();
    for (const ContactPair& c : contacts()) {
        const double amplitude = c.paper_force_amplitude();
        if (amplitude == 0.0) continue;
        const double held = static_contact_force(0.0, initial_, contact_index(c.name()));
        if (amplitude > held)
            warnings_.push_back(detail::concat("contact '", c.name(),
                                               "': the paper's literal eccentricity force K_h epsilon = ", amplitude,
                                               " N exceeds the static contact force ", held,
                                               " N (what the return spring's preload holds): "
                                               "the formulation, not the defect, would open the contact"));
    }
}

template <int N>
auto Mechanism<N>::workspace() const -> Workspace {
    Workspace w;
    w.states = elements_.states();
    return w;
}

template <int N>
auto Mechanism<N>::tangent_pattern() const -> std::vector<std::vector<int>> {
    std::vector<std::vector<int>> groups;
    elements_.for_each([&](const auto& e) { groups.push_back(e.tangent_dofs()); });
    return groups;
}

template <int N>
auto Mechanism<N>::dof_names() const -> std::vector<std::string> {
    std::vector<std::string> names;
    for (const DofSpec& d : spec_.structure.dofs()) names.push_back(d.name);
    return names;
}

template <int N>
auto Mechanism<N>::channel_names() const -> std::vector<std::string> {
    std::vector<std::string> names{"theta", "drive.speed", "drive.torque", "drive.power"};
    elements_.for_each([&](const auto& e) { e.add_channel_names(names); });
    return names;
}

template <int N>
auto Mechanism<N>::event_names() const -> std::vector<std::string> {
    std::vector<std::string> names;
    elements_.for_each([&](const auto& e) { e.add_event_names(names); });
    return names;
}

template <int N>
auto Mechanism<N>::contact_index(const std::string& name) const -> std::size_t {
    for (std::size_t i = 0; i < contacts().size(); ++i)
        if (contacts()[i].name() == name) return i;
    detail::fail("no contact named '", name, "'");
}

template <int N>
auto Mechanism<N>::static_contact_force(double theta, const Vector& q, std::size_t i) const -> double {
    const Workspace w = workspace_at(theta);
    return contacts().at(i).static_force(w.t, q, w.template of<ContactElement>()[i]);
}

template <int N>
auto Mechanism<N>::static_equilibrium(double theta) const -> Vector {
    detail::require_finite(theta, "theta");
    const Workspace w = workspace_at(theta);
    Vector q = Vector::Zero(n_), dq(n_);
    // The contact-free deflection as the start, unless the structure alone barely holds the
    // loads (a displacement no machine has): then from zero.
    if (solve_static(K_, load_, dq) && dq.cwiseAbs().maxCoeff() < 1e3) q = dq;
    const double scale = load_.cwiseAbs().maxCoeff() + 1.0;
    const double norm_K = K_.cwiseAbs().rowwise().sum().maxCoeff();
    Vector r(n_), previous_step = Vector::Zero(n_);
    Matrix Kt(n_, n_);
    for (int it = 0; it < 200; ++it) {
        static_residual(w, q, r, Kt);
        // 1e-12 of the load, or the rounding floor of K q when the lift makes q large.
        const double tolerance =
            std::max(1e-12 * scale, 64.0 * std::numeric_limits<double>::epsilon() * norm_K * q.cwiseAbs().maxCoeff());
        if (r.cwiseAbs().maxCoeff() <= tolerance) return q;
        // A follower held only by its contact (gravity or a load, no spring) starts with the
        // contact just touching, where the law has no stiffness: take the step as if every
        // contact were closed (the active-set guess), with the law's stiffness at 1 um, and every
        // free clearance seated on the wall its load pushes it to.
        // A step no machine makes (> 1 km) means the tangent barely holds: an open contact with
        // a spring far too soft for its preload; treat it as singular.
        const auto plausible = [&] { return dq.allFinite() && dq.cwiseAbs().maxCoeff() < 1e3; };
        if (!solve_static(Kt, r, dq) || !plausible()) {
            elements_.for_each(w.states, [&](const auto& e, const auto& s) { e.add_active_set_guess(s, q, r, Kt); });
            if (!solve_static(Kt, r, dq) || !plausible())
                detail::fail("static equilibrium at theta = ", radians_to_degrees(theta),
                             " deg: the structure with its active contacts is not held in place (a DOF with no "
                             "spring to ground and no contact, e.g. a follower without a return spring or load, "
                             "or a shaft without bearings or drive); unconstrained: ",
                             unconstrained_dofs(dq));
        }
        // Two contacts pressing one DOF from both sides (conjugate cams with no spring) make Newton
        // jump between their zero-force points, each step undoing the last: take half of it, where
        // both touch.
        if ((dq + previous_step).cwiseAbs().maxCoeff() <= 1e-9 * dq.cwiseAbs().maxCoeff()) dq *= 0.5;
        previous_step = dq;
        q -= dq;
        // A very stiff contact (1e13 N/m) or pin joint turns the rounding of its gap (of coordinates up
        // to a metre: 1e-16 m) into newtons above the load's 1e-12: a step at the rounding level of
        // the positions (1e-15 m, or 1e-14 of the displacement) is as converged as it gets.
        if (dq.cwiseAbs().maxCoeff() <= 1e-14 * (q.cwiseAbs().maxCoeff() + 0.1)) return q;
    }
    throw ConvergenceError(detail::concat("static equilibrium at theta = ", radians_to_degrees(theta),
                                          " deg did not converge in 200 Newton iterations"));
}

template <int N>
auto Mechanism<N>::tangent_stiffness(double theta, const Vector& q) const -> Matrix {
    const Workspace w = workspace_at(theta);
    Vector r(n_);
    Matrix Kt(n_, n_);
    static_residual(w, q, r, Kt);
    return Kt;
}

template <int N>
auto Mechanism<N>::workspace_at(double theta) const -> Workspace {
    Workspace w = workspace();
    prepare(drive_.time_at_angle(theta), w);
    return w;
}

template <int N>
auto Mechanism<N>::static_residual(const Workspace& w, const Vector& q, Vector& r, Matrix& Kt) const -> void {
    r.noalias() = K_ * q - load_;
    Kt = K_;
    elements_.for_each(w.states, [&](const auto& e, auto& s) { e.add_static(w.t, q, s, r, Kt); });
}

template <int N>
auto Mechanism<N>::quasi_static_velocity(double theta, const Vector& q) const -> Vector {
    const Workspace w = workspace_at(theta);
    Vector r(n_);
    Matrix Kt(n_, n_);
    static_residual(w, q, r, Kt);
    Vector rate = Vector::Zero(n_);
    elements_.for_each(w.states, [&](const auto& e, const auto& s) { e.add_quasi_static_rate(s, q, rate); });
    if (rate.isZero(0.0)) return Vector::Zero(n_);
    Vector dq(n_);
    if (!solve_static(Kt, rate, dq)) return Vector::Zero(n_);  // not held statically: start at rest
    return -dq;
}

template <int N>
auto Mechanism<N>::solve_static(const Matrix& A, const Vector& b, Vector& x) const -> bool {
    if (n_ <= dense_static_limit) {
        const Eigen::FullPivLU<Matrix> lu(A);
        if (lu.isInvertible()) return x = lu.solve(b), true;
        const auto kernel = lu.kernel();
        x = kernel.col(0);
        return false;
    }
    const Eigen::SparseMatrix<double> S = A.sparseView();
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(S);
    if (lu.info() == Eigen::Success) {
        x = lu.solve(b);
        // A rigid-body mode that rounding hides from the pivots shows as a displacement no machine
        // has (the solution is then that mode, amplified).
        if (x.allFinite() && x.cwiseAbs().maxCoeff() < 1e3) return true;
        if (!x.allFinite()) x = Vector::Ones(n_);
        return false;
    }
    x = Vector::Ones(n_);  // the factorization does not say which DOFs: name none in particular
    return false;
}

template <int N>
auto Mechanism<N>::unconstrained_dofs(const Vector& direction) const -> std::string {
    const double largest = direction.cwiseAbs().maxCoeff();
    std::string out;
    int listed = 0;
    for (int i = 0; i < n_; ++i)
        if (std::abs(direction[i]) >= 0.1 * largest) {
            if (++listed > 12) {
                out += ", ...";
                break;
            }
            out += (out.empty() ? "" : ", ") + spec_.structure.dofs()[std::size_t(i)].name;
        }
    return out;
}

template <int N>
auto Mechanism<N>::dense(const NetworkSpec::Triplets& t) const -> Matrix {
    Matrix A = Matrix::Zero(n_, n_);
    for (const auto& e : t) A(e.row(), e.col()) += e.value();
    return A;
}

template <int N>
auto Mechanism<N>::add_modal_damping(const std::vector<double>& ratios) -> void {
    if (ratios.size() != 1 && int(ratios.size()) != n_)
        detail::fail("modal damping: give one ratio or one per mode (", n_, "), got ", ratios.size());
    const Matrix Kt = tangent_stiffness(0.0, initial_);
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> eig(Kt, M_);
    if (eig.info() != Eigen::Success) detail::fail("modal damping: the eigen solver did not converge");
    Vector d(n_);
    for (int i = 0; i < n_; ++i) {
        const double zeta = ratios.size() == 1 ? ratios[0] : ratios[std::size_t(i)];
        d[i] = 2.0 * zeta * std::sqrt(std::max(eig.eigenvalues()[i], 0.0));
    }
    const Matrix MPhi = M_ * eig.eigenvectors();
    C_ += MPhi * d.asDiagonal() * MPhi.transpose();
}

}  // namespace camfollower

// CAMFOLLOWER_MECHANISM_CLASS_INSTANCE(extern, N) declares Mechanism<N> compiled in
// camfollower::precompiled (as Mechanism<> is, and the paper preset's, presets/paper.hpp);
// (, N) compiles it there.
#define CAMFOLLOWER_MECHANISM_CLASS_INSTANCE(PREFIX, DOFS) PREFIX template class camfollower::Mechanism<DOFS>;
#if CAMFOLLOWER_USE_PRECOMPILED
CAMFOLLOWER_MECHANISM_CLASS_INSTANCE(extern, Eigen::Dynamic)
#endif
