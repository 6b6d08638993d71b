#include "cli/MotionOptions.h"

#include <glm/glm.hpp>

#include "cli/Args.h"

namespace rad::cli {

void addMotionOptions(CLI::App& command, MotionRequest& request) {
    command.add_option("--object", request.object, "the object to move, any object with polygons")
        ->type_name("NAME")
        ->required();
    command.add_option("--frames", request.frames, "number of equal steps of the motion, 1..100000")
        ->type_name("N")
        ->required()
        ->transform(integerIn(1, 100000));
    command.add_option("--translate", "total translation in metres (repeatable, summed)")
        ->type_name("X,Y,Z")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->each([&request](const std::string& text) {
            const auto v = parseNumbers(text, 3);
            request.motion.translation += glm::dvec3(v[0], v[1], v[2]);
            ++request.motionOptions;
        });
    command
        .add_option("--rotate",
                    "total rotation about the axis through the object's bounding-box\n"
                    "centre at the start (repeatable, applied in order)")
        ->type_name("AX,AY,AZ,DEG")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->each([&request](const std::string& text) {
            const auto v = parseNumbers(text, 4);
            const glm::dvec3 axis(v[0], v[1], v[2]);
            if (!(glm::length(axis) > 0.0))
                throw CLI::ValidationError("the axis must not be zero, got '" + text + "'");
            request.motion.rotations.push_back({glm::normalize(axis), v[3]});
            ++request.motionOptions;
        });
}

void requireMotion(const MotionRequest& request) {
    if (request.motionOptions == 0)
        throw UsageError("needs a motion: --translate X,Y,Z and/or --rotate AX,AY,AZ,DEG");
}

std::optional<std::size_t> parseBudget(const std::string& text) {
    if (text == "inf" || text == "unlimited") return std::nullopt;
    return static_cast<std::size_t>(parseInteger(text, 0, 1'000'000'000'000LL));
}

}  // namespace rad::cli
