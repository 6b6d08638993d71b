#pragma once
// The solver options that `solve`, `animate` and `sweep` share.

#include <CLI/CLI.hpp>

#include "radiosity/Engine.h"

namespace rad::cli {

// --epsilon, --min-area, --max-iterations and --max-memory, bound to
// `settings` (whose values are the defaults --help shows).
void addEngineOptions(CLI::App& command, EngineSettings& settings);

}  // namespace rad::cli
