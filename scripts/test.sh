#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Every test: set-up; the C++ tests and the command-line program built with AddressSanitizer +
# UndefinedBehaviorSanitizer (float-cast-overflow included) and our warnings (-Wshadow -Wconversion
# ...) as errors in ./build-sanitize, run by ctest (Catch2, install/consumer check, command line);
# then the Python tests on the installed package (the config fuzzer drives the sanitized program).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh test
# ccache (installed by setup.sh) keyed on paths relative to the clone: a rebuild, or another clone of
# the same sources on this machine, compiles only what changed.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
# -O1 without debug information: a third of the compile time of -O1 -g; reports still name functions.
cmake -S . -B build-sanitize -G Ninja -DCAMFOLLOWER_BUILD_TESTS=ON -DCAMFOLLOWER_BUILD_CLI=ON \
      -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O1 \
      -DCMAKE_CXX_COMPILER_LAUNCHER="$(command -v ccache || true)" \
      -DCAMFOLLOWER_SANITIZE=address,undefined -DCAMFOLLOWER_WERROR=ON >/dev/null
cmake --build build-sanitize
# Both cores: the tests are independent (each writes in its own temporary folder).
ctest --test-dir build-sanitize --output-on-failure -j 2
# The design page's browser test must run here (setup.sh installed Chromium), not be skipped.
CAMFOLLOWER_REQUIRE_BROWSER=1 .venv/bin/python -m pytest tests/python -n 2
