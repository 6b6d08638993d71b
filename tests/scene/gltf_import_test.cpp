#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"
#include "scene/Placement.h"
#include "support/Cli.h"
#include "support/GltfBuilder.h"
#include "support/Motion.h"
#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

namespace fs = std::filesystem;
using test::TempDir;
using test::GltfBuilder;
using test::writeFile;
using test::base64;

// A 2 x 3 rectangle in the z = 0 plane, facing +Z, as two triangles sharing
// the diagonal 0-2.
const std::vector<glm::vec3> kRect = {{0, 0, 0}, {2, 0, 0}, {2, 3, 0}, {0, 3, 0}};
const std::vector<std::uint32_t> kRectIndices = {0, 1, 2, 0, 2, 3};

std::string noteWith(const ImportNotes& notes, const std::string& word);

int addRectMesh(GltfBuilder& g, const std::string& name, int material) {
    return g.addMesh(name, g.addPositions(kRect), g.addIndices(kRectIndices), material);
}

// Unit cube centred at the origin, 24 vertices, outward counter-clockwise faces.
void cubeGeometry(std::vector<glm::vec3>& pos, std::vector<std::uint32_t>& idx) {
    for (int axis = 0; axis < 3; ++axis) {
        for (int sign : {1, -1}) {
            glm::vec3 n(0.0f), u(0.0f), v(0.0f);
            n[axis] = static_cast<float>(sign);
            u[(axis + 1) % 3] = 1.0f;
            v[(axis + 2) % 3] = 1.0f;
            if (sign < 0) std::swap(u, v);  // keeps cross(u, v) == n
            const auto base = static_cast<std::uint32_t>(pos.size());
            for (auto [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
                pos.push_back(0.5f * (n + static_cast<float>(a) * u + static_cast<float>(b) * v));
            for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) idx.push_back(base + k);
        }
    }
}

// The unit cube of cubeGeometry as a mesh of one material; returns the mesh.
int addCubeMesh(GltfBuilder& g, int material) {
    std::vector<glm::vec3> pos;
    std::vector<std::uint32_t> idx;
    cubeGeometry(pos, idx);
    return g.addMesh("Cube", g.addPositions(pos), g.addIndices(idx), material);
}

std::string path(const fs::path& p) { return p.string(); }

// Runs loadGltf expecting a SceneError; returns its message.
std::string importError(const fs::path& file) {
    try {
        loadGltf(file.string());
    } catch (const SceneError& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
        return {};
    }
    ADD_FAILURE() << "no SceneError for " << file;
    return {};
}

// The one-line "<path>: <item>: <problem>" shape, naming the file and the item.
void expectOneLineError(const std::string& message, const fs::path& file, const std::string& item) {
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.find('\r'), std::string::npos) << message;
    EXPECT_EQ(message.rfind(file.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(item), std::string::npos) << "missing '" << item << "' in: " << message;
}

bool hasVertex(const Scene& s, const glm::dvec3& p, double tol = 1e-9) {
    for (const Polygon& poly : s.polygons)
        for (int i = 0; i < poly.vertexCount; ++i)
            if (glm::length(poly.vertices[i] - p) < tol) return true;
    return false;
}

// ---------------------------------------------------------------------------

TEST(GltfImport, QuadAsTwoTrianglesMergesToOneQuad) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Floor", g.addGrey("Grey"));
    g.addNode("\"name\":\"Floor\",\"mesh\":0");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    ASSERT_EQ(s.polygons.size(), 1u);
    const Polygon& p = s.polygons[0];
    EXPECT_EQ(p.vertexCount, 4);
    EXPECT_NEAR(p.area(), 6.0, 1e-12);
    EXPECT_NEAR(glm::length(p.normal() - glm::dvec3(0, 0, 1)), 0.0, 1e-12);
    for (const glm::vec3& v : kRect) EXPECT_TRUE(hasVertex(s, glm::dvec3(v)));
    EXPECT_EQ(notes.mergedQuads, 1u);
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].name, "Floor");
    EXPECT_EQ(s.objects[0].firstPolygon, 0u);
    EXPECT_EQ(s.objects[0].polygonCount, 1u);
    EXPECT_EQ(s.sourcePath, path(dir / "scene.gltf"));
}

// A wall as a CAD tool triangulates it: 21 points along its bottom edge, 8
// along its top, joined by long slivers. It imports as the one quad it is,
// and lit by a panel in front of it, its solution is the one-quad wall's:
// no streaks along slivers.
TEST(GltfImport, ASliverTriangulatedWallImportsAsTheWall) {
    TempDir dir;
    const auto scene = [&](bool slivers) {
        GltfBuilder g;
        const int grey = g.addGrey("Grey", 0.6);
        std::vector<glm::vec3> p;
        std::vector<std::uint32_t> idx;
        if (slivers) {
            const int nb = 21, nt = 8;
            for (int i = 0; i < nb; ++i) p.push_back({4.0f * float(i) / float(nb - 1), 0.0f, 0.0f});
            for (int j = 0; j < nt; ++j) p.push_back({4.0f * float(j) / float(nt - 1), 2.5f, 0.0f});
            // Advance along whichever edge's next point comes first in x.
            for (int i = 0, j = 0; i < nb - 1 || j < nt - 1;) {
                const bool bottom = j == nt - 1 || (i < nb - 1 && p[std::size_t(i + 1)].x <= p[std::size_t(nb + j + 1)].x);
                if (bottom) {
                    idx.insert(idx.end(), {std::uint32_t(i), std::uint32_t(i + 1), std::uint32_t(nb + j)});
                    ++i;
                } else {
                    idx.insert(idx.end(), {std::uint32_t(i), std::uint32_t(nb + j + 1), std::uint32_t(nb + j)});
                    ++j;
                }
            }
        } else {
            p = {{0, 0, 0}, {4, 0, 0}, {4, 2.5f, 0}, {0, 2.5f, 0}};
            idx = {0, 1, 2, 0, 2, 3};
        }
        g.addNode("\"name\":\"Wall\",\"mesh\":" + std::to_string(g.addMesh("Wall", g.addPositions(p), g.addIndices(idx), grey)));
        // A panel 1 m in front, facing the wall.
        const int lamp = g.addMaterial("{\"name\":\"Lamp\",\"emissiveFactor\":[1,1,1]}");
        const std::vector<glm::vec3> q = {{1.5f, 1.0f, 1.0f}, {1.5f, 1.5f, 1.0f}, {2.5f, 1.5f, 1.0f}, {2.5f, 1.0f, 1.0f}};
        g.addNode("\"name\":\"Lamp\",\"mesh\":" + std::to_string(g.addMesh("Lamp", g.addPositions(q), g.addIndices({0, 1, 2, 0, 2, 3}), lamp)));
        ImportNotes notes;
        Scene s = loadGltf(path(g.writeEmbedded(dir, slivers ? "slivers.gltf" : "quad.gltf")), &notes);
        if (slivers) {
            EXPECT_EQ(notes.mergedRegionTriangles, 27u);
        }
        return s;
    };
    const Scene slivers = scene(true), quad = scene(false);
    ASSERT_EQ(slivers.objects[0].polygonCount, 1u);
    const Polygon& wall = slivers.polygons[slivers.objects[0].firstPolygon];
    EXPECT_EQ(wall.vertexCount, 4);
    EXPECT_NEAR(wall.area(), 10.0, 1e-5);
    EXPECT_NEAR(glm::length(wall.normal() - glm::dvec3(0, 0, 1)), 0.0, 1e-9);
    Engine a(slivers, EngineSettings{}), b(quad, EngineSettings{});
    a.solve();
    b.solve();
    EXPECT_LT(compareSamples(a.samples(), b.samples()).rms, 0.01);
}

// The luminance the display shows at (x, y) on a wall in the plane z = 0
// facing +z: the snapshot's colours interpolated over its triangle there.
double shownOnWall(const MeshSnapshot& m, double x, double y) {
    const auto cross = [](glm::dvec2 a, glm::dvec2 b) { return a.x * b.y - a.y * b.x; };
    const glm::dvec2 p(x, y);
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const std::array<std::uint32_t, 3> v = {m.indices[t], m.indices[t + 1], m.indices[t + 2]};
        if (std::abs(m.positions[v[0]].z) > 1e-4 || std::abs(m.positions[v[1]].z) > 1e-4 ||
            std::abs(m.positions[v[2]].z) > 1e-4)
            continue;
        const glm::dvec2 a(m.positions[v[0]]), b(m.positions[v[1]]), c(m.positions[v[2]]);
        const double d = cross(b - a, c - a);
        if (d <= 0.0) continue;  // facing -z, or degenerate
        const double wa = cross(b - p, c - p) / d, wb = cross(c - p, a - p) / d, wc = 1.0 - wa - wb;
        if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
        return wa * luminance(glm::dvec3(m.colors[v[0]])) + wb * luminance(glm::dvec3(m.colors[v[1]])) +
               wc * luminance(glm::dvec3(m.colors[v[2]]));
    }
    ADD_FAILURE() << "no triangle of the wall under (" << x << ", " << y << ")";
    return 0.0;
}

