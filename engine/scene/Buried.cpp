#include "scene/Buried.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>

#include "scene/MeshGeometry.h"
#include "scene/Pieces.h"

namespace rad {
namespace {

// Past this many faces a closed part is not taken as a solid (slabs, walls
// and furniture have few). Past kMostPieces a polygon is left whole by a
// solid: each face crossing the polygon cuts it along a line.
constexpr std::size_t kMostFaces = 512;

// The segments where the solid's faces cross the polygon's plane inside
// the polygon (a face that only touches the plane is not a crossing: contact
// is not burial).
std::vector<std::pair<glm::dvec3, glm::dvec3>> crossings(const Piece& polygon,
                                                         const glm::dvec3& normal,
                                                         const ClosedSolid& solid) {
    std::vector<std::pair<glm::dvec3, glm::dvec3>> found;
    const double offset = glm::dot(normal, polygon[0].p);
    for (const auto& t : solid.triangles) {
        PlaneSection s = planeSection(t, normal, offset, solid.tolerance);
        if (s.count < 2 || !s.front || !s.back) continue;
        if (clipToPiece(polygon, normal, s.a, s.b, solid.tolerance)) found.emplace_back(s.a, s.b);
    }
    return found;
}

// Whether `p` lies on the triangle `t`, within `tolerance`.
bool onTriangle(const std::array<glm::dvec3, 3>& t, const glm::dvec3& p, double tolerance) {
    const glm::dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
    const double twice = glm::length(n);
    if (std::abs(glm::dot(n, p - t[0])) > tolerance * twice) return false;
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 edge = t[(k + 1) % 3] - t[k];
        if (glm::dot(glm::cross(edge, p - t[k]), n) < -tolerance * glm::length(edge) * twice)
            return false;
    }
    return true;
}

}  // namespace

bool ClosedSolid::holds(const glm::dvec3& p) const {
    if (glm::any(glm::lessThan(p, box.lo)) || glm::any(glm::greaterThan(p, box.hi))) return false;
    double omega = 0.0;
    for (const auto& t : triangles) {
        // On a face the winding number is not defined (a face's own solid
        // angle is +-2 pi by rounding): a point there is not inside.
        if (onTriangle(t, p, tolerance)) return false;
        omega += solidAngle(t[0] - p, t[1] - p, t[2] - p);
    }
    return omega / (4.0 * std::numbers::pi) > 0.75;
}

std::vector<ClosedSolid> closedSolids(std::span<const std::array<glm::dvec3, 3>> triangles) {
    const IndexedTriangles indexed = indexTriangles(triangles);
    const auto& tri = indexed.triangles;
    std::unordered_map<std::uint32_t, std::vector<std::size_t>> parts;
    for (std::size_t t = 0; t < tri.size(); ++t) parts[indexed.part[t]].push_back(t);

    std::vector<ClosedSolid> solids;
    const auto key = [](std::uint32_t a, std::uint32_t b) { return std::uint64_t(a) << 32 | b; };
    for (const auto& [root, faces] : parts) {
        if (faces.size() < 4 || faces.size() > kMostFaces) continue;
        // Closed: each directed edge as often as its reverse.
        std::unordered_map<std::uint64_t, int> edges;
        bool closed = true;
        for (std::size_t t : faces)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = tri[t][k], b = tri[t][(k + 1) % 3];
                closed = closed && a != b;
                ++edges[key(a, b)];
            }
        for (const auto& [e, n] : edges) {
            const auto reverse = edges.find(key(std::uint32_t(e), std::uint32_t(e >> 32)));
            closed = closed && reverse != edges.end() && reverse->second == n;
        }
        if (!closed) continue;
        ClosedSolid solid;
        for (std::size_t t : faces) {
            solid.triangles.push_back(triangles[t]);
            for (const glm::dvec3& v : triangles[t]) solid.box.extend(v);
        }
        const glm::dvec3 extent = solid.box.extent();
        const double size = glm::length(extent);
        const double thinnest = std::min({extent.x, extent.y, extent.z});
        solid.tolerance = positionTolerance(solid.box);
        // Faces out, around a volume (not a sheet closed on itself).
        const glm::dvec3 o = solid.triangles.front()[0];
        double volume = 0.0;
        for (const auto& t : solid.triangles)
            volume += glm::dot(t[0] - o, glm::cross(t[1] - o, t[2] - o)) / 6.0;
        if (volume <= 1e-6 * thinnest * size * size || thinnest <= 10.0 * solid.tolerance) continue;
        solids.push_back(std::move(solid));
    }
    return solids;
}

BuriedParts cutBuriedParts(std::vector<std::vector<Polygon>>& polygons, std::span<const char> cut,
                           std::span<const ClosedSolid> solids) {
    BuriedParts result;
    result.areaLeftOut.assign(polygons.size(), 0.0);
    if (solids.empty()) return result;
    std::vector<Aabb> boxes;
    for (const ClosedSolid& s : solids) boxes.push_back(s.box);
    BoxGrid grid(boxes);
    std::vector<Piece> pieces, next;
    for (std::size_t o = 0; o < polygons.size(); ++o) {
        if (!cut[o]) continue;
        std::vector<Polygon> out;
        out.reserve(polygons[o].size());
        for (const Polygon& polygon : polygons[o]) {
            const Aabb box = boxOf(polygon);
            const glm::dvec3 normal = polygon.normal();
            const Piece whole = pieceOf(polygon);
            pieces.assign(1, whole);
            bool changed = false;
            for (std::uint32_t s : grid.near(box)) {
                const ClosedSolid& solid = solids[s];
                if (!overlaps(box, solid.box, solid.tolerance)) continue;
                // Cut the pieces along the segments where the solid's faces
                // cross the polygon (none: it is wholly inside or outside),
                // then leave out the pieces inside; when none is, the pieces
                // stay as they were.
                const auto cuts = crossings(whole, normal, solid);
                if (cuts.empty() && !(glm::all(glm::greaterThanEqual(box.lo, solid.box.lo)) &&
                                      glm::all(glm::lessThanEqual(box.hi, solid.box.hi))))
                    continue;  // uncut and not within the solid's box: outside it
                next = pieces;
                for (const auto& [a, b] : cuts) {
                    cutAlong(next, normal, a, b, solid.tolerance);
                    if (next.size() > kMostPieces) break;
                }
                if (next.size() > kMostPieces) continue;
                const std::size_t before = next.size();
                std::erase_if(next, [&](const Piece& piece) {
                    glm::dvec3 centre(0.0);
                    for (const PieceVertex& v : piece) centre += v.p;
                    return solid.holds(centre / double(piece.size()));
                });
                if (next.size() == before) continue;
                changed = true;
                pieces.swap(next);
                if (pieces.empty()) break;
            }
            if (!changed) {
                out.push_back(polygon);
                continue;
            }
            ++result.polygonsCut;
            double left = 0.0;
            for (const Piece& piece : pieces) left += pieceArea(piece);
            appendPieces(polygon, pieces, out);
            result.areaLeftOut[o] += std::max(0.0, polygon.area() - left);
        }
        polygons[o] = std::move(out);
    }
    return result;
}

}  // namespace rad
