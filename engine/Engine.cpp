#include "radiosity/Engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <stdexcept>
#include <set>
#include <span>
#include <sstream>

#include "geometry/RayCaster.h"
#include "radiosity/Gltf.h"
#include "hierarchy/Hierarchy.h"
#include "lights/LightLinks.h"
#include "links/Link.h"
#include "refine/ReceiverLight.h"
#include "refine/Refiner.h"
#include "refine/Surroundings.h"
#include "snapshot/Sampling.h"
#include "solve/Closure.h"
#include "solve/ClusterExposure.h"
#include "solve/Diagnosis.h"
#include "solve/EnergyAudit.h"
#include "solve/Solver.h"
#include "snapshot/RadiositySnapshot.h"
#include "update/BudgetControl.h"
#include "update/Obstacles.h"
#include "update/OracleSteps.h"
#include "update/LineSpaceUpdate.h"
#include "update/Timing.h"
#include "update/Reinsertion.h"

namespace rad {
namespace {

// The energy guard is reported where it divided by more than this: below it,
// the sums exceed one only by the point quadrature's error.
constexpr double kGuardWarningThreshold = 0.05;
// Above this share of the emitted light meeting backs the solve warns (the
// shipped scenes: 0.2% to 0.6%).
constexpr double kBackFaceWarningShare = 0.05;
// Above this share of the emitted light lost the solve warns (the shipped
// scenes: -0.4% to 1.7%, `dark-room` the most).
constexpr double kLostWarningShare = 0.1;
// Above this share of the emitted light made (a negative `lost`) the solve
// warns (the shipped scenes make at most 0.63%, `office`; of the Cycles
// references, the kitchen makes 1.4%).
constexpr double kMadeWarningShare = 0.01;
// Above this share of the emitted light leaving the scene straight from
// glowing faces the solve warns (the shipped scenes: none measured).
constexpr double kEscapingWarningShare = 0.01;
constexpr double kRoundTolerance = 3e-3;
// How far from the scene as loaded, in its sizes, an object or light may be
// moved. Rays are traced in single precision in that scene's frame
// (RayCaster::setFrame), and Embree rejects rays past about 1e18 of its
// sizes (an assertion, then an abort); at 1,000 sizes a point is still
// placed to a ten-thousandth of the scene's size.
constexpr double kReach = 1000.0;
// The least share of the emitted light an edit may leave (Engine::editMaterials).
constexpr double kLeastPowerRatio = 1e-10;

// The scene's emitted power once `edits` (checked) are made: each edited
// polygon's emission, or material, and each edited light's intensity,
// replaced. Summed afresh, not as a difference: a light dimmed to 1e-30 of
// itself would vanish in the rounding of one.
double emittedPowerAfter(const Scene& scene, const std::vector<Engine::MaterialEdit>& edits) {
    std::vector<glm::dvec3> emission(scene.polygons.size());
    for (std::size_t p = 0; p < scene.polygons.size(); ++p)
        emission[p] = scene.materials[scene.polygons[p].material].emission;
    std::vector<glm::dvec3> intensity(scene.lights.size());
    for (std::size_t l = 0; l < scene.lights.size(); ++l) intensity[l] = scene.lights[l].intensity;
    for (const Engine::MaterialEdit& e : edits) {
        if (const std::optional<std::uint32_t> light = scene.findLight(e.object)) {
            if (e.emission) intensity[*light] = *e.emission;
            continue;
        }
        const Object& o = scene.objects[*scene.findObject(e.object)];
        for (std::uint32_t p = o.firstPolygon; p < o.firstPolygon + o.polygonCount; ++p) {
            if (!e.restore.empty())
                emission[p] = scene.materials[e.restore[p - o.firstPolygon]].emission;
            else if (e.emission)
                emission[p] = *e.emission;
        }
    }
    double power = 0.0;
    for (std::size_t p = 0; p < scene.polygons.size(); ++p) power += scene.polygons[p].area() * luminance(emission[p]);
    for (std::size_t l = 0; l < scene.lights.size(); ++l) {
        PunctualLight edited = scene.lights[l];
        edited.intensity = intensity[l];
        power += edited.power();
    }
    return power;
}

double emittedPower(const Scene& scene) { return emittedPowerAfter(scene, {}); }

// Whether `to` turns (rotates, mirrors or scales) an object from `from`, or
// only translates it.
bool turnedBetween(const glm::dmat4& from, const glm::dmat4& to) {
    const glm::dmat3 turn = glm::dmat3(to) - glm::dmat3(from);
    return std::max({glm::length(turn[0]), glm::length(turn[1]), glm::length(turn[2])}) >
           1e-12 * std::max(1.0, glm::length(glm::dmat3(to)[0]));
}

// The share of the thresholds' references (emitted power, area) a point's
// surroundings make up (refine/Surroundings.h), measured with the scene's
// own rays before the hierarchy is built: the scene's, and in an open scene
// each object's for its area threshold.
ThresholdScales localThresholdScales(const Scene& scene, const EngineSettings& settings) {
    if (!settings.localThresholds || scene.polygons.empty()) return {};
    RayCaster rays;
    rays.setFrame(scene.bounds(), scene.detailCentre(), scene.detailBounds());
    std::vector<std::uint32_t> all(scene.polygons.size());
    std::iota(all.begin(), all.end(), 0u);
    rays.setLayer(Layer::Static, scene, all);
    return measureThresholdScales(scene, rays);
}

// The default area threshold, scaled.
double defaultMinArea(const Scene& scene, double scale) { return kDefaultMinAreaShare * scale * scene.area(); }

std::vector<double> objectMinAreas(const Scene& scene, const EngineSettings& settings, const ThresholdScales& scales) {
    if (settings.minArea > 0.0 || scales.objectArea.empty()) return {};
    std::vector<double> out(scales.objectArea.size());
    for (std::size_t o = 0; o < out.size(); ++o) out[o] = defaultMinArea(scene, scales.objectArea[o]);
    return out;
}

Scene checkedScene(Scene scene) {
    if (!scene.hasEmitter())
        throw SceneError(scene.sourcePath + ": nothing emits light (no material has a positive emissiveFactor "
                         "and no punctual light a positive intensity); there is nothing to solve");
    return scene;
}

}  // namespace

struct Engine::State {
    State(Scene s, const EngineSettings& settings)
        : scene(checkedScene(std::move(s))),
          settings(settings),
          scales(localThresholdScales(scene, settings)),
          scale(scales.scene),
          hierarchy(scene, settings.minArea > 0.0 ? settings.minArea : defaultMinArea(scene, scale),
                    objectMinAreas(scene, settings, scales)),
          refiner(hierarchy, links, rays,
                  RefineSettings{settings.epsilon, scale * emittedPower(scene), settings.samplesPerElement,
                                 settings.maxMemoryBytes > 0 ? settings.maxMemoryBytes : defaultMemoryLimit(),
                                 LineSpaceUpdate::memoryBeside()}),
          solver(hierarchy, links),
          updater(hierarchy, links, refiner, solver, emittedPower(scene) / scene.area()),
          lightLinks(scene, hierarchy, rays) {}

    // Adds `object` to the dynamic layer (the objects chosen so far) and
    // splits the polygons into the two visibility layers around them.
    void chooseDynamic(std::optional<std::uint32_t> object) {
        if (!object) {
            rays.setLayer(Layer::Static, scene, allPolygons());
            return;
        }
        dynamic = object;
        if (chosen.count(*object)) return;
        const Object& o = scene.objects[*object];
        std::vector<std::uint32_t> own(o.polygonCount);
        std::iota(own.begin(), own.end(), o.firstPolygon);
        chosen[*object] = Chosen{{scene.polygons.begin() + o.firstPolygon, scene.polygons.begin() + o.firstPolygon + o.polygonCount},
                                 o.worldFromLocal, rays.addInstance(scene, own)};
        rays.commitInstances();
        std::vector<std::uint32_t> staticPolygons;
        for (std::uint32_t p = 0; p < scene.polygons.size(); ++p)
            if (!chosen.count(scene.polygons[p].object)) staticPolygons.push_back(p);
        rays.setLayer(Layer::Static, scene, staticPolygons);
    }
    std::vector<std::uint32_t> allPolygons() const {
        std::vector<std::uint32_t> all(scene.polygons.size());
        for (std::uint32_t p = 0; p < all.size(); ++p) all[p] = p;
        return all;
    }

    Scene scene;
    EngineSettings settings;
    ThresholdScales scales;
    double scale;  // the scene's: scales.scene
    Hierarchy hierarchy;
    LinkStore links;
    RayCaster rays;
    Refiner refiner;
    Solver solver;
    LineSpaceUpdate updater;
    LightLinks lightLinks;
    BudgetControl budget{1e-5};

    // The light links' threshold: the refiner's.
    void setLightThreshold() {
        lightLinks.setThreshold(refiner.settings().epsilon * refiner.settings().referencePower);
    }
    // Elements whose direct light changed are pushed again, and the
    // solver's bound follows the lights.
    void lightChanged(const std::vector<ElementId>& elements) {
        for (ElementId e : elements) refiner.markDirty(e);
        updater.noteLightChanges(lightLinks.takeChanges());
        solver.setDirectBound(lightLinks.directBound());
    }
    SolveStats stats;
    bool solved = false;

