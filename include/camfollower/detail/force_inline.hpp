// SPDX-License-Identifier: BSD-3-Clause
// CAMFOLLOWER_FORCE_INLINE: for the few small functions of the time-step hot path whose inlining the
// compiler gives up once a second integrator calls them too (measured: the 7-DOF model's force()
// called out of line cost 9 % more instructions and 22 % of the steps per second).
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define CAMFOLLOWER_FORCE_INLINE inline __attribute__((always_inline))
#elif defined(_MSC_VER)
#define CAMFOLLOWER_FORCE_INLINE __forceinline
#else
#define CAMFOLLOWER_FORCE_INLINE inline
#endif

// CAMFOLLOWER_NOINLINE: for the rare branch of a hot function (an event to locate), kept out of line
// so that it does not weigh on the inlining of the common path.
#if defined(__GNUC__) || defined(__clang__)
#define CAMFOLLOWER_NOINLINE __attribute__((noinline))
#elif defined(_MSC_VER)
#define CAMFOLLOWER_NOINLINE __declspec(noinline)
#else
#define CAMFOLLOWER_NOINLINE
#endif
