// SPDX-License-Identifier: BSD-3-Clause
#include "dof_motion.hpp"

#include <utility>

#include "camfollower/error.hpp"

namespace camfollower::config {

namespace {

const char* name(DofMotion m) { return m == DofMotion::rotation ? "turns" : "translates"; }

// The units that fit a measure on a motion (those of units.cpp's quantity kinds).
const char* fitting(Measure measure, DofMotion m) {
    const bool turns = m == DofMotion::rotation;
    switch (measure) {
        case Measure::stiffness: return turns ? "N m/rad" : "N/m, N/mm or N/um";
        case Measure::damping: return turns ? "N m s/rad" : "N s/m";
        case Measure::force: break;
    }
    return turns ? "N m or N mm (a moment)" : "N or kN";
}

}  // namespace

DofMotion motion_of_unit(std::string_view unit) {
    static const std::map<std::string, DofMotion, std::less<>> table{
        {"kg", DofMotion::translation},    {"g", DofMotion::translation},    {"kg m^2", DofMotion::rotation},
        {"kg mm^2", DofMotion::rotation},  {"N/m", DofMotion::translation},  {"N/mm", DofMotion::translation},
        {"N/um", DofMotion::translation},  {"N m/rad", DofMotion::rotation}, {"N s/m", DofMotion::translation},
        {"N*s/m", DofMotion::translation}, {"Ns/m", DofMotion::translation}, {"N m s/rad", DofMotion::rotation},
        {"N", DofMotion::translation},     {"kN", DofMotion::translation},   {"N m", DofMotion::rotation},
        {"N*m", DofMotion::rotation},      {"Nm", DofMotion::rotation},      {"N mm", DofMotion::rotation},
    };
    const auto it = table.find(unit);
    return it == table.end() ? DofMotion::unstated : it->second;
}

void DofMotions::note(const std::string& dof, const Section& s) {
    const DofMotion m = motion_of_unit(s.unit("mass"));
    if (m != DofMotion::unstated) stated_[dof] = m;
}

DofMotion DofMotions::of(const std::string& dof) const {
    const auto it = stated_.find(dof);
    return it == stated_.end() ? DofMotion::unstated : it->second;
}

void DofMotions::check(const Section& s, std::string_view key, Measure measure, const std::vector<std::string>& dofs,
                       std::string_view dofs_key) const {
    std::string first;
    DofMotion motion = DofMotion::unstated;
    for (const std::string& d : dofs) {
        const DofMotion m = of(d);
        if (m == DofMotion::unstated) continue;
        if (motion == DofMotion::unstated) {
            motion = m, first = d;
        } else if (m != motion) {
            s.fail(dofs_key, detail::concat("joins DOF '", detail::printable(first), "', which ", name(motion),
                                            " (the unit of its mass), and DOF '", detail::printable(d), "', which ",
                                            name(m), ": an element acts between two rotations or two translations"));
        }
    }
    if (motion == DofMotion::unstated || !s.has(key)) return;
    const DofMotion written = motion_of_unit(s.unit(key));
    if (written == DofMotion::unstated || written == motion) return;
    s.fail(key, detail::concat("unit '", s.unit(key), "' is for a DOF that ", name(written), ", but DOF '",
                               detail::printable(first), "' ", name(motion), " (the unit of its mass): write it in ",
                               fitting(measure, motion), " (or, if '", detail::printable(first), "' ", name(written),
                               ", its mass in ", written == DofMotion::rotation ? "kg m^2" : "kg", ")"));
}

void DofMotions::require(const Section& s, std::string_view key, const std::string& dof, DofMotion wanted,
                         const std::string& role) const {
    const DofMotion m = of(dof);
    if (m == DofMotion::unstated || m == wanted) return;
    s.fail(key, detail::concat("DOF '", detail::printable(dof), "' is ", role, ", so it ", name(wanted),
                               ", but its mass is written in units of a DOF that ", name(m), ": write ",
                               wanted == DofMotion::rotation ? "its moment of inertia in kg m^2" : "its mass in kg"));
}

double force_or_moment(const Section& s, std::string_view key, std::optional<double> fallback) {
    const std::string_view kind = motion_of_unit(s.unit(key)) == DofMotion::rotation ? "N m" : "N";
    return fallback ? s.quantity(key, kind, *fallback) : s.quantity(key, kind);
}

}  // namespace camfollower::config
