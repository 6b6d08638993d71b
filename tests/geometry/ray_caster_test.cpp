// Two-layer Embree visibility: blockers, segment ends on surfaces, layer independence, picking,
// instances moved by their transforms, and the same answers at millimetre and kilometre scale.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "geometry/RayCaster.h"

namespace rad {
namespace {

// Axis-aligned square [x0,x1] x [y0,y1] at height z, facing +z.
Polygon squareZ(double x0, double x1, double y0, double y1, double z) {
    Polygon p;
    p.vertices = {glm::dvec3(x0, y0, z), glm::dvec3(x1, y0, z), glm::dvec3(x1, y1, z),
                  glm::dvec3(x0, y1, z)};
    p.vertexCount = 4;
    return p;
}

// Square [y0,y1] x [z0,z1] in the plane x = x0, facing +x.
Polygon squareX(double y0, double y1, double z0, double z1, double x) {
    Polygon p;
    p.vertices = {glm::dvec3(x, y0, z0), glm::dvec3(x, y1, z0), glm::dvec3(x, y1, z1),
                  glm::dvec3(x, y0, z1)};
    p.vertexCount = 4;
    return p;
}

constexpr std::uint32_t kNo = RayCaster::kNoPolygon;

// Whether the segment a -> b (its ends on the given polygons) is blocked in
// the layer: one segment through the engine's own query.
bool occluded(const RayCaster& rc, Layer layer, const glm::dvec3& a, const glm::dvec3& b, std::uint32_t fromPolygon = kNo,
              std::uint32_t toPolygon = kNo) {
    const RayCaster::Segment s{a, b, fromPolygon, toPolygon};
    return rc.blocked(layer, std::span(&s, 1)) != 0;
}

// How many of the segments from[i] -> to[i] the layer blocks, in packets of 16.
std::size_t blockedCount(const RayCaster& rc, Layer layer, const std::vector<glm::dvec3>& from,
                         const std::vector<glm::dvec3>& to) {
    std::size_t n = 0;
    std::vector<RayCaster::Segment> segments;
    for (std::size_t i = 0; i < from.size(); ++i) segments.push_back({from[i], to[i]});
    for (std::size_t i = 0; i < segments.size(); i += 16) {
        const std::size_t m = std::min<std::size_t>(16, segments.size() - i);
        n += std::popcount(rc.blocked(layer, std::span(segments.data() + i, m)));
    }
    return n;
}

std::vector<std::uint32_t> allIds(const Scene& s) {
    std::vector<std::uint32_t> ids(s.polygons.size());
    std::iota(ids.begin(), ids.end(), 0u);
    return ids;
}

TEST(RayCaster, BlockerBlocksAndSegmentBesideDoesNot) {
    Scene scene;
    scene.polygons = {squareZ(-1, 1, -1, 1, 0)};
    RayCaster rc;
    rc.setLayer(Layer::Static, scene, allIds(scene));
    EXPECT_TRUE(occluded(rc, Layer::Static, {0, 0, -1}, {0, 0, 1}));
    EXPECT_TRUE(occluded(rc, Layer::Static, {0, 0, 1}, {0.5, 0.5, -1}));  // from the back too
    EXPECT_FALSE(occluded(rc, Layer::Static, {3, 0, -1}, {3, 0, 1}));
    EXPECT_FALSE(occluded(rc, Layer::Static, {0, 0, 0.5}, {0, 0, 2}));  // both ends above
}

TEST(RayCaster, MaskMarksTheBlockedSegments) {
    Scene scene;
    scene.polygons = {squareZ(-1, 1, -1, 1, 0)};
    RayCaster rc;
    rc.setLayer(Layer::Static, scene, allIds(scene));
    std::vector<glm::dvec3> from, to;
    for (int i = 0; i < 10; ++i) {
        const double x = -1.9 + 0.4 * i;  // -1.9 .. 1.7: -0.7, -0.3, 0.1, 0.5, 0.9 cross the square
        from.push_back({x, 0.3, -1});
        to.push_back({x, -0.2, 1});
    }
    std::vector<RayCaster::Segment> segments;
    for (int i = 0; i < 10; ++i) segments.push_back({from[i], to[i]});
    EXPECT_EQ(rc.blocked(Layer::Static, segments), 0b0011111000);
    EXPECT_EQ(rc.blocked(Layer::Static, {}), 0);
    EXPECT_EQ(blockedCount(rc, Layer::Static, from, to), 5u);
}

// Coincident surfaces: of a stack of identical polygons facing the same way,
// the one with the lowest index is seen and the others are hidden behind it,
// from both ends of a segment; so a receiver sees their union, not their sum.
TEST(RayCaster, CoincidentDuplicatesHideAllButTheLowestIndex) {
    Scene scene;
    Polygon down = squareZ(-1, 1, -1, 1, 1);  // facing -z after the swap below
    std::swap(down.vertices[1], down.vertices[3]);
    scene.polygons = {down, down, squareZ(-2, 2, -2, 2, 0)};  // 0 and 1 identical, 2 the floor below
    RayCaster rc;
    rc.setFrame(scene.bounds());
    rc.setLayer(Layer::Static, scene, allIds(scene));
    const glm::dvec3 floor(0.2, 0.1, 0), plate(-0.3, 0.4, 1);
    EXPECT_FALSE(occluded(rc, Layer::Static, floor, plate, 2, 0));  // the floor sees plate 0
    EXPECT_TRUE(occluded(rc, Layer::Static, floor, plate, 2, 1));   // plate 1 is behind it
    EXPECT_FALSE(occluded(rc, Layer::Static, plate, floor, 0, 2));  // plate 0 sees the floor
    EXPECT_TRUE(occluded(rc, Layer::Static, plate, floor, 1, 2));   // plate 1 does not
    // A plate 0.1 mm above the floor is not coincident with it: it blocks.
    Scene thin;
    Polygon plateDown = squareZ(-1, 1, -1, 1, 1e-4);
    std::swap(plateDown.vertices[1], plateDown.vertices[3]);
    thin.polygons = {squareZ(-2, 2, -2, 2, 0), plateDown, squareZ(-1, 1, -1, 1, 1e-4)};
    RayCaster thinRc;
    thinRc.setFrame(Aabb{glm::dvec3(-2, -2, 0), glm::dvec3(2, 2, 3)});
    thinRc.setLayer(Layer::Static, thin, allIds(thin));
    EXPECT_TRUE(occluded(thinRc, Layer::Static, glm::dvec3(0.1, 0.2, 0), glm::dvec3(0.3, 0.1, 3), 0, kNo));
    // The plate's underside sees the floor under it, its top the space above.
    EXPECT_FALSE(occluded(thinRc, Layer::Static, glm::dvec3(0.1, 0.2, 1e-4), glm::dvec3(0.3, 0.1, 0), 1, 0));
    EXPECT_FALSE(occluded(thinRc, Layer::Static, glm::dvec3(0.1, 0.2, 1e-4), glm::dvec3(0.3, 0.1, 3), 2, kNo));
}

// A zero-thickness slab: two coincident faces back to back. Each is seen from
// its own side; nothing passes through.
TEST(RayCaster, ZeroThicknessSlabShowsEachFaceFromItsSide) {
    Scene scene;
    Polygon bottom = squareZ(-1, 1, -1, 1, 1);
    std::swap(bottom.vertices[1], bottom.vertices[3]);
    scene.polygons = {squareZ(-1, 1, -1, 1, 1), bottom};  // 0 faces +z, 1 faces -z
    RayCaster rc;
    rc.setFrame(Aabb{glm::dvec3(-2, -2, 0), glm::dvec3(2, 2, 2)});
    rc.setLayer(Layer::Static, scene, allIds(scene));
    const glm::dvec3 on(0.2, 0.3, 1), above(0.5, 0.1, 2), below(-0.4, 0.2, 0);
    EXPECT_FALSE(occluded(rc, Layer::Static, above, on, kNo, 0));
    EXPECT_FALSE(occluded(rc, Layer::Static, below, on, kNo, 1));
    EXPECT_FALSE(occluded(rc, Layer::Static, on, above, 0, kNo));
    EXPECT_FALSE(occluded(rc, Layer::Static, on, below, 1, kNo));
    EXPECT_TRUE(occluded(rc, Layer::Static, above, below));
    EXPECT_TRUE(occluded(rc, Layer::Static, below, above));
}

TEST(RayCaster, SegmentEndsOnAPolygonAreNotBlockedByIt) {
    Scene scene;
    scene.polygons = {squareZ(0, 1, 0, 1, 0), squareX(0, 1, 0, 1, 0), squareZ(0, 1, 0, 1, 1)};
    RayCaster rc;
    rc.setLayer(Layer::Static, scene, allIds(scene));
    // Floor to ceiling, both ends on polygons of the layer.
    EXPECT_FALSE(occluded(rc, Layer::Static, {0.3, 0.4, 0}, {0.7, 0.2, 1}));
    // Floor to the wall, close to the shared corner, oblique.
    EXPECT_FALSE(occluded(rc, Layer::Static, {0.02, 0.5, 0}, {0, 0.45, 0.03}));
    // Steep grazing angle from the floor.
    EXPECT_FALSE(occluded(rc, Layer::Static, {0.1, 0.1, 0}, {0.9, 0.9, 0.05}));
    // On a triangulation seam (the quad's diagonal).
    EXPECT_FALSE(occluded(rc, Layer::Static, {0.5, 0.5, 0}, {0.5, 0.5, 1}));
}

TEST(RayCaster, LayersAreIndependent) {
    Scene scene;
    scene.polygons = {squareZ(-5, 5, -5, 5, 0), squareZ(-0.5, 0.5, -0.5, 0.5, 1)};
    RayCaster rc;
    const std::uint32_t staticIds[] = {0};
    const std::uint32_t dynamicIds[] = {1};
    rc.setLayer(Layer::Static, scene, staticIds);
    // Dynamic layer not set yet: nothing blocks there.
    EXPECT_FALSE(occluded(rc, Layer::Dynamic, {0, 0, 0}, {0, 0, 2}));
    rc.setLayer(Layer::Dynamic, scene, dynamicIds);
    EXPECT_TRUE(occluded(rc, Layer::Dynamic, {0, 0, 0}, {0, 0, 2}));
    EXPECT_FALSE(occluded(rc, Layer::Static, {0, 0, 0}, {0, 0, 2}));  // floor end is ignored
    EXPECT_TRUE(occluded(rc, Layer::Static, {0, 0, -1}, {0, 0, 2}));
    EXPECT_FALSE(occluded(rc, Layer::Dynamic, {0, 0, -1}, {3, 0, 2}));
    // Emptying a layer.
    rc.setLayer(Layer::Dynamic, scene, {});
    EXPECT_FALSE(occluded(rc, Layer::Dynamic, {0, 0, 0}, {0, 0, 2}));
    const std::uint32_t bad[] = {7};
    EXPECT_THROW(rc.setLayer(Layer::Dynamic, scene, bad), std::out_of_range);
}

TEST(RayCaster, ReplacingTheDynamicLayerAfterAMove) {
    Scene scene;
    scene.polygons = {squareZ(-0.5, 0.5, -0.5, 0.5, 1)};
    RayCaster rc;
    const std::uint32_t ids[] = {0};
    rc.setLayer(Layer::Dynamic, scene, ids);
    const glm::dvec3 a(0, 0, 0), b(0, 0, 2), c(3, 0, 0), d(3, 0, 2);
    EXPECT_TRUE(occluded(rc, Layer::Dynamic, a, b));
    EXPECT_FALSE(occluded(rc, Layer::Dynamic, c, d));
    for (glm::dvec3& v : scene.polygons[0].vertices) v.x += 3.0;  // the object moves
    rc.setLayer(Layer::Dynamic, scene, ids);
    EXPECT_FALSE(occluded(rc, Layer::Dynamic, a, b));
    EXPECT_TRUE(occluded(rc, Layer::Dynamic, c, d));
    // Moving the caster keeps the layers.
    RayCaster moved = std::move(rc);
    EXPECT_TRUE(occluded(moved, Layer::Dynamic, c, d));
}

// Instances moved by their transforms block exactly what the same polygons,
// moved and built from scratch, block: through them, from points on them
// (the end polygon is never its own blocker), and when picked.
TEST(RayCaster, InstancesMovedByTransformsBlockAsPolygonsBuiltWhereTheyAre) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Scene scene;
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 c(u(rng), u(rng), u(rng));
        scene.polygons.push_back(i % 2 ? squareZ(c.x, c.x + 0.1, c.y, c.y + 0.1, c.z) : squareX(c.y, c.y + 0.1, c.z, c.z + 0.1, c.x));
    }
    std::vector<std::uint32_t> a(100), b(100);
    std::iota(a.begin(), a.end(), 0u);
    std::iota(b.begin(), b.end(), 100u);
    RayCaster rc;
    rc.setFrame(Aabb{glm::dvec3(-1.2), glm::dvec3(1.2)});
    const std::size_t ia = rc.addInstance(scene, a), ib = rc.addInstance(scene, b);
    // Two rigid motions, then the first again from its added pose (a move is
    // not added to the one before).
    const glm::dmat4 ma = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(0.3, -0.2, 0.1)), 0.7, glm::dvec3(1, 2, 3));
    const glm::dmat4 mb = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(-0.1, 0.25, 0.0)), -1.1, glm::dvec3(0, 1, 0));
    rc.moveInstance(ia, glm::rotate(glm::dmat4(1.0), 0.3, glm::dvec3(0, 0, 1)));
    rc.moveInstance(ib, mb);
    rc.commitInstances();
    rc.moveInstance(ia, ma);
    rc.commitInstances();
    Scene moved = scene;
    for (std::uint32_t i = 0; i < moved.polygons.size(); ++i)
        for (glm::dvec3& v : moved.polygons[i].vertices) v = glm::dvec3((i < 100 ? ma : mb) * glm::dvec4(v, 1.0));
    RayCaster fresh;
    fresh.setFrame(Aabb{glm::dvec3(-1.2), glm::dvec3(1.2)});
    fresh.setLayer(Layer::Static, moved, allIds(moved));
    int differ = 0, blocked = 0, segments = 0;
    for (int i = 0; i < 4000; ++i) {
        // Half the segments leave a moved polygon's centre along its normal.
        RayCaster::Segment s{{u(rng), u(rng), u(rng)}, {u(rng), u(rng), u(rng)}};
        if (i % 2) {
            const auto k = static_cast<std::uint32_t>(i % 200);
            s.from = moved.polygons[k].centroid();
            s.to = s.from + 2.0 * moved.polygons[k].normal() + 0.5 * glm::dvec3(u(rng), u(rng), u(rng));
            s.fromPolygon = k;
        }
        const bool byInstances = rc.blocked(Layer::Dynamic, std::span(&s, 1)) != 0;
        differ += byInstances != (fresh.blocked(Layer::Static, std::span(&s, 1)) != 0);
        blocked += byInstances;
        ++segments;
    }
    // Embree finds candidates in float, and a transformed instance rounds
    // otherwise than moved vertices: a segment grazing an edge may go either way.
    EXPECT_LE(differ, 2);
    EXPECT_GT(blocked, segments / 20);
    EXPECT_LT(blocked, segments - segments / 20);
    for (std::uint32_t k : {3u, 150u}) {
        const Polygon& p = moved.polygons[k];
        const auto hit = rc.intersect(p.centroid() + 0.001 * p.normal(), -p.normal(), 1.0);
        ASSERT_TRUE(hit.has_value());
        EXPECT_EQ(hit->polygon, k);
        EXPECT_TRUE(hit->front);
        EXPECT_NEAR(hit->t, 0.001, 1e-6);
    }
    // Cleared: nothing blocks in the dynamic layer.
    rc.clearInstances();
    const RayCaster::Segment through{moved.polygons[3].centroid() + moved.polygons[3].normal(),
                                     moved.polygons[3].centroid() - moved.polygons[3].normal()};
    EXPECT_TRUE(fresh.blocked(Layer::Static, std::span(&through, 1)) != 0);
    EXPECT_FALSE(rc.blocked(Layer::Dynamic, std::span(&through, 1)) != 0);
    EXPECT_THROW(rc.moveInstance(0, glm::dmat4(1.0)), std::out_of_range);
}

