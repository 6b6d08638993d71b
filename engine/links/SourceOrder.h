#pragma once
// The order of the links arriving at an H-element. Index ranges (sec. 3.2)
// are nested or disjoint, so a source lies in a range exactly when its own
// index does; with a receiver's links and p-links ordered by their source's
// index, the links from any range are one contiguous run, found by binary
// search. The line-space traversal asks every node it visits for its links
// from a range, and a node is often visited for several ranges: without the
// order it would read all of its links each time.
//
// Refinement appends to the lists and marks them unordered
// (Refiner::sortLinkLists puts them back in order before each traversal);
// removals keep the order.

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "links/Link.h"

namespace rad {

inline std::uint64_t sourceIndex(const Hierarchy& h, const LinkStore& links, LinkId id) {
    return h.range(links[id].source).first;
}

// Puts a list in source order (ties, which a list never has, by id).
inline void sortBySource(const Hierarchy& h, const LinkStore& links, IdList& list) {
    std::vector<std::pair<std::uint64_t, LinkId>> keyed;
    keyed.reserve(list.size());
    for (LinkId id : list) keyed.emplace_back(sourceIndex(h, links, id), id);
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t i = 0; i < list.size(); ++i) list[i] = keyed[i].second;
}

// The links of a list in source order whose source lies in `sources`. Each
// look at a key reads three places far apart (the list, the link, its
// source's range), so it looks at few: the ends first (a range often holds
// all of a list, or begins before it), then the end of the run by galloping
// from its start (runs are mostly short).
inline std::span<const LinkId> linksFrom(const Hierarchy& h, const LinkStore& links,
                                         std::span<const LinkId> list, const IndexRange& sources) {
    const auto key = [&](LinkId id) { return sourceIndex(h, links, id); };
    const auto begin = list.begin(), end = list.end();
    if (begin == end) return {};
    const auto lo = key(*begin) >= sources.first
                        ? begin
                        : std::partition_point(begin + 1, end, [&](LinkId id) { return key(id) < sources.first; });
    if (lo == end || key(list.back()) <= sources.last) return {lo, end};
    // The last key lies past the range: the run ends before it.
    std::ptrdiff_t inside = -1, past = (end - 1) - lo;
    for (std::ptrdiff_t probe = 0; probe < past; probe = 2 * probe + 1) {
        if (key(lo[probe]) > sources.last) {
            past = probe;
            break;
        }
        inside = probe;
    }
    const auto hi = std::partition_point(lo + inside + 1, lo + past, [&](LinkId id) { return key(id) <= sources.last; });
    return {lo, hi};
}

}  // namespace rad
