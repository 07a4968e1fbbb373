#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Benchmarks (not part of the tests): C++ throughput (Google Benchmark), flexible camshafts with 1-64
# cams on the dense and sparse backends, work against precision of every method (and boost odeint's
# and SUNDIALS') on contact force and follower acceleration, the side-by-side comparison with scipy and Exudyn at equal
# accuracy, the scaling runs, the Monte-Carlo study on a Dask LocalCluster and Monte-Carlo transients on C++
# threads (simulate_many). Results go to ./bench-out.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh test
# boost::numeric::odeint (header-only) and SUNDIALS for the work-precision peers and reference;
# valgrind (callgrind) for the instructions per step.
for pkg in libboost-dev libsundials-dev valgrind; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
    $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "$pkg" >/dev/null
  fi
done
.venv/bin/python -c "import exudyn" 2>/dev/null || .venv/bin/python -m pip install -q exudyn
mkdir -p bench-out
cmake -S . -B build-bench -G Ninja -DCMAKE_BUILD_TYPE=Release -DCAMFOLLOWER_BUILD_BENCHMARKS=ON \
      -DCAMFOLLOWER_BUILD_TESTS=OFF -DCAMFOLLOWER_BUILD_CLI=OFF >/dev/null
cmake --build build-bench
build-bench/bench/camfollower_bench --benchmark_out=bench-out/throughput.json --benchmark_out_format=json
build-bench/bench/camfollower_bench_camshaft --benchmark_out=bench-out/camshaft.json --benchmark_out_format=json
bash bench/step_cost.sh | tee bench-out/step_cost.md
build-bench/bench/camfollower_work_precision | tee bench-out/work_precision.md
build-bench/bench/camfollower_work_precision --stiff | tee bench-out/work_precision_stiff.md
build-bench/bench/camfollower_work_precision --rpm 2000 | tee bench-out/work_precision_contact_loss.md
.venv/bin/python bench/camshaft_scaling.py bench-out/camshaft.json | tee bench-out/camshaft_scaling.txt
.venv/bin/python bench/valve_train_accuracy.py | tee bench-out/valve_train_accuracy.txt
.venv/bin/python bench/compare.py --out bench-out
.venv/bin/python bench/scaling.py | tee bench-out/scaling.txt
.venv/bin/python bench/montecarlo.py | tee bench-out/montecarlo.txt
.venv/bin/python bench/montecarlo_threads.py | tee bench-out/montecarlo_threads.txt
