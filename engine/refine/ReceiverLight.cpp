#include "refine/ReceiverLight.h"

#include <algorithm>
#include <cmath>

namespace rad {

std::vector<float> receiverLightScales(const Scene& scene, const Hierarchy& h) {
    const std::size_t n = h.polygonCount();
    std::vector<double> area(n, 0.0), light(n, 0.0);
    std::vector<ElementId> leaves;
    for (std::uint32_t p = 0; p < n; ++p) {
        if (h.polygonElement(p) == kNone) continue;  // not meshed (buried, degenerate)
        leaves.clear();
        h.collectLeaves(h.polygonElement(p), leaves);
        for (ElementId id : leaves) {
            const HElement& e = h[id];
            area[p] += e.area;
            light[p] += e.area * std::max(0.0, luminance(e.radiosity - e.emission));
        }
    }
    const auto glows = [&](std::uint32_t p) {
        return luminance(scene.materials[scene.polygons[p].material].emission) > 0.0;
    };
    double sumArea = 0.0, sumLight = 0.0;
    for (std::uint32_t p = 0; p < n; ++p)
        if (!glows(p)) {
            sumArea += area[p];
            sumLight += light[p];
        }
    std::vector<float> scales(n, 1.0f);
    if (!(sumArea > 0.0) || !(sumLight > 0.0)) return scales;
    const double mean = sumLight / sumArea;
    for (std::uint32_t p = 0; p < n; ++p) {
        if (glows(p) || !(area[p] > 0.0)) continue;
        const double ratio = kDarkRatio * light[p] / area[p] / mean;
        if (ratio >= 1.0) continue;
        // Rounded to a power of two in the log: 0.7 keeps 1, 0.6 takes 0.5.
        const double rounded = ratio > 0.0 ? std::exp2(std::round(std::log2(ratio))) : 0.0;
        scales[p] = static_cast<float>(std::clamp(rounded, kFinestScale, 1.0));
    }
    return scales;
}

}  // namespace rad