// A 12 x 2.5 m wall with a 1 x 1 m window, as a CAD tool triangulates it:
// eight triangles joining the window's corners to the wall's, two of them
// slivers 12 m long. It imports as four rectangles, and lit by a panel in
// front of it, the display shows across the wall the light of the same wall
// modelled as four other rectangles (strips beside, under and over the
// window): no streaks along the slivers.
TEST(GltfImport, AWallWithAWindowImportsAsRectangles) {
    TempDir dir;
    const auto solved = [&](bool slivers, const EngineSettings& settings) {
        GltfBuilder g;
        const int grey = g.addGrey("Grey", 0.6);
        std::vector<glm::vec3> p;
        std::vector<std::uint32_t> idx;
        if (slivers) {
            // The wall's corners A B C D, then the window's a b c d.
            p = {{0, 0, 0}, {12, 0, 0}, {12, 2.5f, 0}, {0, 2.5f, 0}, {5, 1, 0}, {6, 1, 0}, {6, 2, 0}, {5, 2, 0}};
            idx = {0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
        } else {
            for (const auto& [x0, y0, x1, y1] : std::vector<std::array<float, 4>>{
                     {0, 0, 5, 2.5f}, {6, 0, 12, 2.5f}, {5, 0, 6, 1}, {5, 2, 6, 2.5f}}) {
                const auto k = static_cast<std::uint32_t>(p.size());
                p.insert(p.end(), {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}});
                idx.insert(idx.end(), {k, k + 1, k + 2, k, k + 2, k + 3});
            }
        }
        g.addNode("\"name\":\"Wall\",\"mesh\":" + std::to_string(g.addMesh("Wall", g.addPositions(p), g.addIndices(idx), grey)));
        const int lamp = g.addMaterial("{\"name\":\"Lamp\",\"emissiveFactor\":[1,1,1]}");
        const std::vector<glm::vec3> q = {{3.0f, 0.5f, 1.0f}, {3.0f, 1.5f, 1.0f}, {4.0f, 1.5f, 1.0f}, {4.0f, 0.5f, 1.0f}};
        g.addNode("\"name\":\"Lamp\",\"mesh\":" + std::to_string(g.addMesh("Lamp", g.addPositions(q), g.addIndices({0, 1, 2, 0, 2, 3}), lamp)));
        ImportNotes notes;
        const Scene s = loadGltf(path(g.writeEmbedded(dir, slivers ? "slivers.gltf" : "strips.gltf")), &notes);
        if (slivers) {
            EXPECT_EQ(notes.mergedRegionTriangles, 8u);
            EXPECT_EQ(s.objects[0].polygonCount, 4u);
            double area = 0.0;
            for (std::uint32_t i = 0; i < s.objects[0].polygonCount; ++i) {
                const Polygon& wall = s.polygons[s.objects[0].firstPolygon + i];
                EXPECT_EQ(wall.vertexCount, 4);
                EXPECT_NEAR(glm::length(wall.normal() - glm::dvec3(0, 0, 1)), 0.0, 1e-9);
                for (int k = 0; k < 4; ++k)
                    EXPECT_NEAR(glm::dot(wall.vertices[(k + 1) % 4] - wall.vertices[k],
                                         wall.vertices[(k + 2) % 4] - wall.vertices[(k + 1) % 4]),
                                0.0, 1e-6);
                area += wall.area();
            }
            EXPECT_NEAR(area, 29.0, 1e-5);
        }
        Engine e(s, settings);
        EXPECT_TRUE(e.solve().converged);
        return compactMesh(e.snapshot());
    };
    const MeshSnapshot rectangles = solved(true, EngineSettings{}), strips = solved(false, EngineSettings{});
    EngineSettings fine;
    fine.epsilon /= 16.0;
    const MeshSnapshot reference = solved(false, fine);
    // Relative to the reference's mean over the points: rms and worst.
    const auto error = [&](const MeshSnapshot& m) {
        double sum = 0.0, squares = 0.0, worst = 0.0;
        int n = 0;
        for (double x = 0.1; x < 12.0; x += 0.2)
            for (double y = 0.05; y < 2.5; y += 0.1) {
                if (x > 5.0 && x < 6.0 && y > 1.0 && y < 2.0) continue;  // the window
                const double shown = shownOnWall(m, x, y), expected = shownOnWall(reference, x, y);
                sum += expected;
                squares += (shown - expected) * (shown - expected);
                worst = std::max(worst, std::abs(shown - expected));
                ++n;
            }
        return std::pair(std::sqrt(squares / n) / (sum / n), worst / (sum / n));
    };
    const auto [rms, worst] = error(rectangles);
    const auto [stripsRms, stripsWorst] = error(strips);
    std::printf("  against epsilon / 16: rectangles rms %.4f worst %.4f, strips rms %.4f worst %.4f\n", rms, worst,
                stripsRms, stripsWorst);
    EXPECT_LT(rms, 1.5 * stripsRms);
    EXPECT_LT(worst, 1.5 * stripsWorst);
    RecordProperty("rms", std::to_string(rms));
}

TEST(GltfImport, SmallIndexTypesAndNonIndexedLoad) {
    TempDir dir;
    GltfBuilder g;
    const int grey = g.addGrey("Grey");
    g.addMesh("U8", g.addPositions(kRect), g.addIndices(kRectIndices, 5121), grey);
    g.addMesh("U16", g.addPositions(kRect), g.addIndices(kRectIndices, 5123), grey);
    std::vector<glm::vec3> soup;
    for (std::uint32_t i : kRectIndices) soup.push_back(kRect[i]);
    g.addMesh("Soup", g.addPositions(soup), -1, grey);
    // Apart, or the second and third would be dropped as repeats of the first.
    for (int m = 0; m < 3; ++m)
        g.addNode("\"name\":\"n" + std::to_string(m) + "\",\"mesh\":" + std::to_string(m) +
                  ",\"translation\":[0,0," + std::to_string(m) + "]");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    ASSERT_EQ(s.polygons.size(), 3u);
    for (const Polygon& p : s.polygons) {
        EXPECT_EQ(p.vertexCount, 4);
        EXPECT_NEAR(p.area(), 6.0, 1e-12);
    }
    EXPECT_EQ(notes.mergedQuads, 3u);
}

TEST(GltfImport, NonPlanarPairDoesNotMerge) {
    TempDir dir;
    GltfBuilder g;
    std::vector<glm::vec3> bent = kRect;
    bent[3].z = 0.5f;
    g.addMesh("Bent", g.addPositions(bent), g.addIndices(kRectIndices), g.addGrey("Grey"));
    g.addNode("\"name\":\"Bent\",\"mesh\":0");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    ASSERT_EQ(s.polygons.size(), 2u);
    EXPECT_EQ(s.polygons[0].vertexCount, 3);
    EXPECT_EQ(s.polygons[1].vertexCount, 3);
    EXPECT_EQ(notes.mergedQuads, 0u);
}

TEST(GltfImport, ConcavePairDoesNotMerge) {
    TempDir dir;
    GltfBuilder g;
    // A dart: the union of (A,B,C) and (A,C,D) has a reflex corner at C.
    const std::vector<glm::vec3> dart = {{0, 0, 0}, {2, 0, 0}, {0.5f, 0.5f, 0}, {0, 2, 0}};
    g.addMesh("Dart", g.addPositions(dart), g.addIndices(kRectIndices), g.addGrey("Grey"));
    g.addNode("\"name\":\"Dart\",\"mesh\":0");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    ASSERT_EQ(s.polygons.size(), 2u);
    EXPECT_EQ(notes.mergedQuads, 0u);
    EXPECT_NEAR(s.polygons[0].area() + s.polygons[1].area(), 1.0, 1e-6);
}

TEST(GltfImport, DifferentMaterialsDoNotMerge) {
    TempDir dir;
    GltfBuilder g;
    const int pos = g.addPositions(kRect);
    const int a = g.addGrey("A", 0.2);
    const int b = g.addGrey("B", 0.7);
    g.meshes.push_back(
        "{\"name\":\"Two\",\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
        "},\"indices\":" + std::to_string(g.addIndices({0, 1, 2})) + ",\"material\":" +
        std::to_string(a) + "},{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
        "},\"indices\":" + std::to_string(g.addIndices({0, 2, 3})) +
        ",\"material\":" + std::to_string(b) + "}]}");
    g.addNode("\"name\":\"Two\",\"mesh\":0");
    const Scene s = loadGltf(path(g.writeEmbedded(dir)));
    ASSERT_EQ(s.polygons.size(), 2u);
    EXPECT_NE(s.polygons[0].material, s.polygons[1].material);
    EXPECT_NEAR(s.materials[s.polygons[0].material].reflectance.x, 0.2, 1e-12);
    EXPECT_NEAR(s.materials[s.polygons[1].material].reflectance.x, 0.7, 1e-12);
}

TEST(GltfImport, ParentChildTranslationRotationScale) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    const double h = std::sqrt(0.5);
    // Child: scale 2, then 90 degrees about +Y, then up by 1; parent moves by +10 x.
    const int child = g.addNode(
        "\"name\":\"Child\",\"mesh\":0,\"translation\":[0,1,0],"
        "\"rotation\":[0," +
            std::to_string(h) + ",0," + std::to_string(h) + "],\"scale\":[2,2,2]",
        false);
    g.addNode("\"name\":\"Parent\",\"translation\":[10,0,0],\"children\":[" +
              std::to_string(child) + "]");
    // A matrix node (column-major): translate by (0, 0, 5).
    g.addNode("\"name\":\"Matrix\",\"mesh\":0,\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,5,1]");
    const Scene s = loadGltf(path(g.writeEmbedded(dir)));
    ASSERT_EQ(s.objects.size(), 2u);
    const auto childIndex = s.findObject("Child");
    ASSERT_TRUE(childIndex.has_value());
    EXPECT_FALSE(s.findObject("Parent").has_value()) << "a node without a mesh is no object";

    // Local (x, y, 0) -> scale (2x, 2y, 0) -> rotate about Y: x -> -z -> (0, 2y, -2x)
    // -> + (0, 1, 0) -> + (10, 0, 0).
    const Aabb box = s.objectBounds(*childIndex);
    EXPECT_NEAR(glm::length(box.lo - glm::dvec3(10, 1, -4)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(box.hi - glm::dvec3(10, 7, 0)), 0.0, 1e-6);
    EXPECT_TRUE(hasVertex(s, glm::dvec3(10, 1, -4), 1e-6));  // from local (2, 0, 0)
    const Polygon& p = s.polygons[s.objects[*childIndex].firstPolygon];
    EXPECT_NEAR(glm::length(p.normal() - glm::dvec3(1, 0, 0)), 0.0, 1e-6);
    EXPECT_NEAR(p.area(), 24.0, 1e-5);

    const glm::dmat4& m = s.objects[*childIndex].worldFromLocal;
    const glm::dvec3 mapped(m * glm::dvec4(2, 0, 0, 1));
    EXPECT_NEAR(glm::length(mapped - glm::dvec3(10, 1, -4)), 0.0, 1e-6);

    const auto matrixIndex = s.findObject("Matrix");
    ASSERT_TRUE(matrixIndex.has_value());
    const Aabb mbox = s.objectBounds(*matrixIndex);
    EXPECT_NEAR(glm::length(mbox.lo - glm::dvec3(0, 0, 5)), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(mbox.hi - glm::dvec3(2, 3, 5)), 0.0, 1e-12);
}

