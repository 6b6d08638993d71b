#include "refine/Refiner.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "links/FormFactor.h"
#include "links/SourceOrder.h"
#include "solve/ClusterTransfer.h"

namespace rad {
namespace {

double radius(const Aabb& box) { return 0.5 * glm::length(box.extent()); }

// Link lists are sets: removal swaps the last entry in (a light can hold
// thousands of outgoing links; shifting them on every removal would not do).
void unorderedErase(IdList& list, LinkId id) {
    const auto it = std::find(list.begin(), list.end(), id);
    // A link missing from its list is a broken hierarchy (a link refined
    // twice); going on would write past the list.
    if (it == list.end()) throw std::logic_error("link " + std::to_string(id) + " is not in the list it is erased from");
    *it = list.back();
    list.pop_back();
}

// A receiver's lists keep their source order (links/SourceOrder.h) when a
// link leaves them.
void orderedErase(IdList& list, LinkId id) {
    const auto it = std::find(list.begin(), list.end(), id);
    if (it == list.end()) throw std::logic_error("link " + std::to_string(id) + " is not in the list it is erased from");
    list.erase(it);
}

// The part of surface `e` in front of the plane of surface `other`, as the
// centroids of its fan's triangles (at most three: a quad cut by a plane has
// at most five corners), each standing for its triangle's area.
SourcePoints frontPart(const Hierarchy& h, ElementId id, ElementId otherId) {
    const HElement& e = h[id];
    const HElement& other = h[otherId];
    const PatchGeometry patch = h.patch(id);
    const glm::dvec3 normal = h.normal(other);
    std::array<glm::dvec3, 8> cut;
    int m = 0;
    const auto height = [&](const glm::dvec3& p) { return glm::dot(normal, p - other.center); };
    for (int k = 0; k < patch.n && m + 2 <= int(cut.size()); ++k) {
        const glm::dvec3 a = patch.v[k], b = patch.v[(k + 1) % patch.n];
        const double ha = height(a), hb = height(b);
        if (ha > 0.0) cut[m++] = a;
        if ((ha > 0.0) != (hb > 0.0)) cut[m++] = a + (b - a) * (ha / (ha - hb));
    }
    SourcePoints out;
    for (int k = 1; k + 1 < m && out.n < SourcePoints::kMax; ++k) {
        const double area = 0.5 * glm::length(glm::cross(cut[k] - cut[0], cut[k + 1] - cut[0]));
        if (!(area > 0.0)) continue;
        out.p[out.n] = (cut[0] + cut[k] + cut[k + 1]) / 3.0;
        out.normal[out.n] = h.normal(e);
        out.polygon[out.n] = e.polygon;
        out.area[out.n++] = area;
    }
    return out;
}

}  // namespace

Refiner::Refiner(Hierarchy& hierarchy, LinkStore& links, const RayCaster& rays, RefineSettings settings)
    : h_(hierarchy), links_(links), rays_(rays), settings_(settings) {}

bool Refiner::touchesMovable(ElementId e) const {
    const IndexRange& r = h_.range(e);
    for (ElementId m : h_.movableClusters()) {
        const IndexRange& mr = h_.range(m);
        if (mr.contains(r) || r.contains(mr)) return true;
    }
    return false;
}

std::size_t Refiner::segments(ElementId s, ElementId r, Segments& out, RayWeights& weights) const {
    const int order = settings_.samplesPerElement >= 4 ? 2 : 1;
    std::size_t n = 0;
    double total = 0.0;
    const auto pair = [&](const SourcePoints& ps, const SourcePoints& pr) {
        n = 0;
        total = 0.0;
        for (int i = 0; i < ps.n; ++i)
            for (int j = 0; j < pr.n; ++j) {
                out[n] = {ps.p[i], pr.p[j], ps.polygon[i], pr.polygon[j]};
                // The point-to-point transfer the ray stands for: A_i A_j cos cos / r^2.
                const glm::dvec3 d = pr.p[j] - ps.p[i];
                const double r2 = glm::dot(d, d);
                const double c = r2 > 0.0 ? std::max(0.0, glm::dot(ps.normal[i], d)) * std::max(0.0, -glm::dot(pr.normal[j], d)) : 0.0;
                weights[n] = r2 > 0.0 ? ps.area[i] * pr.area[j] * c / (r2 * r2) : 0.0;
                total += weights[n++];
            }
    };
    pair(sourcePoints(h_, s, h_.box(r), order), sourcePoints(h_, r, h_.box(s), order));
    // Two surfaces that see each other only between their points (a wall
    // element across an uplight's plane, its points below it): the rays run
    // between the parts of each in front of the other.
    if (!(total > 0.0) && h_[s].isSurface() && h_[r].isSurface()) {
        const SourcePoints fs = frontPart(h_, s, r), fr = frontPart(h_, r, s);
        if (fs.n > 0 && fr.n > 0) pair(fs, fr);
    }
    // Facing nowhere (a pair judged by other points): the rays count alike.
    if (!(total > 0.0) || !std::isfinite(total))
        for (std::size_t i = 0; i < n; ++i) weights[i] = 1.0;
    return n;
}

float Refiner::weightedVisibility(const Link& l, const RayWeights& weights) const {
    double seen = 0.0, total = 0.0;
    for (std::size_t i = 0; i < l.rays; ++i) {
        total += weights[i];
        if (!(((l.blockedStatic | l.blockedDynamic) >> i) & 1u)) seen += weights[i];
    }
    // No ray between the ends (a cluster none of whose points faces the
    // other end): nothing shows that light crosses, so none does.
    return total > 0.0 ? static_cast<float>(seen / total) : 0.0f;
}

namespace {

// Where a box lies with respect to a surface's plane.
enum class Side { Front, Behind, Both };
Side sideOf(const HElement& surface, const glm::dvec3& normal, const Aabb& surfaceBox,
            const Aabb& box) {
    const double tolerance = 1e-9 * glm::length(box.extent() + surfaceBox.extent());
    bool front = false, behind = false;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner((k & 1) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 4) ? box.hi.z : box.lo.z);
        const double h = glm::dot(normal, corner - surface.center);
        front = front || h > tolerance;
        behind = behind || h < -tolerance;
    }
    return front && behind ? Side::Both : front ? Side::Front : Side::Behind;
}

}  // namespace

