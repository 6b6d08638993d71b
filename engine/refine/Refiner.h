#pragma once
// BF refinement (Hanrahan et al. 1991) with clusters (Sillion 1995). Links
// are created with their form factor and both visibility parts; a refined
// link stays on its receiver as a p-link (paper sec. 3.1), so the line-space
// hierarchy exists from the first solve.

#include <cstddef>
#include <array>
#include <optional>
#include <utility>
#include <functional>
#include <vector>

#include "geometry/RayCaster.h"
#include "hierarchy/Hierarchy.h"
#include "links/Link.h"

namespace rad {


struct RefineSettings {
    // A link is refined while B_s * F * A_r exceeds epsilon times the total
    // emitted power: relative, so the same epsilon suits any scene scale.
    double epsilon = 5e-5;
    double referencePower = 1.0;  // total emitted power (luminance)
    // Visibility sample points per surface element: 4 (a 2 x 2 Gauss grid)
    // or 1 (its centre). A link casts the product of its two ends' counts.
    int samplesPerElement = 4;
    // Refinement stops before links and elements would take more bytes.
    std::size_t maxMemoryBytes = std::size_t(4) << 30;
    // What is kept beside them and counted against the same limit (the
    // update's marks and sums per element and per link, in chunks of a
    // fixed size): a tiny limit then holds for the whole engine.
    struct Beside {
        std::size_t fixed = 0, perElement = 0, perLink = 0;
    } beside;
};

class Refiner {
public:
    Refiner(Hierarchy& hierarchy, LinkStore& links, const RayCaster& rays, RefineSettings settings);

    // The link s -> r computed but not attached; `live` is false when it
    // carries nothing and never can (facing away, both static).
    Link compute(ElementId s, ElementId r) const;
    // The same without the visibility rays: the link's visibility is stale.
    Link computeUnoccluded(ElementId s, ElementId r) const;
    // Casts the rays of both visibility parts.
    void refreshVisibility(Link& link) const;
    // Whether the link would be refined whatever its visibility (not
    // admissible, or a cluster end whose unoccluded transfer alone exceeds
    // the threshold): a p-link then needs no rays to be judged.
    bool refinesAtAnyVisibility(const Link& link) const;
    // Only the dynamic part of the visibility (sec. 3.4): what a move changes
    // for a link whose two ends stay put. The same rays as the static part.
    void refreshDynamicVisibility(Link& link) const;

    // Link bookkeeping. Each keeps the receiver's irradiance equal to the sum
    // of held transfer times the radiosity its source sends over its active
    // links (the in-place gather, eq. 1 and 2): the receiver is marked to sum
    // its links again before the next push (takeDirty), and dirty.
    LinkId attach(const Link& link);  // a new active link
    // A new active link whose rays are not cast yet: it holds no transfer.
    LinkId attachUnseen(const Link& link);
    // Casts the deferred rays of active links among `ids` and gathers them.
    void castPendingRays(const std::vector<LinkId>& ids);
    void activate(LinkId id);         // p-link -> active (reinstate)
    void deactivate(LinkId id);       // active -> p-link (refined)
    void regather(LinkId id);         // its form factor changed
    void remove(LinkId id);           // active or passive, gone

    // Puts the link lists that refinement appended to back in source order
    // (links/SourceOrder.h); every list, after the index ranges were
    // numbered again (Hierarchy::attachToRoot).
    void sortLinkLists();
    void sortAllLinkLists();

    // Elements that began or ceased to be the source of an active link
    // (what an unsent element has to send goes nowhere without one), from
    // the call that turned recording on; handed out by takeSendersChanged.
    void recordSendersChanged() { recordSenders_ = true; }
    std::vector<ElementId> takeSendersChanged() { return std::exchange(sendersChanged_, {}); }

    // Elements whose own irradiance changed since the last takeDirty().
    void markDirty(ElementId e);
    // Dirty, and its irradiance is summed again from its links then (its
    // links, or what their sources hold as gathered, changed).
    void markStale(ElementId receiver);
    // Sums again the irradiance of the elements whose links changed, and
    // hands out the dirty elements (for a partial push-pull).
    std::vector<ElementId> takeDirty();

    // The first link of a solve: the root cluster with itself.
    void linkRoot();

    // Refines every active link until the criterion holds everywhere (or the
    // memory cap is met). Returns the number of links refined. `onWave`, if
    // given, hears the count refined so far after each wave (for progress).
    using WaveReport = std::function<void(std::size_t refined)>;
    std::size_t refineAll(const WaveReport& onWave = {});
    // The same for the given active links and the links their refinement makes.
    std::size_t refineAll(std::vector<LinkId> links, const WaveReport& onWave = {});

