#pragma once
// Thresholds relative to the light a receiver gets. BF refinement compares a
// link's transfer with epsilon times the emitted power, so a region lit a
// hundredth as brightly as the rest is refined a hundred times more coarsely
// for its own light: a storey lit only through a stair opening read 42.7%
// from a path tracer (README, "Accuracy against ground truth"). After the
// first refinement round, a polygon whose reflected light is under
// 1 / kDarkRatio of the scene's mean gets a finer threshold for the links it
// receives: kDarkRatio times its light over the mean, rounded to a power of
// two, at least kFinestScale. A large polygon (kLargeShare of the surface a
// room's points see, or more: a storey's walls and floor) is refined for
// its own light alone: its light over the mean (of the strongest channel),
// at least kLargeFinestScale: its light is much of what is seen there; the
// many small dim polygons under furniture and in shelves are not, and
// refining them as finely took `office` 23% more links (2.9 s, over the 2 s
// its solve may take) for 4.1% from Cycles against 4.3%. Where the light is
// sent matters as much (the bright storey's links into the dark one), and
// those links have dark receivers too; refining dark sources among
// themselves helped little (measured in the README).
//
// The scales are fixed from then on: moves and edits keep them, so that a
// scene moved back to where it was solved is refined as it was. Rounding to
// powers of two keeps most polygons at the same scale in a from-scratch
// solve of a moved scene: only a polygon whose light crosses a rounding
// boundary changes its scale.

#include <vector>

#include "hierarchy/Hierarchy.h"
#include "radiosity/Scene.h"

namespace rad {

inline constexpr double kDarkRatio = 4.0;
inline constexpr double kFinestScale = 0.25;
inline constexpr double kLargeShare = 0.01;
inline constexpr double kLargeFinestScale = 1.0 / 16.0;

// One scale per input polygon, in [kLargeFinestScale, 1], from the
// radiosity of its leaves (B - E, by area; luminance, and the strongest
// channel for large polygons) against the area mean
// over the polygons that do not glow. Glowing polygons, and every polygon of
// a scene that reflects nothing, keep 1. `roomShare`: the share of the
// scene's surface a point sees (the local thresholds' scale, 1 for a room;
// refine/Surroundings.h), which a large polygon's area is judged against.
std::vector<float> receiverLightScales(const Scene& scene, const Hierarchy& hierarchy, double roomShare);

}  // namespace rad
