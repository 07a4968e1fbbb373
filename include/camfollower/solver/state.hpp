// SPDX-License-Identifier: BSD-3-Clause
// What every stepper shares: the integration State, the run's SolverStatistics, and the time scales
// of a system at a state (its natural frequencies, the error norms' reference rate).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "camfollower/constants.hpp"
#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"

namespace camfollower {

struct SolverStatistics {
    std::uint64_t steps = 0;              // accepted steps, substeps included
    std::uint64_t newton_iterations = 0;  // linear solves
    std::uint64_t halvings = 0;
    std::uint64_t evaluations = 0;     // adaptive methods: force evaluations
    std::uint64_t rejected_steps = 0;  // adaptive methods: steps retried smaller
    std::uint64_t stiff_steps = 0;     // explicit methods: steps bounded by stability, not accuracy
    int max_iterations_in_a_step = 0;
    double mean_iterations() const { return steps ? double(newton_iterations) / double(steps) : 0.0; }
    void add(const SolverStatistics& o) {
        steps += o.steps, newton_iterations += o.newton_iterations, halvings += o.halvings;
        evaluations += o.evaluations, rejected_steps += o.rejected_steps, stiff_steps += o.stiff_steps;
        max_iterations_in_a_step = std::max(max_iterations_in_a_step, o.max_iterations_in_a_step);
    }
};

// The integrator's state: time, displacement, velocity, acceleration, the nonlinear force at them
// (f(t, q, v) - p(t), needed by HHT) and the system's workspace (time terms prepared at t, path memory).
template <class System>
struct State {
    using Vector = typename System::Vector;
    double t = 0.0;
    Vector q, v, a, f;
    workspace_t<System> workspace;
};

// A user's initial displacement or velocity (`name`: "initial q" or "initial v"), refused entry by
// entry naming the DOF: finite, and a displacement within +-max_part_length (m, or rad for a twist).
template <class System>
void check_initial(const System& system, const std::optional<typename System::Vector>& x, const char* name,
                   bool displacement) {
    if (!x) return;
    if (x->size() != system.size())
        detail::fail(name, " must have ", system.size(), " entries (one per DOF), got ", x->size());
    const double bound = displacement ? detail::max_part_length : std::numeric_limits<double>::infinity();
    for (int k = 0; k < x->size(); ++k)
        if (!std::isfinite((*x)[k]) || std::abs((*x)[k]) > bound)
            detail::fail(name, "[", k, "] (", dof_names(system)[std::size_t(k)], ") must be ",
                         displacement ? detail::concat("in [", -bound, ", ", bound, "] (m, or rad for a twist)")
                                      : std::string("finite (m/s, or rad/s for a twist)"),
                         ", got ", (*x)[k]);
}

// A state at (t, q, v) with a fresh workspace prepared at t and the nonlinear force there; the
// acceleration is the stepper's to set. Refuses a non-finite time or state and a wrong size.
template <class System>
State<System> state_at(const System& system, double t, const typename System::Vector& q,
                       const typename System::Vector& v) {
    detail::require_finite(t, "start time");
    const int n = system.size();
    if (q.size() != n || v.size() != n)
        detail::fail("initial q and v must have size ", n, ", got ", q.size(), ", ", v.size());
    if (!q.allFinite() || !v.allFinite()) detail::fail("initial q and v must be finite");
    State<System> s;
    s.t = t, s.q = q, s.v = v;
    s.workspace = make_workspace(system);
    prepare(system, t, s.workspace);
    s.f.resize(n);
    nonlinear_force(system, s.workspace, s.q, s.v, s.f);
    s.a.resize(n);
    return s;
}

// Lowest (above rigid-body modes) and highest undamped natural angular frequencies (rad/s) of
// `system` with its contacts' tangent at state s (NaN when the eigen solve fails): the time scales a
// run has to resolve. Allocates; call once per run.
struct FrequencyRange {
    double lowest = std::numeric_limits<double>::quiet_NaN(), highest = std::numeric_limits<double>::quiet_NaN();
};
template <class System>
FrequencyRange natural_frequency_range(const System& system, const State<System>& s) {
    using Matrix = typename System::Matrix;
    LowRank<typename System::Vector> uv(system.size(), std::max(1, max_rank(system)));
    uv.clear();
    tangent(system, s.workspace, s.q, s.v, 1.0, 0.0, uv);
    const Matrix t = uv.U.leftCols(uv.rank) * uv.V.leftCols(uv.rank).transpose();
    const Matrix Kt = system.stiffness() + 0.5 * (t + t.transpose());
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> eig(Kt, system.mass(), Eigen::EigenvaluesOnly);
    FrequencyRange r;
    if (eig.info() != Eigen::Success) return r;
    const double top = std::max(eig.eigenvalues().maxCoeff(), 0.0);
    r.highest = std::sqrt(top);
    for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k)
        if (eig.eigenvalues()[k] > 1e-12 * top) {
            r.lowest = std::sqrt(eig.eigenvalues()[k]);
            break;
        }
    return r;
}
template <class System>
double highest_angular_frequency(const System& system, const State<System>& s) {
    return natural_frequency_range(system, s).highest;
}

// The rate (rad/s) setting the error norms' velocity reference (ErrorScales): 2 pi / period for a
// camshaft-driven system, else its lowest natural frequency at s, else 1 / time_step.
template <class System>
double reference_rate(const System& system, const State<System>& s, double time_step) {
    if constexpr (detail::has_period<System>::value) {
        return 2.0 * pi / system.period();
    } else {
        const double lowest = natural_frequency_range(system, s).lowest;
        return std::isfinite(lowest) ? lowest : 1.0 / time_step;
    }
}

}  // namespace camfollower
