// Punctual lights (KHR_lights_punctual), written into glTF files as a
// modelling tool writes them, checked against closed forms: a point light of
// intensity I at height h over the centre of a square floor of side L and
// reflectance rho, nothing else, gives the floor a mean radiosity of
// rho I Omega / L^2, Omega the solid angle of the floor seen from the light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "geometry/RayCaster.h"
#include "hierarchy/Hierarchy.h"
#include "lights/LightLinks.h"
#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"
#include "support/GltfBuilder.h"
#include "support/Motion.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using test::GltfBuilder;
using test::TempDir;

// Solid angle of a 2a x 2a square seen from a point at height h over its centre.
double squareSolidAngle(double a, double h) { return 4.0 * std::asin(a * a / (a * a + h * h)); }

std::string number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

// A horizontal square of side 2a at height y, centred on the axis, facing
// up (+Y) or down.
int addSquare(GltfBuilder& g, const std::string& name, double a, double y, bool up, int material) {
    const float fa = static_cast<float>(a), fy = static_cast<float>(y);
    std::vector<glm::vec3> p = {{-fa, fy, -fa}, {-fa, fy, fa}, {fa, fy, fa}, {fa, fy, -fa}};
    if (!up) std::swap(p[1], p[3]);
    const int mesh = g.addMesh(name, g.addPositions(p), g.addIndices({0, 1, 2, 0, 2, 3}), material);
    return g.addNode("\"name\":\"" + name + "\",\"mesh\":" + std::to_string(mesh));
}

// The lights section and a node per light: `lights` is the JSON array.
void addLights(GltfBuilder& g, const std::string& lights) {
    g.extraTopLevel = "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":{"
                      "\"lights\":" + lights + "}},";
}

int addLightNode(GltfBuilder& g, const std::string& name, int light, const glm::dvec3& at,
                 const std::string& rotation = "") {
    return g.addNode("\"name\":\"" + name + "\",\"translation\":[" + number(at.x) + "," + number(at.y) + "," +
                     number(at.z) + "]" + rotation + ",\"extensions\":{\"KHR_lights_punctual\":{\"light\":" +
                     std::to_string(light) + "}}");
}

double floorRadiosity(const Engine& engine, const std::string& name = "floor") {
    for (const ObjectRadiosity& o : engine.objectRadiosity())
        if (o.name == name) return luminance(o.radiosity);
    ADD_FAILURE() << "no object " << name;
    return 0.0;
}

constexpr double kRho = 0.5;

// A floor of side 2a, a point light of intensity I at height h.
Scene pointOverFloor(const TempDir& dir, double a, double h, double intensity) {
    GltfBuilder g;
    addSquare(g, "floor", a, 0.0, true, g.addGrey("grey", kRho));
    addLights(g, "[{\"type\":\"point\",\"intensity\":" + number(intensity) + "}]");
    addLightNode(g, "bulb", 0, {0.0, h, 0.0});
    return loadGltf(g.writeEmbedded(dir).string());
}

TEST(PunctualLight, PointLightOverAFloorGivesTheClosedForm) {
    TempDir dir;
    for (const auto& [a, h] : {std::pair{1.0, 1.0}, std::pair{2.0, 0.5}}) {
        const double intensity = 10.0;
        Engine engine(pointOverFloor(dir, a, h, intensity), EngineSettings{});
        engine.solve();
        const double expected = kRho * intensity * squareSolidAngle(a, h) / (4.0 * a * a);
        EXPECT_NEAR(floorRadiosity(engine), expected, 0.01 * expected) << "a " << a << " h " << h;
        // Energy: the light's 4 pi I goes to the floor (the part in Omega)
        // or escapes; nothing is lost.
        const EnergyBalance e = engine.energy();
        EXPECT_NEAR(e.emitted, 4.0 * std::numbers::pi * intensity, 1e-9 * e.emitted);
        EXPECT_NEAR(e.received, intensity * squareSolidAngle(a, h), 0.01 * e.received);
        EXPECT_LT(std::abs(e.lost), 0.01 * e.emitted);
    }
}

// A spot light pointing down whose cone lands wholly on a floor: the floor
// receives the spot's whole power, luminance(I) times the integral of glTF's
// falloff (2 pi ((1 - cos inner) + (cos inner - cos outer) / 3)); a ring of
// floor around it, outside the outer cone, gets nothing.
TEST(PunctualLight, SpotLightSendsItsConeOnly) {
    TempDir dir;
    GltfBuilder g;
    const double a = 0.6, h = 1.0, inner = 0.3, outer = 0.5, intensity = 20.0;  // cone radius 0.55 m
    const int grey = g.addGrey("grey", kRho);
    addSquare(g, "floor", a, 0.0, true, grey);
    // The ring: four quads from |x|,|z| = a out to 3a, facing up.
    const float fa = static_cast<float>(a), fb = static_cast<float>(3.0 * a);
    std::vector<glm::vec3> ring = {{-fb, 0, -fb}, {-fb, 0, fb}, {-fa, 0, fb}, {-fa, 0, -fb},
                                   {fa, 0, -fb},  {fa, 0, fb},  {fb, 0, fb},  {fb, 0, -fb},
                                   {-fa, 0, fa},  {-fa, 0, fb}, {fa, 0, fb},  {fa, 0, fa},
                                   {-fa, 0, -fb}, {-fa, 0, -fa}, {fa, 0, -fa}, {fa, 0, -fb}};
    std::vector<std::uint32_t> idx;
    for (std::uint32_t q = 0; q < 4; ++q)
        for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) idx.push_back(4 * q + k);
    g.addNode("\"name\":\"ring\",\"mesh\":" + std::to_string(g.addMesh("ring", g.addPositions(ring), g.addIndices(idx), grey)));
    addLights(g, "[{\"type\":\"spot\",\"intensity\":" + number(intensity) + ",\"spot\":{\"innerConeAngle\":" +
                     number(inner) + ",\"outerConeAngle\":" + number(outer) + "}}]");
    // The node's -Z turned to -Y: a quarter turn about X.
    const double s = std::sqrt(0.5);
    addLightNode(g, "spot", 0, {0.0, h, 0.0}, ",\"rotation\":[" + number(-s) + ",0,0," + number(s) + "]");
    Engine engine(loadGltf(g.writeEmbedded(dir).string()), EngineSettings{});
    engine.solve();
    const double cone = 2.0 * std::numbers::pi * ((1.0 - std::cos(inner)) + (std::cos(inner) - std::cos(outer)) / 3.0);
    const EnergyBalance e = engine.energy();
    EXPECT_NEAR(e.emitted, intensity * cone, 1e-9 * e.emitted);
    EXPECT_NEAR(e.received, intensity * cone, 0.01 * e.received);
    const double expected = kRho * intensity * cone / (4.0 * a * a);
    EXPECT_NEAR(floorRadiosity(engine), expected, 0.01 * expected);
    EXPECT_EQ(floorRadiosity(engine, "ring"), 0.0);
}

