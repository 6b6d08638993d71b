#pragma once
// Surfaces buried in solids.
//
// Modellers build rooms from slabs: one floor slab under several rooms,
// walls that run through the floor, the ceiling and each other, a cabinet
// sunk into a wall. The parts of those polygons inside another solid can
// neither be seen nor lit, but an element that straddles a solid's face is
// one constant: lit on one side, it shines on the other, under a partition
// into the next room (a leak), and into the solid's inside, whose backs
// absorb it (light lost). So the import cuts each polygon of a static object
// along the faces of the closed solids of static objects it passes
// into, and leaves out the pieces inside them. Objects marked dynamic neither
// cut nor are cut: they move out of where they were buried.

#include <array>
#include <cstddef>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "radiosity/Scene.h"

namespace rad {

// The closed solids of one object's triangles (world space, front faces
// counter-clockwise): the parts joined by shared vertices (matched exactly,
// as exporters write them) in which each directed edge appears as often as
// its reverse (two boxes that touch along an edge, or a wall cut around a
// doorway, are closed too), that face outward and enclose a volume.
struct ClosedSolid {
    std::vector<std::array<glm::dvec3, 3>> triangles;
    Aabb box;
    double tolerance = 0.0;  // a point this near a face is on it

    // Whether `p` lies inside: the faces' winding number about it is 1 (0
    // outside), and it is not within the tolerance of a face.
    bool holds(const glm::dvec3& p) const;
};
std::vector<ClosedSolid> closedSolids(std::span<const std::array<glm::dvec3, 3>> triangles);

struct BuriedParts {
    std::size_t polygonsCut = 0;      // polygons that lost a part
    std::vector<double> areaLeftOut;  // per object, m^2
};

// Cuts every polygon of `polygons` (per object; polygons of objects whose
// `cut` is false are left whole) away where it lies inside one of `solids`
// (strictly: a polygon on a solid's face is not inside it). A polygon is cut
// along the lines where the solid's faces cross its plane, and the pieces
// inside are left out; a polygon nothing of which is inside stays whole.
// What is left is split into convex polygons of at most four vertices, with
// texture coordinates interpolated along the cuts.
BuriedParts cutBuriedParts(std::vector<std::vector<Polygon>>& polygons, std::span<const char> cut,
                           std::span<const ClosedSolid> solids);

}  // namespace rad
