#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "radiosity/Gltf.h"
#include "radiosity/Scene.h"
#include "support/TempDir.h"

namespace rad {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

// Two triangles of a unit square with colours above 1 (radiosity is not
// clamped) and an odd vertex order, so a silent reordering would show.
MeshSnapshot sampleMesh() {
    MeshSnapshot m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.25f}, {-2, 3, -4}};
    m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 1, 0}};
    m.colors = {{0.1f, 0.2f, 0.3f}, {2.5f, 0.0f, 1.0f}, {0.25f, 0.5f, 0.75f}, {7, 8, 9}, {0, 0, 0}};
    m.indices = {0, 1, 2, 0, 2, 3, 2, 4, 3};
    return m;
}

tinygltf::Model readBack(const fs::path& file) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
    const bool binary = file.extension() == ".glb";
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                           : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
    EXPECT_TRUE(ok) << err;
    return model;
}

template <typename T>
std::vector<T> readAccessor(const tinygltf::Model& model, int index) {
    const tinygltf::Accessor& acc = model.accessors.at(index);
    const tinygltf::BufferView& view = model.bufferViews.at(acc.bufferView);
    const tinygltf::Buffer& buf = model.buffers.at(view.buffer);
    const std::size_t stride = view.byteStride != 0 ? view.byteStride : sizeof(T);
    std::vector<T> out(acc.count);
    for (std::size_t i = 0; i < acc.count; ++i) {
        const std::size_t offset = view.byteOffset + acc.byteOffset + i * stride;
        EXPECT_LE(offset + sizeof(T), buf.data.size());
        std::memcpy(&out[i], buf.data.data() + offset, sizeof(T));
    }
    return out;
}

void expectSameMesh(const MeshSnapshot& mesh, const fs::path& file) {
    const tinygltf::Model model = readBack(file);
    ASSERT_EQ(model.meshes.size(), 1u);
    ASSERT_EQ(model.nodes.size(), 1u);
    EXPECT_EQ(model.nodes[0].mesh, 0);
    ASSERT_EQ(model.meshes[0].primitives.size(), 1u);
    const tinygltf::Primitive& prim = model.meshes[0].primitives[0];
    EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);

    const int posIndex = prim.attributes.at("POSITION");
    const tinygltf::Accessor& pos = model.accessors.at(posIndex);
    EXPECT_EQ(pos.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(pos.type, TINYGLTF_TYPE_VEC3);
    EXPECT_EQ(readAccessor<glm::vec3>(model, posIndex), mesh.positions);
    ASSERT_EQ(pos.minValues.size(), 3u);
    ASSERT_EQ(pos.maxValues.size(), 3u);
    EXPECT_EQ(glm::vec3(pos.minValues[0], pos.minValues[1], pos.minValues[2]),
              glm::vec3(-2, 0, -4));
    EXPECT_EQ(glm::vec3(pos.maxValues[0], pos.maxValues[1], pos.maxValues[2]),
              glm::vec3(1, 3, 0.25f));

    const int colIndex = prim.attributes.at("COLOR_0");
    EXPECT_EQ(model.accessors.at(colIndex).type, TINYGLTF_TYPE_VEC3);
    EXPECT_EQ(model.accessors.at(colIndex).componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(readAccessor<glm::vec3>(model, colIndex), mesh.colors);
    EXPECT_EQ(readAccessor<glm::vec3>(model, prim.attributes.at("NORMAL")), mesh.normals);

    ASSERT_GE(prim.indices, 0);
    EXPECT_EQ(model.accessors.at(prim.indices).componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
    EXPECT_EQ(readAccessor<std::uint32_t>(model, prim.indices), mesh.indices);

    ASSERT_EQ(prim.material, 0);
    const tinygltf::Material& mat = model.materials.at(0);
    EXPECT_EQ(mat.pbrMetallicRoughness.baseColorFactor, std::vector<double>({1, 1, 1, 1}));
    EXPECT_EQ(mat.extensions.count("KHR_materials_unlit"), 1u);
    EXPECT_NE(
        std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), "KHR_materials_unlit"),
        model.extensionsUsed.end());
    EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
}

TEST(GltfExport, GlbRoundTripKeepsPositionsAndColours) {
    TempDir dir;
    const MeshSnapshot mesh = sampleMesh();
    const fs::path file = dir / "out.glb";
    exportGltf(mesh, file.string());
    std::string magic(4, '\0');
    std::ifstream(file, std::ios::binary).read(magic.data(), 4);
    EXPECT_EQ(magic, "glTF");
    expectSameMesh(mesh, file);
}

TEST(GltfExport, GltfRoundTripKeepsPositionsAndColours) {
    TempDir dir;
    const MeshSnapshot mesh = sampleMesh();
    const fs::path file = dir / "out.gltf";
    exportGltf(mesh, file.string());
    expectSameMesh(mesh, file);
    // The buffer is embedded: the directory holds the .gltf alone.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir / ""), fs::directory_iterator()), 1);
}

