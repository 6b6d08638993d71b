#include "update/Reinsertion.h"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "refine/Refiner.h"

namespace rad {
namespace {

bool holds(const std::vector<ElementId>& set, ElementId e) { return std::find(set.begin(), set.end(), e) != set.end(); }

// Step 1: the object's subtree keeps no link and no subdivision.
void unlinkSubtree(Hierarchy& h, LinkStore& links, Refiner& refiner, ElementId cluster,
                   const std::vector<ElementId>& emptied, std::vector<LinkId>& atAncestors,
                   const std::vector<ElementId>& ancestors, ReinsertionStats& stats) {
    const IndexRange object = h.range(cluster);
    const auto doomedEnd = [&](ElementId e) { return object.contains(h.range(e)) || holds(emptied, e); };
    std::vector<LinkId> doomed;
    // Every link is on its receiver's lists, active or passive.
    for (ElementId e = 0; e < h.size(); ++e)
        for (const IdList* list : {&h[e].links, &h[e].plinks})
            for (LinkId id : *list) {
                const Link& l = links[id];
                if (doomedEnd(l.source) || doomedEnd(l.receiver))
                    doomed.push_back(id);
                else if (holds(ancestors, l.source) || holds(ancestors, l.receiver))
                    atAncestors.push_back(id);
            }
    for (LinkId id : doomed) refiner.remove(id);  // eq. 2 for the active ones
    stats.removed = doomed.size();

    // Without links, nothing is gathered here any more (the subtractions of
    // eq. 2 leave rounding errors). The subdivision stays until the new links
    // are refined: its elements keep the radiosity that refinement judges by.
    std::vector<ElementId> stack{cluster};
    while (!stack.empty()) {
        const ElementId e = stack.back();
        stack.pop_back();
        h[e].irradiance = h[e].clusterIrradiance = glm::dvec3(0.0);
        for (ElementId c : h[e].children) stack.push_back(c);
    }
}

// The subdivision of the object that its new links did not reach goes.
void pruneSubdivision(Hierarchy& h, ElementId e) {
    HElement& el = h[e];
    if (el.isSurface() && !el.isLeaf()) {
        bool any = false;
        for (ElementId c : el.children) any = any || !h.subtreeUnlinked(c);
        if (!any) {
            h.removeChildren(e);
            return;
        }
    }
    for (ElementId c : IdList(h[e].children)) pruneSubdivision(h, c);
}

// Step 2: the links at the former ancestors now stand for smaller clusters.
void recomputeAtAncestors(LinkStore& links, Refiner& refiner, const std::vector<LinkId>& ids) {
    std::vector<Link> fresh(ids.size());
    tbb::parallel_for(std::size_t(0), ids.size(),
                      [&](std::size_t i) { fresh[i] = refiner.compute(links[ids[i]].source, links[ids[i]].receiver); });
    for (std::size_t i = 0; i < ids.size(); ++i) {
        Link& l = links[ids[i]];
        l.unoccluded = fresh[i].unoccluded;
        l.spread = fresh[i].spread;
        l.blockedStatic = fresh[i].blockedStatic;
        l.blockedDynamic = fresh[i].blockedDynamic;
        l.visible = fresh[i].visible;
        l.rays = fresh[i].rays;
        l.visStale = fresh[i].visStale;
        if (!l.passive) refiner.regather(ids[i]);  // eq. 1
    }
}

// Step 3: the line-space children of the root's p-link that the new child lacks.
std::size_t linkUnderRoot(const Hierarchy& h, LinkStore& links, Refiner& refiner, ElementId cluster,
                          ReinsertionStats& stats) {
    std::vector<std::pair<ElementId, ElementId>> pairs{{cluster, cluster}};
    for (ElementId b : h[h.root()].children)
        if (b != cluster) {
            pairs.emplace_back(cluster, b);
            pairs.emplace_back(b, cluster);
        }
    std::vector<Link> computed(pairs.size());
    tbb::parallel_for(std::size_t(0), pairs.size(),
                      [&](std::size_t i) { computed[i] = refiner.compute(pairs[i].first, pairs[i].second); });
    const std::size_t before = links.liveCount();
    std::vector<LinkId> created;
    for (const Link& l : computed)
        if (l.live) created.push_back(refiner.attach(l));
    stats.refined = refiner.refineAll(std::move(created));
    return links.liveCount() - before;
}

}  // namespace

ReinsertionStats reinsertUnderRoot(Hierarchy& h, LinkStore& links, Refiner& refiner, ElementId cluster) {
    ReinsertionStats stats;
    // Movable clusters are under the root and were linked as such (links
    // that carry nothing where they stand were kept: a move may change that).
    // A cluster of the static tree right under the root (small scenes) still
    // needs those links, so it is relinked too.
    if (h.isMovable(cluster)) return stats;
    const bool linked = links.liveCount() > 0;
    const std::vector<ElementId> emptied = h.emptiedBy(cluster);
    std::vector<ElementId> ancestors;  // those that stay, lowest first
    for (ElementId a : h.ancestorsBelowRoot(cluster))
        if (!holds(emptied, a)) ancestors.push_back(a);

    std::vector<LinkId> atAncestors;
    if (linked) unlinkSubtree(h, links, refiner, cluster, emptied, atAncestors, ancestors, stats);
    h.attachToRoot(cluster);
    refiner.sortAllLinkLists();  // the index ranges were numbered again
    if (!linked) return stats;

    recomputeAtAncestors(links, refiner, atAncestors);
    stats.recomputed = atAncestors.size();
    // Their mean radiosity no longer includes the object: pushed again.
    if (!ancestors.empty()) refiner.markDirty(ancestors.front());
    stats.created = linkUnderRoot(h, links, refiner, cluster, stats);
    pruneSubdivision(h, cluster);
    return stats;
}

}  // namespace rad
