#include "Engine.h"

#include <chrono>
#include <sstream>

#include "geometry/RayCaster.h"
#include "hierarchy/Hierarchy.h"
#include "links/Link.h"
#include "refine/Refiner.h"
#include "snapshot/RadiositySnapshot.h"

namespace rad {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double totalArea(const Scene& scene) {
    double a = 0.0;
    for (const Polygon& p : scene.polygons) a += p.area();
    return a;
}

double emittedPower(const Scene& scene) {
    double power = 0.0;
    for (const Polygon& p : scene.polygons) power += p.area() * luminance(scene.materials[p.material].emission);
    return power;
}

Scene checkedScene(Scene scene) {
    if (!scene.hasEmitter())
        throw SceneError(scene.sourcePath + ": nothing emits light (no material has a positive emissiveFactor); "
                         "there is nothing to solve");
    return scene;
}

}  // namespace

struct Engine::State {
    State(Scene s, const EngineSettings& settings)
        : scene(checkedScene(std::move(s))),
          settings(settings),
          hierarchy(scene, settings.minArea > 0.0 ? settings.minArea : 2e-5 * totalArea(scene)),
          refiner(hierarchy, links, rays,
                  RefineSettings{settings.epsilon, emittedPower(scene), settings.samplesPerSide, settings.maxLinks}),
          solver(hierarchy, links) {}

    Scene scene;
    EngineSettings settings;
    Hierarchy hierarchy;
    LinkStore links;
    RayCaster rays;
    Refiner refiner;
    Solver solver;
    SolveStats stats;
};

Engine::Engine(Scene scene, const EngineSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    state_ = std::make_unique<State>(std::move(scene), settings);
    State& s = *state_;
    // The dynamic object is the first one marked dynamic; the others are static.
    std::vector<std::uint32_t> staticPolygons, dynamicPolygons;
    std::optional<std::uint32_t> dynamicObject;
    for (std::uint32_t o = 0; o < s.scene.objects.size(); ++o)
        if (s.scene.objects[o].dynamic && s.scene.objects[o].polygonCount > 0) {
            dynamicObject = o;
            break;
        }
    for (std::uint32_t p = 0; p < s.scene.polygons.size(); ++p)
        (dynamicObject && s.scene.polygons[p].object == *dynamicObject ? dynamicPolygons : staticPolygons).push_back(p);
    s.rays.setLayer(Layer::Static, s.scene, staticPolygons);
    s.rays.setLayer(Layer::Dynamic, s.scene, dynamicPolygons);
    if (dynamicObject) s.refiner.setDynamicRange(s.hierarchy[s.hierarchy.objectCluster(*dynamicObject)].range);
    s.stats.polygons = s.scene.polygons.size();
    s.stats.minArea = s.hierarchy.minArea();
    s.stats.hierarchySeconds = secondsSince(start);
}

Engine::~Engine() = default;

const SolveStats& Engine::solve(const Progress& progress) {
    State& s = *state_;
    SolveStats& st = s.stats;
    s.refiner.linkRoot();
    // Radiosity starts at emission, so the first refinement sees the lights.
    s.solver.pushPull();
    for (int round = 1; round <= s.settings.maxRefineRounds; ++round) {
        auto t = std::chrono::steady_clock::now();
        const std::size_t refined = s.refiner.refineAll();
        st.refineSeconds += secondsSince(t);
        st.refineRounds = round;
        t = std::chrono::steady_clock::now();
        const SolveResult r = s.solver.solve(s.settings.solve);
        st.solveSeconds += secondsSince(t);
        st.iterations += r.iterations;
        st.converged = r.converged;
        if (progress) {
            std::ostringstream line;
            line << "round " << round << ": refined " << refined << " links, " << s.links.liveCount()
                 << " links in all, " << r.iterations << " sweeps, change " << r.lastChange;
            progress(line.str());
        }
        if (!r.converged) {
            std::ostringstream m;
            m << "did not converge: after " << r.iterations << " sweeps the estimated remaining error is "
              << r.estimatedError << " (tolerance " << s.settings.solve.tolerance
              << "); reflectance near 1 needs more sweeps (raise the iteration limit)";
            st.message = m.str();
            break;
        }
        if (refined == 0) break;
        if (round == s.settings.maxRefineRounds) st.message = "stopped refining after the round limit";
    }
    if (s.refiner.capReached()) st.message = "refinement stopped at the memory cap of " +
                                             std::to_string(s.settings.maxLinks) + " links";
    st.elements = s.hierarchy.liveCount();
    st.links = st.passiveLinks = 0;
    for (ElementId e = 0; e < s.hierarchy.size(); ++e) {
        st.links += s.hierarchy[e].links.size();
        st.passiveLinks += s.hierarchy[e].plinks.size();
    }
    st.memory = {s.hierarchy.memoryBytes(), s.links.memoryBytes()};
    st.energy = s.solver.energy();
    return st;
}

MeshSnapshot Engine::snapshot() const { return makeRadiositySnapshot(state_->scene, state_->hierarchy); }

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
