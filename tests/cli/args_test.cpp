// The option parsers both programs share (app/cli/Args.h), through CLI11 as
// the commands use them: what they accept, and the one-line message naming
// the option when they do not.

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/Args.h"

namespace rad::cli {
namespace {

// Parses `args` (after the program name) and returns CLI11's error message,
// or "" when the command line was accepted.
std::string parse(CLI::App& app, std::vector<std::string> args) {
    std::reverse(args.begin(), args.end());  // CLI11 takes them last first
    try {
        app.parse(args);
        return "";
    } catch (const CLI::ParseError& e) {
        return e.what();
    }
}

struct Options {
    double epsilon = 2e-4;
    double exposure = 0.0;
    int frames = 0;
    std::optional<ImageSize> size;
    std::vector<double> translate;
    bool force = false;
};

// A command line like the CLI's: one option of each kind of parser.
class ArgsTest : public ::testing::Test {
  protected:
    ArgsTest() {
        configure(app);
        app.add_option("--epsilon", o.epsilon)->check(positiveNumber())->capture_default_str();
        app.add_option("--exposure", o.exposure)->check(number());
        app.add_option("--frames", o.frames)->transform(integerIn(1, 100));
        app.add_option("--size")->each([this](const std::string& text) { o.size = parseSize(text); });
        app.add_option("--translate")
            ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
            ->each([this](const std::string& text) {
                for (double v : parseNumbers(text, 3)) o.translate.push_back(v);
            });
        addFlag(app, "--force", o.force, "");
    }

    CLI::App app{"test", "radiosity-cli"};
    Options o;
};

TEST_F(ArgsTest, AcceptsWellFormedValues) {
    EXPECT_EQ(parse(app, {"--epsilon", "1e-3", "--exposure=-1.5", "--frames", "7", "--size", "64x32", "--translate",
                          "1,2,3", "--translate", "-4,0,0.5", "--force"}),
              "");
    EXPECT_EQ(o.epsilon, 1e-3);
    EXPECT_EQ(o.exposure, -1.5);
    EXPECT_EQ(o.frames, 7);
    ASSERT_TRUE(o.size);
    EXPECT_EQ(o.size->width, 64);
    EXPECT_EQ(o.size->height, 32);
    EXPECT_EQ(o.translate, (std::vector<double>{1, 2, 3, -4, 0, 0.5}));  // every --translate, in order
    EXPECT_TRUE(o.force);
}

TEST_F(ArgsTest, DefaultsStayWhenOptionsAreAbsent) {
    EXPECT_EQ(parse(app, {}), "");
    EXPECT_EQ(o.epsilon, 2e-4);
    EXPECT_FALSE(o.size);
    EXPECT_FALSE(o.force);
    EXPECT_EQ(app.get_option("--epsilon")->get_default_str(), "0.0002");  // what --help shows
}

TEST_F(ArgsTest, TheLastOfARepeatedOptionWins) {
    EXPECT_EQ(parse(app, {"--epsilon", "1", "--epsilon", "2", "--size", "8x8", "--size", "16x4"}), "");
    EXPECT_EQ(o.epsilon, 2.0);
    EXPECT_EQ(o.size->width, 16);
}

TEST_F(ArgsTest, IntegersAreDecimal) {
    EXPECT_EQ(parse(app, {"--frames", "010"}), "");
    EXPECT_EQ(o.frames, 10);  // not octal 8
}

TEST_F(ArgsTest, BadValuesAreNamedInOneLine) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"--epsilon", "abc"}, "--epsilon: expected a number, got 'abc'"},
        {{"--epsilon", "-1"}, "--epsilon: must be > 0, got '-1'"},
        {{"--epsilon", "0"}, "--epsilon: must be > 0, got '0'"},
        {{"--exposure", "inf"}, "--exposure: expected a number, got 'inf'"},
        {{"--exposure", "nan"}, "--exposure: expected a number, got 'nan'"},
        {{"--exposure", "1e999"}, "--exposure: expected a number, got '1e999'"},
        {{"--frames", "0"}, "--frames: 0 is outside 1..100"},
        {{"--frames", "1.5"}, "--frames: expected an integer, got '1.5'"},
        {{"--frames", "0x10"}, "--frames: expected an integer, got '0x10'"},
        {{"--size", "12"}, "--size: expected WxH, got '12'"},
        {{"--size", "+5x5"}, "--size: expected WxH, got '+5x5'"},
        {{"--size", "0x64"}, "--size: 0x64 has a side outside 1..8192"},
        {{"--size", "64x8193"}, "--size: 64x8193 has a side outside 1..8192"},
        {{"--translate", "1,2"}, "--translate: expected 3 comma-separated numbers, got '1,2'"},
        {{"--translate", "1,nan,0"}, "--translate: expected a number, got 'nan'"},
    };
    for (const auto& [args, message] : cases) {
        EXPECT_EQ(parse(app, args), message) << args[0] << " " << args[1];
        app.clear();
    }
}

TEST_F(ArgsTest, FlagsTakeNoValueAndOptionsNeedOne) {
    EXPECT_NE(parse(app, {"--force=0"}), "");
    app.clear();
    EXPECT_NE(parse(app, {"--epsilon"}).find("--epsilon"), std::string::npos);
    app.clear();
    EXPECT_NE(parse(app, {"--frobnicate"}).find("--frobnicate"), std::string::npos);
}

TEST(ByteSize, BytesWithABinarySuffix) {
    EXPECT_EQ(parseByteSize("0"), 0u);
    EXPECT_EQ(parseByteSize("4096"), 4096u);
    EXPECT_EQ(parseByteSize("1K"), 1024u);
    EXPECT_EQ(parseByteSize("3k"), 3u * 1024);
    EXPECT_EQ(parseByteSize("1M"), std::size_t(1) << 20);
    EXPECT_EQ(parseByteSize("512m"), std::size_t(512) << 20);
    EXPECT_EQ(parseByteSize("2G"), std::size_t(2) << 30);
    EXPECT_EQ(parseByteSize("010"), 10u);  // decimal, not octal
    for (const char* bad : {"", "K", "-1", "+1", " 1", "1.5M", "1T", "1MB", "1 M", "0x10", "inf"}) {
        try {
            parseByteSize(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const CLI::ValidationError& e) {
            EXPECT_EQ(std::string(e.what()),
                      std::string("expected bytes with an optional K, M or G suffix (1K = 1024), got '") + bad + "'");
        }
    }
    EXPECT_THROW(parseByteSize("99999999999999999999"), CLI::ValidationError);
    EXPECT_THROW(parseByteSize("99999999999G"), CLI::ValidationError);
}

TEST(ByteSize, ReadsBack) {
    EXPECT_EQ(byteSizeText(std::size_t(512) << 20), "512 MiB");
    EXPECT_EQ(byteSizeText(std::size_t(3) << 30), "3.0 GiB");
}

TEST(SplitList, KeepsEmptyItems) {
    EXPECT_EQ(splitList("0,30,inf"), (std::vector<std::string>{"0", "30", "inf"}));
    EXPECT_EQ(splitList(""), (std::vector<std::string>{""}));
    EXPECT_EQ(splitList("a,"), (std::vector<std::string>{"a", ""}));
}

}  // namespace
}  // namespace rad::cli
