// SPDX-License-Identifier: BSD-3-Clause
// Mechanism<7>, its modes, simulate() and periodic_orbit() for the paper preset's fixed-size mechanism
// (camfollower/precompiled.hpp).
#define CAMFOLLOWER_BUILDING_PRECOMPILED
#include "camfollower/precompiled.hpp"

CAMFOLLOWER_MECHANISM_INSTANCES(, camfollower::presets::paper_dofs)
CAMFOLLOWER_SIMULATE_INSTANCES(, camfollower::Mechanism<camfollower::presets::paper_dofs>)
