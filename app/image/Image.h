#pragma once
// A linear RGB float image and its encoders (PNG sRGB, PFM linear). Files are
// written atomically: to a temporary beside the target, then renamed.

#include <string>
#include <vector>

namespace rad {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgb;  // row-major, top row first, 3 floats per pixel, linear

    float* pixel(int x, int y) { return &rgb[3 * (static_cast<std::size_t>(y) * width + x)]; }
    const float* pixel(int x, int y) const { return &rgb[3 * (static_cast<std::size_t>(y) * width + x)]; }
};

// Linear to sRGB-encoded 8 bit, after clamping to [0,1].
unsigned char encodeSrgb(float linear);

// Writes by extension: ".png" (sRGB) or ".pfm" (linear). Throws std::runtime_error.
void writeImage(const Image& image, const std::string& path);
Image readPfm(const std::string& path);

}  // namespace rad
