// SPDX-License-Identifier: BSD-3-Clause
// A pin joint (linkage/coupler_linkage.hpp) as an element of a Mechanism (the contract in
// model/element_set.hpp): two points of two links, each a function of a few DOFs
// (linkage/planar_point.hpp), pulled together by an isotropic spring-damper,
//   F = k d + c d',  d = p_a(q) - p_b(q),   f += J_a^T F - J_b^T F   (virtual work).
// Its tangent is k J^T J (two column pairs, one per plane direction) and the geometric stiffness
// F . d2p / d q_rot^2 on each rotation (one pair each); the rate of J in the damping force is left out
// of the tangent (a quasi-Newton tangent: the residual is exact).
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "camfollower/linkage/coupler_linkage.hpp"
#include "camfollower/model/mechanism_builder.hpp"
#include "camfollower/motion/speed_program.hpp"
#include "camfollower/structure/network.hpp"

namespace camfollower {

class PinJointElement {
public:
    using Spec = PinJointSpec;
    struct State {
        PlanarPoint::Value a, b;                          // of the last add_force
        Eigen::Vector2d force = Eigen::Vector2d::Zero();  // on end a, towards b: -F (N)
    };
    static const std::vector<Spec>& specs(const MechanismBuilder& b) { return b.pin_joints; }

    PinJointElement(const Spec& s, const NetworkSpec& net, const SpeedProgram&) : spec_(s) {
        spec_.validate();
        resolve(spec_.a, net, "end a", dofs_a_);
        resolve(spec_.b, net, "end b", dofs_b_);
        for (int i : dofs_a_)
            for (int j : dofs_b_)
                if (i >= 0 && i == j)
                    detail::fail("pin joint '", spec_.name, "': both ends move with DOF '",
                                 net.dofs()[std::size_t(i)].name, "'; a joint holds two different links together");
    }

    const std::string& name() const { return spec_.name; }
    const Spec& spec() const { return spec_; }
    int max_rank() const { return 4; }
    std::vector<int> tangent_dofs() const {
        std::vector<int> d;
        for (int i : dofs_a_)
            if (i >= 0) d.push_back(i);
        for (int i : dofs_b_)
            if (i >= 0) d.push_back(i);
        return d;
    }

    void prepare(double, State&) const {}
    template <class Vector>
    void add_force(double, const Vector& q, const Vector& v, State& s, Vector& f) const {
        const Eigen::Vector2d F = evaluate(q, &v, s);
        for (int i = 0; i < 3; ++i) {
            if (dofs_a_[i] >= 0) f[dofs_a_[i]] += s.a.dp[std::size_t(i)].dot(F);
            if (dofs_b_[i] >= 0) f[dofs_b_[i]] -= s.b.dp[std::size_t(i)].dot(F);
        }
    }
    template <class Vector, class Sink>
    void add_tangent(const State& s, const Vector&, double cq, double cv, Sink& sink) const {
        const double a = cq * spec_.stiffness + cv * spec_.damping;
        for (int r = 0; r < 2; ++r) {  // the rows of J = [J_a, -J_b]: k J^T J as two pairs
            sink.start_column();
            for (int i = 0; i < 3; ++i) {
                if (dofs_a_[i] >= 0) sink.add(dofs_a_[i], s.a.dp[std::size_t(i)][r], a * s.a.dp[std::size_t(i)][r]);
                if (dofs_b_[i] >= 0) sink.add(dofs_b_[i], -s.b.dp[std::size_t(i)][r], -a * s.b.dp[std::size_t(i)][r]);
            }
        }
        // F = k d + c d' at the last force; the geometric stiffness is -force . d2p (force = -F on a).
        const Eigen::Vector2d F = -s.force;
        add_geometric(spec_.a, dofs_a_, F.dot(s.a.d2p_rotation) * cq, sink);
        add_geometric(spec_.b, dofs_b_, -F.dot(s.b.d2p_rotation) * cq, sink);
    }
    void accepted(double, State&) const {}
    int event_count() const { return 0; }
    void event_located(State&, int, double, int) const {}

