// SPDX-License-Identifier: BSD-3-Clause
// One dispatcher from a concrete method (not "auto": solver/choose_method.hpp makes it concrete) to
// the stepper type that runs it, used by simulate(), periodic_orbit() and the benchmarks. Adding an
// integrator: its header, a row in solver/settings.hpp's method_table, and a line here
// (solver/stepper.hpp: the contract and the checklist).
#pragma once

#include <type_traits>
#include <utility>

#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"
#include "camfollower/solver/dormand_prince.hpp"
#include "camfollower/solver/newmark.hpp"
#include "camfollower/solver/radau.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/sparse_newton.hpp"
#include "camfollower/solver/stepper.hpp"

namespace camfollower {

// Names a stepper type for the callable given to with_stepper(); checks the stepper contract.
template <class Stepper>
struct StepperTag {
    static_assert(check_stepper<Stepper>());
    using type = Stepper;
};

namespace detail {
template <class S, class = void>
struct has_sparse_matrices : std::false_type {};
template <class S>
struct has_sparse_matrices<
    S, void_t<decltype(std::declval<const S&>().sparse_mass()), decltype(std::declval<const S&>().tangent_pattern())>>
    : std::bool_constant<S::Vector::RowsAtCompileTime == Eigen::Dynamic> {};
}  // namespace detail

// Whether the Newmark family runs `system` on the sparse backend with these settings.
template <class System>
bool uses_sparse_backend(const System& system, const SolverSettings& settings) {
    if constexpr (detail::has_sparse_matrices<System>::value) {
        if (settings.backend == Backend::sparse) return true;
        return settings.backend == Backend::automatic && system.size() >= sparse_backend_threshold;
    } else {
        if (settings.backend == Backend::sparse)
            detail::fail(
                "linear_solver 'sparse' or 'klu' (the sparse backend) needs a dynamic-size system with sparse "
                "matrices (a Mechanism of other than the paper preset's 7 DOFs)");
        return false;
    }
}

// f(StepperTag<S>{}) with the stepper S that runs `settings` (a concrete method) on `system`.
template <class System, class F>
decltype(auto) with_stepper(const System& system, const SolverSettings& settings, F&& f) {
    const StepperKind kind = traits(settings.method).stepper;
    if (kind == StepperKind::automatic)
        detail::fail("method 'auto' is chosen at the start of a run (choose_method) before a stepper can run it");
    if (kind != StepperKind::newmark && settings.backend == Backend::sparse)
        detail::fail("linear_solver 'sparse' or 'klu' applies to the Newmark family; ", method_name(settings.method),
                     kind == StepperKind::radau ? " runs on the dense backend only" : " solves no linear system");
    if (settings.method == Method::dop853) return std::forward<F>(f)(StepperTag<Dop853<System>>{});
    if (settings.method == Method::dormand_prince) return std::forward<F>(f)(StepperTag<DormandPrince<System>>{});
    if (settings.method == Method::radau) return std::forward<F>(f)(StepperTag<Radau<System>>{});
    if constexpr (detail::has_sparse_matrices<System>::value) {
        if (uses_sparse_backend(system, settings)) return std::forward<F>(f)(StepperTag<SparseNewmark<System>>{});
    } else {
        (void)uses_sparse_backend(system, settings);  // refuses backend = sparse
    }
    return std::forward<F>(f)(StepperTag<Newmark<System>>{});
}

}  // namespace camfollower
