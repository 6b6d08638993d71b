#include "image/Image.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <stb/stb_image_write.h>

namespace rad {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

void writePng(const Image& image, const std::string& path) {
    std::vector<unsigned char> bytes(static_cast<std::size_t>(image.width) * image.height * 3);
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = encodeSrgb(image.rgb[i]);
    if (!stbi_write_png(path.c_str(), image.width, image.height, 3, bytes.data(), image.width * 3))
        throw std::runtime_error(path + ": cannot write PNG");
}

void writePfm(const Image& image, const std::string& path) {
    std::ofstream out(path, std::ios::binary);
    if (!out) throw std::runtime_error(path + ": cannot open for writing");
    // Negative scale means little-endian; PFM rows go bottom to top.
    out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
    for (int y = image.height - 1; y >= 0; --y)
        out.write(reinterpret_cast<const char*>(image.pixel(0, y)),
                  static_cast<std::streamsize>(sizeof(float) * 3 * image.width));
    if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace

unsigned char encodeSrgb(float linear) {
    float c = std::isfinite(linear) ? std::fmin(std::fmax(linear, 0.0f), 1.0f) : 0.0f;
    c = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return static_cast<unsigned char>(std::lround(c * 255.0f));
}

void writeImage(const Image& image, const std::string& path) {
    const std::string ext = lower(path);
    const bool png = endsWith(ext, ".png");
    if (!png && !endsWith(ext, ".pfm"))
        throw std::runtime_error(path + ": unknown image type (use .png or .pfm)");
    const std::string tmp = path + ".tmp";
    try {
        png ? writePng(image, tmp) : writePfm(image, tmp);
        std::filesystem::rename(tmp, path);
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        throw;
    }
}

Image readPfm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot open");
    std::string magic;
    Image image;
    double scale = 0.0;
    in >> magic >> image.width >> image.height >> scale;
    in.get();
    if (magic != "PF" || image.width <= 0 || image.height <= 0 || scale >= 0.0)
        throw std::runtime_error(path + ": not a little-endian RGB PFM");
    image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
    for (int y = image.height - 1; y >= 0; --y)
        in.read(reinterpret_cast<char*>(image.pixel(0, y)),
                static_cast<std::streamsize>(sizeof(float) * 3 * image.width));
    if (!in) throw std::runtime_error(path + ": truncated PFM");
    return image;
}

}  // namespace rad
