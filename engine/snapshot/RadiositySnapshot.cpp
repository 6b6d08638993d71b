#include "snapshot/RadiositySnapshot.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

namespace rad {
// Meshing's working types, named (not in an anonymous namespace): the cache
// keeps a Scratch per thread (SnapshotCache::Scratches).
namespace meshing {

// A point of the dyadic lattice of one input polygon's quadtree.
struct LatticePoint {
    std::int64_t i, j;
    auto operator<=>(const LatticePoint&) const = default;
};

// A mesh vertex of one polygon: the leaves' corners at one lattice point.
struct Vertex {
    LatticePoint p;
    glm::dvec3 weighted{0.0};  // sum of leaf area times B
    double weight = 0.0;       // sum of leaf area
    glm::dvec3 position{0.0};
    glm::dvec3 value{0.0};     // the B it shows
    glm::dvec3 albedo{0.0};    // sum of leaf area times reflectance (textured polygons)
    std::uint32_t leaf = 0;    // a corner's leaf, in the leaves' order
};

// What addPolygon works in, reused from polygon to polygon.
struct Scratch {
    std::vector<ElementId> leaves;
    std::vector<Vertex> corners, vertices;
    // Per leaf, in `leaves` order: its outline, the corners and the
    // T-vertices between them (indices into `vertices`), from ringAt[l].
    std::vector<std::uint32_t> ring, ringAt;
    std::vector<std::uint32_t> cut;  // the outline triangulateOutline cuts down
    std::vector<glm::dvec3> values;  // a part's leaf values, coloured again
};

}  // namespace meshing

namespace {

using meshing::LatticePoint;
using meshing::Scratch;
using meshing::Vertex;

// Triangles over a leaf's outline (convex, counter-clockwise, with
// T-vertices on its edges), every outline vertex used and none degenerate:
// a T-vertex left off would leave a T-junction, where the rasteriser leaves
// cracks of background between the leaves. Cuts off a true corner at a time
// (a convex polygon stays convex), at the lattice's exact coordinates.
// `ring` is used up.
template <class Emit>
void triangulateOutline(std::vector<std::uint32_t>& ring, const std::vector<Vertex>& vertices,
                        const Emit& emit) {
    const auto turn = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const LatticePoint &p = vertices[a].p, &q = vertices[b].p, &r = vertices[c].p;
        return (q.i - p.i) * (r.j - q.j) - (q.j - p.j) * (r.i - q.i);
    };
    while (ring.size() > 3) {
        const std::size_t n = ring.size();
        std::size_t k = 0;
        while (k < n && turn(ring[(k + n - 1) % n], ring[k], ring[(k + 1) % n]) == 0) ++k;
        if (k == n) return;  // no area left
        emit(ring[(k + n - 1) % n], ring[k], ring[(k + 1) % n]);
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
    }
    if (ring.size() == 3 && turn(ring[0], ring[1], ring[2]) != 0) emit(ring[0], ring[1], ring[2]);
}

// Sorted vectors, not hash maps: a polygon has a few vertices on average,
// and building a map per polygon per frame was most of the snapshot.
void addPolygon(const Scene& scene, const Hierarchy& h, ElementId top, const glm::dvec3& origin, SnapshotCache::Part& part,
                Scratch& scratch) {
    MeshSnapshot& mesh = part.mesh;
    std::vector<double>& weights = part.weights;
    std::vector<std::uint32_t>& outline = part.outline;
    {
        const Material& m = scene.materials[scene.polygons[h[top].polygon].material];
        const bool emits = luminance(m.emission) > 0.0;
        for (int c = 0; c < 3; ++c)
            part.perLight[c] = emits || !(m.reflectance[c] > 0.0) ? 0.0f : static_cast<float>(1.0 / m.reflectance[c]);
    }
    std::vector<ElementId>& leaves = scratch.leaves;
    leaves.clear();
    h.collectLeaves(top, leaves);
    int maxDepth = 0;
    for (ElementId l : leaves) maxDepth = std::max<int>(maxDepth, h[l].depth);
    const double scale = std::ldexp(1.0, maxDepth);
    auto lattice = [&](const glm::vec2& uv) {
        return LatticePoint{std::llround(double(uv.x) * scale), std::llround(double(uv.y) * scale)};
    };

    std::vector<Vertex>& corners = scratch.corners;
    corners.clear();
    for (std::uint32_t li = 0; li < leaves.size(); ++li) {
        const HElement& e = h[leaves[li]];
        const PatchGeometry patch = h.patch(leaves[li]);
        for (int k = 0; k < patch.n; ++k)
            corners.push_back({lattice(e.param[k]),
                               e.area * e.radiosity,
                               e.area,
                               patch.v[k],
                               {},
                               e.area * glm::dvec3(e.reflectance),
                               li});
    }
    std::sort(corners.begin(), corners.end(), [](const Vertex& a, const Vertex& b) { return a.p < b.p; });
    std::vector<Vertex>& vertices = scratch.vertices;  // one per lattice point, in lattice order
    vertices.clear();
    part.cornerLeaf.clear();
    part.firstCorner.clear();
    part.between.clear();
    for (const Vertex& c : corners) {
        part.cornerLeaf.push_back(c.leaf);
        if (vertices.empty() || vertices.back().p != c.p) {
            part.firstCorner.push_back(static_cast<std::uint32_t>(part.cornerLeaf.size() - 1));
            vertices.push_back(c);
            continue;
        }
        vertices.back().weighted += c.weighted;
        vertices.back().weight += c.weight;
        vertices.back().albedo += c.albedo;
        vertices.back().position = c.position;
    }
    part.firstCorner.push_back(static_cast<std::uint32_t>(part.cornerLeaf.size()));
    for (Vertex& v : vertices) v.value = v.weight > 0.0 ? v.weighted / v.weight : glm::dvec3(0.0);
    const auto find = [&](const LatticePoint& p) {
        const auto it = std::lower_bound(vertices.begin(), vertices.end(), p,
                                         [](const Vertex& v, const LatticePoint& q) { return v.p < q; });
        return it != vertices.end() && it->p == p ? it : vertices.end();
    };

    // Coarse leaves first: their edge ends are final when their T-vertices are set.
    std::sort(leaves.begin(), leaves.end(), [&](ElementId a, ElementId b) { return h[a].depth < h[b].depth; });
    std::vector<std::uint32_t>& ring = scratch.ring;
    std::vector<std::uint32_t>& ringAt = scratch.ringAt;
    ring.clear();
    ringAt.clear();
    for (ElementId l : leaves) {
        const HElement& e = h[l];
        ringAt.push_back(static_cast<std::uint32_t>(ring.size()));
        const int n = h.cornerCount(l);
        for (int k = 0; k < n; ++k) {
            const LatticePoint a = lattice(e.param[k]), b = lattice(e.param[(k + 1) % n]);
            const auto corner = find(a);
            ring.push_back(static_cast<std::uint32_t>(corner - vertices.begin()));
            const std::int64_t n = std::max(std::llabs(b.i - a.i), std::llabs(b.j - a.j));
            if (n < 2) continue;
            const glm::dvec3 va = corner->value, vb = find(b)->value;
            for (std::int64_t s = 1; s < n; ++s) {
                const auto it = find(LatticePoint{a.i + (b.i - a.i) / n * s, a.j + (b.j - a.j) / n * s});
                if (it == vertices.end()) continue;
                it->value = glm::mix(va, vb, double(s) / double(n));
                part.between.push_back({static_cast<std::uint32_t>(it - vertices.begin()),
                                        static_cast<std::uint32_t>(corner - vertices.begin()),
                                        static_cast<std::uint32_t>(find(b) - vertices.begin()), double(s) / double(n)});
                ring.push_back(static_cast<std::uint32_t>(it - vertices.begin()));
            }
        }
    }
    ringAt.push_back(static_cast<std::uint32_t>(ring.size()));

    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    const glm::vec3 normal(h.normal(h[top]));
    // Textured display (Snapshot.h): an emitter is not textured.
    const Polygon& polygon = scene.polygons[h[top].polygon];
    const Material& material = scene.materials[polygon.material];
    const bool textures = !scene.textures.empty();
    const bool textured = textures && material.texture >= 0 && luminance(material.emission) <= 0.0;
    // The outline of the parametric domain: the unit square of a quad, the
    // triangle (0,0), (1,0), (0,1) of a triangle, on the lattice.
    const auto size = static_cast<std::int64_t>(scale);
    const bool triangle = h.cornerCount(top) == 3;
    for (const Vertex& v : vertices) {
        const LatticePoint& q = v.p;
        // The edges it lies on, edge k from polygon vertex k to k + 1. One
        // on a crease keeps its own value (a partition stands there).
        const bool on[4] = {q.j == 0, triangle ? q.i + q.j == size : q.i == size,
                            triangle ? q.i == 0 : q.j == size, !triangle && q.i == 0};
        bool crease = false;
        for (int k = 0; k < 4; ++k) crease = crease || (on[k] && (polygon.creases >> k & 1));
        if ((on[0] || on[1] || on[2] || on[3]) && !crease)
            outline.push_back(static_cast<std::uint32_t>(mesh.positions.size()));
        mesh.positions.emplace_back(v.position - origin);
        mesh.normals.push_back(normal);
        mesh.colors.emplace_back(v.value);
        weights.push_back(v.weight);
        if (!textures) continue;
        if (!textured) {
            mesh.uvs.emplace_back(0.0f);
            mesh.textureLayer.push_back(-1);
            mesh.texelScale.emplace_back(1.0f);
            continue;
        }
        // colors * texel * texelScale = B with the texel's reflectance in
        // place of the mean reflectance the leaves computed B with.
        const glm::dvec3 albedo = v.weight > 0.0 ? v.albedo / v.weight : glm::dvec3(0.0);
        glm::dvec3 perTexel(0.0);
        for (int c = 0; c < 3; ++c)
            if (albedo[c] > 0.0 && material.textureMean[c] > 0.0)
                perTexel[c] = material.reflectance[c] / material.textureMean[c] / albedo[c];
        mesh.uvs.emplace_back(polygonTexCoord(polygon, glm::dvec2(double(q.i), double(q.j)) / scale));
        mesh.textureLayer.push_back(material.texture);
        mesh.texelScale.emplace_back(perTexel);
    }
    for (std::size_t li = 0; li < leaves.size(); ++li) {
        const auto first = ring.begin() + ringAt[li], last = ring.begin() + ringAt[li + 1];
        // No T-vertex: a fan from the first corner, the triangles it always had.
        if (last - first == h.cornerCount(leaves[li])) {
            for (auto k = first + 1; k + 1 < last; ++k)
                mesh.indices.insert(mesh.indices.end(), {base + *first, base + *k, base + k[1]});
            continue;
        }
        scratch.cut.assign(first, last);
        triangulateOutline(
            scratch.cut, vertices,
            [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
                mesh.indices.insert(mesh.indices.end(), {base + a, base + b, base + c});
            });
    }
}

// Input polygons that meet edge to edge in one plane (a tiled wall) share
// their vertices' values, so the tiling does not show as steps. Only the
// vertices on polygon outlines can meet; they are matched by sorting their
// keys (on all cores), not by a hash map.
using Key = SnapshotCache::Key;

// The smoothing's grid: a millionth of the scene's diagonal. `origin` is the
// grid's, relative to the mesh's own (MeshSnapshot::origin).
double keyCellOf(const Aabb& box) { return std::max(1e-300, 1e-6 * glm::length(box.extent())); }

// A vertex's position on that grid (0 to a million cells along the box, 22
// bits with room either side), packed into 128 bits: the building floor
// keeps a million and more keys, and every pass over them reads a third of
// what six 64-bit numbers took. Vertices at one place with other normals
// share a key; which of them are smoothed together is up to their normals
// (smoothGroup).
Key vertexKey(const MeshSnapshot& mesh, std::uint32_t i, const glm::dvec3& origin, double cell) {
    const glm::dvec3 p = (glm::dvec3(mesh.positions[i]) - origin) / cell;
    constexpr long long kCells = (1LL << 22) - 1;
    const auto cellBits = [&](double v) {
        return static_cast<std::uint64_t>(std::clamp(std::llround(v) + (1LL << 20), 0LL, kCells));
    };
    return Key{cellBits(p.x) | cellBits(p.y) << 22, cellBits(p.z)};
}

// The smoothed value of a vertex of the group keyed[a, b) (one place): the
// area-weighted mean of the own values of the group's vertices whose
// normals are within 18 degrees of its own (kSmoothAngleCos); a vertex
// alone keeps its own. Polygons that meet in one plane (a tiled wall) so
// share their light, and so do the facets of a tessellated curved surface
// (a sphere of 20,000 triangles, whose clusters give groups of facets one
// value each, showed bands); a box's faces, at right angles, and a
// 16-sided column's sides, 22.5 degrees apart, keep theirs.
// With textures, what is smoothed is the light a vertex shows per unit of
// texel (colour times texelScale: the irradiance, up to the material's
// factor), and each vertex takes it back times its own reflectance: tiles
// of a checkered floor that meet at a seam share their light, not their
// colour. Untextured, the same with the polygon's own reflectance
// (SnapshotCache::Part::perLight).
//
// A seam where the light steps (one side's light more than kSeamStep times
// the other's) is not smoothed: each vertex keeps its own value. There the
// seam is an edge of the light, not a place the leaves happen to end: the
// floor of a doorway's reveal, lit from the corridor, meets the dark
// room's floor under a closed door, and the shared value drew a bright
// band along the door's foot into the dark room.
inline constexpr double kSeamStep = 4.0;
inline constexpr double kSmoothAngleCos = 0.9510565162951535;  // cos 18 degrees

template <class Own, class Weight, class Scale>
void smoothGroup(const std::vector<std::pair<Key, std::uint32_t>>& keyed, std::size_t a, std::size_t b,
                 MeshSnapshot& mesh, const Own& own, const Weight& weight, const Scale& scale) {
    // Each member's light (own value times scale, per channel; a channel it
    // reflects nothing in says nothing about the light there), read once
    // before any value is written.
    struct Member {
        glm::vec3 normal, value;  // value: what it shows, written last
        glm::dvec3 scale, light;
        double weight = 0.0, mean = -1.0;  // mean light over its channels; -1: none
    };
    // Groups are small (a vertex where a few polygons meet): on the stack.
    constexpr std::size_t kInline = 16;
    std::array<Member, kInline> inlineMembers;
    std::vector<Member> heapMembers(b - a > kInline ? b - a : 0);
    Member* members = b - a > kInline ? heapMembers.data() : inlineMembers.data();
    for (std::size_t k = a; k < b; ++k) {
        const std::uint32_t i = keyed[k].second;
        Member& m = members[k - a];
        m.normal = mesh.normals[i];
        m.scale = scale(i);
        m.weight = weight(i);
        m.light = glm::dvec3(0.0);
        double sum = 0.0;
        int channels = 0;
        for (int c = 0; c < 3; ++c)
            if (m.scale[c] > 0.0) {
                m.light[c] = own(i)[c] * m.scale[c];
                sum += m.light[c];
                ++channels;
            }
        m.mean = channels > 0 ? sum / channels : -1.0;
    }
    for (std::size_t k = a; k < b; ++k) {
        const Member& m = members[k - a];
        glm::dvec3 sum(0.0), w(0.0);
        double darkest = std::numeric_limits<double>::infinity(), brightest = 0.0;
        std::size_t alike = 0;
        for (std::size_t o = 0; o < b - a; ++o) {
            const Member& other = members[o];
            if (glm::dot(m.normal, other.normal) < kSmoothAngleCos) continue;
            ++alike;
            for (int c = 0; c < 3; ++c)
                if (other.scale[c] > 0.0) {
                    sum[c] += other.weight * other.light[c];
                    w[c] += other.weight;
                }
            if (other.mean < 0.0) continue;
            darkest = std::min(darkest, other.mean);
            brightest = std::max(brightest, other.mean);
        }
        glm::vec3 value = own(keyed[k].second);
        if (alike > 1 && !(brightest > kSeamStep * darkest))
            for (int c = 0; c < 3; ++c)
                if (m.scale[c] > 0.0 && w[c] > 0.0) value[c] = static_cast<float>(sum[c] / w[c] / m.scale[c]);
        members[k - a].value = value;
    }
    for (std::size_t k = a; k < b; ++k) mesh.colors[keyed[k].second] = members[k - a].value;
}

// What vertex i's value is multiplied by to be smoothed (smoothGroup).
glm::dvec3 scaleOf(const MeshSnapshot& mesh, const SnapshotCache& cache, std::uint32_t i) {
    return glm::dvec3(mesh.texelScale.empty() ? cache.parts[cache.partOfVertex[i]].perLight : mesh.texelScale[i]);
}

// Needs cache.partOfVertex for the mesh (numberVertices).
void smoothAcrossPolygons(const Scene& scene, MeshSnapshot& mesh, const std::vector<double>& weights,
                          const std::vector<std::uint32_t>& outline, SnapshotCache& cache) {
    const Aabb box = cache.objectBoxes.all(scene);
    cache.keyOrigin = box.lo;
    cache.keyCell = keyCellOf(box);
    const std::size_t n = outline.size();
    std::vector<std::pair<Key, std::uint32_t>>& keyed = cache.keyed;
    keyed.resize(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t k) {
        keyed[k] = {vertexKey(mesh, outline[k], cache.keyOrigin - mesh.origin, cache.keyCell), outline[k]};
    });
    tbb::parallel_sort(keyed.begin(), keyed.end());
    // Groups are disjoint: each is summed before any of it is written.
    for (std::size_t a = 0, b = 0; a < n; a = b) {
        for (b = a; b < n && keyed[b].first == keyed[a].first; ++b) {
        }
        if (b - a > 1)
            smoothGroup(keyed, a, b, mesh, [&](std::uint32_t i) { return mesh.colors[i]; },
                        [&](std::uint32_t i) { return weights[i]; }, [&](std::uint32_t i) { return scaleOf(mesh, cache, i); });
    }
}

