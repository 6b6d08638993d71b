#include "cli/Commands.h"

#include <algorithm>
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

int usageError(const std::string& problem) {
    std::fprintf(stderr, "radiosity-cli: %s\n", oneLine(problem).c_str());
    return kExitUsage;
}

// CLI11 would report a missing, misspelt or misplaced command alike, as "A
// subcommand is required"; these messages name what is wrong.
void checkCommandName(const std::vector<std::string>& args, const std::vector<Command>& commands) {
    if (args.empty()) throw UsageError("missing COMMAND (see --help)");
    const std::string& name = args[0];
    if (name == "--help" || name == "-h") return;
    if (name.starts_with("-")) throw UsageError("unknown option '" + name + "' before COMMAND (see --help)");
    if (std::none_of(commands.begin(), commands.end(), [&](const Command& c) { return c.app->get_name() == name; }))
        throw UsageError("unknown command '" + name + "' (see --help)");
}

}  // namespace

void addScene(CLI::App& command, std::string& scene) {
    command.add_option("SCENE", scene, "the glTF scene (.gltf or .glb)")->required()->type_name("");
}

int runCli(const std::vector<std::string>& args) {
    CLI::App app("Headless solving, animation and rendering of glTF scenes with clustering hierarchical radiosity.",
                 "radiosity-cli");
    configure(app);
    app.require_subcommand(1);
    app.get_formatter()->label("SUBCOMMAND", "COMMAND");
    app.footer(
        "`radiosity-cli COMMAND --help` describes one command.\n"
        "Environment: RADIOSITY_VALIDATION=1 turns on the Vulkan validation layer;\n"
        "any message it prints makes the command fail.\n"
        "Exit codes: 0 success, 1 failure, 2 bad command line.");
    const std::vector<Command> commands{addRender(app), addSolve(app), addAnimate(app), addSweep(app)};
    for (const Command& c : commands) c.app->group("Commands");  // the heading of their list in --help
    try {
        checkCommandName(args, commands);
        std::vector<std::string> lastFirst(args.rbegin(), args.rend());  // the order CLI11 takes
        app.parse(lastFirst);
    } catch (const CLI::CallForHelp&) {
        // `COMMAND --help` describes that command (CLI11 picks it); plain
        // `--help` lists the commands, then describes every one of them.
        std::string text = app.help();
        if (app.get_subcommands().empty())
            for (const Command& c : commands) text += "\n" + c.app->help(app.get_name());
        std::fputs(text.c_str(), stdout);
        return kExitOk;
    } catch (const CLI::ParseError& e) {
        return usageError(e.what());
    } catch (const UsageError& e) {
        return usageError(e.what());
    }
    // Exactly one: require_subcommand(1) made CLI11 refuse anything else.
    const auto chosen = std::find_if(commands.begin(), commands.end(), [](const Command& c) { return c.app->parsed(); });
    try {
        return chosen->run();
    } catch (const UsageError& e) {
        return usageError(e.what());
    } catch (const std::exception& e) {
        // SceneError included: its message already names the file and the item.
        std::fprintf(stderr, "error: %s\n", oneLine(e.what()).c_str());
        return kExitFailure;
    }
}

}  // namespace rad::cli
