// ChunkedArray: the element store that grows without copying itself. What it
// promises: an item stays where it is while the array grows (nothing is
// copied, so no growth costs more than one chunk), items keep their values,
// a resize adds default items, and the slack is at most one chunk.

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "hierarchy/ChunkedArray.h"

namespace rad {
namespace {

struct Item {
    double value = -1.0;
    std::vector<int> list;  // an item that owns memory, as an H-element does
};

TEST(ChunkedArray, GrowingMovesNoItem) {
    ChunkedArray<Item, 4> a;  // 16 items a chunk
    a.push_back({0.0, {0}});
    const Item* first = &a[0];
    const int* firstList = a[0].list.data();
    for (int i = 1; i < 1000; ++i) a.push_back({double(i), {i, i}});
    EXPECT_EQ(&a[0], first);
    EXPECT_EQ(a[0].list.data(), firstList);
    ASSERT_EQ(a.size(), 1000u);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].value, double(i));
        EXPECT_EQ(a[i].list.front(), int(i));
    }
    // 1,000 items in chunks of 16: 63 chunks, 8 slots of slack.
    EXPECT_EQ(a.capacity(), 1008u);
}

TEST(ChunkedArray, ResizeAddsDefaultItemsAndShrinkFreesWholeChunks) {
    ChunkedArray<Item, 4> a;
    a.resize(40);
    EXPECT_EQ(a.size(), 40u);
    EXPECT_EQ(a.capacity(), 48u);
    a[39].value = 5.0;
    a[39].list = {1, 2, 3};
    a.resize(20);  // the items past 20 are dropped...
    a.shrink_to_fit();
    EXPECT_EQ(a.capacity(), 32u);
    a.resize(40);  // ...and come back as default items
    EXPECT_EQ(a[39].value, -1.0);
    EXPECT_TRUE(a[39].list.empty());
    const std::size_t bytes = a.memoryBytes();
    EXPECT_GE(bytes, 48 * sizeof(Item));
    EXPECT_LT(bytes, 48 * sizeof(Item) + 1024);
}

TEST(ChunkedArray, ResizeAndAssignWithAValue) {
    ChunkedArray<double, 4> a;
    a.resize(10, -1.0);
    a[3] = 2.0;
    a.resize(40, 7.0);  // the first ten kept, the rest 7
    EXPECT_EQ(a[0], -1.0);
    EXPECT_EQ(a[3], 2.0);
    EXPECT_EQ(a[10], 7.0);
    EXPECT_EQ(a[39], 7.0);
    a.assign(20, 0.5);  // every one
    ASSERT_EQ(a.size(), 20u);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], 0.5);
}

}  // namespace
}  // namespace rad
