#pragma once
// Comparing a rendered image with a path-traced reference (bench/cycles): the
// accuracy metric of issue 12, "Light that is right". bench/cycles/compare.py
// computes the same numbers in Python; keep the two in step.

#include <cstddef>

#include "image/Image.h"

namespace rad::test {

// Rec. 709 luminance of a linear RGB pixel.
double luminance(const float* rgb);

struct BlockCompareOptions {
    int blockSize = 8;
    // Light pixels within this many pixels (8-neighbourhood) of a marked one
    // are left out too: a light's edge that falls half a pixel differently in
    // the two renderers is not a radiosity error, yet one such pixel (E ~ 15
    // against B ~ 0.2) would dominate its block.
    int maskDilation = 1;
    // A block is compared only if at least this fraction of its pixels is
    // left after masking; blocks that are mostly light say nothing about B.
    double minBlockFraction = 0.5;
};

struct BlockComparison {
    // sqrt(mean over blocks of (ours - reference)^2) / reference mean, on the
    // blocks' mean luminance over their unmasked pixels.
    double blockRms = 0.0;
    double meanRatio = 0.0;      // ours mean / reference mean, same pixels
    double referenceMean = 0.0;  // mean luminance of the reference over the pixels compared
    int blocks = 0;              // blocks compared
    std::size_t pixels = 0;      // pixels compared
};

// lightMask: same size; a pixel with any channel > 0 shows a light source.
// Throws std::invalid_argument when the sizes differ, and std::runtime_error
// when no block is left or the reference is black there.
BlockComparison compareBlocks(const Image& ours, const Image& reference, const Image& lightMask,
                              const BlockCompareOptions& options = {});

}  // namespace rad::test
