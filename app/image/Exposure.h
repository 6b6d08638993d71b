#pragma once
// An exposure that shows a picture whose light is mostly past white.
//
// A scene in photometric units (Blender writes its 100 W bulb as 5,435 in a
// glTF light's intensity) lights its surfaces thousands of times brighter
// than white at exposure 0, and shows nothing but outlines.

#include <optional>
#include <vector>

namespace rad {

// `peaks`: the largest linear channel of each lit pixel or vertex (zeros are
// left out), at exposure `exposure` (EV). When more than a quarter of them
// are past white, the exposure, in half stops, that brings nine in ten
// under it; none otherwise.
std::optional<double> exposureThatShows(std::vector<float> peaks, double exposure);

}  // namespace rad