    // <name>.force (N, the magnitude of k d + c d'), .stretch (m, |d|: the joint's deflection).
    void add_channel_names(std::vector<std::string>& names) const {
        names.push_back(name() + ".force");
        names.push_back(name() + ".stretch");
    }
    template <class Vector>
    double* observe(double, const State&, const Vector& q, const Vector& v, double* out) const {
        State s;
        const Eigen::Vector2d F = evaluate(q, &v, s);
        *out++ = F.norm();
        *out++ = (s.a.p - s.b.p).norm();
        return out;
    }
    void add_event_names(std::vector<std::string>&) const {}
    double* event_values(const State&, double* g) const { return g; }

    template <class Vector, class Matrix>
    void add_static(double, const Vector& q, State& s, Vector& r, Matrix& Kt) const {
        const Eigen::Vector2d F = evaluate(q, static_cast<const Vector*>(nullptr), s);
        std::array<std::pair<int, Eigen::Vector2d>, 6> columns;
        int n = 0;
        for (int i = 0; i < 3; ++i) {
            if (dofs_a_[i] >= 0) columns[std::size_t(n++)] = {dofs_a_[i], s.a.dp[std::size_t(i)]};
            if (dofs_b_[i] >= 0) columns[std::size_t(n++)] = {dofs_b_[i], -s.b.dp[std::size_t(i)]};
        }
        for (int x = 0; x < n; ++x) {
            r[columns[std::size_t(x)].first] += columns[std::size_t(x)].second.dot(F);
            for (int y = 0; y < n; ++y)
                Kt(columns[std::size_t(x)].first, columns[std::size_t(y)].first) +=
                    spec_.stiffness * columns[std::size_t(x)].second.dot(columns[std::size_t(y)].second);
        }
        const int ra = spec_.a.rotation_slot(), rb = spec_.b.rotation_slot();
        if (ra >= 0 && dofs_a_[ra] >= 0) Kt(dofs_a_[ra], dofs_a_[ra]) += F.dot(s.a.d2p_rotation);
        if (rb >= 0 && dofs_b_[rb] >= 0) Kt(dofs_b_[rb], dofs_b_[rb]) -= F.dot(s.b.d2p_rotation);
    }
    template <class Vector, class Matrix>
    void add_active_set_guess(const State&, const Vector&, Vector&, Matrix&) const {}
    template <class Vector>
    void add_quasi_static_rate(const State&, const Vector&, Vector&) const {}

private:
    static void resolve(const PlanarPoint& p, const NetworkSpec& net, const char* end, std::array<int, 3>& dofs) {
        dofs = {-1, -1, -1};
        for (int i = 0; i < p.dof_count(); ++i)
            dofs[std::size_t(i)] = net.index(p.dofs[std::size_t(i)], std::string("pin joint ") + end + " DOF");
    }
    // k d + c d' at q (and v; none: at rest), the points cached in s.
    template <class Vector>
    Eigen::Vector2d evaluate(const Vector& q, const Vector* v, State& s) const {
        std::array<double, 3> xa{}, xb{};
        for (int i = 0; i < 3; ++i) {
            if (dofs_a_[i] >= 0) xa[std::size_t(i)] = q[dofs_a_[i]];
            if (dofs_b_[i] >= 0) xb[std::size_t(i)] = q[dofs_b_[i]];
        }
        s.a = spec_.a.at(xa);
        s.b = spec_.b.at(xb);
        Eigen::Vector2d F = spec_.stiffness * (s.a.p - s.b.p);
        if (v && spec_.damping != 0.0) {
            Eigen::Vector2d rate = Eigen::Vector2d::Zero();
            for (int i = 0; i < 3; ++i) {
                if (dofs_a_[i] >= 0) rate += s.a.dp[std::size_t(i)] * (*v)[dofs_a_[i]];
                if (dofs_b_[i] >= 0) rate -= s.b.dp[std::size_t(i)] * (*v)[dofs_b_[i]];
            }
            F += spec_.damping * rate;
        }
        s.force = -F;
        return F;
    }
    template <class Sink>
    static void add_geometric(const PlanarPoint& p, const std::array<int, 3>& dofs, double value, Sink& sink) {
        const int slot = p.rotation_slot();
        if (slot < 0 || dofs[std::size_t(slot)] < 0 || value == 0.0) return;
        sink.start_column();
        sink.add(dofs[std::size_t(slot)], 1.0, value);
    }

    PinJointSpec spec_;
    std::array<int, 3> dofs_a_{}, dofs_b_{};
};

}  // namespace camfollower
