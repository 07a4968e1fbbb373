// SPDX-License-Identifier: BSD-3-Clause
// Built with EIGEN_MAX_STATIC_ALIGN_BYTES=0 against a library built with the default alignment: the
// fixed-size vectors would be laid out differently, so the link must fail (camfollower/precompiled.hpp).
#include <camfollower/precompiled.hpp>

int main() { return 0; }
