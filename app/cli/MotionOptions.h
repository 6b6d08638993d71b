#pragma once
// The options that say what `animate` and `sweep` move, how far, and under
// which link-update budget.

#include <cstddef>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/Animation.h"

namespace rad::cli {

struct MotionRequest {
    std::string object;
    int frames = 0;
    Motion motion;
    int motionOptions = 0;  // --translate and --rotate given: at least one is needed
};

// --object NAME and --frames N (both required), --translate X,Y,Z and
// --rotate AX,AY,AZ,DEG (repeatable).
void addMotionOptions(CLI::App& command, MotionRequest& request);
// After parsing: throws UsageError unless a --translate or --rotate was given.
void requireMotion(const MotionRequest& request);

// A link-update budget: "inf" (or "unlimited") for none, else a count of link
// updates. Throws CLI::ValidationError (see cli/Args.h).
std::optional<std::size_t> parseBudget(const std::string& text);

}  // namespace rad::cli
