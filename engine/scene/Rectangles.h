#pragma once
// A planar region whose outline runs along two perpendicular directions (a
// wall with a door or window cut out of it) cut into a few rectangles. CAD
// tools triangulate such a wall into long slivers; the coplanar merge
// (GltfImport.cpp) makes one polygon of a region that is a convex triangle
// or quad, and hands other regions here, so that a wall with an opening is
// meshed as the rectangles it is made of rather than as its slivers.

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace rad {

// `outline`: the region's boundary as directed edges (from, to), every loop
// of it (the outer one and its holes), turning counter-clockwise about
// `normal` around the region. `area`: the region's area (its triangles').
// Returns rectangles whose corners turn counter-clockwise about `normal`
// and whose union is the region, cut along the grid of the outline's
// coordinates, each the largest within kMaxAspect (or else the squarest)
// that starts at its first free cell; a corner that is a vertex of the
// outline is that vertex exactly. Nothing when an edge runs along
// neither direction, when the rectangles' area is not `area` (the outline
// folds or overlaps), or when the outline's coordinates make a grid of more
// than kMaxCells cells.
std::optional<std::vector<std::array<glm::dvec3, 4>>> rectanglesOf(
    const std::vector<std::pair<glm::dvec3, glm::dvec3>>& outline, const glm::dvec3& normal, double area);

inline constexpr std::size_t kMaxCells = 4096;
// Longest side over shortest: rectangles within it are preferred.
inline constexpr double kMaxAspect = 3.0;

}  // namespace rad
