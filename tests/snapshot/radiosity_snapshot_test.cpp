#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <tuple>
#include <utility>

#include "hierarchy/Hierarchy.h"
#include "snapshot/RadiositySnapshot.h"
#include "radiosity/Engine.h"
#include "support/Motion.h"
#include "support/SameMesh.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

// Two quads in one plane, white and grey, meeting along x = 1 under a bulb:
// at the seam the display shares their light, each vertex showing it times
// its own reflectance, not their mean colour (the grey bled into the white).
TEST(RadiositySnapshot, PolygonsMeetingAtASeamShareTheirLightNotTheirColour) {
    using V = glm::dvec3;
    Scene s;
    const auto white = test::addMaterial(s, V(0.8), V(0.0), "white");
    const auto grey = test::addMaterial(s, V(0.2), V(0.0), "grey");
    test::addQuadObject(s, "a", white, {{V(0, 0, 0), V(1, 0, 0), V(1, 3, 0), V(0, 3, 0)}});
    test::addQuadObject(s, "b", grey, {{V(1, 0, 0), V(2, 0, 0), V(2, 3, 0), V(1, 3, 0)}});
    PunctualLight bulb;
    bulb.name = "bulb";
    bulb.position = V(1.0, 1.5, 1.0);
    bulb.intensity = V(10.0);
    s.lights.push_back(bulb);
    Engine engine(s, EngineSettings{});
    ASSERT_TRUE(engine.solve().converged);
    const MeshSnapshot mesh = compactMesh(engine.snapshot());  // without the room its slots keep to grow in
    int seams = 0;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        for (std::size_t j = i + 1; j < mesh.positions.size(); ++j) {
            if (mesh.positions[i] != mesh.positions[j] || mesh.positions[i].x != 1.0f - float(mesh.origin.x))
                continue;
            // Which is which: the white one is the brighter.
            const double bright = std::max(mesh.colors[i].x, mesh.colors[j].x);
            const double dim = std::min(mesh.colors[i].x, mesh.colors[j].x);
            EXPECT_GT(dim, 0.0);
            EXPECT_NEAR(bright / 0.8, dim / 0.2, 1e-5 * bright) << "seam vertex at y = " << mesh.positions[i].y;
            ++seams;
        }
    EXPECT_GE(seams, 2);
}

// One unit quad: split once, then split the first child again. The fine
// leaves put a vertex in the middle of the coarse neighbours' edges (a
// T-vertex); its value must be the interpolation along the coarse edge.
TEST(RadiositySnapshot, TVerticesTakeTheValueAlongTheCoarseEdge) {
    using V = glm::dvec3;
    Scene s;
    const auto m = test::addMaterial(s, V(0.5), V(1.0));
    test::addQuadObject(s, "quad", m, {{V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}});
    Hierarchy h(s, 1e-3);
    const ElementId top = h.polygonElement(0);
    h.subdivide(top);
    const ElementId fine = h[top].children[0];  // param [0,0.5]^2
    h.subdivide(fine);
    // Distinct values per leaf.
    double value = 1.0;
    for (ElementId c : h[top].children) {
        if (c == fine) continue;
        h[c].radiosity = V(value += 1.0);
    }
    for (ElementId c : h[fine].children) h[c].radiosity = V(value += 1.0);

    const MeshSnapshot mesh = makeRadiositySnapshot(s, h);
    auto at = [&](double x, double y) {
        for (std::size_t i = 0; i < mesh.positions.size(); ++i)
            if (glm::length(glm::dvec3(mesh.positions[i]) - V(x, y, 0)) < 1e-6) return double(mesh.colors[i].x);
        ADD_FAILURE() << "no vertex at " << x << "," << y;
        return 0.0;
    };
    // Child 1 (param [0.5,1]x[0,0.5]) has the edge x = 0.5 from y = 0 to 0.5;
    // the fine leaves put a vertex at (0.5, 0.25).
    EXPECT_NEAR(at(0.5, 0.25), 0.5 * (at(0.5, 0.0) + at(0.5, 0.5)), 1e-6);
    // Child 3 (param [0,0.5]x[0.5,1]) has the edge y = 0.5 from x = 0 to 0.5.
    EXPECT_NEAR(at(0.25, 0.5), 0.5 * (at(0.0, 0.5) + at(0.5, 0.5)), 1e-6);
    // Every triangle has positive area and the mesh covers the quad exactly.
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
            c(mesh.positions[mesh.indices[t + 2]]);
        const double twice = glm::cross(b - a, c - a).z;
        EXPECT_GT(twice, 0.0);  // counter-clockwise, facing +z like the quad
        area += 0.5 * twice;
    }
    EXPECT_NEAR(area, 1.0, 1e-6);
    // No T-junction: no vertex lies inside a triangle's edge (the rasteriser
    // leaves cracks of background along such an edge). The coarse leaves'
    // edges through (0.5, 0.25) and (0.25, 0.5) are cut there.
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 a(mesh.positions[mesh.indices[t + k]]),
                b(mesh.positions[mesh.indices[t + (k + 1) % 3]]);
            for (const glm::vec3& p : mesh.positions) {
                const glm::dvec3 x(p);
                const double along = glm::dot(x - a, b - a) / glm::dot(b - a, b - a);
                EXPECT_FALSE(along > 1e-9 && along < 1.0 - 1e-9 &&
                             glm::length(a + along * (b - a) - x) < 1e-9)
                    << "vertex " << x.x << "," << x.y << " inside the edge " << a.x << "," << a.y
                    << " - " << b.x << "," << b.y;
            }
        }
}

