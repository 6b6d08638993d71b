#include "update/LineSpaceUpdate.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hierarchy/ClusterShape.h"
#include "refine/Refiner.h"
#include "solve/Solver.h"
#include "update/Timing.h"

namespace rad {

bool LineSpaceUpdate::movedEnd(ElementId e) const {
    const IndexRange& r = h_.range(e);
    return std::any_of(motions_.begin(), motions_.end(), [&](const ObjectMotion& m) { return m.range.nestedWith(r); });
}

FrameStats LineSpaceUpdate::update(const std::vector<ObjectMotion>& motions, const UpdateSettings& settings) {
    layersChanged_ = false;
    fresh_.reset();
    return run(motions, settings, true);
}

FrameStats LineSpaceUpdate::chooseObject(const Aabb& box, const IndexRange& range, bool relinked,
                                         const UpdateSettings& settings) {
    layersChanged_ = true;
    meanReflectance_.reset();  // polygons may have moved in the tree
    carried_.clear();
    unsent_.forget();
    fresh_ = relinked ? std::optional(range) : std::nullopt;
    FrameStats stats = run({{box, box, range}}, settings, false);
    layersChanged_ = false;
    fresh_.reset();
    return stats;
}

FrameStats LineSpaceUpdate::run(const std::vector<ObjectMotion>& motions,
                                const UpdateSettings& settings, bool mayFindOnly) {
    checkNotTraversing("a move");
    const auto start = std::chrono::steady_clock::now();
    response_.clear();  // links change: what an edit sent no longer scales
    FrameStats stats;
    setDeadline(start, settings);
    nextFrame();
    motions_ = motions;
    if (layersChanged_) layersChangedFrame_ = frame_;
    for (const ObjectMotion& m : motions) {
        const auto same = std::find_if(lastMoved_.begin(), lastMoved_.end(), [&](const auto& e) {
            return e.first.first == m.range.first && e.first.last == m.range.last;
        });
        if (same == lastMoved_.end())
            lastMoved_.emplace_back(m.range, frame_);
        else
            same->second = frame_;
    }
    double step = 0.0;
    for (const ObjectMotion& m : motions) step = std::max(step, motionShare(m.oldBox, m.newBox));
    motionBefore_ = motion_;
    motion_ += step;
    candidates_.clear();
    modified_.clear();
    shaftTests_ = 0;
    reinstated_ = 0;
    stamps_.cover(links_.slots());
    prunePending();
    beginTraversal();
    return goOn(stats, settings, start, mayFindOnly, false);
}

FrameStats LineSpaceUpdate::resume(const UpdateSettings& settings, bool idle) {
    if (!traversing_) throw std::logic_error("LineSpaceUpdate::resume with no traversal under way");
    const auto start = std::chrono::steady_clock::now();
    FrameStats stats;
    setDeadline(start, settings);
    // The same frame for the stamps (a link is found once per traversal).
    shaftTests_ = 0;
    reinstated_ = 0;
    idle_ = idle;
    stats = goOn(stats, settings, start, true, true);
    idle_ = false;
    return stats;
}

void LineSpaceUpdate::abandonTraversal() {
    traversing_ = false;
    deferringFound_ = false;  // what it deferred waits, stale; the rest is found again
    deferStack_.clear();
    traversalLevel_.clear();
    nextLevel_.clear();
    levelDone_ = 0;
    obstacles_.clear();
}

void LineSpaceUpdate::checkNotTraversing(const char* what) const {
    if (traversing_) throw std::logic_error(std::string(what) + " while a traversal is under way (resume or abandon it first)");
}

FrameStats LineSpaceUpdate::goOn(FrameStats stats, const UpdateSettings& settings,
                                 std::chrono::steady_clock::time_point start, bool mayFindOnly, bool resumed) {
    const std::size_t budget = settings.budget.value_or(kUnlimited);
    stats.budget = budget;
    const auto left = [&] { return budgetLeft(budget, stats.spent); };
    // The share of the frame the traversal may take: of what the updater
    // was given, less the mesh's fixed part.
    const auto share = [&](double s) {
        return start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(
                           s * std::max(0.0, std::chrono::duration<double>(*deadline_ - start).count() - tailSeconds(0))));
    };
    const bool onTheClock = mayFindOnly && !motions_.empty() && deadline_;

