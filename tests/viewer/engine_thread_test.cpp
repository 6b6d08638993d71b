// The viewer's engine thread (app/viewer/EngineThread.h) driven directly:
// the panel's colour and light controls post EditMaterial, and the published
// snapshot carries the new values and a picture lit by them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "radiosity/Gltf.h"
#include "support/GltfBuilder.h"
#include "support/TempDir.h"
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

// At a target frame rate, a frame's deadline leaves publishing its picture
// (copying the lit mesh for the window) its time: the target frame time less
// what publications take, never under half of it. The building floor's
// copy takes 7 ms of a 33 ms frame, which the frames ran past their target
// by before. The objects' boxes it lists are kept while their transforms
// stay, and follow a move.
TEST(EngineThread, AFramesDeadlineLeavesPublishingThePictureItsTime) {
    EngineSettings settings;
    settings.epsilon = 1e-3;
    viewer::EngineThreadOptions options;
    options.targetFps = 30.0;
    EngineThread thread(loadGltf(test::kCornell), settings, options);
    const auto solved = waitFor(thread, [](const ViewerSnapshot& s) { return !s.solving && s.mesh; });
    ASSERT_TRUE(solved->error.empty()) << solved->error;
    std::uint32_t block = 0;
    while (solved->objects[block].name != "short-block") ++block;
    const glm::dmat4 start = solved->objects[block].worldFromLocal;
    for (int i = 1; i <= 3; ++i)
        thread.post(viewer::SetTransform{block, glm::translate(glm::dmat4(1.0), glm::dvec3(0.02 * i, 0.0, 0.0)) * start});
    const glm::dmat4 last = glm::translate(glm::dmat4(1.0), glm::dvec3(0.06, 0.0, 0.0)) * start;
    const auto moved = waitFor(thread, [&](const ViewerSnapshot& s) { return s.objects[block].worldFromLocal == last && s.mesh; });
    ASSERT_EQ(moved->objects[block].worldFromLocal, last);
    // The listed box follows the move (boxes are kept while transforms stay).
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(moved->objects[block].bounds.lo[k], solved->objects[block].bounds.lo[k] + (k == 0 ? 0.06 : 0.0), 1e-9);
        EXPECT_NEAR(moved->objects[block].bounds.hi[k], solved->objects[block].bounds.hi[k] + (k == 0 ? 0.06 : 0.0), 1e-9);
    }
    const double target = 1.0 / 30.0;
    EXPECT_GT(moved->publishSeconds, 0.0);
    EXPECT_LT(moved->frameSeconds, target);
    EXPECT_GE(moved->frameSeconds, 0.5 * target);
    EXPECT_DOUBLE_EQ(moved->frameSeconds, std::max(0.5 * target, target - moved->publishSeconds));
    // Without a target frame rate, no deadline.
    EngineThread free(loadGltf(test::kCornell), settings, unlimited());
    EXPECT_EQ(waitFor(free, [](const ViewerSnapshot& s) { return !s.solving && s.mesh; })->frameSeconds, 0.0);
}

// An object of two materials: the panel's colour edit gives all of it one
// colour; its undo (the viewer posts the materials the snapshot listed)
// gives each polygon its own back, and the picture returns.
TEST(EngineThread, UndoOfAnEditGivesEachPolygonItsMaterialBack) {
    Scene scene = test::roomWithBlock();
    const std::uint32_t top = test::addMaterial(scene, glm::dvec3(0.9, 0.2, 0.1), glm::dvec3(0.0), "block-top");
    scene.polygons[scene.objects[*scene.findObject("block")].firstPolygon + 1].material = top;
    EngineSettings settings;
    settings.epsilon = 1e-3;
    EngineThread thread(std::move(scene), settings, unlimited());
    const auto solved = waitFor(thread, [](const ViewerSnapshot& s) { return !s.solving && s.mesh; });
    ASSERT_TRUE(solved->error.empty()) << solved->error;
    const std::shared_ptr<const std::vector<std::uint32_t>> materials = objectNamed(*solved, "block").materials;
    ASSERT_TRUE(materials);
    ASSERT_EQ(materials->size(), 6u);
    ASSERT_NE((*materials)[0], (*materials)[1]);
    const double before = meanColor(*solved->mesh);

    const glm::dvec3 green(0.1, 0.6, 0.2);
    thread.post(EditMaterial{"block", std::nullopt, green});
    const auto edited = waitFor(thread, [&](const ViewerSnapshot& s) { return objectNamed(s, "block").reflectance == green; });
    ASSERT_EQ(objectNamed(*edited, "block").reflectance, green);
    const std::vector<std::uint32_t> after = *objectNamed(*edited, "block").materials;
    EXPECT_NE(after, *materials) << "the edit gave the block copies of its materials in the new colour";

    thread.post(EditMaterial{"block", std::nullopt, std::nullopt, *materials});
    // Once idle time has sent what the edit's frame left unsent.
    const auto undone = waitFor(thread, [&](const ViewerSnapshot& s) {
        const FrameStats& f = s.frame;
        return *objectNamed(s, "block").materials == *materials &&
               f.pending + f.stale + f.unsent + f.deferred + f.unmeshed + f.finer == 0;
    });
    EXPECT_EQ(*objectNamed(*undone, "block").materials, *materials);
    EXPECT_NEAR(meanColor(*undone->mesh) / before, 1.0, 0.001);
}