// A part whose leaves and corners are as they were, coloured again from its
// leaves' radiosity (`leaves` as collected), in the sums addPolygon made:
// the same colours, a tenth of the time (no sorting, no triangles).
void recolour(const Hierarchy& h, const std::vector<ElementId>& leaves, SnapshotCache::Part& part,
              std::vector<glm::dvec3>& values) {
    const std::size_t n = part.firstCorner.size() - 1;
    values.resize(n);
    for (std::size_t v = 0; v < n; ++v) {
        const std::uint32_t first = part.firstCorner[v], last = part.firstCorner[v + 1];
        const HElement& e = h[leaves[part.cornerLeaf[first]]];
        glm::dvec3 weighted = e.area * e.radiosity;
        for (std::uint32_t c = first + 1; c < last; ++c) {
            const HElement& o = h[leaves[part.cornerLeaf[c]]];
            weighted += o.area * o.radiosity;
        }
        values[v] = part.weights[v] > 0.0 ? weighted / part.weights[v] : glm::dvec3(0.0);
    }
    for (const SnapshotCache::Part::Between& b : part.between) values[b.vertex] = glm::mix(values[b.a], values[b.b], b.t);
    for (std::size_t v = 0; v < n; ++v) part.mesh.colors[v] = glm::vec3(values[v]);
}

