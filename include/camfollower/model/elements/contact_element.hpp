// SPDX-License-Identifier: BSD-3-Clause
// A cam-follower contact pair (contact/contact_pair.hpp) as an element of a Mechanism (the contract in
// model/element_set.hpp): force, tangent, channels, events and statics of one unilateral Hertz
// contact, on a rigid camshaft (time-only terms prepared once per step) or a twisting one (the cam
// angle adds the shaft's twist, a state: the terms are re-evaluated at every force). A grooved cam
// (contact/groove.hpp) adds its outer flank: a second unilateral contact on the same terms, pushing
// the other way, with its own channels (<name>.outer_force, ...) and event (<name>.outer_contact).
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "camfollower/contact/contact_pair.hpp"
#include "camfollower/model/mechanism_builder.hpp"
#include "camfollower/structure/network.hpp"

namespace camfollower {

class ContactElement : public ContactPair {
public:
    using Spec = ContactPairSpec;
    struct State {
        ContactTerms terms;    // time-only terms (on a twisting camshaft, at the last force's q)
        ContactResponse last;  // of the last add_force, reused by add_tangent, events and accepted
        ContactResponse outer{0.0, 0.0, 0.0, false, 0.0};  // a groove's outer flank, likewise
        bool started = false;                              // accepted() has taken the initial side
        bool in_contact = true;
        double loss_start = 0.0;
        std::vector<std::pair<double, double>> losses;  // contact-loss intervals [start, end), s
    };
    static const std::vector<Spec>& specs(const MechanismBuilder& b) { return b.contacts; }

    ContactElement(const Spec& c, const NetworkSpec& net, const SpeedProgram& drive)
        : ContactPair(c, net.index(c.cam_x, who(c) + " cam_x"), net.index(c.cam_y, who(c) + " cam_y"),
                      net.index(c.follower_dof, who(c) + " follower_dof"), net.index(c.lateral, who(c) + " lateral"),
                      net.index(c.cam_twist, who(c) + " cam_twist"),
                      net.index(c.paper_backlash.guide_dof, who(c) + " paper_backlash.guide_dof")),
          drive_(drive) {}

    int max_rank() const { return 1; }
    std::vector<int> tangent_dofs() const {
        std::vector<int> d = dofs();
        if (twist() >= 0) d.push_back(twist());
        return d;
    }

    void prepare(double t, State& s) const {
        if (twist() < 0) ContactPair::prepare(t, drive_, s.terms);
    }
    template <class Vector>
    void add_force(double t, const Vector& q, const Vector& v, State& s, Vector& f) const {
        ContactTerms& c = s.terms;
        if (twist() >= 0) twist_terms(t, q, v[twist()], c);
        const double rate = penetration_rate(c, q, v);
        s.last = spec().law(penetration(c, q), rate);
        double F = s.last.force;
        if (grooved()) {
            s.outer = outer_response(s.last, rate);
            F -= s.outer.force;
        }
        if (c.loaded)
            for (int k = 0; k < c.count; ++k) f[c.dof[k]] -= c.p[k];
        if (F == 0.0) return;
        for (int k = 0; k < c.count; ++k) f[c.dof[k]] += F * c.g[k];
        if (c.twist >= 0) f[c.twist] += F * c.moment_arm;
    }
    template <class Vector, class Sink>
    void add_tangent(const State& s, const Vector& v, double cq, double cv, Sink& sink) const {
        const ContactTerms& c = s.terms;
        // The outer flank's force -F_o g with delta_o = -delta - c has the inner one's tangent form.
        double stiffness = s.last.in_contact ? s.last.stiffness : 0.0;
        double damping = s.last.in_contact ? s.last.damping : 0.0;
        if (s.outer.in_contact) stiffness += s.outer.stiffness, damping += s.outer.damping;
        if (stiffness == 0.0 && damping == 0.0) return;
        const double a = cq * stiffness + cv * damping, b = cq * damping;
        sink.start_column();
        for (int k = 0; k < c.count; ++k) sink.add(c.dof[k], c.g[k], a * c.g[k] + b * c.g_dot[k]);
        // d delta / d q_twist = moment arm; d delta' / d q_twist ~ g_theta . v (the arm's own rate
        // and F d2 delta / d theta2 are left out: a quasi-Newton tangent, the residual is exact).
        if (c.twist >= 0) sink.add(c.twist, c.moment_arm, a * c.moment_arm + b * twist_rate_term(c, v));
    }
    // The contact-loss intervals switch at the instants the stepper located (event_located), not at
    // step ends: they then agree with the run's events whatever the method and step, and a step that
    // ends a rounding error on the wrong side of a located crossing starts no sliver of an interval.
    // accepted() takes the initial side only.
    void accepted(double t, State& s) const {
        if (s.started) return;
        s.started = true;
        s.in_contact = s.last.in_contact;
        if (!s.in_contact) s.loss_start = t;
    }
    int event_count() const { return grooved() ? 2 : 1; }
    void event_located(State& s, int which, double time, int direction) const {
        if (which == 1) return;  // the outer flank: its instants are the run's events
        if (direction < 0 && s.in_contact) s.in_contact = false, s.loss_start = time;
        else if (direction > 0 && !s.in_contact) s.in_contact = true, s.losses.emplace_back(s.loss_start, time);
    }

