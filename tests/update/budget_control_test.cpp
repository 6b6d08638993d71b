// The target frame time to budget model (update/BudgetControl): frames are
// t = overhead + cost * updates. Timings here are given, not measured.

#include <gtest/gtest.h>

#include <limits>

#include "update/BudgetControl.h"

namespace rad {
namespace {

TEST(BudgetControl, FirstFrameMeasuresTheFixedPart) {
    BudgetControl control(1e-6);
    EXPECT_EQ(control.budgetFor(1.0), 0u) << "before any frame the overhead is unknown";
    control.record(0, 0.020);  // a frame with no link update: its time is the overhead
    EXPECT_NEAR(double(control.budgetFor(0.030)), 10000.0, 1.0);
    EXPECT_EQ(control.budgetFor(0.015), 0u) << "a target under the overhead allows nothing";
}

TEST(BudgetControl, FitsOverheadAndCostOnceTheUpdatesVary) {
    BudgetControl control(1e-5);  // a first guess ten times too high
    for (double updates : {0.0, 2000.0, 5000.0, 1000.0, 8000.0}) control.record(std::size_t(updates), 0.020 + 2e-6 * updates);
    EXPECT_NEAR(double(control.budgetFor(0.030)), 5000.0, 1.0);
    EXPECT_NEAR(double(control.budgetFor(0.120)), 50000.0, 1.0);
    EXPECT_EQ(control.budgetFor(0.019), 0u);
}

// Frames of one budget vary: the budget keeps four frames in five within
// the target, so that a few slow ones do not set it, but more do.
TEST(BudgetControl, BudgetKeepsFourFramesInFiveWithinTheTarget) {
    BudgetControl oneSlow(1e-6), twoSlow(1e-6);
    for (int i = 0; i < 10; ++i) {
        oneSlow.record(0, i < 9 ? 0.020 : 0.025);
        twoSlow.record(0, i < 8 ? 0.020 : 0.025);
    }
    EXPECT_NEAR(double(oneSlow.budgetFor(0.035)), 15000.0, 1.0);
    EXPECT_NEAR(double(twoSlow.budgetFor(0.035)), 10000.0, 1.0);
    EXPECT_NEAR(twoSlow.spread(), 0.005, 1e-12);
}

// The first frame of a drag is slower than the rest (its traversal finds
// the lists cold): it must not hold the budget at 0 while the frames that
// follow leave a third of the target unused.
TEST(BudgetControl, ASlowFirstFrameDoesNotHoldTheBudgetAtZero) {
    BudgetControl control(1e-6);
    control.record(0, 0.037);
    control.record(0, 0.020);
    EXPECT_NEAR(double(control.budgetFor(0.033)), 13000.0, 1.0);
    for (int i = 0; i < 4; ++i) control.record(0, 0.020);
    EXPECT_NEAR(double(control.budgetFor(0.033)), 13000.0, 1.0) << "one slow frame in six";
    control.record(0, 0.037);
    EXPECT_EQ(control.budgetFor(0.033), 0u) << "two slow frames in seven";
}

TEST(BudgetControl, IgnoresFramesThatAreNotTimes) {
    BudgetControl control(1e-6);
    control.record(100, -1.0);
    control.record(100, std::numeric_limits<double>::quiet_NaN());
    EXPECT_EQ(control.budgetFor(1.0), 0u) << "no valid frame yet";
}

}  // namespace
}  // namespace rad
