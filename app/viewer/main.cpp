// radiosity-viewer: the interactive viewer (see --help).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/Args.h"
#include "viewer/ViewerOptions.h"

#if defined(__SANITIZE_THREAD__)
// libtbb is not instrumented: ThreadSanitizer cannot see the synchronisation
// inside the engine's tbb::parallel_for and reports false races there. Under
// TSan the engine's loops run on the engine thread itself, so what TSan
// checks is the viewer's own hand-over between threads.
#include <oneapi/tbb/global_control.h>
#endif

namespace rad::viewer {
namespace {

constexpr const char* kDescription =
    "Opens a glTF scene, solves its radiosity and shows it in a window. Click an\n"
    "object to select it and get a gizmo (any object can move; those marked dynamic\n"
    "in the scene start under the root of the hierarchy, the others are attached\n"
    "there when selected): drag an arrow to translate, the ring to turn about +Y. Left drag\n"
    "orbits, right or middle drag pans, the wheel zooms; L and C toggle the\n"
    "overlays, Ctrl+Q quits. The panel sets the target\n"
    "frame rate (and so the link-update budget), epsilon (re-solves), exposure and\n"
    "the overlays, and saves screenshots and the lit mesh beside the scene.\n"
    "Without a display use radiosity-cli.";

constexpr const char* kFooter =
    "Environment: RADIOSITY_VALIDATION=1 turns on the Vulkan validation layer; any\n"
    "message makes the exit code 1.\n"
    "Exit codes: 0 success, 1 failure (no display, bad scene, Vulkan error), 2 bad\n"
    "command line.";

std::string defaultScene(const std::string& name) {
#ifdef RADIOSITY_SOURCE_DIR
    std::string inTree = RADIOSITY_SOURCE_DIR;
    inTree += "/scenes/";
    inTree += name;
    if (std::filesystem::exists(inTree)) return inTree;
#endif
    std::string local = "scenes/";
    local += name;
    return local;
}

// "links,changed", either or both; empty items are ignored.
SnapshotOverlays parseOverlays(const std::string& list) {
    SnapshotOverlays overlays;
    for (const std::string& item : cli::splitList(list)) {
        if (item == "links")
            overlays.modifiedLinks = true;
        else if (item == "changed")
            overlays.changedElements = true;
        else if (!item.empty())
            throw CLI::ValidationError("unknown overlay '" + item + "' (links, changed)");
    }
    return overlays;
}

void addOptions(CLI::App& app, ViewerOptions& o) {
    app.add_option("SCENE", o.scene,
                   "glTF scene (default: scenes/office.gltf of the source tree, or of the\n"
                   "current directory; scenes/cornell-box.gltf with --headless-stress)")
        ->type_name("");
    app.add_option("--size", "window size, each side 64..8192")
        ->type_name("WxH")
        ->each([&o](const std::string& text) {
            const cli::ImageSize size = cli::parseSize(text, 64, 8192);
            o.width = size.width;
            o.height = size.height;
        })
        ->default_str(std::to_string(o.width) + "x" + std::to_string(o.height));
    app.add_option("--target-fps", o.targetFps, "target frame rate, 1..60")
        ->type_name("F")
        ->check(cli::numberIn(1.0, 60.0))
        ->capture_default_str();
    app.add_option("--epsilon", o.engine.epsilon, "BF refinement threshold")
        ->type_name("E")
        ->check(cli::positiveNumber())
        ->capture_default_str();
    app.add_option("--exposure", o.exposure, "display exposure")
        ->type_name("EV")
        ->check(cli::number())
        ->capture_default_str();
    app.add_option("--overlays", "start with overlays on: links, changed or both (links,changed)")
        ->type_name("LIST")
        ->each([&o](const std::string& text) { o.overlays = parseOverlays(text); });
    app.add_option("--select", o.select, "preselect an object (any; it becomes the dynamic one)")->type_name("NAME");

    const std::string hooks = "Test hooks";
    app.add_option("--screenshot-after", o.screenshots,
                   "write a PNG of the whole window S seconds after start\n"
                   "(once the solution shows); repeatable")
        ->type_name("S PATH")
        ->allow_extra_args(false)  // one S PATH pair per --screenshot-after
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->check(cli::number().application_index(0))
        ->group(hooks);
    app.add_option("--quit-after", o.quitAfter,
                   "close the window after S seconds (after the screenshots\n"
                   "asked for earlier)")
        ->type_name("S")
        ->check(cli::number())
        ->group(hooks);
    cli::addFlag(app, "--log-transforms", o.logTransforms,
                 "print 'engine: transform NAME translation X Y Z' for every\n"
                 "transform the engine thread applies, 'engine: caught up after M\n"
                 "moves' when it has nothing left to update, 'viewer: shown\n"
                 "overlays links=0|1 changed=0|1' once the window shows other\n"
                 "overlays, and 'viewer: shown caught up after M moves' once it\n"
                 "shows that picture")
        ->group(hooks);
    cli::addFlag(app, "--print-gizmo", o.printGizmo,
                 "print 'object: NAME X Y' (screen pixels of each object's box\n"
                 "centre) once solved, and 'gizmo: x-handle X Y center X Y'\n"
                 "when a selection's gizmo first shows")
        ->group(hooks);
    app.add_option("--headless-stress", o.headlessStress,
                   "no window: send N transforms from one thread while reading\n"
                   "snapshots on another, then exit. Under ThreadSanitizer:\n"
                   "  cmake -S . -B build-tsan -DRADIOSITY_TSAN=ON\n"
                   "  cmake --build build-tsan --target radiosity-viewer\n"
                   "  build-tsan/app/radiosity-viewer --headless-stress 300")
        ->type_name("N")
        ->transform(cli::integerIn(1, 1'000'000'000))
        ->group(hooks);
}

}  // namespace
}  // namespace rad::viewer

int main(int argc, char** argv) {
    using namespace rad::viewer;
    namespace cli = rad::cli;
#if defined(__SANITIZE_THREAD__)
    const tbb::global_control serialTbb(tbb::global_control::max_allowed_parallelism, 1);
#endif
    ViewerOptions options;
    CLI::App app(kDescription, "radiosity-viewer");
    cli::configure(app);
    app.footer(kFooter);
    addOptions(app, options);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::fputs(app.help().c_str(), stdout);
        return cli::kExitOk;
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "radiosity-viewer: %s (see --help)\n", e.what());
        return cli::kExitUsage;
    }
    options.exposureGiven = app.count("--exposure") > 0;
    if (options.scene.empty()) options.scene = defaultScene(options.headlessStress ? "cornell-box.gltf" : "office.gltf");
    try {
        if (options.headlessStress) return runHeadlessStress(options);
        return runViewer(options);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "radiosity-viewer: %s\n", e.what());
        return cli::kExitFailure;
    }
}