bool Refiner::admissible(ElementId s, ElementId r) const {
    const HElement& a = h_[s];
    const HElement& b = h_[r];
    if (a.isSurface() && b.isSurface()) return true;
    if (s == r) return false;
    const double reach = radius(h_.box(s)) + radius(h_.box(r));
    const glm::dvec3 d = b.center - a.center;
    return glm::dot(d, d) > reach * reach * (1.0 + 1e-9);
}

bool Refiner::neverCarries(ElementId s, ElementId r) const {
    const HElement& a = h_[s];
    const HElement& b = h_[r];
    // One-sided: a surface sends and receives only in front of itself.
    if (a.isSurface() && sideOf(a, h_.normal(a), h_.box(s), h_.box(r)) == Side::Behind) return true;
    if (b.isSurface() && sideOf(b, h_.normal(b), h_.box(r), h_.box(s)) == Side::Behind) return true;
    return a.isSurface() && b.isSurface() && a.polygon == b.polygon;
}

FormFactorEstimate Refiner::unoccludedFormFactor(ElementId s, ElementId r) const {
    const HElement& src = h_[s];
    const HElement& rcv = h_[r];
    if (src.isSurface() && rcv.isSurface()) {
        if (src.polygon == rcv.polygon) return {};  // one plane
        // Close pairs need more quadrature points: the integrand varies fast.
        const double reach = radius(h_.box(s)) + radius(h_.box(r));
        const glm::dvec3 d = rcv.center - src.center;
        const double d2 = glm::dot(d, d);
        const int order = d2 < reach * reach ? 5 : d2 < 4.0 * reach * reach ? 4 : d2 < 16.0 * reach * reach ? 3 : 2;
        // Integrate over the smaller patch (the inner integral over the other
        // is exact) and use reciprocity, A_r F_rs = A_s F_sr: sampling the
        // larger patch would miss the peak of a small neighbour's kernel.
        // Order 2 from the points each element keeps.
        const auto estimate = [&](ElementId a, ElementId b, int n) {
            return n == 2 ? estimateFormFactor(h_.quadrature(a), h_.patch(a), h_.patch(b))
                          : estimateFormFactor(h_.patch(a), h_.patch(b), n);
        };
        FormFactorEstimate e = estimate(r, s, rcv.area > src.area ? 2 : order);
        if (rcv.area > src.area) e.mean = src.area / rcv.area * estimate(s, r, order).mean;
        // A surface facing the receiver close in front of it (a door 2 mm
        // before a wall) may cover a strip along the receiver's edge that the
        // Gauss points miss: the variation is judged at the corners too.
        if (facingClose(s, r)) {
            const PatchGeometry rp = h_.patch(r), sp = h_.patch(s);
            for (int k = 0; k < rp.n; ++k) {
                const glm::dvec3 corner = rp.v[k] + 0.01 * (rcv.center - rp.v[k]);
                const double f = pointToPolygonFormFactor(corner, h_.normal(rcv), sp);
                e.min = std::min(e.min, f);
                e.max = std::max(e.max, f);
            }
        }
        return e;
    }
    // A cluster end: the source as a few points (ClusterTransfer.h). A
    // surface receiver: the mean over its Gauss points of the form factor to
    // them. A cluster receiver: the kernel at its centre, which each facet
    // takes times its cosine toward the source.
    const SourcePoints source = sourcePoints(h_, s, h_.box(r));
    if (!rcv.isSurface()) {
        const double g = pointKernel(source, rcv.center);
        return {g, g, g};
    }
    FormFactorEstimate e;
    e.min = INFINITY;
    for (const SamplePoint& q : h_.quadrature(r)) {
        const double f = pointToSource(source, q.p, h_.normal(rcv));
        e.mean += q.w * f;
        e.min = std::min(e.min, f);
        e.max = std::max(e.max, f);
    }
    return e;
}