    bool wouldRefine(const Link& link) const;
    // The power the link could carry at full visibility, from the oracle of
    // its source: the quantity BF refinement compares with the threshold.
    double potentialTransfer(const Link& link) const;
    // How far the link's transfer, as one mean over its receiver, can be
    // from what finer links would carry: its source's oracle times how much
    // the point form factor varies across the receiver (at most the
    // potential transfer). What a link left coarse gets wrong.
    double variationBound(const Link& link) const;
    // How many links refining this one would create (before dropping those
    // that carry nothing): its cost under a budget.
    std::size_t childCount(const Link& link) const;
    // Subdivides each link's larger element and replaces the link by its
    // line-space children; the link becomes a p-link. Appends the new links.
    // The links must be distinct and active; their new links are computed in
    // parallel.
    // deferRays: new links that will be refined whatever their visibility
    // are attached without casting rays (see attachUnseen); the caller must
    // refine them or cast their rays (castPendingRays).
    void refine(const std::vector<LinkId>& ids, std::vector<LinkId>& created, bool deferRays = false);

    bool capReached() const { return capReached_; }
    // Per input polygon, the scale of the threshold for the links it
    // receives (refine/ReceiverLight.h); empty: 1 for all.
    void setReceiverScales(std::vector<float> scales) { receiverScales_ = std::move(scales); }
    // The active links: every receiver's list summed, kept as they come and
    // go (a frame's figures read it; summing the lists took 2.2 ms a frame
    // on the building floor).
    std::size_t activeLinks() const { return activeLinks_; }
    // The power the active links that the criterion would still refine could
    // carry (potentialTransfer): what a stopped refinement left coarse.
    double unrefinedPower() const;
    // What links and elements take now, as refinement counts it: the
    // containers' sizes, not their capacities.
    std::size_t memoryInUse() const;
    const RefineSettings& settings() const { return settings_; }
    void setSettings(const RefineSettings& s) { settings_ = s; }

    // Whether the point (cluster) approximation of the form factor is valid.
    bool admissible(ElementId s, ElementId r) const;
    // Whether no light can go from s to r: one of them a surface with the
    // other entirely behind it, or both parts of one polygon.
    bool neverCarries(ElementId s, ElementId r) const;

private:
    // How much more an estimated transfer (a cluster end, or a partial
    // visibility) counts in the refinement criterion than an exact one: set
    // so that the measured error against path-traced references is about the
    // same for both kinds at the default epsilon (README, "Accuracy").
    static constexpr double kEstimatedWeight = 2.5;
    // What a link's transfer is compared with: epsilon times the reference
    // power, times its receiver's scale (a surface's polygon; 1 for a
    // cluster).
    double threshold(const Link& link) const;
    enum class Split { None, Source, Receiver, Both };
    Split chooseSplit(const Link& link) const;
    // `below`: levels below the area threshold allowed (Hierarchy::canSubdivide).
    bool canSplit(ElementId e, int below = 0) const;
    // Two surfaces facing each other, nearly parallel, with a gap under a
    // tenth of their size (a door 2 mm before a wall, a box on a shelf):
    // the form factor's variation is judged at the receiver's corners too,
    // and the source may split one level below the area threshold.
    bool facingClose(ElementId s, ElementId r) const;
    // The surface s emits and stands on r's plane, across it, or close to it
    // (a lamp's side on its wall, a strip under a cupboard 2 cm from the
    // wall), and r does not glow itself: r may split two levels below the
    // area threshold.
    bool litAlongBy(ElementId s, ElementId r) const;
    // Whether a link from a close facing source must reach the receiver's
    // children (see the .cpp): it is refined whatever its own transfer.
    bool goesToChildren(const Link& link) const;
    FormFactorEstimate unoccludedFormFactor(ElementId s, ElementId r) const;
    // A transfer of the link (unoccluded F, or kernel G) times the receiving area it reaches (A_r F for
    // a surface receiver, G times the projected area for a cluster).
    double coupling(const Link& link, double transfer) const;
    // Visibility rays: between the two ends' points (ClusterTransfer's
    // sourcePoints: Gauss points on a surface, a cluster's points on its
    // surfaces facing the other end), in fixed storage: a link is computed
    // for every refinement and every move, and heap allocations there cost
    // more than the points.
    using Segments = std::array<RayCaster::Segment, RayCaster::kMaxSegments>;
    using RayWeights = std::array<double, RayCaster::kMaxSegments>;
    std::size_t segments(ElementId s, ElementId r, Segments& out, RayWeights& weights) const;
    float weightedVisibility(const Link& link, const RayWeights& weights) const;
    // Whether e lies in, or holds, an object cluster that can move (under the
    // root): its links are kept even when they carry nothing where it stands.
    bool touchesMovable(ElementId e) const;
    std::vector<std::pair<ElementId, ElementId>> childPairs(const Link& link);
    // Appends to a receiver's list, which is then out of source order.
    void append(IdList& list, ElementId receiver, LinkId id);
    // Puts a link in its receiver's and its source's active lists, its rays
    // cast if they wait, and its transfer gathered (attach, activate).
    void enlist(LinkId id);

    Hierarchy& h_;
    LinkStore& links_;
    const RayCaster& rays_;
    RefineSettings settings_;
    bool capReached_ = false;
    std::vector<float> receiverScales_;
    std::size_t activeLinks_ = 0;
    std::vector<ElementId> dirty_;
    std::vector<ElementId> unordered_;  // elements whose lists were appended to
    bool recordSenders_ = false;
    std::vector<ElementId> sendersChanged_;
    void addOutLink(ElementId source, LinkId id);
    void eraseOutLink(ElementId source, LinkId id);
};

}  // namespace rad
