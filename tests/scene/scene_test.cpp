#include <gtest/gtest.h>

#include "radiosity/Scene.h"

namespace rad {
namespace {

Polygon unitSquare() {
    Polygon p;
    p.vertexCount = 4;
    p.vertices = {glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(1, 1, 0), glm::dvec3(0, 1, 0)};
    return p;
}

TEST(Polygon, AreaNormalCentroidOfSquare) {
    const Polygon p = unitSquare();
    EXPECT_DOUBLE_EQ(p.area(), 1.0);
    EXPECT_EQ(p.normal(), glm::dvec3(0, 0, 1));
    const glm::dvec3 c = p.centroid();
    EXPECT_NEAR(c.x, 0.5, 1e-12);
    EXPECT_NEAR(c.y, 0.5, 1e-12);
}

TEST(Polygon, ClockwiseWindingFlipsNormal) {
    Polygon p;
    p.vertices = {glm::dvec3(0, 0, 0), glm::dvec3(0, 2, 0), glm::dvec3(2, 0, 0), glm::dvec3(0)};
    EXPECT_EQ(p.normal(), glm::dvec3(0, 0, -1));
    EXPECT_DOUBLE_EQ(p.area(), 2.0);
}

TEST(Scene, BoundsAndLookup) {
    Scene s;
    s.materials.push_back({"m", glm::dvec3(0.5), glm::dvec3(0.0)});
    s.polygons.push_back(unitSquare());
    s.objects.push_back({"square", glm::dmat4(1.0), false, 0, 1, {}});
    EXPECT_EQ(s.bounds().hi, glm::dvec3(1, 1, 0));
    EXPECT_EQ(s.findObject("square"), 0u);
    EXPECT_FALSE(s.findObject("missing").has_value());
    EXPECT_FALSE(s.hasEmitter());
    s.materials[0].emission = glm::dvec3(1.0);
    EXPECT_TRUE(s.hasEmitter());
}

}  // namespace
}  // namespace rad