double Refiner::coupling(const Link& link, double transfer) const {
    const HElement& r = h_[link.receiver];
    if (r.isSurface()) return r.area * transfer;
    // A cluster receives by its projected area toward the source.
    return transfer * h_.shape(link.receiver).projectedArea(centreDirection(h_, link.receiver, link.source));
}

double Refiner::potentialTransfer(const Link& link) const {
    return h_[link.source].oracle * coupling(link, link.unoccluded);
}

double Refiner::variationBound(const Link& link) const {
    return std::min(potentialTransfer(link), h_[link.source].oracle * coupling(link, double(link.spread)));
}

Link Refiner::compute(ElementId s, ElementId r) const {
    Link l = computeUnoccluded(s, r);
    if (l.live) refreshVisibility(l);
    return l;
}

void Refiner::refreshVisibility(Link& l) const {
    l.visStale = false;
    l.blockedStatic = l.blockedDynamic = 0;
    l.rays = 0;
    l.visible = 1.0f;
    if (!(l.unoccluded > 0.0)) return;
    Segments seg;
    RayWeights weights;
    const std::size_t n = segments(l.source, l.receiver, seg, weights);
    l.rays = static_cast<std::uint8_t>(n);
    l.blockedStatic = rays_.blocked(Layer::Static, std::span(seg.data(), n));
    l.blockedDynamic = rays_.blocked(Layer::Dynamic, std::span(seg.data(), n));
    l.visible = weightedVisibility(l, weights);
}

bool Refiner::refinesAtAnyVisibility(const Link& link) const {
    if (chooseSplit(link) == Split::None) return false;
    if (!admissible(link.source, link.receiver)) return true;
    // wouldRefine's bound is at least this for a cluster end, whatever v.
    const bool clusterEnd = !h_[link.source].isSurface() || !h_[link.receiver].isSurface();
    return clusterEnd && kEstimatedWeight * potentialTransfer(link) > threshold(link) * (1.0 + 1e-9);
}

double Refiner::threshold(const Link& link) const {
    const double t = settings_.epsilon * settings_.referencePower;
    const HElement& r = h_[link.receiver];
    return receiverScales_.empty() || !r.isSurface() ? t : t * receiverScales_[r.polygon];
}

