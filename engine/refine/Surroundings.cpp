#include "refine/Surroundings.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "radiosity/Settings.h"

namespace rad {

namespace {

// `count` points spread by area over `polygons` (stratified over their
// running area), kSurroundingsRays each; shares of `total`, the scene's area.
Surroundings measureFrom(const Scene& scene, const RayCaster& rays, const std::vector<std::uint32_t>& polygons,
                         int count, double total) {
    std::vector<double> cumulative(polygons.size());
    double area = 0.0;
    for (std::size_t i = 0; i < polygons.size(); ++i) cumulative[i] = area += scene.polygons[polygons[i]].area();
    const Aabb bounds = scene.bounds();
    if (!(area > 0.0) || !(total > 0.0) || bounds.empty()) return {};
    const double reach = 4.0 * glm::length(bounds.extent()) + 1.0;
    std::vector<double> seen(static_cast<std::size_t>(count), 0.0);
    std::vector<int> escaped(static_cast<std::size_t>(count), 0);
    tbb::parallel_for(0, count, [&](int k) {
        const double u = (k + 0.5) / count * area;
        const std::size_t at =
            std::min<std::size_t>(std::lower_bound(cumulative.begin(), cumulative.end(), u) - cumulative.begin(),
                                  polygons.size() - 1);
        const Polygon& p = scene.polygons[polygons[at]];
        const auto& params = polygonSampleParams(p.vertexCount);
        const glm::dvec3 x = polygonPoint(p, params[static_cast<std::size_t>(k) % params.size()]);
        const glm::dvec3 n = p.normal();
        const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        const glm::dvec3 t = glm::normalize(glm::cross(n, a)), b = glm::cross(n, t);
        double visible = 0.0;
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
            visible += 2.0 * std::numbers::pi * hit->t * hit->t / c;
        }
        seen[static_cast<std::size_t>(k)] = visible / kSurroundingsRays;
    });
    double mean = 0.0;
    int left = 0;
    for (std::size_t k = 0; k < seen.size(); ++k) {
        mean += seen[k];
        left += escaped[k];
    }
    mean /= count;
    return {std::clamp(mean / total, 0.0, 1.0), double(left) / (double(count) * kSurroundingsRays)};
}

}  // namespace

Surroundings measureSurroundings(const Scene& scene, const RayCaster& rays) {
    std::vector<std::uint32_t> all(scene.polygons.size());
    for (std::uint32_t p = 0; p < all.size(); ++p) all[p] = p;
    return measureFrom(scene, rays, all, kSurroundingsPoints, scene.area());
}

std::vector<Surroundings> measureObjectSurroundings(const Scene& scene, const RayCaster& rays) {
    const double total = scene.area();
    std::vector<Surroundings> out(scene.objects.size());
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        std::vector<std::uint32_t> own(object.polygonCount);
        for (std::uint32_t i = 0; i < object.polygonCount; ++i) own[i] = object.firstPolygon + i;
        if (!own.empty()) out[o] = measureFrom(scene, rays, own, kObjectPoints, total);
    }
    return out;
}

double thresholdScale(const Surroundings& surroundings) {
    if (surroundings.escapedShare > kOpenShare || !(surroundings.visibleShare > 0.0)) return 1.0;
    return std::min(1.0, std::exp2(std::floor(std::log2(surroundings.visibleShare / kRoomShare))));
}

std::vector<double> objectAreaScales(const Scene& scene, const std::vector<Surroundings>& objects) {
    const auto closedIn = [&](std::size_t o) {
        return scene.objects[o].polygonCount > 0 && objects[o].escapedShare <= kOpenShare;
    };
    double seen = 0.0, area = 0.0;
    for (std::size_t o = 0; o < objects.size(); ++o) {
        if (!closedIn(o)) continue;
        double own = 0.0;
        for (std::uint32_t i = 0; i < scene.objects[o].polygonCount; ++i)
            own += scene.polygons[scene.objects[o].firstPolygon + i].area();
        seen += objects[o].visibleShare * own;
        area += own;
    }
    const double closed = area > 0.0 ? thresholdScale({seen / area, 0.0}) : 1.0;
    std::vector<double> out(objects.size(), 1.0);
    for (std::size_t o = 0; o < objects.size(); ++o)
        if (closedIn(o)) out[o] = closed;
    return out;
}

ThresholdScales measureThresholdScales(const Scene& scene, const RayCaster& rays) {
    const Surroundings whole = measureSurroundings(scene, rays);
    ThresholdScales out{thresholdScale(whole), {}};
    if (whole.escapedShare > kOpenShare) out.objectArea = objectAreaScales(scene, measureObjectSurroundings(scene, rays));
    return out;
}

}  // namespace rad
