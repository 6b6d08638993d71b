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

// Polygons of `dropped` that repeat polygons of `kept` in place (see
// ImportNotes::duplicatePolygons); the two may be the same object.
struct DuplicatePolygons {
    std::string kept;
    std::string dropped;
    std::size_t count = 0;
};

// A material whose base colour reaches 1 in some channel (glTF's default
// base colour is white): its reflectance is clamped to kMaxReflectance.
struct ClampedReflectance {
    std::string material;
    double largest = 0.0;  // the largest channel before the clamp
};

// No real surface reflects all the light it receives, and a closed room of
// reflectance 1 has no finite solution: base colours in (0.98, 1] are read as
// 0.98 (a fresh white paint or snow). Above 1 or below 0 is an error.
constexpr double kMaxReflectance = 0.98;

struct ImportNotes {
    std::vector<std::string> lines;  // things ignored or dropped, for the log
    std::size_t degenerateTriangles = 0;
    std::size_t mergedQuads = 0;
    // Triangles whose coplanar region (one material, joined by shared edges)
    // became one convex polygon, or rectangles: a CAD triangulation of a wall
    // in slivers imports as the wall, a wall with a window as its rectangles.
    std::size_t mergedRegionTriangles = 0;
    // Polygons dropped because an earlier polygon (in node order) has the
    // same vertices in the same cyclic order, so faces the same way, after
    // the node transforms and quad merging. Equal means within 1e-9 of the
    // scene's bounding-box diagonal, which absorbs rounding. Light would see
    // both copies: the form factors to them would add up twice. The same
    // polygons facing opposite ways (a zero-thickness slab) are kept.
    std::size_t duplicatePolygons = 0;
    std::vector<DuplicatePolygons> duplicates;  // per pair of objects, in the order first met
    std::vector<ClampedReflectance> clampedReflectance;
    // Polygons of static objects cut where they pass into a closed convex
    // solid of a static object (a floor slab under a wall, a wall into a
    // partition), and the area inside the solids left out.
    std::size_t buriedPolygons = 0;
    double buriedArea = 0.0;
    // Polygons of static objects cut where a smaller polygon of a static
    // object lies in their plane, facing the same way (a poster on a wall, a
    // lamp panel in the ceiling's plane), and the area under them left out
    // (scene/Covered.h).
    std::size_t coveredPolygons = 0;
    double coveredArea = 0.0;
    // Polygons of static objects split along where polygons of static
    // objects stand on them or pass through them (scene/Contacts.h).
    std::size_t contactPolygons = 0;
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
