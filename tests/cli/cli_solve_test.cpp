// radiosity-cli solve on the Cornell box, as a user would run it.
//
// Reference image: tests/data/cornell-box-solved.pfm is
//   radiosity-cli solve scenes/cornell-box.gltf --image X.pfm --size 128x128
// Regenerate after an intended change with
//   RADIOSITY_UPDATE_REFERENCES=1 build/tests/radiosity-tests --gtest_filter='CliSolve.*'
// and look at it before committing.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "image/Image.h"
#include "radiosity/Settings.h"
#include "support/Cli.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using test::jsonAt;
using test::runCli;
using test::shellQuote;

using test::kCornell;
const std::string kSolvedReference = test::sourcePath("tests/data/cornell-box-solved.pfm");

TEST(CliSolve, CornellBoxReportImageAndExport) {
    const test::TempDir dir;
    const std::string report = (dir / "r.json").string(), pfm = (dir / "b.pfm").string(),
                      glb = (dir / "lit.glb").string();
    const auto r = runCli("solve " + shellQuote(kCornell) + " --report " + shellQuote(report) + " --image " +
                          shellQuote(pfm) + " --size 128x128 --export " + shellQuote(glb));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json json = test::readJson(report);
    EXPECT_EQ(json.at("scene"), kCornell);
    EXPECT_EQ(jsonAt(json, "/epsilon"), EngineSettings{}.epsilon);  // the default
    EXPECT_GT(jsonAt(json, "/min_area"), 0.0);
    EXPECT_EQ(jsonAt(json, "/threshold_scale"), 1.0);  // one box, open in front: the whole scene's thresholds
    for (const char* key : {"/polygons", "/elements", "/links", "/passive_links", "/iterations", "/refine_rounds"}) {
        EXPECT_TRUE(jsonAt(json, key).is_number_integer()) << key;
        EXPECT_GT(jsonAt(json, key), 0) << key;
    }
    EXPECT_EQ(jsonAt(json, "/converged"), true);
    EXPECT_EQ(jsonAt(json, "/message"), "");
    // Nothing stopped refinement; no duplicates in the box. Any warning is
    // one line with the four keys.
    EXPECT_TRUE(json.contains("stopped_by") && json["stopped_by"].is_null());
    EXPECT_EQ(jsonAt(json, "/unrefined_power_share"), 0.0);
    ASSERT_TRUE(jsonAt(json, "/warnings").is_array());
    for (const nlohmann::json& w : json["warnings"]) {
        EXPECT_NE(w.at("kind"), "duplicates");
        EXPECT_NE(w.at("kind"), "memory_limit");
        EXPECT_TRUE(w.at("objects").is_array());
        EXPECT_TRUE(w.at("amount").is_number());
        EXPECT_EQ(w.at("message").get<std::string>().find('\n'), std::string::npos);
        EXPECT_NE(r.output.find("warning: " + w["message"].get<std::string>()), std::string::npos) << r.output;
    }
    // The phases are parts of the whole.
    double phases = 0.0;
    for (const char* key : {"/seconds/load", "/seconds/hierarchy", "/seconds/refine", "/seconds/solve"}) {
        ASSERT_TRUE(jsonAt(json, key).is_number()) << key;
        EXPECT_GE(jsonAt(json, key), 0.0) << key;
        phases += json.at(nlohmann::json::json_pointer(key)).get<double>();
    }
    ASSERT_TRUE(jsonAt(json, "/seconds/total").is_number());
    EXPECT_LE(phases, json["seconds"]["total"].get<double>());
    ASSERT_TRUE(jsonAt(json, "/memory_bytes/total").is_number_integer());
    EXPECT_GT(json["memory_bytes"]["total"], 0);
    EXPECT_EQ(json["memory_bytes"]["total"],
              jsonAt(json, "/memory_bytes/elements").get<std::size_t>() + jsonAt(json, "/memory_bytes/links").get<std::size_t>() +
                  jsonAt(json, "/memory_bytes/update").get<std::size_t>());
    // Energy bookkeeping: absorbed + escaped = emitted, reflected + absorbed = received.
    const nlohmann::json& energy = json.at("energy");
    for (const char* key : {"emitted", "received", "absorbed", "reflected", "escaped", "back_faces", "lost", "created"})
        ASSERT_TRUE(energy.contains(key) && energy[key].is_number()) << key;
    const double emitted = energy["emitted"], absorbed = energy["absorbed"], reflected = energy["reflected"],
                 received = energy["received"], escaped = energy["escaped"], backFaces = energy["back_faces"],
                 lost = energy["lost"], created = energy["created"];
    EXPECT_GT(emitted, 0.0);
    EXPECT_NEAR(reflected + absorbed, received, 1e-9 * received);
    // The README's balance: emitted = absorbed + escaped + back_faces + lost.
    EXPECT_NEAR(absorbed + escaped + backFaces + lost, emitted, 1e-9 * emitted);
    EXPECT_GE(backFaces, 0.0);
    EXPECT_NEAR(created, std::max(0.0, absorbed - emitted), 1e-12 * emitted);
    // Escaped light is measured by rays; what the links deliver and what
    // leaves never add to more than was emitted (energy.lost is the rest).
    EXPECT_LE(absorbed + escaped, emitted * (1.0 + 1e-3));
    EXPECT_GT(absorbed + escaped, 0.95 * emitted);
    EXPECT_GT(escaped, 0.0);  // the box is open at the front: some light leaves
    // One entry per object of the box, each with its area and mean RGB radiosity.
    const nlohmann::json& objects = json.at("objects");
    ASSERT_TRUE(objects.is_array());
    EXPECT_EQ(objects.size(), 8u);
    const nlohmann::json* light = nullptr;
    for (const nlohmann::json& o : objects) {
        ASSERT_TRUE(o.at("name").is_string());
        EXPECT_GT(o.at("area"), 0.0) << o["name"];
        ASSERT_EQ(o.at("radiosity").size(), 3u) << o["name"];
        for (const nlohmann::json& b : o["radiosity"]) EXPECT_GE(b, 0.0) << o["name"];
        if (o["name"] == "light") light = &o;
    }
    // The light reads its emission plus what it reflects: at least E = (17, 12, 4).
    ASSERT_NE(light, nullptr);
    EXPECT_GE((*light)["radiosity"][0], 17.0);
    EXPECT_GE((*light)["radiosity"][1], 12.0);
    EXPECT_GE((*light)["radiosity"][2], 4.0);

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

    if (std::getenv("RADIOSITY_UPDATE_REFERENCES")) std::filesystem::copy_file(pfm, kSolvedReference, std::filesystem::copy_options::overwrite_existing);
    const Image reference = readPfm(kSolvedReference);
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

// Every number in a report is finite: writeReport turns a non-finite one
// into null, so no value may be null.
void expectNoNull(const nlohmann::json& value, const std::string& path = "") {
    EXPECT_FALSE(value.is_null()) << path << " is null";
    if (value.is_object())
        for (const auto& [key, member] : value.items()) expectNoNull(member, path + "/" + key);
    if (value.is_array())
        for (std::size_t i = 0; i < value.size(); ++i) expectNoNull(value[i], path + "/" + std::to_string(i));
}

// One sweep cannot tell what remains (the estimate takes two): the message
// says so, where it read "did not converge: did not converge: after 1 sweeps
// the estimated remaining error is 0".
TEST(CliSolve, OneSweepSaysItCannotEstimateWhatRemains) {
    const auto r = runCli("solve " + shellQuote(kCornell) + " --max-iterations 1");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("after 1 sweep the change was "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("takes two sweeps"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("remaining error is 0 "), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("did not converge: did not converge"), std::string::npos) << r.output;
    // animate's initial solve says it the same way.
    const auto a = runCli("animate " + shellQuote(kCornell) + " --object tall-block --translate 0.1,0,0 --frames 1 "
                          "--max-iterations 1");
    EXPECT_EQ(a.exitCode, 1) << a.output;
    EXPECT_NE(a.output.find("the initial solve did not converge: after 1 sweep the change was "), std::string::npos)
        << a.output;
}

// Issue 11: a memory limit hit is not a converged solve. A tiny --max-memory
// stops refinement; the solve says so everywhere and exits 1.
TEST(CliSolve, ATinyMemoryLimitFailsAndSaysSo) {
    const test::TempDir dir;
    const std::string report = (dir / "r.json").string(), png = (dir / "b.png").string();
    const auto r = runCli("solve " + shellQuote(kCornell) + " --max-memory 1M --report " + shellQuote(report) +
                          " --image " + shellQuote(png) + " --size 32x32");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("warning: refinement stopped at the memory limit"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("error: the solve did not converge: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--max-memory"), std::string::npos) << r.output;  // how to raise it
    // The report and the image are still written: what there is, said to be incomplete.
    EXPECT_TRUE(std::filesystem::exists(png));
    const nlohmann::json json = test::readJson(report);
    EXPECT_EQ(jsonAt(json, "/converged"), false);
    EXPECT_EQ(jsonAt(json, "/stopped_by"), "memory_limit");
    ASSERT_TRUE(jsonAt(json, "/message").is_string());
    EXPECT_NE(json["message"].get<std::string>().find("memory limit"), std::string::npos) << json["message"];
    ASSERT_TRUE(jsonAt(json, "/unrefined_power_share").is_number());
    const double share = json["unrefined_power_share"];
    EXPECT_GT(share, 0.0);
    const nlohmann::json* warning = nullptr;
    for (const nlohmann::json& w : json.at("warnings"))
        if (w.at("kind") == "memory_limit") warning = &w;
    ASSERT_NE(warning, nullptr) << json["warnings"].dump();
    EXPECT_EQ((*warning)["amount"], share);
    EXPECT_LE(jsonAt(json, "/memory_bytes/total"), 1 << 20);
    expectNoNull(json);
    EXPECT_LE(jsonAt(json, "/energy/created"), 1e-3 * json["energy"]["emitted"].get<double>());
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
