#pragma once
// Fixed sample points on every input polygon (RadiositySamples), for
// comparing two solutions of the same scene.

#include "hierarchy/Hierarchy.h"
#include "radiosity/Scene.h"
#include "radiosity/Snapshot.h"

namespace rad {

RadiositySamples sampleRadiosity(const Scene& scene, const Hierarchy& hierarchy);

}  // namespace rad
