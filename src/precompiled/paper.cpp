// SPDX-License-Identifier: BSD-3-Clause
// Mechanism<7>, its damper fit, its modes, simulate() and periodic_orbit() for the paper preset's fixed-size mechanism
// (camfollower/precompiled.hpp).
#define CAMFOLLOWER_BUILDING_PRECOMPILED
#include "camfollower/precompiled.hpp"

CAMFOLLOWER_MECHANISM_CLASS_INSTANCE(, camfollower::presets::paper_dofs)
CAMFOLLOWER_MODES_INSTANCES(, camfollower::presets::paper_dofs)
template camfollower::presets::PaperDampers camfollower::presets::fit_dampers<camfollower::presets::paper_dofs>(
    const camfollower::Mechanism<camfollower::presets::paper_dofs>&, double);
CAMFOLLOWER_SIMULATE_INSTANCES(, camfollower::Mechanism<camfollower::presets::paper_dofs>)