    // 1. The first line-space traversal finds the affected links (shaft
    //    tests and index ranges only) and pulls their work up; on a
    //    deadline it may stop, and go on in the next frame.
    //    One that ends after kTraversalShare of the frame leaves the frame
    //    nothing but what it found: it is kept, and the next frame goes on
    //    with it as with a traversal under way (resume: its links are
    //    deferred there, and caught up on). Deferring them in its own frame
    //    (their potential transfers read for the estimate) ran it 4 to 6 ms
    //    over at 120 fps.
    const bool endedBefore = traversalLevel_.empty();
    const bool ended = traverse(onTheClock ? std::optional(share(kTraversalMost)) : std::nullopt);
    stats.traversalSeconds = secondsSince(start);
    stats.shaftTests = shaftTests_;
    stats.foundOnly = ended && !endedBefore && onTheClock && std::chrono::steady_clock::now() > share(kTraversalShare);
    if (ended) obstacles_.clear();
    if (stats.foundOnly) traversing_ = true;  // its level empty: the next resume ends it at once
    const auto goesOn = [&] {
        // What else is dirty (a moved light's direct light) is pushed as the
        // clock allows; the rest waits, counted in the estimate.
        stats.traversing = true;
        const auto pushStart = std::chrono::steady_clock::now();
        touch(pushPull(stats, true));
        stats.pushPullSeconds = secondsSince(pushStart);
        finish(stats, start, false);
        return stats;
    };
    if (traversing_) return goesOn();
    startLinkUpdates();

    // 2. The second spends the budget top-down (Fig. 8): link updates,
    //    reinstated p-links; the stale links of earlier frames next; then
    //    the candidates' in-place gather and refinement from the heap. A
    //    traversal that began in an earlier frame leaves what it found
    //    stale, behind what earlier frames left, and the frame catches up
    //    on the clock: the top-down spending stops only between levels, and
    //    with no budget but the deadline's a level overran the frame by
    //    half (`office`'s chair at 120 fps).
    //    A resumed traversal defers what it found on the clock (70,000
    //    links of `two-offices`' chair took 6 ms, a frame at 120 fps
    //    spending nothing else): one the deadline stops goes on deferring
    //    in the next frame, as a traversal under way.
    auto t = std::chrono::steady_clock::now();
    if (resumed && !deferFound()) {
        traversing_ = true;
        stats.updateSeconds = secondsSince(t);
        return goesOn();
    }
    if (!resumed) stats.spent = controlledUpdate(budget, stats);
    stats.spent += catchUp(left(), stats);
    updateCandidates(stats, left());
    stats.reinstated = reinstated_;
    stats.updateSeconds = secondsSince(t);

    // 3. Partial push-pull, then further bounces where radiosity changed.
    t = std::chrono::steady_clock::now();
    std::vector<ElementId> visited = pushPull(stats, true);
    recordOverlay(visited, false);
    touch(visited);  // with what a deadline left
    moving_ = true;
    const struct Reset {
        bool& flag;
        ~Reset() { flag = false; }
    } reset{moving_};
    bounce(std::move(visited), settings, stats);
    // 4. Refinement follows the light: links from elements whose oracle
    //    stepped are judged again, with what is left of the budget.
    followTheLight(settings, stats, left());
    stats.pushPullSeconds = secondsSince(t);

    obstacles_.clear();
    finish(stats, start, !resumed);
    return stats;
}

void LineSpaceUpdate::recordOverlay(const std::vector<ElementId>& changed, bool append) {
    // Ids only: the segments are made when a display asks for them (a
    // frame that changes half the building floor would otherwise spend 0.1 s
    // sorting outlines nobody draws), and so is the choice of the leaves
    // among them (reading whether each is one took 1 to 2 ms of such a
    // frame's 33). Bounded: a display of more than this says nothing more.
    constexpr std::size_t kMaxRecorded = 200'000;
    if (!append) {
        overlayLinks_.clear();
        overlayChanged_.clear();
    }
    for (const std::vector<LinkId>* ids : {&modified_, &candidates_})
        for (LinkId id : *ids) {
            if (overlayLinks_.size() >= kMaxRecorded) break;
            overlayLinks_.push_back(id);
        }
    const std::size_t room = kMaxRecorded - std::min(kMaxRecorded, overlayChanged_.size());
    const std::size_t taken = std::min(changed.size(), room);
    overlayChanged_.insert(overlayChanged_.end(), changed.begin(), changed.begin() + std::ptrdiff_t(taken));
}

std::vector<std::array<glm::dvec3, 2>> LineSpaceUpdate::modifiedLinks() const {
    std::vector<std::array<glm::dvec3, 2>> segments;
    segments.reserve(overlayLinks_.size());
    for (LinkId id : overlayLinks_) {
        if (!overlayLinkLive(id)) continue;  // removed since
        const Link& l = links_[id];
        segments.push_back({h_[l.source].center, h_[l.receiver].center});
    }
    return segments;
}

std::size_t LineSpaceUpdate::modifiedLinkCount() const {
    return static_cast<std::size_t>(
        std::count_if(overlayLinks_.begin(), overlayLinks_.end(), [&](LinkId id) { return overlayLinkLive(id); }));
}