    // The emitted power the solve refined by: the threshold stays relative
    // to it, and an edit's light is judged in that scale
    // (LineSpaceUpdate::setLightScale).
    double anchorPower = 0.0;

    // Refinement judges a link by its source's radiosity as last solved.
    void setOracles() {
        for (ElementId e = 0; e < hierarchy.size(); ++e) hierarchy[e].oracle = oracleOf(hierarchy, e);
    }

    // The lit mesh a frame ends with: the viewer draws it, so building it is
    // part of the frame's time. Valid until the solution changes again.
    // On a deadline (the frame's, begun at frameStart), polygons are meshed
    // again only until the time the assembly needs is left; the others keep
    // their last mesh for a later frame (FrameStats::unmeshed). The frame's
    // total is the wall clock from frameStart through the mesh: what no
    // phase times (the live estimate of a deferred move, 1 to 12 ms on the
    // building floor) is in it too.
    void buildMesh(FrameStats& f, std::chrono::steady_clock::time_point frameStart,
                   std::optional<double> deadlineSeconds = std::nullopt) {
        f.totalSeconds = secondsSince(frameStart);
        const auto start = std::chrono::steady_clock::now();
        std::optional<std::chrono::steady_clock::time_point> stop;
        // The polygons whose leaves changed or moved are meshed anew, at ten
        // times the cost a leaf of colouring one again: their time is known
        // apart (SnapshotCache::reshapeSecondsPerLeaf), and the fit is of
        // the rest.
        const double reshape = meshParts.reshapeSecondsPerLeaf * double(hierarchy.reshapedLeaves());
        if (deadlineSeconds) {
            const double left = std::max(0.0, *deadlineSeconds - f.totalSeconds - meshCost.model().first - reshape);
            stop = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(left));
        }
        f.unmeshed = makeRadiositySnapshot(scene, hierarchy, mesh, meshParts, stop, &hierarchy.meshTouched());
        meshValid = true;
        f.snapshotSeconds = secondsSince(start);
        f.totalSeconds += f.snapshotSeconds;
        meshCost.record(f.changedLeaves, std::max(0.0, f.snapshotSeconds - reshape));
        hierarchy.clearReshaped();
    }
    // Its time against the surface leaves the frame changed (their polygons
    // are meshed again), so that a frame on a deadline leaves it the time
    // it needs. The first guess: measured on `office`.
    BudgetControl meshCost{1e-6};
    static constexpr double kMostOwed = 0.25;
    // When light links stop refining in a frame that began at `start`: half
    // of its deadline, after `elapsed` seconds spent before it.
    std::optional<LightLinks::Clock::time_point> lightDeadline(std::chrono::steady_clock::time_point start,
                                                               const UpdateSettings& settings, double elapsed) const {
        if (!settings.deadlineSeconds) return std::nullopt;
        const double seconds = std::max(0.0, *settings.deadlineSeconds - elapsed) / 2.0;
        return start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
    }
    // The settings the updater gets: a deadline is for the whole frame, of
    // which `elapsed` seconds are gone and the lit mesh is still to come.
    // `carrying`: the clusters of the objects whose links may wait at the end
    // of the frame (the estimate sums the light they carry); `traversal`:
    // the frame begins a traversal, which makes those sums again.
    UpdateSettings forUpdater(const UpdateSettings& settings, double elapsed,
                              std::span<const ElementId> carrying = {}, bool traversal = false) {
        // The mesh's time varies with more than the leaves (how many
        // polygons they lie in, how much smoothing): its fixed part is taken
        // at the 80th percentile of the frames, not their mean. A new layout
        // the last mesh left waiting is made in this one whatever its
        // deadline (SnapshotCache::resizesWaited): its time is left for it,
        // up to a quarter of the frame (the building floor's take 100 to
        // 150 ms, more than a frame at 30 fps: left in full, the frames that
        // owed one did nothing else). Meshing anew the polygons whose leaves
        // change or move is counted as the frame goes (Hierarchy::
        // reshapedLeaves), at its own rate. The live estimate comes after
        // the work too (LineSpaceUpdate::estimateSeconds).
        const auto [base, perLeaf] = meshCost.model();
        double owed = meshParts.resizesWaited ? meshParts.relayoutSeconds : 0.0;
        if (settings.deadlineSeconds) owed = std::min(owed, kMostOwed * *settings.deadlineSeconds);
        updater.setFrameTail(
            {base + meshCost.spread() + owed + updater.estimateSeconds(carrying, traversal), perLeaf,
             meshParts.reshapeSecondsPerLeaf});
        UpdateSettings u = settings;
        if (u.deadlineSeconds) u.deadlineSeconds = *u.deadlineSeconds - elapsed;
        return u;
    }
    MeshSnapshot mesh;
    SnapshotCache meshParts;
    bool meshValid = false;

    std::optional<std::uint32_t> dynamic;  // the last chosen
    // The dynamic layer: every object chosen so far, with its polygons and
    // transform as chosen (moves are applied to those, not accumulated), and
    // its Embree instance in the layer (placed from there).
    struct Chosen {
        std::vector<Polygon> polygons;
        glm::dmat4 world{1.0};
        std::size_t instance = 0;
    };
    std::map<std::uint32_t, Chosen> chosen;

    // A move deferred for lack of time (Engine::moveObjects): per object,
    // its box and transform where its links were last updated. The frame
    // that has time updates the links for one move from there to where the
    // object is then; where it passed between does not matter, since no
    // link was updated for it.
    struct Deferred {
        Aabb box;
        glm::dmat4 world{1.0};
    };
    std::map<std::uint32_t, Deferred> deferred;
    // The last frame ended a traversal and left stale links (FrameStats::
    // resumed or caughtUp), or its budget left some: the next move's frame
    // first updates them (on the clock, as idle time would), with the
    // objects still where they were found, and then defers its own move;
    // the traversal after the catch-up covers the moves since.
    bool catchUpFirst = false;
    double lastMoveSeconds = 0.0;  // what the last move took (the catch-up leaves it that time)
    // The time frames that catch up or go on with a traversal leave for
    // running over their deadline: their pushes and meshing follow the link
    // updates by more than the frame's tail expects (in `two-offices` at
    // 60 fps, a median 2 ms over, up to 6 ms). Raised by a twentieth of the
    // frame when such a frame ends past its deadline, lowered by a ninth of
    // that when one ends within it, it settles where one such frame in ten
    // runs over: the frames' 95th percentile is what the target frame rate
    // asks of, not their mean (smoothed by halves toward how far frames
    // ran over, it held the mean near the deadline, and half of them ran
    // over). At most a quarter of the frame: a frame whose mesh moved to a
    // new layout (223 ms on the building floor at 30 fps) once left the next
    // frames no time at all.
    double catchUpOver = 0.0;
    static constexpr double kOverRaise = 0.05, kMostOver = 0.25;
    // A traversal a deadline stopped (FrameStats::traversing): per object,
    // where its links were when the traversal began. The next frame goes on
    // with it before its own move, which it defers; anything else that
    // changes links first drops it, and the move waits again from there.
    std::map<std::uint32_t, Deferred> finding;
    void abandonFinding() {
        if (finding.empty()) return;
        for (const auto& [object, d] : finding) deferred[object] = d;  // where the links still are
        finding.clear();
        updater.abandonTraversal();
    }
    // The clusters whose exposure what moved may change are measured again;
    // where it changed, their light divides anew: their arrivals are summed
    // again and pushed.
    void measureExposureAround(std::span<const ExposureMotion> motions, std::span<const ElementId> also = {},
                               bool layersChanged = false) {
        for (ElementId e : rad::measureExposureAround(hierarchy, rays, motions, also, layersChanged)) {
            hierarchy.shape(e).ownValid = false;
            refiner.markDirty(e);
        }
    }
    // The clusters of these objects and of those whose moves wait (being
    // found, or deferred).
    std::vector<ElementId> waitingClusters(std::span<const std::pair<std::uint32_t, glm::dmat4>> moving) const {
        std::set<std::uint32_t> objects;
        for (const auto& [object, world] : moving) objects.insert(object);
        for (const auto& [object, d] : finding) objects.insert(object);
        for (const auto& [object, d] : deferred) objects.insert(object);
        std::vector<ElementId> clusters;
        for (std::uint32_t object : objects) clusters.push_back(hierarchy.objectCluster(object));
        return clusters;
    }
    // A frame in which objects' links wait for their moves (being found, or
    // deferred): how many, and the estimate with their links in the share
    // of its size each object has moved since they were last updated.
    void countWaitingMoves(FrameStats& f) {
        std::map<std::uint32_t, Aabb> since;
        for (const auto& [object, d] : finding) since.emplace(object, d.box);
        for (const auto& [object, d] : deferred) since.emplace(object, d.box);
        std::vector<std::pair<ElementId, double>> shares;
        for (const auto& [object, box] : since)
            shares.emplace_back(hierarchy.objectCluster(object),
                                std::min(1.0, LineSpaceUpdate::motionShare(box, scene.objectBounds(object))));
        f.deferred = since.size();
        f.estimatedError = updater.estimatedError(shares);
        f.estimateSeconds += updater.lastEstimateSeconds();
    }
};

