// SPDX-License-Identifier: BSD-3-Clause
// Method "auto" (solver/choose_method.hpp): the fastest modes' rates and damping ratios against the
// closed form of a two-mass system, the choice under a tolerance (radau where the fastest mode is
// damped or, at tolerances of 1e-7 and looser, rings alone; else fox_goodwin at 1e-5 and looser,
// dop853 below) run exactly as the method chosen, the reason in words, bad settings.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/choose_method.hpp"
#include "camfollower/solver/simulate.hpp"
#include "linear_system_instances.hpp"

using namespace camfollower;

namespace {

// Two unit masses on a soft spring to ground (k0), coupled by a stiff spring k and a damper c. Their
// relative motion is a mode of natural rate sqrt(2 k) (reduced mass 1/2) and damping ratio
// c / (2 sqrt(k / 2)) = c / sqrt(2 k), to within k0 / k.
LinearSystem<2> coupled(double k, double c) {
    LinearSystem<2> s;
    const double k0 = 250.0;
    s.M = Eigen::Matrix2d::Identity();
    s.K << k0 + k, -k, -k, k;
    s.C << c, -c, -c, c;
    s.external = [](double t) { return Eigen::Vector2d(std::sin(6.0 * t), 0.0); };
    return s;
}

SolverSettings automatic(double output_interval, double tolerance) {
    SolverSettings s;
    s.method = method_from_name("auto");
    s.time_step = output_interval;
    s.tolerance = tolerance;
    return s;
}

// `chosen_by_auto` runs as the method auto names, value for value.
template <class System>
void check_same_run(const System& system, const SolverSettings& chosen_by_auto, const char* method, double duration) {
    RunOptions o;
    o.duration = duration;
    const auto r = simulate(system, chosen_by_auto, o);
    CHECK(std::string(r.method) == method);
    CHECK(std::string(r.requested_method) == "auto");
    CHECK(r.method_choice.rfind(std::string(method) + ": ", 0) == 0);
    SolverSettings named = chosen_by_auto;
    named.method = method_from_name(method);
    const auto direct = simulate(system, named, o);
    CHECK(direct.method_choice.empty());
    REQUIRE(direct.recording.rows == r.recording.rows);
    REQUIRE(r.report.stats.steps == direct.report.stats.steps);
    REQUIRE(r.recording.names == direct.recording.names);
    std::size_t differ = 0;
    for (const std::string& name : r.recording.names)
        for (std::size_t i = 0; i < r.recording.rows; ++i)
            differ += r.recording.at(name, i) != direct.recording.at(name, i);
    CHECK(differ == 0u);
}

}  // namespace

TEST_CASE("The fastest ringing and damped modes: rates and damping ratios of a coupled pair against the closed form") {
    const double k = 1e10;
    const double soft = std::sqrt(250.0 / 2.0);  // both masses on k0 as one
    for (double c : {1e3, 1e5}) {
        const LinearSystem<2> s = coupled(k, c);
        const FastestModes modes = fastest_modes(s, state_at(s, 0.0, s.q0, Eigen::Vector2d::Zero().eval()));
        const double rate = std::sqrt(2.0 * k), zeta = c / std::sqrt(2.0 * k);
        CAPTURE(c, zeta);
        const ModeRate& fast = zeta < ringing_damping_ratio ? modes.ringing : modes.damped;
        CHECK(fast.rate == Approx(rate).epsilon(1e-6));
        CHECK(fast.damping_ratio == Approx(zeta).epsilon(1e-6));
        // The soft mode rings (the damper does not act on the pair moving as one), next to the stiff one
        // or alone.
        const ModeRate& slow = zeta < ringing_damping_ratio ? modes.next_ringing : modes.ringing;
        CHECK(slow.rate == Approx(soft).epsilon(1e-6));
        CHECK(slow.damping_ratio < 1e-6);
        CHECK((zeta < ringing_damping_ratio ? modes.damped.rate : modes.next_ringing.rate) == 0.0);
    }
}

