#pragma once
// The face of the radiosity engine for the programs: build the hierarchy of a
// scene, solve it, and hand out immutable snapshots and statistics.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/Scene.h"
#include "radiosity/Settings.h"
#include "radiosity/Snapshot.h"
#include "radiosity/Stats.h"

namespace rad {

// How far a solve is (Engine::solve).
struct SolveProgress {
    // What it is doing: "round 2: refining", "round 2: sweep 6, change
    // 0.013", "round 2: refined 1234 links, 56789 links in all, 6 sweeps,
    // change 0.0016", "final solve: sweep 2, ...", "done: 4 rounds, 19 sweeps".
    std::string line;
    // The share of the solve's time done, in [0, 1]: never decreasing from
    // one call to the next of one solve, 1 at the end (only there).
    double fraction = 0.0;
    // The time left, estimated from the decay of refinement and of the
    // sweeps measured so far (the model: SolveClock in Engine.cpp); finite
    // and >= 0. Absent until it rests on measurements rather than guesses
    // (usually from the second round on).
    std::optional<double> secondsLeft;
};

class Engine {
public:
    // Throws SceneError for a scene that cannot be solved (nothing emits) and
    // IndexRangeOverflow when the area threshold is too small to number.
    Engine(Scene scene, const EngineSettings& settings);
    ~Engine();
    Engine(const Engine&) = delete;
    Engine& operator=(const Engine&) = delete;

    using Progress = std::function<void(const SolveProgress&)>;
    // Refines and solves to convergence (paper sec. 5: "no more links can be
    // refined for the given error threshold, and the energy balance has been
    // computed using all links"). `progress` is called as each refinement
    // round starts and ends, during the sweeps of each solve (at most ten
    // times a second) and once at the end with fraction 1; an exception it
    // throws leaves the solve (the engine is then unsolved, to be discarded).
    const SolveStats& solve(const Progress& progress = {});

    // The dynamic object (the one moveDynamicObject moves): the first object
    // marked dynamic in the scene, until another is chosen.
    std::optional<std::uint32_t> dynamicObject() const;
    // Chooses any object with polygons as the dynamic one. It joins the
    // dynamic visibility layer, where every object chosen before stays. Its
    // cluster is attached to the root if it is not there yet (see
    // update/Reinsertion.h: only its own links and those of its former
    // ancestor clusters change), then the visibility of the links around it is
    // split again by a line-space traversal, not by a re-solve. Objects marked
    // dynamic in the file start under the root, so choosing them costs the
    // traversal only; choosing one chosen before costs nothing. Throws std::invalid_argument naming the
    // object when there is no such object or it has no polygons.
    FrameStats setDynamicObject(const std::string& name, const UpdateSettings& settings = {});
    // Moves the dynamic object to a rigid world transform (its transform in the
    // file is the starting one) and updates the solution incrementally.
    // Throws std::invalid_argument for a non-rigid or non-finite transform.
    FrameStats moveDynamicObject(const glm::dmat4& worldFromLocal, const UpdateSettings& settings = {});
    // Moves several objects in one frame, each to a rigid world transform
    // (as moveDynamicObject does one): one line-space traversal finds the
    // links any of them touched. Every object chosen (by setDynamicObject or
    // here) stays in the dynamic visibility layer, so moving one chosen
    // before costs no new split of the layers; an object not chosen yet is
    // chosen first. Throws std::invalid_argument naming the object for an
    // unknown one, one given twice, or a non-rigid transform. On a deadline
    // that cannot leave the line-space traversal the time it last took, the
    // move is deferred (FrameStats::deferred): the objects move, their links
    // wait, and the next frame with the time, or refinePending, updates
    // them for one move from where they were last updated.
    FrameStats moveObjects(const std::vector<std::pair<std::string, glm::dmat4>>& moves,
                           const UpdateSettings& settings = {});
    // What moveObjects checks of one move, before or after the solve:
    // throws std::invalid_argument naming the object or light when there is
    // none of that name, when the motion from where it stands is not finite
    // and rigid, or when it would take it more than 1,000 times the scene's
    // size from the scene as loaded (its rays could not be traced there).
    void checkMove(const std::string& name, const glm::dmat4& worldFromLocal) const;

