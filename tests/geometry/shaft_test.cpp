// Shafts between boxes (Haines & Wallace 1994): never miss a box that a joining segment meets,
// and do cull boxes off to the side.

#include "geometry/Shaft.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

namespace rad {
namespace {

Aabb box(glm::dvec3 lo, glm::dvec3 hi) {
    Aabb b;
    b.lo = lo;
    b.hi = hi;
    return b;
}

// Slab test: does the segment p -> q meet the closed box?
bool segmentMeetsBox(const glm::dvec3& p, const glm::dvec3& q, const Aabb& b) {
    double t0 = 0.0, t1 = 1.0;
    const glm::dvec3 d = q - p;
    for (int k = 0; k < 3; ++k) {
        if (d[k] == 0.0) {
            if (p[k] < b.lo[k] || p[k] > b.hi[k]) return false;
            continue;
        }
        double ta = (b.lo[k] - p[k]) / d[k], tb = (b.hi[k] - p[k]) / d[k];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

glm::dvec3 pointIn(std::mt19937& rng, const Aabb& b) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    return b.lo + glm::dvec3(u(rng), u(rng), u(rng)) * (b.hi - b.lo);
}

// Random box; on some axes flat (like a single axis-aligned wall polygon).
Aabb randomBox(std::mt19937& rng, double range, double maxSize) {
    std::uniform_real_distribution<double> u(-range, range), s(0.0, maxSize);
    glm::dvec3 lo(u(rng), u(rng), u(rng)), size(s(rng), s(rng), s(rng));
    for (int k = 0; k < 3; ++k)
        if (rng() % 6 == 0) size[k] = 0.0;
    return box(lo, lo + size);
}

TEST(Shaft, NeverMissesABoxThatAJoiningSegmentMeets) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int hits = 0, culled = 0, culledByPlanes = 0, maxPlanesSeen = 0;
    for (int pair = 0; pair < 3000; ++pair) {
        Aabb a = randomBox(rng, 10, 4);
        Aabb b = randomBox(rng, 10, 4);
        if (pair % 10 == 0) b = a;                                      // identical
        if (pair % 10 == 1) b = box(pointIn(rng, a), pointIn(rng, a));  // (nearly) contained
        if (pair % 10 == 1) b = box(glm::min(b.lo, b.hi), glm::max(b.lo, b.hi));
        const Shaft shaft(a, b);
        EXPECT_LE(shaft.planeCount(), Shaft::maxPlanes);
        maxPlanesSeen = std::max<int>(maxPlanesSeen, int(shaft.planeCount()));
        for (int t = 0; t < 20; ++t) {
            // Test boxes: small ones near a random joining segment, and arbitrary ones.
            Aabb test;
            bool onSegment = false;
            if (t % 4 == 1) {
                // A point box on a segment joining two corners of the boxes: such segments run
                // along the hull's boundary, where the planes (and their rounding) matter.
                const glm::dvec3 ca(rng() % 2 ? a.hi.x : a.lo.x, rng() % 2 ? a.hi.y : a.lo.y,
                                    rng() % 2 ? a.hi.z : a.lo.z);
                const glm::dvec3 cb(rng() % 2 ? b.hi.x : b.lo.x, rng() % 2 ? b.hi.y : b.lo.y,
                                    rng() % 2 ? b.hi.z : b.lo.z);
                const glm::dvec3 p = glm::mix(ca, cb, u(rng));
                test = box(p, p);
                onSegment = true;
            } else if (t % 2 == 0) {
                const glm::dvec3 c = glm::mix(pointIn(rng, a), pointIn(rng, b), u(rng)) +
                                     glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * 3.0;
                const glm::dvec3 h = glm::dvec3(u(rng), u(rng), u(rng)) * 0.3;
                test = box(c - h, c + h);
            } else {
                test = randomBox(rng, 12, 3);
            }
            bool met = onSegment;
            for (int s = 0; s < 64 && !met; ++s)
                met = segmentMeetsBox(pointIn(rng, a), pointIn(rng, b), test);
            const bool says = shaft.intersects(test);
            if (met) {
                ++hits;
                EXPECT_TRUE(says) << "pair " << pair << " test " << t;
            }
            if (!says) ++culled;
            bool inHullBox = true;
            for (int k = 0; k < 3; ++k)
                inHullBox = inHullBox && test.lo[k] <= shaft.hull().hi[k] &&
                            test.hi[k] >= shaft.hull().lo[k];
            if (inHullBox && !says) ++culledByPlanes;
        }
    }
    // Seen: 20,997 met test boxes (about 15,000 of them points on corner-to-corner segments,
    // on the hull's boundary), none missed; 33,133 culled, 8,744 of them overlapping the hull
    // box and culled by the planes alone.
    EXPECT_GT(hits, 15000);           // the check is exercised
    EXPECT_GT(culled, 20000);         // the shaft does reject
    EXPECT_GT(culledByPlanes, 2000);  // and the planes earn their keep
    std::printf("[ shaft    ] %d met, %d culled, %d by planes\n", hits, culled, culledByPlanes);
    EXPECT_EQ(maxPlanesSeen, 8);
}

TEST(Shaft, CullsABoxOffToTheSideOfALongThinShaft) {
    // Diagonal shaft from a small box at the origin to one at (100, 50, 0): its hull box is large,
    // the shaft itself thin.
    const Aabb a = box({0, 0, 0}, {0.1, 0.1, 0.1});
    const Aabb b = box({100, 50, 0}, {100.1, 50.1, 0.1});
    const Shaft shaft(a, b);
    EXPECT_GT(shaft.planeCount(), 0u);
    const Aabb offToTheSide = box({50, 0, 0}, {51, 1, 0.1});  // inside the hull box
    EXPECT_TRUE(shaft.hull().lo.x <= 50 && shaft.hull().hi.y >= 1);
    EXPECT_FALSE(shaft.intersects(offToTheSide));
    const Aabb onTheWay = box({49.9, 24.9, 0.04}, {50.1, 25.1, 0.06});
    EXPECT_TRUE(shaft.intersects(onTheWay));
    EXPECT_FALSE(shaft.intersects(box({200, 0, 0}, {201, 1, 1})));    // outside the hull box
    EXPECT_FALSE(shaft.intersects(box({50, 25, 0.2}, {51, 26, 1})));  // above the flat shaft
}

TEST(Shaft, TouchingContainedIdenticalAndFlatBoxes) {
    const Aabb unit = box({0, 0, 0}, {1, 1, 1});
    // Touching boxes (sharing a face): the hull is their union box, no planes needed.
    const Shaft touching(unit, box({1, 0, 0}, {2, 1, 1}));
    EXPECT_EQ(touching.planeCount(), 0u);
    EXPECT_TRUE(touching.intersects(box({1.5, 0.5, 0.5}, {1.6, 0.6, 0.6})));
    EXPECT_TRUE(touching.intersects(box({2, 1, 1}, {3, 3, 3})));  // touches a hull corner
    EXPECT_FALSE(touching.intersects(box({2.01, 0, 0}, {3, 1, 1})));

    // One containing the other: the shaft is the big box.
    const Shaft contained(box({-1, -1, -1}, {2, 2, 2}), unit);
    EXPECT_EQ(contained.planeCount(), 0u);
    EXPECT_TRUE(contained.intersects(box({1.9, 1.9, 1.9}, {3, 3, 3})));
    EXPECT_FALSE(contained.intersects(box({2.1, 0, 0}, {3, 1, 1})));

    // Identical boxes.
    const Shaft same(unit, unit);
    EXPECT_EQ(same.planeCount(), 0u);
    EXPECT_TRUE(same.intersects(box({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5})));  // a point inside
    EXPECT_FALSE(same.intersects(box({1.5, 0, 0}, {2, 1, 1})));

    // Two flat boxes like a floor polygon and a wall polygon facing each other across a room.
    const Aabb floorPatch = box({0, 0, 0}, {1, 0, 1});  // y = 0
    const Aabb wallPatch = box({4, 2, 3}, {4, 3, 4});   // x = 4
    const Shaft flat(floorPatch, wallPatch);
    EXPECT_LE(flat.planeCount(), Shaft::maxPlanes);
    EXPECT_TRUE(flat.intersects(box({2, 1, 2}, {2.1, 1.1, 2.1})));   // the midpoint region
    EXPECT_FALSE(flat.intersects(box({3.5, 0, 0}, {4, 0.5, 0.5})));  // a corner of the hull box
    // Both flat in the same plane (two coplanar patches): a flat shaft.
    const Shaft coplanar(box({0, 0, 0}, {1, 0, 1}), box({5, 0, 5}, {6, 0, 6}));
    EXPECT_TRUE(coplanar.intersects(box({3, -1, 3}, {3.1, 1, 3.1})));
    EXPECT_FALSE(coplanar.intersects(box({3, 0.01, 3}, {3.1, 1, 3.1})));
    EXPECT_FALSE(coplanar.intersects(box({0, -1, 5}, {1, 1, 6})));  // off the diagonal
    // Degenerate to points: the shaft is the segment's box cut by planes.
    const Shaft points(box({0, 0, 0}, {0, 0, 0}), box({1, 1, 1}, {1, 1, 1}));
    EXPECT_TRUE(points.intersects(box({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5})));
    EXPECT_FALSE(points.intersects(box({0.9, 0.1, 0.5}, {1, 0.2, 0.5})));
    // An empty box: the shaft is the other box; nothing meets an empty test box.
    const Shaft withEmpty(Aabb{}, unit);
    EXPECT_TRUE(withEmpty.intersects(box({0.5, 0.5, 0.5}, {2, 2, 2})));
    EXPECT_FALSE(withEmpty.intersects(box({1.5, 0, 0}, {2, 1, 1})));
    EXPECT_FALSE(same.intersects(Aabb{}));
}

TEST(Shaft, IsCompact) {
    // 48-byte hull box + 8 planes as three arrays of doubles + 8 axis bytes + a count.
    EXPECT_LE(sizeof(Shaft), 256u) << sizeof(Shaft);
}

}  // namespace
}  // namespace rad
