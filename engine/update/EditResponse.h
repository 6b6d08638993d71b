#pragma once
// The light the last edit of emitters sent, kept for the next edit.
//
// Radiosity is linear in the emission: B = (I - rho F)^-1 E. An edit that
// changes the same emitters by c times the last edit's change (channel by
// channel: a light dimmed or brightened on a slider, frame after frame)
// changes every element's radiosity by c times what the last one did, as
// long as the links stay as they are. So each element's change of gathered
// radiosity over the last edit's bounces is kept, and the next such edit
// sends c times it at once instead of bounce after bounce (`office`'s light
// dimmed: 14 to 24 bounces of up to 500,000 transfers each).
//
// The guess is sent as a bounce sends: each element holds it as gathered,
// and the receivers of its links sum their irradiance again from the links
// (Refiner::markStale), so a receiver's irradiance stays the sum over its
// links of what their sources hold as gathered. What the guess misses
// (links refined or reinstated since, a deadline that cut the last edit's
// bounces short) is then B - gathered, and goes out in plain bounces: the
// solution depends on the guess only below the bounce threshold, where
// what each element has yet to send waits either way.

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <tbb/parallel_for.h>

#include "hierarchy/Hierarchy.h"
#include "radiosity/Scene.h"

namespace rad {

// An edit's change of emission, sorted by key: per polygon (its index) the
// emission added, per punctual light (the polygon count plus its index) the
// intensity added.
using EmissionChange = std::vector<std::pair<std::uint32_t, glm::dvec3>>;

class EditResponse {
  public:
    // Per channel, c such that `change` is c times the kept edit's change
    // (to within kProportional, relatively); none if it is not, or nothing is
    // kept. A channel the kept change left at 0 gets c = 0: nothing of it
    // was sent, and plain bounces send the new one.
    std::optional<glm::dvec3> scaleFor(const EmissionChange& change) const;

    // The frame of `change` begins: every element's radiosity (a cluster's
    // facet powers) as it stands, to take the frame's change from.
    void begin(const Hierarchy& h, const EmissionChange& change);
    // Sends c times the kept response: each element that is still the
    // element it was, and whose change is above `threshold` (a change of
    // radiosity; a cluster's by facet, times the facet's area), adds it to
    // what it holds as gathered, and is handed to `sent`, which tells its
    // links' receivers. What lies under the threshold is left to the
    // bounces, as they leave it: an edit of a millionth and back returns
    // the solution exactly.
    template <class Sent>
    void send(Hierarchy& h, const glm::dvec3& c, double threshold, const Sent& sent) const;
    // Whether e's radiosity (a cluster's facet powers, by area) moved by more
    // than `threshold` since begin(): a sender for the bounces after a guess.
    bool movedSinceBegin(const Hierarchy& h, ElementId e, double threshold) const;
    // The frame's bounces are done: each element's change of radiosity
    // since begin() is kept, where it has links to send it through.
    void keep(const Hierarchy& h);
    // Nothing kept (a move or a change of reflectance: the links or the
    // operator changed).
    void clear();

    static constexpr double kProportional = 1e-3;

  private:
    // An element as it was kept, to tell it from another element given its
    // id since (a reinstated subdivision frees its elements): the same
    // polygon, depth and corners, or the same cluster shape and facets.
    struct Entry {
        ElementId id = kNone;
        std::uint32_t polygon = kNone;
        std::uint32_t shape = kNone;
        std::uint32_t firstFacet = 0;  // into facets_
        std::uint8_t facetCount = 0;
        std::uint8_t depth = 0;
        std::array<glm::vec2, 4> param{};
        glm::dvec3 change{0.0};  // of B (a surface)
    };
    static bool stillThere(const Hierarchy& h, const Entry& entry);

    EmissionChange change_, recordingChange_;
    std::vector<Entry> entries_;
    std::vector<glm::dvec3> facets_;  // the change of a cluster's facet powers
    // At begin(): per element its B, and for a cluster where its facet
    // powers start in startPowers_.
    std::vector<glm::dvec3> startB_;
    std::vector<std::uint32_t> startFacet_;
    std::vector<glm::dvec3> startPowers_;
};

template <class Sent>
void EditResponse::send(Hierarchy& h, const glm::dvec3& c, double threshold, const Sent& sent) const {
    // Each entry is its own element: sent on all cores, handed on in order.
    std::vector<std::uint8_t> sends(entries_.size(), 0);
    tbb::parallel_for(std::size_t(0), entries_.size(), [&](std::size_t i) {
        const Entry& e = entries_[i];
        if (!stillThere(h, e)) return;
        bool above = std::abs(luminance(c * e.change)) > threshold;
        if (e.shape != kNone) {
            const ClusterShape& shape = h.shape(e.id);
            for (int f = 0; f < e.facetCount && !above; ++f)
                above = std::abs(luminance(c * facets_[e.firstFacet + f])) > threshold * shape.facets[f].area;
        }
        if (!above) return;
        h[e.id].gathered += c * e.change;
        if (e.shape != kNone) {
            ClusterShape& shape = h.shape(e.id);
            for (int f = 0; f < e.facetCount; ++f) shape.gathered[f] += c * facets_[e.firstFacet + f];
        }
        sends[i] = 1;
    });
    for (std::size_t i = 0; i < entries_.size(); ++i)
        if (sends[i]) sent(entries_[i].id);
}

}  // namespace rad
