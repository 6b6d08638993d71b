// radiosity-cli sweep: the same motion under several link-update budgets and
// target frame rates, each frame compared with a from-scratch solve: the
// speed/accuracy trade of the controlled update (paper sec. 6, 7.2).

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
#include "plot/Plot.h"
#include "radiosity/Gltf.h"

namespace rad::cli {
namespace {

const std::vector<OptionSpec>& sweepOptions() {
    static const std::vector<OptionSpec> options = [] {
        std::vector<OptionSpec> o = motionOptions();
        o.insert(o.end(), {
            {"--budgets", "B1,B2,...", "link-update budgets per frame, inf for none (default 0,30,100,330,1000,inf)"},
            {"--target-fps", "F1,F2,...", "target frame rates (default 5,10,30,60)"},
            {"--out", "DIR", "where trade.json, trade.csv, trade.png and trade.svg go (required)"},
            {"--force", "", "overwrite existing output files"},
        });
        const auto& e = engineOptions();
        o.insert(o.end(), e.begin(), e.end());
        return o;
    }();
    return options;
}

void printSweepHelp() {
    std::printf(
        "usage: radiosity-cli sweep SCENE --object NAME --frames N (--translate X,Y,Z | --rotate AX,AY,AZ,DEG)...\n"
        "                           [--budgets 0,30,100,330,1000,inf] [--target-fps 5,10,30,60] --out DIR\n"
        "Plays the motion once per budget and once per target frame rate, comparing\n"
        "every frame with a from-scratch solve, and writes the trade between update\n"
        "time and error as JSON, CSV and a plot.\n\n%s",
        formatOptions(sweepOptions()).c_str());
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> out;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        out.push_back(text.substr(start, comma - start));
        if (comma == std::string::npos) return out;
        start = comma + 1;
    }
}

struct Row {
    std::string kind;  // "budget" or "target_fps"
    std::optional<std::size_t> budget;
    std::optional<double> targetFps;
    double medianSeconds = 0.0, worstSeconds = 0.0, medianRms = 0.0, worstRms = 0.0, worstMax = 0.0;
    double medianSpent = 0.0, medianBudget = 0.0;
};

std::string budgetText(const std::optional<std::size_t>& b) { return b ? std::to_string(*b) : "inf"; }

}  // namespace

