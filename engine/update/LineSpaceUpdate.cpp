#include "update/LineSpaceUpdate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "geometry/Shaft.h"
#include "refine/Refiner.h"
#include "solve/ClusterTransfer.h"
#include "solve/Solver.h"
#include "update/OracleSteps.h"

namespace rad {
namespace {

double since(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Whether element range `e` lies in, or holds, the moved subtree.
bool touches(const IndexRange& moved, const IndexRange& e) { return moved.contains(e) || e.contains(moved); }

}  // namespace

FrameStats LineSpaceUpdate::update(const Aabb& oldBox, const Aabb& newBox, const IndexRange& moved,
                                   const UpdateSettings& settings, bool layersChanged) {
    const auto start = std::chrono::steady_clock::now();
    FrameStats stats;
    ++frame_;
    oldBox_ = oldBox;
    newBox_ = newBox;
    moved_ = moved;
    layersChanged_ = layersChanged;
    candidates_.clear();
    modified_.clear();
    shaftTests_ = 0;
    reinstated_ = 0;
    budgetReinstated_ = 0;
    linkStamp_.resize(links_.slots(), 0);
    prunePending();
    const std::size_t budget = settings.budget.value_or(kUnlimited);
    stats.budget = budget;

    // 1. Line-space traversal: candidates, reinstated p-links, cleanup; under
    //    a budget, the controlled descent of Fig. 8.
    recomputeSeconds_ = 0.0;
    findModifiedLinks();
    const std::size_t used = controlledUpdate(0, budget);
    // The link recomputes the traversal waited for are link updates.
    stats.traversalSeconds = since(start) - recomputeSeconds_;
    stats.shaftTests = shaftTests_;
    stats.reinstated = reinstated_;
    stats.budgetReinstated = budgetReinstated_;
    stats.spent = used;

    // 2. Link update with in-place gather, and refinement from a heap with
    //    what is left of the budget.
    auto t = std::chrono::steady_clock::now();
    updateCandidates(stats, budget == kUnlimited ? kUnlimited : (budget > used ? budget - used : 0));
    stats.updateSeconds = since(t) + recomputeSeconds_;

    // 3. Partial push-pull, then further bounces where radiosity changed.
    t = std::chrono::steady_clock::now();
    std::vector<ElementId> visited = solver_.partialPushPull(refiner_.takeDirty());
    stats.changedElements = visited.size();
    // The overlay on the other core: it reads positions and link ends, the
    // bounces write radiosity and irradiance.
    tbb::task_group overlay;
    overlay.run([this, changed = visited] { recordOverlay(changed); });
    touched_.assign(visited.begin(), visited.end());
    bounce(std::move(visited), settings, stats);
    overlay.wait();
    // 4. Refinement follows the light: links from elements whose oracle
    //    stepped are judged again, with what is left of the budget.
    followTheLight(settings, stats, budget == kUnlimited ? kUnlimited : (budget > stats.spent ? budget - stats.spent : 0));
    stats.pushPullSeconds = since(t);

    obstacles_.clear();
    finish(stats, start);
    return stats;
}

void LineSpaceUpdate::recordOverlay(const std::vector<ElementId>& changed) {
    // Bounded: a display of more segments than this says nothing more.
    constexpr std::size_t kMaxSegments = 200'000;
    modifiedSegments_.clear();
    changedSegments_.clear();
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
    // Top-down: a reinstated p-link takes its line-space children with it.
    std::vector<ElementId> stack{h_.root()};
    while (!stack.empty()) {
        const ElementId e = stack.back();
        stack.pop_back();
        for (LinkId pl : std::vector<LinkId>(h_[e].plinks)) {
            const Link& l = links_[pl];
            if (l.live && l.passive && l.receiver == e && !refiner_.wouldRefine(l)) reinstate(pl);
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
    stats.links = 0;
    for (ElementId e = 0; e < h_.size(); ++e) stats.links += h_[e].links.size();
    stats.elements = h_.liveCount();
    stats.pending = pending_.size();
    stats.totalSeconds = since(start);
}

FrameStats LineSpaceUpdate::refinePending(const UpdateSettings& settings) {
    const auto start = std::chrono::steady_clock::now();
    FrameStats stats;
    const std::size_t budget = settings.budget.value_or(kUnlimited);
    stats.budget = budget;
    RefineHeap heap;
    std::vector<LinkId> pending;
    prunePending();
    pending.swap(pending_);
    for (LinkId id : pending) heap.push({heapKey(links_[id]), id});
    refineFromHeap(heap, stats, budget);
    stats.updateSeconds = since(start);
    const auto t = std::chrono::steady_clock::now();
    std::vector<ElementId> visited = solver_.partialPushPull(refiner_.takeDirty());
    stats.changedElements = visited.size();
    touched_.assign(visited.begin(), visited.end());
    bounce(std::move(visited), settings, stats);
    followTheLight(settings, stats, budget == kUnlimited ? kUnlimited : (budget > stats.spent ? budget - stats.spent : 0));
    stats.pushPullSeconds = since(t);
    finish(stats, start);
    return stats;
}

void LineSpaceUpdate::followTheLight(const UpdateSettings& settings, FrameStats& stats, std::size_t budget) {
    std::sort(touched_.begin(), touched_.end());
    touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
    const std::vector<ElementId> moved = stepOracles(h_, touched_, kOracleFloor * referenceRadiosity_);
    touched_.clear();
    if (moved.empty()) return;
    const std::size_t spentBefore = stats.spent;
    RefineHeap heap;
    for (ElementId s : moved) {
        for (LinkId id : h_[s].outLinks)
            if (refiner_.wouldRefine(links_[id])) heap.push({heapKey(links_[id]), id});
        // Refinement its new oracle no longer asks for goes (its line-space
        // children with it).
        for (LinkId id : std::vector<LinkId>(h_[s].outPlinks)) {
            const Link& l = links_[id];
            if (l.live && l.passive && l.source == s && !refiner_.wouldRefine(l)) {
                reinstate(id);
                ++stats.reinstated;
                ++stats.spent;
            }
        }
    }
    const std::size_t used = stats.spent - spentBefore;
    refineFromHeap(heap, stats, budget == kUnlimited ? kUnlimited : (budget > used ? budget - used : 0));
    // The light that the new links carry, once around.
    std::vector<ElementId> visited = solver_.partialPushPull(refiner_.takeDirty());
    stats.changedElements += visited.size();
    bounce(std::move(visited), settings, stats);
    touched_.clear();  // what moved now is stepped at the next frame
}

bool LineSpaceUpdate::affectedByMotion(ElementId s, ElementId r) {
    // Both ends on the object: a rigid motion changes neither the form factor
    // nor the object's occlusion of its own parts; only static geometry in
    // the object (the obstacles) can come between them.
    if (!layersChanged_ && moved_.contains(h_[s].range) && moved_.contains(h_[r].range)) {
        const Aabb& a = h_[s].box;
        const Aabb& b = h_[r].box;
        const auto near = [&](const Aabb& o) { return Shaft::hullMeets(a, b, o); };
        if (obstacles_.empty()) return false;
        ++shaftTests_;
        if (std::none_of(obstacles_.begin(), obstacles_.end(), near)) return false;
        const Shaft shaft(a, b);
        return std::any_of(obstacles_.begin(), obstacles_.end(),
                           [&](const Aabb& o) { return near(o) && shaft.intersects(o); });
    }
    if (touches(moved_, h_[s].range) || touches(moved_, h_[r].range)) return true;
    ++shaftTests_;
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

void LineSpaceUpdate::recompute(LinkId id) {
    Link& l = links_[id];
    // A p-link refined whatever its visibility is judged without rays; they
    // are cast if it is ever made active again. Nearly every affected p-link
    // has a cluster end and is refined (measured in office: 3,843 of the
    // 4,365 per frame), and its rays were half the link recomputes.
    const auto lazy = [&] { return l.passive && refiner_.refinesAtAnyVisibility(l); };
    if (layersChanged_ || touches(moved_, h_[l.source].range) || touches(moved_, h_[l.receiver].range)) {
        // An end moved: its form factor and both visibility parts change.
        const Link fresh = refiner_.computeUnoccluded(l.source, l.receiver);
        l.unoccluded = fresh.unoccluded;
        l.spread = fresh.spread;
        l.visStale = true;
        if (!lazy()) refiner_.refreshVisibility(l);
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

void LineSpaceUpdate::findModifiedLinks() {
    // Level by level, so that the affected p-links of a whole level are
    // recomputed in one parallel batch: a single node has too few to keep
    // both cores busy. The levels' subtrees are disjoint, and the visits of
    // one node (one per group of its parent) have disjoint source ranges, so
    // nothing one visit does reaches the links another visit looks at.
    // Each level's candidates are recomputed in the background, on the core
    // the serial traversal leaves idle: the traversal only removes links below
    // the visits still to come, never a candidate, and reads none of the
    // fields a recompute writes.
    visits_.assign(1, Visit{});
    std::vector<Step> level{Step{h_.root(), h_[h_.root()].range, 0}}, next;
    std::vector<LinkId> affected;
    std::vector<std::size_t> firstAffected;  // per step: where its affected p-links start
    tbb::task_group background;
    while (!level.empty()) {
        affected.clear();
        firstAffected.clear();
        for (const Step& step : level) {
            firstAffected.push_back(affected.size());
            for (LinkId pl : h_[step.he].plinks) {
                const ElementId q = links_[pl].source;  // the "source" node
                if (step.ind.contains(h_[q].range) && affectedByMotion(q, step.he)) affected.push_back(pl);
            }
        }
        firstAffected.push_back(affected.size());
        // The shaft tests are cheap, the new transfers are not. Isolated: a
        // background recompute must not hold up the level's decisions.
        const auto t = std::chrono::steady_clock::now();
        tbb::this_task_arena::isolate([&] {
            tbb::parallel_for(std::size_t(0), affected.size(), [&](std::size_t i) { recompute(affected[i]); });
        });
        recomputeSeconds_ += since(t);
        next.clear();
        const std::size_t firstCandidate = candidates_.size();
        for (std::size_t i = 0; i < level.size(); ++i) {
            const std::span<const LinkId> own(affected.data() + firstAffected[i], affected.data() + firstAffected[i + 1]);
            visitNode(level[i], own, next);
        }
        background.run([this, batch = std::vector<LinkId>(candidates_.begin() + firstCandidate, candidates_.end())] {
            tbb::parallel_for(std::size_t(0), batch.size(), [&](std::size_t i) { recompute(batch[i]); });
        });
        level.swap(next);
    }
    const auto t = std::chrono::steady_clock::now();
    background.wait();
    recomputeSeconds_ += since(t);
    // Pull the work up (sec. 6.1): a visit's children come after it.
    for (std::size_t i = visits_.size(); i-- > 0;) {
        Visit& v = visits_[i];
        v.work = v.own;
        for (Group& g : v.groups) {
            for (std::size_t child : g.visits) g.work += visits_[child].work;
            v.work += g.work;
        }
    }
}

void LineSpaceUpdate::visitNode(const Step& step, std::span<const LinkId> affected, std::vector<Step>& next) {
    const ElementId he = step.he;
    std::vector<LinkId> refining;  // p-links whose line-space children are visited
    for (LinkId pl : affected) {
        const Link& l = links_[pl];
        // A reinstate earlier in this loop may have removed it.
        if (!l.live || !l.passive || l.receiver != he) continue;
        if (refiner_.wouldRefine(l))
            refining.push_back(pl);
        else
            reinstate(pl);
    }
    // A reinstate later in the loop may have removed an earlier p-link (one of
    // its line-space children).
    std::erase_if(refining, [&](LinkId pl) { return !links_[pl].live || !links_[pl].passive; });
    visits_[step.visit].own = affected.size() + checkAddLinks(he, step.ind);

    // Descend once per maximal range: a p-link refined by splitting its source
    // leaves p-links from q's children on he itself, whose ranges lie inside
    // q's; visiting the children for each of them again would repeat the same
    // traversal.
    std::sort(refining.begin(), refining.end(), [&](LinkId a, LinkId b) {
        const IndexRange& ra = h_[links_[a].source].range;
        const IndexRange& rb = h_[links_[b].source].range;
        return ra.first < rb.first || (ra.first == rb.first && ra.last > rb.last);
    });
    std::vector<Group> groups;
    for (LinkId pl : refining) {
        const IndexRange& r = h_[links_[pl].source].range;
        if (groups.empty() || !groups.back().range.contains(r)) groups.push_back(Group{r, {}, 0.0, false, {}, 0});
        Group& g = groups.back();
        g.plinks.push_back(pl);
        g.transfer += heapKey(links_[pl]);
        // Links with a cluster end are descended whatever the budget: the
        // isotropic cluster approximation would stand in for a whole refined
        // subtree and lose (or make) light where clusters are not isotropic
        // (measured on the Cornell box: a third of the absorbed power). Only
        // surface pairs, whose form factors are accurate, become coarser.
        g.mustDescend = g.mustDescend || !h_[links_[pl].source].isSurface() || !h_[he].isSurface();
    }
    for (Group& g : groups)
        for (ElementId c : h_[he].children) {
            // No link from the range on c means no line-space child of it below c.
            if (!hasLinkFrom(c, g.range)) continue;
            g.visits.push_back(visits_.size());
            next.push_back(Step{c, g.range, visits_.size()});
            visits_.emplace_back();
        }
    visits_[step.visit].groups = std::move(groups);
}

std::size_t LineSpaceUpdate::controlledUpdate(std::size_t index, std::size_t budget) {
    Visit& v = visits_[index];
    // The links of the current node first (Fig. 8): what is above is then up
    // to date whatever happens below.
    std::size_t used = v.own;
    if (budget == kUnlimited || v.work <= budget) return v.work;  // everything below fits
    std::size_t remaining = budget > used ? budget - used : 0;
    // The groups that must be descended first, then the largest transfers,
    // as long as the work pulled up from below fits.
    std::vector<Group*> order;
    for (Group& g : v.groups) order.push_back(&g);
    std::stable_sort(order.begin(), order.end(), [](const Group* a, const Group* b) {
        return a->mustDescend != b->mustDescend ? a->mustDescend : a->transfer > b->transfer;
    });
    std::vector<Group*> descend;
    for (Group* g : order) {
        if (g->mustDescend || g->work <= remaining) {
            descend.push_back(g);
            continue;
        }
        // Not enough budget to go down: the coarser links stand instead (still
        // a complete covering of line space), refined when budget allows.
        // Their line-space children, candidates included, go.
        for (LinkId pl : g->plinks) {
            if (!links_[pl].live || !links_[pl].passive) continue;
            reinstate(pl);
            ++budgetReinstated_;
            pending_.push_back(pl);
            ++used;
        }
    }
    remaining = budget > used ? budget - used : 0;
    std::size_t need = 0;
    for (const Group* g : descend) need += g->work;
    for (const Group* g : descend)
        for (std::size_t child : g->visits) {
            // Each child gets the part of the budget its pulled-up work calls for.
            const std::size_t share =
                need == 0 ? 0 : static_cast<std::size_t>(double(remaining) * double(visits_[child].work) / double(need));
            used += controlledUpdate(child, share);
        }
    return used;
}

// Links made during the frame (refinement) have ids past the stamps sized
// when it began.
bool LineSpaceUpdate::stampedThisFrame(LinkId id) const { return id < linkStamp_.size() && linkStamp_[id] == frame_; }

void LineSpaceUpdate::stamp(LinkId id) {
    if (id >= linkStamp_.size()) linkStamp_.resize(links_.slots(), 0);
    linkStamp_[id] = frame_;
}

bool LineSpaceUpdate::hasLinkFrom(ElementId e, const IndexRange& sources) const {
    const auto from = [&](LinkId id) { return sources.contains(h_[links_[id].source].range.first); };
    return std::any_of(h_[e].links.begin(), h_[e].links.end(), from) ||
           std::any_of(h_[e].plinks.begin(), h_[e].plinks.end(), from);
}

std::size_t LineSpaceUpdate::checkAddLinks(ElementId he, const IndexRange& ind) {
    std::size_t added = 0;
    for (LinkId id : h_[he].links) {
        const ElementId s = links_[id].source;
        if (stampedThisFrame(id) || !ind.contains(h_[s].range)) continue;
        if (!affectedByMotion(s, he)) continue;
        stamp(id);
        candidates_.push_back(id);
        ++added;
    }
    return added;
}

void LineSpaceUpdate::reinstate(LinkId id) {
    const ElementId he = links_[id].receiver;
    const IndexRange sources = h_[links_[id].source].range;
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
        if (sources.contains(h_[links_[id].source].range.first)) doomed_.push_back(id);
    for (LinkId id : h_[e].plinks)
        if (id != keep && sources.contains(h_[links_[id].source].range.first)) {
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


void LineSpaceUpdate::updateCandidates(FrameStats& stats, std::size_t budget) {
    RefineHeap heap;
    // Drop candidates a reinstate under the budget removed; the traversal
    // recomputed them all.
    std::erase_if(candidates_, [&](LinkId id) { return !links_[id].live || links_[id].passive; });
    for (LinkId id : candidates_) {
        ++stats.candidates;
        if (refiner_.wouldRefine(links_[id])) {
            double key = heapKey(links_[id]);
            // Sec. 6.2: the object entering a shaft it did not cut before makes
            // refinement there more urgent.
            const Link& l = links_[id];
            if (!touches(moved_, h_[l.source].range) && !touches(moved_, h_[l.receiver].range) &&
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
    std::size_t left = budget;
    while (!heap.empty()) {
        batch.clear();
        std::size_t cost = 0;
        while (!heap.empty()) {
            const LinkId id = heap.top().second;
            if (!links_[id].live || links_[id].passive) {
                heap.pop();
                continue;
            }
            const std::size_t c = refiner_.childCount(links_[id]);
            if (budget != kUnlimited && cost + c > left) break;
            heap.pop();
            batch.push_back(id);
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
    }
    // Out of budget: the rest stay at their level with their new form factors
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

void LineSpaceUpdate::bounce(std::vector<ElementId> visited, const UpdateSettings& settings, FrameStats& stats) {
    const double threshold = settings.bounceThreshold * referenceRadiosity_;
    std::vector<Transfer> transfers;
    // What a receiver got that could not yet move its radiosity by the
    // threshold waits here instead of pushing its subtree at every bounce
    // (a cluster's push walks all of its members); one push at the end
    // takes it all in.
    std::vector<ElementId> waiting;
    for (int b = 0; b < settings.maxBounces; ++b) {
        if (!collectTransfers(visited, threshold, transfers)) break;
        // In the serial order, so that every irradiance gets the same sum.
        // Bound by memory: the receivers a few transfers ahead are asked for early.
        constexpr std::size_t kAhead = 8;
        for (std::size_t k = 0; k < transfers.size(); ++k) {
            if (k + kAhead < transfers.size()) {
                const HElement& ahead = h_[transfers[k + kAhead].receiver];
                __builtin_prefetch(&ahead.irradiance);
                __builtin_prefetch(&ahead.dirty);
            }
            const Transfer& t = transfers[k];
            HElement& r = h_[t.receiver];
            if (r.isSurface())
                r.irradiance += t.irradiance;
            else
                addTransfer(h_, t.receiver, t.source, t.irradiance);
            if (r.dirty) continue;
            // The most the receiver's radiosity can move (a cluster's
            // members reflect at most all of it).
            const glm::dvec3 moved = r.isSurface() ? r.reflectance * t.irradiance : t.irradiance;
            if (waitingChange_.size() < h_.size()) waitingChange_.resize(h_.size(), -1.0);
            double& sum = waitingChange_[t.receiver];
            if (sum < 0.0) {
                waiting.push_back(t.receiver);
                sum = 0.0;
            }
            sum += std::abs(luminance(moved));
            if (sum > threshold) refiner_.markDirty(t.receiver);
        }
        ++stats.bounces;
        std::erase_if(waiting, [&](ElementId e) {
            if (!h_[e].dirty) return false;
            waitingChange_[e] = -1.0;  // pushed now
            return true;
        });
        visited = solver_.partialPushPull(refiner_.takeDirty());
        stats.changedElements += visited.size();
        touched_.insert(touched_.end(), visited.begin(), visited.end());
    }
    if (waiting.empty()) return;
    for (ElementId e : waiting) {
        waitingChange_[e] = -1.0;
        refiner_.markDirty(e);
    }
    visited = solver_.partialPushPull(refiner_.takeDirty());
    stats.changedElements += visited.size();
    touched_.insert(touched_.end(), visited.begin(), visited.end());
}

bool LineSpaceUpdate::collectTransfers(const std::vector<ElementId>& visited, double threshold,
                                       std::vector<Transfer>& transfers) {
    // The senders and their transfers are found on all cores: reading the
    // elements and links is most of a bounce.
    std::vector<char> sends(visited.size());
    tbb::parallel_for(std::size_t(0), visited.size(), [&](std::size_t i) {
        const ElementId id = visited[i];
        const HElement& el = h_[id];
        if (el.outLinks.empty()) return;
        if (el.isSurface()) {
            sends[i] = std::abs(luminance(el.radiosity - el.gathered)) > threshold;
            return;
        }
        // A cluster sends by facet: any facet's radiosity that moved.
        const ClusterShape& shape = h_.shape(id);
        for (int k = 0; k < shape.facetCount && !sends[i]; ++k)
            sends[i] = shape.facets[k].area > 0.0 &&
                       std::abs(luminance(shape.power[k] - shape.gathered[k])) > threshold * shape.facets[k].area;
    });
    std::vector<ElementId> sources;
    std::vector<std::size_t> first;  // per source: where its transfers start
    std::size_t count = 0;
    for (std::size_t i = 0; i < visited.size(); ++i) {
        if (!sends[i]) continue;
        sources.push_back(visited[i]);
        first.push_back(count);
        count += h_[visited[i]].outLinks.size();
    }
    transfers.resize(count);
    tbb::parallel_for(std::size_t(0), sources.size(), [&](std::size_t k) {
        HElement& el = h_[sources[k]];
        // In-place gather of the difference on every link leaving the source.
        const glm::dvec3 delta = el.radiosity - el.gathered;
        ClusterShape::Powers facetDelta{};
        if (el.shape != kNone) {
            ClusterShape& shape = h_.shape(sources[k]);
            for (int f = 0; f < shape.facetCount; ++f) facetDelta[f] = shape.power[f] - shape.gathered[f];
            shape.gathered = shape.power;
        }
        for (std::size_t j = 0; j < el.outLinks.size(); ++j) {
            const Link& l = links_[el.outLinks[j]];
            transfers[first[k] + j] = Transfer{l.receiver, l.source, l.gathered * sentChange(h_, l, delta, facetDelta)};
        }
        el.gathered = el.radiosity;
    });
    return !sources.empty();
}

}  // namespace rad
