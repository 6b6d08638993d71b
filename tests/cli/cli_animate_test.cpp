// radiosity-cli animate on the Cornell box, as a user would run it.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "support/Cli.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using test::jsonNumber;
using test::runCli;
using test::shellQuote;

const std::string kCornell = test::sourcePath("scenes/cornell-box.gltf");

TEST(CliAnimate, ReportsEveryFrameAndMatchesAFullSolve) {
    test::TempDir dir;
    const std::string report = (dir / "a.json").string(), images = (dir / "frames").string();
    const auto r = runCli("animate " + shellQuote(kCornell) +
                          " --object short-block --frames 3 --translate 0,0,0.15 --rotate 0,1,0,15 --compare-full"
                          " --report " + shellQuote(report) + " --images " + shellQuote(images) + " --size 64x64");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string json = test::readFile(report);
    std::size_t at = 0;
    for (int f = 1; f <= 3; ++f) {
        at = json.find("\"frame\": " + std::to_string(f), at);
        ASSERT_NE(at, std::string::npos) << "frame " << f;
        for (const char* key : {"traversal", "update", "push_pull", "total", "shaft_tests", "candidates",
                                "links_updated", "reinstated", "refined", "changed_elements", "links", "elements",
                                "full_solve_seconds"})
            EXPECT_GE(jsonNumber(json, key, at), 0.0) << key << " frame " << f;
        EXPECT_GT(jsonNumber(json, "candidates", at), 0.0);
        // The bound: the incremental solution is within 1% rms of a from-scratch solve.
        EXPECT_LE(jsonNumber(json, "rms", at), 0.01) << "frame " << f;
    }
    EXPECT_GT(jsonNumber(json, "median_seconds"), 0.0);
    for (int f = 0; f <= 3; ++f)
        EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(images) / ("frame-000" + std::to_string(f) + ".png")));
}

TEST(CliAnimate, BadArgumentsFailWithOneLine) {
    auto r = runCli("animate " + shellQuote(kCornell) + " --object short-block --frames 2");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("motion"), std::string::npos) << r.output;
    r = runCli("animate " + shellQuote(kCornell) + " --object short-block --frames 2 --translate 1,nan,0");
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("--translate"), std::string::npos) << r.output;
    r = runCli("animate " + shellQuote(kCornell) + " --object short-block --frames 2 --rotate 0,0,0,10");
    EXPECT_EQ(r.exitCode, 2);
    r = runCli("animate " + shellQuote(kCornell) + " --object floor --frames 1 --translate 0,0.1,0");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("not marked dynamic"), std::string::npos) << r.output;
    r = runCli("animate " + shellQuote(kCornell) + " --object nobody --frames 1 --translate 0,0.1,0");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("nobody"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace rad
