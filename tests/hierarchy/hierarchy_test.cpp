// The H-element hierarchy: attaching an object's cluster to the root (paper
// sec. 3.3) must leave a well-formed tree, with index ranges that still nest
// (sec. 3.2) and cluster boxes and areas that still enclose their children,
// and cluster shapes whose facets are sized to them and hold their area,
// with samples on their members' front sides that stand for that area.

#include "hierarchy/Hierarchy.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "radiosity/Gltf.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

bool holds(const Aabb& outer, const Aabb& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::lessThanEqual(inner.hi, outer.hi));
}

// Checks the subtree of `id` and returns the number of elements in it.
std::size_t checkSubtree(const Scene& scene, const Hierarchy& h, ElementId id, std::string& problem) {
    const HElement& e = h[id];
    std::size_t count = 1;
    double area = 0.0;
    const IndexRange range = h.range(id);
    std::uint64_t next = range.first + 1;
    for (std::size_t k = 0; k < e.children.size(); ++k) {
        const ElementId c = e.children[k];
        const HElement& child = h[c];
        const IndexRange childRange = h.range(c);
        if (child.parent != id) problem = "element " + std::to_string(c) + ": wrong parent";
        if (!range.contains(childRange)) problem = "element " + std::to_string(c) + ": range outside its parent's";
        if (childRange.first < next) problem = "element " + std::to_string(c) + ": range overlaps a sibling's";
        next = childRange.last + 1;
        if (e.isSurface()) {
            const IndexRange expected = quadtreeChildRange(range, static_cast<int>(k));
            if (childRange.first != expected.first || childRange.last != expected.last)
                problem = "element " + std::to_string(c) + ": not its quadtree range";
        } else {
            if (!holds(h.box(id), h.box(c)))
                problem = "cluster " + std::to_string(id) + ": box does not hold child " + std::to_string(c);
            area += child.area;
        }
        count += checkSubtree(scene, h, c, problem);
    }
    if (!e.isSurface()) {
        if (e.children.empty()) problem = "cluster " + std::to_string(id) + " is empty";
        if (std::abs(area - e.area) > 1e-9 * std::max(1.0, area)) problem = "cluster " + std::to_string(id) + ": area";
        // Its facets, sized to the cluster, hold every member's area once.
        const ClusterShape& shape = h.shape(id);
        const auto n = static_cast<std::size_t>(shape.facetCount());
        if (n < 1 || n > ClusterShape::kMaxFacets || shape.power.size() != n || shape.gathered.size() != n)
            problem = "cluster " + std::to_string(id) + ": facets not sized to its " + std::to_string(n);
        double facetArea = 0.0;
        for (const ClusterShape::Facet& f : shape.facets) facetArea += f.area;
        if (std::abs(facetArea - e.area) > 1e-9 * std::max(1.0, area)) problem = "cluster " + std::to_string(id) + ": facet areas";
        // Its samples stand for its area, and lie on front sides of its members.
        if (std::abs(shape.sampleCount * double(shape.sampleWeight) - e.area) > 1e-5 * std::max(1.0, area))
            problem = "cluster " + std::to_string(id) + ": sample weights";
        for (int k = 0; k < shape.sampleCount; ++k) {
            const ClusterShape::Sample& q = shape.samples[k];
            const Polygon& on = scene.polygons[q.polygon];
            if (glm::dot(q.normal(), on.normal()) < 1.0 - 1e-8)
                problem = "cluster " + std::to_string(id) + ": sample normal";
            // Its position, relative to the cluster's centre, on the polygon's
            // plane (within the float rounding of the file's coordinates: a
            // quad read from float32 is planar to about 1e-7 of them).
            const glm::dvec3 p = e.center + glm::dvec3(q.p);
            const double size = glm::length(h.box(id).extent());
            const double magnitude = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
            if (std::abs(glm::dot(on.normal(), p - on.vertices[0])) > 1e-6 * size + 1e-7 * magnitude)
                problem = "cluster " + std::to_string(id) + ": sample off its polygon";
        }
    }
    return count;
}

