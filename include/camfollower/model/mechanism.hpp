// A cam mechanism built from a runtime description: the linear structure (structure/network.hpp),
// any number of cam-follower contact pairs (contact/contact_pair.hpp) on one camshaft turning at a
// constant speed. Mechanism<N> is immutable and implements the system contract (core/system.hpp);
// N is the DOF count when known at compile time (fixed-size Eigen, the fast path), Eigen::Dynamic
// otherwise.
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
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "camfollower/contact/contact_pair.hpp"
#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"
#include "camfollower/structure/network.hpp"

namespace camfollower {

// The runtime description of a mechanism (mutable; Mechanism<N>(builder) makes the immutable model).
struct MechanismBuilder {
    NetworkSpec structure;
    std::vector<ContactPairSpec> contacts;
    double camshaft_speed = 750.0 * two_pi / 60.0;  // rad/s

    // The structure's elements (structure/network.hpp), by DOF name ("ground" for the frame).
    void add_dof(const std::string& name, double mass, const Eigen::Vector3d& direction = Eigen::Vector3d::Zero()) {
        structure.add_dof(name, mass, direction);
    }
    void add_spring(const std::string& name, const std::string& a, const std::string& b, double stiffness,
                    double damping = 0.0, double preload = 0.0) {
        structure.add_spring(name, a, b, stiffness, damping, preload);
    }
    void add_damper(const std::string& name, const std::string& a, const std::string& b, double damping) {
        structure.add_spring(name, a, b, 0.0, damping, 0.0);
    }
    void add_load(const std::string& dof, double force) { structure.add_load(dof, force); }
    void set_gravity(const Eigen::Vector3d& g) { structure.set_gravity(g); }
    void set_rayleigh_damping(double alpha, double beta) { structure.set_rayleigh_damping(alpha, beta); }
    void set_modal_damping(const std::vector<double>& ratios) { structure.set_modal_damping(ratios); }

    void add_contact(const ContactPairSpec& c) {
        if (c.name.empty()) detail::fail("contact name must be non-empty");
        for (const ContactPairSpec& other : contacts)
            if (other.name == c.name) detail::fail("contact '", c.name, "' is defined twice");
        contacts.push_back(c);
    }
    void set_camshaft_speed_rpm(double rpm) {
        detail::require_positive(rpm, "camshaft_speed_rpm", "(rpm)");
        camshaft_speed = rpm * two_pi / 60.0;
    }
    double camshaft_speed_rpm() const { return camshaft_speed * 60.0 / two_pi; }
};

template <int N = Eigen::Dynamic>
class Mechanism {
public:
    using Vector = Eigen::Matrix<double, N, 1>;
    using Matrix = Eigen::Matrix<double, N, N>;

    struct ContactMemory {
        bool in_contact = true;
        double loss_start = 0.0;
        std::vector<std::pair<double, double>> losses;  // [start, end) times, s
    };
    struct Workspace {
        double t = 0.0;
        std::vector<ContactTerms> terms;     // one per contact pair
        std::vector<ContactMemory> memory;   // path memory: contact-loss intervals
        // Contact responses of the last force() call, reused by tangent() and accepted() (which the
        // stepper calls at the same q, v: core/system.hpp).
        mutable std::vector<ContactResponse> last;
    };

    explicit Mechanism(MechanismBuilder description) : spec_(std::move(description)) {
        const NetworkSpec& net = spec_.structure;
        n_ = net.size();
        if (n_ == 0) detail::fail("a mechanism needs at least one DOF");
        if (N != Eigen::Dynamic && n_ != N)
            detail::fail("Mechanism<", N, "> built from a description with ", n_, " DOFs");
        detail::require_positive(spec_.camshaft_speed, "camshaft_speed", "(rad/s)");
        NetworkSpec::Triplets tm, tc, tk;
        net.assemble(tm, tc, tk);
        M_ = dense(tm), C_ = dense(tc), K_ = dense(tk);
        const Eigen::VectorXd p = net.constant_load();
        load_ = p;
        for (const ContactPairSpec& c : spec_.contacts) {
            const std::string who = "contact '" + c.name + "'";
            contacts_.emplace_back(c, net.index(c.cam_x, who + " cam_x"), net.index(c.cam_y, who + " cam_y"),
                                   net.index(c.follower_dof, who + " follower_dof"), net.index(c.lateral, who + " lateral"));
        }
        if (net.rayleigh_alpha() != 0.0 || net.rayleigh_beta() != 0.0)
            C_ += net.rayleigh_alpha() * M_ + net.rayleigh_beta() * K_;
        initial_ = static_equilibrium(0.0);
        if (!net.modal_ratios().empty()) add_modal_damping(net.modal_ratios());
    }

