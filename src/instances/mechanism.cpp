// SPDX-License-Identifier: BSD-3-Clause
// simulate() and periodic_orbit() for any mechanism (dynamic size) (simulate_instances.hpp).
#include "simulate_instances.hpp"

CAMFOLLOWER_SIMULATE_INSTANCES(, camfollower::Mechanism<>)
