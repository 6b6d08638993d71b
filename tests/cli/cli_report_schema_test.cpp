// The reports and README.md's tables of them ("The `solve` report", "The
// `animate` report", "The `sweep` report") say the same thing: every key path
// a report writes has a row, with a type that fits every value written there,
// and every row's key is written. The commands run on the Cornell box with
// every option that adds keys, at small sizes.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/Cli.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using nlohmann::json;
using test::runCli;
using test::shellQuote;

using test::kCornell;

// Key path ("frames[].seconds.total") -> the type column ("integer or null").
using Schema = std::map<std::string, std::string>;

// The table under the README heading that starts with `heading`: rows
// "| `key` | type | meaning |" up to the next heading.
Schema readmeTable(const std::string& heading) {
    std::ifstream readme(test::sourcePath("README.md"));
    Schema schema;
    bool inSection = false;
    for (std::string line; std::getline(readme, line);) {
        if (line.starts_with("#")) {
            inSection = line.starts_with(heading);
            continue;
        }
        if (!inSection || !line.starts_with("| `")) continue;
        const std::size_t keyEnd = line.find('`', 3);
        const std::size_t typeStart = line.find('|', keyEnd) + 1;
        const std::size_t typeEnd = line.find('|', typeStart);
        std::string type = line.substr(typeStart, typeEnd - typeStart);
        type = type.substr(type.find_first_not_of(' '));
        type = type.substr(0, type.find_last_not_of(' ') + 1);
        schema[line.substr(3, keyEnd - 3)] = type;
    }
    return schema;
}

// Every key path in `value` with every value found there; the elements of
// an array of objects add their keys under "array[]".
void collect(const json& value, const std::string& path, std::map<std::string, std::vector<json>>& out) {
    if (value.is_object()) {
        for (const auto& [key, member] : value.items()) {
            const std::string memberPath = path.empty() ? key : path + "." + key;
            out[memberPath].push_back(member);
            collect(member, memberPath, out);
        }
    } else if (value.is_array()) {
        for (const json& element : value)
            if (element.is_object()) collect(element, path + "[]", out);
    }
}

// Whether `value` has one of the types in `type`: "integer", "number",
// "string", "boolean", "null", "object", "array of objects", "array of
// strings", "array of N numbers", joined by " or ".
bool hasType(const json& value, const std::string& type) {
    std::istringstream alternatives(type);
    std::string word, one;
    std::vector<std::string> kinds;
    while (alternatives >> word) {
        if (word == "or") {
            kinds.push_back(one);
            one.clear();
        } else {
            one += one.empty() ? word : " " + word;
        }
    }
    kinds.push_back(one);
    for (const std::string& kind : kinds) {
        if ((kind == "integer" && value.is_number_integer()) || (kind == "number" && value.is_number()) ||
            (kind == "string" && value.is_string()) || (kind == "boolean" && value.is_boolean()) ||
            (kind == "null" && value.is_null()) || (kind == "object" && value.is_object()))
            return true;
        if (kind == "array of objects" && value.is_array() &&
            std::all_of(value.begin(), value.end(), [](const json& e) { return e.is_object(); }))
            return true;
        if (kind == "array of strings" && value.is_array() &&
            std::all_of(value.begin(), value.end(), [](const json& e) { return e.is_string(); }))
            return true;
        if (kind.starts_with("array of ") && kind.ends_with(" numbers") && value.is_array() &&
            std::to_string(value.size()) + " numbers" == kind.substr(9) &&
            std::all_of(value.begin(), value.end(), [](const json& e) { return e.is_number(); }))
            return true;
    }
    return false;
}

// Several reports of one command count together: a key written by any of
// them is written.
void expectReportMatchesReadme(const std::vector<std::string>& reportPaths, const std::string& heading) {
    const Schema schema = readmeTable(heading);
    ASSERT_FALSE(schema.empty()) << "README.md has no key table under '" << heading << "'";
    std::map<std::string, std::vector<json>> written;
    for (const std::string& path : reportPaths) collect(test::readJson(path), "", written);
    for (const auto& [path, values] : written) {
        const auto row = schema.find(path);
        if (row == schema.end()) {
            ADD_FAILURE() << "'" << path << "' is in the report but not in README.md under '" << heading << "'";
            continue;
        }
        for (const json& v : values)
            EXPECT_TRUE(hasType(v, row->second))
                << "'" << path << "' is " << v.dump() << ", README.md says " << row->second;
    }
    for (const auto& [path, type] : schema)
        EXPECT_TRUE(written.count(path)) << "README.md under '" << heading << "' documents '" << path
                                         << "', which the report does not write";
}

TEST(CliReportSchema, SolveReportMatchesTheReadme) {
    const test::TempDir dir;
    const std::string report = (dir / "solve.json").string(), limited = (dir / "limited.json").string();
    auto r = runCli("solve " + shellQuote(kCornell) + " --report " + shellQuote(report));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // A memory limit hit adds what a converged solve leaves empty: a
    // warning, stopped_by.
    r = runCli("solve " + shellQuote(kCornell) + " --max-memory 1M --report " + shellQuote(limited));
    ASSERT_EQ(r.exitCode, 1) << r.output;
    expectReportMatchesReadme({report, limited}, "### The `solve` report");
}

TEST(CliReportSchema, AnimateReportMatchesTheReadme) {
    const test::TempDir dir;
    const std::string report = (dir / "animate.json").string();
    // --compare-full and --target-fps add the keys that are optional.
    const auto r = runCli("animate " + shellQuote(kCornell) +
                          " --object short-block --frames 2 --translate 0,0,0.05 --compare-full --target-fps 30"
                          " --report " + shellQuote(report));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    // And one whose solve warns (`lamp-room`'s energy guard): the warnings' keys.
    const std::string warned = (dir / "warned.json").string();
    const auto w = runCli("animate " + shellQuote(test::sourcePath("scenes/lamp-room.gltf")) +
                          " --object chair --frames 1 --translate 0.05,0,0 --epsilon 2e-4 --report " + shellQuote(warned));
    ASSERT_EQ(w.exitCode, 0) << w.output;
    expectReportMatchesReadme({report, warned}, "### The `animate` report");
}

TEST(CliReportSchema, SweepReportMatchesTheReadme) {
    const test::TempDir dir;
    const std::string out = (dir / "sweep").string();
    // Both kinds of run: budgets (one of them unlimited) and a target frame rate.
    const auto r = runCli("sweep " + shellQuote(kCornell) +
                          " --object short-block --frames 1 --translate 0,0,0.05 --budgets 0,inf --target-fps 30"
                          " --epsilon 2e-4 --out " + shellQuote(out));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    expectReportMatchesReadme({out + "/trade.json"}, "### The `sweep` report");
    // The converged reference defaults to a tenth of the epsilon.
    EXPECT_DOUBLE_EQ(test::readJson(out + "/trade.json").at("reference_epsilon").get<double>(), 2e-5);
}

}  // namespace
}  // namespace rad
