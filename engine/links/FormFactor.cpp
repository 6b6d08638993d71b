#include "links/FormFactor.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad {

namespace {

// Newell's vector area: twice the area times the unit normal; exact for planar polygons and
// well defined (zero) for degenerate ones. Taken relative to the first vertex, so that its
// rounding scales with the polygon's size, not with its distance from the origin.
glm::dvec3 vectorArea2(const PatchGeometry& polygon) {
    glm::dvec3 n(0.0);
    const int count = std::clamp(polygon.n, 0, 4);
    for (int i = 1; i + 1 < count; ++i) n += glm::cross(polygon.v[i] - polygon.v[0], polygon.v[i + 1] - polygon.v[0]);
    return n;
}

// Gauss-Legendre nodes and weights on [0, 1] (weights sum to 1), by Newton's iteration on the
// Legendre polynomial P_n from the Chebyshev-like initial guess cos(pi (i - 1/4) / (n + 1/2)).
void gaussLegendre01(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    nodes.assign(n, 0.0);
    weights.assign(n, 0.0);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double dp = 1.0;
        for (int iter = 0; iter < 100; ++iter) {
            // Three-term recurrence k P_k = (2k - 1) z P_{k-1} - (k - 1) P_{k-2}, up to P_n.
            double pk = z, pkm1 = 1.0;
            for (int k = 2; k <= n; ++k) {
                const double pk1 = ((2.0 * k - 1.0) * z * pk - (k - 1.0) * pkm1) / k;
                pkm1 = pk;
                pk = pk1;
            }
            dp = n * (z * pk - pkm1) / (z * z - 1.0);  // P_n'(z)
            const double dz = pk / dp;
            z -= dz;
            if (std::abs(dz) < 1e-16) break;
        }
        const double w = 2.0 / ((1.0 - z * z) * dp * dp);  // weight on [-1, 1]
        // Map [-1, 1] to [0, 1]: x = (1 - z) / 2 keeps nodes ascending; weights halve.
        nodes[i] = 0.5 * (1.0 - z);
        nodes[n - 1 - i] = 0.5 * (1.0 + z);
        weights[i] = weights[n - 1 - i] = 0.5 * w;
    }
}

struct GaussRule {
    std::vector<double> nodes, weights;
};

// The rules for orders 1..kMaxOrder, computed once: the Newton iteration above costs
// more than the form factor it serves.
const GaussRule& gaussRule(int order) {
    static const std::vector<GaussRule> rules = [] {
        std::vector<GaussRule> r(kMaxOrder + 1);
        for (int n = 1; n <= kMaxOrder; ++n) gaussLegendre01(n, r[n].nodes, r[n].weights);
        return r;
    }();
    return rules[order];
}

}  // namespace

double polygonArea(const PatchGeometry& polygon) { return 0.5 * glm::length(vectorArea2(polygon)); }

glm::dvec3 polygonNormal(const PatchGeometry& polygon) {
    const glm::dvec3 n = vectorArea2(polygon);
    const double len = glm::length(n);
    return len > 0.0 && std::isfinite(len) ? n / len : glm::dvec3(0.0);
}