// 64-bit hashes of what a polygon's mesh is made from: its material (an
// emitter is drawn untextured), its leaves (which, and how deep), their
// corners (in the polygon, and the polygon's in space), their reflectance and
// the normal (the shape); and their
// radiosity (the light). A change of the shape re-meshes the polygon, of the
// light alone colours it again. Word by word, with a multiply-xorshift mix:
// it runs over every leaf of the scene each frame.
std::pair<std::uint64_t, std::uint64_t> polygonSignature(const Hierarchy& h, ElementId top, std::uint32_t material,
                                                         std::vector<ElementId>& leaves) {
    leaves.clear();
    h.collectLeaves(top, leaves);
    std::uint64_t shape = 0x9E3779B97F4A7C15ULL, light = shape;
    const auto add = [](std::uint64_t& hash, std::uint64_t word) {
        hash = (hash ^ word) * 0xBF58476D1CE4E5B9ULL;
        hash ^= hash >> 31;
    };
    const auto addVector = [&](std::uint64_t& hash, const glm::dvec3& v) {
        for (int k = 0; k < 3; ++k) add(hash, std::bit_cast<std::uint64_t>(v[k]));
    };
    add(shape, material);
    const PatchGeometry outline = h.patch(top);
    for (int k = 0; k < outline.n; ++k) addVector(shape, outline.v[k]);
    for (ElementId l : leaves) {
        const HElement& e = h[l];
        add(shape, std::uint64_t(l) << 8 | e.depth);
        for (const glm::vec2& uv : e.param) add(shape, std::bit_cast<std::uint64_t>(uv));
        addVector(shape, e.reflectance);
        addVector(light, e.radiosity);
    }
    addVector(shape, h.normal(h[top]));
    return {shape, light};
}

