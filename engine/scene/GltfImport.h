#pragma once
// glTF 2.0 (.gltf with embedded or external buffers, and .glb) into a Scene.
// Conventions: ../shared/DESIGN.md ("Scenes").

#include <string>
#include <vector>

#include "scene/Scene.h"

namespace rad {

struct ImportNotes {
    std::vector<std::string> lines;  // things ignored or dropped, for the log
    std::size_t degenerateTriangles = 0;
    std::size_t mergedQuads = 0;
};

// Throws SceneError with one line naming the file and the offending item.
Scene loadGltf(const std::string& path, ImportNotes* notes = nullptr);

}  // namespace rad
