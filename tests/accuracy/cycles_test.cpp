// Accuracy against ground truth: radiosity-cli's solution, rendered through the
// scene camera, against a Blender Cycles path-traced reference of the same scene
// with the same conventions (bench/cycles/README.md). Issue 12, "Light that is
// right": the Cornell box within 5% block RMS, the furnished room within 7%.
//
// The references are bench/references/NAME.pfm (linear B per pixel),
// NAME-lights.pfm (pixels that see a light) and NAME.json (how they were made,
// with a checksum of the scene file). Re-render them whenever a scene changes:
// CyclesReference.MatchesTheSceneFiles fails until then.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "image/Image.h"
#include "support/Cli.h"
#include "support/ImageCompare.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using test::runCli;
using test::shellQuote;

struct ReferenceCase {
    std::string name;  // bench/references/NAME.*
    int width;
    int height;
    double targetBlockRms;
    std::string scene = "";  // from the repository's root; empty: scenes/NAME.gltf
};

const ReferenceCase kCornellBoxCase{"cornell-box", 128, 128, 0.05};
const ReferenceCase kFurnishedRoomCase{"furnished-room", 128, 96, 0.07};
// Written by Blender's glTF exporter with its defaults (bench/untuned/blender_room.py):
// every material doubleSided, a point light, a table of five meshes under one node. No
// issue sets its target; it is held to the Cornell box's 5% (measured 2.3%). No light is
// in its camera's view, so it has no camera check.
const ReferenceCase kBlenderRoomCase{"blender-room", 128, 72, 0.05,
                                     "bench/untuned/blender-room.glb"};
// Two rooms built of slabs that run through each other, lit through a
// doorway (bench/untuned/slab_rooms.py --doorway), seen from the dark room.
// No issue sets its target; it is held to 8% (measured 5.9%; 16.0% before
// the import cut polygons where they pass into closed solids, when the
// wall elements straddling the partition shone into the dark room). No light
// is in its camera's view.
const ReferenceCase kSlabRoomsCase{"slab-rooms", 120, 80, 0.08, "bench/untuned/slab-rooms.gltf"};
// Lit by punctual lights only: a point bulb and a spot (glTF's cone falloff,
// which the reference script reproduces with shader nodes). No issue sets its
// target; it is held to the Cornell box's 5% (measured 3.1%; a reference made
// with Blender's own spot blend read 14%). No light surface is in its view.
const ReferenceCase kLampRoomCase{"lamp-room", 128, 96, 0.05};
// A room turned 30 degrees about the vertical, so that nothing in it lies
// along the world's axes, its camera a child of the turned node
// (bench/untuned/turned_room.py): a luminous ceiling panel, a glowing box flush
// with a wall, 2 cm shelves, a 16-sided column, steps. No issue sets its
// target; it is held to the Cornell box's 5% (measured 2.6%; 4.3% before a
// surface a lamp stands on could split below the area threshold, 3.6% with
// one level below it). Its panel
// and box are in view: the camera check covers a turned camera.
const ReferenceCase kTurnedRoomCase{"turned-room", 128, 96, 0.05, "bench/untuned/turned-room.gltf"};
// A room lit only by two uplights on tall cabinets against its side walls
// (bench/untuned/uplight_room.py): the walls above the cabinets take nearly
// half their light, and everything else sees the white ceiling, a mezzanine
// shading a sofa and a table under it. No issue sets its target; it is held
// to the Cornell box's 5% (measured 4.5%; 4.9%, its light 2.7% darker in
// the mean, before two surfaces that see each other only between their
// sample points cast their rays between the parts that face). Its lights
// face up, away from the camera.
const ReferenceCase kUplightRoomCase{"uplight-room", 128, 96, 0.05, "bench/untuned/uplight-room.gltf"};
// A kitchen lit only by strips under its wall cupboards, 2 cm from the tiled
// wall (bench/untuned/kitchen_room.py): their light lands on the tiles in a
// band a few centimetres tall, the brightest part of the image. No issue
// sets its target; it is held to the furnished room's 7% (measured 5.2%;
// 18.6% before a surface an emitter shines along could split two levels
// below the area threshold). Its strips face down, away from the camera.
const ReferenceCase kKitchenCase{"kitchen-room", 128, 96, 0.07, "bench/untuned/kitchen-room.gltf"};
// A bedroom lit by table lamps inside shades and a window behind blind slats
// (bench/untuned/bedroom_room.py): measured in the README (7.0%), not
// asserted; its shades' inner sides share their clusters' facets with the
// outer ones (README, "Known limits"). Its reference is checked against the
// scene file.
const ReferenceCase kBedroomCase{"bedroom", 128, 96, 0.0, "bench/untuned/bedroom.gltf"};
// Two storeys joined by a stair through an opening in the slab, seen from the
// lower one, which the light reaches only through the opening, about a
// hundredth of the upper one's (bench/untuned/stair_hall.py). No issue sets
// its target; it is held to 13% (measured 10.4%; 19.4% when dim polygons
// were refined at most four times finer for their own light, 42.7% before
// any, 8.1% at a sixteenth of the epsilon: README, "Known limits").
const ReferenceCase kStairHallCase{"stair-hall", 128, 96, 0.13, "bench/untuned/stair-hall.gltf"};
// Measured in the README (4.5% at the default settings; 6.6% before the
// clusters' exposure, 12.2% before the fill), not asserted: no
// issue sets its target, and its solve under the sanitizers would cost CI
// time the others need. Its reference is checked against the scene file.
const ReferenceCase kOfficeCase{"office", 128, 96, 0.0};

