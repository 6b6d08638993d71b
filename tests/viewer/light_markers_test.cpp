// The viewer's light markers (app/viewer/LightMarkers.h): a star of fixed
// size in pixels at the light's place on the screen, a stroke along a spot's
// axis, in the light's colour at full brightness.
#include <gtest/gtest.h>

#include <cmath>

#include "viewer/LightMarkers.h"

namespace rad::viewer {
namespace {

TEST(LightMarkers, AStarThroughTheLightAndAStrokeAlongASpot) {
    const glm::dvec2 centre(300.0, 200.0);
    const std::vector<ScreenSegment> star = lightMarker(centre, std::nullopt, 10.0);
    ASSERT_EQ(star.size(), 4u);
    for (const ScreenSegment& s : star) {
        EXPECT_LT(glm::length(0.5 * (s.a + s.b) - centre), 1e-9) << "each stroke centred on the light";
        EXPECT_NEAR(glm::length(s.b - s.a), 20.0, 1e-9);
    }
    // A spot pointing right and down on the screen: one more stroke from the
    // centre that way, 2.5 radii long, whatever the length given.
    const std::vector<ScreenSegment> spot = lightMarker(centre, glm::dvec2(3.0, 4.0), 10.0);
    ASSERT_EQ(spot.size(), 5u);
    EXPECT_EQ(spot.back().a, centre);
    EXPECT_LT(glm::length(spot.back().b - (centre + glm::dvec2(15.0, 20.0))), 1e-9);
    // Seen end on, a spot's axis has no screen direction: no stroke.
    EXPECT_EQ(lightMarker(centre, glm::dvec2(0.0), 10.0).size(), 4u);
}

TEST(LightMarkers, TheLightsColourAtFullBrightness) {
    EXPECT_EQ(lightMarkerColour(glm::dvec3(20.0, 4.0, 10.0)), glm::dvec3(1.0, 0.2, 0.5));
    EXPECT_EQ(lightMarkerColour(glm::dvec3(0.0)), glm::dvec3(0.5)) << "dimmed to 0: grey, still shown";
}

}  // namespace
}  // namespace rad::viewer
