#pragma once
// How much of a cluster's facets light from outside the cluster can reach.
//
// A cluster receives by its facets' orientation (ClusterShape): a facet of
// normal n takes G max(0, n . u) from a source in direction u. A row of books
// 4 mm apart has most of its area on the sides that face the slots between
// them, which almost no light from outside reaches, and its spines little:
// by orientation alone the slots' sides took the light the spines catch
// (`office`'s bookcases read 0.5 to 0.9 of Cycles). So each facet gets an
// exposure, the share of 16 rays (cosine-distributed, from 4 points spread
// over its members by area) that reach the cluster's box, or 5% of its size
// beyond it, unblocked, and a link's light divides among the facets that
// face it by A c e rather than A c (ClusterShape::arrivalWeights): the
// cluster catches what it did, and the exposed facets take the slots' share.

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/RayCaster.h"
#include "hierarchy/Hierarchy.h"

namespace rad {

// Measures the exposure of the given clusters' facets (surfaces are left
// out), against both layers of `rays` as they stand; or, where
// `staticKnown[i]` is set and cluster i was measured before, against the
// dynamic layer only, with the static layer's part kept from then (the
// cluster and the static layer near it have not moved since).
void measureExposure(Hierarchy& hierarchy, const RayCaster& rays,
                     std::span<const ElementId> clusters,
                     std::span<const std::uint8_t> staticKnown = {});
// The same for every live cluster.
void measureExposure(Hierarchy& hierarchy, const RayCaster& rays);
// An object that moved: its top cluster, its boxes before and after, and
// how: translated by `shift`, or turned (its clusters' shapes built again).
struct ExposureMotion {
    ElementId cluster = kNone;
    Aabb oldBox, newBox;
    glm::dvec3 shift{0.0};
    bool turned = false;
};
// After objects moved, or the hierarchy changed around them, measures again
// the clusters whose exposure may have changed, and `also`:
//   - clusters of other objects whose box (widened by the rays' reach beyond
//     it) meets a moved object's box before or after: what moved may be in
//     their way now, or no longer; but those that hold a moved object only
//     if their facets regrouped (ClusterShape::exposureMeasured);
//   - a moved object's own clusters if it turned, or if their box, before
//     or after, meets a surface of another object: a translated cluster's
//     own surfaces block its rays alike wherever it stands, and so does a
//     plane it slides along that axis-aligned rectangles cover before and
//     after (a floor of tiles).
// `layersChanged`: an object joined the dynamic layer; the clusters are
// cast in full (the static part they kept had it).
// Returns those whose exposure changed by more than kExposureTolerance:
// their light divides anew, and they are to be pushed again.
std::vector<ElementId> measureExposureAround(Hierarchy& hierarchy, const RayCaster& rays,
                                             std::span<const ExposureMotion> motions,
                                             std::span<const ElementId> also = {},
                                             bool layersChanged = false);
inline constexpr double kExposureTolerance = 0.02;

}  // namespace rad