std::string scenePath(const ReferenceCase& c) {
    return test::sourcePath(c.scene.empty() ? "scenes/" + c.name + ".gltf" : c.scene);
}
std::string referencePath(const ReferenceCase& c, const std::string& suffix) {
    return test::sourcePath("bench/references/" + c.name + suffix);
}
std::string sizeArgument(const ReferenceCase& c) {
    return std::to_string(c.width) + "x" + std::to_string(c.height);
}

// 64-bit FNV-1a, as bench/cycles/render_reference.py records it.
std::string fnv1a64(const std::string& bytes) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char b : bytes) h = (h ^ b) * 0x100000001b3ull;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return hex;
}

// Pixels where our material preview shows an emitter. The preview draws
// reflectance (< 1) plus emission per polygon, and every light in these scenes
// emits well over 1 in some channel, so "> 1" separates lights from the rest.
std::vector<bool> ourLightPixels(const Image& preview) {
    std::vector<bool> light(static_cast<std::size_t>(preview.width) * preview.height);
    for (int y = 0; y < preview.height; ++y)
        for (int x = 0; x < preview.width; ++x) {
            const float* p = preview.pixel(x, y);
            light[static_cast<std::size_t>(y) * preview.width + x] = p[0] > 1.0f || p[1] > 1.0f || p[2] > 1.0f;
        }
    return light;
}

void expectReferenceMatchesScene(const ReferenceCase& c) {
    SCOPED_TRACE(c.name);
    const std::string json = test::readFile(referencePath(c, ".json"));
    ASSERT_FALSE(json.empty()) << referencePath(c, ".json") << " is missing";
    const std::string hash = fnv1a64(test::readFile(scenePath(c)));
    EXPECT_NE(json.find("\"scene_fnv1a64\": \"" + hash + "\""), std::string::npos)
        << scenePath(c) << " changed since its reference was rendered (FNV-1a " << hash
        << "); re-render it as bench/cycles/README.md says";
    const Image reference = readPfm(referencePath(c, ".pfm"));
    const Image lights = readPfm(referencePath(c, "-lights.pfm"));
    EXPECT_EQ(reference.width, c.width);
    EXPECT_EQ(reference.height, c.height);
    EXPECT_EQ(lights.width, c.width);
    EXPECT_EQ(lights.height, c.height);
}

// The camera check: our rasterised lights must cover exactly the pixels whose
// centres see a light in Cycles. A wrong field of view, aspect, orientation
// or a half-pixel shift moves whole edges; allow two pixels for centres that
// lie on an edge to within rounding.
void expectCameraLinesUp(const ReferenceCase& c) {
    SCOPED_TRACE(c.name);
    const test::TempDir dir;
    const std::string preview = (dir / "preview.pfm").string();
    const auto r = runCli("render " + shellQuote(scenePath(c)) + " --image " + shellQuote(preview) + " --size " +
                          sizeArgument(c));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::vector<bool> ours = ourLightPixels(readPfm(preview));
    const Image mask = readPfm(referencePath(c, "-lights.pfm"));
    ASSERT_EQ(ours.size(), static_cast<std::size_t>(mask.width) * mask.height);
    int theirs = 0, mismatched = 0;
    std::string where;  // the first few pixels that differ
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            const bool cycles = mask.pixel(x, y)[0] > 0.0f;
            theirs += cycles;
            if (cycles == ours[static_cast<std::size_t>(y) * mask.width + x]) continue;
            if (++mismatched <= 10)
                where += " (" + std::to_string(x) + "," + std::to_string(y) + (cycles ? ": Cycles only)" : ": ours only)");
        }
    EXPECT_GT(theirs, 50) << "the reference should show its light";
    EXPECT_LE(mismatched, 2) << "light pixels that differ:" << where;
}