// A part's texturing copied into the mesh at `offset` (nothing when the
// scene has no textures).
void copyTexturing(const MeshSnapshot& part, MeshSnapshot& mesh, std::size_t offset) {
    const auto at = static_cast<std::ptrdiff_t>(offset);
    std::copy(part.uvs.begin(), part.uvs.end(), mesh.uvs.begin() + at);
    std::copy(part.textureLayer.begin(), part.textureLayer.end(), mesh.textureLayer.begin() + at);
    std::copy(part.texelScale.begin(), part.texelScale.end(), mesh.texelScale.begin() + at);
}

// `v` resized to n for writing over, grown with room to spare; what it held
// is lost when it grows. A vector grown to its exact size copies what it
// held into a new allocation the next time it grows (on the building floor,
// a new layout then took 67 and 128 ms where one within its capacity took
// 10).
std::size_t withRoom(std::size_t n) { return n + n / 8; }
template <class T>
void resizeWithRoom(std::vector<T>& v, std::size_t n) {
    if (n > v.capacity()) {
        v.clear();
        v.reserve(withRoom(n));
    }
    v.resize(n);
}

// Room for `v` to grow by an eighth without moving, its pages written once
// now: the building floor's first new layout took 98 ms where the next took
// 9, growing the sorted keys (14 MB) and the vertices' parts into fresh
// memory (a page fault costs about 11 us a 4 KiB page here).
template <class T>
void keepRoomWritten(std::vector<T>& v) {
    const std::size_t n = v.size();
    v.reserve(withRoom(n));
    v.resize(v.capacity());
    v.resize(n);
}

// The slot a part that outgrew its own gets: half as much again, and a few
// (index counts stay multiples of three).
std::size_t slotVertices(std::size_t n) { return n + n / 2 + 8; }
std::size_t slotIndices(std::size_t n) { return n + 3 * (n / 6) + 12; }

// A part written into its slot of `mesh`, vertices [v0, vEnd) and indices
// [i0, iEnd): what the part does not fill holds copies of its first vertex
// and degenerate triangles on it, which no renderer draws.
void writePart(const MeshSnapshot& part, MeshSnapshot& mesh, std::size_t v0, std::size_t vEnd, std::size_t i0,
               std::size_t iEnd) {
    const auto at = static_cast<std::ptrdiff_t>(v0);
    std::copy(part.positions.begin(), part.positions.end(), mesh.positions.begin() + at);
    std::copy(part.normals.begin(), part.normals.end(), mesh.normals.begin() + at);
    std::copy(part.colors.begin(), part.colors.end(), mesh.colors.begin() + at);
    copyTexturing(part, mesh, v0);
    for (std::size_t i = 0; i < part.indices.size(); ++i) mesh.indices[i0 + i] = part.indices[i] + static_cast<std::uint32_t>(v0);
    if (!part.positions.empty())
        for (std::size_t v = v0 + part.positions.size(); v < vEnd; ++v) {
            mesh.positions[v] = mesh.positions[v0];
            mesh.normals[v] = mesh.normals[v0];
            mesh.colors[v] = mesh.colors[v0];
            if (mesh.uvs.empty()) continue;
            mesh.uvs[v] = mesh.uvs[v0];
            mesh.textureLayer[v] = mesh.textureLayer[v0];
            mesh.texelScale[v] = mesh.texelScale[v0];
        }
    std::fill(mesh.indices.begin() + static_cast<std::ptrdiff_t>(i0 + part.indices.size()),
              mesh.indices.begin() + static_cast<std::ptrdiff_t>(iEnd), static_cast<std::uint32_t>(v0));
}

// Which part each mesh vertex belongs to, from the parts' places.
void numberVertices(SnapshotCache& cache) {
    const std::size_t parts = cache.vertexAt.size() - 1;
    cache.partOfVertex.resize(cache.vertexAt.back());
    tbb::parallel_for(std::size_t(0), parts, [&](std::size_t p) {
        std::fill(cache.partOfVertex.begin() + static_cast<std::ptrdiff_t>(cache.vertexAt[p]),
                  cache.partOfVertex.begin() + static_cast<std::ptrdiff_t>(cache.vertexAt[p + 1]), static_cast<std::uint32_t>(p));
    });
}

