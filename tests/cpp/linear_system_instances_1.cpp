// SPDX-License-Identifier: BSD-3-Clause
// simulate() and periodic_orbit() for LinearSystem<1> (linear_system_instances.hpp), a unit of its own
// so that the three build in parallel.
#include "linear_system_instances.hpp"

CAMFOLLOWER_SIMULATE_INSTANCES(, LinearSystem<1>)