// A packet that misses the dynamic layer's box is not traced there: the box
// must follow the instances as they move.
TEST(RayCaster, AMovedInstanceBlocksWhereItWentNotWhereItWas) {
    Scene scene;
    scene.polygons.push_back(squareZ(0.0, 1.0, 0.0, 1.0, 0.0));
    RayCaster rc;
    rc.setFrame(Aabb{glm::dvec3(-1.0), glm::dvec3(7.0)});
    const std::size_t i = rc.addInstance(scene, allIds(scene));
    rc.commitInstances();
    const auto across = [](double x) { return RayCaster::Segment{{x, 0.5, -1.0}, {x, 0.5, 1.0}}; };
    EXPECT_TRUE(occluded(rc, Layer::Dynamic, {0.5, 0.5, -1.0}, {0.5, 0.5, 1.0}));
    rc.moveInstance(i, glm::translate(glm::dmat4(1.0), glm::dvec3(5.0, 0.0, 0.0)));
    rc.commitInstances();
    EXPECT_FALSE(occluded(rc, Layer::Dynamic, {0.5, 0.5, -1.0}, {0.5, 0.5, 1.0}));
    EXPECT_TRUE(occluded(rc, Layer::Dynamic, {5.5, 0.5, -1.0}, {5.5, 0.5, 1.0}));
    // One packet: only the segment through the square's new place is blocked.
    std::vector<RayCaster::Segment> packet;
    for (int k = 0; k < 16; ++k) packet.push_back(across(k == 9 ? 5.5 : 0.05 * k));
    EXPECT_EQ(rc.blocked(Layer::Dynamic, std::span(packet)), std::uint16_t(1u << 9));
    // A packet whose own box spans the square but whose rays pass beside it.
    const std::vector<RayCaster::Segment> beside{{{4.0, 0.5, 0.5}, {4.9, 0.5, 0.5}}, {{6.1, 0.5, -0.5}, {6.5, 0.5, -0.5}}};
    EXPECT_EQ(rc.blocked(Layer::Dynamic, std::span(beside)), 0u);
}

