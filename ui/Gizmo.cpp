#include "ui/Gizmo.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace rad::ui {
namespace {

constexpr int kRingSegments = 48;

std::optional<glm::dvec2> project(const GizmoView& v, const glm::dvec3& p) {
    const glm::dvec4 clip = v.viewProjection * glm::dvec4(p, 1.0);
    if (clip.w <= 1e-9) return std::nullopt;
    const glm::dvec2 ndc(clip.x / clip.w, clip.y / clip.w);
    return glm::dvec2((ndc.x + 1.0) * 0.5 * v.viewport.x, (ndc.y + 1.0) * 0.5 * v.viewport.y);
}

// World length that shows as about kArrowPixels at center.
double arrowWorldLength(const GizmoView& v, const glm::dvec3& center) {
    const auto a = project(v, center);
    const auto b = project(v, center + v.cameraUp);
    if (!a || !b) return 1.0;
    const double perUnit = glm::length(*b - *a);
    return perUnit > 1e-9 ? Gizmo::kArrowPixels / perUnit : 1.0;
}

glm::dvec3 axisOf(GizmoPart part) {
    switch (part) {
        case GizmoPart::AxisX: return {1, 0, 0};
        case GizmoPart::AxisY: return {0, 1, 0};
        case GizmoPart::AxisZ: return {0, 0, 1};
        default: return {0, 0, 0};
    }
}

double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
    const glm::dvec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

std::vector<std::optional<glm::dvec2>> ringPoints(const GizmoView& v, const glm::dvec3& c, double radius) {
    std::vector<std::optional<glm::dvec2>> pts;
    for (int i = 0; i <= kRingSegments; ++i) {
        const double a = 2.0 * std::numbers::pi * i / kRingSegments;
        pts.push_back(project(v, c + radius * glm::dvec3(std::cos(a), 0.0, std::sin(a))));
    }
    return pts;
}

ImVec2 im(const glm::dvec2& p) { return ImVec2(static_cast<float>(p.x), static_cast<float>(p.y)); }

}  // namespace

std::optional<glm::dvec2> Gizmo::handlePosition(const GizmoView& view, const glm::dvec3& center,
                                                GizmoPart part) {
    const double len = arrowWorldLength(view, center);
    if (part == GizmoPart::RingY) return project(view, center + glm::dvec3(0.8 * len, 0.0, 0.0));
    if (part == GizmoPart::None) return project(view, center);
    return project(view, center + 0.75 * len * axisOf(part));
}

