#pragma once
// A small glTF writer for tests: JSON text plus one binary buffer, written
// embedded, as .glb or with an external .bin, the way a modelling tool
// writes a file (tests of import features build their scenes with it).

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "support/TempDir.h"
#include "support/TestScenes.h"

namespace rad::test {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------
// Helpers: a small glTF writer (JSON text plus one binary buffer, written
// embedded, as .glb or with an external .bin).

inline std::string base64(const std::string& bytes) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                           (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                           static_cast<unsigned char>(bytes[i + 2]);
        for (int s = 18; s >= 0; s -= 6) out += table[(v >> s) & 63];
    }
    const std::size_t rest = bytes.size() - i;
    if (rest > 0) {
        unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
        if (rest == 2) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += rest == 2 ? table[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

inline void writeFile(const fs::path& path, const std::string& bytes) {
    std::ofstream f(path, std::ios::binary);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(f.good()) << path;
}

inline std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (i > 0) out += ',';
        out += items[i];
    }
    return out;
}

// A tiny PNG writer (stored deflate blocks) for the texture tests.

inline std::uint32_t crc32(const std::string& bytes) {
    std::uint32_t c = 0xffffffffu;
    for (char ch : bytes) {
        c ^= static_cast<unsigned char>(ch);
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c ^ 0xffffffffu;
}

inline std::string bigEndian(std::uint32_t v) {
    return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
            static_cast<char>(v)};
}

inline std::string pngChunk(const std::string& type, const std::string& data) {
    return bigEndian(static_cast<std::uint32_t>(data.size())) + type + data +
           bigEndian(crc32(type + data));
}

// RGB8 image, rows top to bottom.
inline std::string makePng(int width, int height, const std::vector<std::array<unsigned char, 3>>& rgb) {
    std::string raw;
    for (int y = 0; y < height; ++y) {
        raw += '\0';  // filter: none
        for (int x = 0; x < width; ++x)
            for (unsigned char c : rgb[static_cast<std::size_t>(y * width + x)])
                raw += static_cast<char>(c);
    }
    std::uint32_t a = 1, b = 0;
    for (char ch : raw) {
        a = (a + static_cast<unsigned char>(ch)) % 65521;
        b = (b + a) % 65521;
    }
    const auto len = static_cast<std::uint16_t>(raw.size());
    std::string z = "\x78\x01";
    z += '\x01';  // final stored block
    z += static_cast<char>(len & 0xff);
    z += static_cast<char>(len >> 8);
    z += static_cast<char>(~len & 0xff);
    z += static_cast<char>((~len >> 8) & 0xff);
    z += raw + bigEndian((b << 16) | a);
    std::string ihdr = bigEndian(static_cast<std::uint32_t>(width)) +
                       bigEndian(static_cast<std::uint32_t>(height));
    ihdr += std::string("\x08\x02\x00\x00\x00", 5);  // 8-bit RGB, no interlace
    return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) + pngChunk("IDAT", z) +
           pngChunk("IEND", "");
}

struct GltfBuilder {
    std::string bin;
    std::vector<std::string> bufferViews, accessors, meshes, nodes, materials, cameras, images,
        textures;
    std::vector<int> roots;
    std::string extraTopLevel;  // e.g. "\"extensionsUsed\":[...]," (with trailing comma)

