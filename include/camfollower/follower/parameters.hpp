// SPDX-License-Identifier: BSD-3-Clause
// What defines a follower type, said once in its class: each type lists its constructor's parameters
// in order (name, kind, default, meaning) as `static constexpr parameters` and returns their values
// with `parameter_values()` (a tuple in the same order, so `std::make_from_tuple<F>` rebuilds it).
// The config reader, the Python bindings (constructor, properties, pickling, repr) and the one-line
// description read that list, so a new follower type writes none of them.
//
// The C++ type of each kind: length and angle double (m, rad), point Eigen::Vector2d (m, ground
// frame), turn ArmTurn. A parameter's name is its config key, Python keyword and property.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "camfollower/constants.hpp"
#include "camfollower/error.hpp"
#include "camfollower/follower/arm_turn.hpp"
#include "camfollower/units.hpp"

namespace camfollower {

enum class ParameterKind { length, angle, point, turn };

struct FollowerParameter {
    const char* name;
    ParameterKind kind;
    const char* meaning;  // one line with its unit: docstrings and docs
    bool required = true;
    // Without `required`: a length's (m) or an angle's (rad) default; a turn defaults to
    // counter_clockwise; a point is always required.
    double default_value = 0.0;
};

constexpr FollowerParameter required_parameter(const char* name, ParameterKind kind, const char* meaning) {
    return {name, kind, meaning, true, 0.0};
}
constexpr FollowerParameter optional_parameter(const char* name, ParameterKind kind, const char* meaning,
                                               double default_value = 0.0) {
    return {name, kind, meaning, false, default_value};
}

// The parameters several types share, described once.
namespace common_parameter {
inline constexpr FollowerParameter base_radius =
    required_parameter("base_radius", ParameterKind::length, "base circle radius r_b (m, > 0)");
inline constexpr FollowerParameter roller_radius =
    required_parameter("roller_radius", ParameterKind::length, "roller radius r_r (m, > 0)");
inline constexpr FollowerParameter pivot =
    required_parameter("pivot", ParameterKind::point, "arm pivot P (m, ground frame, outside the base circle)");
inline constexpr FollowerParameter turn = optional_parameter("turn", ParameterKind::turn, "the arm's lifting sense");
}  // namespace common_parameter

// The C++ type that holds a parameter of this kind.
template <ParameterKind K>
using parameter_type = std::conditional_t<K == ParameterKind::point, Eigen::Vector2d,
                                          std::conditional_t<K == ParameterKind::turn, ArmTurn, double>>;

// The tuple of F's parameter values, and the type of the I-th.
template <class F>
using follower_parameter_values = decltype(std::declval<const F&>().parameter_values());
template <class F, std::size_t I>
using follower_parameter_type = std::decay_t<std::tuple_element_t<I, follower_parameter_values<F>>>;

namespace detail {
template <class F, std::size_t... I>
constexpr bool parameters_match(std::index_sequence<I...>) {
    return ((std::is_same_v<follower_parameter_type<F, I>, double> ==
             (F::parameters[I].kind == ParameterKind::length || F::parameters[I].kind == ParameterKind::angle)) &&
            ...) &&
           ((std::is_same_v<follower_parameter_type<F, I>, Eigen::Vector2d> ==
             (F::parameters[I].kind == ParameterKind::point)) &&
            ...) &&
           ((std::is_same_v<follower_parameter_type<F, I>, ArmTurn> ==
             (F::parameters[I].kind == ParameterKind::turn)) &&
            ...) &&
           ((F::parameters[I].required || F::parameters[I].kind != ParameterKind::point) && ...);
}
}  // namespace detail

// Compile-time check that F's description and values agree (count, kinds, no defaulted point).
template <class F>
constexpr bool check_follower_parameters() {
    constexpr std::size_t n = F::parameters.size();
    static_assert(std::tuple_size_v<follower_parameter_values<F>> == n,
                  "parameter_values() must return one value per entry of parameters");
    static_assert(detail::parameters_match<F>(std::make_index_sequence<n>{}),
                  "each parameter's kind must match its value's type (length/angle double, point Vector2d, "
                  "turn ArmTurn); a point cannot have a default");
    return true;
}

inline const char* arm_turn_name(ArmTurn t) { return t == ArmTurn::clockwise ? "clockwise" : "counter_clockwise"; }
// "counter_clockwise"/"ccw" or "clockwise"/"cw".
inline ArmTurn arm_turn_from(std::string_view name) {
    if (name == "counter_clockwise" || name == "ccw") return ArmTurn::counter_clockwise;
    if (name == "clockwise" || name == "cw") return ArmTurn::clockwise;
    detail::fail("turn must be 'counter_clockwise' or 'clockwise', got '", detail::printable(name), "'");
}

namespace detail {
inline std::string parameter_text(const FollowerParameter& p, double value, LengthUnit unit) {
    if (p.kind == ParameterKind::angle) return concat(p.name, " = ", radians_to_degrees(value), " deg");
    return concat(p.name, " = ", metres_to(unit, value), " ", length_unit_name(unit));
}
inline std::string parameter_text(const FollowerParameter& p, const Eigen::Vector2d& v, LengthUnit unit) {
    return concat(p.name, " = (", metres_to(unit, v.x()), ", ", metres_to(unit, v.y()), ") ", length_unit_name(unit),
                  " (ground frame)");
}
inline std::string parameter_text(const FollowerParameter& p, ArmTurn t, LengthUnit) {
    return concat(p.name, " = ", arm_turn_name(t));
}
}  // namespace detail

// One line naming the type and its parameters, lengths in `unit`, angles in deg (export headers,
// the command line): "translating_roller: base_radius = 40 mm, roller_radius = 10 mm, offset = 0 mm".
template <class F>
std::string describe_follower(const F& follower, LengthUnit unit) {
    std::string out = std::string(F::type_name) + ":";
    const auto values = follower.parameter_values();
    std::apply(
        [&](const auto&... v) {
            std::size_t i = 0;
            ((out += (i == 0 ? " " : ", ") + detail::parameter_text(F::parameters[i], v, unit), ++i), ...);
        },
        values);
    return out;
}

}  // namespace camfollower
