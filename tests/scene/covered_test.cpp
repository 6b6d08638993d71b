// Surfaces covered by smaller ones laid in their plane (scene/Covered.h): a
// poster flush with its wall, a lamp in the ceiling's plane. The larger is
// cut away under the smaller, which is seen whatever the file's order.

#include "scene/Covered.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"
#include "support/GltfBuilder.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;

// A quad in the plane z = z0 over [x0,x1] x [y0,y1], facing +z (or -z).
Polygon quadZ(double x0, double x1, double y0, double y1, double z0, bool back = false) {
    Polygon p;
    p.vertexCount = 4;
    p.vertices = {V(x0, y0, z0), V(x1, y0, z0), V(x1, y1, z0), V(x0, y1, z0)};
    if (back) std::swap(p.vertices[1], p.vertices[3]);
    return p;
}

double areaOf(const std::vector<Polygon>& polygons) {
    double a = 0.0;
    for (const Polygon& p : polygons) a += p.area();
    return a;
}

bool inside(const V& p, double x0, double x1, double y0, double y1) {
    return p.x > x0 && p.x < x1 && p.y > y0 && p.y < y1;
}

TEST(Covered, APosterGivenAfterItsWallCutsTheWallAndStaysWhole) {
    // Wall 4 x 2.5, poster 1 x 0.7 on it, listed after it.
    std::vector<std::vector<Polygon>> polygons = {{quadZ(0, 4, 0, 2.5, 0)},
                                                  {quadZ(1, 2, 1, 1.7, 0)}};
    const std::vector<char> cut = {1, 1};
    const CoveredParts covered = cutCoveredParts(polygons, cut);
    EXPECT_EQ(covered.polygonsCut, 1u);
    ASSERT_EQ(covered.areaLeftOut.size(), 2u);
    EXPECT_NEAR(covered.areaLeftOut[0], 0.7, 1e-9);
    EXPECT_EQ(covered.areaLeftOut[1], 0.0);
    ASSERT_EQ(polygons[1].size(), 1u);
    EXPECT_NEAR(polygons[1][0].area(), 0.7, 1e-12);
    EXPECT_NEAR(areaOf(polygons[0]), 10.0 - 0.7, 1e-9);
    for (const Polygon& p : polygons[0]) {
        EXPECT_GT(glm::dot(p.normal(), V(0, 0, 1)), 0.999);  // the wall's pieces face as it did
        EXPECT_FALSE(inside(p.centroid(), 1, 2, 1, 1.7))
            << "a piece of the wall lies under the poster";
    }
}

TEST(Covered, WhatDoesNotCoverStaysWhole) {
    std::vector<std::vector<Polygon>> polygons = {
        {quadZ(0, 4, 0, 2.5, 0)},
        {quadZ(1, 2, 1, 1.7, 0, true)},  // back to back with the wall: a slab of no thickness
        {quadZ(1, 2, 1, 1.7, 0.001)},    // 1 mm in front: a surface of its own
        {quadZ(4, 5, 0, 1, 0)},          // beside it, touching along its edge
        {quadZ(2.5, 3, 1, 1.5, 0)}};     // on it, but dynamic
    const std::vector<char> cut = {1, 1, 1, 1, 0};
    const std::vector<std::vector<Polygon>> before = polygons;
    const CoveredParts covered = cutCoveredParts(polygons, cut);
    EXPECT_EQ(covered.polygonsCut, 0u);
    for (std::size_t o = 0; o < polygons.size(); ++o) {
        ASSERT_EQ(polygons[o].size(), before[o].size()) << o;
        EXPECT_EQ(polygons[o][0].vertices, before[o][0].vertices) << o;
    }
}

TEST(Covered, OfTwoAlikeOverlappingTheEarlierIsSeen) {
    // Two 1 x 1 plates overlapping by half: the second loses the half, and
    // together they cover their union once.
    std::vector<std::vector<Polygon>> polygons = {{quadZ(0, 1, 0, 1, 0)},
                                                  {quadZ(0.5, 1.5, 0, 1, 0)}};
    const CoveredParts covered = cutCoveredParts(polygons, std::vector<char>{1, 1});
    EXPECT_EQ(covered.polygonsCut, 1u);
    EXPECT_NEAR(areaOf(polygons[0]), 1.0, 1e-12);
    EXPECT_NEAR(areaOf(polygons[1]), 0.5, 1e-9);
    for (const Polygon& p : polygons[1]) EXPECT_GE(p.centroid().x, 1.0 - 1e-9);
}

