// Initial solve of the shipped scenes (issue: the converged static
// solution): time, elements, links and memory per link.
//   build/bench/radiosity-bench --benchmark_filter=InitialSolve
// Counters: elements, links (active), plinks, bytes_per_link (all engine
// memory divided by links + p-links).

#include <benchmark/benchmark.h>

#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"

namespace {

void InitialSolve(benchmark::State& state, const char* scene) {
    const rad::Scene loaded = rad::loadGltf(std::string(RADIOSITY_SOURCE_DIR) + "/scenes/" + scene);
    rad::SolveStats stats;
    for (auto _ : state) {
        rad::Engine engine(loaded, rad::EngineSettings{});
        stats = engine.solve();
    }
    state.counters["polygons"] = double(stats.polygons);
    state.counters["elements"] = double(stats.elements);
    state.counters["links"] = double(stats.links);
    state.counters["plinks"] = double(stats.passiveLinks);
    state.counters["bytes_per_link"] = double(stats.memory.total()) / double(stats.links + stats.passiveLinks);
    state.counters["refine_s"] = stats.refineSeconds;
    state.counters["solve_s"] = stats.solveSeconds;
}

BENCHMARK_CAPTURE(InitialSolve, office, "office.gltf")->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(InitialSolve, two_offices, "two-offices.gltf")->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
