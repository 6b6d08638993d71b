#include "cli/EngineOptions.h"

#include <cstdint>
#include <string>

#include "cli/Args.h"

namespace rad::cli {

void addEngineOptions(CLI::App& command, EngineSettings& settings) {
    command.add_option("--epsilon", settings.epsilon,
                       "BF refinement threshold, relative to the total emitted power (of a room's share of it in a "
                       "scene of many rooms: see --whole-scene-thresholds)")
        ->type_name("E")
        ->check(positiveNumber())
        ->capture_default_str();
    // 0 in the settings means "derive it from the scene", which is no value to type.
    command.add_option("--min-area", settings.minArea, "area threshold in m^2 (default: 2e-5 of the scene's polygon area, or of a room's share of it)")
        ->type_name("A")
        ->check(positiveNumber());
    command.add_flag(
        "--whole-scene-thresholds", [&settings](std::int64_t) { settings.localThresholds = false; },
        "epsilon and the default area threshold relative to the whole scene, even where a point sees only a room of "
        "it, and for dimly lit surfaces as for the rest (by default a building's rooms are each refined as alone, "
        "a surface under a quarter of the mean light up to four times finer, and a large one under the mean up to "
        "sixteen times)");
    command.add_option("--max-iterations", settings.solve.maxIterations,
                       "gather/push-pull sweeps per round before giving up")
        ->type_name("N")
        ->transform(integerIn(1, 10'000'000))
        ->capture_default_str();
    // 0 asks the engine for its default, which depends on the machine: --help
    // says what it is here and now.
    const std::string memoryHelp =
        "memory for links and elements; refinement stops there and the solve fails saying so. Bytes with an "
        "optional K, M or G suffix (1K = 1024); 0 = auto: half of the available memory (here " +
        byteSizeText(defaultMemoryLimit()) + ")";
    command.add_option("--max-memory", memoryHelp)
        ->type_name("SIZE")
        ->each([&settings](const std::string& text) { settings.maxMemoryBytes = parseByteSize(text); })
        ->default_str(std::to_string(settings.maxMemoryBytes));
}

}  // namespace rad::cli
