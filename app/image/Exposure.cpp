#include "image/Exposure.h"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace rad {

std::optional<double> exposureThatShows(std::vector<float> peaks, double exposure) {
    std::erase_if(peaks, [](float v) { return !(v > 0.0f) || !std::isfinite(v); });
    if (peaks.empty()) return std::nullopt;
    const auto past = std::count_if(peaks.begin(), peaks.end(), [](float v) { return v >= 1.0f; });
    if (4 * past <= std::ssize(peaks)) return std::nullopt;
    const auto ninth = peaks.begin() + static_cast<std::ptrdiff_t>(0.9 * double(peaks.size() - 1));
    std::nth_element(peaks.begin(), ninth, peaks.end());
    return exposure + std::floor(-2.0 * std::log2(double(*ninth))) / 2.0;
}

}  // namespace rad
