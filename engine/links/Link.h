#pragma once
// Links (Hanrahan et al. 1991) carrying radiosity from a source H-element to a
// receiver H-element, and p-links: refined links kept on their receiver as the
// parents of the line-space hierarchy (paper sec. 3.1).

#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "hierarchy/ChunkedArray.h"
#include "hierarchy/HElement.h"

namespace rad {

struct Link {
    ElementId source = kNone;
    ElementId receiver = kNone;
    // The transfer without occlusion. A surface receiver: the form factor
    // F(receiver -> source). A cluster receiver: the geometric kernel G of the
    // point approximation (the source's projected area over pi d^2); each
    // member surface takes G times its own cosine toward the source (see
    // solve/ClusterTransfer.h).
    float unoccluded = 0.0f;
    // The transfer the receiver's irradiance currently holds for this link
    // (formFactor() when it was gathered); the in-place gather (eq. 1, 2)
    // adds the source's B times its change. Single precision, like the
    // other per-link numbers: the receiver's irradiance, a double, takes
    // exactly the value stored here off again when the link changes, so
    // moves away and back still return the solution (a link is 32 bytes).
    float gathered = 0.0f;
    // How much the unoccluded point form factor varies across the receiver
    // (max - min at the quadrature points): where it is large, pushing the
    // mean down the receiver's subtree is a poor approximation.
    float spread = 0.0f;
    // Two-part visibility (sec. 3.4), exact per ray: bit i is set when the
    // static scene, or the dynamic objects, block visibility ray i. The
    // visibility is the share of the rays blocked by neither, each ray
    // weighted by the transfer between its two end points (near pairs carry
    // more than far ones), so a ray blocked by both counts once. It is kept
    // in `visible`, set whenever a mask changes (Refiner), because the
    // weights need the geometry.
    float visible = 1.0f;
    std::uint16_t blockedStatic = 0;
    std::uint16_t blockedDynamic = 0;
    std::uint8_t rays = 0;
    bool passive = false;
    bool live = false;
    // The visibility masks are out of date: a p-link that is refined whatever
    // its visibility needs none to be judged, and gets it if it is made
    // active again (Refiner::activate).
    bool visStale = false;

    double visibility() const { return visible; }
    // Rounded as `gathered` stores it, so that a link gathered at its form
    // factor compares equal to it.
    double formFactor() const { return static_cast<float>(double(unoccluded) * visibility()); }
};
static_assert(sizeof(Link) == 32, "a link is two ids, four floats, two masks and four bytes of flags");

// All links and p-links, addressed by LinkId; freed slots are reused. They
// live in chunks of 8,192 (256 KiB, hierarchy/ChunkedArray.h): a store of a
// million links grows without ever copying itself, and has at most one chunk
// of slack.
class LinkStore {
public:
    LinkId add(const Link& link) {
        LinkId id;
        if (!free_.empty()) {
            id = free_.back();
            free_.pop_back();
            links_[id] = link;
        } else {
            id = static_cast<LinkId>(links_.size());
            links_.push_back(link);
        }
        links_[id].live = true;
        return id;
    }
    void remove(LinkId id) {
        links_[id] = Link{};
        free_.push_back(id);
    }
    Link& operator[](LinkId id) { return links_[id]; }
    const Link& operator[](LinkId id) const { return links_[id]; }
    std::size_t slots() const { return links_.size(); }
    std::size_t liveCount() const { return links_.size() - free_.size(); }
    // Reading the links of a list in turn, asks for the one a few places
    // ahead of `k`: a list's links are scattered in the store, and a sum
    // over them otherwise waits on memory at each (summing every receiver
    // of `office` again: 8.6 -> 7.1 ms; pushing its clusters: 6.7 -> 5.3).
    void prefetchAhead(std::span<const LinkId> ids, std::size_t k) const {
        constexpr std::size_t kAhead = 8;
        if (k + kAhead < ids.size()) __builtin_prefetch(&links_[ids[k + kAhead]]);
    }
    // Drops the growth slack of the free list (after a solve: links come and
    // go by a few percent per move from then on).
    void compact() { free_.shrink_to_fit(); }
    std::size_t memoryBytes() const { return links_.memoryBytes() + free_.capacity() * sizeof(LinkId); }

private:
    ChunkedArray<Link, 13> links_;
    std::vector<LinkId> free_;
};

}  // namespace rad