// The mesh moved to a new layout where re-meshed parts outgrew their slots:
// every re-meshed part gets room to grow (slotVertices, slotIndices: where
// the light changes now, it is likely to change again; at the first new
// layout of the building floor's chair, 2 of its 1,050 parts outgrew their
// slots, and another one 14 frames later), every part goes to its
// new place, the others copied whole from the mesh as it was (their smoothed
// values), their indices and their sorted keys shifted by how far their part
// moved. The order of the keys is kept: vertices stay in part order, and
// within a part in their order.
void relayout(MeshSnapshot& mesh, SnapshotCache& cache, const std::vector<std::uint8_t>& remeshed) {
    const std::size_t polygons = cache.parts.size();
    std::vector<std::size_t> vertexAt(polygons + 1, 0), indexAt(polygons + 1, 0);
    for (std::size_t p = 0; p < polygons; ++p) {
        std::size_t v = cache.vertexAt[p + 1] - cache.vertexAt[p], i = cache.indexAt[p + 1] - cache.indexAt[p];
        const MeshSnapshot& part = cache.parts[p].mesh;
        if (remeshed[p]) {
            v = std::max(v, slotVertices(part.positions.size()));
            i = std::max(i, slotIndices(part.indices.size()));
        }
        vertexAt[p + 1] = vertexAt[p] + v;
        indexAt[p + 1] = indexAt[p] + i;
    }
    // Into the arrays the last new layout left (a fresh allocation of the
    // building floor's mesh took 5 to 18 ms of faulting its pages in).
    MeshSnapshot& out = cache.spare;
    for (std::vector<glm::vec3>* v : {&out.positions, &out.normals, &out.colors}) resizeWithRoom(*v, vertexAt[polygons]);
    const bool textured = !mesh.uvs.empty();
    if (textured) {
        resizeWithRoom(out.uvs, vertexAt[polygons]);
        resizeWithRoom(out.textureLayer, vertexAt[polygons]);
        resizeWithRoom(out.texelScale, vertexAt[polygons]);
    }
    resizeWithRoom(out.indices, indexAt[polygons]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polygons, 64), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t p = r.begin(); p < r.end(); ++p) {
            const auto to = static_cast<std::ptrdiff_t>(vertexAt[p]);
            if (remeshed[p]) {
                writePart(cache.parts[p].mesh, out, vertexAt[p], vertexAt[p + 1], indexAt[p], indexAt[p + 1]);
                continue;
            }
            const auto from = static_cast<std::ptrdiff_t>(cache.vertexAt[p]);
            const auto n = static_cast<std::ptrdiff_t>(cache.vertexAt[p + 1] - cache.vertexAt[p]);
            std::copy(mesh.positions.begin() + from, mesh.positions.begin() + from + n, out.positions.begin() + to);
            std::copy(mesh.normals.begin() + from, mesh.normals.begin() + from + n, out.normals.begin() + to);
            std::copy(mesh.colors.begin() + from, mesh.colors.begin() + from + n, out.colors.begin() + to);
            if (textured) {
                std::copy(mesh.uvs.begin() + from, mesh.uvs.begin() + from + n, out.uvs.begin() + to);
                std::copy(mesh.textureLayer.begin() + from, mesh.textureLayer.begin() + from + n, out.textureLayer.begin() + to);
                std::copy(mesh.texelScale.begin() + from, mesh.texelScale.begin() + from + n, out.texelScale.begin() + to);
            }
            const auto shift = static_cast<std::int64_t>(vertexAt[p]) - static_cast<std::int64_t>(cache.vertexAt[p]);
            for (std::size_t i = cache.indexAt[p]; i < cache.indexAt[p + 1]; ++i)
                out.indices[indexAt[p] + (i - cache.indexAt[p])] = static_cast<std::uint32_t>(mesh.indices[i] + shift);
        }
    });
    // The keys of the unchanged parts, shifted; those of the re-meshed ones
    // go (patch() puts them back under their new keys). In place: a new
    // vector of the floor's keys faulted 14 MB in.
    const std::vector<std::size_t>& oldAt = cache.vertexAt;
    std::size_t kept = 0;
    for (std::pair<Key, std::uint32_t> entry : cache.keyed) {
        const std::size_t p = cache.partOfVertex[entry.second];
        if (remeshed[p]) continue;
        entry.second = static_cast<std::uint32_t>(entry.second - oldAt[p] + vertexAt[p]);
        cache.keyed[kept++] = entry;
    }
    cache.keyed.resize(kept);
    mesh.positions.swap(out.positions);
    mesh.normals.swap(out.normals);
    mesh.colors.swap(out.colors);
    mesh.uvs.swap(out.uvs);
    mesh.textureLayer.swap(out.textureLayer);
    mesh.texelScale.swap(out.texelScale);
    mesh.indices.swap(out.indices);
    cache.vertexAt = std::move(vertexAt);
    cache.indexAt = std::move(indexAt);
    cache.vertices = mesh.positions.size();
    cache.indices = mesh.indices.size();
    numberVertices(cache);
}