    // Changes the emission and/or the reflectance of one object (every
    // surface element of its polygons, and the object's own copy of its
    // material in the scene) and updates the solution without a new solve:
    // a partial push-pull from its elements, further bounces through the
    // links leaving everything that changed, and refinement that follows the
    // light, within the settings' budget. Emission: each channel in
    // [0, kMaxEmission] (Scene.h). Reflectance: each channel in [0, 1], values above
    // kMaxReflectance (Gltf.h) read as it. Throws std::invalid_argument naming
    // the object and the value otherwise, or for an unknown object.
    FrameStats editMaterial(const std::string& object, const std::optional<glm::dvec3>& emission,
                            const std::optional<glm::dvec3>& reflectance, const UpdateSettings& settings = {});
    // Several objects' edits in one frame: one push-pull, one stepping of
    // the oracles, whatever the number of objects.
    struct MaterialEdit {
        std::string object;
        std::optional<glm::dvec3> emission;
        std::optional<glm::dvec3> reflectance;
        // Not empty: the object's polygons take these materials back (what
        // objectMaterials gave before an edit: an undo), and emission and
        // reflectance are not used. An edit sets every polygon of an object
        // to one value, so taking back an edit of an object of several
        // materials needs this.
        std::vector<std::uint32_t> restore{};
    };
    FrameStats editMaterials(const std::vector<MaterialEdit>& edits, const UpdateSettings& settings = {});
    // The material (index in scene().materials) of each of the object's
    // polygons, in order; empty for a punctual light. Edits add materials
    // and never remove one, so this is the object's whole look.
    std::vector<std::uint32_t> objectMaterials(const std::string& object) const;
    // Refines, within the settings' budget and without motion, the links an
    // earlier budget left coarse; with nothing left to refine, gives back the
    // growth slack of the link lists.
    FrameStats refinePending(const UpdateSettings& settings = {});
    // The link-update budget that fits a target frame time, from the cost of
    // link updates measured on the frames so far (sec. 6.1).
    std::size_t budgetFor(double targetSeconds) const;

    // Consistency check (sec. 6.1): the number of active links that carry the
    // light from a point of polygon `from` to a point of polygon `to` (each
    // given by its parametric (u,v), as in HElement::param). A complete
    // covering of line space has exactly one for every pair of points that
    // face each other.
    std::size_t linksCarrying(std::uint32_t from, const glm::dvec2& uvFrom, std::uint32_t to,
                              const glm::dvec2& uvTo) const;

    // The power balance and the memory of the current solution (after moves too).
    EnergyBalance energy() const;
    MemoryStats memory() const;
    std::size_t linkCount() const;  // active links and p-links

    // The lit mesh; with overlays, also the links the last move modified
    // (yellow lines between the centres of their H-elements) and the outlines
    // of the elements it marked changed (red), in MeshSnapshot's lines.
    MeshSnapshot snapshot(SnapshotOverlays overlays = {}) const;
    // The lit mesh made anew from the current solution, every polygon
    // meshed: what snapshot() builds frame by frame from the polygons that
    // changed must equal it, once no polygon waits (FrameStats::unmeshed).
    MeshSnapshot snapshotFromScratch() const;

    // The object whose surface a ray meets first (for picking), or nullopt.
    std::optional<std::uint32_t> pick(const glm::dvec3& origin, const glm::dvec3& direction) const;
    // Leaf radiosity at fixed points of every input polygon (see Sampling.h).
    RadiositySamples samples() const;
    std::vector<ObjectRadiosity> objectRadiosity() const;
    const Scene& scene() const;
    const SolveStats& stats() const;

private:
    // allowDeferral: false when catching up a deferred move (refinePending).
    FrameStats moveObjects(const std::vector<std::pair<std::string, glm::dmat4>>& moves,
                           const UpdateSettings& settings, bool allowDeferral);
    struct State;
    std::unique_ptr<State> state_;
};

}  // namespace rad