TEST(GltfImport, NegativeScaleKeepsNormalsOutward) {
    TempDir dir;
    GltfBuilder g;
    addCubeMesh(g, g.addGrey("Grey"));
    g.addNode("\"name\":\"Plain\",\"mesh\":0");
    g.addNode("\"name\":\"Mirrored\",\"mesh\":0,\"translation\":[5,0,0],\"scale\":[-1,2,1]");
    // A mirror split between parent and child cancels out; a mirror on the
    // parent alone does not.
    const int c1 = g.addNode("\"name\":\"C1\",\"mesh\":0,\"scale\":[1,1,-1]", false);
    g.addNode("\"name\":\"P1\",\"translation\":[0,5,0],\"scale\":[-1,1,1],\"children\":[" +
              std::to_string(c1) + "]");
    const int c2 = g.addNode("\"name\":\"C2\",\"mesh\":0", false);
    g.addNode("\"name\":\"P2\",\"translation\":[0,-5,0],\"scale\":[1,-1,1],\"children\":[" +
              std::to_string(c2) + "]");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    ASSERT_EQ(s.objects.size(), 4u);
    EXPECT_EQ(notes.mergedQuads, 24u);
    for (std::uint32_t o = 0; o < s.objects.size(); ++o) {
        const Object& obj = s.objects[o];
        const glm::dvec3 centre = s.objectBounds(o).center();
        ASSERT_EQ(obj.polygonCount, 6u) << obj.name;
        for (std::uint32_t i = obj.firstPolygon; i < obj.firstPolygon + obj.polygonCount; ++i) {
            const Polygon& p = s.polygons[i];
            EXPECT_EQ(p.object, o);
            EXPECT_GT(glm::dot(p.normal(), p.centroid() - centre), 0.0)
                << obj.name << " polygon " << i << " faces inward";
        }
    }
}

TEST(GltfImport, MaterialsFactorsEmissiveStrengthAndDefault) {
    TempDir dir;
    GltfBuilder g;
    g.extraTopLevel = "\"extensionsUsed\":[\"KHR_materials_emissive_strength\"],";
    const int red = g.addMaterial(
        "{\"name\":\"Red\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.1,0.2,1]}}");
    const int lamp = g.addMaterial(
        "{\"name\":\"Lamp\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.1,0.1,0.1,1]},"
        "\"emissiveFactor\":[1,0.5,0.25],"
        "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":4}}}");
    const int glow = g.addMaterial(
        "{\"name\":\"Glow\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},"
        "\"emissiveFactor\":[0.5,0.5,0.5]}");
    const int pos = g.addPositions(kRect);
    const int idx = g.addIndices(kRectIndices);
    g.addMesh("R", pos, idx, red);
    g.addMesh("L", pos, idx, lamp);
    g.addMesh("G", pos, idx, glow);
    g.addMesh("D", pos, idx, -1);
    // Apart, or all but the first would be dropped as repeats.
    for (int m = 0; m < 4; ++m)
        g.addNode("\"mesh\":" + std::to_string(m) + ",\"translation\":[0,0," + std::to_string(m) + "]");
    const Scene s = loadGltf(path(g.writeEmbedded(dir)));
    ASSERT_EQ(s.polygons.size(), 4u);
    const auto materialOf = [&](std::size_t polygon) {
        return s.materials[s.polygons[polygon].material];
    };
    EXPECT_EQ(materialOf(0).name, "Red");
    EXPECT_NEAR(glm::length(materialOf(0).reflectance - glm::dvec3(0.8, 0.1, 0.2)), 0.0, 1e-12);
    EXPECT_EQ(materialOf(0).emission, glm::dvec3(0.0));
    EXPECT_EQ(materialOf(1).name, "Lamp");
    EXPECT_NEAR(glm::length(materialOf(1).emission - glm::dvec3(4, 2, 1)), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(materialOf(2).emission - glm::dvec3(0.5)), 0.0, 1e-12);
    EXPECT_EQ(materialOf(3).name, "default");
    EXPECT_EQ(materialOf(3).reflectance, glm::dvec3(0.5));
    EXPECT_EQ(materialOf(3).emission, glm::dvec3(0.0));
    EXPECT_TRUE(s.hasEmitter());
    // Unnamed mesh nodes are named after their index.
    EXPECT_EQ(s.objects[0].name, "node0");
    EXPECT_EQ(s.objects[3].name, "node3");
}

double srgbDecode(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

TEST(GltfImport, BaseColorTextureMeanIsTakenInLinearSpace) {
    TempDir dir;
    GltfBuilder g;
    const std::string png = test::makePng(2, 1, {{255, 128, 0}, {0, 128, 64}});
    g.images.push_back("{\"uri\":\"data:image/png;base64," + base64(png) + "\"}");
    g.textures.push_back("{\"source\":0}");
    const int mat = g.addMaterial(
        "{\"name\":\"Tex\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.8,0.5,0.9,1],"
        "\"baseColorTexture\":{\"index\":0}}}");
    addRectMesh(g, "T", mat);
    g.addNode("\"name\":\"T\",\"mesh\":0");
    const Scene s = loadGltf(path(g.writeEmbedded(dir)));
    ASSERT_EQ(s.polygons.size(), 1u);
    const glm::dvec3 rho = s.materials[s.polygons[0].material].reflectance;
    // Decode each texel, then average: 255 and 0 average to 0.5, not to decode(0.5).
    EXPECT_NEAR(rho.x, 0.8 * 0.5, 1e-9);
    EXPECT_NEAR(rho.y, 0.5 * srgbDecode(128.0 / 255.0), 1e-9);
    EXPECT_NEAR(rho.z, 0.9 * 0.5 * srgbDecode(64.0 / 255.0), 1e-9);
}

TEST(GltfImport, ExtrasDynamicFlag) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    // Apart, or the last two would be dropped as repeats of the first.
    g.addNode("\"name\":\"Mover\",\"mesh\":0,\"extras\":{\"dynamic\":true}");
    g.addNode("\"name\":\"Still\",\"mesh\":0,\"translation\":[0,0,1],\"extras\":{\"dynamic\":false}");
    g.addNode("\"name\":\"Plain\",\"mesh\":0,\"translation\":[0,0,2],\"extras\":{\"other\":1}");
    // Blender writes a custom property set to True as 1 (its properties have
    // no boolean type); a string is no flag, and says so.
    g.addNode(
        "\"name\":\"FromBlender\",\"mesh\":0,\"translation\":[0,0,3],\"extras\":{\"dynamic\":1}");
    g.addNode(
        "\"name\":\"Real\",\"mesh\":0,\"translation\":[0,0,4],\"extras\":{\"dynamic\":0.0,"
        "\"object\":1.0}");
    g.addNode(
        "\"name\":\"Worded\",\"mesh\":0,\"translation\":[0,0,5],\"extras\":{\"dynamic\":\"yes\"}");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    ASSERT_EQ(s.objects.size(), 6u);
    EXPECT_TRUE(s.objects[*s.findObject("Mover")].dynamic);
    EXPECT_FALSE(s.objects[*s.findObject("Still")].dynamic);
    EXPECT_FALSE(s.objects[*s.findObject("Plain")].dynamic);
    EXPECT_TRUE(s.objects[*s.findObject("FromBlender")].dynamic);
    EXPECT_FALSE(s.objects[*s.findObject("Real")].dynamic);
    EXPECT_FALSE(s.objects[*s.findObject("Worded")].dynamic);
    bool worded = false;
    for (const std::string& line : notes.lines)
        worded = worded || (line.find("Worded") != std::string::npos &&
                            line.find("extras.dynamic") != std::string::npos);
    EXPECT_TRUE(worded) << "a string flag is noted";
}

TEST(GltfImport, RepeatedNamesGetSuffixes) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    // Apart, or the last two would be dropped as repeats of the first.
    for (int i = 0; i < 3; ++i)
        g.addNode("\"name\":\"Box\",\"mesh\":0,\"translation\":[0,0," + std::to_string(i) + "]");
    const Scene s = loadGltf(path(g.writeEmbedded(dir)));
    ASSERT_EQ(s.objects.size(), 3u);
    EXPECT_EQ(s.objects[0].name, "Box");
    EXPECT_EQ(s.objects[1].name, "Box#2");
    EXPECT_EQ(s.objects[2].name, "Box#3");
    for (std::uint32_t o = 0; o < 3; ++o) {
        EXPECT_EQ(s.objects[o].firstPolygon, o);
        EXPECT_EQ(s.polygons[o].object, o);
    }
}

TEST(GltfImport, FirstPerspectiveCameraIsParsed) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    g.cameras.push_back(
        "{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.8,\"aspectRatio\":1.5,\"znear\":0."
        "05}}");
    g.cameras.push_back("{\"type\":\"perspective\",\"perspective\":{\"yfov\":0.3,\"znear\":1}}");
    const double h = std::sqrt(0.5);
    const int eye = g.addNode("\"name\":\"Eye\",\"camera\":0,\"rotation\":[0," + std::to_string(h) +
                                  ",0," + std::to_string(h) + "]",
                              false);
    g.addNode("\"name\":\"Rig\",\"translation\":[1,2,3],\"children\":[" + std::to_string(eye) +
              "]");
    g.addNode("\"name\":\"Other\",\"camera\":1");
    g.addNode("\"name\":\"Rect\",\"mesh\":0");
    const Scene s = loadGltf(path(g.writeEmbedded(dir)));
    ASSERT_TRUE(s.camera.has_value());
    const Camera& c = *s.camera;
    EXPECT_NEAR(glm::length(c.position - glm::dvec3(1, 2, 3)), 0.0, 1e-12);
    EXPECT_NEAR(glm::length(c.forward - glm::dvec3(-1, 0, 0)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(c.up - glm::dvec3(0, 1, 0)), 0.0, 1e-6);
    EXPECT_NEAR(c.yfov, 0.8, 1e-12);
    ASSERT_TRUE(c.aspectRatio.has_value());
    EXPECT_NEAR(*c.aspectRatio, 1.5, 1e-12);
    EXPECT_NEAR(c.znear, 0.05, 1e-12);
}

