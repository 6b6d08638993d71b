// A cluster's visibility samples keep their normals in 32 bits (octahedral
// encoding, hierarchy/ClusterShape.h): exact for axis-aligned surfaces, whose
// one-sidedness tests against a coplanar neighbour must not tip, and within
// 1e-4 radians for any other direction.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hierarchy/ClusterShape.h"

namespace rad {
namespace {

glm::dvec3 roundTrip(const glm::dvec3& n) {
    ClusterShape::Sample s;
    s.octNormal = ClusterShape::Sample::encode(n);
    return s.normal();
}

TEST(ClusterShape, AxisAlignedSampleNormalsAreExact) {
    for (int axis = 0; axis < 3; ++axis)
        for (double sign : {1.0, -1.0}) {
            glm::dvec3 n(0.0);
            n[axis] = sign;
            EXPECT_EQ(roundTrip(n), n) << "axis " << axis << " sign " << sign;
        }
}

TEST(ClusterShape, SampleNormalsKeepTheirDirection) {
    std::mt19937 rng(7);
    std::normal_distribution<double> gauss;
    double worst = 0.0;
    for (int i = 0; i < 100000; ++i) {
        const glm::dvec3 n = glm::normalize(glm::dvec3(gauss(rng), gauss(rng), gauss(rng)));
        const glm::dvec3 back = roundTrip(n);
        ASSERT_NEAR(glm::length(back), 1.0, 1e-12);
        worst = std::max(worst, std::acos(std::min(1.0, glm::dot(n, back))));
    }
    EXPECT_LT(worst, 1e-4);
    EXPECT_GT(worst, 0.0);  // the encoding is lossy: the bound above is what the test checks
}

TEST(ClusterShape, ZeroNormalDecodesToAUnitVector) {
    EXPECT_NEAR(glm::length(roundTrip(glm::dvec3(0.0))), 1.0, 1e-12);
}

}  // namespace
}  // namespace rad
