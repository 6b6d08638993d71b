// The first traversal of the line-space hierarchy (paper sec. 4.1, Fig. 6):
// from the root, every p-link whose source lies in the current index range
// and whose shaft the object cut before or after the move is affected, and
// the traversal goes on below it, restricted to its source's range; active
// links found so are the candidates. It only finds: the links are updated by
// the second traversal (ControlledUpdate.cpp), which spends the frame's
// budget top-down with the work this one pulls up (sec. 6.1). On a deadline
// it stops between runs of visits and goes on in the next frame (resume).

#include <algorithm>

#include <tbb/parallel_for.h>

#include "geometry/Shaft.h"
#include "links/SourceOrder.h"
#include "refine/Refiner.h"
#include "update/LineSpaceUpdate.h"

namespace rad {

bool LineSpaceUpdate::affectedByMotion(ElementId s, ElementId r, std::size_t& tests) const {
    // Links made after the layers changed (chooseObject) are up to date, and
    // so are their line-space children, which have an end in the same object.
    if (fresh_ && (fresh_->contains(h_.range(s)) || fresh_->contains(h_.range(r)))) return false;
    const Aabb& a = h_.box(s);
    const Aabb& b = h_.box(r);
    // Whether the shaft of s -> r meets a moving object's old or new box,
    // except object `skip`. The shaft is built only when tested (storing one
    // per link would cost 256 bytes each), and only when the boxes' hull
    // meets a box: most tested links are far from every object.
    const auto cut = [&](std::size_t skip) {
        bool near = false;
        for (std::size_t k = 0; k < motions_.size() && !near; ++k)
            near = k != skip && (Shaft::hullMeets(a, b, motions_[k].oldBox) || Shaft::hullMeets(a, b, motions_[k].newBox));
        if (!near) return false;
        const Shaft shaft(a, b);
        for (std::size_t k = 0; k < motions_.size(); ++k)
            if (k != skip && (shaft.intersects(motions_[k].oldBox) || shaft.intersects(motions_[k].newBox))) return true;
        return false;
    };
    // Both ends on one moving object: a rigid motion changes neither the form
    // factor nor the object's occlusion of its own parts; only static
    // geometry in the object (the obstacles) or another moving object can
    // come between them.
    for (std::size_t k = 0; k < motions_.size() && !layersChanged_; ++k) {
        const ObjectMotion& m = motions_[k];
        if (!m.range.contains(h_.range(s)) || !m.range.contains(h_.range(r))) continue;
        if (obstacles_.empty() && motions_.size() == 1) return false;
        ++tests;
        const auto nearObstacle = [&](const Aabb& o) { return Shaft::hullMeets(a, b, o); };
        if (std::any_of(obstacles_.begin(), obstacles_.end(), nearObstacle)) {
            const Shaft shaft(a, b);
            if (std::any_of(obstacles_.begin(), obstacles_.end(),
                            [&](const Aabb& o) { return nearObstacle(o) && shaft.intersects(o); }))
                return true;
        }
        return motions_.size() > 1 && cut(k);
    }
    if (movedEnd(s) || movedEnd(r)) return true;
    ++tests;
    return cut(motions_.size());
}

bool LineSpaceUpdate::cutBefore(ElementId s, ElementId r) const {
    const Aabb& a = h_.box(s);
    const Aabb& b = h_.box(r);
    return std::any_of(motions_.begin(), motions_.end(), [&](const ObjectMotion& m) {
        return Shaft::hullMeets(a, b, m.oldBox) && Shaft(a, b).intersects(m.oldBox);
    });
}

void LineSpaceUpdate::beginTraversal() {
    carried_.clear();  // the links it finds are updated after it
    refiner_.sortLinkLists();  // what the last frame appended (links/SourceOrder.h)
    visitCount_ = 0;
    addVisit(h_.root(), h_.range(h_.root()));
    traversalLevel_.assign(1, 0);
    nextLevel_.clear();
    levelDone_ = 0;
    traversing_ = true;
}

bool LineSpaceUpdate::traverse(std::optional<std::chrono::steady_clock::time_point> stop) {
    // Level by level, each level's visits on all cores: a visit only reads,
    // and stamps its own candidates (the visits of a level have disjoint
    // subtrees, or disjoint source ranges on the same node). On the clock a
    // level goes in runs of kVisitsPerLook visits, the clock looked at
    // between them: the traversal stops there, where it is in the level
    // kept, and goes on at the next call (a level of `office`'s chair takes
    // up to a few milliseconds). At least one run a call, so that frames on
    // a deadline already past still end it.
    std::vector<std::size_t>& level = traversalLevel_;
    if (level.empty()) {  // ended, its work pulled up, in an earlier call (a frame that only found)
        traversing_ = false;
        return true;
    }
    std::vector<std::vector<std::pair<ElementId, IndexRange>>>& children = childVisits_;
    std::vector<std::size_t> tests;
    for (bool first = true; !level.empty(); first = false) {
        if (!first && stop && std::chrono::steady_clock::now() >= *stop) return false;
        const std::size_t begin = levelDone_;
        const std::size_t end = stop ? std::min(level.size(), begin + kVisitsPerLook) : level.size();
        const std::size_t n = end - begin;
        if (children.size() < n) children.resize(n);
        for (std::size_t i = 0; i < n; ++i) children[i].clear();
        tests.assign(n, 0);
        tbb::parallel_for(std::size_t(0), n,
                          [&](std::size_t i) { tests[i] = visitNode(visits_[level[begin + i]], children[i]); });
        for (std::size_t i = 0; i < n; ++i) {
            shaftTests_ += tests[i];
            // The child visits, in the order of the groups and of the children.
            std::size_t k = 0;
            for (Group& g : visits_[level[begin + i]].groups) {
                g.firstVisit = visitCount_;
                while (k < children[i].size() && children[i][k].second.first == g.range.first &&
                       children[i][k].second.last == g.range.last) {
                    nextLevel_.push_back(addVisit(children[i][k].first, children[i][k].second));
                    ++k;
                }
                g.visitCount = visitCount_ - g.firstVisit;
            }
        }
        levelDone_ = end;
        if (levelDone_ == level.size()) {
            level.swap(nextLevel_);
            nextLevel_.clear();
            levelDone_ = 0;
        }
    }
    // Pull the work up (sec. 6.1): a visit's children come after it.
    for (std::size_t i = visitCount_; i-- > 0;) {
        Visit& v = visits_[i];
        v.work = v.own();
        for (Group& g : v.groups) {
            g.work = 0;
            for (std::size_t child : g.visits()) g.work += visits_[child].work;
            v.work += g.work;
        }
    }
    traversing_ = false;
    return true;
}

std::size_t LineSpaceUpdate::addVisit(ElementId he, const IndexRange& ind) {
    if (visitCount_ == visits_.size()) visits_.push_back(Visit{});
    Visit& v = visits_[visitCount_];
    v.he = he;
    v.ind = ind;
    v.affected.clear();
    v.candidates.clear();
    v.groups.clear();
    v.work = 0;
    return visitCount_++;
}

std::size_t LineSpaceUpdate::visitNode(Visit& v, std::vector<std::pair<ElementId, IndexRange>>& children) {
    std::size_t tests = 0;
    // The links from the visit's range: one run of each list, in source order.
    // Each link's source box is read at random: the links are asked for a
    // few places ahead.
    const std::span<const LinkId> plinks = linksFrom(h_, links_, h_[v.he].plinks, v.ind);
    for (std::size_t k = 0; k < plinks.size(); ++k) {
        links_.prefetchAhead(plinks, k);
        if (affectedByMotion(links_[plinks[k]].source, v.he, tests)) v.affected.push_back(plinks[k]);
    }
    const std::span<const LinkId> active = linksFrom(h_, links_, h_[v.he].links, v.ind);
    for (std::size_t k = 0; k < active.size(); ++k) {
        links_.prefetchAhead(active, k);
        const LinkId id = active[k];
        // Found once a frame (a link older than the frame: its slot is
        // within the stamps).
        if (stamps_.testConcurrently(id) || !affectedByMotion(links_[id].source, v.he, tests) ||
            !stamps_.setConcurrently(id))
            continue;
        v.candidates.push_back(id);
    }
    // Descend once per maximal range: a p-link refined by splitting its source
    // leaves p-links from q's children on he itself, whose ranges lie inside
    // q's; visiting the children for each of them again would repeat the same
    // traversal. (The affected p-links are in source order: a range comes
    // before the ranges inside it.)
    for (std::size_t k = 0; k < v.affected.size(); ++k) {
        const IndexRange& r = h_.range(links_[v.affected[k]].source);
        if (v.groups.empty() || !v.groups.back().range.contains(r))
            v.groups.push_back(Group{r, static_cast<std::uint32_t>(k), 0, 0, 0, 0});
        ++v.groups.back().plinkCount;
    }
    // Each group goes on below every child: a child with no link from the
    // group's range finds nothing there (one binary search, which a test for
    // links from the range before descending would repeat).
    for (const Group& g : v.groups)
        for (ElementId c : h_[v.he].children) children.emplace_back(c, g.range);
    return tests;
}

}  // namespace rad
