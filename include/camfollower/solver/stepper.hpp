// SPDX-License-Identifier: BSD-3-Clause
// The stepper contract: what simulate(), periodic_orbit(), settle() and shoot() ask of an integrator,
// checked at compile time by check_stepper<S>() (one message per missing member), as check_system<S>()
// checks a system (core/system.hpp).
//
//   using SystemType (the System), Vector, StateType = State<System>;
//   S(const System&, const SolverSettings&)       validates the settings, refuses a method not its own;
//                                                 keeps a reference to the system (S(System&&, ...) deleted)
//   StateType start(double t, const Vector& q, const Vector& v)
//                                                 a state at (t, q, v) with its consistent acceleration;
//                                                 restarts everything (error history, events, path memory)
//   void step(StateType&, SolverStatistics&)      moves the state exactly one time_step() on: a fixed step,
//                                                 or under a tolerance one output interval in adaptive steps
//                                                 (dense output onto the grid); counts into the statistics
//   double time_step() const                      the output interval
//   std::vector<Event> take_events()              contact losses and re-contacts since start(), in time order
//   (optional) void set_interrupt(std::function<bool()>)
//                                                 polled within an output interval; false: stop (cancelled run)
//
// Adding an integrator:
//   1. its header in solver/, a class satisfying this contract, templated on the System;
//   2. a row in method_table (solver/settings.hpp): its name, stepper kind, order and one-line summary;
//   3. a line in with_stepper() (solver/dispatch.hpp);
//   then add it to the stepper conformance tests (order on a closed form, events, restart, statistics,
//   no allocation per step) and its row to the table in docs/solvers.md (a test checks the list).
#pragma once

#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include "camfollower/core/system.hpp"
#include "camfollower/solver/events.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/state.hpp"

namespace camfollower {

namespace detail {
#define CAMFOLLOWER_DETECT(NAME, EXPR) \
    template <class S, class = void>   \
    struct NAME : std::false_type {};  \
    template <class S>                 \
    struct NAME<S, void_t<decltype(EXPR)>> : std::true_type {};
CAMFOLLOWER_DETECT(stepper_has_types, (std::declval<typename S::SystemType>(), std::declval<typename S::Vector>(),
                                       std::declval<typename S::StateType>()))
CAMFOLLOWER_DETECT(stepper_has_start,
                   std::declval<typename S::StateType&>() = std::declval<S&>().start(
                       0.0, std::declval<const typename S::Vector&>(), std::declval<const typename S::Vector&>()))
CAMFOLLOWER_DETECT(stepper_has_step,
                   std::declval<S&>().step(std::declval<typename S::StateType&>(), std::declval<SolverStatistics&>()))
CAMFOLLOWER_DETECT(stepper_has_time_step, double(std::declval<const S&>().time_step()))
CAMFOLLOWER_DETECT(stepper_has_take_events, std::declval<std::vector<Event>&>() = std::declval<S&>().take_events())
#undef CAMFOLLOWER_DETECT
}  // namespace detail

template <class S>
constexpr bool check_stepper() {
    static_assert(detail::stepper_has_types<S>::value,
                  "stepper: missing `using SystemType`, `using Vector` or `using StateType = State<System>`");
    if constexpr (detail::stepper_has_types<S>::value) {
        static_assert(std::is_same_v<typename S::StateType, State<typename S::SystemType>>,
                      "stepper: StateType must be State<System>");
        static_assert(std::is_constructible_v<S, const typename S::SystemType&, const SolverSettings&>,
                      "stepper: missing constructor S(const System&, const SolverSettings&)");
        static_assert(!std::is_constructible_v<S, typename S::SystemType&&, const SolverSettings&>,
                      "stepper: S(System&&, const SolverSettings&) must be deleted (the stepper keeps a reference)");
    }
    static_assert(detail::stepper_has_start<S>::value,
                  "stepper: missing `StateType start(double t, const Vector& q, const Vector& v)`");
    static_assert(detail::stepper_has_step<S>::value, "stepper: missing `void step(StateType&, SolverStatistics&)`");
    static_assert(detail::stepper_has_time_step<S>::value, "stepper: missing `double time_step() const`");
    static_assert(detail::stepper_has_take_events<S>::value, "stepper: missing `std::vector<Event> take_events()`");
    return true;
}

}  // namespace camfollower
