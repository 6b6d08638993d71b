// The offscreen renderer on synthetic meshes, with the validation layer on.
// Positions are given directly in Vulkan clip space (identity viewProjection):
// x -1..1 is left..right, y -1..1 is top..bottom, z 0..1 is near..far.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "image/Image.h"
#include "radiosity/Scene.h"
#include "radiosity/Snapshot.h"
#include "render/CameraView.h"
#include "render/GpuTextures.h"
#include "render/OffscreenRenderer.h"
#include "render/VulkanContext.h"

namespace rad {
namespace {

const glm::vec3 kRed(1, 0, 0), kGreen(0, 1, 0), kBlue(0, 0, 1), kYellow(1, 1, 0);
const glm::dmat4 kIdentity(1.0);

void addTriangle(MeshSnapshot& mesh, std::array<glm::vec3, 3> p, std::array<glm::vec3, 3> c) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (int i = 0; i < 3; ++i) {
        mesh.positions.push_back(p[i]);
        mesh.normals.emplace_back(0, 0, -1);
        mesh.colors.push_back(c[i]);
    }
    mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});
}

// A triangle given in clip space, wound so that it faces the viewer: the
// renderer culls back faces (OneSidedPanelSeenFromBehindIsNotDrawn), and
// these tests are about rasterisation, not facing. A front face is
// counter-clockwise in Vulkan's framebuffer space (y down).
void addFrontTriangle(MeshSnapshot& mesh, std::array<glm::vec3, 3> p, std::array<glm::vec3, 3> c) {
    const glm::vec2 u(p[1] - p[0]), v(p[2] - p[0]);
    if (u.x * v.y - u.y * v.x > 0.0f) {
        std::swap(p[1], p[2]);
        std::swap(c[1], c[2]);
    }
    addTriangle(mesh, p, c);
}

// Axis-aligned rectangle at depth z, two triangles.
void addRect(MeshSnapshot& mesh, float x0, float y0, float x1, float y1, float z, glm::vec3 color) {
    addFrontTriangle(mesh, {{{x0, y0, z}, {x1, y0, z}, {x1, y1, z}}}, {color, color, color});
    addFrontTriangle(mesh, {{{x0, y0, z}, {x1, y1, z}, {x0, y1, z}}}, {color, color, color});
}

// Clip-space position of a pixel centre.
glm::vec2 pixelCenter(const Image& image, int x, int y) {
    return {(x + 0.5f) / image.width * 2.0f - 1.0f, (y + 0.5f) / image.height * 2.0f - 1.0f};
}

// The pixel whose centre is nearest a clip-space point.
std::array<int, 2> pixelAt(const Image& image, float x, float y) {
    return {static_cast<int>((x + 1.0f) * 0.5f * image.width),
            static_cast<int>((y + 1.0f) * 0.5f * image.height)};
}

void expectColor(const Image& image, int x, int y, glm::vec3 expected, float tolerance = 1e-5f) {
    const float* p = image.pixel(x, y);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(p[c], expected[c], tolerance)
            << "pixel (" << x << ", " << y << ") channel " << c;
}

class OffscreenRendererTest : public ::testing::Test {
  protected:
    void SetUp() override {
        VulkanContextOptions options;
        options.validation = true;  // a missing layer is a failure here, not a skip
        try {
            context_ = std::make_unique<VulkanContext>(options);
        } catch (const std::exception& e) {
            FAIL() << "cannot create a Vulkan context with validation: " << e.what();
        }
        ASSERT_TRUE(context_->validationEnabled());
        renderer_ = std::make_unique<OffscreenRenderer>(*context_);
    }

    void TearDown() override {
        if (!context_) return;
        // Checked after destruction: leaked objects are reported then.
        const auto messages = context_->validationMessageCounter();
        renderer_.reset();
        context_.reset();
        EXPECT_EQ(messages->load(), 0u) << "validation messages are on stderr";
    }

    std::unique_ptr<VulkanContext> context_;
    std::unique_ptr<OffscreenRenderer> renderer_;
};

