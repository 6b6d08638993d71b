#include "update/LineSpaceUpdate.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>

#include <tbb/parallel_for.h>

#include "geometry/Shaft.h"
#include "refine/Refiner.h"
#include "solve/Solver.h"

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
    visits_.clear();
    findModifiedLinks(h_.root(), h_[h_.root()].range);
    const std::size_t used = controlledUpdate(0, budget);
    stats.traversalSeconds = since(start);
    stats.shaftTests = shaftTests_;
    stats.reinstated = reinstated_;
    stats.budgetReinstated = budgetReinstated_;
    stats.spent = used;

    // 2. Link update with in-place gather, and refinement from a heap with
    //    what is left of the budget.
    auto t = std::chrono::steady_clock::now();
    updateCandidates(stats, budget == kUnlimited ? kUnlimited : (budget > used ? budget - used : 0));
    stats.updateSeconds = since(t);

    // 3. Partial push-pull, then further bounces where radiosity changed.
    t = std::chrono::steady_clock::now();
    std::vector<ElementId> visited = solver_.partialPushPull(refiner_.takeDirty());
    stats.changedElements = visited.size();
    recordOverlay(visited);
    bounce(std::move(visited), settings, stats);
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
    bounce(std::move(visited), settings, stats);
    stats.pushPullSeconds = since(t);
    finish(stats, start);
    return stats;
}

bool LineSpaceUpdate::affectedByMotion(ElementId s, ElementId r) {
    // Both ends on the object: a rigid motion changes neither the form factor
    // nor the object's occlusion of its own parts; only static geometry in
    // the object (the obstacles) can come between them.
    if (!layersChanged_ && moved_.contains(h_[s].range) && moved_.contains(h_[r].range)) {
        if (obstacles_.empty()) return false;
        ++shaftTests_;
        const Shaft shaft(h_[s].box, h_[r].box);
        return std::any_of(obstacles_.begin(), obstacles_.end(), [&](const Aabb& b) { return shaft.intersects(b); });
    }
    if (touches(moved_, h_[s].range) || touches(moved_, h_[r].range)) return true;
    ++shaftTests_;
    // The shaft is built only when tested: storing one per link would cost
    // 256 bytes each.
    const Shaft shaft(h_[s].box, h_[r].box);
    return shaft.intersects(oldBox_) || shaft.intersects(newBox_);
}

void LineSpaceUpdate::recompute(LinkId id) {
    Link& l = links_[id];
    if (layersChanged_ || touches(moved_, h_[l.source].range) || touches(moved_, h_[l.receiver].range)) {
        // An end moved: its form factor and both visibility parts change.
        const Link fresh = refiner_.compute(l.source, l.receiver);
        l.unoccluded = fresh.unoccluded;
        l.spread = fresh.spread;
        l.visStatic = fresh.visStatic;
        l.visDynamic = fresh.visDynamic;
    } else if (l.unoccluded > 0.0) {
        // Two-part visibility: only the dynamic object's part can change.
        l.visDynamic = refiner_.dynamicVisibility(l.source, l.receiver);
    }
}