// A floor of side 2a, a black square of side 2b at height y over its
// centre, facing up, and a point light of intensity I at height h.
constexpr double kA = 2.0, kH = 2.0, kB = 0.3, kY = 1.0, kIntensity = 10.0;
Scene blockerScene(const TempDir& dir) {
    GltfBuilder g;
    addSquare(g, "floor", kA, 0.0, true, g.addGrey("grey", kRho));
    addSquare(g, "blocker", kB, kY, true, g.addGrey("black", 0.0));
    addLights(g, "[{\"type\":\"point\",\"intensity\":" + number(kIntensity) + "}]");
    addLightNode(g, "bulb", 0, {0.0, kH, 0.0});
    return loadGltf(g.writeEmbedded(dir).string());
}

// A black square between the light and the floor takes its solid angle out
// of what the floor gets, whatever the sampling: rho I (Omega_floor -
// Omega_blocker) / L^2.
TEST(PunctualLight, ABlockerCastsItsShadow) {
    TempDir dir;
    Engine engine(blockerScene(dir), EngineSettings{});
    engine.solve();
    const double expected =
        kRho * kIntensity * (squareSolidAngle(kA, kH) - squareSolidAngle(kB, kH - kY)) / (4.0 * kA * kA);
    EXPECT_NEAR(floorRadiosity(engine), expected, 0.01 * expected);
}

