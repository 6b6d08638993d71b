#pragma once
// Static geometry that the moving object goes into (issue: "an object moved
// ... into other geometry still gives a valid solution").
//
// A rigid motion changes neither the form factor of a link with both ends on
// the dynamic object nor the object's occlusion of its own parts, so the
// update skips those links. Static geometry changes their visibility only
// where it lies between two parts of the object: inside the object's box,
// and cutting the object (a plane with the object wholly on one side, such
// as the floor under a chair or the wall behind a bookcase, cannot come
// between two of its points). Those pieces, where the object now is and
// where it was (carried along with it into its new frame), are the
// obstacles; a link inside the object whose shaft meets one is updated.

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/Scene.h"

namespace rad {

// The obstacles of a move of object `object` from `oldBox` to its current
// position, `oldToNew` being the motion (world space, rigid). Boxes in the
// current frame of the object.
std::vector<Aabb> motionObstacles(const Scene& scene, std::uint32_t object, const Aabb& oldBox,
                                  const glm::dmat4& oldToNew);

}  // namespace rad
