// radiosity-cli sweep: the same motion under several link-update budgets and
// target frame rates, each frame compared with a from-scratch solve: the
// speed/accuracy trade of the controlled update (paper sec. 6, 7.2).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/Animation.h"
#include "cli/Args.h"
#include "cli/Commands.h"
#include "cli/EngineOptions.h"
#include "cli/MotionOptions.h"
#include "cli/RenderOutput.h"
#include "cli/Report.h"
#include "cli/Script.h"
#include "cli/Warnings.h"
#include "image/AtomicFile.h"
#include "plot/Plot.h"
#include "radiosity/Gltf.h"

namespace rad::cli {
namespace {

struct SweepSettings {
    std::string scene;
    MotionRequest motion;
    std::vector<std::optional<std::size_t>> budgets;  // nullopt: no limit
    std::vector<double> rates;                        // target frame rates
    std::string out;
    EngineSettings engine;
    std::optional<double> referenceEpsilon;  // default: engine.epsilon / 10
    bool force = false;
};

struct Row {
    std::string kind;  // "budget" or "target_fps"
    std::optional<std::size_t> budget;
    std::optional<double> targetFps;
    double medianSeconds = 0.0, p95Seconds = 0.0, worstSeconds = 0.0, medianRms = 0.0, worstRms = 0.0, worstMax = 0.0;
    // Over the frames, of each frame's worst object rms (SolutionError::worstObjectRms).
    double medianWorstObjectRms = 0.0, worstObjectRms = 0.0;
    double medianSpent = 0.0, medianBudget = 0.0;
    double medianEstimatedError = 0.0;  // FrameStats::estimatedError
    // Against the converged reference (a finer epsilon) instead of the full
    // solve at the same settings.
    double medianRmsReference = 0.0, worstRmsReference = 0.0;
};

// Spearman's rank correlation of two series (ties share their mean rank).
double rankCorrelation(const std::vector<double>& a, const std::vector<double>& b) {
    const auto ranks = [](const std::vector<double>& v) {
        std::vector<std::size_t> order(v.size());
        for (std::size_t i = 0; i < v.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return v[x] < v[y]; });
        std::vector<double> r(v.size());
        for (std::size_t i = 0; i < order.size();) {
            std::size_t j = i;
            while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
            for (std::size_t k = i; k <= j; ++k) r[order[k]] = 0.5 * double(i + j);
            i = j + 1;
        }
        return r;
    };
    const std::vector<double> ra = ranks(a), rb = ranks(b);
    const double n = double(a.size());
    if (n < 2.0) return NAN;
    double ma = 0.0, mb = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ma += ra[i] / n;
        mb += rb[i] / n;
    }
    double sab = 0.0, saa = 0.0, sbb = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        sab += (ra[i] - ma) * (rb[i] - mb);
        saa += (ra[i] - ma) * (ra[i] - ma);
        sbb += (rb[i] - mb) * (rb[i] - mb);
    }
    return saa > 0.0 && sbb > 0.0 ? sab / std::sqrt(saa * sbb) : NAN;
}

std::string budgetText(const std::optional<std::size_t>& b) { return b ? std::to_string(*b) : "inf"; }

