#pragma once
// Polygons split where others stand on them.
//
// A partition standing on a floor that runs under both rooms (a quad of no
// thickness, or a box on a slab): an element of the floor across the line
// where the partition stands is one constant, lit on one side and shining
// on the other. So the import splits each polygon of a static object along
// the segments where a polygon of another static object meets it from its
// front side, standing on it along an edge or passing through it, when the
// segment runs across at least half of the polygon's width there. Nothing
// is left out: an object moved later leaves only the split behind. Objects
// marked dynamic neither split nor are split. Small contacts (a table leg
// on a floor) and an object's own (shelves on a bookcase's sides) are left
// to refinement: splitting along every polygon that stands on another gave
// `office` 26% more links and its image 7.2% block RMS from Cycles instead
// of 6.6%. The pieces' edges along a split, and a polygon's edges that
// another stands on, are creases (Polygon::creases), which the display does
// not smooth across.

#include <cstddef>
#include <span>
#include <vector>

#include "radiosity/Scene.h"

namespace rad {

// Splits the polygons (per object) of objects whose `split` is set along
// the segments where polygons of other such objects meet them from their
// front side; returns how many polygons were split. A split that would
// leave a side narrower than `narrowest` across the segment is not made
// (books on a shelf: slots of a few millimetres are left to refinement).
// The pieces are convex polygons of at most four vertices, texture
// coordinates following.
// `emits` (per material): an emitting polygon of another object that traps
// its light in front of a polygon (trappingGap) splits it along its outline.
std::size_t splitAtContacts(std::vector<std::vector<Polygon>>& polygons,
                            std::span<const char> split, double narrowest = 0.0,
                            std::span<const char> emits = {});

// An emitting polygon traps its light where a surface lies parallel in front
// of it and faces it, nearer than this share of the square root of its area
// (a panel 1 cm under a ceiling with its normal flipped, a cove light facing
// its wall; a 1 x 1 m panel: up to 10 cm, not an uplight 30 cm under it).
inline constexpr double kTrappedGapShare = 0.1;

// How far `surface` lies in front of `emitter`, when it is parallel, faces
// it and is nearer than kTrappedGapShare of its size (and farther than
// `tolerance`); a negative value otherwise.
double trappingGap(const Polygon& emitter, const Polygon& surface, double tolerance = 0.0);

}  // namespace rad
