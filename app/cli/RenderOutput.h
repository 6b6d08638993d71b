#pragma once
// What every command that writes pictures shares: the output checks and
// "render this mesh through the scene's camera into this file".

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/Args.h"
#include "radiosity/Scene.h"
#include "radiosity/Snapshot.h"

namespace rad::cli {

struct ImageRequest {
    std::string path;                // .png (sRGB) or .pfm (linear)
    std::optional<ImageSize> size;   // default: 512 high, the camera's aspect
    double exposure = 0.0;           // PNG only: times 2^EV
};

// --size WxH and --exposure EV, bound to `size` and `exposure`.
void addImageOptions(CLI::App& command, std::optional<ImageSize>& size, double& exposure);
// Throws CLI::ValidationError unless the path ends in .png or .pfm: an option
// check, as in add_option("--image", path)->each(checkImagePath).
void checkImagePath(const std::string& path);
// Throws std::runtime_error when the file exists and force is false: nothing
// the user owns is overwritten without asking.
void checkWritable(const std::string& path, bool force);
// The image size a request resolves to for this scene.
ImageSize imageSizeFor(const Scene& scene, const std::optional<ImageSize>& size);

// Renders `mesh` through the scene camera (or an automatic view) with
// lavapipe and writes the file atomically. Throws std::runtime_error, also
// when the validation layer (RADIOSITY_VALIDATION=1) reported anything.
void renderToFile(const Scene& scene, const MeshSnapshot& mesh, const ImageRequest& request);

}  // namespace rad::cli