    // --- the system contract ---
    int size() const { return n_; }
    const Matrix& mass() const { return M_; }
    const Matrix& damping() const { return C_; }
    const Matrix& stiffness() const { return K_; }
    const Vector& initial_displacement() const { return initial_; }
    int max_rank() const { return int(contacts_.size()); }

    Workspace workspace() const {
        Workspace w;
        w.terms.resize(contacts_.size());
        w.memory.resize(contacts_.size());
        w.last.resize(contacts_.size());
        return w;
    }
    void prepare(double t, Workspace& w) const {
        w.t = t;
        for (std::size_t i = 0; i < contacts_.size(); ++i) contacts_[i].prepare(t, spec_.camshaft_speed, w.terms[i]);
    }
    void force(const Workspace& w, const Vector& q, const Vector& v, Vector& f) const {
        f = -load_;
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            w.last[i] = contacts_[i].response(c, q, v);
            const double F = w.last[i].force;
            if (F == 0.0) continue;
            for (int k = 0; k < c.count; ++k) f[c.dof[k]] += F * c.g[k];
        }
    }
    void tangent(const Workspace& w, const Vector&, const Vector&, double cq, double cv, LowRank<Vector>& uv) const {
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            const ContactResponse& r = w.last[i];
            if (!r.in_contact || (r.stiffness == 0.0 && r.damping == 0.0)) continue;
            const double a = cq * r.stiffness + cv * r.damping, b = cq * r.damping;
            auto u = uv.U.col(uv.rank);
            auto vv = uv.V.col(uv.rank);
            u.setZero(), vv.setZero();
            for (int k = 0; k < c.count; ++k) {
                u[c.dof[k]] = c.g[k];
                vv[c.dof[k]] = a * c.g[k] + b * c.g_dot[k];
            }
            ++uv.rank;
        }
    }
    void accepted(Workspace& w, const Vector&, const Vector&) const {
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            ContactMemory& m = w.memory[i];
            const bool contact = w.last[i].in_contact;
            if (contact == m.in_contact) continue;
            if (!contact) m.loss_start = w.t;
            else m.losses.emplace_back(m.loss_start, w.t);
            m.in_contact = contact;
        }
    }
    std::vector<std::string> dof_names() const {
        std::vector<std::string> names;
        for (const DofSpec& d : spec_.structure.dofs()) names.push_back(d.name);
        return names;
    }
    // Per contact: <name>.force (N), .penetration (m), .stiffness (dF/d delta, N/m), .pressure_angle
    // (rad), .cam_angle (rad), .in_contact (0/1).
    static constexpr int channels_per_contact = 6;
    std::vector<std::string> channel_names() const {
        std::vector<std::string> names{"theta"};
        for (const ContactPair& c : contacts_)
            for (const char* s : {".force", ".penetration", ".stiffness", ".pressure_angle", ".cam_angle", ".in_contact"})
                names.push_back(c.name() + s);
        return names;
    }
    void observe(const Workspace& w, const Vector& q, const Vector& v, double* out) const {
        *out++ = spec_.camshaft_speed * w.t;
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            const double delta = ContactPair::penetration(c, q);
            const ContactResponse r = contacts_[i].response(c, q, v);
            *out++ = r.force;
            *out++ = delta;
            *out++ = r.stiffness;
            *out++ = std::atan2(c.sin_alpha, c.cos_alpha);
            *out++ = c.theta;
            *out++ = r.in_contact ? 1.0 : 0.0;
        }
    }

    // --- queries ---
    // The description it was built from: copy, change and build again for a changed mechanism.
    const MechanismBuilder& description() const { return spec_; }
    const std::vector<ContactPair>& contacts() const { return contacts_; }
    double omega() const { return spec_.camshaft_speed; }
    double period() const { return two_pi / spec_.camshaft_speed; }
    const Vector& constant_load() const { return load_; }
    int dof_index(const std::string& name) const { return spec_.structure.index(name, "dof_index"); }

    // Contact-loss intervals of contact i up to t_end (a loss still open at t_end ends there).
    static std::vector<std::pair<double, double>> contact_loss(const Workspace& w, std::size_t i, double t_end) {
        std::vector<std::pair<double, double>> out = w.memory.at(i).losses;
        if (!w.memory[i].in_contact) out.emplace_back(w.memory[i].loss_start, t_end);
        return out;
    }

    // Quasi-static equilibrium at camshaft angle theta, at rest: K q + sum F_i(delta_i, 0) g_i = p (the
    // contact laws at zero penetration rate: a static state has no impact damping). Newton from the
    // contact-free deflection (or zero when the structure alone is singular) on the exact tangent,
    // with an all-contacts-closed step where that tangent is singular.
    Vector static_equilibrium(double theta) const {
        detail::require_finite(theta, "theta");
        Workspace w = workspace();
        prepare(theta / spec_.camshaft_speed, w);
        Vector q = Vector::Zero(n_);
        const Eigen::PartialPivLU<Matrix> k_lu(K_);
        const double det = k_lu.determinant();
        if (std::isfinite(det) && det != 0.0) q = k_lu.solve(load_);
        const double scale = load_.cwiseAbs().maxCoeff() + 1.0;
        const double norm_K = K_.cwiseAbs().rowwise().sum().maxCoeff();
        Vector r(n_);
        Matrix Kt(n_, n_);
        for (int it = 0; it < 200; ++it) {
            static_residual(w, q, r, Kt);
            // 1e-12 of the load, or the rounding floor of K q when the lift makes q large.
            const double tolerance =
                std::max(1e-12 * scale, 64.0 * std::numeric_limits<double>::epsilon() * norm_K * q.cwiseAbs().maxCoeff());
            if (r.cwiseAbs().maxCoeff() <= tolerance) return q;
            Eigen::FullPivLU<Matrix> lu(Kt);
            // A follower held only by its contact (gravity or a load, no spring) starts with the
            // contact just touching, where the law has no stiffness: take the step as if every
            // contact were closed (the active-set guess), with the law's stiffness at 1 um.
            if (!lu.isInvertible()) lu.compute(Kt + closed_contact_stiffness(w));
            if (!lu.isInvertible())
                detail::fail("static equilibrium at theta = ", radians_to_degrees(theta),
                             " deg: the structure with its active contacts is not held in place (a DOF with no "
                             "spring to ground and no contact, e.g. a follower without a return spring or load)");
            q -= lu.solve(r);
        }
        throw ConvergenceError(detail::concat("static equilibrium at theta = ", radians_to_degrees(theta),
                                              " deg did not converge in 200 Newton iterations"));
    }

    // Tangent stiffness K + sum k_i g_i g_i^T at rest at camshaft angle theta and displacement q
    // (for modal analysis about a static equilibrium).
    Matrix tangent_stiffness(double theta, const Vector& q) const {
        Workspace w = workspace();
        prepare(theta / spec_.camshaft_speed, w);
        Vector r(n_);
        Matrix Kt(n_, n_);
        static_residual(w, q, r, Kt);
        return Kt;
    }

