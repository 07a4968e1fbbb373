// SPDX-License-Identifier: BSD-3-Clause
// simulate() and periodic_orbit() for the library's own system types, compiled once in the
// camfollower_instances library (one .cpp per system type) instead of in every unit that calls them:
// each instantiation builds every stepper (Newmark, sparse Newmark, both Runge-Kutta schemes), minutes
// of compile time per unit under the sanitizers. For the tests and the command line; a user's program
// needs none of this (the headers instantiate on demand).
#pragma once

#include <functional>
#include <optional>

#include "camfollower/model/cam_follower_model.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/simulate.hpp"

// CAMFOLLOWER_SIMULATE_INSTANCES(extern, S) declares the instantiations for system type S;
// CAMFOLLOWER_SIMULATE_INSTANCES(, S) defines them (in exactly one unit).
#define CAMFOLLOWER_SIMULATE_INSTANCES(PREFIX, SYSTEM)                                                           \
    PREFIX template camfollower::RunResult<SYSTEM> camfollower::simulate<SYSTEM>(                                \
        const SYSTEM&, const camfollower::SolverSettings&, const camfollower::RunOptions&,                      \
        const std::optional<SYSTEM::Vector>&, const std::optional<SYSTEM::Vector>&);                             \
    PREFIX template camfollower::PeriodicOrbit camfollower::periodic_orbit<SYSTEM>(                              \
        const SYSTEM&, const camfollower::SolverSettings&, camfollower::ShootingOptions,                       \
        const std::optional<SYSTEM::Vector>&, const std::optional<SYSTEM::Vector>&, const std::function<bool()>&);

CAMFOLLOWER_SIMULATE_INSTANCES(extern, camfollower::CamFollowerModel)
CAMFOLLOWER_SIMULATE_INSTANCES(extern, camfollower::Mechanism<>)
CAMFOLLOWER_SIMULATE_INSTANCES(extern, camfollower::Mechanism<camfollower::presets::paper_dofs>)
