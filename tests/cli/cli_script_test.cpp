// radiosity-cli animate --script on the Cornell box: moves and light or
// colour edits over the frames, checked against a from-scratch solve of every
// frame; and the one-line errors of bad scripts (exit 2).

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>

#include "support/Cli.h"
#include "support/GltfBuilder.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using nlohmann::json;
using test::jsonAt;
using test::kCornell;
using test::runCli;
using test::shellQuote;

std::string writeScript(const test::TempDir& dir, const std::string& name, const std::string& text) {
    const std::string path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
}

// animate SCENE --script SCRIPT --compare-full --report R: the run, and its
// report when it succeeded (null otherwise).
std::pair<test::RunResult, json> animateComparing(const test::TempDir& dir, const std::string& scene,
                                                  const std::string& script) {
    const std::string report = (dir / "r.json").string();
    test::RunResult r = runCli("animate " + shellQuote(scene) + " --script " + shellQuote(script) +
                               " --compare-full --report " + shellQuote(report));
    return {r, r.exitCode == 0 ? test::readJson(report) : json()};
}

// A box of quads (two triangles each) as a node of its own; `inward` turns
// its faces to its inside (a room); `extras`: the node's extras, if any.
void addBox(test::GltfBuilder& g, int material, const std::string& name, glm::vec3 lo, glm::vec3 hi, bool inward,
            const std::string& extras = "") {
    std::vector<glm::vec3> p;
    std::vector<std::uint32_t> idx;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const auto base = static_cast<std::uint32_t>(p.size());
            for (auto [a, b] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
                glm::vec3 q;
                q[axis] = side ? hi[axis] : lo[axis];
                q[u] = a ? hi[u] : lo[u];
                q[v] = b ? hi[v] : lo[v];
                p.push_back(q);
            }
            // (u, v) counter-clockwise faces +axis: outward on the high side.
            const bool flip = (side == 0) != inward;
            for (std::uint32_t k : flip ? std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2}
                                        : std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3})
                idx.push_back(base + k);
        }
    g.addNode("\"name\":\"" + name + "\",\"mesh\":" +
              std::to_string(g.addMesh(name, g.addPositions(p), g.addIndices(idx), material)) +
              (extras.empty() ? "" : ",\"extras\":" + extras));
}

TEST(CliScript, MovesAndEditsMatchAFullSolveEveryFrame) {
    test::TempDir dir;
    const std::string script = writeScript(dir, "moves.json", R"({"frames": 3, "actions": [
        {"object": "short-block", "translate": [0, 0, 0.15]},
        {"object": "short-block", "rotate": [0, 1, 0, 15]},
        {"object": "light", "emission": [12, 10, 6]},
        {"object": "back-wall", "reflectance": [0.2, 0.5, 0.3]}]})");
    const auto [r, doc] = animateComparing(dir, kCornell, script);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(jsonAt(doc, "/object"), "short-block");
    EXPECT_EQ(jsonAt(doc, "/frames_requested"), 3);
    const json frames = jsonAt(doc, "/frames");
    ASSERT_EQ(frames.size(), 3u);
    for (const json& f : frames) {
        EXPECT_LE(jsonAt(f, "/error_vs_full/rms"), 0.01) << f.dump();
        EXPECT_LE(jsonAt(f, "/error_vs_full/worst_object_rms"), 0.05) << f.dump();
        EXPECT_GT(jsonAt(f, "/changed_elements"), 0);
    }
}

// A closed 4 x 3 x 4 m room lit by a KHR_lights_punctual point light, with a
// box on the floor: the script carries the light across the room and dims
// it; every frame matches a full solve of the scene as it then is.
TEST(CliScript, APunctualLightMovesAndDimsInAScript) {
    test::TempDir dir;
    test::GltfBuilder g;
    const int grey = g.addGrey("grey", 0.6);
    addBox(g, grey, "room", {0, 0, 0}, {4, 3, 4}, true);
    addBox(g, grey, "box", {1.5f, 0, 1.5f}, {2.3f, 0.8f, 2.3f}, false);
    g.extraTopLevel = R"("extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","color":[1,0.9,0.8],"intensity":40}]}},)";
    g.addNode(R"("name":"bulb","translation":[1,2.5,1],"extensions":{"KHR_lights_punctual":{"light":0}})");
    const std::string scene = g.writeEmbedded(dir).string();
    const std::string script = writeScript(dir, "lamp.json", R"({"frames": 3, "actions": [
        {"object": "bulb", "translate": [2, 0, 2]},
        {"object": "bulb", "emission": [10, 9, 8]}]})");
    const auto [r, doc] = animateComparing(dir, scene, script);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(jsonAt(doc, "/moving_objects"), json::array({"bulb"}));
    const json frames = jsonAt(doc, "/frames");
    ASSERT_EQ(frames.size(), 3u);
    for (const json& f : frames) {
        EXPECT_LE(jsonAt(f, "/error_vs_full/rms"), 0.01) << f.dump();
        EXPECT_LE(jsonAt(f, "/error_vs_full/worst_object_rms"), 0.03) << f.dump();
    }
    // A light has no reflectance to set.
    const std::string bad = writeScript(dir, "bad.json", R"({"frames": 1, "actions": [
        {"object": "bulb", "reflectance": [0.5, 0.5, 0.5]}]})");
    const auto e = runCli("animate " + shellQuote(scene) + " --script " + shellQuote(bad));
    EXPECT_EQ(e.exitCode, 2) << e.output;
    EXPECT_NE(e.output.find("punctual light"), std::string::npos) << e.output;
}