std::vector<std::array<glm::dvec3, 2>> LineSpaceUpdate::changedOutlines() const {
    // The outlines of the changed leaves (a changed parent's area is its
    // changed leaves'), each edge once: neighbours of one polygon share
    // edges, and a software rasteriser pays for every line.
    std::vector<std::array<glm::dvec3, 2>> edges;
    const auto key = [](const glm::dvec3& p) { return std::tie(p.x, p.y, p.z); };
    for (ElementId e : overlayChanged_) {
        if (e >= h_.size()) continue;
        const HElement& el = h_[e];
        if (!el.isSurface() || !el.isLeaf()) continue;  // subdivided since, or never a leaf
        const PatchGeometry patch = h_.patch(e);
        for (int k = 0; k < patch.n; ++k) {
            std::array<glm::dvec3, 2> edge{patch.v[k], patch.v[(k + 1) % patch.n]};
            if (key(edge[1]) < key(edge[0])) std::swap(edge[0], edge[1]);
            edges.push_back(edge);
        }
    }
    std::sort(edges.begin(), edges.end(), [&](const auto& a, const auto& b) {
        return std::tie(a[0].x, a[0].y, a[0].z, a[1].x, a[1].y, a[1].z) <
               std::tie(b[0].x, b[0].y, b[0].z, b[1].x, b[1].y, b[1].z);
    });
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

std::size_t LineSpaceUpdate::reinstateUnneeded() {
    stamps_.cover(links_.slots());
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

void LineSpaceUpdate::finish(FrameStats& stats, std::chrono::steady_clock::time_point start, bool estimate) {
    stats.links = refiner_.activeLinks();
    stats.elements = h_.liveCount();
    countWaiting(stats);
    // The light changes whose push has been made are in the solution now.
    std::vector<ElementId> unpushed = solver_.unpushed();
    std::sort(unpushed.begin(), unpushed.end());
    std::erase_if(lightChanges_, [&](const auto& c) { return !std::binary_search(unpushed.begin(), unpushed.end(), c.first); });
    if (estimate) {
        stats.estimatedError = estimatedError();
        stats.estimateSeconds = lastEstimateSeconds_;
    }
    stats.totalSeconds = secondsSince(start);
}

void LineSpaceUpdate::countWaiting(FrameStats& stats) const {
    stats.pending = pending_.size() + judgeLater_.size();
    stats.stale = stale_.size();
    stats.finer = coarsenLater_.size();
    stats.unsent = unsent_.size() + waiting_.size() + solver_.unpushed().size();
}

double LineSpaceUpdate::motionShare(const Aabb& from, const Aabb& to) {
    const double size = glm::length(from.extent());
    if (!(size > 0.0)) return 0.0;
    return std::max(glm::length(to.lo - from.lo), glm::length(to.hi - from.hi)) / size;
}

void LineSpaceUpdate::dropCarriedOfFreed() const {
    // Freed elements (an id may be another's now) call for new sums: of
    // the tops freed or holding a freed receiver (all when the log of
    // freed ids no longer reaches back).
    if (carriedReleases_ == h_.releases()) return;
    if (const auto freed = h_.releasedSince(carriedReleases_)) {
        std::vector<ElementId> ids(freed->begin(), freed->end());
        std::sort(ids.begin(), ids.end());
        const auto isFreed = [&](ElementId e) { return std::binary_search(ids.begin(), ids.end(), e); };
        std::erase_if(carried_, [&](const auto& entry) {
            return isFreed(entry.first) ||
                   std::any_of(entry.second.begin(), entry.second.end(), [&](const auto& rp) { return isFreed(rp.first); });
        });
    } else {
        carried_.clear();
    }
    carriedReleases_ = h_.releases();
}

namespace {
// Calls f on `top` and every element below it.
template <class F>
void forEachBelow(const Hierarchy& h, ElementId top, F&& f) {
    for (std::vector<ElementId> stack{top}; !stack.empty();) {
        const HElement& e = h[stack.back()];
        stack.pop_back();
        f(e);
        stack.insert(stack.end(), e.children.begin(), e.children.end());
    }
}
}  // namespace

const std::vector<std::pair<ElementId, double>>& LineSpaceUpdate::carriedBy(ElementId top) const {
    dropCarriedOfFreed();
    auto [it, made] = carried_.try_emplace(top);
    if (!made) return it->second;
    const auto start = std::chrono::steady_clock::now();
    // The subtree's links first (a walk of its id lists), then each one's
    // potential transfer on all cores, summed per receiver in the walk's
    // order: one by one, a chair's 98,000 links and p-links on the building
    // floor took 4.5 ms (a sixth of them reach a cluster, whose projected
    // area toward the source is a sum over its facets).
    std::vector<LinkId> ids;
    forEachBelow(h_, top, [&](const HElement& e) {
        for (const IdList* list : {&e.links, &e.outLinks}) ids.insert(ids.end(), list->begin(), list->end());
    });
    std::vector<double> transfer(ids.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ids.size(), 1024), [&](const auto& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const Link& l = links_[ids[i]];
            transfer[i] = l.live && !l.passive ? heapKey(l) : 0.0;
        }
    });
    std::vector<double>& power = carriedScratch_;
    if (power.size() < h_.size()) power.resize(h_.size(), 0.0);
    std::vector<ElementId> receivers;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        if (!(transfer[i] > 0.0)) continue;
        const ElementId r = links_[ids[i]].receiver;
        if (power[r] == 0.0) receivers.push_back(r);
        power[r] += transfer[i];
    }
    it->second.reserve(receivers.size());
    for (ElementId r : receivers) it->second.emplace_back(r, std::exchange(power[r], 0.0));
    const double seconds = secondsSince(start);
    carriedSeconds_ += seconds;
    if (!ids.empty()) carriedSecondsPerLink_ = seconds / double(ids.size());
    return it->second;
}