// The re-meshed parts written over their places (moved to a new layout
// first when their sizes changed). The smoothing groups any of their outline
// vertices were in or are in now are summed again from the parts' own
// values, in key order as a full build sums them.
// `walked`: how long the walk along the keys took (its groups' sums
// included; 0 when the groups were found by their keys). Returns whether
// the mesh moved to a new layout.
bool patch(MeshSnapshot& mesh, SnapshotCache& cache, const std::vector<std::uint8_t>& remeshed, double& walked) {
    walked = 0.0;
    std::vector<std::size_t> changed;
    bool resized = false;
    for (std::size_t p = 0; p < remeshed.size(); ++p) {
        if (!remeshed[p]) continue;
        const SnapshotCache::Part& part = cache.parts[p];
        resized = resized || part.mesh.positions.size() > cache.vertexAt[p + 1] - cache.vertexAt[p] ||
                  part.mesh.indices.size() > cache.indexAt[p + 1] - cache.indexAt[p];
        changed.push_back(p);
    }
    if (changed.empty()) return false;
    // The part a mesh vertex belongs to, and its own (unsmoothed) value and weight.
    const auto partOf = [&](std::uint32_t v) { return std::size_t(cache.partOfVertex[v]); };
    const auto own = [&](std::uint32_t v) {
        const std::size_t p = partOf(v);
        return cache.parts[p].mesh.colors[v - cache.vertexAt[p]];
    };
    const auto weight = [&](std::uint32_t v) {
        const std::size_t p = partOf(v);
        return cache.parts[p].weights[v - cache.vertexAt[p]];
    };
    // The parts whose vertices moved (a moved object's, one whose count
    // changed within its slot; all of them when the mesh moves to a new
    // layout). The others were meshed again with their vertices where they
    // were: new light only, the common case, and their keys stand as they
    // are.
    std::vector<std::uint8_t> moved(changed.size(), 1);
    if (!resized) {
        tbb::parallel_for(std::size_t(0), changed.size(), [&](std::size_t c) {
            const std::size_t p = changed[c];
            const MeshSnapshot& part = cache.parts[p].mesh;
            const auto at = static_cast<std::ptrdiff_t>(cache.vertexAt[p]);
            moved[c] = !(part.positions.size() == cache.usedVertices[p] && part.indices.size() == cache.usedIndices[p] &&
                         std::equal(part.positions.begin(), part.positions.end(), mesh.positions.begin() + at) &&
                         std::equal(part.normals.begin(), part.normals.end(), mesh.normals.begin() + at) &&
                         std::equal(part.indices.begin(), part.indices.end(),
                                    mesh.indices.begin() + static_cast<std::ptrdiff_t>(cache.indexAt[p]),
                                    [&](std::uint32_t local, std::uint32_t global) {
                                        return std::size_t(local) + cache.vertexAt[p] == std::size_t(global);
                                    }));
        });
    }
    // The keys the moved parts' outline vertices had go. Whether a vertex
    // is theirs, from the runs of vertices they hold (in order; a moved
    // object's parts are one run): the keys are in space order, and looking
    // up each one's part read memory at random (the building floor keeps a
    // million and more). Only the moved parts' runs: with the 2,000 parts a
    // chair's frame colours again, a search among all their runs per key
    // took 26 ms of the floor's snapshot.
    std::vector<Key> gone;
    std::vector<std::pair<std::size_t, std::size_t>> runs;
    for (std::size_t c = 0; c < changed.size(); ++c) {
        if (!moved[c]) continue;
        const std::size_t p = changed[c];
        if (!runs.empty() && runs.back().second == cache.vertexAt[p])
            runs.back().second = cache.vertexAt[p + 1];
        else
            runs.emplace_back(cache.vertexAt[p], cache.vertexAt[p + 1]);
    }
    const auto inRuns = [&](std::uint32_t v) {
        const auto after = std::upper_bound(runs.begin(), runs.end(), std::size_t(v),
                                            [](std::size_t x, const auto& run) { return x < run.first; });
        return after != runs.begin() && v < std::prev(after)->second;
    };
    if (resized) {
        for (const auto& entry : cache.keyed)
            if (inRuns(entry.second)) gone.push_back(entry.first);
        relayout(mesh, cache, remeshed);  // drops their keys and shifts the others
    } else {
        if (!runs.empty())
            std::erase_if(cache.keyed, [&](const std::pair<Key, std::uint32_t>& entry) {
                if (!inRuns(entry.second)) return false;
                gone.push_back(entry.first);
                return true;
            });
        tbb::parallel_for(std::size_t(0), changed.size(), [&](std::size_t c) {
            const std::size_t p = changed[c];
            const SnapshotCache::Part& part = cache.parts[p];
            if (moved[c]) {
                writePart(part.mesh, mesh, cache.vertexAt[p], cache.vertexAt[p + 1], cache.indexAt[p], cache.indexAt[p + 1]);
                return;
            }
            const auto offset = static_cast<std::uint32_t>(cache.vertexAt[p]);
            std::copy(part.mesh.colors.begin(), part.mesh.colors.end(), mesh.colors.begin() + offset);
            copyTexturing(part.mesh, mesh, offset);
        });
    }
    for (std::size_t p : changed) {
        cache.usedVertices[p] = static_cast<std::uint32_t>(cache.parts[p].mesh.positions.size());
        cache.usedIndices[p] = static_cast<std::uint32_t>(cache.parts[p].mesh.indices.size());
    }
    // The moved parts' outline vertices, under their new keys.
    std::vector<std::pair<Key, std::uint32_t>> fresh;
    for (std::size_t c = 0; c < changed.size(); ++c) {
        if (!moved[c]) continue;
        const std::size_t p = changed[c];
        for (std::uint32_t local : cache.parts[p].outline) {
            const auto v = static_cast<std::uint32_t>(cache.vertexAt[p] + local);
            fresh.push_back({vertexKey(mesh, v, cache.keyOrigin - mesh.origin, cache.keyCell), v});
        }
    }
    if (!fresh.empty()) {
        // Merged from the back into room made at the end: std::inplace_merge
        // took a buffer as large as all the keys (7 ms of a patch on the
        // building floor, for a few hundred new keys).
        std::sort(fresh.begin(), fresh.end());
        std::vector<std::pair<Key, std::uint32_t>>& keyed = cache.keyed;
        std::size_t i = keyed.size(), j = fresh.size();
        if (i + j > keyed.capacity()) keyed.reserve(i + j + (i + j) / 8);
        keyed.resize(i + j);
        for (std::size_t k = i + j; j > 0;) {
            --k;
            if (i > 0 && fresh[j - 1] < keyed[i - 1])
                keyed[k] = keyed[--i];
            else
                keyed[k] = fresh[--j];
        }
    }
    std::sort(gone.begin(), gone.end());
    gone.erase(std::unique(gone.begin(), gone.end()), gone.end());
    // Summed again: every group with an outline vertex of a changed part,
    // and every group a moved vertex left.
    const std::vector<std::pair<Key, std::uint32_t>>& keyed = cache.keyed;
    const auto smooth = [&](std::size_t a, std::size_t b) {
        smoothGroup(keyed, a, b, mesh, own, weight, [&](std::uint32_t v) { return scaleOf(mesh, cache, v); });
    };
    // Few groups to sum again (a chair's parts coloured again among the
    // building floor's 600,000 keys): each is found by its key; the walk
    // along all keys took 2.5 ms of every frame there.
    std::size_t outlineVertices = 0;
    for (std::size_t p : changed) outlineVertices += cache.parts[p].outline.size();
    if ((outlineVertices + gone.size()) * cache.keysPerSearch < keyed.size()) {
        std::vector<Key> keys = std::move(gone);
        for (std::size_t p : changed)
            for (std::uint32_t local : cache.parts[p].outline)
                keys.push_back(vertexKey(mesh, static_cast<std::uint32_t>(cache.vertexAt[p] + local),
                                         cache.keyOrigin - mesh.origin, cache.keyCell));
        std::sort(keys.begin(), keys.end());
        keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
        const auto before = [](const std::pair<Key, std::uint32_t>& entry, const Key& key) { return entry.first < key; };
        for (const Key& key : keys) {
            const auto a = std::lower_bound(keyed.begin(), keyed.end(), key, before);
            auto b = a;
            while (b != keyed.end() && b->first == key) ++b;
            if (a != b) smooth(static_cast<std::size_t>(a - keyed.begin()), static_cast<std::size_t>(b - keyed.begin()));
        }
        return resized;
    }
    // Many: found in one walk along the keys (new light on every polygon, as
    // an edit of a light makes, sorted them all each frame).
    std::vector<std::uint8_t> mine(mesh.positions.size(), 0);
    for (std::size_t p : changed)
        for (std::uint32_t local : cache.parts[p].outline) mine[cache.vertexAt[p] + local] = 1;
    const auto walkStart = std::chrono::steady_clock::now();
    std::size_t g = 0;
    for (std::size_t a = 0, b = 0; a < keyed.size(); a = b) {
        const Key& key = keyed[a].first;
        while (g < gone.size() && gone[g] < key) ++g;
        bool any = g < gone.size() && gone[g] == key;
        for (b = a; b < keyed.size() && keyed[b].first == key; ++b) any = any || mine[keyed[b].second];
        if (any) smooth(a, b);
    }
    walked = std::chrono::duration<double>(std::chrono::steady_clock::now() - walkStart).count();
    return resized;
}

}  // namespace

struct SnapshotCache::Scratches {
    tbb::enumerable_thread_specific<meshing::Scratch> perThread;
};
SnapshotCache::ScratchesHolder::ScratchesHolder() : held(std::make_unique<Scratches>()) {}
SnapshotCache::ScratchesHolder::ScratchesHolder(const ScratchesHolder&) : ScratchesHolder() {}
SnapshotCache::ScratchesHolder& SnapshotCache::ScratchesHolder::operator=(const ScratchesHolder&) { return *this; }
SnapshotCache::ScratchesHolder::~ScratchesHolder() = default;

glm::dvec3 displayOrigin(const Scene& scene) {
    const Aabb bounds = scene.bounds(), detail = scene.detailBounds();
    const bool holdsOrigin = glm::all(glm::lessThanEqual(bounds.lo, glm::dvec3(0.0))) &&
                             glm::all(glm::lessThanEqual(glm::dvec3(0.0), bounds.hi));
    if (bounds.empty() || holdsOrigin) return glm::dvec3(0.0);
    const glm::dvec3 e = detail.extent();
    const double size = std::max({e.x, e.y, e.z});
    if (!(size > 0.0) || !std::isfinite(size)) return bounds.center();
    const double cell = std::exp2(std::ceil(std::log2(size)));
    return glm::round(scene.detailCentre() / cell) * cell;
}