int sweep(const SweepSettings& settingsGiven) {
    SweepSettings s = settingsGiven;
    resolveMotion(s.motion);
    const std::string& scenePath = s.scene;
    const MotionRequest& request = s.motion;
    const EngineSettings& settings = s.engine;
    const bool force = s.force;
    const std::filesystem::path out(s.out);
    for (const char* name : {"trade.json", "trade.csv", "trade.png", "trade.svg"})
        checkWritable((out / name).string(), force);
    if (!std::filesystem::exists(scenePath)) throw std::runtime_error(scenePath + ": no such file");
    ImportNotes notes;
    const Scene scene = loadGltf(scenePath, &notes);
    printImportNotes(notes);
    printWarnings(importWarnings(notes));
    if (request.script) checkScriptObjects(Script{request.frames, request.moves, request.edits}, *request.script, scene);
    std::vector<std::string> moved;
    for (const ObjectMove& m : request.moves) moved.push_back(m.object);
    printWarnings(movedCutObjects(scene, moved));
    std::filesystem::create_directories(out);

    References references;  // the from-scratch solves, shared by every run
    references.convergedEpsilon = s.referenceEpsilon.value_or(settings.epsilon / 10.0);
    std::vector<Row> rows;
    std::vector<double> allEstimated, allRms;  // every frame of every run
    auto play = [&](Row row, const BudgetControlSetting& control) {
        std::fprintf(stderr, "sweep: %s %s\n", row.kind.c_str(),
                     row.kind == "budget" ? budgetText(row.budget).c_str() : std::to_string(*row.targetFps).c_str());
        const AnimationRun run =
            runAnimation(scene, settings, request.moves, request.edits, request.frames, control,
                         &references);
        if (rows.empty()) printWarnings(run.initial.warnings);  // every run solves the same: say it once
        std::vector<double> seconds, rms, objectRms, spent, budget, estimated, rmsReference;
        for (const FrameRecord& f : run.frames) {
            estimated.push_back(f.stats.estimatedError);
            seconds.push_back(f.stats.totalSeconds);
            spent.push_back(double(f.stats.spent));
            budget.push_back(f.stats.budget == kUnlimited ? -1.0 : double(f.stats.budget));
            row.worstSeconds = std::max(row.worstSeconds, f.stats.totalSeconds);
            if (!f.error || !f.errorVsConverged) continue;  // a frame where nothing emits (runAnimation)
            rmsReference.push_back(f.errorVsConverged->rms);
            row.worstRmsReference = std::max(row.worstRmsReference, f.errorVsConverged->rms);
            allEstimated.push_back(f.stats.estimatedError);
            allRms.push_back(f.error->rms);
            rms.push_back(f.error->rms);
            objectRms.push_back(f.error->worstObjectRms);
            row.worstRms = std::max(row.worstRms, f.error->rms);
            row.worstMax = std::max(row.worstMax, f.error->max);
            row.worstObjectRms = std::max(row.worstObjectRms, f.error->worstObjectRms);
        }
        row.medianSeconds = median(seconds);
        row.p95Seconds = percentile(seconds, 0.95);
        row.medianRms = median(rms);
        row.medianWorstObjectRms = median(objectRms);
        row.medianSpent = median(spent);
        row.medianBudget = median(budget);
        row.medianEstimatedError = median(estimated);
        row.medianRmsReference = median(rmsReference);
        std::printf("%-10s %-8s median frame %.4f s, worst %.4f s, median rms %.4f, worst rms %.4f, "
                    "median rms vs reference %.4f\n",
                    row.kind.c_str(),
                    row.kind == "budget" ? budgetText(row.budget).c_str() : std::to_string(*row.targetFps).c_str(),
                    row.medianSeconds, row.worstSeconds, row.medianRms, row.worstRms, row.medianRmsReference);
        rows.push_back(row);
    };
    for (const auto& b : s.budgets) play(Row{"budget", b, std::nullopt}, BudgetControlSetting{b, std::nullopt});
    for (double f : s.rates) play(Row{"target_fps", std::nullopt, f}, BudgetControlSetting{std::nullopt, f});

    // JSON and CSV.
    Report runs = Report::array();
    std::string csv =
        "kind,budget,target_fps,target_seconds,median_seconds,worst_seconds,median_rms,worst_rms,worst_max,"
        "median_worst_object_rms,worst_object_rms,median_spent,median_budget,median_estimated_error,"
        "median_rms_reference,worst_rms_reference,p95_seconds\n";
    for (const Row& r : rows) {
        Report run{{"kind", r.kind}, {"budget", valueOrNull(r.budget)}};
        if (r.targetFps) {
            run["target_fps"] = *r.targetFps;
            run["target_seconds"] = 1.0 / *r.targetFps;
        }
        run.update({{"median_seconds", r.medianSeconds},
                    {"p95_seconds", r.p95Seconds},
                    {"worst_seconds", r.worstSeconds},
                    {"median_rms", r.medianRms},
                    {"worst_rms", r.worstRms},
                    {"worst_max", r.worstMax},
                    {"median_worst_object_rms", r.medianWorstObjectRms},
                    {"worst_object_rms", r.worstObjectRms},
                    {"median_spent", r.medianSpent},
                    {"median_budget", r.medianBudget},
                    {"median_estimated_error", r.medianEstimatedError},
                    {"median_rms_reference", r.medianRmsReference},
                    {"worst_rms_reference", r.worstRmsReference}});
        runs.push_back(run);
        char line[512];
        std::snprintf(line, sizeof line, "%s,%s,%s,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n",
                      r.kind.c_str(),
                      r.kind == "budget" ? budgetText(r.budget).c_str() : "",
                      r.targetFps ? std::to_string(*r.targetFps).c_str() : "",
                      r.targetFps ? std::to_string(1.0 / *r.targetFps).c_str() : "", r.medianSeconds, r.worstSeconds,
                      r.medianRms, r.worstRms, r.worstMax, r.medianWorstObjectRms, r.worstObjectRms, r.medianSpent,
                      r.medianBudget, r.medianEstimatedError, r.medianRmsReference, r.worstRmsReference, r.p95Seconds);
        csv += line;
    }
    writeReport((out / "trade.json").string(), {{"scene", scenePath},
                                                {"object", request.object.empty() ? Report(nullptr) : Report(request.object)},
                                                {"frames", request.frames},
                                                {"epsilon", settings.epsilon},
                                                {"median_full_solve_seconds", median(references.seconds)},
                                                {"reference_epsilon", *references.convergedEpsilon},
                                                {"median_reference_solve_seconds", median(references.convergedSeconds)},
                                                {"estimate_rank_correlation", rankCorrelation(allEstimated, allRms)},
                                                {"runs", runs}});
    writeFileAtomically((out / "trade.csv").string(), csv);

    // The plot: update time against error per budget; achieved against target frame time.
    plot::Chart trade;
    trade.title = "Update time against error, one point per budget";
    trade.xLabel = "median frame time (s)";
    trade.yLabel = "median rms error";
    plot::Series perBudget{"vs full solve, same epsilon", {}, {}, true, true, {0.1f, 0.2f, 0.8f}, {}};
    char referenceName[96];
    std::snprintf(referenceName, sizeof referenceName, "vs converged reference (epsilon %g)",
                  *references.convergedEpsilon);
    plot::Series perBudgetReference{referenceName, {}, {}, true, true, {0.1f, 0.6f, 0.2f}, {}};
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
            perBudgetReference.x.push_back(r.medianSeconds);
            perBudgetReference.y.push_back(r.medianRmsReference);
            perBudgetReference.pointLabels.push_back(budgetText(r.budget));
        } else {
            perRate.x.push_back(1.0 / *r.targetFps);
            perRate.y.push_back(r.medianSeconds);
            perRate.pointLabels.push_back(std::to_string(int(*r.targetFps + 0.5)) + " fps");
            lo = std::min({lo, 1.0 / *r.targetFps, r.medianSeconds});
            hi = std::max({hi, 1.0 / *r.targetFps, r.medianSeconds});
        }
    }
    trade.series.push_back(perBudget);
    trade.series.push_back(perBudgetReference);
    rate.series.push_back(perRate);
    if (hi > 0.0) rate.diagonal = std::pair(lo, hi);
    plot::writeCharts({trade, rate}, (out / "trade").string(), force);
    for (const char* name : {"trade.json", "trade.csv", "trade.png", "trade.svg"})
        std::printf("wrote %s\n", (out / name).string().c_str());
    return kExitOk;
}

}  // namespace

