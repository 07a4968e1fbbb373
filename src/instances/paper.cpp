// SPDX-License-Identifier: BSD-3-Clause
// simulate() and periodic_orbit() for the paper preset's fixed-size mechanism (simulate_instances.hpp).
#include "simulate_instances.hpp"

CAMFOLLOWER_SIMULATE_INSTANCES(, camfollower::Mechanism<camfollower::presets::paper_dofs>)
