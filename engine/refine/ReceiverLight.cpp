#include "refine/ReceiverLight.h"

#include <algorithm>
#include <cmath>

namespace rad {

std::vector<float> receiverLightScales(const Scene& scene, const Hierarchy& h, double roomShare) {
    const std::size_t n = h.polygonCount();
    std::vector<double> area(n, 0.0), light(n, 0.0), strongest(n, 0.0);
    std::vector<ElementId> leaves;
    for (std::uint32_t p = 0; p < n; ++p) {
        if (h.polygonElement(p) == kNone) continue;  // not meshed (buried, degenerate)
        leaves.clear();
        h.collectLeaves(h.polygonElement(p), leaves);
        for (ElementId id : leaves) {
            const HElement& e = h[id];
            area[p] += e.area;
            const glm::dvec3 reflected = e.radiosity - h.emission(e);
            light[p] += e.area * std::max(0.0, luminance(reflected));
            strongest[p] += e.area * std::max({0.0, reflected.x, reflected.y, reflected.z});
        }
    }
    const auto glows = [&](std::uint32_t p) {
        return luminance(scene.materials[scene.polygons[p].material].emission) > 0.0;
    };
    double sumArea = 0.0, sumLight = 0.0, sumStrongest = 0.0;
    for (std::uint32_t p = 0; p < n; ++p)
        if (!glows(p)) {
            sumArea += area[p];
            sumLight += light[p];
            sumStrongest += strongest[p];
        }
    std::vector<float> scales(n, 1.0f);
    if (!(sumArea > 0.0) || !(sumLight > 0.0)) return scales;
    const double mean = sumLight / sumArea, meanStrongest = sumStrongest / sumArea;
    for (std::uint32_t p = 0; p < n; ++p) {
        if (glows(p) || !(area[p] > 0.0)) continue;
        // A large polygon is dim when its strongest channel is: a saturated
        // red wall is as bright in red as a white one (by luminance it read
        // a quarter of the mean, and the Cornell box's red wall, refined
        // four times finer, moved between a full solve and the update).
        const bool large = area[p] >= kLargeShare * roomShare * sumArea;
        const double ratio = large ? strongest[p] / area[p] / meanStrongest : kDarkRatio * light[p] / area[p] / mean;
        if (ratio >= 1.0) continue;
        // Rounded to a power of two in the log: 0.7 keeps 1, 0.6 takes 0.5.
        const double rounded = ratio > 0.0 ? std::exp2(std::round(std::log2(ratio))) : 0.0;
        scales[p] = static_cast<float>(std::clamp(rounded, large ? kLargeFinestScale : kFinestScale, 1.0));
    }
    return scales;
}

}  // namespace rad
