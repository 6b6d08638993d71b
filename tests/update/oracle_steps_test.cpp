// The oracles' steps (update/OracleSteps.h): an element's oracle follows its
// light in steps of sqrt(2) from the solve's, with hysteresis, and comes back
// exactly; the elements whose oracle rose are told apart, since only their
// links can ask for refinement they did not ask for before.

#include <gtest/gtest.h>

#include <vector>

#include "hierarchy/Hierarchy.h"
#include "support/TestScenes.h"
#include "update/OracleSteps.h"

namespace rad {
namespace {

TEST(OracleSteps, StepWithTheLightTellWhichRoseAndComeBackExactly) {
    const Scene scene = test::parallelSquares(0.5);
    Hierarchy h(scene, 1.0);
    const ElementId a = h.polygonElement(0), b = h.polygonElement(1);
    ASSERT_TRUE(h[a].isSurface());
    ASSERT_TRUE(h[b].isSurface());
    for (ElementId e : {a, b}) {
        h[e].peak = 1.0f;
        h[e].oracle = 1.0f;
    }
    anchorOracles(h);
    const std::vector<ElementId> both = {b, a};
    // Within the hysteresis (0.75 of a step): nothing moves.
    h[a].peak = 1.2f;
    h[b].peak = 0.85f;
    SteppedOracles s = stepOracles(h, both, 0.0, 1.0);
    EXPECT_TRUE(s.moved.empty());
    EXPECT_TRUE(s.rose.empty());
    // a four times brighter (4 steps up), b four times darker (4 down).
    h[a].peak = 4.0f;
    h[b].peak = 0.25f;
    s = stepOracles(h, both, 0.0, 1.0);
    EXPECT_EQ(s.moved, both);  // in the given order
    EXPECT_EQ(s.rose, std::vector<ElementId>{a});
    EXPECT_EQ(h[a].level, 4);
    EXPECT_EQ(h[b].level, -4);
    EXPECT_NEAR(h[a].oracle, 4.0, 1e-6);
    EXPECT_NEAR(h[b].oracle, 0.25, 1e-6);
    // The scale (the solve's power over the power now) counts as the light
    // does: every element twice as bright relative to the scene.
    s = stepOracles(h, both, 0.0, 2.0);
    EXPECT_EQ(s.rose, both);
    EXPECT_EQ(h[a].level, 6);
    // Back: the levels return to 0 and the oracles to the anchors, to the bit.
    h[a].peak = h[b].peak = 1.0f;
    s = stepOracles(h, both, 0.0, 1.0);
    EXPECT_EQ(s.moved, both);
    EXPECT_EQ(s.rose, std::vector<ElementId>{b});
    for (ElementId e : {a, b}) {
        EXPECT_EQ(h[e].level, 0);
        EXPECT_EQ(h[e].oracle, 1.0f);
    }
}

}  // namespace
}  // namespace rad
