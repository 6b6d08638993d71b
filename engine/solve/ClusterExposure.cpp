#include "solve/ClusterExposure.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>

namespace rad {

namespace {

// Per facet, one packet of rays: 4 points, 4 rays from each.
constexpr int kPointsPerFacet = 4;
constexpr int kRaysPerPoint = 4;
static_assert(kPointsPerFacet * kRaysPerPoint <= int(RayCaster::kMaxSegments));
// How far beyond its box a cluster's rays reach, in its box's size: a
// surface on the box's face or close behind it (a bookcase's back, the
// wall behind a row of books) blocks.
constexpr double kReach = 0.05;

// Cosine-weighted directions in a frame (t, b, n): point i's rays are a
// 2 x 2 stratification of the disk, turned by i's golden-angle offset so
// that a facet's 4 points look 16 ways.
glm::dvec3 localDirection(int sample, int ray) {
    const double u = ((ray & 1) + 0.5) / 2.0, v = ((ray >> 1) + 0.5) / 2.0;
    const double r = std::sqrt(u);
    const double phi = 2.0 * std::numbers::pi * v + sample * 2.399963229728653;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0 - u)};
}

// Where a ray from p along d leaves the box (p inside, or near it).
double exitDistance(const Aabb& box, const glm::dvec3& p, const glm::dvec3& d) {
    double t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0.0) t = std::min(t, (box.hi[a] - p[a]) / d[a]);
        if (d[a] < 0.0) t = std::min(t, (box.lo[a] - p[a]) / d[a]);
    }
    return std::max(t, 0.0);
}

// The member surface at `at` (an area, from 0 to the facet's) along
// facet k of a cluster: down through the children whose facets map to it
// (ClusterShape::childFacet), by their areas. kNone past the end (rounding).
ElementId memberAt(const Hierarchy& h, ElementId cluster, int k, double at) {
    for (ElementId e = cluster;;) {
        const ClusterShape& shape = h.shape(e);
        std::size_t entry = 0;
        ElementId next = kNone;
        for (ElementId child : h[e].children) {
            const HElement& c = h[child];
            if (c.isSurface()) {
                if (shape.childFacet[entry++] != k) continue;
                if (at <= c.area) return child;
                at -= c.area;
                continue;
            }
            const ClusterShape& inner = h.shape(child);
            for (int j = 0; j < inner.facetCount() && next == kNone; ++j) {
                if (shape.childFacet[entry++] != k) continue;
                if (at <= inner.facets[j].area) {
                    next = child;
                    k = j;
                } else {
                    at -= inner.facets[j].area;
                }
            }
            if (next != kNone) break;
        }
        if (next == kNone) return kNone;
        e = next;
    }
}

void measureOne(Hierarchy& h, const RayCaster& rays, ElementId id) {
    ClusterShape& shape = h.shape(id);
    shape.exposureMeasured = true;
    const int facets = shape.facetCount();
    for (ClusterShape::Facet& f : shape.facets) f.exposure = 1.0;
    if (facets < 2) return;  // one facet: nothing to divide
    const Aabb& box = h.box(id);
    const double margin = kReach * glm::length(box.extent());
    std::array<RayCaster::Segment, RayCaster::kMaxSegments> segments;
    for (int k = 0; k < facets; ++k) {
        // kPointsPerFacet points spread over the facet's area (the member
        // at each quantile, one of its quadrature points), kRaysPerPoint
        // cosine-distributed rays from each: one packet.
        std::size_t n = 0;
        for (int j = 0; j < kPointsPerFacet; ++j) {
            const ElementId member =
                memberAt(h, id, k, (j + 0.5) / kPointsPerFacet * shape.facets[k].area);
            if (member == kNone) continue;
            const HElement& surface = h[member];
            const QuadraturePoints& q = h.quadrature(member);
            const glm::dvec3 p =
                q.size() > 0 ? q.points[std::size_t(j) % q.size()].p : surface.center;
            const glm::dvec3 normal = surface.normal;
            const glm::dvec3 t =
                glm::normalize(std::abs(normal.x) < 0.9 ? glm::cross(normal, glm::dvec3(1, 0, 0))
                                                        : glm::cross(normal, glm::dvec3(0, 1, 0)));
            const glm::dvec3 b = glm::cross(normal, t);
            for (int r = 0; r < kRaysPerPoint; ++r) {
                const glm::dvec3 l = localDirection(j, r);
                const glm::dvec3 d = l.x * t + l.y * b + l.z * normal;
                segments[n++] = {p, p + (exitDistance(box, p, d) + margin) * d, surface.polygon,
                                 RayCaster::kNoPolygon};
            }
        }
        if (n == 0) continue;
        const std::span<const RayCaster::Segment> all(segments.data(), n);
        const std::uint16_t blocked =
            rays.blocked(Layer::Static, all) | rays.blocked(Layer::Dynamic, all);
        shape.facets[k].exposure = double(n - std::popcount(blocked)) / double(n);
    }
}

}  // namespace

