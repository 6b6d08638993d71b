#include "render/CameraView.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace rad {

Camera autoFitCamera(const Aabb& bounds, double aspect, double yfov) {
    Camera camera;
    camera.yfov = yfov;
    if (bounds.empty()) return camera;  // at the origin looking down -Z: as good as any

    const glm::dvec3 center = bounds.center();
    const double radius = std::max(0.5 * glm::length(bounds.extent()), 1e-9);
    // The sphere fits a cone of half-angle a when distance = radius / sin(a);
    // the narrower of the two fields of view decides.
    const double xfov = 2.0 * std::atan(std::tan(0.5 * yfov) * aspect);
    const double halfAngle = 0.5 * std::min(yfov, xfov);
    const double distance = radius / std::sin(halfAngle);

    // From the front (+Z) and a little above, so floors read as floors.
    const glm::dvec3 direction = glm::normalize(glm::dvec3(0.0, 0.3, 1.0));
    camera.position = center + distance * direction;
    camera.forward = -direction;
    const glm::dvec3 right = glm::normalize(glm::cross(camera.forward, glm::dvec3(0.0, 1.0, 0.0)));
    camera.up = glm::cross(right, camera.forward);
    camera.aspectRatio = aspect;
    // Everything lies at least distance - radius away; keep near well inside that.
    camera.znear = std::max((distance - radius) * 0.5, distance * 1e-5);
    return camera;
}

CameraView makeCameraView(const Camera& camera, const Aabb& bounds, double aspect) {
    CameraView v;
    v.view = glm::lookAt(camera.position, camera.position + camera.forward, camera.up);

    double farthest = 0.0;
    if (!bounds.empty()) {
        for (int i = 0; i < 8; ++i) {
            const glm::dvec3 corner((i & 1) ? bounds.hi.x : bounds.lo.x,
                                    (i & 2) ? bounds.hi.y : bounds.lo.y,
                                    (i & 4) ? bounds.hi.z : bounds.lo.z);
            farthest = std::max(farthest, glm::length(corner - camera.position));
        }
    }
    const double cameraNear = camera.znear > 0.0 ? camera.znear : 0.01;
    // A little margin so the farthest surface is not clipped by rounding.
    v.zfar = farthest > 0.0 ? farthest * 1.01 : 1000.0 * cameraNear;
    // The near plane no farther than 1e-7 of the far one: the 32-bit float
    // depth still tells surfaces 4 mm apart 5 m away from each other at
    // that ratio. (At 1e-5, a stray polygon 100 km away pushed the near
    // plane 1.5 m out, through the room the camera stood in.)
    v.znear = std::max(cameraNear, v.zfar * 1e-7);
    if (v.zfar <= v.znear) v.zfar = 2.0 * v.znear;  // the whole scene is behind the near plane

    v.projection = glm::perspectiveRH_ZO(camera.yfov, aspect, v.znear, v.zfar);
    v.projection[1][1] *= -1.0;  // Vulkan's y points down; world up stays up in the image
    return v;
}

Camera sceneCameraOrAutoFit(const Scene& scene, double aspect) {
    return scene.camera ? *scene.camera : autoFitCamera(scene.bounds(), aspect);
}

}  // namespace rad
