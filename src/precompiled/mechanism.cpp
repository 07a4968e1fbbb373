// SPDX-License-Identifier: BSD-3-Clause
// Mechanism<>, its modes, simulate() and periodic_orbit() for any mechanism (dynamic size), the
// motion laws' decompositions (detail/linear_solvers.hpp) and the library's Eigen alignment
// (camfollower/precompiled.hpp).
#define CAMFOLLOWER_BUILDING_PRECOMPILED
#include "camfollower/precompiled.hpp"

extern "C" const int CAMFOLLOWER_PRECOMPILED_ALIGNMENT = EIGEN_MAX_STATIC_ALIGN_BYTES;

CAMFOLLOWER_MECHANISM_CLASS_INSTANCE(, Eigen::Dynamic)
CAMFOLLOWER_MODES_INSTANCES(, Eigen::Dynamic)
CAMFOLLOWER_SIMULATE_INSTANCES(, camfollower::Mechanism<>)
CAMFOLLOWER_LINEAR_SOLVER_INSTANCES()
