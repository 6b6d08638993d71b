#include "scene/Buried.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <numeric>
#include <unordered_map>

#include "scene/MeshGeometry.h"

namespace rad {
namespace {

// Past this many faces a closed part is not taken as a solid (slabs, walls
// and furniture have few), and past this many pieces a polygon is left
// whole by a solid: each face crossing the polygon cuts it along a line.
constexpr std::size_t kMostFaces = 512;
constexpr std::size_t kMostPieces = 64;

struct Vertex {
    glm::dvec3 p;
    glm::vec2 uv;
};
using Piece = std::vector<Vertex>;

double pieceArea(const Piece& piece) {
    glm::dvec3 sum(0.0);
    for (std::size_t i = 1; i + 1 < piece.size(); ++i)
        sum += glm::cross(piece[i].p - piece[0].p, piece[i + 1].p - piece[0].p);
    return 0.5 * glm::length(sum);
}

// Splits `piece` by a plane into the part on its outer side (signed
// distance >= 0) and the part on its inner side; a vertex within
// `tolerance` of the plane belongs to both.
void split(const Piece& piece, const glm::dvec4& plane, double tolerance, Piece& outer,
           Piece& inner) {
    outer.clear();
    inner.clear();
    const auto distance = [&](const Vertex& v) {
        const double d = glm::dot(glm::dvec3(plane), v.p) - plane.w;
        return std::abs(d) <= tolerance ? 0.0 : d;
    };
    for (std::size_t i = 0; i < piece.size(); ++i) {
        const Vertex& a = piece[i];
        const Vertex& b = piece[(i + 1) % piece.size()];
        const double da = distance(a), db = distance(b);
        if (da >= 0.0) outer.push_back(a);
        if (da <= 0.0) inner.push_back(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            const double t = da / (da - db);
            const Vertex x{a.p + t * (b.p - a.p), a.uv + float(t) * (b.uv - a.uv)};
            outer.push_back(x);
            inner.push_back(x);
        }
    }
}

// Drops vertices that repeat their neighbour or lie on the line through
// their neighbours, which a cut through a vertex leaves.
void dropStraightVertices(Piece& piece, double tolerance) {
    bool changed = true;
    while (changed && piece.size() >= 3) {
        changed = false;
        for (std::size_t i = 0; i < piece.size() && piece.size() >= 3; ++i) {
            const glm::dvec3& a = piece[(i + piece.size() - 1) % piece.size()].p;
            const glm::dvec3& b = piece[i].p;
            const glm::dvec3& c = piece[(i + 1) % piece.size()].p;
            const double base = glm::length(c - a);
            if (glm::length(glm::cross(b - a, c - a)) <= tolerance * std::max(base, tolerance)) {
                piece.erase(piece.begin() + static_cast<std::ptrdiff_t>(i));
                changed = true;
            }
        }
    }
}

bool overlaps(const Aabb& a, const Aabb& b, double tolerance) {
    return glm::all(glm::lessThan(a.lo, b.hi - tolerance)) &&
           glm::all(glm::lessThan(b.lo, a.hi - tolerance));
}

// Which solids may hold part of a box: a uniform grid over the solids,
// each solid listed in the cells its box overlaps.
class SolidGrid {
  public:
    explicit SolidGrid(std::span<const ClosedSolid> solids) : seen_(solids.size(), 0) {
        for (const ClosedSolid& s : solids) bounds_.extend(s.box);
        const int n = std::clamp(static_cast<int>(std::cbrt(double(solids.size()))) + 1, 1, 32);
        size_ = glm::ivec3(n);
        cells_.resize(std::size_t(n) * n * n);
        for (std::size_t i = 0; i < solids.size(); ++i)
            forEachCell(solids[i].box,
                        [&](std::size_t c) { cells_[c].push_back(static_cast<std::uint32_t>(i)); });
    }

    // The solids listed in the cells `box` overlaps, each once.
    const std::vector<std::uint32_t>& near(const Aabb& box) {
        found_.clear();
        ++stamp_;
        if (bounds_.empty()) return found_;
        forEachCell(box, [&](std::size_t c) {
            for (std::uint32_t s : cells_[c])
                if (seen_[s] != stamp_) {
                    seen_[s] = stamp_;
                    found_.push_back(s);
                }
        });
        return found_;
    }

  private:
    template <class F>
    void forEachCell(const Aabb& box, F&& f) const {
        const glm::dvec3 extent = glm::max(bounds_.extent(), glm::dvec3(1e-300));
        const auto cell = [&](const glm::dvec3& p) {
            const glm::dvec3 t = (p - bounds_.lo) / extent * glm::dvec3(size_);
            return glm::clamp(glm::ivec3(glm::floor(t)), glm::ivec3(0), size_ - 1);
        };
        if (glm::any(glm::lessThan(box.hi, bounds_.lo)) ||
            glm::any(glm::greaterThan(box.lo, bounds_.hi)))
            return;
        const glm::ivec3 lo = cell(box.lo), hi = cell(box.hi);
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) f((std::size_t(z) * size_.y + y) * size_.x + x);
    }

