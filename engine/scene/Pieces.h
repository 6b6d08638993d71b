#pragma once
// Convex pieces of a polygon, as the import's cutting steps make them
// (scene/Buried.h, scene/Contacts.h): split along lines in its plane,
// then written back as polygons of at most four vertices.

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "radiosity/Scene.h"

namespace rad {

// Past this many pieces a polygon takes no more cuts (a floor under a room
// full of furniture legs).
inline constexpr std::size_t kMostPieces = 64;

struct PieceVertex {
    glm::dvec3 p;
    glm::vec2 uv;  // texture coordinates, interpolated along cuts
};
using Piece = std::vector<PieceVertex>;  // convex, counter-clockwise seen from the front

Piece pieceOf(const Polygon& polygon);
Aabb boxOf(const Polygon& polygon);
// How near a point must be to count as on a plane or line of what fills
// `box`: positions come as float32, so allow for their rounding where the
// box lies, and for the box's own size.
double positionTolerance(const Aabb& box);
double pieceArea(const Piece& piece);

// Splits `piece` by a plane into the part on its outer side (signed
// distance >= 0) and the part on its inner side; a vertex within
// `tolerance` of the plane belongs to both. Vertices left on straight
// stretches are dropped; a side with nothing of it has under 3 vertices.
void split(const Piece& piece, const glm::dvec4& plane, double tolerance, Piece& outer,
           Piece& inner);

// Clips the segment [a, b] in the plane of `piece` (facing `normal`) to the
// piece; returns whether more than `tolerance` of it lies inside, away from
// the piece's edges.
bool clipToPiece(const Piece& piece, const glm::dvec3& normal, glm::dvec3& a, glm::dvec3& b,
                 double tolerance);

// Where the convex polygon `corners` meets the plane dot(normal, x) =
// offset: its corners on the plane (within `tolerance`) and where its edges
// cross it. `count` 2 is the segment [a, b]; `front` and `back` say whether
// any corner lies off the plane on either side.
struct PlaneSection {
    glm::dvec3 a{0.0}, b{0.0};
    int count = 0;
    bool front = false, back = false;
};
PlaneSection planeSection(std::span<const glm::dvec3> corners, const glm::dvec3& normal,
                          double offset, double tolerance);

// Cuts each of `pieces` that the segment [a, b] runs through along the
// segment's line (in the plane of the pieces, facing `normal`), unless a
// side would be narrower than `narrowest` across the line.
void cutAlong(std::vector<Piece>& pieces, const glm::dvec3& normal, const glm::dvec3& a,
              const glm::dvec3& b, double tolerance, double narrowest = 0.0);

// Appends `pieces` to `out` as polygons like `polygon` (its material and
// object): a piece of more than four vertices as a fan of quads (and a
// triangle), each convex.
void appendPieces(const Polygon& polygon, std::span<const Piece> pieces, std::vector<Polygon>& out);

bool overlaps(const Aabb& a, const Aabb& b, double tolerance);
// `box` reaching out `reach` further along `normal` (where a surface facing
// it may lie).
Aabb reachingAhead(Aabb box, const glm::dvec3& normal, double reach);

// Which boxes may overlap a box: a uniform grid over them, each box listed
// in the cells it overlaps.
class BoxGrid {
  public:
    explicit BoxGrid(std::span<const Aabb> boxes);
    // The boxes listed in the cells `box` overlaps, each once.
    const std::vector<std::uint32_t>& near(const Aabb& box);

  private:
    template <class F>
    void forEachCell(const Aabb& box, F&& f) const;

    Aabb bounds_;
    glm::ivec3 size_{1};
    std::vector<std::vector<std::uint32_t>> cells_;
    std::vector<std::uint32_t> seen_;
    std::uint32_t stamp_ = 0;
    std::vector<std::uint32_t> found_;
};

}  // namespace rad
