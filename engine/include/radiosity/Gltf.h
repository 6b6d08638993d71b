#pragma once
// glTF 2.0 in and out. Import: .gltf with embedded or external buffers, and
// .glb, into a Scene (conventions: README, "Scenes"). Export: a lit mesh with
// linear vertex colours, for other tools.

#include <cstddef>
#include <string>
#include <vector>

#include "radiosity/Scene.h"
#include "radiosity/Snapshot.h"

namespace rad {

struct ImportNotes {
    std::vector<std::string> lines;  // things ignored or dropped, for the log
    std::size_t degenerateTriangles = 0;
    std::size_t mergedQuads = 0;
};

// Throws SceneError with one line naming the file and the offending item.
Scene loadGltf(const std::string& path, ImportNotes* notes = nullptr);

// Writes POSITION, NORMAL, COLOR_0 (linear RGB) and indices as one node with
// one mesh and an unlit material (KHR_materials_unlit), so viewers show the
// colours as they are. ".glb" writes binary, anything else a .gltf with the
// buffer embedded. The file appears atomically (written beside it, then
// renamed). Throws std::runtime_error with one line on failure.
void exportGltf(const MeshSnapshot& mesh, const std::string& path);

}  // namespace rad
