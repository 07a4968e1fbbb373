// SPDX-License-Identifier: BSD-3-Clause
// simulate_many: every case on the pool gives bit for bit what simulate() gives alone, a failing case
// keeps its own error while the others run, every index runs exactly once, bad counts are refused.
#include <catch2/catch.hpp>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "camfollower/model/presets/paper.hpp"
#include "camfollower/solver/simulate_many.hpp"
#include "camfollower/precompiled.hpp"  // simulate() for the library's mechanisms, compiled once

using namespace camfollower;
using Paper = Mechanism<presets::paper_dofs>;

namespace {

Paper paper_with_contact_stiffness(double scale) {
    CamFollowerParameters p;
    p.contact_stiffness *= scale;
    return presets::paper(p);
}

SolverSettings fox_goodwin(const Paper& m) {
    SolverSettings s;
    s.method = method_from_name("fox_goodwin");
    s.time_step = m.period() / 4096.0;
    return s;
}

}  // namespace

TEST_CASE("simulate_many gives every case bit for bit what simulate gives it alone") {
    std::vector<Paper> models;
    for (double scale : {0.9, 1.0, 1.1, 1.2, 0.8}) models.push_back(paper_with_contact_stiffness(scale));
    std::vector<const Paper*> systems;
    for (const Paper& m : models) systems.push_back(&m);
    systems.push_back(&models[1]);  // one system twice: runs share only the immutable model
    const SolverSettings s = fox_goodwin(models[0]);
    RunOptions options;
    options.duration = 0.5 * models[0].period();
    options.record.decimation = 64;
    const std::vector<CaseRun<Paper>> runs = simulate_many(systems, s, {options}, 2);
    REQUIRE(runs.size() == systems.size());
    for (std::size_t i = 0; i < systems.size(); ++i) {
        INFO("case " << i);
        REQUIRE(runs[i].ok());
        const RunResult<Paper> alone = simulate(*systems[i], s, options);
        const Recording& a = alone.recording;
        const Recording& b = runs[i].result->recording;
        REQUIRE(a.rows == b.rows);
        REQUIRE(a.rows > 10);
        for (const char* channel : {"cam.force", "a.x3", "q.y1"})
            for (std::size_t r = 0; r < a.rows; ++r) REQUIRE(a.at(channel, r) == b.at(channel, r));
        CHECK(runs[i].result->report.stats.steps == alone.report.stats.steps);
    }
    // Different contact stiffnesses give different forces: the cases did not all run one system.
    CHECK(runs[0].result->recording.at("cam.force", 20) != runs[3].result->recording.at("cam.force", 20));
}

TEST_CASE("simulate_many keeps a failing case's error and runs the others") {
    const Paper m = presets::paper();
    const std::vector<const Paper*> systems{&m, &m, &m};
    RunOptions good;
    good.duration = 0.1 * m.period();
    RunOptions bad = good;
    bad.duration = -1.0;
    const std::vector<CaseRun<Paper>> runs = simulate_many(systems, fox_goodwin(m), {good, bad, good}, 3);
    CHECK(runs[0].ok());
    CHECK(runs[2].ok());
    REQUIRE_FALSE(runs[1].ok());
    REQUIRE(runs[1].error);
    try {
        std::rethrow_exception(runs[1].error);
    } catch (const std::invalid_argument& e) {
        CHECK_THAT(e.what(), Catch::Matchers::Contains("duration"));
    }
}

TEST_CASE("parallel_for runs every index exactly once on any number of threads") {
    for (unsigned threads : {0u, 1u, 2u, 7u}) {
        std::vector<std::atomic<int>> hits(1000);
        parallel_for(hits.size(), threads, [&](std::size_t i) { hits[i].fetch_add(1); });
        for (std::size_t i = 0; i < hits.size(); ++i) REQUIRE(hits[i].load() == 1);
    }
    CHECK(worker_threads(0, 1) == 1);
    CHECK(worker_threads(8, 3) == 3);
    CHECK(worker_threads(2, 100) == 2);
}

TEST_CASE("simulate_many refuses bad thread counts and option lists by name") {
    const Paper m = presets::paper();
    RunOptions o;
    o.duration = 0.01;
    CHECK_THROWS_WITH(simulate_many<Paper>({&m}, fox_goodwin(m), {o}, 5000), Catch::Matchers::Contains("threads"));
    CHECK_THROWS_WITH(simulate_many<Paper>({&m}, fox_goodwin(m), {o, o}, 1), Catch::Matchers::Contains("options"));
    CHECK_THROWS_WITH(simulate_many<Paper>({&m, nullptr}, fox_goodwin(m), {o}, 1),
                      Catch::Matchers::Contains("system 1"));
}
