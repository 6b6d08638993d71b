#include "cli/EngineOptions.h"

namespace rad::cli {

const std::vector<OptionSpec>& engineOptions() {
    static const std::vector<OptionSpec> options{
        {"--epsilon", "E", "BF refinement threshold, relative to the total emitted power (default 2e-4)"},
        {"--min-area", "A", "area threshold in m^2 (default: 2e-5 of the scene's polygon area)"},
        {"--max-iterations", "N", "gather/push-pull sweeps per round before giving up (default 5000)"},
    };
    return options;
}

EngineSettings engineSettingsFrom(const ParsedArgs& args) {
    EngineSettings settings;
    if (auto v = args.value("--epsilon")) {
        settings.epsilon = parseDouble("--epsilon", *v);
        if (!(settings.epsilon > 0.0)) throw UsageError("--epsilon: must be > 0, got '" + *v + "'");
    }
    if (auto v = args.value("--min-area")) {
        settings.minArea = parseDouble("--min-area", *v);
        if (!(settings.minArea > 0.0)) throw UsageError("--min-area: must be > 0, got '" + *v + "'");
    }
    if (auto v = args.value("--max-iterations"))
        settings.solve.maxIterations = static_cast<int>(parseInteger("--max-iterations", *v, 1, 10'000'000));
    return settings;
}

}  // namespace rad::cli