std::size_t LineSpaceUpdate::linksCarriedBy(ElementId top) const {
    std::size_t links = 0;
    forEachBelow(h_, top, [&](const HElement& e) { links += e.links.size() + e.outLinks.size(); });
    return links;
}

double LineSpaceUpdate::estimateSeconds(std::span<const ElementId> carrying, bool traversal) const {
    // Before any were made, at a bounce's rate per link (of a sweep of the
    // solve, before a bounce was measured): both read a link and its ends.
    const double perLink = carriedSecondsPerLink_ > 0.0 ? carriedSecondsPerLink_ : bounceSecondsPerLink_;
    double seconds = estimateSeconds_;
    if (!traversal) dropCarriedOfFreed();  // a traversal drops them all
    for (ElementId top : carrying)
        if (traversal || !carried_.count(top)) seconds += perLink * double(linksCarriedBy(top));
    return seconds;
}

double LineSpaceUpdate::estimatedError(const std::vector<std::pair<ElementId, double>>& deferred) const {
    const auto start = std::chrono::steady_clock::now();
    carriedSeconds_ = 0.0;
    const double error = estimateNow(deferred);
    lastEstimateSeconds_ = secondsSince(start);
    // The mean leaves out the sums over the links objects carry, which only
    // some frames make (estimateSeconds counts them where they are made).
    estimateSeconds_ = 0.75 * estimateSeconds_ + 0.25 * std::max(0.0, lastEstimateSeconds_ - carriedSeconds_);
    return error;
}

