#pragma once
// What the engine hands to a renderer or an exporter: an immutable triangle
// mesh with one linear RGB value per vertex (radiosity B, or a material
// preview), plus optional overlay lines. Single precision: it is for display.

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

struct Scene;

// Material-preview colours (reflectance + emission) per polygon, flat.
MeshSnapshot makePreviewSnapshot(const Scene& scene);

}  // namespace rad
