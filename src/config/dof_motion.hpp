// SPDX-License-Identifier: BSD-3-Clause
// Rotation or translation, as a config's units state it. A DOF whose mass is written in kg m^2 turns,
// one in kg or g translates; a bare number states nothing. The springs, dampers, loads and contacts on
// a DOF whose motion is stated must use the units of that motion (a rate in N m/rad, not N/mm, on a
// turning arm): a unit of the other motion is refused at its key, naming the DOF and the units that
// fit (docs/config.md, "Rotations and translations").
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "section.hpp"

namespace camfollower::config {

enum class DofMotion { unstated, translation, rotation };

// The motion a unit states: kg, g, N/m, N s/m, N ... translate; kg m^2, N m/rad, N m s/rad, N m ...
// rotate; "" (a bare number) and units of neither (m, s, ...) state nothing.
DofMotion motion_of_unit(std::string_view unit);

// What an element's quantity is, for the units that fit it: its stiffness, damping or force.
enum class Measure { stiffness, damping, force };

class DofMotions {
public:
    // Notes a [[dof]]'s motion from the unit of its mass (at key "mass" of s).
    void note(const std::string& dof, const Section& s);
    DofMotion of(const std::string& dof) const;
    // Refuses, at `key` of s, a unit of `measure` that states the other motion than the stated DOFs among
    // `dofs` (ground and unstated DOFs say nothing), and DOFs of both motions joined by one element (at
    // `dofs_key`).
    void check(const Section& s, std::string_view key, Measure measure, const std::vector<std::string>& dofs,
               std::string_view dofs_key) const;
    // Refuses, at `key` of s, a DOF whose stated motion is not `wanted` (`role`: what the element needs
    // it to be, e.g. "an oscillating follower's arm angle").
    void require(const Section& s, std::string_view key, const std::string& dof, DofMotion wanted,
                 const std::string& role) const;

private:
    std::map<std::string, DofMotion> stated_;
};

// A force or, on a turning DOF, a moment (N m) read at `key` (required without a fallback): the
// quantity kind its unit names.
double force_or_moment(const Section& s, std::string_view key, std::optional<double> fallback = std::nullopt);

}  // namespace camfollower::config
