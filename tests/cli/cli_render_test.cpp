// radiosity-cli render, run as a user would: a separate process with the
// validation layer on (any validation message makes the CLI exit non-zero).
//
// Reference image: tests/data/cornell-box-preview.pfm is
//   radiosity-cli render scenes/cornell-box.gltf --image X.pfm --size 128x128
// To regenerate it after an intended change (scene, camera, renderer), run
//   RADIOSITY_UPDATE_REFERENCES=1 build/tests/radiosity-tests --gtest_filter='CliRender.*'
// and commit the new file after looking at it.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "image/Image.h"
#include "radiosity/Gltf.h"
#include "support/Cli.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

const std::string kPreviewReference = test::sourcePath("tests/data/cornell-box-preview.pfm");
using test::kCornell;

using test::readFile;
using test::RunResult;
using test::runCli;
const auto quote = test::shellQuote;

std::size_t lineCount(const std::string& text) {
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// Width and height from the PNG signature and IHDR chunk.
std::array<int, 2> pngSize(const std::string& path) {
    const std::string bytes = readFile(path);
    if (bytes.size() < 24 || bytes.compare(1, 3, "PNG") != 0 || bytes.compare(12, 4, "IHDR") != 0)
        return {0, 0};
    const auto be32 = [&](std::size_t at) {
        int v = 0;
        for (std::size_t i = 0; i < 4; ++i)
            v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
        return v;
    };
    return {be32(16), be32(20)};
}

// Mean of one channel over a rectangle given in fractions of the image.
float regionMean(const Image& image, int channel, double x0, double x1, double y0, double y1) {
    double sum = 0.0;
    int n = 0;
    for (int y = static_cast<int>(y0 * image.height); y < static_cast<int>(y1 * image.height); ++y)
        for (int x = static_cast<int>(x0 * image.width); x < static_cast<int>(x1 * image.width);
             ++x, ++n)
            sum += image.pixel(x, y)[channel];
    return n ? static_cast<float>(sum / n) : 0.0f;
}

class CliRender : public ::testing::Test {
  protected:
    void SetUp() override { ASSERT_TRUE(fs::exists(kCornell)) << kCornell << " is missing"; }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    test::TempDir dir_;
};

TEST_F(CliRender, CornellBoxPfmMatchesReference) {
    const std::string out = path("cornell.pfm");
    const RunResult run =
        runCli("render " + quote(kCornell) + " --image " + quote(out) + " --size 128x128");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find(out), std::string::npos) << "prints the path written: " << run.output;
    const Image image = readPfm(out);
    ASSERT_EQ(image.width, 128);
    ASSERT_EQ(image.height, 128);

    if (const char* update = std::getenv("RADIOSITY_UPDATE_REFERENCES");
        update && std::string(update) == "1") {
        fs::create_directories(fs::path(kPreviewReference).parent_path());
        fs::copy_file(out, kPreviewReference, fs::copy_options::overwrite_existing);
        std::printf("updated %s\n", kPreviewReference.c_str());
    }
    ASSERT_TRUE(fs::exists(kPreviewReference)) << kPreviewReference << " is missing; see the top of this file";
    const Image reference = readPfm(kPreviewReference);
    ASSERT_EQ(reference.width, image.width);
    ASSERT_EQ(reference.height, image.height);

    // lavapipe rasterises deterministically, so the tolerance only has to
    // absorb edge pixels on another rasteriser: the mean absolute difference
    // (each capped at 1 so one pixel of the bright light cannot dominate) is
    // below 0.01, and fewer than 1% of pixels differ by more than 0.05 in a channel.
    double sumDiff = 0.0;
    std::size_t differingPixels = 0;
    const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
    for (std::size_t i = 0; i < pixels; ++i) {
        float worst = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float d = std::fabs(image.rgb[3 * i + c] - reference.rgb[3 * i + c]);
            sumDiff += std::min(d, 1.0f);
            worst = std::max(worst, d);
        }
        if (!(worst <= 0.05f)) ++differingPixels;  // NaN counts as differing
    }
    EXPECT_LT(sumDiff / (3.0 * pixels), 0.01);
    EXPECT_LT(static_cast<double>(differingPixels) / pixels, 0.01)
        << differingPixels << " pixels differ";
}

TEST_F(CliRender, CornellBoxRedWallLeftGreenWallRight) {
    const std::string out = path("cornell.pfm");
    const RunResult run =
        runCli("render " + quote(kCornell) + " --image " + quote(out) + " --size 96x96");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const Image image = readPfm(out);
    // Middle height of the left and right thirds.
    const float leftR = regionMean(image, 0, 0.02, 0.15, 0.4, 0.6);
    const float leftG = regionMean(image, 1, 0.02, 0.15, 0.4, 0.6);
    const float rightR = regionMean(image, 0, 0.85, 0.98, 0.4, 0.6);
    const float rightG = regionMean(image, 1, 0.85, 0.98, 0.4, 0.6);
    EXPECT_GT(leftR, 2.0f * leftG) << "the left wall should be red";
    EXPECT_GT(rightG, 2.0f * rightR) << "the right wall should be green";
    // The ceiling light is at the top, the floor at the bottom: the brightest
    // pixel is in the upper half.
    int brightestRow = 0;
    float brightest = -1.0f;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (image.pixel(x, y)[0] > brightest) {
                brightest = image.pixel(x, y)[0];
                brightestRow = y;
            }
    EXPECT_LT(brightestRow, image.height / 2);
}

