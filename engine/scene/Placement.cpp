#include "scene/Placement.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rad {

bool Placement::reaches(const glm::dvec3& p) const {
    return !(size > 0.0) || glm::length(p - centre) <= kMaxReach * size;
}

Placement placementOf(std::span<const glm::dvec3> points) {
    Placement out;
    if (points.empty()) return out;
    std::vector<double> axis(points.size());
    glm::dvec3 low{0.0}, high{0.0};
    const auto at = [&](double q) {
        const auto k = static_cast<std::ptrdiff_t>(std::llround(q * double(axis.size() - 1)));
        std::nth_element(axis.begin(), axis.begin() + k, axis.end());
        return axis[static_cast<std::size_t>(k)];
    };
    for (int c = 0; c < 3; ++c) {
        for (std::size_t i = 0; i < points.size(); ++i) axis[i] = points[i][c];
        low[c] = at(0.25);
        high[c] = at(0.75);
        out.centre[c] = at(0.5);
    }
    out.size = glm::length(high - low);
    return out;
}

}  // namespace rad
