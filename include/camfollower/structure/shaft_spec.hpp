// SPDX-License-Identifier: BSD-3-Clause
// A flexible shaft as part of a mechanism: a straight Timoshenko shaft along the global x axis from
// x = 0 to x = length, meshed so that every station (where a cam, a bearing, the drive or a mass sits)
// is a node, with no element longer than max_element_length.
//
// Each node carries the DOFs u_y, u_z (lateral translations, m), theta_x (twist, rad), theta_y,
// theta_z (cross-section rotations, rad), and u_x (axial, m) when `axial` is set. The twist is
// measured relative to the shaft's rigid rotation at the nominal speed, so a cam mounted at a node
// turns through omega t + phase + theta_x there. DOF names are "<shaft>.<node>.<dof>", node counted
// from 0 at x = 0 (shaft_dof_name()).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "camfollower/error.hpp"
#include "camfollower/structure/beam_section.hpp"

namespace camfollower {

struct ShaftSpec {
    std::string name;
    BeamSection section;
    double length = 0.0;              // m
    double max_element_length = 0.0;  // m; 0: one element between neighbouring stations
    std::vector<double> stations;     // m, in [0, length]: positions that must be nodes
    bool axial = false;               // model the axial DOF u_x (stiff and usually irrelevant)
    // Material damping, s: C = damping K of the shaft's own elements (stiffness-proportional), so a
    // mode of the shaft at omega has the ratio damping omega / 2: light on the low modes, heavy on the
    // high ones a time step does not resolve.
    double damping = 0.0;

    void validate() const {
        const std::string who = "shaft '" + name + "'";
        detail::require_name(name, "shaft");
        if (name.find('.') != std::string::npos)
            detail::fail("shaft name must be non-empty and without '.', got '", name, "'");
        try {
            section.validate();
        } catch (const std::invalid_argument& e) {
            detail::fail(who, " section: ", e.what());
        }
        detail::require_length(length, (who + " length").c_str());
        if (!(std::isfinite(max_element_length) && max_element_length >= 0.0))
            detail::fail(who, " max_element_length must be >= 0 (0: one element between stations), got ",
                         max_element_length);
        if (!(std::isfinite(damping) && damping >= 0.0))
            detail::fail(who, " damping must be >= 0 s (stiffness-proportional), got ", damping);
        for (double x : stations)
            if (!(std::isfinite(x) && x >= 0.0 && x <= length))
                detail::fail(who, ": station x = ", x, " m is outside the shaft [0, ", length, "] m");
        // Beam theory has nothing to say below a fraction of the section's size: an element much
        // shorter than its radius of gyration is a unit slip (um for mm) far more often than a plan.
        const double gyration = std::sqrt(section.second_moment_y / section.area);
        if (max_element_length > 0.0 && max_element_length < 0.1 * gyration)
            detail::fail(who, " max_element_length = ", max_element_length,
                         " m is below a tenth of the section's radius of gyration (", gyration,
                         " m), far finer than a beam model can use (um written for mm? that would be ",
                         max_element_length * 1e3, " m); 0 gives one element between stations");
        if (max_element_length > 0.0 && length / max_element_length + double(stations.size()) > max_elements)
            detail::fail(who, " max_element_length = ", max_element_length, " m would make about ",
                         length / max_element_length, " elements (limit ", max_elements,
                         " per shaft: 5 or 6 DOFs each, and a mechanism's matrices are dense)");
    }
    static constexpr double max_elements = 500;

    // Node positions: 0, length and the stations (merged within 1 um), each interval split into equal
    // elements no longer than max_element_length.
    std::vector<double> node_positions() const {
        validate();
        std::vector<double> fixed = stations;
        fixed.push_back(0.0), fixed.push_back(length);
        std::sort(fixed.begin(), fixed.end());
        std::vector<double> unique;
        for (double x : fixed)
            if (unique.empty() || x - unique.back() > merge_distance) unique.push_back(x);
        unique.back() = length;
        std::vector<double> nodes{0.0};
        for (std::size_t i = 1; i < unique.size(); ++i) {
            const double span = unique[i] - unique[i - 1];
            const int parts =
                max_element_length > 0.0 ? std::max(1, int(std::ceil(span / max_element_length - 1e-9))) : 1;
            for (int k = 1; k <= parts; ++k) nodes.push_back(k == parts ? unique[i] : unique[i - 1] + span * k / parts);
        }
        return nodes;
    }

    // The node at station x (which must be one of the stations, 0 or length).
    int node_at(double x) const {
        const std::vector<double> nodes = node_positions();
        for (std::size_t k = 0; k < nodes.size(); ++k)
            if (std::abs(nodes[k] - x) <= merge_distance) return int(k);
        detail::fail("shaft '", name, "' has no node at x = ", x, " m (list it among the stations)");
    }

    static constexpr double merge_distance = 1e-6;  // m: stations closer than this are one node
};

inline const char* shaft_dof_suffix(int d) {
    static const char* names[] = {"ux", "uy", "uz", "rx", "ry", "rz"};
    return names[d];
}

// Name of DOF d (0..5 as in timoshenko_beam.hpp: ux, uy, uz, rx, ry, rz) of a shaft's node.
inline std::string shaft_dof_name(const std::string& shaft, int node, int d) {
    return shaft + "." + std::to_string(node) + "." + shaft_dof_suffix(d);
}

}  // namespace camfollower