// A frame re-meshes only the polygons whose leaves changed (SnapshotCache):
// after radiosity changes, a subdivision, a removal and a moved polygon, the
// cached mesh is the mesh made from scratch, vertex for vertex, but for the
// room its slots keep to grow in (compactMesh drops it).
TEST(RadiositySnapshot, CachedPartsGiveTheMeshMadeFromScratch) {
    Scene s = test::roomWithBlock();
    Hierarchy h(s, 1e-3);
    double value = 0.1;
    const auto light = [&](ElementId e) {
        value += 0.01;
        h[e].radiosity = glm::dvec3(value, 0.5 * value, 0.25);
    };
    for (std::uint32_t p = 0; p < h.polygonCount(); ++p) light(h.polygonElement(p));
    SnapshotCache cache;
    MeshSnapshot cached;
    const auto expectSame = [&](const char* after) {
        makeRadiositySnapshot(s, h, cached, cache);
        test::expectSameMesh(cached, makeRadiositySnapshot(s, h), after);
    };
    expectSame("the first build");
    const ElementId wall = h.polygonElement(0);
    h.subdivide(wall);
    for (ElementId c : h[wall].children) light(c);
    expectSame("a subdivision");
    light(h[wall].children[2]);
    expectSame("a leaf's radiosity changed");
    // Leaves of two depths: T-vertices on the coarse leaves' edges, set
    // again when only the light changes (the part is coloured again, not
    // meshed again).
    const ElementId quarter = h[wall].children[1];
    h.subdivide(quarter);
    for (ElementId c : h[quarter].children) light(c);
    expectSame("a quarter subdivided");
    for (ElementId c : h[wall].children) light(c == quarter ? h[quarter].children[3] : c);
    expectSame("new light on leaves of two depths");
    h.removeChildren(quarter);
    h.removeChildren(wall);
    expectSame("the children removed");
    const std::uint32_t moved = s.objects.back().firstPolygon;
    for (int k = 0; k < s.polygons[moved].vertexCount; ++k) s.polygons[moved].vertices[k] += glm::dvec3(0.1, 0.0, 0.0);
    h.updateGeometry(h.polygonElement(moved));
    expectSame("a polygon moved");
    expectSame("nothing changed");
    // A copied cache meshes with working arrays of its own (SnapshotCache::
    // scratches), to the same mesh as the one it was copied from.
    SnapshotCache copy = cache;
    MeshSnapshot fromCopy = cached;
    light(h.polygonElement(1));
    makeRadiositySnapshot(s, h, fromCopy, copy);
    expectSame("new light, after the cache was copied");
    test::expectSameMesh(fromCopy, compactMesh(cached), "the copied cache's build");
}