double LineSpaceUpdate::estimateNow(const std::vector<std::pair<ElementId, double>>& deferred) const {
    // The power each receiver could still change by: its stale and pending
    // active links (a p-link's transfer is carried by its children), and
    // the links with an end in a deferred object's subtree, in the share of
    // its size it has moved.
    // Summed per receiver (a receiver's first power puts it on the list),
    // in an array kept zero between calls: zeroing one per element each
    // frame was a fifth of a deferred frame on the building floor.
    auto& power = powerScratch_;
    if (power.size() < h_.size()) power.resize(h_.size(), 0.0);
    std::vector<ElementId> receivers;
    const auto addPower = [&](ElementId r, double p) {
        if (!(p > 0.0)) return;
        if (power[r] == 0.0) receivers.push_back(r);
        power[r] += p;
    };
    const auto active = [](const Link& l) { return l.live && !l.passive; };
    // A link left coarse (pending refinement) carries the right light on
    // average, wrong by how much it varies across its receiver.
    for (LinkId id : pending_)
        if (active(links_[id])) addPower(links_[id].receiver, refiner_.variationBound(links_[id]));
    // A stale link could change by its whole transfer once the objects have
    // moved by their size since it was last right; by that share before.
    // Their potential transfers as they were deferred (StaleLink): a starved
    // drag leaves tens of thousands.
    double since = 0.0;
    for (const auto& d : deferred) since = std::max(since, d.second);
    for (const StaleLink& s : stale_)
        if (const Link& l = links_[s.id]; active(l)) addPower(l.receiver, std::min(1.0, motion_ + since - s.at) * s.transfer);
    // The links with an end in a deferred object's subtree, in the share of
    // its size it has moved.
    for (const auto& [top, share] : deferred)
        for (const auto& [r, p] : carriedBy(top)) addPower(r, share * p);
    const HElement& root = h_[h_.root()];
    const double area = root.area, total = area * luminance(root.radiosity);
    const auto clearPower = [&] {
        for (ElementId r : receivers) power[r] = 0.0;
    };
    if (!(total > 0.0)) {
        clearPower();
        return 0.0;
    }
    // The scene's mean reflectance, for receivers that are clusters and for
    // the unsent power, which spreads over everything its senders see. Kept
    // until an edit or a choice of object (reading every polygon's element
    // was a third of this on the building floor, each frame).
    if (!meanReflectance_) {
        double rhoArea = 0.0;
        for (std::uint32_t p = 0; p < h_.polygonCount(); ++p)
            if (const ElementId e = h_.polygonElement(p); e != kNone) rhoArea += h_[e].area * luminance(h_[e].reflectance);
        meanReflectance_ = area > 0.0 ? rhoArea / area : 0.0;
    }
    const double rhoMean = *meanReflectance_;
    // In the units of SolutionError::rms: a receiver r whose irradiance is
    // off by P_r / A_r has its radiosity off by rho_r P_r / A_r over its area
    // A_r, so the area-weighted mean square is sum (rho_r P_r)^2 / A_r over
    // the scene's area. A change gathered in one place (a shadow) weighs
    // more than the same power spread over the scene, as in the measure.
    double squares = 0.0;
    for (ElementId r : receivers) {
        const HElement& e = h_[r];
        const double rho = e.isSurface() ? luminance(e.reflectance) : rhoMean;
        if (e.area > 0.0) squares += (rho * power[r]) * (rho * power[r]) / e.area;
    }
    clearPower();
    // Receivers waiting for a push are off by what they gathered since
    // (times their reflectance), over their own area.
    for (ElementId e : waiting_)
        if (e < waitingChange_.size() && waitingChange_[e] > 0.0) squares += waitingChange_[e] * waitingChange_[e] * h_[e].area;
    // Direct light waiting for its push: over the elements it lands on.
    for (const auto& [e, moved] : lightChanges_) squares += moved;
    // What unsent elements have yet to send spreads over what they see: a
    // moving shadow's darker and lighter parts send changes of opposite
    // signs that cancel there, so their sum counts, spread over the scene.
    // Kept term by term (UnsentSet): a push, freed elements, links that
    // begin or cease to leave an element, and a move's clusters (a turned
    // object's facets may regroup) make their terms again; a rigid move
    // keeps a surface's B.
    const double unsent = unsentPower() * rhoMean;
    squares += unsent * unsent / area;
    return std::sqrt(squares * area) / total;
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
    ++pushFrame_;  // every frame begins here, a resumed traversal's too
    deadline_.reset();
    if (settings.deadlineSeconds) deadline_ = start + seconds(std::max(0.0, *settings.deadlineSeconds));
    startLinkUpdates();
}

void LineSpaceUpdate::startLinkUpdates() {
    linkDeadline_.reset();
    if (!deadline_) return;
    const auto now = std::chrono::steady_clock::now();
    const double left = std::chrono::duration<double>(*deadline_ - now).count() - tailSeconds(0);
    linkDeadline_ = now + seconds(std::max(0.0, left) / 2.0);
}

std::vector<ElementId> LineSpaceUpdate::pushPull(FrameStats& stats, bool onTheClock) {
    // On a deadline, a push expected to pass it waits: its cost by the area
    // below the dirty element, at what the last large pushes took per
    // element, the frame's tail left its time.
    std::optional<Solver::PushDeadline> deadline;
    if (onTheClock && deadline_ && !idle_) {
        const double elementsPerArea = double(h_.liveCount()) / std::max(1e-300, h_[h_.root()].area);
        deadline = Solver::PushDeadline{*deadline_ - seconds(tailSeconds(stats.changedLeaves)),
                                        pushSecondsPerElement_ * elementsPerArea};
    }
    const auto began = std::chrono::steady_clock::now();
    std::vector<std::uint32_t> polygons;  // of the leaves the push visited
    std::vector<ElementId> visited = solver_.partialPushPull(refiner_.takeDirty(), deadline, &polygons);
    unsent_.mayHaveChanged(visited);  // radiosity moved
    // Small pushes say more about the call than about elements.
    if (visited.size() >= kPushSample)
        pushSecondsPerElement_ = std::max(secondsSince(began) / double(visited.size()), 0.75 * pushSecondsPerElement_);
    stats.changedElements += visited.size();
    // The snapshot meshes again every polygon with a changed leaf, all of
    // its leaves: that, counted once a frame, is what its time follows.
    // (Read from the visited elements and counted by walking each polygon's
    // tree, it took 2 to 6 ms of a building-floor frame whose push visited
    // 100,000 to 190,000 elements.)
    if (polygonStamp_.size() < h_.polygonCount()) polygonStamp_.resize(h_.polygonCount(), 0);
    for (std::uint32_t p : polygons)
        if (std::exchange(polygonStamp_[p], pushFrame_) != pushFrame_) stats.changedLeaves += h_.polygonLeaves(p);
    return visited;
}

double LineSpaceUpdate::shareThatFits(std::size_t changedLeaves, double work, double first) const {
    if (!deadline_) return 1.0;
    const double left = std::chrono::duration<double>(*deadline_ - std::chrono::steady_clock::now()).count() -
                        tailSeconds(changedLeaves) - first;
    if (!(left > 0.0)) return 0.0;
    return work > left ? left / work : 1.0;
}