// Solves with the default settings, renders through the scene camera and
// compares with the reference. Prints the figures whether or not they pass.
// The same solve keeps the scale issue's memory target: at most 64 bytes a
// link or p-link, everything the solution holds included (these small
// rooms, 25 to 40 links an H-element, are where the elements weigh most).
void expectWithinTarget(const ReferenceCase& c) {
    SCOPED_TRACE(c.name);
    const test::TempDir dir;
    const std::string image = (dir / "solved.pfm").string(), report = (dir / "r.json").string();
    const auto r = runCli("solve " + shellQuote(scenePath(c)) + " --image " + shellQuote(image) + " --size " +
                          sizeArgument(c) + " --report " + shellQuote(report));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json json = test::readJson(report);
    const double links = json.at("links").get<double>() + json.at("passive_links").get<double>();
    const double bytesPerLink = json.at("memory_bytes").at("total").get<double>() / links;
    std::printf("[ memory ] %s: %.2f bytes per link\n", c.name.c_str(), bytesPerLink);
    EXPECT_LE(bytesPerLink, 64.0);
    const test::BlockComparison m =
        test::compareBlocks(readPfm(image), readPfm(referencePath(c, ".pfm")), readPfm(referencePath(c, "-lights.pfm")));
    std::printf("[ accuracy ] %s: block RMS %.4f (target %.2f), mean ratio %.4f, %d blocks, %zu pixels\n",
                c.name.c_str(), m.blockRms, c.targetBlockRms, m.meanRatio, m.blocks, m.pixels);
    ::testing::Test::RecordProperty("block_rms", std::to_string(m.blockRms));
    ::testing::Test::RecordProperty("mean_ratio", std::to_string(m.meanRatio));
    EXPECT_LE(m.blockRms, c.targetBlockRms) << "mean ratio (ours / Cycles) " << m.meanRatio;
}

TEST(CyclesReference, MatchesTheSceneFiles) {
    expectReferenceMatchesScene(kCornellBoxCase);
    expectReferenceMatchesScene(kFurnishedRoomCase);
    expectReferenceMatchesScene(kBlenderRoomCase);
    expectReferenceMatchesScene(kSlabRoomsCase);
    expectReferenceMatchesScene(kLampRoomCase);
    expectReferenceMatchesScene(kTurnedRoomCase);
    expectReferenceMatchesScene(kUplightRoomCase);
    expectReferenceMatchesScene(kKitchenCase);
    expectReferenceMatchesScene(kBedroomCase);
    expectReferenceMatchesScene(kStairHallCase);
    expectReferenceMatchesScene(kOfficeCase);
}

TEST(CyclesReference, CornellBoxCameraLinesUp) { expectCameraLinesUp(kCornellBoxCase); }
TEST(CyclesReference, FurnishedRoomCameraLinesUp) { expectCameraLinesUp(kFurnishedRoomCase); }
TEST(CyclesReference, TurnedRoomCameraLinesUp) { expectCameraLinesUp(kTurnedRoomCase); }

TEST(CyclesAccuracy, CornellBoxWithinFivePercent) { expectWithinTarget(kCornellBoxCase); }
TEST(CyclesAccuracy, FurnishedRoomWithinSevenPercent) { expectWithinTarget(kFurnishedRoomCase); }
TEST(CyclesAccuracy, ARoomWrittenByBlenderWithinFivePercent) {
    expectWithinTarget(kBlenderRoomCase);
}
TEST(CyclesAccuracy, RoomsOfSlabsWithinEightPercent) { expectWithinTarget(kSlabRoomsCase); }
TEST(CyclesAccuracy, PointAndSpotLightsWithinFivePercent) { expectWithinTarget(kLampRoomCase); }
TEST(CyclesAccuracy, ARoomTurnedOffTheAxesWithinFivePercent) { expectWithinTarget(kTurnedRoomCase); }
TEST(CyclesAccuracy, ARoomLitByUplightsWithinFivePercent) { expectWithinTarget(kUplightRoomCase); }
TEST(CyclesAccuracy, AKitchenLitByStripsUnderItsCupboardsWithinSevenPercent) { expectWithinTarget(kKitchenCase); }
TEST(CyclesAccuracy, AStoreyLitThroughAStairOpeningWithinThirteenPercent) { expectWithinTarget(kStairHallCase); }

}  // namespace
}  // namespace rad
