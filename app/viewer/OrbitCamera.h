#pragma once
// Orbit / pan / zoom around a target, starting from a scene camera.

#include <glm/glm.hpp>

#include "render/CameraView.h"
#include "radiosity/Scene.h"

namespace rad::viewer {

class OrbitCamera {
  public:
    OrbitCamera() = default;
    // Starts at camera, orbiting a point straight ahead at the distance of
    // the scene's centre.
    OrbitCamera(const Camera& camera, const Aabb& bounds);

    void orbit(double dxPixels, double dyPixels);  // drag: yaw about world +Y, pitch
    void pan(double dxPixels, double dyPixels, double viewportHeight);
    void zoom(double steps);  // mouse wheel: positive moves closer

    Camera camera() const;
    CameraView view(double aspect) const { return makeCameraView(camera(), bounds_, aspect); }

  private:
    glm::dvec3 target_{0.0};
    double distance_ = 1.0;
    double yaw_ = 0.0;    // radians about +Y
    double pitch_ = 0.0;  // radians, up positive
    Camera base_;         // yfov, znear
    Aabb bounds_;
};

}  // namespace rad::viewer
