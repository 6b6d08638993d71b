#include "ui/Panels.h"

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

namespace rad::ui {
namespace {

std::string bytes(std::size_t b) {
    char buf[64];
    if (b >= (1u << 20))
        std::snprintf(buf, sizeof buf, "%.1f MiB", static_cast<double>(b) / (1 << 20));
    else
        std::snprintf(buf, sizeof buf, "%.1f KiB", static_cast<double>(b) / (1 << 10));
    return buf;
}

float toLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace

void linearizeStyleColors() {
    ImGuiStyle& style = ImGui::GetStyle();
    for (ImVec4& c : style.Colors) {
        c.x = toLinear(c.x);
        c.y = toLinear(c.y);
        c.z = toLinear(c.z);
    }
}

PanelActions drawPanels(const PanelState& s, PanelControls& c) {
    PanelActions a;
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(370, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("Radiosity");

    ImGui::TextUnformatted(s.sceneName.c_str());
    // Errors and warnings wrap: they are long lines that name objects and
    // figures, and must be read whole.
    const auto coloured = [](const ImVec4& colour, const std::string& text) {
        ImGui::PushStyleColor(ImGuiCol_Text, colour);
        ImGui::TextWrapped("%s", text.c_str());
        ImGui::PopStyleColor();
    };
    if (s.error)
        coloured(ImVec4(1.0f, 0.3f, 0.3f, 1.0f), s.status);
    else
        ImGui::TextWrapped("%s", s.status.c_str());
    if (s.progress) ImGui::ProgressBar(std::clamp(*s.progress, 0.0f, 1.0f), ImVec2(-FLT_MIN, 0.0f), s.progressText.c_str());
    // More than a couple of warnings (the energy guard may name several
    // objects) scroll in a box of their own, so the controls stay in place.
    const bool box = s.warnings.size() > 2;
    if (box) ImGui::BeginChild("##warnings", ImVec2(0.0f, 6.0f * ImGui::GetTextLineHeightWithSpacing()), true);
    for (const std::string& w : s.warnings) coloured(ImVec4(1.0f, 0.8f, 0.2f, 1.0f), "warning: " + w);
    if (box) ImGui::EndChild();
    ImGui::Separator();

    a.targetFpsChanged = ImGui::SliderFloat("target fps", &c.targetFps, 1.0f, 60.0f, "%.0f");
    if (s.budgetUnlimited)
        ImGui::Text("budget: unlimited");
    else
        ImGui::Text("budget: %zu link updates / frame", s.budget);
    ImGui::SliderFloat("epsilon", &c.epsilon, 1e-5f, 1e-2f, "%.1e", ImGuiSliderFlags_Logarithmic);
    a.epsilonCommitted = ImGui::IsItemDeactivatedAfterEdit();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("re-solves when the slider is released");
    a.exposureChanged = ImGui::SliderFloat("exposure EV", &c.exposure, -20.0f, 20.0f, "%.1f");
    a.overlaysChanged |= ImGui::Checkbox("modified links (yellow, L)", &c.showLinks);
    if (c.showLinks && s.overlayLinksShown < s.overlayLinks)
        ImGui::TextDisabled("  %zu of %zu drawn, evenly spread", s.overlayLinksShown, s.overlayLinks);
    a.overlaysChanged |= ImGui::Checkbox("changed elements (red, C)", &c.showChanged);

    ImGui::Separator();
    ImGui::Text("polygons %zu   elements %zu", s.polygons, s.elements);
    ImGui::Text("links %zu   p-links %zu", s.links, s.passiveLinks);
    ImGui::Text("memory %s   solve %.2f s", bytes(s.memoryBytes).c_str(), s.solveSeconds);
    ImGui::Text("moves %zu   last %.1f ms (+%.1f to show)   est. error %.2f%%   updated %zu   pending %zu", s.moves,
                s.lastUpdateMs, s.publishMs, 100.0 * s.estimatedError, s.linksUpdated, s.pending);

    // Update times against the target frame time.
    const float target = 1000.0f / std::max(c.targetFps, 1.0f);
    float top = target * 1.5f;
    for (float v : s.updateMs) top = std::max(top, v * 1.1f);
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "update ms (target %.0f)", target);
    const std::vector<float> empty(2, 0.0f);
    const std::vector<float>& values = s.updateMs.empty() ? empty : s.updateMs;
    const ImVec2 plotPos = ImGui::GetCursorScreenPos();
    ImGui::PlotLines("##updates", values.data(), static_cast<int>(values.size()), 0, overlay, 0.0f,
                     top, ImVec2(ImGui::GetContentRegionAvail().x, 70));
    // The target as a horizontal line across the plot.
    const ImVec2 plotMax = ImGui::GetItemRectMax();
    const float y = plotMax.y - (plotMax.y - plotPos.y) * (target / top);
    ImGui::GetWindowDrawList()->AddLine(ImVec2(plotPos.x, y), ImVec2(plotMax.x, y),
                                        IM_COL32(255, 80, 80, 200));

    ImGui::Separator();
    if (s.selected.empty())
        ImGui::TextWrapped("Click an object to select it (shift+click: several); drag the gizmo to move it.");
    else
        ImGui::Text("selected: %s%s", s.selected.c_str(), s.movable ? "" : " (fixed)");
    if (s.selectionCount > 1) ImGui::Text("and %zu more (shift+click adds or removes)", s.selectionCount - 1);
    if (!s.selectionNote.empty()) ImGui::TextWrapped("%s", s.selectionNote.c_str());
    if (!s.selected.empty() && s.movable) {
        // Applied when released: each edit updates the whole solution.
        if (!s.light) {
            ImGui::ColorEdit3("reflectance", c.reflectance, ImGuiColorEditFlags_Float);
            a.reflectanceEdited = ImGui::IsItemDeactivatedAfterEdit();
        }
        if (s.emitter) {
            ImGui::ColorEdit3("light colour", c.emissionColor, ImGuiColorEditFlags_Float);
            a.emissionEdited = ImGui::IsItemDeactivatedAfterEdit();
            // A punctual light's intensity (W/sr) can be far above a panel's
            // emission: the slider reaches 4 times what the light has.
            const float top = std::max(100.0f, 4.0f * c.emissionIntensity);
            ImGui::SliderFloat("intensity", &c.emissionIntensity, 0.0f, top, "%.2f", ImGuiSliderFlags_Logarithmic);
            a.emissionEdited |= ImGui::IsItemDeactivatedAfterEdit();
        }
    }
    if (!s.movableObjects.empty() && ImGui::TreeNode("objects that can move")) {
        ImGui::BeginChild("##objects", ImVec2(0.0f, 8.0f * ImGui::GetTextLineHeightWithSpacing()), true);
        for (const std::string& name : s.movableObjects)
            if (ImGui::Selectable(name.c_str(), name == s.selected)) a.select = name;
        ImGui::EndChild();
        ImGui::TreePop();
    }
    ImGui::TextDisabled("left drag: orbit   right drag: pan");
    ImGui::TextDisabled("wheel: zoom   Ctrl+Z / Ctrl+Shift+Z: undo / redo   Ctrl+Q: quit");
    ImGui::TextDisabled("P: widen the selection to its parent glTF node (again: further up)");

    ImGui::Separator();
    a.saveScreenshot = ImGui::Button("Save screenshot");
    ImGui::SameLine();
    a.exportMesh = ImGui::Button("Export lit mesh");
    if (!s.lastMessage.empty()) ImGui::TextWrapped("%s", s.lastMessage.c_str());
    ImGui::End();
    return a;
}

}  // namespace rad::ui
