#pragma once
// What the engine hands to a renderer or an exporter: an immutable triangle
// mesh with one linear RGB value per vertex (radiosity B, or a material
// preview), plus optional overlay lines. Single precision: it is for display.
// And fixed sample points of a solution, for comparing two solutions of the
// same scene.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace rad {

struct MeshSnapshot {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec3> colors;  // linear RGB, same units as B
    std::vector<std::uint32_t> indices;  // triangles, counter-clockwise front faces

    // Overlay line segments: pairs of points, one colour per point.
    std::vector<glm::vec3> linePositions;
    std::vector<glm::vec3> lineColors;
};

struct SnapshotOverlays {
    bool modifiedLinks = false;
    bool changedElements = false;
};

struct Scene;

// Material-preview colours (reflectance + emission) per polygon, flat.
MeshSnapshot makePreviewSnapshot(const Scene& scene);

// Leaf radiosity at 16 fixed points of every input polygon: a 4 x 4 grid of
// cell centres on quads, the centroids of the 16 sub-triangles of a 4-level
// split on triangles.
struct RadiositySamples {
    std::vector<double> luminance;  // per sample: luminance of the leaf's B there
    std::vector<double> weight;     // per sample: the area it stands for
};

struct SolutionError {
    double rms = 0.0;  // area-weighted RMS difference / area-weighted mean of the reference
    double max = 0.0;  // largest absolute difference / that same mean
};
SolutionError compareSamples(const RadiositySamples& solution, const RadiositySamples& reference);

}  // namespace rad
