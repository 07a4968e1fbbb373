// SPDX-License-Identifier: BSD-3-Clause
// A cam mechanism built from a runtime description: the linear structure (structure/network.hpp),
// any number of cam-follower contact pairs (contact/contact_pair.hpp) on one camshaft turning at a
// constant nominal speed; with flexible shafts (structure/shaft_spec.hpp) a cam's angle adds the
// shaft's twist at the cam, a state. Mechanism<N> is immutable and implements the system contract (core/system.hpp);
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
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "camfollower/contact/clearance.hpp"
#include "camfollower/contact/contact_pair.hpp"
#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"
#include "camfollower/structure/network.hpp"

namespace camfollower {

// The runtime description of a mechanism (mutable; Mechanism<N>(builder) makes the immutable model).
struct MechanismBuilder {
    NetworkSpec structure;
    std::vector<ContactPairSpec> contacts;
    std::vector<ClearanceSpec> clearances;
    double camshaft_speed = 750.0 * two_pi / 60.0;  // rad/s

    // The structure's elements (structure/network.hpp), by DOF name ("ground" for the frame).
    void add_dof(const std::string& name, double mass, const Eigen::Vector3d& direction = Eigen::Vector3d::Zero()) {
        structure.add_dof(name, mass, direction);
    }
    void add_spring(const std::string& name, const std::string& a, const std::string& b, double stiffness,
                    double damping = 0.0, double preload = 0.0) {
        require_unused_name(name, "element");
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
        detail::require_name(c.name, "contact");
        require_unused_name(c.name, "contact");
        c.require_distinct_roles();
        contacts.push_back(c);
    }
    // A radial clearance (contact/clearance.hpp); add_guide adds one per bushing.
    void add_clearance(const ClearanceSpec& c) {
        c.validate();
        require_unused_name(c.name, "clearance");
        clearances.push_back(c);
    }
    void add_guide(const GuideSpec& g) {
        for (const ClearanceSpec& c : g.clearances()) add_clearance(c);
    }
    // --- flexible camshafts (structure/shaft_spec.hpp); the shaft's axis is the global x axis, a cam's
    // contact frame has its x along global y and its y (a translating follower's axis) along global z.
    void add_shaft(const ShaftSpec& shaft) { structure.add_shaft(shaft); }

    // A bearing at station x: radial spring-dampers from u_y and u_z to ground ("<name>.y", "<name>.z").
    void add_bearing(const std::string& name, const std::string& shaft, double x, double radial_stiffness,
                     double radial_damping = 0.0) {
        const int node = structure.shaft(shaft).spec.node_at(x);
        for (const Mount& b : bearings_)
            if (b.shaft == shaft && b.node == node)
                detail::fail("bearings '", b.name, "' and '", name, "' are at the same station x = ", x, " m of shaft '", shaft, "'");
        detail::require_positive(radial_stiffness, ("radial stiffness of bearing '" + name + "'").c_str(), "(N/m)");
        add_spring(name + ".y", structure.shaft_dof_at(shaft, x, 1), ground_name, radial_stiffness, radial_damping);
        add_spring(name + ".z", structure.shaft_dof_at(shaft, x, 2), ground_name, radial_stiffness, radial_damping);
        bearings_.push_back({name, shaft, x, node, 0.0});
    }

    // The drive as an imposed speed through a compliance: a torsional spring-damper (N m/rad, N m s/rad)
    // from the shaft's twist at station x to the rigid rotation omega t.
    void add_drive(const std::string& name, const std::string& shaft, double x, double stiffness, double damping = 0.0) {
        detail::require_positive(stiffness, ("stiffness of drive '" + name + "'").c_str(), "(N m/rad)");
        add_spring(name, structure.shaft_dof_at(shaft, x, 3), ground_name, stiffness, damping);
    }

