#include "cli/EngineOptions.h"

#include "cli/Args.h"

namespace rad::cli {

void addEngineOptions(CLI::App& command, EngineSettings& settings) {
    command.add_option("--epsilon", settings.epsilon, "BF refinement threshold, relative to the total emitted power")
        ->type_name("E")
        ->check(positiveNumber())
        ->capture_default_str();
    // 0 in the settings means "derive it from the scene", which is no value to type.
    command.add_option("--min-area", settings.minArea, "area threshold in m^2 (default: 2e-5 of the scene's polygon area)")
        ->type_name("A")
        ->check(positiveNumber());
    command.add_option("--max-iterations", settings.solve.maxIterations,
                       "gather/push-pull sweeps per round before giving up")
        ->type_name("N")
        ->transform(integerIn(1, 10'000'000))
        ->capture_default_str();
}

}  // namespace rad::cli
