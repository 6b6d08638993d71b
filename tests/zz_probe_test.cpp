#include <gtest/gtest.h>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"
#include "support/TestScenes.h"
namespace rad {
TEST(Probe, Floor) {
    const Scene loaded = loadGltf(test::sourcePath("scenes/building-floor.gltf"));
    Engine engine(loaded, EngineSettings{});
    engine.solve();
    const std::uint32_t chair = *engine.scene().findObject("chair");
    engine.setDynamicObject("chair");
    const glm::dmat4 start = engine.scene().objects[chair].worldFromLocal;
    std::vector<double> times;
    for (int f = 1; f <= 30; ++f) {
        UpdateSettings u;
        u.budget = engine.budgetFor(1.0 / 30);
        u.deadlineSeconds = 1.0 / 30;
        const FrameStats fs = engine.moveDynamicObject(glm::translate(glm::dmat4(1.0), glm::dvec3(f / 30.0, 0, 0)) * start, u);
        times.push_back(fs.totalSeconds);
    }
    std::vector<double> s = times; std::sort(s.begin(), s.end());
    std::printf("frames: median %.1f p95 %.1f worst %.1f ms\n", 1e3 * s[15], 1e3 * s[28], 1e3 * s[29]);
    Engine full(engine.scene(), EngineSettings{});
    full.solve();
    const RadiositySamples ref = full.samples();
    auto report = [&](const char* when) {
        const SolutionError e = compareSamples(engine.samples(), ref);
        std::vector<std::pair<double, std::uint32_t>> worst;
        for (const ObjectError& o : e.objects) if (!o.dark) worst.push_back({o.rms, o.object});
        std::sort(worst.rbegin(), worst.rend());
        std::printf("%s: rms %.4f%% worst object %.3f%%:", when, 100 * e.rms, 100 * e.worstObjectRms);
        for (int k = 0; k < 6; ++k) std::printf(" %s %.2f%%", engine.scene().objects[worst[k].second].name.c_str(), 100 * worst[k].first);
        std::printf("\n");
    };
    report("after frame 30");
    for (int k = 1; k <= 64; k *= 2) {
        for (int i = 0; i < k; ++i) { UpdateSettings u; u.deadlineSeconds = 1.0 / 30; engine.refinePending(u); }
    }
    report("after 127 idle frames");
}
}  // namespace rad
