#include "update/OracleSteps.h"

#include <algorithm>
#include <cmath>

namespace rad {

double oracleOf(const Hierarchy& h, ElementId e) {
    const HElement& el = h[e];
    return el.shape != kNone ? h.shape(e).peakLuminance(h.shape(e).power) : el.peak;
}

void anchorOracles(Hierarchy& h) {
    for (ElementId e = 0; e < h.size(); ++e) {
        h[e].anchor = h[e].oracle;
        h[e].anchorLight = oracleOf(h, e);
        h[e].level = 0;
    }
}

std::vector<ElementId> stepOracles(Hierarchy& h, std::span<const ElementId> elements,
                                   double floor, double scale) {
    std::vector<ElementId> moved;
    const double logStep = std::log(OracleSteps::kStep);
    for (ElementId e : elements) {
        HElement& el = h[e];
        const double b = scale * oracleOf(h, e);
        if (!std::isfinite(b)) continue;
        const double steps =
            std::log((std::max(b, 0.0) + floor) / (el.anchorLight + floor)) / logStep;
        if (std::abs(steps - el.level) <= OracleSteps::kHysteresis) continue;
        el.level = static_cast<std::int8_t>(std::clamp(std::lround(steps), -127L, 127L));
        el.oracle = el.level == 0
                        ? el.anchor
                        : (el.anchor + floor) * std::pow(OracleSteps::kStep, el.level) - floor;
        moved.push_back(e);
    }
    return moved;
}

}  // namespace rad