// An object not marked dynamic that the import cut where it passes into
// another (a shelf sunk 10 cm into a pillar) keeps the hole when moved: the
// move warns, naming it and the area left out, on stderr and in the report.
// One marked dynamic is imported whole and moves without a word.
TEST(CliScript, MovingAnObjectTheImportCutWarns) {
    test::TempDir dir;
    test::GltfBuilder g;
    const int grey = g.addGrey("grey", 0.6);
    const int lamp = g.addMaterial(R"({"name":"lamp","emissiveFactor":[1,1,1],)"
                                   R"("pbrMetallicRoughness":{"baseColorFactor":[0.8,0.8,0.8,1]}})");
    addBox(g, grey, "room", {0, 0, 0}, {4, 3, 4}, true);
    addBox(g, grey, "pillar", {2.0f, 0, 1.0f}, {2.4f, 3.0f, 1.4f}, false);
    addBox(g, grey, "shelf", {1.0f, 1.0f, 1.1f}, {2.1f, 1.05f, 1.3f}, false);  // its last 10 cm in the pillar
    addBox(g, grey, "crate", {1.9f, 0, 2.0f}, {2.5f, 0.4f, 2.6f}, false, R"({"dynamic":true})");
    addBox(g, grey, "bin", {2.3f, 0, 2.4f}, {2.8f, 0.3f, 2.9f}, false);  // passes into the crate: left whole
    addBox(g, lamp, "panel", {1.5f, 2.98f, 1.5f}, {2.5f, 2.99f, 2.5f}, false);
    const std::string scene = g.writeEmbedded(dir).string();
    const std::string report = (dir / "r.json").string();
    const std::string script = writeScript(dir, "move.json", R"({"frames": 1, "actions": [
        {"object": "shelf", "translate": [-0.5, 0, 0]},
        {"object": "crate", "translate": [-0.5, 0, 0]}]})");
    const auto r = runCli("animate " + shellQuote(scene) + " --script " + shellQuote(script) + " --report " +
                          shellQuote(report));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("warning: 'shelf' is not marked dynamic and the import left 0.0"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("warning: 'crate'"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("warning: 'bin'"), std::string::npos) << r.output;
    const json doc = test::readJson(report);
    int found = 0;
    for (const json& w : jsonAt(doc, "/warnings")) {
        if (w.at("kind") != "moved_cut_object") continue;
        ++found;
        EXPECT_EQ(w.at("objects"), json::array({"shelf"}));
        // The shelf's top, bottom and two sides lose 10 cm each inside the
        // pillar (4 x 0.1 x 0.2 or 0.05), and its end face is inside whole.
        EXPECT_NEAR(w.at("amount").get<double>(), 2 * 0.1 * 0.2 + 2 * 0.1 * 0.05 + 0.2 * 0.05, 1e-6) << w.dump();
    }
    EXPECT_EQ(found, 1) << jsonAt(doc, "/warnings").dump();
}

TEST(CliScript, TwoObjectsMoveAtOnce) {
    test::TempDir dir;
    const std::string script = writeScript(dir, "two.json", R"({"frames": 2, "actions": [
        {"object": "short-block", "translate": [0, 0, 0.12]},
        {"object": "tall-block", "translate": [0.1, 0, 0]},
        {"object": "tall-block", "rotate": [0, 1, 0, -10]}]})");
    const auto [r, doc] = animateComparing(dir, kCornell, script);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(jsonAt(doc, "/moving_objects"), json::array({"short-block", "tall-block"}));
    for (const json& f : jsonAt(doc, "/frames")) EXPECT_LE(jsonAt(f, "/error_vs_full/rms"), 0.01) << f.dump();
}

TEST(CliScript, EditsAloneNeedNoMovingObject) {
    test::TempDir dir;
    const std::string script = writeScript(dir, "dim.json", R"({"frames": 2, "actions": [
        {"object": "light", "emission": [2, 2, 2]}]})");
    const auto [r, doc] = animateComparing(dir, kCornell, script);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(jsonAt(doc, "/object").is_null());
    const json frames = jsonAt(doc, "/frames");
    ASSERT_EQ(frames.size(), 2u);
    // The only light dimmed, halfway and all the way: as a full solve of
    // each frame's scene has it.
    for (const json& f : frames) EXPECT_LE(jsonAt(f, "/error_vs_full/rms"), 0.01) << f.dump();
}