TEST(RayCaster, IntersectReturnsTheNearestPolygonInEitherLayer) {
    Scene scene;
    scene.polygons = {squareZ(-1, 1, -1, 1, 1), squareZ(-1, 1, -1, 1, 2), squareZ(5, 6, 5, 6, 3)};
    RayCaster rc;
    EXPECT_FALSE(rc.intersect({0, 0, 5}, {0, 0, -1}, 100).has_value());  // nothing yet
    const std::uint32_t s[] = {0, 2};
    const std::uint32_t d[] = {1};
    rc.setLayer(Layer::Static, scene, s);
    rc.setLayer(Layer::Dynamic, scene, d);
    auto hit = rc.intersect({0, 0, 5}, {0, 0, -1}, 100);
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->polygon, 1u);  // the dynamic one is nearer from above
    EXPECT_NEAR(hit->t, 3.0, 1e-5);
    hit = rc.intersect({0, 0, -5}, {0, 0, 1}, 100);  // from below the static one is nearer
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->polygon, 0u);
    EXPECT_NEAR(hit->t, 6.0, 1e-5);
    hit = rc.intersect({5.5, 5.5, 10}, {0, 0, -2}, 100);  // t in units of the direction
    ASSERT_TRUE(hit.has_value());
    EXPECT_EQ(hit->polygon, 2u);
    EXPECT_NEAR(hit->t, 3.5, 1e-5);
    EXPECT_FALSE(rc.intersect({0, 0, 5}, {0, 0, -1}, 2.5).has_value());  // beyond tmax
    EXPECT_FALSE(rc.intersect({0, 0, 5}, {0, 0, 1}, 100).has_value());   // away
}

