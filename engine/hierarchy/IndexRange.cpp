#include "hierarchy/IndexRange.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace rad {

int maxQuadtreeDepth(double area, double minArea) {
    if (!(minArea > 0.0) || !(area > 0.0)) return 0;
    int depth = 0;
    // On the ratio, with a little slack: a child exactly at the threshold
    // stays allowed when the scene is scaled and rounding moves it by an ulp.
    // Bounded: beyond 40 levels the index count overflows anyway, and the
    // caller reports that; stopping here keeps a zero-ish threshold from looping.
    double ratio = area / minArea;
    while (ratio / 4.0 >= 1.0 - 1e-9 && depth < 40) {
        ratio /= 4.0;
        ++depth;
    }
    return depth;
}

std::uint64_t quadtreeIndexCount(double area, double minArea, const std::string& what) {
    const int depth = maxQuadtreeDepth(area, minArea);
    // (4^(D+1) - 1) / 3 fits in 64 bits for D <= 31.
    if (depth > 31) {
        // The smallest element numbered (the hierarchy numbers two levels below
        // the minimum area), as 1e-300 m^2 rather than 0.000000.
        std::ostringstream shown;
        shown << minArea;
        throw IndexRangeOverflow(what + ": elements down to " + shown.str() + " m^2 would take " + std::to_string(depth) +
                                 " quadtree levels, more than 64-bit index ranges can number "
                                 "(31 at most); raise the minimum area");
    }
    std::uint64_t power = 1;
    for (int i = 0; i <= depth; ++i) power *= 4;
    return (power - 1) / 3;
}

std::uint64_t checkedAdd(std::uint64_t a, std::uint64_t b, const std::string& what) {
    if (a > std::numeric_limits<std::uint64_t>::max() - b)
        throw IndexRangeOverflow(what + ": index ranges exceed 64 bits; raise the minimum area");
    return a + b;
}

IndexRange quadtreeChildRange(const IndexRange& parent, int k) {
    // size = 1 + 4 * childSize for a complete quadtree.
    const std::uint64_t childSize = (parent.size() - 1) / 4;
    const std::uint64_t first = parent.first + 1 + static_cast<std::uint64_t>(k) * childSize;
    return {first, first + childSize - 1};
}

}  // namespace rad
