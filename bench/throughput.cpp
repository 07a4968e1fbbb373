// SPDX-License-Identifier: BSD-3-Clause
// Throughput of the paper preset's Newmark-Newton integration (Google Benchmark).
//   cmake -S . -B build-bench -DCAMFOLLOWER_BUILD_BENCHMARKS=ON && cmake --build build-bench
//   build-bench/bench/camfollower_bench
// items_per_second = time steps per second; iterations_per_step = Newton linear solves per step.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "camfollower/camfollower.hpp"
#include "tight_newmark.hpp"

namespace cf = camfollower;
using Model = cf::Mechanism<cf::presets::paper_dofs>;

namespace {

// The paper preset: healthy (0), with the paper's 10 um camshaft eccentricity as its literal force (1),
// with the paper's imposed 10 um backlash, switched over 2 degrees (2).
Model defect_case(int which) {
    cf::presets::PaperOptions options;
    if (which == 1) {
        options.eccentricity.radius = 10e-6;
        options.eccentricity.formulation = cf::EccentricityFormulation::paper_force_camshaft;
    }
    if (which == 2) options.paper_backlash = 10e-6, options.paper_backlash_switch_width = cf::degrees_to_radians(2.0);
    return cf::presets::paper({}, cf::MotionProgram::paper_default(), options);
}

// Bare stepping: step() over one revolution, no output recorded.
void BM_Steps(benchmark::State& state) {
    const Model model = defect_case(int(state.range(0)));
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
    state.SetLabel(std::string(state.range(0) == 0   ? "healthy"
                               : state.range(0) == 1 ? "eccentricity"
                                                     : "backlash") +
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

// Fox-Goodwin at T/8192 (its velocity processed to fourth order since 2026-11-30), Mechanism<7>.
void BM_PresetFoxGoodwinSteps(benchmark::State& state) {
    const auto model = cf::presets::paper();
    using M = std::decay_t<decltype(model)>;
    const double dt = model.period() / 8192.0;
    cf::Newmark<M> stepper(model, cf::SolverSettings::named(cf::Method::fox_goodwin, dt));
    cf::SolverStatistics stats;
    for (auto _ : state) {
        auto s = stepper.start(0.0, model.initial_displacement(), M::Vector::Zero());
        for (int n = 0; n < 8192; ++n) stepper.step(s, stats);
        benchmark::DoNotOptimize(s.q.data());
    }
    state.SetItemsProcessed(state.iterations() * 8192);
    state.SetLabel("paper preset, fox_goodwin, T/8192");
}
BENCHMARK(BM_PresetFoxGoodwinSteps)->Unit(benchmark::kMillisecond);

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
    const Model model = cf::presets::paper();
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

// The time-dependent part of a step: the motion law and the contact geometry (normal, lever, their
// rates) of the paper's translating roller.
void BM_ProfileEvaluation(benchmark::State& state) {
    const cf::MotionProgram program = cf::MotionProgram::paper_default();
    const cf::TranslatingRoller roller(0.030, 0.008, 0.010);
    double theta = 0.0;
    const double step = cf::degrees_to_radians(0.01);
    for (auto _ : state) {
        const cf::ContactGeometry c = roller.contact(theta, program.evaluate(theta));
        benchmark::DoNotOptimize(c);
        theta += step;
        if (theta > cf::two_pi) theta = 0.0;
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ProfileEvaluation);

// A user's lift table of 10 000 points: interpolating (arg 0) or smoothing (arg 1) quintic spline.
void BM_LiftTable(benchmark::State& state) {
    const int n = 10000;
    std::vector<double> theta(n), h(n);
    for (int i = 0; i < n; ++i) {
        theta[std::size_t(i)] = 2.0 * cf::pi * i / n;
        h[std::size_t(i)] =
            0.004 * (1.0 - std::cos(theta[std::size_t(i)])) + 0.001 * std::sin(2.0 * theta[std::size_t(i)]);
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
