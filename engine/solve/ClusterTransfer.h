#pragma once
// Light carried by links with a cluster end (Sillion 1995; Sillion,
// Drettakis, Soler 1995), with the clusters' orientation (ClusterShape).
//
// A link is a point-to-point transfer between the centres of its two ends:
//   - a cluster source sends toward the receiver the radiosity of its facets
//     that face it (ClusterShape::radiosityToward), from its projected area;
//   - a cluster receiver does not store what arrives: when it is pushed, each
//     of its links brings to each member surface the form factor from the
//     member to the source (by the member's own position and cosine, over a
//     few points of the source) times the link's visibility times the
//     radiosity sent. A surface facing away gets none, and each member gets
//     what its own view of the source allows, not a mean over the cluster.

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
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
// The same for a change of the source's state: a surface's change of B, or a
// cluster's change of facet powers.
glm::dvec3 sentChange(const Hierarchy& h, const Link& link, const glm::dvec3& surfaceChange,
                      const ClusterShape::Powers& facetChange);

// A source element as a few points for quadrature over its area: a surface's
// 2 x 2 Gauss points, a cluster's sample points on surfaces facing a given
// point, each with its normal and the area it stands for.
struct SourcePoints {
    static constexpr int kMax = 4;
    std::array<glm::dvec3, kMax> p{}, normal{};
    std::array<double, kMax> area{};
    std::array<std::uint32_t, kMax> polygon{};  // the input polygon each lies on
    int n = 0;
    double totalArea() const;
};
// surfaceOrder: the Gauss order on a surface (2: 2 x 2 points, 1: its centre).
SourcePoints sourcePoints(const Hierarchy& h, ElementId source, const glm::dvec3& toward,
                          int surfaceOrder = 2);
// The form factor from a point x of normal nx to the source (unoccluded),
// by quadrature over its points: sum of A_k cos_k cos_x / (pi r_k^2).
double pointToSource(const SourcePoints& source, const glm::dvec3& x, const glm::dvec3& nx);

// What a cluster's links bring to its members, by geometry: for each of its
// active links and each member (the input polygons below it, in hierarchy
// order, Hierarchy::memberSpan), the unoccluded form factor from the
// member's centre to the link's source (pointToSource). Built once per link
// set and geometry; a push multiplies it by each link's visibility and sent
// radiosity as currently held.
struct ArrivalTable {
    std::vector<LinkId> links;
    std::uint32_t firstMember = 0, memberCount = 0;
    std::vector<float> formFactors;  // [member * links.size() + link]
    bool built = false;
    std::size_t memoryBytes() const;
};
void buildArrivalTable(const Hierarchy& h, const LinkStore& links, ElementId cluster,
                       ArrivalTable& table);

// The arrivals of the clusters above a member, for a push: per cluster its
// table and, per link, the held visibility and the irradiance it brings to a
// surface of unit form factor (visibility times sent radiosity).
class Arrivals {
  public:
    // Adds a cluster's arrivals (from the links' gathered state); returns a
    // mark for drop().
    std::size_t add(const Hierarchy& h, const LinkStore& links, const ArrivalTable& table);
    void drop(std::size_t mark);
    // The irradiance and form-factor sum a member (an input polygon's own
    // element) takes from all clusters above it. A member facing away from a
    // source gets none from it (the table's form factor is zero).
    void resolve(const Hierarchy& h, const HElement& member, glm::dvec3& irradiance,
                 double& formFactorSum) const;

  private:
    struct Level {
        const ArrivalTable* table;
        std::size_t first;  // into the per-link values
    };
    std::vector<Level> levels_;
    std::vector<glm::dvec3> strength_;
    std::vector<double> visibility_;
};

}  // namespace rad
