#include "cli/RenderOutput.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

#include "image/Exposure.h"
#include "image/Image.h"
#include "render/CameraView.h"
#include "render/OffscreenRenderer.h"
#include "render/VulkanContext.h"

namespace rad::cli {
namespace {

constexpr int kDefaultHeight = 512;
constexpr int kMaxSide = 8192;

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace

void addImageOptions(CLI::App& command, std::optional<ImageSize>& size, double& exposure) {
    command.add_option("--size")
        ->description("image size, each side 1.." + std::to_string(kMaxSide) + " (default: " +
                      std::to_string(kDefaultHeight) + " high with the camera's\naspect, square without a camera)")
        ->type_name("WxH")
        ->each([&size](const std::string& text) { size = parseSize(text, 1, kMaxSide); });
    command.add_option("--exposure", exposure, "PNG only: multiply by 2^EV before sRGB encoding")
        ->type_name("EV")
        ->check(number())
        ->capture_default_str();
}

void checkImagePath(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext != ".png" && ext != ".pfm") throw CLI::ValidationError("'" + path + "' must end in .png or .pfm");
}

void checkWritable(const std::string& path, bool force) {
    if (std::filesystem::exists(path) && !force)
        throw std::runtime_error(path + " exists; use --force to overwrite it");
}

ImageSize imageSizeFor(const Scene& scene, const std::optional<ImageSize>& size) {
    if (size) return *size;
    ImageSize s{kDefaultHeight, kDefaultHeight};
    if (scene.camera && scene.camera->aspectRatio && *scene.camera->aspectRatio > 0.0) {
        const double width = std::round(kDefaultHeight * *scene.camera->aspectRatio);
        s.width = static_cast<int>(std::clamp(width, 1.0, static_cast<double>(kMaxSide)));
    }
    return s;
}

void renderToFile(const Scene& scene, const MeshSnapshot& mesh, const ImageRequest& request) {
    const ImageSize size = imageSizeFor(scene, request.size);
    // The image decides the aspect, so a --size unlike the camera's widens or
    // narrows the view instead of stretching it.
    const double aspect = static_cast<double>(size.width) / size.height;
    const CameraView view = makeCameraView(sceneCameraOrAutoFit(scene, aspect), scene.bounds(), aspect);

    // The context is gone before the validation check so that objects reported
    // as leaked when the device and instance are destroyed count too.
    Image image;
    std::shared_ptr<const std::atomic<std::size_t>> validationMessages;
    {
        VulkanContext context;  // validation follows RADIOSITY_VALIDATION
        validationMessages = context.validationMessageCounter();
        OffscreenRenderer renderer(context);
        // Exposure is the shader's (a push constant), for PNG only: PFM holds B.
        MeshDrawOptions options;
        options.exposure = lowerExtension(request.path) == ".png" ? request.exposure : 0.0;
        image = renderer.render(mesh, view.viewProjection(), size.width, size.height, options);
    }
    if (const std::size_t messages = *validationMessages; messages > 0)
        throw std::runtime_error("the Vulkan validation layer reported " + std::to_string(messages) +
                                 " message(s); " + request.path + " not written");
    writeImage(image, request.path);
    if (lowerExtension(request.path) != ".png") return;
    std::vector<float> peaks(image.rgb.size() / 3);
    for (std::size_t i = 0; i < peaks.size(); ++i)
        peaks[i] = std::max({image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]});
    if (const std::optional<double> better = exposureThatShows(std::move(peaks), request.exposure))
        std::fprintf(
            stderr,
            "note: %s: most lit pixels are past white at --exposure %g; --exposure %g shows them\n",
            request.path.c_str(), request.exposure, *better);
}

}  // namespace rad::cli
