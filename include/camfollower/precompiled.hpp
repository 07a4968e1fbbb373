// SPDX-License-Identifier: BSD-3-Clause
// simulate() and periodic_orbit() for the library's mechanisms, compiled once in the
// camfollower::precompiled library instead of in every unit that calls them: each instantiation
// builds every stepper (Newmark dense and sparse, Dormand-Prince 5(4) and 8(5,3), Radau), minutes of
// compile time per unit. Linking camfollower::precompiled defines CAMFOLLOWER_PRECOMPILED, and the
// facade (camfollower.hpp) then includes this header: a user's unit calling simulate() on a
// Mechanism<> or the paper preset instantiates no stepper (about half its compile time; the rest is
// the headers' own). Other systems instantiate on demand as before.
//
// The library and the user's units must agree on Eigen's alignment (a unit built with AVX, and the
// library without, would lay out the fixed-size vectors differently): a mismatch is a link error
// naming camfollower_precompiled_eigen_alignment_<bytes>, not a crash.
#pragma once

#include <functional>
#include <optional>

#include <Eigen/Core>

#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/simulate.hpp"

// CAMFOLLOWER_SIMULATE_INSTANCES(extern, S) declares the instantiations for system type S;
// CAMFOLLOWER_SIMULATE_INSTANCES(, S) defines them (in exactly one unit).
#define CAMFOLLOWER_SIMULATE_INSTANCES(PREFIX, SYSTEM)                                     \
    PREFIX template camfollower::RunResult<SYSTEM> camfollower::simulate<SYSTEM>(          \
        const SYSTEM&, const camfollower::SolverSettings&, const camfollower::RunOptions&, \
        const std::optional<SYSTEM::Vector>&, const std::optional<SYSTEM::Vector>&);       \
    PREFIX template camfollower::PeriodicOrbit camfollower::periodic_orbit<SYSTEM>(        \
        const SYSTEM&, const camfollower::SolverSettings&, camfollower::ShootingOptions,   \
        const std::optional<SYSTEM::Vector>&, const std::optional<SYSTEM::Vector>&, const std::function<bool()>&);

#define CAMFOLLOWER_PRECOMPILED_CAT2(a, b) a##b
#define CAMFOLLOWER_PRECOMPILED_CAT(a, b) CAMFOLLOWER_PRECOMPILED_CAT2(a, b)
// Defined in the library with its own EIGEN_MAX_STATIC_ALIGN_BYTES in the name.
#define CAMFOLLOWER_PRECOMPILED_ALIGNMENT \
    CAMFOLLOWER_PRECOMPILED_CAT(camfollower_precompiled_eigen_alignment_, EIGEN_MAX_STATIC_ALIGN_BYTES)

extern "C" const int CAMFOLLOWER_PRECOMPILED_ALIGNMENT;

#ifndef CAMFOLLOWER_BUILDING_PRECOMPILED
CAMFOLLOWER_SIMULATE_INSTANCES(extern, camfollower::Mechanism<>)
CAMFOLLOWER_SIMULATE_INSTANCES(extern, camfollower::Mechanism<camfollower::presets::paper_dofs>)
namespace camfollower::detail {
namespace {
// Every unit including this header refers to the library's alignment symbol (kept by `used` whatever
// the optimization): linked, or refused at link time.
[[gnu::used]] const int* const precompiled_alignment_check = &CAMFOLLOWER_PRECOMPILED_ALIGNMENT;
}  // namespace
}  // namespace camfollower::detail
#endif