// The polygons under each cluster of `cluster`'s subtree, each list sorted.
void collectGroups(const Hierarchy& h, ElementId cluster,
                   std::vector<std::vector<std::uint32_t>>& groups) {
    std::vector<std::uint32_t> polygons;
    for (std::vector<ElementId> stack{cluster}; !stack.empty();) {
        const ElementId e = stack.back();
        stack.pop_back();
        if (h[e].isSurface()) {
            polygons.push_back(h[e].polygon);
            continue;
        }
        for (ElementId c : h[e].children) stack.push_back(c);
    }
    std::sort(polygons.begin(), polygons.end());
    groups.push_back(polygons);
    for (ElementId c : h[cluster].children)
        if (!h[c].isSurface()) collectGroups(h, c, groups);
}

// An object's cluster tree follows its own axes: turned by a few degrees
// with its node, it groups its polygons into the same clusters, and so
// divides the light a cluster link brings it alike. A diamond of tiles, as
// wide along x as along z, split along the world's axes, was split along x
// unturned and along z turned by 5 degrees.
// Each surface keeps the 2 x 2 Gauss points of its patch (the visibility
// rays' ends): made with the patch, at subdivision and after a move.
TEST(Hierarchy, QuadraturePointsFollowThePatch) {
    Scene scene = test::roomWithBlock();
    Hierarchy h(scene, 1e-4);
    std::uint32_t block = 0;
    while (scene.objects[block].name != "block") ++block;
    // Subdivide a wall and a face of the block, each two levels deep.
    for (std::uint32_t p : {0u, scene.objects[block].firstPolygon}) {
        const ElementId e = h.polygonElement(p);
        h.subdivide(e);
        h.subdivide(h[e].children[2]);
    }
    const auto checkAll = [&](const char* when) {
        int surfaces = 0;
        for (ElementId e = 0; e < h.size(); ++e) {
            if (!h.isLive(e) || !h[e].isSurface()) continue;
            ++surfaces;
            const SampleSet fresh = patchSamples(h.patch(e), 2);
            const QuadraturePoints kept = h.quadrature(e);
            ASSERT_EQ(kept.size(), fresh.size()) << when << ", element " << e;
            // Kept in single precision (PackedQuadrature): within a float's
            // rounding of the offset from the patch's corner, and of the weight.
            const double size = glm::length(h.box(e).hi - h.box(e).lo);
            for (std::size_t k = 0; k < fresh.size(); ++k) {
                EXPECT_LE(glm::length(kept.points[k].p - fresh[k].p), 1e-7 * size)
                    << when << ", element " << e << ", point " << k;
                EXPECT_NEAR(kept.points[k].w, fresh[k].w, 1e-7 * fresh[k].w)
                    << when << ", element " << e << ", point " << k;
            }
        }
        EXPECT_GT(surfaces, int(scene.polygons.size()) + 12) << when;
    };
    checkAll("subdivided");
    // The block turns and moves: its elements' patches and points go with it.
    const glm::dmat4 move = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(0.4, 0.1, -0.3)), 0.6,
                                        glm::dvec3(0.0, 1.0, 0.0));
    const Object& o = scene.objects[block];
    for (std::uint32_t p = o.firstPolygon; p < o.firstPolygon + o.polygonCount; ++p)
        for (glm::dvec3& v : scene.polygons[p].vertices) v = glm::dvec3(move * glm::dvec4(v, 1.0));
    const glm::dvec3 before = h.quadrature(h.polygonElement(o.firstPolygon)).points[0].p;
    h.updateGeometry(h.objectCluster(block));
    EXPECT_NE(h.quadrature(h.polygonElement(o.firstPolygon)).points[0].p, before);
    checkAll("moved");
}

// Each polygon's count of leaves (what meshing it writes, and what a
// frame's meshing time is expected from) follows subdivision and removal:
// it equals the leaves found by walking the polygon's quadtree.
TEST(Hierarchy, PolygonLeavesFollowSubdivisionAndRemoval) {
    const Scene scene = test::roomWithBlock();
    Hierarchy h(scene, 1e-4);
    const auto expectCounts = [&](const char* when) {
        for (std::uint32_t p = 0; p < h.polygonCount(); ++p) {
            std::uint32_t leaves = 0;
            for (std::vector<ElementId> stack{h.polygonElement(p)}; !stack.empty();) {
                const HElement& e = h[stack.back()];
                stack.pop_back();
                leaves += e.isLeaf();
                stack.insert(stack.end(), e.children.begin(), e.children.end());
            }
            EXPECT_EQ(h.polygonLeaves(p), leaves) << when << ", polygon " << p;
        }
    };
    expectCounts("built");
    const ElementId wall = h.polygonElement(0), floor = h.polygonElement(1);
    h.subdivide(wall);
    h.subdivide(h[wall].children[2]);
    h.subdivide(h[h[wall].children[2]].children[0]);
    h.subdivide(floor);
    EXPECT_EQ(h.polygonLeaves(0), 10u);
    expectCounts("subdivided");
    h.removeChildren(h[wall].children[2]);  // seven leaves become one
    EXPECT_EQ(h.polygonLeaves(0), 4u);
    expectCounts("a subtree removed");
    h.removeChildren(floor);
    h.removeChildren(floor);  // nothing left to remove
    EXPECT_EQ(h.polygonLeaves(1), 1u);
    expectCounts("removed");
}

