#include "cli/Animation.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "cli/Args.h"
#include "cli/ProgressLines.h"
#include "cli/Warnings.h"

namespace rad::cli {
namespace {

double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Where a move starts: the object's or light's transform, and the point it
// turns about (a light's position, an object's box centre).
std::pair<glm::dmat4, glm::dvec3> motionStart(const Scene& scene, const std::string& name) {
    if (const auto light = scene.findLight(name)) return {scene.lights[*light].worldFromLocal, scene.lights[*light].position};
    const std::uint32_t object = *scene.findObject(name);
    return {scene.objects[object].worldFromLocal, scene.objectBounds(object).center()};
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

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const auto rank = static_cast<std::size_t>(std::ceil(p * double(v.size())));
    return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

// The frame's figures when it both moved and edited: times and counts add
// up, the state after it (links, pending, estimate) is the last one's.
void addFrame(FrameStats& into, const FrameStats& more) {
    into.traversalSeconds += more.traversalSeconds;
    into.updateSeconds += more.updateSeconds;
    into.pushPullSeconds += more.pushPullSeconds;
    into.bounceSeconds += more.bounceSeconds;
    into.moveSeconds += more.moveSeconds;
    into.estimateSeconds += more.estimateSeconds;
    into.snapshotSeconds += more.snapshotSeconds;
    into.totalSeconds += more.totalSeconds;
    into.spent += more.spent;
    into.reinstated += more.reinstated;
    into.refined += more.refined;
    into.changedElements += more.changedElements;
    into.changedLeaves += more.changedLeaves;
    into.bounces += more.bounces;
    into.transfers += more.transfers;
    into.links = more.links;
    into.elements = more.elements;
    into.pending = more.pending;
    into.stale = more.stale;
    into.unsent = more.unsent;
    into.unmeshed = more.unmeshed;
    into.finer = more.finer;
    // An edit after a deferred move leaves the move deferred: what it
    // estimated stands.
    into.estimatedError = std::max(into.estimatedError, more.estimatedError);
}

AnimationRun runAnimation(const Scene& scene, const EngineSettings& settings, const std::vector<ObjectMove>& moves,
                          const std::vector<Edit>& edits, int frames, const BudgetControlSetting& control,
                          References* references, const std::function<void(int, const Engine&, const FrameRecord*)>& onFrame) {
    AnimationRun run;
    Engine engine(scene, settings);
    for (const ObjectMove& m : moves)
        if (!engine.scene().findObject(m.object) && !engine.scene().findLight(m.object))
            throw std::runtime_error(scene.sourcePath + ": no object or light named '" + m.object + "'");
    // Where each edit starts: the object's values in the file (a light's
    // emission is its intensity).
    std::vector<Material> startOf;
    for (const Edit& e : edits) {
        if (const auto light = engine.scene().findLight(e.object)) {
            startOf.push_back(Material{e.object, glm::dvec3(0.0), engine.scene().lights[*light].intensity});
            continue;
        }
        const auto o = engine.scene().findObject(e.object);
        if (!o || engine.scene().objects[*o].polygonCount == 0)
            throw std::runtime_error(scene.sourcePath + ": no object named '" + e.object + "' with polygons");
        startOf.push_back(engine.scene().materials[engine.scene().polygons[engine.scene().objects[*o].firstPolygon].material]);
    }
    // Every frame's move is checked before the solve: a script that takes an
    // object out of the rays' reach fails at once, not after the solve.
    for (const ObjectMove& m : moves) {
        const auto [from, about] = motionStart(engine.scene(), m.object);
        for (int f = 1; f <= frames; ++f) {
            try {
                engine.checkMove(m.object, m.motion.at(double(f) / frames, about, from));
            } catch (const std::invalid_argument& e) {
                throw UsageError("frame " + std::to_string(f) + ": " + e.what());
            }
        }
    }
    const auto start = std::chrono::steady_clock::now();
    engine.solve(progressOnStderr("solve"));
    run.solveSeconds = secondsSince(start);
    run.initial = engine.stats();
    if (!run.initial.converged) throw std::runtime_error("the initial solve did not converge: " + whyNotConverged(run.initial));
    // Each moving object chosen (the first is the run's selection), and
    // where its motion starts.
    std::vector<glm::dmat4> startTransform;
    std::vector<glm::dvec3> center;
    for (std::size_t k = 0; k < moves.size(); ++k) {
        try {
            const FrameStats chosen = engine.setDynamicObject(moves[k].object);
            if (k == 0) {
                // A light is not in the hierarchy: nothing to attach.
                const auto object = engine.scene().findObject(moves[k].object);
                run.markedDynamic = !object || engine.scene().objects[*object].dynamic;
                run.selection = chosen;
            }
        } catch (const std::invalid_argument& e) {
            throw std::runtime_error(e.what());
        }
        const auto [from, about] = motionStart(engine.scene(), moves[k].object);
        startTransform.push_back(from);
        center.push_back(about);
    }
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
            update.deadlineSeconds = record.targetSeconds;
        }
        const double t = double(f) / frames;
        if (!moves.empty()) {
            std::vector<std::pair<std::string, glm::dmat4>> frame;
            for (std::size_t k = 0; k < moves.size(); ++k)
                frame.emplace_back(moves[k].object, moves[k].motion.at(t, center[k], startTransform[k]));
            record.stats = engine.moveObjects(frame, update);
        }
        if (!edits.empty()) {
            std::vector<Engine::MaterialEdit> frameEdits;
            for (std::size_t k = 0; k < edits.size(); ++k) {
                Engine::MaterialEdit& e = frameEdits.emplace_back(Engine::MaterialEdit{edits[k].object, {}, {}});
                if (edits[k].emission) e.emission = glm::mix(startOf[k].emission, *edits[k].emission, t);
                if (edits[k].reflectance) e.reflectance = glm::mix(startOf[k].reflectance, *edits[k].reflectance, t);
            }
            // What the move left of the frame's budget.
            UpdateSettings left = update;
            if (update.budget) left.budget = *update.budget - std::min(*update.budget, record.stats.spent);
            if (update.deadlineSeconds) left.deadlineSeconds = *update.deadlineSeconds - record.stats.totalSeconds;
            try {
                addFrame(record.stats, engine.editMaterials(frameEdits, left));
            } catch (const std::invalid_argument& error) {
                throw std::runtime_error("frame " + std::to_string(f) + ": " + error.what());
            }
        }
        if (moves.empty()) record.stats.budget = update.budget.value_or(kUnlimited);
        // A frame whose edits leave nothing emitting has a black full solve:
        // no error relative to it is measured (it would divide by its mean
        // of 0). Its samples are left empty; the frame says so.
        const bool black = references && !engine.scene().hasEmitter();
        if (black && references->samples.size() < std::size_t(f)) {
            std::fprintf(stderr,
                         "note: frame %d: nothing emits light, so its full solve is black; no error is measured "
                         "against it\n",
                         f);
            references->seconds.push_back(0.0);
            references->samples.emplace_back();
            references->fullConverged.push_back(1);
            if (references->convergedEpsilon) {
                references->convergedSeconds.push_back(0.0);
                references->converged.emplace_back();
            }
        }
        if (references && !black) {
            if (references->samples.size() < std::size_t(f)) {
                const auto t = std::chrono::steady_clock::now();
                Engine full(engine.scene(), settings);
                const SolveStats& st = full.solve(progressOnStderr("frame " + std::to_string(f) + " full solve"));
                // Its error is still measured, and said to be against a
                // solve that did not converge (a reference left oscillating
                // once read 679% rms).
                if (!st.converged)
                    std::fprintf(stderr, "warning: the full solve of frame %d did not converge: %s\n", f,
                                 whyNotConverged(st).c_str());
                references->seconds.push_back(secondsSince(t));
                references->samples.push_back(full.samples());
                references->fullConverged.push_back(st.converged);
            }
            record.fullSolveSeconds = references->seconds[f - 1];
            record.fullSolveConverged = references->fullConverged[f - 1];
            record.error = compareSamples(engine.samples(), references->samples[f - 1]);
            if (references->convergedEpsilon) {
                if (references->converged.size() < std::size_t(f)) {
                    const auto t = std::chrono::steady_clock::now();
                    EngineSettings finer = settings;
                    finer.epsilon = *references->convergedEpsilon;
                    Engine converged(engine.scene(), finer);
                    const SolveStats& st =
                        converged.solve(progressOnStderr("frame " + std::to_string(f) + " reference solve"));
                    if (!st.converged)
                        std::fprintf(stderr, "warning: the reference of frame %d (epsilon %g) did not converge: %s\n", f,
                                     finer.epsilon, whyNotConverged(st).c_str());
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
