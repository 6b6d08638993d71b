#include "scene/Contacts.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scene/Pieces.h"

namespace rad {
namespace {

// A contact splits a polygon when its segment runs across at least this
// share of the polygon's width along it.
constexpr double kDividing = 0.5;

// The segments of `emitter`'s outline seen on the plane of `surface`, when
// it traps its light in front of it (trappingGap); none otherwise.
std::vector<std::pair<glm::dvec3, glm::dvec3>> outlineAcrossGap(const Polygon& emitter, const Polygon& surface,
                                                               double tolerance) {
    const double gap = trappingGap(emitter, surface, tolerance);
    if (gap < 0.0) return {};
    const glm::dvec3 down = gap * emitter.normal();  // from the emitter onto the surface
    std::vector<std::pair<glm::dvec3, glm::dvec3>> out;
    for (int k = 0; k < emitter.vertexCount; ++k)
        out.emplace_back(emitter.vertices[k] + down, emitter.vertices[(k + 1) % emitter.vertexCount] + down);
    return out;
}

}  // namespace

std::size_t splitAtContacts(std::vector<std::vector<Polygon>>& polygons, std::span<const char> split,
                            double narrowest, std::span<const char> emits) {
    // The polygons that may split and be split: those of the objects to split.
    struct Ref {
        std::uint32_t object, index;
    };
    std::vector<Ref> refs;
    std::vector<Aabb> boxes;
    for (std::size_t o = 0; o < polygons.size(); ++o)
        if (split[o])
            for (std::size_t i = 0; i < polygons[o].size(); ++i) {
                refs.push_back({static_cast<std::uint32_t>(o), static_cast<std::uint32_t>(i)});
                boxes.push_back(boxOf(polygons[o][i]));
            }
    if (refs.empty()) return 0;
    BoxGrid grid(boxes);
    // The segments of each polygon first, then the splits: a split polygon
    // still meets the others as it was.
    std::vector<std::vector<std::pair<glm::dvec3, glm::dvec3>>> segments(refs.size());
    std::vector<std::uint8_t> onEdges(refs.size(), 0);  // creases where a polygon stands on an edge
    std::vector<double> tolerances(refs.size());
    for (std::size_t r = 0; r < refs.size(); ++r) {
        const Polygon& p = polygons[refs[r].object][refs[r].index];
        const Aabb& box = boxes[r];
        const double tolerance = tolerances[r] = positionTolerance(box);
        const glm::dvec3 normal = p.normal();
        const double offset = glm::dot(normal, p.vertices[0]);
        Aabb around = box;
        around.lo -= glm::dvec3(tolerance);
        around.hi += glm::dvec3(tolerance);
        const Piece whole = pieceOf(p);
        // Emitters close in front, facing it: the box reaches out along the
        // normal as far as the largest gap kTrappedGapShare allows here.
        const Aabb ahead = reachingAhead(around, normal, kTrappedGapShare * glm::length(box.extent()));
        for (std::uint32_t q : grid.near(ahead)) {
            if (refs[q].object == refs[r].object || !overlaps(ahead, boxes[q], 0.0)) continue;
            const Polygon& other = polygons[refs[q].object][refs[q].index];
            if (other.material >= emits.size() || !emits[other.material]) continue;
            for (auto [a, b] : outlineAcrossGap(other, p, tolerance))
                if (clipToPiece(whole, normal, a, b, tolerance)) segments[r].emplace_back(a, b);
        }
        for (std::uint32_t q : grid.near(around)) {
            // Another object's: a partition on a floor, not a shelf on its
            // bookcase's side (refinement divides around an object's own
            // contacts; splitting there too multiplied the polygons).
            if (refs[q].object == refs[r].object || !overlaps(around, boxes[q], 0.0)) continue;
            const Polygon& other = polygons[refs[q].object][refs[q].index];
            PlaneSection s = planeSection(std::span(other.vertices.data(), other.vertexCount),
                                          normal, offset, tolerance);
            if (s.count < 2 || !s.front) continue;
            // Standing on an edge of it (the polygon ends under the other):
            // no split, but a crease.
            for (int k = 0; k < p.vertexCount; ++k) {
                const glm::dvec3& u = p.vertices[k];
                const glm::dvec3 edge = p.vertices[(k + 1) % p.vertexCount] - u;
                const double length = glm::length(edge);
                const auto off = [&](const glm::dvec3& x) {
                    return glm::length(glm::cross(edge, x - u)) / length;
                };
                if (off(s.a) > tolerance || off(s.b) > tolerance) continue;
                const double ta = glm::dot(s.a - u, edge) / length,
                             tb = glm::dot(s.b - u, edge) / length;
                if (std::min(std::max(ta, tb), length) - std::max(std::min(ta, tb), 0.0) >
                    tolerance)
                    onEdges[r] |= static_cast<std::uint8_t>(1u << k);
            }
            if (!clipToPiece(whole, normal, s.a, s.b, tolerance)) continue;
            // Only lines that divide the polygon: a partition across a floor,
            // not a table leg on it (refinement divides around small
            // contacts; splitting there too would multiply the polygons).
            const glm::dvec3 along = glm::normalize(s.b - s.a);
            double lo = 0.0, hi = 0.0;
            for (int k = 0; k < p.vertexCount; ++k) {
                const double t = glm::dot(p.vertices[k] - s.a, along);
                lo = std::min(lo, t);
                hi = std::max(hi, t);
            }
            if (glm::length(s.b - s.a) >= kDividing * (hi - lo)) segments[r].emplace_back(s.a, s.b);
        }
    }
    std::size_t count = 0;
    std::vector<std::vector<Polygon>> out(polygons.size());
    std::vector<Piece> pieces;
    std::size_t r = 0;
    for (std::size_t o = 0; o < polygons.size(); ++o) {
        if (!split[o]) {
            out[o] = std::move(polygons[o]);
            continue;
        }
        for (const Polygon& p : polygons[o]) {
            const std::vector<std::pair<glm::dvec3, glm::dvec3>>& cuts = segments[r];
            const std::uint8_t edgeCreases = onEdges[r];
            const double tolerance = tolerances[r++];
            if (cuts.empty()) {
                out[o].push_back(p);
                out[o].back().creases |= edgeCreases;
                continue;
            }
            const glm::dvec3 normal = p.normal();
            pieces.assign(1, pieceOf(p));
            for (const auto& [a, b] : cuts) {
                if (pieces.size() >= kMostPieces) break;
                cutAlong(pieces, normal, a, b, tolerance, narrowest);
            }
            count += pieces.size() > 1;
            const std::size_t first = out[o].size();
            appendPieces(p, pieces, out[o]);
            // The pieces' edges along the cuts, and along the polygon's own
            // edges that another polygon stands on, are creases.
            std::vector<std::pair<glm::dvec3, glm::dvec3>> lines = cuts;
            for (int k = 0; k < p.vertexCount; ++k)
                if (edgeCreases >> k & 1)
                    lines.emplace_back(p.vertices[k], p.vertices[(k + 1) % p.vertexCount]);
            for (std::size_t i = first; i < out[o].size(); ++i) {
                Polygon& piece = out[o][i];
                for (int k = 0; k < piece.vertexCount; ++k) {
                    const glm::dvec3& u = piece.vertices[k];
                    const glm::dvec3& v = piece.vertices[(k + 1) % piece.vertexCount];
                    for (const auto& [a, b] : lines) {
                        // On the line, and where the segment is (an outline
                        // seen across a gap ends inside the polygon).
                        const glm::dvec3 across = glm::normalize(glm::cross(normal, b - a));
                        const double length = glm::length(b - a);
                        const double t = glm::dot(0.5 * (u + v) - a, (b - a) / length);
                        if (std::abs(glm::dot(across, u - a)) <= tolerance &&
                            std::abs(glm::dot(across, v - a)) <= tolerance && t >= -tolerance &&
                            t <= length + tolerance) {
                            piece.creases |= static_cast<std::uint8_t>(1u << k);
                            break;
                        }
                    }
                }
            }
        }
    }
    polygons = std::move(out);
    return count;
}

double trappingGap(const Polygon& emitter, const Polygon& surface, double tolerance) {
    const glm::dvec3 n = emitter.normal();
    if (glm::dot(surface.normal(), n) > -1.0 + 1e-9) return -1.0;  // facing the emitter
    const double gap = glm::dot(n, surface.vertices[0] - emitter.vertices[0]);
    return gap > tolerance && gap <= kTrappedGapShare * std::sqrt(emitter.area()) ? gap : -1.0;
}

}  // namespace rad
