#pragma once

#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>

#include "hierarchy/Hierarchy.h"
#include "radiosity/Scene.h"
#include "radiosity/Snapshot.h"

namespace rad {

// Per-vertex radiosity for Gouraud shading. Within each input polygon, a
// vertex takes the area-weighted mean B of the leaves around it; a vertex
// that lies inside the edge of a coarser leaf (a T-vertex) takes the value
// interpolated along that edge instead, so that shading has no cracks or
// jumps where neighbouring leaves differ in depth.
MeshSnapshot makeRadiositySnapshot(const Scene& scene, const Hierarchy& hierarchy);

// Each polygon's part of the mesh as last built, with a signature of what it
// was built from (its leaves, their corners and radiosity): a frame re-meshes
// only the polygons whose signature changed. A moved chair re-meshes; one
// lit differently, its leaves and corners as they were, is only coloured
// again; the rest of the room is copied.
struct SnapshotCache {
    struct Part {
        // What it was built from: its leaves, their corners, reflectance and
        // normal (`shape`); and their radiosity (`light`).
        std::uint64_t shape = 0, light = 0;
        bool valid = false;
        // How its vertices' colours come from its leaves' radiosity, to
        // colour it again in the same sums: per vertex, the leaves of its
        // corners (indices into the leaves as collected) from
        // firstCorner[v]; then the T-vertices, each set between two
        // vertices of a coarser leaf's edge, in the order they were set.
        std::vector<std::uint32_t> cornerLeaf, firstCorner;
        struct Between {
            std::uint32_t vertex, a, b;
            double t;
        };
        std::vector<Between> between;
        MeshSnapshot mesh;            // positions, normals, colors; indices from 0
        std::vector<double> weights;  // per vertex: the leaf area around it
        // The vertices on the polygon's outline: only they can meet another
        // polygon's, so only they take part in smoothing across polygons.
        std::vector<std::uint32_t> outline;
        // Untextured, what its values are multiplied by to be smoothed with
        // another polygon's: 1 / reflectance, so that what is shared is the
        // light arriving, not the colour (a red poster on a white wall, the
        // tiles of a chequered floor); 0 for an emitter and a channel it
        // does not reflect, which keep their own.
        glm::vec3 perLight{1.0f};
        std::size_t leaves = 0;  // when it was meshed: another count changes its size
    };
    std::vector<Part> parts;  // per input polygon
    glm::dvec3 origin{0.0};   // the parts' positions are relative to it (MeshSnapshot::origin), set by the first build
    // The mesh last assembled from the parts: where each part starts in it,
    // and the smoothing's sorted keys of the outline vertices (with the
    // frame they were made in). When no part changed, that mesh stands as it
    // is; when the parts that changed kept their sizes (a moved object, new
    // radiosity), they are written in place and only the smoothing groups
    // they were or are in are summed again.
    bool assembled = false;
    std::size_t vertices = 0, indices = 0;
    // Each part's slot in the mesh: from vertexAt[p] and indexAt[p] to the
    // next part's. A slot holds room to grow: a part that changes size
    // within its slot is written in place (the rest of the slot unused:
    // copies of its first vertex, and degenerate triangles on it), and only
    // one that outgrows its slot moves the mesh to a new layout, which gives
    // the parts it re-meshes half as much again. On the building floor a new
    // layout took 13 to 35 ms, and came every few frames of a moving chair.
    std::vector<std::size_t> vertexAt, indexAt;  // per part, and the total last
    std::vector<std::uint32_t> usedVertices, usedIndices;  // per part: what its slot holds
    MeshSnapshot spare;  // the arrays the mesh had before its last new layout, for the next
    std::vector<std::uint32_t> partOfVertex;    // per mesh vertex: its part (a table, not a search per look)
    // What writing a re-meshed part into the mesh costs (its seams smoothed
    // again), and the walk along every key a patch makes besides, measured:
    // a build with a stop leaves that time for them. Apart, because the
    // walk costs the same for 2,000 parts as for 50,000: on the building
    // floor a mean per part from small patches made a patch of 13,000
    // parts look dearer than joining the whole mesh (80 ms, where the
    // patch takes 30).
    double patchSecondsPerPart = 2e-6;
    double walkSeconds = 0.0;
    // What a patch that moves the mesh to a new layout (a part changed
    // size) costs beyond one that does not, and
    // whether the last build with a stop left such parts for later: the
    // next one then meshes them whatever its stop, so they are never left
    // for good.
    double relayoutSeconds = 0.0;
    bool resizesWaited = false;
    // What meshing a part anew (its leaves changed, or its polygon moved)
    // costs per leaf, measured on builds that did so for at least
    // kReshapeSample leaves: ten times what colouring a part's leaves again
    // costs (a random room's floor of 2,500 leaves, meshed anew when the
    // light links under a moving box refined: 9 to 12 ms of a 16.7 ms
    // frame, where the fit over all frames' changed leaves left 1 to 2).
    // A frame on a deadline leaves this time for the leaves it reshapes
    // (Hierarchy::reshapedLeaves, LineSpaceUpdate::tailSeconds).
    double reshapeSecondsPerLeaf = 0.0;
    static constexpr std::size_t kReshapeSample = 256;
    // What joining every part into a new mesh costs (smoothing included),
    // measured: when patching the re-meshed parts in would cost more (a frame
    // that changed much of a small scene), the mesh is joined anew.
    double assembleSeconds = 0.0;
    // A patch finds the smoothing groups to sum again by their keys when
    // they number fewer than this share of the keys (a binary search among
    // the building floor's keys costs about as much as walking 256 of
    // them), else it walks along all keys.
    std::size_t keysPerSearch = 256;
    struct Key {  // a vertex's position and normal, quantised and packed (vertexKey)
        std::uint64_t a, b;
        auto operator<=>(const Key&) const = default;
    };
    std::vector<std::pair<Key, std::uint32_t>> keyed;  // sorted
    glm::dvec3 keyOrigin{0.0};
    double keyCell = 0.0;
    // The keys' grid follows the scene's box: taken from the objects'
    // boxes, measured again only for the objects that moved.
    ObjectBoxes objectBoxes;
    // Meshing's working arrays, one set per thread, kept from build to
    // build: made afresh, a random room's floor of 2,200 leaves grew a
    // megabyte of corners into fresh memory each time it was meshed, at a
    // page fault per 4 KiB: 9 to 12 ms of a 16.7 ms frame, against 3.2 to
    // 3.6 ms with the memory kept. A copied cache gets arrays of its own.
    struct Scratches;
    struct ScratchesHolder {
        std::unique_ptr<Scratches> held;
        ScratchesHolder();
        ScratchesHolder(const ScratchesHolder&);
        ScratchesHolder& operator=(const ScratchesHolder&);
        ~ScratchesHolder();
    };
    ScratchesHolder scratches;
};

// The same into `mesh`, reusing its memory and the parts in `cache`. With
// `stop`: once that time has passed, polygons whose signature changed keep
// their last mesh (they are drawn with their last light) rather than being
// meshed again, but never before kLeastRemeshed of them were; a later call
// meshes them. Returns how many polygons it left so.
// With `touched` (Hierarchy::meshTouched, per polygon): only the polygons
// marked there (and those never meshed) are looked at; each is unmarked once
// its part matches its leaves again, and stays marked when the stop leaves
// it. Without: every polygon's leaves are hashed.
inline constexpr std::size_t kLeastRemeshed = 32;
std::size_t makeRadiositySnapshot(const Scene& scene, const Hierarchy& hierarchy, MeshSnapshot& mesh, SnapshotCache& cache,
                                  std::optional<std::chrono::steady_clock::time_point> stop = std::nullopt,
                                  std::vector<std::uint8_t>* touched = nullptr);

}  // namespace rad
