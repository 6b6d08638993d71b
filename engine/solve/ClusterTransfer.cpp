#include "solve/ClusterTransfer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <tbb/parallel_for.h>

#include "links/FormFactor.h"

namespace rad {

namespace {

// The unit vector from a toward b (zero when they coincide).
glm::dvec3 unitToward(const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 d = b - a;
    const double len = glm::length(d);
    return len > 0.0 ? d / len : glm::dvec3(0.0);
}

}  // namespace

glm::dvec3 centreDirection(const Hierarchy& h, ElementId from, ElementId to) {
    return unitToward(h[from].center, h[to].center);
}

glm::dvec3 sentRadiosity(const Hierarchy& h, const Link& link) {
    const HElement& s = h[link.source];
    if (s.isSurface()) return s.gathered;
    const ClusterShape& shape = h.shape(link.source);
    return shape.radiosityToward(centreDirection(h, link.source, link.receiver), shape.gathered);
}

SourceStates::SourceStates(const Hierarchy& h) : sources_(h.size()) {
    // Each element's state, then the clusters' facets placed one after
    // another and copied, on all cores.
    tbb::parallel_for(ElementId(0), static_cast<ElementId>(h.size()), [&](ElementId e) {
        const HElement& el = h[e];
        if (el.isSurface()) {
            sources_[e].value = el.gathered;
        } else if (el.shape != kNone) {  // a cluster (a freed element has no shape)
            sources_[e].value = el.center;
            sources_[e].first = 0;  // placed below
            sources_[e].count = static_cast<std::uint32_t>(h.shape(e).facetCount());
        }
    });
    std::uint32_t next = 0;
    for (Source& s : sources_)
        if (s.first != kSurface) {
            s.first = next;
            next += s.count;
        }
    facets_.resize(next);
    powers_.resize(next);
    tbb::parallel_for(ElementId(0), static_cast<ElementId>(h.size()), [&](ElementId e) {
        const Source& s = sources_[e];
        if (s.count == 0) return;
        const ClusterShape& shape = h.shape(e);
        std::copy_n(shape.facets.begin(), s.count, facets_.begin() + s.first);
        std::copy_n(shape.gathered.begin(), s.count, powers_.begin() + s.first);
    });
}

glm::dvec3 SourceStates::sent(const Link& link, const glm::dvec3& receiverCentre) const {
    const Source& s = sources_[link.source];
    if (s.first == kSurface) return s.value;
    // centreDirection(h, link.source, link.receiver), from the copied centre.
    return ClusterShape::radiosityToward(std::span(facets_.data() + s.first, s.count), unitToward(s.value, receiverCentre),
                                         std::span(powers_.data() + s.first, s.count));
}

glm::dvec3 sentChange(const Hierarchy& h, const Link& link, const glm::dvec3& surfaceChange,
                      std::span<const glm::dvec3> facetChange) {
    if (h[link.source].isSurface()) return surfaceChange;
    return h.shape(link.source)
        .radiosityToward(centreDirection(h, link.source, link.receiver), facetChange);
}

double SourcePoints::totalArea() const {
    double a = 0.0;
    for (int k = 0; k < n; ++k) a += area[k];
    return a;
}

SourcePoints sourcePoints(const Hierarchy& h, ElementId source, const Aabb& toward,
                          int surfaceOrder) {
    SourcePoints out;
    const HElement& s = h[source];
    if (s.isSurface()) {
        const auto take = [&](const auto& points) {
            for (const SamplePoint& q : points) {
                if (out.n == SourcePoints::kMax) break;
                out.p[out.n] = q.p;
                out.normal[out.n] = h.normal(s);
                out.polygon[out.n] = s.polygon;
                out.area[out.n++] = q.w * s.area;
            }
        };
        if (surfaceOrder == 2)
            take(h.quadrature(source));
        else
            take(patchSamples(h.patch(source), surfaceOrder));
        return out;
    }
    // The cluster's points on surfaces facing `toward`, evenly picked from
    // its stratified order; each stands for its share of the facing area.
    const ClusterShape& shape = h.shape(source);
    const glm::dvec3 centre = toward.center(), half = 0.5 * toward.extent();
    const double tolerance = 1e-9 * glm::length(half);
    const auto faces = [&](const glm::dvec3& p, const glm::dvec3& n) {
        // The box's farthest corner along the normal lies in front of the plane.
        return glm::dot(n, centre - p) + glm::dot(glm::abs(n), half) > tolerance;
    };
    // Facing is a sign: the octahedron point serves as well as the unit normal.
    std::array<int, ClusterShape::kSamples> facing{};
    int count = 0;
    for (int k = 0; k < shape.sampleCount; ++k)
        if (faces(s.center + glm::dvec3(shape.samples[k].p), shape.samples[k].octahedronPoint())) facing[count++] = k;
    const double facingArea = count * double(shape.sampleWeight);
    const int n = std::min(count, SourcePoints::kMax);
    for (int i = 0; i < n; ++i) {
        const int k = facing[i * count / n];
        out.p[out.n] = s.center + glm::dvec3(shape.samples[k].p);
        out.normal[out.n] = shape.samples[k].normal();
        out.polygon[out.n] = shape.samples[k].polygon;
        out.area[out.n++] = facingArea / n;
    }
    return out;
}

double pointToSource(const SourcePoints& source, const glm::dvec3& x, const glm::dvec3& nx) {
    double f = 0.0;
    for (int k = 0; k < source.n; ++k) {
        const glm::dvec3 d = source.p[k] - x;
        const double r2 = glm::dot(d, d);
        if (!(r2 > 0.0)) continue;
        const double cx = glm::dot(nx, d), cs = -glm::dot(source.normal[k], d);
        if (cx <= 0.0 || cs <= 0.0) continue;  // one-sided at both ends
        f += source.area[k] * cx * cs / (std::numbers::pi * r2 * r2);
    }
    return std::min(f, 1.0);
}

double pointKernel(const SourcePoints& source, const glm::dvec3& x) {
    double g = 0.0;
    for (int k = 0; k < source.n; ++k) {
        const glm::dvec3 d = source.p[k] - x;
        const double r2 = glm::dot(d, d);
        const double cs = -glm::dot(source.normal[k], d);
        if (r2 > 0.0 && cs > 0.0)
            g += source.area[k] * cs / (std::numbers::pi * r2 * std::sqrt(r2));
    }
    return std::min(g, 1.0);
}

void addArrivals(const Hierarchy& h, const LinkStore& links, ElementId cluster,
                 FacetArrivals& arrivals) {
    const ClusterShape& shape = h.shape(cluster);
    const IdList& own = h[cluster].links;
    for (std::size_t k = 0; k < own.size(); ++k) {
        links.prefetchAhead(own, k);
        const Link& l = links[own[k]];
        if (l.gathered == 0.0) continue;
        const glm::dvec3 u = centreDirection(h, cluster, l.source);
        // sentRadiosity, with a cluster source's direction toward the
        // receiver taken as -u (the same numbers: it is u's negation, exactly).
        const HElement& s = h[l.source];
        const glm::dvec3 sent = s.isSurface() ? s.gathered : h.shape(l.source).radiosityToward(-u, h.shape(l.source).gathered);
        // The light by exposure (ClusterShape::arrivalWeights); the view the
        // link covers, which the energy guard and the fill read, by
        // orientation: a hidden facet's view is covered, and lit by nothing.
        std::array<double, ClusterShape::kMaxFacets> w, c;
        shape.arrivalWeights(u, w, c);
        for (int k = 0; k < shape.facetCount(); ++k) {
            if (c[k] <= 0.0) continue;  // one-sided: facing away, it gets none
            arrivals.irradiance[k] += w[k] * l.gathered * sent;
            arrivals.formFactorSum[k] += c[k] * l.gathered;
        }
    }
}

void addTransfer(Hierarchy& h, ElementId cluster, ElementId source, const glm::dvec3& irradiance) {
    ClusterShape& shape = h.shape(cluster);
    if (!shape.ownValid) return;
    std::array<double, ClusterShape::kMaxFacets> w, c;
    shape.arrivalWeights(centreDirection(h, cluster, source), w, c);
    for (int k = 0; k < shape.facetCount(); ++k)
        if (w[k] > 0.0) shape.ownIrradiance[k] += w[k] * irradiance;
}

FacetArrivals ChildArrivals::cluster(ElementId child) {
    FacetArrivals out;
    const ClusterShape& childShape = h_.shape(child);
    for (int j = 0; j < childShape.facetCount(); ++j) {
        const std::uint8_t k = shape_.childFacet[entry_++];
        out.irradiance[j] = arrivals_.irradiance[k];
        out.formFactorSum[j] = arrivals_.formFactorSum[k];
    }
    return out;
}

void ChildArrivals::surface(glm::dvec3& irradiance, double& formFactorSum) {
    const std::uint8_t k = shape_.childFacet[entry_++];
    irradiance += arrivals_.irradiance[k];
    formFactorSum += arrivals_.formFactorSum[k];
}

}  // namespace rad
