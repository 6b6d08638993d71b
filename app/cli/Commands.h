#pragma once
// radiosity-cli commands. Each takes the arguments after its name and returns
// the exit code. Errors may also be thrown; main turns them into one line:
//   cli::UsageError          -> "radiosity-cli: <problem>", exit 2
//   rad::SceneError, others  -> "error: <message>",         exit 1
//
// To add a command: declare `int runX(const std::vector<std::string>&)` here,
// define it in app/cli/XCommand.cpp, and add a row to commands() in Commands.cpp.

#include <string>
#include <vector>

namespace rad::cli {

using CommandFunction = int (*)(const std::vector<std::string>& args);

struct CommandInfo {
    const char* name;     // "render"
    const char* usage;    // "SCENE --image OUT [options]"
    const char* summary;  // one line for `radiosity-cli --help`
    CommandFunction run;
};

// Every command, in the order `radiosity-cli --help` lists them.
const std::vector<CommandInfo>& commands();

// Dispatches argv[1] to its command and maps exceptions to exit codes as
// described above. What main() calls; tests may call it too.
int runCli(const std::vector<std::string>& argsAfterProgram);

// radiosity-cli render SCENE --image OUT.png|OUT.pfm [--size WxH] [--exposure EV] [--force]
int runRender(const std::vector<std::string>& args);

// radiosity-cli solve SCENE [--epsilon E] [--min-area A] [--report R.json] [--image OUT] [--size WxH] [--export OUT.glb]
int runSolve(const std::vector<std::string>& args);

// radiosity-cli animate SCENE --object NAME --frames N (--translate X,Y,Z | --rotate AX,AY,AZ,DEG)...
//                       [--compare-full] [--report R.json] [--images DIR] [--size WxH]
int runAnimate(const std::vector<std::string>& args);

// radiosity-cli sweep SCENE --object NAME --frames N (--translate | --rotate)... [--budgets ...]
//                     [--target-fps ...] --out DIR
int runSweep(const std::vector<std::string>& args);

}  // namespace rad::cli
