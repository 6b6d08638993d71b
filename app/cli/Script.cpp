#include "cli/Script.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "cli/Args.h"

namespace rad::cli {
namespace {

using Json = nlohmann::json;

// `count` finite numbers from the action's `key`.
std::vector<double> numbers(const Json& action, const char* key, std::size_t count, const std::string& where) {
    const Json& v = action.at(key);
    if (!v.is_array() || v.size() != count)
        throw UsageError(where + ": '" + key + "' needs " + std::to_string(count) + " numbers, got " +
                         (v.is_array() ? std::to_string(v.size()) : std::string("'") + v.dump() + "'"));
    std::vector<double> out;
    for (const Json& x : v) {
        if (!x.is_number() || !std::isfinite(x.get<double>()))
            throw UsageError(where + ": '" + key + "' holds '" + x.dump() + "', not a finite number");
        out.push_back(x.get<double>());
    }
    return out;
}

ObjectMove& moveOf(Script& script, const std::string& object) {
    for (ObjectMove& m : script.moves)
        if (m.object == object) return m;
    script.moves.push_back(ObjectMove{object, {}});
    return script.moves.back();
}

Edit& editOf(Script& script, const std::string& object) {
    for (Edit& e : script.edits)
        if (e.object == object) return e;
    script.edits.push_back(Edit{object, {}, {}});
    return script.edits.back();
}

}  // namespace

Script readScript(const std::string& path) {
    if (std::filesystem::is_directory(path)) throw UsageError(path + ": is a directory, not a script");
    std::ifstream in(path);
    if (!in) throw UsageError(path + ": cannot read the script");
    Json doc;
    try {
        doc = Json::parse(in);
    } catch (const Json::exception& e) {
        // Malformed, or a number out of range (1e309): nlohmann's message
        // names the byte; keep it to one line.
        throw UsageError(path + ": not valid JSON (" + std::string(e.what()).substr(0, 160) + ")");
    }
    if (!doc.is_object()) throw UsageError(path + ": the script must be a JSON object with 'frames' and 'actions'");
    Script script;
    const auto frames = doc.find("frames");
    if (frames == doc.end() || !frames->is_number_integer() || frames->get<long long>() < 1 ||
        frames->get<long long>() > 100000)
        throw UsageError(path + ": 'frames' must be a whole number in 1..100000");
    script.frames = frames->get<int>();
    const auto actions = doc.find("actions");
    if (actions == doc.end() || !actions->is_array() || actions->empty())
        throw UsageError(path + ": 'actions' must be a list of at least one action");
    for (std::size_t i = 0; i < actions->size(); ++i) {
        const Json& a = (*actions)[i];
        std::string where = path + ": action " + std::to_string(i + 1);
        if (!a.is_object() || !a.contains("object") || !a["object"].is_string())
            throw UsageError(where + ": needs an \"object\" name");
        const std::string object = a["object"].get<std::string>();
        where += " ('" + object + "')";
        int done = 0;
        for (const auto& [key, value] : a.items())
            if (key != "object" && key != "translate" && key != "rotate" && key != "emission" && key != "reflectance")
                throw UsageError(where + ": unknown key '" + key + "' (translate, rotate, emission, reflectance)");
        if (a.contains("translate")) {
            const auto v = numbers(a, "translate", 3, where);
            moveOf(script, object).motion.translation += glm::dvec3(v[0], v[1], v[2]);
            ++done;
        }
        if (a.contains("rotate")) {
            const auto v = numbers(a, "rotate", 4, where);
            const glm::dvec3 axis(v[0], v[1], v[2]);
            if (!(glm::length(axis) > 0.0)) throw UsageError(where + ": the rotation axis must not be zero");
            moveOf(script, object).motion.rotations.push_back({glm::normalize(axis), v[3]});
            ++done;
        }
        if (a.contains("emission")) {
            const auto v = numbers(a, "emission", 3, where);
            for (double x : v)
                if (x < 0.0 || x > kMaxEmission) {
                    std::ostringstream bound;
                    bound << kMaxEmission;
                    throw UsageError(where + ": emission must be at least 0 and at most " + bound.str() + " in each channel");
                }
            editOf(script, object).emission = glm::dvec3(v[0], v[1], v[2]);
            ++done;
        }
        if (a.contains("reflectance")) {
            const auto v = numbers(a, "reflectance", 3, where);
            for (double x : v)
                if (x < 0.0 || x > 1.0) throw UsageError(where + ": reflectance must be in [0, 1] in each channel");
            editOf(script, object).reflectance = glm::dvec3(v[0], v[1], v[2]);
            ++done;
        }
        if (done == 0) throw UsageError(where + ": nothing to do (translate, rotate, emission or reflectance)");
    }
    return script;
}

void checkScriptObjects(const Script& script, const std::string& path, const Scene& scene) {
    const auto check = [&](const std::string& name) {
        if (scene.findLight(name)) return;  // a punctual light moves and dims like an object
        const auto o = scene.findObject(name);
        if (!o || scene.objects[*o].polygonCount == 0)
            throw UsageError(path + ": no object '" + name + "' with polygons and no light of that name in " +
                             scene.sourcePath);
    };
    for (const ObjectMove& m : script.moves) check(m.object);
    for (const Edit& e : script.edits) {
        check(e.object);
        if (e.reflectance && scene.findLight(e.object))
            throw UsageError(path + ": '" + e.object + "' is a punctual light: it has no reflectance");
    }
}

}  // namespace rad::cli
