// --headless-stress N: the engine thread without a window. One thread sends
// transforms (and now and then other commands) while this one reads
// snapshots, as the render loop would; run under ThreadSanitizer to check
// the hand-over.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "radiosity/Gltf.h"
#include "viewer/EngineThread.h"
#include "viewer/ViewerOptions.h"

namespace rad::viewer {

int runHeadlessStress(const ViewerOptions& options) {
    Scene scene = loadGltf(options.scene);
    std::optional<std::uint32_t> object;
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o)
        if (scene.objects[o].polygonCount > 0 &&
            (options.select.empty() ? scene.objects[o].dynamic : scene.objects[o].name == options.select)) {
            object = o;
            break;
        }
    if (!object) throw std::runtime_error(options.scene + (options.select.empty() ? ": no object marked dynamic to move; name one with --select"
                                                                                 : ": no object named '" + options.select + "' with polygons"));
    const glm::dmat4 start = scene.objects[*object].worldFromLocal;
    const std::string name = scene.objects[*object].name;
    const Aabb box = scene.objectBounds(*object);
    const double step = 0.1 * std::max({box.extent().x, box.extent().z, 1e-6});
    const int n = *options.headlessStress;

    EngineThreadOptions eo;
    eo.targetFps = options.targetFps;
    eo.select = name;
    if (options.logTransforms)
        eo.log = [](const std::string& line) {
            std::printf("%s\n", line.c_str());
            std::fflush(stdout);
        };
    EngineThread engine(std::move(scene), options.engine, eo);

    // Wait for the solve (reading snapshots the whole time).
    const auto t0 = std::chrono::steady_clock::now();
    std::shared_ptr<const ViewerSnapshot> s = engine.latest();
    while (s->solving && s->error.empty()) {
        s = engine.waitNewer(s->version, 1.0);
        if (std::chrono::steady_clock::now() - t0 > std::chrono::minutes(5))
            throw std::runtime_error("headless-stress: the solve took longer than 5 minutes");
    }
    if (!s->error.empty()) throw std::runtime_error(s->error);

    auto transformAt = [&](int i) {
        glm::dmat4 m = start;
        m[3][0] += step * std::sin(0.05 * i);
        m[3][2] += 0.5 * step * (1.0 - std::cos(0.05 * i));
        return m;
    };
    std::thread sender([&] {
        for (int i = 1; i <= n; ++i) {
            engine.post(SetTransform{*object, transformAt(i)});
            if (i % 50 == 0) engine.post(SetTargetFps{i % 100 == 0 ? 60.0 : 20.0});
            if (i % 70 == 0) engine.post(SetOverlays{{i % 140 == 0, true}});
            std::this_thread::sleep_for(std::chrono::microseconds(500));
        }
    });
    std::size_t reads = 0, triangles = 0;
    std::uint64_t lastVersion = 0;
    while (true) {
        s = engine.latest();
        if (s->version != lastVersion) {
            lastVersion = s->version;
            if (!s->mesh) throw std::runtime_error("headless-stress: a snapshot without a mesh");
            triangles += s->mesh->indices.size() / 3;
            ++reads;
        }
        bool done = false;
        for (const ObjectInfo& info : s->objects)
            if (info.name == name && info.worldFromLocal == transformAt(n)) done = true;
        if (done) break;
        if (std::chrono::steady_clock::now() - t0 > std::chrono::minutes(10))
            throw std::runtime_error("headless-stress: the last transform never arrived");
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    sender.join();
    std::printf("headless-stress: %d transforms sent, %llu applied, %zu snapshots read (%zu triangles)\n", n,
                static_cast<unsigned long long>(s->moves), reads, triangles);
    engine.stop();
    return s->moves > 0 ? 0 : 1;
}

}  // namespace rad::viewer
