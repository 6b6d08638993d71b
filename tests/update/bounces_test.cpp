// Further bounces (update/Bounces.cpp): the change of an edit carried
// through the links until nothing moves, with Aitken's extrapolation of the
// bounces to come once the change falls steadily.

#include <gtest/gtest.h>

#include "radiosity/Engine.h"
#include "support/Motion.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

double boxLuminance(const Engine& engine) {
    for (const ObjectRadiosity& o : engine.objectRadiosity())
        if (o.name == "box") return luminance(o.radiosity);
    ADD_FAILURE() << "no box";
    return 0.0;
}

// A closed box of reflectance 0.9 whose every face emits E reads E / (1 - 0.9)
// everywhere. Doubling E: each bounce sends 0.9 of the one before, so plain
// bounces take tens of them; sent ahead once the ratio is steady, a few. Both
// reach the furnace's answer, and the same solution.
TEST(FurtherBounces, ExtrapolatedBouncesReachTheFurnaceAnswerInFewerBounces) {
    const double rho = 0.9;
    int bounces[2] = {0, 0};
    double b[2] = {0.0, 0.0};
    for (bool extrapolate : {false, true}) {
        Engine engine(test::closedBox(rho), test::coarse());
        ASSERT_TRUE(engine.solve().converged);
        ASSERT_NEAR(boxLuminance(engine), 1.0 / (1.0 - rho), 0.01 / (1.0 - rho));
        UpdateSettings settings;
        settings.extrapolateBounces = extrapolate;
        const FrameStats stats = engine.editMaterial("box", glm::dvec3(2.0), std::nullopt, settings);
        bounces[extrapolate] = stats.bounces;
        b[extrapolate] = boxLuminance(engine);
        EXPECT_NEAR(b[extrapolate], 2.0 / (1.0 - rho), 0.01 * 2.0 / (1.0 - rho)) << "extrapolate " << extrapolate;
    }
    EXPECT_NEAR(b[1], b[0], 0.002 * b[0]);
    EXPECT_LT(bounces[1], bounces[0] / 3) << bounces[1] << " against " << bounces[0];
}

// A move's bounces send only the changes above
// UpdateSettings::moveBounceThreshold: the smaller ones wait, unsent
// (counted, and in the estimated error), and idle time sends them down to
// bounceThreshold, where the solution is the one a move that sends every
// change above bounceThreshold gives.
TEST(FurtherBounces, AMoveHoldsBackSmallChangesThatIdleTimeSends) {
    Engine held(test::roomWithBlock(), test::coarse());
    Engine sent(test::roomWithBlock(), test::coarse());
    ASSERT_TRUE(held.solve().converged);
    ASSERT_TRUE(sent.solve().converged);
    UpdateSettings all;
    all.moveBounceThreshold = all.bounceThreshold;
    const glm::dmat4 move = test::translation(glm::dvec3(0.3, 0.0, 0.1));
    const FrameStats h = held.moveDynamicObject(move);
    const FrameStats s = sent.moveDynamicObject(move, all);
    EXPECT_EQ(s.unsent, 0u);
    EXPECT_GT(h.unsent, 0u);
    EXPECT_GT(h.estimatedError, 0.0);
    EXPECT_LT(h.bounces, s.bounces);
    const double before = compareSamples(held.samples(), sent.samples()).rms;
    EXPECT_GT(before, 0.0);
    const FrameStats idle = held.refinePending();
    EXPECT_EQ(idle.unsent, 0u);
    EXPECT_GT(idle.bounces, 0);
    EXPECT_LT(compareSamples(held.samples(), sent.samples()).rms, 1e-4) << "before idle: " << before;
}

}  // namespace
}  // namespace rad