    Aabb bounds_;
    glm::ivec3 size_{1};
    std::vector<std::vector<std::uint32_t>> cells_;
    std::vector<std::uint32_t> seen_;
    std::uint32_t stamp_ = 0;
    std::vector<std::uint32_t> found_;
};

// Clips the segment [a, b] in the plane of `piece` (convex, facing
// `normal`) to the piece; returns whether more than `tolerance` of it lies
// inside, away from the piece's edges.
bool clipToPiece(const Piece& piece, const glm::dvec3& normal, glm::dvec3& a, glm::dvec3& b,
                 double tolerance) {
    for (std::size_t k = 0; k < piece.size(); ++k) {
        if (glm::length(b - a) <= tolerance) return false;
        const glm::dvec3& p = piece[k].p;
        const glm::dvec3 inward = glm::cross(normal, piece[(k + 1) % piece.size()].p - p);
        const double scale = glm::length(inward);
        const double da = glm::dot(inward, a - p) / scale, db = glm::dot(inward, b - p) / scale;
        if (da <= tolerance && db <= tolerance) return false;
        if (da < 0.0) {
            a += da / (da - db) * (b - a);
        } else if (db < 0.0) {
            b += db / (db - da) * (a - b);
        }
    }
    return glm::length(b - a) > tolerance;
}

// Where a face of the solid crosses the polygon: the segment, and the plane
// perpendicular to the polygon through it (n.xyz, d: one side where
// dot(n, x) > d).
struct Crossing {
    glm::dvec3 a, b;
    glm::dvec4 line;
};

std::vector<Crossing> crossings(const Piece& polygon, const glm::dvec3& normal,
                                const ClosedSolid& solid) {
    std::vector<Crossing> found;
    const double offset = glm::dot(normal, polygon[0].p);
    const double tolerance = solid.tolerance;
    for (const auto& t : solid.triangles) {
        double d[3];
        for (int k = 0; k < 3; ++k) {
            d[k] = glm::dot(normal, t[k]) - offset;
            if (std::abs(d[k]) <= tolerance) d[k] = 0.0;
        }
        if (std::max({d[0], d[1], d[2]}) <= 0.0 || std::min({d[0], d[1], d[2]}) >= 0.0) continue;
        // The face's segment in the plane: its vertices on the plane and
        // where its edges cross it.
        glm::dvec3 ends[3];
        int count = 0;
        for (int k = 0; k < 3 && count < 3; ++k) {
            const int l = (k + 1) % 3;
            if (d[k] == 0.0) ends[count++] = t[k];
            if ((d[k] < 0.0 && d[l] > 0.0) || (d[k] > 0.0 && d[l] < 0.0))
                ends[count++] = t[k] + d[k] / (d[k] - d[l]) * (t[l] - t[k]);
        }
        if (count < 2) continue;
        Crossing c{ends[0], ends[1], {}};
        if (!clipToPiece(polygon, normal, c.a, c.b, tolerance)) continue;
        const glm::dvec3 across = glm::normalize(glm::cross(normal, c.b - c.a));
        c.line = glm::dvec4(across, glm::dot(across, c.a));
        found.push_back(c);
    }
    return found;
}

}  // namespace

bool ClosedSolid::holds(const glm::dvec3& p) const {
    if (glm::any(glm::lessThan(p, box.lo)) || glm::any(glm::greaterThan(p, box.hi))) return false;
    double omega = 0.0;
    for (const auto& t : triangles) {
        // On a face the winding number is not defined (a face's own solid
        // angle is +-2 pi by rounding): a point there is not inside.
        const glm::dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
        const double twice = glm::length(n);
        if (std::abs(glm::dot(n, p - t[0])) <= tolerance * twice) {
            bool within = true;
            for (int k = 0; k < 3 && within; ++k) {
                const glm::dvec3 edge = t[(k + 1) % 3] - t[k];
                within = glm::dot(glm::cross(edge, p - t[k]), n) >=
                         -tolerance * glm::length(edge) * twice;
            }
            if (within) return false;
        }
        omega += solidAngle(t[0] - p, t[1] - p, t[2] - p);
    }
    return omega / (4.0 * std::numbers::pi) > 0.75;
}

