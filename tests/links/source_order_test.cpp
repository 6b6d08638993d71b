// The source order of a receiver's links (links/SourceOrder.h), which the
// line-space traversal's binary search relies on: after refinement and after
// links are refined again and reinstated, every list is in order once sorted,
// and the links from any element's range are exactly those whose source lies
// below it.

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "geometry/RayCaster.h"
#include "hierarchy/Hierarchy.h"
#include "links/SourceOrder.h"
#include "refine/Refiner.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

// Whether q lies in the subtree of a, by walking up the tree (not by ranges).
bool below(const Hierarchy& h, ElementId q, ElementId a) {
    for (ElementId e = q; e != kNone; e = h[e].parent)
        if (e == a) return true;
    return false;
}

// Checks every list's order and, for every receiver and the ranges of some
// 60 elements spread over the hierarchy, that linksFrom finds exactly the
// links whose source is below the element.
void expectSourceOrder(const Hierarchy& h, const LinkStore& links, std::size_t& checked) {
    std::vector<ElementId> live, sample;
    for (ElementId e = 0; e < h.size(); ++e)
        if (e == h.root() || h[e].parent != kNone) live.push_back(e);
    for (std::size_t i = 0; i < live.size(); i += std::max<std::size_t>(1, live.size() / 60)) sample.push_back(live[i]);
    for (ElementId r : live)
        for (const IdList* list : {&h[r].links, &h[r].plinks}) {
            ASSERT_TRUE(std::is_sorted(list->begin(), list->end(), [&](LinkId a, LinkId b) {
                return sourceIndex(h, links, a) < sourceIndex(h, links, b);
            })) << "element " << r;
            if (list->empty()) continue;
            for (ElementId a : sample) {
                std::vector<LinkId> expected;
                for (LinkId id : *list)
                    if (below(h, links[id].source, a)) expected.push_back(id);
                const std::span<const LinkId> found = linksFrom(h, links, *list, h.range(a));
                std::vector<LinkId> got(found.begin(), found.end());
                std::sort(expected.begin(), expected.end());
                std::sort(got.begin(), got.end());
                ASSERT_EQ(got, expected) << "receiver " << r << ", sources below " << a;
                ++checked;
            }
        }
}

TEST(SourceOrder, ListsStayInOrderThroughRefinementAndReinstatement) {
    const Scene scene = test::roomWithBlock();
    Hierarchy h(scene, 0.05);
    LinkStore links;
    RayCaster rays;
    std::vector<std::uint32_t> all(scene.polygons.size());
    for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    rays.setLayer(Layer::Static, scene, all);
    RefineSettings settings;
    settings.epsilon = 2e-3;
    settings.referencePower = 1.0;
    Refiner refiner(h, links, rays, settings);
    // Every source as bright as a light: refinement goes down to the area
    // threshold wherever the criterion lets it.
    for (ElementId e = 0; e < h.size(); ++e) h[e].oracle = 1.0;
    refiner.linkRoot();
    refiner.refineAll();
    refiner.sortLinkLists();
    std::size_t checked = 0;
    expectSourceOrder(h, links, checked);
    EXPECT_GT(checked, 1000u);

    // Refine a third of the active links once more, then reinstate a few
    // p-links: appends and removals out of order, put back by sortLinkLists.
    std::vector<LinkId> active, passive;
    for (ElementId e = 0; e < h.size(); ++e) {
        for (std::size_t i = 0; i < h[e].links.size(); i += 3) active.push_back(h[e].links[i]);
        for (std::size_t i = 0; i < h[e].plinks.size(); i += 7) passive.push_back(h[e].plinks[i]);
    }
    std::vector<LinkId> created;
    refiner.refine(active, created);
    for (LinkId id : passive)
        if (links[id].live && links[id].passive) refiner.activate(id);
    refiner.sortLinkLists();
    checked = 0;
    expectSourceOrder(h, links, checked);
    EXPECT_GT(checked, 1000u);
}

}  // namespace
}  // namespace rad
