// SPDX-License-Identifier: BSD-3-Clause
// The library's mechanisms, Mechanism<> and the paper preset's Mechanism<7> (construction, static
// analyses, modes), and simulate() and periodic_orbit() for both,
// compiled once in the camfollower::precompiled library instead of in every unit that uses them:
// each simulate() instantiation builds every stepper (Newmark dense and sparse, Dormand-Prince 5(4)
// and 8(5,3), Radau) and each Mechanism<N> Eigen's dense and sparse LU and eigen solvers, minutes of
// compile time per unit. Linking camfollower::precompiled defines CAMFOLLOWER_PRECOMPILED, and the
// facade (camfollower.hpp) then includes this header: a user's unit building and simulating a
// Mechanism<> or the paper preset instantiates neither. Other systems instantiate on demand as before.
// (Mechanism's heavy members are defined outside its class body so that the declaration below keeps
// them out of the user's unit; members defined in a class body are inline, and an optimizing compiler
// instantiates those even so.)
//
// The library and the user's units must agree on Eigen's alignment (a unit built with AVX, and the
// library without, would lay out the fixed-size vectors differently): a mismatch is a link error
// naming camfollower_precompiled_eigen_alignment_<bytes>, not a crash.
#pragma once

#include <functional>
#include <optional>

#include <Eigen/Core>

#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/mechanism_modes.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/simulate.hpp"

// CAMFOLLOWER_SIMULATE_INSTANCES(extern, S) declares the instantiations for system type S;
// CAMFOLLOWER_SIMULATE_INSTANCES(, S) defines them (in exactly one unit). With them the dense Newmark
// stepper, for a unit that steps one itself.
#define CAMFOLLOWER_SIMULATE_INSTANCES(PREFIX, SYSTEM)                                     \
    PREFIX template class camfollower::Newmark<SYSTEM>;                                    \
    PREFIX template camfollower::RunResult<SYSTEM> camfollower::simulate<SYSTEM>(          \
        const SYSTEM&, const camfollower::SolverSettings&, const camfollower::RunOptions&, \
        const std::optional<SYSTEM::Vector>&, const std::optional<SYSTEM::Vector>&);       \
    PREFIX template camfollower::PeriodicOrbit camfollower::periodic_orbit<SYSTEM>(        \
        const SYSTEM&, const camfollower::SolverSettings&, camfollower::ShootingOptions,   \
        const std::optional<SYSTEM::Vector>&, const std::optional<SYSTEM::Vector>&, const std::function<bool()>&);

// CAMFOLLOWER_MODES_INSTANCES(extern, N): the same for the modes of Mechanism<N>. Mechanism<N> itself
// (its construction and static analyses, which instantiate Eigen's dense and sparse LU and eigen
// solvers), the paper preset's damper fit and the motion laws' decompositions are declared extern where
// they are defined (detail/precompiled_use.hpp), before any inline code uses them.
#define CAMFOLLOWER_MODES_INSTANCES(PREFIX, DOFS)                                                                    \
    PREFIX template camfollower::MechanismModes camfollower::lowest_modes<DOFS>(const camfollower::Mechanism<DOFS>&, \
                                                                                double, int);

#define CAMFOLLOWER_PRECOMPILED_CAT2(a, b) a##b
#define CAMFOLLOWER_PRECOMPILED_CAT(a, b) CAMFOLLOWER_PRECOMPILED_CAT2(a, b)
// Defined in the library with its own EIGEN_MAX_STATIC_ALIGN_BYTES in the name.
#define CAMFOLLOWER_PRECOMPILED_ALIGNMENT \
    CAMFOLLOWER_PRECOMPILED_CAT(camfollower_precompiled_eigen_alignment_, EIGEN_MAX_STATIC_ALIGN_BYTES)

extern "C" const int CAMFOLLOWER_PRECOMPILED_ALIGNMENT;

#ifndef CAMFOLLOWER_BUILDING_PRECOMPILED
CAMFOLLOWER_MODES_INSTANCES(extern, Eigen::Dynamic)
CAMFOLLOWER_MODES_INSTANCES(extern, camfollower::presets::paper_dofs)
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
