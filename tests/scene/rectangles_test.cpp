// A planar region whose outline runs along two directions, cut into
// rectangles (scene/Rectangles.h): their union is the region, and regions
// it cannot cut are refused.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "scene/Rectangles.h"

namespace rad {
namespace {

using V = glm::dvec3;
using Edges = std::vector<std::pair<V, V>>;

// The edges of a closed loop of points in the plane z = 0.
void addLoop(Edges& edges, const std::vector<V>& loop) {
    for (std::size_t i = 0; i < loop.size(); ++i) edges.emplace_back(loop[i], loop[(i + 1) % loop.size()]);
}

double areaAbout(const std::array<V, 4>& q, const V& n) {
    V sum(0.0);
    for (int i = 0; i < 4; ++i) sum += glm::cross(q[i], q[(i + 1) % 4]);
    return 0.5 * glm::dot(sum, n);
}

bool inside(const std::array<V, 4>& q, double x, double y) {
    const V lo = glm::min(glm::min(q[0], q[1]), glm::min(q[2], q[3]));
    const V hi = glm::max(glm::max(q[0], q[1]), glm::max(q[2], q[3]));
    return x > lo.x && x < hi.x && y > lo.y && y < hi.y;
}

// Checks that the rectangles are rectangles turning about +z, with the
// given total area, that each point of a grid over [0, w] x [0, h] lies in
// exactly one of them unless `hole` says it lies in none.
template <class Hole>
void expectTiling(const std::vector<std::array<V, 4>>& rects, double w, double h, double area, const Hole& hole) {
    double sum = 0.0;
    for (const auto& q : rects) {
        for (int i = 0; i < 4; ++i)
            EXPECT_NEAR(glm::dot(q[(i + 1) % 4] - q[i], q[(i + 2) % 4] - q[(i + 1) % 4]), 0.0, 1e-9) << "a right angle";
        EXPECT_GT(areaAbout(q, V(0, 0, 1)), 0.0) << "turns counter-clockwise about +z";
        sum += areaAbout(q, V(0, 0, 1));
    }
    EXPECT_NEAR(sum, area, 1e-9 * area);
    for (double x = 0.05; x < w; x += 0.1)
        for (double y = 0.05; y < h; y += 0.1) {
            int count = 0;
            for (const auto& q : rects) count += inside(q, x, y);
            EXPECT_EQ(count, hole(x, y) ? 0 : 1) << "at (" << x << ", " << y << ")";
        }
}

TEST(Rectangles, AWallWithAWindowIsFourRectangles) {
    Edges edges;
    addLoop(edges, {V(0, 0, 0), V(12, 0, 0), V(12, 2.5, 0), V(0, 2.5, 0)});
    addLoop(edges, {V(5, 1, 0), V(5, 2, 0), V(6, 2, 0), V(6, 1, 0)});  // the hole turns the other way
    const auto rects = rectanglesOf(edges, V(0, 0, 1), 29.0);
    ASSERT_TRUE(rects.has_value());
    EXPECT_EQ(rects->size(), 4u);
    expectTiling(*rects, 12, 2.5, 29.0, [](double x, double y) { return x > 5 && x < 6 && y > 1 && y < 2; });
    // Corners at a vertex of the outline are that vertex exactly.
    int atVertices = 0;
    for (const auto& q : *rects)
        for (const V& c : q)
            for (const auto& [from, to] : edges)
                if (glm::length(c - from) < 1e-9) {
                    EXPECT_EQ(c, from);
                    ++atVertices;
                }
    EXPECT_GE(atVertices, 8);
}

TEST(Rectangles, AWallWithADoorAndAnLShapeAndATiltedPlane) {
    // A door at the bottom edge: one loop, not convex.
    Edges door;
    addLoop(door, {V(0, 0, 0), V(2, 0, 0), V(2, 2, 0), V(3, 2, 0), V(3, 0, 0), V(6, 0, 0), V(6, 2.5, 0), V(0, 2.5, 0)});
    const auto a = rectanglesOf(door, V(0, 0, 1), 15.0 - 2.0);
    ASSERT_TRUE(a.has_value());
    EXPECT_EQ(a->size(), 3u);
    expectTiling(*a, 6, 2.5, 13.0, [](double x, double y) { return x > 2 && x < 3 && y < 2; });
    Edges l;
    addLoop(l, {V(0, 0, 0), V(4, 0, 0), V(4, 1, 0), V(1, 1, 0), V(1, 3, 0), V(0, 3, 0)});
    const auto b = rectanglesOf(l, V(0, 0, 1), 6.0);
    ASSERT_TRUE(b.has_value());
    EXPECT_EQ(b->size(), 2u);
    expectTiling(*b, 4, 3, 6.0, [](double x, double y) { return x > 1 && y > 1; });
    // The same window wall turned 30 degrees about x: the frame follows the plane.
    const double c = std::cos(0.5235987755982988), s = std::sin(0.5235987755982988);
    const auto turn = [&](double x, double y) { return V(x, c * y, s * y); };
    Edges tilted;
    addLoop(tilted, {turn(0, 0), turn(12, 0), turn(12, 2.5), turn(0, 2.5)});
    addLoop(tilted, {turn(5, 1), turn(5, 2), turn(6, 2), turn(6, 1)});
    const auto t = rectanglesOf(tilted, V(0, -s, c), 29.0);
    ASSERT_TRUE(t.has_value());
    EXPECT_EQ(t->size(), 4u);
    double sum = 0.0;
    for (const auto& q : *t) sum += areaAbout(q, V(0, -s, c));
    EXPECT_NEAR(sum, 29.0, 1e-9);
}

TEST(Rectangles, RegionsItCannotCutAreRefused) {
    // A diagonal edge.
    Edges slanted;
    addLoop(slanted, {V(0, 0, 0), V(4, 0, 0), V(4, 1, 0), V(1, 3, 0), V(0, 3, 0)});
    EXPECT_FALSE(rectanglesOf(slanted, V(0, 0, 1), 9.0).has_value());
    // An area that is not the outline's (overlapping triangles under it).
    Edges box;
    addLoop(box, {V(0, 0, 0), V(4, 0, 0), V(4, 1, 0), V(2, 1, 0), V(2, 2, 0), V(0, 2, 0)});
    EXPECT_TRUE(rectanglesOf(box, V(0, 0, 1), 6.0).has_value());
    EXPECT_FALSE(rectanglesOf(box, V(0, 0, 1), 7.0).has_value());
    // A grid of more cells than kMaxCells: a comb of 100 teeth along both ways.
    std::vector<V> comb{V(0, 0, 0)};
    for (int i = 0; i < 100; ++i) {
        comb.push_back(V(2 * i + 1, 0, 0));
        comb.push_back(V(2 * i + 1, 1 + 0.01 * i, 0));
        comb.push_back(V(2 * i + 2, 1 + 0.01 * i, 0));
        comb.push_back(V(2 * i + 2, 0, 0));
    }
    comb.push_back(V(201, 0, 0));
    comb.push_back(V(201, -1, 0));
    comb.push_back(V(0, -1, 0));
    Edges teeth;
    addLoop(teeth, comb);
    EXPECT_FALSE(rectanglesOf(teeth, V(0, 0, 1), 1.0).has_value());
    // Too few edges, or no area.
    EXPECT_FALSE(rectanglesOf({}, V(0, 0, 1), 1.0).has_value());
    Edges square;
    addLoop(square, {V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)});
    EXPECT_FALSE(rectanglesOf(square, V(0, 0, 1), 0.0).has_value());
}

}  // namespace
}  // namespace rad
