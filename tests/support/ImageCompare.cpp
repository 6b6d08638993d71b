#include "support/ImageCompare.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace rad::test {
namespace {

std::string sizeOf(const Image& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
}

// true for pixels to compare: not a light and not next to one.
std::vector<bool> keptPixels(const Image& lightMask, int dilation) {
    const int w = lightMask.width, h = lightMask.height;
    std::vector<bool> keep(static_cast<std::size_t>(w) * h, true);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float* m = lightMask.pixel(x, y);
            if (!(m[0] > 0.0f || m[1] > 0.0f || m[2] > 0.0f)) continue;
            for (int yy = std::max(0, y - dilation); yy <= std::min(h - 1, y + dilation); ++yy)
                for (int xx = std::max(0, x - dilation); xx <= std::min(w - 1, x + dilation); ++xx)
                    keep[static_cast<std::size_t>(yy) * w + xx] = false;
        }
    return keep;
}

}  // namespace

double luminance(const float* rgb) {
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

BlockComparison compareBlocks(const Image& ours, const Image& reference, const Image& lightMask,
                              const BlockCompareOptions& options) {
    if (ours.width != reference.width || ours.height != reference.height ||
        lightMask.width != reference.width || lightMask.height != reference.height)
        throw std::invalid_argument("image sizes differ: ours " + sizeOf(ours) + ", reference " +
                                    sizeOf(reference) + ", light mask " + sizeOf(lightMask));
    if (options.blockSize < 1) throw std::invalid_argument("block size must be positive");

    const int w = reference.width, h = reference.height, n = options.blockSize;
    const std::vector<bool> keep = keptPixels(lightMask, options.maskDilation);
    BlockComparison result;
    double squares = 0.0, sumOurs = 0.0, sumReference = 0.0;
    for (int by = 0; by < h; by += n)
        for (int bx = 0; bx < w; bx += n) {
            const int yEnd = std::min(h, by + n), xEnd = std::min(w, bx + n);
            double blockOurs = 0.0, blockReference = 0.0;
            int count = 0;
            for (int y = by; y < yEnd; ++y)
                for (int x = bx; x < xEnd; ++x) {
                    if (!keep[static_cast<std::size_t>(y) * w + x]) continue;
                    blockOurs += luminance(ours.pixel(x, y));
                    blockReference += luminance(reference.pixel(x, y));
                    ++count;
                }
            const int total = (yEnd - by) * (xEnd - bx);
            if (count == 0 || count < options.minBlockFraction * total) continue;
            const double d = (blockOurs - blockReference) / count;
            squares += d * d;
            sumOurs += blockOurs;
            sumReference += blockReference;
            result.pixels += static_cast<std::size_t>(count);
            ++result.blocks;
        }
    if (result.blocks == 0) throw std::runtime_error("no block left to compare after masking");
    if (!(sumReference > 0.0)) throw std::runtime_error("the reference is black where compared");
    result.referenceMean = sumReference / static_cast<double>(result.pixels);
    result.blockRms = std::sqrt(squares / result.blocks) / result.referenceMean;
    result.meanRatio = sumOurs / sumReference;
    return result;
}

}  // namespace rad::test
