#pragma once
// Running a scripted motion through the engine: what `animate` and `sweep`
// share. The total motion is applied in N equal steps.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/Engine.h"

namespace rad::cli {

struct Motion {
    glm::dvec3 translation{0.0};
    struct Rotation {
        glm::dvec3 axis;  // unit
        double degrees;
    };
    std::vector<Rotation> rotations;  // about the object's bounding-box centre at the start
    // The object's transform at fraction f of the motion.
    glm::dmat4 at(double f, const glm::dvec3& center, const glm::dmat4& start) const;
};

// One object's total motion.
struct ObjectMove {
    std::string object;
    Motion motion;
};

// A script's edit of one object's light or colour (Engine::editMaterial):
// each given value goes linearly, over the frames, from the object's value in
// the file (its first polygon's material) to this one.
struct Edit {
    std::string object;
    std::optional<glm::dvec3> emission;
    std::optional<glm::dvec3> reflectance;
};

// How the link-update budget of each frame is set: none (unlimited), a fixed
// number of link updates, or from a target frame rate (sec. 6.1).
struct BudgetControlSetting {
    std::optional<std::size_t> budget;
    std::optional<double> targetFps;
};

struct FrameRecord {
    FrameStats stats;
    std::optional<double> targetSeconds;
    std::optional<double> fullSolveSeconds;
    bool fullSolveConverged = true;  // false: `error` is against a solve that did not converge
    std::optional<SolutionError> error;  // against a from-scratch solve of the frame
    // Against the converged reference of the frame (References::convergedEpsilon).
    std::optional<SolutionError> errorVsConverged;
};

struct AnimationRun {
    double solveSeconds = 0.0;
    SolveStats initial;
    // Choosing the object after the solve: for one not marked dynamic in
    // the file, its cluster is attached to the root and relinked.
    FrameStats selection;
    bool markedDynamic = false;
    std::vector<FrameRecord> frames;
};

// Reference solutions of each frame, computed once and shared by runs of the
// same motion at the same settings.
struct References {
    std::vector<RadiositySamples> samples;
    std::vector<double> seconds;
    std::vector<std::uint8_t> fullConverged;  // whether each frame's full solve converged
    // With an epsilon: each frame solved again from scratch at that finer
    // epsilon, the converged answer the user should see.
    std::optional<double> convergedEpsilon;
    std::vector<RadiositySamples> converged;
    std::vector<double> convergedSeconds;
};

// Solves `scene`, chooses the moving objects (the first is the report's
// `selection`) and plays their motions and the edits, each frame its share
// of each; every frame moves all the objects at once (Engine::moveObjects).
// With `references` (empty on the first call, filled by it) every frame is
// compared with a from-scratch solve, and with its converged reference when
// one is asked for. `onFrame` sees the engine after each
// frame, with its record (frame 0: the initial solution, with the choice of
// the object as its record). Throws on bad input.
AnimationRun runAnimation(const Scene& scene, const EngineSettings& settings, const std::vector<ObjectMove>& moves,
                          const std::vector<Edit>& edits, int frames,
                          const BudgetControlSetting& control,
                          References* references, const std::function<void(int, const Engine&, const FrameRecord*)>& onFrame = {});

double median(std::vector<double> values);
// The nearest-rank percentile (p in (0, 1]): the smallest value that at
// least p of the values do not exceed. 0 for none.
double percentile(std::vector<double> values, double p);

}  // namespace rad::cli
