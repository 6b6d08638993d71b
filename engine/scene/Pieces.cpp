#include "scene/Pieces.h"

#include <algorithm>
#include <cmath>

namespace rad {
namespace {

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

}  // namespace

Piece pieceOf(const Polygon& polygon) {
    Piece piece;
    for (int k = 0; k < polygon.vertexCount; ++k)
        piece.push_back({polygon.vertices[k], polygon.uv[k]});
    return piece;
}

Aabb boxOf(const Polygon& polygon) {
    Aabb box;
    for (int k = 0; k < polygon.vertexCount; ++k) box.extend(polygon.vertices[k]);
    return box;
}

double positionTolerance(const Aabb& box) {
    const glm::dvec3 reach = glm::max(glm::abs(box.lo), glm::abs(box.hi));
    return 1e-6 * glm::length(box.extent()) + 1e-7 * std::max({reach.x, reach.y, reach.z});
}

double pieceArea(const Piece& piece) {
    glm::dvec3 sum(0.0);
    for (std::size_t i = 1; i + 1 < piece.size(); ++i)
        sum += glm::cross(piece[i].p - piece[0].p, piece[i + 1].p - piece[0].p);
    return 0.5 * glm::length(sum);
}

void split(const Piece& piece, const glm::dvec4& plane, double tolerance, Piece& outer,
           Piece& inner) {
    outer.clear();
    inner.clear();
    const auto distance = [&](const PieceVertex& v) {
        const double d = glm::dot(glm::dvec3(plane), v.p) - plane.w;
        return std::abs(d) <= tolerance ? 0.0 : d;
    };
    for (std::size_t i = 0; i < piece.size(); ++i) {
        const PieceVertex& a = piece[i];
        const PieceVertex& b = piece[(i + 1) % piece.size()];
        const double da = distance(a), db = distance(b);
        if (da >= 0.0) outer.push_back(a);
        if (da <= 0.0) inner.push_back(a);
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            const double t = da / (da - db);
            const PieceVertex x{a.p + t * (b.p - a.p), a.uv + float(t) * (b.uv - a.uv)};
            outer.push_back(x);
            inner.push_back(x);
        }
    }
    dropStraightVertices(outer, tolerance);
    dropStraightVertices(inner, tolerance);
}

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

PlaneSection planeSection(std::span<const glm::dvec3> corners, const glm::dvec3& normal,
                          double offset, double tolerance) {
    PlaneSection section;
    std::vector<double> d(corners.size());
    for (std::size_t k = 0; k < corners.size(); ++k) {
        d[k] = glm::dot(normal, corners[k]) - offset;
        if (std::abs(d[k]) <= tolerance) d[k] = 0.0;
        section.front = section.front || d[k] > 0.0;
        section.back = section.back || d[k] < 0.0;
    }
    const auto add = [&](const glm::dvec3& x) {
        if (section.count == 0) section.a = x;
        if (section.count == 1) section.b = x;
        ++section.count;
    };
    for (std::size_t k = 0; k < corners.size(); ++k) {
        const std::size_t l = (k + 1) % corners.size();
        if (d[k] == 0.0) add(corners[k]);
        if ((d[k] < 0.0 && d[l] > 0.0) || (d[k] > 0.0 && d[l] < 0.0))
            add(corners[k] + d[k] / (d[k] - d[l]) * (corners[l] - corners[k]));
    }
    return section;
}

void cutAlong(std::vector<Piece>& pieces, const glm::dvec3& normal, const glm::dvec3& a,
              const glm::dvec3& b, double tolerance, double narrowest) {
    const glm::dvec3 across = glm::normalize(glm::cross(normal, b - a));
    const glm::dvec4 line(across, glm::dot(across, a));
    const auto width = [&](const Piece& piece) {
        double w = 0.0;
        for (const PieceVertex& v : piece)
            w = std::max(w, std::abs(glm::dot(across, v.p) - line.w));
        return w;
    };
    Piece outer, inner;
    const std::size_t count = pieces.size();
    for (std::size_t i = 0; i < count; ++i) {
        glm::dvec3 p = a, q = b;
        if (!clipToPiece(pieces[i], normal, p, q, tolerance)) continue;
        split(pieces[i], line, tolerance, outer, inner);
        if (outer.size() < 3 || inner.size() < 3) continue;
        if (narrowest > 0.0 && std::min(width(outer), width(inner)) < narrowest) continue;
        pieces[i] = outer;
        pieces.push_back(inner);
    }
}

void appendPieces(const Polygon& polygon, std::span<const Piece> pieces,
                  std::vector<Polygon>& out) {
    for (const Piece& piece : pieces)
        for (std::size_t first = 1; first + 1 < piece.size(); first += 2) {
            Polygon p = polygon;
            p.vertexCount =
                static_cast<std::uint8_t>(std::min<std::size_t>(4, piece.size() - first + 1));
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

bool overlaps(const Aabb& a, const Aabb& b, double tolerance) {
    return glm::all(glm::lessThan(a.lo, b.hi - tolerance)) &&
           glm::all(glm::lessThan(b.lo, a.hi - tolerance));
}

Aabb reachingAhead(Aabb box, const glm::dvec3& normal, double reach) {
    box.hi += glm::max(normal, glm::dvec3(0.0)) * reach;
    box.lo += glm::min(normal, glm::dvec3(0.0)) * reach;
    return box;
}

BoxGrid::BoxGrid(std::span<const Aabb> boxes) : seen_(boxes.size(), 0) {
    for (const Aabb& b : boxes) bounds_.extend(b);
    const int n = std::clamp(static_cast<int>(std::cbrt(double(boxes.size()))) + 1, 1, 32);
    size_ = glm::ivec3(n);
    cells_.resize(std::size_t(n) * n * n);
    for (std::size_t i = 0; i < boxes.size(); ++i)
        forEachCell(boxes[i],
                    [&](std::size_t c) { cells_[c].push_back(static_cast<std::uint32_t>(i)); });
}

const std::vector<std::uint32_t>& BoxGrid::near(const Aabb& box) {
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

template <class F>
void BoxGrid::forEachCell(const Aabb& box, F&& f) const {
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

}  // namespace rad
