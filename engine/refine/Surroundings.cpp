#include "refine/Surroundings.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "radiosity/Settings.h"

namespace rad {

Surroundings measureSurroundings(const Scene& scene, const RayCaster& rays) {
    std::vector<double> cumulative(scene.polygons.size());
    double total = 0.0;
    for (std::size_t p = 0; p < scene.polygons.size(); ++p)
        cumulative[p] = total += scene.polygons[p].area();
    const Aabb bounds = scene.bounds();
    if (!(total > 0.0) || bounds.empty()) return {};
    const double reach = 4.0 * glm::length(bounds.extent()) + 1.0;
    std::vector<double> seen(kSurroundingsPoints, 0.0);
    std::vector<int> escaped(kSurroundingsPoints, 0);
    tbb::parallel_for(0, kSurroundingsPoints, [&](int k) {
        // The point: area-weighted, stratified over the polygons' running area.
        const double u = (k + 0.5) / kSurroundingsPoints * total;
        const std::size_t id = std::min<std::size_t>(
            std::lower_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin(),
            scene.polygons.size() - 1);
        const Polygon& p = scene.polygons[id];
        const auto& params = polygonSampleParams(p.vertexCount);
        const glm::dvec3 x = polygonPoint(p, params[static_cast<std::size_t>(k) % params.size()]);
        const glm::dvec3 n = p.normal();
        const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        const glm::dvec3 t = glm::normalize(glm::cross(n, a)), b = glm::cross(n, t);
        double area = 0.0;
        for (int j = 0; j < kSurroundingsRays; ++j) {
            const auto index = static_cast<std::uint32_t>(k * kSurroundingsRays + j);
            // Uniform over the hemisphere: cos theta uniform in (0, 1].
            const double z = 1.0 - radicalInverse(index, 2),
                         phi = 2.0 * std::numbers::pi * radicalInverse(index, 3);
            const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
            const glm::dvec3 d = s * std::cos(phi) * t + s * std::sin(phi) * b + z * n;
            // Leave the point's own polygon (coincident starts would meet it).
            const auto hit = rays.intersect(x + 1e-6 * glm::length(bounds.extent()) * n, d, reach);
            if (!hit) {
                ++escaped[static_cast<std::size_t>(k)];
                continue;
            }
            const double c =
                std::max(0.2, std::abs(glm::dot(scene.polygons[hit->polygon].normal(), d)));
            area += 2.0 * std::numbers::pi * hit->t * hit->t / c;
        }
        seen[static_cast<std::size_t>(k)] = area / kSurroundingsRays;
    });
    double mean = 0.0;
    int left = 0;
    for (std::size_t k = 0; k < seen.size(); ++k) {
        mean += seen[k];
        left += escaped[k];
    }
    mean /= kSurroundingsPoints;
    return {std::clamp(mean / total, 0.0, 1.0),
            double(left) / (double(kSurroundingsPoints) * kSurroundingsRays)};
}

double thresholdScale(const Surroundings& surroundings) {
    if (surroundings.escapedShare > kOpenShare || !(surroundings.visibleShare > 0.0)) return 1.0;
    return std::min(1.0, std::exp2(std::floor(std::log2(surroundings.visibleShare / kRoomShare))));
}

}  // namespace rad