TEST(GltfImport, NoCameraLeavesItEmpty) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    g.addNode("\"name\":\"Rect\",\"mesh\":0");
    EXPECT_FALSE(loadGltf(path(g.writeEmbedded(dir))).camera.has_value());
}

TEST(GltfImport, GlbAndExternalBufferLoadTheSameScene) {
    TempDir dir;
    GltfBuilder g;
    std::vector<glm::vec3> pos;
    std::vector<std::uint32_t> idx;
    cubeGeometry(pos, idx);
    g.addMesh("Cube", g.addPositions(pos), g.addIndices(idx, 5123), g.addGrey("Grey"));
    addRectMesh(g, "Rect", g.addGrey("Dark", 0.1));
    g.addNode("\"name\":\"Cube\",\"mesh\":0,\"translation\":[1,2,3],\"extras\":{\"dynamic\":true}");
    g.addNode("\"name\":\"Rect\",\"mesh\":1,\"scale\":[1,1,2]");
    const Scene a = loadGltf(path(g.writeEmbedded(dir)));
    const Scene b = loadGltf(path(g.writeGlb(dir)));
    const Scene c = loadGltf(path(g.writeExternal(dir)));
    ASSERT_EQ(a.polygons.size(), 7u);
    for (const Scene* other : {&b, &c}) {
        ASSERT_EQ(other->polygons.size(), a.polygons.size());
        ASSERT_EQ(other->objects.size(), a.objects.size());
        ASSERT_EQ(other->materials.size(), a.materials.size());
        for (std::size_t i = 0; i < a.polygons.size(); ++i) {
            EXPECT_EQ(other->polygons[i].vertices, a.polygons[i].vertices);
            EXPECT_EQ(other->polygons[i].vertexCount, a.polygons[i].vertexCount);
            EXPECT_EQ(other->polygons[i].material, a.polygons[i].material);
        }
        for (std::size_t o = 0; o < a.objects.size(); ++o) {
            EXPECT_EQ(other->objects[o].name, a.objects[o].name);
            EXPECT_EQ(other->objects[o].dynamic, a.objects[o].dynamic);
        }
        for (std::size_t m = 0; m < a.materials.size(); ++m)
            EXPECT_EQ(other->materials[m].reflectance, a.materials[m].reflectance);
    }
    EXPECT_TRUE(a.objects[0].dynamic);
}

TEST(GltfImport, DegenerateTrianglesAreDroppedAndCounted) {
    TempDir dir;
    GltfBuilder g;
    std::vector<glm::vec3> pos = kRect;
    pos.push_back({1, 1, 0});
    pos.push_back({1, 1, 0});  // a repeated vertex: zero area
    pos.push_back({3, 3, 0});  // collinear with (1,1) and (2,2)... with (0,0): zero area
    const std::vector<std::uint32_t> idx = {0, 1, 2, 0, 2, 3, 4, 5, 1, 0, 4, 6};
    g.addMesh("M", g.addPositions(pos), g.addIndices(idx), g.addGrey("Grey"));
    g.addNode("\"name\":\"M\",\"mesh\":0");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    EXPECT_EQ(notes.degenerateTriangles, 2u);
    ASSERT_EQ(s.polygons.size(), 1u);
    EXPECT_EQ(s.polygons[0].vertexCount, 4);
    EXPECT_FALSE(notes.lines.empty());
}

TEST(GltfImport, UnsupportedThingsAreNotedNotFatal) {
    TempDir dir;
    GltfBuilder g;
    g.extraTopLevel = "\"extensionsUsed\":[\"KHR_materials_clearcoat\"],";
    const int mat = g.addMaterial(
        "{\"name\":\"Two\",\"doubleSided\":true,\"alphaMode\":\"BLEND\",\"pbrMetallicRoughness\":{"
        "\"baseColorFactor\":[0.5,0.5,0.5,0.2]}}");
    addRectMesh(g, "Rect", mat);
    // Vertex colours: one VEC3 float per vertex, as COLOR_0 allows.
    const int colours = g.addPositions({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}});
    const std::string attributes = "\"attributes\":{";
    g.meshes.back().insert(g.meshes.back().find(attributes) + attributes.size(),
                           "\"COLOR_0\":" + std::to_string(colours) + ",");
    g.cameras.push_back(
        "{\"type\":\"orthographic\",\"orthographic\":{\"xmag\":1,\"ymag\":1,\"zfar\":10,\"znear\":"
        "0.1}}");
    g.addNode("\"name\":\"Ortho\",\"camera\":0");
    g.addNode("\"name\":\"Rect\",\"mesh\":0");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    EXPECT_EQ(s.polygons.size(), 2u);  // the doubleSided rectangle and its back face
    EXPECT_FALSE(s.camera.has_value());
    const auto noted = [&](const std::string& word) {
        for (const std::string& line : notes.lines)
            if (line.find(word) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(noted("KHR_materials_clearcoat"));
    EXPECT_TRUE(noted("alphaMode BLEND (base colour alpha 0.2) read as opaque"));
    EXPECT_TRUE(noted("COLOR_0 (vertex colours) ignored"));
    EXPECT_TRUE(noted("doubleSided"));
    EXPECT_TRUE(noted("orthographic"));
}

// A doubleSided panel between two lights, one on each side: both faces are
// polygons, each lit by the light it faces, alike (the set-up is symmetric),
// and each as an emitter facing it over that distance lights it. The same
// panel one-sided has one face, lit from its front only.
TEST(GltfImport, DoubleSidedPanelIsLitOnBothSides) {
    for (bool doubleSided : {true, false}) {
        TempDir dir;
        GltfBuilder g;
        const int panel = g.addMaterial(std::string("{\"name\":\"Panel\",\"doubleSided\":") +
                                        (doubleSided ? "true" : "false") +
                                        ",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1]}}");
        const int light = g.addMaterial(
            "{\"name\":\"Light\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},\"emissiveFactor\":[1,1,1]}");
        addRectMesh(g, "Panel", panel);  // z = 0, facing +z
        addRectMesh(g, "Lamp", light);
        g.addNode("\"name\":\"Panel\",\"mesh\":0");
        g.addNode("\"name\":\"Below\",\"mesh\":1,\"translation\":[0,0,-1]");  // facing +z, up at the panel
        g.addNode("\"name\":\"Above\",\"mesh\":1,\"translation\":[0,3,1],\"rotation\":[1,0,0,0]");  // facing -z
        ImportNotes notes;
        const Scene scene = loadGltf(path(g.writeEmbedded(dir)), &notes);
        ASSERT_EQ(scene.objects[0].polygonCount, doubleSided ? 2u : 1u);
        Engine engine(scene, EngineSettings{});
        ASSERT_TRUE(engine.solve().converged);
        const MeshSnapshot mesh = compactMesh(engine.snapshot());
        double front = 0.0, back = 0.0;
        int frontCount = 0, backCount = 0;
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            if (std::abs(mesh.positions[v].z) > 1e-4f) continue;  // the lamps
            (mesh.normals[v].z > 0.0f ? front : back) += mesh.colors[v].x;
            ++(mesh.normals[v].z > 0.0f ? frontCount : backCount);
        }
        ASSERT_GT(frontCount, 0);
        front /= frontCount;
        // rho E F with F between 0.3 and 0.5 for a 2 x 3 m rectangle 1 m away.
        EXPECT_GT(front, 0.5 * 0.3);
        EXPECT_LT(front, 0.5 * 0.5);
        if (doubleSided) {
            ASSERT_GT(backCount, 0);
            EXPECT_NEAR(back / backCount, front, 0.02 * front);
        } else {
            EXPECT_EQ(backCount, 0);
        }
    }
}

// Modelling tools mark materials doubleSided by default, and most of their
// meshes are closed: a box's backs face its inside, where no light is, and
// stay one-sided (scene/ClosedBackFaces.h). An open panel keeps its back,
// and so does a closed housing with a bulb in it.
TEST(GltfImport, AClosedDoubleSidedMeshKeepsOneFaceWhereItsBacksFaceNoLight) {
    TempDir dir;
    GltfBuilder g;
    const int two = g.addMaterial(
        "{\"name\":\"Two\",\"doubleSided\":true,\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,"
        "0.5,0.5,1]}}");
    const int light = g.addMaterial(
        "{\"name\":\"Light\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0,0,0,1]},"
        "\"emissiveFactor\":[1,1,1]}");
    const int cube = addCubeMesh(g, two);  // unit cube about the origin, faces outward
    const int panel = addRectMesh(g, "Panel", two);
    const int lamp = addRectMesh(g, "Lamp", light);
    // Standing 1 cm above the floor panel: on it, its bottom would lie in
    // the plane of the panel's back and cut it (scene/Covered.h).
    g.addNode("\"name\":\"Box\",\"mesh\":" + std::to_string(cube) + ",\"translation\":[1,1,0.51]");
    g.addNode("\"name\":\"Floor\",\"mesh\":" + std::to_string(panel) +
              ",\"translation\":[-1,-1,0]");
    g.addNode("\"name\":\"Lamp\",\"mesh\":" + std::to_string(lamp) +
              ",\"translation\":[0,3,2],\"rotation\":[1,0,0,0]");
    g.addNode("\"name\":\"Housing\",\"mesh\":" + std::to_string(cube) +
              ",\"translation\":[5,5,1],\"scale\":[0.5,0.5,0.5]");
    g.addNode("\"name\":\"Bulb\",\"mesh\":" + std::to_string(lamp) +
              ",\"translation\":[4.95,4.93,1],\"scale\":[0.05,0.05,1]");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    EXPECT_EQ(s.objects[*s.findObject("Box")].polygonCount, 6u);
    EXPECT_EQ(s.objects[*s.findObject("Floor")].polygonCount, 2u);
    EXPECT_EQ(s.objects[*s.findObject("Housing")].polygonCount, 12u);
    EXPECT_NE(noteWith(notes, "left one-sided").find("'Box'"), std::string::npos);
    EXPECT_EQ(noteWith(notes, "left one-sided").find("Housing"), std::string::npos);
    // The housing is closed around the bulb: said, and only of it.
    const std::string enclosed = noteWith(notes, "is a closed mesh around");
    EXPECT_NE(enclosed.find("node 'Housing' is a closed mesh around the light of node 'Bulb'"), std::string::npos)
        << enclosed;
    EXPECT_EQ(enclosed.find("alphaMode"), std::string::npos);  // an opaque material
    int count = 0;
    for (const std::string& line : notes.lines) count += line.find("is a closed mesh around") != std::string::npos;
    EXPECT_EQ(count, 1);
}

