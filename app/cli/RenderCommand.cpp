// radiosity-cli render: a scene's material preview through its camera, to an image file.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "cli/Args.h"
#include "cli/Commands.h"
#include "cli/RenderOutput.h"
#include "radiosity/Gltf.h"
#include "radiosity/Snapshot.h"

namespace rad::cli {
namespace {

struct RenderSettings {
    std::string scene;
    ImageRequest image;
    bool force = false;
};

int render(const RenderSettings& s) {
    checkWritable(s.image.path, s.force);
    if (!std::filesystem::exists(s.scene)) throw std::runtime_error(s.scene + ": no such file");
    const Scene scene = loadGltf(s.scene);
    renderToFile(scene, makePreviewSnapshot(scene), s.image);
    std::printf("wrote %s\n", s.image.path.c_str());
    return kExitOk;
}

}  // namespace

Command addRender(CLI::App& cli) {
    auto s = std::make_shared<RenderSettings>();
    CLI::App* c = cli.add_subcommand("render", "render a glTF scene's material preview to PNG or PFM");
    c->footer(
        "Renders the material preview (reflectance + emission per polygon) of the glTF\n"
        "SCENE through its camera, or through an automatic view of the whole scene when\n"
        "it has none. The PFM is linear, without exposure or tone mapping.");
    addScene(*c, s->scene);
    c->add_option("--image", s->image.path, "output file: .png is sRGB-encoded, .pfm holds linear values")
        ->type_name("OUT")
        ->required()
        ->each(checkImagePath);
    addImageOptions(*c, s->image.size, s->image.exposure);
    addFlag(*c, "--force", s->force, "overwrite OUT if it exists");
    return {c, [s] { return render(*s); }};
}

}  // namespace rad::cli
