// The first traversal of the line-space hierarchy (paper sec. 4.1, Fig. 6):
// from the root, every p-link whose source lies in the current index range
// and whose shaft the object cut before or after the move is affected, and
// the traversal goes on below it, restricted to its source's range; active
// links found so are the candidates. It only finds: the links are updated by
// the second traversal (ControlledUpdate.cpp), which spends the frame's
// budget top-down with the work this one pulls up (sec. 6.1).

#include <algorithm>

#include <tbb/parallel_for.h>

#include "geometry/Shaft.h"
#include "update/LineSpaceUpdate.h"

namespace rad {

bool LineSpaceUpdate::affectedByMotion(ElementId s, ElementId r, std::size_t& tests) const {
    // Both ends on the object: a rigid motion changes neither the form factor
    // nor the object's occlusion of its own parts; only static geometry in
    // the object (the obstacles) can come between them.
    if (!layersChanged_ && moved_.contains(h_[s].range) && moved_.contains(h_[r].range)) {
        const Aabb& a = h_[s].box;
        const Aabb& b = h_[r].box;
        const auto near = [&](const Aabb& o) { return Shaft::hullMeets(a, b, o); };
        if (obstacles_.empty()) return false;
        ++tests;
        if (std::none_of(obstacles_.begin(), obstacles_.end(), near)) return false;
        const Shaft shaft(a, b);
        return std::any_of(obstacles_.begin(), obstacles_.end(),
                           [&](const Aabb& o) { return near(o) && shaft.intersects(o); });
    }
    if (moved_.nestedWith(h_[s].range) || moved_.nestedWith(h_[r].range)) return true;
    ++tests;
    // The shaft is built only when tested (storing one per link would cost
    // 256 bytes each), and only when the boxes' hull meets the object: most
    // tested links are far from it.
    const Aabb& a = h_[s].box;
    const Aabb& b = h_[r].box;
    if (!Shaft::hullMeets(a, b, oldBox_) && !Shaft::hullMeets(a, b, newBox_)) return false;
    const Shaft shaft(a, b);
    return shaft.intersects(oldBox_) || shaft.intersects(newBox_);
}

bool LineSpaceUpdate::cutBefore(ElementId s, ElementId r) const {
    const Aabb& a = h_[s].box;
    const Aabb& b = h_[r].box;
    return Shaft::hullMeets(a, b, oldBox_) && Shaft(a, b).intersects(oldBox_);
}

void LineSpaceUpdate::findModifiedLinks() {
    visits_.assign(1, Visit{h_.root(), h_[h_.root()].range, {}, {}, {}, 0});
    // Level by level, each level's visits on all cores: a visit only reads,
    // and stamps its own candidates (the visits of a level have disjoint
    // subtrees, or disjoint source ranges on the same node).
    std::vector<std::size_t> level{0}, next;
    std::vector<std::vector<std::pair<ElementId, IndexRange>>> children;
    std::vector<std::size_t> tests;
    while (!level.empty()) {
        children.assign(level.size(), {});
        tests.assign(level.size(), 0);
        tbb::parallel_for(std::size_t(0), level.size(),
                          [&](std::size_t i) { tests[i] = visitNode(visits_[level[i]], children[i]); });
        next.clear();
        for (std::size_t i = 0; i < level.size(); ++i) {
            shaftTests_ += tests[i];
            // The child visits, in the order of the groups and of the children.
            std::size_t k = 0;
            for (Group& g : visits_[level[i]].groups)
                while (k < children[i].size() && children[i][k].second.first == g.range.first &&
                       children[i][k].second.last == g.range.last) {
                    g.visits.push_back(visits_.size());
                    next.push_back(visits_.size());
                    visits_.push_back(Visit{children[i][k].first, children[i][k].second, {}, {}, {}, 0});
                    ++k;
                }
        }
        level.swap(next);
    }
    // Pull the work up (sec. 6.1): a visit's children come after it.
    for (std::size_t i = visits_.size(); i-- > 0;) {
        Visit& v = visits_[i];
        v.work = v.own();
        for (Group& g : v.groups) {
            g.work = 0;
            for (std::size_t child : g.visits) g.work += visits_[child].work;
            v.work += g.work;
        }
    }
}

std::size_t LineSpaceUpdate::visitNode(Visit& v, std::vector<std::pair<ElementId, IndexRange>>& children) {
    std::size_t tests = 0;
    for (LinkId pl : h_[v.he].plinks) {
        const ElementId q = links_[pl].source;  // the "source" node
        if (v.ind.contains(h_[q].range) && affectedByMotion(q, v.he, tests)) v.affected.push_back(pl);
    }
    for (LinkId id : h_[v.he].links) {
        const ElementId s = links_[id].source;
        if (linkStamp_[id] == frame_ || !v.ind.contains(h_[s].range) || !affectedByMotion(s, v.he, tests)) continue;
        linkStamp_[id] = frame_;  // older than the frame: within the stamps
        v.candidates.push_back(id);
    }
    // Descend once per maximal range: a p-link refined by splitting its source
    // leaves p-links from q's children on he itself, whose ranges lie inside
    // q's; visiting the children for each of them again would repeat the same
    // traversal.
    std::sort(v.affected.begin(), v.affected.end(), [&](LinkId a, LinkId b) {
        const IndexRange& ra = h_[links_[a].source].range;
        const IndexRange& rb = h_[links_[b].source].range;
        return ra.first < rb.first || (ra.first == rb.first && ra.last > rb.last);
    });
    for (LinkId pl : v.affected) {
        const IndexRange& r = h_[links_[pl].source].range;
        if (v.groups.empty() || !v.groups.back().range.contains(r)) v.groups.push_back(Group{r, {}, {}, 0});
        v.groups.back().plinks.push_back(pl);
    }
    for (const Group& g : v.groups)
        for (ElementId c : h_[v.he].children)
            // No link from the range on c means no line-space child of it below c.
            if (hasLinkFrom(c, g.range)) children.emplace_back(c, g.range);
    return tests;
}

bool LineSpaceUpdate::hasLinkFrom(ElementId e, const IndexRange& sources) const {
    const auto from = [&](LinkId id) { return sources.contains(h_[links_[id].source].range.first); };
    return std::any_of(h_[e].links.begin(), h_[e].links.end(), from) ||
           std::any_of(h_[e].plinks.begin(), h_[e].plinks.end(), from);
}

}  // namespace rad