// A room whose ceiling lamp is modelled in the ceiling's plane and given
// after the room, as tools export a recessed panel, and a poster flush with
// a wall: before the cut, the ceiling hid the lamp (all its light lost, the
// room black, reported converged) and the wall hid the poster. Both must read
// as the same scene with each 1 mm off its surface.
std::string flushRoom(const test::TempDir& dir, double off) {
    test::GltfBuilder g;
    const int plaster = g.addGrey("plaster", 0.7);
    const int red = g.addMaterial(
        R"({"name":"red","pbrMetallicRoughness":{"baseColorFactor":[0.7,0.15,0.1,1]}})");
    const int lamp = g.addMaterial(
        R"({"name":"lamp","pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1]},"emissiveFactor":[1,1,1]})");
    const double W = 4.0, H = 2.6, D = 3.0;
    std::vector<glm::vec3> room;
    std::vector<std::uint32_t> indices;
    for (const auto& q : test::boxFaces(V(0), V(W, H, D), true)) {
        const auto base = static_cast<std::uint32_t>(room.size());
        for (const V& v : q) room.emplace_back(v);
        for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + k);
    }
    g.addNode(
        R"("name":"room","mesh":)" +
        std::to_string(g.addMesh("room", g.addPositions(room), g.addIndices(indices), plaster)));
    const auto quad = [&](const std::string& name, std::vector<glm::vec3> corners, int material) {
        g.addNode("\"name\":\"" + name + "\",\"mesh\":" +
                  std::to_string(g.addMesh(name, g.addPositions(corners),
                                           g.addIndices({0, 1, 2, 0, 2, 3}), material)));
    };
    const auto h = static_cast<float>(H - off), z = static_cast<float>(off);
    quad("lamp", {{1.5f, h, 1.0f}, {2.5f, h, 1.0f}, {2.5f, h, 2.0f}, {1.5f, h, 2.0f}},
         lamp);  // facing down
    quad("poster", {{1.0f, 1.0f, z}, {2.0f, 1.0f, z}, {2.0f, 1.7f, z}, {1.0f, 1.7f, z}},
         red);  // facing +z
    return g.writeEmbedded(dir).string();
}

TEST(Covered, ALampAndAPosterFlushWithTheirSurfacesAreSeenAndLit) {
    const test::TempDir flushDir, offDir;
    ImportNotes notes;
    Engine flush(loadGltf(flushRoom(flushDir, 0.0), &notes), EngineSettings{});
    Engine off(loadGltf(flushRoom(offDir, 0.001), nullptr), EngineSettings{});
    EXPECT_EQ(notes.coveredPolygons, 2u);  // the ceiling and the wall
    EXPECT_NEAR(notes.coveredArea, 1.0 + 0.7, 1e-4);
    ASSERT_TRUE(flush.solve().converged);
    ASSERT_TRUE(off.solve().converged);
    const EnergyBalance e = flush.energy();
    EXPECT_LT(std::abs(e.lost), 0.01 * e.emitted);
    EXPECT_NEAR(e.absorbed, off.energy().absorbed, 0.01 * off.energy().absorbed);
    // The power each object reflects: 1 mm off, the room keeps the dark
    // 1.7 m^2 under the lamp and the poster, which the cut leaves out.
    const auto power = [](const Engine& engine, const std::string& name) {
        for (const ObjectRadiosity& o : engine.objectRadiosity())
            if (o.name == name) return luminance(o.radiosity) * o.area;
        ADD_FAILURE() << "no object " << name;
        return 0.0;
    };
    for (const std::string name : {"room", "poster"})
        EXPECT_NEAR(power(flush, name), power(off, name), 0.02 * power(off, name)) << name;
}

}  // namespace
}  // namespace rad
