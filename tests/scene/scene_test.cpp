#include <gtest/gtest.h>

#include <string>

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

// The kept boxes give Scene::bounds(), and measure again an object whose
// transform changed with its polygons (as a move does); another scene starts
// over.
TEST(ObjectBoxes, FollowAMovedObjectAndGiveTheScenesBounds) {
    Scene s;
    s.materials.push_back({"m", glm::dvec3(0.5), glm::dvec3(0.0)});
    for (int k = 0; k < 2; ++k) {
        Polygon p = unitSquare();
        for (glm::dvec3& v : p.vertices) v.x += 2.0 * k;
        s.polygons.push_back(p);
        s.objects.push_back({"square-" + std::to_string(k), glm::dmat4(1.0), false, std::uint32_t(k), 1, {}});
    }
    ObjectBoxes boxes;
    EXPECT_EQ(boxes.all(s).lo, s.bounds().lo);
    EXPECT_EQ(boxes.all(s).hi, s.bounds().hi);
    // Moved 5 along y: its polygon and its transform.
    for (glm::dvec3& v : s.polygons[1].vertices) v.y += 5.0;
    s.objects[1].worldFromLocal[3].y = 5.0;
    EXPECT_EQ(boxes.of(s, 1).lo, glm::dvec3(2, 5, 0));
    EXPECT_EQ(boxes.all(s).hi, s.bounds().hi);
    EXPECT_EQ(boxes.of(s, 0).hi, glm::dvec3(1, 1, 0));
    Scene other = s;
    for (glm::dvec3& v : other.polygons[0].vertices) v.z -= 1.0;
    EXPECT_EQ(boxes.all(other).lo, other.bounds().lo);
}

}  // namespace
}  // namespace rad
