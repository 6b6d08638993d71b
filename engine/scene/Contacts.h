#pragma once
// Polygons split where others stand on them.
//
// A partition drawn as one quad (no thickness) standing on a floor that
// runs under both rooms: an element of the floor across the line where the
// partition stands is one constant, lit on one side and shining on the
// other. So the import splits each polygon of a static object along the
// segments where a sheet of another static object (a polygon on no closed
// solid's face) meets it from its front side, standing on it along an edge
// or passing through it, across at least half of the polygon's width there.
// Nothing is left out: an object moved later leaves only the split behind.
// Objects marked dynamic neither split nor are split. Solids are left to
// scene/Buried.h (what they bury) and to refinement (what they stand on),
// and so are an object's own contacts: splitting along every polygon that
// stands on another (shelves on a bookcase's sides, furniture on a floor)
// gave `office` 26% more links and its image 7.2% block RMS from Cycles
// instead of 6.6%.

#include <cstddef>
#include <span>
#include <vector>

#include "radiosity/Scene.h"
#include "scene/Buried.h"

namespace rad {

// Splits the polygons (per object) of objects whose `split` is set along
// the segments where sheets of such objects (polygons on none of `solids`'
// faces) meet them from their front side; returns how many polygons were
// split. The pieces are convex polygons of at most four vertices, texture
// coordinates following.
std::size_t splitAtContacts(std::vector<std::vector<Polygon>>& polygons,
                            std::span<const char> split, std::span<const ClosedSolid> solids);

}  // namespace rad
