// radiosity-cli render: a scene's material preview through its camera, to an image file.

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/Args.h"
#include "cli/Commands.h"
#include "cli/RenderOutput.h"
#include "radiosity/Gltf.h"
#include "radiosity/Snapshot.h"

namespace rad::cli {
namespace {

const std::vector<OptionSpec>& renderOptions() {
    static const std::vector<OptionSpec> options{
        {"--image", "OUT",
         "output file (required): .png is sRGB-encoded, .pfm holds linear values"},
        {"--size", "WxH",
         "image size, each side 1..8192 (default 512x512, or 512 high with the camera's aspect)"},
        {"--exposure", "EV", "PNG only: multiply by 2^EV before sRGB encoding (default 0)"},
        {"--force", "", "overwrite OUT if it exists"},
    };
    return options;
}

void printRenderHelp() {
    std::printf(
        "usage: radiosity-cli render SCENE --image OUT.png|OUT.pfm [--size WxH] [--exposure EV] "
        "[--force]\n"
        "Renders the material preview (reflectance + emission per polygon) of the glTF\n"
        "SCENE through its camera, or through an automatic view of the whole scene when\n"
        "it has none. The PFM is linear, without exposure or tone mapping.\n\n%s",
        formatOptions(renderOptions()).c_str());
}

}  // namespace

int runRender(const std::vector<std::string>& argv) {
    // Set up: read and check the whole command line before any work.
    const ParsedArgs args = parseArgs(argv, renderOptions());
    if (args.has("--help")) {
        printRenderHelp();
        return kExitOk;
    }
    requirePositionals(args, {"SCENE"});
    const std::string scenePath = args.positionals[0];
    const std::optional<std::string> out = args.value("--image");
    if (!out) throw UsageError("render needs --image OUT.png|OUT.pfm");
    checkImagePath("--image", *out);
    ImageRequest request{*out, std::nullopt, 0.0};
    if (auto s = args.value("--size")) request.size = parseSize("--size", *s);
    if (auto e = args.value("--exposure")) request.exposure = parseDouble("--exposure", *e);
    checkWritable(*out, args.has("--force"));
    if (!std::filesystem::exists(scenePath)) throw std::runtime_error(scenePath + ": no such file");
    const Scene scene = loadGltf(scenePath);

    // Draw.
    renderToFile(scene, makePreviewSnapshot(scene), request);
    std::printf("wrote %s\n", out->c_str());
    return kExitOk;
}

}  // namespace rad::cli
