// radiosity-cli solve on the Cornell box, as a user would run it.
//
// Reference image: tests/data/cornell-box-solved.pfm is
//   radiosity-cli solve scenes/cornell-box.gltf --image X.pfm --size 128x128
// Regenerate after an intended change with
//   RADIOSITY_UPDATE_REFERENCES=1 build/tests/radiosity-tests --gtest_filter='CliSolve.*'
// and look at it before committing.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "image/Image.h"
#include "support/Cli.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using test::jsonNumber;
using test::runCli;
using test::shellQuote;

const std::string kCornell = test::sourcePath("scenes/cornell-box.gltf");
const std::string kReference = test::sourcePath("tests/data/cornell-box-solved.pfm");

TEST(CliSolve, CornellBoxReportImageAndExport) {
    const test::TempDir dir;
    const std::string report = (dir / "r.json").string(), pfm = (dir / "b.pfm").string(),
                      glb = (dir / "lit.glb").string();
    const auto r = runCli("solve " + shellQuote(kCornell) + " --report " + shellQuote(report) + " --image " +
                          shellQuote(pfm) + " --size 128x128 --export " + shellQuote(glb));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string json = test::readFile(report);
    for (const char* key : {"polygons", "elements", "links", "passive_links", "iterations"})
        EXPECT_GT(jsonNumber(json, key), 0.0) << key;
    EXPECT_NE(json.find("\"converged\": true"), std::string::npos);
    for (const char* key : {"load", "hierarchy", "refine", "solve", "total"})
        EXPECT_GE(jsonNumber(json, key), 0.0) << key;
    EXPECT_GT(jsonNumber(json, "total", json.find("memory_bytes")), 0.0);
    // Energy bookkeeping: absorbed + escaped = emitted, reflected + absorbed = received.
    const double emitted = jsonNumber(json, "emitted"), absorbed = jsonNumber(json, "absorbed"),
                 reflected = jsonNumber(json, "reflected"), received = jsonNumber(json, "received");
    EXPECT_GT(emitted, 0.0);
    EXPECT_NEAR(reflected + absorbed, received, 1e-9 * received);
    EXPECT_LT(absorbed, emitted * 1.01);  // the box is open at the front: some light leaves
    // The light reads its emission plus what it reflects: at least E = (17, 12, 4).
    const std::size_t light = json.find("\"name\": \"light\"");
    ASSERT_NE(light, std::string::npos);
    const std::size_t values = json.find('[', json.find("\"radiosity\"", light));
    EXPECT_GE(std::strtod(json.c_str() + values + 1, nullptr), 17.0);

    const Image image = readPfm(pfm);
    ASSERT_EQ(image.width, 128);
    // No cracks: inside the box's opening every pixel sees a surface (B > 0).
    for (int y = 16; y < 112; ++y)
        for (int x = 16; x < 112; ++x) {
            const float* p = image.pixel(x, y);
            ASSERT_GT(p[0] + p[1] + p[2], 0.0f) << "hole at " << x << "," << y;
        }
    // Colour bleeding: the floor near the red wall is redder than near the green wall.
    const float* nearRed = image.pixel(30, 118);
    const float* nearGreen = image.pixel(98, 118);
    EXPECT_GT(nearRed[0] / nearRed[1], nearGreen[0] / nearGreen[1]);

    if (std::getenv("RADIOSITY_UPDATE_REFERENCES")) std::filesystem::copy_file(pfm, kReference, std::filesystem::copy_options::overwrite_existing);
    const Image reference = readPfm(kReference);
    ASSERT_EQ(reference.rgb.size(), image.rgb.size());
    // Tolerance: the solve is deterministic; rasterisation on lavapipe too.
    // Mean absolute difference under 1% of the mean, and under 1% of pixels
    // off by more than 5% of the mean (edges).
    double mean = 0.0, diff = 0.0;
    for (std::size_t i = 0; i < image.rgb.size(); ++i) {
        mean += reference.rgb[i];
        diff += std::abs(image.rgb[i] - reference.rgb[i]);
    }
    mean /= image.rgb.size();
    diff /= image.rgb.size();
    EXPECT_LT(diff, 0.01 * mean);
    std::size_t off = 0;
    for (std::size_t i = 0; i < image.rgb.size(); ++i) off += std::abs(image.rgb[i] - reference.rgb[i]) > 0.05 * mean;
    EXPECT_LT(off, image.rgb.size() / 100);

    // The export holds COLOR_0.
    EXPECT_NE(test::readFile(glb).find("COLOR_0"), std::string::npos);
}

TEST(CliSolve, BadSettingsAndMissingFilesFailWithOneLine) {
    const test::TempDir dir;
    auto r = runCli("solve " + shellQuote(kCornell) + " --epsilon -1");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find("--epsilon"), std::string::npos);
    r = runCli("solve " + shellQuote((dir / "missing.gltf").string()));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("missing.gltf"), std::string::npos);
    // Nothing emits: a clear refusal.
    const std::string dark = (dir / "dark.gltf").string();
    std::string text = test::readFile(kCornell);
    for (std::string::size_type at; (at = text.find("\"emissiveFactor\"")) != std::string::npos;) text.replace(at, 16, "\"ignoredFactor\"");
    { std::ofstream(dark) << text; }
    r = runCli("solve " + shellQuote(dark));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("nothing emits"), std::string::npos) << r.output;
    // An existing report is not overwritten without --force.
    const std::string report = (dir / "keep.json").string();
    { std::ofstream(report) << "mine"; }
    r = runCli("solve " + shellQuote(kCornell) + " --report " + shellQuote(report));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(test::readFile(report), "mine");
}

}  // namespace
}  // namespace rad
