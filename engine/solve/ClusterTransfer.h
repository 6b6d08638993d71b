#pragma once
// Light carried by links with a cluster end (Sillion 1995; Sillion,
// Drettakis, Soler 1995), with the clusters' orientation (ClusterShape).
//
// A link is a point-to-point transfer between the centres of its two ends:
//   - a cluster source sends toward the receiver the radiosity of its facets
//     that face it (ClusterShape::radiosityToward), from its projected area;
//   - a cluster receiver keeps, per link, the kernel G at its centre (the
//     form factor per unit of the receiving surface's cosine) and resolves
//     what arrives per facet when it is pushed: a facet of normal n takes
//     G max(0, n . u) from a source in direction u, times the visibility and
//     the radiosity sent. Each member surface takes its facet's share, so a
//     surface facing away gets none, and the cluster as a whole catches
//     G times its projected area toward the source. A per-cluster sum over
//     its links, not a loop over members per link: pushing a cluster costs
//     its links times its facets, and each member one look-up.

#include <array>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "links/Link.h"

namespace rad {

// Unit vector from the centre of `from` toward the centre of `to` (zero when
// they coincide).
glm::dvec3 centreDirection(const Hierarchy& h, ElementId from, ElementId to);

// The radiosity the link's source sends to its receiver, as the receivers
// hold it (the source's gathered state).
glm::dvec3 sentRadiosity(const Hierarchy& h, const Link& link);
// What every source sends, from flat arrays: a surface's gathered
// radiosity; a cluster's centre, facets and gathered facet powers. For
// summing many receivers' links at once. Read from the elements, each link
// costs cache misses on its source's element and, for a cluster, on its
// shape: summing every receiver of `office` took 11 ms, and 8.6 with the
// surfaces alone read from an array; in later runs 7.0 to 7.7 ms that way
// and 5.8 to 6.7 with the clusters read from arrays too.
class SourceStates {
  public:
    explicit SourceStates(const Hierarchy& h);
    // sentRadiosity(h, link), the link's receiver centred at `receiverCentre`.
    glm::dvec3 sent(const Link& link, const glm::dvec3& receiverCentre) const;

  private:
    static constexpr std::uint32_t kSurface = ~0u;
    struct Source {
        glm::dvec3 value{0.0};          // a surface's gathered B; a cluster's centre
        std::uint32_t first = kSurface;  // a cluster's first facet in facets_ and powers_
        std::uint32_t count = 0;
    };
    std::vector<Source> sources_;  // per element
    std::vector<ClusterShape::Facet> facets_;
    std::vector<glm::dvec3> powers_;  // the facets' gathered powers
};
// The same for a change of the source's state: a surface's change of B, or a
// cluster's change of facet powers.
glm::dvec3 sentChange(const Hierarchy& h, const Link& link, const glm::dvec3& surfaceChange,
                      std::span<const glm::dvec3> facetChange);

// A source element as a few points for quadrature over its area: a surface's
// 2 x 2 Gauss points, a cluster's sample points on surfaces that face some
// of a given box (the other end of a link: facing its centre alone would
// leave a cluster beside a large element with no point that sees it, and a
// link without rays), each with its normal and the area it stands for.
struct SourcePoints {
    static constexpr int kMax = 4;
    // The first n are set; the rest are left unset (zeroing them was a tenth
    // of making the points, made twice for every link's rays).
    std::array<glm::dvec3, kMax> p, normal;
    std::array<double, kMax> area;
    std::array<std::uint32_t, kMax> polygon;  // the input polygon each lies on
    int n = 0;
    double totalArea() const;
};
// surfaceOrder: the Gauss order on a surface (2: 2 x 2 points, 1: its centre).
SourcePoints sourcePoints(const Hierarchy& h, ElementId source, const Aabb& toward,
                          int surfaceOrder = 2);
// The form factor from a point x of normal nx to the source (unoccluded),
// by quadrature over its points: sum of A_k cos_k cos_x / (pi r_k^2).
double pointToSource(const SourcePoints& source, const glm::dvec3& x, const glm::dvec3& nx);

// The kernel of the point approximation at x: the form factor from x to the
// source per unit of x's cosine toward it (sum of A_k cos_k / (pi r_k^2)).
double pointKernel(const SourcePoints& source, const glm::dvec3& x);

// What arrives at a cluster's facets from its links and those of the
// clusters above it.
using FacetArrivals = ClusterShape::Arrivals;

// Adds what the cluster's own active links bring (from their gathered state).
void addArrivals(const Hierarchy& h, const LinkStore& links, ElementId cluster,
                 FacetArrivals& arrivals);

// Adds one further-bounce transfer from `source` (the link's form factor
// times the change it sends) to the cluster's own arrivals, if they are
// valid (if not, the next push sums them from the links).
void addTransfer(Hierarchy& h, ElementId cluster, ElementId source, const glm::dvec3& irradiance);

// Walks a cluster's children in order with what each inherits from the
// cluster's facets: a child cluster its facets' values, a surface its own.
class ChildArrivals {
  public:
    ChildArrivals(const Hierarchy& h, ElementId cluster, const FacetArrivals& arrivals)
        : h_(h), shape_(h.shape(cluster)), arrivals_(arrivals) {}
    // The next child's arrivals (a cluster child).
    FacetArrivals cluster(ElementId child);
    // The next child's irradiance and form-factor sum (a surface child).
    void surface(glm::dvec3& irradiance, double& formFactorSum);

  private:
    const Hierarchy& h_;
    const ClusterShape& shape_;
    const FacetArrivals& arrivals_;
    std::size_t entry_ = 0;  // into shape_.childFacet
};

}  // namespace rad
