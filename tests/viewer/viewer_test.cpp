// The viewer driven as a person would: a real window on Xvfb, screenshots,
// mouse drags with xdotool; and the engine thread under load without a window.
// Every run has the validation layer on and a time limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <utility>
#include <vector>

#include "support/Cli.h"
#include "support/GltfBuilder.h"
#include "support/TempDir.h"

namespace rad::test {
namespace {

const std::string kViewer = RADIOSITY_VIEWER;
const std::string kScene = std::string(RADIOSITY_SOURCE_DIR) + "/scenes/cornell-box.gltf";
const std::string kXvfb = "xvfb-run -a -s '-screen 0 1280x800x24' ";

struct ProcessResult {
    int exitCode = -1;
    std::string output;
};

ProcessResult run(const std::string& command) {
    ProcessResult r;
    std::string full = "RADIOSITY_VALIDATION=1 ";
    full += command;
    full += " 2>&1";
    FILE* pipe = popen(full.c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buf{};
    while (std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe)) r.output.append(buf.data(), n);
    const int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

// An 8-bit RGB picture read through ImageMagick (PNG -> binary PPM).
struct Picture {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    const unsigned char* at(int x, int y) const { return &rgb[3 * (std::size_t(y) * width + x)]; }
};

Picture readPicture(const std::string& png) {
    Picture p;
    const std::string ppm = png + ".ppm";
    if (std::system(("convert " + shellQuote(png) + " -strip " + shellQuote(ppm)).c_str()) != 0) return p;
    std::ifstream in(ppm, std::ios::binary);
    // Header: P6 width height maxval, with optional # comment lines between.
    auto token = [&in] {
        std::string t;
        while (in >> t && t[0] == '#') std::getline(in, t);
        return t;
    };
    const std::string magic = token();
    p.width = std::atoi(token().c_str());
    p.height = std::atoi(token().c_str());
    const int maxValue = std::atoi(token().c_str());
    in.get();
    if (magic != "P6" || maxValue != 255) return {};
    p.rgb.resize(std::size_t(p.width) * p.height * 3);
    in.read(reinterpret_cast<char*>(p.rgb.data()), static_cast<std::streamsize>(p.rgb.size()));
    return p;
}

template <typename Pred>
int countPixels(const Picture& p, int x0, int y0, int x1, int y1, Pred pred) {
    int n = 0;
    for (int y = y0; y < y1 && y < p.height; ++y)
        for (int x = x0; x < x1 && x < p.width; ++x) n += pred(p.at(x, y)) ? 1 : 0;
    return n;
}

// The panel's warning text: yellow (ImGui text antialiased over the dark
// window background).
bool warningText(const unsigned char* c) { return c[0] > 150 && c[1] > 120 && c[2] + 60 < c[1] && c[0] >= c[1]; }

double meanAbsDifference(const Picture& a, const Picture& b, int x0, int y0, int x1, int y1) {
    double sum = 0.0;
    int n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++n)
            for (int c = 0; c < 3; ++c) sum += std::abs(int(a.at(x, y)[c]) - int(b.at(x, y)[c]));
    return n ? sum / (3.0 * n) : 0.0;
}

TEST(ViewerTest, WithoutADisplayPointsToTheCli) {
    const ProcessResult r = run("env -u DISPLAY timeout 20 " + shellQuote(kViewer) + " " + shellQuote(kScene));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.output,
              "radiosity-viewer: no display (DISPLAY is not set); use radiosity-cli for headless work "
              "(radiosity-cli --help)\n");
}

TEST(ViewerTest, HelpListsEveryOption) {
    const ProcessResult r = run("timeout 20 " + shellQuote(kViewer) + " --help");
    EXPECT_EQ(r.exitCode, 0);
    for (const char* option : {"--screenshot-after", "--quit-after", "--log-transforms", "--select",
                               "--print-gizmo", "--overlays", "--headless-stress", "--target-fps",
                               "--epsilon", "RADIOSITY_TSAN"})
        EXPECT_NE(r.output.find(option), std::string::npos) << option;
}

TEST(ViewerTest, WindowShowsTheSolvedSceneAndThePanel) {
    ASSERT_TRUE(haveXvfb()) << "xvfb-run is not installed (apt-get install xvfb xauth)";
    TempDir dir;
    const std::string png = (dir / "window.png").string();
    const ProcessResult r = run("timeout 60 " + kXvfb + shellQuote(kViewer) + " " + shellQuote(kScene) +
                      " --screenshot-after 1.5 " + shellQuote(png) + " --quit-after 2.5");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // Written through the one PNG writer: renamed into place, no temporary left.
    EXPECT_FALSE(std::filesystem::exists(png + ".tmp"));
    const Picture p = readPicture(png);
    ASSERT_EQ(p.width, 1200) << r.output;
    ASSERT_EQ(p.height, 760);

    // The scene (right of the panel): the red and the green wall, and not one colour.
    const int red = countPixels(p, 400, 60, 1200, 760, [](const unsigned char* c) {
        return c[0] > 60 && c[0] > c[1] + 40 && c[0] > c[2] + 40;
    });
    const int green = countPixels(p, 400, 60, 1200, 760, [](const unsigned char* c) {
        return c[1] > 40 && c[1] > c[0] + 15 && c[1] > c[2] + 20;
    });
    EXPECT_GT(red, 5000) << "red wall";
    EXPECT_GT(green, 5000) << "green wall";

    // The panel (top left): ImGui's dark window background and its blue frames.
    const int area = 330 * 300;
    const int dark = countPixels(p, 20, 40, 350, 340, [](const unsigned char* c) {
        return c[0] < 45 && c[1] < 45 && c[2] < 55 && std::abs(int(c[0]) - int(c[1])) < 12;
    });
    const int blue = countPixels(p, 20, 40, 350, 340, [](const unsigned char* c) {
        return c[2] > c[0] + 25 && c[2] > 50;
    });
    EXPECT_GT(dark, area / 3) << "panel background";
    EXPECT_GT(blue, area / 20) << "panel widgets";
    // No warning: the Cornell box has none (the next test has one).
    EXPECT_LT(countPixels(p, 20, 40, 350, 340, warningText), 20) << "a warning in the panel";
}

// Issue 11: what the CLI prints as `warning:` lines, the panel shows. The
// Cornell box with its tall block shown twice in place: the copy is dropped
// at import and named in the panel, in its warning colour.
TEST(ViewerTest, ThePanelShowsTheWarnings) {
    ASSERT_TRUE(haveXvfb()) << "xvfb-run is not installed (apt-get install xvfb xauth)";
    TempDir dir;
    nlohmann::json gltf = readJson(kScene);
    int tallBlock = -1;
    for (const nlohmann::json& node : gltf["nodes"])
        if (node.value("name", "") == "tall-block") tallBlock = node.at("mesh");
    ASSERT_GE(tallBlock, 0);
    gltf["nodes"].push_back({{"name", "tall-block-copy"}, {"mesh", tallBlock}});
    gltf["scenes"][0]["nodes"].push_back(gltf["nodes"].size() - 1);
    const std::string scene = (dir / "doubled.gltf").string(), png = (dir / "window.png").string();
    { std::ofstream(scene) << gltf.dump(); }
    const ProcessResult r = run("timeout 60 " + kXvfb + shellQuote(kViewer) + " " + shellQuote(scene) +
                                " --screenshot-after 1.5 " + shellQuote(png) + " --quit-after 2.5");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Picture p = readPicture(png);
    ASSERT_EQ(p.width, 1200) << r.output;
    // Two lines of yellow text under the status line.
    EXPECT_GT(countPixels(p, 20, 40, 350, 340, warningText), 300) << "no warning in the panel";
}

// Exposure is applied on the GPU (a push constant): one EV down halves the
// linear values on screen. The solve is the same in both runs.
TEST(ViewerTest, ExposureOneEvDownHalvesTheLinearValuesOnScreen) {
    ASSERT_TRUE(haveXvfb()) << "xvfb-run is not installed (apt-get install xvfb xauth)";
    TempDir dir;
    auto shot = [&](const std::string& ev) {
        const std::string png = (dir / ("ev" + ev + ".png")).string();
        const ProcessResult r = run("timeout 60 " + kXvfb + shellQuote(kViewer) + " " + shellQuote(kScene) +
                                    " --exposure " + ev + " --screenshot-after 1.5 " + shellQuote(png) +
                                    " --quit-after 2.5");
        EXPECT_EQ(r.exitCode, 0) << r.output;
        return readPicture(png);
    };
    const Picture ev0 = shot("0");
    const Picture evMinus1 = shot("-1");
    ASSERT_EQ(ev0.width, 1200);
    ASSERT_EQ(evMinus1.width, 1200);

    // Mean linear value over the back wall, high up (lit, not clipped).
    auto meanLinear = [](const Picture& p) {
        double sum = 0.0;
        int n = 0;
        for (int y = 150; y < 250; ++y)
            for (int x = 700; x < 800; ++x)
                for (int c = 0; c < 3; ++c, ++n) {
                    const double v = p.at(x, y)[c] / 255.0;
                    sum += v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
                }
        return sum / n;
    };
    const double bright = meanLinear(ev0), dim = meanLinear(evMinus1);
    EXPECT_GT(bright, 0.02);
    EXPECT_LT(bright, 0.9) << "clipped: pick a darker region";
    EXPECT_NEAR(dim / bright, 0.5, 0.02) << bright << " " << dim;
}

// A scene in photometric units is white at exposure 0. Without --exposure
// the first solution picks the exposure that shows its light; with it, the
// user's stands. The Cornell box with its light 10,000 times brighter.
TEST(ViewerTest, ALightPastWhiteGetsAnExposureThatShowsIt) {
    ASSERT_TRUE(haveXvfb()) << "xvfb-run is not installed (apt-get install xvfb xauth)";
    TempDir dir;
    nlohmann::json gltf = readJson(kScene);
    for (nlohmann::json& m : gltf["materials"])
        if (m.contains("emissiveFactor"))
            m["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = 10000.0;
    gltf["extensionsUsed"].push_back("KHR_materials_emissive_strength");
    const std::string scene = (dir / "bright.gltf").string();
    { std::ofstream(scene) << gltf.dump(); }
    auto backWall = [&](const std::string& options) {
        const std::string png = (dir / "shot.png").string();
        std::filesystem::remove(png);
        const ProcessResult r = run("timeout 60 " + kXvfb + shellQuote(kViewer) + " " + shellQuote(scene) + options +
                                    " --screenshot-after 1.5 " + shellQuote(png) + " --quit-after 2.5");
        EXPECT_EQ(r.exitCode, 0) << r.output;
        const Picture p = readPicture(png);
        EXPECT_EQ(p.width, 1200) << r.output;
        double sum = 0.0;
        int n = 0;
        for (int y = 150; y < 250; ++y)
            for (int x = 700; x < 800; ++x, ++n) sum += p.at(x, y)[1] / 255.0;
        return n > 0 ? sum / n : 0.0;
    };
    EXPECT_GT(backWall(" --exposure 0"), 0.99) << "white at the exposure asked for";
    const double chosen = backWall("");
    EXPECT_GT(chosen, 0.05);
    EXPECT_LT(chosen, 0.95) << "the exposure chosen shows the wall";
}

bool haveDragTools() { return std::system("command -v xdotool >/dev/null && command -v xwd >/dev/null") == 0; }

// tests/viewer/drag_gizmo.sh under Xvfb, writing into `dir`; `pick`: an object
// to click on first, or empty for the preselected short block.
ProcessResult runDragScript(const TempDir& dir, const std::string& pick, const std::string& pick2 = "") {
    const std::string script = std::string(RADIOSITY_SOURCE_DIR) + "/tests/viewer/drag_gizmo.sh";
    std::string command = "timeout 90 " + kXvfb + shellQuote(script) + " " + shellQuote(kViewer) + " " +
                          shellQuote(kScene) + " " + shellQuote(dir.path().string());
    if (!pick.empty()) command.append(" ").append(shellQuote(pick));  // append: GCC 12's false -Wrestrict
    if (!pick2.empty()) command.append(" ").append(shellQuote(pick2));
    return run(command);
}

TEST(ViewerTest, DraggingTheGizmoMovesTheBlockAndItsShadow) {
    ASSERT_TRUE(haveXvfb()) << "xvfb-run is not installed (apt-get install xvfb xauth)";
    ASSERT_TRUE(haveDragTools()) << "xdotool and xwd (x11-apps) are needed";
    TempDir dir;
    const ProcessResult r = runDragScript(dir, "");
    const std::string log = readFile((dir / "viewer.log").string());
    ASSERT_NE(r.output.find("viewer-exit 0"), std::string::npos) << r.output << log;

    // The engine thread received the drag.
    std::size_t transforms = 0;
    for (std::size_t at = log.find("engine: transform short-block"); at != std::string::npos;
         at = log.find("engine: transform short-block", at + 1))
        ++transforms;
    EXPECT_GE(transforms, 1u) << log;

    const Picture before = readPicture((dir / "before.png").string());
    const Picture after = readPicture((dir / "after.png").string());
    const Picture overlays = readPicture((dir / "overlays.png").string());
    ASSERT_GE(before.width, 1000);
    ASSERT_EQ(after.width, before.width);
    ASSERT_EQ(overlays.width, before.width);

    // The floor right of the block (floor in both pictures) lost the shadow.
    EXPECT_GT(meanAbsDifference(before, after, 815, 690, 900, 735), 2.0);
    // The back wall high up, far from the block, stays as it was.
    EXPECT_LT(meanAbsDifference(before, after, 700, 150, 800, 250), 1.0);

    // Ctrl+Z put the block back, shadow and all; Ctrl+Shift+Z moved it again.
    const Picture undone = readPicture((dir / "undone.png").string());
    const Picture redone = readPicture((dir / "redone.png").string());
    ASSERT_EQ(undone.width, before.width);
    ASSERT_EQ(redone.width, before.width);
    EXPECT_LT(meanAbsDifference(before, undone, 815, 690, 900, 735), 1.0);
    EXPECT_LT(meanAbsDifference(after, redone, 815, 690, 900, 735), 1.0);

    // L and C turned on the overlays: yellow links (linear 1, 0.85, 0.1) and
    // red changed elements (linear 1, 0.1, 0.1), sRGB-encoded on screen.
    auto yellow = [](const unsigned char* c) { return c[0] > 220 && c[1] > 200 && c[2] < 130; };
    auto red = [](const unsigned char* c) {
        return c[0] > 220 && c[1] > 60 && c[1] < 110 && c[2] > 60 && c[2] < 110;
    };
    EXPECT_GT(countPixels(overlays, 400, 0, 1200, 760, yellow),
              countPixels(after, 400, 0, 1200, 760, yellow) + 500);
    EXPECT_GT(countPixels(overlays, 400, 0, 1200, 760, red), countPixels(after, 400, 0, 1200, 760, red) + 50);
}

// Picking by click: the tall block is not marked dynamic; clicking on it
// selects it, the engine thread attaches it to the root, and its gizmo drags it.
TEST(ViewerTest, ClickingAnObjectNotMarkedDynamicSelectsAndMovesIt) {
    ASSERT_TRUE(haveXvfb()) << "xvfb-run is not installed (apt-get install xvfb xauth)";
    ASSERT_TRUE(haveDragTools()) << "xdotool and xwd (x11-apps) are needed";
    TempDir dir;
    const ProcessResult r = runDragScript(dir, "tall-block");
    const std::string log = readFile((dir / "viewer.log").string());
    ASSERT_NE(r.output.find("viewer-exit 0"), std::string::npos) << r.output << log;
    EXPECT_NE(log.find("gizmo:"), std::string::npos) << "the click selected nothing movable\n" << log;
    EXPECT_NE(log.find("engine: transform tall-block"), std::string::npos) << log;
    EXPECT_EQ(log.find("engine: transform short-block"), std::string::npos) << log;
    const Picture before = readPicture((dir / "before.png").string());
    const Picture after = readPicture((dir / "after.png").string());
    ASSERT_GE(before.width, 1000);
    ASSERT_EQ(after.width, before.width);
    // Where the block's front stood, the back wall shows now; far up the back
    // wall, little changes. (Under the sanitizers frames get small budgets,
    // and what idle time catches up to differs by up to about 3 of 255 there:
    // README, "Known limits".)
    EXPECT_GT(meanAbsDifference(before, after, 530, 330, 600, 460), 10.0);
    EXPECT_LT(meanAbsDifference(before, after, 700, 150, 800, 250), 4.0);
}

// Shift+click: the tall block clicked, then the short block shift+clicked;
// the gizmo (on the short block) drags both in one frame each.
TEST(ViewerTest, ShiftClickingTwoObjectsMovesThemTogether) {
    ASSERT_TRUE(haveXvfb()) << "xvfb-run is not installed (apt-get install xvfb xauth)";
    ASSERT_TRUE(haveDragTools()) << "xdotool and xwd (x11-apps) are needed";
    TempDir dir;
    const ProcessResult r = runDragScript(dir, "tall-block", "short-block");
    const std::string log = readFile((dir / "viewer.log").string());
    ASSERT_NE(r.output.find("viewer-exit 0"), std::string::npos) << r.output << log;
    EXPECT_NE(log.find("engine: transform tall-block"), std::string::npos) << log;
    EXPECT_NE(log.find("engine: transform short-block"), std::string::npos) << log;
    const Picture before = readPicture((dir / "before.png").string());
    const Picture after = readPicture((dir / "after.png").string());
    ASSERT_GE(before.width, 1000);
    ASSERT_EQ(after.width, before.width);
    // Both blocks left where they stood: the tall block's front (as in the
    // click test) and the floor beside the short block (as in the drag test).
    EXPECT_GT(meanAbsDifference(before, after, 530, 330, 600, 460), 10.0);
    EXPECT_GT(meanAbsDifference(before, after, 815, 690, 900, 735), 2.0);
    EXPECT_LT(meanAbsDifference(before, after, 700, 150, 800, 250), 4.0);
}

// A floor; a "lamp" node holding two meshes (base and shade); a table
// beside it; and a magenta point light "bulb" over the floor. The surfaces
// reflect no blue: lit, they never look like the light's marker.
std::string writeLampScene(const TempDir& dir) {
    GltfBuilder g;
    const int grey = g.addMaterial("{\"name\":\"olive\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0,1]}}");
    const auto square = [&](const std::string& name, float a, float y, bool root, const std::string& more = "") {
        const std::vector<glm::vec3> p = {{-a, y, -a}, {-a, y, a}, {a, y, a}, {a, y, -a}};
        const int mesh = g.addMesh(name, g.addPositions(p), g.addIndices({0, 1, 2, 0, 2, 3}), grey);
        return g.addNode("\"name\":\"" + name + "\",\"mesh\":" + std::to_string(mesh) + more, root);
    };
    square("floor", 1.0f, 0.0f, true);
    const int base = square("base", 0.15f, 0.05f, false);
    const int shade = square("shade", 0.1f, 0.3f, false);
    g.addNode("\"name\":\"lamp\",\"translation\":[-0.3,0,0.2],\"children\":[" + std::to_string(base) + "," +
              std::to_string(shade) + "]");
    square("table", 0.25f, 0.25f, true, ",\"translation\":[0.5,0,0.3]");
    g.extraTopLevel = "\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":{"
                      "\"lights\":[{\"type\":\"point\",\"color\":[1,0.2,1],\"intensity\":5}]}},";
    g.addNode("\"name\":\"bulb\",\"translation\":[0.3,0.5,-0.3],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}");
    return g.writeEmbedded(dir, "lamp.gltf").string();
}

// tests/viewer/select_key_drag.sh under Xvfb: `select` preselected, `key`
// pressed, the gizmo's x-arrow dragged.
ProcessResult runSelectKeyDrag(const TempDir& dir, const std::string& scene, const std::string& select,
                               const std::string& key = "") {
    const std::string script = std::string(RADIOSITY_SOURCE_DIR) + "/tests/viewer/select_key_drag.sh";
    std::string command = "timeout 90 " + kXvfb + shellQuote(script) + " " + shellQuote(kViewer) + " " +
                          shellQuote(scene) + " " + shellQuote(dir.path().string());
    command.append(" ").append(shellQuote(select));  // append: GCC 12's false -Wrestrict
    if (!key.empty()) command.append(" ").append(shellQuote(key));
    return run(command);
}

// P widens the selection from the lamp's base to the lamp node's subtree:
// the gizmo's drag moves base and shade, not the table beside them.
TEST(ViewerTest, PWidensTheSelectionToTheParentNode) {
    ASSERT_TRUE(haveXvfb()) << "xvfb-run is not installed (apt-get install xvfb xauth)";
    ASSERT_TRUE(haveDragTools()) << "xdotool and xwd (x11-apps) are needed";
    TempDir dir;
    const ProcessResult r = runSelectKeyDrag(dir, writeLampScene(dir), "base", "p");
    const std::string log = readFile((dir / "viewer.log").string());
    ASSERT_NE(r.output.find("viewer-exit 0"), std::string::npos) << r.output << log;
    EXPECT_NE(log.find("engine: transform base"), std::string::npos) << log;
    EXPECT_NE(log.find("engine: transform shade"), std::string::npos) << "P did not widen to the lamp\n" << log;
    EXPECT_EQ(log.find("engine: transform table"), std::string::npos) << log;
}

// A light, selected by name (it has no polygons to click): drawn as a
// magenta star, its gizmo at its position drags it, and the star follows.
TEST(ViewerTest, ALightIsMarkedAndItsGizmoDragsIt) {
    ASSERT_TRUE(haveXvfb()) << "xvfb-run is not installed (apt-get install xvfb xauth)";
    ASSERT_TRUE(haveDragTools()) << "xdotool and xwd (x11-apps) are needed";
    TempDir dir;
    const ProcessResult r = runSelectKeyDrag(dir, writeLampScene(dir), "bulb");
    const std::string log = readFile((dir / "viewer.log").string());
    ASSERT_NE(r.output.find("viewer-exit 0"), std::string::npos) << r.output << log;
    EXPECT_NE(log.find("engine: transform bulb"), std::string::npos) << log;
    // The marker: linear (1, 0.2, 1), sRGB-encoded on screen; its mean x.
    const auto marker = [](const Picture& p) {
        double sum = 0.0;
        int n = 0;
        for (int y = 0; y < p.height; ++y)
            for (int x = 400; x < p.width; ++x) {
                const unsigned char* c = p.at(x, y);
                if (c[0] > 200 && c[2] > 200 && c[1] > 60 && c[1] < 180) {
                    sum += x;
                    ++n;
                }
            }
        return std::pair{n, n > 0 ? sum / n : 0.0};
    };
    const Picture before = readPicture((dir / "before.png").string());
    const Picture after = readPicture((dir / "after.png").string());
    ASSERT_GE(before.width, 1000);
    ASSERT_EQ(after.width, before.width);
    const auto [nBefore, xBefore] = marker(before);
    const auto [nAfter, xAfter] = marker(after);
    EXPECT_GT(nBefore, 20) << "no light marker";
    EXPECT_GT(nAfter, 20) << "no light marker after the drag";
    EXPECT_LT(xAfter, xBefore - 30.0) << "the marker did not follow the drag to the left";
}

TEST(ViewerTest, EngineThreadHeadlessStress) {
    const ProcessResult r = run("timeout 120 " + shellQuote(kViewer) + " " + shellQuote(kScene) + " --headless-stress 300");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("headless-stress: 300 transforms sent"), std::string::npos) << r.output;
}

// The tall block is not marked dynamic: selecting it attaches its cluster to
// the root on the engine thread, then it moves like any other.
TEST(ViewerTest, EngineThreadMovesAnObjectNotMarkedDynamic) {
    const ProcessResult r = run("timeout 120 " + shellQuote(kViewer) + " " + shellQuote(kScene) +
                                " --select tall-block --headless-stress 100");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("headless-stress: 100 transforms sent"), std::string::npos) << r.output;
    const ProcessResult none = run("timeout 60 " + shellQuote(kViewer) + " " + shellQuote(kScene) +
                                   " --select nobody --headless-stress 10");
    EXPECT_NE(none.exitCode, 0);
    EXPECT_NE(none.output.find("'nobody'"), std::string::npos) << none.output;
}

TEST(ViewerTest, HelpShowsTheDefaults) {
    const ProcessResult r = run("timeout 20 " + shellQuote(kViewer) + " --help");
    EXPECT_EQ(r.exitCode, 0);
    for (const char* shown : {"--size WxH=1200x760", "--target-fps F=30", "--epsilon E=5e-05", "--exposure EV=0"})
        EXPECT_NE(r.output.find(shown), std::string::npos) << shown << "\n" << r.output;
}

// A bad option or value: one line naming it, exit code 2, no window.
TEST(ViewerTest, CommandLineMistakesExitWithCode2) {
    for (const auto& [args, named] : std::vector<std::pair<std::string, std::string>>{
             {"--size 10x10", "--size"},
             {"--size 800", "--size"},
             {"--target-fps 100", "--target-fps"},
             {"--target-fps abc", "--target-fps"},
             {"--epsilon 0", "--epsilon"},
             {"--exposure nan", "--exposure"},
             {"--overlays links,shadows", "'shadows'"},
             {"--screenshot-after soon shot.png", "--screenshot-after"},
             {"--screenshot-after 1", "--screenshot-after"},
             {"--quit-after", "--quit-after"},
             {"--headless-stress 0", "--headless-stress"},
             {"--print-gizmo=1", "print-gizmo"},
             {"--frobnicate", "--frobnicate"},
             {"a.gltf b.gltf", "b.gltf"},
         }) {
        const ProcessResult r = run("env -u DISPLAY timeout 20 " + shellQuote(kViewer) + " " + args);
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
        EXPECT_EQ(r.output.rfind("radiosity-viewer: ", 0), 0u) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(named), std::string::npos) << args << "\n" << r.output;
    }
}

}  // namespace
}  // namespace rad::test
