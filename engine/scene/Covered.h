#pragma once
// Surfaces covered by others laid on them.
//
// A poster flush with its wall, a rug at the floor's height, a light panel
// in the ceiling's plane, a CAD export that lays a panel over a wall's
// face: two polygons in one plane, facing the same way, overlap. Of
// coincident surfaces only one is seen (RayCaster::blocked: the smaller),
// and the other is dark where they overlap, while the display draws both:
// the lit and the dark one fight for depth. (When the earlier one was seen,
// a lamp in a ceiling's plane listed after the ceiling lit nothing.) The
// import cuts the larger polygon away where a smaller one covers it: what is
// laid on a surface is seen, whatever the order of the two in the file.
// Objects marked dynamic neither cut nor are cut (they move off what they
// lay on; the rays' rule decides there).

#include <cstddef>
#include <span>
#include <vector>

#include "radiosity/Scene.h"

namespace rad {

struct CoveredParts {
    std::size_t polygonsCut = 0;      // polygons that lost a part
    std::vector<double> areaLeftOut;  // per object, m^2
};

// Cuts every polygon of the objects whose `cut` is set away where a smaller
// polygon of such an object (ties: the earlier one) lies in its plane,
// facing the same way, and covers it. What is left is split into convex
// polygons of at most four vertices, texture coordinates following; a
// polygon that would take more than kMostPieces pieces stays whole.
CoveredParts cutCoveredParts(std::vector<std::vector<Polygon>>& polygons,
                             std::span<const char> cut);

}  // namespace rad
