// SPDX-License-Identifier: BSD-3-Clause
// The name of the fixed frame wherever an element's end or role names a DOF.
#pragma once

#include <string>

namespace camfollower {

inline const std::string ground_name = "ground";

}  // namespace camfollower
