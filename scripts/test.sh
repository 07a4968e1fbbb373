#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Every test: set-up, then the C++ tests (Catch2 + install/consumer check) and the Python tests.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh test
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build
ctest --test-dir build --output-on-failure
.venv/bin/python -m pytest tests/python
