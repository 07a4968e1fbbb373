// SPDX-License-Identifier: BSD-3-Clause
// Instructions per Newmark step of the paper preset, camfollower's stepper against the hand-written
// tight one (tight_newmark.hpp) on the same model evaluation: run under callgrind by
// bench/step_cost.sh, which takes the difference between N steps and none (model construction and
// start-up cancel out).
//   camfollower_step_cost {camfollower|tight} {newmark|fox_goodwin} STEPS
// newmark: average acceleration at the default 3 us; fox_goodwin: T / 8192.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/newmark.hpp"
#include "tight_newmark.hpp"

namespace cf = camfollower;

int main(int argc, char** argv) {
    if (argc != 4 || (std::strcmp(argv[1], "camfollower") && std::strcmp(argv[1], "tight")) ||
        (std::strcmp(argv[2], "newmark") && std::strcmp(argv[2], "fox_goodwin"))) {
        std::fprintf(stderr, "usage: %s {camfollower|tight} {newmark|fox_goodwin} STEPS\n", argv[0]);
        return 2;
    }
    const auto model = cf::presets::paper();
    using M = std::decay_t<decltype(model)>;
    const long steps = std::atol(argv[3]);
    cf::SolverSettings settings;
    settings.method = cf::method_from_name(argv[2]);
    if (settings.method == cf::Method::fox_goodwin) settings.time_step = model.period() / 8192.0;
    double q_end = 0.0;
    if (!std::strcmp(argv[1], "tight")) {
        bench::TightNewmark<M> stepper(model, settings.time_step, cf::newmark_parameters(settings).beta);
        stepper.start(0.0, model.initial_displacement(), M::Vector::Zero());
        for (long n = 0; n < steps; ++n)
            if (!stepper.step()) return 1;
        q_end = stepper.q()[3];
    } else {
        cf::Newmark<M> stepper(model, settings);
        cf::SolverStatistics stats;
        auto s = stepper.start(0.0, model.initial_displacement(), M::Vector::Zero());
        for (long n = 0; n < steps; ++n) stepper.step(s, stats);
        q_end = s.q[3];
    }
    std::printf("%.17g\n", q_end);  // the same for both steppers (same states)
    return 0;
}