// A wall of 10 x 10 unit tiles meeting edge to edge (their seams smoothed),
// its hierarchy, and a mesh built from a cache frame after frame.
// Textured: each tile shows a 2 x 1 texture of a light and a dark texel.
struct TiledWall {
    explicit TiledWall(bool textured = false) : scene(wall(textured)) {}
    static Scene wall(bool textured) {
        using V = glm::dvec3;
        Scene s;
        const auto m = test::addMaterial(s, V(0.5), V(0.0));
        std::vector<std::array<V, 4>> tiles;
        for (int j = 0; j < 10; ++j)
            for (int i = 0; i < 10; ++i)
                tiles.push_back({V(i, j, 0), V(i + 1, j, 0), V(i + 1, j + 1, 0), V(i, j + 1, 0)});
        test::addQuadObject(s, "wall", m, tiles);
        if (textured) {
            auto texture = std::make_shared<Texture>();
            texture->width = 2;
            texture->height = 1;
            texture->srgba = {230, 230, 230, 255, 60, 60, 60, 255};
            s.materials[m].texture = 0;
            s.materials[m].textureMean = texture->mean();
            s.textures.push_back(std::move(texture));
            for (Polygon& p : s.polygons) p.uv = {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)};
        }
        return s;
    }
    Scene scene;
    Hierarchy h{scene, 1e-3};
    SnapshotCache cache;
    MeshSnapshot cached;
    // Every element a radiosity that varies from element to element, times `scale`.
    void paint(double scale) {
        for (std::uint32_t p = 0; p < h.polygonCount(); ++p)
            for (std::vector<ElementId> stack{h.polygonElement(p)}; !stack.empty();) {
                const ElementId e = stack.back();
                stack.pop_back();
                h[e].radiosity = scale * glm::dvec3(1.0 + 0.1 * (e % 7), 0.5, 0.25);
                stack.insert(stack.end(), h[e].children.begin(), h[e].children.end());
            }
    }
    std::size_t build(std::optional<std::chrono::steady_clock::time_point> stop = std::nullopt) {
        return makeRadiositySnapshot(scene, h, cached, cache, stop);
    }
    // A build without a stop leaves nothing, and gives the mesh made from scratch.
    void expectTheMeshMadeFromScratch(const char* after) {
        EXPECT_EQ(build(), 0u) << after;
        test::expectSameMesh(cached, makeRadiositySnapshot(scene, h), after);
    }
};

// A wall of 10 x 10 tiles meeting edge to edge (their seams smoothed): the
// cached mesh is the mesh made from scratch after tiles are subdivided (the
// parts change size and the mesh moves to a new layout) and their children
// removed; and a build whose stop has passed meshes kLeastRemeshed tiles or
// a few more, keeps the others as they were, and the next build catches up.
// Both ways of finding the seams' groups to sum again: walking along all
// keys, and finding each by its key (keysPerSearch 0: always); and with
// textures, whose coordinates and layers the slots' room holds too.
TEST(RadiositySnapshot, CachedTilesAcrossResizesAndAStopGiveTheMeshMadeFromScratch) {
    for (const auto& [keysPerSearch, textured] :
         {std::pair{std::size_t(256), false}, std::pair{std::size_t(0), false}, std::pair{std::size_t(0), true}}) {
        SCOPED_TRACE(keysPerSearch);
        SCOPED_TRACE(textured);
        TiledWall w(textured);
        ASSERT_EQ(makeRadiositySnapshot(w.scene, w.h).uvs.empty(), !textured);
        w.cache.keysPerSearch = keysPerSearch;
        w.paint(1.0);
        w.expectTheMeshMadeFromScratch("the first build");
        w.cache.assembleSeconds = 3600.0;  // as if joining all parts anew took an hour: builds patch
        for (std::uint32_t p : {11u, 12u, 55u, 98u}) w.h.subdivide(w.h.polygonElement(p));
        w.h.subdivide(w.h[w.h.polygonElement(12)].children[1]);
        w.paint(1.5);
        w.expectTheMeshMadeFromScratch("subdivisions");
        w.h.removeChildren(w.h.polygonElement(12));
        w.paint(1.7);
        w.expectTheMeshMadeFromScratch("children removed");

        w.paint(2.0);
        const MeshSnapshot before = w.cached;
        const std::size_t left = w.build(std::chrono::steady_clock::now() - std::chrono::seconds(1));
        EXPECT_GT(left, 0u);
        EXPECT_LE(left, 100u - kLeastRemeshed);
        // The tiles left keep their colours: as many vertices as before are unchanged.
        std::size_t same = 0;
        for (std::size_t v = 0; v < w.cached.colors.size(); ++v) same += w.cached.colors[v] == before.colors[v];
        EXPECT_GT(same, 0u);
        w.expectTheMeshMadeFromScratch("the next build");
    }
}

