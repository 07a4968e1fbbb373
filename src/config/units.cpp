// SPDX-License-Identifier: BSD-3-Clause
#include "units.hpp"

#include <map>
#include <string>

#include "camfollower/error.hpp"
#include "camfollower/motion/program.hpp"  // pi, two_pi
#include "camfollower/units.hpp"

namespace camfollower::config {

namespace {

// Length units from the library's one table (camfollower/units.hpp), plus the micro sign as an alias.
std::vector<UnitFactor> lengths(bool with_angles) {
    std::vector<UnitFactor> out;
    for (const LengthUnitSpec& u : length_units()) out.push_back({u.name, u.metres});
    out.push_back({"µm", 1e-6});
    if (with_angles) out.insert(out.end(), {{"rad", 1.0}, {"deg", pi / 180.0}});
    return out;
}

}  // namespace

const QuantityKind& quantity_kind(std::string_view si) {
    static const std::map<std::string, QuantityKind, std::less<>> table{
        {"m", {"m", lengths(false)}},
        {"kg", {"kg", {{"kg", 1.0}, {"g", 1e-3}, {"kg m^2", 1.0}, {"kg mm^2", 1e-6}}}},  // mass or inertia of a DOF
        {"N", {"N", {{"N", 1.0}, {"kN", 1e3}}}},
        {"N/m", {"N/m", {{"N/m", 1.0}, {"N/mm", 1e3}, {"N/um", 1e6}, {"N m/rad", 1.0}}}},
        {"N s/m", {"N s/m", {{"N s/m", 1.0}, {"N*s/m", 1.0}, {"Ns/m", 1.0}, {"N m s/rad", 1.0}}}},
        {"N/m^n", {"N/m^n", {{"N/m^n", 1.0}}}},
        {"s/m", {"s/m", {{"s/m", 1.0}}}},
        {"m/s", {"m/s", {{"m/s", 1.0}, {"mm/s", 1e-3}}}},
        {"m/s^2", {"m/s^2", {{"m/s^2", 1.0}, {"g", 9.80665}}}},
        {"rpm", {"rpm", {{"rpm", 1.0}, {"rad/s", 60.0 / two_pi}, {"Hz", 60.0}}}},
        // A motion program's lift: a length (translating followers) or an arm angle (oscillating).
        {"lift", {"m or rad", lengths(true)}},
        {"rad", {"rad", {{"rad", 1.0}, {"deg", pi / 180.0}}}},
        {"s", {"s", {{"s", 1.0}, {"ms", 1e-3}, {"us", 1e-6}}}},
        {"Pa", {"Pa", {{"Pa", 1.0}, {"kPa", 1e3}, {"MPa", 1e6}, {"GPa", 1e9}, {"N/mm^2", 1e6}}}},
        {"kg/m^3", {"kg/m^3", {{"kg/m^3", 1.0}, {"g/cm^3", 1e3}}}},
        {"N m", {"N m", {{"N m", 1.0}, {"N*m", 1.0}, {"Nm", 1.0}, {"N mm", 1e-3}}}},
        {"-", {"-", {}}},
    };
    const auto it = table.find(si);
    if (it == table.end()) detail::fail("internal: unknown quantity kind '", si, "'");
    return it->second;
}

double to_si(double number, std::string_view unit, std::string_view si) {
    const QuantityKind& kind = quantity_kind(si);
    std::string accepted;
    for (const UnitFactor& u : kind.accepted) {
        if (unit == u.unit) return number * u.factor;
        accepted += std::string(accepted.empty() ? "" : ", ") + u.unit;
    }
    if (accepted.empty()) detail::fail("takes a plain number (dimensionless), got unit '", unit, "'");
    detail::fail("unit '", unit, "' does not fit this quantity (", kind.si, "); use one of ", accepted);
}

}  // namespace camfollower::config
