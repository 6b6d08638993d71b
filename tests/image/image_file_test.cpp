// rad::writePng / writeImage: the files decode to what was written, appear
// whole or not at all, and failures say so in one line naming the file.

#include <gtest/gtest.h>

#include <stb_image.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <stdexcept>
#include <string>

#include "image/AtomicFile.h"
#include "image/Image.h"
#include "support/TempDir.h"

namespace rad {
namespace {

struct Decoded {
    int width = 0, height = 0;
    std::unique_ptr<unsigned char, decltype(&stbi_image_free)> pixels{nullptr, &stbi_image_free};
};

Decoded decodePng(const std::string& path) {
    Decoded d;
    int channels = 0;
    d.pixels.reset(stbi_load(path.c_str(), &d.width, &d.height, &channels, 3));
    return d;
}

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Only `name` in the directory: no temporary left behind.
void expectOnlyFile(const std::filesystem::path& dir, const std::string& name) {
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string(), name) << "stray file";
}

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "(no exception)";
}

TEST(ImageFile, PngDecodesToTheWrittenSizeAndBytes) {
    test::TempDir dir;
    Rgb8Image image;
    image.width = 5;
    image.height = 3;
    for (int i = 0; i < image.width * image.height * 3; ++i) image.rgb.push_back(static_cast<unsigned char>(17 * i));
    const std::string path = (dir / "shot.png").string();
    writePng(image, path);

    const Decoded d = decodePng(path);
    ASSERT_TRUE(d.pixels) << stbi_failure_reason();
    EXPECT_EQ(d.width, 5);
    EXPECT_EQ(d.height, 3);
    EXPECT_EQ(std::memcmp(d.pixels.get(), image.rgb.data(), image.rgb.size()), 0);
    expectOnlyFile(dir.path(), "shot.png");
}

TEST(ImageFile, LinearImageIsSrgbEncodedInPngAndKeptInPfm) {
    test::TempDir dir;
    Image image;
    image.width = 2;
    image.height = 1;
    image.rgb = {0.0f, 0.5f, 1.0f, 2.0f, 0.0031308f, 0.214f};
    writeImage(image, (dir / "a.png").string());
    writeImage(image, (dir / "a.pfm").string());

    const Decoded d = decodePng((dir / "a.png").string());
    ASSERT_TRUE(d.pixels);
    ASSERT_EQ(d.width, 2);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(d.pixels.get()[i], encodeSrgb(image.rgb[i])) << i;
    EXPECT_EQ(encodeSrgb(0.5f), 188);  // the sRGB curve, not a gamma of 2.2 (186)
    EXPECT_EQ(encodeSrgb(2.0f), 255);

    const Image back = readPfm((dir / "a.pfm").string());
    EXPECT_EQ(back.width, 2);
    EXPECT_EQ(back.height, 1);
    EXPECT_EQ(back.rgb, image.rgb);
}

TEST(ImageFile, FailedWriteKeepsTheOldFileAndSaysWhyInOneLine) {
    test::TempDir dir;
    const std::string path = (dir / "kept.png").string();
    writeFileAtomically(path, "old");

    Rgb8Image wrong;  // 2x2 needs 12 bytes
    wrong.width = 2;
    wrong.height = 2;
    wrong.rgb.assign(5, 0);
    const std::string malformed = messageOf([&] { writePng(wrong, path); });
    EXPECT_EQ(malformed.rfind(path + ": ", 0), 0u) << malformed;
    EXPECT_EQ(malformed.find('\n'), std::string::npos) << malformed;
    EXPECT_EQ(readAll(path), "old");

    // A directory where the file should go: the rename fails, nothing is lost.
    const std::string blocked = (dir / "blocked.png").string();
    std::filesystem::create_directory(blocked);
    std::filesystem::create_directory(dir / "blocked.png" / "inside");
    Rgb8Image one;
    one.width = one.height = 1;
    one.rgb = {1, 2, 3};
    const std::string replace = messageOf([&] { writePng(one, blocked); });
    EXPECT_EQ(replace.rfind(blocked + ": cannot replace (", 0), 0u) << replace;
    EXPECT_EQ(replace.find('\n'), std::string::npos) << replace;
    EXPECT_TRUE(std::filesystem::is_directory(blocked));
    EXPECT_FALSE(std::filesystem::exists(blocked + ".tmp"));

    const std::string missing = (dir / "no-such-dir" / "x.pfm").string();
    const std::string open = messageOf([&] { writeImage(Image{1, 1, {0, 0, 0}}, missing); });
    EXPECT_EQ(open, missing + ": cannot write (No such file or directory)");

    EXPECT_EQ(messageOf([&] { writeImage(Image{1, 1, {0, 0, 0}}, (dir / "x.jpg").string()); }),
              (dir / "x.jpg").string() + ": unknown image type (use .png or .pfm)");
}

}  // namespace
}  // namespace rad