std::size_t defaultMemoryLimit() {
    std::ifstream meminfo("/proc/meminfo");
    std::string key;
    std::size_t kib = 0;
    std::string unit;
    while (meminfo >> key >> kib >> unit)
        if (key == "MemAvailable:") return kib * 1024 / 2;
    return std::size_t(4) << 30;
}

Engine::Engine(Scene scene, const EngineSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    state_ = std::make_unique<State>(std::move(scene), settings);
    State& s = *state_;
    // The dynamic object is the first one marked dynamic; the others are static.
    std::optional<std::uint32_t> dynamicObject;
    for (std::uint32_t o = 0; o < s.scene.objects.size(); ++o)
        if (s.scene.objects[o].dynamic && s.scene.objects[o].polygonCount > 0) {
            dynamicObject = o;
            break;
        }
    s.rays.setFrame(s.scene.bounds(), s.scene.detailCentre(), s.scene.detailBounds());
    s.solver.setEnergyGuard(settings.energyGuard);
    s.chooseDynamic(dynamicObject);
    s.stats.polygons = s.scene.polygons.size();
    s.stats.minArea = s.stats.minAreaSmallest = s.hierarchy.minArea();
    for (std::uint32_t o = 0; o < s.scene.objects.size(); ++o)
        if (s.scene.objects[o].polygonCount > 0)
            s.stats.minAreaSmallest = std::min(s.stats.minAreaSmallest, s.hierarchy.minArea(o));
    s.stats.thresholdScale = s.scale;
    s.stats.hierarchySeconds = secondsSince(start);
}

Engine::~Engine() = default;

namespace {

// Engine::solve's progress: the share of its time done and the time left.
//
// The model, and why. A solve's time goes to rounds (every link judged and
// the coarse ones refined, then sweeps to the round tolerance) and to a
// final solve (sweeps to the asked tolerance). Both loops stop on quantities
// that fall about geometrically, so what is left is projected from their
// decay as measured in this solve rather than from fixed guesses:
// - Sweeps: the solver stops once the change extrapolated as a geometric
//   series, err = delta r / (1 - r), is under the tolerance. With r the
//   ratio of the last sweeps' changes, that takes log(tol / err) / log(r)
//   more sweeps, each as long as this solve's sweeps so far. While the
//   change does not fall yet (the first sweep after a refinement), r is the
//   last round's.
// - Rounds: they stop after a round that refines fewer than 1/1000 of the
//   links. Right after a refinement it is known whether that round is the
//   last (the loop's own test). Otherwise the rounds to come are projected.
//   A round refines the links whose source's radiosity changed enough since
//   the last refinement, so the share of the links it refines is taken in
//   proportion to C, the change of the radiosity over the round before
//   (the sum of its sweeps' changes; the factor is the last round's share
//   over the change before it), and C falls from round to round by the
//   ratio its last two rounds measured. (On the scenes in scenes/ that
//   factor stays within 2-3x from round to round, while the share's own
//   ratio varies tenfold: round 1 refines for the direct light, round 2
//   for the indirect, the later ones only correct.) Each refined link adds
//   as many links as in the last round, and costs what one did there. A
//   round sweeps until its change has decayed at r under the round
//   tolerance, at least twice (the solver's test needs two sweeps); a sweep
//   costs in proportion to the links.
// - The final solve: from the error the rounds leave (their changes decayed
//   at r) down to the asked tolerance, at least two sweeps.
// - What follows the rounds (reinstating the links no longer needed;
//   after the final solve compaction and sorting of the link lists) walks
//   every link a few times: it is taken as kAfterSweeps sweeps at the
//   final links (4 to 8 on the scenes in scenes/).
// Until the decays have been measured (C's needs two rounds, r two falling
// sweeps) a guess stands in: the fraction moves with it, but secondsLeft
// stays absent. The refinement reports after each of its waves that it
// runs, without moving the fraction: that moves at its end.
class SolveClock {
  public:
    SolveClock(const Engine::Progress& progress, int maxRounds, double roundTolerance,
               const SolveSettings& solve)
        : progress_(progress),
          maxRounds_(maxRounds),
          maxSweeps_(solve.maxIterations),
          roundTolerance_(roundTolerance),
          finalTolerance_(solve.tolerance) {}

    explicit operator bool() const { return bool(progress_); }

    void refining(int round) { report("round " + std::to_string(round) + ": refining"); }
    // During a round's refinement, after each wave, once nothing has been
    // reported for kQuiet: the fraction stands (the refinement's own length
    // is not projected), the line says it runs. Only long refinements say so:
    // a line per wave would take the places of the lines with an estimate
    // (the programs print at most one a second).
    void refiningWave(int round, std::size_t refined, std::size_t links) {
        if (std::chrono::duration<double>(now() - lastReport_).count() < kQuiet) return;
        report("round " + std::to_string(round) + ": refining, " + std::to_string(refined) + " links refined, " +
               std::to_string(links) + " links in all");
    }
    // After the refinement of `round`: links refined, links live before and
    // after, its time, and whether the loop ends after this round's solve.
    void refined(int round, std::size_t refined, std::size_t linksBefore, std::size_t links, double seconds,
                 bool last) {
        Round r;
        r.refined = double(refined);
        r.links = std::max(1.0, double(links));
        if (refined > 0) r.growth = std::max(0.0, (double(links) - double(linksBefore)) / double(refined));
        r.refineSeconds = seconds;
        rounds_.push_back(r);
        round_ = round;
        last_ = last || round >= maxRounds_;
    }
    void startSolve(bool final) {
        final_ = final;
        solving_ = true;
        solveStart_ = now();
        changes_.clear();
    }
    // The solver's sweep `it` changed the radiosity by `change`.
    void sweep(int it, double change) {
        changes_.push_back(change);
        if (std::chrono::duration<double>(now() - lastReport_).count() < kInterval) return;
        std::ostringstream line;
        line << (final_ ? std::string("final solve") : "round " + std::to_string(round_)) << ": sweep " << it
             << ", change " << change;
        report(line.str());
    }
    // The running solve ended after `sweeps`.
    void solved(int sweeps) {
        solving_ = false;
        if (final_ || rounds_.empty() || changes_.empty()) return;
        Round& r = rounds_.back();
        r.sweeps = sweeps;
        r.solveSeconds = std::chrono::duration<double>(now() - solveStart_).count();
        r.lastChange = changes_.back();
        for (double c : changes_) r.change += c;
        r.ratio = ratio();
    }
    void report(const std::string& line) {
        lastReport_ = now();
        SolveProgress p;
        p.line = line;
        const std::optional<Estimate> left = estimate();
        if (left && std::isfinite(left->seconds)) {
            const double elapsed = std::chrono::duration<double>(lastReport_ - start_).count();
            const double seconds = std::max(0.0, left->seconds);
            // Never back, and 1 only at the end.
            if (elapsed + seconds > 0.0)
                fraction_ = std::max(fraction_, std::min(kBeforeEnd, elapsed / (elapsed + seconds)));
            if (left->measured) p.secondsLeft = seconds;
        }
        p.fraction = fraction_;
        progress_(p);
    }
    void finish(const std::string& line) {
        fraction_ = 1.0;
        progress_(SolveProgress{line, 1.0, 0.0});
    }

  private:
    struct Round {
        double refined = 0.0, links = 1.0;
        double growth = 0.0;  // links added per link refined
        double refineSeconds = 0.0;
        int sweeps = 0;       // of its solve; 0 while it runs
        double solveSeconds = 0.0, lastChange = 0.0;
        double change = 0.0;  // C: the sum of its solve's changes
        std::optional<double> ratio;  // of the changes at the end of its solve
    };
    struct Estimate {
        double seconds = 0.0;
        bool measured = true;  // false: a guess stood in for a decay
    };
    static constexpr double kInterval = 0.1;            // seconds between sweep reports
    static constexpr double kQuiet = 3.0;               // seconds of silence before a refinement wave reports
    static constexpr double kBeforeEnd = 0.99;          // the fraction short of the end
    // Before two rounds measured them: the share refined per change of the
    // round before, and the decay of that change (typical of scenes/).
    static constexpr double kGuessedSharePerChange = 0.2;
    static constexpr double kGuessedChangeDecay = 0.1;
    static constexpr double kGuessedRatio = 0.5;        // r before any solve measured it
    static constexpr double kStopShare = 1e-3;          // Engine::solve's test
    static constexpr double kAfterSweeps = 6.0;         // what follows the rounds, in sweeps

    static std::chrono::steady_clock::time_point now() { return std::chrono::steady_clock::now(); }

    // The ratio of the running solve's changes per sweep, over its last
    // three sweeps; none while they do not fall.
    std::optional<double> ratio() const {
        const std::size_t n = changes_.size();
        if (n < 2) return std::nullopt;
        const std::size_t span = std::min<std::size_t>(3, n - 1);
        const double a = changes_[n - 1 - span], b = changes_[n - 1];
        if (!(a > 0.0) || !(b > 0.0) || !(b < a)) return std::nullopt;
        return std::pow(b / a, 1.0 / double(span));
    }
    // Sweeps for a decay `r` per sweep to bring `error` under `tolerance`.
    double sweepsFor(double error, double tolerance, double r) const {
        if (!(error > tolerance)) return 0.0;
        return std::min(double(maxSweeps_), std::ceil(std::log(tolerance / error) / std::log(r)));
    }