    // The drive as a speed-controlled motor with a flywheel at station x: the flywheel's inertia
    // (kg m^2) on the twist, the controller's position gain (N m/rad, > 0: it holds the shaft's angle
    // to the nominal rotation, so a static equilibrium exists) and velocity gain (N m s/rad), and a
    // constant torque (N m, forward: the cams' mean torque as feed-forward).
    void add_motor(const std::string& name, const std::string& shaft, double x, double inertia, double position_gain,
                   double velocity_gain, double torque) {
        const std::string twist = structure.shaft_dof_at(shaft, x, 3);
        detail::require_positive(position_gain, ("position_gain of motor '" + name + "'").c_str(),
                                 "(N m/rad; a motor without one leaves the shaft's angle free)");
        detail::require_non_negative(velocity_gain, ("velocity_gain of motor '" + name + "'").c_str(), "(N m s/rad)");
        detail::require_finite(torque, ("torque of motor '" + name + "'").c_str());
        add_mass(twist, inertia);
        add_spring(name, twist, ground_name, position_gain, velocity_gain);
        if (torque != 0.0) add_load(twist, torque);
    }

    // A cam mounted at station x of a shaft: the contact's cam centre and twist become the node's u_y,
    // u_z and theta_x; the cam's mass (kg) and inertia (kg m^2) are added there; `width` (m) is its
    // axial extent, checked against the other cams on the shaft.
    void mount_cam(ContactPairSpec contact, const std::string& shaft, double x, double width = 0.0, double mass = 0.0,
                   double inertia = 0.0) {
        const ShaftEntry& s = structure.shaft(shaft);
        if (!(std::isfinite(x) && x >= 0.0 && x <= s.spec.length))
            detail::fail("cam '", contact.name, "' at x = ", x, " m is outside shaft '", shaft, "' [0, ", s.spec.length, "] m");
        detail::require_non_negative(width, ("width of cam '" + contact.name + "'").c_str(), "(m)");
        detail::require_non_negative(mass, ("mass of cam '" + contact.name + "'").c_str(), "(kg)");
        detail::require_non_negative(inertia, ("inertia of cam '" + contact.name + "'").c_str(), "(kg m^2)");
        if (x - 0.5 * width < -ShaftSpec::merge_distance || x + 0.5 * width > s.spec.length + ShaftSpec::merge_distance)
            detail::fail("cam '", contact.name, "' (x = ", x, " m, width ", width, " m) reaches past the ends of shaft '", shaft, "'");
        const int node = s.spec.node_at(x);
        for (const Mount& o : cams_)
            if (o.shaft == shaft && (o.node == node || std::abs(o.x - x) < 0.5 * (o.width + width)))
                detail::fail("cams '", o.name, "' (x = ", o.x, " m, width ", o.width, " m) and '", contact.name, "' (x = ", x,
                             " m, width ", width, " m) overlap on shaft '", shaft, "'");
        contact.cam_x = structure.shaft_dof_at(shaft, x, 1);
        contact.cam_y = structure.shaft_dof_at(shaft, x, 2);
        contact.cam_twist = structure.shaft_dof_at(shaft, x, 3);
        add_contact(contact);
        if (mass > 0.0) add_mass(contact.cam_x, mass), add_mass(contact.cam_y, mass);
        if (inertia > 0.0) add_mass(contact.cam_twist, inertia);
        cams_.push_back({contact.name, shaft, x, node, width});
    }
    void add_mass(const std::string& dof, double mass) { structure.add_mass(dof, mass); }
    void add_spring_chain(const std::string& name, const std::string& a, const std::string& b, double stiffness,
                          double mass, int elements, double damping = 0.0, double preload = 0.0,
                          const Eigen::Vector3d& direction = Eigen::Vector3d::Zero()) {
        require_unused_name(name, "element");
        structure.add_spring_chain(name, a, b, stiffness, mass, elements, damping, preload, direction);
    }

    void set_camshaft_speed_rpm(double rpm) {
        detail::require_camshaft_speed_rpm(rpm, "camshaft_speed_rpm");
        camshaft_speed = rpm * two_pi / 60.0;
    }
    double camshaft_speed_rpm() const { return camshaft_speed * 60.0 / two_pi; }

private:
    // Elements name their channels ("<name>.force", ...): one name, one element, whatever its kind.
    void require_unused_name(const std::string& name, const char* kind) const {
        for (const ContactPairSpec& c : contacts)
            if (c.name == name) detail::fail(kind, " '", name, "': the name is taken by contact '", name, "'");
        for (const ClearanceSpec& c : clearances)
            if (c.name == name) detail::fail(kind, " '", name, "': the name is taken by clearance '", name, "'");
        for (const SpringSpec& s : structure.springs())
            if (s.name == name) detail::fail(kind, " '", name, "': the name is taken by element '", name, "'");
    }

