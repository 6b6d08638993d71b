#include "update/Obstacles.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace rad {
namespace {

std::array<glm::dvec3, 8> corners(const Aabb& b) {
    std::array<glm::dvec3, 8> c;
    for (int k = 0; k < 8; ++k) c[k] = glm::dvec3(k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z);
    return c;
}

Aabb intersection(const Aabb& a, const Aabb& b) {
    Aabb r;
    r.lo = glm::max(a.lo, b.lo);
    r.hi = glm::min(a.hi, b.hi);
    return glm::all(glm::lessThanEqual(r.lo, r.hi)) ? r : Aabb{};
}

// The static polygons cutting `box` (the object's box at some position),
// clipped to it.
void cutting(const Scene& scene, std::uint32_t object, const Aabb& box, std::vector<Aabb>& out) {
    const std::array<glm::dvec3, 8> c = corners(box);
    const glm::dvec3 e = box.extent();
    const double tolerance = 1e-6 * std::max({e.x, e.y, e.z});
    for (const Polygon& p : scene.polygons) {
        if (p.object == object) continue;
        Aabb pb;
        for (int k = 0; k < p.vertexCount; ++k) pb.extend(p.vertices[k]);
        const Aabb piece = intersection(pb, box);
        if (piece.empty()) continue;
        const glm::dvec3 n = p.normal();
        bool below = false, above = false;
        for (const glm::dvec3& x : c) {
            const double d = glm::dot(n, x - p.vertices[0]);
            below = below || d < -tolerance;
            above = above || d > tolerance;
        }
        if (below && above) out.push_back(piece);
    }
}

}  // namespace

std::vector<Aabb> motionObstacles(const Scene& scene, std::uint32_t object, const Aabb& oldBox,
                                  const glm::dmat4& oldToNew) {
    std::vector<Aabb> now, before;
    cutting(scene, object, scene.objectBounds(object), now);
    cutting(scene, object, oldBox, before);
    // What stood in the object at the old position, carried along with it.
    for (const Aabb& b : before) {
        Aabb moved;
        for (const glm::dvec3& x : corners(b)) moved.extend(glm::dvec3(oldToNew * glm::dvec4(x, 1.0)));
        now.push_back(moved);
    }
    return now;
}

}  // namespace rad