// The same room at scale s, rotated (so that no coordinate is exact in float) and offset from
// the origin as real scenes are: a floor, a wall, a blocker at half height. at() maps room
// coordinates in [0,1]^3 to the world.
struct ScaledRoom {
    double s;
    glm::dvec3 o;
    glm::dmat3 rot;
    Scene scene;
    explicit ScaledRoom(double scale) : s(scale), o(3 * scale, -2 * scale, 5 * scale) {
        const double a = 0.3, b = 0.7;  // rotation about z then about x
        const glm::dmat3 rz(std::cos(a), std::sin(a), 0, -std::sin(a), std::cos(a), 0, 0, 0, 1);
        const glm::dmat3 rx(1, 0, 0, 0, std::cos(b), std::sin(b), 0, -std::sin(b), std::cos(b));
        rot = rx * rz;
        scene.polygons = {squareZ(0, 1, 0, 1, 0), squareX(0, 1, 0, 1, 0),
                          squareZ(0.4, 0.6, 0.4, 0.6, 0.5)};
        for (Polygon& p : scene.polygons)
            for (glm::dvec3& v : p.vertices) v = at(v.x, v.y, v.z);
    }
    glm::dvec3 at(double x, double y, double z) const {
        return o + s * (rot * glm::dvec3(x, y, z));
    }
    glm::dvec3 dir(double x, double y, double z) const { return rot * glm::dvec3(x, y, z); }
};