Link Refiner::computeUnoccluded(ElementId s, ElementId r) const {
    Link l;
    l.source = s;
    l.receiver = r;
    // Only a pair that no light can cross is dropped, before its form factor
    // is computed (a sixth of the pairs a solve of `office` makes); a pair
    // whose sample points happen to see nothing keeps its link (refinement
    // may find more).
    const bool dynamic = touchesMovable(s) || touchesMovable(r);
    if (!dynamic && neverCarries(s, r)) return l;  // not live, carrying nothing
    const FormFactorEstimate f = unoccludedFormFactor(s, r);
    l.unoccluded = f.mean;
    l.spread = static_cast<float>(f.max - f.min);
    l.live = true;
    l.visStale = l.unoccluded > 0.0;
    return l;
}

void Refiner::refreshDynamicVisibility(Link& link) const {
    Segments seg;
    RayWeights weights;
    const std::size_t n = segments(link.source, link.receiver, seg, weights);
    link.blockedDynamic = rays_.blocked(Layer::Dynamic, std::span(seg.data(), n));
    link.visible = weightedVisibility(link, weights);
}

LinkId Refiner::attachUnseen(const Link& link) {
    const LinkId id = links_.add(link);
    Link& l = links_[id];
    l.gathered = 0.0;  // carries nothing until its rays are cast (activate)
    append(h_[link.receiver].links, link.receiver, id);
    ++activeLinks_;
    addOutLink(link.source, id);
    return id;
}

void Refiner::castPendingRays(const std::vector<LinkId>& ids) {
    tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t i) {
        Link& l = links_[ids[i]];
        if (l.live && !l.passive && l.visStale) refreshVisibility(l);
    });
    for (LinkId id : ids)
        if (links_[id].live && !links_[id].passive && links_[id].gathered != links_[id].formFactor()) regather(id);
}

LinkId Refiner::attach(const Link& link) {
    const LinkId id = links_.add(link);
    enlist(id);
    return id;
}

void Refiner::activate(LinkId id) {
    const Link& l = links_[id];
    orderedErase(h_[l.receiver].plinks, id);
    unorderedErase(h_[l.source].outPlinks, id);
    enlist(id);
}

void Refiner::enlist(LinkId id) {
    Link& l = links_[id];
    append(h_[l.receiver].links, l.receiver, id);
    ++activeLinks_;
    addOutLink(l.source, id);
    l.passive = false;
    if (l.visStale) refreshVisibility(l);
    l.gathered = l.formFactor();
    markStale(l.receiver);  // eq. 1: the receiver now holds this link's transfer
}

void Refiner::deactivate(LinkId id) {
    Link& l = links_[id];
    HElement& r = h_[l.receiver];
    l.gathered = 0.0;
    orderedErase(r.links, id);
    --activeLinks_;
    eraseOutLink(l.source, id);
    append(r.plinks, l.receiver, id);
    h_[l.source].outPlinks.push_back(id);
    l.passive = true;
    markStale(l.receiver);  // eq. 2: what it gathered through this link goes
}

void Refiner::addOutLink(ElementId source, LinkId id) {
    IdList& out = h_[source].outLinks;
    out.push_back(id);
    if (recordSenders_ && out.size() == 1) sendersChanged_.push_back(source);
}

void Refiner::eraseOutLink(ElementId source, LinkId id) {
    IdList& out = h_[source].outLinks;
    unorderedErase(out, id);
    if (recordSenders_ && out.empty()) sendersChanged_.push_back(source);
}

void Refiner::regather(LinkId id) {
    Link& l = links_[id];
    l.gathered = l.formFactor();
    markStale(l.receiver);
}

void Refiner::append(IdList& list, ElementId receiver, LinkId id) {
    list.push_back(id);
    if (h_[receiver].unordered) return;
    h_[receiver].unordered = true;
    unordered_.push_back(receiver);
}

void Refiner::sortLinkLists() {
    std::sort(unordered_.begin(), unordered_.end());  // each once: sorted on all cores
    unordered_.erase(std::unique(unordered_.begin(), unordered_.end()), unordered_.end());
    tbb::parallel_for(std::size_t(0), unordered_.size(), [&](std::size_t i) {
        HElement& e = h_[unordered_[i]];
        if (!e.unordered) return;  // freed since
        sortBySource(h_, links_, e.links);
        sortBySource(h_, links_, e.plinks);
        e.unordered = false;
    });
    unordered_.clear();
}