// A tile that outgrows its slot moves the mesh to a new layout and gets a
// larger slot: its next subdivision and the removal of its children fit in
// that slot, and the mesh keeps its layout (its size), the same mesh as one
// made from scratch once compacted.
TEST(RadiositySnapshot, APartThatChangesSizeWithinItsSlotKeepsTheLayout) {
    TiledWall w;
    w.paint(1.0);
    w.expectTheMeshMadeFromScratch("the first build");
    w.cache.assembleSeconds = 3600.0;  // as if joining all parts anew took an hour: builds patch
    const std::size_t before = w.cached.positions.size();
    const ElementId tile = w.h.polygonElement(44);
    w.h.subdivide(tile);
    w.paint(1.5);
    w.expectTheMeshMadeFromScratch("a tile subdivided");
    const std::size_t grown = w.cached.positions.size(), grownIndices = w.cached.indices.size();
    EXPECT_GT(grown, before + 5) << "the tile's new slot has room beyond its 9 vertices";
    w.h.subdivide(w.h[tile].children[2]);
    w.paint(1.7);
    w.expectTheMeshMadeFromScratch("a quarter of it subdivided");
    EXPECT_EQ(w.cached.positions.size(), grown);
    EXPECT_EQ(w.cached.indices.size(), grownIndices);
    w.h.removeChildren(w.h[tile].children[2]);
    w.h.removeChildren(tile);
    w.paint(2.0);
    w.expectTheMeshMadeFromScratch("its children removed");
    EXPECT_EQ(w.cached.positions.size(), grown) << "a part that shrinks keeps its slot";
    EXPECT_EQ(w.cached.indices.size(), grownIndices);
}

// A build after one that left resized parts waiting makes the new layout
// whatever its stop, so the other parts leave it the time it takes: with a
// new layout taking longer than the stop leaves, only kLeastRemeshed parts
// (or a few more) go ahead, though the stop leaves ample time for them
// alone. The next build without a stop catches up.
TEST(RadiositySnapshot, ABuildThatOwesANewLayoutLeavesItsTime) {
    TiledWall w;
    w.paint(1.0);
    w.expectTheMeshMadeFromScratch("the first build");
    const auto inAMinute = [] { return std::chrono::steady_clock::now() + std::chrono::minutes(1); };
    for (std::uint32_t p : {11u, 55u}) w.h.subdivide(w.h.polygonElement(p));
    w.paint(1.5);
    w.cache.relayoutSeconds = 3600.0;  // as if a new layout took an hour
    EXPECT_EQ(w.build(inAMinute()), 2u) << "the resized tiles wait";
    EXPECT_TRUE(w.cache.resizesWaited);
    w.paint(2.0);
    const std::size_t left = w.build(inAMinute());
    // "A few more": parts meshed at once, in chunks of 16 (at most 7 here).
    EXPECT_GE(left, 100u - kLeastRemeshed - 8u);
    EXPECT_LE(left, 100u - kLeastRemeshed);
    w.expectTheMeshMadeFromScratch("the build after");
}

