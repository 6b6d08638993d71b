// The link update (paper sec. 5.2): each candidate, recomputed for the new
// position, either adds B_s (F_new - F_old) to its receiver (eq. 1, the
// in-place gather) or goes to a heap ordered by its potential power
// transfer, from which links are refined while the budget lasts (eq. 2 for
// the parent, new transfers for its children).

#include <algorithm>
#include <unordered_set>

#include "refine/Refiner.h"
#include "update/LineSpaceUpdate.h"

namespace rad {

void LineSpaceUpdate::updateCandidates(FrameStats& stats, std::size_t budget) {
    RefineHeap heap;
    // Drop candidates a reinstate under the budget removed; the traversal
    // recomputed them all.
    // A link reached from two visits (or again while catching up) is one
    // candidate: updated twice, its refinement would be made twice.
    // Found by sorting (the first of each kept, in the traversal's order),
    // not by a mark per link slot: a frame's candidates are few beside the
    // links of a large scene.
    std::vector<std::pair<LinkId, std::size_t>> order(candidates_.size());
    for (std::size_t i = 0; i < candidates_.size(); ++i) order[i] = {candidates_[i], i};
    std::sort(order.begin(), order.end());
    std::vector<char> keep(candidates_.size(), 0);
    for (std::size_t i = 0; i < order.size(); ++i) {
        const LinkId id = order[i].first;
        keep[order[i].second] = (i == 0 || order[i - 1].first != id) && links_[id].live && !links_[id].passive;
    }
    std::size_t n = 0;
    for (std::size_t i = 0; i < candidates_.size(); ++i)
        if (keep[i]) candidates_[n++] = candidates_[i];
    candidates_.resize(n);
    for (LinkId id : candidates_) {
        ++stats.candidates;
        if (refiner_.wouldRefine(links_[id])) {
            double key = heapKey(links_[id]);
            // Sec. 6.2: the object entering a shaft it did not cut before makes
            // refinement there more urgent.
            const Link& l = links_[id];
            if (!movedEnd(l.source) && !movedEnd(l.receiver) &&
                !cutBefore(l.source, l.receiver))
                key *= kEnteringBoost;
            heap.push({key, id});
        } else {
            refiner_.regather(id);  // eq. 1
            ++stats.linksUpdated;
        }
    }
    refineFromHeap(heap, stats, budget);
}

void LineSpaceUpdate::refineFromHeap(RefineHeap& heap, FrameStats& stats, std::size_t budget) {
    // Highest transfer first, in batches whose new links are computed in
    // parallel; a refinement costs the links it creates.
    std::vector<LinkId> batch, created;
    // A link can be in the heap twice (found from the old and the new box, or
    // pushed again with a new key); it is refined once. Refined in an earlier
    // batch it is passive; in this one, it is in `inBatch`.
    std::unordered_set<LinkId> inBatch;
    std::size_t left = budget;
    // Past the deadline nothing is begun, but by an idle frame, which makes
    // one batch whatever the clock says (so that idle time converges).
    while (!heap.empty() && (idle_ || !pastDeadline())) {
        batch.clear();
        inBatch.clear();
        std::size_t cost = 0;
        while (!heap.empty()) {
            const LinkId id = heap.top().second;
            if (!links_[id].live || links_[id].passive || inBatch.count(id)) {
                heap.pop();
                continue;
            }
            const std::size_t c = refiner_.childCount(links_[id]);
            if (budget != kUnlimited && cost + c > left) break;
            if (deadline_ && !batch.empty() && cost + c > kDeadlineChunk) break;  // look at the clock
            heap.pop();
            batch.push_back(id);
            inBatch.insert(id);
            cost += c;
        }
        if (batch.empty()) break;
        created.clear();
        refiner_.refine(batch, created);  // eq. 2 for the parents, new transfers for the children
        modified_.insert(modified_.end(), created.begin(), created.end());
        stats.refined += batch.size();
        stats.linksUpdated += created.size();
        stats.spent += created.size();
        if (budget != kUnlimited) left -= std::min(left, created.size());
        for (LinkId c : created)
            if (refiner_.wouldRefine(links_[c])) heap.push({heapKey(links_[c]), c});
        if (pastDeadline()) break;
    }
    // Out of budget or time: the rest stay at their level with their new form factors
    // (sec. 5.2), and wait for budget to be refined.
    while (!heap.empty()) {
        const LinkId id = heap.top().second;
        heap.pop();
        if (!links_[id].live || links_[id].passive) continue;
        refiner_.regather(id);
        ++stats.linksUpdated;
        pending_.push_back(id);
    }
}

double LineSpaceUpdate::heapKey(const Link& l) const { return refiner_.potentialTransfer(l); }

}  // namespace rad