TEST_F(CliRender, PngHasRequestedSizeAndDefaultFollowsCameraAspect) {
    const std::string sized = path("sized.png");
    RunResult run = runCli("render " + quote(kCornell) + " --image " + quote(sized) +
                           " --size 96x64 --exposure -1");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_EQ(pngSize(sized), (std::array<int, 2>{96, 64}));

    const std::string byDefault = path("default.png");
    run = runCli("render " + quote(kCornell) + " --image " + quote(byDefault));
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const Scene scene = loadGltf(kCornell);
    const double aspect =
        scene.camera && scene.camera->aspectRatio ? *scene.camera->aspectRatio : 1.0;
    EXPECT_EQ(pngSize(byDefault),
              (std::array<int, 2>{static_cast<int>(std::lround(512 * aspect)), 512}));
}

// A PNG whose lit pixels are mostly past white (a scene in photometric
// units: Blender writes its 100 W bulb as 5,435) says which exposure shows
// them; rendered at that exposure, it says nothing.
TEST_F(CliRender, AnOverexposedPngSaysWhichExposureShowsIt) {
    RunResult run = runCli("render " + quote(kCornell) + " --image " + quote(path("bright.png")) +
                           " --size 64x64 --exposure 8");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string says = "most lit pixels are past white at --exposure 8; --exposure ";
    const std::size_t at = run.output.find(says);
    ASSERT_NE(at, std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("note: " + path("bright.png")), run.output.rfind('\n', at) + 1)
        << "one note line";
    const double shows = std::stod(run.output.substr(at + says.size()));
    EXPECT_LT(shows, 8.0);
    std::ostringstream ev;
    ev << shows;
    run = runCli("render " + quote(kCornell) + " --image " + quote(path("shown.png")) +
                 " --size 64x64 --exposure " + ev.str());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_EQ(run.output.find("past white"), std::string::npos) << run.output;
}

TEST_F(CliRender, MissingSceneFailsWithOneLineNamingIt) {
    const std::string scene = path("no-such-scene.gltf");
    const RunResult run = runCli("render " + quote(scene) + " --image " + quote(path("x.png")));
    EXPECT_NE(run.exitCode, 0);
    EXPECT_EQ(lineCount(run.output), 1u) << run.output;
    EXPECT_NE(run.output.find(scene), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(path("x.png")));
}

TEST_F(CliRender, CommandLineMistakesExitWithCode2) {
    const std::string scene = quote(kCornell);
    const std::string image = " --image " + quote(path("x.png"));
    for (const std::string& args : std::vector<std::string>{
             "render " + scene + image + " --size 0x64",
             "render " + scene + image + " --size 64x8193",
             "render " + scene + image + " --size 64",
             "render " + scene + image + " --size axb",
             "render " + scene + image + " --size",
             "render " + scene + image + " --exposure bright",
             "render " + scene + image + " --frobnicate",
             "render " + scene,
             "render " + scene + " --image " + quote(path("x.jpg")),
             "render" + image,
             std::string("no-such-command"),
             std::string(),
         }) {
        const RunResult run = runCli(args);
        EXPECT_EQ(run.exitCode, 2) << args << "\n" << run.output;
        EXPECT_EQ(lineCount(run.output), 1u) << args << "\n" << run.output;
        EXPECT_EQ(run.output.rfind("radiosity-cli: ", 0), 0u) << args << "\n" << run.output;
    }
    EXPECT_FALSE(fs::exists(path("x.png")));
}

TEST_F(CliRender, ExistingOutputIsKeptWithoutForce) {
    const std::string out = path("existing.png");
    std::ofstream(out) << "precious";
    const std::string args =
        "render " + quote(kCornell) + " --image " + quote(out) + " --size 16x16";
    const RunResult refused = runCli(args);
    EXPECT_NE(refused.exitCode, 0);
    EXPECT_EQ(lineCount(refused.output), 1u) << refused.output;
    EXPECT_NE(refused.output.find("--force"), std::string::npos) << refused.output;
    EXPECT_EQ(readFile(out), "precious");

    const RunResult forced = runCli(args + " --force");
    EXPECT_EQ(forced.exitCode, 0) << forced.output;
    EXPECT_EQ(pngSize(out), (std::array<int, 2>{16, 16}));
}

TEST_F(CliRender, HelpDescribesEveryOption) {
    for (const char* args : {"--help", "render --help"}) {
        const RunResult run = runCli(args);
        EXPECT_EQ(run.exitCode, 0) << args;
        for (const char* option : {"render", "--image", "--size", "--exposure", "--force"})
            EXPECT_NE(run.output.find(option), std::string::npos) << args << " lacks " << option;
    }
}

}  // namespace
}  // namespace rad
