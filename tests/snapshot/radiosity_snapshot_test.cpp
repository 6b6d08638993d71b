#include <gtest/gtest.h>

#include "hierarchy/Hierarchy.h"
#include "snapshot/RadiositySnapshot.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

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
}

// A frame re-meshes only the polygons whose leaves changed (SnapshotCache):
// after radiosity changes, a subdivision, a removal and a moved polygon, the
// cached mesh is the mesh made from scratch, vertex for vertex.
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
        const MeshSnapshot fresh = makeRadiositySnapshot(s, h);
        ASSERT_EQ(cached.positions, fresh.positions) << after;
        ASSERT_EQ(cached.normals, fresh.normals) << after;
        ASSERT_EQ(cached.colors, fresh.colors) << after;
        ASSERT_EQ(cached.indices, fresh.indices) << after;
    };
    expectSame("the first build");
    const ElementId wall = h.polygonElement(0);
    h.subdivide(wall);
    for (ElementId c : h[wall].children) light(c);
    expectSame("a subdivision");
    light(h[wall].children[2]);
    expectSame("a leaf's radiosity changed");
    h.removeChildren(wall);
    expectSame("the children removed");
    const std::uint32_t moved = s.objects.back().firstPolygon;
    for (int k = 0; k < s.polygons[moved].vertexCount; ++k) s.polygons[moved].vertices[k] += glm::dvec3(0.1, 0.0, 0.0);
    h.updateGeometry(h.polygonElement(moved));
    expectSame("a polygon moved");
    expectSame("nothing changed");
}

}  // namespace
}  // namespace rad