    std::optional<Estimate> estimate() const {
        if (rounds_.empty()) return std::nullopt;  // nothing measured before the first refinement ends
        Estimate e;
        const Round& k = rounds_.back();
        const Round* before = rounds_.size() >= 2 ? &rounds_[rounds_.size() - 2] : nullptr;
        const int done = solving_ ? int(changes_.size()) : 0;
        // The decay per sweep: the running solve's, else the last round's.
        std::optional<double> decay = done > 0 ? ratio() : std::nullopt;
        const bool running = bool(decay);
        for (auto it = rounds_.rbegin(); !decay && it != rounds_.rend(); ++it) decay = it->ratio;
        if (!decay) e.measured = false;
        const double r = std::clamp(decay.value_or(kGuessedRatio), 0.01, 0.99);
        // Seconds per sweep at round k's links.
        double sweepSeconds = 0.0;
        if (done > 0)
            sweepSeconds = std::chrono::duration<double>(now() - solveStart_).count() / done;
        else if (k.sweeps > 0)
            sweepSeconds = k.solveSeconds / k.sweeps;
        else if (before && before->sweeps > 0)
            sweepSeconds = before->solveSeconds / before->sweeps * k.links / before->links;
        else
            e.measured = false;
        // The running solve, the error it leaves and its change C.
        double error = 0.0, change = k.change;
        if (done > 0) {
            const double tolerance = final_ ? finalTolerance_ : roundTolerance_;
            const double last = changes_.back(), errorNow = last * r / (1.0 - r);
            // The solver tests from its second sweep on.
            double sweeps = sweepsFor(errorNow, tolerance, r);
            if (!running) sweeps = std::max(1.0, sweeps);
            e.seconds += sweeps * sweepSeconds;
            error = errorNow * std::pow(r, sweeps);
            change = last * r * (1.0 - std::pow(r, sweeps)) / (1.0 - r);
            for (double c : changes_) change += c;
        } else if (k.sweeps > 0) {
            error = k.lastChange * r / (1.0 - r);
        }
        if (final_) {
            e.seconds += kAfterSweeps * sweepSeconds;
            return e;
        }
        // The rounds to come.
        double links = k.links;
        if (!last_) {
            double sharePerChange = kGuessedSharePerChange, changeDecay = kGuessedChangeDecay;
            if (before && before->change > 0.0 && change > 0.0) {
                sharePerChange = k.refined / k.links / before->change;
                changeDecay = std::min(0.9, change / before->change);
            } else {
                e.measured = false;
            }
            const double perRefined = k.refined > 0.0 ? k.refineSeconds / k.refined : 0.0;
            for (int round = round_ + 1; round <= maxRounds_; ++round) {
                const double share = std::min(1.0, sharePerChange * change);
                // n = share L after the round, L = L before + growth n.
                const double grown = links / std::max(0.1, 1.0 - k.growth * share);
                const double refined = share * grown;
                links = grown;
                change *= changeDecay;
                // A geometric series of sweeps summing to C starts at C (1 - r).
                const double first = change * (1.0 - r);
                const double sweeps =
                    std::max(2.0, 1.0 + sweepsFor(first * r / (1.0 - r), roundTolerance_, r));
                e.seconds += perRefined * refined + sweeps * sweepSeconds * links / k.links;
                error = (error + change) * std::pow(r, sweeps);
                if (refined < 1.0 || share < kStopShare) break;
            }
        }
        // The final solve.
        const double sweeps = std::max(2.0, 1.0 + sweepsFor(error, finalTolerance_, r));
        e.seconds += (sweeps + kAfterSweeps) * sweepSeconds * links / k.links;
        return e;
    }

    Engine::Progress progress_;
    int maxRounds_, maxSweeps_;
    double roundTolerance_, finalTolerance_;
    std::chrono::steady_clock::time_point start_ = now(), lastReport_ = start_, solveStart_ = start_;
    std::vector<Round> rounds_;
    int round_ = 0;
    bool last_ = false, final_ = false, solving_ = false;
    std::vector<double> changes_;  // of the running solve's sweeps
    double fraction_ = 0.0;
};

}  // namespace

const SolveStats& Engine::solve(const Progress& progress) {
    State& s = *state_;
    SolveStats& st = s.stats;
    s.meshValid = false;
    s.deferred.clear();  // the solve is of the objects where they are
    s.finding.clear();
    s.updater.abandonTraversal();
    s.catchUpFirst = false;
    s.refiner.setReceiverScales({});
    s.refiner.linkRoot();
    // Punctual lights reach the surfaces through light links, refined once:
    // the light a point gets from them does not depend on the solution.
    s.setLightThreshold();
    s.lightLinks.linkAll();
    s.lightLinks.takeChanges();  // the solve pushes everything
    s.solver.setDirectBound(s.lightLinks.directBound());
    if (s.settings.fill) {
        std::vector<float> closure;
        measureClosure(s.scene, s.rays, s.allPolygons(), closure);
        s.solver.setClosure(std::move(closure));
    }
    measureExposure(s.hierarchy, s.rays);
    // Radiosity starts at emission and direct light, so the first
    // refinement sees the lights.
    s.solver.pushPull();
    SolveResult r;
    // A round's radiosity only guides the next refinement: a looser
    // tolerance does (the last solve below meets the asked one).
    SolveSettings roundSettings = s.settings.solve;
    roundSettings.tolerance = std::max(roundSettings.tolerance, kRoundTolerance);
    SolveClock clock(progress, s.settings.maxRefineRounds, roundSettings.tolerance, s.settings.solve);
    // The solver's sweeps report to the clock (nothing without a callback).
    const auto sweepReports = [&](bool final) -> std::function<void(int, double)> {
        if (!clock) return {};
        clock.startSolve(final);
        return [&clock](int sweep, double change) { clock.sweep(sweep, change); };
    };
    for (int round = 1; round <= s.settings.maxRefineRounds; ++round) {
        if (clock) clock.refining(round);
        auto t = std::chrono::steady_clock::now();
        const std::size_t linksBefore = s.links.liveCount();
        s.setOracles();
        Refiner::WaveReport onWave;
        if (clock)
            onWave = [&clock, &s, round](std::size_t n) { clock.refiningWave(round, n, s.links.liveCount()); };
        const std::size_t refined = s.refiner.refineAll(onWave);
        st.refineSeconds += secondsSince(t);
        st.refineRounds = round;
        // A round that refines almost nothing changes the radiosity too little
        // for another round to find more worth refining.
        const bool lastRound = refined == 0 || refined * 1000 < s.links.liveCount();
        if (clock)
            clock.refined(round, refined, linksBefore, s.links.liveCount(), secondsSince(t), lastRound);
        t = std::chrono::steady_clock::now();
        r = s.solver.solve(roundSettings, sweepReports(false));
        st.solveSeconds += secondsSince(t);
        st.iterations += r.iterations;
        if (clock) {
            clock.solved(r.iterations);
            std::ostringstream line;
            line << "round " << round << ": refined " << refined << " links, " << s.links.liveCount()
                 << " links in all, " << r.iterations << " sweeps, change " << r.lastChange;
            clock.report(line.str());
        }
        if (r.status != SolveResult::Status::Converged) break;
        // After the first round the light is where it goes: polygons it
        // reaches little are refined finer for what they get (the scales
        // fixed from then on), and at least one round follows to do it.
        bool rescaled = false;
        if (round == 1 && s.settings.localThresholds) {
            std::vector<float> scales = receiverLightScales(s.scene, s.hierarchy, s.scale);
            rescaled = std::any_of(scales.begin(), scales.end(), [](float v) { return v < 1.0f; });
            s.refiner.setReceiverScales(std::move(scales));
        }
        if (lastRound && !rescaled) break;
        if (round == s.settings.maxRefineRounds) st.message = "stopped refining after the round limit";
    }
    // Refinement made under an earlier round's radiosity that the final one
    // no longer asks for goes, and the system is solved to the tolerance.
    if (r.status == SolveResult::Status::Converged) {
        s.updater.reinstateUnneeded();
        const auto t = std::chrono::steady_clock::now();
        r = s.solver.solve(s.settings.solve, sweepReports(true));
        st.solveSeconds += secondsSince(t);
        st.iterations += r.iterations;
    }
    st.converged = r.status == SolveResult::Status::Converged;
    if (!st.converged) {
        st.message = diagnoseFailure(s.scene, s.hierarchy, s.solver, r, s.settings.solve);
        // Nothing non-finite leaves the engine: the values that ran away are
        // cleared, and the solve says why.
        clearNonFinite(s.hierarchy);
    }
    if (s.refiner.capReached()) {
        st.converged = false;
        st.stoppedBy = "memory_limit";
        st.unrefinedPowerShare = s.refiner.unrefinedPower() / std::max(1e-300, s.refiner.settings().referencePower);
        std::ostringstream m;
        m << "refinement stopped at the memory limit of " << (s.refiner.settings().maxMemoryBytes >> 20)
          << " MiB; links coarser than the criterion asks carry " << 100.0 * st.unrefinedPowerShare
          << "% of the emitted power (raise the limit with --max-memory, or raise epsilon)";
        st.message = st.message.empty() ? m.str() : st.message + "; " + m.str();
        st.warnings.push_back({"memory_limit", m.str(), {}, st.unrefinedPowerShare});
    }
    for (Warning& w : guardWarnings(s.scene, s.solver, kGuardWarningThreshold)) st.warnings.push_back(std::move(w));
    st.elements = s.hierarchy.liveCount();
    st.links = st.passiveLinks = 0;
    for (ElementId e = 0; e < s.hierarchy.size(); ++e) {
        st.links += s.hierarchy[e].links.size();
        st.passiveLinks += s.hierarchy[e].plinks.size();
    }
    s.hierarchy.compact();
    s.links.compact();
    st.energy = energy();
    for (Warning& w : backFaceWarnings(s.scene, st.energy, kBackFaceWarningShare)) st.warnings.push_back(std::move(w));
    for (Warning& w : escapingLightWarnings(s.scene, st.energy, kEscapingWarningShare)) st.warnings.push_back(std::move(w));
    // Unconverged, light still on its way counts as lost: the message says why it stopped.
    if (st.converged)
        for (Warning& w : lostLightWarnings(st.energy, kLostWarningShare)) st.warnings.push_back(std::move(w));
    for (Warning& w : madeLightWarnings(st.energy, kMadeWarningShare)) st.warnings.push_back(std::move(w));
    for (Warning& w : trappedLightWarnings(s.scene)) st.warnings.push_back(std::move(w));
    // The full sweeps left every receiver's irradiance consistent with the
    // sources' gathered B: the in-place updates start from here.
    s.refiner.takeDirty();
    s.refiner.sortLinkLists();  // the first traversal then finds its ranges at once
    s.solved = true;
    // The lit mesh the viewer draws, made once here: the first frame of a
    // drag then meshes again only what it changed (the building floor's
    // whole mesh takes 0.25 s, which its first frame paid). Not a frame:
    // the mesh's cost model is left to the frames.
    makeRadiositySnapshot(s.scene, s.hierarchy, s.mesh, s.meshParts, std::nullopt, &s.hierarchy.meshTouched());
    s.hierarchy.clearReshaped();
    s.meshValid = true;
    s.updater.prepare();
    st.memory = memory();  // the update's marks included
    // First guess of a further bounce's cost, until a frame makes one: a
    // sweep of the solve (every link gathered, everything pushed), which a
    // bounce from part of the scene costs at most. A guess of nothing would
    // let the first bounce of a drag run whatever the deadline.
    if (st.iterations > 0) s.updater.guessBounceSeconds(st.solveSeconds / st.iterations, st.links, st.elements);
    // From here on the oracles follow the light in steps from these anchors.
    anchorOracles(s.hierarchy);
    s.anchorPower = s.refiner.settings().referencePower;
    // First guess of a link update's cost, until the frames give a fit: the
    // refinement time per link made, times 5 for the push-pull and meshing
    // of what it changes (in `office`, a frame's time grows by 8.6 us per
    // link update against 1.7 us of refinement per link): a guess too low
    // makes the first frame that spends overrun its target several times.
    s.budget = BudgetControl(5.0 * st.refineSeconds / double(std::max<std::size_t>(1, st.links + st.passiveLinks)));
    if (clock) {
        std::ostringstream line;
        line << "done: " << st.refineRounds << " rounds, " << st.iterations << " sweeps";
        clock.finish(line.str());
    }
    return st;
}

