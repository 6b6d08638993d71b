#include "snapshot/RadiositySnapshot.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace rad {
namespace {

// A point of the dyadic lattice of one input polygon's quadtree.
struct LatticePoint {
    std::int64_t i, j;
    bool operator==(const LatticePoint&) const = default;
};
struct LatticeHash {
    std::size_t operator()(const LatticePoint& p) const {
        return std::hash<std::int64_t>()(p.i * 0x9E3779B97F4A7C15LL ^ p.j);
    }
};

struct VertexSum {
    glm::dvec3 weighted{0.0};
    double weight = 0.0;
    glm::dvec3 position{0.0};
    std::uint32_t index = 0;
};

void collectLeaves(const Hierarchy& h, ElementId e, std::vector<ElementId>& out) {
    if (h[e].isLeaf()) {
        out.push_back(e);
        return;
    }
    for (ElementId c : h[e].children) collectLeaves(h, c, out);
}

void addPolygon(const Hierarchy& h, ElementId top, MeshSnapshot& mesh, std::vector<double>& weights) {
    std::vector<ElementId> leaves;
    collectLeaves(h, top, leaves);
    int maxDepth = 0;
    for (ElementId l : leaves) maxDepth = std::max<int>(maxDepth, h[l].depth);
    const double scale = std::ldexp(1.0, maxDepth);
    auto lattice = [&](const glm::dvec2& uv) {
        return LatticePoint{std::llround(uv.x * scale), std::llround(uv.y * scale)};
    };

    std::unordered_map<LatticePoint, VertexSum, LatticeHash> vertices;
    for (ElementId l : leaves) {
        const HElement& e = h[l];
        for (int k = 0; k < e.patch.n; ++k) {
            VertexSum& v = vertices[lattice(e.param[k])];
            v.weighted += e.area * e.radiosity;
            v.weight += e.area;
            v.position = e.patch.v[k];
        }
    }
    std::unordered_map<LatticePoint, glm::dvec3, LatticeHash> value;
    for (const auto& [p, v] : vertices) value[p] = v.weight > 0.0 ? v.weighted / v.weight : glm::dvec3(0.0);

    // Coarse leaves first: their edge ends are final when their T-vertices are set.
    std::sort(leaves.begin(), leaves.end(), [&](ElementId a, ElementId b) { return h[a].depth < h[b].depth; });
    for (ElementId l : leaves) {
        const HElement& e = h[l];
        for (int k = 0; k < e.patch.n; ++k) {
            const LatticePoint a = lattice(e.param[k]), b = lattice(e.param[(k + 1) % e.patch.n]);
            const std::int64_t n = std::max(std::llabs(b.i - a.i), std::llabs(b.j - a.j));
            const glm::dvec3 va = value[a], vb = value[b];
            for (std::int64_t s = 1; s < n; ++s) {
                const LatticePoint p{a.i + (b.i - a.i) / n * s, a.j + (b.j - a.j) / n * s};
                const auto it = value.find(p);
                if (it != value.end()) it->second = glm::mix(va, vb, double(s) / double(n));
            }
        }
    }

    const glm::vec3 normal(h[top].normal);
    for (auto& [p, v] : vertices) {
        v.index = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.emplace_back(v.position);
        mesh.normals.push_back(normal);
        mesh.colors.emplace_back(value[p]);
        weights.push_back(v.weight);
    }
    for (ElementId l : leaves) {
        const HElement& e = h[l];
        std::array<std::uint32_t, 4> idx{};
        for (int k = 0; k < e.patch.n; ++k) idx[k] = vertices[lattice(e.param[k])].index;
        for (int k = 1; k + 1 < e.patch.n; ++k) mesh.indices.insert(mesh.indices.end(), {idx[0], idx[k], idx[k + 1]});
    }
}

// Input polygons that meet edge to edge in one plane (a tiled wall) share
// their vertices' values, so the tiling does not show as steps.
void smoothAcrossPolygons(const Scene& scene, MeshSnapshot& mesh, const std::vector<double>& weights) {
    const Aabb box = scene.bounds();
    const double cell = std::max(1e-300, 1e-6 * glm::length(box.extent()));
    struct Key {
        std::int64_t x, y, z, nx, ny, nz;
        bool operator==(const Key&) const = default;
    };
    struct KeyHash {
        std::size_t operator()(const Key& k) const {
            std::size_t h = 0;
            for (std::int64_t v : {k.x, k.y, k.z, k.nx, k.ny, k.nz}) h = h * 0x100000001B3ULL ^ std::hash<std::int64_t>()(v);
            return h;
        }
    };
    auto keyOf = [&](std::size_t i) {
        const glm::dvec3 p = (glm::dvec3(mesh.positions[i]) - box.lo) / cell;
        const glm::dvec3 n = glm::dvec3(mesh.normals[i]) * 1e3;
        return Key{std::llround(p.x), std::llround(p.y), std::llround(p.z),
                   std::llround(n.x), std::llround(n.y), std::llround(n.z)};
    };
    // Each vertex hashed once: its slot among the distinct keys.
    const std::size_t n = mesh.positions.size();
    std::unordered_map<Key, std::uint32_t, KeyHash> slotOf;
    slotOf.reserve(n);
    std::vector<std::uint32_t> slot(n);
    std::vector<std::pair<glm::dvec3, double>> sums;
    sums.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const auto [it, added] = slotOf.try_emplace(keyOf(i), std::uint32_t(sums.size()));
        if (added) sums.emplace_back(glm::dvec3(0.0), 0.0);
        slot[i] = it->second;
        sums[it->second].first += weights[i] * glm::dvec3(mesh.colors[i]);
        sums[it->second].second += weights[i];
    }
    for (std::size_t i = 0; i < n; ++i) {
        const auto& [sum, w] = sums[slot[i]];
        if (w > 0.0) mesh.colors[i] = glm::vec3(sum / w);
    }
}

}  // namespace

MeshSnapshot makeRadiositySnapshot(const Scene& scene, const Hierarchy& hierarchy) {
    MeshSnapshot mesh;
    makeRadiositySnapshot(scene, hierarchy, mesh);
    return mesh;
}

void makeRadiositySnapshot(const Scene& scene, const Hierarchy& hierarchy, MeshSnapshot& mesh) {
    // Cleared, not freed: a frame's mesh reuses the last one's memory.
    for (std::vector<glm::vec3>* v : {&mesh.positions, &mesh.normals, &mesh.colors, &mesh.linePositions, &mesh.lineColors})
        v->clear();
    mesh.indices.clear();
    std::vector<double> weights;  // per vertex: the leaf area around it
    weights.reserve(mesh.positions.capacity());
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const ElementId top = hierarchy.polygonElement(p);
        if (top != kNone) addPolygon(hierarchy, top, mesh, weights);
    }
    smoothAcrossPolygons(scene, mesh, weights);
}

}  // namespace rad
