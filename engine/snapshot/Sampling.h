#pragma once
// Fixed sample points on every input polygon, for comparing two solutions of
// the same scene (the incremental update against a from-scratch solve).

#include <vector>

#include "hierarchy/Hierarchy.h"
#include "scene/Scene.h"

namespace rad {

struct RadiositySamples {
    std::vector<double> luminance;  // per sample: luminance of the leaf's B there
    std::vector<double> weight;     // per sample: the area it stands for
};

// 16 points per input polygon: a 4 x 4 grid of cell centres on quads, the
// centroids of the 16 sub-triangles of a 4-level split on triangles.
RadiositySamples sampleRadiosity(const Scene& scene, const Hierarchy& hierarchy);

struct SolutionError {
    double rms = 0.0;  // area-weighted RMS difference / area-weighted mean of the reference
    double max = 0.0;  // largest absolute difference / that same mean
};
SolutionError compareSamples(const RadiositySamples& solution, const RadiositySamples& reference);

}  // namespace rad
