// SPDX-License-Identifier: BSD-3-Clause
// Building a case from an already parsed TOML table (the Python bindings convert a dict to one).
#pragma once

#include <string>

#include <toml++/toml.h>

#include "case_config.hpp"

namespace camfollower::config {

CaseConfig build_case(const toml::table& root, const std::string& origin, const std::string& base_dir);

}  // namespace camfollower::config
