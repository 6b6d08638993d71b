#include "viewer/EngineThread.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <map>
#include <sstream>
#include <stdexcept>

#include "viewer/SelectionWidening.h"

namespace rad::viewer {
namespace {

struct Cancelled {};

// 'name' and the rest of a message (an ostream: GCC 12 reports false
// -Wrestrict errors on small string concatenations once inlined).
std::string quoted(const std::string& name, const std::string& rest) {
    std::ostringstream out;
    out << '\'' << name << '\'' << rest;
    return out.str();
}  // thrown from the solve's progress callback on Quit

template <class... F>
struct Overloaded : F... {
    using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace

// Everything only the engine thread touches.
struct EngineThread::Worker {
    Scene original;  // as loaded: a new epsilon solves it again
    EngineSettings settings;
    EngineThreadOptions options;
    std::unique_ptr<Engine> engine;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();

    bool solving = true;
    std::string progress;
    double progressFraction = 0.0;       // of the running solve
    std::optional<double> secondsLeft;  // its estimate, once it has one
    std::string error;
    FrameStats frame;
    // What a publication with a picture takes (copying the lit mesh and the
    // objects' boxes for the window): a dearer one counts at once, else
    // smoothed by halves.
    double publishSeconds = 0.0;
    ObjectBoxes boxes;  // the boxes a picture lists, measured again only for what moved
    std::uint64_t moves = 0;
    std::optional<std::uint64_t> caughtUpLogged;  // `moves` at the last "caught up" line
    std::uint64_t version = 0;
    double targetFps = 30.0;
    SnapshotOverlays overlays;
    std::optional<std::uint32_t> selected;
    std::vector<std::uint32_t> selection;
    std::string selectionNote;
    std::map<std::uint32_t, glm::dmat4> moved;  // transforms applied, to re-apply after a re-solve
    std::vector<EditMaterial> edits;            // likewise, in order
    // ObjectInfo::materials per object, made again after an edit or a solve.
    std::vector<std::shared_ptr<const std::vector<std::uint32_t>>> materials;
    std::deque<UpdateSample> history;

