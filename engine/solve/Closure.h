#pragma once
// How closed a polygon's surroundings are: the share of its view (cosine
// weighted, from its front side) that meets a surface instead of leaving the
// scene. The solve fills the part of a point's view that its links leave
// uncovered (Solver, "the fill") only where that view is closed: there every
// direction meets some surface, and what the links see stands for what they
// miss. Where the view leaves the scene (the open front of a box), an
// uncovered direction may see nothing at all.

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/RayCaster.h"
#include "radiosity/Scene.h"

namespace rad {

// Rays per polygon: 4 directions from each of its 16 sample points.
inline constexpr int kClosureRays = 64;

// Sets closure[p] for each listed polygon p (closure is sized to the
// scene's polygons): the share of its rays that meet a polygon of either
// layer, front or back. The rays are fixed in the polygon's own frame (its
// normal and longest edge), so a polygon carried by a rigid move casts the
// same rays from where it stands, and its closure is a function of where
// everything is, not of how it got there.
void measureClosure(const Scene& scene, const RayCaster& rays,
                    std::span<const std::uint32_t> polygons, std::vector<float>& closure);

}  // namespace rad