TEST_F(OffscreenRendererTest, RedTriangleLeftGreenTriangleRightOnBlack) {
    MeshSnapshot mesh;
    addFrontTriangle(mesh, {{{-0.9f, 0.5f, 0.5f}, {-0.1f, 0.5f, 0.5f}, {-0.5f, -0.5f, 0.5f}}},
                {kRed, kRed, kRed});
    addFrontTriangle(mesh, {{{0.1f, 0.5f, 0.5f}, {0.9f, 0.5f, 0.5f}, {0.5f, -0.5f, 0.5f}}},
                {kGreen, kGreen, kGreen});
    const Image image = renderer_->render(mesh, kIdentity, 64, 48);
    ASSERT_EQ(image.width, 64);
    ASSERT_EQ(image.height, 48);
    ASSERT_EQ(image.rgb.size(), 64u * 48u * 3u);

    const auto [lx, ly] = pixelAt(image, -0.5f, 0.2f);
    expectColor(image, lx, ly, kRed);
    const auto [rx, ry] = pixelAt(image, 0.5f, 0.2f);
    expectColor(image, rx, ry, kGreen);
    // Background: corners, the gap between the triangles, above and below.
    for (auto [x, y] :
         {std::array<int, 2>{0, 0}, {63, 0}, {0, 47}, {63, 47}, {32, 24}, {16, 2}, {48, 45}})
        expectColor(image, x, y, glm::vec3(0), 0.0f);
}

// Polygons are one-sided (counter-clockwise seen from the front, as in the
// scenes): through a real camera, a panel facing it is drawn, the same panel
// turned away is not, and the panel behind it shows instead.
TEST_F(OffscreenRendererTest, OneSidedPanelSeenFromBehindIsNotDrawn) {
    const auto addWorldQuad = [](MeshSnapshot& mesh, std::array<glm::vec3, 4> q, glm::vec3 color) {
        addTriangle(mesh, {{q[0], q[1], q[2]}}, {color, color, color});
        addTriangle(mesh, {{q[0], q[2], q[3]}}, {color, color, color});
    };
    Camera camera;  // at the origin, looking down -Z, +Y up
    camera.yfov = 1.0;
    Aabb bounds;
    bounds.lo = glm::dvec3(-2, -2, -3);
    bounds.hi = glm::dvec3(2, 2, 0);
    const glm::dmat4 viewProjection = makeCameraView(camera, bounds, 1.0).viewProjection();
    // Facing +Z (toward the camera): counter-clockwise seen from +Z.
    const std::array<glm::vec3, 4> facing{{{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}}};
    const std::array<glm::vec3, 4> away{{facing[0], facing[3], facing[2], facing[1]}};
    const std::array<glm::vec3, 4> back{{{-2, -2, -2}, {2, -2, -2}, {2, 2, -2}, {-2, 2, -2}}};
    for (bool turned : {false, true}) {
        MeshSnapshot mesh;
        addWorldQuad(mesh, turned ? away : facing, kRed);
        addWorldQuad(mesh, back, kBlue);
        const Image image = renderer_->render(mesh, viewProjection, 32, 32);
        SCOPED_TRACE(turned ? "turned away" : "facing the camera");
        expectColor(image, 16, 16, turned ? kBlue : kRed);
    }
}

// A snapshot far from the world's origin keeps its positions relative to its
// own (MeshSnapshot::origin), and the renderer adds it back in double: 1000
// km out, a red panel 1 cm in front of a blue one is drawn as at the origin
// (in world floats both would round to the same 6 cm grid and fight).
TEST_F(OffscreenRendererTest, FarFromTheOriginDrawsAsAtIt) {
    const auto addQuad = [](MeshSnapshot& mesh, double z, double half, glm::vec3 color) {
        const std::array<glm::vec3, 4> q{{{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}}};
        addTriangle(mesh, {{q[0], q[1], q[2]}}, {color, color, color});
        addTriangle(mesh, {{q[0], q[2], q[3]}}, {color, color, color});
    };
    std::vector<Image> images;
    for (double distance : {0.0, 1e6}) {
        const glm::dvec3 origin(distance, 0.5 * distance, -distance);
        Camera camera;  // looking down -Z, +Y up, 1 m in front of the panels
        camera.position = origin + glm::dvec3(0.0, 0.0, 1.0);
        camera.yfov = 1.0;
        Aabb bounds;
        bounds.lo = origin + glm::dvec3(-1, -1, -0.1);
        bounds.hi = origin + glm::dvec3(1, 1, 1);
        MeshSnapshot mesh;
        mesh.origin = origin;
        addQuad(mesh, 0.0, 0.2, kRed);
        addQuad(mesh, -0.01, 0.5, kBlue);
        images.push_back(renderer_->render(mesh, makeCameraView(camera, bounds, 1.0).viewProjection(), 32, 32));
        SCOPED_TRACE(distance);
        expectColor(images.back(), 16, 16, kRed);
        expectColor(images.back(), 3, 16, kBlue);
    }
    // The matrices differ in their last bits: an edge pixel may differ.
    std::size_t differ = 0;
    for (std::size_t i = 0; i < images[0].rgb.size(); ++i) differ += std::abs(images[0].rgb[i] - images[1].rgb[i]) > 1e-4f;
    EXPECT_LE(differ, images[0].rgb.size() / 100);
}

