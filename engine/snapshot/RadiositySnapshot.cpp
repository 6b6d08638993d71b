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

void addPolygon(const Hierarchy& h, ElementId top, MeshSnapshot& mesh) {
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
    }
    for (ElementId l : leaves) {
        const HElement& e = h[l];
        std::array<std::uint32_t, 4> idx{};
        for (int k = 0; k < e.patch.n; ++k) idx[k] = vertices[lattice(e.param[k])].index;
        for (int k = 1; k + 1 < e.patch.n; ++k) mesh.indices.insert(mesh.indices.end(), {idx[0], idx[k], idx[k + 1]});
    }
}

}  // namespace

MeshSnapshot makeRadiositySnapshot(const Scene& scene, const Hierarchy& hierarchy) {
    MeshSnapshot mesh;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const ElementId top = hierarchy.polygonElement(p);
        if (top != kNone) addPolygon(hierarchy, top, mesh);
    }
    return mesh;
}

}  // namespace rad
