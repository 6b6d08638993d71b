#pragma once
// Index ranges (paper sec. 3.2, Fig. 3). Every H-element owns the interval of
// indices of all the descendants it could ever have under the area threshold,
// numbered in pre-order, so "q lies below s" is one interval test.

#include <cstdint>
#include <stdexcept>
#include <string>

namespace rad {

struct IndexRange {
    std::uint64_t first = 0;  // the element's own index
    std::uint64_t last = 0;   // inclusive

    bool contains(std::uint64_t index) const { return first <= index && index <= last; }
    bool contains(const IndexRange& r) const { return first <= r.first && r.last <= last; }
    std::uint64_t size() const { return last - first + 1; }
    // Ranges are nested or disjoint: whether this one holds r or lies in it.
    bool nestedWith(const IndexRange& r) const { return contains(r) || r.contains(*this); }
};

// Thrown when the numbering would not fit in 64 bits: the area threshold is so
// small that a single polygon could be split into more than 2^64 elements.
struct IndexRangeOverflow : std::overflow_error {
    using std::overflow_error::overflow_error;
};

// The deepest level a quadtree may reach: children are made while each child
// keeps at least minArea (Hanrahan et al.'s area threshold A_e).
int maxQuadtreeDepth(double area, double minArea);

// Number of nodes of the complete quadtree of that depth, (4^(D+1) - 1) / 3.
// Throws IndexRangeOverflow naming `what` when it exceeds 64 bits.
std::uint64_t quadtreeIndexCount(double area, double minArea, const std::string& what);

// a + b, or IndexRangeOverflow naming `what`.
std::uint64_t checkedAdd(std::uint64_t a, std::uint64_t b, const std::string& what);

// The range of child k (0..3) of a surface element with range `parent`.
IndexRange quadtreeChildRange(const IndexRange& parent, int k);

}  // namespace rad
