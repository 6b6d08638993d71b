// radiosity-cli: headless solving, animation and rendering. The commands live
// in app/cli/*Command.cpp; see Commands.h.

#include <string>
#include <vector>

#include "cli/Commands.h"

int main(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    return rad::cli::runCli(args);
}