    // <name>.force (N), .penetration (m), .stiffness (dF/d delta, N/m), .pressure_angle (rad),
    // .cam_angle (rad, with the shaft's twist), .in_contact (0/1); on a twisting camshaft also
    // .cam_torque (N m: the contact's moment about the shaft axis against the cam's rotation); in a
    // groove also the inner flank's .penetration_rate (m/s: at a flank's contact event, the impact
    // velocity, with the outer flank's sign reversed) and the outer flank's .outer_force (N),
    // .outer_penetration (m), .outer_in_contact (0/1).
    void add_channel_names(std::vector<std::string>& names) const {
        for (const char* s : {".force", ".penetration", ".stiffness", ".pressure_angle", ".cam_angle", ".in_contact"})
            names.push_back(name() + s);
        if (twist() >= 0) names.push_back(name() + ".cam_torque");
        if (grooved())
            for (const char* s : {".penetration_rate", ".outer_force", ".outer_penetration", ".outer_in_contact"})
                names.push_back(name() + s);
    }
    // The torque (N m) the camshaft must give this cam, (F - F_outer) d delta / d theta, and its power
    // (W) at the cam's speed (the drive's, plus the twist rate on a twisting camshaft): observe() adds
    // them to `drive` (the mechanism's drive channels) from the response it computes anyway.
    struct DriveLoad {
        double torque = 0.0, power = 0.0;
    };
    template <class Vector>
    double* observe(double t, const State& s, const Vector& q, const Vector& v, double* out,
                    DriveLoad* drive = nullptr) const {
        const ContactTerms& c = s.terms;
        const double rate = penetration_rate(c, q, v);
        const ContactResponse r = spec().law(penetration(c, q), rate);
        *out++ = r.force;
        *out++ = penetration(c, q);
        *out++ = r.stiffness;
        *out++ = std::atan2(c.sin_alpha, c.cos_alpha);
        *out++ = c.theta;
        *out++ = r.in_contact ? 1.0 : 0.0;
        const ContactResponse o = grooved() ? outer_response(r, rate) : ContactResponse{0.0, 0.0, 0.0, false, 0.0};
        if (c.twist >= 0) *out++ = (r.force - o.force) * c.moment_arm;
        if (grooved()) {
            *out++ = rate;
            *out++ = o.force;
            *out++ = o.delta;
            *out++ = o.in_contact ? 1.0 : 0.0;
        }
        const double force = r.force - o.force;
        if (drive && force != 0.0) {
            const double torque = force * moment_arm(c, q);
            drive->torque += torque;
            drive->power += torque * (drive_.rate(t) + (c.twist >= 0 ? v[c.twist] : 0.0));
        }
        return out;
    }

    // <name>.contact: the penetration (m), > 0 in contact; in a groove <name>.outer_contact likewise.
    void add_event_names(std::vector<std::string>& names) const {
        names.push_back(name() + ".contact");
        if (grooved()) names.push_back(name() + ".outer_contact");
    }
    double* event_values(const State& s, double* g) const {
        *g++ = s.last.delta;
        if (grooved()) *g++ = s.outer.delta;
        return g;
    }