std::vector<ClosedSolid> closedSolids(std::span<const std::array<glm::dvec3, 3>> triangles) {
    std::unordered_map<glm::dvec3, std::uint32_t, PointHash> ids;
    std::vector<glm::dvec3> points;
    std::vector<std::array<std::uint32_t, 3>> tri(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (int k = 0; k < 3; ++k) {
            const auto [at, added] =
                ids.try_emplace(triangles[t][k], static_cast<std::uint32_t>(points.size()));
            if (added) points.push_back(triangles[t][k]);
            tri[t][k] = at->second;
        }
    // The parts: triangles joined by their vertices.
    std::vector<std::uint32_t> parent(points.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](std::uint32_t v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& t : tri)
        for (int k = 1; k < 3; ++k) parent[find(t[k])] = find(t[0]);
    std::unordered_map<std::uint32_t, std::vector<std::size_t>> parts;
    for (std::size_t t = 0; t < tri.size(); ++t) parts[find(tri[t][0])].push_back(t);

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
        // Positions come as float32: allow for their rounding, and for the
        // solid's own size.
        const glm::dvec3 reach = glm::max(glm::abs(solid.box.lo), glm::abs(solid.box.hi));
        const double far = std::max({reach.x, reach.y, reach.z});
        const double thinnest = std::min({extent.x, extent.y, extent.z});
        solid.tolerance = 1e-6 * size + 1e-7 * far;
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
    SolidGrid grid(solids);
    std::vector<Piece> pieces, next;
    Piece outer, inner;
    for (std::size_t o = 0; o < polygons.size(); ++o) {
        if (!cut[o]) continue;
        std::vector<Polygon> out;
        out.reserve(polygons[o].size());
        for (const Polygon& polygon : polygons[o]) {
            Aabb box;
            for (int k = 0; k < polygon.vertexCount; ++k) box.extend(polygon.vertices[k]);
            const glm::dvec3 normal = polygon.normal();
            Piece whole;
            for (int k = 0; k < polygon.vertexCount; ++k)
                whole.push_back({polygon.vertices[k], polygon.uv[k]});
            pieces.assign(1, whole);
            bool changed = false;
            for (std::uint32_t s : grid.near(box)) {
                const ClosedSolid& solid = solids[s];
                if (!overlaps(box, solid.box, solid.tolerance)) continue;
                // Cut every piece along every line where the solid's faces
                // cross the polygon (none: it is wholly inside or outside),
                // then leave out the pieces inside; when none is, the pieces
                // stay as they were.
                const std::vector<Crossing> cuts = crossings(whole, normal, solid);
                if (cuts.empty() && !(glm::all(glm::greaterThanEqual(box.lo, solid.box.lo)) &&
                                      glm::all(glm::lessThanEqual(box.hi, solid.box.hi))))
                    continue;  // uncut and not within the solid's box: outside it
                next = pieces;
                std::vector<Piece> cutNow;
                for (const Crossing& c : cuts) {
                    // Each piece the face's segment runs through is cut along
                    // its line, so no segment is left inside a piece.
                    cutNow.clear();
                    for (const Piece& piece : next) {
                        glm::dvec3 a = c.a, b = c.b;
                        if (clipToPiece(piece, normal, a, b, solid.tolerance)) {
                            split(piece, c.line, solid.tolerance, outer, inner);
                            dropStraightVertices(outer, solid.tolerance);
                            dropStraightVertices(inner, solid.tolerance);
                            if (outer.size() >= 3 && inner.size() >= 3) {
                                cutNow.push_back(outer);
                                cutNow.push_back(inner);
                                continue;
                            }
                        }
                        cutNow.push_back(piece);
                    }
                    next.swap(cutNow);
                    if (next.size() > kMostPieces) break;
                }
                if (next.size() > kMostPieces) continue;
                const std::size_t before = next.size();
                std::erase_if(next, [&](const Piece& piece) {
                    glm::dvec3 centre(0.0);
                    for (const Vertex& v : piece) centre += v.p;
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
            for (const Piece& piece : pieces) {
                left += pieceArea(piece);
                // Convex pieces of more than four vertices as a fan of quads
                // (and a triangle), each convex.
                for (std::size_t first = 1; first + 1 < piece.size(); first += 2) {
                    Polygon p = polygon;
                    p.vertexCount = static_cast<std::uint8_t>(
                        std::min<std::size_t>(4, piece.size() - first + 1));
                    p.vertices = {};
                    p.uv = {};
                    p.vertices[0] = piece[0].p;
                    p.uv[0] = piece[0].uv;
                    for (int k = 1; k < p.vertexCount; ++k) {
                        p.vertices[k] = piece[first + k - 1].p;
                        p.uv[k] = piece[first + k - 1].uv;
                    }
                    out.push_back(p);
                }
            }
            result.areaLeftOut[o] += std::max(0.0, polygon.area() - left);
        }
        polygons[o] = std::move(out);
    }
    return result;
}

}  // namespace rad