    struct Mount {
        std::string name, shaft;
        double x;
        int node;
        double width;
    };
    std::vector<Mount> cams_, bearings_;
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
        // One per contact pair; on a twisting camshaft re-evaluated at every force() call.
        mutable std::vector<ContactTerms> terms;
        std::vector<ContactMemory> memory;   // path memory: contact-loss intervals
        // Contact responses of the last force() call, reused by tangent() and accepted() (which the
        // stepper calls at the same q, v: core/system.hpp).
        mutable std::vector<ContactResponse> last;
        mutable std::vector<ClearanceResponse> last_clearance;
    };

    explicit Mechanism(MechanismBuilder description) : spec_(std::move(description)) {
        const NetworkSpec& net = spec_.structure;
        n_ = net.size();
        if (n_ == 0) detail::fail("a mechanism needs at least one DOF");
        if (n_ > max_dofs)
            detail::fail("the mechanism has ", n_, " DOFs, more than the ", max_dofs, " a Mechanism assembles (dense n x n "
                         "matrices: ", 24.0 * double(n_) * double(n_) / 1e9, " GB for M, C and K alone); coarsen the shafts' "
                         "meshes (max_element_length) or split the model");
        if (N != Eigen::Dynamic && n_ != N)
            detail::fail("Mechanism<", N, "> built from a description with ", n_, " DOFs");
        detail::require_camshaft_speed(spec_.camshaft_speed, "camshaft_speed");
        NetworkSpec::Triplets tm, tc, tk;
        net.assemble(tm, tc, tk);
        M_ = dense(tm), C_ = dense(tc), K_ = dense(tk);
        const Eigen::VectorXd p = net.constant_load();
        load_ = p;
        for (const ContactPairSpec& c : spec_.contacts) {
            const std::string who = "contact '" + c.name + "'";
            contacts_.emplace_back(c, net.index(c.cam_x, who + " cam_x"), net.index(c.cam_y, who + " cam_y"),
                                   net.index(c.follower_dof, who + " follower_dof"), net.index(c.lateral, who + " lateral"),
                                   net.index(c.cam_twist, who + " cam_twist"));
        }
        for (const ClearanceSpec& c : spec_.clearances) {
            c.validate();
            const std::string who = "clearance '" + c.name + "'";
            std::vector<int> dofs;
            for (const auto& term : c.gap) {
                dofs.push_back(net.index(term.first, who + " gap DOF"));
                if (dofs.back() < 0) detail::fail(who, ": the gap coordinate's DOFs must not be ground");
            }
            const int sliding = c.friction > 0.0 ? net.index(c.sliding_dof, who + " sliding_dof") : -1;
            if (c.friction > 0.0 && sliding < 0) detail::fail(who, ": sliding_dof must be a DOF, not ground");
            clearances_.emplace_back(c, dofs, sliding);
            max_rank_ += clearances_.back().max_rank();
        }
        max_rank_ += int(contacts_.size());
        if (net.rayleigh_alpha() != 0.0 || net.rayleigh_beta() != 0.0)
            C_ += net.rayleigh_alpha() * M_ + net.rayleigh_beta() * K_;
        initial_ = static_equilibrium(0.0);
        if (!net.modal_ratios().empty()) add_modal_damping(net.modal_ratios());
        M_sparse_ = M_.sparseView(), C_sparse_ = C_.sparseView(), K_sparse_ = K_.sparseView();
        initial_velocity_ = quasi_static_velocity(0.0, initial_);
        for (const ContactPair& c : contacts_) {
            const double amplitude = c.paper_force_amplitude();
            if (amplitude == 0.0) continue;
            const double held = static_contact_force(0.0, initial_, contact_index(c.name()));
            if (amplitude > held)
                warnings_.push_back(detail::concat(
                    "contact '", c.name(), "': the paper's literal eccentricity force K_h epsilon = ", amplitude,
                    " N exceeds the static contact force ", held, " N (what the return spring's preload holds): "
                    "the formulation, not the defect, would open the contact"));
        }
    }

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