std::optional<std::uint32_t> Engine::dynamicObject() const { return state_->dynamic; }

FrameStats Engine::setDynamicObject(const std::string& name, const UpdateSettings& settings) {
    State& s = *state_;
    // A punctual light is not in the hierarchy: nothing to split.
    if (s.scene.findLight(name)) return {};
    const std::optional<std::uint32_t> object = s.scene.findObject(name);
    if (!object) throw std::invalid_argument("no object named '" + name + "' in " + s.scene.sourcePath);
    const ElementId cluster = s.hierarchy.objectCluster(*object);
    if (cluster == kNone) throw std::invalid_argument("object '" + name + "' in " + s.scene.sourcePath + " has no polygons to move");
    // Chosen before: it is in the dynamic layer already, nothing to split.
    if (s.chosen.count(*object)) {
        s.dynamic = object;
        return {};
    }
    const auto start = std::chrono::steady_clock::now();
    s.abandonFinding();  // its links change under a traversal under way
    // The layers first: the object's new links split their visibility by them.
    s.chooseDynamic(object);
    std::vector<ElementId> left = s.hierarchy.ancestorsBelowRoot(cluster);  // their shapes are built again
    left.push_back(s.hierarchy.root());
    const ReinsertionStats r = reinsertUnderRoot(s.hierarchy, s.links, s.refiner, cluster);
    s.meshValid = false;
    if (!s.solved) return {};  // the solve measures every cluster's exposure
    const Aabb objectBox = s.scene.objectBounds(*object);
    const ExposureMotion stays{cluster, objectBox, objectBox};
    s.measureExposureAround(std::span(&stays, 1), left, true);  // it left the static layer
    const double reinsertSeconds = secondsSince(start);
    // The links around it: their rays that it blocks move from the static
    // part of the visibility to the dynamic one.
    const Aabb box = s.scene.objectBounds(*object);
    const bool relinked = r.removed > 0 || r.created > 0;
    FrameStats f = s.updater.chooseObject(box, s.hierarchy.range(cluster), relinked, settings);
    f.reinsertion = r;
    f.updateSeconds += reinsertSeconds;
    s.buildMesh(f, start);
    return f;
}

FrameStats Engine::moveDynamicObject(const glm::dmat4& worldFromLocal, const UpdateSettings& settings) {
    State& s = *state_;
    if (!s.dynamic) throw std::invalid_argument(s.scene.sourcePath + ": no dynamic object to move");
    return moveObjects({{s.scene.objects[*s.dynamic].name, worldFromLocal}}, settings);
}

FrameStats Engine::moveObjects(const std::vector<std::pair<std::string, glm::dmat4>>& moves,
                               const UpdateSettings& settings) {
    return moveObjects(moves, settings, true);
}

void Engine::checkMove(const std::string& name, const glm::dmat4& worldFromLocal) const {
    const State& s = *state_;
    const std::optional<std::uint32_t> light = s.scene.findLight(name);
    const std::optional<std::uint32_t> object = s.scene.findObject(name);
    if (!light && (!object || s.hierarchy.objectCluster(*object) == kNone))
        throw std::invalid_argument("no object '" + name + "' with polygons and no light of that name in " +
                                    s.scene.sourcePath);
    // The motion from where it stands must be rigid; its node's own
    // transform may scale or mirror it (as tools write them).
    const glm::dmat4& current =
        light ? s.scene.lights[*light].worldFromLocal : s.scene.objects[*object].worldFromLocal;
    const glm::dmat4 motion = worldFromLocal * glm::inverse(current);
    const glm::dmat3 r(motion);
    const glm::dmat3 rtr = glm::transpose(r) * r;
    bool rigid = std::abs(glm::determinant(r) - 1.0) < 1e-6 && std::abs(motion[0][3]) < 1e-9 &&
                 std::abs(motion[1][3]) < 1e-9 && std::abs(motion[2][3]) < 1e-9 &&
                 std::abs(motion[3][3] - 1.0) < 1e-9;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rigid = rigid && std::abs(rtr[i][j] - (i == j ? 1.0 : 0.0)) < 1e-6;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) rigid = rigid && std::isfinite(worldFromLocal[i][j]) && std::isfinite(motion[i][j]);
    if (!rigid)
        throw std::invalid_argument("the transform of '" + name + "' is not a finite rigid motion (rotation and translation)");
    const Aabb box = light ? Aabb{s.scene.lights[*light].position, s.scene.lights[*light].position}
                           : s.scene.objectBounds(*object);
    double farthest = 0.0;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner(k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y, k & 4 ? box.hi.z : box.lo.z);
        farthest = std::max(farthest, s.rays.framesFromCentre(glm::dvec3(motion * glm::dvec4(corner, 1.0))));
    }
    if (!(farthest <= kReach)) {
        const double size = s.rays.frameSize();
        char what[160];
        std::snprintf(what, sizeof what, "%.3g m from the scene's centre, more than %.0f times the scene's size (%.3g m)",
                      farthest * size, kReach, size);
        throw std::invalid_argument("'" + name + "' would be moved " + what + ": its rays cannot be traced there");
    }
}