// The log of freed ids: what keeps a value per element (the live estimate's
// sums) makes it again for the ids freed since it last looked, or for all
// when the log no longer reaches back that far (it keeps the last
// kReleaseLog at least, and none after compact(0), the end of a solve).
TEST(Hierarchy, FreedIdsAreLoggedForWhatKeepsAValuePerElement) {
    const Scene scene = test::roomWithBlock();
    Hierarchy h(scene, 1e-4);
    const ElementId wall = h.polygonElement(0);
    const std::uint64_t before = h.releases();
    ASSERT_TRUE(h.releasedSince(before).has_value());
    EXPECT_TRUE(h.releasedSince(before)->empty());
    h.subdivide(wall);
    h.subdivide(h[wall].children[1]);
    std::vector<ElementId> expected(h[wall].children.begin(), h[wall].children.end());
    for (ElementId c : h[h[wall].children[1]].children) expected.push_back(c);
    h.removeChildren(wall);
    EXPECT_EQ(h.releases(), before + expected.size());
    const auto freed = h.releasedSince(before);
    ASSERT_TRUE(freed.has_value());
    std::vector<ElementId> got(freed->begin(), freed->end());
    std::sort(got.begin(), got.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(got, expected);
    EXPECT_EQ(h.releasedSince(h.releases())->size(), 0u);
    EXPECT_FALSE(h.releasedSince(h.releases() + 1).has_value()) << "a count from the future";
    // Past the log's reach, an old count gets nothing: all is made again.
    while (h.releases() < before + 3 * Hierarchy::kReleaseLog) {
        h.subdivide(wall);
        h.removeChildren(wall);
    }
    EXPECT_FALSE(h.releasedSince(before).has_value());
    const std::uint64_t recent = h.releases() - Hierarchy::kReleaseLog;
    ASSERT_TRUE(h.releasedSince(recent).has_value());
    EXPECT_EQ(h.releasedSince(recent)->size(), Hierarchy::kReleaseLog);
    h.compact(0.0);
    EXPECT_FALSE(h.releasedSince(recent).has_value());
    EXPECT_TRUE(h.releasedSince(h.releases()).has_value());
}

// The leaves of the polygons to be meshed anew (what a frame on a deadline
// leaves the snapshot time for): a polygon counts its leaves when its
// quadtree first changes, and three more per subdivision after; a polygon
// marked by the engine (a move) counts its leaves; after a snapshot only
// those it left (still marked in meshTouched) stay counted.
TEST(Hierarchy, ReshapedLeavesCountThePolygonsToMeshAnew) {
    const Scene scene = test::roomWithBlock();
    Hierarchy h(scene, 1e-4);
    EXPECT_EQ(h.reshapedLeaves(), 0u);
    const ElementId wall = h.polygonElement(0), floor = h.polygonElement(1);
    h.subdivide(wall);
    EXPECT_EQ(h.reshapedLeaves(), 4u);
    h.subdivide(h[wall].children[2]);
    EXPECT_EQ(h.reshapedLeaves(), 7u);
    h.subdivide(floor);
    EXPECT_EQ(h.reshapedLeaves(), 11u);
    h.markReshaped(2);  // moved: its one leaf
    h.markReshaped(2);  // once
    EXPECT_EQ(h.reshapedLeaves(), 12u);
    // A snapshot that meshed the floor and polygon 2 but left the wall.
    std::vector<std::uint8_t>& touched = h.meshTouched();
    std::fill(touched.begin(), touched.end(), std::uint8_t(0));
    touched[0] = 1;
    h.clearReshaped();
    EXPECT_EQ(h.reshapedLeaves(), h.polygonLeaves(0));
    // The wall's removal keeps it marked; the next snapshot meshes it.
    h.removeChildren(h[wall].children[2]);
    touched[0] = 0;
    h.clearReshaped();
    EXPECT_EQ(h.reshapedLeaves(), 0u);
    h.removeChildren(floor);  // marked again: its leaves before the removal
    EXPECT_EQ(h.reshapedLeaves(), 4u);
}

TEST(Hierarchy, AnObjectsClustersDoNotChangeWhenItTurns) {
    const auto grouped = [](double degrees) {
        Scene s;
        const auto m = test::addMaterial(s, glm::dvec3(0.5), glm::dvec3(0.0));
        const glm::dmat4 turn =
            glm::rotate(glm::dmat4(1.0), glm::radians(degrees), glm::dvec3(0.0, 1.0, 0.0));
        const glm::dmat4 diamond =
            glm::rotate(glm::dmat4(1.0), glm::radians(45.0), glm::dvec3(0.0, 1.0, 0.0));
        std::vector<std::array<glm::dvec3, 4>> quads;
        const double h = 0.05;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                const glm::dvec3 c(0.3 * (i - 1.5), 0.0, 0.3 * (j - 1.5));
                std::array<glm::dvec3, 4> q = {c + glm::dvec3(-h, 0, -h), c + glm::dvec3(-h, 0, h),
                                               c + glm::dvec3(h, 0, h),
                                               c + glm::dvec3(h, 0, -h)};  // facing +y
                for (glm::dvec3& v : q)
                    v = glm::dvec3(turn * diamond * glm::dvec4(v, 1.0)) + glm::dvec3(2.0, 1.0, 3.0);
                quads.push_back(q);
            }
        const std::uint32_t o = test::addQuadObject(s, "tiles", m, quads);
        s.objects[o].worldFromLocal =
            glm::translate(glm::dmat4(1.0), glm::dvec3(2.0, 1.0, 3.0)) * turn;
        const Hierarchy hierarchy(s, 1e-3);
        std::vector<std::vector<std::uint32_t>> groups;
        collectGroups(hierarchy, hierarchy.objectCluster(o), groups);
        std::sort(groups.begin(), groups.end());
        return groups;
    };
    const auto unturned = grouped(0.0);
    EXPECT_GT(unturned.size(), 2u) << "the tiles make a tree";
    for (double degrees : {5.0, -5.0, 30.0})
        EXPECT_EQ(grouped(degrees), unturned) << degrees << " degrees";
}