TEST_F(OffscreenRendererTest, TopOfClipSpaceIsFirstRow) {
    // A band across the top quarter: y = -1 is the first row of the image.
    MeshSnapshot mesh;
    addRect(mesh, -1.0f, -1.0f, 1.0f, -0.5f, 0.5f, kBlue);
    const Image image = renderer_->render(mesh, kIdentity, 16, 16);
    expectColor(image, 8, 0, kBlue);
    expectColor(image, 8, 15, glm::vec3(0), 0.0f);
}

TEST_F(OffscreenRendererTest, NearQuadHidesFarQuadWhateverTheDrawOrder) {
    for (bool nearFirst : {true, false}) {
        MeshSnapshot mesh;
        if (nearFirst) addRect(mesh, -0.5f, -0.5f, 0.5f, 0.5f, 0.2f, kRed);
        addRect(mesh, -0.9f, -0.9f, 0.9f, 0.9f, 0.8f, kBlue);
        if (!nearFirst) addRect(mesh, -0.5f, -0.5f, 0.5f, 0.5f, 0.2f, kRed);
        const Image image = renderer_->render(mesh, kIdentity, 32, 32);
        SCOPED_TRACE(nearFirst ? "near drawn first" : "far drawn first");
        expectColor(image, 16, 16, kRed);  // the near quad where both cover
        expectColor(image, 3, 16, kBlue);  // the far one where only it covers
        expectColor(image, 0, 0, glm::vec3(0), 0.0f);
    }
}

TEST_F(OffscreenRendererTest, GouraudInterpolatesVertexColours) {
    const std::array<glm::vec3, 3> p{
        {{-0.9f, 0.9f, 0.5f}, {0.9f, 0.9f, 0.5f}, {0.0f, -0.9f, 0.5f}}};
    MeshSnapshot mesh;
    addFrontTriangle(mesh, p, {kRed, kGreen, kBlue});
    const Image image = renderer_->render(mesh, kIdentity, 128, 128);

    const glm::vec3 centroid = (p[0] + p[1] + p[2]) / 3.0f;
    const auto [x, y] = pixelAt(image, centroid.x, centroid.y);
    // Barycentric coordinates of the sampled pixel centre, which lies within
    // half a pixel of the centroid.
    const glm::vec2 s = pixelCenter(image, x, y);
    const glm::vec2 a(p[0]), b(p[1]), c(p[2]);
    const auto cross2 = [](glm::vec2 u, glm::vec2 v) { return u.x * v.y - u.y * v.x; };
    const float area = cross2(b - a, c - a);
    const float wb = cross2(s - a, c - a) / area;
    const float wc = cross2(b - a, s - a) / area;
    const glm::vec3 exact = (1.0f - wb - wc) * kRed + wb * kGreen + wc * kBlue;
    expectColor(image, x, y, exact, 1e-3f);
    // And, as the picture promises, one third of each at the centroid, within 1%.
    expectColor(image, x, y, glm::vec3(1.0f / 3.0f), 0.01f);
}

TEST_F(OffscreenRendererTest, OverlayLinesAreDrawnOnTopOfSurfaces) {
    MeshSnapshot mesh;
    addRect(mesh, -0.9f, -0.9f, 0.9f, 0.9f, 0.1f, kBlue);  // nearer than the line
    const Image probe = renderer_->render(mesh, kIdentity, 64, 64);
    // A horizontal line through the centres of row 32, behind the quad.
    const float y = pixelCenter(probe, 0, 32).y;
    mesh.linePositions = {{-0.8f, y, 0.9f}, {0.8f, y, 0.9f}};
    mesh.lineColors = {kYellow, kYellow};
    const Image image = renderer_->render(mesh, kIdentity, 64, 64);
    expectColor(image, 32, 32, kYellow);
    expectColor(image, 32, 20, kBlue);

    MeshDrawOptions noOverlays;
    noOverlays.overlays = false;
    expectColor(renderer_->render(mesh, kIdentity, 64, 64, noOverlays), 32, 32, kBlue);
}

