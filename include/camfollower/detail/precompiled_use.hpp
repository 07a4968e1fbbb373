// SPDX-License-Identifier: BSD-3-Clause
// CAMFOLLOWER_USE_PRECOMPILED is 1 in a unit that links camfollower::precompiled without being part of
// it. The templates the library compiles are then declared extern next to their definitions (so before
// any inline code can use them), and such a unit neither instantiates nor compiles them: an Eigen
// decomposition named in a header's inline code costs seconds of compile time in every unit including
// it, whether or not the unit calls it (camfollower/precompiled.hpp).
#pragma once

#if defined(CAMFOLLOWER_PRECOMPILED) && !defined(CAMFOLLOWER_BUILDING_PRECOMPILED)
#define CAMFOLLOWER_USE_PRECOMPILED 1
#else
#define CAMFOLLOWER_USE_PRECOMPILED 0
#endif
