#pragma once
// Where a scene's geometry lies, and how far from it anything may be.
//
// Geometry is kept in double precision, but the rays (Embree) and the
// import's plane tests work relative to the scene's scale: a node misplaced
// far out (a floor translated by 1e10, a light by 1e20) made every polygon
// "repeat" another in place, or crashed Embree on a ray it could not hold.
// `lamp-room` with its floor moved 5e6 m out (2.3 million of the sizes
// below) solved as with it 1e5 m out, to 0.02%; 1e7 m out, 55 polygons
// went missing without a word (README, "Scenes"). So the import refuses
// anything farther than kMaxReach sizes from the scene's detail, naming
// the node.

#include <span>

#include <glm/glm.hpp>

namespace rad {

// How many detail sizes (below) from the detail's centre a vertex or a light
// may lie: 20 times inside the farthest seen to solve right.
inline constexpr double kMaxReach = 1e5;

struct Placement {
    glm::dvec3 centre{0.0};  // per axis, the median of the points
    // The diagonal of the box from the 1st to the 3rd quartile of the points
    // per axis: a node moved far out with a twentieth of the vertices (the
    // floor of `lamp-room`) does not make it large, as a box from the 1st
    // to the 99th percentile would.
    double size = 0.0;
    // Whether p lies within kMaxReach sizes of the centre (always, for a
    // scene of no size).
    bool reaches(const glm::dvec3& p) const;
};

// The placement of a scene's vertices.
Placement placementOf(std::span<const glm::dvec3> points);

}  // namespace rad
