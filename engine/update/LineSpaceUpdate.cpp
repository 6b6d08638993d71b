#include "update/LineSpaceUpdate.h"

#include <algorithm>
#include <chrono>
#include <functional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_group.h>

#include "hierarchy/ClusterShape.h"
#include "refine/Refiner.h"
#include "solve/Solver.h"
#include "update/Timing.h"

namespace rad {

bool LineSpaceUpdate::movedEnd(ElementId e) const {
    const IndexRange& r = h_.range(e);
    return std::any_of(motions_.begin(), motions_.end(), [&](const ObjectMotion& m) { return m.range.nestedWith(r); });
}

FrameStats LineSpaceUpdate::update(const std::vector<ObjectMotion>& motions, const UpdateSettings& settings,
                                   bool layersChanged) {
    const auto start = std::chrono::steady_clock::now();
    FrameStats stats;
    setDeadline(start, settings);
    ++frame_;
    motions_ = motions;
    layersChanged_ = layersChanged;
    candidates_.clear();
    modified_.clear();
    shaftTests_ = 0;
    reinstated_ = 0;
    linkStamp_.resize(links_.slots(), 0);
    prunePending();
    const std::size_t budget = settings.budget.value_or(kUnlimited);
    stats.budget = budget;
    const auto left = [&] { return budgetLeft(budget, stats.spent); };

    // 1. The first line-space traversal finds the affected links (shaft
    //    tests and index ranges only) and pulls their work up.
    findModifiedLinks();
    stats.traversalSeconds = secondsSince(start);
    stats.shaftTests = shaftTests_;
    startLinkUpdates();

    // 2. The second spends the budget top-down (Fig. 8): link updates,
    //    reinstated p-links; the stale links of earlier frames next; then
    //    the candidates' in-place gather and refinement from the heap.
    auto t = std::chrono::steady_clock::now();
    stats.spent = controlledUpdate(budget, stats);
    stats.spent += catchUp(left(), stats);
    updateCandidates(stats, left());
    stats.reinstated = reinstated_;
    stats.updateSeconds = secondsSince(t);

    // 3. Partial push-pull, then further bounces where radiosity changed.
    t = std::chrono::steady_clock::now();
    std::vector<ElementId> visited = pushPull(stats);
    // The overlay on the other core: it reads positions and link ends, the
    // bounces write radiosity and irradiance.
    tbb::task_group overlay;
    overlay.run([this, changed = visited] { recordOverlay(changed, false); });
    touched_.assign(visited.begin(), visited.end());
    bounce(std::move(visited), settings, stats);
    overlay.wait();
    // 4. Refinement follows the light: links from elements whose oracle
    //    stepped are judged again, with what is left of the budget.
    followTheLight(settings, stats, left());
    stats.pushPullSeconds = secondsSince(t);

    obstacles_.clear();
    finish(stats, start);
    return stats;
}

void LineSpaceUpdate::recordOverlay(const std::vector<ElementId>& changed, bool append) {
    // Bounded: a display of more segments than this says nothing more.
    constexpr std::size_t kMaxSegments = 200'000;
    if (!append) {
        modifiedSegments_.clear();
        changedSegments_.clear();
    }
    modified_.insert(modified_.end(), candidates_.begin(), candidates_.end());
    for (LinkId id : modified_) {
        if (modifiedSegments_.size() >= kMaxSegments) break;
        const Link& l = links_[id];
        if (!l.live) continue;
        modifiedSegments_.push_back({h_[l.source].center, h_[l.receiver].center});
    }
    for (ElementId e : changed) {
        const HElement& el = h_[e];
        if (!el.isSurface() || changedSegments_.size() >= kMaxSegments) continue;
        for (int k = 0; k < el.patch.n; ++k) changedSegments_.push_back({el.patch.v[k], el.patch.v[(k + 1) % el.patch.n]});
    }
}

std::size_t LineSpaceUpdate::reinstateUnneeded() {
    linkStamp_.resize(links_.slots(), 0);
    const std::size_t before = reinstated_;
    // Which p-links the criterion no longer asks for, judged on all cores
    // (the judging is most of it: a link's judgement does not depend on
    // what is reinstated around it).
    std::vector<std::vector<LinkId>> unneeded(h_.size());
    tbb::parallel_for(ElementId(0), ElementId(h_.size()), [&](ElementId e) {
        for (LinkId pl : h_[e].plinks) {
            const Link& l = links_[pl];
            if (l.live && l.passive && l.receiver == e && !refiner_.wouldRefine(l)) unneeded[e].push_back(pl);
        }
    });
    // Top-down: a reinstated p-link takes its line-space children with it,
    // some of which may have been judged unneeded too.
    std::vector<ElementId> stack{h_.root()};
    while (!stack.empty()) {
        const ElementId e = stack.back();
        stack.pop_back();
        for (LinkId pl : unneeded[e]) {
            const Link& l = links_[pl];
            if (l.live && l.passive && l.receiver == e) reinstate(pl);
        }
        for (ElementId c : h_[e].children) stack.push_back(c);
    }
    modified_.clear();
    return reinstated_ - before;
}

void LineSpaceUpdate::prunePending() {
    std::erase_if(pending_, [&](LinkId id) {
        return !links_[id].live || links_[id].passive || !refiner_.wouldRefine(links_[id]);
    });
    std::sort(pending_.begin(), pending_.end());
    pending_.erase(std::unique(pending_.begin(), pending_.end()), pending_.end());
}

void LineSpaceUpdate::finish(FrameStats& stats, std::chrono::steady_clock::time_point start) const {
    // On all cores: at budget 0 the stale links' keys are a tenth of a frame.
    stats.links = tbb::parallel_reduce(
        tbb::blocked_range<ElementId>(0, ElementId(h_.size())), std::size_t(0),
        [&](const tbb::blocked_range<ElementId>& r, std::size_t n) {
            for (ElementId e = r.begin(); e < r.end(); ++e) n += h_[e].links.size();
            return n;
        },
        std::plus<>());
    stats.elements = h_.liveCount();
    stats.pending = pending_.size();
    stats.stale = stale_.size();
    stats.unsent = unsent_.size() + waiting_.size();
    stats.estimatedError = waitingShare();
    stats.totalSeconds = secondsSince(start);
}

double LineSpaceUpdate::waitingShare() const {
    // Active links only: a p-link's transfer is carried by its children.
    const auto waitingIn = [&](const auto& ids) {
        return tbb::parallel_reduce(
            tbb::blocked_range<std::size_t>(0, ids.size()), 0.0,
            [&](const tbb::blocked_range<std::size_t>& r, double sum) {
                for (std::size_t i = r.begin(); i < r.end(); ++i) {
                    const Link& l = links_[ids[i]];
                    if (l.live && !l.passive) sum += heapKey(l);
                }
                return sum;
            },
            std::plus<>());
    };
    const double waiting = waitingIn(pending_) + waitingIn(stale_) + unsentPower();
    const HElement& root = h_[h_.root()];
    const double power = root.area * luminance(root.radiosity);
    return power > 0.0 ? waiting / power : 0.0;
}

double LineSpaceUpdate::linkShare(const std::vector<ElementId>& clusters) const {
    double sum = 0.0;
    for (ElementId top : clusters)
        for (std::vector<ElementId> stack{top}; !stack.empty();) {
            const HElement& e = h_[stack.back()];
            stack.pop_back();
            for (LinkId id : e.links) sum += heapKey(links_[id]);
            for (LinkId id : e.outLinks) sum += heapKey(links_[id]);
            for (ElementId c : e.children) stack.push_back(c);
        }
    const HElement& root = h_[h_.root()];
    const double power = root.area * luminance(root.radiosity);
    return power > 0.0 ? sum / power : 0.0;
}

std::size_t LineSpaceUpdate::budgetLeft(std::size_t budget, std::size_t spent) {
    return budget == kUnlimited ? kUnlimited : budget - std::min(budget, spent);
}

namespace {
std::chrono::steady_clock::duration seconds(double s) {
    return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}
}  // namespace

void LineSpaceUpdate::setDeadline(std::chrono::steady_clock::time_point start, const UpdateSettings& settings) {
    deadline_.reset();
    if (settings.deadlineSeconds) deadline_ = start + seconds(std::max(0.0, *settings.deadlineSeconds));
    startLinkUpdates();
}

void LineSpaceUpdate::startLinkUpdates() {
    linkDeadline_.reset();
    if (!deadline_) return;
    const auto now = std::chrono::steady_clock::now();
    const double left = std::chrono::duration<double>(*deadline_ - now).count() - tail_.seconds(0);
    linkDeadline_ = now + seconds(std::max(0.0, left) / 2.0);
}

std::vector<ElementId> LineSpaceUpdate::pushPull(FrameStats& stats) {
    std::vector<ElementId> visited = solver_.partialPushPull(refiner_.takeDirty());
    stats.changedElements += visited.size();
    for (ElementId e : visited) stats.changedLeaves += h_[e].isSurface() && h_[e].children.empty();
    return visited;
}

double LineSpaceUpdate::shareThatFits(std::size_t changedLeaves, double work) const {
    if (!deadline_) return 1.0;
    const double left = std::chrono::duration<double>(*deadline_ - std::chrono::steady_clock::now()).count() -
                        tail_.seconds(changedLeaves);
    if (!(left > 0.0)) return 0.0;
    return work > left ? left / work : 1.0;
}

double LineSpaceUpdate::unsentPowerOf(ElementId e) const {
    const HElement& el = h_[e];
    if (el.outLinks.empty()) return 0.0;
    if (el.shape == kNone) return std::abs(luminance(el.radiosity - el.gathered)) * el.area;
    const ClusterShape& shape = h_.shape(e);
    double power = 0.0;
    for (int k = 0; k < shape.facetCount; ++k) power += std::abs(luminance(shape.power[k] - shape.gathered[k]));
    return power;
}

double LineSpaceUpdate::unsentPower() const {
    double power = 0.0;
    for (ElementId e : unsent_) power += unsentPowerOf(e);
    for (ElementId e : waiting_) power += std::max(0.0, waitingChange_[e]) * h_[e].area;
    return power;
}

FrameStats LineSpaceUpdate::refinePending(const UpdateSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    idle_ = true;
    FrameStats stats;
    const std::size_t budget = settings.budget.value_or(kUnlimited);
    stats.budget = budget;
    const auto left = [&] { return budgetLeft(budget, stats.spent); };
    setDeadline(start, settings);
    ++frame_;
    candidates_.clear();
    modified_.clear();
    linkStamp_.resize(links_.slots(), 0);
    // The stale links first (they carry transfers of an earlier position),
    // then the refinement the budget left pending.
    stats.spent = catchUp(left(), stats);
    updateCandidates(stats, left());
    RefineHeap heap;
    std::vector<LinkId> pending;
    prunePending();
    pending.swap(pending_);
    for (LinkId id : pending) heap.push({heapKey(links_[id]), id});
    refineFromHeap(heap, stats, left());
    stats.updateSeconds = secondsSince(start);
    const auto t = std::chrono::steady_clock::now();
    std::vector<ElementId> visited = pushPull(stats);
    // What catching up changed joins what the last move changed on show.
    recordOverlay(visited, true);
    touched_.assign(visited.begin(), visited.end());
    bounce(std::move(visited), settings, stats);
    followTheLight(settings, stats, left());
    idle_ = false;
    stats.pushPullSeconds = secondsSince(t);
    finish(stats, start);
    return stats;
}

FrameStats LineSpaceUpdate::propagate(const std::vector<ElementId>& elements, const UpdateSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    editStart_ = start;
    FrameStats stats;
    const std::size_t budget = settings.budget.value_or(kUnlimited);
    stats.budget = budget;
    setDeadline(start, settings);
    ++frame_;
    candidates_.clear();
    modified_.clear();
    linkStamp_.resize(links_.slots(), 0);
    // Pushed whole (a dirty element's subtree is pushed again), then the
    // steps 3 and 4 of a move: nothing moved, so no link changes its form
    // factor; what changed is the light the links carry.
    for (ElementId e : elements) refiner_.markDirty(e);
    std::vector<ElementId> visited = pushPull(stats);
    recordOverlay(visited, false);
    bounce(std::move(visited), settings, stats);
    stats.pushPullSeconds = secondsSince(start);
    return stats;  // judgeAgain finishes the frame
}

void LineSpaceUpdate::judgeAgain(const UpdateSettings& settings, FrameStats& stats) {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t budget = settings.budget.value_or(kUnlimited);
    // Every active link, on all cores (judging is most of it when little
    // changes), in element order.
    std::vector<std::vector<LinkId>> wanted(h_.size());
    tbb::parallel_for(ElementId(0), ElementId(h_.size()), [&](ElementId e) {
        for (LinkId id : h_[e].links)
            if (refiner_.wouldRefine(links_[id])) wanted[e].push_back(id);
    });
    RefineHeap heap;
    for (const std::vector<LinkId>& ids : wanted)
        for (LinkId id : ids) heap.push({heapKey(links_[id]), id});
    refineFromHeap(heap, stats, budgetLeft(budget, stats.spent));
    const std::size_t reinstated = reinstateUnneeded();
    stats.reinstated += reinstated;
    stats.spent += reinstated;
    std::vector<ElementId> visited = pushPull(stats);
    bounce(std::move(visited), settings, stats);
    touched_.clear();  // the oracles are anchored at this light next (Engine)
    stats.updateSeconds += secondsSince(start);
    finish(stats, editStart_);
}

// Links made during the frame (refinement) have ids past the stamps sized
// when it began.
bool LineSpaceUpdate::stampedThisFrame(LinkId id) const { return id < linkStamp_.size() && linkStamp_[id] == frame_; }

void LineSpaceUpdate::stamp(LinkId id) {
    if (id >= linkStamp_.size()) linkStamp_.resize(links_.slots(), 0);
    linkStamp_[id] = frame_;
}

}  // namespace rad
