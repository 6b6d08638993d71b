// Engine::solve's progress reports: a fraction that only grows and ends at
// 1, a time left that is finite and not negative when given, reports more
// often than once per round, and a solve that computes the same with them.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

std::vector<SolveProgress> solveRecording(Engine& engine) {
    std::vector<SolveProgress> reports;
    engine.solve([&](const SolveProgress& p) { reports.push_back(p); });
    return reports;
}

TEST(SolveProgress, FractionGrowsToOneAndTimeLeftIsFiniteWhenGiven) {
    Engine engine(loadGltf(test::kCornell), EngineSettings{});
    const std::vector<SolveProgress> reports = solveRecording(engine);
    const SolveStats& st = engine.stats();
    ASSERT_TRUE(st.converged) << st.message;
    ASSERT_GT(st.refineRounds, 1) << "the box needs several rounds: the test then sees the estimate";
    // Every round's start and end, the final report, and the sweeps between.
    ASSERT_GE(reports.size(), std::size_t(2 * st.refineRounds + 1));
    double previous = 0.0;
    std::size_t estimates = 0;
    for (std::size_t i = 0; i < reports.size(); ++i) {
        const SolveProgress& p = reports[i];
        EXPECT_FALSE(p.line.empty()) << i;
        EXPECT_GE(p.fraction, 0.0) << i << ": " << p.line;
        EXPECT_LE(p.fraction, 1.0) << i << ": " << p.line;
        EXPECT_GE(p.fraction, previous) << i << ": " << p.line;
        if (i + 1 < reports.size()) {
            EXPECT_LT(p.fraction, 1.0) << "1 only at the end: " << i << ": " << p.line;
        }
        previous = p.fraction;
        if (p.secondsLeft) {
            ++estimates;
            EXPECT_TRUE(std::isfinite(*p.secondsLeft)) << i << ": " << p.line;
            EXPECT_GE(*p.secondsLeft, 0.0) << i << ": " << p.line;
        }
    }
    EXPECT_EQ(reports.back().fraction, 1.0);
    ASSERT_TRUE(reports.back().secondsLeft);
    EXPECT_EQ(*reports.back().secondsLeft, 0.0);
    EXPECT_EQ(reports.back().line.rfind("done: ", 0), 0u) << reports.back().line;
    // From the second round on the decays are measured: an estimate is given.
    EXPECT_GT(estimates, 1u);
    EXPECT_GT(reports[reports.size() - 2].fraction, 0.0);
}

TEST(SolveProgress, ReportsDoNotChangeTheSolution) {
    Engine silent(loadGltf(test::kCornell), EngineSettings{});
    Engine reporting(loadGltf(test::kCornell), EngineSettings{});
    const SolveStats a = silent.solve();
    const std::vector<SolveProgress> reports = solveRecording(reporting);
    const SolveStats& b = reporting.stats();
    EXPECT_FALSE(reports.empty());
    EXPECT_EQ(a.refineRounds, b.refineRounds);
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_EQ(a.elements, b.elements);
    EXPECT_EQ(a.links, b.links);
    EXPECT_EQ(a.passiveLinks, b.passiveLinks);
    const std::vector<ObjectRadiosity> ra = silent.objectRadiosity(), rb = reporting.objectRadiosity();
    ASSERT_EQ(ra.size(), rb.size());
    for (std::size_t i = 0; i < ra.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(ra[i].radiosity[c], rb[i].radiosity[c], 1e-12 * (1.0 + std::abs(ra[i].radiosity[c])))
                << ra[i].name;
}

TEST(SolveProgress, AnExceptionFromTheCallbackLeavesTheSolve) {
    // The viewer cancels a solve this way when it quits.
    Engine engine(loadGltf(test::kCornell), EngineSettings{});
    int calls = 0;
    EXPECT_THROW(engine.solve([&](const SolveProgress&) {
        if (++calls == 3) throw std::runtime_error("cancelled");
    }),
                 std::runtime_error);
    EXPECT_EQ(calls, 3);
}

}  // namespace
}  // namespace rad