namespace {

// atan2(y, x) for y >= 0, the angle between two vectors from |a x b| and
// a . b: the arctangent on [0, 1] by Abramowitz & Stegun 4.4.49 (error under
// 2e-8 rad, far below the quadrature's), reflected to [0, pi]. The library
// atan2 was a sixth of a solve.
double vectorAngle(double y, double x) {
    const double ax = std::abs(x);
    const bool steep = y > ax;
    const double t = steep ? ax / y : (ax > 0.0 ? y / ax : 0.0);
    const double t2 = t * t;
    double a = 0.0028662257;
    for (double c : {-0.0161657367, 0.0429096138, -0.0752896400, 0.1065626393, -0.1420889944, 0.1999355085,
                     -0.3333314528, 1.0})
        a = a * t2 + c;
    a *= t;
    if (steep) a = 0.5 * std::numbers::pi - a;
    return x < 0.0 ? std::numbers::pi - a : a;
}

// A 3- or 4-gon's unit normal, or zero when it is not one (or degenerate).
glm::dvec3 emitterNormal(const PatchGeometry& polygon) {
    return polygon.n < 3 || polygon.n > 4 ? glm::dvec3(0.0) : polygonNormal(polygon);
}

// pointToPolygonFormFactor, with the polygon's emitterNormal np computed once
// for all the points of a quadrature.
double pointToPolygon(const glm::dvec3& x, const glm::dvec3& nx, const PatchGeometry& polygon,
                      const glm::dvec3& np) {
    if (np == glm::dvec3(0.0)) return 0.0;

    // One-sided emitter: x must be strictly in front of the polygon's plane. The tolerance is
    // relative to the polygon's size and distance so that it means the same at every scale.
    const double height = glm::dot(np, x - polygon.v[0]);
    if (!(height > 0.0)) return 0.0;  // behind, in the plane, or NaN input
    std::array<glm::dvec3, 4> v;  // the vertices relative to x
    std::array<double, 4> side;   // their heights over x's tangent plane
    double scale2 = 0.0;          // squared: no root needed for a tolerance
    for (int i = 0; i < polygon.n; ++i) {
        v[i] = polygon.v[i] - x;
        side[i] = glm::dot(nx, v[i]);
        scale2 = std::max(scale2, glm::dot(v[i], v[i]));
    }
    if (!(height * height > 1e-24 * scale2)) return 0.0;
    // Nor closer than coordinates so far from the origin are rounded: a point
    // on the back face a doubleSided polygon gets, 1000 km out, lies up to
    // 1e-10 m off it and would see it as a whole hemisphere.
    if (!(height > 1e-13 * std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)}))) return 0.0;

    // Sutherland-Hodgman clip to the half-space above x's tangent plane (nx . (p - x) >= 0):
    // the Lambert contour integral below assumes the whole polygon is visible from x's front.
    // A convex polygon of 4 vertices clipped by one plane has at most 5.
    std::array<glm::dvec3, 8> r;  // clipped vertices relative to x (uninitialised: set before read)
    int count = 0;
    for (int i = 0; i < polygon.n; ++i) {
        const int j = i + 1 == polygon.n ? 0 : i + 1;
        const glm::dvec3& a = v[i];
        const glm::dvec3& b = v[j];
        const double sa = side[i], sb = side[j];
        if (sa >= 0.0) r[count++] = a;
        if ((sa > 0.0 && sb < 0.0) || (sa < 0.0 && sb > 0.0))
            r[count++] = a + (b - a) * (sa / (sa - sb));
    }
    if (count < 3) return 0.0;

    // Lambert's formula (Hottel & Sarofim; Cohen & Wallace 1993, eq. 4.22):
    //   F(dA_x -> A) = 1/(2 pi) * sum_i beta_i * (nx . gamma_i),
    // beta_i the angle subtended at x by edge i, gamma_i the unit normal of the triangle
    // (x, v_i, v_i+1). With counter-clockwise-front winding seen from x, gamma_i is taken as
    // unit(r_{i+1} x r_i). beta_i = atan2(|c|, r_i . r_{i+1}) (vectorAngle) stays accurate for tiny and
    // near-straight angles, unlike acos of a normalised dot product.
    std::array<double, 8> length2;
    for (int i = 0; i < count; ++i) length2[i] = glm::dot(r[i], r[i]);
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
        const int j = (i + 1) % count;
        const glm::dvec3& ri = r[i];
        const glm::dvec3& rj = r[j];
        const glm::dvec3 c = glm::cross(rj, ri);
        const double cl2 = glm::dot(c, c);
        // Coincident vertices or an edge through x (only possible within the plane tolerance):
        // the edge subtends no solid angle we can orient; skip it instead of dividing by zero.
        if (!(cl2 > 1e-30 * length2[i] * length2[j])) continue;
        const double cl = std::sqrt(cl2);
        const double beta = vectorAngle(cl, glm::dot(ri, rj));
        sum += beta * glm::dot(nx, c) / cl;
    }
    const double f = sum / (2.0 * std::numbers::pi);
    return std::isfinite(f) ? std::clamp(f, 0.0, 1.0) : 0.0;
}

}  // namespace

double pointToPolygonFormFactor(const glm::dvec3& x, const glm::dvec3& nx,
                                const PatchGeometry& polygon) {
    return pointToPolygon(x, nx, polygon, emitterNormal(polygon));
}