// Two tiles of one wall that meet edge to edge: the vertices on the shared
// edge show the area-weighted mean of both sides, the same in both tiles'
// meshes, so the tiling does not show; a vertex inside a tile keeps its own.
// The same 1000 km from the world's origin: the mesh's positions are
// relative to its origin (in world floats they would round to 6 cm, and the
// tile's inner vertex onto its edge).
TEST(RadiositySnapshot, TilesMeetingEdgeToEdgeShareTheirEdgeValues) {
    using V = glm::dvec3;
    for (const V offset : {V(0.0), V(1e6, 5e5, -1e6)}) {
        SCOPED_TRACE(offset.x);
        Scene s;
        const auto m = test::addMaterial(s, V(0.5), V(0.0));
        test::addQuadObject(s, "left", m, {{offset + V(0, 0, 0), offset + V(1, 0, 0), offset + V(1, 1, 0), offset + V(0, 1, 0)}});
        test::addQuadObject(s, "right", m, {{offset + V(1, 0, 0), offset + V(2, 0, 0), offset + V(2, 1, 0), offset + V(1, 1, 0)}});
        Hierarchy h(s, 1e-3);
        const ElementId left = h.polygonElement(0), right = h.polygonElement(1);
        h.subdivide(left);  // the left tile has an interior vertex at (0.5, 0.5)
        for (ElementId c : h[left].children) h[c].radiosity = V(1.0);
        h[right].radiosity = V(3.0);
        const MeshSnapshot mesh = makeRadiositySnapshot(s, h);
        EXPECT_EQ(mesh.origin == V(0.0), offset == V(0.0));
        int shared = 0, inner = 0;
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            const glm::dvec3 p = mesh.origin + glm::dvec3(mesh.positions[i]) - offset;
            if (std::abs(p.x - 1.0) < 1e-6 && (std::abs(p.y) < 1e-6 || std::abs(p.y - 1.0) < 1e-6)) {
                // Left: one child of area 1/4 at a corner; right: the whole tile, area 1.
                EXPECT_NEAR(mesh.colors[i].x, (0.25 * 1.0 + 1.0 * 3.0) / 1.25, 1e-5) << p.x << "," << p.y;
                ++shared;
            }
            if (glm::length(p - V(0.5, 0.5, 0.0)) < 1e-6) {
                EXPECT_NEAR(mesh.colors[i].x, 1.0, 1e-6);
                ++inner;
            }
        }
        EXPECT_EQ(shared, 4) << "both corners of the shared edge, once in each tile";
        EXPECT_EQ(inner, 1);
    }
}

