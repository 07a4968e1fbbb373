// SPDX-License-Identifier: BSD-3-Clause
// simulate() and periodic_orbit() for the original 7-DOF class (simulate_instances.hpp).
#include "simulate_instances.hpp"

CAMFOLLOWER_SIMULATE_INSTANCES(, camfollower::CamFollowerModel)
