#include "image/Image.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include <stb_image_write.h>

#include "image/AtomicFile.h"

namespace rad {
namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// stb_image_write's callback: appends to the std::string behind context.
void appendBytes(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
}

std::string encodePfm(const Image& image) {
    // Negative scale means little-endian; PFM rows go bottom to top.
    std::string bytes = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
    const std::size_t row = sizeof(float) * 3 * static_cast<std::size_t>(image.width);
    for (int y = image.height - 1; y >= 0; --y) bytes.append(reinterpret_cast<const char*>(image.pixel(0, y)), row);
    return bytes;
}

}  // namespace

unsigned char encodeSrgb(float linear) {
    float c = std::isfinite(linear) ? std::fmin(std::fmax(linear, 0.0f), 1.0f) : 0.0f;
    c = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return static_cast<unsigned char>(std::lround(c * 255.0f));
}

Rgb8Image encodeSrgb(const Image& image) {
    Rgb8Image out;
    out.width = image.width;
    out.height = image.height;
    out.rgb.resize(image.rgb.size());
    for (std::size_t i = 0; i < image.rgb.size(); ++i) out.rgb[i] = encodeSrgb(image.rgb[i]);
    return out;
}

void writePng(const Rgb8Image& image, const std::string& path) {
    if (image.width < 1 || image.height < 1 ||
        image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
        throw std::runtime_error(path + ": cannot write PNG: the image is " + std::to_string(image.width) + "x" +
                                 std::to_string(image.height) + " with " + std::to_string(image.rgb.size()) +
                                 " bytes");
    // Encoded in memory, so that writing the file (and its errors) is done in one place.
    std::string png;
    if (!stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 3, image.rgb.data(),
                                image.width * 3))
        throw std::runtime_error(path + ": cannot encode PNG");
    writeFileAtomically(path, png);
}

void writeImage(const Image& image, const std::string& path) {
    const std::string ext = lower(path);
    if (endsWith(ext, ".png"))
        writePng(encodeSrgb(image), path);
    else if (endsWith(ext, ".pfm"))
        writeFileAtomically(path, encodePfm(image));
    else
        throw std::runtime_error(path + ": unknown image type (use .png or .pfm)");
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
