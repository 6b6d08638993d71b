#pragma once
// Form factors between differential areas, polygons and clusters, in double precision.
//
// Conventions: polygons are one-sided; counter-clockwise seen from the front is the front, the
// side that emits and receives. F(receiver -> source) is the fraction of the energy leaving the
// receiver (diffusely) that arrives at the source, which is the factor used in the gather
// B_r = E_r + rho_r * sum_s F(r -> s) B_s.

#include <array>
#include <glm/glm.hpp>
#include <vector>

namespace rad {

// A planar convex polygon (3 or 4 vertices, counter-clockwise = front).
struct PatchGeometry {
    std::array<glm::dvec3, 4> v{};
    int n = 3;
};

// Area of the polygon (Newell's vector area; 0 for degenerate input).
double polygonArea(const PatchGeometry& polygon);

// Unit front normal from the winding (Newell's method), or zero for a degenerate polygon.
glm::dvec3 polygonNormal(const PatchGeometry& polygon);

// Form factor from a differential area at x (unit normal nx) to the FRONT side of `polygon`:
// the analytic contour integral (Lambert / Hottel), after clipping the polygon to the half-space
// above x's tangent plane. Zero when x lies behind or in the polygon's plane (one-sided emitter).
double pointToPolygonFormFactor(const glm::dvec3& x, const glm::dvec3& nx,
                                const PatchGeometry& polygon);

// Area-averaged form factor F(receiver -> source) = (1/A_r) ∫_r F(dA_x -> source) dA_x,
// by a deterministic quadrature over the receiver with about order*order points
// (Gauss-Legendre on the quad's bilinear parametrisation; for a triangle the collapsed-square
// (Duffy) rule). Only the receiver is sampled: the inner integral is exact.
double polygonToPolygonFormFactor(const PatchGeometry& receiver, const PatchGeometry& source,
                                  int order = 4);

// The same, with the smallest and largest point form factor met at the
// quadrature points: how much the transfer varies across the receiver.
struct FormFactorEstimate {
    double mean = 0.0;
    double min = 0.0;
    double max = 0.0;
};
FormFactorEstimate estimateFormFactor(const PatchGeometry& receiver, const PatchGeometry& source,
                                      int order = 4);

// Quadrature points (and weights summing to 1) over a patch, used also for visibility rays.
// order is clamped to [1, kMaxOrder]; a quad gives order*order points, a triangle order*order
// points of the collapsed square. A degenerate (zero-area) patch gives equal weights. Fixed
// storage: links are computed by the million, and a heap allocation per call costs more than
// the points.
struct SamplePoint {
    glm::dvec3 p;
    double w;
};
inline constexpr int kMaxOrder = 16;
struct SampleSet {
    std::array<SamplePoint, kMaxOrder * kMaxOrder> points;
    std::size_t count = 0;
    const SamplePoint* begin() const { return points.data(); }
    const SamplePoint* end() const { return points.data() + count; }
    std::size_t size() const { return count; }
    const SamplePoint& operator[](std::size_t i) const { return points[i]; }
};
SampleSet patchSamples(const PatchGeometry& patch, int order);

// patchSamples(patch, 2): the points of the visibility rays and of a
// cluster end's surface, made once per element (Hierarchy::quadrature)
// rather than for every link.
struct QuadraturePoints {
    std::array<SamplePoint, 4> points;
    std::size_t count = 0;
    const SamplePoint* begin() const { return points.data(); }
    const SamplePoint* end() const { return points.data() + count; }
    std::size_t size() const { return count; }
};
QuadraturePoints quadraturePoints(const PatchGeometry& patch);

// QuadraturePoints as an element keeps them (Hierarchy::quadrature): each
// point's offset from the patch's first corner, and its weight, in single
// precision; 68 bytes instead of 136 (1.8 bytes a link in `office`). An
// offset is within 6e-8 of the element's size, sixteen times finer than the
// tolerance within which a ray's end counts as on a surface (RayCaster's
// coincidenceOfSize, 1e-6 of the polygon's size).
struct PackedQuadrature {
    std::array<glm::vec3, 4> offset{};
    std::array<float, 4> weight{};
    std::uint32_t count = 0;
};
PackedQuadrature pack(const QuadraturePoints& points, const glm::dvec3& origin);
QuadraturePoints unpack(const PackedQuadrature& packed, const glm::dvec3& origin);

// estimateFormFactor with the receiver's points given: its quadraturePoints.
FormFactorEstimate estimateFormFactor(const QuadraturePoints& receiverPoints, const PatchGeometry& receiver,
                                      const PatchGeometry& source);

// Point approximation used for links with a cluster end (Sillion 1995): the form factor from a
// receiver to a source seen as a small element of area aSource, with orientation factors:
// F = aSource * gSource * gReceiver / (pi * d^2), where g is the cosine toward the other end
// (clusters: the projected area over the area, ClusterShape).
// The result is clamped to [0, 1] (a form factor cannot exceed one; the point approximation does
// when d is small compared with the source); d^2 <= 0 gives 1 if the numerator is positive.
double pointApproxFormFactor(double aSource, double gSource, double gReceiver,
                             double distanceSquared);

}  // namespace rad