void measureExposure(Hierarchy& h, const RayCaster& rays, std::span<const ElementId> clusters) {
    tbb::parallel_for(std::size_t(0), clusters.size(),
                      [&](std::size_t i) { measureOne(h, rays, clusters[i]); });
}

void measureExposure(Hierarchy& h, const RayCaster& rays) {
    std::vector<ElementId> clusters;
    for (ElementId e = 0; e < h.size(); ++e)
        if (h.isLive(e) && !h[e].isSurface() && h[e].shape != kNone) clusters.push_back(e);
    measureExposure(h, rays, clusters);
}

std::vector<ElementId> measureExposureAround(Hierarchy& h, const RayCaster& rays,
                                             std::span<const ExposureMotion> motions,
                                             std::span<const ElementId> also) {
    const auto widened = [&](const Aabb& b) {
        const glm::dvec3 reach(kReach * glm::length(b.extent()));
        return Aabb{b.lo - reach, b.hi + reach};
    };
    const auto meet = [](const Aabb& a, const Aabb& b) {
        return !a.empty() && !b.empty() && glm::all(glm::lessThanEqual(a.lo, b.hi)) &&
               glm::all(glm::lessThanEqual(b.lo, a.hi));
    };
    const auto meetsMotion = [&](const Aabb& b) {
        return std::any_of(motions.begin(), motions.end(), [&](const ExposureMotion& m) {
            return meet(b, m.oldBox) || meet(b, m.newBox);
        });
    };
    std::vector<ElementId> clusters(also.begin(), also.end());
    // Others' clusters that meet a moved box (a cluster's box holds its
    // children's: below one that meets none, none does), and others'
    // surfaces that do: what the moved objects' own clusters may meet.
    std::vector<Aabb> foreign;
    for (const ExposureMotion& m : motions) foreign.insert(foreign.end(), {m.oldBox, m.newBox});
    for (std::vector<ElementId> stack{h.root()}; !stack.empty();) {
        const ElementId e = stack.back();
        stack.pop_back();
        if (std::any_of(motions.begin(), motions.end(),
                        [&](const ExposureMotion& m) { return m.cluster == e; }))
            continue;
        const Aabb& box = h.box(e);
        if (h[e].isSurface()) {
            // Within the reach of the moved objects' clusters' rays.
            if (std::any_of(motions.begin(), motions.end(), [&](const ExposureMotion& m) {
                    return meet(box, widened(m.oldBox)) || meet(box, widened(m.newBox));
                }))
                foreign.push_back(box);
            continue;
        }
        if (!meetsMotion(widened(box))) continue;
        // One that holds a moved object keeps its exposure unless its facets
        // regrouped: that object is a small part of what its rays meet, and
        // measured again, the room's clusters moved past the tolerance with a
        // ray or two and were pushed whole, a tenth of a chair's frame.
        const bool holds =
            std::any_of(motions.begin(), motions.end(), [&](const ExposureMotion& m) {
                return m.cluster != kNone && h.range(e).contains(h.range(m.cluster));
            });
        if (!holds || !h.shape(e).exposureMeasured) clusters.push_back(e);
        for (ElementId c : h[e].children) stack.push_back(c);
    }
    for (const ExposureMotion& m : motions) {
        const auto mine = [&](std::size_t i) {
            return i >= 2 * std::size_t(&m - motions.data()) &&
                   i < 2 * std::size_t(&m - motions.data()) + 2;
        };
        for (std::vector<ElementId> stack{m.cluster}; !stack.empty();) {
            const ElementId e = stack.back();
            stack.pop_back();
            if (e == kNone || h[e].isSurface()) continue;
            const Aabb now = widened(h.box(e)), before{now.lo - m.shift, now.hi - m.shift};
            bool near = m.turned;
            for (std::size_t i = 0; i < foreign.size() && !near; ++i)
                near = !mine(i) && (meet(now, foreign[i]) || meet(before, foreign[i]));
            if (near) clusters.push_back(e);
            for (ElementId c : h[e].children) stack.push_back(c);
        }
    }
    std::sort(clusters.begin(), clusters.end());
    clusters.erase(std::unique(clusters.begin(), clusters.end()), clusters.end());
    std::erase_if(clusters, [&](ElementId e) {
        return !h.isLive(e) || h[e].isSurface() || h[e].shape == kNone;
    });
    std::vector<double> before;
    for (ElementId e : clusters)
        for (const ClusterShape::Facet& f : h.shape(e).facets) before.push_back(f.exposure);
    measureExposure(h, rays, clusters);
    std::vector<ElementId> changed;
    std::size_t i = 0;
    for (ElementId e : clusters) {
        double most = 0.0;
        for (const ClusterShape::Facet& f : h.shape(e).facets)
            most = std::max(most, std::abs(f.exposure - before[i++]));
        if (most > kExposureTolerance) changed.push_back(e);
    }
    return changed;
}

}  // namespace rad
