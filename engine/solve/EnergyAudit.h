#pragma once
// Where the light goes, measured independently of the links: from every input
// polygon, rays in cosine-weighted directions find what its light meets. A
// ray that meets nothing leaves the scene (an open scene); one that meets the
// back of a one-sided polygon is absorbed there. With what the links deliver
// to front sides (EnergyBalance::absorbed), the balance then says how much
// light the solution itself lost or made.

#include <vector>

#include "geometry/RayCaster.h"
#include "hierarchy/Hierarchy.h"
#include "radiosity/Scene.h"
#include "radiosity/Stats.h"

namespace rad {

// Per input polygon, the share of its outgoing light (cosine-weighted) that
// meets nothing, and that meets a back face.
struct LightDestinations {
    std::vector<float> escaped, backFaces;
};

// Rays per polygon: enough for the scene's totals, fewer for large scenes.
LightDestinations traceDestinations(const Scene& scene, const RayCaster& rays);

// Fills escaped, backFaces, lost and created from the polygons' radiosity.
void auditEnergy(const Hierarchy& hierarchy, const LightDestinations& destinations,
                 EnergyBalance& energy);

}  // namespace rad