    Workspace workspace() const {
        Workspace w;
        w.terms.resize(contacts_.size());
        w.memory.resize(contacts_.size());
        w.last.resize(contacts_.size());
        w.last_clearance.resize(clearances_.size());
        return w;
    }
    void prepare(double t, Workspace& w) const {
        w.t = t;
        for (std::size_t i = 0; i < contacts_.size(); ++i)
            if (contacts_[i].twist() < 0) contacts_[i].prepare(t, spec_.camshaft_speed, w.terms[i]);
    }
    void force(const Workspace& w, const Vector& q, const Vector& v, Vector& f) const {
        f = -load_;
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            if (contacts_[i].twist() >= 0) twist_terms(w.t, i, q, v[contacts_[i].twist()], w.terms[i]);
            w.last[i] = contacts_[i].response(c, q, v);
            const double F = w.last[i].force;
            if (c.loaded)
                for (int k = 0; k < c.count; ++k) f[c.dof[k]] -= c.p[k];
            if (F == 0.0) continue;
            for (int k = 0; k < c.count; ++k) f[c.dof[k]] += F * c.g[k];
            if (c.twist >= 0) f[c.twist] += F * c.moment_arm;
        }
        for (std::size_t i = 0; i < clearances_.size(); ++i) {
            w.last_clearance[i] = clearances_[i].response(q, v);
            clearances_[i].add_force(w.last_clearance[i], f);
        }
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
    std::vector<std::vector<int>> tangent_pattern() const {
        std::vector<std::vector<int>> groups;
        for (const ContactPair& c : contacts_) {
            groups.push_back(c.dofs());
            if (c.twist() >= 0) groups.back().push_back(c.twist());
        }
        for (const Clearance& cl : clearances_) {
            groups.push_back(cl.dofs());
            if (cl.has_friction()) groups.back().push_back(cl.sliding());
        }
        return groups;
    }
    const Eigen::SparseMatrix<double>& sparse_mass() const { return M_sparse_; }
    const Eigen::SparseMatrix<double>& sparse_damping() const { return C_sparse_; }
    const Eigen::SparseMatrix<double>& sparse_stiffness() const { return K_sparse_; }
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
    // (rad), .cam_angle (rad, with the shaft's twist), .in_contact (0/1); on a twisting camshaft also
    // .cam_torque (N m: the contact's moment about the shaft axis against the cam's rotation).
    // Per clearance: <name>.force (wall force, N, >= 0), .side (-1, 0 free, +1), .gap (u, m),
    // .friction (N, along +sliding DOF on the rod).
    static constexpr int channels_per_contact = 6;
    static constexpr int channels_per_clearance = 4;
    std::vector<std::string> channel_names() const {
        std::vector<std::string> names{"theta"};
        for (const ContactPair& c : contacts_)
        {
            for (const char* s : {".force", ".penetration", ".stiffness", ".pressure_angle", ".cam_angle", ".in_contact"})
                names.push_back(c.name() + s);
            if (c.twist() >= 0) names.push_back(c.name() + ".cam_torque");
        }
        for (const Clearance& c : clearances_)
            for (const char* s : {".force", ".side", ".gap", ".friction"}) names.push_back(c.name() + s);
        return names;
    }
    // Switching functions (solver/events.hpp): per contact <name>.contact, its penetration (m); per
    // clearance <name>.wall, |u| - c (m): > 0 while touching.
    std::vector<std::string> event_names() const {
        std::vector<std::string> names;
        for (const ContactPair& c : contacts_) names.push_back(c.name() + ".contact");
        for (const Clearance& c : clearances_) names.push_back(c.name() + ".wall");
        return names;
    }
    // (force() at the same q, v computed them: its responses are reused)
    CAMFOLLOWER_FORCE_INLINE void event_values(const Workspace& w, const Vector&, const Vector&, double* g) const {
        for (const ContactResponse& r : w.last) *g++ = r.delta;
        for (std::size_t i = 0; i < clearances_.size(); ++i)
            *g++ = std::abs(w.last_clearance[i].u) - clearances_[i].spec().clearance;
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
            if (c.twist >= 0) *out++ = r.force * c.moment_arm;
        }
        for (const Clearance& cl : clearances_) {
            const ClearanceResponse r = cl.response(q, v);
            *out++ = r.wall.force;
            *out++ = r.side;
            *out++ = r.u;
            *out++ = cl.has_friction() ? -cl.spec().friction * r.wall.force * r.slip : 0.0;
        }
    }

    // --- queries ---
    // The description it was built from: copy, change and build again for a changed mechanism.
    const MechanismBuilder& description() const { return spec_; }
    const std::vector<ContactPair>& contacts() const { return contacts_; }
    const std::vector<Clearance>& clearances() const { return clearances_; }
    // What the model's user should know about its formulation (e.g. the paper's literal eccentricity
    // force exceeding the static contact force). Python turns each into a UserWarning.
    const std::vector<std::string>& warnings() const { return warnings_; }
    std::size_t contact_index(const std::string& name) const {
        for (std::size_t i = 0; i < contacts_.size(); ++i)
            if (contacts_[i].name() == name) return i;
        detail::fail("no contact named '", name, "'");
    }
    // Contact force of contact i at rest at camshaft angle theta and displacement q, N.
    double static_contact_force(double theta, const Vector& q, std::size_t i) const {
        const Workspace w = workspace_at(theta);
        if (contacts_.at(i).twist() >= 0) twist_terms(w.t, i, q, 0.0, w.terms[i]);
        return contacts_[i].spec().law(ContactPair::penetration(w.terms[i], q), 0.0).force;
    }
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
        const Workspace w = workspace_at(theta);
        Vector q = Vector::Zero(n_), dq(n_);
        // The contact-free deflection as the start, unless the structure alone barely holds the
        // loads (a displacement no machine has): then from zero.
        if (solve_static(K_, load_, dq) && dq.cwiseAbs().maxCoeff() < 1e3) q = dq;
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
            // A follower held only by its contact (gravity or a load, no spring) starts with the
            // contact just touching, where the law has no stiffness: take the step as if every
            // contact were closed (the active-set guess), with the law's stiffness at 1 um, and every
            // free clearance seated on the wall its load pushes it to.
            // A step no machine makes (> 1 km) means the tangent barely holds: an open contact with
            // a spring far too soft for its preload; treat it as singular.
            const auto plausible = [&] { return dq.allFinite() && dq.cwiseAbs().maxCoeff() < 1e3; };
            if (!solve_static(Kt, r, dq) || !plausible()) {
                Kt += closed_contact_stiffness(w);
                close_free_clearances(q, r, Kt);
                if (!solve_static(Kt, r, dq) || !plausible())
                    detail::fail("static equilibrium at theta = ", radians_to_degrees(theta),
                                 " deg: the structure with its active contacts is not held in place (a DOF with no "
                                 "spring to ground and no contact, e.g. a follower without a return spring or load, "
                                 "or a shaft without bearings or drive); unconstrained: ", unconstrained_dofs(dq));
            }
            q -= dq;
            // A very stiff contact (1e13 N/m) turns the rounding of its gap into newtons above the
            // load's 1e-12: a step at the rounding level of the position is as converged as it gets.
            if (dq.cwiseAbs().maxCoeff() <= 1e-14 * (q.cwiseAbs().maxCoeff() + 1e-3)) return q;
        }
        throw ConvergenceError(detail::concat("static equilibrium at theta = ", radians_to_degrees(theta),
                                              " deg did not converge in 200 Newton iterations"));
    }

    // Tangent stiffness K + sum k_i g_i g_i^T at rest at camshaft angle theta and displacement q
    // (for modal analysis about a static equilibrium).
    Matrix tangent_stiffness(double theta, const Vector& q) const {
        const Workspace w = workspace_at(theta);
        Vector r(n_);
        Matrix Kt(n_, n_);
        static_residual(w, q, r, Kt);
        return Kt;
    }