TEST(Hierarchy, AttachToRootKeepsTheTreeWellFormed) {
    const Scene scene = loadGltf(test::sourcePath("scenes/office.gltf"));
    Hierarchy h(scene, 1e-4);
    const std::uint32_t desk = *scene.findObject("desk-1");
    const ElementId cluster = h.objectCluster(desk);
    ASSERT_NE(h[cluster].parent, h.root());
    // Some subdivision below the desk and elsewhere, whose ranges must follow.
    h.subdivide(h.polygonElement(scene.objects[desk].firstPolygon));
    h.subdivide(h[h.polygonElement(scene.objects[desk].firstPolygon)].children[2]);
    h.subdivide(h.polygonElement(0));
    const std::size_t elements = h.liveCount();
    const std::uint64_t indices = h.range(h.root()).size();
    const std::size_t movableBefore = h.movableClusters().size();
    EXPECT_TRUE(h.emptiedBy(cluster).empty());

    h.attachToRoot(cluster);
    EXPECT_EQ(h[cluster].parent, h.root());
    EXPECT_TRUE(h.isMovable(cluster));
    EXPECT_EQ(h.movableClusters().size(), movableBefore + 1);
    std::string problem;
    EXPECT_EQ(checkSubtree(scene, h, h.root(), problem), elements);
    EXPECT_TRUE(problem.empty()) << problem;
    EXPECT_EQ(h.liveCount(), elements);
    EXPECT_EQ(h.range(h.root()).size(), indices);  // the same elements, numbered again
    // The desk's path of elements is found from the root.
    const auto path = h.pathTo(scene.objects[desk].firstPolygon, glm::dvec2(0.75, 0.75));
    ASSERT_GE(path.size(), 4u);
    EXPECT_EQ(path[0], h.root());
    EXPECT_EQ(path[1], cluster);
}

