#include "scene/ClosedBackFaces.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

#include "scene/MeshGeometry.h"

namespace rad {
namespace {

struct Component {
    double volume = 0.0;  // signed: positive when the faces point out
    glm::dvec3 lo{std::numeric_limits<double>::infinity()},
        hi{-std::numeric_limits<double>::infinity()};
    std::vector<std::size_t> triangles;
};

}  // namespace

bool backFacesFaceNoLight(std::span<const std::array<glm::dvec3, 3>> triangles,
                          std::span<const glm::dvec3> lightPoints, std::size_t mostVisits) {
    if (triangles.empty()) return false;
    const IndexedTriangles indexed = indexTriangles(triangles);
    const auto& tri = indexed.triangles;
    // Closed and consistently turned: each directed edge once, and its
    // reverse once.
    std::unordered_map<std::uint64_t, int> edges;
    const auto key = [](std::uint32_t a, std::uint32_t b) { return std::uint64_t(a) << 32 | b; };
    for (const auto& t : tri)
        for (int k = 0; k < 3; ++k) {
            if (t[k] == t[(k + 1) % 3]) return false;
            if (++edges[key(t[k], t[(k + 1) % 3])] > 1) return false;
        }
    for (const auto& [e, n] : edges)
        if (!edges.contains(key(std::uint32_t(e), std::uint32_t(e >> 32)))) return false;
    std::unordered_map<std::uint32_t, Component> components;
    for (std::size_t t = 0; t < tri.size(); ++t) {
        Component& c = components[indexed.part[t]];
        c.triangles.push_back(t);
        const auto& v = triangles[t];
        // About the first vertex of the component: small numbers far from the origin.
        const glm::dvec3 o = triangles[c.triangles.front()][0];
        c.volume += glm::dot(v[0] - o, glm::cross(v[1] - o, v[2] - o)) / 6.0;
        for (const glm::dvec3& x : v) {
            c.lo = glm::min(c.lo, x);
            c.hi = glm::max(c.hi, x);
        }
    }
    std::size_t visits = 0;
    for (const auto& [root, c] : components) {
        const glm::dvec3 e = c.hi - c.lo;
        // Flat (a sheet closed on itself): no inside to speak of.
        if (std::abs(c.volume) <= 1e-9 * std::max({e.x, e.y, e.z}) * glm::dot(e, e)) return false;
        const double turn = c.volume > 0.0 ? 1.0 : -1.0;
        for (const glm::dvec3& p : lightPoints) {
            // The winding number, +1 inside whichever way the faces point.
            double inside = 0.0;
            const glm::dvec3 margin = 1e-6 * e;
            if (glm::all(glm::greaterThanEqual(p, c.lo - margin)) &&
                glm::all(glm::lessThanEqual(p, c.hi + margin))) {
                visits += c.triangles.size();
                if (visits > mostVisits) return false;
                double omega = 0.0;
                for (std::size_t t : c.triangles)
                    omega +=
                        solidAngle(triangles[t][0] - p, triangles[t][1] - p, triangles[t][2] - p);
                inside = turn * omega / (4.0 * std::numbers::pi);
            }
            // The backs face the inside (faces out) or the outside (faces
            // in); a point not clearly on the front side counts as behind.
            const bool behind = turn > 0.0 ? inside > 0.25 : inside < 0.75;
            if (behind) return false;
        }
    }
    return true;
}

}  // namespace rad