TEST_F(OffscreenRendererTest, ReusedForFramesOfDifferentSizes) {
    MeshSnapshot mesh;
    addRect(mesh, -1.0f, -1.0f, 0.0f, 1.0f, 0.5f, kGreen);  // left half
    for (auto [w, h] : {std::array<int, 2>{32, 16}, {7, 9}, {32, 16}, {1, 1}}) {
        const Image image = renderer_->render(mesh, kIdentity, w, h);
        ASSERT_EQ(image.width, w);
        ASSERT_EQ(image.height, h);
        if (w > 1) {
            expectColor(image, 0, h / 2, kGreen);
            expectColor(image, w - 1, h / 2, glm::vec3(0), 0.0f);
        }
    }
    EXPECT_THROW(renderer_->render(mesh, kIdentity, 0, 16), std::runtime_error);
}

TEST_F(OffscreenRendererTest, EmptySnapshotGivesBlackImage) {
    const Image image = renderer_->render(MeshSnapshot{}, kIdentity, 8, 8);
    for (float v : image.rgb) ASSERT_EQ(v, 0.0f);
}

// Exposure is a push constant: one upload, drawn at several exposures. The
// float target shows the scaling exactly, above 1 too (no clipping before the
// PNG encoder).
TEST_F(OffscreenRendererTest, ExposureScalesSurfacesOnTheGpuWithoutReuploading) {
    MeshSnapshot snapshot;
    addRect(snapshot, -1.0f, -1.0f, 0.0f, 1.0f, 0.5f, glm::vec3(0.3f, 0.7f, 1.5f));  // left half
    addFrontTriangle(snapshot, {{{0.1f, 0.9f, 0.5f}, {0.9f, 0.9f, 0.5f}, {0.5f, -0.9f, 0.5f}}},
                {kRed, kGreen, kBlue});  // right: interpolated colours
    const int lineRow = 40;  // a row through both shapes
    const float y = (lineRow + 0.5f) / 64.0f * 2.0f - 1.0f;  // through the pixel centres
    snapshot.linePositions = {{-0.8f, y, 0.1f}, {0.8f, y, 0.1f}};
    snapshot.lineColors = {kYellow, kYellow};
    const GpuMesh mesh(*context_, snapshot);  // the only upload
    const GpuTextures textures(*context_, snapshot.textures);

    MeshDrawOptions options;
    const Image ev0 = renderer_->render(mesh, textures, kIdentity, 64, 64, options);
    options.exposure = 1.0;
    const Image ev1 = renderer_->render(mesh, textures, kIdentity, 64, 64, options);
    options.exposure = -1.0;
    const Image evMinus1 = renderer_->render(mesh, textures, kIdentity, 64, 64, options);
    options.exposure = 0.7;  // not a power of two
    const Image ev07 = renderer_->render(mesh, textures, kIdentity, 64, 64, options);

    const auto [lx, ly] = pixelAt(ev0, -0.5f, -0.5f);
    const auto [rx, ry] = pixelAt(ev0, 0.5f, -0.2f);
    for (auto [x, yy] : {std::array<int, 2>{lx, ly}, {rx, ry}})
        for (int c = 0; c < 3; ++c) {
            const float base = ev0.pixel(x, yy)[c];
            EXPECT_EQ(ev1.pixel(x, yy)[c], 2.0f * base) << x << "," << yy << " channel " << c;
            EXPECT_EQ(evMinus1.pixel(x, yy)[c], 0.5f * base) << x << "," << yy << " channel " << c;
        }
    expectColor(ev1, lx, ly, glm::vec3(0.6f, 1.4f, 3.0f));

    // The same floats as scaling the EV 0 image on the CPU (what PNG output did
    // before): every pixel, to the bit. Overlay lines are markers: unscaled.
    const auto scale = static_cast<float>(std::exp2(0.7));
    int linePixels = 0;
    for (int py = 0; py < ev0.height; ++py)
        for (int px = 0; px < ev0.width; ++px) {
            const float* p = ev0.pixel(px, py);
            const bool onLine = py == lineRow && glm::vec3(p[0], p[1], p[2]) == kYellow;
            linePixels += onLine ? 1 : 0;
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(ev07.pixel(px, py)[c], onLine ? p[c] : p[c] * scale)
                    << px << "," << py << " channel " << c;
        }
    EXPECT_GT(linePixels, 40);
}

