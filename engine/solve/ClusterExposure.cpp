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

// For a surface that is an axis-aligned rectangle (its area that of its
// box's face), the axis of its normal; -1 otherwise.
int planeAxis(const Hierarchy& h, ElementId id) {
    const HElement& surface = h[id];
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (std::abs(h.normal(surface)[a]) > std::abs(h.normal(surface)[axis])) axis = a;
    if (std::abs(h.normal(surface)[axis]) < 1.0 - 1e-12 || h.cornerCount(id) != 4) return -1;
    const PatchGeometry patch = h.patch(id);
    glm::dvec3 lo = patch.v[0], hi = lo;
    for (int i = 1; i < 4; ++i) {
        lo = glm::min(lo, patch.v[i]);
        hi = glm::max(hi, patch.v[i]);
    }
    const glm::dvec3 e = hi - lo;
    const double face = e[(axis + 1) % 3] * e[(axis + 2) % 3];
    return std::abs(face - surface.area) <= 1e-9 * face ? axis : -1;
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

// `staticKnown`: the cluster has not moved since it was last measured, and
// neither has the static layer near it: its rays are those it cast then,
// and only the dynamic layer is asked.
void measureOne(Hierarchy& h, const RayCaster& rays, ElementId id, bool staticKnown) {
    ClusterShape& shape = h.shape(id);
    staticKnown = staticKnown && shape.exposureMeasured;
    shape.exposureMeasured = true;
    const int facets = shape.facetCount();
    for (ClusterShape::Facet& f : shape.facets) f.exposure = 1.0f;
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
            const QuadraturePoints q = h.quadrature(member);
            const glm::dvec3 p =
                q.size() > 0 ? q.points[std::size_t(j) % q.size()].p : surface.center;
            const glm::dvec3 normal = h.normal(surface);
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
        ClusterShape::Facet& f = shape.facets[k];
        if (!staticKnown) f.staticBlocked = rays.blocked(Layer::Static, all);
        const std::uint16_t blocked = f.staticBlocked | rays.blocked(Layer::Dynamic, all);
        f.exposure = float(double(n - std::popcount(blocked)) / double(n));
    }
}

}  // namespace

void measureExposure(Hierarchy& h, const RayCaster& rays, std::span<const ElementId> clusters,
                     std::span<const std::uint8_t> staticKnown) {
    tbb::parallel_for(std::size_t(0), clusters.size(), [&](std::size_t i) {
        measureOne(h, rays, clusters[i], i < staticKnown.size() && staticKnown[i]);
    });
}

void measureExposure(Hierarchy& h, const RayCaster& rays) {
    std::vector<ElementId> clusters;
    for (ElementId e = 0; e < h.size(); ++e)
        if (h.isLive(e) && !h[e].isSurface() && h[e].shape != kNone) clusters.push_back(e);
    measureExposure(h, rays, clusters);
}

std::vector<ElementId> measureExposureAround(Hierarchy& h, const RayCaster& rays,
                                             std::span<const ExposureMotion> motions,
                                             std::span<const ElementId> also, bool layersChanged) {
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
    // (cluster, whether its static part is known: it did not move and its
    // facets did not regroup)
    std::vector<std::pair<ElementId, std::uint8_t>> found;
    for (ElementId e : also) found.emplace_back(e, 0);
    // Others' clusters that meet a moved box (a cluster's box holds its
    // children's: below one that meets none, none does), and others'
    // surfaces that do: what the moved objects' own clusters may meet.
    struct Foreign {
        Aabb box;
        ElementId surface = kNone;  // kNone: another moved object's box
    };
    std::vector<Foreign> foreign;
    for (const ExposureMotion& m : motions) foreign.insert(foreign.end(), {{m.oldBox}, {m.newBox}});
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
                foreign.push_back({box, e});
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
        if (!holds || !h.shape(e).exposureMeasured) found.emplace_back(e, layersChanged ? 0 : 1);
        for (ElementId c : h[e].children) stack.push_back(c);
    }
    for (std::size_t index = 0; index < motions.size(); ++index) {
        const ExposureMotion& m = motions[index];
        // Its own boxes, first in `foreign`, are not in its way.
        const auto mine = [&](std::size_t i) { return i / 2 == index && i < 2 * motions.size(); };
        for (std::vector<ElementId> stack{m.cluster}; !stack.empty();) {
            const ElementId e = stack.back();
            stack.pop_back();
            if (e == kNone || h[e].isSurface()) continue;
            const Aabb now = widened(h.box(e)), before{now.lo - m.shift, now.hi - m.shift};
            // The planes the cluster slides along, covered by axis-aligned
            // rectangles wherever it stands before and after (a floor of
            // tiles under a chair), stand where they stood to it.
            const Aabb both{glm::min(now.lo, before.lo), glm::max(now.hi, before.hi)};
            const auto alongside = [&](const Foreign& f) {
                if (f.surface == kNone) return false;
                const int axis = planeAxis(h, f.surface);
                if (axis < 0 || std::abs(m.shift[axis]) > 1e-9 * glm::length(m.shift)) return false;
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                double covered = 0.0;
                for (const Foreign& g : foreign) {
                    if (g.surface == kNone || planeAxis(h, g.surface) != axis ||
                        h.normal(h[g.surface])[axis] * h.normal(h[f.surface])[axis] < 0.0 ||
                        std::abs(g.box.lo[axis] - f.box.lo[axis]) >
                            1e-9 * glm::length(both.extent()))
                        continue;
                    const double du =
                        std::min(g.box.hi[u], both.hi[u]) - std::max(g.box.lo[u], both.lo[u]);
                    const double dv =
                        std::min(g.box.hi[v], both.hi[v]) - std::max(g.box.lo[v], both.lo[v]);
                    if (du > 0.0 && dv > 0.0) covered += du * dv;
                }
                const glm::dvec3 extent = both.extent();
                return covered >= (1.0 - 1e-9) * extent[u] * extent[v];
            };
            bool near = m.turned;
            for (std::size_t i = 0; i < foreign.size() && !near; ++i)
                near = !mine(i) && (meet(now, foreign[i].box) || meet(before, foreign[i].box)) &&
                       !alongside(foreign[i]);
            if (near) found.emplace_back(e, 0);
            for (ElementId c : h[e].children) stack.push_back(c);
        }
    }
    // Each once, its static part unknown if any finding says so.
    std::sort(found.begin(), found.end());
    std::vector<ElementId> clusters;
    std::vector<std::uint8_t> staticKnown;
    for (const auto& [e, known] : found) {
        if (!h.isLive(e) || h[e].isSurface() || h[e].shape == kNone) continue;
        if (!clusters.empty() && clusters.back() == e) continue;  // the lowest flag sorts first
        clusters.push_back(e);
        staticKnown.push_back(known);
    }
    std::vector<double> before;
    for (ElementId e : clusters)
        for (const ClusterShape::Facet& f : h.shape(e).facets) before.push_back(f.exposure);
    measureExposure(h, rays, clusters, staticKnown);
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
