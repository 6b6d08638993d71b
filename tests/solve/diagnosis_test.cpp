// What a solve tells the user when light goes missing (solve/Diagnosis.h).

#include "solve/Diagnosis.h"
#include "support/TestScenes.h"

#include <gtest/gtest.h>

namespace rad {
namespace {

TEST(Diagnosis, LightLostPastTheThresholdIsSaid) {
    EnergyBalance e;
    e.emitted = 2.0;
    e.lost = 0.1;  // 5%: what coarse links leave, said in the report's balance only
    EXPECT_TRUE(lostLightWarnings(e, 0.1).empty());
    e.lost = 0.6;  // 30%: a lamp under a ceiling, say
    const std::vector<Warning> w = lostLightWarnings(e, 0.1);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].kind, "lost_light");
    EXPECT_DOUBLE_EQ(w[0].amount, 0.3);
    EXPECT_NE(w[0].message.find("30% of the emitted light is lost"), std::string::npos)
        << w[0].message;
    e.emitted = 0.0;  // nothing emits: nothing to say here
    EXPECT_TRUE(lostLightWarnings(e, 0.1).empty());
}

// A lamp panel 1 cm under the ceiling of a room: facing down it lights the
// room; facing up (its normal flipped, the commonest slip) its light is
// trapped between it and the ceiling, and the solve says so.
TEST(Diagnosis, ALampFacingTheCeilingCloseByIsSaid) {
    using V = glm::dvec3;
    const auto room = [](double below, bool up) {
        Scene s;
        const auto grey = test::addMaterial(s, V(0.7), V(0.0), "grey");
        const auto light = test::addMaterial(s, V(0.0), V(5.0), "light");
        test::addQuadObject(s, "room", grey, test::boxFaces(V(0.0), V(4.0, 2.6, 3.0), true));
        const double y = 2.6 - below;
        std::array<V, 4> q = {V(1.6, y, 1.4), V(2.4, y, 1.4), V(2.4, y, 2.1), V(1.6, y, 2.1)};  // faces down
        if (up) std::swap(q[1], q[3]);
        test::addQuadObject(s, "lamp", light, {q});
        return s;
    };
    const std::vector<Warning> flipped = trappedLightWarnings(room(0.01, true));
    ASSERT_EQ(flipped.size(), 1u);
    EXPECT_EQ(flipped[0].kind, "trapped_light");
    EXPECT_EQ(flipped[0].objects, (std::vector<std::string>{"lamp", "room"}));
    EXPECT_DOUBLE_EQ(flipped[0].amount, 1.0);
    EXPECT_NE(flipped[0].message.find("is the normal of 'lamp' flipped?"), std::string::npos) << flipped[0].message;
    EXPECT_TRUE(trappedLightWarnings(room(0.01, false)).empty());  // facing the room
    // 30 cm under the ceiling, facing it (an uplight): farther than a tenth
    // of the panel's size (7.5 cm), its light spreads over the ceiling.
    EXPECT_TRUE(trappedLightWarnings(room(0.3, true)).empty());
}

}  // namespace
}  // namespace rad