MeshSnapshot compactMesh(const MeshSnapshot& mesh) {
    MeshSnapshot out;
    out.origin = mesh.origin;
    out.fileOrigin = mesh.fileOrigin;
    out.textures = mesh.textures;
    out.linePositions = mesh.linePositions;
    out.lineColors = mesh.lineColors;
    out.modifiedLinks = mesh.modifiedLinks;
    out.modifiedLinksShown = mesh.modifiedLinksShown;
    constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> to(mesh.positions.size(), kUnused);
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t* i = &mesh.indices[t];
        if (i[0] == i[1] && i[1] == i[2]) continue;
        for (int k = 0; k < 3; ++k) to[i[k]] = 0;
    }
    const bool textured = !mesh.uvs.empty();
    for (std::size_t v = 0; v < to.size(); ++v) {
        if (to[v] == kUnused) continue;
        to[v] = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(mesh.positions[v]);
        if (!mesh.normals.empty()) out.normals.push_back(mesh.normals[v]);
        if (!mesh.colors.empty()) out.colors.push_back(mesh.colors[v]);
        if (!textured) continue;
        out.uvs.push_back(mesh.uvs[v]);
        out.textureLayer.push_back(mesh.textureLayer[v]);
        out.texelScale.push_back(mesh.texelScale[v]);
    }
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t* i = &mesh.indices[t];
        if (i[0] == i[1] && i[1] == i[2]) continue;
        out.indices.insert(out.indices.end(), {to[i[0]], to[i[1]], to[i[2]]});
    }
    return out;
}

MeshSnapshot makeRadiositySnapshot(const Scene& scene, const Hierarchy& hierarchy) {
    MeshSnapshot mesh;
    SnapshotCache cache;
    makeRadiositySnapshot(scene, hierarchy, mesh, cache);
    return mesh;
}