// bench/untuned/random_room.py's seed 1 (tests/data/random-room-1.gltf):
// three spot lights over a floating box and a table. Made nearly black,
// the room absorbs what the spots send it at once. An element of the floor
// all of whose sample points fell in the box's and the table's shadows,
// around a band lit between them, was left unlinked and never refined: the
// room lost 2.3% of the light (0.7% now). Its corners, edge midpoints and
// centre are looked at too.
TEST(PunctualLight, ABandLitBetweenTwoShadowsKeepsItsLight) {
    Scene room = loadGltf(RADIOSITY_SOURCE_DIR "/tests/data/random-room-1.gltf");
    for (Material& m : room.materials) m.reflectance = glm::dvec3(0.01);
    Engine engine(std::move(room), EngineSettings{});
    const SolveStats& s = engine.solve();
    ASSERT_TRUE(s.converged);
    EXPECT_LT(s.energy.lost, 0.01 * s.energy.emitted) << "absorbed " << s.energy.absorbed / s.energy.emitted;
}

// The floor's radiosity in a solve of pointOverFloor with the bulb at `to`.
double solvedWithBulbAt(const TempDir& dir, double a, double h, double intensity, const glm::dvec3& to) {
    Scene moved = pointOverFloor(dir, a, h, intensity);
    moved.lights[0].position = to;
    Engine fresh(std::move(moved), EngineSettings{});
    fresh.solve();
    return floorRadiosity(fresh);
}

// A light is moved like any object, by name: the update equals a solve of
// the scene with the light where it ended, and dimming it to zero leaves
// the floor dark.
TEST(PunctualLight, MovedAndDimmedLikeAnObject) {
    TempDir dir;
    const double a = 1.0, h = 1.0, intensity = 10.0;
    Engine engine(pointOverFloor(dir, a, h, intensity), EngineSettings{});
    engine.solve();
    const glm::dvec3 to(0.4, 0.8, -0.3);
    engine.moveObjects({{"bulb", glm::translate(glm::dmat4(1.0), to)}});
    const double fresh = solvedWithBulbAt(dir, a, h, intensity, to);
    EXPECT_NEAR(floorRadiosity(engine), fresh, 0.01 * fresh);
    EXPECT_GT(std::abs(floorRadiosity(engine) - kRho * intensity * squareSolidAngle(a, h) / (4.0 * a * a)),
              0.05 * fresh);  // it did move the light

    engine.editMaterial("bulb", glm::dvec3(0.0), std::nullopt);
    EXPECT_EQ(floorRadiosity(engine), 0.0);
    engine.editMaterial("bulb", glm::dvec3(2.0 * intensity), std::nullopt);
    EXPECT_NEAR(floorRadiosity(engine), 2.0 * fresh, 0.01 * fresh);
    EXPECT_THROW(engine.editMaterial("bulb", std::nullopt, glm::dvec3(0.5)), std::invalid_argument);
}

// The blocker scene with a second bulb of intensity `side` off to the side,
// which the blocker does not shade; `name`: the file.
Scene twoBulbs(const TempDir& dir, double bulb, double side, const std::string& name) {
    GltfBuilder g;
    addSquare(g, "floor", kA, 0.0, true, g.addGrey("grey", kRho));
    addSquare(g, "blocker", kB, kY, true, g.addGrey("black", 0.0));
    // A small far tile, linked alike at any of these intensities: a relink
    // leaves its links as they were.
    const std::vector<glm::vec3> far = {{3, 0, 3}, {3, 0, 3.1f}, {3.1f, 0, 3.1f}, {3.1f, 0, 3}};
    g.addNode("\"name\":\"far\",\"mesh\":" +
              std::to_string(g.addMesh("far", g.addPositions(far), g.addIndices({0, 1, 2, 0, 2, 3}), g.addGrey("far", kRho))));
    addLights(g, "[{\"type\":\"point\",\"intensity\":" + number(bulb) + "},{\"type\":\"point\",\"intensity\":" +
                     number(side) + "}]");
    addLightNode(g, "bulb", 0, {0.0, kH, 0.0});
    addLightNode(g, "side", 1, {1.5, kH, 1.5});
    return loadGltf(g.writeEmbedded(dir, name).string());
}

