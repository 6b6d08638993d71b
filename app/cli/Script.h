#pragma once
// Motion scripts (`animate --script MOVES.json`, `sweep --script`):
//   {"frames": 6, "actions": [
//     {"object": "chair", "translate": [1.0, 0, 0.5]},
//     {"object": "chair", "rotate": [0, 1, 0, 45]},
//     {"object": "light-1", "emission": [6, 5, 3]},
//     {"object": "desk-1", "reflectance": [0.2, 0.5, 0.3]}]}
// Every action is spread over the frames in equal steps. Translations add
// up; rotations turn about the object's bounding-box centre at the start, in
// order. Emission and reflectance go linearly from the object's values in the
// file to the given ones. One object may carry several actions.

#include <string>
#include <vector>

#include "cli/Animation.h"
#include "radiosity/Scene.h"

namespace rad::cli {

struct Script {
    int frames = 0;
    std::vector<ObjectMove> moves;  // one per moving object, in the order first named
    std::vector<Edit> edits;        // one per object edited
};

// Reads and checks a script. Throws UsageError (one line: the file, the
// action by number and object, what is wrong) for a missing or malformed
// file, a wrong number of values, a reflectance outside [0, 1], a negative
// or non-finite emission, a zero rotation axis, an action with nothing to
// do, or frames outside 1..100000.
Script readScript(const std::string& path);

// Throws UsageError naming the action's object when the scene has no object
// of that name with polygons.
void checkScriptObjects(const Script& script, const std::string& path, const Scene& scene);

}  // namespace rad::cli
