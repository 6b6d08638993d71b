#pragma once

#include "hierarchy/Hierarchy.h"
#include "radiosity/Scene.h"
#include "radiosity/Snapshot.h"

namespace rad {

// Per-vertex radiosity for Gouraud shading. Within each input polygon, a
// vertex takes the area-weighted mean B of the leaves around it; a vertex
// that lies inside the edge of a coarser leaf (a T-vertex) takes the value
// interpolated along that edge instead, so that shading has no cracks or
// jumps where neighbouring leaves differ in depth.
MeshSnapshot makeRadiositySnapshot(const Scene& scene, const Hierarchy& hierarchy);
// The same into `mesh`, reusing its memory.
void makeRadiositySnapshot(const Scene& scene, const Hierarchy& hierarchy, MeshSnapshot& mesh);

}  // namespace rad