// A light's links are refined by its share of the light (LightLinks::
// judgedIntensity): a bulb that casts the blocker's shadow at a hundredth
// of the side bulb's intensity is linked coarsely; brightened to the side
// bulb's, its shadow's edge is refined as a solve at that intensity refines
// it, and set back, its links return to the solve's.
TEST(PunctualLight, ABrightenedLightIsRefinedByItsNewShare) {
    TempDir dir;
    Engine engine(twoBulbs(dir, 0.1, 10.0, "dim.gltf"), EngineSettings{});
    ASSERT_TRUE(engine.solve().converged);
    const RadiositySamples solved = engine.samples();
    const MemoryStats before = engine.memory();
    engine.editMaterial("bulb", glm::dvec3(10.0), std::nullopt);
    Engine fresh(twoBulbs(dir, 10.0, 10.0, "bright.gltf"), EngineSettings{});
    ASSERT_TRUE(fresh.solve().converged);
    const SolutionError e = compareSamples(engine.samples(), fresh.samples());
    EXPECT_NEAR(floorRadiosity(engine, "far"), floorRadiosity(fresh, "far"), 1e-6 * floorRadiosity(fresh, "far"))
        << "the far tile's links did not change, its light did";
    std::printf("  brightened: rms %.5f max %.4f against a solve at that intensity; light links %zu -> %zu bytes\n",
                e.rms, e.max, before.links, engine.memory().links);
    EXPECT_LT(e.rms, 1e-4);  // measured 0: linked as the solve links it (46% rms before)
    EXPECT_GT(engine.memory().links, before.links);  // the shadow's edge refined
    // Set back, it has the solve's links again. (Brightened, it halved the
    // side bulb's share, which was linked again too, coarser: kept as they
    // were, finer, the side bulb's links left the brightened frame 1.3% rms
    // from the solve.)
    engine.editMaterial("bulb", glm::dvec3(0.1), std::nullopt);
    EXPECT_EQ(engine.memory().links, before.links);
    EXPECT_LT(compareSamples(engine.samples(), solved).rms, 1e-4);
}

// A light dark at the solve has no links; lit by an edit, it is linked under
// the threshold of the lit scene, as a solve of that scene links it, and
// that intensity becomes its anchor: brightened and set back to it, it has
// the same links again.
TEST(PunctualLight, ALightDarkAtTheSolveIsLinkedAsTheLitScene) {
    TempDir dir;
    Engine engine(twoBulbs(dir, 0.0, 10.0, "dark.gltf"), EngineSettings{});
    ASSERT_TRUE(engine.solve().converged);
    engine.editMaterial("bulb", glm::dvec3(10.0), std::nullopt);
    Engine fresh(twoBulbs(dir, 10.0, 10.0, "lit.gltf"), EngineSettings{});
    ASSERT_TRUE(fresh.solve().converged);
    EXPECT_LT(compareSamples(engine.samples(), fresh.samples()).rms, 1e-4);
    const MemoryStats lit = engine.memory();
    engine.editMaterial("bulb", glm::dvec3(40.0), std::nullopt);
    engine.editMaterial("bulb", glm::dvec3(10.0), std::nullopt);
    EXPECT_EQ(engine.memory().links, lit.links);
    EXPECT_LT(compareSamples(engine.samples(), fresh.samples()).rms, 1e-4);
}

// A light moved on a deadline already past is linked at the first level only
// (every polygon facing it, coarse); the polygons left coarse wait, pending,
// and idle frames on the same deadline link them in full, a few at a time:
// the floor then equals a solve with the light where it ended.
TEST(PunctualLight, AMovedLightOnADeadlineIsRefinedWhenIdle) {
    TempDir dir;
    const double a = 1.0, h = 1.0, intensity = 10.0;
    Engine engine(pointOverFloor(dir, a, h, intensity), EngineSettings{});
    engine.solve();
    const glm::dvec3 to(0.4, 0.8, -0.3);
    UpdateSettings past;
    past.deadlineSeconds = 0.0;
    const FrameStats moved = engine.moveObjects({{"bulb", glm::translate(glm::dmat4(1.0), to)}}, past);
    EXPECT_GT(moved.pending, 0u);
    FrameStats idle = engine.refinePending(past);
    for (int i = 0; i < 100 && idle.pending > 0; ++i) idle = engine.refinePending(past);
    EXPECT_EQ(idle.pending, 0u);
    const double fresh = solvedWithBulbAt(dir, a, h, intensity, to);
    EXPECT_NEAR(floorRadiosity(engine), fresh, 0.01 * fresh);
}