Command addSweep(CLI::App& cli) {
    auto s = std::make_shared<SweepSettings>();
    CLI::App* c = cli.add_subcommand("sweep", "the speed/accuracy trade of budgets and target frame rates");
    c->footer(
        "Plays the motion once per budget and once per target frame rate, comparing\n"
        "every frame with a from-scratch solve at the same settings and with a converged\n"
        "reference (the frame solved at --reference-epsilon), and writes the trade between\n"
        "update time and error as JSON, CSV and a plot. Needs at least one --translate or --rotate.");
    addScene(*c, s->scene);
    addMotionOptions(*c, s->motion);
    c->add_option("--budgets", "link-update budgets per frame, inf for none")
        ->type_name("B1,B2,...")
        ->each([&budgets = s->budgets](const std::string& text) {
            budgets.clear();
            for (const std::string& b : splitList(text)) budgets.push_back(parseBudget(b));
        })
        ->default_val("0,30,100,330,1000,inf");
    c->add_option("--target-fps", "target frame rates")
        ->type_name("F1,F2,...")
        ->each([&rates = s->rates](const std::string& text) {
            rates.clear();
            for (const std::string& f : splitList(text)) {
                rates.push_back(parseNumber(f));
                if (!(rates.back() > 0.0)) throw CLI::ValidationError("rates must be > 0, got '" + f + "'");
            }
        })
        ->default_val("5,10,30,60");
    c->add_option("--out", s->out, "where trade.json, trade.csv, trade.png and trade.svg go")
        ->type_name("DIR")
        ->required();
    c->add_option("--reference-epsilon", "epsilon of the converged reference each frame is also compared with")
        ->type_name("E")
        ->check(positiveNumber())
        ->each([&e = s->referenceEpsilon](const std::string& text) { e = parseNumber(text); })
        ->default_str("epsilon / 10");
    addFlag(*c, "--force", s->force, "overwrite existing output files");
    addEngineOptions(*c, s->engine);
    return {c, [s] { return sweep(*s); }};
}

}  // namespace rad::cli
