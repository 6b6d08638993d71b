// The partial push-pull (paper Fig. 7) on a deadline (solve/Solver.h): a
// dirty element whose push would end after the deadline waits, unpushed,
// with its subtree's radiosity as it was, and so does a large part of a
// subtree pushed whole once the clock has passed the deadline; the next
// partial push-pull pushes them, and the result is the one a push without a
// deadline gives, to the bit.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "solve/Solver.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;

struct Room {
    Scene scene;
    Hierarchy h;
    LinkStore links;
    Solver solver;
    ElementId wall;  // a subdivided wall, two levels deep
    explicit Room(const Scene& s) : scene(s), h(scene, 1e-6), solver(h, links) {
        wall = h.polygonElement(0);
        h.subdivide(wall);
        h.subdivide(h[wall].children[1]);
        solver.pushPull();  // every B from emission and irradiance (none yet)
    }
    // Light arrives on the wall: its subtree must be pushed again.
    void lightTheWall() {
        h[wall].irradiance = V(2.0, 1.0, 0.5);
        h[wall].dirty = true;
    }
    std::vector<V> radiosity() const {
        std::vector<V> b;
        for (ElementId e = 0; e < h.size(); ++e) b.push_back(h[e].radiosity);
        return b;
    }
};

Scene room() {
    Scene s;
    s.sourcePath = "push-deadline";
    const auto white = test::addMaterial(s, V(0.5), V(0.0), "white");
    test::addQuadObject(s, "room", white, test::boxFaces(V(0.0), V(4.0, 3.0, 5.0), true));
    return s;
}

TEST(PartialPushPull, APushThatWouldPassTheDeadlineWaitsAndIsMadeLater) {
    const Scene s = room();
    Room onTime(s), late(s);
    onTime.lightTheWall();
    const std::vector<ElementId> visited = onTime.solver.partialPushPull({onTime.wall});
    EXPECT_TRUE(onTime.solver.unpushed().empty());
    const std::vector<V> expected = onTime.radiosity();
    ASSERT_NE(expected, late.radiosity()) << "the light changed something";

    late.lightTheWall();
    const std::vector<V> before = late.radiosity();
    // A deadline already passed: the wall's subtree is not pushed.
    const Solver::PushDeadline passed{std::chrono::steady_clock::now() - std::chrono::seconds(1),
                                      1e-9};
    const std::vector<ElementId> none = late.solver.partialPushPull({late.wall}, passed);
    for (ElementId e : none) EXPECT_NE(e, late.wall);
    ASSERT_EQ(late.solver.unpushed(), std::vector<ElementId>{late.wall});
    EXPECT_EQ(late.radiosity(), before);
    // A deadline far away: what waited is pushed now, with nothing new dirty.
    const Solver::PushDeadline later{std::chrono::steady_clock::now() + std::chrono::hours(1),
                                     1e-9};
    const std::vector<ElementId> pushed = late.solver.partialPushPull({}, later);
    EXPECT_EQ(pushed.size(), visited.size());
    EXPECT_TRUE(late.solver.unpushed().empty());
    EXPECT_EQ(late.radiosity(), expected);
}

// The clock passes the stop while a dirty wall's subtree, whose push was
// expected to fit, is pushed whole: its children, each expected to take
// longer than the push looks at the clock for, wait unpushed, and the next
// push makes them. The result is again the one a push without a deadline
// gives, to the bit.
TEST(PartialPushPull, APushWholeStopsWhenTheClockPassesAndTheRestIsMadeLater) {
    const Scene s = room();
    Room onTime(s), late(s);
    onTime.lightTheWall();
    onTime.solver.partialPushPull({onTime.wall});
    const std::vector<V> expected = onTime.radiosity();

    late.lightTheWall();
    const std::vector<ElementId> children(late.h[late.wall].children.begin(),
                                          late.h[late.wall].children.end());
    ASSERT_EQ(children.size(), 4u);
    const auto start = std::chrono::steady_clock::now();
    std::atomic<int> reads{0};
    // Each child's subtree is expected to take twice as long as the push
    // goes without looking at the clock; the wall's, four times that, fits
    // in the second before the stop. The clock's first reading (the wall's)
    // is before the stop, every later one after it (atomic: the push may
    // walk the room's polygons on several threads).
    Solver::PushDeadline deadline{start + std::chrono::seconds(1),
                                  2.0 * Solver::kPushClockSeconds / late.h[children[0]].area};
    deadline.now = [&] { return reads++ == 0 ? start : start + std::chrono::seconds(2); };
    const std::vector<ElementId> visited = late.solver.partialPushPull({late.wall}, deadline);
    EXPECT_NE(std::find(visited.begin(), visited.end(), late.wall), visited.end()) << "the wall itself was pushed";
    EXPECT_EQ(late.solver.unpushed(), children);
    for (ElementId c : children) EXPECT_EQ(std::find(visited.begin(), visited.end(), c), visited.end());
    EXPECT_NE(late.radiosity(), expected) << "its children wait";

    const Solver::PushDeadline later{std::chrono::steady_clock::now() + std::chrono::hours(1), 1e-9};
    late.solver.partialPushPull({}, later);
    EXPECT_TRUE(late.solver.unpushed().empty());
    EXPECT_EQ(late.radiosity(), expected);
}

