// SPDX-License-Identifier: BSD-3-Clause
// A simulation case described in a TOML config file: motion programs, the mechanism (its parts, or a
// named preset with overrides), the solver and the output. Used by the command line and by Python's
// camfollower.load_config; docs/config.md is the reference for the format.
//
// Errors: std::invalid_argument naming the file, the line and the key path
// ("cam.toml:14: contact[0].follower.base_radius: must be finite and > 0 (m), got -1").
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "camfollower/model/mechanism.hpp"
#include "camfollower/precompiled.hpp"  // the mechanisms and simulate() for them, compiled once
#include "camfollower/solver/newmark.hpp"

namespace camfollower::config {

struct SolverConfig {
    double revolutions = 1.0;  // of the camshaft; used unless duration > 0
    double duration = 0.0;     // s
    double time_step = 0.0;    // s; 0: period / steps_per_revolution
    long long steps_per_revolution = 32768;
    SolverSettings settings;  // method and Newton tolerances (its time_step: see time_step_for)
    bool settle = false;      // first settle on the periodic response
    double settle_tolerance = 1e-4;
    std::vector<std::string> settle_dofs;  // empty: each contact's follower DOF
    int settle_min_revolutions = 2;
    int settle_max_revolutions = 200;

    double time_step_for(double period) const {
        return time_step > 0.0 ? time_step : period / double(steps_per_revolution);
    }
    double duration_for(double period) const { return duration > 0.0 ? duration : revolutions * period; }
};

struct OutputConfig {
    std::string file;          // CSV of the recorded channels ("" : none); relative to the working directory
    long long decimation = 1;  // one row every `decimation` steps
    double record_last_revolutions = 0.0;  // > 0: record only the last revolutions
};

struct CaseConfig {
    std::string origin;                                           // the file (or "<config>") the case came from
    std::vector<std::pair<std::string, MotionProgram>> programs;  // by name, in file order
    std::string preset;  // "" for a mechanism described part by part, else the preset's name
    MechanismBuilder mechanism;
    SolverConfig solver;
    OutputConfig output;

    const MotionProgram& program(const std::string& name) const;
};

// `base_dir` resolves relative data-file paths (lift tables); load_case uses the config's folder.
CaseConfig parse_case(std::string_view text, const std::string& origin = "<config>", const std::string& base_dir = ".");
// Refuses a directory, an empty file or an unreadable path, naming it.
CaseConfig load_case(const std::string& path);

}  // namespace camfollower::config
