#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The main job: set-up, then the paper's study on its built-in default case, written to ./out
# (extra arguments go to `camfollower study`, see its --help).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh study
.venv/bin/camfollower study "$@"
