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
    shaftTests_ = 0;
    reinstated_ = 0;
    linkStamp_.resize(links_.slots(), 0);

    // 1. Line-space traversal: candidates, reinstated p-links, cleanup.
    findModifiedLinks(h_.root(), h_[h_.root()].range);
    stats.traversalSeconds = since(start);
    stats.shaftTests = shaftTests_;
    stats.reinstated = reinstated_;

    // 2. Link update with in-place gather, and refinement from a heap.
    auto t = std::chrono::steady_clock::now();
    updateCandidates(stats);
    stats.updateSeconds = since(t);

    // 3. Partial push-pull, then further bounces where radiosity changed.
    t = std::chrono::steady_clock::now();
    std::vector<ElementId> visited = solver_.partialPushPull(refiner_.takeDirty());
    stats.changedElements = visited.size();
    bounce(std::move(visited), settings, stats);
    stats.pushPullSeconds = since(t);

    stats.links = 0;
    for (ElementId e = 0; e < h_.size(); ++e) stats.links += h_[e].links.size();
    stats.elements = h_.liveCount();
    stats.totalSeconds = since(start);
    return stats;
}

bool LineSpaceUpdate::affectedByMotion(ElementId s, ElementId r) {
    // Both ends on the object: a rigid motion changes neither the form factor
    // nor the object's occlusion of its own parts. (Static geometry that ends
    // up between two of its parts is not seen: the links keep their static
    // visibility.)
    if (!layersChanged_ && moved_.contains(h_[s].range) && moved_.contains(h_[r].range)) return false;
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

void LineSpaceUpdate::findModifiedLinks(ElementId he, const IndexRange& ind) {
    std::vector<IndexRange> descend;  // source ranges whose line-space children lie below
    // The affected p-links of he, recomputed together (in parallel) before
    // any is judged: the shaft tests are cheap, the new transfers are not.
    std::vector<LinkId> affected;
    for (LinkId pl : h_[he].plinks) {
        const ElementId q = links_[pl].source;  // the "source" node
        if (ind.contains(h_[q].range) && affectedByMotion(q, he)) affected.push_back(pl);
    }
    tbb::parallel_for(std::size_t(0), affected.size(), [&](std::size_t i) { recompute(affected[i]); });
    for (LinkId pl : affected) {
        const Link& l = links_[pl];
        // A reinstate earlier in this loop may have removed it.
        if (!l.live || !l.passive || l.receiver != he) continue;
        if (refiner_.wouldRefine(l))
            descend.push_back(h_[l.source].range);
        else
            reinstate(pl);
    }
    // Descend once per maximal range: a p-link refined by splitting its
    // source leaves p-links from q's children on he itself, whose ranges lie
    // inside q's; visiting the children for each of them again would repeat
    // the same traversal.
    std::sort(descend.begin(), descend.end(),
              [](const IndexRange& a, const IndexRange& b) { return a.first < b.first || (a.first == b.first && a.last > b.last); });
    std::vector<IndexRange> maximal;
    for (const IndexRange& r : descend)
        if (maximal.empty() || !maximal.back().contains(r)) maximal.push_back(r);
    for (const IndexRange& range : maximal)
        for (ElementId c : std::vector<ElementId>(h_[he].children)) findModifiedLinks(c, range);
    checkAddLinks(he, ind);
}

void LineSpaceUpdate::checkAddLinks(ElementId he, const IndexRange& ind) {
    for (LinkId id : h_[he].links) {
        const ElementId s = links_[id].source;
        if (linkStamp_[id] == frame_ || !ind.contains(h_[s].range)) continue;
        if (!affectedByMotion(s, he)) continue;
        linkStamp_[id] = frame_;
        candidates_.push_back(id);
    }
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

void LineSpaceUpdate::updateCandidates(FrameStats& stats) {
    // Sec. 5.2: the link with the highest potential power transfer is refined first.
    RefineHeap heap;
    // Drop candidates a reinstate removed; recompute the rest on all cores
    // (each writes only its own link; the geometry and the rays are read-only).
    std::erase_if(candidates_, [&](LinkId id) { return !links_[id].live || links_[id].passive; });
    tbb::parallel_for(std::size_t(0), candidates_.size(), [&](std::size_t i) { recompute(candidates_[i]); });
    for (LinkId id : candidates_) {
        ++stats.candidates;
        if (refiner_.wouldRefine(links_[id])) {
            heap.push({heapKey(links_[id]), id});
        } else {
            refiner_.regather(id);  // eq. 1
            ++stats.linksUpdated;
        }
    }
    refineFromHeap(heap, stats);
}

void LineSpaceUpdate::refineFromHeap(RefineHeap& heap, FrameStats& stats) {
    // Without a budget every link in the heap is refined: take them all as one
    // batch (highest transfer first) so the new links are computed in parallel.
    std::vector<LinkId> batch, created;
    while (!heap.empty()) {
        batch.clear();
        while (!heap.empty()) {
            const LinkId id = heap.top().second;
            heap.pop();
            if (links_[id].live && !links_[id].passive) batch.push_back(id);
        }
        created.clear();
        refiner_.refine(batch, created);  // eq. 2 for the parents, new transfers for the children
        stats.refined += batch.size();
        stats.linksUpdated += batch.size();
        for (LinkId c : created)
            if (refiner_.wouldRefine(links_[c])) heap.push({heapKey(links_[c]), c});
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
