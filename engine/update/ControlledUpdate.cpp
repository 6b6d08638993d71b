// The second traversal (paper sec. 6.1, Fig. 8): the frame's link-update
// budget is spent top-down over the visits the first traversal found
// (Traversal.cpp). At each visit its own links are updated first (its
// affected p-links and its candidates), so that what is above is up to date
// whatever happens below; a p-link the criterion no longer refines is
// reinstated (sec. 5.1); the budget left goes to the groups of p-links in
// order of their potential transfer, each child visit getting the share its
// pulled-up work calls for. A group that does not fit:
//   - p-links between two surfaces are reinstated: the coarser links stand
//     for their line-space children, at the new position, and wait in the
//     pending list to be refined again;
//   - p-links with a cluster end stay, and the links below them wait in the
//     stale queue with their old transfers: reinstating a cluster link stands
//     one coarse link for a whole refined subtree (the root's self-link for
//     the whole solution at budget 0), which later frames would have to
//     refine again from scratch.
// Later frames, and idle time, work off the stale queue (top-down, in the
// traversal's order) before they refine.

#include <algorithm>
#include <limits>

#include <tbb/parallel_for.h>

#include "refine/Refiner.h"
#include "update/LineSpaceUpdate.h"
#include "update/Timing.h"

namespace rad {

void LineSpaceUpdate::recompute(LinkId id, bool full) {
    Link& l = links_[id];
    // A p-link refined whatever its visibility is judged without rays; they
    // are cast if it is ever made active again. Nearly every affected p-link
    // has a cluster end and is refined (measured in office: 3,843 of the
    // 4,365 per frame), and its rays were half the link recomputes.
    const auto lazy = [&] { return l.passive && refiner_.refinesAtAnyVisibility(l); };
    if (full || (!layersChanged_ && (movedEnd(l.source) || movedEnd(l.receiver)))) {
        // An end moved: its form factor and both visibility parts change.
        const Link fresh = refiner_.computeUnoccluded(l.source, l.receiver);
        l.unoccluded = fresh.unoccluded;
        l.spread = fresh.spread;
        l.visStale = true;
        if (!lazy()) refiner_.refreshVisibility(l);
    } else if (layersChanged_) {
        // Nothing moved; which rays are static and which dynamic changed.
        l.visStale = true;
        if (l.unoccluded > 0.0 && !lazy()) refiner_.refreshVisibility(l);
    } else if (l.unoccluded > 0.0) {
        // Two-part visibility: only the dynamic object's part can change.
        if (lazy())
            l.visStale = true;
        else if (l.visStale)
            refiner_.refreshVisibility(l);
        else
            refiner_.refreshDynamicVisibility(l);
    }
}

std::size_t LineSpaceUpdate::controlledUpdate(std::size_t budget, FrameStats& stats) {
    // (visit, its budget; kUnlimited: no limit)
    std::vector<std::pair<std::size_t, std::size_t>> level{{0, budget}}, next;
    std::vector<LinkId> batch;
    std::size_t spent = 0;
    while (!level.empty()) {
        if (pastDeadline()) {
            // Out of time: this level and everything below it waits, stale.
            for (const auto& [visit, share] : level) defer(visit);
            break;
        }
        // The own links of every visit reached, in one parallel batch: the
        // visits of a level have disjoint subtrees or disjoint source ranges.
        batch.clear();
        for (const auto& [visit, share] : level) {
            for (LinkId id : visits_[visit].affected)
                if (links_[id].live && links_[id].passive) batch.push_back(id);
            for (LinkId id : visits_[visit].candidates)
                if (links_[id].live && !links_[id].passive) batch.push_back(id);
        }
        // Each link once: two threads must not recompute the same link.
        std::sort(batch.begin(), batch.end());
        batch.erase(std::unique(batch.begin(), batch.end()), batch.end());
        tbb::parallel_for(std::size_t(0), batch.size(), [&](std::size_t i) { recompute(batch[i]); });
        spent += batch.size();
        for (LinkId id : batch)
            if (!links_[id].passive) candidates_.push_back(id);
        next.clear();
        for (const auto& [visit, share] : level) spendOn(visit, share, next, stats);
        level.swap(next);
    }
    return spent;
}

void LineSpaceUpdate::spendOn(std::size_t index, std::size_t budget,
                              std::vector<std::pair<std::size_t, std::size_t>>& next, FrameStats& stats) {
    const ElementId he = visits_[index].he;
    // Sec. 5.1: an affected p-link the criterion no longer refines is
    // reinstated (a reinstate may remove others of the list).
    for (LinkId pl : visits_[index].affected) {
        const Link& l = links_[pl];
        if (l.live && l.passive && l.receiver == he && !refiner_.wouldRefine(l)) reinstate(pl);
    }
    const std::size_t own = visits_[index].own();
    std::size_t left = budget == kUnlimited ? kUnlimited : budget - std::min(budget, own);
    // The groups that still hold refining p-links, largest potential transfer first.
    struct Order {
        Group* group;
        double transfer;
    };
    std::vector<Order> order;
    const Visit& visit = visits_[index];
    for (Group& g : visits_[index].groups) {
        double transfer = 0.0;
        bool refining = false;
        for (LinkId pl : visit.plinks(g))
            if (links_[pl].live && links_[pl].passive) {
                refining = true;
                transfer += heapKey(links_[pl]);
            }
        if (refining) order.push_back({&g, transfer});
    }
    std::stable_sort(order.begin(), order.end(), [](const Order& a, const Order& b) { return a.transfer > b.transfer; });
    for (const Order& o : order) {
        Group& g = *o.group;
        if (left == kUnlimited) {
            for (std::size_t child : g.visits()) next.emplace_back(child, kUnlimited);
            continue;
        }
        if (g.work <= left) {
            left -= g.work;
            for (std::size_t child : g.visits()) next.emplace_back(child, visits_[child].work);
            continue;
        }
        // Not enough budget to go down.
        const std::span<const LinkId> plinks = visit.plinks(g);
        const bool surfaces = std::all_of(plinks.begin(), plinks.end(), [&](LinkId pl) {
            const Link& l = links_[pl];
            return !l.live || !l.passive || (h_[l.source].isSurface() && h_[l.receiver].isSurface());
        });
        if (surfaces) {
            for (LinkId pl : plinks) {
                if (!links_[pl].live || !links_[pl].passive) continue;
                reinstate(pl);
                ++stats.budgetReinstated;
                pending_.push_back(pl);
            }
            continue;
        }
        // A cluster group: what budget is left goes down as far as it
        // reaches, each child visit its share; the rest waits, stale.
        const std::size_t give = left;
        left = 0;
        for (std::size_t child : g.visits()) {
            const std::size_t share =
                g.work == 0 ? 0 : std::size_t(double(give) * double(visits_[child].work) / double(g.work));
            if (share > 0 && share >= visits_[child].own())
                next.emplace_back(child, share);
            else
                defer(child);
        }
    }
}

void LineSpaceUpdate::markStale(LinkId id, bool stale) {
    if (!stale && !isStale(id)) return;
    staleMarks_.cover(links_.slots());
    staleMarks_.set(id, stale);
}

void LineSpaceUpdate::defer(std::size_t index) {
    std::vector<std::size_t> stack{index};
    deferFrom(stack, false);
}

bool LineSpaceUpdate::deferFound() {
    if (!deferringFound_) deferStack_.assign(1, 0);
    deferringFound_ = !deferFrom(deferStack_, true);
    return !deferringFound_;
}

bool LineSpaceUpdate::deferFrom(std::vector<std::size_t>& stack, bool onTheClock) {
    // Their potential transfers, read for the estimate, a run at a time on
    // all cores.
    std::size_t keyed = stale_.size();
    const auto key = [&] {
        tbb::parallel_for(keyed, stale_.size(), [&](std::size_t i) {
            const Link& l = links_[stale_[i].id];
            stale_[i].transfer = l.live ? heapKey(l) : 0.0;  // a reinstate may have removed it
        });
        keyed = stale_.size();
    };
    while (!stack.empty()) {
        if (onTheClock && stale_.size() - keyed >= kDeadlineChunk) {
            key();
            if (pastDeadline()) return false;
        }
        const Visit& v = visits_[stack.back()];
        stack.pop_back();
        for (const std::vector<LinkId>* list : {&v.affected, &v.candidates})
            for (LinkId id : *list) {
                if (isStale(id)) continue;
                markStale(id, true);
                stale_.push_back({id, frame_, motionBefore_, 0.0});
            }
        for (const Group& g : v.groups)
            for (std::size_t child : g.visits()) stack.push_back(child);
    }
    key();
    return true;
}

bool LineSpaceUpdate::changedSince(const Link& l, std::uint32_t frame) const {
    if (layersChangedFrame_ >= frame) return true;
    return std::any_of(lastMoved_.begin(), lastMoved_.end(), [&](const auto& m) {
        return m.second >= frame && (m.first.nestedWith(h_.range(l.source)) || m.first.nestedWith(h_.range(l.receiver)));
    });
}

std::size_t LineSpaceUpdate::catchUp(std::size_t budget, FrameStats& stats) {
    // In the order deferred (a p-link before the links below it), as many as
    // the budget allows; each is recomputed at the current position, in full
    // where an end moved or the layers changed since the frame that found it
    // (changedSince), otherwise its dynamic visibility only.
    // In chunks, so that a deadline is looked at. On one, a chunk holds what
    // is expected to fit before the link updates stop (at the time per unit
    // the last chunk took, a link recomputed in full kFullRecompute units,
    // one whose dynamic visibility only is one), but kLeastChunk at least: a
    // chunk of 1,024 links of the moved object (all in full) took 1.1 to
    // 1.8 ms in `two-offices`, against 0.3 to 0.4 ms for the others, and
    // frames at 120 fps ran over by as much.
    std::vector<std::pair<LinkId, bool>> batch;  // and whether in full
    std::size_t done = 0;
    while (!stale_.empty() && (budget == kUnlimited || done < budget) && !pastDeadline()) {
        batch.clear();
        const std::size_t chunk = budget == kUnlimited ? kDeadlineChunk : std::min(kDeadlineChunk, budget - done);
        double units = std::numeric_limits<double>::infinity(), cost = 0.0;
        if (linkDeadline_ && catchUpSecondsPerUnit_ > 0.0)
            units = std::chrono::duration<double>(*linkDeadline_ - std::chrono::steady_clock::now()).count() /
                    catchUpSecondsPerUnit_;
        while (!stale_.empty() && batch.size() < chunk && (batch.size() < kLeastChunk || cost < units)) {
            const auto [id, frame, at, transfer] = stale_.front();
            stale_.pop_front();
            markStale(id, false);
            if (!links_[id].live) continue;
            const bool full = changedSince(links_[id], frame);
            batch.emplace_back(id, full);
            cost += full ? kFullRecompute : 1.0;
        }
        const auto began = std::chrono::steady_clock::now();
        tbb::parallel_for(std::size_t(0), batch.size(), [&](std::size_t i) { recompute(batch[i].first, batch[i].second); });
        if (batch.size() >= kLeastChunk)
            catchUpSecondsPerUnit_ = std::max(secondsSince(began) / cost, 0.75 * catchUpSecondsPerUnit_);
        for (const auto& [id, full] : batch) {
            const Link& l = links_[id];
            if (!l.live) continue;  // a reinstate earlier in the batch removed it
            if (l.passive) {
                if (!refiner_.wouldRefine(l)) reinstate(id);
            } else {
                stamp(id);
                candidates_.push_back(id);
            }
        }
        done += batch.size();
    }
    stats.stale = stale_.size();
    return done;
}

void LineSpaceUpdate::reinstate(LinkId id) {
    const ElementId he = links_[id].receiver;
    const IndexRange sources = h_.range(links_[id].source);
    // Sec. 4.2: its line-space children go, and the subdivision they leave
    // without links.
    removeLineSpaceChildren(he, sources, id);
    if (h_[he].isSurface() && !h_[he].isLeaf()) {
        bool unlinked = true;
        for (ElementId c : h_[he].children) unlinked = unlinked && h_.subtreeUnlinked(c);
        if (unlinked) h_.removeChildren(he);
    }
    refiner_.activate(id);
    modified_.push_back(id);
    stamp(id);  // already recomputed: not a candidate again
    ++reinstated_;
}

void LineSpaceUpdate::removeLineSpaceChildren(ElementId e, const IndexRange& sources, LinkId keep) {
    // Collected before any goes: a removal reorders the lists. (Removing an
    // active link leaves the p-links' order as it was.)
    doomed_.clear();
    bool refined = e == links_[keep].receiver;
    for (LinkId id : h_[e].links)
        if (sources.contains(h_.range(links_[id].source).first)) doomed_.push_back(id);
    for (LinkId id : h_[e].plinks)
        if (id != keep && sources.contains(h_.range(links_[id].source).first)) {
            doomed_.push_back(id);
            refined = true;
        }
    for (LinkId id : doomed_) refiner_.remove(id);
    // A line-space child of `keep` below e descends, through p-links of the
    // same sources, from one on its receiver's parent (a split receiver) or
    // on its receiver (a split source), and so from one on e: without one
    // here (e itself holds `keep`), there is none below.
    if (!refined) return;
    for (ElementId c : h_[e].children) removeLineSpaceChildren(c, sources, keep);
}

}  // namespace rad
