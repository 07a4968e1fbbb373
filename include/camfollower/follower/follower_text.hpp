// SPDX-License-Identifier: BSD-3-Clause
// The pieces of a follower's one-line description (each follower's describe(): the export headers,
// the command line): "name = value unit" with lengths given in m and written in a chosen unit.
#pragma once

#include <string>

#include <Eigen/Core>

#include "camfollower/error.hpp"
#include "camfollower/follower/arm_turn.hpp"
#include "camfollower/units.hpp"

namespace camfollower::detail {

inline std::string length_text(const char* name, double metres, LengthUnit unit) {
    return concat(name, " = ", metres_to(unit, metres), " ", length_unit_name(unit));
}

inline std::string pivot_text(const Eigen::Vector2d& pivot, LengthUnit unit) {
    return concat("pivot = (", metres_to(unit, pivot.x()), ", ", metres_to(unit, pivot.y()), ") ",
                  length_unit_name(unit), " (ground frame)");
}

inline std::string turn_text(ArmTurn t) {
    return concat("turn = ", t == ArmTurn::counter_clockwise ? "counter_clockwise" : "clockwise");
}

}  // namespace camfollower::detail