// A bulb in a glass globe, as a tool exports it: alphaMode BLEND, read as
// opaque. None of the bulb's light leaves the globe, and the note says why
// (the solve's only other word was a back_faces warning blaming the globe's
// normals).
TEST(GltfImport, ALightInAClosedGlassGlobeIsNoted) {
    TempDir dir;
    GltfBuilder g;
    const int glass = g.addMaterial(
        R"({"name":"glass","alphaMode":"BLEND","pbrMetallicRoughness":{"baseColorFactor":[0.9,0.9,0.9,0.15]}})");
    const int cube = addCubeMesh(g, glass);
    g.addNode("\"name\":\"globe\",\"mesh\":" + std::to_string(cube) +
              ",\"translation\":[0,2,0],\"scale\":[0.3,0.3,0.3]");
    g.addNode(R"("name":"bulb","translation":[0,2,0],"extensions":{"KHR_lights_punctual":{"light":0}})");
    g.extraTopLevel = R"("extensionsUsed":["KHR_lights_punctual"],)"
                      R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":5}]}},)";
    ImportNotes notes;
    loadGltf(path(g.writeEmbedded(dir)), &notes);
    const std::string enclosed = noteWith(notes, "is a closed mesh around");
    EXPECT_NE(enclosed.find("node 'globe' is a closed mesh around light 'bulb'"), std::string::npos) << enclosed;
    EXPECT_NE(enclosed.find("alphaMode BLEND is read as opaque"), std::string::npos) << enclosed;
}

// A node marked extras.dynamic (or extras.object) is one object with its
// whole subtree: a chair of seat and back under one node is one object, and
// moves as one, within 1% of a full solve. Nodes outside it stay their own.
TEST(GltfImport, AMarkedNodeIsOneObjectWithItsSubtree) {
    TempDir dir;
    GltfBuilder g;
    const int cube = addCubeMesh(g, g.addGrey("Wood", 0.6));  // unit cube about the origin, faces outward
    const int floor = addRectMesh(g, "Floor", g.addGrey("Floor", 0.5));  // z = 0, facing +z
    const int lamp = addRectMesh(g, "Lamp", g.addMaterial("{\"name\":\"Light\",\"pbrMetallicRoughness\":"
                                                          "{\"baseColorFactor\":[0,0,0,1]},\"emissiveFactor\":[5,5,5]}"));
    const int seat = g.addNode("\"name\":\"Seat\",\"mesh\":" + std::to_string(cube) +
                                   ",\"translation\":[0,0,0.45],\"scale\":[0.5,0.5,0.1]",
                               false);
    const int back = g.addNode("\"name\":\"Back\",\"mesh\":" + std::to_string(cube) +
                                   ",\"translation\":[0,0.22,0.75],\"scale\":[0.5,0.06,0.5]",
                               false);
    g.addNode("\"name\":\"Chair\",\"translation\":[1,1,0],\"extras\":{\"dynamic\":true},\"children\":[" +
              std::to_string(seat) + "," + std::to_string(back) + "]");
    g.addNode("\"name\":\"Floor\",\"mesh\":" + std::to_string(floor));
    g.addNode("\"name\":\"Lamp\",\"mesh\":" + std::to_string(lamp) +
              ",\"translation\":[0.5,2.5,2],\"rotation\":[1,0,0,0],\"scale\":[0.5,0.33,1]");
    const Scene scene = loadGltf(path(g.writeEmbedded(dir)));
    ASSERT_EQ(scene.objects.size(), 3u);
    EXPECT_EQ(scene.objects[0].name, "Chair");
    EXPECT_TRUE(scene.objects[0].dynamic);
    EXPECT_EQ(scene.objects[0].polygonCount, 12u);  // two cubes of six quads
    EXPECT_EQ(scene.objects[1].name, "Floor");
    EXPECT_FALSE(scene.objects[1].dynamic);

    const EngineSettings settings;
    Engine engine(scene, settings);
    ASSERT_TRUE(engine.solve().converged);
    ASSERT_EQ(engine.dynamicObject(), 0u);
    const glm::dmat4 start = scene.objects[0].worldFromLocal;
    const RadiositySamples before = engine.samples();
    engine.moveDynamicObject(glm::translate(glm::dmat4(1.0), glm::dvec3(0.4, -0.2, 0.0)) * start);
    // Both parts moved: every polygon of the object, by the same offset.
    const Scene& moved = engine.scene();
    for (std::uint32_t p = 0; p < 12; ++p)
        EXPECT_NEAR(moved.polygons[p].vertices[0].x - scene.polygons[p].vertices[0].x, 0.4, 1e-9) << p;
    EXPECT_GT(compareSamples(engine.samples(), before).rms, 1e-3) << "the move changed the light";
    EXPECT_LT(test::compareWithFullSolve(engine, settings).rms, 0.01);
}

// --- Duplicate polygons (issue 11): dropped at import, counted and named. ---

// A note line that contains `word`, or "".
std::string noteWith(const ImportNotes& notes, const std::string& word) {
    for (const std::string& line : notes.lines)
        if (line.find(word) != std::string::npos) return line;
    return "";
}

TEST(GltfImportDuplicates, AnObjectRepeatedInPlaceByASecondNodeIsDropped) {
    TempDir dir;
    GltfBuilder g;
    addCubeMesh(g, g.addGrey("Grey"));
    g.addNode("\"name\":\"Box\",\"mesh\":0");
    g.addNode("\"name\":\"Box-copy\",\"mesh\":0");  // the same mesh, the same place
    // Off by 1e-12 m: rounding, within 1e-9 of the scene's size (about 1.7 m).
    g.addNode("\"name\":\"Box-rounded\",\"mesh\":0,\"translation\":[1e-12,0,0]");
    // Off by 1 micrometre: not a duplicate, but within the float rounding of
    // its place (scene/Pieces.h, positionTolerance), so every face lies in
    // the plane of one of Box's, as large and later: covered, cut away.
    g.addNode("\"name\":\"Box-apart\",\"mesh\":0,\"translation\":[1e-6,0,0]");

    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);

    EXPECT_EQ(notes.duplicatePolygons, 12u);
    ASSERT_EQ(notes.duplicates.size(), 2u);
    EXPECT_EQ(notes.duplicates[0].kept, "Box");
    EXPECT_EQ(notes.duplicates[0].dropped, "Box-copy");
    EXPECT_EQ(notes.duplicates[0].count, 6u);
    EXPECT_EQ(notes.duplicates[1].kept, "Box");
    EXPECT_EQ(notes.duplicates[1].dropped, "Box-rounded");
    EXPECT_EQ(notes.duplicates[1].count, 6u);
    // One summary line with the count; the emptied objects are not imported.
    EXPECT_NE(noteWith(notes, "12 duplicate polygon(s) dropped"), "");
    EXPECT_NE(noteWith(notes, "'Box-copy': every polygon repeats"), "");
    EXPECT_EQ(notes.coveredPolygons, 6u);
    EXPECT_NE(noteWith(notes, "'Box-apart': every polygon is covered"), "");
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].name, "Box");
    EXPECT_EQ(s.objects[0].polygonCount, 6u);
    ASSERT_EQ(s.polygons.size(), 6u);
    for (const Polygon& p : s.polygons) EXPECT_EQ(p.object, 0u);
}

TEST(GltfImportDuplicates, ARepeatStartingAtAnotherVertexIsADuplicate) {
    TempDir dir;
    GltfBuilder g;
    const int grey = g.addGrey("Grey");
    addRectMesh(g, "Rect", grey);
    // The same rectangle with its triangles listed from vertex 1: it merges
    // into the quad (1,2,3,0), the same cyclic order from another start.
    // With another rectangle beside it, which stays.
    std::vector<glm::vec3> pos = kRect;
    for (const glm::vec3& v : kRect) pos.push_back(v + glm::vec3(5, 0, 0));
    g.addMesh("Shifted", g.addPositions(pos), g.addIndices({1, 2, 3, 1, 3, 0, 4, 5, 6, 4, 6, 7}), grey);
    g.addNode("\"name\":\"Floor\",\"mesh\":0");
    g.addNode("\"name\":\"Patch\",\"mesh\":1");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    EXPECT_EQ(notes.duplicatePolygons, 1u);
    ASSERT_EQ(notes.duplicates.size(), 1u);
    EXPECT_EQ(notes.duplicates[0].kept, "Floor");
    EXPECT_EQ(notes.duplicates[0].dropped, "Patch");
    ASSERT_EQ(s.objects.size(), 2u);  // Patch keeps its other rectangle
    EXPECT_EQ(s.objects[1].polygonCount, 1u);
    EXPECT_TRUE(hasVertex(s, glm::dvec3(7, 3, 0)));
}

TEST(GltfImportDuplicates, TheTwoFacesOfAZeroThicknessSlabAreKept) {
    TempDir dir;
    GltfBuilder g;
    const int grey = g.addGrey("Grey");
    addRectMesh(g, "Top", grey);
    // The same rectangle wound the other way: it faces -Z.
    g.addMesh("Bottom", g.addPositions(kRect), g.addIndices({0, 2, 1, 0, 3, 2}), grey);
    g.addNode("\"name\":\"Top\",\"mesh\":0");
    g.addNode("\"name\":\"Bottom\",\"mesh\":1");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    EXPECT_EQ(notes.duplicatePolygons, 0u);
    EXPECT_TRUE(notes.duplicates.empty());
    EXPECT_EQ(noteWith(notes, "duplicate"), "");
    ASSERT_EQ(s.polygons.size(), 2u);
    EXPECT_NEAR(glm::dot(s.polygons[0].normal(), s.polygons[1].normal()), -1.0, 1e-12);
}