private:
    // A workspace with the time-only terms prepared at camshaft angle theta (static analyses).
    Workspace workspace_at(double theta) const {
        Workspace w = workspace();
        prepare(theta / spec_.camshaft_speed, w);
        return w;
    }

    // r = K q + sum F_i(delta_i, 0) g_i - p and its Jacobian.
    void static_residual(const Workspace& w, const Vector& q, Vector& r, Matrix& Kt) const {
        r.noalias() = K_ * q - load_;
        Kt = K_;
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            if (contacts_[i].twist() >= 0) twist_terms(w.t, i, q, 0.0, w.terms[i]);
            const ContactResponse f = contacts_[i].spec().law(ContactPair::penetration(c, q), 0.0);
            for (int a = 0; a < c.count; ++a) r[c.dof[a]] += f.force * c.g[a] - c.p[a];
            if (c.twist >= 0) r[c.twist] += f.force * c.moment_arm;
            for_each_gradient(c, [&](int a, double ga) {
                for_each_gradient(c, [&](int b, double gb) { Kt(a, b) += f.stiffness * ga * gb; });
            });
        }
        for (const Clearance& cl : clearances_) {
            const ClearanceResponse f = cl.response(q, q, true);
            cl.add_force(f, r);
            const std::vector<int>& d = cl.dofs();
            const std::vector<double>& c = cl.coefficients();
            for (std::size_t a = 0; a < d.size(); ++a)
                for (std::size_t b = 0; b < d.size(); ++b) Kt(d[a], d[b]) += f.wall.stiffness * c[a] * c[b];
        }
    }

    // The active-set guess for a clearance that is free (|u| <= c): seated on the side the residual
    // pushes it to, with the wall law's stiffness at 1 um: r += k (u - side c) c, Kt += k c c^T.
    void close_free_clearances(const Vector& q, Vector& r, Matrix& Kt) const {
        for (const Clearance& cl : clearances_) {
            const double u = cl.gap(q);
            if (std::abs(u) > cl.spec().clearance) continue;
            const std::vector<int>& d = cl.dofs();
            const std::vector<double>& c = cl.coefficients();
            double push = 0.0;  // generalized load along +u
            for (std::size_t a = 0; a < d.size(); ++a) push -= c[a] * r[d[a]];
            const double side = push != 0.0 ? (push > 0.0 ? 1.0 : -1.0) : (u < 0.0 ? -1.0 : 1.0);
            const double k = cl.spec().wall(1e-6, 0.0).stiffness;
            for (std::size_t a = 0; a < d.size(); ++a) {
                r[d[a]] += k * (u - side * cl.spec().clearance) * c[a];
                for (std::size_t b = 0; b < d.size(); ++b) Kt(d[a], d[b]) += k * c[a] * c[b];
            }
        }
    }

    // d q_static / dt at (theta, q): Kt dq/dt = -(d r / dt at fixed q), the time-only terms' rates.
    Vector quasi_static_velocity(double theta, const Vector& q) const {
        const Workspace w = workspace_at(theta);
        Vector r(n_);
        Matrix Kt(n_, n_);
        static_residual(w, q, r, Kt);
        Vector rate = Vector::Zero(n_);
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            const ContactResponse f = contacts_[i].spec().law(ContactPair::penetration(c, q), 0.0);
            double delta_rate = c.delta0_dot;  // d delta / dt at fixed q
            for (int a = 0; a < c.count; ++a) delta_rate += c.g_dot[a] * q[c.dof[a]];
            for (int a = 0; a < c.count; ++a)
                rate[c.dof[a]] += f.stiffness * delta_rate * c.g[a] + f.force * c.g_dot[a] - c.p_dot[a];
            // The moment arm's own rate is left out (a start close to, not exactly at, quasi-statics).
            if (c.twist >= 0) rate[c.twist] += f.stiffness * delta_rate * c.moment_arm;
        }
        if (rate.isZero(0.0)) return Vector::Zero(n_);
        Vector dq(n_);
        if (!solve_static(Kt, rate, dq)) return Vector::Zero(n_);  // not held statically: start at rest
        return -dq;
    }

    Matrix closed_contact_stiffness(const Workspace& w) const {
        Matrix Kc = Matrix::Zero(n_, n_);
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            const double k = contacts_[i].spec().law(1e-6, 0.0).stiffness;
            for_each_gradient(c, [&](int a, double ga) {
                for_each_gradient(c, [&](int b, double gb) { Kc(a, b) += k * ga * gb; });
            });
        }
        return Kc;
    }

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
        for (std::size_t i = 0; i < contacts_.size(); ++i) {
            const ContactTerms& c = w.terms[i];
            const ContactResponse& r = w.last[i];
            if (!r.in_contact || (r.stiffness == 0.0 && r.damping == 0.0)) continue;
            const double a = cq * r.stiffness + cv * r.damping, b = cq * r.damping;
            sink.start_column();
            for (int k = 0; k < c.count; ++k) sink.add(c.dof[k], c.g[k], a * c.g[k] + b * c.g_dot[k]);
            // d delta / d q_twist = moment arm; d delta' / d q_twist ~ g_theta . v (the arm's own rate
            // and F d2 delta / d theta2 are left out: a quasi-Newton tangent, the residual is exact).
            if (c.twist >= 0) sink.add(c.twist, c.moment_arm, a * c.moment_arm + b * twist_rate_term(c, v));
        }
        for (std::size_t i = 0; i < clearances_.size(); ++i) {
            const Clearance& cl = clearances_[i];
            const ClearanceResponse& r = w.last_clearance[i];
            if (r.side == 0 || (r.wall.stiffness == 0.0 && r.wall.damping == 0.0)) continue;
            const std::vector<int>& dofs = cl.dofs();
            const std::vector<double>& c = cl.coefficients();
            // Normal: c (cq N_delta + cv N_rate) c^T.
            const double a = cq * r.wall.stiffness + cv * r.wall.damping;
            sink.start_column();
            for (std::size_t j = 0; j < dofs.size(); ++j) sink.add(dofs[j], c[j], a * c[j]);
            if (!cl.has_friction()) continue;
            // Friction row w: mu T sign(u) (cq N_delta + cv N_rate) c^T + cv mu N T' e_w^T.
            const double mu = cl.spec().friction;
            sink.start_column();
            sink.add(cl.sliding(), 1.0, cv * mu * r.wall.force * r.dslip);
            for (std::size_t j = 0; j < dofs.size(); ++j) sink.add(dofs[j], 0.0, mu * r.slip * r.side * a * c[j]);
        }
    }

    // The terms of twisting-camshaft contact i at time t, displacement q and twist rate v_twist:
    // theta = omega t + phase + q_twist, and the moment arm d delta / d theta at q.
    void twist_terms(double t, std::size_t i, const Vector& q, double v_twist, ContactTerms& c) const {
        const ContactPair& pair = contacts_[i];
        const double omega = spec_.camshaft_speed;
        pair.evaluate(omega * t + pair.spec().phase + q[pair.twist()], omega + v_twist, c);
        double arm = c.delta0_theta;
        for (int k = 0; k < c.count; ++k) arm += c.g_theta[k] * q[c.dof[k]];
        c.moment_arm = arm;
    }
    // d delta' / d q_twist without the arm's own rate: g_theta . v.
    static double twist_rate_term(const ContactTerms& c, const Vector& v) {
        double d = 0.0;
        for (int k = 0; k < c.count; ++k) d += c.g_theta[k] * v[c.dof[k]];
        return d;
    }
    // f(dof, d delta / d q_dof) over the pair's gradient, the twist included.
    template <class F>
    static void for_each_gradient(const ContactTerms& c, F&& f) {
        for (int k = 0; k < c.count; ++k) f(c.dof[k], c.g[k]);
        if (c.twist >= 0) f(c.twist, c.moment_arm);
    }

    // x = A^-1 b for a static analysis: dense full-pivoting LU up to dense_static_limit DOFs, sparse LU
    // above. False when A is singular; x is then the direction that is not held (a null vector).
    static constexpr int dense_static_limit = 200;
    bool solve_static(const Matrix& A, const Vector& b, Vector& x) const {
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
    // The DOFs that dominate a direction not held in place (at least a tenth of its largest entry).
    std::string unconstrained_dofs(const Vector& direction) const {
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
    Eigen::SparseMatrix<double> M_sparse_, C_sparse_, K_sparse_;
    Vector load_, initial_, initial_velocity_;
    std::vector<ContactPair> contacts_;
    std::vector<Clearance> clearances_;
    int max_rank_ = 0;
    std::vector<std::string> warnings_;
};

}  // namespace camfollower
