#pragma once
// H-elements (paper sec. 3.1): clusters and surface elements in one hierarchy.

#include <array>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

#include "hierarchy/IdList.h"
#include "hierarchy/IndexRange.h"
#include "links/FormFactor.h"
#include "radiosity/Scene.h"

namespace rad {

using ElementId = std::uint32_t;
using LinkId = std::uint32_t;
inline constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

enum class ElementKind : std::uint8_t { Cluster, Surface };

// The fields the line-space traversal reads for every link it passes: the
// index range and the box of a link's ends. They live apart from the rest of
// an H-element (Hierarchy::range, Hierarchy::box), one cache line each, so
// that a traversal over hundreds of thousands of links does not pull in the
// 320 bytes of geometry and solution state of every end it looks at.
struct alignas(64) ElementBounds {
    IndexRange range;
    Aabb box;
};

// Fields are ordered so that the small ones share words: an office holds
// about 23,000 H-elements, and every byte of one is 0.03 bytes per link.
struct HElement {
    ElementId parent = kNone;
    // Clusters: their orientation (facets, sample points, facet powers), an
    // index into Hierarchy's shapes; kNone for surfaces.
    std::uint32_t shape = kNone;
    // Eight bytes of small fields, read on every visit.
    ElementKind kind = ElementKind::Cluster;
    std::uint8_t depth = 0;  // quadtree depth below the input polygon
    bool lit = false;        // a light link of a punctual light ends here (Hierarchy::direct)
    bool changed = false;  // on the path to a modified element (sec. 4.1, Fig. 7)
    bool dirty = false;    // own irradiance changed: the whole subtree is pushed again
    // Its links changed: its irradiance is summed again from them before the
    // next push (Refiner::takeDirty), rather than adjusted link by link.
    bool stale = false;
    // Links were appended to `links` or `plinks`: they are out of source
    // order (links/SourceOrder.h) until Refiner::sortLinkLists.
    bool unordered = false;
    std::int8_t level = 0;  // of the oracle's steps (below)
    IdList children;        // clusters: any number; surfaces: none or four

    // Geometry. Surfaces: the patch, a part of input polygon `polygon`, given
    // by the parametric corners (u,v) of that polygon (barycentric-like for
    // triangles), which the display uses to find shared vertices; its corners
    // in space are made from them when asked (Hierarchy::patch), as the
    // polygon stands.
    // Single precision: the corners are dyadic fractions (halves of halves),
    // exact in a float's 24-bit mantissa down to kMaxDepth levels: elements
    // of 4^-24 (about 4e-15) of the polygon's area, far below any useful
    // area threshold (the index ranges would allow 31 levels).
    std::array<glm::vec2, 4> param{};
    std::uint32_t polygon = kNone;
    std::uint32_t object = kNone;  // set for surfaces and for a whole object's cluster
    // (A surface's normal is its polygon's: Hierarchy::normal.)
    glm::dvec3 center{0.0};
    double area = 0.0;  // surfaces: own area; clusters: total surface area inside

    // Solution state (double precision: the in-place gather adds differences).
    // Surfaces: the irradiance gathered on their own active links, and the sum
    // of those links' form factors (what the energy guard bounds). A cluster's
    // links arrive from directions; what each member gets is found when the
    // cluster is pushed (solve/ClusterTransfer.h), so it stores neither.
    glm::dvec3 irradiance{0.0};
    double formFactorSum = 0.0;
    // Of those, the part on links from clusters (an estimate, which gives
    // way first under the energy guard: Solver::arriving).
    glm::dvec3 clusterIrradiance{0.0};
    double clusterSum = 0.0;
    // Surfaces: how much of the element's view its own links and those below
    // it cover, on average over its area (formFactorSum plus the area-mean
    // coverage of its children). The push of irradiance to children uses it
    // (Solver: what coarse links bring goes to the part of each child's view
    // that finer links leave uncovered).
    double coverage = 0.0;
    glm::dvec3 radiosity{0.0};   // B; for clusters the area-weighted mean below
    // The B that the receivers of this element's links currently hold in
    // their irradiance: the in-place gather adds F times the difference.
    glm::dvec3 gathered{0.0};
    // The source luminance that refinement decisions use (update/OracleSteps.h):
    // set from B by the solve, then it follows B in steps while objects move:
    // anchor * kappa^level, the level set by how far B is from anchorLight
    // (its value when the solve ended), so that a scene moved back to where
    // it was solved is refined as it was.
    // Single precision, as the few digits a threshold test needs (four
    // bytes each matter: a building floor's links hold 64 bytes each,
    // elements included).
    float oracle = 0.0f;
    float anchor = 0.0f;
    float anchorLight = 0.0f;
    // Surfaces: the largest luminance of B among the leaves below (a leaf's
    // own). A link sends the mean B of its source, which stands for its
    // brightest part only as long as the link is fine enough: refinement
    // judges surfaces by this (update/OracleSteps.h).
    float peak = 0.0f;
    // Material (surfaces): the reflectance of the part of the polygon's
    // texture it covers, in single precision like the material's colour it
    // comes from (its emission is its polygon's: Hierarchy::emission).
    glm::vec3 reflectance{0.0f};

    // Links arriving here (this element is the receiver), in source order
    // (links/SourceOrder.h).
    IdList links;   // active
    IdList plinks;  // passive: refined, kept as line-space parents
    // Active links leaving this element (it is their source), for further
    // bounces (sec. 5.3.2) and to know what still depends on it; and the
    // p-links leaving it, judged again when its oracle changes.
    IdList outLinks;
    IdList outPlinks;

    static constexpr int kMaxDepth = 24;  // quadtree levels below a polygon
    bool isLeaf() const { return children.empty(); }
    // The parametric corners in double precision, for computing with them.
    std::array<glm::dvec2, 4> corners() const {
        return {glm::dvec2(param[0]), glm::dvec2(param[1]), glm::dvec2(param[2]), glm::dvec2(param[3])};
    }
    bool isSurface() const { return kind == ElementKind::Surface; }
};

// A surface element's sums over its own links, as they are gathered: the
// irradiance and the form factors, and the part of each on links from
// clusters (HElement::clusterIrradiance).
struct LinkSums {
    glm::dvec3 irradiance{0.0}, fromClusters{0.0};
    double sum = 0.0, clusterSum = 0.0;

    void add(const glm::dvec3& arriving, double formFactor, bool fromCluster) {
        irradiance += arriving;
        sum += formFactor;
        if (fromCluster) {
            fromClusters += arriving;
            clusterSum += formFactor;
        }
    }
    void storeIn(HElement& e) const {
        e.irradiance = irradiance;
        e.formFactorSum = sum;
        e.clusterIrradiance = fromClusters;
        e.clusterSum = clusterSum;
    }
};

}  // namespace rad
