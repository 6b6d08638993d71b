#pragma once
// The shaft between two axis-aligned boxes (Haines & Wallace 1994, "Shaft culling for efficient
// ray-cast radiosity"): a conservative volume around all segments joining the two boxes, used
// by the line-space hierarchy (paper sec. 3.2) to find the links a moving object may touch.

#include <array>
#include <cstddef>
#include <cstdint>

#include "radiosity/Scene.h"

namespace rad {

class Shaft {
  public:
    // Both boxes may be flat (zero thickness on some axes); an empty box contributes nothing.
    Shaft(const Aabb& a, const Aabb& b);

    // Conservative: returns false only when `box` certainly does not meet the convex hull of
    // a ∪ b. Touching counts as meeting.
    bool intersects(const Aabb& box) const;
    // The first test of intersects, without building the shaft: whether `box` meets the box
    // around a ∪ b. False means Shaft(a, b).intersects(box) is false too.
    static bool hullMeets(const Aabb& a, const Aabb& b, const Aabb& box);

    static constexpr std::size_t maxPlanes = 8;

    const Aabb& hull() const { return hull_; }
    std::size_t planeCount() const { return count_; }

  private:
    // The hull box, then the planes in structure-of-arrays form. Every plane is parallel to one
    // coordinate axis (axis_[p]), so it is n_i x_i + n_j x_j <= d over the two other axes
    // i < j; its normal (n_i, n_j) is unit. sizeof(Shaft) == 256 on x86-64 (4 cache lines).
    Aabb hull_;
    std::array<double, maxPlanes> ni_{};
    std::array<double, maxPlanes> nj_{};
    std::array<double, maxPlanes> d_{};
    std::array<std::uint8_t, maxPlanes> axis_{};
    std::uint8_t count_ = 0;
};

}  // namespace rad