SampleSet patchSamples(const PatchGeometry& patch, int order) {
    order = std::clamp(order, 1, kMaxOrder);
    SampleSet samples;
    const auto add = [&](const glm::dvec3& p, double w) { samples.points[samples.count++] = {p, w}; };
    if (patch.n < 3 || patch.n > 4) {
        // Not a polygon: one point at the mean of the given vertices.
        const int count = std::clamp(patch.n, 1, 4);
        glm::dvec3 c(0.0);
        for (int i = 0; i < count; ++i) c += patch.v[i];
        add(c / double(count), 1.0);
        return samples;
    }
    const std::vector<double>& t = gaussRule(order).nodes;
    const std::vector<double>& w = gaussRule(order).weights;
    double total = 0.0;
    const auto& v = patch.v;
    if (patch.n == 4) {
        // Bilinear map p(u,v) of the unit square onto the quad; the weight is the GL product
        // weight times the Jacobian |p_u x p_v| (linear in u, v for a planar quad, so the sum
        // is exactly the area before normalisation).
        for (int i = 0; i < order; ++i) {
            for (int j = 0; j < order; ++j) {
                const double u = t[i], s = t[j];
                const glm::dvec3 p = (1 - u) * (1 - s) * v[0] + u * (1 - s) * v[1] + u * s * v[2] +
                                     (1 - u) * s * v[3];
                const glm::dvec3 pu = (1 - s) * (v[1] - v[0]) + s * (v[2] - v[3]);
                const glm::dvec3 ps = (1 - u) * (v[3] - v[0]) + u * (v[2] - v[1]);
                const double wk = w[i] * w[j] * glm::length(glm::cross(pu, ps));
                add(p, wk);
                total += wk;
            }
        }
    } else {
        // Collapsed square (Duffy): p(s,t) = v0 + s (v1 - v0) + s t (v2 - v1), Jacobian 2 A s.
        for (int i = 0; i < order; ++i) {
            for (int j = 0; j < order; ++j) {
                const double s = t[i], q = t[j];
                const glm::dvec3 p = v[0] + s * (v[1] - v[0]) + s * q * (v[2] - v[1]);
                const double wk = w[i] * w[j] * 2.0 * s;
                add(p, wk);
                total += wk;
            }
        }
    }
    for (std::size_t i = 0; i < samples.count; ++i)
        samples.points[i].w = total > 0.0 && std::isfinite(total) ? samples.points[i].w / total
                                                                  : 1.0 / double(samples.count);
    return samples;
}

QuadraturePoints quadraturePoints(const PatchGeometry& patch) {
    const SampleSet all = patchSamples(patch, 2);
    QuadraturePoints q;
    for (const SamplePoint& s : all) q.points[q.count++] = s;
    return q;
}

PackedQuadrature pack(const QuadraturePoints& points, const glm::dvec3& origin) {
    PackedQuadrature packed;
    for (const SamplePoint& s : points) {
        packed.offset[packed.count] = glm::vec3(s.p - origin);
        packed.weight[packed.count++] = static_cast<float>(s.w);
    }
    return packed;
}

QuadraturePoints unpack(const PackedQuadrature& packed, const glm::dvec3& origin) {
    QuadraturePoints points;
    for (; points.count < packed.count; ++points.count)
        points.points[points.count] = {origin + glm::dvec3(packed.offset[points.count]), packed.weight[points.count]};
    return points;
}

namespace {

// The mean, least and largest form factor from the receiver's points to the source.
template <class Points>
FormFactorEstimate estimateOver(const Points& points, const PatchGeometry& receiver, const PatchGeometry& source) {
    FormFactorEstimate e;
    const glm::dvec3 nr = polygonNormal(receiver);
    if (nr == glm::dvec3(0.0)) return e;
    e.min = INFINITY;
    const glm::dvec3 ns = emitterNormal(source);
    for (const SamplePoint& s : points) {
        const double f = pointToPolygon(s.p, nr, source, ns);
        e.mean += s.w * f;
        e.min = std::min(e.min, f);
        e.max = std::max(e.max, f);
    }
    return e;
}

}  // namespace

FormFactorEstimate estimateFormFactor(const PatchGeometry& receiver, const PatchGeometry& source,
                                      int order) {
    return estimateOver(patchSamples(receiver, order), receiver, source);
}

FormFactorEstimate estimateFormFactor(const QuadraturePoints& receiverPoints, const PatchGeometry& receiver,
                                      const PatchGeometry& source) {
    return estimateOver(receiverPoints, receiver, source);
}

double polygonToPolygonFormFactor(const PatchGeometry& receiver, const PatchGeometry& source,
                                  int order) {
    return estimateFormFactor(receiver, source, order).mean;
}

double pointApproxFormFactor(double aSource, double gSource, double gReceiver,
                             double distanceSquared) {
    const double numerator = aSource * gSource * gReceiver;
    if (!(numerator > 0.0)) return 0.0;
    if (!(distanceSquared > 0.0)) return 1.0;
    const double f = numerator / (std::numbers::pi * distanceSquared);
    return std::isfinite(f) ? std::min(f, 1.0) : 1.0;
}

}  // namespace rad
