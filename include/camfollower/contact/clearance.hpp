// SPDX-License-Identifier: BSD-3-Clause
// A radial clearance (a rod in a bushing of its guide): the gap coordinate u = sum_j c_j q_j (the
// rod's lateral displacement at the bushing, e.g. x + z tilt for a bushing at axial position z on a
// rod with a tilt DOF) moves freely for |u| <= c and meets a wall beyond:
//   delta = |u| - c,  normal force N = law(delta, sign(u) u')   (Hertz law with contact damping)
//   generalized force on the DOFs: -sign(u) N c_j  (pushes u back towards the centre)
// With a friction coefficient mu and a sliding DOF (the rod's axial coordinate w), regularized
// Coulomb friction mu N tanh(w' / v_slip) opposes the sliding while the rod touches the wall.
//
// Internal force f (core/system.hpp sign: M q'' + C q' + K q + f = p) and its tangent:
//   f_j += sign(u) N c_j,  f_w += mu N T,  T = tanh(w' / v_slip)
//   df/dq = N_delta c c^T + mu T sign(u) N_delta e_w c^T
//   df/dv = N_rate  c c^T + mu T sign(u) N_rate e_w c^T + mu N T' / v_slip e_w e_w^T
// i.e. rank one (normal) plus rank one (friction row), both low-rank updates of the Newton matrix.
#pragma once

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "camfollower/contact/hertz.hpp"
#include "camfollower/error.hpp"

namespace camfollower {

struct ClearanceSpec {
    std::string name;
    std::vector<std::pair<std::string, double>> gap;  // (DOF, coefficient): u = sum c_j q_j, m
    double clearance = 0.0;                           // radial gap c, m (> 0)
    HertzContact wall{2.5e8, 1.0, 0.0};               // wall contact law
    double friction = 0.0;                            // Coulomb coefficient mu (>= 0)
    std::string sliding_dof;                          // DOF sliding in the bushing (needed when mu > 0)
    double slip_velocity = 1e-3;                      // m/s: tanh regularization of the friction

    void validate() const {
        const std::string who = "clearance '" + name + "'";
        detail::require_name(name, "clearance");
        if (gap.empty()) detail::fail(who, ": the gap coordinate needs at least one (DOF, coefficient) term");
        for (std::size_t i = 0; i < gap.size(); ++i) {
            const auto& [dof, c] = gap[i];
            if (!std::isfinite(c) || c == 0.0)
                detail::fail(who, ": coefficient of DOF '", dof, "' must be finite and non-zero, got ", c);
            for (std::size_t j = 0; j < i; ++j)
                if (gap[j].first == dof) detail::fail(who, ": DOF '", dof, "' appears twice in the gap coordinate");
        }
        detail::require_positive(clearance, (who + " clearance").c_str(), "(m)");
        detail::require_positive(wall.stiffness, (who + " wall stiffness").c_str(), "(N/m^n)");
        detail::require_in_range(wall.exponent, 1.0, 3.0, (who + " wall exponent").c_str());
        detail::require_non_negative(wall.damping_factor, (who + " wall damping factor").c_str(), "(s/m)");
        detail::require_non_negative(friction, (who + " friction coefficient").c_str());
        if (friction > 0.0 && sliding_dof.empty())
            detail::fail(who, ": friction coefficient ", friction,
                         " > 0 needs the sliding DOF (the rod's axial coordinate)");
        for (const auto& term : gap)
            if (friction > 0.0 && term.first == sliding_dof)
                detail::fail(who, ": sliding_dof '", sliding_dof,
                             "' is also a DOF of the gap coordinate; the rod slides "
                             "along its axis, across the gap: each role needs a DOF of its own");
        detail::require_positive(slip_velocity, (who + " slip velocity").c_str(), "(m/s)");
    }
};

// A guide of length `length` holding a rod at one or two bushings (axial positions measured from the
// guide's end nearest the cam, 0 <= z <= length). One bushing: the gap coordinate is the rod's
// lateral DOF. Two: each bushing sees lateral + (z - reference) tilt, the rod's tilt DOF in rad about
// the axial position `tilt_reference` (where the lateral DOF is measured).
struct GuideSpec {
    std::string name;
    std::string lateral_dof, tilt_dof, sliding_dof;
    double length = 0.0;           // m
    std::vector<double> bushings;  // axial positions, m (one or two)
    double tilt_reference = 0.0;   // m, where lateral_dof is measured
    double clearance = 0.0;        // radial, m
    HertzContact wall{2.5e8, 1.0, 0.0};
    double friction = 0.0;
    double slip_velocity = 1e-3;

