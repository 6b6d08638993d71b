#pragma once
// The backs of closed meshes (glTF doubleSided materials).
//
// A doubleSided material reflects on both faces, so the importer gives each
// of its polygons a back face of its own. Modelling tools mark materials so
// by default (Blender does, unless backface culling is on), and most of
// their meshes are closed: the backs of a box's faces face its inside, and
// the backs of a room made of a box with its normals turned in face the
// world outside. No light reaches a closed space with no light in it, so
// back faces that face only such spaces stay black whatever the solve does:
// they are left out (half the polygons of a closed doubleSided object, and
// its inside's near pairs, whose form factors add up past 1).

#include <array>
#include <cstddef>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace rad {

// Whether `triangles` (one object's, world space, front faces counter-
// clockwise) form closed surfaces whose back faces face only spaces that none
// of `lightPoints` is in. Closed: every edge is shared by exactly two
// triangles that run along it in opposite directions (vertices matched
// exactly, as an exporter writes them). A light point on or near a surface
// counts as in the space behind it. Each light point within a closed part's
// box costs a pass over its triangles; past `mostVisits` triangle visits (20
// million: about half a second; a whole building in one mesh with many
// lights inside) the answer is false.
bool backFacesFaceNoLight(std::span<const std::array<glm::dvec3, 3>> triangles,
                          std::span<const glm::dvec3> lightPoints, std::size_t mostVisits = 20'000'000);

}  // namespace rad
