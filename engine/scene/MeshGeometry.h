#pragma once
// What the closed-mesh steps of the import share (scene/ClosedBackFaces.h,
// scene/Buried.h).

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace rad {

// Hashes a point by its exact bits: exporters write a vertex that several
// triangles share as the same numbers, so equal bits mean one vertex.
struct PointHash {
    std::size_t operator()(const glm::dvec3& p) const {
        std::uint64_t bits[3];
        std::memcpy(bits, &p, sizeof bits);
        return std::hash<std::uint64_t>()(bits[0] * 0x9E3779B97F4A7C15ull ^
                                          bits[1] * 0xC2B2AE3D27D4EB4Full ^ bits[2]);
    }
};

// Triangles as indices into their distinct corners (matched exactly), and
// the parts they form: triangles joined by shared corners.
struct IndexedTriangles {
    std::vector<glm::dvec3> points;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<std::uint32_t> part;  // per triangle: its part's first corner
};
IndexedTriangles indexTriangles(std::span<const std::array<glm::dvec3, 3>> triangles);

// The solid angle of a triangle seen from the origin, signed: positive when
// the origin is behind it (Van Oosterom and Strackee 1983).
inline double solidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    const double num = glm::dot(a, glm::cross(b, c));
    const double den =
        la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
    return 2.0 * std::atan2(num, den);
}

}  // namespace rad
