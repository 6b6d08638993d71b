// IdList: an H-element's children and link lists in 16 bytes. What it
// promises: the operations the hierarchy and the refiner use behave as a
// std::vector's do (checked against one through random edits), copies are
// deep, and its capacity is what it says (memory is counted from it).

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "hierarchy/IdList.h"

namespace rad {
namespace {

std::vector<std::uint32_t> asVector(const IdList& l) { return {l.begin(), l.end()}; }

TEST(IdList, TakesSixteenBytes) { EXPECT_EQ(sizeof(IdList), 16u); }

TEST(IdList, RandomEditsMatchAVector) {
    std::mt19937 rng(7);
    IdList list;
    std::vector<std::uint32_t> expected;
    for (int step = 0; step < 20000; ++step) {
        const auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
        switch (pick(8)) {
        case 0:
        case 1:
        case 2: {
            const auto id = static_cast<std::uint32_t>(pick(50));
            list.push_back(id);
            expected.push_back(id);
            break;
        }
        case 3:
            if (!expected.empty()) {
                const std::size_t at = pick(expected.size());
                list.erase(list.begin() + at);
                expected.erase(expected.begin() + static_cast<std::ptrdiff_t>(at));
            }
            break;
        case 4: {
            const auto id = static_cast<std::uint32_t>(pick(50));
            EXPECT_EQ(list.eraseValue(id), static_cast<std::size_t>(std::erase(expected, id)));
            break;
        }
        case 5:
            if (!expected.empty()) {  // as Refiner's unordered erase does
                list[0] = list.back();
                list.pop_back();
                expected[0] = expected.back();
                expected.pop_back();
            }
            break;
        case 6:
            list.shrink_to_fit();
            EXPECT_EQ(list.capacity(), expected.size());
            break;
        default: {
            const std::vector<std::uint32_t> more(pick(6), static_cast<std::uint32_t>(step));
            list.append(more.begin(), more.end());
            expected.insert(expected.end(), more.begin(), more.end());
            break;
        }
        }
        ASSERT_EQ(asVector(list), expected) << "step " << step;
        ASSERT_GE(list.capacity(), list.size());
        ASSERT_EQ(list.empty(), expected.empty());
    }
}

TEST(IdList, CopiesAreDeepAndMovesEmptyTheSource) {
    IdList a{1, 2, 3};
    IdList b = a;
    b[0] = 9;
    EXPECT_EQ(asVector(a), (std::vector<std::uint32_t>{1, 2, 3}));
    EXPECT_EQ(asVector(b), (std::vector<std::uint32_t>{9, 2, 3}));
    a = b;
    EXPECT_EQ(asVector(a), asVector(b));
    EXPECT_NE(a.data(), b.data());
    const std::uint32_t* storage = b.data();
    IdList c = std::move(b);
    EXPECT_EQ(c.data(), storage);  // nothing copied
    EXPECT_TRUE(b.empty());        // NOLINT(bugprone-use-after-move): a moved-from list is empty
    EXPECT_EQ(b.capacity(), 0u);
    const IdList& same = a;
    a = same;  // self-assignment keeps it
    EXPECT_EQ(asVector(a), (std::vector<std::uint32_t>{9, 2, 3}));
}

TEST(IdList, ResizeAssignAndReserve) {
    IdList l;
    l.resize(3);
    EXPECT_EQ(asVector(l), (std::vector<std::uint32_t>{0, 0, 0}));
    l.resize(1);
    EXPECT_EQ(asVector(l), (std::vector<std::uint32_t>{0}));
    const std::vector<std::uint32_t> ids{4, 5, 6, 7, 8};
    l.assign(ids.begin(), ids.end());
    EXPECT_EQ(asVector(l), ids);
    l.reserve(100);
    EXPECT_EQ(l.capacity(), 100u);
    EXPECT_EQ(asVector(l), ids);
    l.clear();
    EXPECT_TRUE(l.empty());
    EXPECT_EQ(l.capacity(), 100u);
    l.shrink_to_fit();
    EXPECT_EQ(l.capacity(), 0u);
}

}  // namespace
}  // namespace rad
