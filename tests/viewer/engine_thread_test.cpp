// The viewer's engine thread (app/viewer/EngineThread.h) driven directly:
// the panel's colour and light controls post EditMaterial, and the published
// snapshot carries the new values and a picture lit by them.

#include <gtest/gtest.h>

#include <optional>

#include <glm/gtc/matrix_transform.hpp>

#include "radiosity/Gltf.h"
#include "support/TestScenes.h"
#include "viewer/EngineThread.h"
#include "viewer/UndoHistory.h"

namespace rad {
namespace {

using viewer::EditMaterial;
using viewer::EngineThread;
using viewer::ViewerSnapshot;

// The newest snapshot for which `done` holds, waiting up to a minute.
template <class Done>
std::shared_ptr<const ViewerSnapshot> waitFor(const EngineThread& thread, const Done& done) {
    std::shared_ptr<const ViewerSnapshot> s = thread.latest();
    for (int i = 0; i < 600 && !done(*s); ++i) s = thread.waitNewer(s->version, 0.1);
    return s;
}

// No target frame rate: every frame unlimited, so what the test sees does
// not depend on how fast the machine (or the sanitizers) runs.
viewer::EngineThreadOptions unlimited() {
    viewer::EngineThreadOptions o;
    o.targetFps = 0.0;
    return o;
}

const viewer::ObjectInfo& objectNamed(const ViewerSnapshot& s, const std::string& name) {
    for (const viewer::ObjectInfo& o : s.objects)
        if (o.name == name) return o;
    throw std::runtime_error("no object " + name);
}

// The picture's mean over the surfaces: each triangle's mean vertex value
// weighted by its area (independent of how finely the mesh is cut).
double meanColor(const MeshSnapshot& mesh) {
    double sum = 0.0, area = 0.0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 a(mesh.positions[mesh.indices[t]]), b(mesh.positions[mesh.indices[t + 1]]),
            c(mesh.positions[mesh.indices[t + 2]]);
        const double at = 0.5 * glm::length(glm::cross(b - a, c - a));
        glm::dvec3 v(0.0);
        for (int k = 0; k < 3; ++k) v += glm::dvec3(mesh.colors[mesh.indices[t + k]]);
        sum += at * (v.x + v.y + v.z) / 9.0;
        area += at;
    }
    return area > 0.0 ? sum / area : 0.0;
}

TEST(EngineThread, LightAndColourEditsReachTheSnapshot) {
    EngineSettings settings;
    settings.epsilon = 1e-3;
    EngineThread thread(loadGltf(test::kCornell), settings, unlimited());
    const auto solved = waitFor(thread, [](const ViewerSnapshot& s) { return !s.solving && s.mesh; });
    ASSERT_FALSE(solved->solving);
    ASSERT_TRUE(solved->error.empty()) << solved->error;
    const glm::dvec3 light = objectNamed(*solved, "light").emission;
    ASSERT_GT(light.x, 0.0);
    const double before = meanColor(*solved->mesh);

    thread.post(EditMaterial{"light", 0.5 * light, std::nullopt});
    const auto dimmed = waitFor(thread, [&](const ViewerSnapshot& s) { return objectNamed(s, "light").emission == 0.5 * light; });
    ASSERT_EQ(objectNamed(*dimmed, "light").emission, 0.5 * light);
    // Half the light: the whole picture at half its brightness (the light's
    // own polygon, which reads E, included).
    EXPECT_NEAR(meanColor(*dimmed->mesh) / before, 0.5, 0.02);

    thread.post(EditMaterial{"back-wall", std::nullopt, glm::dvec3(0.2, 0.5, 0.3)});
    const auto coloured = waitFor(thread, [&](const ViewerSnapshot& s) {
        return objectNamed(s, "back-wall").reflectance == glm::dvec3(0.2, 0.5, 0.3);
    });
    EXPECT_EQ(objectNamed(*coloured, "back-wall").reflectance, glm::dvec3(0.2, 0.5, 0.3));
    EXPECT_EQ(objectNamed(*coloured, "light").emission, 0.5 * light) << "an edit keeps the earlier ones";

    // A bad value is refused with a note; the thread goes on.
    thread.post(EditMaterial{"back-wall", std::nullopt, glm::dvec3(0.2, 1.5, 0.3)});
    const auto refused = waitFor(thread, [](const ViewerSnapshot& s) { return !s.selectionNote.empty(); });
    EXPECT_NE(refused->selectionNote.find("reflectance"), std::string::npos) << refused->selectionNote;
}

// The viewer's undo history (Ctrl+Z, Ctrl+Shift+Z) over the engine thread:
// a move and an edit taken back in turn return the object and the picture
// to where they were, and redone they come back.
TEST(EngineThread, UndoAndRedoAMoveAndAnEdit) {
    EngineSettings settings;
    settings.epsilon = 1e-3;
    EngineThread thread(loadGltf(test::kCornell), settings, unlimited());
    const auto solved = waitFor(thread, [](const ViewerSnapshot& s) { return !s.solving && s.mesh; });
    ASSERT_TRUE(solved->error.empty()) << solved->error;
    std::uint32_t block = 0;
    while (solved->objects[block].name != "short-block") ++block;
    const glm::dmat4 start = solved->objects[block].worldFromLocal;
    const glm::dmat4 moved = glm::translate(glm::dmat4(1.0), glm::dvec3(0.1, 0.0, 0.05)) * start;
    const glm::dvec3 wall = objectNamed(*solved, "back-wall").reflectance;
    const double before = meanColor(*solved->mesh);

    viewer::UndoHistory history;
    const auto act = [&](const viewer::Command& undo, const viewer::Command& redo) {
        thread.post(redo);
        history.record(undo, redo);
    };
    act(viewer::SetTransform{block, start}, viewer::SetTransform{block, moved});
    act(EditMaterial{"back-wall", std::nullopt, wall}, EditMaterial{"back-wall", std::nullopt, glm::dvec3(0.1, 0.6, 0.2)});
    waitFor(thread, [&](const ViewerSnapshot& s) { return objectNamed(s, "back-wall").reflectance != wall; });

    for (int i = 0; i < 2; ++i) thread.post(*history.undo());
    EXPECT_FALSE(history.undo()) << "two steps, both undone";
    const auto undone = waitFor(thread, [&](const ViewerSnapshot& s) {
        return objectNamed(s, "back-wall").reflectance == wall && s.objects[block].worldFromLocal == start &&
               s.frame.pending + s.frame.stale == 0;
    });
    EXPECT_EQ(undone->objects[block].worldFromLocal, start);
    EXPECT_EQ(objectNamed(*undone, "back-wall").reflectance, wall);
    EXPECT_NEAR(meanColor(*undone->mesh) / before, 1.0, 0.001);

    thread.post(*history.redo());
    const auto redone = waitFor(thread, [&](const ViewerSnapshot& s) { return s.objects[block].worldFromLocal == moved; });
    EXPECT_EQ(redone->objects[block].worldFromLocal, moved);
    EXPECT_EQ(objectNamed(*redone, "back-wall").reflectance, wall) << "only the move is redone";
}

}  // namespace
}  // namespace rad
