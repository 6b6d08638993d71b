// radiosity-cli solve: the converged static solution of a scene, with a JSON
// report, a rendering and a glTF export of the lit mesh.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "radiosity/Engine.h"
#include "cli/Args.h"
#include "cli/Commands.h"
#include "cli/EngineOptions.h"
#include "cli/Json.h"
#include "cli/RenderOutput.h"
#include "radiosity/Gltf.h"

namespace rad::cli {
namespace {

const std::vector<OptionSpec>& solveOptions() {
    static const std::vector<OptionSpec> options = [] {
        std::vector<OptionSpec> o = engineOptions();
        o.insert(o.end(), {
        {"--report", "R.json", "write a JSON report of counts, times, memory, energy and object radiosity"},
        {"--image", "OUT", "render the solution: .png sRGB-encoded, .pfm linear radiosity B"},
        {"--size", "WxH", "image size, each side 1..8192 (default 512 high, the camera's aspect)"},
        {"--exposure", "EV", "PNG only: multiply by 2^EV before sRGB encoding (default 0)"},
        {"--export", "OUT.glb", "write the lit mesh as glTF (.glb or .gltf) with COLOR_0 = B"},
        {"--force", "", "overwrite existing output files"},
        });
        return o;
    }();
    return options;
}

void printSolveHelp() {
    std::printf(
        "usage: radiosity-cli solve SCENE [--epsilon E] [--min-area A] [--report R.json]\n"
        "                           [--image OUT.png|OUT.pfm] [--size WxH] [--export OUT.glb]\n"
        "Solves the glTF SCENE with clustering hierarchical radiosity (BF refinement,\n"
        "gather and push-pull to convergence) and writes what was asked for.\n\n%s",
        formatOptions(solveOptions()).c_str());
}

double seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

std::string reportJson(const std::string& scenePath, const EngineSettings& settings, const Engine& engine,
                       double loadSeconds, double totalSeconds) {
    const SolveStats& st = engine.stats();
    JsonWriter j;
    j.beginObject();
    j.value("scene", scenePath);
    j.value("epsilon", settings.epsilon);
    j.value("min_area", st.minArea);
    j.value("polygons", st.polygons);
    j.value("elements", st.elements);
    j.value("links", st.links);
    j.value("passive_links", st.passiveLinks);
    j.value("iterations", st.iterations);
    j.value("refine_rounds", st.refineRounds);
    j.value("converged", st.converged);
    j.value("message", st.message);
    j.beginObject("seconds");
    j.value("load", loadSeconds);
    j.value("hierarchy", st.hierarchySeconds);
    j.value("refine", st.refineSeconds);
    j.value("solve", st.solveSeconds);
    j.value("total", totalSeconds);
    j.endObject();
    j.beginObject("memory_bytes");
    j.value("total", st.memory.total());
    j.value("elements", st.memory.elements);
    j.value("links", st.memory.links);
    j.endObject();
    j.beginObject("energy");
    j.value("emitted", st.energy.emitted);
    j.value("received", st.energy.received);
    j.value("absorbed", st.energy.absorbed);
    j.value("reflected", st.energy.reflected);
    j.value("escaped", st.energy.escaped);
    j.endObject();
    j.beginArray("objects");
    for (const ObjectRadiosity& o : engine.objectRadiosity()) {
        j.beginObject();
        j.value("name", o.name);
        j.value("area", o.area);
        j.beginArray("radiosity");
        j.element(o.radiosity.x).element(o.radiosity.y).element(o.radiosity.z);
        j.endArray();
        j.endObject();
    }
    j.endArray();
    j.endObject();
    return j.str();
}

}  // namespace

int runSolve(const std::vector<std::string>& argv) {
    const auto start = std::chrono::steady_clock::now();
    const ParsedArgs args = parseArgs(argv, solveOptions());
    if (args.has("--help")) {
        printSolveHelp();
        return kExitOk;
    }
    requirePositionals(args, {"SCENE"});
    const std::string scenePath = args.positionals[0];
    const EngineSettings settings = engineSettingsFrom(args);
    const bool force = args.has("--force");
    std::optional<ImageRequest> image;
    if (auto v = args.value("--image")) {
        checkImagePath("--image", *v);
        image = ImageRequest{*v, std::nullopt, 0.0};
        if (auto s = args.value("--size")) image->size = parseSize("--size", *s);
        if (auto e = args.value("--exposure")) image->exposure = parseDouble("--exposure", *e);
    }
    const std::optional<std::string> report = args.value("--report");
    const std::optional<std::string> exportPath = args.value("--export");
    for (const auto& out : {report, image ? std::optional(image->path) : std::nullopt, exportPath})
        if (out) checkWritable(*out, force);

    if (!std::filesystem::exists(scenePath)) throw std::runtime_error(scenePath + ": no such file");
    Scene scene = loadGltf(scenePath);
    const auto loaded = std::chrono::steady_clock::now();

    Engine engine(std::move(scene), settings);
    // Progress only for solves long enough to wonder about.
    const auto progress = [&](const std::string& line) {
        if (seconds(start, std::chrono::steady_clock::now()) > 1.0) std::fprintf(stderr, "solve: %s\n", line.c_str());
    };
    const SolveStats& st = engine.solve(progress);
    const auto solved = std::chrono::steady_clock::now();
    std::printf("%zu polygons, %zu elements, %zu links, %zu p-links, %d sweeps, %.2f s\n", st.polygons, st.elements,
                st.links, st.passiveLinks, st.iterations, seconds(start, solved));
    if (!st.message.empty()) std::fprintf(stderr, "solve: %s\n", st.message.c_str());

    if (report) {
        writeFileAtomically(*report, reportJson(scenePath, settings, engine, seconds(start, loaded), seconds(start, solved)));
        std::printf("wrote %s\n", report->c_str());
    }
    if (image || exportPath) {
        const MeshSnapshot mesh = engine.snapshot();
        if (image) {
            renderToFile(engine.scene(), mesh, *image);
            std::printf("wrote %s\n", image->path.c_str());
        }
        if (exportPath) {
            exportGltf(mesh, *exportPath);
            std::printf("wrote %s\n", exportPath->c_str());
        }
    }
    return st.converged ? kExitOk : kExitFailure;
}

}  // namespace rad::cli