TEST_CASE("Auto under a tolerance: radau where the fastest mode is damped or rings alone, else fox_goodwin or dop853") {
    // zeta = 0.707: damped, radau (L-stable) steps over it.
    check_same_run(coupled(1e10, 1e5), automatic(0.01, 1e-6), "radau", 0.2);
    // zeta = 0.007: the stiff mode rings, 1.3e4 times faster than the soft one (alone): radau down to
    // 1e-7, dop853 below.
    check_same_run(coupled(1e10, 1e3), automatic(1e-4, 1e-6), "radau", 2e-3);
    check_same_run(coupled(1e10, 1e3), automatic(1e-4, 1e-8), "dop853", 2e-3);
    check_same_run(coupled(1e10, 1e3), automatic(0.1, 1e-6), "radau", 0.2);
    // The paper preset's fastest mode is the undamped cam contact (12.0 kHz), 1.15 times the next:
    // fox_goodwin at tolerances of 1e-5 and looser (with at least 12 halvings), dop853 below. With 3 % of critical in
    // every element a stiffly damped mode (11.0 kHz, 0.79) is faster than half of the fastest ringing one; with the
    // contact 100 times stiffer the contact mode (86 kHz) is 8.2 times the next.
    const Mechanism<presets::paper_dofs> paper = presets::paper(), damped = presets::paper_damped();
    CamFollowerParameters p;
    p.contact_stiffness *= 100.0;
    const Mechanism<presets::paper_dofs> stiff = presets::paper(p);
    SolverSettings loose = automatic(paper.period() / 512, 1e-5);
    loose.max_halvings = fox_goodwin_halvings;  // as auto sets it: the named run gets the same
    check_same_run(paper, loose, "fox_goodwin", paper.period() / 16);
    check_same_run(paper, automatic(paper.period() / 512, 1e-6), "dop853", paper.period() / 16);
    check_same_run(paper, automatic(paper.period() / 512, 1e-8), "dop853", paper.period() / 16);
    check_same_run(damped, automatic(damped.period() / 512, 1e-6), "radau", damped.period() / 16);
    check_same_run(stiff, automatic(stiff.period() / 512, 1e-7), "radau", stiff.period() / 16);
    check_same_run(stiff, automatic(stiff.period() / 512, 1e-9), "dop853", stiff.period() / 64);
    RunOptions o;
    o.duration = damped.period() / 64;
    const std::string why = simulate(damped, automatic(damped.period() / 512, 1e-6), o).method_choice;
    CHECK_THAT(
        why, Catch::StartsWith("radau: the fastest modes are damped: ") && Catch::Contains("Hz at damping ratio 0.78"));
    const std::string alone = simulate(stiff, automatic(stiff.period() / 512, 1e-6), o).method_choice;
    CHECK_THAT(alone, Catch::StartsWith("radau: the fastest mode rings alone") &&
                          Catch::Contains(" times the next ringing mode (1.052e+04 Hz)"));
    const std::string tight = simulate(stiff, automatic(stiff.period() / 512, 1e-8), o).method_choice;
    CHECK_THAT(tight, Catch::StartsWith("dop853: ") && Catch::Contains("tolerance < 1e-07"));
    const std::string ringing = simulate(paper, automatic(paper.period() / 512, 1e-6), o).method_choice;
    CHECK_THAT(ringing, Catch::StartsWith("dop853: the fastest modes ring: ") &&
                            !Catch::Contains("tolerance < 1e-07") && Catch::EndsWith("; tolerance < 1e-05"));
    const auto fox = simulate(paper, automatic(paper.period() / 512, 1e-4), o);
    CHECK_THAT(fox.method_choice,
               Catch::StartsWith("fox_goodwin: the fastest modes ring: ") && Catch::EndsWith("; tolerance >= 1e-05"));
    const State<Mechanism<presets::paper_dofs>> rest =
        state_at(paper, 0.0, paper.initial_displacement(), paper.initial_velocity());
    CHECK(choose_method(paper, automatic(paper.period() / 512, 1e-4), rest).settings.max_halvings == 12);
    SolverSettings more = automatic(paper.period() / 512, 1e-4);
    more.max_halvings = 14;
    CHECK(choose_method(paper, more, rest).settings.max_halvings == 14);
}