void LineSpaceUpdate::joinUnsent(ElementId e, std::size_t links) {
    if (unsent_.join(e)) unsentLinks_ += links;
}

void LineSpaceUpdate::holdUnsent(const std::vector<ElementId>& elements) {
    // Their links counted by the mean per element (what sending them is
    // expected to cost); one with none joins too: it has nothing to send.
    std::size_t joined = 0;
    for (ElementId e : elements) joined += unsent_.join(e);
    const double mean = double(refiner_.activeLinks()) / double(std::max<std::size_t>(1, h_.liveCount()));
    unsentLinks_ += static_cast<std::size_t>(std::llround(mean * double(joined)));
}

void LineSpaceUpdate::prepare() {
    carried_.clear();
    stamps_.cover(links_.slots());
    stamps_.clearAll();
    staleMarks_.cover(links_.slots());
    staleMarks_.clearAll();
    // The marks and sums per element, made here and not in the first frames
    // that need them: fresh memory costs a page fault per 4 KiB (about 11 us
    // on this project's machines), and on the building floor (623,000
    // elements) the first bounce a deadline cut spent 38 ms of a 33 ms
    // frame growing the unsent set's terms to their ids, one by one. They
    // grow without copying (ChunkedArray).
    waitingChange_.resize(h_.size(), -1.0);
    isTouched_.resize(h_.size(), 0);
    powerScratch_.resize(h_.size(), 0.0);
    sending_.resize(h_.size(), 0);
    unsent_.cover(h_.size());
    transferBlock_ = std::clamp<std::size_t>(links_.liveCount() / kLinksPerTransfer, kLeastTransfers, kMostTransfers);
    transfers_.assign(transferBlock_, Transfer{});  // its pages written now
    transfers_.clear();
    refiner_.recordSendersChanged();  // for the sum of what the unsent have to send
}

RefineSettings::Beside LineSpaceUpdate::memoryBeside() {
    // A chunk of each per-element and per-link array, and the bounce's
    // transfer buffer at its least; per element its marks and sums (the
    // sums of what a deferred object carries included); per link its two
    // marks, rounded up to a byte, and its share of the transfer buffer.
    RefineSettings::Beside b;
    b.fixed = decltype(isTouched_)::kChunkBytes + decltype(waitingChange_)::kChunkBytes +
              decltype(powerScratch_)::kChunkBytes + decltype(sending_)::kChunkBytes + UnsentSet::kFixedBytes +
              2 * LinkBits::kChunkBytes + kLeastTransfers * sizeof(Transfer);
    b.perElement = sizeof(decltype(isTouched_)::value_type) + sizeof(decltype(waitingChange_)::value_type) +
                   sizeof(decltype(powerScratch_)::value_type) + sizeof(decltype(sending_)::value_type) +
                   sizeof(decltype(carriedScratch_)::value_type) + UnsentSet::kBytesPerElement;
    b.perLink = 1 + (sizeof(Transfer) + kLinksPerTransfer - 1) / kLinksPerTransfer;
    return b;
}

std::size_t LineSpaceUpdate::memoryBytes() const {
    return waitingChange_.memoryBytes() + isTouched_.memoryBytes() + powerScratch_.memoryBytes() +
           sending_.memoryBytes() + unsent_.memoryBytes() + polygonStamp_.capacity() * sizeof(std::uint32_t) +
           stamps_.memoryBytes() + staleMarks_.memoryBytes() + transfers_.capacity() * sizeof(Transfer);
}

void LineSpaceUpdate::clustersMoved(ElementId objectCluster) {
    if (unsent_.empty()) return;
    std::vector<ElementId> moved;
    for (ElementId a = h_[objectCluster].parent; a != kNone; a = h_[a].parent) moved.push_back(a);
    for (std::vector<ElementId> stack{objectCluster}; !stack.empty();) {
        const ElementId e = stack.back();
        stack.pop_back();
        if (h_[e].isSurface()) continue;  // a rigid move keeps a surface's B
        moved.push_back(e);
        stack.insert(stack.end(), h_[e].children.begin(), h_[e].children.end());
    }
    unsent_.mayHaveChanged(moved);
}

double LineSpaceUpdate::unsentPower() const {
    // Freed elements (an id may be another's now) make their terms again
    // (every term when the log of freed ids no longer reaches back); an
    // element with no active link leaving it has nothing to send.
    if (unsentReleases_ != h_.releases()) {
        if (const auto freed = h_.releasedSince(unsentReleases_))
            unsent_.mayHaveChanged(*freed);
        else
            unsent_.forget();
        unsentReleases_ = h_.releases();
    }
    unsent_.mayHaveChanged(refiner_.takeSendersChanged());
    return unsent_.sum([this](ElementId e) { return unsentPowerOf(e, false); });
}