// A moved light whose push the deadline leaves for later: the solution still
// shows the light where it was, and the frame's estimated error says so
// (within the factor the estimate keeps for budget-starved moves; measured
// 0.68 rms and estimated 1.58, where it said 7e-5 before it counted the
// direct light waiting for its push).
TEST(PunctualLight, AMovedLightWhosePushWaitsCountsInTheEstimate) {
    Engine engine(loadGltf(test::sourcePath("scenes/lamp-room.gltf")), test::coarse());
    engine.solve();
    const glm::dmat4 at = engine.scene().lights[*engine.scene().findLight("bulb")].worldFromLocal;
    UpdateSettings past;
    past.deadlineSeconds = 0.0;
    const FrameStats moved = engine.moveObjects({{"bulb", glm::translate(glm::dmat4(1.0), glm::dvec3(0.3, 0.0, 0.2)) * at}}, past);
    const SolutionError measured = test::compareWithFullSolve(engine, test::coarse());
    ASSERT_GT(measured.rms, 0.05) << "the push waits: the floor keeps the light of where the bulb was";
    EXPECT_GT(moved.estimatedError, 0.2 * measured.rms);
    EXPECT_LT(moved.estimatedError, 5.0 * measured.rms);
}

// An object that moves into the light's path casts its shadow, and leaving
// takes it away: the update equals a solve of the scene as it ends.
TEST(PunctualLight, AMovingBlockerShadowsThroughTheUpdate) {
    TempDir dir;
    Engine engine(blockerScene(dir), EngineSettings{});
    engine.solve();
    const double shadowed = floorRadiosity(engine);
    // Out of the way: far to the side, above the light's height.
    engine.moveObjects({{"blocker", glm::translate(glm::dmat4(1.0), glm::dvec3(3.0, 2.0, 0.0))}});
    const double open = kRho * kIntensity * squareSolidAngle(kA, kH) / (4.0 * kA * kA);
    EXPECT_NEAR(floorRadiosity(engine), open, 0.01 * open);
    engine.moveObjects({{"blocker", glm::dmat4(1.0)}});
    EXPECT_NEAR(floorRadiosity(engine), shadowed, 0.001 * shadowed);
}

// After an object moves, the polygons it shades or shaded are linked to
// the lights again only below elements whose shaft toward a light meets its
// old or new box; the others keep their links (relinkAround). The direct
// light is the same, to the bit, as linking every such polygon again whole:
// bench/untuned/random_room.py's seed 1, its table moved under three spots.
TEST(PunctualLight, LinkedAgainAroundAMoveAsIfWhole) {
    Scene scene = loadGltf(RADIOSITY_SOURCE_DIR "/tests/data/random-room-1.gltf");
    const std::uint32_t table = *scene.findObject("table");
    std::vector<std::uint32_t> moved, others;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const Object& o = scene.objects[table];
        (p >= o.firstPolygon && p < o.firstPolygon + o.polygonCount ? moved : others).push_back(p);
    }
    double power = 0.0;
    for (const PunctualLight& l : scene.lights) power += l.power();
    struct Lit {
        Hierarchy h;
        RayCaster rays;
        LightLinks links;
        Lit(const Scene& s, double threshold, const std::vector<std::uint32_t>& fixed,
            const std::vector<std::uint32_t>& dynamic)
            : h(s, 1e-4), links(s, h, rays) {
            rays.setLayer(Layer::Static, s, fixed);
            rays.setLayer(Layer::Dynamic, s, dynamic);
            links.setThreshold(threshold);
            links.linkAll();
        }
    };
    const double threshold = EngineSettings{}.epsilon * power;
    Lit around(scene, threshold, others, moved), whole(scene, threshold, others, moved);
    const Aabb before = scene.objectBounds(table);
    for (std::uint32_t p : moved)
        for (glm::dvec3& v : scene.polygons[p].vertices) v += glm::dvec3(0.4, 0.0, 0.3);
    const std::vector<Aabb> boxes{before, scene.objectBounds(table)};
    for (Lit* lit : {&around, &whole}) {
        lit->rays.setLayer(Layer::Dynamic, scene, moved);
        lit->h.updateGeometry(lit->h.objectCluster(table));
        lit->h.refreshAncestors(lit->h.objectCluster(table));
    }
    const std::vector<ElementId> changed = around.links.relinkAround(moved, boxes);
    std::vector<std::uint32_t> shaded = moved;
    for (std::uint32_t p : whole.links.shadedBy(boxes)) shaded.push_back(p);
    std::sort(shaded.begin(), shaded.end());
    shaded.erase(std::unique(shaded.begin(), shaded.end()), shaded.end());
    EXPECT_EQ(changed, whole.links.relink(shaded));
    EXPECT_FALSE(changed.empty());
    EXPECT_GT(around.links.keptLastRelink(), 0u) << "every shaded element linked again";
    ASSERT_EQ(around.h.size(), whole.h.size());
    EXPECT_EQ(around.links.linkCount(), whole.links.linkCount());
    for (ElementId e = 0; e < around.h.size(); ++e) EXPECT_EQ(around.h.direct(e), whole.h.direct(e)) << "element " << e;
}

