#include "refine/Refiner.h"

#include <algorithm>
#include <cmath>
#include <span>

#include <tbb/parallel_for.h>

#include "geometry/RayCaster.h"
#include "links/FormFactor.h"

namespace rad {
namespace {

double radius(const HElement& e) { return 0.5 * glm::length(e.box.extent()); }

// Moves a ray end a little off its surface so that it does not start inside
// a neighbouring polygon that meets this one at an edge.
glm::dvec3 lift(const glm::dvec3& p, const glm::dvec3& normal, double size) { return p + 1e-4 * size * normal; }

// Link lists are sets: removal swaps the last entry in (a light can hold
// thousands of outgoing links; shifting them on every removal would not do).
void unorderedErase(std::vector<LinkId>& list, LinkId id) {
    const auto it = std::find(list.begin(), list.end(), id);
    *it = list.back();
    list.pop_back();
}

}  // namespace

Refiner::Refiner(Hierarchy& hierarchy, LinkStore& links, const RayCaster& rays, RefineSettings settings)
    : h_(hierarchy), links_(links), rays_(rays), settings_(settings) {
    clusterSamples_.resize(h_.size());
    refreshClusterSamples(h_.root());
}

void Refiner::refreshClusterSamples(ElementId subtree) {
    const HElement& c = h_[subtree];
    if (c.isSurface()) return;
    for (ElementId k : c.children) refreshClusterSamples(k);
    refreshClusterSample(subtree);
}

void Refiner::refreshClusterSample(ElementId cluster) {
    // The input polygons below this cluster, with their cumulative area.
    std::vector<ElementId> surfaces;
    std::vector<ElementId> stack{cluster};
    while (!stack.empty()) {
        const ElementId e = stack.back();
        stack.pop_back();
        if (h_[e].isSurface()) surfaces.push_back(e);
        else for (ElementId k : h_[e].children) stack.push_back(k);
    }
    if (surfaces.empty()) return;
    std::sort(surfaces.begin(), surfaces.end());
    std::vector<double> cumulative;
    double total = 0.0;
    for (ElementId s : surfaces) cumulative.push_back(total += h_[s].area);
    if (clusterSamples_.size() <= cluster) clusterSamples_.resize(h_.size());
    std::array<glm::dvec3, 4>& out = clusterSamples_[cluster];
    for (int k = 0; k < 4; ++k) {
        const double target = (k + 0.5) / 4.0 * total;
        const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
        const HElement& s = h_[surfaces[std::min<std::size_t>(it - cumulative.begin(), surfaces.size() - 1)]];
        out[k] = lift(s.center, s.normal, std::sqrt(s.area));
    }
}

bool Refiner::touchesMovable(ElementId e) const {
    const IndexRange& r = h_[e].range;
    for (ElementId m : h_.movableClusters()) {
        const IndexRange& mr = h_[m].range;
        if (mr.contains(r) || r.contains(mr)) return true;
    }
    return false;
}

Refiner::Points Refiner::samplePoints(ElementId id) const {
    const HElement& e = h_[id];
    Points points;
    if (!e.isSurface()) {
        for (const glm::dvec3& p : clusterSamples_[id]) points.p[points.n++] = p;
        return points;
    }
    const int order = std::clamp(static_cast<int>(std::lround(std::sqrt(settings_.samplesPerElement))), 1, 4);
    for (const SamplePoint& s : patchSamples(e.patch, order))
        if (points.n < kMaxPoints) points.p[points.n++] = lift(s.p, e.normal, std::sqrt(e.area));
    return points;
}

bool Refiner::admissible(ElementId s, ElementId r) const {
    const HElement& a = h_[s];
    const HElement& b = h_[r];
    if (a.isSurface() && b.isSurface()) return true;
    if (s == r) return false;
    const double reach = radius(a) + radius(b);
    const glm::dvec3 d = b.center - a.center;
    return glm::dot(d, d) > reach * reach * (1.0 + 1e-9);
}

FormFactorEstimate Refiner::unoccludedFormFactor(ElementId s, ElementId r) const {
    const HElement& src = h_[s];
    const HElement& rcv = h_[r];
    if (src.isSurface() && rcv.isSurface()) {
        if (src.polygon == rcv.polygon) return {};  // one plane
        // Close pairs need more quadrature points: the integrand varies fast.
        const double reach = radius(src) + radius(rcv);
        const glm::dvec3 d = rcv.center - src.center;
        const int order = glm::dot(d, d) < 4.0 * reach * reach ? 5 : 3;
        // Integrate over the smaller patch (the inner integral over the other
        // is exact) and use reciprocity, A_r F_rs = A_s F_sr: sampling the
        // larger patch would miss the peak of a small neighbour's kernel.
        FormFactorEstimate e = estimateFormFactor(rcv.patch, src.patch, rcv.area > src.area ? 2 : order);
        if (rcv.area > src.area) e.mean = src.area / rcv.area * estimateFormFactor(src.patch, rcv.patch, order).mean;
        return e;
    }
    const glm::dvec3 d = rcv.center - src.center;
    const double d2 = glm::dot(d, d);
    if (!(d2 > 0.0)) return {};
    const glm::dvec3 dir = d / std::sqrt(d2);
    const double gs = src.isSurface() ? std::max(0.0, glm::dot(src.normal, dir)) : 0.25;
    const double gr = rcv.isSurface() ? std::max(0.0, -glm::dot(rcv.normal, dir)) : 0.25;
    const double f = pointApproxFormFactor(src.area, gs, gr, d2);
    return {f, f, f};
}

Link Refiner::compute(ElementId s, ElementId r) const {
    Link l = computeUnoccluded(s, r);
    if (l.live) refreshVisibility(l);
    return l;
}

void Refiner::refreshVisibility(Link& l) const {
    l.visStale = false;
    l.visStatic = l.visDynamic = 1.0f;
    if (!(l.unoccluded > 0.0)) return;
    Segments seg;
    segments(l.source, l.receiver, seg);
    l.visStatic = static_cast<float>(unoccluded(Layer::Static, seg));
    l.visDynamic = static_cast<float>(unoccluded(Layer::Dynamic, seg));
}

bool Refiner::refinesAtAnyVisibility(const Link& link) const {
    if (chooseSplit(link) == Split::None) return false;
    if (!admissible(link.source, link.receiver)) return true;
    // wouldRefine's bound is at least this for a cluster end, whatever v.
    const bool clusterEnd = !h_[link.source].isSurface() || !h_[link.receiver].isSurface();
    return clusterEnd && h_[link.source].oracle * h_[link.receiver].area * link.unoccluded >
                             settings_.epsilon * settings_.referencePower * (1.0 + 1e-9);
}

Link Refiner::computeUnoccluded(ElementId s, ElementId r) const {
    Link l;
    l.source = s;
    l.receiver = r;
    const FormFactorEstimate f = unoccludedFormFactor(s, r);
    l.unoccluded = f.mean;
    l.spread = static_cast<float>(f.max - f.min);
    const bool dynamic = touchesMovable(s) || touchesMovable(r);
    // A cluster pair that is not admissible still needs its link: it is refined next.
    const bool mustRefine = !admissible(s, r);
    if (l.unoccluded <= 0.0 && !dynamic && !mustRefine) return l;  // not live: never carries light
    l.live = true;
    l.visStale = l.unoccluded > 0.0;
    return l;
}

void Refiner::segments(ElementId s, ElementId r, Segments& out) const {
    const Points ps = samplePoints(s), pr = samplePoints(r);
    out.n = 0;
    for (std::size_t i = 0; i < ps.n; ++i)
        for (std::size_t j = 0; j < pr.n; ++j) {
            out.from[out.n] = ps.p[i];
            out.to[out.n++] = pr.p[j];
        }
}

double Refiner::unoccluded(Layer layer, const Segments& s) const {
    return rays_.unoccludedFraction(layer, std::span(s.from.data(), s.n), std::span(s.to.data(), s.n));
}

float Refiner::dynamicVisibility(ElementId s, ElementId r) const {
    Segments seg;
    segments(s, r, seg);
    return static_cast<float>(unoccluded(Layer::Dynamic, seg));
}

LinkId Refiner::attach(const Link& link) {
    const LinkId id = links_.add(link);
    links_[id].passive = true;  // activate() expects a p-link
    h_[link.receiver].plinks.push_back(id);
    activate(id);
    return id;
}

void Refiner::activate(LinkId id) {
    Link& l = links_[id];
    HElement& r = h_[l.receiver];
    unorderedErase(r.plinks, id);
    r.links.push_back(id);
    h_[l.source].outLinks.push_back(id);
    l.passive = false;
    if (l.visStale) refreshVisibility(l);
    l.gathered = l.formFactor();
    // In-place gather (eq. 1): the receiver now holds this link's transfer.
    r.irradiance += l.gathered * h_[l.source].gathered;
    markDirty(l.receiver);
}

void Refiner::deactivate(LinkId id) {
    Link& l = links_[id];
    HElement& r = h_[l.receiver];
    // Eq. 2: take back what the receiver gathered through this link.
    r.irradiance -= l.gathered * h_[l.source].gathered;
    markDirty(l.receiver);
    l.gathered = 0.0;
    unorderedErase(r.links, id);
    auto& out = h_[l.source].outLinks;
    unorderedErase(out, id);
    r.plinks.push_back(id);
    l.passive = true;
}

void Refiner::regather(LinkId id) {
    Link& l = links_[id];
    HElement& r = h_[l.receiver];
    const double f = l.formFactor();
    r.irradiance += (f - l.gathered) * h_[l.source].gathered;
    markDirty(l.receiver);
    l.gathered = f;
}

void Refiner::markDirty(ElementId e) {
    if (h_[e].dirty) return;
    h_[e].dirty = true;
    dirty_.push_back(e);
}

std::vector<ElementId> Refiner::takeDirty() {
    std::vector<ElementId> out;
    out.swap(dirty_);
    return out;
}

void Refiner::remove(LinkId id) {
    if (!links_[id].passive) deactivate(id);
    HElement& r = h_[links_[id].receiver];
    unorderedErase(r.plinks, id);
    links_.remove(id);
}

void Refiner::linkRoot() {
    const ElementId root = h_.root();
    Link l;
    l.source = l.receiver = root;
    l.live = true;
    attach(l);
}

bool Refiner::canSplit(ElementId e) const {
    const HElement& el = h_[e];
    return el.isSurface() ? h_.canSubdivide(e) : !el.children.empty();
}

Refiner::Split Refiner::chooseSplit(const Link& link) const {
    if (link.source == link.receiver) return canSplit(link.source) ? Split::Both : Split::None;
    const bool cs = canSplit(link.source), cr = canSplit(link.receiver);
    // Equal areas (with a little slack, so a scaled scene decides alike): the receiver.
    if (cs && cr) return h_[link.source].area > h_[link.receiver].area * (1.0 + 1e-9) ? Split::Source : Split::Receiver;
    if (cs) return Split::Source;
    if (cr) return Split::Receiver;
    return Split::None;
}

bool Refiner::wouldRefine(const Link& link) const {
    if (chooseSplit(link) == Split::None) return false;
    if (!admissible(link.source, link.receiver)) return true;
    // Partly occluded links are judged by their unoccluded transfer, so that
    // shadow boundaries get refined. So are links with a cluster end whatever
    // their visibility: a cluster's few sample points can all lie on faces
    // hidden from the other end, and a visibility of 0 there must not stop
    // the refinement that would find the faces that do see it.
    const double v = link.visibility();
    const bool clusterEnd = !h_[link.source].isSurface() || !h_[link.receiver].isSurface();
    const double f = (clusterEnd || (v > 0.0 && v < 1.0)) ? link.unoccluded : link.formFactor();
    // BF, and the same bound on how much the transfer varies across the receiver.
    const double bound = h_[link.source].oracle * h_[link.receiver].area *
                         std::max(f, double(link.spread) * v);
    // A little slack: symmetric scenes put many links exactly on the threshold,
    // and the same scene at another scale must not fall on the other side.
    return bound > settings_.epsilon * settings_.referencePower * (1.0 + 1e-9);
}

std::size_t Refiner::childCount(const Link& link) const {
    const auto count = [&](ElementId e) { return h_[e].isSurface() ? std::size_t(4) : h_[e].children.size(); };
    switch (chooseSplit(link)) {
        case Split::None: return 0;
        case Split::Source: return count(link.source);
        case Split::Receiver: return count(link.receiver);
        case Split::Both: return count(link.source) * count(link.source);
    }
    return 0;
}

std::vector<std::pair<ElementId, ElementId>> Refiner::childPairs(const Link& link) {
    std::vector<std::pair<ElementId, ElementId>> pairs;
    const ElementId s = link.source, r = link.receiver;
    switch (chooseSplit(link)) {
        case Split::None:
            break;
        case Split::Source:
            h_.subdivide(s);
            for (ElementId k : h_[s].children) pairs.emplace_back(k, r);
            break;
        case Split::Receiver:
            h_.subdivide(r);
            for (ElementId k : h_[r].children) pairs.emplace_back(s, k);
            break;
        case Split::Both:
            h_.subdivide(s);
            for (ElementId a : h_[s].children)
                for (ElementId b : h_[s].children)
                    if (a != b || !h_[a].isSurface()) pairs.emplace_back(a, b);
            break;
    }
    return pairs;
}

void Refiner::refine(const std::vector<LinkId>& ids, std::vector<LinkId>& created) {
    // Subdivide first (it changes the hierarchy), then compute every new
    // link of the batch on all cores, then attach them in a fixed order.
    std::vector<std::pair<ElementId, ElementId>> pairs;
    for (LinkId id : ids) {
        const auto p = childPairs(links_[id]);
        pairs.insert(pairs.end(), p.begin(), p.end());
    }
    std::vector<Link> computed(pairs.size());
    tbb::parallel_for(std::size_t(0), pairs.size(),
                      [&](std::size_t i) { computed[i] = compute(pairs[i].first, pairs[i].second); });
    for (const Link& l : computed)
        if (l.live) created.push_back(attach(l));
    // The refined links stay as p-links on their receivers.
    for (LinkId id : ids) deactivate(id);
}

std::size_t Refiner::refineAll() {
    std::vector<LinkId> wave;
    for (ElementId e = 0; e < h_.size(); ++e)
        for (LinkId l : h_[e].links) wave.push_back(l);
    return refineAll(std::move(wave));
}

std::size_t Refiner::refineAll(std::vector<LinkId> wave) {
    std::size_t refined = 0;
    while (!wave.empty()) {
        std::vector<LinkId> batch;
        for (LinkId id : wave)
            if (wouldRefine(links_[id])) batch.push_back(id);
        if (batch.empty()) break;
        if (links_.liveCount() + 4 * batch.size() > settings_.maxLinks) {
            capReached_ = true;
            break;
        }
        wave.clear();
        refine(batch, wave);
        refined += batch.size();
    }
    return refined;
}

}  // namespace rad
