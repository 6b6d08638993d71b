// Base colour textures (issue 15): texture coordinates reach the polygons,
// each surface element reflects the mean of the texels under it, the light
// the solution computes follows the texture, and the snapshot gives a
// renderer what it needs to draw the texels.

#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"
#include "snapshot/RadiositySnapshot.h"
#include "support/GltfBuilder.h"

namespace rad {
namespace {

using test::GltfBuilder;

// A material with an RGB texture of one row, baseColorFactor 0.8;
// `textureInfo`: more members of its baseColorTexture (e.g. extensions).
int addTexturedMaterial(GltfBuilder& g, const std::vector<std::array<unsigned char, 3>>& row,
                        const std::string& textureInfo = "") {
    const std::string png = test::makePng(static_cast<int>(row.size()), 1, row);
    g.images.push_back("{\"uri\":\"data:image/png;base64," + test::base64(png) + "\"}");
    g.textures.push_back("{\"source\":" + std::to_string(g.images.size() - 1) + "}");
    return g.addMaterial(
        "{\"name\":\"Tex\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.8,0.8,1],"
        "\"baseColorTexture\":{\"index\":" + std::to_string(g.textures.size() - 1) + textureInfo + "}}}");
}

// A 2 x 3 m rectangle in the plane z = 0 facing +z, texture coordinates
// u = x / 2, v = y / 3, and a 4 x 1 texture: two white texels, then two
// black ones, so the half x < 1 is white. baseColorFactor 0.8.
GltfBuilder texturedRectangle(const std::string& textureInfo = "") {
    GltfBuilder g;
    const int mat = addTexturedMaterial(g, {{255, 255, 255}, {255, 255, 255}, {0, 0, 0}, {0, 0, 0}}, textureInfo);
    const std::vector<glm::vec3> p = {{0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, 0}};
    const std::vector<glm::vec2> uv = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    g.addMesh("T", g.addPositions(p), g.addIndices({0, 1, 2, 0, 2, 3}), mat, -1, g.addTexCoords(uv));
    g.addNode("\"name\":\"T\",\"mesh\":0");
    return g;
}

// The lit mesh of the scene solved at the default settings under a point
// light of intensity 10 at `at` (an empty mesh, and a failure, if the solve
// does not converge).
MeshSnapshot solvedUnderABulb(Scene s, const glm::dvec3& at) {
    PunctualLight bulb;
    bulb.name = "bulb";
    bulb.position = at;
    bulb.intensity = glm::dvec3(10.0);
    s.lights.push_back(bulb);
    Engine engine(s, EngineSettings{});
    if (!engine.solve().converged) {
        ADD_FAILURE() << "the solve did not converge";
        return {};
    }
    return compactMesh(engine.snapshot());  // without the room its slots keep to grow in
}

TEST(Texture, CoordinatesReachThePolygons) {
    test::TempDir dir;
    const Scene s = loadGltf(texturedRectangle().writeEmbedded(dir).string());
    ASSERT_EQ(s.textures.size(), 1u);
    ASSERT_EQ(s.polygons.size(), 1u);  // the two triangles merge: the coordinates are affine
    const Polygon& p = s.polygons[0];
    const Material& m = s.materials[p.material];
    EXPECT_EQ(m.texture, 0);
    EXPECT_NEAR(m.textureMean.x, 0.5, 1e-12);
    EXPECT_NEAR(m.reflectance.x, 0.4, 1e-12);  // the factor times the mean
    for (int k = 0; k < p.vertexCount; ++k) {
        EXPECT_NEAR(p.uv[k].x, p.vertices[k].x / 2.0, 1e-6) << k;
        EXPECT_NEAR(p.uv[k].y, p.vertices[k].y / 3.0, 1e-6) << k;
    }
}

TEST(Texture, ElementsReflectTheTexelsUnderThem) {
    test::TempDir dir;
    const Scene s = loadGltf(texturedRectangle().writeEmbedded(dir).string());
    Hierarchy h(s, 1e-6);
    const ElementId top = h.polygonElement(0);
    // Elements keep their reflectance in single precision: within a float's step.
    EXPECT_NEAR(h[top].reflectance.x, 0.4, 1e-7);  // the whole texture: its mean
    h.subdivide(top);
    ASSERT_EQ(h[top].children.size(), 4u);
    for (ElementId c : h[top].children) {
        const bool white = h[c].center.x < 1.0;
        EXPECT_NEAR(h[c].reflectance.x, white ? 0.8 : 0.0, 1e-7)
            << "child at x = " << h[c].center.x;
    }
}

// The four children's reflectance (red) of the rectangle's polygon, with
// their centres.
std::vector<std::pair<glm::dvec3, double>> childReflectance(const Scene& s) {
    Hierarchy h(s, 1e-6);
    const ElementId top = h.polygonElement(0);
    h.subdivide(top);
    std::vector<std::pair<glm::dvec3, double>> out;
    for (ElementId c : h[top].children) out.emplace_back(h[c].center, h[c].reflectance.x);
    return out;
}

// KHR_texture_transform, as Blender writes it for a mapping node, is baked
// into the texture coordinates: an offset and scale that pick the black half
// of the texture make the whole rectangle black; a quarter turn makes the
// texture run along y, white where y < 1.5 (the other way round, it would be
// white where y > 1.5); the extension's texCoord picks another set.
TEST(Texture, TheTextureTransformMovesTheTexelsUnderTheElements) {
    test::TempDir dir;
    const Scene shifted = loadGltf(
        texturedRectangle(",\"extensions\":{\"KHR_texture_transform\":{\"offset\":[0.5,0],\"scale\":[0.5,1]}}")
            .writeEmbedded(dir, "shifted.gltf")
            .string());
    for (const auto& [centre, rho] : childReflectance(shifted)) EXPECT_EQ(rho, 0.0) << "child at x = " << centre.x;

    const Scene turned = loadGltf(
        texturedRectangle(",\"extensions\":{\"KHR_texture_transform\":{\"rotation\":1.5707963267948966}}")
            .writeEmbedded(dir, "turned.gltf")
            .string());
    for (const auto& [centre, rho] : childReflectance(turned))
        EXPECT_NEAR(rho, centre.y < 1.5 ? 0.8 : 0.0, 1e-6) << "child at y = " << centre.y;

    // TEXCOORD_1 = 1 - TEXCOORD_0 in u: the texture mirrored, white where x > 1.
    GltfBuilder g = texturedRectangle(",\"extensions\":{\"KHR_texture_transform\":{\"texCoord\":1}}");
    const int second = g.addTexCoords({{1, 0}, {0, 0}, {0, 1}, {1, 1}});
    const std::string first = "\"TEXCOORD_0\":";
    g.meshes[0].insert(g.meshes[0].find(first), "\"TEXCOORD_1\":" + std::to_string(second) + ",");
    for (const auto& [centre, rho] : childReflectance(loadGltf(g.writeEmbedded(dir, "second.gltf").string())))
        EXPECT_NEAR(rho, centre.x > 1.0 ? 0.8 : 0.0, 1e-6) << "child at x = " << centre.x;
}

TEST(Texture, ABadTextureTransformIsAnErrorNamingTheMaterial) {
    test::TempDir dir;
    try {
        loadGltf(texturedRectangle(",\"extensions\":{\"KHR_texture_transform\":{\"scale\":[1]}}")
                     .writeEmbedded(dir)
                     .string());
        ADD_FAILURE() << "a scale of one number was accepted";
    } catch (const std::exception& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("'Tex'"), std::string::npos) << m;
        EXPECT_NE(m.find("KHR_texture_transform"), std::string::npos) << m;
        EXPECT_NE(m.find("scale must be two finite numbers"), std::string::npos) << m;
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
}

// A light over the rectangle: the white half reflects, the black half does
// not, and the snapshot's texels times texelScale give back the
// reflectance each vertex's radiosity was computed with.
TEST(Texture, TheSolutionAndTheSnapshotFollowTheTexture) {
    test::TempDir dir;
    const MeshSnapshot mesh = solvedUnderABulb(loadGltf(texturedRectangle().writeEmbedded(dir).string()), glm::dvec3(1.0, 1.5, 2.0));
    ASSERT_EQ(mesh.uvs.size(), mesh.positions.size());
    ASSERT_EQ(mesh.textureLayer.size(), mesh.positions.size());
    ASSERT_EQ(mesh.texelScale.size(), mesh.positions.size());
    ASSERT_EQ(mesh.textures.size(), 1u);
    int white = 0, black = 0;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_EQ(mesh.textureLayer[i], 0);
        EXPECT_NEAR(mesh.uvs[i].x, mesh.positions[i].x / 2.0, 1e-5);
        const double x = mesh.positions[i].x;
        if (x < 0.9) {
            // Leaves that all lie on white texels: B = 0.8 H there, and the
            // texel (white, 1) times texelScale is 1.
            EXPECT_GT(mesh.colors[i].x, 0.0);
            EXPECT_NEAR(mesh.textures[0]->texel(glm::dvec2(mesh.uvs[i])).x * mesh.texelScale[i].x, 1.0, 1e-5);
            ++white;
        } else if (x > 1.1) {
            EXPECT_EQ(mesh.colors[i].x, 0.0f);  // black texels reflect nothing
            ++black;
        }
    }
    EXPECT_GT(white, 4);
    EXPECT_GT(black, 4);
}

// The textured rectangle made to glow by an edit: an emitter is drawn
// untextured, in the next frame's mesh too (its polygon is meshed again,
// not only coloured again: its material is part of what its mesh is made
// from).
TEST(Texture, ARectangleMadeToGlowIsDrawnUntextured) {
    test::TempDir dir;
    Scene s = loadGltf(texturedRectangle().writeEmbedded(dir).string());
    PunctualLight bulb;
    bulb.name = "bulb";
    bulb.position = glm::dvec3(1.0, 1.5, 2.0);
    bulb.intensity = glm::dvec3(10.0);
    s.lights.push_back(bulb);
    Engine engine(s, EngineSettings{});
    ASSERT_TRUE(engine.solve().converged);
    const MeshSnapshot before = compactMesh(engine.snapshot());
    ASSERT_FALSE(before.textureLayer.empty());
    for (int layer : before.textureLayer) EXPECT_EQ(layer, 0);
    engine.editMaterial("T", glm::dvec3(5.0), std::nullopt);
    const MeshSnapshot after = compactMesh(engine.snapshot());
    ASSERT_EQ(after.textureLayer.size(), after.positions.size());
    for (int layer : after.textureLayer) EXPECT_EQ(layer, -1);
}

// Two tiles of one textured material meeting at x = 1, one on white texels,
// one on mid-grey ones: the seam's vertices show the same light per unit of
// reflectance on both sides (colour times texelScale), each its own colour.
TEST(Texture, TilesMeetingAtASeamShareTheirLightNotTheirColour) {
    test::TempDir dir;
    GltfBuilder g;
    const int mat = addTexturedMaterial(g, {{255, 255, 255}, {255, 255, 255}, {128, 128, 128}, {128, 128, 128}});
    // Two quads that share no vertex index: two polygons.
    const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 3, 0}, {0, 3, 0}, {1, 0, 0}, {2, 0, 0}, {2, 3, 0}, {1, 3, 0}};
    std::vector<glm::vec2> uv;
    for (const glm::vec3& q : p) uv.emplace_back(q.x / 2.0f, q.y / 3.0f);
    g.addMesh("T", g.addPositions(p), g.addIndices({0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}), mat, -1, g.addTexCoords(uv));
    g.addNode("\"name\":\"T\",\"mesh\":0");
    const Scene s = loadGltf(g.writeEmbedded(dir).string());
    ASSERT_EQ(s.polygons.size(), 2u);
    const MeshSnapshot mesh = solvedUnderABulb(s, glm::dvec3(1.0, 1.5, 1.0));
    ASSERT_EQ(mesh.texelScale.size(), mesh.positions.size());
    int seams = 0;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i)
        for (std::size_t j = i + 1; j < mesh.positions.size(); ++j) {
            if (mesh.positions[i] != mesh.positions[j] || mesh.positions[i].x != 1.0f) continue;
            const double a = mesh.colors[i].x * mesh.texelScale[i].x, b = mesh.colors[j].x * mesh.texelScale[j].x;
            EXPECT_GT(a, 0.0);
            EXPECT_NEAR(a, b, 1e-5 * a) << "seam vertex at y = " << mesh.positions[i].y;
            EXPECT_GT(std::abs(mesh.colors[i].x - mesh.colors[j].x), 0.2 * mesh.colors[i].x);  // white and grey
            ++seams;
        }
    EXPECT_GE(seams, 2);
}

// A textured primitive without texture coordinates: its texture counts as
// its mean, with a note.
TEST(Texture, NoCoordinatesMeansTheMean) {
    test::TempDir dir;
    GltfBuilder g = texturedRectangle();
    g.meshes.clear();
    g.addMesh("T", g.addPositions({{0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, 0}}), g.addIndices({0, 1, 2, 0, 2, 3}), 0);
    ImportNotes notes;
    const Scene s = loadGltf(g.writeEmbedded(dir).string(), &notes);
    const Material& m = s.materials[s.polygons[0].material];
    EXPECT_LT(m.texture, 0);
    EXPECT_NEAR(m.reflectance.x, 0.4, 1e-12);
    bool noted = false;
    for (const std::string& n : notes.lines) noted = noted || n.find("TEXCOORD_0") != std::string::npos;
    EXPECT_TRUE(noted);
}

}  // namespace
}  // namespace rad
