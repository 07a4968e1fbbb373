// SPDX-License-Identifier: BSD-3-Clause
// simulate() and periodic_orbit() for the library's system types, compiled once for the tests and the
// command line: the mechanisms in camfollower::precompiled (camfollower/precompiled.hpp), the original
// 7-DOF class here (camfollower_instances). A user's program links camfollower::precompiled or
// instantiates on demand.
#pragma once

#include "camfollower/model/cam_follower_model.hpp"
#include "camfollower/precompiled.hpp"

CAMFOLLOWER_SIMULATE_INSTANCES(extern, camfollower::CamFollowerModel)