// For a UNORM window the fragment shader encodes: the same curve as the PNG
// encoder, after exposure.
TEST_F(OffscreenRendererTest, SrgbEncodedOutputFollowsThePngEncoder) {
    OffscreenRenderer encoding(*context_, ShaderOutput::SrgbEncoded);
    const std::array<float, 6> values{0.0f, 0.002f, 0.05f, 0.214f, 0.5f, 0.9f};
    MeshSnapshot mesh;
    for (std::size_t i = 0; i < values.size(); ++i) {
        const float x0 = -1.0f + 2.0f * static_cast<float>(i) / values.size();
        addRect(mesh, x0, -1.0f, x0 + 2.0f / values.size(), 1.0f, 0.5f, glm::vec3(values[i], values[i] * 0.5f, 2.0f));
    }
    MeshDrawOptions options;
    options.exposure = 0.5;
    const Image image = encoding.render(mesh, kIdentity, 6 * 8, 4, options);
    const auto scale = static_cast<float>(std::exp2(0.5));
    for (std::size_t i = 0; i < values.size(); ++i) {
        const int x = static_cast<int>(i) * 8 + 4;
        const std::array<float, 3> linear{values[i] * scale, values[i] * 0.5f * scale, 2.0f * scale};
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(image.pixel(x, 2)[c] * 255.0f, encodeSrgb(linear[c]), 0.51f)
                << "value " << values[i] << " channel " << c;
    }
}

// Textured surfaces (GpuTextures, MeshSnapshot::uvs / textureLayer /
// texelScale): drawn as colour * linear texel * texelScale.

// A texture of width x height texels given as sRGB RGBA8, rows from the top.
std::shared_ptr<const Texture> makeTexture(std::uint32_t width, std::uint32_t height,
                                           std::vector<std::uint8_t> srgba,
                                           const std::string& name = "test") {
    auto texture = std::make_shared<Texture>();
    texture->name = name;
    texture->width = width;
    texture->height = height;
    texture->srgba = std::move(srgba);
    return texture;
}

// 2x2: black and white on the first row, white and black on the second.
std::shared_ptr<const Texture> checker2x2() {
    return makeTexture(2, 2, {0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255, 0, 0, 0, 255});
}

// Gives every vertex so far the untextured defaults, so that the three
// per-vertex vectors stay one per vertex.
void padTextureVectors(MeshSnapshot& mesh) {
    const std::size_t n = mesh.positions.size();
    mesh.uvs.resize(n, glm::vec2(0.0f));
    mesh.textureLayer.resize(n, -1);
    mesh.texelScale.resize(n, glm::vec3(1.0f));
}

