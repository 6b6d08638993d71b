#pragma once
// radiosity-cli commands. Each is a CLI11 subcommand: addX() declares its
// options, bound to settings the command owns, and returns what runs once the
// whole command line has parsed. runCli() maps every error to one line:
//   bad command line (CLI11 or cli::UsageError) -> "radiosity-cli: <problem>", exit 2
//   rad::SceneError and any other exception      -> "error: <message>",         exit 1
//
// To add a command: declare `Command addX(CLI::App&)` here, define it in
// app/cli/XCommand.cpp, and add it to the list in runCli (Commands.cpp).

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace rad::cli {

struct Command {
    CLI::App* app;             // the subcommand, owned by the program's CLI::App
    std::function<int()> run;  // returns the exit code
};

// Parses the arguments, runs the command they name and returns the exit
// code. What main() calls; tests may call it too.
int runCli(const std::vector<std::string>& argsAfterProgram);

// radiosity-cli render SCENE --image OUT.png|OUT.pfm [--size WxH] [--exposure EV] [--force]
Command addRender(CLI::App& cli);

// radiosity-cli solve SCENE [--epsilon E] [--min-area A] [--report R.json] [--image OUT] [--size WxH] [--export OUT.glb]
Command addSolve(CLI::App& cli);

// radiosity-cli animate SCENE --object NAME --frames N (--translate X,Y,Z | --rotate AX,AY,AZ,DEG)...
//                       [--compare-full] [--report R.json] [--images DIR] [--size WxH]
Command addAnimate(CLI::App& cli);

// radiosity-cli sweep SCENE --object NAME --frames N (--translate | --rotate)... [--budgets ...]
//                     [--target-fps ...] --out DIR
Command addSweep(CLI::App& cli);

// The SCENE argument every command takes.
void addScene(CLI::App& command, std::string& scene);

}  // namespace rad::cli
