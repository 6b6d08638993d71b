// Surfaces buried in solids (scene/Buried.h): the parts of polygons inside
// closed solids are cut away at import, so rooms built from slabs that run
// through each other keep their light on their own side.

#include "scene/Buried.h"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"
#include "support/GltfBuilder.h"
#include "support/Regions.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;
using Triangle = std::array<glm::dvec3, 3>;

// An axis-aligned box as an exporter writes it: triangles facing out.
std::vector<Triangle> boxTriangles(V lo, V hi) {
    std::vector<Triangle> out;
    for (const auto& q : test::boxFaces(lo, hi, false)) {
        out.push_back({q[0], q[1], q[2]});
        out.push_back({q[0], q[2], q[3]});
    }
    return out;
}

std::vector<Triangle> joined(std::initializer_list<std::vector<Triangle>> parts) {
    std::vector<Triangle> out;
    for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}

// A floor [0, 4] x [0, 3] at y = 0 facing up, textured by u = x / 4, v = z / 3.
Polygon floorPolygon() {
    Polygon p;
    p.vertexCount = 4;
    p.vertices = {V(0, 0, 0), V(0, 0, 3), V(4, 0, 3), V(4, 0, 0)};
    for (int k = 0; k < 4; ++k) p.uv[k] = glm::vec2(p.vertices[k].x / 4.0, p.vertices[k].z / 3.0);
    return p;
}

double area(const std::vector<Polygon>& polygons) {
    double a = 0.0;
    for (const Polygon& p : polygons) a += p.area();
    return a;
}

BuriedParts cutFloor(std::vector<Polygon>& floor, const std::vector<Triangle>& solid,
                     bool cut = true) {
    std::vector<std::vector<Polygon>> polygons{floor};
    const std::vector<char> flags{cut ? char(1) : char(0)};
    const BuriedParts parts = cutBuriedParts(polygons, flags, closedSolids(solid));
    floor = polygons[0];
    return parts;
}

TEST(Buried, AWallThroughTheFloorTakesItsFootprint) {
    std::vector<Polygon> floor{floorPolygon()};
    const BuriedParts parts = cutFloor(floor, boxTriangles(V(1.9, -0.1, -0.1), V(2.1, 2.5, 3.1)));
    EXPECT_EQ(parts.polygonsCut, 1u);
    EXPECT_NEAR(parts.areaLeftOut[0], 0.2 * 3.0, 1e-9);
    EXPECT_NEAR(area(floor), 12.0 - 0.6, 1e-9);
    for (const Polygon& p : floor) {
        EXPECT_LE(p.vertexCount, 4);
        EXPECT_NEAR(glm::dot(p.normal(), V(0, 1, 0)), 1.0, 1e-12);
        const V c = p.centroid();
        EXPECT_TRUE(c.x < 1.9 || c.x > 2.1) << c.x;
        for (int k = 0; k < p.vertexCount; ++k) {
            // Texture coordinates keep following the position along the cuts.
            EXPECT_NEAR(p.uv[k].x, p.vertices[k].x / 4.0, 1e-6);
            EXPECT_NEAR(p.uv[k].y, p.vertices[k].z / 3.0, 1e-6);
        }
    }
}

TEST(Buried, ABoxStandingOnTheFloorOrBesideItCutsNothing) {
    for (const auto& [lo, hi] : {std::pair{V(1, 0, 1), V(2, 1, 2)},        // on it
                                 std::pair{V(1, -1, 1), V(2, 0, 2)},       // under it
                                 std::pair{V(5, -0.1, 1), V(6, 1, 2)}}) {  // beside it
        std::vector<Polygon> floor{floorPolygon()};
        const BuriedParts parts = cutFloor(floor, boxTriangles(lo, hi));
        EXPECT_EQ(parts.polygonsCut, 0u);
        ASSERT_EQ(floor.size(), 1u);
        EXPECT_EQ(floor[0].vertices, floorPolygon().vertices);
    }
}

TEST(Buried, AnObjectNotToBeCutStaysWhole) {
    std::vector<Polygon> floor{floorPolygon()};
    const BuriedParts parts =
        cutFloor(floor, boxTriangles(V(1.9, -0.1, -0.1), V(2.1, 2.5, 3.1)), false);
    EXPECT_EQ(parts.polygonsCut, 0u);
    EXPECT_EQ(floor.size(), 1u);
}

