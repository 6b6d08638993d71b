#pragma once
// The viewer's control panel (Dear ImGui). Thin and engine-agnostic: the
// program fills PanelState from its snapshot each frame, the panel draws it
// and reports what the user asked for in PanelActions.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace rad::ui {

struct PanelState {
    std::string sceneName;
    std::string status;  // "solving: round 2 ..." / "solved" / an error
    bool error = false;  // status is an error, or why the solve did not converge
    bool solving = false;
    // While solving: the share done (a bar under the status) and its text
    // ("42%, about 3 s left").
    std::optional<float> progress;
    std::string progressText;
    // One line each: the import's (duplicates dropped) and the solve's
    // (memory limit, energy guard), as the CLI prints them.
    std::vector<std::string> warnings;

    // Statistics.
    std::size_t polygons = 0, elements = 0, links = 0, passiveLinks = 0;
    std::size_t memoryBytes = 0;
    double solveSeconds = 0.0;
    std::size_t budget = 0;  // link updates per frame
    bool budgetUnlimited = false;
    std::size_t moves = 0, pending = 0, linksUpdated = 0;
    double lastUpdateMs = 0.0;
    double publishMs = 0.0;  // handing a frame's picture to the window, after its update
    double estimatedError = 0.0;  // FrameStats::estimatedError of the last frame
    // The modified-link overlay: links recorded by the last update, and drawn.
    std::size_t overlayLinks = 0, overlayLinksShown = 0;
    std::vector<float> updateMs;  // the last seconds of updates, oldest first

    // Selection.
    std::string selected;  // empty: nothing selected
    std::size_t selectionCount = 0;  // shift+click selects several; the gizmo moves them together
    bool movable = false;
    std::string selectionNote;
    // The selected object emits (its controls show colour and intensity).
    bool emitter = false;
    bool light = false;  // a punctual light: no surface, no reflectance
    // Every object that can move (has polygons), for the list.
    std::vector<std::string> movableObjects;

    std::string lastMessage;  // "saved x.png", errors from the buttons
};

struct PanelControls {
    // Edited in place by the panel.
    float targetFps = 30.0f;   // 1..60
    float epsilon = 2e-4f;
    float exposure = 0.0f;     // EV
    bool showLinks = false;
    bool showChanged = false;
    // The selected object's colour and light, linear RGB; the program loads
    // them when the selection changes.
    float reflectance[3] = {0.0f, 0.0f, 0.0f};
    float emissionColor[3] = {1.0f, 1.0f, 1.0f};  // largest channel 1
    float emissionIntensity = 0.0f;                // emission = colour x intensity
};

struct PanelActions {
    bool targetFpsChanged = false;
    bool epsilonCommitted = false;  // on release of the slider
    bool overlaysChanged = false;
    bool exposureChanged = false;
    bool saveScreenshot = false;
    bool exportMesh = false;
    bool reflectanceEdited = false;  // on release of the control
    bool emissionEdited = false;
    std::optional<std::string> select;  // an object chosen in the list
};

// Draws the panel window at the top left.
PanelActions drawPanels(const PanelState& state, PanelControls& controls);

// Converts the current ImGui style's colours from sRGB to linear, for a
// swapchain whose hardware encodes to sRGB (otherwise the panel looks washed out).
void linearizeStyleColors();

}  // namespace rad::ui
