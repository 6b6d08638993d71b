#include "radiosity/Gltf.h"
#include "radiosity/Snapshot.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace rad {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
    throw std::runtime_error(path + ": " + problem);
}

bool isGlb(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".glb";
}

void validate(const MeshSnapshot& mesh, const std::string& path) {
    const std::size_t n = mesh.positions.size();
    if (n == 0) fail(path, "mesh is empty, nothing to export");
    if (mesh.normals.size() != n && !mesh.normals.empty())
        fail(path, "mesh has " + std::to_string(mesh.normals.size()) + " normals for " +
                       std::to_string(n) + " positions");
    if (mesh.colors.size() != n && !mesh.colors.empty())
        fail(path, "mesh has " + std::to_string(mesh.colors.size()) + " colours for " +
                       std::to_string(n) + " positions");
    if (mesh.indices.size() % 3 != 0) fail(path, "index count is not a multiple of 3");
    for (std::uint32_t i : mesh.indices)
        if (i >= n) fail(path, "index " + std::to_string(i) + " is out of range");
}

// Appends raw bytes as a new bufferView of buffer 0; returns its index.
template <typename T>
int addView(tinygltf::Model& model, const std::vector<T>& data, int target) {
    std::vector<unsigned char>& bytes = model.buffers[0].data;
    // Every view starts 4-byte aligned, as glTF requires for float components.
    bytes.resize((bytes.size() + 3) & ~std::size_t{3}, 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = bytes.size();
    view.byteLength = data.size() * sizeof(T);
    view.target = target;
    bytes.resize(bytes.size() + view.byteLength);
    std::memcpy(bytes.data() + view.byteOffset, data.data(), view.byteLength);
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size()) - 1;
}

int addVec3Accessor(tinygltf::Model& model, const std::vector<glm::vec3>& data, bool withBounds) {
    tinygltf::Accessor acc;
    acc.bufferView = addView(model, data, TINYGLTF_TARGET_ARRAY_BUFFER);
    acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    acc.type = TINYGLTF_TYPE_VEC3;
    acc.count = data.size();
    if (withBounds) {
        glm::vec3 lo = data.front();
        glm::vec3 hi = data.front();
        for (const glm::vec3& p : data) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        acc.minValues = {lo.x, lo.y, lo.z};
        acc.maxValues = {hi.x, hi.y, hi.z};
    }
    model.accessors.push_back(acc);
    return static_cast<int>(model.accessors.size()) - 1;
}

int addIndexAccessor(tinygltf::Model& model, const std::vector<std::uint32_t>& indices) {
    tinygltf::Accessor acc;
    acc.bufferView = addView(model, indices, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    acc.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    acc.type = TINYGLTF_TYPE_SCALAR;
    acc.count = indices.size();
    model.accessors.push_back(acc);
    return static_cast<int>(model.accessors.size()) - 1;
}

tinygltf::Material unlitMaterial() {
    tinygltf::Material m;
    m.name = "radiosity";
    m.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
    m.pbrMetallicRoughness.metallicFactor = 0.0;
    m.pbrMetallicRoughness.roughnessFactor = 1.0;
    // The colours are already the light leaving each vertex: no shading.
    m.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object());
    return m;
}

tinygltf::Model buildModel(const MeshSnapshot& mesh) {
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "radiosity";
    model.buffers.emplace_back();

    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = addVec3Accessor(model, mesh.positions, true);
    if (!mesh.normals.empty())
        prim.attributes["NORMAL"] = addVec3Accessor(model, mesh.normals, false);
    if (!mesh.colors.empty())
        prim.attributes["COLOR_0"] = addVec3Accessor(model, mesh.colors, false);
    if (!mesh.indices.empty()) prim.indices = addIndexAccessor(model, mesh.indices);
    prim.material = 0;

    model.materials.push_back(unlitMaterial());
    model.extensionsUsed.push_back("KHR_materials_unlit");

    tinygltf::Mesh gm;
    gm.name = "radiosity";
    gm.primitives.push_back(prim);
    model.meshes.push_back(gm);

    tinygltf::Node node;
    node.name = "radiosity";
    node.mesh = 0;
    // The positions are relative to the snapshot's origin, and the scene to
    // where the file had it; glTF's node translation is a double in the
    // JSON, so nothing is lost far out.
    const glm::dvec3 at = mesh.origin + mesh.fileOrigin;
    if (at != glm::dvec3(0.0)) node.translation = {at.x, at.y, at.z};
    model.nodes.push_back(node);

    tinygltf::Scene scene;
    scene.nodes.push_back(0);
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    return model;
}

}  // namespace

void exportGltf(const MeshSnapshot& mesh, const std::string& path) {
    validate(mesh, path);
    // A frame's mesh holds room for polygons to grow in (compactMesh): the
    // file gets none of it.
    const tinygltf::Model model = buildModel(compactMesh(mesh));
    const std::string tmp = path + ".tmp";
    tinygltf::TinyGLTF writer;
    const bool binary = isGlb(path);
    if (!writer.WriteGltfSceneToFile(&model, tmp, /*embedImages=*/true, /*embedBuffers=*/true,
                                     /*prettyPrint=*/!binary, binary)) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        fail(path, "could not write " + tmp);
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        fail(path, "could not rename " + tmp + ": " + ec.message());
    }
}

}  // namespace rad