// A subtree pushed whole of many small elements, none expected to take as
// long as the push goes without looking at the clock: the clock is read
// every kPushClockEvery elements all the same, and once it has passed the
// stop the rest waits, unpushed (an estimate by area misjudges the dense
// hierarchy around a moving object). The next push makes them, and the
// result is the one a push without a deadline gives, to the bit.
TEST(PartialPushPull, ManySmallElementsPushedWholeStopWhenTheClockPasses) {
    const Scene s = room();
    Room onTime(s), late(s);
    // The wall three levels deep: 85 elements.
    for (Room* r : {&onTime, &late}) {
        std::vector<ElementId> level{r->wall};
        for (int depth = 0; depth < 3; ++depth) {
            std::vector<ElementId> next;
            for (ElementId e : level) {
                if (r->h[e].isLeaf()) r->h.subdivide(e);
                next.insert(next.end(), r->h[e].children.begin(), r->h[e].children.end());
            }
            level = next;
        }
        ASSERT_EQ(level.size(), 64u);
        r->solver.pushPull();
    }
    onTime.lightTheWall();
    onTime.solver.partialPushPull({onTime.wall});
    const std::vector<V> expected = onTime.radiosity();

    late.lightTheWall();
    const auto start = std::chrono::steady_clock::now();
    std::atomic<int> reads{0};
    // The wall's push is expected to take a nanosecond; the clock's first
    // reading (the wall's) is before the stop, every later one after it.
    Solver::PushDeadline deadline{start + std::chrono::seconds(1), 1e-9 / late.h[late.wall].area};
    deadline.now = [&] { return reads++ == 0 ? start : start + std::chrono::seconds(2); };
    const std::vector<ElementId> visited = late.solver.partialPushPull({late.wall}, deadline);
    EXPECT_EQ(reads.load(), 2) << "the wall's reading, and one after kPushClockEvery elements";
    std::vector<ElementId> below;  // the wall's subtree, the wall left out
    for (std::vector<ElementId> stack(late.h[late.wall].children.begin(),
                                      late.h[late.wall].children.end());
         !stack.empty();) {
        below.push_back(stack.back());
        stack.pop_back();
        stack.insert(stack.end(), late.h[below.back()].children.begin(), late.h[below.back()].children.end());
    }
    ASSERT_EQ(below.size(), 84u);
    const auto pushedBelow = std::count_if(visited.begin(), visited.end(), [&](ElementId e) {
        return std::find(below.begin(), below.end(), e) != below.end();
    });
    EXPECT_GT(pushedBelow, 0);
    EXPECT_LT(pushedBelow, std::ptrdiff_t(Solver::kPushClockEvery));
    EXPECT_FALSE(late.solver.unpushed().empty());
    EXPECT_NE(late.radiosity(), expected) << "part of the wall waits";

    const Solver::PushDeadline later{std::chrono::steady_clock::now() + std::chrono::hours(1), 1e-9};
    late.solver.partialPushPull({}, later);
    EXPECT_TRUE(late.solver.unpushed().empty());
    EXPECT_EQ(late.radiosity(), expected);
}

}  // namespace
}  // namespace rad