    int addView(const std::string& bytes) {
        while (bin.size() % 4 != 0) bin += '\0';
        bufferViews.push_back("{\"buffer\":0,\"byteOffset\":" + std::to_string(bin.size()) +
                              ",\"byteLength\":" + std::to_string(bytes.size()) + "}");
        bin += bytes;
        return static_cast<int>(bufferViews.size()) - 1;
    }
    int addAccessor(const std::string& json) {
        accessors.push_back(json);
        return static_cast<int>(accessors.size()) - 1;
    }
    int addPositions(const std::vector<glm::vec3>& p) {
        std::string bytes(p.size() * 12, '\0');
        std::memcpy(bytes.data(), p.data(), bytes.size());
        const int view = addView(bytes);
        return addAccessor("{\"bufferView\":" + std::to_string(view) +
                           ",\"componentType\":5126,\"type\":\"VEC3\",\"count\":" +
                           std::to_string(p.size()) + "}");
    }
    int addIndices(const std::vector<std::uint32_t>& idx, int componentType = 5125) {
        const std::size_t size = componentType == 5121 ? 1 : componentType == 5123 ? 2 : 4;
        std::string bytes;
        for (std::uint32_t i : idx)
            for (std::size_t b = 0; b < size; ++b)
                bytes += static_cast<char>((i >> (8 * b)) & 0xff);
        const int view = addView(bytes);
        return addAccessor("{\"bufferView\":" + std::to_string(view) +
                           ",\"componentType\":" + std::to_string(componentType) +
                           ",\"type\":\"SCALAR\",\"count\":" + std::to_string(idx.size()) + "}");
    }
    int addTexCoords(const std::vector<glm::vec2>& uv) {
        std::string bytes(uv.size() * 8, '\0');
        std::memcpy(bytes.data(), uv.data(), bytes.size());
        const int view = addView(bytes);
        return addAccessor("{\"bufferView\":" + std::to_string(view) +
                           ",\"componentType\":5126,\"type\":\"VEC2\",\"count\":" + std::to_string(uv.size()) + "}");
    }
    // Axis-aligned boxes (pairs of corners) as one mesh of outward triangles,
    // as a modelling tool writes solids.
    int addBoxMesh(const std::string& name, const std::vector<std::pair<glm::dvec3, glm::dvec3>>& boxes,
                   int material) {
        std::vector<glm::vec3> positions;
        std::vector<std::uint32_t> indices;
        for (const auto& [lo, hi] : boxes)
            for (const auto& q : boxFaces(lo, hi, false)) {
                const auto base = static_cast<std::uint32_t>(positions.size());
                for (const glm::dvec3& v : q) positions.emplace_back(v);
                for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + k);
            }
        return addMesh(name, addPositions(positions), addIndices(indices), material);
    }
    // A mesh with one primitive; material < 0 leaves it out, mode < 0 too.
    // texCoords >= 0: its TEXCOORD_0 accessor.
    int addMesh(const std::string& name, int positions, int indices, int material, int mode = -1, int texCoords = -1) {
        std::string prim = "{\"attributes\":{\"POSITION\":" + std::to_string(positions);
        if (texCoords >= 0) prim += ",\"TEXCOORD_0\":" + std::to_string(texCoords);
        prim += "}";
        if (indices >= 0) prim += ",\"indices\":" + std::to_string(indices);
        if (material >= 0) prim += ",\"material\":" + std::to_string(material);
        if (mode >= 0) prim += ",\"mode\":" + std::to_string(mode);
        prim += "}";
        meshes.push_back("{\"name\":\"" + name + "\",\"primitives\":[" + prim + "]}");
        return static_cast<int>(meshes.size()) - 1;
    }
    int addMaterial(const std::string& json) {
        materials.push_back(json);
        return static_cast<int>(materials.size()) - 1;
    }
    int addGrey(const std::string& name, double rho = 0.5) {
        const std::string r = std::to_string(rho);
        return addMaterial("{\"name\":\"" + name +
                           "\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[" + r + "," + r +
                           "," + r + ",1]}}");
    }
    // Members after "{" of a node, e.g. "\"name\":\"A\",\"mesh\":0".
    int addNode(const std::string& members, bool root = true) {
        nodes.push_back("{" + members + "}");
        const int index = static_cast<int>(nodes.size()) - 1;
        if (root) roots.push_back(index);
        return index;
    }

    std::string json(const std::string& bufferJson) const {
        std::string rootList;
        for (std::size_t i = 0; i < roots.size(); ++i) {
            if (i > 0) rootList += ',';
            rootList += std::to_string(roots[i]);
        }
        std::string s = "{\"asset\":{\"version\":\"2.0\"}," + extraTopLevel +
                        "\"scene\":0,\"scenes\":[{\"nodes\":[" + rootList + "]}]," + "\"nodes\":[" +
                        joined(nodes) + "]";
        const auto section = [&](const char* name, const std::vector<std::string>& items) {
            if (!items.empty()) s += std::string(",\"") + name + "\":[" + joined(items) + "]";
        };
        section("meshes", meshes);
        section("materials", materials);
        section("cameras", cameras);
        section("images", images);
        section("textures", textures);
        section("accessors", accessors);
        section("bufferViews", bufferViews);
        if (!bin.empty()) s += ",\"buffers\":[" + bufferJson + "]";
        return s + "}";
    }
    std::string embeddedBuffer() const {
        return "{\"byteLength\":" + std::to_string(bin.size()) +
               ",\"uri\":\"data:application/octet-stream;base64," + base64(bin) + "\"}";
    }

    fs::path writeEmbedded(const TempDir& dir, const std::string& name = "scene.gltf") const {
        const fs::path path = dir / name;
        writeFile(path, json(embeddedBuffer()));
        return path;
    }
    fs::path writeExternal(const TempDir& dir, const std::string& name = "external.gltf") const {
        const fs::path path = dir / name;
        writeFile(dir / "external.bin", bin);
        writeFile(path, json("{\"byteLength\":" + std::to_string(bin.size()) +
                             ",\"uri\":\"external.bin\"}"));
        return path;
    }
    fs::path writeGlb(const TempDir& dir, const std::string& name = "scene.glb") const {
        std::string text = json("{\"byteLength\":" + std::to_string(bin.size()) + "}");
        while (text.size() % 4 != 0) text += ' ';
        std::string data = bin;
        while (data.size() % 4 != 0) data += '\0';
        std::string out;
        const auto u32 = [&out](std::uint32_t v) {
            for (int b = 0; b < 4; ++b) out += static_cast<char>((v >> (8 * b)) & 0xff);
        };
        out += "glTF";
        u32(2);
        u32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + data.size()));
        u32(static_cast<std::uint32_t>(text.size()));
        u32(0x4E4F534A);  // JSON
        out += text;
        u32(static_cast<std::uint32_t>(data.size()));
        u32(0x004E4942);  // BIN
        out += data;
        const fs::path path = dir / name;
        writeFile(path, out);
        return path;
    }
};


}  // namespace rad::test