    // Earlier frames left work for idle time.
    bool behind() const { return engine && frame.pending + frame.stale + frame.unsent + frame.deferred + frame.unmeshed + frame.finer > 0; }
    double now() const {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    // Objects and lights share one numbering (ObjectInfo): the objects,
    // then the lights.
    const Scene& scene() const { return engine ? engine->scene() : original; }
    std::optional<std::uint32_t> lightOf(std::uint32_t id) const {
        const Scene& s = scene();
        if (id < s.objects.size() || id - s.objects.size() >= s.lights.size()) return std::nullopt;
        return static_cast<std::uint32_t>(id - s.objects.size());
    }
    const std::string& nameOf(std::uint32_t id) const {
        const Scene& s = scene();
        return id < s.objects.size() ? s.objects[id].name : s.lights[id - s.objects.size()].name;
    }
    bool exists(std::uint32_t id) const { return id < scene().objects.size() + scene().lights.size(); }
    std::optional<std::uint32_t> find(const std::string& name) const {
        const Scene& s = scene();
        if (const auto light = s.findLight(name)) return static_cast<std::uint32_t>(s.objects.size() + *light);
        return s.findObject(name);
    }
    // A frame ends by the target frame time less what publishing its
    // picture takes (its deadline; the copy of the building floor's lit
    // mesh takes 7 ms, of `office`'s 0.1 ms), but never before half the
    // target frame time; a move frame's budget also comes from there. An
    // idle frame (catching up) works until that deadline.
    double frameSeconds() const {
        const double target = 1.0 / targetFps;
        return std::max(0.5 * target, target - publishSeconds);
    }
    UpdateSettings update(bool idle = false) const {
        UpdateSettings u;
        if (!engine || !(targetFps > 0.0)) return u;
        u.deadlineSeconds = frameSeconds();
        if (!idle) u.budget = engine->budgetFor(*u.deadlineSeconds);
        return u;
    }
};

EngineThread::EngineThread(Scene scene, const EngineSettings& settings, EngineThreadOptions options)
    : worker_(std::make_unique<Worker>()) {
    worker_->original = std::move(scene);
    worker_->settings = settings;
    worker_->targetFps = options.targetFps;
    worker_->overlays = options.overlays;
    worker_->options = std::move(options);
    auto first = std::make_shared<ViewerSnapshot>();
    first->targetFps = worker_->targetFps;
    first->epsilon = settings.epsilon;
    first->overlays = worker_->overlays;
    first->progress = "starting";
    latest_ = std::move(first);
    thread_ = std::thread([this] { run(); });
}

EngineThread::~EngineThread() { stop(); }

void EngineThread::stop() {
    {
        std::lock_guard lock(queueMutex_);
        quit_ = true;
        queue_.emplace_back(Quit{});
    }
    queueCv_.notify_all();
    if (thread_.joinable()) thread_.join();
}

void EngineThread::post(Command command) {
    {
        std::lock_guard lock(queueMutex_);
        if (std::holds_alternative<Quit>(command)) quit_ = true;
        queue_.push_back(std::move(command));
    }
    queueCv_.notify_all();
}

std::shared_ptr<const ViewerSnapshot> EngineThread::latest() const {
    std::lock_guard lock(snapshotMutex_);
    return latest_;
}

std::shared_ptr<const ViewerSnapshot> EngineThread::waitNewer(std::uint64_t after,
                                                              double timeoutSeconds) const {
    std::unique_lock lock(snapshotMutex_);
    snapshotCv_.wait_for(lock, std::chrono::duration<double>(timeoutSeconds),
                         [&] { return latest_->version > after; });
    return latest_;
}

void EngineThread::run() {
    Worker& w = *worker_;
    auto quitRequested = [this] {
        std::lock_guard lock(queueMutex_);
        return quit_;
    };

    auto publish = [&](bool withMesh) {
        const auto began = std::chrono::steady_clock::now();
        auto s = std::make_shared<ViewerSnapshot>();
        s->version = ++w.version;
        s->solving = w.solving;
        s->progress = w.progress;
        s->progressFraction = w.progressFraction;
        s->secondsLeft = w.secondsLeft;
        s->error = w.error;
        s->frame = w.frame;
        s->moves = w.moves;
        s->caughtUp = w.engine && !w.solving && w.error.empty() && !w.behind();
        if (s->caughtUp && w.options.log && w.caughtUpLogged != w.moves) {
            w.options.log("engine: caught up after " + std::to_string(w.moves) + " moves");
            w.caughtUpLogged = w.moves;
        }
        s->targetFps = w.targetFps;
        s->epsilon = w.settings.epsilon;
        s->overlays = w.overlays;
        s->selected = w.selected;
        s->selection = w.selection;
        s->selectionNote = w.selectionNote;
        s->updateTimes.assign(w.history.begin(), w.history.end());
        const Scene& scene = w.engine ? w.engine->scene() : w.original;
        for (std::uint32_t o = 0; o < scene.objects.size(); ++o) {
            const Object& object = scene.objects[o];
            ObjectInfo info{object.name, object.polygonCount > 0, object.worldFromLocal, w.boxes.of(scene, o)};
            if (object.polygonCount > 0) {
                const Material& m = scene.materials[scene.polygons[object.firstPolygon].material];
                info.emission = m.emission;
                info.reflectance = m.reflectance;
                if (w.engine) {
                    if (w.materials.size() != scene.objects.size()) w.materials.assign(scene.objects.size(), nullptr);
                    if (!w.materials[o])
                        w.materials[o] = std::make_shared<const std::vector<std::uint32_t>>(w.engine->objectMaterials(object.name));
                    info.materials = w.materials[o];
                }
            }
            info.nodePath = object.nodePath;
            s->objects.push_back(std::move(info));
        }
        for (const PunctualLight& light : scene.lights) {
            ObjectInfo info{light.name, true, light.worldFromLocal, {}};
            info.bounds.extend(light.position);
            info.emission = light.intensity;
            info.light = true;
            info.spot = light.type == PunctualLight::Type::Spot;
            s->objects.push_back(std::move(info));
        }
        if (w.engine && !w.solving && w.error.empty()) {
            s->solve = w.engine->stats();
            s->memory = w.engine->memory();
            s->linkCount = w.engine->linkCount();
            s->budget = w.update().budget.value_or(kUnlimited);
            if (withMesh) s->mesh = std::make_shared<const MeshSnapshot>(w.engine->snapshot(w.overlays));
        }
        if (s->mesh) {
            const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
            w.publishSeconds = std::max(took, 0.5 * (w.publishSeconds + took));
        }
        s->publishSeconds = w.publishSeconds;
        s->frameSeconds = w.update().deadlineSeconds.value_or(0.0);  // what the next frame gets
        {
            std::lock_guard lock(snapshotMutex_);
            if (!s->mesh && latest_) s->mesh = latest_->mesh;  // keep showing the last picture
            latest_ = std::move(s);
        }
        snapshotCv_.notify_all();
    };

    auto fail = [&](const std::string& message) {
        w.error = message;
        w.solving = false;
        publish(false);
    };

    // `add` (shift+click): the object joins the selection, or leaves it if
    // it was in; otherwise it is the whole selection.
    auto select = [&](std::optional<std::uint32_t> object, bool add = false) {
        const bool wasIn = object && std::find(w.selection.begin(), w.selection.end(), *object) != w.selection.end();
        if (!add) w.selection.clear();
        if (add && wasIn) {
            std::erase(w.selection, *object);
            w.selected = w.selection.empty() ? std::nullopt : std::optional(w.selection.back());
            return;
        }
        w.selected = object;
        w.selectionNote.clear();
        if (!object) return;
        // Not in the selection here: added, or the selection was cleared (a
        // plain click on one of several selected objects selects it alone).
        if (w.lightOf(*object)) {  // a light: not in the hierarchy, nothing to attach
            w.selection.push_back(*object);
            return;
        }
        const Object& o = w.engine->scene().objects[*object];
        if (o.polygonCount > 0) w.selection.push_back(*object);
        if (o.polygonCount == 0) {
            w.selectionNote = quoted(o.name, " has no polygons: it cannot be moved");
            return;
        }
        // An object not marked dynamic has its cluster attached to the root
        // here (paper sec. 3.3); the panel shows what that cost.
        if (w.engine->dynamicObject() != object) w.frame = w.engine->setDynamicObject(o.name, w.update());
        if (w.frame.reinsertion.created > 0) {
            std::ostringstream note;
            note << " attached to the root: " << w.frame.reinsertion.removed << " links removed, "
                 << w.frame.reinsertion.created << " created";
            w.selectionNote = quoted(o.name, note.str());
        }
    };

    // WidenSelection: every object under the node the selection shares (or
    // its parent's); each joins as shift+click would add it.
    auto widen = [&] {
        const Scene& scene = w.engine->scene();
        std::vector<std::optional<NodePath>> paths;
        for (const Object& o : scene.objects)
            paths.push_back(o.polygonCount > 0 ? std::optional(o.nodePath) : std::nullopt);
        for (const PunctualLight& l : scene.lights) paths.push_back(l.nodePath);
        const std::optional<Widening> wider = widenSelection(paths, w.selection);
        if (!wider) {
            const bool anObject = std::any_of(w.selection.begin(), w.selection.end(),
                                              [&](std::uint32_t o) { return o < scene.objects.size(); });
            w.selectionNote = !anObject ? "nothing to widen: select an object (a light has no glTF node path)"
                                        : "nothing to widen: every object is selected";
            return;
        }
        const std::optional<std::uint32_t> gizmo = w.selected;
        std::size_t removed = 0, created = 0;
        w.frame.reinsertion = {};
        for (std::uint32_t o : wider->selection)
            if (std::find(w.selection.begin(), w.selection.end(), o) == w.selection.end()) {
                select(o, true);
                removed += w.frame.reinsertion.removed;
                created += w.frame.reinsertion.created;
                w.frame.reinsertion = {};
            }
        w.selected = gizmo ? gizmo : std::optional(wider->selection.front());
        std::ostringstream note;
        note << wider->selection.size() << " selected: everything under ";
        if (wider->prefix.empty())
            note << "the scene's roots";
        else
            note << "glTF node " << wider->prefix.back();
        if (created > 0) note << " (attached to the root: " << removed << " links removed, " << created << " created)";
        w.selectionNote = note.str();
    };

    // Moves objects in one frame (Engine::moveObjects; an object not chosen
    // yet is chosen first), logging each transform for the tests.
    auto applyMoves = [&](const std::vector<SetTransform>& transforms) {
        const Scene& scene = w.engine->scene();
        std::vector<std::pair<std::string, glm::dmat4>> moves;
        for (const SetTransform& m : transforms) {
            if (!w.exists(m.object)) continue;
            const std::string& name = w.nameOf(m.object);
            if (w.options.log) {
                std::ostringstream line;
                line << "engine: transform " << name << " translation " << m.worldFromLocal[3][0] << ' '
                     << m.worldFromLocal[3][1] << ' ' << m.worldFromLocal[3][2];
                w.options.log(line.str());
            }
            // A light moves by name too (its transform: scene.lights[i].worldFromLocal).
            if (w.lightOf(m.object) || scene.objects[m.object].polygonCount > 0) moves.emplace_back(name, m.worldFromLocal);
        }
        if (moves.empty()) return;
        w.frame = w.engine->moveObjects(moves, w.update());
        for (const SetTransform& m : transforms) w.moved[m.object] = m.worldFromLocal;
        // A light under a moved object's node went with it
        // (PunctualLight::object): kept where it is now, for a re-solve.
        for (std::uint32_t l = 0; l < scene.lights.size(); ++l)
            if (l < w.original.lights.size() && scene.lights[l].worldFromLocal != w.original.lights[l].worldFromLocal)
                w.moved[static_cast<std::uint32_t>(scene.objects.size() + l)] = scene.lights[l].worldFromLocal;
        ++w.moves;
        w.history.push_back({w.now(), w.frame.totalSeconds});
        while (!w.history.empty() && w.history.front().time < w.now() - w.options.historySeconds) w.history.pop_front();
    };

    // Builds and solves the engine; re-applies earlier moves and the selection.
    auto solveEngine = [&]() -> bool {
        w.solving = true;
        w.progress = "building the hierarchy";
        w.progressFraction = 0.0;
        w.secondsLeft.reset();
        publish(false);
        try {
            w.engine.reset();
            w.engine = std::make_unique<Engine>(Scene(w.original), w.settings);
            w.engine->solve([&](const SolveProgress& p) {
                if (quitRequested()) throw Cancelled{};
                w.progress = p.line;
                w.progressFraction = p.fraction;
                w.secondsLeft = p.secondsLeft;
                publish(false);
            });
            const auto current = w.selected;
            const std::vector<std::uint32_t> selection = w.selection;
            // Objects and lights, each to where it was moved last.
            std::vector<std::pair<std::string, glm::dmat4>> moves;
            for (const auto& [id, m] : w.moved) moves.emplace_back(w.nameOf(id), m);
            if (!moves.empty()) w.frame = w.engine->moveObjects(moves);
            for (const EditMaterial& e : w.edits)
                w.frame = w.engine->editMaterials({{e.object, e.emission, e.reflectance, e.restore}});
            w.materials.clear();
            w.solving = false;
            w.progress = w.engine->stats().converged ? "solved" : w.engine->stats().message;
            w.selection.clear();
            for (std::uint32_t o : selection) select(o, true);
            if (selection.empty()) select(current);
            w.selected = current;  // the gizmo's object again
            return true;
        } catch (const Cancelled&) {
            return false;
        } catch (const std::exception& e) {
            w.engine.reset();
            fail(e.what());
            return false;
        }
    };

    if (!solveEngine()) return;
    if (!w.options.select.empty()) {
        try {
            const auto object = w.find(w.options.select);
            if (!object) {
                std::string m = "--select: no object named '";
                m += w.options.select;
                m += "'";
                throw std::invalid_argument(m);
            }
            select(object);
        } catch (const std::exception& e) {
            w.selectionNote = e.what();
        }
    }
    publish(true);

    for (;;) {
        std::deque<Command> commands;
        {
            std::unique_lock lock(queueMutex_);
            if (queue_.empty() && !w.behind()) queueCv_.wait(lock, [&] { return !queue_.empty(); });
            commands.swap(queue_);
        }
        if (commands.empty()) {  // idle: update what earlier frames left stale, coarse or unsent
            const std::size_t before = w.frame.pending + w.frame.stale + w.frame.unmeshed;
            try {
                w.frame = w.engine->refinePending(w.update(true));
            } catch (const std::exception& e) {
                w.selectionNote = e.what();
                w.frame.pending = w.frame.stale = w.frame.unsent = w.frame.deferred = w.frame.unmeshed = w.frame.finer = 0;
            }
            if (w.frame.pending + w.frame.stale + w.frame.unmeshed >= before && w.frame.spent == 0 &&
                w.frame.bounces == 0 && w.frame.shaftTests == 0)
                w.frame.pending = w.frame.stale = w.frame.unsent = w.frame.deferred = w.frame.unmeshed = w.frame.finer = 0;  // no progress: stop
            publish(true);
            continue;
        }

        bool changed = false;
        for (std::size_t i = 0; i < commands.size(); ++i) {
            const Command& command = commands[i];
            if (std::holds_alternative<Quit>(command)) return;
            if (!w.engine) continue;  // the solve failed: nothing to do but quit
            try {
                std::visit(
                    Overloaded{
                        [&](const SetTransform& t) {
                            // Consecutive transforms of one object: only the newest counts.
                            if (i + 1 < commands.size())
                                if (const auto* next = std::get_if<SetTransform>(&commands[i + 1]);
                                    next && next->object == t.object)
                                    return;
                            applyMoves({t});
                            changed = true;
                        },
                        [&](const SelectObject& s) {
                            if (s.name.empty()) {
                                select(std::nullopt);
                            } else {
                                const auto object = w.find(s.name);
                                if (!object) {
                                    std::string m = "no object named '";
                                    m += s.name;
                                    m += "'";
                                    throw std::invalid_argument(m);
                                }
                                select(object);
                            }
                            changed = true;
                        },
                        [&](const PickObject& p) {
                            const auto picked = w.engine->pick(p.origin, p.direction);
                            if (!p.add || picked) select(picked, p.add);
                            changed = true;
                        },
                        [&](const SetTransforms& t) {
                            // Consecutive moves of the same objects: only the newest counts.
                            if (i + 1 < commands.size())
                                if (const auto* next = std::get_if<SetTransforms>(&commands[i + 1]);
                                    next && next->moves.size() == t.moves.size() &&
                                    std::equal(t.moves.begin(), t.moves.end(), next->moves.begin(),
                                               [](const SetTransform& a, const SetTransform& b) { return a.object == b.object; }))
                                    return;
                            applyMoves(t.moves);
                            changed = true;
                        },
                        [&](const SetTargetFps& f) {
                            w.targetFps = f.fps;
                            changed = true;
                        },
                        [&](const SetEpsilon& e) {
                            if (e.epsilon == w.settings.epsilon) return;
                            w.settings.epsilon = e.epsilon;
                            if (!solveEngine()) throw Cancelled{};
                            changed = true;
                        },
                        [&](const SetOverlays& o) {
                            w.overlays = o.overlays;
                            changed = true;
                        },
                        [&](const EditMaterial& e) {
                            // Consecutive edits of one object: only the newest counts
                            // (unless it leaves a value the earlier one sets; a restore sets all).
                            if (i + 1 < commands.size())
                                if (const auto* next = std::get_if<EditMaterial>(&commands[i + 1]);
                                    next && next->object == e.object &&
                                    (!next->restore.empty() ||
                                     (e.restore.empty() && (next->emission || !e.emission) &&
                                      (next->reflectance || !e.reflectance))))
                                    return;
                            w.frame = w.engine->editMaterials({{e.object, e.emission, e.reflectance, e.restore}}, w.update());
                            w.edits.push_back(e);
                            w.materials.clear();
                            changed = true;
                        },
                        [&](const WidenSelection&) {
                            widen();
                            changed = true;
                        },
                        [&](const Quit&) {},
                    },
                    command);
            } catch (const Cancelled&) {
                return;
            } catch (const std::exception& e) {
                w.selectionNote = e.what();
                changed = true;
            }
        }
        if (changed) publish(true);
    }
}

}  // namespace rad::viewer
