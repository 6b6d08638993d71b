#include "support/Coverage.h"

#include <cstdio>
#include <random>
#include <utility>

namespace rad::test {
namespace {

using V = glm::dvec3;

// The point of an input polygon at parametric (u,v): bilinear over vertices
// 0..3 for quads, v0 + u (v1 - v0) + v (v2 - v0) for triangles.
V pointAt(const Polygon& p, const glm::dvec2& uv) {
    if (p.vertexCount == 3) return p.vertices[0] + uv.x * (p.vertices[1] - p.vertices[0]) + uv.y * (p.vertices[2] - p.vertices[0]);
    const V a = glm::mix(p.vertices[0], p.vertices[1], uv.x);
    const V b = glm::mix(p.vertices[3], p.vertices[2], uv.x);
    return glm::mix(a, b, uv.y);
}

glm::dvec2 randomParam(const Polygon& p, std::mt19937& random) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    glm::dvec2 uv(unit(random), unit(random));
    if (p.vertexCount == 3 && uv.x + uv.y > 1.0) uv = glm::dvec2(1.0) - uv;
    return uv;
}

}  // namespace

CoverageResult checkCoverage(const Engine& engine, unsigned seed, int wanted, std::optional<std::uint32_t> object) {
    const Scene& scene = engine.scene();
    std::mt19937 random(seed);
    std::uniform_int_distribution<std::uint32_t> pick(0, static_cast<std::uint32_t>(scene.polygons.size() - 1));
    std::uniform_int_distribution<std::uint32_t> pickOnObject(
        object ? scene.objects[*object].firstPolygon : 0,
        object ? scene.objects[*object].firstPolygon + scene.objects[*object].polygonCount - 1 : 0);
    CoverageResult r;
    for (int attempt = 0; r.pairs < wanted && attempt < 100 * wanted; ++attempt) {
        std::uint32_t a = object ? pickOnObject(random) : pick(random), b = pick(random);
        // Both directions of the light matter.
        if (object && random() % 2 == 0) std::swap(a, b);
        if (a == b) continue;
        const Polygon& pa = scene.polygons[a];
        const Polygon& pb = scene.polygons[b];
        const glm::dvec2 ua = randomParam(pa, random), ub = randomParam(pb, random);
        const V xa = pointAt(pa, ua), xb = pointAt(pb, ub);
        const V d = xb - xa;
        const double len = glm::length(d);
        // Facing, not grazing: each point clearly in front of the other's plane.
        if (!(len > 1e-6) || glm::dot(pa.normal(), d) <= 1e-6 * len || glm::dot(pb.normal(), -d) <= 1e-6 * len) continue;
        ++r.pairs;
        const std::size_t n = engine.linksCarrying(a, ua, b, ub);
        if (n == 1) continue;
        (n == 0 ? r.missing : r.doubled) += 1;
        if (r.firstBad.empty()) {
            char buf[256];
            std::snprintf(buf, sizeof buf, "%zu links from polygon %u (%.4f, %.4f) to polygon %u (%.4f, %.4f)", n, a,
                          ua.x, ua.y, b, ub.x, ub.y);
            r.firstBad = buf;
        }
    }
    return r;
}

}  // namespace rad::test
