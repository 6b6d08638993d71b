// An emission edit c times the last one sends c times that edit's light at
// once, and its bounces only what that misses (update/EditResponse.h):
// checked against the same edits made by bounces alone and against a full
// solve of the edited scene.

#include <gtest/gtest.h>

#include "radiosity/Engine.h"
#include "support/Motion.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;

UpdateSettings bouncesOnly() {
    UpdateSettings s;
    s.scaleLastEdit = false;
    return s;
}

// The room solved twice: `scaled` scales the last edit's light, `plain` is
// given bouncesOnly().
class ScaledLastEdit : public ::testing::Test {
  protected:
    void SetUp() override {
        ASSERT_TRUE(scaled.solve().converged);
        ASSERT_TRUE(plain.solve().converged);
    }
    const EngineSettings settings = test::coarse();
    Engine scaled{test::roomWithBlock(), settings};
    Engine plain{test::roomWithBlock(), settings};
};

// The room's light dimmed in equal steps: from the second step on, each
// step is the last one again, and sends its light at once. Both ways reach
// the same solution (to the bounce threshold), that of a full solve.
TEST_F(ScaledLastEdit, ALightDimmedInStepsSendsEachStepsLightAtOnce) {
    const V emission(10.0);
    for (int step = 1; step <= 4; ++step) {
        const V to = emission * (1.0 - 0.2 * step);
        const FrameStats a = scaled.editMaterial("light", to, std::nullopt);
        const FrameStats b = plain.editMaterial("light", to, std::nullopt, bouncesOnly());
        EXPECT_GT(b.transfers, 0u);
        if (step > 1) {
            EXPECT_LT(a.transfers, b.transfers / 3) << "step " << step;
        }
        EXPECT_LT(compareSamples(scaled.samples(), plain.samples()).rms, 2e-3) << "step " << step;
    }
    const SolutionError e = test::compareWithFullSolve(scaled, settings);
    EXPECT_LT(e.rms, 0.005) << "max " << e.max << ", worst object " << e.worstObjectRms;
}

// Each channel scales on its own: a light turned redder in steps (its red
// falling, its green and blue kept) is the last step again.
TEST_F(ScaledLastEdit, ALightRecolouredInStepsScalesChannelByChannel) {
    for (int step = 1; step <= 3; ++step) {
        const V to(10.0, 10.0 - 2.0 * step, 10.0 - 3.0 * step);
        const FrameStats a = scaled.editMaterial("light", to, std::nullopt);
        const FrameStats b = plain.editMaterial("light", to, std::nullopt, bouncesOnly());
        if (step > 1) {
            EXPECT_LT(a.transfers, b.transfers / 3) << "step " << step;
        }
        EXPECT_LT(compareSamples(scaled.samples(), plain.samples()).rms, 2e-3) << "step " << step;
    }
}

// What changes the links or the transfer (a wall recoloured, an object
// moved) drops the kept light: the next dimming bounces as the first did,
// and both ways still agree.
TEST_F(ScaledLastEdit, AChangeOfColourOrAMoveDropsTheKeptLight) {
    const auto both = [&](const auto& edit) {
        const FrameStats a = edit(scaled, UpdateSettings{});
        const FrameStats b = edit(plain, bouncesOnly());
        EXPECT_LT(compareSamples(scaled.samples(), plain.samples()).rms, 2e-3);
        return std::pair(a, b);
    };
    const auto dim = [](V to) {
        return [to](Engine& e, const UpdateSettings& s) { return e.editMaterial("light", to, std::nullopt, s); };
    };
    both(dim(V(8.0)));
    both([](Engine& e, const UpdateSettings& s) { return e.editMaterial("wall-x0", std::nullopt, V(0.3, 0.6, 0.2), s); });
    auto [a, b] = both(dim(V(6.0)));
    EXPECT_GT(a.transfers, b.transfers / 2) << "a wall recoloured: nothing to scale";
    both(dim(V(4.0)));  // kept again
    both([](Engine& e, const UpdateSettings& s) {
        return e.moveDynamicObject(test::translation(V(0.3, 0.0, 0.1)), s);
    });
    std::tie(a, b) = both(dim(V(2.0)));
    EXPECT_GT(a.transfers, b.transfers / 2) << "the block moved: nothing to scale";
    // Within the 1% the edit issue asks of a full solve of the edited scene
    // (0.73%: after its move the block's shadow is meshed otherwise), and
    // no further from an 8x finer solve than that full solve is (2.51%
    // against 2.71%).
    const SolutionError e = test::compareWithFullSolve(scaled, settings);
    EXPECT_LT(e.rms, 0.01) << "max " << e.max << ", worst object " << e.worstObjectRms;
    Engine full(scaled.scene(), settings);
    ASSERT_TRUE(full.solve().converged);
    const RadiositySamples finer = test::finerSolve(scaled.scene(), settings);
    EXPECT_LT(compareSamples(scaled.samples(), finer).rms, 1.1 * compareSamples(full.samples(), finer).rms);
}

// On a deadline the scaled light is sent only when it is expected to fit:
// with no time left the frame is the one bounces alone give (what waits is
// counted), and without a deadline the scaled light goes out.
TEST_F(ScaledLastEdit, ADeadlineWithNoTimeLeftSendsNoScaledLight) {
    scaled.editMaterial("light", V(8.0), std::nullopt);
    plain.editMaterial("light", V(8.0), std::nullopt, bouncesOnly());
    UpdateSettings past;
    past.deadlineSeconds = 1e-9;
    UpdateSettings pastPlain = bouncesOnly();
    pastPlain.deadlineSeconds = 1e-9;
    const FrameStats a = scaled.editMaterial("light", V(6.0), std::nullopt, past);
    const FrameStats b = plain.editMaterial("light", V(6.0), std::nullopt, pastPlain);
    EXPECT_GT(a.unsent, 0u);
    EXPECT_EQ(a.unsent, b.unsent);
    EXPECT_EQ(compareSamples(scaled.samples(), plain.samples()).rms, 0.0);
    // Given time, the scaled light goes out and the two agree to the bounce threshold.
    const FrameStats c = scaled.editMaterial("light", V(4.0), std::nullopt);
    plain.editMaterial("light", V(4.0), std::nullopt, bouncesOnly());
    EXPECT_EQ(c.unsent, 0u);
    EXPECT_LT(compareSamples(scaled.samples(), plain.samples()).rms, 2e-3);
}

}  // namespace
}  // namespace rad
