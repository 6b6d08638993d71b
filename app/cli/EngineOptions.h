#pragma once
// The solver options that `solve`, `animate` and `sweep` share.

#include <vector>

#include "radiosity/Engine.h"
#include "cli/Args.h"

namespace rad::cli {

// --epsilon, --min-area, --max-iterations.
const std::vector<OptionSpec>& engineOptions();
// Reads them (defaults where absent); throws UsageError for bad values.
EngineSettings engineSettingsFrom(const ParsedArgs& args);

}  // namespace rad::cli
