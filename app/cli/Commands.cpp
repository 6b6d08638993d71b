#include "cli/Commands.h"

#include <cstdio>
#include <exception>
#include <string>

#include "cli/Args.h"

namespace rad::cli {
namespace {

// Messages from libraries may span lines; the CLI promises one line per error.
std::string oneLine(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    std::string out;
    for (char c : text) {
        if (c == '\n')
            out += "; ";
        else if (c != '\r')
            out += c;
    }
    return out;
}

void printUsage(std::FILE* to) {
    std::fprintf(to, "usage: radiosity-cli COMMAND [ARGS...]\n\ncommands:\n");
    for (const CommandInfo& c : commands()) std::fprintf(to, "  %-8s %s\n", c.name, c.summary);
    std::fprintf(to,
                 "\n`radiosity-cli COMMAND --help` describes one command.\n"
                 "Environment: RADIOSITY_VALIDATION=1 turns on the Vulkan validation layer;\n"
                 "any message it prints makes the command fail.\n"
                 "Exit codes: 0 success, 1 failure, 2 bad command line.\n");
}

}  // namespace

const std::vector<CommandInfo>& commands() {
    static const std::vector<CommandInfo> table{
        {"render", "SCENE --image OUT [options]",
         "render a glTF scene's material preview to PNG or PFM", &runRender},
        {"solve", "SCENE [options]", "solve a scene's radiosity; report, image and glTF export", &runSolve},
        {"animate", "SCENE --object NAME --frames N (--translate|--rotate)...",
         "move an object in steps, updating through the line-space hierarchy", &runAnimate},
        {"sweep", "SCENE --object NAME --frames N (--translate|--rotate)... --out DIR",
         "the speed/accuracy trade of budgets and target frame rates", &runSweep},
    };
    return table;
}

int runCli(const std::vector<std::string>& args) {
    try {
        if (args.empty()) throw UsageError("missing COMMAND (see --help)");
        const std::string& name = args[0];
        if (name == "--help" || name == "-h" || name == "help") {
            printUsage(stdout);
            // Every option of every command, so one page says it all.
            for (const CommandInfo& c : commands()) {
                std::printf("\n");
                c.run({"--help"});
            }
            return kExitOk;
        }
        for (const CommandInfo& c : commands())
            if (name == c.name)
                return c.run(std::vector<std::string>(args.begin() + 1, args.end()));
        throw UsageError("unknown command '" + name + "' (see --help)");
    } catch (const UsageError& e) {
        std::fprintf(stderr, "radiosity-cli: %s\n", oneLine(e.what()).c_str());
        return kExitUsage;
    } catch (const std::exception& e) {
        // SceneError included: its message already names the file and the item.
        std::fprintf(stderr, "error: %s\n", oneLine(e.what()).c_str());
        return kExitFailure;
    }
}

}  // namespace rad::cli
