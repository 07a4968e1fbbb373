// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the lift synthesis measures on a mechanism (docs/synthesis.md): one revolution of its periodic
// steady state reduced to the samples its objective squares or bounds, and the response its limits
// hold (the contact force, the output's acceleration). camfollower.synthesis (Python) drives its
// optimizer with these functions; a C++ design loop calls evaluate_lift() on each candidate.
//
// The output is any DOF. Its quasi-static path is the mechanism's static equilibrium on the cam as it
// is (springs, preloads, loads, eccentricity, profile error), so a defect's own lift of the follower
// is not counted as vibration.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "camfollower/constants.hpp"
#include "camfollower/contact/contact_pair.hpp"
#include "camfollower/error.hpp"
#include "camfollower/motion/program.hpp"
#include "camfollower/solver/simulate.hpp"

namespace camfollower::synthesis {

// What the objective measures on the output DOF.
enum class LiftObjective {
    residual,        // the output less its quasi-static path, in the contact's dwells
    follower_error,  // the same over the whole revolution
    acceleration,    // the output's acceleration over the revolution
};

inline const char* lift_objective_name(LiftObjective o) {
    switch (o) {
        case LiftObjective::residual: return "residual";
        case LiftObjective::follower_error: return "follower_error";
        case LiftObjective::acceleration: return "acceleration";
    }
    return "?";
}

inline LiftObjective lift_objective(const std::string& name) {
    for (LiftObjective o : {LiftObjective::residual, LiftObjective::follower_error, LiftObjective::acceleration})
        if (name == lift_objective_name(o)) return o;
    detail::fail("objective must be one of acceleration, follower_error, residual, got '", name, "'");
}

// Static equilibria per revolution the quasi-static path interpolates (every 0.5 deg).
inline constexpr int quasi_static_angles = 720;

// The program's dwells as [start, end) cam angles (rad): the segments that keep their lift.
inline std::vector<std::pair<double, double>> dwell_windows(const MotionProgram& program) {
    std::vector<std::pair<double, double>> out;
    for (const Segment& s : program.segments())
        if (s.h_end == s.h_start && s.theta_end > s.theta_start) out.emplace_back(s.theta_start, s.theta_end);
    return out;
}

// The DOF's static equilibrium at the shaft angles theta (rad, in [0, 2 pi]): solved at `angles` equally
// spaced angles and interpolated linearly, periodically (constant in a dwell, as the equilibrium is;
// off by up to max|h''| (2 pi / angles)^2 / 8 in a move), or with angles = 0 solved at every theta.
// Throws where the mechanism has no static equilibrium (a follower no spring holds on its cam).
template <class System>
std::vector<double> quasi_static_path(const System& m, int dof, const std::vector<double>& theta,
                                      int angles = quasi_static_angles) {
    if (dof < 0 || dof >= m.size())
        detail::fail("quasi_static_path: dof index ", dof, " is not in [0, ", m.size(), ")");
    if (angles == 0) {
        std::vector<double> exact(theta.size());
        for (std::size_t i = 0; i < theta.size(); ++i) exact[i] = m.static_equilibrium(theta[i])[dof];
        return exact;
    }
    if (angles < 2) detail::fail("quasi_static_path: angles must be 0 (every theta) or >= 2, got ", angles);
    std::vector<double> path(std::size_t(angles) + 1);
    for (int k = 0; k < angles; ++k) path[std::size_t(k)] = m.static_equilibrium(two_pi * k / angles)[dof];
    path.back() = path.front();
    const double step = two_pi / angles;
    std::vector<double> out(theta.size());
    for (std::size_t i = 0; i < theta.size(); ++i) {
        const double x = std::clamp(theta[i], 0.0, two_pi) / step;
        const int k = std::min(int(x), angles - 1);
        const double f = x - k;
        out[i] = (1.0 - f) * path[std::size_t(k)] + f * path[std::size_t(k) + 1];
    }
    return out;
}

// The largest peak-to-peak over one dwell and the rms over all dwells of `moving` sampled at the
// contact's cam angles `cam` (rad, in [0, 2 pi)).
struct DwellResidual {
    double peak_to_peak = 0.0;
    double rms = 0.0;
    std::size_t samples = 0;
};

inline DwellResidual dwell_residual(const std::vector<std::pair<double, double>>& dwells,
                                    const std::vector<double>& cam, const std::vector<double>& moving) {
    if (cam.size() != moving.size())
        detail::fail("dwell_residual: ", cam.size(), " cam angles but ", moving.size(), " samples");
    DwellResidual r;
    double squares = 0.0;
    for (const auto& [a, b] : dwells) {
        double lo = INFINITY, hi = -INFINITY;
        std::size_t n = 0;
        for (std::size_t i = 0; i < cam.size(); ++i)
            if (cam[i] >= a && cam[i] < b) lo = std::min(lo, moving[i]), hi = std::max(hi, moving[i]), ++n;
        if (n > 1) r.peak_to_peak = std::max(r.peak_to_peak, hi - lo);
        for (std::size_t i = 0; i < cam.size(); ++i)
            if (cam[i] >= a && cam[i] < b) squares += moving[i] * moving[i], ++r.samples;
    }
    r.rms = r.samples ? std::sqrt(squares / double(r.samples)) : 0.0;
    return r;
}

// One recorded revolution, reduced. Inputs per sample: the shaft angle theta (rad, from 0), the output's
// displacement q and acceleration a, the contact's force.
struct LiftSamples {
    std::vector<double> theta;       // shaft angle of each kept sample (rad)
    std::vector<double> values;      // the objective's samples (residual: the dwells' only)
    DwellResidual dwells;            // the output less its quasi-static path, over the dwells
    double min_force = NAN;          // N: the contact force's least (NaN for a grooved contact)
    double peak_acceleration = 0.0;  // the output's largest |acceleration|
};

// `dwells`: the windows the residual is measured in (default: the contact's program's; a synthesis
// measures a candidate drawn without dwells in its reference program's).
template <class System>
LiftSamples lift_samples(const System& m, std::size_t contact, int output, LiftObjective objective,
                         const std::vector<double>& theta, const std::vector<double>& q, const std::vector<double>& a,
                         const std::vector<double>& force,
                         const std::optional<std::vector<std::pair<double, double>>>& dwells_of = std::nullopt) {
    const auto& contacts = m.contacts();
    if (contact >= contacts.size())
        detail::fail("lift_samples: contact index ", contact, " is not in [0, ", contacts.size(), ")");
    if (q.size() != theta.size() || a.size() != theta.size() || force.size() != theta.size())
        detail::fail("lift_samples: theta, q, a and force must have one value per sample, got ", theta.size(), ", ",
                     q.size(), ", ", a.size(), ", ", force.size());
    const ContactPairSpec& spec = contacts[contact].spec();
    const auto dwells = dwells_of ? *dwells_of : dwell_windows(spec.program);
    if (objective == LiftObjective::residual && dwells.empty())
        detail::fail("objective 'residual' measures the dwells, and contact '", spec.name,
                     "''s program has none; choose 'follower_error' or 'acceleration'");
    std::vector<double> cam(theta.size());
    for (std::size_t i = 0; i < theta.size(); ++i)
        cam[i] = std::fmod(std::fmod(theta[i] + spec.phase, two_pi) + two_pi, two_pi);
    // The equilibrium at every sample: the objective follows the output through the moves too, where
    // an interpolated path would be off by ~1e-7 of a lift.
    std::vector<double> moving = quasi_static_path(m, output, theta, 0);
    for (std::size_t i = 0; i < q.size(); ++i) moving[i] = q[i] - moving[i];
    LiftSamples out;
    out.dwells = dwell_residual(dwells, cam, moving);
    for (std::size_t i = 0; i < theta.size(); ++i) {
        bool keep = true;
        if (objective == LiftObjective::residual)
            keep = std::any_of(dwells.begin(), dwells.end(),
                               [&](const auto& w) { return cam[i] >= w.first && cam[i] < w.second; });
        if (!keep) continue;
        out.theta.push_back(theta[i]);
        out.values.push_back(objective == LiftObjective::acceleration ? a[i] : moving[i]);
    }
    for (double x : a) out.peak_acceleration = std::max(out.peak_acceleration, std::abs(x));
    if (!spec.groove) out.min_force = *std::min_element(force.begin(), force.end());
    return out;
}

// The periodic steady state of `m` (its own camshaft speed) at the settings' fixed step, one revolution
// recorded from it every `decimation` steps, reduced: a candidate lift evaluated. The orbit is found
// from (q0, v0) or the static equilibrium (shooting: options.tolerance, options.monodromy from a nearby
// candidate). Throws when the shooting does not converge (a response that is not periodic: contact loss).
template <class System>
struct LiftEvaluation {
    PeriodicOrbit orbit;
    LiftSamples samples;
};

template <class System>
LiftEvaluation<System> evaluate_lift(const System& m, const SolverSettings& settings, const ShootingOptions& options,
                                     std::size_t contact, int output, LiftObjective objective,
                                     std::size_t decimation = 1,
                                     const std::optional<typename System::Vector>& q0 = std::nullopt,
                                     const std::optional<typename System::Vector>& v0 = std::nullopt) {
    if (contact >= m.contacts().size())
        detail::fail("evaluate_lift: contact index ", contact, " is not in [0, ", m.contacts().size(), ")");
    if (output < 0 || output >= m.size())
        detail::fail("evaluate_lift: output DOF index ", output, " is not in [0, ", m.size(), ")");
    LiftEvaluation<System> e;
    e.orbit = periodic_orbit(m, settings, options, q0, v0);
    require_converged(e.orbit, options);
    RunOptions run;
    run.duration = m.period();
    run.record.decimation = decimation;
    const typename System::Vector q = e.orbit.q, v = e.orbit.v;
    const RunResult<System> r = simulate(m, settings, run, q, v);
    const Recording& rec = r.recording;
    const std::string name = m.contacts()[contact].spec().name;
    const double* th = rec.channel("theta");
    const double* qo = rec.channel(rec.block(0) + std::size_t(output));
    const double* ao = rec.channel(rec.block(2) + std::size_t(output));
    const double* f = rec.channel(name + ".force");
    // Rows 1..N: row 0 (the start) repeats row N a period later.
    const std::vector<double> theta(th + 1, th + rec.rows), qs(qo + 1, qo + rec.rows), as(ao + 1, ao + rec.rows),
        force(f + 1, f + rec.rows);
    e.samples = lift_samples(m, contact, output, objective, theta, qs, as, force);
    return e;
}

}  // namespace camfollower::synthesis