FrameStats Engine::moveObjects(const std::vector<std::pair<std::string, glm::dmat4>>& moves,
                               const UpdateSettings& settings, bool allowDeferral) {
    State& s = *state_;
    if (!s.solved) throw std::logic_error("moveObjects before solve()");
    const auto frameStart = std::chrono::steady_clock::now();
    std::vector<std::pair<std::uint32_t, glm::dmat4>> objects, lights;
    for (const auto& [name, worldFromLocal] : moves) {
        for (const auto& [other, m] : moves)
            if (&other != &name && other == name) throw std::invalid_argument("'" + name + "' is moved twice in one frame");
        checkMove(name, worldFromLocal);
        const std::optional<std::uint32_t> light = s.scene.findLight(name);
        const std::optional<std::uint32_t> object = s.scene.findObject(name);
        if (light)
            lights.emplace_back(*light, worldFromLocal);
        else
            objects.emplace_back(*object, worldFromLocal);
    }
    // A light under a moving object's node moves with it, unless it is
    // moved itself.
    for (const auto& [object, worldFromLocal] : objects)
        for (std::uint32_t l = 0; l < s.scene.lights.size(); ++l) {
            const PunctualLight& light = s.scene.lights[l];
            if (light.object != s.scene.objects[object].name) continue;
            if (std::any_of(lights.begin(), lights.end(), [&](const auto& m) { return m.first == l; })) continue;
            lights.emplace_back(l, worldFromLocal * glm::inverse(s.scene.objects[object].worldFromLocal) *
                                       light.worldFromLocal);
        }
    // Objects not chosen yet join the dynamic layer first (paper sec. 3.3).
    double choosingSeconds = 0.0;
    for (const auto& [object, m] : objects)
        if (!s.chosen.count(object)) choosingSeconds += setDynamicObject(s.scene.objects[object].name, settings).totalSeconds;
    if (!objects.empty()) s.dynamic = objects.back().first;

    // Stale links left by the last traversal (State::catchUpFirst):
    // first they are updated, with the objects where they were found, on the
    // clock, leaving the move the time the last one took; this frame's move
    // is then deferred. The deadline governs, not the budget, whose fit is
    // of frames that traverse. Frames catch up so while stale links are left
    // and they make progress: a traversal begun before they are worked off
    // finds most of them again, and at 120 fps in `office` the light then
    // stayed 2.1% rms from full solves, as if every move waited (1.1% when
    // they are worked off first). (A frame that chose an object caught up
    // in choosing it.)
    const bool catchingUp = std::exchange(s.catchUpFirst, false) && allowDeferral &&
                            settings.deadlineSeconds && choosingSeconds == 0.0;
    FrameStats caught;
    if (catchingUp) {
        UpdateSettings u = s.forUpdater(settings, s.lastMoveSeconds + s.catchUpOver, s.waitingClusters(objects));
        u.budget.reset();
        caught = s.updater.refinePending(u, false);
        s.catchUpFirst = caught.stale > 0 && caught.spent > 0;
    }
    // A traversal the last frame's deadline stopped (or ended too late in it
    // to defer what it found) goes on first, with the objects where it found
    // them, leaving the move the time the last one took; once it ends, the
    // links it found wait, stale, and the frame catches up on them with the
    // time it has left, and the next frames go on catching up. This frame's
    // move is deferred: the traversal after it covers it. Without a deadline
    // the traversal ends, its links are updated in full, and the move goes
    // on.
    const bool resumed = !s.finding.empty();
    if (resumed) {
        UpdateSettings u =
            s.forUpdater(settings, s.lastMoveSeconds + choosingSeconds + s.catchUpOver, s.waitingClusters(objects));
        if (settings.deadlineSeconds) u.budget.reset();  // as in a catch-up: the deadline governs
        caught = s.updater.resume(u);
        if (!caught.traversing) {
            s.finding.clear();
            s.catchUpFirst = caught.stale > 0;
        }
    }

    const auto start = std::chrono::steady_clock::now();
    // Where each object's links were last updated: where it starts this
    // frame, or where a deferred move left them.
    std::map<std::uint32_t, State::Deferred> from = s.deferred;
    std::vector<Aabb> boxes;  // this frame's, before and after, for the light links
    for (const auto& [object, worldFromLocal] : objects) {
        const Aabb before = s.scene.objectBounds(object);
        from.emplace(object, State::Deferred{before, s.scene.objects[object].worldFromLocal});
        Object& o = s.scene.objects[object];
        const State::Chosen& c = s.chosen.at(object);
        const glm::dmat4 delta = worldFromLocal * glm::inverse(c.world);
        for (std::uint32_t i = 0; i < o.polygonCount; ++i) {
            Polygon& p = s.scene.polygons[o.firstPolygon + i];
            for (int k = 0; k < p.vertexCount; ++k) p.vertices[k] = glm::dvec3(delta * glm::dvec4(c.polygons[i].vertices[k], 1.0));
        }
        // Turned (rotated, mirrored or scaled), or only translated since its
        // clusters' shapes were built (kept then: Hierarchy::updateGeometry).
        const bool turned = turnedBetween(o.worldFromLocal, worldFromLocal);
        o.worldFromLocal = worldFromLocal;
        s.rays.moveInstance(c.instance, delta);
        const ElementId cluster = s.hierarchy.objectCluster(object);
        s.hierarchy.updateGeometry(cluster, turned);
        s.hierarchy.refreshAncestors(cluster);
        s.updater.clustersMoved(cluster);
        boxes.insert(boxes.end(), {before, s.scene.objectBounds(object)});
    }
    s.rays.commitInstances();
    std::vector<std::uint32_t> moved;  // the moved objects' polygons
    for (const auto& [object, m] : objects) {
        const Object& o = s.scene.objects[object];
        for (std::uint32_t p = o.firstPolygon; p < o.firstPolygon + o.polygonCount; ++p) moved.push_back(p);
    }
    for (std::uint32_t p : moved) s.hierarchy.markReshaped(p);  // meshed anew where they now stand
    // The fill follows a moved object's polygons where the scene is not
    // closed (in a closed one every polygon's view stays closed): their
    // closure is measured again where they now stand, with the rays a solve
    // there casts (fixed in each polygon's frame). Other polygons keep
    // theirs (see the README's known limits).
    if (!s.solver.allClosed()) {
        std::vector<float>& closure = s.solver.closure();
        std::vector<float> before(moved.size());
        for (std::size_t i = 0; i < moved.size(); ++i) before[i] = closure[moved[i]];
        measureClosure(s.scene, s.rays, moved, closure);
        for (std::size_t i = 0; i < moved.size(); ++i)
            if (closure[moved[i]] != before[i]) s.refiner.markDirty(s.hierarchy.polygonElement(moved[i]));
    }
    // The light links: the lights that moved are linked again everywhere;
    // for the others, the polygons the objects moved on, and those whose
    // shafts toward a light the objects cross before or after the move.
    // On a deadline they get up to half of the frame; what they could not
    // refine in it waits, pending, linked coarser.
    if (!s.scene.lights.empty()) {
        const auto lightDeadline = s.lightDeadline(start, settings, choosingSeconds);
        std::vector<ElementId> changed = s.lightLinks.relinkAround(moved, boxes, lightDeadline);
        for (const auto& [light, worldFromLocal] : lights) {
            PunctualLight& l = s.scene.lights[light];
            l.worldFromLocal = worldFromLocal;
            l.position = glm::dvec3(worldFromLocal * glm::dvec4(0.0, 0.0, 0.0, 1.0));
            l.direction = glm::normalize(glm::dmat3(worldFromLocal) * glm::dvec3(0.0, 0.0, -1.0));
            for (ElementId e : s.lightLinks.relinkLight(light, lightDeadline)) changed.push_back(e);
        }
        s.lightChanged(changed);
    }
    const double moveSeconds = secondsSince(start);
    s.lastMoveSeconds = moveSeconds;
    // A frame that caught up or went on with a traversal defers its move (a
    // traversal still under way must): the objects are drawn where they are,
    // with the light of where their links were last updated, until a frame
    // with the time (or an idle one) updates the links for one move from
    // there.
    if (s.updater.traversing() || ((catchingUp || resumed) && allowDeferral && settings.deadlineSeconds)) {
        s.deferred = std::move(from);
        FrameStats stats = caught;
        stats.caughtUp = catchingUp;
        stats.resumed = resumed;
        stats.moveSeconds = moveSeconds;
        stats.updateSeconds += choosingSeconds;
        // The estimate: what waits already, and the light the objects' own
        // links carry, in the share of the object's size it has moved (its
        // shadow and its light move with it, all of them once it has moved
        // by its size).
        s.countWaitingMoves(stats);
        s.updater.countWaiting(stats);
        stats.pending += s.lightLinks.pendingCount();
        // A new layout the mesh owes and no reserve could hold (the building
        // floor's, 50 to 150 ms) is made whatever the frame leaves it: such a
        // frame says nothing of the reserve (counted, the reserve grew to its
        // cap there, and most frames ended 10 to 18 ms early).
        const bool layoutBeyondReserve =
            settings.deadlineSeconds && s.meshParts.resizesWaited &&
            s.meshParts.relayoutSeconds > State::kMostOver * *settings.deadlineSeconds;
        s.buildMesh(stats, frameStart, settings.deadlineSeconds);  // not a frame of the budget's fit: its traversal began before
        if ((catchingUp || resumed) && settings.deadlineSeconds && !layoutBeyondReserve) {
            const double frame = *settings.deadlineSeconds, raise = State::kOverRaise * frame;
            s.catchUpOver = std::clamp(s.catchUpOver + (stats.totalSeconds > frame ? raise : -raise / 9.0), 0.0,
                                       State::kMostOver * frame);
        }
        return stats;
    }
    std::vector<ObjectMotion> motions;
    std::vector<Aabb> obstacles;
    // The clusters' exposure, from where the links were last updated (a
    // deferred move's frames leave it, as they leave the links).
    std::vector<ExposureMotion> exposureMotions;
    for (const auto& [object, d] : from) {
        const glm::dmat4& world = s.scene.objects[object].worldFromLocal;
        const glm::dmat4 oldToNew = world * glm::inverse(d.world);
        for (const Aabb& box : motionObstacles(s.scene, object, d.box, oldToNew)) obstacles.push_back(box);
        motions.push_back({d.box, s.scene.objectBounds(object), s.hierarchy.range(s.hierarchy.objectCluster(object))});
        exposureMotions.push_back({s.hierarchy.objectCluster(object), d.box, s.scene.objectBounds(object),
                                   glm::dvec3(world[3]) - glm::dvec3(d.world[3]), turnedBetween(d.world, world)});
    }
    const auto exposureStart = std::chrono::steady_clock::now();
    s.measureExposureAround(exposureMotions);
    const double movedSeconds = moveSeconds + secondsSince(exposureStart);  // the move's part of the frame
    const std::vector<ElementId> carrying = s.waitingClusters(objects);  // if the traversal stops
    s.deferred.clear();
    s.updater.setObstacles(std::move(obstacles));
    FrameStats stats = s.updater.update(motions, s.forUpdater(settings, movedSeconds + choosingSeconds, carrying, true));
    if (stats.traversing) {
        s.finding = std::move(from);
        s.countWaitingMoves(stats);
    }
    stats.moveSeconds = movedSeconds;
    stats.pending += s.lightLinks.pendingCount();
    stats.updateSeconds += choosingSeconds;
    s.buildMesh(stats, frameStart, settings.deadlineSeconds);
    // Links the frame's budget left stale are caught up on first, as those
    // of a traversal over frames are: otherwise each frame's traversal
    // finds more than its budget updates, and they pile up (in `office` at
    // 30 fps 46,000 to 51,000 stale links in every frame, the light 0.2%
    // to 1.7% rms from full solves and growing frame after frame).
    if (allowDeferral && settings.deadlineSeconds && !stats.traversing && stats.stale > 0) s.catchUpFirst = true;
    // The budget's fit leaves out the further bounces: on a deadline they
    // fill what the frame has left, so that frames that spent few link
    // updates take as long as those that spent many, and a fit of the whole
    // frame read the budget as fixed cost and held it at 0 (`office` at 30
    // fps: 0 to 228 link updates a frame while the stale links grew). A
    // frame that only found, or is still finding, says nothing of what link
    // updates cost.
    if (!stats.foundOnly && !stats.traversing)
        s.budget.record(stats.spent, stats.totalSeconds - stats.bounceSeconds);
    return stats;
}

