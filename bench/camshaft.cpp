// SPDX-License-Identifier: BSD-3-Clause
// Cost per time step of a flexible camshaft with N cams (each with a valve and a surging spring), on
// the dense and the sparse (SuiteSparse) backends, side by side (Google Benchmark).
//   cmake -S . -B build-bench -DCAMFOLLOWER_BUILD_BENCHMARKS=ON && cmake --build build-bench
//   build-bench/bench/camfollower_bench_camshaft
// BM_CamshaftSteps/<cams>/<backend 0 dense, 1 sparse>: items_per_second = time steps per second;
// counters: dofs, iterations_per_step (Newton solves), peak_rss_MiB (process high-water mark so far:
// run one size alone, --benchmark_filter, for its own figure).
// BM_ValveTrainRevolution/<time step, ns>/<method 0 newmark, 1 fox_goodwin>: one camshaft revolution of
// the 16-cam valve train at 6000 engine rpm through simulate() (bench/valve_train_accuracy.py gives the
// accuracy of each); side by side: --benchmark_filter=ValveTrain --benchmark_repetitions=3
// --benchmark_enable_random_interleaving=true.
#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <algorithm>
#include <cmath>

#include "camfollower/camfollower.hpp"
#include "camfollower/model/presets/valve_train.hpp"
#include "camfollower/solver/sparse_newton.hpp"

namespace cf = camfollower;

namespace {

cf::presets::ValveTrainParameters with_cams(int cams) {
    cf::presets::ValveTrainParameters p;
    p.valves_per_cylinder = cams == 1 ? 1 : 2;
    p.cylinders = cams == 1 ? 1 : cams / 2;
    p.firing_order.clear();
    return p;
}

double peak_rss_mib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

constexpr double time_step = 1e-5;  // s

template <class Stepper>
void steps_of(benchmark::State& state, const cf::Mechanism<>& model, std::int64_t steps) {
    cf::SolverSettings settings;
    settings.time_step = time_step;
    Stepper stepper(model, settings);
    cf::SolverStatistics stats;
    for (auto _ : state) {
        auto s = stepper.start(0.0, model.initial_displacement(), model.initial_velocity());
        for (std::int64_t n = 0; n < steps; ++n) stepper.step(s, stats);
        benchmark::DoNotOptimize(s.q.data());
    }
    state.SetItemsProcessed(state.iterations() * steps);
    state.counters["dofs"] = model.size();
    state.counters["iterations_per_step"] = stats.mean_iterations();
    state.counters["peak_rss_MiB"] = peak_rss_mib();
}

void BM_CamshaftSteps(benchmark::State& state) {
    const int cams = int(state.range(0));
    const cf::Mechanism<> model(cf::presets::valve_train(with_cams(cams)));
    // Fewer steps per iteration for the dense backend at large sizes: it is the cost per step that counts.
    if (state.range(1) == 0)
        steps_of<cf::Newmark<cf::Mechanism<>>>(state, model, std::max<std::int64_t>(10, 400 / cams));
    else steps_of<cf::SparseNewmark<cf::Mechanism<>>>(state, model, 200);
    state.SetLabel(std::string(state.range(1) ? "sparse" : "dense") + ", " + std::to_string(cams) + " cams");
}
// The dense backend stops at 32 cams: its full LU (every cam in contact) costs ~n^3 per Newton iteration.
BENCHMARK(BM_CamshaftSteps)
    ->ArgsProduct({{1, 2, 4, 8, 16, 32}, {0, 1}})
    ->Args({64, 1})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(0.5);

void BM_ValveTrainRevolution(benchmark::State& state) {
    cf::presets::ValveTrainParameters p;
    p.cylinders = 8;  // 16 cams: an inline-8's intake shaft, or both shafts of an inline-4 DOHC
    p.firing_order.clear();
    p.engine_speed_rpm = 6000.0;
    const cf::Mechanism<> model(cf::presets::valve_train(p));
    cf::SolverSettings settings;
    settings.time_step = double(state.range(0)) * 1e-9;  // ns
    settings.method = state.range(1) == 0 ? cf::Method::newmark : cf::Method::fox_goodwin;
    cf::RunOptions options;
    options.duration = model.period();
    options.record.decimation = std::max<std::size_t>(1, std::size_t(std::lround(20e-6 / settings.time_step)));
    for (auto _ : state) {
        auto r = cf::simulate(model, settings, options);
        benchmark::DoNotOptimize(r.final_state.q.data());
        state.counters["backend_sparse"] = std::string(r.backend) == "sparse";
        state.counters["steps"] = double(r.report.stats.steps);
    }
}
BENCHMARK(BM_ValveTrainRevolution)
    ->Args({312, 0})
    ->Args({625, 0})
    ->Args({1250, 0})
    ->Args({2500, 0})
    ->Args({10000, 0})
    ->Args({625, 1})
    ->Args({1000, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
