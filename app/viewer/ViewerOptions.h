#pragma once
// The viewer's command line (declared with CLI11 in viewer/main.cpp; the
// defaults here are the ones --help shows).

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "radiosity/Engine.h"

namespace rad::viewer {

struct ViewerOptions {
    std::string scene;
    int width = 1200, height = 760;
    double targetFps = 30.0;
    double exposure = 0.0;
    // No --exposure: the first solution's light picks one when most of it is
    // past white (image/Exposure.h).
    bool exposureGiven = false;
    EngineSettings engine;
    SnapshotOverlays overlays;
    std::string select;
    // Test hooks.
    std::vector<std::pair<double, std::string>> screenshots;  // (seconds, path)
    std::optional<double> quitAfter;
    bool logTransforms = false;
    bool printGizmo = false;
    std::optional<int> headlessStress;
};

// The window (returns the exit code).
int runViewer(const ViewerOptions& options);
// --headless-stress N: the engine thread without a window.
int runHeadlessStress(const ViewerOptions& options);

}  // namespace rad::viewer