private:
    // r = K q + sum F_i(delta_i, 0) g_i - p and its Jacobian.
    void static_residual(const Workspace& w, const Vector& q, Vector& r, Matrix& Kt) const {
        r.noalias() = K_ * q - load_;
        Kt = K_;
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            const ContactResponse f = contacts_[i].spec().law(ContactPair::penetration(c, q), 0.0);
            for (int a = 0; a < c.count; ++a) {
                r[c.dof[a]] += f.force * c.g[a];
                for (int b = 0; b < c.count; ++b) Kt(c.dof[a], c.dof[b]) += f.stiffness * c.g[a] * c.g[b];
            }
        }
    }

    Matrix closed_contact_stiffness(const Workspace& w) const {
        Matrix Kc = Matrix::Zero(n_, n_);
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            const double k = contacts_[i].spec().law(1e-6, 0.0).stiffness;
            for (int a = 0; a < c.count; ++a)
                for (int b = 0; b < c.count; ++b) Kc(c.dof[a], c.dof[b]) += k * c.g[a] * c.g[b];
        }
        return Kc;
    }

    Matrix dense(const NetworkSpec::Triplets& t) const {
        Matrix A = Matrix::Zero(n_, n_);
        for (const auto& e : t) A(e.row(), e.col()) += e.value();
        return A;
    }

    void add_modal_damping(const std::vector<double>& ratios) {
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

    MechanismBuilder spec_;
    int n_ = 0;
    Matrix M_, C_, K_;
    Vector load_, initial_;
    std::vector<ContactPair> contacts_;
};

}  // namespace camfollower
