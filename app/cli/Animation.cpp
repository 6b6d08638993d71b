#include "cli/Animation.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

namespace rad::cli {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

glm::dmat4 Motion::at(double f, const glm::dvec3& center, const glm::dmat4& start) const {
    glm::dmat4 m = glm::translate(glm::dmat4(1.0), f * translation + center);
    for (const Rotation& r : rotations) m = m * glm::rotate(glm::dmat4(1.0), glm::radians(f * r.degrees), r.axis);
    return glm::translate(m, -center) * start;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

const std::vector<OptionSpec>& motionOptions() {
    static const std::vector<OptionSpec> options{
        {"--object", "NAME", "the object to move, any object with polygons (required)"},
        {"--frames", "N", "number of equal steps of the motion, 1..100000 (required)"},
        {"--translate", "X,Y,Z", "total translation in metres (repeatable, summed)"},
        {"--rotate", "AX,AY,AZ,DEG", "total rotation about the axis through the object's bounding-box centre (repeatable)"},
    };
    return options;
}

MotionRequest motionFrom(const ParsedArgs& args) {
    MotionRequest r;
    const std::optional<std::string> object = args.value("--object");
    if (!object) throw UsageError("needs --object NAME");
    r.object = *object;
    if (!args.value("--frames")) throw UsageError("needs --frames N");
    r.frames = static_cast<int>(parseInteger("--frames", *args.value("--frames"), 1, 100000));
    for (const std::string& t : args.all("--translate")) {
        const auto v = parseNumbers("--translate", t, 3);
        r.motion.translation += glm::dvec3(v[0], v[1], v[2]);
    }
    for (const std::string& text : args.all("--rotate")) {
        const auto v = parseNumbers("--rotate", text, 4);
        const glm::dvec3 axis(v[0], v[1], v[2]);
        if (!(glm::length(axis) > 0.0)) throw UsageError("--rotate: the axis must not be zero, got '" + text + "'");
        r.motion.rotations.push_back({glm::normalize(axis), v[3]});
    }
    if (args.all("--translate").empty() && r.motion.rotations.empty())
        throw UsageError("needs a motion: --translate X,Y,Z and/or --rotate AX,AY,AZ,DEG");
    return r;
}

std::optional<std::size_t> parseBudget(const std::string& option, const std::string& text) {
    if (text == "inf" || text == "unlimited") return std::nullopt;
    return static_cast<std::size_t>(parseInteger(option, text, 0, 1'000'000'000'000LL));
}

AnimationRun runAnimation(const Scene& scene, const EngineSettings& settings, const std::string& objectName,
                          const Motion& motion, int frames, const BudgetControlSetting& control,
                          References* references, const std::function<void(int, const Engine&, const FrameRecord*)>& onFrame) {
    AnimationRun run;
    Engine engine(scene, settings);
    const auto object = engine.scene().findObject(objectName);
    if (!object) throw std::runtime_error(scene.sourcePath + ": no object named '" + objectName + "'");
    const auto start = std::chrono::steady_clock::now();
    engine.solve([&](const std::string& line) {
        if (secondsSince(start) > 1.0) std::fprintf(stderr, "solve: %s\n", line.c_str());
    });
    run.solveSeconds = secondsSince(start);
    run.initial = engine.stats();
    if (!run.initial.converged) throw std::runtime_error("the initial solve did not converge: " + run.initial.message);
    run.markedDynamic = engine.scene().objects[*object].dynamic;
    try {
        run.selection = engine.setDynamicObject(objectName);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(e.what());
    }
    const glm::dmat4 startTransform = engine.scene().objects[*object].worldFromLocal;
    const glm::dvec3 center = engine.scene().objectBounds(*object).center();
    if (onFrame) {
        FrameRecord chosen;
        chosen.stats = run.selection;
        onFrame(0, engine, &chosen);
    }

    for (int f = 1; f <= frames; ++f) {
        FrameRecord record;
        UpdateSettings update;
        update.budget = control.budget;
        if (control.targetFps) {
            record.targetSeconds = 1.0 / *control.targetFps;
            update.budget = engine.budgetFor(*record.targetSeconds);
        }
        record.stats = engine.moveDynamicObject(motion.at(double(f) / frames, center, startTransform), update);
        if (references) {
            if (references->samples.size() < std::size_t(f)) {
                const auto t = std::chrono::steady_clock::now();
                Engine full(engine.scene(), settings);
                full.solve();
                references->seconds.push_back(secondsSince(t));
                references->samples.push_back(full.samples());
            }
            record.fullSolveSeconds = references->seconds[f - 1];
            record.error = compareSamples(engine.samples(), references->samples[f - 1]);
        }
        run.frames.push_back(record);
        if (onFrame) onFrame(f, engine, &run.frames.back());
    }
    return run;
}

}  // namespace rad::cli