// A lamp: a node marked as one object, its shade and its bulb's light
// child nodes. Moving the lamp carries the light: the update equals a solve
// of the file with the lamp where it ended.
TEST(PunctualLight, ALightUnderAMovingObjectMovesWithIt) {
    TempDir dir;
    const auto lampScene = [&](const glm::dvec3& at) {
        GltfBuilder g;
        addSquare(g, "floor", 2.0, 0.0, true, g.addGrey("grey", kRho));
        const int shade = addSquare(g, "shade", 0.15, 0.2, false, g.addGrey("black", 0.0));
        addLights(g, "[{\"type\":\"point\",\"intensity\":10}]");
        const int bulb = addLightNode(g, "bulb", 0, {0.0, 0.0, 0.0});
        g.roots = {0};
        g.addNode("\"name\":\"lamp\",\"extras\":{\"object\":true},\"translation\":[" + number(at.x) + "," +
                  number(at.y) + "," + number(at.z) + "],\"children\":[" + std::to_string(shade) + "," +
                  std::to_string(bulb) + "]");
        return loadGltf(g.writeEmbedded(dir, "lamp.gltf").string());
    };
    const glm::dvec3 from(0.0, 1.0, 0.0), to(0.7, 1.3, -0.5);
    Engine engine(lampScene(from), EngineSettings{});
    ASSERT_EQ(engine.scene().lights.size(), 1u);
    EXPECT_EQ(engine.scene().lights[0].object, "lamp");
    engine.solve();
    const double before = floorRadiosity(engine);
    engine.moveObjects({{"lamp", glm::translate(glm::dmat4(1.0), to)}});
    Engine fresh(lampScene(to), EngineSettings{});
    fresh.solve();
    EXPECT_NEAR(engine.scene().lights[0].position.x, to.x, 1e-12);
    EXPECT_NEAR(floorRadiosity(engine), floorRadiosity(fresh), 0.01 * floorRadiosity(fresh));
    EXPECT_GT(std::abs(before - floorRadiosity(fresh)), 0.05 * floorRadiosity(fresh));
}

TEST(PunctualLight, BadLightsAreOneLineErrors) {
    TempDir dir;
    const auto errorFor = [&](const std::string& light) {
        GltfBuilder g;
        addSquare(g, "floor", 1.0, 0.0, true, g.addGrey("grey", kRho));
        addLights(g, "[" + light + "]");
        addLightNode(g, "bulb", 0, {0.0, 1.0, 0.0});
        try {
            loadGltf(g.writeEmbedded(dir).string());
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string negative = errorFor("{\"name\":\"L\",\"type\":\"point\",\"intensity\":-1}");
    EXPECT_NE(negative.find("light 'L'"), std::string::npos) << negative;
    EXPECT_NE(negative.find("intensity"), std::string::npos) << negative;
    const std::string cone =
        errorFor("{\"name\":\"S\",\"type\":\"spot\",\"spot\":{\"innerConeAngle\":0.6,\"outerConeAngle\":0.5}}");
    EXPECT_NE(cone.find("light 'S'"), std::string::npos) << cone;
    EXPECT_NE(cone.find("cone"), std::string::npos) << cone;
    EXPECT_NE(errorFor("{\"type\":\"point\",\"color\":[1,-1,1]}").find("color"), std::string::npos);
    for (const std::string& e : {negative, cone}) EXPECT_EQ(e.find('\n'), std::string::npos);

    // A directional light has no position: noted, and alone it lights nothing.
    GltfBuilder g;
    addSquare(g, "floor", 1.0, 0.0, true, g.addGrey("grey", kRho));
    addLights(g, "[{\"type\":\"directional\"}]");
    addLightNode(g, "sun", 0, {0.0, 1.0, 0.0});
    ImportNotes notes;
    const Scene s = loadGltf(g.writeEmbedded(dir).string(), &notes);
    EXPECT_TRUE(s.lights.empty());
    bool noted = false;
    for (const std::string& line : notes.lines) noted = noted || line.find("directional") != std::string::npos;
    EXPECT_TRUE(noted);
    EXPECT_THROW(Engine(s, EngineSettings{}), SceneError);
}

}  // namespace
}  // namespace rad