TEST(RayCaster, MillimetreAndKilometreScalesBehaveTheSame) {
    for (double scale : {1e-3, 1.0, 1e3}) {
        ScaledRoom room(scale);
        RayCaster rc;
        rc.setLayer(Layer::Static, room.scene, allIds(room.scene));
        SCOPED_TRACE(scale);
        // Through the blocker, from the floor.
        EXPECT_TRUE(occluded(rc, Layer::Static, room.at(0.5, 0.5, 0), room.at(0.5, 0.5, 1)));
        // A blocker 2% of the length from an end still blocks.
        EXPECT_TRUE(occluded(rc, Layer::Static, room.at(0.5, 0.5, 0.51), room.at(0.45, 0.55, 0)));
        // Beside the blocker.
        EXPECT_FALSE(occluded(rc, Layer::Static, room.at(0.9, 0.9, 0), room.at(0.9, 0.9, 1)));
        // Floor to wall near the corner: both ends on surfaces of the layer.
        EXPECT_FALSE(occluded(rc, Layer::Static, room.at(0.01, 0.5, 0), room.at(0, 0.5, 0.01)));
        // From the floor to the top of the blocker: the end on the blocker is ignored.
        EXPECT_FALSE(occluded(rc, Layer::Static, room.at(0.2, 0.2, 0), room.at(0.5, 0.5, 0.5)));
        // Grazing: a floor point a millionth of the room from the wall, to the wall.
        EXPECT_FALSE(occluded(rc, Layer::Static, room.at(1e-6, 0.1, 0), room.at(0, 0.9, 0.3)));
        // Random floor-to-wall segments: none is blocked by floor or wall (the blocker may).
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        std::vector<glm::dvec3> from, to;
        for (int i = 0; i < 20000; ++i) {
            from.push_back(room.at(u(rng) * (i % 2 ? 1.0 : 1e-3), u(rng), 0));
            to.push_back(room.at(0, u(rng), u(rng)));
        }
        Scene noBlocker = room.scene;
        noBlocker.polygons.pop_back();
        RayCaster walls;
        walls.setLayer(Layer::Static, noBlocker, allIds(noBlocker));
        EXPECT_EQ(blockedCount(walls, Layer::Static, from, to), 0u);
        // Picking at scale.
        auto hit = rc.intersect(room.at(0.5, 0.5, 2), room.dir(0, 0, -1), 10 * scale);
        ASSERT_TRUE(hit.has_value());
        EXPECT_EQ(hit->polygon, 2u);
        EXPECT_NEAR(hit->t, 1.5 * scale, 1e-5 * scale);
    }
}

TEST(RayCaster, ConcurrentQueriesAgreeWithSerialOnes) {
    Scene scene;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 c(u(rng), u(rng), u(rng));
        scene.polygons.push_back(squareZ(c.x, c.x + 0.1, c.y, c.y + 0.1, c.z));
    }
    RayCaster rc;
    rc.setLayer(Layer::Static, scene, allIds(scene));
    std::vector<glm::dvec3> from, to;
    for (int i = 0; i < 4000; ++i) {
        from.push_back({u(rng), u(rng), -2});
        to.push_back({u(rng), u(rng), 2});
    }
    std::vector<char> serial(from.size()), parallel(from.size());
    for (std::size_t i = 0; i < from.size(); ++i)
        serial[i] = occluded(rc, Layer::Static, from[i], to[i]);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (std::size_t i = t; i < from.size(); i += 4)
                parallel[i] = occluded(rc, Layer::Static, from[i], to[i]);
        });
    for (std::thread& th : threads) th.join();
    EXPECT_EQ(serial, parallel);
    const std::size_t blocked = blockedCount(rc, Layer::Static, from, to);
    EXPECT_GT(blocked, 0u);
    EXPECT_LT(blocked, from.size());
}

}  // namespace
}  // namespace rad
