// Where a scene's geometry lies and how far from it anything may be
// (scene/Placement.h).

#include "scene/Placement.h"

#include <gtest/gtest.h>

#include <vector>

namespace rad {
namespace {

// The centre is the median per axis and the size the diagonal of the middle
// half of the points: a twentieth of them far out moves neither.
TEST(Placement, AFewPointsFarOutMoveNeitherTheCentreNorTheSize) {
    std::vector<glm::dvec3> points;
    for (int i = 0; i <= 100; ++i) points.emplace_back(0.04 * i, 0.0, 0.0);  // 0 to 4 m along x
    const Placement near = placementOf(points);
    EXPECT_DOUBLE_EQ(near.centre.x, 2.0);
    EXPECT_NEAR(near.size, 2.0, 1e-12);  // the quartiles 1 m and 3 m
    for (int i = 0; i < 5; ++i) points.emplace_back(1e30, 0.0, 0.0);
    const Placement withFar = placementOf(points);
    EXPECT_NEAR(withFar.centre.x, 2.0, 0.15);  // the median moves by 2.5 points of 0.04 m
    EXPECT_NEAR(withFar.size, 2.0, 0.15);
    EXPECT_TRUE(withFar.reaches(glm::dvec3(0.9 * kMaxReach * withFar.size, 0.0, 0.0)));
    EXPECT_FALSE(withFar.reaches(glm::dvec3(1.1 * kMaxReach * withFar.size + 2.0, 0.0, 0.0)));
    EXPECT_FALSE(withFar.reaches(glm::dvec3(1e30, 0.0, 0.0)));
}

// Points of no extent (or none) refuse nothing: a scene of no size has no
// scale to be far from.
TEST(Placement, NoSizeRefusesNothing) {
    EXPECT_TRUE(placementOf({}).reaches(glm::dvec3(1e300)));
    const std::vector<glm::dvec3> one(3, glm::dvec3(1.0, 2.0, 3.0));
    const Placement p = placementOf(one);
    EXPECT_EQ(p.centre, glm::dvec3(1.0, 2.0, 3.0));
    EXPECT_EQ(p.size, 0.0);
    EXPECT_TRUE(p.reaches(glm::dvec3(-1e300)));
}

}  // namespace
}  // namespace rad
