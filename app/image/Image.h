#pragma once
// Images and the one place that writes them to files.
//
// Image is linear RGB in floats, what the renderer computes. Rgb8Image is 8-bit
// sRGB-encoded, what a window shows. PNG files (sRGB) come from writePng alone,
// through stb_image_write; PFM files (linear) from writeImage. Every file is
// written atomically (image/AtomicFile.h).

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

struct Rgb8Image {
    int width = 0;
    int height = 0;
    std::vector<unsigned char> rgb;  // row-major, top row first, 3 bytes per pixel, sRGB-encoded

    const unsigned char* pixel(int x, int y) const { return &rgb[3 * (static_cast<std::size_t>(y) * width + x)]; }
};

// Linear to sRGB-encoded 8 bit, after clamping to [0,1] (not finite: 0).
unsigned char encodeSrgb(float linear);
// Every channel of the image through encodeSrgb.
Rgb8Image encodeSrgb(const Image& image);

// Throws std::runtime_error("<path>: ...") when the image is malformed or the
// file cannot be written.
void writePng(const Rgb8Image& image, const std::string& path);
// By extension: ".png" (sRGB-encoded, via writePng) or ".pfm" (linear).
// Throws std::runtime_error("<path>: ...").
void writeImage(const Image& image, const std::string& path);
Image readPfm(const std::string& path);

}  // namespace rad