    // r += F(delta, 0) g - p, Kt += k g g^T at rest.
    template <class Vector, class Matrix>
    void add_static(double t, const Vector& q, State& s, Vector& r, Matrix& Kt) const {
        ContactTerms& c = s.terms;
        if (twist() >= 0) twist_terms(t, q, 0.0, c);
        const Static f = at_rest(c, q);
        for (int a = 0; a < c.count; ++a) r[c.dof[a]] += f.force * c.g[a] - c.p[a];
        if (c.twist >= 0) r[c.twist] += f.force * c.moment_arm;
        for_each_gradient(c, [&](int a, double ga) {
            for_each_gradient(c, [&](int b, double gb) { Kt(a, b) += f.stiffness * ga * gb; });
        });
    }
    // As if closed: the law's stiffness at 1 um on g g^T (a follower held only by its contact starts
    // just touching, where the law has no stiffness).
    template <class Vector, class Matrix>
    void add_active_set_guess(const State& s, const Vector&, Vector&, Matrix& Kt) const {
        const ContactTerms& c = s.terms;
        const double k = spec().law(1e-6, 0.0).stiffness;
        for_each_gradient(
            c, [&](int a, double ga) { for_each_gradient(c, [&](int b, double gb) { Kt(a, b) += k * ga * gb; }); });
    }
    // d r / dt at fixed q from the time-only terms' rates.
    template <class Vector>
    void add_quasi_static_rate(const State& s, const Vector& q, Vector& rate) const {
        const ContactTerms& c = s.terms;
        const Static f = at_rest(c, q);
        double delta_rate = c.delta0_dot;  // d delta / dt at fixed q
        for (int a = 0; a < c.count; ++a) delta_rate += c.g_dot[a] * q[c.dof[a]];
        for (int a = 0; a < c.count; ++a)
            rate[c.dof[a]] += f.stiffness * delta_rate * c.g[a] + f.force * c.g_dot[a] - c.p_dot[a];
        // The moment arm's own rate is left out (a start close to, not exactly at, quasi-statics).
        if (c.twist >= 0) rate[c.twist] += f.stiffness * delta_rate * c.moment_arm;
    }

    // --- queries ---
    // The contact force at rest at time t and displacement q, N; in a groove the inner flank's less
    // the outer's (< 0: the outer flank carries the roller).
    template <class Vector>
    double static_force(double t, const Vector& q, State& s) const {
        if (twist() >= 0) twist_terms(t, q, 0.0, s.terms);
        return at_rest(s.terms, q).force;
    }
    // The contact-loss intervals up to t_end (a loss still open at t_end ends there).
    static std::vector<std::pair<double, double>> losses_until(const State& s, double t_end) {
        std::vector<std::pair<double, double>> out = s.losses;
        if (!s.in_contact) out.emplace_back(s.loss_start, t_end);
        return out;
    }

private:
    static std::string who(const Spec& c) { return "contact '" + c.name + "'"; }

    // At rest (no penetration rate): the force along g (inner flank less outer) and d force / d delta.
    struct Static {
        double force, stiffness;
    };
    template <class Vector>
    Static at_rest(const ContactTerms& c, const Vector& q) const {
        const ContactResponse inner = spec().law(penetration(c, q), 0.0);
        if (!grooved()) return {inner.force, inner.stiffness};
        const ContactResponse outer = outer_response(inner, 0.0);
        return {inner.force - outer.force, inner.stiffness + outer.stiffness};
    }

    // The terms at time t, displacement q and twist rate v_twist: theta = drive angle + phase +
    // q_twist, and the moment arm d delta / d theta at q.
    template <class Vector>
    void twist_terms(double t, const Vector& q, double v_twist, ContactTerms& c) const {
        const DriveState d = drive_.at(t);
        evaluate(d.angle + spec().phase + q[twist()], d.rate + v_twist, c, d.acceleration);
        c.moment_arm = moment_arm(c, q);
    }
    // d delta / d theta at q: the contact force's moment arm about the shaft axis, m.
    template <class Vector>
    static double moment_arm(const ContactTerms& c, const Vector& q) {
        double arm = c.delta0_theta;
        for (int k = 0; k < c.count; ++k) arm += c.g_theta[k] * q[c.dof[k]];
        return arm;
    }
    // d delta' / d q_twist without the arm's own rate: g_theta . v.
    template <class Vector>
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

    SpeedProgram drive_;  // the camshaft's rotation
};

}  // namespace camfollower
