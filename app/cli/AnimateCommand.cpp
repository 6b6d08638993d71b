// radiosity-cli animate: solve, then move the dynamic object in N equal
// steps with the line-space update, reporting each frame; optionally against
// a from-scratch solve of every frame.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "Engine.h"
#include "cli/Args.h"
#include "cli/Commands.h"
#include "cli/EngineOptions.h"
#include "cli/Json.h"
#include "cli/RenderOutput.h"
#include "scene/GltfImport.h"

namespace rad::cli {
namespace {

const std::vector<OptionSpec>& animateOptions() {
    static const std::vector<OptionSpec> options = [] {
        std::vector<OptionSpec> o{
            {"--object", "NAME", "the object to move (marked dynamic in the scene; required)"},
            {"--frames", "N", "number of equal steps of the motion, 1..100000 (required)"},
            {"--translate", "X,Y,Z", "total translation in metres (repeatable, summed)"},
            {"--rotate", "AX,AY,AZ,DEG", "total rotation about the axis through the object's bounding-box centre (repeatable)"},
            {"--compare-full", "", "also solve every frame from scratch and report the error against it"},
            {"--report", "R.json", "write per-frame figures as JSON"},
            {"--images", "DIR", "write DIR/frame-NNNN.png for the start (0000) and every frame"},
            {"--size", "WxH", "image size (default 512 high, the camera's aspect)"},
            {"--exposure", "EV", "PNG brightness: multiply by 2^EV (default 0)"},
            {"--force", "", "overwrite existing output files"},
        };
        const auto& e = engineOptions();
        o.insert(o.end(), e.begin(), e.end());
        return o;
    }();
    return options;
}

void printAnimateHelp() {
    std::printf(
        "usage: radiosity-cli animate SCENE --object NAME --frames N (--translate X,Y,Z | --rotate AX,AY,AZ,DEG)...\n"
        "                             [--compare-full] [--report R.json] [--images DIR] [--size WxH]\n"
        "Solves SCENE, then applies the total motion in N equal steps to the object,\n"
        "updating the solution through the line-space hierarchy after each step.\n"
        "Rotations turn about the object's bounding-box centre at the start.\n\n%s",
        formatOptions(animateOptions()).c_str());
}

struct Rotation {
    glm::dvec3 axis;
    double degrees;
};

// The object's transform at fraction f of the motion.
glm::dmat4 motionAt(double f, const glm::dvec3& translation, const std::vector<Rotation>& rotations,
                    const glm::dvec3& center, const glm::dmat4& start) {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), f * translation + center);
    for (const Rotation& r : rotations) m = m * glm::rotate(glm::dmat4(1.0), glm::radians(f * r.degrees), r.axis);
    return glm::translate(m, -center) * start;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int runAnimate(const std::vector<std::string>& argv) {
    const ParsedArgs args = parseArgs(argv, animateOptions());
    if (args.has("--help")) {
        printAnimateHelp();
        return kExitOk;
    }
    requirePositionals(args, {"SCENE"});
    const std::string scenePath = args.positionals[0];
    const std::optional<std::string> objectName = args.value("--object");
    if (!objectName) throw UsageError("animate needs --object NAME");
    if (!args.value("--frames")) throw UsageError("animate needs --frames N");
    const int frames = static_cast<int>(parseInteger("--frames", *args.value("--frames"), 1, 100000));
    glm::dvec3 translation(0.0);
    for (const std::string& t : args.all("--translate")) {
        const auto v = parseNumbers("--translate", t, 3);
        translation += glm::dvec3(v[0], v[1], v[2]);
    }
    std::vector<Rotation> rotations;
    for (const std::string& r : args.all("--rotate")) {
        const auto v = parseNumbers("--rotate", r, 4);
        const glm::dvec3 axis(v[0], v[1], v[2]);
        if (!(glm::length(axis) > 0.0)) throw UsageError("--rotate: the axis must not be zero, got '" + r + "'");
        rotations.push_back({glm::normalize(axis), v[3]});
    }
    if (args.all("--translate").empty() && rotations.empty())
        throw UsageError("animate needs a motion: --translate X,Y,Z and/or --rotate AX,AY,AZ,DEG");
    const EngineSettings settings = engineSettingsFrom(args);
    const bool force = args.has("--force"), compare = args.has("--compare-full");
    const std::optional<std::string> report = args.value("--report"), images = args.value("--images");
    std::optional<ImageSize> size;
    if (auto s = args.value("--size")) size = parseSize("--size", *s);
    const double exposure = args.value("--exposure") ? parseDouble("--exposure", *args.value("--exposure")) : 0.0;
    if (report) checkWritable(*report, force);
    if (images) {
        std::filesystem::create_directories(*images);
        checkWritable((std::filesystem::path(*images) / "frame-0000.png").string(), force);
    }

    if (!std::filesystem::exists(scenePath)) throw std::runtime_error(scenePath + ": no such file");
    Engine engine(loadGltf(scenePath), settings);
    const auto object = engine.scene().findObject(*objectName);
    if (!object) throw std::runtime_error(scenePath + ": no object named '" + *objectName + "'");
    const auto solveStart = std::chrono::steady_clock::now();
    engine.solve([&](const std::string& line) {
        if (secondsSince(solveStart) > 1.0) std::fprintf(stderr, "solve: %s\n", line.c_str());
    });
    const double solveSeconds = secondsSince(solveStart);
    if (!engine.stats().converged) throw std::runtime_error("the initial solve did not converge: " + engine.stats().message);
    engine.setDynamicObject(*objectName);
    const glm::dmat4 start = engine.scene().objects[*object].worldFromLocal;
    const glm::dvec3 center = engine.scene().objectBounds(*object).center();

    auto writeFrame = [&](int frame) {
        if (!images) return;
        char name[32];
        std::snprintf(name, sizeof name, "frame-%04d.png", frame);
        const std::string path = (std::filesystem::path(*images) / name).string();
        checkWritable(path, force);
        renderToFile(engine.scene(), engine.snapshot(), ImageRequest{path, size, exposure});
    };
    writeFrame(0);

    JsonWriter j;
    j.beginObject();
    j.value("scene", scenePath);
    j.value("object", *objectName);
    j.value("frames_requested", frames);
    j.value("epsilon", settings.epsilon);
    j.beginObject("initial");
    j.value("seconds", solveSeconds);
    j.value("links", engine.stats().links);
    j.value("passive_links", engine.stats().passiveLinks);
    j.value("elements", engine.stats().elements);
    j.endObject();
    j.beginArray("frames");
    std::vector<double> totals, fullTimes, errors;
    for (int f = 1; f <= frames; ++f) {
        const glm::dmat4 m = motionAt(double(f) / frames, translation, rotations, center, start);
        const FrameStats st = engine.moveDynamicObject(m);
        totals.push_back(st.totalSeconds);
        j.beginObject();
        j.value("frame", f);
        j.beginObject("seconds");
        j.value("traversal", st.traversalSeconds);
        j.value("update", st.updateSeconds);
        j.value("push_pull", st.pushPullSeconds);
        j.value("total", st.totalSeconds);
        j.endObject();
        j.value("shaft_tests", st.shaftTests);
        j.value("candidates", st.candidates);
        j.value("links_updated", st.linksUpdated);
        j.value("reinstated", st.reinstated);
        j.value("refined", st.refined);
        j.value("changed_elements", st.changedElements);
        j.value("bounces", st.bounces);
        j.value("links", st.links);
        j.value("elements", st.elements);
        std::printf("frame %d: %.3f s (traversal %.3f, update %.3f, push-pull %.3f), %zu candidates, %zu refined",
                    f, st.totalSeconds, st.traversalSeconds, st.updateSeconds, st.pushPullSeconds, st.candidates,
                    st.refined);
        if (compare) {
            const auto t = std::chrono::steady_clock::now();
            Engine full(engine.scene(), settings);
            full.solve();
            const double fullSeconds = secondsSince(t);
            const SolutionError e = compareSamples(engine.samples(), full.samples());
            fullTimes.push_back(fullSeconds);
            errors.push_back(e.rms);
            j.value("full_solve_seconds", fullSeconds);
            j.beginObject("error_vs_full");
            j.value("rms", e.rms);
            j.value("max", e.max);
            j.endObject();
            std::printf(", full solve %.2f s, error rms %.4f max %.4f", fullSeconds, e.rms, e.max);
        }
        std::printf("\n");
        j.endObject();
        writeFrame(f);
    }
    j.endArray();
    j.beginObject("summary");
    j.value("median_seconds", median(totals));
    j.value("worst_seconds", *std::max_element(totals.begin(), totals.end()));
    if (compare) {
        j.value("median_full_solve_seconds", median(fullTimes));
        j.value("full_over_update", median(fullTimes) / std::max(median(totals), 1e-12));
        j.value("worst_rms", *std::max_element(errors.begin(), errors.end()));
    }
    j.endObject();
    j.endObject();
    if (report) {
        writeFileAtomically(*report, j.str());
        std::printf("wrote %s\n", report->c_str());
    }
    if (images) std::printf("wrote %d images in %s\n", frames + 1, images->c_str());
    return kExitOk;
}

}  // namespace rad::cli
