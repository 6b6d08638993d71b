#pragma once
// The options that say what `animate` and `sweep` move, how far, and under
// which link-update budget.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/Animation.h"

namespace rad::cli {

struct MotionRequest {
    std::string object;  // --object
    int frames = 0;
    Motion motion;       // --translate, --rotate
    // After resolveMotion: what moves (the --object, or the script's moving
    // objects; none for a script of edits only) and the script's edits.
    std::vector<ObjectMove> moves;
    std::vector<Edit> edits;
    int motionOptions = 0;  // --translate and --rotate given: at least one is needed
    std::optional<std::string> script;
};

// --object NAME and --frames N, --translate X,Y,Z and --rotate AX,AY,AZ,DEG
// (repeatable); or --script MOVES.json instead of all of them (cli/Script.h).
void addMotionOptions(CLI::App& command, MotionRequest& request);
// After parsing: reads the script if one was given (throws UsageError for a
// bad one); otherwise throws UsageError unless --object, --frames and a
// --translate or --rotate were given.
void resolveMotion(MotionRequest& request);

// A link-update budget: "inf" (or "unlimited") for none, else a count of link
// updates. Throws CLI::ValidationError (see cli/Args.h).
std::optional<std::size_t> parseBudget(const std::string& text);

}  // namespace rad::cli
