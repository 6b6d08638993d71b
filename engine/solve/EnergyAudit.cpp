#include "solve/EnergyAudit.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

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

// Rays for the whole scene, shared out by power.
constexpr double kRays = 200'000;

}  // namespace

void auditEnergy(const Scene& scene, const Hierarchy& h, const RayCaster& rays,
                 EnergyBalance& energy) {
    // The surface leaves and the light leaving each (B A).
    std::vector<ElementId> leaves;
    for (std::uint32_t p = 0; p < scene.polygons.size() && p < h.polygonCount(); ++p) {
        std::vector<ElementId> stack;
        if (h.polygonElement(p) != kNone) stack.push_back(h.polygonElement(p));
        while (!stack.empty()) {
            const ElementId e = stack.back();
            stack.pop_back();
            if (h[e].isLeaf())
                leaves.push_back(e);
            else
                stack.insert(stack.end(), h[e].children.begin(), h[e].children.end());
        }
    }
    std::vector<double> leaving(leaves.size(), 0.0);
    double total = 0.0;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        leaving[i] = std::max(0.0, h[leaves[i]].area * luminance(h[leaves[i]].radiosity));
        if (std::isfinite(leaving[i])) total += leaving[i];
    }
    std::vector<double> escaped(leaves.size(), 0.0), back(leaves.size(), 0.0);
    // Where the light meets backs, by object (summed per thread).
    const auto objectOf = [&](std::uint32_t polygon) {
        return polygon < scene.polygons.size() ? scene.polygons[polygon].object : std::uint32_t(scene.objects.size());
    };
    tbb::combinable<std::vector<double>> backBy([&] { return std::vector<double>(scene.objects.size() + 1, 0.0); });
    tbb::combinable<std::vector<double>> escapedBy([&] { return std::vector<double>(scene.objects.size() + 1, 0.0); });
    // A ray leaves a surface ten times as far off it as what counts as
    // coincident there (RayCaster::blocked), and beyond what Embree's floats
    // resolve. (Ten times the frame's tolerance, a millionth of a scene that
    // a stray polygon made 10 km wide, started rays 10 cm off, behind the
    // books on a shelf: 16% of the light read as meeting backs.)
    const auto sizeOf = [&](std::uint32_t polygon) {
        Aabb box;
        for (int k = 0; k < scene.polygons[polygon].vertexCount; ++k) box.extend(scene.polygons[polygon].vertices[k]);
        return glm::length(box.extent());
    };
    const auto offsetFrom = [&](const glm::dvec3& point, double polygonSize) {
        return 10.0 * std::max(RayCaster::coincidenceOfSize * polygonSize, rays.resolutionAt(point));
    };
    tbb::parallel_for(std::size_t(0), leaves.size(), [&](std::size_t i) {
        if (!(leaving[i] > 0.0) || !std::isfinite(leaving[i])) return;
        const HElement& leaf = h[leaves[i]];
        const glm::dvec3 n = h.normal(leaf);
        if (n == glm::dvec3(0.0)) return;
        const auto count = static_cast<std::uint32_t>(
            std::clamp(std::lround(kRays * leaving[i] / total), 4L, 1L << 16));
        const glm::dvec3 t =
            glm::normalize(std::abs(n.x) > 0.5 ? glm::cross(n, glm::dvec3(0, 1, 0))
                                               : glm::cross(n, glm::dvec3(1, 0, 0)));
        const glm::dvec3 b = glm::cross(n, t);
        const PatchGeometry patch = h.patch(leaves[i]);
        const auto& v = patch.v;
        const double polygonSize = sizeOf(leaf.polygon);
        std::uint32_t missed = 0, backs = 0;
        std::vector<double>& by = backBy.local();
        for (std::uint32_t k = 0; k < count; ++k) {
            // A point on the leaf, kept off its edges (a ray from a point on
            // an edge shared with another polygon starts in that polygon's
            // plane), and a cosine-weighted direction from it.
            glm::dvec2 uv = 0.005 + 0.99 * hammersley(k, count);
            glm::dvec3 point;
            if (patch.n == 4) {
                point = glm::mix(glm::mix(v[0], v[1], uv.x), glm::mix(v[3], v[2], uv.x), uv.y);
            } else {
                if (uv.x + uv.y > 1.0) uv = glm::dvec2(1.0) - uv;
                point = v[0] + uv.x * (v[1] - v[0]) + uv.y * (v[2] - v[0]);
            }
            const glm::dvec2 q = hammersley((k * 7u + 3u) % count, count);
            const double phi = 2.0 * std::numbers::pi * q.y, r = std::sqrt(q.x);
            const glm::dvec3 dir =
                r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(1.0 - q.x) * n;
            const double offset = offsetFrom(point, polygonSize);
            const auto hit =
                rays.intersect(point + offset * n, dir, std::numeric_limits<double>::infinity());
            if (!hit) {
                ++missed;
            } else if (!hit->front) {
                ++backs;
                by[objectOf(hit->polygon)] += leaving[i] / count;
            }
        }
        escaped[i] = leaving[i] * missed / count;
        // A glowing leaf most of whose rays meet nothing looks out of the
        // scene (an open room's lamp sends some of its light out through
        // the opening, and does not count): the emitted part of what it
        // loses (E of its B).
        const double emitted = leaf.area * luminance(h.emission(leaf));
        if (2 * missed > count && emitted > 0.0) escapedBy.local()[objectOf(leaf.polygon)] += emitted * missed / count;
        back[i] = leaving[i] * backs / count;
    });
    energy.escaped = energy.backFaces = 0.0;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        energy.escaped += escaped[i];
        energy.backFaces += back[i];
    }
    // Punctual lights: where their light goes, from directions spread evenly
    // over the sphere, each weighted by the light's falloff.
    for (const PunctualLight& light : scene.lights) {
        const double power = light.power();
        if (!(power > 0.0)) continue;
        constexpr std::uint32_t kLightRays = 16384;
        std::vector<double> weight(kLightRays, 0.0), missed(kLightRays, 0.0), backs(kLightRays, 0.0);
        std::vector<std::uint32_t> backObject(kLightRays, 0);
        tbb::parallel_for(std::uint32_t(0), kLightRays, [&](std::uint32_t k) {
            const glm::dvec2 q = hammersley(k, kLightRays);
            const double z = 1.0 - 2.0 * q.x, s = std::sqrt(std::max(0.0, 1.0 - z * z));
            const double phi = 2.0 * std::numbers::pi * q.y;
            const glm::dvec3 dir(s * std::cos(phi), s * std::sin(phi), z);
            weight[k] = light.falloff(dir);
            if (!(weight[k] > 0.0)) return;
            auto hit = rays.intersect(light.position, dir, std::numeric_limits<double>::infinity());
            // A light on a surface (a downlight in the ceiling's plane, a
            // bulb on a wall) meets it at once: leaving through its front,
            // the ray goes on; going into it, the light is lost there (in
            // backFaces, but no object's normals are to blame for it).
            const double offset = hit ? offsetFrom(light.position, sizeOf(hit->polygon)) : 0.0;
            if (hit && hit->t < offset) {
                if (hit->front) {
                    backs[k] = weight[k];
                    backObject[k] = std::uint32_t(scene.objects.size());
                    return;
                }
                hit = rays.intersect(light.position + offset * dir, dir, std::numeric_limits<double>::infinity());
            }
            if (!hit)
                missed[k] = weight[k];
            else if (!hit->front) {
                backs[k] = weight[k];
                backObject[k] = objectOf(hit->polygon);
            }
        });
        double total = 0.0, miss = 0.0, back = 0.0;
        for (std::uint32_t k = 0; k < kLightRays; ++k) {
            total += weight[k];
            miss += missed[k];
            back += backs[k];
        }
        if (total > 0.0) {
            energy.escaped += power * miss / total;
            energy.backFaces += power * back / total;
            std::vector<double>& by = backBy.local();
            for (std::uint32_t k = 0; k < kLightRays; ++k)
                if (backs[k] > 0.0) by[backObject[k]] += power * backs[k] / total;
        }
    }
    energy.escapedEmissionByObject.assign(scene.objects.size(), 0.0);
    escapedBy.combine_each([&](const std::vector<double>& by) {
        for (std::size_t o = 0; o < scene.objects.size(); ++o) energy.escapedEmissionByObject[o] += by[o];
    });
    energy.backFacesByObject.assign(scene.objects.size(), 0.0);
    backBy.combine_each([&](const std::vector<double>& by) {
        for (std::size_t o = 0; o < scene.objects.size(); ++o) energy.backFacesByObject[o] += by[o];
    });
    energy.lost = energy.emitted - energy.absorbed - energy.escaped - energy.backFaces;
    energy.created = std::max(0.0, energy.absorbed - energy.emitted);
}

}  // namespace rad
