// SPDX-License-Identifier: BSD-3-Clause
// Length units for output files (manufacturing exports): the one table of conversion factors.
//
// Everything inside the library is SI (m); a unit is applied only when numbers leave it for a file
// or a drawing. The inch is the international inch, 0.0254 m exactly.
#pragma once

#include <array>
#include <string>

#include "camfollower/error.hpp"

namespace camfollower {

enum class LengthUnit { m, mm, um, inch };

struct LengthUnitSpec {
    LengthUnit unit;
    const char* name;  // as written in file headers and accepted by length_unit_from_name
    double metres;     // length of one unit, m
};

inline const std::array<LengthUnitSpec, 4>& length_units() {
    static const std::array<LengthUnitSpec, 4> table{{{LengthUnit::m, "m", 1.0},
                                                      {LengthUnit::mm, "mm", 1e-3},
                                                      {LengthUnit::um, "um", 1e-6},
                                                      {LengthUnit::inch, "inch", 0.0254}}};
    return table;
}

inline const LengthUnitSpec& length_unit_spec(LengthUnit unit) {
    for (const LengthUnitSpec& s : length_units())
        if (s.unit == unit) return s;
    detail::fail("unit must be one of m, mm, um, inch (LengthUnit), got enumerator ", static_cast<int>(unit));
}

inline const char* length_unit_name(LengthUnit unit) { return length_unit_spec(unit).name; }

inline LengthUnit length_unit_from_name(const std::string& name) {
    std::string accepted;
    for (const LengthUnitSpec& s : length_units()) {
        if (name == s.name) return s.unit;
        accepted += std::string(accepted.empty() ? "" : ", ") + s.name;
    }
    detail::fail("unit must be one of ", accepted, ", got '", name, "'");
}

// A length in m expressed in `unit`.
inline double metres_to(LengthUnit unit, double metres) { return metres / length_unit_spec(unit).metres; }

}  // namespace camfollower
