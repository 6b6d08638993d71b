#include <gtest/gtest.h>

#include "hierarchy/Hierarchy.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

TEST(IndexRange, DepthAndCountFollowTheAreaThreshold) {
    EXPECT_EQ(maxQuadtreeDepth(1.0, 2.0), 0);
    EXPECT_EQ(maxQuadtreeDepth(1.0, 0.25), 1);
    EXPECT_EQ(maxQuadtreeDepth(1.0, 0.2), 1);
    EXPECT_EQ(maxQuadtreeDepth(1.0, 1.0 / 16.0), 2);
    EXPECT_EQ(quadtreeIndexCount(1.0, 2.0, "p"), 1u);
    EXPECT_EQ(quadtreeIndexCount(1.0, 0.25, "p"), 5u);
    EXPECT_EQ(quadtreeIndexCount(1.0, 1.0 / 16.0, "p"), 21u);
}

TEST(IndexRange, ChildRangesAreNestedAndDisjoint) {
    const IndexRange parent{10, 10 + 21 - 1};
    IndexRange previous{0, 10};
    for (int k = 0; k < 4; ++k) {
        const IndexRange c = quadtreeChildRange(parent, k);
        EXPECT_EQ(c.size(), 5u);
        EXPECT_TRUE(parent.contains(c));
        EXPECT_FALSE(c.contains(parent.first));
        EXPECT_EQ(c.first, previous.last + 1);
        previous = c;
    }
    EXPECT_EQ(previous.last, parent.last);
}

TEST(IndexRange, OverflowIsAnErrorNotAWrap) {
    // 31 levels fit in 64 bits; 32 do not.
    EXPECT_NO_THROW(quadtreeIndexCount(1.0, std::ldexp(1.0, -62), "p"));
    EXPECT_THROW(quadtreeIndexCount(1.0, std::ldexp(1.0, -64), "p"), IndexRangeOverflow);
    try {
        quadtreeIndexCount(1.0, 1e-30, "polygon 7");
        FAIL() << "no overflow reported";
    } catch (const IndexRangeOverflow& e) {
        EXPECT_NE(std::string(e.what()).find("polygon 7"), std::string::npos);
        // The threshold as given, not rounded to 0.000000.
        EXPECT_NE(std::string(e.what()).find("1e-30 m^2"), std::string::npos) << e.what();
    }
    EXPECT_THROW(checkedAdd(~std::uint64_t(0), 1, "cluster"), IndexRangeOverflow);
    // The hierarchy of a real scene with a threshold that small refuses to build.
    const Scene s = test::closedBox(0.5);
    EXPECT_THROW(Hierarchy(s, 1e-30), IndexRangeOverflow);
}

// Every element's range holds exactly its descendants: the test the
// line-space traversal relies on ("is q below s").
TEST(Hierarchy, RangesMatchTheTreeAfterSubdivision) {
    const Scene s = test::closedBox(0.5);
    Hierarchy h(s, 1.0 / 50.0);
    const ElementId face = h.polygonElement(2);
    h.subdivide(face);
    h.subdivide(h[face].children[1]);
    std::vector<ElementId> all;
    for (ElementId e = 0; e < h.size(); ++e)
        if (h[e].kind == ElementKind::Surface || !h[e].children.empty()) all.push_back(e);
    auto isBelow = [&](ElementId q, ElementId a) {
        for (ElementId p = h[q].parent; p != kNone; p = h[p].parent)
            if (p == a) return true;
        return false;
    };
    for (ElementId a : all)
        for (ElementId q : all)
            if (a != q) {
                EXPECT_EQ(h.range(a).contains(h.range(q).first), isBelow(q, a)) << a << " " << q;
            }
    // Subdivided children tile their parent.
    double area = 0.0;
    for (ElementId c : h[face].children) area += h[c].area;
    EXPECT_NEAR(area, 1.0, 1e-12);
    EXPECT_FALSE(h.canSubdivide(h[h[face].children[1]].children[0]));  // 1/16 / 4 < 1/50
}

}  // namespace
}  // namespace rad