TEST(GltfImportDuplicates, RepeatsWithinOneObjectAreFoundToo) {
    TempDir dir;
    GltfBuilder g;
    // Two triangles, the second listed twice (the third from a rotated start).
    const std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {3, 0, 0}, {4, 0, 0}, {3, 1, 0}};
    g.addMesh("Tris", g.addPositions(pos), g.addIndices({0, 1, 2, 3, 4, 5, 4, 5, 3}), g.addGrey("Grey"));
    g.addNode("\"name\":\"Tris\",\"mesh\":0");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    EXPECT_EQ(s.polygons.size(), 2u);
    ASSERT_EQ(notes.duplicates.size(), 1u);
    EXPECT_EQ(notes.duplicates[0].kept, "Tris");
    EXPECT_EQ(notes.duplicates[0].dropped, "Tris");
    EXPECT_EQ(notes.duplicates[0].count, 1u);
}

// 100k polygons, half of them a second node's copy: linear time (the grid
// hash), well under a second in Release.
TEST(GltfImportDuplicates, AHundredThousandPolygonsAreQuick) {
    TempDir dir;
    GltfBuilder g;
    constexpr int n = 224;  // 224^2 = 50,176 quads
    std::vector<glm::vec3> pos;
    std::vector<std::uint32_t> idx;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) pos.push_back({0.01f * float(i), 0.01f * float(j), 0.0f});
    const auto at = [](int i, int j) { return std::uint32_t(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (std::uint32_t k : {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)})
                idx.push_back(k);
    g.addMesh("Grid", g.addPositions(pos), g.addIndices(idx), g.addGrey("Grey"));
    g.addNode("\"name\":\"Grid\",\"mesh\":0");
    g.addNode("\"name\":\"Grid-again\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    const auto start = std::chrono::steady_clock::now();
    ImportNotes notes;
    const Scene s = loadGltf(path(file), &notes);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(s.polygons.size(), std::size_t(n) * n);
    EXPECT_EQ(notes.duplicatePolygons, std::size_t(n) * n);
    // The whole import; generous for sanitizer builds and a busy machine.
    EXPECT_LT(seconds, 20.0);
    std::printf("imported %zu polygons and dropped %zu duplicates in %.2f s\n", 2 * s.polygons.size(),
                notes.duplicatePolygons, seconds);
}

// The issue's test: furniture duplicated in place in a furnished room gives
// the room's answer. A second node shows the chair's mesh again.
TEST(GltfImportDuplicates, AFurnishedRoomWithADuplicatedChairSolvesLikeTheRoom) {
    const TempDir dir;
    const std::string room = test::sourcePath("scenes/furnished-room.gltf");
    nlohmann::json gltf = test::readJson(room);
    int chairMesh = -1;
    for (const nlohmann::json& node : gltf["nodes"])
        if (node.value("name", "") == "chair") chairMesh = node.at("mesh");
    ASSERT_GE(chairMesh, 0);
    gltf["nodes"].push_back({{"name", "chair-copy"}, {"mesh", chairMesh}});
    gltf["scenes"][0]["nodes"].push_back(gltf["nodes"].size() - 1);
    const std::string doubled = (dir / "doubled.gltf").string();
    { std::ofstream(doubled) << gltf.dump(); }

    const std::string plainReport = (dir / "plain.json").string(), doubledReport = (dir / "doubled.json").string();
    auto r = test::runCli("solve " + test::shellQuote(room) + " --report " + test::shellQuote(plainReport));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    r = test::runCli("solve " + test::shellQuote(doubled) + " --report " + test::shellQuote(doubledReport));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("warning: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("'chair-copy'"), std::string::npos) << r.output;

    const nlohmann::json plain = test::readJson(plainReport), twice = test::readJson(doubledReport);
    // The duplicate is named in the report's warnings, with the count.
    const nlohmann::json* warning = nullptr;
    for (const nlohmann::json& w : twice.at("warnings"))
        if (w.at("kind") == "duplicates") warning = &w;
    ASSERT_NE(warning, nullptr) << twice["warnings"].dump();
    EXPECT_EQ((*warning)["objects"], nlohmann::json({"chair", "chair-copy"}));
    // Every polygon of the copy went: the whole chair, as many polygons as
    // the chair imports as.
    const Scene plainScene = loadGltf(room);
    EXPECT_EQ((*warning)["amount"], double(plainScene.objects[*plainScene.findObject("chair")].polygonCount));
    EXPECT_EQ(twice.at("polygons"), plain.at("polygons"));

    // Energy as sound as without the copy, and every object within 2%.
    for (const nlohmann::json* report : {&plain, &twice}) {
        const nlohmann::json& e = report->at("energy");
        EXPECT_TRUE(e.at("created").is_number());
        EXPECT_LE(e["created"].get<double>(), 1e-3 * e.at("emitted").get<double>());
    }
    std::map<std::string, nlohmann::json> doubledObjects;
    for (const nlohmann::json& o : twice.at("objects")) doubledObjects[o.at("name")] = o.at("radiosity");
    EXPECT_EQ(doubledObjects.count("chair-copy"), 0u);
    for (const nlohmann::json& o : plain.at("objects")) {
        const std::string name = o.at("name");
        ASSERT_EQ(doubledObjects.count(name), 1u) << name;
        for (int c = 0; c < 3; ++c) {
            const double want = o["radiosity"][c], got = doubledObjects[name][c];
            EXPECT_NEAR(got, want, 0.02 * std::abs(want) + 1e-9) << name << " channel " << c;
        }
    }
}

// --- Errors: one line, "<path>: <item>: <problem>". ---

TEST(GltfImportErrors, MissingFile) {
    TempDir dir;
    const fs::path file = dir / "nope.gltf";
    expectOneLineError(importError(file), file, "file");
}

TEST(GltfImportErrors, MalformedJson) {
    TempDir dir;
    const fs::path file = dir / "broken.gltf";
    writeFile(file, "{\"asset\": {\"version\": \"2.0\"},\n \"nodes\": [ {\n");
    expectOneLineError(importError(file), file, "glTF");
}

TEST(GltfImportErrors, AccessorPastEndOfBuffer) {
    TempDir dir;
    GltfBuilder g;
    const int view = g.addView(std::string(36, '\0'));  // room for 3 positions only
    g.addAccessor("{\"bufferView\":" + std::to_string(view) +
                  ",\"componentType\":5126,\"type\":\"VEC3\",\"count\":6}");
    g.addMesh("Short", 0, -1, g.addGrey("Grey"));
    g.addNode("\"name\":\"Short\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    const std::string message = importError(file);
    expectOneLineError(message, file, "mesh 'Short' primitive 0 POSITION accessor 0");
}

TEST(GltfImportErrors, AccessorOffsetAndStridePastEnd) {
    TempDir dir;
    GltfBuilder g;
    g.bin = std::string(48, '\0');
    // A strided view of 48 bytes: 3 elements at stride 16 fit, 4 do not.
    g.bufferViews.push_back("{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48,\"byteStride\":16}");
    g.addAccessor(
        "{\"bufferView\":0,\"byteOffset\":4,\"componentType\":5126,\"type\":\"VEC3\",\"count\":3}");
    g.addMesh("Strided", 0, -1, g.addGrey("Grey"));
    g.addNode("\"name\":\"Strided\",\"mesh\":0");
    // 4 + 2*16 + 12 = 48 fits exactly (the triangle is degenerate, all zeros).
    expectOneLineError(importError(g.writeEmbedded(dir, "fits.gltf")), dir / "fits.gltf",
                       "contains no polygons");
    g.accessors[0] =
        "{\"bufferView\":0,\"byteOffset\":8,\"componentType\":5126,\"type\":\"VEC3\",\"count\":3}";
    const fs::path file = g.writeEmbedded(dir, "past.gltf");
    expectOneLineError(importError(file), file, "accessor 0");
}

TEST(GltfImportErrors, BufferViewPastEndOfBuffer) {
    TempDir dir;
    GltfBuilder g;
    g.bin = std::string(36, '\0');
    g.bufferViews.push_back("{\"buffer\":0,\"byteOffset\":12,\"byteLength\":36}");
    g.addAccessor("{\"bufferView\":0,\"componentType\":5126,\"type\":\"VEC3\",\"count\":3}");
    g.addMesh("View", 0, -1, g.addGrey("Grey"));
    g.addNode("\"name\":\"View\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    const std::string message = importError(file);
    expectOneLineError(message, file, "mesh 'View' primitive 0");
    EXPECT_NE(message.find("bufferView 0"), std::string::npos) << message;
}

TEST(GltfImportErrors, TruncatedExternalBuffer) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    g.addNode("\"name\":\"Rect\",\"mesh\":0");
    const fs::path file = g.writeExternal(dir);
    fs::resize_file(dir / "external.bin", g.bin.size() / 2);
    expectOneLineError(importError(file), file, "glTF");
}

TEST(GltfImportErrors, IndexOutOfRange) {
    TempDir dir;
    GltfBuilder g;
    g.addMesh("Bad", g.addPositions(kRect), g.addIndices({0, 1, 7}), g.addGrey("Grey"));
    g.addNode("\"name\":\"Bad\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    expectOneLineError(importError(file), file, "mesh 'Bad' primitive 0");
}

// Strips and fans are triangles written another way (glTF 2.0, 3.7.2.1): the
// rectangle as a strip and as a fan imports as the one quad, facing +Z.
TEST(GltfImport, StripsAndFansImportAsTheirTriangles) {
    TempDir dir;
    for (const auto& [mode, order] : {std::pair{5, std::vector<std::uint32_t>{0, 1, 3, 2}},
                                      std::pair{6, std::vector<std::uint32_t>{0, 1, 2, 3}}}) {
        GltfBuilder g;
        g.addMesh("Rect", g.addPositions(kRect), g.addIndices(order), g.addGrey("Grey"), mode);
        g.addNode("\"name\":\"Rect\",\"mesh\":0");
        const Scene s = loadGltf(path(g.writeEmbedded(dir, "mode" + std::to_string(mode) + ".gltf")));
        ASSERT_EQ(s.polygons.size(), 1u) << "mode " << mode;
        const Polygon& p = s.polygons[0];
        ASSERT_EQ(p.vertexCount, 4) << "mode " << mode;
        for (const glm::dvec3& corner : {glm::dvec3(0, 0, 0), glm::dvec3(2, 0, 0), glm::dvec3(2, 3, 0), glm::dvec3(0, 3, 0)})
            EXPECT_TRUE(hasVertex(s, corner)) << "mode " << mode;
        EXPECT_GT(glm::cross(p.vertices[1] - p.vertices[0], p.vertices[2] - p.vertices[0]).z, 0.0) << "mode " << mode;
    }
}

// Points and lines have no area (a CAD export's edges): skipped with a note,
// and the triangles beside them import.
TEST(GltfImport, PointsAndLinesAreSkippedWithANote) {
    TempDir dir;
    GltfBuilder g;
    const int grey = g.addGrey("Grey");
    g.addMesh("Edges", g.addPositions(kRect), g.addIndices({0, 1, 1, 2}), grey, 1);
    g.addMesh("Rect", g.addPositions(kRect), g.addIndices(kRectIndices), grey);
    g.addNode("\"name\":\"Edges\",\"mesh\":0");
    g.addNode("\"name\":\"Rect\",\"mesh\":1");
    ImportNotes notes;
    const Scene s = loadGltf(path(g.writeEmbedded(dir)), &notes);
    EXPECT_EQ(s.polygons.size(), 1u);
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].name, "Rect");
    EXPECT_NE(noteWith(notes, "LINES"), "") << "no note of the skipped lines";
}

TEST(GltfImportErrors, UnknownPrimitiveMode) {
    TempDir dir;
    GltfBuilder g;
    g.addMesh("Chair", g.addPositions(kRect), g.addIndices({0, 1, 2}), g.addGrey("Grey"), 7);
    g.addNode("\"name\":\"Chair\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    const std::string message = importError(file);
    expectOneLineError(message, file, "mesh 'Chair' primitive 0");
    EXPECT_NE(message.find("(7) is not supported"), std::string::npos) << message;
}

// A required extension changes what the data means (compressed buffers):
// a scene read without it would be wrong.
TEST(GltfImportErrors, UnsupportedRequiredExtension) {
    TempDir dir;
    GltfBuilder g;
    g.extraTopLevel =
        "\"extensionsUsed\":[\"KHR_draco_mesh_compression\"],\"extensionsRequired\":[\"KHR_draco_mesh_compression\"],";
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    g.addNode("\"name\":\"Rect\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    expectOneLineError(importError(file), file, "requires extension KHR_draco_mesh_compression");
}

TEST(GltfImportErrors, NanPosition) {
    TempDir dir;
    GltfBuilder g;
    std::vector<glm::vec3> pos = kRect;
    pos[2].y = std::numeric_limits<float>::quiet_NaN();
    g.addMesh("Nan", g.addPositions(pos), g.addIndices(kRectIndices), g.addGrey("Grey"));
    g.addNode("\"name\":\"Nan\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    const std::string message = importError(file);
    expectOneLineError(message, file, "mesh 'Nan' primitive 0");
    EXPECT_NE(message.find("NaN"), std::string::npos) << message;
}

TEST(GltfImportErrors, InfPosition) {
    TempDir dir;
    GltfBuilder g;
    std::vector<glm::vec3> pos = kRect;
    pos[0].x = std::numeric_limits<float>::infinity();
    g.addMesh("Inf", g.addPositions(pos), g.addIndices(kRectIndices), g.addGrey("Grey"));
    g.addNode("\"name\":\"Inf\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    expectOneLineError(importError(file), file, "mesh 'Inf' primitive 0");
}

TEST(GltfImportErrors, InfinityInJsonIsMalformed) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    // JSON has no infinity; a number that overflows a double is rejected by
    // the reader, as malformed glTF.
    g.addNode("\"name\":\"Far\",\"mesh\":0,\"translation\":[1e400,0,0]");
    const fs::path file = g.writeEmbedded(dir);
    const std::string message = importError(file);
    expectOneLineError(message, file, "glTF");
    EXPECT_NE(message.find("1e400"), std::string::npos) << message;
}

TEST(GltfImportErrors, TransformOverflowsAcrossParents) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    const int child =
        g.addNode("\"name\":\"Huge\",\"mesh\":0,\"scale\":[1e300,1e300,1e300]", false);
    g.addNode("\"name\":\"Big\",\"scale\":[1e300,1e300,1e300],\"children\":[" +
              std::to_string(child) + "]");
    const fs::path file = g.writeEmbedded(dir);
    expectOneLineError(importError(file), file, "node 'Huge'");
}

// A node matrix with a projective last row (here a zero corner) is not a
// transform of a rigid scene: named, not imported as a squashed mesh.
TEST(GltfImportErrors, NodeMatrixThatIsNotAffine) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    g.addNode("\"name\":\"Squashed\",\"mesh\":0,\"matrix\":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,0]");
    const fs::path file = g.writeEmbedded(dir);
    const std::string message = importError(file);
    expectOneLineError(message, file, "node 'Squashed'");
    EXPECT_NE(message.find("not affine"), std::string::npos) << message;
}

// "scene" naming a scene the file does not have: an error, not the first
// scene imported in its place.
TEST(GltfImportErrors, DefaultSceneThatDoesNotExist) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    g.addNode("\"name\":\"Rect\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    std::string text = test::readFile(file.string());
    const std::size_t at = text.find("\"scene\":0");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 9, "\"scene\":3");
    writeFile(file, text);
    const std::string message = importError(file);
    expectOneLineError(message, file, "scene");
    EXPECT_NE(message.find("scene 3 which does not exist"), std::string::npos) << message;
}

TEST(GltfImportErrors, InfiniteFactor) {
    TempDir dir;
    GltfBuilder g;
    const int mat = g.addMaterial(
        "{\"name\":\"Hot\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1]},"
        "\"emissiveFactor\":[1e300,0,0],"
        "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":1e300}}}");
    addRectMesh(g, "Rect", mat);
    g.addNode("\"name\":\"Rect\",\"mesh\":0");
    const fs::path file = g.writeEmbedded(dir);
    expectOneLineError(importError(file), file, "material 'Hot'");
}