std::size_t LineSpaceUpdate::findModifiedLinks(ElementId he, const IndexRange& ind) {
    const std::size_t index = visits_.size();
    visits_.push_back(Visit{});
    // The affected p-links of he, recomputed together (in parallel) before
    // any is judged: the shaft tests are cheap, the new transfers are not.
    std::vector<LinkId> affected;
    for (LinkId pl : h_[he].plinks) {
        const ElementId q = links_[pl].source;  // the "source" node
        if (ind.contains(h_[q].range) && affectedByMotion(q, he)) affected.push_back(pl);
    }
    tbb::parallel_for(std::size_t(0), affected.size(), [&](std::size_t i) { recompute(affected[i]); });
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
    const std::size_t own = affected.size() + checkAddLinks(he, ind);

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
    std::size_t work = own;
    for (Group& g : groups) {
        for (ElementId c : std::vector<ElementId>(h_[he].children)) {
            // No link from the range on c means no line-space child of it below c.
            if (linksFrom(c, g.range) == 0) continue;
            const std::size_t child = findModifiedLinks(c, g.range);
            g.visits.push_back(child);
            g.work += visits_[child].work;
        }
        work += g.work;
    }
    Visit& v = visits_[index];
    v.own = own;
    v.work = work;
    v.groups = std::move(groups);
    return index;
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

std::size_t LineSpaceUpdate::linksFrom(ElementId e, const IndexRange& sources) const {
    std::size_t n = 0;
    for (LinkId id : h_[e].links) n += sources.contains(h_[links_[id].source].range.first);
    for (LinkId id : h_[e].plinks) n += sources.contains(h_[links_[id].source].range.first);
    return n;
}

std::size_t LineSpaceUpdate::checkAddLinks(ElementId he, const IndexRange& ind) {
    std::size_t added = 0;
    for (LinkId id : h_[he].links) {
        const ElementId s = links_[id].source;
        if (linkStamp_[id] == frame_ || !ind.contains(h_[s].range)) continue;
        if (!affectedByMotion(s, he)) continue;
        linkStamp_[id] = frame_;
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
        for (ElementId c : h_[he].children) unlinked = unlinked && subtreeUnlinked(c);
        if (unlinked) h_.removeChildren(he);
    }
    refiner_.activate(id);
    modified_.push_back(id);
    linkStamp_[id] = frame_;  // already recomputed: not a candidate again
    ++reinstated_;
}

void LineSpaceUpdate::removeLineSpaceChildren(ElementId e, const IndexRange& sources, LinkId keep) {
    for (LinkId id : std::vector<LinkId>(h_[e].links))
        if (sources.contains(h_[links_[id].source].range.first)) refiner_.remove(id);
    for (LinkId id : std::vector<LinkId>(h_[e].plinks))
        if (id != keep && sources.contains(h_[links_[id].source].range.first)) refiner_.remove(id);
    for (ElementId c : h_[e].children) removeLineSpaceChildren(c, sources, keep);
}

bool LineSpaceUpdate::subtreeUnlinked(ElementId e) const {
    const HElement& el = h_[e];
    if (!el.links.empty() || !el.plinks.empty() || !el.outLinks.empty()) return false;
    for (ElementId c : el.children)
        if (!subtreeUnlinked(c)) return false;
    return true;
}

void LineSpaceUpdate::updateCandidates(FrameStats& stats, std::size_t budget) {
    RefineHeap heap;
    // Drop candidates a reinstate removed; recompute the rest on all cores
    // (each writes only its own link; the geometry and the rays are read-only).
    std::erase_if(candidates_, [&](LinkId id) { return !links_[id].live || links_[id].passive; });
    tbb::parallel_for(std::size_t(0), candidates_.size(), [&](std::size_t i) { recompute(candidates_[i]); });
    for (LinkId id : candidates_) {
        ++stats.candidates;
        if (refiner_.wouldRefine(links_[id])) {
            double key = heapKey(links_[id]);
            // Sec. 6.2: the object entering a shaft it did not cut before makes
            // refinement there more urgent.
            const Link& l = links_[id];
            if (!touches(moved_, h_[l.source].range) && !touches(moved_, h_[l.receiver].range)) {
                const Shaft shaft(h_[l.source].box, h_[l.receiver].box);
                if (!shaft.intersects(oldBox_)) key *= kEnteringBoost;
            }
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

double LineSpaceUpdate::heapKey(const Link& l) const {
    return luminance(h_[l.source].gathered) * l.unoccluded * h_[l.receiver].area;
}

void LineSpaceUpdate::bounce(std::vector<ElementId> visited, const UpdateSettings& settings, FrameStats& stats) {
    const double threshold = settings.bounceThreshold * referenceRadiosity_;
    for (int b = 0; b < settings.maxBounces; ++b) {
        bool any = false;
        for (ElementId e : visited) {
            HElement& el = h_[e];
            const glm::dvec3 delta = el.radiosity - el.gathered;
            if (el.outLinks.empty() || std::abs(luminance(delta)) <= threshold) continue;
            // In-place gather of the difference on every link leaving e.
            for (LinkId id : el.outLinks) {
                const Link& l = links_[id];
                h_[l.receiver].irradiance += l.gathered * delta;
                refiner_.markDirty(l.receiver);
            }
            el.gathered = el.radiosity;
            any = true;
        }
        if (!any) return;
        ++stats.bounces;
        visited = solver_.partialPushPull(refiner_.takeDirty());
        stats.changedElements += visited.size();
    }
}

}  // namespace rad
