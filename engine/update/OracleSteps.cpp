#include "update/OracleSteps.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <tbb/parallel_for.h>

namespace rad {

namespace {
// Below this many, stepping on one core costs less than sharing it out.
constexpr std::size_t kParallelElements = 4096;
}  // namespace

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

SteppedOracles stepOracles(Hierarchy& h, std::span<const ElementId> elements, double floor, double scale) {
    const double logStep = std::log(OracleSteps::kStep);
    // Each element steps alone: on all cores when they are many (an edit of
    // a light touches every element), the moved ones returned in the given
    // order.
    std::vector<std::uint8_t> stepped(elements.size(), 0);
    const auto step = [&](std::size_t i) {
        HElement& el = h[elements[i]];
        const double b = scale * oracleOf(h, elements[i]);
        if (!std::isfinite(b)) return;
        const double steps =
            std::log((std::max(b, 0.0) + floor) / (el.anchorLight + floor)) / logStep;
        if (std::abs(steps - el.level) <= OracleSteps::kHysteresis) return;
        const std::int8_t was = el.level;
        el.level = static_cast<std::int8_t>(std::clamp(std::lround(steps), -127L, 127L));
        el.oracle = el.level == 0
                        ? el.anchor
                        : (el.anchor + floor) * std::pow(OracleSteps::kStep, el.level) - floor;
        stepped[i] = el.level > was ? 2 : 1;
    };
    if (elements.size() >= kParallelElements)
        tbb::parallel_for(std::size_t(0), elements.size(), step);
    else
        for (std::size_t i = 0; i < elements.size(); ++i) step(i);
    SteppedOracles out;
    for (std::size_t i = 0; i < elements.size(); ++i) {
        if (stepped[i]) out.moved.push_back(elements[i]);
        if (stepped[i] == 2) out.rose.push_back(elements[i]);
    }
    return out;
}

}  // namespace rad
