// SPDX-License-Identifier: BSD-3-Clause
// The solver's vocabulary: one Method per integration method, the table of their names and traits
// (read by C++, the config, Python, the command line and the docs' test), and SolverSettings.
//
// A run is error-controlled exactly when SolverSettings::tolerance is set: every method then adapts
// its steps under it and time_step becomes the output interval. Without one the Newmark family takes
// fixed steps of time_step; a Runge-Kutta method takes fixed steps of max_step only when max_step is
// set (for order studies and benchmarks) and is refused with neither. The front ends (config,
// Python, command line) give a Runge-Kutta method runge_kutta_default_tolerance when none is asked for.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "camfollower/error.hpp"

namespace camfollower {

enum class Method { newmark, fox_goodwin, hht, dormand_prince, dop853, radau, automatic };

// How a method steps; the dispatcher (solver/dispatch.hpp) picks the stepper by it.
enum class StepperKind {
    newmark,      // implicit Newmark family (solver/newmark.hpp; sparse backend: solver/sparse_newton.hpp)
    explicit_rk,  // embedded explicit Runge-Kutta (solver/dormand_prince.hpp)
    radau,        // implicit Radau IIA (solver/radau.hpp)
    automatic,    // chosen at the start of the run (solver/choose_method.hpp)
};

struct MethodTraits {
    Method method;
    const char* name;  // in config files, Python, the command line and RunResult::method
    StepperKind stepper;
    int order;            // global order on smooth problems (0: the chosen method's)
    const char* summary;  // one line for lists and --help
};

// The methods, in the order they are listed to users.
inline constexpr std::array<MethodTraits, 7> method_table{{
    {Method::newmark, "newmark", StepperKind::newmark, 2,
     "implicit Newmark-beta with gamma and beta (default 1/2, 1/4: average acceleration, unconditionally stable)"},
    {Method::fox_goodwin, "fox_goodwin", StepperKind::newmark, 4,
     "Newmark with gamma = 1/2, beta = 1/12, its velocity processed to fourth order (damping included); stable "
     "below dt = sqrt(6) / omega_max, the processed velocity lower with damping (beyond it, and on the sparse "
     "backend, the trapezoidal velocity)"},
    {Method::hht, "hht", StepperKind::newmark, 2,
     "HHT-alpha (hht_alpha in [-1/3, 0]): Newmark that damps the highest modes, unconditionally stable"},
    {Method::dormand_prince, "dormand_prince", StepperKind::explicit_rk, 5,
     "explicit Runge-Kutta 5(4) with dense output"},
    {Method::dop853, "dop853", StepperKind::explicit_rk, 8,
     "explicit Runge-Kutta 8(5,3) (Hairer's DOP853), 7th-order dense output: for errors of 1e-8 and contact losses"},
    {Method::radau, "radau", StepperKind::radau, 5,
     "implicit Radau IIA of order 5 (L-stable): for models stiff at the accuracy wanted; dense backend"},
    {Method::automatic, "auto", StepperKind::automatic, 0,
     "fixed steps: fox_goodwin within its stability limit, else newmark; under a tolerance: radau when the "
     "fastest modes are damped or one rings alone, else dop853"},
}};

// The Runge-Kutta methods' tolerance in the front ends when none is given (relative error per step).
inline constexpr double runge_kutta_default_tolerance = 1e-6;
// HHT's alpha in the front ends when none is given: light damping of the highest modes.
inline constexpr double default_hht_alpha = -0.05;

inline constexpr const MethodTraits& traits(Method m) {
    for (const MethodTraits& t : method_table)
        if (t.method == m) return t;
    return method_table.back();  // unreachable: every Method has a row
}
inline constexpr const char* method_name(Method m) { return traits(m).name; }
inline constexpr bool is_newmark_family(Method m) { return traits(m).stepper == StepperKind::newmark; }
inline constexpr bool is_runge_kutta(Method m) {
    return traits(m).stepper == StepperKind::explicit_rk || traits(m).stepper == StepperKind::radau;
}
inline constexpr bool is_automatic(Method m) { return m == Method::automatic; }

// "'newmark', 'fox_goodwin', ... or 'auto'": the names for error messages.
inline std::string method_names_listed() {
    std::string list;
    for (std::size_t k = 0; k < method_table.size(); ++k) {
        if (k > 0) list += k + 1 == method_table.size() ? " or " : ", ";
        list += std::string("'") + method_table[k].name + "'";
    }
    return list;
}
inline Method method_from_name(std::string_view name) {
    for (const MethodTraits& t : method_table)
        if (name == t.name) return t.method;
    detail::fail("method must be ", method_names_listed(), ", got '", std::string(name), "'");
}

enum class LinearSolver { sherman_morrison, dense_lu };
// Dense (small models, fixed-size Eigen) or sparse (SuiteSparse: solver/sparse_newton.hpp) Newton
// algebra; automatic picks sparse from sparse_backend_threshold DOFs on systems that support it.
enum class Backend { automatic, dense, sparse };
// The sparse backend's factorization: automatic is CHOLMOD when the Newton matrix is symmetric
// positive definite, KLU otherwise; klu always uses KLU.
enum class SparseFactorization { automatic, klu };
inline constexpr int sparse_backend_threshold = 100;  // DOFs; measured crossover: bench/camshaft.cpp

// Newmark's gamma, beta and HHT's alpha as a method steps with them. `processed`: the scheme's velocity
// is post-processed to fourth order (docs/solvers.md, "Fourth order with damping"): with gamma = 1/2
// the displacements follow Numerov's recurrence, exact to fourth order for beta = 1/12, while the
// trapezoidal velocity vN is off by dt^2 / 12 a' (a' the jerk); the forces and the recorded state see
// v = vN - dt^2 / 12 a', a' from the last three accelerations. The velocity then moves by
// damping_gamma dt per unit of the new acceleration (the Newton matrix's damping coefficient):
// 1/2 - (1/12)(3/2) = 3/8 for the three-point jerk at equal steps.
struct NewmarkParameters {
    double gamma = 0.5, beta = 0.25, alpha = 0.0;
    bool processed = false;
    double damping_gamma = 0.5;
};
inline constexpr double processed_damping_gamma = 3.0 / 8.0;

// The fraction of a conditionally stable scheme's step limit a run may use: a 10 % margin for the
// highest mode's variation along the motion (contact directions turn with the cam).
inline constexpr double step_limit_margin = 0.9;

// Largest stable step of unprocessed Newmark with beta < gamma / 2 (undamped: omega_max dt < 1 /
// sqrt(gamma / 2 - beta)), with step_limit_margin; +inf when the scheme is unconditionally stable. A
// processed velocity has its own, lower with damping (solver/step_limit.hpp).
inline double newmark_step_limit(double gamma, double beta, double omega_max) {
    if (beta >= 0.5 * gamma) return std::numeric_limits<double>::infinity();
    return step_limit_margin / (omega_max * std::sqrt(0.5 * gamma - beta));
}

// gamma and beta belong to method newmark, hht_alpha to hht: a value another method would ignore is
// refused (validate(): gamma, beta other than their defaults, hht_alpha set; the front ends: any
// value given).
inline void check_newmark_parameters_apply(Method method, bool gamma_or_beta_given, bool hht_alpha_given) {
    if (gamma_or_beta_given && method != Method::newmark)
        detail::fail("gamma and beta apply to method 'newmark' only, got them with method '", method_name(method), "'");
    if (hht_alpha_given && method != Method::hht)
        detail::fail("hht_alpha applies to method 'hht' only, got it with method '", method_name(method), "'",
                     method == Method::newmark ? " (HHT-alpha is method 'hht')" : "");
}

struct SolverSettings {
    Method method = Method::newmark;
    double time_step = 3e-6;             // s: the fixed step, or under a tolerance the output interval
    std::optional<double> tolerance;     // set: adaptive steps, relative error per step (displacements, forces)
    double max_step = 0.0;               // s, 0: unbounded. Under a tolerance the largest step (Newmark: at most
                                         // time_step); a Runge-Kutta method without one: its fixed step (required)
    double gamma = 0.5, beta = 0.25;     // method newmark only
    std::optional<double> hht_alpha;     // method hht only, in [-1/3, 0]; unset: default_hht_alpha
    double residual_tolerance = 1e-10;   // Newton, relative to the system's force scale
    double increment_tolerance = 1e-10;  // Newton, relative to max |q| (+ 1 nm floor)
    int max_iterations = 25;
    int max_halvings = 6;  // Newmark: a failed step is halved up to this often; under a tolerance the
                           // smallest step is time_step / 2^max_halvings
    LinearSolver linear_solver = LinearSolver::sherman_morrison;  // dense backend: low-rank updates, or dense LU always
    Backend backend = Backend::automatic;
    SparseFactorization sparse_factorization = SparseFactorization::automatic;
    // Newmark with gamma = 1/2 and beta < 1/4 (fox_goodwin, the studies' matched scheme): the velocity
    // processed to fourth order (NewmarkParameters::processed). simulate() and periodic_orbit() turn it
    // off where the processed velocity is unstable at a fixed step the trapezoidal one allows, and on the
    // sparse backend (choose_velocity, solver/step_limit.hpp), and say so (RunResult::velocity_choice).
    bool process_velocity = true;
    static constexpr int max_levels = 16;