void Refiner::sortAllLinkLists() {
    unordered_.clear();
    for (ElementId e = 0; e < h_.size(); ++e) {
        h_[e].unordered = true;
        unordered_.push_back(e);
    }
    sortLinkLists();
}

void Refiner::markStale(ElementId receiver) {
    h_[receiver].stale = true;
    markDirty(receiver);
}

void Refiner::markDirty(ElementId e) {
    if (h_[e].dirty) return;
    h_[e].dirty = true;
    dirty_.push_back(e);
}

std::vector<ElementId> Refiner::takeDirty() {
    std::vector<ElementId> out;
    out.swap(dirty_);
    // Summed again rather than adjusted link by link: exact whatever changed
    // (a cluster source's direction moves with it), and no rounding drift.
    // When many are (an edit's light scaled at once: every element), the
    // sources' states are read from flat arrays (SourceStates).
    const std::optional<SourceStates> states =
        out.size() > h_.size() / 8 ? std::optional<SourceStates>(std::in_place, h_) : std::nullopt;
    tbb::parallel_for(std::size_t(0), out.size(), [&](std::size_t i) {
        HElement& e = h_[out[i]];
        if (!e.stale) return;
        if (!e.isSurface()) {
            h_.shape(out[i]).ownValid = false;  // summed from its links when pushed
            return;
        }
        LinkSums sums;
        const std::size_t n = e.links.size();
        for (std::size_t k = 0; k < n; ++k) {
            links_.prefetchAhead(e.links, k);
            const Link& l = links_[e.links[k]];
            sums.add(double(l.gathered) * (states ? states->sent(l, e.center) : sentRadiosity(h_, l)), l.gathered,
                     !h_[l.source].isSurface());
        }
        sums.storeIn(e);
    });
    for (ElementId e : out) {
        if (h_[e].stale && h_[e].isSurface()) h_.refreshCoverage(e);
        h_[e].stale = false;
    }
    return out;
}

void Refiner::remove(LinkId id) {
    if (!links_[id].passive) deactivate(id);
    orderedErase(h_[links_[id].receiver].plinks, id);
    unorderedErase(h_[links_[id].source].outPlinks, id);
    links_.remove(id);
}

void Refiner::linkRoot() {
    const ElementId root = h_.root();
    Link l;
    l.source = l.receiver = root;
    l.live = true;
    attach(l);
}

bool Refiner::canSplit(ElementId e, int below) const {
    const HElement& el = h_[e];
    if (!el.isSurface()) return !el.children.empty();
    return h_.canSubdivide(e, below);
}

bool Refiner::facingClose(ElementId s, ElementId r) const {
    const HElement& a = h_[s];
    const HElement& b = h_[r];
    if (!a.isSurface() || !b.isSurface() || glm::dot(h_.normal(a), h_.normal(b)) > -0.9)
        return false;
    const double gap = std::abs(glm::dot(h_.normal(b), a.center - b.center));
    return gap < 0.1 * std::max(radius(h_.box(s)), radius(h_.box(r)));
}

// An emitter standing on the receiver's plane, across it (a lamp's sides
// on the wall it hangs on, shining along the wall): its light on the
// receiver falls off from the line where they meet as steeply as a contact
// shadow does, and elements at the area threshold draw the lamp's glow a
// whole element wider than it is (a glowing box on a wall: 0.89 of the
// reference's light where Cycles reads 0.70, bench/untuned/turned_room.py).
bool Refiner::litAlongBy(ElementId s, ElementId r) const {
    const HElement& a = h_[s];
    const HElement& b = h_[r];
    // A receiver that glows itself (the faces of a glowing box, a furnace)
    // is not lit along: its own light does not fall off from the line.
    if (!a.isSurface() || !b.isSurface() || !(luminance(h_.emission(a)) > 0.0) ||
        luminance(h_.emission(b)) > 0.0)
        return false;
    if (std::abs(glm::dot(h_.normal(a), h_.normal(b))) > 0.1) return false;
    const double gap = std::abs(glm::dot(h_.normal(b), a.center - b.center));
    return gap < 1.01 * radius(h_.box(s));
}

