// SPDX-License-Identifier: BSD-3-Clause
// camfollower: dynamics of flexible cam-follower mechanisms. Facade header: the whole public API.
#pragma once

#include "camfollower/contact/conjugate.hpp"
#include "camfollower/contact/contact_pair.hpp"  // with every follower type (Follower)
#include "camfollower/contact/hertz.hpp"
#include "camfollower/contact/line_contact.hpp"
#include "camfollower/core/system.hpp"
#include "camfollower/error.hpp"
#include "camfollower/follower/contact_geometry.hpp"
#include "camfollower/follower/profile.hpp"
#include "camfollower/geometry/barrel_groove.hpp"
#include "camfollower/geometry/export.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/mechanism_modes.hpp"
#include "camfollower/model/presets/paper_parameters.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "camfollower/model/presets/valve_train.hpp"
#include "camfollower/motion/laws.hpp"
#include "camfollower/motion/program.hpp"
#include "camfollower/motion/speed_program.hpp"
#include "camfollower/motion/smoothness.hpp"
#include "camfollower/solver/choose_method.hpp"
#include "camfollower/solver/dispatch.hpp"
#include "camfollower/solver/integrate.hpp"
#include "camfollower/solver/newmark.hpp"
#include "camfollower/solver/observers.hpp"
#include "camfollower/solver/radau.hpp"
#include "camfollower/solver/settings.hpp"
#include "camfollower/solver/simulate.hpp"
#include "camfollower/solver/simulate_many.hpp"
#include "camfollower/solver/sparse_newton.hpp"
#include "camfollower/solver/state.hpp"
#include "camfollower/solver/stepper.hpp"
#include "camfollower/structure/network.hpp"
#include "camfollower/structure/shaft_assembly.hpp"
#include "camfollower/structure/shaft_spec.hpp"
#include "camfollower/structure/timoshenko_beam.hpp"
#include "camfollower/synthesis/lift_samples.hpp"
#include "camfollower/units.hpp"

// Linked with camfollower::precompiled: the library's mechanisms and simulate() for them come compiled.
#ifdef CAMFOLLOWER_PRECOMPILED
#include "camfollower/precompiled.hpp"
#endif