TEST(GltfImportErrors, ReflectanceOutsideUnitInterval) {
    TempDir dir;
    for (const char* factor : {"[1.2,0.5,0.5,1]", "[0.5,-0.1,0.5,1]"}) {
        GltfBuilder g;
        const int mat =
            g.addMaterial("{\"name\":\"White\",\"pbrMetallicRoughness\":{\"baseColorFactor\":" +
                          std::string(factor) + "}}");
        addRectMesh(g, "Rect", mat);
        g.addNode("\"name\":\"Rect\",\"mesh\":0");
        const fs::path file = g.writeEmbedded(dir);
        const std::string message = importError(file);
        expectOneLineError(message, file, "material 'White'");
        EXPECT_NE(message.find("[0,1]"), std::string::npos) << message;
    }
}

// Modelling tools write white as 1, and glTF's default base colour (no
// pbrMetallicRoughness at all) is white: read as kMaxReflectance, noted.
TEST(GltfImport, BaseColourOneIsClampedWithANote) {
    TempDir dir;
    GltfBuilder g;
    const int white = g.addMaterial("{\"name\":\"Paper\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[1,0.5,0.25,1]}}");
    const int unset = g.addMaterial("{}");
    addRectMesh(g, "Sheet", white);
    addRectMesh(g, "Card", unset);
    g.addNode("\"name\":\"Sheet\",\"mesh\":0");
    g.addNode("\"name\":\"Card\",\"mesh\":1,\"translation\":[0,0,2]");
    const fs::path file = g.writeEmbedded(dir);
    ImportNotes notes;
    const Scene scene = loadGltf(file.string(), &notes);
    ASSERT_EQ(scene.materials.size(), 2u);
    EXPECT_EQ(scene.materials[0].reflectance, glm::dvec3(kMaxReflectance, 0.5, 0.25));
    EXPECT_EQ(scene.materials[1].reflectance, glm::dvec3(kMaxReflectance));
    ASSERT_EQ(notes.clampedReflectance.size(), 2u);
    EXPECT_EQ(notes.clampedReflectance[0].material, "Paper");
    EXPECT_EQ(notes.clampedReflectance[0].largest, 1.0);
}

// Below 0, or finite but brighter than any light (kMaxEmission): refused
// by its value, naming the material.
TEST(GltfImportErrors, EmissionBelowZeroOrAboveTheLargestAccepted) {
    TempDir dir;
    for (const auto& [strength, says] : {std::pair{"-2", "negative"}, std::pair{"2e12", "above the largest accepted, 1e+12"}}) {
        GltfBuilder g;
        const int mat = g.addMaterial(
            "{\"name\":\"Lamp\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1]},"
            "\"emissiveFactor\":[1,1,1],"
            "\"extensions\":{\"KHR_materials_emissive_strength\":{\"emissiveStrength\":" + std::string(strength) + "}}}");
        addRectMesh(g, "Rect", mat);
        g.addNode("\"name\":\"Rect\",\"mesh\":0");
        const fs::path file = g.writeEmbedded(dir);
        const std::string message = importError(file);
        expectOneLineError(message, file, "material 'Lamp'");
        EXPECT_NE(message.find(says), std::string::npos) << message;
    }
}

TEST(GltfImportErrors, EmptyScene) {
    TempDir dir;
    GltfBuilder g;
    g.addNode("\"name\":\"Nothing\"");
    const fs::path file = g.writeEmbedded(dir);
    expectOneLineError(importError(file), file, "contains no polygons");

    // Only degenerate triangles: nothing left either.
    GltfBuilder d;
    d.addMesh("Flat", d.addPositions({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}), -1, d.addGrey("Grey"));
    d.addNode("\"name\":\"Flat\",\"mesh\":0");
    const fs::path flat = d.writeEmbedded(dir, "flat.gltf");
    expectOneLineError(importError(flat), flat, "contains no polygons");
    EXPECT_NE(importError(flat).find("degenerate"), std::string::npos) << importError(flat);

}

