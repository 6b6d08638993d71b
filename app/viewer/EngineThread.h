#pragma once
// The viewer's engine thread. It owns the Engine (nothing else touches it),
// takes commands from a queue and publishes an immutable ViewerSnapshot after
// every update; the render loop reads the newest one and never waits.
//
//   EngineThread engine(std::move(scene), settings, options);   // starts and solves
//   engine.post(SetTransform{object, worldFromLocal});           // from the UI
//   std::shared_ptr<const ViewerSnapshot> s = engine.latest();   // any time
//   // the destructor sends Quit and joins.

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/Engine.h"

namespace rad::viewer {

// One of the scene's objects, or one of its punctual lights: the snapshot
// lists the objects first (their indices in Scene::objects) and then the
// lights (light i at objects.size() + i, `light` set). Commands and the
// selection name either by that index.
struct ObjectInfo {
    std::string name;
    // Has polygons, or is a light: the gizmo may move it (any object can
    // become the dynamic one; those marked dynamic in the file start under
    // the root).
    bool movable = false;
    glm::dmat4 worldFromLocal{1.0};
    Aabb bounds;
    // Its first polygon's material now (edits included): what the panel's
    // colour and light controls start from.
    glm::dvec3 emission{0.0};
    glm::dvec3 reflectance{0.0};
    // Each polygon's material now (Engine::objectMaterials): what an undo of
    // an edit restores. Null for a light; shared until an edit changes it.
    std::shared_ptr<const std::vector<std::uint32_t>> materials{};
    std::vector<std::uint32_t> nodePath{};  // Object::nodePath; empty for a light
    bool light = false;  // a punctual light: bounds is its position, emission its intensity
    bool spot = false;   // a spot light: it points down its local -Z
};

struct UpdateSample {
    double time = 0.0;     // seconds since the engine thread started
    double seconds = 0.0;  // the update's total time
};

struct ViewerSnapshot {
    std::uint64_t version = 0;  // increases with every publication
    std::shared_ptr<const MeshSnapshot> mesh;  // null before the first solve ends
    bool solving = true;
    std::string progress;  // the solve's last progress line
    double progressFraction = 0.0;      // of the solve done (SolveProgress::fraction)
    std::optional<double> secondsLeft;  // the solve's estimate of its time left, once it has one
    std::string error;     // why the engine could not solve, if it could not
    SolveStats solve;
    FrameStats frame;        // the last update (move or pending refinement)
    std::uint64_t moves = 0; // transforms applied so far
    // Solved, and no earlier frame left anything stale, coarse, unsent or
    // pending: the picture will not change until the next command.
    bool caughtUp = false;
    std::size_t budget = 0;  // link updates allowed per frame at the target rate
    double targetFps = 0.0;
    double epsilon = 0.0;
    MemoryStats memory;
    std::size_t linkCount = 0;
    SnapshotOverlays overlays;
    std::vector<ObjectInfo> objects;
    std::optional<std::uint32_t> selected;  // the object last clicked: the gizmo's
    // Every object selected (shift+click adds one); the gizmo moves them together.
    std::vector<std::uint32_t> selection;
    std::string selectionNote;  // e.g. why the selection cannot move
    std::vector<UpdateSample> updateTimes;  // moves of the last seconds, oldest first
    // What the engine thread's publications with a picture take (copying
    // the lit mesh and the objects' boxes for the window; smoothed, a dearer
    // one at once), and the deadline its frames get: the target frame time
    // less that, at least half of it (0 without a target frame rate).
    double publishSeconds = 0.0;
    double frameSeconds = 0.0;
};

// Commands.
struct SetTransform {
    std::uint32_t object = 0;
    glm::dmat4 worldFromLocal{1.0};
};
struct SelectObject {
    std::string name;  // an object or a light; empty: select nothing
};
struct PickObject {
    glm::dvec3 origin{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0};
    bool add = false;  // shift+click: add to the selection (again: take it out)
};
// Several objects moved in one frame (Engine::moveObjects).
struct SetTransforms {
    std::vector<SetTransform> moves;
};
struct SetTargetFps {
    double fps = 30.0;
};
struct SetEpsilon {
    double epsilon = EngineSettings{}.epsilon;
};
struct SetOverlays {
    SnapshotOverlays overlays;
};
// Engine::editMaterial: the object's emission and/or reflectance.
struct EditMaterial {
    std::string object;
    std::optional<glm::dvec3> emission;
    std::optional<glm::dvec3> reflectance;
    // Not empty: the materials the object's polygons take back (an undo;
    // Engine::MaterialEdit::restore, from ObjectInfo::materials).
    std::vector<std::uint32_t> restore{};
};
// The P key: the selection widened to every object under the glTF node the
// selected objects share, or under its parent when that is selected already
// (viewer/SelectionWidening.h). The gizmo stays on its object.
struct WidenSelection {};
struct Quit {};
using Command = std::variant<SetTransform, SetTransforms, SelectObject, PickObject, SetTargetFps, SetEpsilon,
                            SetOverlays, EditMaterial, WidenSelection, Quit>;

struct EngineThreadOptions {
    double targetFps = 30.0;
    SnapshotOverlays overlays;
    std::string select;  // object (or light) to select once solved
    // Called on the engine thread with one line per transform it receives,
    // and "engine: caught up after M moves" when it has nothing left to do
    // (--log-transforms); empty: silent.
    std::function<void(const std::string&)> log;
    double historySeconds = 10.0;  // how much of updateTimes to keep
};

class EngineThread {
  public:
    EngineThread(Scene scene, const EngineSettings& settings, EngineThreadOptions options = {});
    ~EngineThread();  // posts Quit and joins
    EngineThread(const EngineThread&) = delete;
    EngineThread& operator=(const EngineThread&) = delete;

    void post(Command command);
    std::shared_ptr<const ViewerSnapshot> latest() const;
    // Blocks until a snapshot with version > after exists or timeoutSeconds
    // pass (for tests and the headless stress run; the render loop never calls it).
    std::shared_ptr<const ViewerSnapshot> waitNewer(std::uint64_t after, double timeoutSeconds) const;
    void stop();  // Quit and join; idempotent

  private:
    struct Worker;
    void run();

    std::unique_ptr<Worker> worker_;  // engine-thread-only state
    mutable std::mutex queueMutex_;
    std::condition_variable queueCv_;
    std::deque<Command> queue_;
    bool quit_ = false;  // under queueMutex_

    mutable std::mutex snapshotMutex_;
    mutable std::condition_variable snapshotCv_;
    std::shared_ptr<const ViewerSnapshot> latest_;
    std::thread thread_;
};

}  // namespace rad::viewer