// The push gives a subdivided receiver's children the light of its coarse
// links where finer links leave their view uncovered (Solver::shareOf). A
// surface close in front of part of the receiver covers that part's whole
// view, but a link from it at the receiver's level counts for the mean
// child: the children it covers would take the coarse light of the room. Its
// link goes down to the children, as long as the view it covers holds more
// of the receiver's light than the threshold.
bool Refiner::goesToChildren(const Link& link) const {
    const HElement& r = h_[link.receiver];
    return !r.children.empty() && r.isSurface() && facingClose(link.source, link.receiver) &&
           r.oracle * coupling(link, link.unoccluded) > threshold(link);
}

Refiner::Split Refiner::chooseSplit(const Link& link) const {
    if (link.source == link.receiver) return canSplit(link.source) ? Split::Both : Split::None;
    if (goesToChildren(link)) return Split::Receiver;
    // A source close in front of the receiver may split one level below the
    // area threshold: lit on one part and hidden on the other (a door's lit
    // face over a doorway's edge), it would send the gap the mean of both.
    // A receiver an emitter shines along may split two levels below it
    // (litAlongBy).
    const bool cs = canSplit(link.source, facingClose(link.source, link.receiver) ? 1 : 0),
               cr = canSplit(link.receiver, litAlongBy(link.source, link.receiver) ? 2 : 0);
    // A shadow boundary across one end only: split that end. The rays run
    // from each of the source's four points to each of the receiver's four
    // (ray 4 i + j: source point i, receiver point j). When whether a ray is
    // blocked depends only on its source point, the blocker stands right
    // in front of the source (a door 2 mm before a doorway's edge): splitting
    // the receiver would leave every child link partly visible, each sending
    // the source's mean, lit and hidden parts alike. Such a boundary is split
    // one level below the area threshold: a strip 5 cm wide is otherwise
    // left in elements 5 cm wide (Hierarchy::canSubdivide).
    if (link.rays == 16 && h_[link.source].isSurface() && h_[link.receiver].isSurface()) {
        const unsigned blocked = unsigned(link.blockedStatic | link.blockedDynamic);
        if (blocked != 0u && blocked != 0xFFFFu) {
            bool acrossSource = false, acrossReceiver = false;
            for (int k = 0; k < 4; ++k) {
                const unsigned row = (blocked >> (4 * k)) & 0xFu;       // source point k
                const unsigned column = (blocked >> k) & 0x1111u;       // receiver point k
                acrossReceiver = acrossReceiver || (row != 0u && row != 0xFu);
                acrossSource = acrossSource || (column != 0u && column != 0x1111u);
            }
            if (acrossSource && !acrossReceiver && canSplit(link.source, 1)) return Split::Source;
            if (acrossReceiver && !acrossSource && canSplit(link.receiver, 1)) return Split::Receiver;
        }
    }
    // Equal areas (with a little slack, so a scaled scene decides alike): the receiver.
    if (cs && cr) return h_[link.source].area > h_[link.receiver].area * (1.0 + 1e-9) ? Split::Source : Split::Receiver;
    if (cs) return Split::Source;
    if (cr) return Split::Receiver;
    return Split::None;
}

