// The viewer's engine thread (app/viewer/EngineThread.h) driven directly:
// the panel's colour and light controls post EditMaterial, and the published
// snapshot carries the new values and a picture lit by them.

#include <gtest/gtest.h>

#include <optional>

#include "radiosity/Gltf.h"
#include "support/TestScenes.h"
#include "viewer/EngineThread.h"

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

const viewer::ObjectInfo& objectNamed(const ViewerSnapshot& s, const std::string& name) {
    for (const viewer::ObjectInfo& o : s.objects)
        if (o.name == name) return o;
    throw std::runtime_error("no object " + name);
}

double meanColor(const MeshSnapshot& mesh) {
    double sum = 0.0;
    for (const glm::vec3& c : mesh.colors) sum += c.x + c.y + c.z;
    return mesh.colors.empty() ? 0.0 : sum / (3.0 * double(mesh.colors.size()));
}

TEST(EngineThread, LightAndColourEditsReachTheSnapshot) {
    EngineSettings settings;
    settings.epsilon = 1e-3;
    EngineThread thread(loadGltf(test::kCornell), settings);
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

}  // namespace
}  // namespace rad
