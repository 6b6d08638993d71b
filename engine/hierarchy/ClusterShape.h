#pragma once
// The orientation of a cluster (Sillion 1995; Sillion, Drettakis, Soler 1995):
// what a cluster looks like from a direction. A cluster is not an isotropic
// blob: a wall cluster seen edge-on shows nothing, seen face-on all of its
// area, and only the front sides of its surfaces emit and receive.
//
// The shape is built once from the member surfaces (and again when they
// move), bottom-up from the children's shapes:
//   - facets: the member surfaces grouped by normal, with their areas. The
//     projected area toward a direction is sum_k A_k max(0, n_k . dir), and
//     the radiosity the cluster sends that way is the facets' B A weighted
//     the same way. Surfaces of equal normal share a facet exactly; beyond
//     kMaxFacets normals, the closest are merged (area-weighted normal), which
//     keeps every facet's emitted power and approximates only its direction;
//   - visibility sample points on the member surfaces' front sides, spread by
//     area; a link uses those whose surfaces face its other end.
// The facets' powers (sum of B A) are the solution state the push-pull
// refreshes; `gathered` is what the receivers of the cluster's links hold
// (the in-place gather of eq. 1, 2 works on it as on a surface's B).

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace rad {

struct ClusterShape {
    static constexpr int kMaxFacets = 12;
    // What arrives at each facet: the irradiance on a surface with the
    // facet's normal, and the form factors it came through (for the energy
    // guard).
    struct Arrivals {
        std::array<glm::dvec3, kMaxFacets> irradiance{};
        std::array<double, kMaxFacets> formFactorSum{};
    };
    static constexpr int kSamples = 16;

    struct Facet {
        glm::dvec3 normal{0.0};
        double area = 0.0;
        // The share of the facet's area that light from outside the
        // cluster's box can reach (solve/ClusterExposure.h); 1 until
        // measured. And which of the rays that measured it the static
        // layer blocks: a move measures again only the dynamic part of a
        // cluster that did not move.
        float exposure = 1.0f;
        std::uint16_t staticBlocked = 0;
    };
    // A visibility sample point: 20 bytes, 16 per cluster (it was 32 and
    // the samples were a quarter of a building floor's cluster memory). The
    // position is single precision and relative to the cluster's centre
    // (HElement::center), so that it is as precise as the cluster is small
    // wherever the scene lies: in world coordinates a float is 6e-5 m coarse
    // 1 km from the origin, and such points let 1.5% more light into a
    // lampshade than it was sent. The normal is octahedral in two 16-bit fixed-point numbers
    // (Cigolle et al. 2014, "A survey of efficient representations for
    // independent unit vectors"): within 1e-4 radians, and exact for the
    // axis-aligned walls, floors and ceilings most scenes are made of. Every
    // sample stands for the same area, the shape's sampleWeight.
    struct Sample {
        glm::vec3 p{0.0f};
        std::uint32_t octNormal = 0;
        std::uint32_t polygon = 0;
        static std::uint32_t encode(const glm::dvec3& unitNormal);
        // The point of the octahedron the normal maps to: its direction, not
        // unit length. Inline: a link with a cluster end tests all 16 for
        // facing (solve/ClusterTransfer.cpp).
        glm::dvec3 octahedronPoint() const {
            const auto real = [](std::uint32_t bits) {
                return static_cast<std::int16_t>(static_cast<std::uint16_t>(bits)) / 32767.0;
            };
            glm::dvec3 n(real(octNormal), real(octNormal >> 16), 0.0);
            n.z = 1.0 - std::abs(n.x) - std::abs(n.y);
            if (n.z < 0.0) {  // the lower half, folded back
                const double x = n.x;
                n.x = (1.0 - std::abs(n.y)) * (x < 0.0 ? -1.0 : 1.0);
                n.y = (1.0 - std::abs(x)) * (n.y < 0.0 ? -1.0 : 1.0);
            }
            return n;
        }
        glm::dvec3 normal() const { return glm::normalize(octahedronPoint()); }
    };
    // A value per facet, of fixed size: for temporaries.
    using Powers = std::array<glm::dvec3, kMaxFacets>;

    // The facets and their solution state below are sized to the facets a
    // cluster has (4.5 of the 12 on average in `office`): 12 each would take
    // 800 bytes more per cluster, 3 bytes per link.
    std::vector<Facet> facets;
    int facetCount() const { return static_cast<int>(facets.size()); }
    std::array<Sample, kSamples> samples{};
    int sampleCount = 0;
    float sampleWeight = 0.0f;  // the area each sample stands for
    // For each child in order, and each facet of that child (one for a
    // surface), the facet of this cluster it belongs to.
    std::vector<std::uint8_t> childFacet;
    // The facets' exposure is measured (solve/ClusterExposure.h): false
    // until then, and again when they regroup.
    bool exposureMeasured = false;

    std::vector<glm::dvec3> power;     // per facet: sum of B A over its members
    std::vector<glm::dvec3> gathered;  // the power the receivers of its links hold
    // What its own active links bring (Arrivals, per facet), as a surface
    // keeps its irradiance: summed from the links again when not valid (its
    // links or its facets changed), added to by further bounces (sec. 5.3.2)
    // so that a bounce costs its transfers, not a walk over every link of
    // the cluster.
    std::vector<glm::dvec3> ownIrradiance;
    std::vector<double> ownFormFactorSum;
    bool ownValid = false;

    // sum_k A_k max(0, n_k . dir), dir a unit vector.
    double projectedArea(const glm::dvec3& dir) const;
    // How the light arriving from direction u (unit, toward the source)
    // divides among the facets: facet k takes w_k per unit of its area,
    // c_k e_k s with c_k = max(0, n_k . u), e_k its exposure and s such that
    // sum_k A_k w_k = sum_k A_k c_k (the cluster catches what its projected
    // area does). Facets that face away take 0. `c` gets the c_k.
    void arrivalWeights(const glm::dvec3& u, std::array<double, kMaxFacets>& w,
                        std::array<double, kMaxFacets>& c) const;
    // The radiosity the cluster sends toward dir (unit): the facets' powers
    // weighted by their projected areas, over the projected area; zero when
    // no facet faces dir.
    glm::dvec3 radiosityToward(const glm::dvec3& dir, std::span<const glm::dvec3> powers) const {
        return radiosityToward(facets, dir, powers);
    }
    // The same from given facets (a copy kept apart: solve/ClusterTransfer.h).
    static glm::dvec3 radiosityToward(std::span<const Facet> facets, const glm::dvec3& dir,
                                      std::span<const glm::dvec3> powers);
    // The largest radiosity luminance of a facet (a bound on what it sends).
    double peakLuminance(std::span<const glm::dvec3> powers) const;
    // Keeps `own` as what its own links bring (and sets ownValid).
    void keepOwn(const Arrivals& own);
    // Adds what its own links bring to `arrivals`.
    void addOwn(Arrivals& arrivals) const;
    // Bytes its facet and child-facet vectors hold.
    std::size_t heapBytes() const;
};

// What a child contributes to a shape: its facets, its sample points and
// the area each of them stands for.
struct ShapePart {
    std::span<const ClusterShape::Facet> facets;
    std::span<const ClusterShape::Sample> samples;
    double sampleWeight = 0.0;
    // Added to the samples' positions to make them relative to the new
    // cluster's centre (a child cluster's centre minus the new one's).
    glm::dvec3 offset{0.0};
};

// Builds a cluster's facets, mapping and sample points from its children's
// parts (powers are left to the caller: they are solution state).
void buildShape(std::span<const ShapePart> children, ClusterShape& shape);

}  // namespace rad