// Axis-aligned rectangle at depth z facing the viewer, uv (0, 0) at its top
// left corner (x0, y0) and uv1 at the bottom right, one texture layer.
void addTexturedRect(MeshSnapshot& mesh, float x0, float y0, float x1, float y1, float z,
                     glm::vec3 color, std::int32_t layer, glm::vec2 uv1 = glm::vec2(1.0f),
                     glm::vec3 texelScale = glm::vec3(1.0f)) {
    padTextureVectors(mesh);
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    const std::array<glm::vec3, 4> p{{{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}};
    const std::array<glm::vec2, 4> uv{{{0.0f, 0.0f}, {uv1.x, 0.0f}, uv1, {0.0f, uv1.y}}};
    for (int i = 0; i < 4; ++i) {
        mesh.positions.push_back(p[i]);
        mesh.normals.emplace_back(0, 0, -1);
        mesh.colors.push_back(color);
        mesh.uvs.push_back(uv[i]);
        mesh.textureLayer.push_back(layer);
        mesh.texelScale.push_back(texelScale);
    }
    // Counter-clockwise in framebuffer space (see addFrontTriangle).
    mesh.indices.insert(mesh.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
}

// Mean of channel 0 over the pixels [x0, x1) x [y0, y1).
float meanRed(const Image& image, int x0, int y0, int x1, int y1) {
    double sum = 0.0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += image.pixel(x, y)[0];
    return static_cast<float>(sum / ((x1 - x0) * (y1 - y0)));
}

// One quad over the whole image, grey 0.5, textured with a 2x2 black and
// white checker: the quadrants follow the texels (uv (0, 0), the first
// texel, at the top left). 66 pixels: the centres of pixels 16 and 49 are
// uv 0.25 and 0.75, the texel centres, where bilinear filtering gives the
// texel itself.
TEST_F(OffscreenRendererTest, TexturedQuadShowsTheTexelsWhereTheTextureSaysAndUntexturedIsUniform) {
    constexpr int kSize = 66;
    const glm::vec3 grey(0.5f);
    MeshSnapshot textured;
    textured.textures = {checker2x2()};
    addTexturedRect(textured, -1.0f, -1.0f, 1.0f, 1.0f, 0.5f, grey, 0);
    const Image image = renderer_->render(textured, kIdentity, kSize, kSize);

    expectColor(image, 16, 16, glm::vec3(0.0f), 1e-3f);  // top left: black
    expectColor(image, 49, 16, grey, 1e-3f);             // top right: white * 0.5
    expectColor(image, 16, 49, grey, 1e-3f);             // bottom left: white
    expectColor(image, 49, 49, glm::vec3(0.0f), 1e-3f);  // bottom right: black
    // Quadrant means: bilinear filtering (repeated at the edges) blends a
    // quarter of the neighbours in, so black reads 0.375 * 0.5 and white
    // 0.625 * 0.5 on average.
    const int h = kSize / 2;
    const float topLeft = meanRed(image, 0, 0, h, h), topRight = meanRed(image, h, 0, kSize, h);
    const float bottomLeft = meanRed(image, 0, h, h, kSize);
    const float bottomRight = meanRed(image, h, h, kSize, kSize);
    EXPECT_NEAR(topLeft, 0.1875f, 0.01f);
    EXPECT_NEAR(bottomRight, 0.1875f, 0.01f);
    EXPECT_NEAR(topRight, 0.3125f, 0.01f);
    EXPECT_NEAR(bottomLeft, 0.3125f, 0.01f);
    // Left half against right half of the top and bottom rows of texels.
    EXPECT_LT(meanRed(image, 0, 0, h, h) + 0.1f, meanRed(image, h, 0, kSize, h));
    EXPECT_GT(meanRed(image, 0, h, h, kSize), meanRed(image, h, h, kSize, kSize) + 0.1f);

    // The same quad with layer -1 (the vectors given), and with the vectors
    // empty: the colour alone, every pixel.
    MeshSnapshot layerNone = textured;
    std::fill(layerNone.textureLayer.begin(), layerNone.textureLayer.end(), -1);
    MeshSnapshot vectorsEmpty = textured;
    vectorsEmpty.uvs.clear();
    vectorsEmpty.textureLayer.clear();
    vectorsEmpty.texelScale.clear();
    for (const MeshSnapshot* mesh : {&layerNone, &vectorsEmpty}) {
        SCOPED_TRACE(mesh == &layerNone ? "layer -1" : "no texture vectors");
        const Image uniform = renderer_->render(*mesh, kIdentity, kSize, kSize);
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(uniform.pixel(x, y)[c], 0.5f) << x << "," << y;
    }
}

// The texture's wrap modes beyond uv 1: a quad with u from 0 to 2 over a
// black | white texture repeats it, clamps it to its white edge, or
// mirrors it (white, then black). Pixels 41 and 57 of 66 sit at u 1.26
// and 1.74, near texel centres once wrapped.
TEST_F(OffscreenRendererTest, TexturesWrapAsTheirSamplerSays) {
    constexpr int kSize = 66;
    struct Case {
        Texture::Wrap wrap;
        float at41, at57;
    };
    for (const Case& c : {Case{Texture::Wrap::Repeat, 0.0f, 1.0f}, Case{Texture::Wrap::Clamp, 1.0f, 1.0f},
                          Case{Texture::Wrap::Mirror, 1.0f, 0.0f}}) {
        SCOPED_TRACE(static_cast<int>(c.wrap));
        auto texture = std::make_shared<Texture>(*makeTexture(2, 1, {0, 0, 0, 255, 255, 255, 255, 255}));
        texture->wrapU = texture->wrapV = c.wrap;
        MeshSnapshot mesh;
        mesh.textures = {texture};
        addTexturedRect(mesh, -1.0f, -1.0f, 1.0f, 1.0f, 0.5f, glm::vec3(1.0f), 0, glm::vec2(2.0f, 1.0f));
        const Image image = renderer_->render(mesh, kIdentity, kSize, kSize);
        EXPECT_NEAR(image.pixel(41, 33)[0], c.at41, 0.05f);
        EXPECT_NEAR(image.pixel(57, 33)[0], c.at57, 0.05f);
        EXPECT_NEAR(image.pixel(8, 33)[0], 0.0f, 0.05f);  // u 0.26: the black texel, whatever the mode
    }
}

// The texel is decoded from sRGB (128 reads 0.216, not 0.502) and multiplied
// by the colour and texelScale, per channel; exposure applies after.
TEST_F(OffscreenRendererTest, TexelIsLinearTimesColourTimesTexelScale) {
    MeshSnapshot mesh;
    mesh.textures = {makeTexture(1, 1, {128, 255, 64, 255})};
    addTexturedRect(mesh, -1.0f, -1.0f, 1.0f, 1.0f, 0.5f, glm::vec3(0.5f, 0.5f, 1.0f), 0,
                    glm::vec2(3.0f), glm::vec3(2.0f, 0.5f, 1.0f));
    MeshDrawOptions options;
    options.exposure = 1.0;
    const Image image = renderer_->render(mesh, kIdentity, 16, 16, options);
    const auto decode = [](double v) { return std::pow((v / 255.0 + 0.055) / 1.055, 2.4); };
    const glm::vec3 expected(2.0 * 0.5 * decode(128) * 2.0, 2.0 * 0.5 * 1.0 * 0.5,
                             2.0 * 1.0 * decode(64) * 1.0);
    expectColor(image, 3, 4, expected, 2e-3f);
    expectColor(image, 12, 11, expected, 2e-3f);
}

// Several textures of different sizes share one array: each quad shows its
// own layer (the 1x1 red one resampled to the checker's 2x2 stays red), and
// a new snapshot with the same texture list reuses the upload.
TEST_F(OffscreenRendererTest, EachQuadSamplesItsOwnLayer) {
    MeshSnapshot mesh;
    mesh.textures = {checker2x2(), makeTexture(1, 1, {255, 0, 0, 255}, "red")};
    addTexturedRect(mesh, -1.0f, -1.0f, 0.0f, 1.0f, 0.5f, glm::vec3(1.0f), 1);  // left: red
    addRect(mesh, 0.0f, -1.0f, 1.0f, 0.0f, 0.5f, kGreen);                       // untextured
    addTexturedRect(mesh, 0.0f, 0.0f, 1.0f, 1.0f, 0.5f, glm::vec3(1.0f), 0);    // checker
    padTextureVectors(mesh);
    const Image image = renderer_->render(mesh, kIdentity, 32, 32);
    for (auto [x, y] : {std::array<int, 2>{2, 2}, {8, 16}, {13, 30}})
        expectColor(image, x, y, kRed, 1e-3f);
    expectColor(image, 24, 8, kGreen);
    // The checker quad starts at pixel 16 and is 16 wide: the centres of
    // pixels 19 and 27 are uv 0.22 and 0.72, near the texel centres (the
    // neighbours weigh 12% there).
    EXPECT_LT(image.pixel(19, 19)[0], 0.2f);  // black texel
    EXPECT_GT(image.pixel(27, 19)[0], 0.8f);  // white
    EXPECT_GT(image.pixel(19, 27)[0], 0.8f);  // white
    EXPECT_LT(image.pixel(27, 27)[0], 0.2f);  // black

    const GpuTextures textures(*context_, mesh.textures);
    EXPECT_EQ(textures.layerCount(), 2u);
    EXPECT_EQ(textures.layerExtent().width, 2u);
    EXPECT_TRUE(textures.sameSources(mesh.textures));
    const std::vector<std::shared_ptr<const Texture>> copies{
        std::make_shared<const Texture>(*mesh.textures[0]), mesh.textures[1]};
    EXPECT_FALSE(textures.sameSources(copies));  // equal images, other objects: upload again
    const GpuMesh gpuMesh(*context_, mesh);
    expectColor(renderer_->render(gpuMesh, textures, kIdentity, 32, 32), 2, 2, kRed, 1e-3f);
    // No textures at all: one white texel, the descriptor still valid.
    const GpuTextures none(*context_, {});
    EXPECT_EQ(none.layerCount(), 1u);
    MeshSnapshot plain;
    addRect(plain, -1.0f, -1.0f, 1.0f, 1.0f, 0.5f, kBlue);
    expectColor(renderer_->render(GpuMesh(*context_, plain), none, kIdentity, 8, 8), 4, 4, kBlue);
}

// A texture vector not one per vertex, a layer without a texture, or a
// missing vector is refused, naming what is wrong, before anything is drawn.
TEST_F(OffscreenRendererTest, TextureVectorsOfTheWrongSizeAreRefused) {
    MeshSnapshot good;
    good.textures = {checker2x2()};
    addTexturedRect(good, -1.0f, -1.0f, 1.0f, 1.0f, 0.5f, glm::vec3(0.5f), 0);
    const auto expectRefused = [&](const MeshSnapshot& mesh, const std::string& words) {
        try {
            GpuMesh gpuMesh(*context_, mesh);
            ADD_FAILURE() << "no exception; expected one naming " << words;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
        EXPECT_THROW(renderer_->render(mesh, kIdentity, 8, 8), std::runtime_error);
    };
    MeshSnapshot shortUvs = good;
    shortUvs.uvs.pop_back();
    expectRefused(shortUvs, "3 uvs for 4 vertices");
    MeshSnapshot longScales = good;
    longScales.texelScale.emplace_back(1.0f);
    expectRefused(longScales, "5 texel scales for 4 vertices");
    MeshSnapshot shortLayers = good;
    shortLayers.textureLayer.resize(1);
    expectRefused(shortLayers, "1 texture layers for 4 vertices");
    MeshSnapshot noUvs = good;
    noUvs.uvs.clear();
    expectRefused(noUvs, "all be empty or all one per vertex");
    MeshSnapshot badLayer = good;
    badLayer.textureLayer[2] = 1;
    expectRefused(badLayer, "vertex 2 has texture layer 1 of 1 textures");
    MeshSnapshot noTextures = good;
    noTextures.textures.clear();
    expectRefused(noTextures, "texture layer 0 of 0 textures");
    // And a malformed texture image.
    MeshSnapshot badImage = good;
    badImage.textures = {makeTexture(2, 2, {0, 0, 0, 255}, "short")};
    try {
        renderer_->render(badImage, kIdentity, 8, 8);
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("texture 0 'short' has 4 bytes, not 2x2x4"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_NO_THROW(renderer_->render(good, kIdentity, 8, 8));
}

// The CPU side of the upload: one common size (the largest, capped), same
// sizes copied byte for byte, resampling in linear light.
TEST(RenderTextureLayers, CommonSizeCopiesOrResamples) {
    const auto checker = checker2x2();
    const auto wide =
        makeTexture(4, 1, {10, 20, 30, 255, 40, 50, 60, 255, 70, 80, 90, 255, 100, 110, 120, 128});
    const TextureLayers packed = packTextureLayers({checker, wide}, 2048);
    EXPECT_EQ(packed.width, 4u);
    EXPECT_EQ(packed.height, 2u);
    EXPECT_EQ(packed.layers, 2u);
    ASSERT_EQ(packed.srgba.size(), 4u * 2u * 4u * 2u);
    // Layer 1 (4x1 -> 4x2): every row the source row.
    for (int y = 0; y < 2; ++y)
        for (int i = 0; i < 16; ++i)
            EXPECT_NEAR(packed.srgba[32 + y * 16 + i], wide->srgba[i], 1)
                << "row " << y << " byte " << i;

    // A checker shrunk to one texel is mid grey in linear light: sRGB 188.
    const TextureLayers grey = packTextureLayers({checker}, 1);
    ASSERT_EQ(grey.srgba.size(), 4u);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(grey.srgba[c], 188) << "channel " << c;
    EXPECT_EQ(grey.srgba[3], 255);

    // The same size: copied.
    const TextureLayers same = packTextureLayers({checker, checker}, 2048);
    EXPECT_EQ(same.width, 2u);
    for (int i = 0; i < 16; ++i) EXPECT_EQ(same.srgba[16 + i], checker->srgba[i]);

    const TextureLayers white = packTextureLayers({}, 2048);
    EXPECT_EQ(white.layers, 1u);
    EXPECT_EQ(white.srgba, (std::vector<std::uint8_t>{255, 255, 255, 255}));

    EXPECT_THROW(packTextureLayers({nullptr}, 2048), std::runtime_error);
    EXPECT_THROW(packTextureLayers({makeTexture(0, 0, {})}, 2048), std::runtime_error);
}

TEST(RenderVulkanContext, ValidationLayerCountsMessages) {
    VulkanContextOptions options;
    options.validation = true;
    std::unique_ptr<VulkanContext> context;
    try {
        context = std::make_unique<VulkanContext>(options);
    } catch (const std::exception& e) {
        FAIL() << "cannot create a Vulkan context with validation: " << e.what();
    }
    ASSERT_EQ(context->validationMessageCount(), 0u);
    // A zero-sized buffer is invalid usage: the layer must report it (on stderr).
    auto info = vkStruct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = 0;
    info.usage = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    std::fprintf(stderr, "(the next validation error is expected)\n");
    const VkResult result = vkCreateBuffer(context->device(), &info, nullptr, &buffer);
    if (result == VK_SUCCESS) vkDestroyBuffer(context->device(), buffer, nullptr);
    EXPECT_GT(context->validationMessageCount(), 0u);
}

TEST(RenderVkCheck, ErrorNamesTheCallAndTheResult) {
    try {
        vkCheck(VK_ERROR_DEVICE_LOST, "vkQueueSubmit");
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "vkQueueSubmit failed: VK_ERROR_DEVICE_LOST");
    }
    EXPECT_EQ(vkCheck(VK_INCOMPLETE, "vkEnumeratePhysicalDevices"), VK_INCOMPLETE);
}

}  // namespace
}  // namespace rad