std::uint32_t indexOf(const ViewerSnapshot& s, const std::string& name) {
    for (std::uint32_t i = 0; i < s.objects.size(); ++i)
        if (s.objects[i].name == name) return i;
    throw std::runtime_error("no object " + name);
}

std::string number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

// A horizontal square of side 2a at height y facing up (+Y), as a mesh; the
// node's members (name, mesh) for GltfBuilder::addNode.
std::string square(test::GltfBuilder& g, const std::string& name, double a, double y, int material) {
    const float fa = static_cast<float>(a), fy = static_cast<float>(y);
    const std::vector<glm::vec3> p = {{-fa, fy, -fa}, {-fa, fy, fa}, {fa, fy, fa}, {fa, fy, -fa}};
    const int mesh = g.addMesh(name, g.addPositions(p), g.addIndices({0, 1, 2, 0, 2, 3}), material);
    return "\"name\":\"" + name + "\",\"mesh\":" + std::to_string(mesh);
}

// A point light "bulb" (KHR_lights_punctual) of intensity 10 at `at`.
void addBulb(test::GltfBuilder& g, const glm::dvec3& at) {
    g.extraTopLevel = "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":{"
                      "\"lights\":[{\"type\":\"point\",\"intensity\":10}]}},";
    g.addNode("\"name\":\"bulb\",\"translation\":[" + number(at.x) + "," + number(at.y) + "," + number(at.z) +
              "],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}");
}

// Punctual lights in the viewer: listed after the objects, selected by name
// (they have no polygons to click), moved through SetTransform (the gizmo's
// command) and dimmed through EditMaterial (the panel's light controls), each
// changing the picture; the undo history takes both back.
TEST(EngineThread, MovesAndDimsAPunctualLight) {
    test::TempDir dir;
    test::GltfBuilder g;
    g.addNode(square(g, "floor", 1.0, 0.0, g.addGrey("grey", 0.5)));
    addBulb(g, {0.0, 1.0, 0.0});
    EngineSettings settings;
    settings.epsilon = 1e-3;
    EngineThread thread(loadGltf(g.writeEmbedded(dir).string()), settings, unlimited());
    const auto solved = waitFor(thread, [](const ViewerSnapshot& s) { return !s.solving && s.mesh; });
    ASSERT_TRUE(solved->error.empty()) << solved->error;
    const std::uint32_t bulb = indexOf(*solved, "bulb");
    const viewer::ObjectInfo& light = solved->objects[bulb];
    EXPECT_TRUE(light.light);
    EXPECT_TRUE(light.movable);
    EXPECT_EQ(light.bounds.center(), glm::dvec3(0.0, 1.0, 0.0));
    EXPECT_EQ(light.emission, glm::dvec3(10.0));
    EXPECT_FALSE(light.spot);
    EXPECT_FALSE(objectNamed(*solved, "floor").light);
    const double before = meanColor(*solved->mesh);
    ASSERT_GT(before, 0.0);

    thread.post(viewer::SelectObject{"bulb"});
    const auto selected = waitFor(thread, [&](const ViewerSnapshot& s) { return s.selected == bulb; });
    ASSERT_EQ(selected->selected, bulb) << selected->selectionNote;
    EXPECT_EQ(selected->selection, std::vector<std::uint32_t>{bulb});

    // Lower and to the side: the floor sees it under a larger solid angle.
    viewer::UndoHistory history;
    const glm::dmat4 start = light.worldFromLocal;
    const glm::dmat4 moved = glm::translate(glm::dmat4(1.0), glm::dvec3(0.2, 0.5, -0.1));
    thread.post(viewer::SetTransform{bulb, moved});
    history.record(viewer::SetTransform{bulb, start}, viewer::SetTransform{bulb, moved});
    const auto lowered = waitFor(thread, [&](const ViewerSnapshot& s) { return s.objects[bulb].worldFromLocal == moved; });
    ASSERT_EQ(lowered->objects[bulb].worldFromLocal, moved) << lowered->selectionNote;
    EXPECT_EQ(lowered->objects[bulb].bounds.center(), glm::dvec3(0.2, 0.5, -0.1));
    const double near = meanColor(*lowered->mesh);
    EXPECT_GT(near, 1.3 * before);

    // Turned about its own position (the gizmo's ring): it stays where it is.
    const glm::dmat4 turned = moved * glm::rotate(glm::dmat4(1.0), 0.5, glm::dvec3(0.0, 1.0, 0.0));
    thread.post(viewer::SetTransform{bulb, turned});
    const auto spun = waitFor(thread, [&](const ViewerSnapshot& s) { return s.objects[bulb].worldFromLocal == turned; });
    ASSERT_EQ(spun->objects[bulb].worldFromLocal, turned) << spun->selectionNote;
    EXPECT_LT(glm::length(spun->objects[bulb].bounds.center() - glm::dvec3(0.2, 0.5, -0.1)), 1e-12);
    EXPECT_NEAR(meanColor(*spun->mesh) / near, 1.0, 1e-3) << "a point light sends the same way everywhere";
    thread.post(viewer::SetTransform{bulb, moved});

    // Half its intensity: half the picture (it is the only light).
    thread.post(EditMaterial{"bulb", glm::dvec3(5.0), std::nullopt});
    history.record(EditMaterial{"bulb", glm::dvec3(10.0), std::nullopt}, EditMaterial{"bulb", glm::dvec3(5.0), std::nullopt});
    const auto dimmed = waitFor(thread, [&](const ViewerSnapshot& s) { return s.objects[bulb].emission == glm::dvec3(5.0); });
    ASSERT_EQ(dimmed->objects[bulb].emission, glm::dvec3(5.0)) << dimmed->selectionNote;
    EXPECT_NEAR(meanColor(*dimmed->mesh) / near, 0.5, 0.01);

    // A light has no reflectance: refused with a note, nothing changes.
    thread.post(EditMaterial{"bulb", std::nullopt, glm::dvec3(0.5)});
    const auto refused = waitFor(thread, [](const ViewerSnapshot& s) { return !s.selectionNote.empty(); });
    EXPECT_NE(refused->selectionNote.find("reflectance"), std::string::npos) << refused->selectionNote;

    // Ctrl+Z twice: the dimming, then the move.
    for (int i = 0; i < 2; ++i) thread.post(*history.undo());
    const auto undone = waitFor(thread, [&](const ViewerSnapshot& s) {
        return s.objects[bulb].worldFromLocal == start && s.objects[bulb].emission == glm::dvec3(10.0) &&
               s.frame.pending + s.frame.stale == 0;
    });
    ASSERT_EQ(undone->objects[bulb].worldFromLocal, start);
    EXPECT_EQ(undone->objects[bulb].emission, glm::dvec3(10.0));
    EXPECT_NEAR(meanColor(*undone->mesh) / before, 1.0, 0.01);
}

// The P key's command: the selection widened to the glTF node its objects
// share, then to the parent's subtree; the gizmo stays on its object, and
// the widened selection moves together.
TEST(EngineThread, WidenSelectionTakesTheParentNodesSubtree) {
    test::TempDir dir;
    test::GltfBuilder g;
    const int grey = g.addGrey("grey", 0.5);
    g.addNode(square(g, "floor", 2.0, 0.0, grey));                         // node 0
    const int base = g.addNode(square(g, "base", 0.2, 0.1, grey), false);  // node 1
    const int shade = g.addNode(square(g, "shade", 0.1, 0.4, grey), false);
    const int lamp = g.addNode("\"name\":\"lamp\",\"children\":[" + std::to_string(base) + "," +
                               std::to_string(shade) + "]", false);
    const int table = g.addNode(square(g, "table", 0.3, 0.3, grey), false);
    g.addNode("\"name\":\"corner\",\"translation\":[0.5,0,0.5],\"children\":[" + std::to_string(lamp) + "," +
              std::to_string(table) + "]");
    addBulb(g, {0.0, 1.5, 0.0});
    EngineSettings settings;
    settings.epsilon = 1e-3;
    EngineThread thread(loadGltf(g.writeEmbedded(dir).string()), settings, unlimited());
    const auto solved = waitFor(thread, [](const ViewerSnapshot& s) { return !s.solving && s.mesh; });
    ASSERT_TRUE(solved->error.empty()) << solved->error;
    const std::uint32_t iFloor = indexOf(*solved, "floor"), iBase = indexOf(*solved, "base"),
                        iShade = indexOf(*solved, "shade"), iTable = indexOf(*solved, "table"),
                        iBulb = indexOf(*solved, "bulb");
    const auto sorted = [](std::vector<std::uint32_t> v) {
        std::sort(v.begin(), v.end());
        return v;
    };
    using Ids = std::vector<std::uint32_t>;

    thread.post(viewer::SelectObject{"base"});
    waitFor(thread, [&](const ViewerSnapshot& s) { return s.selected == iBase; });
    thread.post(viewer::WidenSelection{});
    const auto lampWide = waitFor(thread, [&](const ViewerSnapshot& s) { return s.selection.size() == 2; });
    EXPECT_EQ(sorted(lampWide->selection), sorted(Ids{iBase, iShade})) << lampWide->selectionNote;
    EXPECT_EQ(lampWide->selected, iBase) << "the gizmo stays on its object";
    EXPECT_NE(lampWide->selectionNote.find("node " + std::to_string(lamp)), std::string::npos) << lampWide->selectionNote;

    thread.post(viewer::WidenSelection{});
    const auto cornerWide = waitFor(thread, [&](const ViewerSnapshot& s) { return s.selection.size() == 3; });
    EXPECT_EQ(sorted(cornerWide->selection), sorted(Ids{iBase, iShade, iTable})) << cornerWide->selectionNote;

    thread.post(viewer::WidenSelection{});
    // The whole scene: every object, and the light (its node is a root too).
    const auto all = waitFor(thread, [&](const ViewerSnapshot& s) { return s.selection.size() == 5; });
    EXPECT_EQ(sorted(all->selection), sorted(Ids{iFloor, iBase, iShade, iTable, iBulb}));

    thread.post(viewer::WidenSelection{});
    const auto nothing = waitFor(thread, [](const ViewerSnapshot& s) {
        return s.selectionNote.find("nothing to widen") != std::string::npos;
    });
    EXPECT_EQ(nothing->selection.size(), 5u);

    // The lamp's two parts moved as the gizmo moves a selection: one frame.
    thread.post(viewer::SelectObject{"shade"});
    waitFor(thread, [&](const ViewerSnapshot& s) { return s.selection.size() == 1; });
    thread.post(viewer::WidenSelection{});
    const auto lamp2 = waitFor(thread, [&](const ViewerSnapshot& s) { return s.selection.size() == 2; });
    ASSERT_EQ(sorted(lamp2->selection), sorted(Ids{iBase, iShade}));
    const glm::dmat4 shift = glm::translate(glm::dmat4(1.0), glm::dvec3(-0.3, 0.0, 0.2));
    viewer::SetTransforms moves;
    for (std::uint32_t o : lamp2->selection) moves.moves.push_back({o, shift * lamp2->objects[o].worldFromLocal});
    const std::uint64_t movesBefore = lamp2->moves;
    thread.post(moves);
    const auto moved = waitFor(thread, [&](const ViewerSnapshot& s) { return s.moves > movesBefore; });
    for (const viewer::SetTransform& m : moves.moves) EXPECT_EQ(moved->objects[m.object].worldFromLocal, m.worldFromLocal);
    EXPECT_EQ(moved->moves, movesBefore + 1) << "one frame for the group";
}

}  // namespace
}  // namespace rad
