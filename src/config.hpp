// Run configuration for the command-line program: a small TOML subset.
//
//   # comment
//   [model]                      model parameters by name (CamFollowerParameters)
//   offset = "10 mm"             numbers are SI; a quoted "<number> <unit>" converts known units
//   [defects]                    eccentricity, eccentricity_phase, backlash, backlash_switch_width
//   [run]                        revolutions, steps_per_revolution | time_step, decimation, output
//
// Unknown sections or keys, a unit of the wrong kind, a malformed line: std::invalid_argument with
// the file, line and key.
#pragma once

#include <string>

#include "camfollower/model/defects.hpp"
#include "camfollower/model/parameters.hpp"

namespace camfollower::cli {

struct RunConfig {
    CamFollowerParameters parameters;
    Defects defects;
    double revolutions = 1.0;
    double steps_per_revolution = 32768;  // used unless time_step is set
    double time_step = 0.0;               // s; 0 = period / steps_per_revolution
    double decimation = 1;
    std::string output = "camfollower_run.csv";
};

RunConfig parse_config(const std::string& text, const std::string& origin = "config");
RunConfig load_config(const std::string& path);

}  // namespace camfollower::cli
