#pragma once
// Where the punctual lights are: they have no polygons, so nothing on the
// screen shows them. The viewer draws a marker for each one over the scene,
// at a fixed size in pixels whatever the distance: a star of four strokes
// through the light's position on the screen and, for a spot, a longer
// stroke toward where it points; in the light's colour, outlined in black so
// that it shows against a surface the light itself lights. Pure: screen
// geometry and colour only (the drawing is ImGui's, in Viewer.cpp).

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

namespace rad::viewer {

struct ScreenSegment {
    glm::dvec2 a{0.0}, b{0.0};
};

inline constexpr double kLightMarkerPixels = 12.0;  // the star's radius

// `centre`: the light's position on the screen; `axis`: for a spot, the
// screen direction of its axis (any length; nullopt or too short to tell, as
// for a spot seen end on: no stroke).
inline std::vector<ScreenSegment> lightMarker(const glm::dvec2& centre, std::optional<glm::dvec2> axis,
                                              double radius = kLightMarkerPixels) {
    std::vector<ScreenSegment> out;
    for (int k = 0; k < 4; ++k) {
        const double angle = k * 0.25 * 3.14159265358979323846;
        const glm::dvec2 d(std::cos(angle), std::sin(angle));
        out.push_back({centre - radius * d, centre + radius * d});
    }
    if (axis && glm::length(*axis) > 1e-6) out.push_back({centre, centre + 2.5 * radius * glm::normalize(*axis)});
    return out;
}

// The marker's colour, linear RGB: the light's colour at full brightness
// (its largest channel 1), mid grey for a light dimmed to 0.
inline glm::dvec3 lightMarkerColour(const glm::dvec3& intensity) {
    const double top = std::max({intensity.x, intensity.y, intensity.z});
    return top > 0.0 ? intensity / top : glm::dvec3(0.5);
}

}  // namespace rad::viewer