TEST(Hierarchy, AttachToRootFreesTheClustersItEmpties) {
    Scene s;
    const auto white = test::addMaterial(s, glm::dvec3(0.5), glm::dvec3(0.0));
    const auto light = test::addMaterial(s, glm::dvec3(0.0), glm::dvec3(1.0));
    test::addQuadObject(s, "room", white, test::boxFaces(glm::dvec3(0.0), glm::dvec3(2.0), true));
    test::addQuadObject(s, "lamp", light, test::boxFaces(glm::dvec3(0.8), glm::dvec3(1.2), false), true);
    Hierarchy h(s, 1e-3);
    const ElementId room = h.objectCluster(0);
    const auto emptied = h.emptiedBy(room);
    ASSERT_EQ(emptied.size(), 1u);  // the tree over the static objects holds the room alone
    const std::size_t elements = h.liveCount();
    h.attachToRoot(room);
    EXPECT_EQ(h.liveCount(), elements - 1);
    EXPECT_EQ(h[h.root()].children.size(), 2u);  // the lamp and the room
    std::string problem;
    EXPECT_EQ(checkSubtree(s, h, h.root(), problem), elements - 1);
    EXPECT_TRUE(problem.empty()) << problem;
    // Attaching again changes nothing.
    h.attachToRoot(room);
    EXPECT_EQ(h.liveCount(), elements - 1);
    EXPECT_EQ(h.movableClusters().size(), 2u);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// Parametric corners are single precision: exact for dyadic fractions down
// to HElement::kMaxDepth levels. An area threshold that would allow deeper
// quadtrees stops there, and the deepest corners are still exact.
TEST(Hierarchy, SubdivisionStopsWhereFloatCornersStayExact) {
    using V = glm::dvec3;
    for (int corners : {4, 3}) {
        Scene s;
        const auto m = test::addMaterial(s, V(0.5), V(0.0));
        if (corners == 4) {
            test::addQuadObject(s, "quad", m, {{V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}});
        } else {
            Object o;
            o.name = "triangle";
            o.firstPolygon = 0;
            o.polygonCount = 1;
            s.objects.push_back(o);
            Polygon p;
            p.vertexCount = 3;
            p.vertices = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0)};
            p.material = m;
            s.polygons.push_back(p);
        }
        Hierarchy h(s, 1e-18);  // the index ranges allow 29 levels
        ElementId e = h.polygonElement(0);
        int depth = 0;
        while (h.canSubdivide(e)) {
            h.subdivide(e);
            e = h[e].children[3];  // the middle triangle, or a quad's last corner
            ++depth;
        }
        EXPECT_EQ(depth, HElement::kMaxDepth) << corners << " corners";
        for (const glm::vec2& c : h[e].param)
            for (int k = 0; k < 2; ++k) {
                const double scaled = std::ldexp(double(c[k]), HElement::kMaxDepth);
                EXPECT_EQ(scaled, std::round(scaled)) << corners << " corners";
            }
        EXPECT_GT(h[e].area, 0.0);
    }
}

// Children keep at least the area threshold, except near a contact
// (Refiner::chooseSplit), where they may go one level further, and along an
// emitter, two: a unit square at a threshold of 1/16 splits twice, near a
// contact three times and along an emitter four.
TEST(Hierarchy, SubdivisionKeepsTheAreaThresholdAndOneOrTwoLevelsMoreNearAContact) {
    using V = glm::dvec3;
    Scene s;
    const auto m = test::addMaterial(s, V(0.5), V(0.0));
    test::addQuadObject(s, "quad", m, {{V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)}});
    Hierarchy h(s, 1.0 / 16.0);
    ElementId e = h.polygonElement(0);
    std::vector<bool> normal, nearContact, alongEmitter;
    for (int depth = 0; depth < 6 && h.canSubdivide(e, 2); ++depth) {
        normal.push_back(h.canSubdivide(e));
        nearContact.push_back(h.canSubdivide(e, 1));
        alongEmitter.push_back(h.canSubdivide(e, 2));
        h.subdivide(e);
        e = h[e].children[0];
    }
    EXPECT_EQ(normal, (std::vector<bool>{true, true, false, false}));
    EXPECT_EQ(nearContact, (std::vector<bool>{true, true, true, false}));
    EXPECT_EQ(alongEmitter, (std::vector<bool>{true, true, true, true}));
    EXPECT_FALSE(h.canSubdivide(e, 2));
    EXPECT_DOUBLE_EQ(h[e].area, 1.0 / 256.0);
}

}  // namespace
}  // namespace rad
