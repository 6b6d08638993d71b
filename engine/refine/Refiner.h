#pragma once
// BF refinement (Hanrahan et al. 1991) with clusters (Sillion 1995). Links
// are created with their form factor and both visibility parts; a refined
// link stays on its receiver as a p-link (paper sec. 3.1), so the line-space
// hierarchy exists from the first solve.

#include <cstddef>
#include <array>
#include <optional>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "links/Link.h"

namespace rad {

class RayCaster;
enum class Layer;

struct RefineSettings {
    // A link is refined while B_s * F * A_r exceeds epsilon times the total
    // emitted power: relative, so the same epsilon suits any scene scale.
    double epsilon = 2e-4;
    double referencePower = 1.0;  // total emitted power (luminance)
    int samplesPerElement = 4;       // visibility rays: samples on the source x on the receiver
    std::size_t maxLinks = 4'000'000;  // memory cap on live links and p-links
};

class Refiner {
public:
    Refiner(Hierarchy& hierarchy, LinkStore& links, const RayCaster& rays, RefineSettings settings);

    // Recomputes the visibility sample points of the clusters in a subtree
    // (after it moved).
    void refreshClusterSamples(ElementId subtree);
    // The same for one cluster whose children changed.
    void refreshClusterSample(ElementId cluster);

    // The link s -> r computed but not attached; `live` is false when it
    // carries nothing and never can (facing away, both static).
    Link compute(ElementId s, ElementId r) const;
    // The same without the visibility rays: the link's visibility is stale.
    Link computeUnoccluded(ElementId s, ElementId r) const;
    // Casts the rays of both visibility parts (1 where nothing can arrive).
    void refreshVisibility(Link& link) const;
    // Whether the link would be refined whatever its visibility (not
    // admissible, or a cluster end whose unoccluded transfer alone exceeds
    // the threshold): a p-link then needs no rays to be judged.
    bool refinesAtAnyVisibility(const Link& link) const;
    // Only the dynamic part of the visibility (sec. 3.4): what a move changes
    // for a link whose two ends stay put.
    float dynamicVisibility(ElementId s, ElementId r) const;

    // Link bookkeeping. Each keeps the receiver's irradiance equal to the sum
    // of gathered F times the source's gathered B over its active links (the
    // in-place gather, eq. 1 and 2), and marks the receiver dirty.
    LinkId attach(const Link& link);  // a new active link
    void activate(LinkId id);         // p-link -> active (reinstate)
    void deactivate(LinkId id);       // active -> p-link (refined)
    void regather(LinkId id);         // its form factor changed
    void remove(LinkId id);           // active or passive, gone

    // Elements whose own irradiance changed since the last takeDirty().
    void markDirty(ElementId e);
    std::vector<ElementId> takeDirty();

    // The first link of a solve: the root cluster with itself.
    void linkRoot();

    // Refines every active link until the criterion holds everywhere (or the
    // memory cap is met). Returns the number of links refined.
    std::size_t refineAll();
    // The same for the given active links and the links their refinement makes.
    std::size_t refineAll(std::vector<LinkId> links);

    bool wouldRefine(const Link& link) const;
    // How many links refining this one would create (before dropping those
    // that carry nothing): its cost under a budget.
    std::size_t childCount(const Link& link) const;
    // Subdivides each link's larger element and replaces the link by its
    // line-space children; the link becomes a p-link. Appends the new links.
    // The links must be distinct and active; their new links are computed in
    // parallel.
    void refine(const std::vector<LinkId>& ids, std::vector<LinkId>& created);

    bool capReached() const { return capReached_; }
    const RefineSettings& settings() const { return settings_; }
    void setSettings(const RefineSettings& s) { settings_ = s; }

    // Whether the point (cluster) approximation of the form factor is valid.
    bool admissible(ElementId s, ElementId r) const;

private:
    enum class Split { None, Source, Receiver, Both };
    Split chooseSplit(const Link& link) const;
    bool canSplit(ElementId e) const;
    FormFactorEstimate unoccludedFormFactor(ElementId s, ElementId r) const;
    // Visibility sample points of an element, in fixed storage: a link is
    // computed for every refinement and every move, and heap allocations
    // there cost more than the points.
    static constexpr std::size_t kMaxPoints = 16;  // per element: order 4
    struct Points {
        std::array<glm::dvec3, kMaxPoints> p;
        std::size_t n = 0;
    };
    struct Segments {
        std::array<glm::dvec3, kMaxPoints * kMaxPoints> from, to;
        std::size_t n = 0;
    };
    Points samplePoints(ElementId e) const;
    void segments(ElementId s, ElementId r, Segments& out) const;
    double unoccluded(Layer layer, const Segments& s) const;
    // Whether e lies in, or holds, an object cluster that can move (under the
    // root): its links are kept even when they carry nothing where it stands.
    bool touchesMovable(ElementId e) const;
    std::vector<std::pair<ElementId, ElementId>> childPairs(const Link& link);

    Hierarchy& h_;
    LinkStore& links_;
    const RayCaster& rays_;
    RefineSettings settings_;
    // Per cluster: points on its surfaces, stratified by area, for visibility rays.
    std::vector<std::array<glm::dvec3, 4>> clusterSamples_;
    bool capReached_ = false;
    std::vector<ElementId> dirty_;
};

// Luminance of linear RGB (Rec. 709), the scalar used for error estimates.
inline double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

}  // namespace rad