FrameStats Engine::refinePending(const UpdateSettings& settings) {
    State& s = *state_;
    if (!s.solved) throw std::logic_error("refinePending before solve()");
    const auto frameStart = std::chrono::steady_clock::now();
    s.catchUpFirst = false;  // idle time catches up
    // A traversal a deadline stopped goes on first (on the deadline, at
    // least a run of its visits); once it ends, the links it found wait,
    // stale, and are caught up on with the time left, or by the next idle
    // frames.
    if (!s.finding.empty()) {
        FrameStats f = s.updater.resume(s.forUpdater(settings, 0.0), true);
        if (!f.traversing) s.finding.clear();
        s.countWaitingMoves(f);
        f.pending += s.lightLinks.pendingCount();
        s.buildMesh(f, frameStart, settings.deadlineSeconds);
        return f;
    }
    // A deferred move first: the objects stay where they are, and their
    // links are updated for the move from where they were last updated
    // (its traversal is not deferred again; its link updates keep the
    // deadline).
    if (!s.deferred.empty()) {
        std::vector<std::pair<std::string, glm::dmat4>> moves;
        for (const auto& [object, d] : s.deferred)
            moves.emplace_back(s.scene.objects[object].name, s.scene.objects[object].worldFromLocal);
        return moveObjects(moves, settings, false);
    }
    const auto start = std::chrono::steady_clock::now();
    // The light links a deadline left coarse first: their light then goes
    // out with the rest of what catching up changes.
    s.lightChanged(s.lightLinks.refinePending(s.lightDeadline(start, settings, 0.0)));
    const double lightSeconds = secondsSince(start);
    FrameStats f = s.updater.refinePending(s.forUpdater(settings, lightSeconds));
    f.updateSeconds += lightSeconds;
    f.pending += s.lightLinks.pendingCount();
    // Idle with nothing left to refine: the link lists give back the growth
    // slack the moves left them.
    if (f.pending == 0) {
        s.hierarchy.compact(0.25);
        s.links.compact();
    }
    s.buildMesh(f, frameStart, settings.deadlineSeconds);
    return f;
}

std::vector<std::uint32_t> Engine::objectMaterials(const std::string& object) const {
    const Scene& scene = state_->scene;
    const std::optional<std::uint32_t> found = scene.findObject(object);
    if (!found) {
        if (scene.findLight(object)) return {};
        throw std::invalid_argument("no object '" + object + "' in " + scene.sourcePath);
    }
    const Object& o = scene.objects[*found];
    std::vector<std::uint32_t> materials;
    for (std::uint32_t p = o.firstPolygon; p < o.firstPolygon + o.polygonCount; ++p)
        materials.push_back(scene.polygons[p].material);
    return materials;
}

FrameStats Engine::editMaterial(const std::string& object, const std::optional<glm::dvec3>& emission,
                                const std::optional<glm::dvec3>& reflectance, const UpdateSettings& settings) {
    return editMaterials({{object, emission, reflectance}}, settings);
}

namespace {

std::string channels(const glm::dvec3& v) {
    std::ostringstream out;
    out << v.x << "," << v.y << "," << v.z;
    return out.str();
}

std::string number(double x) {
    std::ostringstream out;
    out << x;
    return out.str();
}

}  // namespace

