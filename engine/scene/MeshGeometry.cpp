#include "scene/MeshGeometry.h"

#include <numeric>
#include <unordered_map>

namespace rad {

IndexedTriangles indexTriangles(std::span<const std::array<glm::dvec3, 3>> triangles) {
    IndexedTriangles out;
    std::unordered_map<glm::dvec3, std::uint32_t, PointHash> ids;
    out.triangles.resize(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const auto [at, added] =
                ids.try_emplace(triangles[t][k], static_cast<std::uint32_t>(out.points.size()));
            if (added) out.points.push_back(triangles[t][k]);
            out.triangles[t][k] = at->second;
        }
    std::vector<std::uint32_t> parent(out.points.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& t : out.triangles)
        for (int k = 1; k < 3; ++k) parent[find(t[k])] = find(t[0]);
    out.part.resize(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) out.part[t] = find(out.triangles[t][0]);
    return out;
}

}  // namespace rad
