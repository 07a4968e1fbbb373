#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Every test: set-up; the C++ tests and the command-line program built with AddressSanitizer +
# UndefinedBehaviorSanitizer (float-cast-overflow included) and our warnings (-Wshadow -Wconversion
# ...) as errors in ./build-sanitize, run by ctest (Catch2, install/consumer check, command line);
# then the Python tests on the installed package (the config fuzzer drives the sanitized program).
set -euo pipefail
cd "$(dirname "$0")/.."
# The compilers first; then the sanitized build runs in the background while set-up fetches the rest
# (Chromium, the Python packages: network time) and builds the Python package. Each build runs a job per
# core (CMAKE_BUILD_PARALLEL_LEVEL reaches the package build); the largest sanitized unit takes 6 GiB.
bash scripts/setup.sh compilers
# ccache (installed by setup.sh) keyed on paths relative to the clone: a rebuild, or another clone of
# the same sources on this machine, compiles only what changed.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
jobs=$(nproc)
export CMAKE_BUILD_PARALLEL_LEVEL=$jobs
# -O1 without debug information: a third of the compile time of -O1 -g; reports still name functions.
# Without ASan's use-after-scope instrumentation (a stack object used after its block ended): a sixth
# less compile time (321 against 266 s CPU for the paper preset's precompiled unit, compiled side by
# side); use-after-free, overflows and leaks on heap and stack, and UBSan's checks all stay.
cmake -S . -B build-sanitize -G Ninja -DCAMFOLLOWER_BUILD_TESTS=ON -DCAMFOLLOWER_BUILD_CLI=ON \
      -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -fno-sanitize-address-use-after-scope" \
      -DCMAKE_CXX_COMPILER_LAUNCHER="$(command -v ccache || true)" \
      -DCAMFOLLOWER_SANITIZE=address,undefined -DCAMFOLLOWER_WERROR=ON >/dev/null
build_log=build-sanitize/build.log
# Ninja itself in the background (not through cmake --build), so that stopping it on a failed set-up
# stops its compiles too.
ninja -C build-sanitize -j "$jobs" >"$build_log" 2>&1 &
build=$!
trap 'kill "$build" 2>/dev/null || true' EXIT
echo "test: building the sanitized C++ tests in the background ($build_log)"
bash scripts/setup.sh test
if ! wait "$build"; then
  cat "$build_log"
  echo "test: the sanitized build failed" >&2
  exit 1
fi
trap - EXIT
tail -n 1 "$build_log"
# Both cores: the tests are independent (each writes in its own temporary folder).
ctest --test-dir build-sanitize --output-on-failure -j "$jobs"
# The design page's browser test must run here (setup.sh installed Chromium), not be skipped.
CAMFOLLOWER_REQUIRE_BROWSER=1 .venv/bin/python -m pytest tests/python -n "$jobs"
