#pragma once
// Fixed sample points on every input polygon (RadiositySamples), for
// comparing two solutions of the same scene.

#include "hierarchy/Hierarchy.h"
#include "radiosity/Scene.h"
#include "radiosity/Snapshot.h"

namespace rad {

// About this many points over the whole scene, spread by area, and between
// 4 x 4 and 64 x 64 on each polygon.
inline constexpr int kSamplesOverScene = 20'000;
inline constexpr int kLeastSamplesAcross = 4;
inline constexpr int kMostSamplesAcross = 64;

RadiositySamples sampleRadiosity(const Scene& scene, const Hierarchy& hierarchy);

}  // namespace rad