// A wall with a doorway, as three boxes in one mesh that touch along edges:
// not convex, but closed. The floor in the doorway stays.
TEST(Buried, TheFloorInADoorwayStays) {
    const std::vector<Triangle> wall = joined({boxTriangles(V(1.9, -0.1, -0.1), V(2.1, 2.5, 1.0)),
                                               boxTriangles(V(1.9, 2.0, 1.0), V(2.1, 2.5, 2.0)),
                                               boxTriangles(V(1.9, -0.1, 2.0), V(2.1, 2.5, 3.1))});
    ASSERT_EQ(closedSolids(wall).size(), 1u);
    std::vector<Polygon> floor{floorPolygon()};
    const BuriedParts parts = cutFloor(floor, wall);
    EXPECT_NEAR(parts.areaLeftOut[0], 0.2 * 2.0, 1e-9);
    EXPECT_NEAR(area(floor), 12.0 - 0.4, 1e-9);
}

TEST(Buried, OpenOrInsideOutMeshesAreNoSolids) {
    std::vector<Triangle> open = boxTriangles(V(0), V(1));
    open.resize(10);  // one face missing
    EXPECT_TRUE(closedSolids(open).empty());
    std::vector<Triangle> inward = boxTriangles(V(0), V(1));
    for (Triangle& t : inward) std::swap(t[1], t[2]);
    EXPECT_TRUE(closedSolids(inward).empty());
    const std::vector<ClosedSolid> two =
        closedSolids(joined({boxTriangles(V(0), V(1)), boxTriangles(V(3), V(4))}));
    ASSERT_EQ(two.size(), 2u);
    EXPECT_TRUE(two[0].holds(two[0].box.center()));
    EXPECT_FALSE(two[0].holds(two[1].box.center()));
    EXPECT_FALSE(two[0].holds(two[0].box.lo));  // on its surface
}

// Two rooms built from slabs: one floor slab and one ceiling slab over
// both, outer walls through the slabs, and a whole partition slab running
// 10 cm into the floor, the ceiling and the walls; a cabinet in the east
// room sunk 5 cm into the partition. Only the west room has a light. No
// straight line joins the rooms, so the east room must stay black. Before
// the cut, wall and floor elements straddling the partition were lit on the
// west and shone on the east (the cabinet 0.4% of the west room's light),
// and 6% of the light went into the slabs' insides.
TEST(Buried, SlabRoomsKeepTheirLightOnTheirSide) {
    const double L = 6.2, H = 2.5, D = 3.0, T = 0.2, X = 3.0;
    test::GltfBuilder g;
    const int plaster = g.addGrey("plaster", 0.75);
    const int lamp = g.addMaterial(
        R"({"name":"lamp","pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1]},"emissiveFactor":[1,1,1]})");
    const auto slab = [&](const std::string& name, std::vector<std::pair<V, V>> boxes,
                          int material) {
        g.addNode("\"name\":\"" + name +
                  "\",\"mesh\":" + std::to_string(g.addBoxMesh(name, boxes, material)));
    };
    slab("floor-slab", {{V(-T, -T, -T), V(L + T, 0, D + T)}}, plaster);
    slab("ceiling-slab", {{V(-T, H, -T), V(L + T, H + T, D + T)}}, plaster);
    slab("south-wall", {{V(-T, -T, -T), V(L + T, H + T, 0)}}, plaster);
    slab("north-wall", {{V(-T, -T, D), V(L + T, H + T, D + T)}}, plaster);
    slab("west-wall", {{V(-T, -T, -T), V(0, H + T, D + T)}}, plaster);
    slab("east-wall", {{V(L, -T, -T), V(L + T, H + T, D + T)}}, plaster);
    slab("partition", {{V(X, -0.1, -0.1), V(X + T, H + 0.1, D + 0.1)}}, plaster);
    slab("east-cabinet", {{V(X + T - 0.05, 0, 0.4), V(X + T + 0.5, 1.2, 1.2)}}, plaster);
    slab("east-crate", {{V(4.8, 0, 1.8), V(5.4, 0.6, 2.4)}}, plaster);
    const std::vector<glm::vec3> panel = {{1.0f, float(H - 0.01), 1.2f},
                                          {2.0f, float(H - 0.01), 1.2f},
                                          {2.0f, float(H - 0.01), 1.8f},
                                          {1.0f, float(H - 0.01), 1.8f}};
    g.addNode("\"name\":\"light\",\"mesh\":" +
              std::to_string(g.addMesh("light", g.addPositions(panel),
                                       g.addIndices({0, 1, 2, 0, 2, 3}), lamp)));
    const test::TempDir dir;
    ImportNotes notes;
    Scene scene = loadGltf(g.writeEmbedded(dir).string(), &notes);
    EXPECT_GT(notes.buriedPolygons, 0u);
    // The floor slab's top under the walls and the partition: of its 6.6 x
    // 3.4, the rooms' floors (6.2 - 0.2) x 3.0 stay. And where the walls'
    // faces lie in the planes of its faces, smaller (scene/Covered.h): under
    // their bottoms, the ring 6.6 x 3.4 - 6.2 x 3.0 of its bottom, and at the
    // corners, where the walls' ends (0.2 x 2.9) meet its sides (0.2 thick),
    // 8 squares of 0.2 x 0.2.
    double floorArea = 0.0;
    for (const Polygon& p : scene.polygons)
        if (scene.objects[p.object].name == "floor-slab") floorArea += p.area();
    const double slabArea = 2 * (6.6 * 3.4) + 2 * (6.6 * T) + 2 * (3.4 * T);
    const double covered = (6.6 * 3.4 - L * D) + 8 * T * T;
    EXPECT_NEAR(floorArea, slabArea - (6.6 * 3.4 - (L - T) * D) - covered, 1e-4);
    EXPECT_GT(notes.coveredPolygons, 0u);

    Engine engine(std::move(scene), EngineSettings{});
    const SolveStats& stats = engine.solve();
    ASSERT_TRUE(stats.converged) << stats.message;
    test::expectDarkBeside(engine, "east-", "west-wall", 1e-4);
    const EnergyBalance e = engine.energy();
    EXPECT_LT(e.backFaces, 0.01 * e.emitted);
    EXPECT_LT(std::abs(e.lost), 0.02 * e.emitted);
}

