// radiosity-viewer: the interactive viewer (see --help).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <stdexcept>

#include "viewer/ViewerOptions.h"

#if defined(__SANITIZE_THREAD__)
// libtbb is not instrumented: ThreadSanitizer cannot see the synchronisation
// inside the engine's tbb::parallel_for and reports false races there. Under
// TSan the engine's loops run on the engine thread itself, so what TSan
// checks is the viewer's own hand-over between threads.
#include <oneapi/tbb/global_control.h>
#endif

namespace rad::viewer {

const char* viewerHelp() {
    return "usage: radiosity-viewer [SCENE] [options]\n"
           "\n"
           "Opens a glTF scene, solves its radiosity and shows it in a window. Click an\n"
           "object to select it and get a gizmo (any object can move; those marked dynamic\n"
           "in the scene start under the root of the hierarchy, the others are attached\n"
           "there when selected): drag an arrow to translate, the ring to turn about +Y. Left drag\n"
           "orbits, right or middle drag pans, the wheel zooms; L and C toggle the\n"
           "overlays, Ctrl+Q quits. The panel sets the target\n"
           "frame rate (and so the link-update budget), epsilon (re-solves), exposure and\n"
           "the overlays, and saves screenshots and the lit mesh beside the scene.\n"
           "SCENE defaults to scenes/office.gltf of the source tree (or of the current\n"
           "directory). Without a display use radiosity-cli.\n"
           "\n"
           "options:\n"
           "  --size WxH                 window size (default 1200x760)\n"
           "  --target-fps F             target frame rate, 1..60 (default 30)\n"
           "  --epsilon E                BF refinement threshold (default 2e-4)\n"
           "  --exposure EV              display exposure (default 0)\n"
           "  --overlays LIST            start with overlays on: links,changed\n"
           "  --select NAME              preselect an object (any; it becomes the dynamic one)\n"
           "  --help                     this text\n"
           "test hooks:\n"
           "  --screenshot-after S PATH  write a PNG of the whole window S seconds after\n"
           "                             start (once the solution shows); repeatable\n"
           "  --quit-after S             close the window after S seconds (after the\n"
           "                             screenshots asked for earlier)\n"
           "  --log-transforms           print 'engine: transform NAME translation X Y Z'\n"
           "                             for every transform the engine thread applies\n"
           "  --print-gizmo              print 'object: NAME X Y' (screen pixels of each\n"
           "                             object's box centre) once solved, and 'gizmo:\n"
           "                             x-handle X Y center X Y' when a selection's\n"
           "                             gizmo first shows\n"
           "  --headless-stress N        no window: send N transforms from one thread\n"
           "                             while reading snapshots on another, then exit\n"
           "                             (SCENE defaults to scenes/cornell-box.gltf here).\n"
           "                             Under ThreadSanitizer:\n"
           "                               cmake -S . -B build-tsan -DRADIOSITY_TSAN=ON\n"
           "                               cmake --build build-tsan --target radiosity-viewer\n"
           "                               build-tsan/app/radiosity-viewer --headless-stress 300\n"
           "environment: RADIOSITY_VALIDATION=1 turns on the Vulkan validation layer; any\n"
           "message makes the exit code 1.\n"
           "exit codes: 0 success, 1 failure (no display, bad scene, Vulkan error), 2 bad\n"
           "command line.\n";
}

namespace {

double number(const std::string& option, const char* text) {
    try {
        std::size_t used = 0;
        const double v = std::stod(text, &used);
        if (used != std::string(text).size()) throw std::invalid_argument("");
        return v;
    } catch (const std::exception&) {
        std::string m = option;
        m += ": '";
        m += text;
        m += "' is not a number";
        throw std::invalid_argument(m);
    }
}

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

}  // namespace

ViewerOptions parseViewerArgs(int argc, char** argv, bool& help) {
    ViewerOptions o;
    help = false;
    auto need = [&](int& i, int count) {
        if (i + count >= argc) {
            std::string m = argv[i];
            m += count == 1 ? " needs a value" : " needs two values";
            throw std::invalid_argument(m);
        }
    };
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            help = true;
        } else if (a == "--size") {
            need(i, 1);
            const std::string v = argv[++i];
            const auto x = v.find('x');
            if (x == std::string::npos) throw std::invalid_argument("--size: expected WxH");
            o.width = static_cast<int>(number(a, v.substr(0, x).c_str()));
            o.height = static_cast<int>(number(a, v.substr(x + 1).c_str()));
            if (o.width < 64 || o.height < 64 || o.width > 8192 || o.height > 8192)
                throw std::invalid_argument("--size: each side must be 64..8192");
        } else if (a == "--target-fps") {
            need(i, 1);
            o.targetFps = number(a, argv[++i]);
            if (!(o.targetFps >= 1.0 && o.targetFps <= 60.0))
                throw std::invalid_argument("--target-fps: must be 1..60");
        } else if (a == "--epsilon") {
            need(i, 1);
            o.engine.epsilon = number(a, argv[++i]);
            if (!(o.engine.epsilon > 0.0)) throw std::invalid_argument("--epsilon: must be > 0");
        } else if (a == "--exposure") {
            need(i, 1);
            o.exposure = number(a, argv[++i]);
        } else if (a == "--overlays") {
            need(i, 1);
            std::string list = argv[++i];
            list += ',';
            std::size_t start = 0;
            for (std::size_t p = list.find(','); p != std::string::npos; p = list.find(',', start)) {
                const std::string item = list.substr(start, p - start);
                start = p + 1;
                if (item == "links") o.overlays.modifiedLinks = true;
                else if (item == "changed") o.overlays.changedElements = true;
                else if (!item.empty()) {
                    std::string m = "--overlays: unknown overlay '";
                    m += item;
                    m += "' (links, changed)";
                    throw std::invalid_argument(m);
                }
            }
        } else if (a == "--select") {
            need(i, 1);
            o.select = argv[++i];
        } else if (a == "--screenshot-after") {
            need(i, 2);
            const double s = number(a, argv[i + 1]);
            o.screenshots.emplace_back(s, argv[i + 2]);
            i += 2;
        } else if (a == "--quit-after") {
            need(i, 1);
            o.quitAfter = number(a, argv[++i]);
        } else if (a == "--log-transforms") {
            o.logTransforms = true;
        } else if (a == "--print-gizmo") {
            o.printGizmo = true;
        } else if (a == "--headless-stress") {
            need(i, 1);
            const double n = number(a, argv[++i]);
            if (n < 1) throw std::invalid_argument("--headless-stress: N must be >= 1");
            o.headlessStress = static_cast<int>(n);
        } else if (!a.empty() && a[0] == '-') {
            std::string m = "unknown option ";
            m += a;
            throw std::invalid_argument(m);
        } else if (o.scene.empty()) {
            o.scene = a;
        } else {
            std::string m = "unexpected argument ";
            m += a;
            throw std::invalid_argument(m);
        }
    }
    if (o.scene.empty()) o.scene = defaultScene(o.headlessStress ? "cornell-box.gltf" : "office.gltf");
    return o;
}

}  // namespace rad::viewer

int main(int argc, char** argv) {
    using namespace rad::viewer;
#if defined(__SANITIZE_THREAD__)
    const tbb::global_control serialTbb(tbb::global_control::max_allowed_parallelism, 1);
#endif
    ViewerOptions options;
    try {
        bool help = false;
        options = parseViewerArgs(argc, argv, help);
        if (help) {
            std::fputs(viewerHelp(), stdout);
            return 0;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "radiosity-viewer: %s (see --help)\n", e.what());
        return 2;
    }
    try {
        if (options.headlessStress) return runHeadlessStress(options);
        return runViewer(options);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "radiosity-viewer: %s\n", e.what());
        return 1;
    }
}
