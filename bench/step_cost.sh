#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Instructions per step (callgrind) of camfollower's Newmark against the hand-written tight one, on the
# paper preset, average acceleration and Fox-Goodwin; prints a Markdown table and the ratio.
#   bash bench/step_cost.sh [build-bench/bench/camfollower_step_cost]
set -euo pipefail
program="${1:-build-bench/bench/camfollower_step_cost}"
command -v valgrind >/dev/null || { echo "step_cost: valgrind not installed, skipped"; exit 0; }
instructions() {  # total instructions of one run
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$program" "$@" 2>&1 >/dev/null |
    sed -n 's/.*Collected : *\([0-9]*\).*/\1/p'
}
steps=20000
echo "| method | camfollower instructions / step | tight instructions / step | ratio |"
echo "|---|---|---|---|"
for method in newmark fox_goodwin; do
  [ "$("$program" camfollower $method $steps)" = "$("$program" tight $method $steps)" ] ||
    { echo "step_cost: the two steppers' states differ" >&2; exit 1; }
  ours=$(( ($(instructions camfollower $method $steps) - $(instructions camfollower $method 0)) / steps ))
  tight=$(( ($(instructions tight $method $steps) - $(instructions tight $method 0)) / steps ))
  echo "| $method | $ours | $tight | $(awk -v a="$ours" -v b="$tight" 'BEGIN { printf "%.2f", a / b }') |"
done