double LineSpaceUpdate::unsentPowerOf(ElementId e, bool absolute) const {
    const HElement& el = h_[e];
    if (el.outLinks.empty()) return 0.0;
    const auto part = [&](double p) { return absolute ? std::abs(p) : p; };
    if (el.shape == kNone) return part(luminance(el.radiosity - el.gathered)) * el.area;
    const ClusterShape& shape = h_.shape(e);
    double power = 0.0;
    for (int k = 0; k < shape.facetCount(); ++k) power += part(luminance(shape.power[k] - shape.gathered[k]));
    return power;
}

FrameStats LineSpaceUpdate::refinePending(const UpdateSettings& settings, bool idle) {
    checkNotTraversing("refinePending");
    const auto start = std::chrono::steady_clock::now();
    idle_ = idle;
    FrameStats stats;
    const std::size_t budget = settings.budget.value_or(kUnlimited);
    stats.budget = budget;
    const auto left = [&] { return budgetLeft(budget, stats.spent); };
    setDeadline(start, settings);
    nextFrame();
    candidates_.clear();
    modified_.clear();
    stamps_.cover(links_.slots());
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
    std::vector<ElementId> visited = pushPull(stats, !idle);
    // What idle time changed joins what the last move changed on show; a
    // frame that catches up on a move shows what it changed.
    recordOverlay(visited, idle);
    touch(visited);
    bounce(std::move(visited), settings, stats);
    followTheLight(settings, stats, left());
    idle_ = false;
    stats.pushPullSeconds = secondsSince(t);
    // A frame of a drag that catches up defers its move: the engine makes
    // its estimate, with the move (Engine::moveObjects).
    finish(stats, start, idle);
    return stats;
}

FrameStats LineSpaceUpdate::propagate(const std::vector<ElementId>& elements, const UpdateSettings& settings,
                                      const EmissionChange* emission) {
    checkNotTraversing("an edit");
    const auto start = std::chrono::steady_clock::now();
    editStart_ = start;
    meanReflectance_.reset();  // an edit may change reflectance
    carried_.clear();
    unsent_.forget();
    FrameStats stats;
    const std::size_t budget = settings.budget.value_or(kUnlimited);
    stats.budget = budget;
    setDeadline(start, settings);
    nextFrame();
    candidates_.clear();
    modified_.clear();
    stamps_.cover(links_.slots());
    // Pushed whole (a dirty element's subtree is pushed again), then the
    // steps 3 and 4 of a move: nothing moved, so no link changes its form
    // factor; what changed is the light the links carry.
    for (ElementId e : elements) refiner_.markDirty(e);
    // An emission edit proportional to the last one sends c times its light
    // first; the bounces send what that misses (EditResponse.h).
    std::vector<ElementId> guessed;
    std::optional<std::chrono::steady_clock::time_point> guessBegan;
    if (!emission) {
        response_.clear();
    } else {
        const std::optional<glm::dvec3> c = settings.scaleLastEdit ? response_.scaleFor(*emission) : std::nullopt;
        response_.begin(h_, *emission);
        // On a deadline the guess is sent only if it is expected to fit (what
        // the last one took, its push included; before one, a sweep of the
        // solve: guessBounceSeconds): it is not cut short, and in `office` it
        // takes 18 ms, which made 60 fps frames 23 to 27 ms long. Otherwise
        // the bounces send the edit on the clock.
        const bool fits = !deadline_ || idle_ || shareThatFits(stats.changedLeaves, guessSeconds_) >= 1.0;
        // Skipped, the expectation falls by degrees to the fastest guess yet,
        // so that one slow guess does not keep the next ones from being
        // tried, and one that never fitted is not tried again (at 60 fps,
        // falling further made every third frame 21 ms long).
        if (c && !fits) guessSeconds_ = std::max(0.75 * guessSeconds_, guessLeast_);
        // And only while the last guess was less work than the bounces alone
        // were, per unit of the power the edits changed (editWork). On the
        // building floor a room's light reaches the corridor and, faintly,
        // most rooms: a guess's receivers' pushes reached 1.1 million
        // elements, and its frames took 370 to 470 ms against 330 ms by
        // bounces alone.
        const bool cheaper = guessWork_ < 0.0 || guessWork_ < bounceAloneWork_;
        if (c && fits && cheaper) {
            guessBegan = std::chrono::steady_clock::now();
            std::size_t links = 0;
            response_.send(h_, *c, settings.bounceThreshold * reference(), [&](ElementId e) {
                guessed.push_back(e);
                links += h_[e].outLinks.size();
            });
            // Their receivers sum their irradiance again. When the guess
            // leaves from much of the scene (a light reaches most of a
            // room), every element is marked rather than each link's
            // receiver found: reading 500,000 links scattered in memory to
            // mark them took 24 ms of `office`'s 60.
            if (links > links_.liveCount() / 4) {
                for (ElementId e = 0; e < h_.size(); ++e)
                    if (h_.isLive(e)) refiner_.markStale(e);
            } else {
                for (ElementId e : guessed)
                    for (LinkId id : h_[e].outLinks) refiner_.markStale(links_[id].receiver);
            }
        }
    }
    std::vector<ElementId> visited = pushPull(stats);
    if (guessBegan) {
        guessSeconds_ = secondsSince(*guessBegan);
        guessLeast_ = guessSent_ ? std::min(guessLeast_, guessSeconds_) : guessSeconds_;
        guessSent_ = true;
    }
    recordOverlay(visited, false);
    touch(visited);
    // The senders of the bounces are those that sent a guess (what they
    // sent may not be what their radiosity came to) and those whose
    // radiosity moved as a bounce's receivers would have to be pushed: not
    // every element the push visited, which would send what the solve's
    // last sweep left in each (0.07% of `office`'s light, against 1.5e-6
    // for the bounces alone of an edit by a millionth).
    if (!guessed.empty()) {
        // In the order of their ids, each once: a flag per element, the
        // push's elements judged on all cores (sorting the 43,000 ids of
        // `office`'s push and guess took most of 1.5 ms).
        const double threshold = settings.bounceThreshold * reference();
        std::vector<char> sends(h_.size(), 0);
        tbb::parallel_for(std::size_t(0), visited.size(), [&](std::size_t i) {
            if (response_.movedSinceBegin(h_, visited[i], threshold)) sends[visited[i]] = 1;  // each visited once
        });
        for (ElementId e : guessed) sends[e] = 1;
        visited.clear();
        for (ElementId e = 0; e < h_.size(); ++e)
            if (sends[e]) visited.push_back(e);
    }
    bounce(std::move(visited), settings, stats);
    if (emission) {
        response_.keep(h_);
        (guessBegan ? guessWork_ : bounceAloneWork_) = editWork(stats) / changedPower(*emission);
    }
    stats.pushPullSeconds = secondsSince(start);
    return stats;  // judgeAgain finishes the frame
}

