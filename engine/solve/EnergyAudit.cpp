#include "solve/EnergyAudit.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad {
namespace {

// The i-th of n points of the Hammersley set in the unit square: evenly
// spread, and the same every run.
glm::dvec2 hammersley(std::uint32_t i, std::uint32_t n) {
    std::uint32_t bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return {(i + 0.5) / n, double(bits) * 2.3283064365386963e-10};
}

}  // namespace

LightDestinations traceDestinations(const Scene& scene, const RayCaster& rays) {
    const std::size_t polygons = scene.polygons.size();
    // About 200k rays in all, between 8 and 64 per polygon.
    const auto perPolygon = static_cast<std::uint32_t>(
        std::clamp<std::size_t>(200'000 / std::max<std::size_t>(1, polygons), 8, 64));
    LightDestinations d;
    d.escaped.assign(polygons, 0.0f);
    d.backFaces.assign(polygons, 0.0f);
    const double offset = 10.0 * rays.coincidenceTolerance();
    tbb::parallel_for(std::size_t(0), polygons, [&](std::size_t p) {
        const Polygon& poly = scene.polygons[p];
        const glm::dvec3 n = poly.normal();
        if (n == glm::dvec3(0.0)) return;
        const glm::dvec3 t =
            glm::normalize(std::abs(n.x) > 0.5 ? glm::cross(n, glm::dvec3(0, 1, 0))
                                               : glm::cross(n, glm::dvec3(1, 0, 0)));
        const glm::dvec3 b = glm::cross(n, t);
        std::uint32_t escaped = 0, back = 0;
        for (std::uint32_t k = 0; k < perPolygon; ++k) {
            // A point on the polygon, and a cosine-weighted direction from it.
            glm::dvec2 uv = hammersley(k, perPolygon);
            if (poly.vertexCount == 3 && uv.x + uv.y > 1.0) uv = glm::dvec2(1.0) - uv;
            const glm::dvec3 origin = polygonPoint(poly, uv) + offset * n;
            const glm::dvec2 q = hammersley((k * 7u + 3u) % perPolygon, perPolygon);
            const double phi = 2.0 * std::numbers::pi * q.y, r = std::sqrt(q.x);
            const glm::dvec3 dir =
                r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(1.0 - q.x) * n;
            const auto hit = rays.intersect(origin, dir, std::numeric_limits<double>::infinity());
            if (!hit)
                ++escaped;
            else if (glm::dot(scene.polygons[hit->polygon].normal(), dir) >= 0.0)
                ++back;
        }
        d.escaped[p] = float(escaped) / float(perPolygon);
        d.backFaces[p] = float(back) / float(perPolygon);
    });
    return d;
}

void auditEnergy(const Hierarchy& h, const LightDestinations& d, EnergyBalance& energy) {
    double escaped = 0.0, back = 0.0;
    for (std::uint32_t p = 0; p < h.polygonCount() && p < d.escaped.size(); ++p) {
        const ElementId e = h.polygonElement(p);
        if (e == kNone) continue;
        const double leaving = h[e].area * luminance(h[e].radiosity);
        escaped += leaving * d.escaped[p];
        back += leaving * d.backFaces[p];
    }
    energy.escaped = escaped;
    energy.backFaces = back;
    energy.lost = energy.emitted - energy.absorbed - escaped - back;
    energy.created = std::max(0.0, energy.absorbed - energy.emitted);
}

}  // namespace rad