    std::vector<ClearanceSpec> clearances() const {
        const std::string who = "guide '" + name + "'";
        detail::require_positive(length, (who + " length").c_str(), "(m)");
        if (bushings.empty() || bushings.size() > 2)
            detail::fail(who, ": give one or two bushing positions, got ", bushings.size());
        if (bushings.size() == 2 && tilt_dof.empty())
            detail::fail(who, ": two bushings need the rod's tilt DOF (tilt_dof)");
        if (bushings.size() == 2 && bushings[0] == bushings[1]) detail::fail(who, ": the two bushings coincide");
        std::vector<ClearanceSpec> out;
        for (std::size_t i = 0; i < bushings.size(); ++i) {
            const double z = bushings[i];
            if (!(z >= 0.0 && z <= length))
                detail::fail(who, ": bushing position ", z, " m must lie in the guide, [0, ", length, "] m");
            ClearanceSpec c{name + (bushings.size() == 2 ? (i == 0 ? ".bushing1" : ".bushing2") : ""),
                            {{lateral_dof, 1.0}},
                            clearance,
                            wall,
                            friction,
                            sliding_dof,
                            slip_velocity};
            if (!tilt_dof.empty() && z != tilt_reference) c.gap.emplace_back(tilt_dof, z - tilt_reference);
            out.push_back(std::move(c));
        }
        return out;
    }
};

// The state of one clearance at (q, v): what force() computes and tangent()/observe() reuse.
struct ClearanceResponse {
    double u = 0.0;                                   // gap coordinate, m
    int side = 0;                                     // -1, 0 (free), +1
    ContactResponse wall{0.0, 0.0, 0.0, false, 0.0};  // normal force magnitude and its derivatives
    double slip = 0.0;                                // tanh(w' / v_slip)
    double dslip = 0.0;                               // d slip / d w'
};

// A clearance with its DOFs resolved to indices.
class Clearance {
public:
    Clearance(ClearanceSpec spec, std::vector<int> dofs, int sliding)
        : spec_(std::move(spec)), dofs_(std::move(dofs)), sliding_(sliding) {
        for (const auto& term : spec_.gap) coefficients_.push_back(term.second);
    }
    const ClearanceSpec& spec() const { return spec_; }
    const std::string& name() const { return spec_.name; }
    const std::vector<int>& dofs() const { return dofs_; }
    const std::vector<double>& coefficients() const { return coefficients_; }
    int sliding() const { return sliding_; }
    bool has_friction() const { return spec_.friction > 0.0; }

    template <class Vector>
    double gap(const Vector& x) const {
        double u = 0.0;
        for (std::size_t j = 0; j < dofs_.size(); ++j) u += coefficients_[j] * x[dofs_[j]];
        return u;
    }

    // At rest (static == true) the wall law sees no penetration rate and the friction no sliding.
    template <class Vector>
    ClearanceResponse response(const Vector& q, const Vector& v, bool at_rest = false) const {
        ClearanceResponse r;
        r.u = gap(q);
        const double delta = std::abs(r.u) - spec_.clearance;
        if (!(delta > 0.0)) return r;
        r.side = r.u > 0.0 ? 1 : -1;
        r.wall = spec_.wall(delta, at_rest ? 0.0 : r.side * gap(v));
        if (has_friction() && !at_rest) {
            const double x = v[sliding_] / spec_.slip_velocity;
            r.slip = std::tanh(x);
            r.dslip = (1.0 - r.slip * r.slip) / spec_.slip_velocity;
        }
        return r;
    }

    // f += the clearance's internal force.
    template <class Vector>
    void add_force(const ClearanceResponse& r, Vector& f) const {
        if (r.wall.force == 0.0) return;
        for (std::size_t j = 0; j < dofs_.size(); ++j) f[dofs_[j]] += r.side * r.wall.force * coefficients_[j];
        if (has_friction()) f[sliding_] += spec_.friction * r.wall.force * r.slip;
    }

    // Rank of the tangent when touching: 1 (normal) + 1 (friction).
    int max_rank() const { return has_friction() ? 2 : 1; }

private:
    ClearanceSpec spec_;
    std::vector<int> dofs_;
    std::vector<double> coefficients_;
    int sliding_;
};

}  // namespace camfollower
