// SPDX-License-Identifier: BSD-3-Clause
// Throughput of the 7-DOF Newmark-Newton integration (Google Benchmark).
//   cmake -S . -B build-bench -DCAMFOLLOWER_BUILD_BENCHMARKS=ON && cmake --build build-bench
//   build-bench/bench/camfollower_bench
// items_per_second = time steps per second; iterations_per_step = Newton linear solves per step.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "camfollower/camfollower.hpp"
#include "camfollower/model/mechanism.hpp"
#include "camfollower/model/presets/paper.hpp"
#include "tight_newmark.hpp"

namespace cf = camfollower;
using Model = cf::CamFollowerModel;

namespace {

cf::Defects defect_case(int which) {
    cf::Defects d;
    if (which == 1) d.eccentricity = 10e-6;
    if (which == 2) d.backlash = 10e-6, d.backlash_switch_width = cf::degrees_to_radians(2.0);
    return d;
}

// Bare stepping: step() over one revolution, no output recorded.
void BM_Steps(benchmark::State& state) {
    const Model model({}, cf::MotionProgram::paper_default(), defect_case(int(state.range(0))));
    cf::SolverSettings settings;
    settings.linear_solver = state.range(1) ? cf::LinearSolver::dense_lu : cf::LinearSolver::sherman_morrison;
    cf::Newmark<Model> stepper(model, settings);
    const auto steps = static_cast<std::int64_t>(model.period() / settings.time_step);
    cf::SolverStatistics stats;
    for (auto _ : state) {
        auto s = stepper.start(0.0, model.initial_displacement(), Model::Vector::Zero());
        for (std::int64_t n = 0; n < steps; ++n) stepper.step(s, stats);
        benchmark::DoNotOptimize(s.q.data());
    }
    state.SetItemsProcessed(state.iterations() * steps);
    state.counters["iterations_per_step"] = stats.mean_iterations();
    state.counters["ns_per_step"] = benchmark::Counter(double(state.iterations() * steps),
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.SetLabel(std::string(state.range(0) == 0 ? "healthy" : state.range(0) == 1 ? "eccentricity" : "backlash") +
                   (state.range(1) ? ", dense LU" : ", Sherman-Morrison"));
}
BENCHMARK(BM_Steps)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);

// The same 7-DOF model built by the mechanism builder (the paper preset): fixed size (as the preset
// ships) and the same description at dynamic size (what any other user mechanism gets).
template <class M>
void steps_of(benchmark::State& state, const M& model) {
    cf::Newmark<M> stepper(model, cf::SolverSettings{});
    const auto steps = static_cast<std::int64_t>(model.period() / 3e-6);
    cf::SolverStatistics stats;
    for (auto _ : state) {
        auto s = stepper.start(0.0, model.initial_displacement(), M::Vector::Zero(model.size()));
        for (std::int64_t n = 0; n < steps; ++n) stepper.step(s, stats);
        benchmark::DoNotOptimize(s.q.data());
    }
    state.SetItemsProcessed(state.iterations() * steps);
    state.counters["iterations_per_step"] = stats.mean_iterations();
}
void BM_PresetSteps(benchmark::State& state) {
    const auto preset = cf::presets::paper();
    if (state.range(0) == 0) {
        steps_of(state, preset);
        state.SetLabel("paper preset, Mechanism<7>");
    } else {
        steps_of(state, cf::Mechanism<>(preset.description()));
        state.SetLabel("paper preset, Mechanism<Dynamic>");
    }
}
BENCHMARK(BM_PresetSteps)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The yardstick of the stepper's own overhead: a minimal hand-written Newmark (tight_newmark.hpp) on
// the same model evaluation and step as BM_PresetSteps/0, producing the same states.
void BM_TightSteps(benchmark::State& state) {
    const auto model = cf::presets::paper();
    using M = std::decay_t<decltype(model)>;
    bench::TightNewmark<M> stepper(model, 3e-6, 0.25);
    const auto steps = static_cast<std::int64_t>(model.period() / 3e-6);
    for (auto _ : state) {
        stepper.start(0.0, model.initial_displacement(), M::Vector::Zero());
        for (std::int64_t n = 0; n < steps; ++n)
            if (!stepper.step()) state.SkipWithError("tight Newmark: Newton did not converge");
        benchmark::DoNotOptimize(stepper.q().data());
    }
    state.SetItemsProcessed(state.iterations() * steps);
    state.SetLabel("paper preset, Mechanism<7>, hand-written");
}
BENCHMARK(BM_TightSteps)->Unit(benchmark::kMillisecond);

// A whole run with every step recorded (what simulate() does).
void BM_RunRecorded(benchmark::State& state) {
    const Model model;
    cf::RunOptions options;
    options.duration = model.period();
    options.record.decimation = std::size_t(state.range(0));
    std::uint64_t steps = 0;
    for (auto _ : state) {
        const auto r = cf::simulate(model, cf::SolverSettings{}, options);
        steps = r.report.stats.steps;
        benchmark::DoNotOptimize(r.recording.data.data());
    }
    state.SetItemsProcessed(state.iterations() * std::int64_t(steps));
    state.SetLabel("decimation " + std::to_string(state.range(0)));
}
BENCHMARK(BM_RunRecorded)->Arg(1)->Arg(100)->Unit(benchmark::kMillisecond);

// The time-dependent part of a step: cam profile, contact direction, defect terms.
void BM_ProfileEvaluation(benchmark::State& state) {
    const Model model({}, cf::MotionProgram::paper_default(), defect_case(int(state.range(0))));
    double t = 0.0;
    const double dt = 3e-6;
    for (auto _ : state) {
        const auto c = model.at_time(t);
        benchmark::DoNotOptimize(c.delta0);
        t += dt;
        if (t > model.period()) t = 0.0;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ProfileEvaluation)->Arg(0)->Arg(1)->Arg(2);

// A user's lift table of 10 000 points: interpolating (arg 0) or smoothing (arg 1) quintic spline.
void BM_LiftTable(benchmark::State& state) {
    const int n = 10000;
    std::vector<double> theta(n), h(n);
    for (int i = 0; i < n; ++i) {
        theta[std::size_t(i)] = 2.0 * cf::pi * i / n;
        h[std::size_t(i)] = 0.004 * (1.0 - std::cos(theta[std::size_t(i)])) + 0.001 * std::sin(2.0 * theta[std::size_t(i)]);
    }
    for (auto _ : state) {
        const cf::MotionProgram p = state.range(0) ? cf::MotionProgram::from_table(theta, h, {5, 1e-12})
                                                   : cf::MotionProgram::from_table(theta, h);
        benchmark::DoNotOptimize(p.max_lift());
    }
}
BENCHMARK(BM_LiftTable)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
