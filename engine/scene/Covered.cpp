#include "scene/Covered.h"

#include <algorithm>
#include <cstdint>
#include <glm/glm.hpp>

#include "scene/Pieces.h"

namespace rad {

namespace {

struct Flat {
    std::uint32_t object, index;  // polygons[object][index]
    Aabb box;
    glm::dvec3 normal;
    double area;
    std::size_t order;  // in the file: objects, then polygons
};

// Whether `cover` lies in the plane of `under` and faces the same way.
bool coincident(const Polygon& under, const Flat& u, const Polygon& cover, const Flat& c,
                double tolerance) {
    if (glm::dot(u.normal, c.normal) < 1.0 - 1e-9) return false;
    const double offset = glm::dot(u.normal, under.vertices[0]);
    for (int k = 0; k < cover.vertexCount; ++k)
        if (std::abs(glm::dot(u.normal, cover.vertices[k]) - offset) > tolerance) return false;
    return true;
}

// Splits `piece` by the convex polygon `cover` (in its plane, facing
// `normal`): the parts outside go to `outside`; returns the part inside
// (fewer than 3 vertices: none).
Piece cutBy(const Piece& piece, const Polygon& cover, const glm::dvec3& normal, double tolerance,
            std::vector<Piece>& outside) {
    Piece inside = piece, outer, inner;
    for (int k = 0; k < cover.vertexCount && inside.size() >= 3; ++k) {
        const glm::dvec3& a = cover.vertices[k];
        const glm::dvec3& b = cover.vertices[(k + 1) % cover.vertexCount];
        // Counter-clockwise seen from the front: outward is edge x normal.
        const glm::dvec3 out = glm::cross(b - a, normal);
        const double length = glm::length(out);
        if (length == 0.0) continue;
        const glm::dvec3 n = out / length;
        split(inside, glm::dvec4(n, glm::dot(n, a)), tolerance, outer, inner);
        if (outer.size() >= 3) outside.push_back(outer);
        inside.swap(inner);
    }
    return inside;
}

}  // namespace

CoveredParts cutCoveredParts(std::vector<std::vector<Polygon>>& polygons,
                             std::span<const char> cut) {
    CoveredParts result;
    result.areaLeftOut.assign(polygons.size(), 0.0);
    std::vector<Flat> flat;
    std::vector<Aabb> boxes;
    for (std::uint32_t o = 0; o < polygons.size(); ++o) {
        if (!cut[o]) continue;
        for (std::uint32_t i = 0; i < polygons[o].size(); ++i) {
            const Polygon& p = polygons[o][i];
            flat.push_back({o, i, boxOf(p), p.normal(), p.area(), flat.size()});
            boxes.push_back(flat.back().box);
        }
    }
    if (flat.size() < 2) return result;
    BoxGrid grid(boxes);
    // The new polygons of each object, filled as its polygons are visited.
    std::vector<std::vector<Polygon>> out(polygons.size());
    std::vector<char> changedObject(polygons.size(), 0);
    std::vector<Piece> pieces, next;
    for (const Flat& u : flat) {
        const Polygon& under = polygons[u.object][u.index];
        const double tolerance = positionTolerance(u.box);
        pieces.assign(1, pieceOf(under));
        bool changed = false, tooMany = false;
        for (std::uint32_t s : grid.near(u.box)) {
            const Flat& c = flat[s];
            // Only a smaller polygon covers (of two alike, the earlier).
            if (s == u.order || c.area > u.area || (c.area == u.area && c.order > u.order))
                continue;
            if (!overlaps(u.box, c.box, -tolerance)) continue;  // flat boxes: meeting within the tolerance
            const Polygon& cover = polygons[c.object][c.index];
            if (!coincident(under, u, cover, c, tolerance)) continue;
            next.clear();
            bool covers = false;
            for (const Piece& piece : pieces) {
                const std::size_t before = next.size();
                const Piece inside = cutBy(piece, cover, u.normal, tolerance, next);
                // A sliver inside (touching along an edge, within the
                // tolerance) leaves the piece as it was.
                if (inside.size() >= 3 && pieceArea(inside) > tolerance * std::sqrt(u.area)) {
                    covers = true;
                } else {
                    next.resize(before);
                    next.push_back(piece);
                }
            }
            if (!covers) continue;
            if (next.size() > kMostPieces) {
                tooMany = true;
                break;
            }
            pieces.swap(next);
            changed = true;
        }
        if (!changed || tooMany) {
            out[u.object].push_back(under);
            continue;
        }
        ++result.polygonsCut;
        changedObject[u.object] = 1;
        double left = 0.0;
        for (const Piece& piece : pieces) left += pieceArea(piece);
        appendPieces(under, pieces, out[u.object]);
        result.areaLeftOut[u.object] += std::max(0.0, u.area - left);
    }
    for (std::size_t o = 0; o < polygons.size(); ++o)
        if (changedObject[o]) polygons[o] = std::move(out[o]);
    return result;
}

}  // namespace rad
