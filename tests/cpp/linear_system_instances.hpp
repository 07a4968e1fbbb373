// SPDX-License-Identifier: BSD-3-Clause
// simulate() and periodic_orbit() for the linear test systems, compiled once (linear_system_instances_N.cpp)
// rather than in each test that runs them; with the library's mechanisms (camfollower/precompiled.hpp).
#pragma once

#include "linear_system.hpp"
#include "camfollower/precompiled.hpp"  // simulate() for the library's mechanisms, compiled once

CAMFOLLOWER_SIMULATE_INSTANCES(extern, LinearSystem<1>)
CAMFOLLOWER_SIMULATE_INSTANCES(extern, LinearSystem<2>)
