#pragma once
// From a scene camera (or an automatic one) to the matrices the renderer
// pushes: right-handed view, Vulkan clip space (y down, depth 0..1).

#include <glm/glm.hpp>

#include "radiosity/Scene.h"

namespace rad {

struct CameraView {
    glm::dmat4 view{1.0};        // world to camera: camera at the origin looking down -Z
    glm::dmat4 projection{1.0};  // camera to Vulkan clip space, y flipped so +Y is up in the image
    double znear = 0.01;
    double zfar = 100.0;

    // Double precision: MeshRenderer moves it to a snapshot's origin before
    // it goes to the GPU in float.
    glm::dmat4 viewProjection() const { return projection * view; }
};

// A camera looking at the centre of bounds from the +Z side and a little above,
// far enough that the bounding sphere fits both the vertical field of view
// (yfov) and the horizontal one given by aspect (width / height).
Camera autoFitCamera(const Aabb& bounds, double aspect = 1.0, double yfov = glm::radians(45.0));

// View and projection for camera at aspect (width / height). The far plane
// is just past the farthest corner of bounds; near is the camera's znear, raised
// to far * 1e-5 when that is larger, so millimetre and kilometre scenes keep
// depth precision. An empty bounds gives far = 1000 * near.
CameraView makeCameraView(const Camera& camera, const Aabb& bounds, double aspect);

// The camera to render a scene through: its own, or autoFitCamera when it has none.
Camera sceneCameraOrAutoFit(const Scene& scene, double aspect);

}  // namespace rad