bool Refiner::wouldRefine(const Link& link) const {
    if (chooseSplit(link) == Split::None) return false;
    if (goesToChildren(link)) return true;
    if (!admissible(link.source, link.receiver)) return true;
    // Partly occluded links are judged by their unoccluded transfer, so that
    // shadow boundaries get refined. So are links with a cluster end whatever
    // their visibility: a cluster's few sample points can all lie on faces
    // hidden from the other end, and a visibility of 0 there must not stop
    // the refinement that would find the faces that do see it.
    const double v = link.visibility();
    const bool clusterEnd = !h_[link.source].isSurface() || !h_[link.receiver].isSurface();
    const double f = (clusterEnd || (v > 0.0 && v < 1.0)) ? link.unoccluded : link.formFactor();
    // A transfer that is estimated (a cluster end's point quadrature, or a
    // visibility between 0 and 1 from 16 rays) is less certain than one
    // computed exactly, and counts for more.
    const double weight = (clusterEnd || (v > 0.0 && v < 1.0)) ? kEstimatedWeight : 1.0;
    // BF, and the same bound on how much the transfer varies across the
    // receiver. A link's form factor varying across the receiver also says
    // how the receiver's other, coarser light divides among its children (a
    // wall half hidden by a door 2 mm in front of it: the hidden half takes
    // none of the room's light): judged by the receiver's own radiosity too.
    const double bright = std::max(h_[link.source].oracle, h_[link.receiver].oracle);
    const double bound = weight * std::max(h_[link.source].oracle * coupling(link, std::max(f, double(link.spread) * v)),
                                           bright * coupling(link, double(link.spread)));
    // A little slack: symmetric scenes put many links exactly on the threshold,
    // and the same scene at another scale must not fall on the other side.
    return bound > threshold(link) * (1.0 + 1e-9);
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

void Refiner::refine(const std::vector<LinkId>& ids, std::vector<LinkId>& created, bool deferRays) {
    // Subdivide first (it changes the hierarchy), then compute every new
    // link of the batch on all cores, then attach them in a fixed order.
    std::vector<std::pair<ElementId, ElementId>> pairs;
    for (LinkId id : ids) {
        const auto p = childPairs(links_[id]);
        pairs.insert(pairs.end(), p.begin(), p.end());
    }
    std::vector<Link> computed(pairs.size());
    tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t i) {
        Link& l = computed[i];
        l = computeUnoccluded(pairs[i].first, pairs[i].second);
        // A link about to be refined again whatever its visibility needs no
        // rays: its children cast theirs.
        if (l.live && !(deferRays && refinesAtAnyVisibility(l))) refreshVisibility(l);
    });
    for (const Link& l : computed)
        if (l.live) created.push_back(l.visStale ? attachUnseen(l) : attach(l));
    // The refined links stay as p-links on their receivers.
    for (LinkId id : ids) deactivate(id);
}

double Refiner::unrefinedPower() const {
    double power = 0.0;
    for (ElementId e = 0; e < h_.size(); ++e)
        for (LinkId id : h_[e].links)
            if (wouldRefine(links_[id])) power += potentialTransfer(links_[id]);
    return power;
}

std::size_t Refiner::memoryInUse() const {
    const RefineSettings::Beside& b = settings_.beside;
    return b.fixed + links_.liveCount() * (sizeof(Link) + 3 * sizeof(LinkId) + b.perLink) +
           h_.liveCount() * (h_.bytesPerElement() + b.perElement);
}

std::size_t Refiner::refineAll(const WaveReport& onWave) {
    std::vector<LinkId> wave;
    for (ElementId e = 0; e < h_.size(); ++e)
        for (LinkId l : h_[e].links) wave.push_back(l);
    return refineAll(std::move(wave), onWave);
}

std::size_t Refiner::refineAll(std::vector<LinkId> wave, const WaveReport& onWave) {
    std::size_t refined = 0;
    while (!wave.empty()) {
        // Judged on all cores, kept in the wave's order.
        std::vector<std::uint8_t> refines(wave.size());
        tbb::parallel_for(std::size_t(0), wave.size(), [&](std::size_t i) { refines[i] = wouldRefine(links_[wave[i]]); });
        std::vector<LinkId> batch;
        for (std::size_t i = 0; i < wave.size(); ++i)
            if (refines[i]) batch.push_back(wave[i]);
        if (batch.empty()) break;
        // Each refinement makes a few links and, for a surface, four elements.
        const std::size_t growth =
            batch.size() * (4 * (sizeof(Link) + 3 * sizeof(LinkId) + settings_.beside.perLink) +
                            4 * (h_.bytesPerElement() + settings_.beside.perElement));
        if (memoryInUse() + growth > settings_.maxMemoryBytes) {
            capReached_ = true;
            break;
        }
        wave.clear();
        refine(batch, wave, true);
        refined += batch.size();
        if (onWave) onWave(refined);
    }
    // Links left unrefined (the cap) that deferred their rays cast them now.
    castPendingRays(wave);
    return refined;
}

}  // namespace rad