// Two tiles folded along their shared edge x = 1: bent by 10 degrees (two
// facets of a tessellated curved surface) the edge shows the area-weighted
// mean of both, so the facets do not show as bands; folded by 25 degrees (a
// 16-sided column's sides are 22.5 apart) or at a right angle (a box's
// faces), each keeps its own.
TEST(RadiositySnapshot, FacetsOfACurvedSurfaceShareTheirEdgeValuesFoldsDoNot) {
    using V = glm::dvec3;
    for (const double degrees : {10.0, 25.0, 90.0}) {
        SCOPED_TRACE(degrees);
        const double a = glm::radians(degrees);
        // The right tile turned about the shared edge (the y axis at x = 1).
        const V far = V(1.0 + std::cos(a), 0.0, std::sin(a));
        Scene s;
        const auto m = test::addMaterial(s, V(0.5), V(0.0));
        test::addQuadObject(s, "left", m, {{V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}});
        test::addQuadObject(s, "right", m, {{V(1, 0, 0), far, far + V(0, 1, 0), V(1, 1, 0)}});
        Hierarchy h(s, 1e-3);
        h[h.polygonElement(0)].radiosity = V(1.0);
        h[h.polygonElement(1)].radiosity = V(3.0);
        const MeshSnapshot mesh = makeRadiositySnapshot(s, h);
        int shared = 0;
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            const glm::dvec3 p = mesh.origin + glm::dvec3(mesh.positions[i]);
            if (std::abs(p.x - 1.0) > 1e-6 || std::abs(p.z) > 1e-6) continue;
            ++shared;
            const bool left = std::abs(mesh.normals[i].z) > 0.9999f;  // the left tile's normal is +-z
            EXPECT_NEAR(mesh.colors[i].x, degrees < 18.0 ? 2.0 : (left ? 1.0 : 3.0), 1e-5) << p.y;
        }
        EXPECT_EQ(shared, 4) << "both ends of the shared edge, once in each tile";
    }
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// The modified-link overlay draws at most SnapshotOverlays::maxLinks of the
// links an update recorded, every k-th: the same segments as the full
// overlay, spread over all of it, and it says how many there were.
TEST(RadiositySnapshot, TheLinkOverlayIsThinnedEvenly) {
    Engine engine(test::roomWithBlock(), EngineSettings{});
    ASSERT_TRUE(engine.solve().converged);
    engine.moveDynamicObject(test::translation(glm::dvec3(0.5, 0.0, 0.3)));
    SnapshotOverlays all{true, false};
    all.maxLinks = std::size_t(-1);
    const MeshSnapshot full = engine.snapshot(all);
    ASSERT_GT(full.modifiedLinks, 1000u);  // enough to thin
    EXPECT_EQ(full.modifiedLinksShown, full.modifiedLinks);
    ASSERT_EQ(full.linePositions.size(), 2 * full.modifiedLinks);

    SnapshotOverlays thin{true, false};
    thin.maxLinks = 300;
    const MeshSnapshot mesh = engine.snapshot(thin);
    EXPECT_EQ(mesh.modifiedLinks, full.modifiedLinks);
    const std::size_t stride = (full.modifiedLinks + thin.maxLinks - 1) / thin.maxLinks;
    ASSERT_LE(mesh.modifiedLinksShown, thin.maxLinks);
    ASSERT_EQ(mesh.linePositions.size(), 2 * mesh.modifiedLinksShown);
    // The last one drawn is within one stride of the end: spread over all.
    EXPECT_GT((mesh.modifiedLinksShown - 1) * stride + stride, full.modifiedLinks - 1);
    for (std::size_t i = 0; i < mesh.modifiedLinksShown; ++i)
        for (int k = 0; k < 2; ++k) EXPECT_EQ(mesh.linePositions[2 * i + k], full.linePositions[2 * i * stride + k]) << i;
    // Without the overlay nothing is drawn, but the count is still there.
    const MeshSnapshot none = engine.snapshot();
    EXPECT_TRUE(none.linePositions.empty());
    EXPECT_EQ(none.modifiedLinks, full.modifiedLinks);
    EXPECT_EQ(none.modifiedLinksShown, 0u);
}

// The changed-element overlay outlines the changed leaves, each edge once
// whichever of its two neighbours it came from.
TEST(RadiositySnapshot, ChangedOutlinesDrawEachEdgeOnce) {
    Engine engine(test::roomWithBlock(), EngineSettings{});
    ASSERT_TRUE(engine.solve().converged);
    engine.moveDynamicObject(test::translation(glm::dvec3(0.5, 0.0, 0.3)));
    SnapshotOverlays outlines{false, true};
    const MeshSnapshot mesh = engine.snapshot(outlines);
    ASSERT_GT(mesh.linePositions.size(), 100u);
    ASSERT_EQ(mesh.linePositions.size() % 2, 0u);
    std::vector<std::array<float, 6>> edges;
    for (std::size_t i = 0; i < mesh.linePositions.size(); i += 2) {
        glm::vec3 a = mesh.linePositions[i], b = mesh.linePositions[i + 1];
        if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
        edges.push_back({a.x, a.y, a.z, b.x, b.y, b.z});
    }
    std::sort(edges.begin(), edges.end());
    EXPECT_EQ(std::adjacent_find(edges.begin(), edges.end()), edges.end()) << "an edge drawn twice";
}

}  // namespace
}  // namespace rad
