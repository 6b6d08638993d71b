// radiosity-cli's command line as a user meets it: the help of every command,
// and mistakes refused with exit code 2 and one line naming what is wrong,
// before any work is done.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "support/Cli.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using test::runCli;
using test::shellQuote;

using test::kCornell;

struct CommandOptions {
    std::string command;
    std::vector<std::string> options;
    std::vector<std::string> defaults;  // "NAME=VALUE" as --help shows it
};

const std::vector<CommandOptions>& everyCommand() {
    static const std::vector<CommandOptions> commands{
        {"render", {"--image", "--size", "--exposure", "--force"}, {"--exposure EV=0"}},
        {"solve",
         {"--epsilon", "--min-area", "--max-iterations", "--max-memory", "--report", "--image", "--size", "--exposure",
          "--export", "--force"},
         {"--epsilon E=5e-05", "--max-iterations N=5000", "--max-memory SIZE=0", "--exposure EV=0"}},
        {"animate",
         {"--object", "--frames", "--translate", "--rotate", "--budget", "--target-fps", "--compare-full", "--report",
          "--images", "--size", "--exposure", "--force", "--epsilon", "--min-area", "--max-iterations", "--max-memory"},
         {"--epsilon E=5e-05", "--max-iterations N=5000", "--max-memory SIZE=0", "--exposure EV=0"}},
        {"sweep",
         {"--object", "--frames", "--translate", "--rotate", "--budgets", "--target-fps", "--out", "--force",
          "--epsilon", "--min-area", "--max-iterations", "--max-memory"},
         {"--budgets B1,B2,...=0,30,100,330,1000,inf", "--target-fps F1,F2,...=5,10,30,60", "--epsilon E=5e-05",
          "--max-iterations N=5000", "--max-memory SIZE=0"}},
    };
    return commands;
}

// The help names the memory available when it runs ("here 11.6 GiB"), which
// other processes change between two runs.
std::string withoutMemoryFigure(std::string help) {
    for (std::size_t at = help.find("(here "); at != std::string::npos; at = help.find("(here ", at + 1)) {
        const std::size_t end = help.find(')', at);
        if (end == std::string::npos) break;
        help.replace(at, end - at + 1, "(here)");
    }
    return help;
}

TEST(CliCommandLine, HelpListsEveryOptionWithItsDefault) {
    const test::RunResult all = runCli("--help");
    EXPECT_EQ(all.exitCode, 0) << all.output;
    for (const CommandOptions& c : everyCommand()) {
        const test::RunResult one = runCli(c.command + " --help");
        EXPECT_EQ(one.exitCode, 0) << one.output;
        EXPECT_NE(one.output.find("Usage: radiosity-cli " + c.command), std::string::npos) << one.output;
        // `--help` alone describes every command in full.
        EXPECT_NE(withoutMemoryFigure(all.output).find(withoutMemoryFigure(one.output)), std::string::npos)
            << c.command << " is not described in full:\n"
            << all.output;
        for (const std::string& option : c.options)
            EXPECT_NE(one.output.find(option), std::string::npos) << c.command << " lacks " << option;
        for (const std::string& shown : c.defaults)
            EXPECT_NE(one.output.find(shown), std::string::npos) << c.command << " lacks " << shown << "\n"
                                                                 << one.output;
    }
}

TEST(CliCommandLine, MistakesExitWith2AndOneLineNamingThem) {
    const test::TempDir dir;
    const std::string scene = shellQuote(kCornell), out = shellQuote((dir / "out").string());
    const std::string move = " --object short-block --frames 2 --translate 0,0,0.1";
    const std::vector<std::pair<std::string, std::string>> cases{
        {"", "COMMAND"},
        {"nosuch", "'nosuch'"},
        {"--frobnicate", "--frobnicate"},
        {"solve", "SCENE"},
        {"solve " + scene + " extra", "extra"},
        {"solve " + scene + " --frobnicate", "--frobnicate"},
        {"solve " + scene + " --epsilon", "--epsilon"},
        {"solve " + scene + " --epsilon 0", "--epsilon"},
        {"solve " + scene + " --min-area -1", "--min-area"},
        {"solve " + scene + " --max-iterations 0", "--max-iterations"},
        {"solve " + scene + " --max-memory lots", "--max-memory"},
        {"solve " + scene + " --max-memory -1M", "--max-memory"},
        {"solve " + scene + " --max-memory 1.5G", "--max-memory"},
        {"solve " + scene + " --max-memory", "--max-memory"},
        {"solve " + scene + " --image x.jpg", "--image"},
        {"solve " + scene + " --force=1", "force"},
        {"animate " + scene + " --frames 2 --translate 0,0,0.1", "--object"},
        {"animate " + scene + " --object short-block --translate 0,0,0.1", "--frames"},
        {"animate " + scene + " --object short-block --frames 2", "--translate"},
        {"animate " + scene + move + " --frames 0", "--frames"},
        {"animate " + scene + move + " --translate 1,2", "--translate"},
        {"animate " + scene + move + " --rotate 0,0,0,10", "--rotate"},
        {"animate " + scene + move + " --budget abc", "--budget"},
        {"animate " + scene + move + " --budget -1", "--budget"},
        {"animate " + scene + move + " --target-fps 0", "--target-fps"},
        {"animate " + scene + move + " --budget 3 --target-fps 30", "--target-fps"},
        {"animate " + scene + move + " --size 64", "--size"},
        {"animate " + scene + move + " --max-memory 1T", "--max-memory"},
        {"sweep " + scene + move, "--out"},
        {"sweep " + scene + move + " --out " + out + " --budgets 0,x", "--budgets"},
        {"sweep " + scene + move + " --out " + out + " --budgets 0,,inf", "--budgets"},
        {"sweep " + scene + move + " --out " + out + " --target-fps 30,0", "--target-fps"},
        {"sweep " + scene + move + " --out " + out + " --max-memory 12KB", "--max-memory"},
        {"sweep " + scene + move + " --out " + out + " --reference-epsilon 0", "--reference-epsilon"},
        {"sweep " + scene + move + " --out " + out + " --reference-epsilon nan", "--reference-epsilon"},
    };
    for (const auto& [args, named] : cases) {
        const test::RunResult r = runCli(args);
        EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
        EXPECT_EQ(r.output.rfind("radiosity-cli: ", 0), 0u) << args << "\n" << r.output;
        EXPECT_NE(r.output.find(named), std::string::npos) << args << "\n" << r.output;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace rad
