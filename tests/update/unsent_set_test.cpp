// The unsent elements' sum of what they have to send (update/UnsentSet.h),
// kept term by term: after joins, changes, repeated names and forgetting, it
// equals the sum made from scratch, and it makes only the terms it was told
// may have changed, each once.

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "update/UnsentSet.h"

namespace rad {
namespace {

struct Terms {
    std::vector<double> value = std::vector<double>(100, 0.0);
    std::atomic<int> made{0};
    UnsentSet::Term term() {
        return [this](ElementId e) {
            ++made;
            return value[e];
        };
    }
    double fromScratch(const UnsentSet& set) const {
        double sum = 0.0;
        for (ElementId e : set.members()) sum += value[e];
        return sum;
    }
};

TEST(UnsentSet, KeptSumEqualsTheSumFromScratch) {
    Terms t;
    for (ElementId e = 0; e < 100; ++e) t.value[e] = 0.25 * e - 7.0;  // terms of both signs
    UnsentSet set;
    for (ElementId e : {3u, 17u, 42u, 99u}) EXPECT_TRUE(set.join(e));
    EXPECT_FALSE(set.join(17u)) << "a member joins once";
    EXPECT_EQ(set.size(), 4u);
    EXPECT_EQ(set.sum(t.term()), t.fromScratch(set));
    EXPECT_EQ(t.made, 4);

    // Two members change, one of them named twice, and an element that is
    // not a member: only the two are made again.
    t.value[17] = 11.0;
    t.value[42] = -2.5;
    t.value[50] = 1e6;
    const std::vector<ElementId> pushed{17, 50, 42, 17};
    set.mayHaveChanged(pushed);
    t.made = 0;
    EXPECT_EQ(set.sum(t.term()), t.fromScratch(set));
    EXPECT_EQ(t.made, 2) << "17 (named twice, made once) and 42; 50 is not unsent";

    // A new member is counted once made; nothing else is made again.
    EXPECT_TRUE(set.join(50u));
    t.made = 0;
    EXPECT_EQ(set.sum(t.term()), t.fromScratch(set));
    EXPECT_EQ(t.made, 1);

    // Unsignalled changes stay out until forget() makes every term again.
    t.value[3] = 100.0;
    t.made = 0;
    EXPECT_NE(set.sum(t.term()), t.fromScratch(set));
    EXPECT_EQ(t.made, 0);
    set.forget();
    EXPECT_EQ(set.sum(t.term()), t.fromScratch(set));
    EXPECT_EQ(t.made, 5);
}

TEST(UnsentSet, ClearedItHoldsNothingAndSumsToZero) {
    Terms t;
    t.value[5] = 2.0;
    t.value[6] = 3.0;
    UnsentSet set;
    set.join(5);
    set.join(6);
    EXPECT_EQ(set.sum(t.term()), 5.0);
    set.clear();
    EXPECT_TRUE(set.empty());
    EXPECT_FALSE(set.contains(5));
    EXPECT_EQ(set.sum(t.term()), 0.0);
    const std::vector<ElementId> changed{5, 6};
    set.mayHaveChanged(changed);  // not members any more
    EXPECT_EQ(set.sum(t.term()), 0.0);
    EXPECT_TRUE(set.join(6)) << "a member again after leaving";
    EXPECT_EQ(set.sum(t.term()), 3.0);
}

}  // namespace
}  // namespace rad
