// The exposure that shows a picture whose light is mostly past white
// (image/Exposure.h).

#include "image/Exposure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace rad {
namespace {

TEST(Exposure, APictureMostlyUnderWhiteNeedsNone) {
    EXPECT_FALSE(exposureThatShows({0.2f, 0.5f, 0.9f, 0.99f}, 0.0));
    // A quarter past white (a lamp and its halo): none.
    EXPECT_FALSE(exposureThatShows({0.5f, 0.5f, 0.5f, 30.0f}, 0.0));
    EXPECT_FALSE(exposureThatShows({}, 0.0));
    EXPECT_FALSE(exposureThatShows({0.0f, 0.0f}, 0.0));
}

TEST(Exposure, BringsNineInTenUnderWhiteInHalfStops) {
    // Photometric light: 100 to 1090.
    std::vector<float> peaks;
    for (int i = 0; i < 100; ++i) peaks.push_back(100.0f + 10.0f * float(i));
    const auto ev = exposureThatShows(peaks, 0.0);
    ASSERT_TRUE(ev);
    EXPECT_EQ(2.0 * *ev, std::round(2.0 * *ev)) << "half stops";
    int under = 0;
    for (float p : peaks) under += p * std::exp2(*ev) < 1.0;
    EXPECT_GE(under, 90);
    // Half a stop brighter would put the ninth in ten past white.
    int underBrighter = 0;
    for (float p : peaks) underBrighter += p * std::exp2(*ev + 0.5) < 1.0;
    EXPECT_LT(underBrighter, 90);
    // Measured at another exposure, the answer is the same exposure.
    std::vector<float> atThree;
    for (float p : peaks) atThree.push_back(p * 8.0f);
    EXPECT_EQ(exposureThatShows(atThree, 3.0), ev);
}

TEST(Exposure, UnlitAndNonFiniteValuesAreLeftOut) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const auto ev = exposureThatShows({0.0f, 0.0f, 0.0f, 0.0f, 0.0f, nan, inf, 16.0f, 16.0f}, 0.0);
    ASSERT_TRUE(ev);
    EXPECT_DOUBLE_EQ(*ev, -4.0);
}

}  // namespace
}  // namespace rad