FrameStats Engine::editMaterials(const std::vector<MaterialEdit>& edits, const UpdateSettings& settings) {
    State& s = *state_;
    if (!s.solved) throw std::logic_error("editMaterial before solve()");
    const auto start = std::chrono::steady_clock::now();
    // Every edit checked before any is applied.
    for (const MaterialEdit& e : edits) {
        const std::optional<std::uint32_t> found = s.scene.findObject(e.object);
        const bool light = s.scene.findLight(e.object).has_value();
        if (!light && (!found || s.scene.objects[*found].polygonCount == 0))
            throw std::invalid_argument("no object '" + e.object + "' with polygons and no light of that name in " +
                                        s.scene.sourcePath);
        if (light && e.reflectance)
            throw std::invalid_argument("'" + e.object + "' is a punctual light: it has no reflectance");
        if (e.emission && !(glm::all(glm::greaterThanEqual(*e.emission, glm::dvec3(0.0))) &&
                            glm::all(glm::lessThanEqual(*e.emission, glm::dvec3(kMaxEmission)))))
            throw std::invalid_argument("emission " + channels(*e.emission) + " of '" + e.object +
                                        "': each channel must be at least 0 and at most " + number(kMaxEmission));
        if (e.reflectance && !(glm::all(glm::greaterThanEqual(*e.reflectance, glm::dvec3(0.0))) &&
                               glm::all(glm::lessThanEqual(*e.reflectance, glm::dvec3(1.0)))))
            throw std::invalid_argument("reflectance " + channels(*e.reflectance) + " of '" + e.object +
                                        "': each channel must be in [0, 1]");
        if (!e.restore.empty()) {
            if (light || e.restore.size() != s.scene.objects[*found].polygonCount)
                throw std::invalid_argument("the materials to restore for '" + e.object + "' are " +
                                            std::to_string(e.restore.size()) + ", not one per polygon (" +
                                            std::to_string(light ? 0 : s.scene.objects[*found].polygonCount) + ")");
            for (std::uint32_t m : e.restore)
                if (m >= s.scene.materials.size())
                    throw std::invalid_argument("material " + std::to_string(m) + " to restore for '" + e.object +
                                                "' does not exist");
        }
    }
    // The update works with differences: a light dimmed a trillionfold at
    // once leaves differences of two nearly equal numbers, which rounding
    // swamps (the Cornell box's only light dimmed to 1e-14 of itself in one
    // edit came 0.9% from a full solve, to 1e-16 68%, and its oracles then
    // refined without end). Such an edit is refused; to 0, or in steps, it
    // is exact.
    if (const double before = emittedPower(s.scene); before > 0.0) {
        const double after = emittedPowerAfter(s.scene, edits);
        if (after > 0.0 && after < kLeastPowerRatio * before) {
            std::ostringstream m;
            m << "the edit of '" << edits.front().object << "' would leave the scene " << after / before
              << " of its emitted light at once; an edit can dim it at most " << 1.0 / kLeastPowerRatio
              << " times: set the light to 0, or dim it in steps";
            throw std::invalid_argument(m.str());
        }
    }
    s.abandonFinding();  // the light its links carry changes under a traversal under way
    std::vector<ElementId> changed;
    std::vector<std::uint32_t> editedLights;
    // What the edits change, if only emission (LineSpaceUpdate::propagate).
    EmissionChange emission;
    bool emissionOnly = true;
    for (const MaterialEdit& e : edits) {
        // A light's emission is its intensity (colour times intensity).
        if (const std::optional<std::uint32_t> light = s.scene.findLight(e.object)) {
            if (!e.emission || s.scene.lights[*light].intensity == *e.emission) continue;
            emission.emplace_back(static_cast<std::uint32_t>(s.scene.polygons.size()) + *light,
                                  *e.emission - s.scene.lights[*light].intensity);
            s.scene.lights[*light].intensity = *e.emission;
            editedLights.push_back(*light);  // summed again under the new threshold, below
            continue;
        }
        const Object& o = s.scene.objects[*s.scene.findObject(e.object)];
        // The object's own copies of its materials (other objects may share
        // them), with only the given values changed; or the materials it had.
        std::map<std::uint32_t, std::uint32_t> copyOf;
        for (std::uint32_t p = o.firstPolygon; p < o.firstPolygon + o.polygonCount && e.restore.empty(); ++p) {
            const std::uint32_t old = s.scene.polygons[p].material;
            if (copyOf.count(old)) continue;
            Material m = s.scene.materials[old];
            if (e.emission) m.emission = *e.emission;
            if (e.reflectance) m.reflectance = glm::min(*e.reflectance, glm::dvec3(kMaxReflectance));
            const Material& was = s.scene.materials[old];
            if (m.emission == was.emission && m.reflectance == was.reflectance) {
                copyOf[old] = old;  // nothing to change
                continue;
            }
            m.name = was.name + " (" + e.object + ", edited)";
            copyOf[old] = static_cast<std::uint32_t>(s.scene.materials.size());
            s.scene.materials.push_back(m);
        }
        for (std::uint32_t p = o.firstPolygon; p < o.firstPolygon + o.polygonCount; ++p) {
            const std::uint32_t material =
                e.restore.empty() ? copyOf[s.scene.polygons[p].material] : e.restore[p - o.firstPolygon];
            if (material == s.scene.polygons[p].material) continue;
            const Material& was = s.scene.materials[s.scene.polygons[p].material];
            s.scene.polygons[p].material = material;
            const Material& m = s.scene.materials[material];
            const ElementId top = s.hierarchy.polygonElement(p);
            if (top == kNone) continue;
            emissionOnly = emissionOnly && m.reflectance == was.reflectance;
            if (m.emission != was.emission) emission.emplace_back(p, m.emission - was.emission);
            changed.push_back(top);
            s.hierarchy.touchMesh(p);  // its mesh's colours come from the leaves' reflectance too
            // Every element of its quadtree: the leaves reflect, and children
            // made later copy their parent's.
            for (std::vector<ElementId> stack{top}; !stack.empty();) {
                const ElementId el = stack.back();
                stack.pop_back();
                s.hierarchy[el].reflectance = surfaceReflectance(s.scene, p, s.hierarchy[el].corners());
                for (ElementId c : s.hierarchy[el].children) stack.push_back(c);
            }
        }
    }
    // Refinement follows the light the edit changed in steps from the
    // solve's (update/OracleSteps.h), each element by its share of the
    // emitted power: an edit taken back returns to the solve's hierarchy.
    // The light links of punctual lights judge against the power now (in
    // the scale the solve's thresholds were taken in): an edited light's
    // direct light is summed again (a dark one linked) under it, and a
    // light whose share of it stepped is linked again
    // (LightLinks::judgedIntensity).
    const double power = s.scale * emittedPower(s.scene);
    std::vector<std::uint32_t> stepped;
    if (power > 0.0) {
        s.lightLinks.setThreshold(s.refiner.settings().epsilon * power);
        stepped = s.lightLinks.stepShares();
    }
    for (std::uint32_t light : stepped)
        for (ElementId e : s.lightLinks.relinkLight(light, s.lightDeadline(start, settings, 0.0))) changed.push_back(e);
    // Summed again whether linked again or not: a relink sums only the
    // polygons whose links changed, and an edited light's others still hold
    // its old intensity.
    for (std::uint32_t light : editedLights)
        for (ElementId e : s.lightLinks.refreshIntensity(light)) changed.push_back(e);
    if (changed.empty()) return FrameStats{};  // the values they already have: nothing changes
    if (!editedLights.empty() || !stepped.empty()) {
        s.updater.noteLightChanges(s.lightLinks.takeChanges());
        s.solver.setDirectBound(s.lightLinks.directBound());
    }
    const double lightSeconds = secondsSince(start);
    const UpdateSettings inner = s.forUpdater(settings, lightSeconds);
    std::sort(emission.begin(), emission.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    // Before the bounces: their thresholds follow the power now.
    if (power > 0.0) s.updater.setLightScale(s.anchorPower / power);
    FrameStats stats = s.updater.propagate(changed, inner, emissionOnly ? &emission : nullptr);
    s.updater.judgeAgain(inner, stats);
    stats.updateSeconds += lightSeconds;  // the light links made again
    stats.pending += s.lightLinks.pendingCount();
    s.buildMesh(stats, start, settings.deadlineSeconds);
    return stats;
}

std::size_t Engine::budgetFor(double targetSeconds) const { return state_->budget.budgetFor(targetSeconds); }

std::size_t Engine::linksCarrying(std::uint32_t from, const glm::dvec2& uvFrom, std::uint32_t to,
                                  const glm::dvec2& uvTo) const {
    const State& s = *state_;
    const std::vector<ElementId> sources = s.hierarchy.pathTo(from, uvFrom);
    std::size_t count = 0;
    for (ElementId r : s.hierarchy.pathTo(to, uvTo))
        for (LinkId id : s.hierarchy[r].links)
            count += std::find(sources.begin(), sources.end(), s.links[id].source) != sources.end();
    return count;
}

EnergyBalance Engine::energy() const {
    const State& s = *state_;
    EnergyBalance e = s.solver.energy();
    for (const PunctualLight& l : s.scene.lights) e.emitted += l.power();
    auditEnergy(s.scene, s.hierarchy, s.rays, e);
    return e;
}
MemoryStats Engine::memory() const {
    const State& s = *state_;
    return {s.hierarchy.memoryBytes(), s.links.memoryBytes() + s.lightLinks.memoryBytes(), s.updater.memoryBytes()};
}
std::size_t Engine::linkCount() const { return state_->links.liveCount(); }

RadiositySamples Engine::samples() const { return sampleRadiosity(state_->scene, state_->hierarchy); }

MeshSnapshot Engine::snapshotFromScratch() const { return makeRadiositySnapshot(state_->scene, state_->hierarchy); }

MeshSnapshot Engine::snapshot(SnapshotOverlays overlays) const {
    MeshSnapshot mesh = state_->meshValid ? state_->mesh : makeRadiositySnapshot(state_->scene, state_->hierarchy);
    // Every stride-th segment.
    auto add = [&](const std::vector<std::array<glm::dvec3, 2>>& segments, const glm::vec3& color, std::size_t stride) {
        for (std::size_t i = 0; i < segments.size(); i += stride)
            for (const glm::dvec3& p : segments[i]) {
                mesh.linePositions.emplace_back(p - mesh.origin);
                mesh.lineColors.push_back(color);
            }
    };
    mesh.modifiedLinks = state_->updater.modifiedLinkCount();
    if (overlays.modifiedLinks) {
        const auto links = state_->updater.modifiedLinks();
        const std::size_t most = std::max<std::size_t>(1, overlays.maxLinks);
        const std::size_t stride = std::max<std::size_t>(1, (links.size() + most - 1) / most);
        add(links, glm::vec3(1.0f, 0.85f, 0.1f), stride);
        mesh.modifiedLinksShown = (links.size() + stride - 1) / stride;
    }
    if (overlays.changedElements) add(state_->updater.changedOutlines(), glm::vec3(1.0f, 0.1f, 0.1f), 1);
    return mesh;
}

std::optional<std::uint32_t> Engine::pick(const glm::dvec3& origin, const glm::dvec3& direction) const {
    const State& s = *state_;
    const auto hit = s.rays.intersect(origin, direction, std::numeric_limits<double>::infinity());
    if (!hit) return std::nullopt;
    return s.scene.polygons[hit->polygon].object;
}

std::vector<ObjectRadiosity> Engine::objectRadiosity() const {
    std::vector<ObjectRadiosity> out;
    const State& s = *state_;
    for (std::uint32_t o = 0; o < s.scene.objects.size(); ++o) {
        ObjectRadiosity r;
        r.name = s.scene.objects[o].name;
        const ElementId c = s.hierarchy.objectCluster(o);
        if (c != kNone) {
            r.area = s.hierarchy[c].area;
            r.radiosity = s.hierarchy[c].radiosity;
        }
        out.push_back(r);
    }
    return out;
}

const Scene& Engine::scene() const { return state_->scene; }
const SolveStats& Engine::stats() const { return state_->stats; }

}  // namespace rad
