#include "update/EditResponse.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <tbb/parallel_for.h>

namespace rad {

std::optional<glm::dvec3> EditResponse::scaleFor(const EmissionChange& change) const {
    const EmissionChange& was = change_;
    if (entries_.empty() || change.size() != was.size()) return std::nullopt;
    glm::dvec3 c(0.0);
    glm::bvec3 found(false);
    for (std::size_t i = 0; i < change.size(); ++i) {
        if (change[i].first != was[i].first) return std::nullopt;
        for (int k = 0; k < 3; ++k) {
            const double before = was[i].second[k], now = change[i].second[k];
            if (before == 0.0) continue;  // checked below, once c is known
            const double ratio = now / before;
            if (!found[k]) {
                c[k] = ratio;
                found[k] = true;
            } else if (std::abs(ratio - c[k]) > kProportional * std::max(std::abs(ratio), std::abs(c[k]))) {
                return std::nullopt;
            }
        }
    }
    // A key the kept change left at 0 in a channel where others changed:
    // no c makes the new change from it.
    for (std::size_t i = 0; i < change.size(); ++i)
        for (int k = 0; k < 3; ++k)
            if (was[i].second[k] == 0.0 && change[i].second[k] != 0.0 && found[k]) return std::nullopt;
    if (!(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z))) return std::nullopt;
    return c;
}

void EditResponse::begin(const Hierarchy& h, const EmissionChange& change) {
    recordingChange_ = change;
    startB_.resize(h.size());
    startFacet_.assign(h.size(), kNone);
    startPowers_.clear();
    for (ElementId e = 0; e < h.size(); ++e) {
        startB_[e] = h[e].radiosity;
        if (h[e].shape == kNone || !h.isLive(e)) continue;
        startFacet_[e] = static_cast<std::uint32_t>(startPowers_.size());
        const std::vector<glm::dvec3>& power = h.shape(e).power;
        startPowers_.insert(startPowers_.end(), power.begin(), power.end());
    }
}

void EditResponse::keep(const Hierarchy& h) {
    change_ = std::move(recordingChange_);
    const std::size_t n = std::min<std::size_t>(h.size(), startB_.size());
    // On all cores: which elements are kept and how many facet changes each
    // brings (an edit of a light changes them all); then their places, in
    // the order of their ids; then the entries written.
    std::vector<std::uint32_t> facetsOf(n, kNone);  // kNone: not kept
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t e) {
        const HElement& el = h[e];
        if (el.outLinks.empty() || !h.isLive(static_cast<ElementId>(e))) return;
        bool changed = el.radiosity - startB_[e] != glm::dvec3(0.0);
        std::uint32_t facets = 0;
        if (el.shape != kNone) {
            const std::vector<glm::dvec3>& power = h.shape(static_cast<ElementId>(e)).power;
            // Its facets were made again (a member moved): not the same shape.
            if (startFacet_[e] == kNone || startFacet_[e] + power.size() > startPowers_.size()) return;
            for (std::size_t f = 0; f < power.size(); ++f)
                changed = changed || power[f] - startPowers_[startFacet_[e] + f] != glm::dvec3(0.0);
            facets = static_cast<std::uint32_t>(power.size());
        }
        if (changed) facetsOf[e] = facets;
    });
    std::vector<std::uint32_t> entryAt(n, kNone), facetAt(n, 0);
    std::uint32_t entries = 0, facets = 0;
    for (std::size_t e = 0; e < n; ++e)
        if (facetsOf[e] != kNone) {
            entryAt[e] = entries++;
            facetAt[e] = facets;
            facets += facetsOf[e];
        }
    entries_.assign(entries, Entry{});
    facets_.assign(facets, glm::dvec3(0.0));
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t e) {
        if (entryAt[e] == kNone) return;
        const HElement& el = h[e];
        Entry& entry = entries_[entryAt[e]];
        entry.id = static_cast<ElementId>(e);
        entry.polygon = el.polygon;
        entry.depth = el.depth;
        entry.param = el.param;
        entry.change = el.radiosity - startB_[e];
        if (el.shape == kNone) return;
        const std::vector<glm::dvec3>& power = h.shape(static_cast<ElementId>(e)).power;
        entry.shape = el.shape;
        entry.facetCount = static_cast<std::uint8_t>(power.size());
        entry.firstFacet = facetAt[e];
        for (std::size_t f = 0; f < power.size(); ++f)
            facets_[facetAt[e] + f] = power[f] - startPowers_[startFacet_[e] + f];
    });
}

void EditResponse::clear() {
    change_.clear();
    entries_.clear();
    facets_.clear();
}

bool EditResponse::movedSinceBegin(const Hierarchy& h, ElementId e, double threshold) const {
    if (e >= startB_.size()) return true;  // made since: new to the light
    const HElement& el = h[e];
    if (std::abs(luminance(el.radiosity - startB_[e])) > threshold) return true;
    if (el.shape == kNone || startFacet_[e] == kNone) return false;
    const ClusterShape& shape = h.shape(e);
    if (startFacet_[e] + shape.power.size() > startPowers_.size()) return true;
    for (std::size_t f = 0; f < shape.power.size(); ++f)
        if (std::abs(luminance(shape.power[f] - startPowers_[startFacet_[e] + f])) > threshold * shape.facets[f].area)
            return true;
    return false;
}

bool EditResponse::stillThere(const Hierarchy& h, const Entry& entry) {
    if (entry.id >= h.size()) return false;
    if (!h.isLive(entry.id)) return false;
    const HElement& el = h[entry.id];
    if (el.polygon != entry.polygon || el.depth != entry.depth || el.param != entry.param) return false;
    if (el.shape != entry.shape) return false;
    return entry.shape == kNone || h.shape(entry.id).facetCount() == entry.facetCount;
}

}  // namespace rad