// A frame's mesh keeps room for polygons to grow in (compactMesh): a
// vertex no triangle uses and degenerate triangles on a vertex. The file
// holds the mesh without them, its bounds those of the vertices drawn.
TEST(GltfExport, RoomToGrowIsNotWritten) {
    TempDir dir;
    MeshSnapshot padded = sampleMesh();
    padded.positions.insert(padded.positions.begin() + 3, glm::vec3(50, 50, 50));
    padded.normals.insert(padded.normals.begin() + 3, glm::vec3(0, 0, 1));
    padded.colors.insert(padded.colors.begin() + 3, glm::vec3(5, 5, 5));
    padded.indices = {0, 1, 2, 0, 2, 4, 2, 2, 2, 2, 5, 4, 1, 1, 1};
    const fs::path file = dir / "out.gltf";
    exportGltf(padded, file.string());
    expectSameMesh(sampleMesh(), file);
}

// A snapshot far from the world's origin has positions relative to its own
// (MeshSnapshot::origin): the file keeps them and puts the origin, a double
// in the JSON, in the node's translation. A snapshot at the origin has none.
TEST(GltfExport, TheSnapshotsOriginIsTheNodesTranslation) {
    TempDir dir;
    for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6 + 0.125, 5e5, -1e6)}) {
        MeshSnapshot mesh = sampleMesh();
        mesh.origin = origin;
        const fs::path file = dir / "out.gltf";
        exportGltf(mesh, file.string());
        expectSameMesh(mesh, file);
        const std::vector<double> translation = readBack(file).nodes.at(0).translation;
        if (origin == glm::dvec3(0.0)) {
            EXPECT_TRUE(translation.empty());
        } else {
            EXPECT_EQ(translation, (std::vector<double>{origin.x, origin.y, origin.z}));
        }
    }
}

TEST(GltfExport, OverwritesAnExistingFile) {
    TempDir dir;
    const fs::path file = dir / "out.glb";
    MeshSnapshot first = sampleMesh();
    first.colors[0] = {100, 100, 100};
    exportGltf(first, file.string());
    const MeshSnapshot second = sampleMesh();
    exportGltf(second, file.string());
    expectSameMesh(second, file);
}

TEST(GltfExport, ImportedSceneRoundTripsGeometry) {
    // Scene -> preview snapshot -> glTF: the exported triangles cover the
    // same area as the scene's polygons.
    Scene scene;
    scene.materials.push_back({"m", glm::dvec3(0.5), glm::dvec3(1.0)});
    Polygon quad;
    quad.vertexCount = 4;
    quad.vertices = {glm::dvec3(0, 0, 0), glm::dvec3(2, 0, 0), glm::dvec3(2, 3, 0),
                     glm::dvec3(0, 3, 0)};
    scene.polygons.push_back(quad);
    scene.objects.push_back({"q", glm::dmat4(1.0), false, 0, 1, {}});
    TempDir dir;
    const fs::path file = dir / "preview.gltf";
    const MeshSnapshot mesh = makePreviewSnapshot(scene);
    exportGltf(mesh, file.string());
    const tinygltf::Model model = readBack(file);
    const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
    const auto pos = readAccessor<glm::vec3>(model, prim.attributes.at("POSITION"));
    const auto idx = readAccessor<std::uint32_t>(model, prim.indices);
    double area = 0.0;
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3)
        area += 0.5 * glm::length(
                          glm::cross(pos[idx[t + 1]] - pos[idx[t]], pos[idx[t + 2]] - pos[idx[t]]));
    EXPECT_NEAR(area, 6.0, 1e-6);
    for (const glm::vec3& c : readAccessor<glm::vec3>(model, prim.attributes.at("COLOR_0")))
        EXPECT_EQ(c, glm::vec3(1.5f));
}

TEST(GltfExport, FailuresThrowOneLine) {
    TempDir dir;
    const auto expectOneLine = [](const std::function<void()>& f, const std::string& needle) {
        try {
            f();
            ADD_FAILURE() << "no exception";
        } catch (const std::runtime_error& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            EXPECT_NE(message.find(needle), std::string::npos) << message;
        }
    };
    const fs::path missingDir = dir / "no" / "such" / "dir" / "out.glb";
    expectOneLine([&] { exportGltf(sampleMesh(), missingDir.string()); }, missingDir.string());
    EXPECT_FALSE(fs::exists(missingDir));

    expectOneLine([&] { exportGltf(MeshSnapshot{}, (dir / "empty.glb").string()); }, "empty");
    MeshSnapshot bad = sampleMesh();
    bad.indices.back() = 99;
    expectOneLine([&] { exportGltf(bad, (dir / "bad.glb").string()); }, "index 99");
    EXPECT_FALSE(fs::exists(dir / "bad.glb"));
}

}  // namespace
}  // namespace rad
