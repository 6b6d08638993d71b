// radiosity-cli solve: the converged static solution of a scene, with a JSON
// report, a rendering and a glTF export of the lit mesh.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "radiosity/Engine.h"
#include "cli/Args.h"
#include "cli/Commands.h"
#include "cli/EngineOptions.h"
#include "cli/ProgressLines.h"
#include "cli/RenderOutput.h"
#include "cli/Report.h"
#include "cli/Warnings.h"
#include "radiosity/Gltf.h"

namespace rad::cli {
namespace {

struct SolveSettings {
    std::string scene;
    EngineSettings engine;
    std::optional<std::string> report, exportPath;
    ImageRequest image;  // written when image.path is set
    bool force = false;
};

double seconds(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

// `warnings`: the import's, then the solve's.
Report makeReport(const SolveSettings& s, const Engine& engine, const ImportNotes& notes,
                  const std::vector<Warning>& warnings, double loadSeconds, double totalSeconds) {
    const SolveStats& st = engine.stats();
    Report objects = Report::array();
    for (const ObjectRadiosity& o : engine.objectRadiosity())
        objects.push_back({{"name", o.name},
                           {"area", o.area},
                           {"radiosity", {o.radiosity.x, o.radiosity.y, o.radiosity.z}}});
    return {
        {"scene", s.scene},
        {"epsilon", s.engine.epsilon},
        {"min_area", st.minArea},
        {"min_area_smallest", st.minAreaSmallest},
        {"threshold_scale", st.thresholdScale},
        {"polygons", st.polygons},
        {"elements", st.elements},
        {"links", st.links},
        {"passive_links", st.passiveLinks},
        {"iterations", st.iterations},
        {"refine_rounds", st.refineRounds},
        {"converged", st.converged},
        {"message", st.message},
        {"stopped_by", st.stoppedBy.empty() ? Report(nullptr) : Report(st.stoppedBy)},
        {"unrefined_power_share", st.unrefinedPowerShare},
        {"warnings", warningsReport(warnings)},
        {"import_notes", notes.lines},
        {"seconds",
         {{"load", loadSeconds},
          {"hierarchy", st.hierarchySeconds},
          {"refine", st.refineSeconds},
          {"solve", st.solveSeconds},
          {"total", totalSeconds}}},
        {"memory_bytes", {{"total", st.memory.total()}, {"elements", st.memory.elements}, {"links", st.memory.links}, {"update", st.memory.update}}},
        {"energy",
         {{"emitted", st.energy.emitted},
          {"received", st.energy.received},
          {"filled", st.energy.filled},
          {"absorbed", st.energy.absorbed},
          {"reflected", st.energy.reflected},
          {"escaped", st.energy.escaped},
          {"back_faces", st.energy.backFaces},
          {"lost", st.energy.lost},
          {"created", st.energy.created}}},
        {"objects", objects},
    };
}

int solve(const SolveSettings& s) {
    const auto start = std::chrono::steady_clock::now();
    for (const std::string& out : {s.report.value_or(""), s.image.path, s.exportPath.value_or("")})
        if (!out.empty()) checkWritable(out, s.force);

    if (!std::filesystem::exists(s.scene)) throw std::runtime_error(s.scene + ": no such file");
    ImportNotes notes;
    Scene scene = loadGltf(s.scene, &notes);
    std::vector<Warning> warnings = importWarnings(notes);
    printImportNotes(notes);
    printWarnings(warnings);
    const auto loaded = std::chrono::steady_clock::now();

    Engine engine(std::move(scene), s.engine);
    const SolveStats& st = engine.solve(progressOnStderr("solve"));
    const auto solved = std::chrono::steady_clock::now();
    std::printf("%zu polygons, %zu elements, %zu links, %zu p-links, %d sweeps, %.2f s\n", st.polygons, st.elements,
                st.links, st.passiveLinks, st.iterations, seconds(start, solved));
    printWarnings(st.warnings);
    warnings.insert(warnings.end(), st.warnings.begin(), st.warnings.end());
    // A solve that did not converge fails (exit 1) and says why; a converged
    // one may still carry a note.
    if (!st.converged) std::fprintf(stderr, "error: the solve did not converge: %s\n", whyNotConverged(st).c_str());
    else if (!st.message.empty())
        std::fprintf(stderr, "solve: %s\n", st.message.c_str());

    if (s.report) {
        writeReport(*s.report, makeReport(s, engine, notes, warnings, seconds(start, loaded), seconds(start, solved)));
        std::printf("wrote %s\n", s.report->c_str());
    }
    if (!s.image.path.empty() || s.exportPath) {
        const MeshSnapshot mesh = engine.snapshot();
        if (!s.image.path.empty()) {
            renderToFile(engine.scene(), mesh, s.image);
            std::printf("wrote %s\n", s.image.path.c_str());
        }
        if (s.exportPath) {
            exportGltf(mesh, *s.exportPath);
            std::printf("wrote %s\n", s.exportPath->c_str());
        }
    }
    return st.converged ? kExitOk : kExitFailure;
}

}  // namespace

Command addSolve(CLI::App& cli) {
    auto s = std::make_shared<SolveSettings>();
    CLI::App* c = cli.add_subcommand("solve", "solve a scene's radiosity; report, image and glTF export");
    c->footer(
        "Solves the glTF SCENE with clustering hierarchical radiosity (BF refinement,\n"
        "gather and push-pull to convergence) and writes what was asked for.");
    addScene(*c, s->scene);
    addEngineOptions(*c, s->engine);
    c->add_option("--report", s->report, "write a JSON report of counts, times, memory, energy and object radiosity")
        ->type_name("R.json");
    c->add_option("--image", s->image.path, "render the solution: .png sRGB-encoded, .pfm linear radiosity B")
        ->type_name("OUT")
        ->each(checkImagePath);
    addImageOptions(*c, s->image.size, s->image.exposure);
    c->add_option("--export", s->exportPath, "write the lit mesh as glTF (.glb or .gltf) with COLOR_0 = B")
        ->type_name("OUT.glb");
    addFlag(*c, "--force", s->force, "overwrite existing output files");
    return {c, [s] { return solve(*s); }};
}

}  // namespace rad::cli
