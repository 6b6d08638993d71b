#include "update/EditResponse.h"

#include <algorithm>
#include <cmath>

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
    entries_.clear();
    facets_.clear();
    for (ElementId e = 0; e < std::min<std::size_t>(h.size(), startB_.size()); ++e) {
        const HElement& el = h[e];
        if (el.outLinks.empty() || !h.isLive(e)) continue;
        Entry entry;
        entry.id = e;
        entry.polygon = el.polygon;
        entry.depth = el.depth;
        entry.param = el.param;
        entry.change = el.radiosity - startB_[e];
        bool changed = entry.change != glm::dvec3(0.0);
        if (el.shape != kNone) {
            const std::vector<glm::dvec3>& power = h.shape(e).power;
            // Its facets were made again (a member moved): not the same shape.
            if (startFacet_[e] == kNone || startFacet_[e] + power.size() > startPowers_.size()) continue;
            entry.shape = el.shape;
            entry.facetCount = static_cast<std::uint8_t>(power.size());
            entry.firstFacet = static_cast<std::uint32_t>(facets_.size());
            for (std::size_t f = 0; f < power.size(); ++f) {
                facets_.push_back(power[f] - startPowers_[startFacet_[e] + f]);
                changed = changed || facets_.back() != glm::dvec3(0.0);
            }
            if (!changed) facets_.resize(entry.firstFacet);
        }
        if (changed) entries_.push_back(entry);
    }
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
