// How closed each polygon's view is (solve/Closure.h): the fill acts only
// where it is, so a closed room gets it everywhere and the open side of a
// box none. Checked against the form factor between squares.

#include "solve/Closure.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "geometry/RayCaster.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;

std::vector<float> closureOf(const Scene& scene) {
    RayCaster rays;
    rays.setFrame(scene.bounds());
    std::vector<std::uint32_t> all(scene.polygons.size());
    std::iota(all.begin(), all.end(), 0u);
    rays.setLayer(Layer::Static, scene, all);
    std::vector<float> closure;
    measureClosure(scene, rays, all, closure);
    return closure;
}

TEST(Closure, EveryRayFromInsideAClosedBoxMeetsAWall) {
    for (float c : closureOf(test::closedBox(0.5))) EXPECT_EQ(c, 1.0f);
}

// The same in `office`, whose floor, walls and furniture meet at seams a
// float ray can slip through: a ray that leaves is looked at again, turned
// by a milliradian, and a seam has no width (4 polygons read 63/64 before,
// and every move measured the moved polygons again as in an open scene).
TEST(Closure, RaysThatSlipThroughSeamsDoNotOpenAClosedRoom) {
    const std::vector<float> closure = closureOf(test::office());
    EXPECT_EQ(std::count(closure.begin(), closure.end(), 1.0f), std::ptrdiff_t(closure.size()));
}

// A unit cube without its top: from the floor, the opening is a parallel
// unit square at distance 1, whose form factor is 0.1998 (Howell's
// catalogue, C-11); from a wall, a perpendicular one sharing an edge, 0.2000
// (C-14). The rest of each view meets the box.
TEST(Closure, AnOpenBoxSeesItsOpeningAsTheFormFactorSays) {
    Scene s;
    s.sourcePath = "open-box";
    const auto grey = test::addMaterial(s, V(0.5), V(0.0), "grey");
    const auto faces = test::boxFaces(V(0.0), V(1.0), true);  // -y, +y, then the walls
    for (std::size_t i = 0; i < faces.size(); ++i)
        if (i != 1) test::addQuadObject(s, "face-" + std::to_string(i), grey, {faces[i]});
    const std::vector<float> closure = closureOf(s);
    ASSERT_EQ(closure.size(), 5u);
    // 64 rays a polygon: a share of 0.8 is measured to a standard
    // deviation of 0.05 (measured: the floor 0.80, the walls 0.73 to 0.84,
    // by how their rays' frame lies). The four walls together, 256 rays:
    // 0.025.
    EXPECT_NEAR(closure[0], 1.0 - 0.1998, 0.1) << "floor";
    double walls = 0.0;
    for (std::size_t i = 1; i < closure.size(); ++i) {
        EXPECT_NEAR(closure[i], 1.0 - 0.2, 0.1) << "wall " << i;
        walls += closure[i] / 4.0;
    }
    EXPECT_NEAR(walls, 1.0 - 0.2, 0.05);
}

}  // namespace
}  // namespace rad
