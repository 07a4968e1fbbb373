#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Every test: set-up; the C++ tests and the command-line program built with AddressSanitizer +
# UndefinedBehaviorSanitizer (float-cast-overflow included) and our warnings (-Wshadow -Wconversion
# ...) as errors in ./build-sanitize, run by ctest (Catch2, install/consumer check, command line);
# then the Python tests on the installed package (the config fuzzer drives the sanitized program).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh test
# -O1 without debug information: a third of the compile time of -O1 -g; reports still name functions.
cmake -S . -B build-sanitize -G Ninja -DCAMFOLLOWER_BUILD_TESTS=ON -DCAMFOLLOWER_BUILD_CLI=ON \
      -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O1 \
      -DCAMFOLLOWER_SANITIZE=address,undefined -DCAMFOLLOWER_WERROR=ON >/dev/null
cmake --build build-sanitize
ctest --test-dir build-sanitize --output-on-failure
.venv/bin/python -m pytest tests/python
