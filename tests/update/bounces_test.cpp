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

}  // namespace
}  // namespace rad
