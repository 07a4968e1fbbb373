#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The main job: set-up, then the paper's study on its built-in default case, written to ./out
# (extra arguments go to `python -m camfollower.study`, see --help).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh study
.venv/bin/python -m camfollower.study "$@"