std::size_t makeRadiositySnapshot(const Scene& scene, const Hierarchy& hierarchy, MeshSnapshot& mesh, SnapshotCache& cache,
                                  std::optional<std::chrono::steady_clock::time_point> stop,
                                  std::vector<std::uint8_t>* touched) {
    // Polygons are meshed independently, on all cores; a polygon whose
    // signature is unchanged keeps its part. The parts are joined in polygon
    // order (the same mesh as one core makes from scratch).
    const std::size_t polygons = scene.polygons.size();
    // Parts keep positions relative to the origin the first build chose
    // (a median over the polygons: not remade every frame).
    if (cache.parts.empty()) cache.origin = displayOrigin(scene);
    mesh.origin = cache.origin;
    mesh.fileOrigin = scene.fileOrigin;
    cache.parts.resize(polygons);
    std::vector<std::uint8_t> remeshed(polygons, 0);
    std::atomic<std::size_t> meshed{0}, left{0};
    std::atomic<bool> resizesWait{false}, reshaped{false};
    std::atomic<std::size_t> reshapedLeaves{0};
    const auto meshingStart = std::chrono::steady_clock::now();
    // A build after one that left resizes makes a new layout whatever its
    // stop, and so does one that has meshed a resized part: the other parts
    // leave it the time (at 120 fps in `two-offices` such builds took 6 ms
    // where 2.5 were left).
    const bool mayDelayResizes = stop && !cache.resizesWaited;
    std::atomic<bool> relayoutAhead{stop && cache.resizesWaited};
    // Whether patching `sofar` parts in (and a new layout, if `resizing` or
    // one is ahead) would end past the stop.
    const auto pastStop = [&](std::chrono::steady_clock::time_point stopAt, std::size_t sofar, bool resizing) {
        const double needed = cache.walkSeconds + double(sofar) * cache.patchSecondsPerPart +
                              (resizing || relayoutAhead.load(std::memory_order_relaxed) ? cache.relayoutSeconds : 0.0);
        return std::chrono::steady_clock::now() +
                   std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(needed)) >
               stopAt;
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polygons, 16), [&](const tbb::blocked_range<std::size_t>& r) {
        Scratch& scratch = cache.scratches.held->perThread.local();
        std::vector<glm::dvec3>& values = scratch.values;
        for (std::size_t p = r.begin(); p < r.end(); ++p) {
            SnapshotCache::Part& part = cache.parts[p];
            if (touched && part.valid && !(*touched)[p]) continue;
            // Past the stop, once kLeastRemeshed went ahead, a polygon the
            // frame touched waits with its leaves unread: on the building
            // floor 8,700 polygons waited frame after frame, and hashing
            // their leaves again took 5 ms of every snapshot.
            if (stop && touched && part.valid && meshed.load(std::memory_order_relaxed) >= kLeastRemeshed &&
                pastStop(*stop, meshed.load(std::memory_order_relaxed), false)) {
                left.fetch_add(1, std::memory_order_relaxed);
                continue;
            }
            const ElementId top = hierarchy.polygonElement(static_cast<std::uint32_t>(p));
            const auto [shape, light] =
                top == kNone ? std::pair<std::uint64_t, std::uint64_t>{0, 0}
                             : polygonSignature(hierarchy, top, scene.polygons[p].material, scratch.leaves);
            if (part.valid && part.shape == shape && part.light == light) {
                if (touched) (*touched)[p] = 0;
                continue;
            }
            // Past the stop, a polygon already meshed once waits for a later
            // frame (at least kLeastRemeshed a call go ahead: progress).
            // A part whose leaves changed in number changes size, and the
            // whole mesh moves to a new layout: past the time that leaves,
            // it waits too (one build in two at most).
            const std::size_t sofar = meshed.load(std::memory_order_relaxed);
            const bool resizes = part.valid && scratch.leaves.size() != part.leaves;
            if (stop && part.valid && (sofar >= kLeastRemeshed || (resizes && mayDelayResizes)) &&
                pastStop(*stop, sofar, resizes && mayDelayResizes)) {
                left.fetch_add(1, std::memory_order_relaxed);
                if (resizes) resizesWait.store(true, std::memory_order_relaxed);
                continue;
            }
            if (resizes) relayoutAhead.store(true, std::memory_order_relaxed);
            part.leaves = scratch.leaves.size();
            meshed.fetch_add(1, std::memory_order_relaxed);
            remeshed[p] = 1;
            if (touched) (*touched)[p] = 0;
            // New light on the same leaves: coloured again only.
            if (part.valid && part.shape == shape && top != kNone) {
                recolour(hierarchy, scratch.leaves, part, values);
                part.light = light;
                continue;
            }
            reshaped.store(true, std::memory_order_relaxed);
            reshapedLeaves.fetch_add(scratch.leaves.size(), std::memory_order_relaxed);
            for (std::vector<glm::vec3>* v : {&part.mesh.positions, &part.mesh.normals, &part.mesh.colors, &part.mesh.texelScale})
                v->clear();
            part.mesh.uvs.clear();
            part.mesh.textureLayer.clear();
            part.mesh.indices.clear();
            part.weights.clear();
            part.outline.clear();
            if (top != kNone) addPolygon(scene, hierarchy, top, mesh.origin, part, scratch);
            part.shape = shape;
            part.light = light;
            part.valid = true;
        }
    });
    // The meshing's time, all of it counted to the parts meshed anew (those
    // coloured again cost a tenth as much a leaf); a dearer build counts at
    // once, a cheaper one by degrees.
    if (reshapedLeaves.load() >= SnapshotCache::kReshapeSample) {
        const double rate = std::chrono::duration<double>(std::chrono::steady_clock::now() - meshingStart).count() /
                            double(reshapedLeaves.load());
        cache.reshapeSecondsPerLeaf = std::max(rate, 0.75 * cache.reshapeSecondsPerLeaf);
    }
    // Nothing re-meshed: the mesh assembled last time stands (a frame that
    // changed no radiosity, as when the budget held every link update back).
    // Parts re-meshed to the sizes they had: written in place.
    // The smoothing keys are quantised in the scene's box: a box that
    // changed (an object moved out of it) changes every key.
    const Aabb box = cache.objectBoxes.all(scene);
    const bool same = cache.assembled && mesh.positions.size() == cache.vertices &&
                      mesh.indices.size() == cache.indices && mesh.linePositions.empty() &&
                      cache.vertexAt.size() == polygons + 1 && box.lo == cache.keyOrigin &&
                      keyCellOf(box) == cache.keyCell;
    cache.resizesWaited = resizesWait.load();
    // Parts only coloured again keep their places and the sorted keys: the
    // patch then walks the keys once, and costs less than joining the parts
    // anew (which keys and sorts them all), however many there are.
    const bool cheaperWhole = reshaped.load() && cache.assembleSeconds > 0.0 &&
                              cache.walkSeconds + double(meshed.load()) * cache.patchSecondsPerPart > cache.assembleSeconds;
    if (same && !cheaperWhole) {
        const auto patchStart = std::chrono::steady_clock::now();
        double walked = 0.0;
        const bool resized = patch(mesh, cache, remeshed, walked);
        const std::size_t n = meshed.load();
        const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - patchStart).count() - walked;
        if (resized) {
            // What a new layout adds to the patch: moving every part, and
            // the keys of every re-meshed part made again (not only those of
            // the parts that moved). Timed on relayout() alone it read 0.7 ms
            // in `office` where such patches took 1.3 to 3.9 ms more than
            // the others, and frames at 120 fps ran over by as much. Smoothed
            // by halves, but a dearer one counts at once: a frame leaves it
            // the time.
            const double extra = std::max(0.0, took - double(n) * cache.patchSecondsPerPart);
            cache.relayoutSeconds = std::max(extra, 0.5 * (cache.relayoutSeconds + extra));
        } else if (n >= kLeastRemeshed) {
            cache.patchSecondsPerPart = 0.5 * (cache.patchSecondsPerPart + took / double(n));
        }
        if (n >= kLeastRemeshed && walked > 0.0)
            cache.walkSeconds = cache.walkSeconds > 0.0 ? 0.5 * (cache.walkSeconds + walked) : walked;
        return left.load();
    }
    // Each part's place in the mesh, then the parts copied on all cores.
    const auto assembleStart = std::chrono::steady_clock::now();
    std::vector<std::size_t> vertexAt(polygons + 1, 0), indexAt(polygons + 1, 0), outlineAt(polygons + 1, 0);
    for (std::size_t p = 0; p < polygons; ++p) {
        const SnapshotCache::Part& part = cache.parts[p];
        vertexAt[p + 1] = vertexAt[p] + part.mesh.positions.size();
        indexAt[p + 1] = indexAt[p] + part.mesh.indices.size();
        outlineAt[p + 1] = outlineAt[p] + part.outline.size();
    }
    for (std::vector<glm::vec3>* v : {&mesh.positions, &mesh.normals, &mesh.colors}) resizeWithRoom(*v, vertexAt[polygons]);
    const std::size_t texturedVertices = scene.textures.empty() ? 0 : vertexAt[polygons];
    mesh.uvs.resize(texturedVertices);
    mesh.textureLayer.resize(texturedVertices);
    mesh.texelScale.resize(texturedVertices);
    mesh.textures = scene.textures;
    for (std::vector<glm::vec3>* v : {&mesh.linePositions, &mesh.lineColors}) v->clear();
    resizeWithRoom(mesh.indices, indexAt[polygons]);
    std::vector<double> weights(vertexAt[polygons]);
    std::vector<std::uint32_t> outline(outlineAt[polygons]);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, polygons, 64), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t p = r.begin(); p < r.end(); ++p) {
            const SnapshotCache::Part& part = cache.parts[p];
            const auto offset = static_cast<std::uint32_t>(vertexAt[p]);
            std::copy(part.mesh.positions.begin(), part.mesh.positions.end(), mesh.positions.begin() + offset);
            std::copy(part.mesh.normals.begin(), part.mesh.normals.end(), mesh.normals.begin() + offset);
            std::copy(part.mesh.colors.begin(), part.mesh.colors.end(), mesh.colors.begin() + offset);
            copyTexturing(part.mesh, mesh, offset);
            std::copy(part.weights.begin(), part.weights.end(), weights.begin() + offset);
            for (std::size_t i = 0; i < part.mesh.indices.size(); ++i)
                mesh.indices[indexAt[p] + i] = part.mesh.indices[i] + offset;
            for (std::size_t i = 0; i < part.outline.size(); ++i) outline[outlineAt[p] + i] = part.outline[i] + offset;
        }
    });
    cache.assembled = true;
    cache.usedVertices.resize(polygons);
    cache.usedIndices.resize(polygons);
    for (std::size_t p = 0; p < polygons; ++p) {
        cache.usedVertices[p] = static_cast<std::uint32_t>(vertexAt[p + 1] - vertexAt[p]);
        cache.usedIndices[p] = static_cast<std::uint32_t>(indexAt[p + 1] - indexAt[p]);
    }
    cache.vertices = mesh.positions.size();
    cache.indices = mesh.indices.size();
    cache.vertexAt = std::move(vertexAt);
    cache.indexAt = std::move(indexAt);
    numberVertices(cache);
    smoothAcrossPolygons(scene, mesh, weights, outline, cache);
    cache.assembleSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - assembleStart).count();
    // The arrays of the next new layout, written once now (outside the
    // assembly's timing): the first new layout of the building floor's
    // chair took 27 ms, most of it faulting a new allocation in, against 8
    // for the next ones.
    for (std::vector<glm::vec3>* v : {&cache.spare.positions, &cache.spare.normals, &cache.spare.colors}) {
        resizeWithRoom(*v, mesh.positions.size());
        keepRoomWritten(*v);
    }
    resizeWithRoom(cache.spare.indices, mesh.indices.size());
    keepRoomWritten(cache.spare.indices);
    for (std::vector<glm::vec3>* v : {&mesh.positions, &mesh.normals, &mesh.colors}) keepRoomWritten(*v);
    keepRoomWritten(mesh.indices);
    keepRoomWritten(cache.keyed);
    keepRoomWritten(cache.partOfVertex);
    return left.load();
}

}  // namespace rad
