#include "solve/Closure.h"

#include <tbb/parallel_for.h>

#include <array>
#include <bit>
#include <cmath>
#include <numbers>

#include "hierarchy/Hierarchy.h"

namespace rad {

namespace {

// How far a ray that left is turned to look again (radians, about): a
// millimetre at a metre.
constexpr double kSeamTurn = 1e-3;

// The rays' directions in the frame (t, b, n), cosine-weighted: ray k
// leaves sample point k % 16 (whose 4 rays are a jittered 2 x 2
// stratification of the disk that maps to the hemisphere, so that no point
// looks one way only), the jitter of the 16 points a Halton set (bases 2
// and 3). 64 rays measure a share of 0.8 to about 0.05: an open box's
// walls read 0.73 to 0.84 (tests/solve/closure_test.cpp).
const std::array<glm::dvec3, kClosureRays>& localDirections() {
    static const std::array<glm::dvec3, kClosureRays> directions = [] {
        std::array<glm::dvec3, kClosureRays> d{};
        constexpr int kPoints = 16;
        for (int k = 0; k < kClosureRays; ++k) {
            const int point = k % kPoints, j = k / kPoints;
            const auto index = static_cast<std::uint32_t>(point);
            const double jitterU = radicalInverse(index, 2), jitterV = radicalInverse(index, 3);
            const double u = ((j & 1) + jitterU) / 2.0, v = ((j >> 1) + jitterV) / 2.0;
            const double r = std::sqrt(u), phi = 2.0 * std::numbers::pi * v;
            d[k] = glm::dvec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(1.0 - u));
        }
        return d;
    }();
    return directions;
}

}  // namespace

void measureClosure(const Scene& scene, const RayCaster& rays,
                    std::span<const std::uint32_t> polygons, std::vector<float>& closure) {
    closure.resize(scene.polygons.size(), 1.0f);
    const Aabb bounds = scene.bounds();
    if (bounds.empty()) return;
    // Far enough to leave the scene from any of its points.
    const double reach = 4.0 * glm::length(bounds.extent()) + 1.0;
    const auto& local = localDirections();
    tbb::parallel_for(std::size_t(0), polygons.size(), [&](std::size_t i) {
        const std::uint32_t id = polygons[i];
        const Polygon& p = scene.polygons[id];
        const glm::dvec3 normal = p.normal();
        // The frame's first axis along the polygon's longest edge (a
        // repeated vertex makes a zero edge), in its plane.
        glm::dvec3 edge(0.0);
        for (int k = 0; k < p.vertexCount; ++k) {
            const glm::dvec3 e = p.vertices[(k + 1) % p.vertexCount] - p.vertices[k];
            if (glm::dot(e, e) > glm::dot(edge, edge)) edge = e;
        }
        const glm::dvec3 t = glm::normalize(edge - normal * glm::dot(normal, edge));
        const glm::dvec3 b = glm::cross(normal, t);
        const auto& params = polygonSampleParams(p.vertexCount);
        // The segment from `from` out of the scene along a local direction.
        const auto outward = [&](const glm::dvec3& from, const glm::dvec3& l) {
            return RayCaster::Segment{from, from + reach * (l.x * t + l.y * b + l.z * normal), id,
                                      RayCaster::kNoPolygon};
        };
        int met = 0;
        std::array<RayCaster::Segment, RayCaster::kMaxSegments> segments;
        for (int first = 0; first < kClosureRays;
             first += static_cast<int>(RayCaster::kMaxSegments)) {
            for (int k = 0; k < static_cast<int>(RayCaster::kMaxSegments); ++k) {
                const int ray = first + k;
                const glm::dvec3 from =
                    polygonPoint(p, params[static_cast<std::size_t>(ray) % params.size()]);
                segments[k] = outward(from, local[ray]);
            }
            const std::uint16_t hit =
                rays.blocked(Layer::Static, segments) | rays.blocked(Layer::Dynamic, segments);
            met += std::popcount(hit);
            // A ray that left may have slipped through a seam (two walls
            // meeting at a corner, in float): it counts as leaving only if
            // a neighbour, turned by kSeamTurn, leaves too. Cracks have no
            // width; openings do. Without this, 4 of `office`'s 5,416
            // polygons read 63/64, and the scene was not closed.
            std::array<RayCaster::Segment, RayCaster::kMaxSegments> again;
            std::size_t left = 0;
            for (int k = 0; k < static_cast<int>(RayCaster::kMaxSegments); ++k) {
                if ((hit >> k) & 1u) continue;
                again[left++] = outward(
                    segments[k].from,
                    glm::normalize(local[first + k] + kSeamTurn * glm::dvec3(1.0, 1.0, 0.0)));
            }
            if (left > 0) {
                const std::span<const RayCaster::Segment> retry(again.data(), left);
                met += std::popcount(static_cast<unsigned>(rays.blocked(Layer::Static, retry) |
                                                           rays.blocked(Layer::Dynamic, retry)));
            }
        }
        closure[id] = static_cast<float>(met) / kClosureRays;
    });
}

}  // namespace rad
