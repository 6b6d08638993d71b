// The accuracy metric against the Cycles references (tests/support/ImageCompare).

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "support/ImageCompare.h"

namespace rad {
namespace {

using test::compareBlocks;

Image uniform(int w, int h, float r, float g, float b) {
    Image image;
    image.width = w;
    image.height = h;
    image.rgb.resize(static_cast<std::size_t>(w) * h * 3);
    for (std::size_t i = 0; i < image.rgb.size(); i += 3) {
        image.rgb[i] = r;
        image.rgb[i + 1] = g;
        image.rgb[i + 2] = b;
    }
    return image;
}

// A smooth gradient with some colour, like a lit wall.
Image gradient(int w, int h) {
    Image image = uniform(w, h, 0.0f, 0.0f, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = image.pixel(x, y);
            p[0] = 0.2f + 0.01f * x;
            p[1] = 0.1f + 0.005f * y;
            p[2] = 0.05f + 0.002f * (x + y);
        }
    return image;
}

Image noLights(int w, int h) { return uniform(w, h, 0.0f, 0.0f, 0.0f); }

TEST(ImageCompare, LuminanceIsRec709) {
    const float white[3] = {1.0f, 1.0f, 1.0f}, red[3] = {1.0f, 0.0f, 0.0f}, green[3] = {0.0f, 1.0f, 0.0f},
                blue[3] = {0.0f, 0.0f, 1.0f};
    EXPECT_NEAR(test::luminance(white), 1.0, 1e-12);
    EXPECT_NEAR(test::luminance(red), 0.2126, 1e-12);
    EXPECT_NEAR(test::luminance(green), 0.7152, 1e-12);
    EXPECT_NEAR(test::luminance(blue), 0.0722, 1e-12);
}

TEST(ImageCompare, IdenticalImagesGiveZero) {
    const Image a = gradient(32, 24);
    const auto c = compareBlocks(a, a, noLights(32, 24));
    EXPECT_EQ(c.blockRms, 0.0);
    EXPECT_EQ(c.meanRatio, 1.0);
    EXPECT_EQ(c.blocks, 4 * 3);
    EXPECT_EQ(c.pixels, 32u * 24u);
}

TEST(ImageCompare, UniformlyTenPercentBrighterGivesPointOne) {
    const Image reference = uniform(32, 32, 0.3f, 0.5f, 0.2f);
    const Image ours = uniform(32, 32, 0.33f, 0.55f, 0.22f);
    const auto c = compareBlocks(ours, reference, noLights(32, 32));
    EXPECT_NEAR(c.blockRms, 0.1, 1e-6);
    EXPECT_NEAR(c.meanRatio, 1.1, 1e-6);
    // On an uneven image the ratio still reads 1.1; the RMS is then 0.1 times
    // the RMS of the blocks over their mean (>= 0.1), as a relative RMS should.
    Image brighter = gradient(32, 32);
    for (float& v : brighter.rgb) v *= 1.1f;
    const auto g = compareBlocks(brighter, gradient(32, 32), noLights(32, 32));
    EXPECT_NEAR(g.meanRatio, 1.1, 1e-6);
    EXPECT_GE(g.blockRms, 0.1 - 1e-6);
    EXPECT_LT(g.blockRms, 0.12);
}

TEST(ImageCompare, NoiseThatAveragesOutInABlockCostsNothing) {
    const Image reference = uniform(16, 16, 0.5f, 0.5f, 0.5f);
    Image ours = reference;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            for (int k = 0; k < 3; ++k) ours.pixel(x, y)[k] += (x + y) % 2 ? 0.1f : -0.1f;
    EXPECT_NEAR(compareBlocks(ours, reference, noLights(16, 16)).blockRms, 0.0, 1e-6);
}

TEST(ImageCompare, LightPixelsAndTheirNeighboursAreIgnored) {
    const Image reference = uniform(32, 32, 0.2f, 0.2f, 0.2f);
    Image mask = noLights(32, 32);
    Image ours = reference;
    // A 4 x 3 light at (10..13, 5..7) in the reference; ours draws it one
    // pixel larger all round (a misaligned edge) and much brighter.
    for (int y = 5; y <= 7; ++y)
        for (int x = 10; x <= 13; ++x) mask.pixel(x, y)[0] = 1.0f;
    for (int y = 4; y <= 8; ++y)
        for (int x = 9; x <= 14; ++x)
            for (int k = 0; k < 3; ++k) ours.pixel(x, y)[k] = 15.0f;
    const auto c = compareBlocks(ours, reference, mask);
    EXPECT_EQ(c.blockRms, 0.0);
    EXPECT_EQ(c.meanRatio, 1.0);
    EXPECT_EQ(c.pixels, 32u * 32u - 6u * 5u);
    // Without the dilation the ring of misplaced light pixels counts.
    test::BlockCompareOptions strict;
    strict.maskDilation = 0;
    EXPECT_GT(compareBlocks(ours, reference, mask, strict).blockRms, 0.1);
}

TEST(ImageCompare, BlocksThatAreMostlyLightAreLeftOut) {
    const Image reference = uniform(16, 8, 0.2f, 0.2f, 0.2f);
    Image mask = noLights(16, 8);
    Image ours = reference;
    // The left 8 x 8 block is a light but for its last column, which reads
    // wrong in ours: too few pixels to stand for the block, so it is skipped.
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 7; ++x) mask.pixel(x, y)[1] = 1.0f;
        ours.pixel(7, y)[0] = ours.pixel(7, y)[1] = ours.pixel(7, y)[2] = 5.0f;
    }
    test::BlockCompareOptions noDilation;
    noDilation.maskDilation = 0;
    const auto c = compareBlocks(ours, reference, mask, noDilation);
    EXPECT_EQ(c.blocks, 1);
    EXPECT_EQ(c.pixels, 64u);
    EXPECT_EQ(c.blockRms, 0.0);
}

TEST(ImageCompare, PartialBlocksAtTheEdgesCount) {
    // 20 x 10: blocks of 8 leave 4-pixel columns and 2-pixel rows at the edges.
    const Image reference = gradient(20, 10);
    const auto c = compareBlocks(reference, reference, noLights(20, 10));
    EXPECT_EQ(c.blocks, 3 * 2);
    EXPECT_EQ(c.pixels, 200u);
}

TEST(ImageCompare, OnlyLuminanceCounts) {
    // Trading red for an equal luminance of green changes nothing.
    const Image reference = uniform(8, 8, 0.5f, 0.2f, 0.1f);
    const float dr = 0.1f, dg = -0.1f * 0.2126f / 0.7152f;
    const Image ours = uniform(8, 8, 0.5f + dr, 0.2f + dg, 0.1f);
    EXPECT_NEAR(compareBlocks(ours, reference, noLights(8, 8)).blockRms, 0.0, 1e-6);
}

TEST(ImageCompare, RejectsMismatchedSizesAndEmptyComparisons) {
    EXPECT_THROW(compareBlocks(gradient(8, 8), gradient(16, 8), noLights(16, 8)), std::invalid_argument);
    EXPECT_THROW(compareBlocks(gradient(8, 8), gradient(8, 8), noLights(8, 16)), std::invalid_argument);
    Image allLight = uniform(8, 8, 1.0f, 1.0f, 1.0f);
    EXPECT_THROW(compareBlocks(gradient(8, 8), gradient(8, 8), allLight), std::runtime_error);
    EXPECT_THROW(compareBlocks(gradient(8, 8), noLights(8, 8), noLights(8, 8)), std::runtime_error);
}

}  // namespace
}  // namespace rad
