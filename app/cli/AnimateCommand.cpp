// radiosity-cli animate: solve, then move the dynamic object in N equal
// steps with the line-space update, reporting each frame; optionally under a
// link-update budget or a target frame rate, and against a from-scratch
// solve of every frame.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cli/Animation.h"
#include "cli/Args.h"
#include "cli/Commands.h"
#include "cli/EngineOptions.h"
#include "cli/Json.h"
#include "cli/RenderOutput.h"
#include "radiosity/Gltf.h"

namespace rad::cli {
namespace {

const std::vector<OptionSpec>& animateOptions() {
    static const std::vector<OptionSpec> options = [] {
        std::vector<OptionSpec> o = motionOptions();
        o.insert(o.end(), {
            {"--budget", "LINKS", "link updates allowed per frame, or inf (default: no limit)"},
            {"--target-fps", "F", "set each frame's budget from this frame rate (not with --budget)"},
            {"--compare-full", "", "also solve every frame from scratch and report the error against it"},
            {"--report", "R.json", "write per-frame figures as JSON"},
            {"--images", "DIR", "write DIR/frame-NNNN.png for the start (0000) and every frame"},
            {"--size", "WxH", "image size (default 512 high, the camera's aspect)"},
            {"--exposure", "EV", "PNG brightness: multiply by 2^EV (default 0)"},
            {"--force", "", "overwrite existing output files"},
        });
        const auto& e = engineOptions();
        o.insert(o.end(), e.begin(), e.end());
        return o;
    }();
    return options;
}

void printAnimateHelp() {
    std::printf(
        "usage: radiosity-cli animate SCENE --object NAME --frames N (--translate X,Y,Z | --rotate AX,AY,AZ,DEG)...\n"
        "                             [--budget LINKS | --target-fps F] [--compare-full] [--report R.json]\n"
        "                             [--images DIR] [--size WxH]\n"
        "Solves SCENE, then applies the total motion in N equal steps to the object,\n"
        "updating the solution through the line-space hierarchy after each step.\n"
        "Rotations turn about the object's bounding-box centre at the start.\n\n%s",
        formatOptions(animateOptions()).c_str());
}

void writeFrame(JsonWriter& j, int f, const FrameRecord& r) {
    const FrameStats& st = r.stats;
    j.beginObject();
    j.value("frame", f);
    j.beginObject("seconds");
    j.value("traversal", st.traversalSeconds);
    j.value("update", st.updateSeconds);
    j.value("push_pull", st.pushPullSeconds);
    j.value("move", st.moveSeconds);
    j.value("total", st.totalSeconds);
    j.endObject();
    if (st.budget == kUnlimited)
        j.null("budget");
    else
        j.value("budget", st.budget);
    if (r.targetSeconds)
        j.value("target_seconds", *r.targetSeconds);
    else
        j.null("target_seconds");
    j.value("spent", st.spent);
    j.value("shaft_tests", st.shaftTests);
    j.value("candidates", st.candidates);
    j.value("links_updated", st.linksUpdated);
    j.value("reinstated", st.reinstated);
    j.value("budget_reinstated", st.budgetReinstated);
    j.value("refined", st.refined);
    j.value("pending", st.pending);
    j.value("changed_elements", st.changedElements);
    j.value("bounces", st.bounces);
    j.value("links", st.links);
    j.value("elements", st.elements);
    if (r.error) {
        j.value("full_solve_seconds", *r.fullSolveSeconds);
        j.beginObject("error_vs_full");
        j.value("rms", r.error->rms);
        j.value("max", r.error->max);
        j.endObject();
    }
    j.endObject();
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
    const MotionRequest request = motionFrom(args);
    BudgetControlSetting control;
    if (args.has("--budget") && args.has("--target-fps"))
        throw UsageError("--budget and --target-fps exclude each other");
    if (auto b = args.value("--budget")) control.budget = parseBudget("--budget", *b);
    if (auto f = args.value("--target-fps")) {
        control.targetFps = parseDouble("--target-fps", *f);
        if (!(*control.targetFps > 0.0)) throw UsageError("--target-fps: must be > 0, got '" + *f + "'");
    }
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
    const Scene scene = loadGltf(scenePath);

    References references;
    const AnimationRun run = runAnimation(
        scene, settings, request.object, request.motion, request.frames, control, compare ? &references : nullptr,
        [&](int f, const Engine& engine, const FrameRecord* record) {
            if (f == 0 && !engine.scene().objects[*engine.dynamicObject()].dynamic) {
                const ReinsertionStats& r = record->stats.reinsertion;
                std::printf("'%s' is not marked dynamic: its cluster was attached to the root and relinked "
                            "(%zu links removed, %zu created) in %.3f s\n",
                            request.object.c_str(), r.removed, r.created, record->stats.totalSeconds);
            }
            if (record && f > 0) {
                const FrameStats& st = record->stats;
                std::printf("frame %d: %.3f s (traversal %.3f, update %.3f, push-pull %.3f), %zu candidates, %zu refined\n",
                            f, st.totalSeconds, st.traversalSeconds, st.updateSeconds, st.pushPullSeconds,
                            st.candidates, st.refined);
            }
            if (!images) return;
            char name[32];
            std::snprintf(name, sizeof name, "frame-%04d.png", f);
            const std::string path = (std::filesystem::path(*images) / name).string();
            checkWritable(path, force);
            renderToFile(engine.scene(), engine.snapshot(), ImageRequest{path, size, exposure});
        });

    JsonWriter j;
    j.beginObject();
    j.value("scene", scenePath);
    j.value("object", request.object);
    j.value("frames_requested", request.frames);
    j.value("epsilon", settings.epsilon);
    j.beginObject("initial");
    j.value("seconds", run.solveSeconds);
    j.value("links", run.initial.links);
    j.value("passive_links", run.initial.passiveLinks);
    j.value("elements", run.initial.elements);
    j.endObject();
    // Choosing the object after the solve (paper sec. 3.3).
    j.beginObject("selection");
    j.value("marked_dynamic", run.markedDynamic);
    j.value("seconds", run.selection.totalSeconds);
    j.value("links_removed", run.selection.reinsertion.removed);
    j.value("links_recomputed", run.selection.reinsertion.recomputed);
    j.value("links_created", run.selection.reinsertion.created);
    j.value("shaft_tests", run.selection.shaftTests);
    j.value("candidates", run.selection.candidates);
    j.endObject();
    j.beginArray("frames");
    std::vector<double> totals, fullTimes, errors;
    for (std::size_t i = 0; i < run.frames.size(); ++i) {
        const FrameRecord& r = run.frames[i];
        writeFrame(j, int(i) + 1, r);
        totals.push_back(r.stats.totalSeconds);
        if (r.error) {
            fullTimes.push_back(*r.fullSolveSeconds);
            errors.push_back(r.error->rms);
            std::printf("frame %zu: full solve %.2f s, error rms %.4f max %.4f\n", i + 1, *r.fullSolveSeconds,
                        r.error->rms, r.error->max);
        }
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
    if (images) std::printf("wrote %d images in %s\n", request.frames + 1, images->c_str());
    return kExitOk;
}

}  // namespace rad::cli
