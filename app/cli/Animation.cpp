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
            if (references->convergedEpsilon) {
                if (references->converged.size() < std::size_t(f)) {
                    const auto t = std::chrono::steady_clock::now();
                    EngineSettings finer = settings;
                    finer.epsilon = *references->convergedEpsilon;
                    Engine converged(engine.scene(), finer);
                    const SolveStats& st = converged.solve();
                    if (!st.converged)
                        std::fprintf(stderr, "warning: the reference of frame %d (epsilon %g) did not converge: %s\n", f,
                                     finer.epsilon, st.message.c_str());
                    references->convergedSeconds.push_back(secondsSince(t));
                    references->converged.push_back(converged.samples());
                }
                record.errorVsConverged = compareSamples(engine.samples(), references->converged[f - 1]);
            }
        }
        run.frames.push_back(record);
        if (onFrame) onFrame(f, engine, &run.frames.back());
    }
    return run;
}

}  // namespace rad::cli