    bool adaptive() const { return tolerance.has_value(); }
    // HHT-alpha at time_step.
    static SolverSettings hht(double alpha = default_hht_alpha, double time_step = 3e-6) {
        SolverSettings s;
        s.method = Method::hht;
        s.hht_alpha = alpha;
        s.time_step = time_step;
        return s;
    }
    static SolverSettings named(Method method, double time_step, std::optional<double> tolerance = std::nullopt) {
        SolverSettings s;
        s.method = method;
        s.time_step = time_step;
        s.tolerance = tolerance;
        return s;
    }

    void validate() const {
        // Below a picosecond M / (beta dt^2) leaves the range of doubles for any mechanical mass.
        if (!(std::isfinite(time_step) && time_step >= 1e-12))
            detail::fail("time_step must be finite and > 0 (at least 1e-12 s), got ", time_step);
        check_newmark_parameters_apply(method, gamma != 0.5 || beta != 0.25, hht_alpha.has_value());
        if (method == Method::newmark) {
            detail::require_in_range(gamma, 0.5, 1.0, "gamma (below 1/2 the scheme adds negative damping)");
            if (!(std::isfinite(beta) && beta > 0.0 && beta <= 0.5))
                detail::fail("beta must be in (0, 0.5], got ", beta);
        }
        if (method == Method::hht)
            detail::require_in_range(hht_alpha.value_or(default_hht_alpha), -1.0 / 3.0, 0.0, "hht_alpha");
        detail::require_positive(residual_tolerance, "residual_tolerance");
        detail::require_positive(increment_tolerance, "increment_tolerance");
        if (max_iterations < 1 || max_iterations > 1000)
            detail::fail("max_iterations must be in [1, 1000], got ", max_iterations);
        if (max_halvings < 0 || max_halvings > max_levels - 1)
            detail::fail("max_halvings must be in [0, ", max_levels - 1, "], got ", max_halvings);
        // Below 1e-13 the error estimate is rounding; above 0.1 it no longer measures anything.
        if (tolerance) detail::require_in_range(*tolerance, 1e-13, 0.1, "tolerance");
        // As for time_step: below a picosecond no mechanical model needs a step.
        if (!(std::isfinite(max_step) && (max_step == 0.0 || max_step >= 1e-12)))
            detail::fail("max_step must be 0 (unbounded) or finite and >= 1e-12 s, got ", max_step);
        if (max_step != 0.0 && !tolerance && !is_runge_kutta(method))
            detail::fail("max_step applies with a tolerance only (method '", method_name(method),
                         "' without one runs fixed steps of time_step)");
        // The error estimate is Newmark's (Zienkiewicz & Xie); HHT-alpha's differs.
        if (method == Method::hht && tolerance)
            detail::fail(
                "method 'hht' takes no tolerance (error control for HHT-alpha is not implemented): use "
                "'newmark', 'fox_goodwin' or 'auto' with a tolerance");
    }
};

// The front ends' rule: a Runge-Kutta method asked for without a tolerance runs under
// runge_kutta_default_tolerance (its fixed steps are for order studies, from C++ only).
inline void give_default_tolerance(SolverSettings& s) {
    if (!s.tolerance && is_runge_kutta(s.method)) s.tolerance = runge_kutta_default_tolerance;
}

// The Newmark family's gamma, beta and alpha for its method (newmark: the settings' own). gamma = 1/2
// with beta < 1/4 (Fox-Goodwin and its period-matched neighbours) is processed; average acceleration
// (the paper's rule) and HHT are not.
inline NewmarkParameters newmark_parameters(const SolverSettings& s) {
    NewmarkParameters p{s.gamma, s.beta, 0.0};
    if (s.method == Method::fox_goodwin) p = {0.5, 1.0 / 12.0, 0.0};
    if (s.method == Method::hht) {
        const double alpha = s.hht_alpha.value_or(default_hht_alpha);
        p = {0.5 - alpha, 0.25 * (1.0 - alpha) * (1.0 - alpha), alpha};
    }
    p.processed = s.process_velocity && p.gamma == 0.5 && p.alpha == 0.0 && p.beta < 0.25;
    p.damping_gamma = p.processed ? processed_damping_gamma : p.gamma;
    return p;
}

// The linear-algebra choice by one name (config files, Python):
//   "auto"      dense low-rank below sparse_backend_threshold DOFs, sparse above (the default)
//   "low_rank"  dense backend, Sherman-Morrison / Woodbury ("sherman_morrison" is an alias)
//   "dense_lu"  dense backend, a full LU at every Newton iteration
//   "sparse"    sparse backend, CHOLMOD when the matrix is symmetric positive definite, else KLU
//   "klu"       sparse backend, KLU always
inline void set_linear_solver(SolverSettings& s, const std::string& name) {
    s.linear_solver = LinearSolver::sherman_morrison;
    s.sparse_factorization = SparseFactorization::automatic;
    if (name == "auto") s.backend = Backend::automatic;
    else if (name == "low_rank" || name == "sherman_morrison") s.backend = Backend::dense;
    else if (name == "dense_lu") s.backend = Backend::dense, s.linear_solver = LinearSolver::dense_lu;
    else if (name == "sparse") s.backend = Backend::sparse;
    else if (name == "klu") s.backend = Backend::sparse, s.sparse_factorization = SparseFactorization::klu;
    else detail::fail("linear_solver must be 'auto', 'low_rank', 'dense_lu', 'sparse' or 'klu', got '", name, "'");
}
inline const char* linear_solver_name(const SolverSettings& s) {
    if (s.backend == Backend::sparse) return s.sparse_factorization == SparseFactorization::klu ? "klu" : "sparse";
    if (s.linear_solver == LinearSolver::dense_lu) return "dense_lu";
    return s.backend == Backend::dense ? "low_rank" : "auto";
}

}  // namespace camfollower