// A node or a light misplaced far out (a translation of 1e30 typed for 1.0):
// beyond kMaxReach times the size of the scene's detail the rays and the
// plane tests lose the scene (a floor 1e10 m out made every polygon of
// `lamp-room` "repeat" the ceiling, a light 1e20 m out crashed Embree), so
// the import names it. One cube of five, or a light, 10 km out is kept.
TEST(GltfImport, ANodeOrLightFarOutOfTheSceneIsNamed) {
    TempDir dir;
    const auto scene = [&](double cubeX, double lightX, const std::string& name) {
        GltfBuilder g;
        const int cube = addCubeMesh(g, g.addGrey("Grey"));
        for (int i = 0; i < 4; ++i)
            g.addNode("\"name\":\"near-" + std::to_string(i) + "\",\"mesh\":" + std::to_string(cube) +
                      ",\"translation\":[" + std::to_string(2 * i) + ",0,0]");
        std::ostringstream far, light;
        far << "\"name\":\"far\",\"mesh\":" << cube << ",\"translation\":[" << cubeX << ",0,0]";
        g.addNode(far.str());
        light << R"("name":"bulb","translation":[)" << lightX << R"(,2,0],"extensions":{"KHR_lights_punctual":{"light":0}})";
        g.addNode(light.str());
        g.extraTopLevel = R"("extensionsUsed":["KHR_lights_punctual"],)"
                          R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":5}]}},)";
        return g.writeEmbedded(dir, name);
    };
    // The detail, the middle half of the vertices, is 5 m across at most
    // here (the near cubes span 7 m): its reach is at most 5e5 m, at least 1e5.
    ASSERT_EQ(kMaxReach, 1e5);
    EXPECT_EQ(loadGltf(path(scene(1e4, 1.0, "kept.gltf"))).objects.size(), 5u);
    EXPECT_EQ(loadGltf(path(scene(1.0, 1e4, "light-kept.gltf"))).lights.size(), 1u);
    for (double x : {1e7, 1e10, 1e30}) {
        const fs::path cube = scene(x, 1.0, "far-cube.gltf");
        const std::string message = importError(cube);
        expectOneLineError(message, cube, "node 'far'");
        EXPECT_NE(message.find("misplaced"), std::string::npos) << message;
        const fs::path bulb = scene(1.0, x, "far-light.gltf");
        expectOneLineError(importError(bulb), bulb, "light 'bulb'");
    }
}

// A scene that a parent node's translation places 1000 km out (a
// georeferenced site), its positions stored small: imported as at the
// origin, moved there (Scene::fileOrigin), and exported back where the file
// had it. Before, the plane tests allowed for float32 rounding where the
// polygons ended up (10 cm there): `lamp-room` so placed lost most of its
// bookcase, cut away as covered by polygons "in its plane" (129 polygons
// cut, 8.85 m^2). Positions stored that far out themselves are left where
// they are, with their rounding allowed for.
TEST(GltfImport, AScenePlacedFarOutByATranslationImportsAsAtTheOrigin) {
    TempDir dir;
    const auto scene = [&](const glm::dvec3& at, const std::string& name) {
        GltfBuilder g;
        const int grey = g.addGrey("Grey");
        const int wall = addRectMesh(g, "Wall", grey);  // 2 x 3 m in z = 0, facing +z
        const int poster = g.addMesh("Poster",
                                     g.addPositions({{0.5f, 1, 0.05f}, {1.5f, 1, 0.05f}, {1.5f, 2, 0.05f}, {0.5f, 2, 0.05f}}),
                                     g.addIndices(kRectIndices), grey);
        const int w = g.addNode("\"name\":\"wall\",\"mesh\":" + std::to_string(wall), false);
        const int p = g.addNode("\"name\":\"poster\",\"mesh\":" + std::to_string(poster), false);
        const int b = g.addNode(R"("name":"bulb","translation":[1,1.5,1],"extensions":{"KHR_lights_punctual":{"light":0}})", false);
        std::ostringstream site;
        site << std::setprecision(17) << R"("name":"site","translation":[)" << at.x << "," << at.y << "," << at.z
             << R"(],"children":[)" << w << "," << p << "," << b << "]";
        g.addNode(site.str());
        g.extraTopLevel = R"("extensionsUsed":["KHR_lights_punctual"],)"
                          R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"point","intensity":5}]}},)";
        return g.writeEmbedded(dir, name);
    };
    const Scene here = loadGltf(path(scene(glm::dvec3(0.0), "here.gltf")));
    EXPECT_EQ(here.fileOrigin, glm::dvec3(0.0));
    const glm::dvec3 at(1e6, 20.0, -7e5);
    const Scene far = loadGltf(path(scene(at, "far.gltf")));
    ASSERT_EQ(far.polygons.size(), here.polygons.size());
    EXPECT_EQ(here.polygons.size(), 2u);  // the wall whole, the poster 5 cm in front of it
    for (std::size_t i = 0; i < here.polygons.size(); ++i)
        for (int k = 0; k < here.polygons[i].vertexCount; ++k)
            EXPECT_NEAR(glm::length(far.polygons[i].vertices[k] + far.fileOrigin - at - here.polygons[i].vertices[k]),
                        0.0, 1e-9);
    ASSERT_EQ(far.lights.size(), 1u);
    EXPECT_NEAR(glm::length(far.lights[0].position + far.fileOrigin - at - here.lights[0].position), 0.0, 1e-9);
    EXPECT_LT(glm::length(far.polygons[0].vertices[0]), 10.0);  // near the origin
    // Moved back on export.
    const fs::path lit = dir / "far-lit.gltf";
    exportGltf(makePreviewSnapshot(far), lit.string());
    const Scene exported = loadGltf(path(lit));
    Aabb box;
    for (const Polygon& q : exported.polygons)
        for (int k = 0; k < q.vertexCount; ++k) box.extend(q.vertices[k] + exported.fileOrigin);
    EXPECT_NEAR(box.lo.x, at.x, 1e-6);
    EXPECT_NEAR(box.lo.z, at.z, 1e-6);
    EXPECT_NEAR(box.hi.y, at.y + 3.0, 1e-6);

    // lamp-room, every polygon as at the origin.
    {
        nlohmann::json file = nlohmann::json::parse(std::ifstream(test::sourcePath("scenes/lamp-room.gltf")));
        nlohmann::json& roots = file["scenes"][0]["nodes"];
        file["nodes"].push_back({{"name", "site"}, {"translation", {at.x, at.y, at.z}}, {"children", roots}});
        roots = nlohmann::json::array({file["nodes"].size() - 1});
        const fs::path placed = dir / "lamp-room-far.gltf";
        std::ofstream(placed) << file.dump();
        const Scene original = loadGltf(test::sourcePath("scenes/lamp-room.gltf"));
        const Scene moved = loadGltf(path(placed));
        ASSERT_EQ(moved.polygons.size(), original.polygons.size());
        for (std::size_t i = 0; i < original.polygons.size(); ++i)
            for (int k = 0; k < original.polygons[i].vertexCount; ++k)
                ASSERT_NEAR(glm::length(moved.polygons[i].vertices[k] + moved.fileOrigin - at -
                                        original.polygons[i].vertices[k]),
                            0.0, 1e-6)
                    << i;
    }

    // A wall stored 1000 km out in the buffer: its floats are rounded to
    // 6 cm steps there, which the plane tests must keep allowing for: not
    // moved.
    GltfBuilder baked;
    std::vector<glm::vec3> stored;
    for (const glm::vec3& v : kRect) stored.push_back(v + glm::vec3(1e6f, 0.0f, 0.0f));
    baked.addMesh("Wall", baked.addPositions(stored), baked.addIndices(kRectIndices), baked.addGrey("Grey"));
    baked.addNode("\"name\":\"wall\",\"mesh\":0");
    EXPECT_EQ(loadGltf(path(baked.writeEmbedded(dir, "baked.gltf"))).fileOrigin, glm::dvec3(0.0));
}

// Whether a triangle is degenerate is judged by its own size: an object 1e7 m
// from the others (a stray export) once made every ordinary triangle
// degenerate at the scene's size, and the import failed. Both rectangles
// are kept, and a needle (area 1e-13 of its longest edge squared) is not.
TEST(GltfImport, DegenerateIsJudgedByTheTrianglesOwnSize) {
    TempDir dir;
    GltfBuilder far;
    addRectMesh(far, "Rect", far.addGrey("Grey"));
    far.addNode("\"name\":\"Here\",\"mesh\":0");
    far.addNode("\"name\":\"Stray\",\"mesh\":0,\"translation\":[1e7,0,0]");
    ImportNotes notes;
    const Scene stray = loadGltf(path(far.writeEmbedded(dir, "stray.gltf")), &notes);
    EXPECT_EQ(stray.polygons.size(), 2u);
    EXPECT_EQ(notes.degenerateTriangles, 0u);

    GltfBuilder needle;
    std::vector<glm::vec3> pos = kRect;
    pos.push_back({10, 0, 0});
    pos.push_back({20, 1e-12f, 0});  // with (0,0,0): a needle 20 m long, 1e-12 m wide
    needle.addMesh("M", needle.addPositions(pos), needle.addIndices({0, 1, 2, 0, 2, 3, 0, 4, 5}), needle.addGrey("Grey"));
    needle.addNode("\"name\":\"M\",\"mesh\":0");
    ImportNotes needleNotes;
    const Scene s = loadGltf(path(needle.writeEmbedded(dir, "needle.gltf")), &needleNotes);
    EXPECT_EQ(needleNotes.degenerateTriangles, 1u);
    EXPECT_EQ(s.polygons.size(), 1u);
}

TEST(GltfImportErrors, UnknownExtension) {
    TempDir dir;
    const fs::path file = dir / "scene.obj";
    writeFile(file, "v 0 0 0\n");
    expectOneLineError(importError(file), file, "file");
}

TEST(GltfImport, NoEmitterIsNotAnImportError) {
    TempDir dir;
    GltfBuilder g;
    addRectMesh(g, "Rect", g.addGrey("Grey"));
    g.addNode("\"name\":\"Rect\",\"mesh\":0");
    const Scene s = loadGltf(path(g.writeEmbedded(dir)));
    EXPECT_FALSE(s.hasEmitter());
}

}  // namespace
}  // namespace rad
