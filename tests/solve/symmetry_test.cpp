#include <gtest/gtest.h>
#include <map>

#include "radiosity/Engine.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

// A unit room lit by a centred square light: the solution must keep the
// room's mirror symmetries (left/right and front/back walls read alike).
TEST(Symmetry, CentredLightLightsOppositeWallsAlike) {
    using V = glm::dvec3;
    Scene s;
    s.sourcePath = "symmetric-room";
    const auto white = test::addMaterial(s, V(0.7), V(0.0), "white");
    const auto light = test::addMaterial(s, V(0.0), V(10.0), "light");
    const auto faces = test::boxFaces(V(0.0), V(1.0), true);
    const char* names[] = {"floor", "ceiling", "left", "right", "front", "back"};
    for (int i = 0; i < 6; ++i) test::addQuadObject(s, names[i], white, {faces[i]});
    test::addQuadObject(s, "light", light, {{V(0.4, 0.999, 0.4), V(0.6, 0.999, 0.4), V(0.6, 0.999, 0.6), V(0.4, 0.999, 0.6)}});
    ASSERT_LT(s.polygons.back().normal().y, 0.0);  // faces down

    Engine engine(s, EngineSettings{});
    ASSERT_TRUE(engine.solve().converged);
    std::map<std::string, glm::dvec3> b;
    for (const ObjectRadiosity& o : engine.objectRadiosity()) b[o.name] = o.radiosity;
    EXPECT_NEAR(b["left"].x, b["right"].x, 0.01 * b["left"].x);
    EXPECT_NEAR(b["front"].x, b["back"].x, 0.01 * b["front"].x);
    EXPECT_NEAR(b["left"].x, b["front"].x, 0.01 * b["left"].x);
    EXPECT_GT(b["floor"].x, b["left"].x);  // the floor faces the light
}

}  // namespace
}  // namespace rad