// The only light dimmed to zero: the last frame's full solve is black, so
// no error relative to it is measured (its mean is 0). The frame says so
// and the run goes on, where the full solve used to stop it with "nothing
// emits light" and no report; the sweep leaves the frame out of its errors.
TEST(CliScript, ALightDimmedToBlackIsComparedUntilNothingEmits) {
    test::TempDir dir;
    const std::string script = writeScript(dir, "off.json", R"({"frames": 2, "actions": [
        {"object": "light", "emission": [0, 0, 0]}]})");
    const auto [r, doc] = animateComparing(dir, kCornell, script);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("frame 2: nothing emits light"), std::string::npos) << r.output;
    const json frames = jsonAt(doc, "/frames");
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_LE(jsonAt(frames[0], "/error_vs_full/rms"), 0.01) << frames[0].dump();
    EXPECT_FALSE(frames[1].contains("error_vs_full")) << frames[1].dump();
    const auto sweep = runCli("sweep " + shellQuote(kCornell) + " --script " + shellQuote(script) +
                              " --budgets inf --reference-epsilon 5e-5 --out " + shellQuote((dir / "sweep").string()));
    ASSERT_EQ(sweep.exitCode, 0) << sweep.output;
    const json run = jsonAt(test::readJson((dir / "sweep" / "trade.json").string()), "/runs/0");
    EXPECT_LE(jsonAt(run, "/worst_rms"), 0.01) << run.dump();
}

TEST(CliScript, BadScriptsFailWithOneLineNamingTheAction) {
    test::TempDir dir;
    const auto run = [&](const std::string& text) {
        return runCli("animate " + shellQuote(kCornell) + " --script " + shellQuote(writeScript(dir, "bad.json", text)));
    };
    const struct {
        const char* script;
        const char* says;
    } cases[] = {
        {R"({"frames": 2, "actions": [{"object": "nobody", "translate": [0, 0, 1]}]})", "nobody"},
        {R"({"frames": 2, "actions": [{"object": "light", "emission": [1, 2]}]})", "action 1 ('light')"},
        {R"({"frames": 2, "actions": [{"object": "tall-block", "translate": [0, 0, 1]},
             {"object": "back-wall", "reflectance": [0.5, 1.5, 0.5]}]})", "action 2 ('back-wall')"},
        {R"({"frames": 2, "actions": [{"object": "light", "emission": [-1, 0, 0]}]})", "emission"},
        // Finite, but brighter than any light (kMaxEmission): refused before the solve.
        {R"({"frames": 2, "actions": [{"object": "light", "emission": [1.7e308, 1e308, 1e308]}]})",
         "action 1 ('light'): emission must be at least 0 and at most 1e+12"},
        {R"({"frames": 2, "actions": [{"object": "tall-block", "rotate": [0, 0, 0, 10]}]})", "axis"},
        {R"({"frames": 2, "actions": [{"object": "light", "spin": 3}]})", "spin"},
        {R"({"frames": 0, "actions": [{"object": "light", "translate": [0, 0, 1]}]})", "frames"},
        {R"({"frames": 2, "actions": [{"object": "light", "translate": [0, 0, 1]})", "JSON"},
        {R"({"frames": 2, "actions": [{"object": "light", "emission": [1e309, 0, 0]}]})", "JSON"},
        // Out of the rays' reach (Embree aborted on such a move).
        {R"({"frames": 2, "actions": [{"object": "tall-block", "translate": [1e30, 0, 0]}]})",
         "frame 1: 'tall-block' would be moved"},
    };
    for (const auto& c : cases) {
        const auto r = run(c.script);
        EXPECT_EQ(r.exitCode, 2) << c.script << "\n" << r.output;
        EXPECT_NE(r.output.find(c.says), std::string::npos) << c.script << "\n" << r.output;
        EXPECT_EQ(r.output.find("error:"), r.output.rfind("error:")) << "one error line: " << r.output;
    }
    // A move out of reach is found before the solve, not when its frame comes.
    const auto far = run(R"({"frames": 2, "actions": [{"object": "tall-block", "translate": [1e30, 0, 0]}]})");
    EXPECT_EQ(far.output.find("solve"), std::string::npos) << far.output;
    // --script stands for the motion options.
    const auto r = runCli("animate " + shellQuote(kCornell) + " --script " +
                          shellQuote(writeScript(dir, "ok.json", R"({"frames": 1, "actions": [{"object": "light", "emission": [1, 1, 1]}]})")) +
                          " --object light");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(runCli("animate " + shellQuote(kCornell) + " --script " + shellQuote((dir / "missing.json").string())).exitCode, 2);
    const auto directory = runCli("animate " + shellQuote(kCornell) + " --script " + shellQuote(dir.path().string()));
    EXPECT_EQ(directory.exitCode, 2) << directory.output;
    EXPECT_NE(directory.output.find("directory"), std::string::npos) << directory.output;
}

}  // namespace
}  // namespace rad
