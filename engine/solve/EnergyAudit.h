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

// Fills escaped, backFaces, lost and created: the light leaving each surface
// leaf (its B A) is followed by rays from it, about 200k in all, shared out
// by that power (at least 4 per leaf), so the totals are measured to a
// fraction of a percent whatever the scene.
void auditEnergy(const Scene& scene, const Hierarchy& hierarchy, const RayCaster& rays,
                 EnergyBalance& energy);

}  // namespace rad
