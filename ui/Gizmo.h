#pragma once
// A translate (three axis arrows) and rotate (a ring about +Y) gizmo drawn
// with ImGui's foreground draw list at an object's centre and dragged with
// the mouse. Knows nothing about the engine: it takes the view and the
// object's transform and returns the world transform the drag asks for.

#include <optional>

#include <glm/glm.hpp>

namespace rad::ui {

struct GizmoView {
    glm::dmat4 viewProjection{1.0};  // world to Vulkan clip space
    glm::dvec2 viewport{1.0};        // in ImGui display pixels
    glm::dvec3 cameraPosition{0.0};
    glm::dvec3 cameraUp{0.0, 1.0, 0.0};
};

enum class GizmoPart { None, AxisX, AxisY, AxisZ, RingY };

class Gizmo {
  public:
    static constexpr double kArrowPixels = 110.0;  // on-screen arrow length
    static constexpr double kHitPixels = 8.0;

    // Draws the gizmo at center (world) and handles the mouse. While a handle
    // is dragged it returns the new world transform: worldFromLocal moved
    // along the axis, or turned about +Y through the centre the drag started at.
    std::optional<glm::dmat4> update(const GizmoView& view, const glm::dvec3& center,
                                     const glm::dmat4& worldFromLocal);

    // The part under the mouse (or being dragged): the caller must not treat
    // a click there as a pick or a camera drag.
    GizmoPart hovered() const { return hovered_; }
    bool dragging() const { return dragging_ != GizmoPart::None; }

    // Where a part's grab point lies on the screen (ImGui display pixels), or
    // nullopt when it is behind the camera: 3/4 along an arrow, or the ring's
    // +X point.
    static std::optional<glm::dvec2> handlePosition(const GizmoView& view, const glm::dvec3& center,
                                                    GizmoPart part);

  private:
    GizmoPart hovered_ = GizmoPart::None;
    GizmoPart dragging_ = GizmoPart::None;
    glm::dvec2 startMouse_{0.0};
    glm::dmat4 startTransform_{1.0};
    glm::dvec3 startCenter_{0.0};
    glm::dvec2 startAxisPixels_{0.0};  // screen vector of the arrow
    double arrowWorld_ = 1.0;          // world length of the arrow at drag start
};

}  // namespace rad::ui