TEST_CASE("Auto under a tolerance above 1e-5 bounds radau's steps by the output interval, unless max_step is set") {
    const Mechanism<presets::paper_dofs> damped = presets::paper_damped();
    const State<Mechanism<presets::paper_dofs>> start =
        state_at(damped, 0.0, damped.initial_displacement(), damped.initial_velocity());
    const double dt = damped.period() / 2048;
    const MethodChoice loose = choose_method(damped, automatic(dt, 1e-4), start);
    CHECK(loose.settings.method == Method::radau);
    CHECK(loose.settings.max_step == dt);
    CHECK_THAT(loose.reason, Catch::EndsWith("; max_step = the output interval 3.906e-05 s (tolerance above 1e-05)"));
    SolverSettings bounded = automatic(dt, 1e-4);
    bounded.max_step = 4 * dt;
    CHECK(choose_method(damped, bounded, start).settings.max_step == 4 * dt);
    const MethodChoice tight = choose_method(damped, automatic(dt, 1e-5), start);
    CHECK(tight.settings.method == Method::radau);
    CHECK(tight.settings.max_step == 0.0);
    CHECK_THAT(tight.reason, !Catch::Contains("max_step"));
    // dop853 is left as asked.
    const Mechanism<presets::paper_dofs> paper = presets::paper();
    const MethodChoice explicit_choice = choose_method(
        paper, automatic(dt, 1e-8), state_at(paper, 0.0, paper.initial_displacement(), paper.initial_velocity()));
    CHECK(explicit_choice.settings.method == Method::dop853);
    CHECK(explicit_choice.settings.max_step == 0.0);
}

TEST_CASE("Auto at a fixed step says why it took Fox-Goodwin or average acceleration") {
    const Mechanism<presets::paper_dofs> paper = presets::paper();
    RunOptions o;
    o.duration = paper.period() / 64;
    SolverSettings s;
    s.method = method_from_name("auto");
    s.time_step = paper.period() / 8192;
    const auto fine = simulate(paper, s, o);
    CHECK(std::string(fine.method) == "fox_goodwin");
    CHECK_THAT(fine.method_choice,
               Catch::StartsWith("fox_goodwin: time_step 9.766e-06 s against Fox-Goodwin's stability limit"));
    s.time_step = paper.period() / 1024;  // 78 us: beyond the limit (~29 us at the 12 kHz contact mode)
    const auto coarse = simulate(paper, s, o);
    CHECK(std::string(coarse.method) == "newmark");
    CHECK_THAT(coarse.method_choice, Catch::StartsWith("newmark (average acceleration): time_step 7.81"));
}

TEST_CASE("Auto refuses settings it would ignore, naming them") {
    SolverSettings s = automatic(1e-3, 1e-6);
    CHECK(std::string(method_name(s.method)) == "auto");
    s = automatic(1e-3, 0.0);
    CHECK_THROWS_WITH(s.validate(), Catch::Contains("tolerance must be in [1e-13, 0.1]"));
    s = automatic(1e-3, 1e-6);
    s.beta = 1.0 / 12.0;
    CHECK_THROWS_WITH(s.validate(),
                      Catch::Contains("gamma and beta apply to method 'newmark' only, got them with method 'auto'"));
    s = automatic(1e-3, 1e-6);
    s.hht_alpha = -0.1;
    CHECK_THROWS_WITH(s.validate(),
                      Catch::Contains("hht_alpha applies to method 'hht' only, got it with method 'auto'"));
}
