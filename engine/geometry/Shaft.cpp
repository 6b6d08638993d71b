#include "geometry/Shaft.h"

#include <algorithm>
#include <cmath>

namespace rad {

namespace {

enum class Owner { A, B, Both };

// Which box reaches the hull's face on `axis` at the low (side 0) or high (side 1) end.
Owner faceOwner(const Aabb& a, const Aabb& b, int axis, int side) {
    const double ea = side ? a.hi[axis] : -a.lo[axis];
    const double eb = side ? b.hi[axis] : -b.lo[axis];
    return ea > eb ? Owner::A : (eb > ea ? Owner::B : Owner::Both);
}

// A small outward tolerance (relative to the coordinates' magnitude) keeps the tests
// conservative for boxes and points that were computed with rounding, e.g. a point interpolated
// between two corners of the hull box.
double tolerance(const Aabb& hull) {
    const double scale =
        std::max({std::abs(hull.lo.x), std::abs(hull.lo.y), std::abs(hull.lo.z),
                  std::abs(hull.hi.x), std::abs(hull.hi.y), std::abs(hull.hi.z)});
    return 1e-12 * scale;
}

bool overlaps(const Aabb& hull, const Aabb& box, double tol) {
    for (int k = 0; k < 3; ++k)
        if (!(box.lo[k] <= hull.hi[k] + tol && box.hi[k] >= hull.lo[k] - tol)) return false;
    return true;
}

}  // namespace

bool Shaft::hullMeets(const Aabb& a, const Aabb& b, const Aabb& box) {
    Aabb hull = a;
    hull.extend(b);
    return overlaps(hull, box, tolerance(hull));
}

Shaft::Shaft(const Aabb& a, const Aabb& b) {
    hull_ = a;
    hull_.extend(b);
    if (a.empty() || b.empty()) return;  // the hull is the other box: no planes needed

    // Haines & Wallace: where one box owns a hull face and the other box owns an adjacent hull
    // face, the hull has a slanted face between them, through the corresponding edges of the
    // two boxes. Both edges are parallel to the third axis k, so the plane is too. Counting the
    // owner changes over the 12 hull edges gives at most 8 such planes (each axis' two faces
    // split between the boxes; the sum over axis pairs peaks at 8).
    Owner owner[3][2];
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) owner[axis][side] = faceOwner(a, b, axis, side);
    for (int k = 0; k < 3; ++k) {
        const int i = k == 0 ? 1 : 0;
        const int j = k == 2 ? 1 : 2;
        for (int si = 0; si < 2; ++si) {
            for (int sj = 0; sj < 2; ++sj) {
                const Owner oi = owner[i][si];
                const Owner oj = owner[j][sj];
                if (oi == Owner::Both || oj == Owner::Both || oi == oj) continue;
                // X reaches further along i, Y along j; the plane passes through X's edge
                // (X_i, X_j) and Y's edge (Y_i, Y_j) at this corner of the (i, j) projection.
                const Aabb& x = oi == Owner::A ? a : b;
                const Aabb& y = oi == Owner::A ? b : a;
                const double xi = si ? x.hi[i] : x.lo[i], xj = sj ? x.hi[j] : x.lo[j];
                const double yi = si ? y.hi[i] : y.lo[i], yj = sj ? y.hi[j] : y.lo[j];
                // Normal perpendicular to the edge direction (yi - xi, yj - xj), pointing towards
                // the corner's outside (signs of si, sj): then both boxes' extreme corners in
                // that direction lie on the plane, and both boxes lie on its inner side.
                double n0 = std::abs(yj - xj) * (si ? 1.0 : -1.0);
                double n1 = std::abs(yi - xi) * (sj ? 1.0 : -1.0);
                const double len = std::sqrt(n0 * n0 + n1 * n1);  // not hypot: a fifth of a traversal
                if (!(len > 0.0) || !std::isfinite(len)) continue;
                n0 /= len;
                n1 /= len;
                ni_[count_] = n0;
                nj_[count_] = n1;
                // The larger of the two offsets, so that rounding never cuts into either box.
                d_[count_] = std::max(n0 * xi + n1 * xj, n0 * yi + n1 * yj);
                axis_[count_] = static_cast<std::uint8_t>(k);
                ++count_;
            }
        }
    }
}

bool Shaft::intersects(const Aabb& box) const {
    const double tol = tolerance(hull_);
    if (!overlaps(hull_, box, tol)) return false;
    for (std::uint8_t p = 0; p < count_; ++p) {
        const int k = axis_[p];
        const int i = k == 0 ? 1 : 0;
        const int j = k == 2 ? 1 : 2;
        // The box corner furthest inside the plane (most negative along the normal): if even
        // it is outside, the whole box is.
        const double pi = ni_[p] >= 0.0 ? box.lo[i] : box.hi[i];
        const double pj = nj_[p] >= 0.0 ? box.lo[j] : box.hi[j];
        if (ni_[p] * pi + nj_[p] * pj > d_[p] + tol) return false;
    }
    return true;
}

}  // namespace rad
