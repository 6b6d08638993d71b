// How the CLI writes a report (app/cli/Report.h): JSON that reads back the
// same, keys in the order written, non-finite numbers as null.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>

#include "cli/Report.h"
#include "support/Cli.h"
#include "support/TempDir.h"

namespace rad::cli {
namespace {

TEST(Report, ReadsBackWithItsKeysInOrder) {
    const test::TempDir dir;
    const std::string path = (dir / "r.json").string();
    writeReport(path, {{"zeta", 1}, {"alpha", {{"b", 0.25}, {"a", "x"}}}, {"list", {1.5, 2}}});
    const nlohmann::ordered_json back = nlohmann::ordered_json::parse(test::readFile(path));
    EXPECT_EQ(back.begin().key(), "zeta");  // as written, not sorted
    EXPECT_EQ(back["alpha"]["b"], 0.25);
    EXPECT_EQ(back["alpha"]["a"], "x");
    EXPECT_EQ(back["list"], nlohmann::json({1.5, 2}));
    EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(Report, NonFiniteNumbersAreNull) {
    const test::TempDir dir;
    const std::string path = (dir / "r.json").string();
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    writeReport(path, {{"nan", nan}, {"nested", {{"inf", -inf}, {"finite", 2.0}}}, {"list", {inf, 1.0}},
                       {"valueOrNull", valueOrNull(std::optional<double>())}});
    const nlohmann::json back = test::readJson(path);
    EXPECT_TRUE(back.at("nan").is_null());
    EXPECT_TRUE(back.at("nested").at("inf").is_null());
    EXPECT_EQ(back.at("nested").at("finite"), 2.0);
    EXPECT_EQ(back.at("list"), nlohmann::json({nullptr, 1.0}));
    EXPECT_TRUE(back.at("valueOrNull").is_null());
}

TEST(Report, NamesThatAreNotUtf8StillWrite) {
    const test::TempDir dir;
    const std::string path = (dir / "r.json").string();
    writeReport(path, {{"scene", std::string("caf\xe9.gltf")}});  // Latin-1 byte
    EXPECT_EQ(test::readJson(path).at("scene"), "caf\xef\xbf\xbd.gltf");  // U+FFFD in its place
}

}  // namespace
}  // namespace rad::cli
