#include "cli/MotionOptions.h"

#include <glm/glm.hpp>

#include "cli/Args.h"
#include "cli/Script.h"

namespace rad::cli {

void addMotionOptions(CLI::App& command, MotionRequest& request) {
    CLI::Option* object = command.add_option("--object", request.object, "the object to move, any object with polygons")
        ->type_name("NAME");
    CLI::Option* frames = command.add_option("--frames", request.frames, "number of equal steps of the motion, 1..100000")
        ->type_name("N")
        ->transform(integerIn(1, 100000));
    CLI::Option* translate = command.add_option("--translate", "total translation in metres (repeatable, summed)")
        ->type_name("X,Y,Z")
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->each([&request](const std::string& text) {
            const auto v = parseNumbers(text, 3);
            request.motion.translation += glm::dvec3(v[0], v[1], v[2]);
            ++request.motionOptions;
        });
    CLI::Option* rotate = command
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
    command
        .add_option("--script", request.script,
                    "moves and light or colour edits over the frames, from a JSON file\n"
                    "(instead of --object, --frames, --translate and --rotate)")
        ->type_name("MOVES.json")
        ->excludes(object)
        ->excludes(frames)
        ->excludes(translate)
        ->excludes(rotate);
}

void resolveMotion(MotionRequest& request) {
    if (request.script) {
        Script script = readScript(*request.script);
        request.frames = script.frames;
        request.moves = std::move(script.moves);
        request.edits = std::move(script.edits);
        request.object = request.moves.empty() ? std::string() : request.moves.front().object;
        return;
    }
    if (request.object.empty() || request.frames == 0)
        throw UsageError("needs --object NAME and --frames N, or --script MOVES.json");
    if (request.motionOptions == 0)
        throw UsageError("needs a motion: --translate X,Y,Z and/or --rotate AX,AY,AZ,DEG");
    request.moves = {ObjectMove{request.object, request.motion}};
}

std::optional<std::size_t> parseBudget(const std::string& text) {
    if (text == "inf" || text == "unlimited") return std::nullopt;
    return static_cast<std::size_t>(parseInteger(text, 0, 1'000'000'000'000LL));
}

}  // namespace rad::cli
