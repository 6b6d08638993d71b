#include "viewer/OrbitCamera.h"

#include <algorithm>
#include <cmath>

namespace rad::viewer {

OrbitCamera::OrbitCamera(const Camera& camera, const Aabb& bounds) : base_(camera), bounds_(bounds) {
    const glm::dvec3 forward = glm::normalize(camera.forward);
    double d = bounds.empty() ? 1.0 : glm::dot(bounds.center() - camera.position, forward);
    if (!(d > 1e-6)) d = bounds.empty() ? 1.0 : std::max(glm::length(bounds.extent()), 1e-3);
    distance_ = d;
    target_ = camera.position + d * forward;
    pitch_ = std::asin(std::clamp(forward.y, -1.0, 1.0));
    yaw_ = std::atan2(forward.x, -forward.z);
}

Camera OrbitCamera::camera() const {
    const glm::dvec3 forward(std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_),
                             -std::cos(pitch_) * std::cos(yaw_));
    Camera c = base_;
    c.forward = forward;
    c.position = target_ - distance_ * forward;
    const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0.0, 1.0, 0.0)));
    c.up = glm::cross(right, forward);
    // Keep the near plane sensible as the camera comes closer.
    c.znear = std::min(base_.znear > 0.0 ? base_.znear : 0.01, distance_ * 0.05);
    return c;
}

void OrbitCamera::orbit(double dx, double dy) {
    yaw_ += dx * 0.005;
    pitch_ = std::clamp(pitch_ - dy * 0.005, -1.5, 1.5);
}

void OrbitCamera::pan(double dx, double dy, double viewportHeight) {
    const Camera c = camera();
    const glm::dvec3 right = glm::normalize(glm::cross(c.forward, c.up));
    const double perPixel = 2.0 * distance_ * std::tan(0.5 * c.yfov) / std::max(viewportHeight, 1.0);
    target_ += (-dx * right + dy * c.up) * perPixel;
}

void OrbitCamera::zoom(double steps) { distance_ = std::max(distance_ * std::pow(0.9, steps), 1e-4); }

}  // namespace rad::viewer
