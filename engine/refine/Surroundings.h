#pragma once
// How much of the scene a surface point sees: the mean, over the scene's
// surface area, of the area visible from a point, as a share of the whole
// scene's area. One room: most of it (0.5 to 0.9). A building floor of 60
// rooms: about a sixtieth. The refinement thresholds (epsilon's reference
// power and the area threshold) are taken relative to what a point sees, not
// to the whole scene, so that each room of a large scene is refined as it
// would be alone (Refiner::settings().referencePower).

#include "geometry/RayCaster.h"
#include "radiosity/Scene.h"

namespace rad {

// Points (area-weighted over the polygons) and directions (uniform over
// each point's hemisphere) are fixed sequences, so a scene always gets the
// same answer.
inline constexpr int kSurroundingsPoints = 4096;
inline constexpr int kSurroundingsRays = 4;  // per point

// The share, in [0, 1], estimated from kSurroundingsPoints x
// kSurroundingsRays nearest hits: a ray from x meeting a surface at distance
// d, at an angle theta to its normal, stands for 2 pi d^2 / |cos theta| of
// visible area (uniform hemisphere sampling), |cos theta| at least 0.2 (a
// grazing hit stands for no more than five times its head-on area). `rays`
// holds the scene's polygons (either layer).
double visibleAreaShare(const Scene& scene, const RayCaster& rays);

}  // namespace rad
