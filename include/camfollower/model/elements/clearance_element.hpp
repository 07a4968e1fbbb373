// SPDX-License-Identifier: BSD-3-Clause
// A radial clearance (contact/clearance.hpp) as an element of a Mechanism (the contract in
// model/element_set.hpp): a gap coordinate u = c . q free within +-c, a unilateral wall law beyond
// it, and optional regularized Coulomb friction on a sliding DOF.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "camfollower/contact/clearance.hpp"
#include "camfollower/motion/speed_program.hpp"
#include "camfollower/model/mechanism_builder.hpp"
#include "camfollower/structure/network.hpp"

namespace camfollower {

class ClearanceElement : public Clearance {
public:
    using Spec = ClearanceSpec;
    struct State {
        ClearanceResponse last;  // of the last add_force, reused by add_tangent and events
    };
    static const std::vector<Spec>& specs(const MechanismBuilder& b) { return b.clearances; }

    ClearanceElement(const Spec& c, const NetworkSpec& net, const SpeedProgram&)
        : Clearance(c, gap_dofs(c, net), sliding_dof(c, net)) {}

    using Clearance::max_rank;
    std::vector<int> tangent_dofs() const {
        std::vector<int> d = dofs();
        if (has_friction()) d.push_back(sliding());
        return d;
    }

    void prepare(double, State&) const {}
    template <class Vector>
    void add_force(double, const Vector& q, const Vector& v, State& s, Vector& f) const {
        s.last = response(q, v);
        Clearance::add_force(s.last, f);
    }
    template <class Vector, class Sink>
    void add_tangent(const State& s, const Vector&, double cq, double cv, Sink& sink) const {
        const ClearanceResponse& r = s.last;
        if (r.side == 0 || (r.wall.stiffness == 0.0 && r.wall.damping == 0.0)) return;
        const std::vector<int>& d = dofs();
        const std::vector<double>& c = coefficients();
        // Normal: c (cq N_delta + cv N_rate) c^T.
        const double a = cq * r.wall.stiffness + cv * r.wall.damping;
        sink.start_column();
        for (std::size_t j = 0; j < d.size(); ++j) sink.add(d[j], c[j], a * c[j]);
        if (!has_friction()) return;
        // Friction row w: mu T sign(u) (cq N_delta + cv N_rate) c^T + cv mu N T' e_w^T.
        const double mu = spec().friction;
        sink.start_column();
        sink.add(sliding(), 1.0, cv * mu * r.wall.force * r.dslip);
        for (std::size_t j = 0; j < d.size(); ++j) sink.add(d[j], 0.0, mu * r.slip * r.side * a * c[j]);
    }
    void accepted(double, State&) const {}
    int event_count() const { return 1; }
    void event_located(State&, int, double, int) const {}

    // <name>.force (wall force, N, >= 0), .side (-1, 0 free, +1), .gap (u, m), .friction (N, along
    // +sliding DOF on the rod).
    void add_channel_names(std::vector<std::string>& names) const {
        for (const char* s : {".force", ".side", ".gap", ".friction"}) names.push_back(name() + s);
    }
    template <class Vector>
    double* observe(double, const State&, const Vector& q, const Vector& v, double* out) const {
        const ClearanceResponse r = response(q, v);
        *out++ = r.wall.force;
        *out++ = r.side;
        *out++ = r.u;
        *out++ = has_friction() ? -spec().friction * r.wall.force * r.slip : 0.0;
        return out;
    }
    // <name>.wall: |u| - c (m), > 0 while touching.
    void add_event_names(std::vector<std::string>& names) const { names.push_back(name() + ".wall"); }
    double* event_values(const State& s, double* g) const {
        *g++ = std::abs(s.last.u) - spec().clearance;
        return g;
    }

    template <class Vector, class Matrix>
    void add_static(double, const Vector& q, State&, Vector& r, Matrix& Kt) const {
        const ClearanceResponse f = response(q, q, true);
        Clearance::add_force(f, r);
        const std::vector<int>& d = dofs();
        const std::vector<double>& c = coefficients();
        for (std::size_t a = 0; a < d.size(); ++a)
            for (std::size_t b = 0; b < d.size(); ++b) Kt(d[a], d[b]) += f.wall.stiffness * c[a] * c[b];
    }
    // A free clearance (|u| <= c) seated on the side the residual pushes it to, with the wall law's
    // stiffness at 1 um: r += k (u - side c) c, Kt += k c c^T.
    template <class Vector, class Matrix>
    void add_active_set_guess(const State&, const Vector& q, Vector& r, Matrix& Kt) const {
        const double u = gap(q);
        if (std::abs(u) > spec().clearance) return;
        const std::vector<int>& d = dofs();
        const std::vector<double>& c = coefficients();
        double push = 0.0;  // generalized load along +u
        for (std::size_t a = 0; a < d.size(); ++a) push -= c[a] * r[d[a]];
        const double side = push != 0.0 ? (push > 0.0 ? 1.0 : -1.0) : (u < 0.0 ? -1.0 : 1.0);
        const double k = spec().wall(1e-6, 0.0).stiffness;
        for (std::size_t a = 0; a < d.size(); ++a) {
            r[d[a]] += k * (u - side * spec().clearance) * c[a];
            for (std::size_t b = 0; b < d.size(); ++b) Kt(d[a], d[b]) += k * c[a] * c[b];
        }
    }
    // No time-only terms.
    template <class Vector>
    void add_quasi_static_rate(const State&, const Vector&, Vector&) const {}

private:
    static std::vector<int> gap_dofs(const Spec& c, const NetworkSpec& net) {
        c.validate();
        const std::string who = "clearance '" + c.name + "'";
        std::vector<int> dofs;
        for (const auto& term : c.gap) {
            dofs.push_back(net.index(term.first, who + " gap DOF"));
            if (dofs.back() < 0) detail::fail(who, ": the gap coordinate's DOFs must not be ground");
        }
        return dofs;
    }
    static int sliding_dof(const Spec& c, const NetworkSpec& net) {
        c.validate();  // whichever argument is evaluated first
        if (!(c.friction > 0.0)) return -1;
        const int sliding = net.index(c.sliding_dof, "clearance '" + c.name + "' sliding_dof");
        if (sliding < 0) detail::fail("clearance '", c.name, "': sliding_dof must be a DOF, not ground");
        return sliding;
    }
};

}  // namespace camfollower