double objectArea(const Scene& scene, const std::string& name) {
    double a = 0.0;
    for (const Polygon& p : scene.polygons)
        if (scene.objects[p.object].name == name) a += p.area();
    return a;
}

// A box sunk 10 cm into a floor slab. Marked dynamic, it moves out of where
// it was sunk: it neither cuts nor is cut. With a light inside it holds lit
// space and cuts nothing, but the slab still cuts it.
TEST(Buried, DynamicBoxesAndLitBoxesCutNothing) {
    const double slab = 2 * 4.4 * 4.4 + 4 * 4.4 * 0.2, box = 2 * 1.0 + 4 * 1.1;
    for (const std::string& kind :
         {std::string("static"), std::string("dynamic"), std::string("lit")}) {
        test::GltfBuilder g;
        const int grey = g.addGrey("grey", 0.5);
        const int lamp = g.addMaterial(
            R"({"name":"lamp","pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1]},"emissiveFactor":[1,1,1]})");
        g.addNode(
            "\"name\":\"slab\",\"mesh\":" +
            std::to_string(g.addBoxMesh("slab", {{V(-0.2, -0.2, -0.2), V(4.2, 0, 4.2)}}, grey)));
        g.addNode("\"name\":\"box\",\"mesh\":" +
                  std::to_string(g.addBoxMesh("box", {{V(1, -0.1, 1), V(2, 1, 2)}}, grey)) +
                  (kind == "dynamic" ? ",\"extras\":{\"dynamic\":true}" : ""));
        const float y = kind == "lit" ? 0.5f : 3.0f;  // facing down
        const std::vector<glm::vec3> panel = {
            {1.2f, y, 1.2f}, {1.8f, y, 1.2f}, {1.8f, y, 1.8f}, {1.2f, y, 1.8f}};
        g.addNode("\"name\":\"light\",\"mesh\":" +
                  std::to_string(g.addMesh("light", g.addPositions(panel),
                                           g.addIndices({0, 1, 2, 0, 2, 3}), lamp)));
        const test::TempDir dir;
        const Scene scene = loadGltf(g.writeEmbedded(dir).string());
        // The slab's top loses the box's footprint, and the box its bottom and
        // the 10 cm of its sides in the slab.
        EXPECT_NEAR(objectArea(scene, "slab"), kind == "static" ? slab - 1.0 : slab, 1e-5) << kind;
        EXPECT_NEAR(objectArea(scene, "box"), kind == "dynamic" ? box : box - 1.0 - 0.4, 1e-5)
            << kind;
    }
}

// A static box wholly inside a static slab: nothing of it can be seen or
// lit, so it is not imported, and the note says why.
TEST(Buried, AnObjectWhollyInsideASolidIsNotImportedAndSaysWhy) {
    test::GltfBuilder g;
    const int grey = g.addGrey("grey", 0.5);
    g.addNode("\"name\":\"slab\",\"mesh\":" +
              std::to_string(g.addBoxMesh("slab", {{V(0, -1, 0), V(4, 0, 4)}}, grey)));
    g.addNode("\"name\":\"inside\",\"mesh\":" +
              std::to_string(g.addBoxMesh("inside", {{V(1, -0.8, 1), V(2, -0.2, 2)}}, grey)));
    const test::TempDir dir;
    ImportNotes notes;
    const Scene scene = loadGltf(g.writeEmbedded(dir).string(), &notes);
    EXPECT_FALSE(scene.findObject("inside").has_value());
    bool said = false;
    for (const std::string& line : notes.lines)
        said = said || (line.find("'inside'") != std::string::npos &&
                        line.find("every polygon lies inside closed solids") != std::string::npos);
    EXPECT_TRUE(said);
}

}  // namespace
}  // namespace rad
