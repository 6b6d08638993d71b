#pragma once
// A MeshSnapshot as glTF 2.0 with linear vertex colours, for other tools.

#include <string>

#include "snapshot/MeshSnapshot.h"

namespace rad {

// Writes POSITION, NORMAL, COLOR_0 (linear RGB) and indices as one node with
// one mesh and an unlit material (KHR_materials_unlit), so viewers show the
// colours as they are. ".glb" writes binary, anything else a .gltf with the
// buffer embedded. The file appears atomically (written beside it, then
// renamed). Throws std::runtime_error with one line on failure.
void exportGltf(const MeshSnapshot& mesh, const std::string& path);

}  // namespace rad