int runSweep(const std::vector<std::string>& argv) {
    const ParsedArgs args = parseArgs(argv, sweepOptions());
    if (args.has("--help")) {
        printSweepHelp();
        return kExitOk;
    }
    requirePositionals(args, {"SCENE"});
    const std::string scenePath = args.positionals[0];
    const MotionRequest request = motionFrom(args);
    std::vector<std::optional<std::size_t>> budgets;
    for (const std::string& b : splitList(args.value("--budgets").value_or("0,30,100,330,1000,inf")))
        budgets.push_back(parseBudget("--budgets", b));
    std::vector<double> rates;
    for (const std::string& f : splitList(args.value("--target-fps").value_or("5,10,30,60"))) {
        rates.push_back(parseDouble("--target-fps", f));
        if (!(rates.back() > 0.0)) throw UsageError("--target-fps: rates must be > 0, got '" + f + "'");
    }
    const std::optional<std::string> outDir = args.value("--out");
    if (!outDir) throw UsageError("sweep needs --out DIR");
    const EngineSettings settings = engineSettingsFrom(args);
    const bool force = args.has("--force");
    const std::filesystem::path out(*outDir);
    for (const char* name : {"trade.json", "trade.csv", "trade.png", "trade.svg"})
        checkWritable((out / name).string(), force);
    if (!std::filesystem::exists(scenePath)) throw std::runtime_error(scenePath + ": no such file");
    const Scene scene = loadGltf(scenePath);
    std::filesystem::create_directories(out);

    References references;  // the from-scratch solves, shared by every run
    std::vector<Row> rows;
    auto play = [&](Row row, const BudgetControlSetting& control) {
        std::fprintf(stderr, "sweep: %s %s\n", row.kind.c_str(),
                     row.kind == "budget" ? budgetText(row.budget).c_str() : std::to_string(*row.targetFps).c_str());
        const AnimationRun run =
            runAnimation(scene, settings, request.object, request.motion, request.frames, control, &references);
        std::vector<double> seconds, rms, spent, budget;
        for (const FrameRecord& f : run.frames) {
            seconds.push_back(f.stats.totalSeconds);
            rms.push_back(f.error->rms);
            spent.push_back(double(f.stats.spent));
            budget.push_back(f.stats.budget == kUnlimited ? -1.0 : double(f.stats.budget));
            row.worstSeconds = std::max(row.worstSeconds, f.stats.totalSeconds);
            row.worstRms = std::max(row.worstRms, f.error->rms);
            row.worstMax = std::max(row.worstMax, f.error->max);
        }
        row.medianSeconds = median(seconds);
        row.medianRms = median(rms);
        row.medianSpent = median(spent);
        row.medianBudget = median(budget);
        std::printf("%-10s %-8s median frame %.4f s, worst %.4f s, median rms %.4f, worst rms %.4f\n", row.kind.c_str(),
                    row.kind == "budget" ? budgetText(row.budget).c_str() : std::to_string(*row.targetFps).c_str(),
                    row.medianSeconds, row.worstSeconds, row.medianRms, row.worstRms);
        rows.push_back(row);
    };
    for (const auto& b : budgets) play(Row{"budget", b, std::nullopt}, BudgetControlSetting{b, std::nullopt});
    for (double f : rates) play(Row{"target_fps", std::nullopt, f}, BudgetControlSetting{std::nullopt, f});

    // JSON and CSV.
    JsonWriter j;
    j.beginObject();
    j.value("scene", scenePath);
    j.value("object", request.object);
    j.value("frames", request.frames);
    j.value("epsilon", settings.epsilon);
    j.value("median_full_solve_seconds", median(references.seconds));
    j.beginArray("runs");
    std::string csv = "kind,budget,target_fps,target_seconds,median_seconds,worst_seconds,median_rms,worst_rms,worst_max,median_spent,median_budget\n";
    for (const Row& r : rows) {
        j.beginObject();
        j.value("kind", r.kind);
        if (r.budget) j.value("budget", *r.budget);
        else j.null("budget");
        if (r.targetFps) {
            j.value("target_fps", *r.targetFps);
            j.value("target_seconds", 1.0 / *r.targetFps);
        }
        j.value("median_seconds", r.medianSeconds);
        j.value("worst_seconds", r.worstSeconds);
        j.value("median_rms", r.medianRms);
        j.value("worst_rms", r.worstRms);
        j.value("worst_max", r.worstMax);
        j.value("median_spent", r.medianSpent);
        j.value("median_budget", r.medianBudget);
        j.endObject();
        char line[512];
        std::snprintf(line, sizeof line, "%s,%s,%s,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", r.kind.c_str(),
                      r.kind == "budget" ? budgetText(r.budget).c_str() : "",
                      r.targetFps ? std::to_string(*r.targetFps).c_str() : "",
                      r.targetFps ? std::to_string(1.0 / *r.targetFps).c_str() : "", r.medianSeconds, r.worstSeconds,
                      r.medianRms, r.worstRms, r.worstMax, r.medianSpent, r.medianBudget);
        csv += line;
    }
    j.endArray();
    j.endObject();
    writeFileAtomically((out / "trade.json").string(), j.str());
    writeFileAtomically((out / "trade.csv").string(), csv);

    // The plot: update time against error per budget; achieved against target frame time.
    plot::Chart trade;
    trade.title = "Update time against error, one point per budget";
    trade.xLabel = "median frame time (s)";
    trade.yLabel = "median rms error vs full solve";
    plot::Series perBudget{"budget (link updates per frame)", {}, {}, true, true, {0.1f, 0.2f, 0.8f}, {}};
    plot::Chart rate;
    rate.title = "Achieved against target frame time";
    rate.xLabel = "target frame time (s)";
    rate.yLabel = "median achieved frame time (s)";
    plot::Series perRate{"target frame rate", {}, {}, true, true, {0.8f, 0.2f, 0.1f}, {}};
    double lo = 1e9, hi = 0.0;
    for (const Row& r : rows) {
        if (r.kind == "budget") {
            perBudget.x.push_back(r.medianSeconds);
            perBudget.y.push_back(r.medianRms);
            perBudget.pointLabels.push_back(budgetText(r.budget));
        } else {
            perRate.x.push_back(1.0 / *r.targetFps);
            perRate.y.push_back(r.medianSeconds);
            perRate.pointLabels.push_back(std::to_string(int(*r.targetFps + 0.5)) + " fps");
            lo = std::min({lo, 1.0 / *r.targetFps, r.medianSeconds});
            hi = std::max({hi, 1.0 / *r.targetFps, r.medianSeconds});
        }
    }
    trade.series.push_back(perBudget);
    rate.series.push_back(perRate);
    if (hi > 0.0) rate.diagonal = std::pair(lo, hi);
    plot::writeCharts({trade, rate}, (out / "trade").string(), force);
    for (const char* name : {"trade.json", "trade.csv", "trade.png", "trade.svg"})
        std::printf("wrote %s\n", (out / name).string().c_str());
    return kExitOk;
}

}  // namespace rad::cli