double LineSpaceUpdate::changedPower(const EmissionChange& emission) const {
    double power = 0.0;
    for (const auto& [key, change] : emission) {
        if (key < h_.polygonCount()) {
            const ElementId e = h_.polygonElement(key);
            if (e != kNone) power += std::abs(luminance(change)) * h_[e].area;
        } else {
            power += std::abs(luminance(change)) * 4.0 * std::numbers::pi;  // a punctual light's intensity
        }
    }
    return std::max(power, 1e-300);
}

void LineSpaceUpdate::judgeAgain(const UpdateSettings& settings, FrameStats& stats) {
    const auto start = std::chrono::steady_clock::now();
    // The oracles step from the anchors of the solve, as after a move, and
    // are not anchored again: an edit taken back returns every oracle, and
    // so the hierarchy, to the solve's. Anchored at each edit's light
    // instead (every link judged again), a light of `office` changed by a
    // millionth and set back was 0.38% rms from the solve, a desk recoloured
    // and given its materials back 0.39%.
    followTheLight(settings, stats, settings.budget.value_or(kUnlimited), false);
    stats.updateSeconds += secondsSince(start);
    finish(stats, editStart_);
}

void LineSpaceUpdate::setLightScale(double scale) {
    if (!(scale > 0.0) || !std::isfinite(scale) || scale == lightScale_) return;
    lightScale_ = scale;
    unsent_.forget();
    // Every element's share of the light moved, reached by the edit's
    // bounces or not.
    for (ElementId e = 0; e < h_.size(); ++e)
        if (h_.isLive(e)) touch({&e, 1});
}

void LineSpaceUpdate::touch(std::span<const ElementId> elements) {
    if (isTouched_.size() < h_.size()) isTouched_.resize(h_.size(), 0);
    for (ElementId e : elements)
        if (!std::exchange(isTouched_[e], 1)) touched_.push_back(e);
}

void LineSpaceUpdate::clearTouched() {
    for (ElementId e : touched_) isTouched_[e] = 0;
    touched_.clear();
}

// Links made during the frame (refinement) have ids past the stamps sized
// when it began.
void LineSpaceUpdate::stamp(LinkId id) {
    stamps_.cover(links_.slots());
    stamps_.set(id, true);
}

void LineSpaceUpdate::nextFrame() {
    ++frame_;
    // A bit a link slot (a byte was 0.9 bytes a link more): wiping them
    // all is 120 KB in `office`, 3 MB on the building floor (25 million
    // slots).
    stamps_.clearAll();
}

}  // namespace rad