std::optional<glm::dmat4> Gizmo::update(const GizmoView& view, const glm::dvec3& center,
                                        const glm::dmat4& worldFromLocal) {
    const ImGuiIO& io = ImGui::GetIO();
    const glm::dvec2 mouse(io.MousePos.x, io.MousePos.y);
    const double len = arrowWorldLength(view, center);
    const auto c = project(view, center);
    if (!c) {
        hovered_ = GizmoPart::None;
        dragging_ = GizmoPart::None;
        return std::nullopt;
    }
    const std::array<GizmoPart, 3> axes{GizmoPart::AxisX, GizmoPart::AxisY, GizmoPart::AxisZ};
    std::array<std::optional<glm::dvec2>, 3> tips;
    for (int i = 0; i < 3; ++i) tips[i] = project(view, center + len * axisOf(axes[i]));
    const auto ring = ringPoints(view, center, 0.8 * len);

    // Hover: arrows first, then the ring; not while ImGui owns the mouse.
    GizmoPart hover = GizmoPart::None;
    if (dragging_ == GizmoPart::None && !io.WantCaptureMouse) {
        double best = kHitPixels;
        for (int i = 0; i < 3; ++i)
            if (tips[i])
                if (const double d = distanceToSegment(mouse, *c, *tips[i]); d < best) {
                    best = d;
                    hover = axes[i];
                }
        if (hover == GizmoPart::None)
            for (int i = 0; i < kRingSegments; ++i)
                if (ring[i] && ring[i + 1] && distanceToSegment(mouse, *ring[i], *ring[i + 1]) < kHitPixels)
                    hover = GizmoPart::RingY;
    }

    std::optional<glm::dmat4> result;
    if (dragging_ == GizmoPart::None && hover != GizmoPart::None && ImGui::IsMouseClicked(0)) {
        dragging_ = hover;
        startMouse_ = mouse;
        startTransform_ = worldFromLocal;
        startCenter_ = center;
        arrowWorld_ = len;
        if (hover != GizmoPart::RingY) {
            const int i = hover == GizmoPart::AxisX ? 0 : hover == GizmoPart::AxisY ? 1 : 2;
            startAxisPixels_ = tips[i] ? *tips[i] - *c : glm::dvec2(0.0);
        }
    }
    if (dragging_ != GizmoPart::None) {
        if (!io.MouseDown[0]) {
            dragging_ = GizmoPart::None;
        } else if (dragging_ == GizmoPart::RingY) {
            const glm::dvec2 centre = project(view, startCenter_).value_or(*c);
            const double a0 = std::atan2(startMouse_.y - centre.y, startMouse_.x - centre.x);
            const double a1 = std::atan2(mouse.y - centre.y, mouse.x - centre.x);
            double delta = a1 - a0;
            while (delta > std::numbers::pi) delta -= 2.0 * std::numbers::pi;
            while (delta < -std::numbers::pi) delta += 2.0 * std::numbers::pi;
            // Seen from above, turning about +Y runs counter-clockwise on a y-down screen.
            const double sign = view.cameraPosition.y >= startCenter_.y ? -1.0 : 1.0;
            const double angle = sign * delta;
            const double cs = std::cos(angle), sn = std::sin(angle);
            glm::dmat4 r(1.0);
            r[0][0] = cs;
            r[0][2] = -sn;
            r[2][0] = sn;
            r[2][2] = cs;
            glm::dmat4 to(1.0), back(1.0);
            to[3] = glm::dvec4(startCenter_, 1.0);
            back[3] = glm::dvec4(-startCenter_, 1.0);
            result = to * r * back * startTransform_;
        } else {
            const double pixels2 = glm::dot(startAxisPixels_, startAxisPixels_);
            if (pixels2 > 1.0) {
                const double t = glm::dot(mouse - startMouse_, startAxisPixels_) / pixels2 * arrowWorld_;
                glm::dmat4 move(1.0);
                move[3] = glm::dvec4(t * axisOf(dragging_), 1.0);
                result = move * startTransform_;
            }
        }
    }
    hovered_ = dragging_ != GizmoPart::None ? dragging_ : hover;

    // Drawing.
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const auto colorFor = [&](GizmoPart part, ImU32 base) {
        return hovered_ == part ? IM_COL32(255, 255, 255, 255) : base;
    };
    for (int i = 0; i + 1 < static_cast<int>(ring.size()); ++i)
        if (ring[i] && ring[i + 1])
            draw->AddLine(im(*ring[i]), im(*ring[i + 1]), colorFor(GizmoPart::RingY, IM_COL32(255, 200, 40, 255)), 3.0f);
    const std::array<ImU32, 3> colors{IM_COL32(230, 50, 50, 255), IM_COL32(60, 200, 60, 255),
                                      IM_COL32(60, 110, 255, 255)};
    for (int i = 0; i < 3; ++i) {
        if (!tips[i]) continue;
        const ImU32 col = colorFor(axes[i], colors[i]);
        draw->AddLine(im(*c), im(*tips[i]), col, 4.0f);
        glm::dvec2 dir = *tips[i] - *c;
        const double l = glm::length(dir);
        if (l < 1.0) continue;
        dir /= l;
        const glm::dvec2 n(-dir.y, dir.x);
        const glm::dvec2 base = *tips[i] - 14.0 * dir;
        draw->AddTriangleFilled(im(*tips[i] + 4.0 * dir), im(base + 7.0 * n), im(base - 7.0 * n), col);
    }
    draw->AddCircleFilled(im(*c), 5.0f, IM_COL32(240, 240, 240, 255));
    return result;
}

}  // namespace rad::ui
