#include "radiosity/Gltf.h"
#include "radiosity/Settings.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <map>
#include <numeric>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "scene/Buried.h"
#include "scene/ClosedBackFaces.h"
#include "scene/Contacts.h"
#include "scene/Covered.h"
#include "scene/Placement.h"
#include "scene/Rectangles.h"

namespace rad {
namespace {

// A triangle in world space before it becomes a Polygon: kept apart so that
// degenerate ones can be dropped and neighbours merged into quads once the
// scene size is known.
struct WorldTriangle {
    std::array<glm::dvec3, 3> v;
    std::uint32_t material = 0;
    std::array<glm::vec2, 3> uv{};  // texture coordinates (zero when untextured)
};

struct PendingObject {
    Object object;
    std::string item;  // "node 'X'", for notes
    std::vector<WorldTriangle> triangles;
};

// tinygltf's messages span several lines; a SceneError is one line.
std::string oneLine(const std::string& text) {
    std::string out;
    bool pendingSeparator = false;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            pendingSeparator = !out.empty();
            continue;
        }
        if (pendingSeparator) {
            out += "; ";
            pendingSeparator = false;
        }
        out += c;
    }
    while (!out.empty() && std::isspace(static_cast<unsigned char>(out.back()))) out.pop_back();
    return out;
}

std::string lowerExtension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

std::string quoted(const std::string& kind, const std::string& name, std::size_t index) {
    if (name.empty()) return kind + " " + std::to_string(index);
    return kind + " '" + name + "'";
}

const char* modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS:
            return "POINTS";
        case TINYGLTF_MODE_LINE:
            return "LINES";
        case TINYGLTF_MODE_LINE_LOOP:
            return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP:
            return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_STRIP:
            return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN:
            return "TRIANGLE_FAN";
        default:
            return "unknown";
    }
}

bool allFinite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
}

bool allFinite(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

// A triangle is degenerate when its area is under this share of its
// longest edge squared: repeated or collinear corners, a needle whose normal
// rounding decides. Its own size, not the scene's: a stray object 100 km
// away once made every triangle under 0.01 m^2 degenerate (a shelf's books).
constexpr double kDegenerateShape = 1e-12;

double triangleArea(const WorldTriangle& t) {
    return 0.5 * glm::length(glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]));
}

bool degenerate(const WorldTriangle& t) {
    double longest2 = 0.0;
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 e = t.v[(k + 1) % 3] - t.v[k];
        longest2 = std::max(longest2, glm::dot(e, e));
    }
    const double area = triangleArea(t);
    return !(area > kDegenerateShape * longest2) || !std::isfinite(area);
}

glm::dvec3 triangleNormal(const WorldTriangle& t) {
    const glm::dvec3 n = glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
    const double len = glm::length(n);
    return len > 0.0 ? n / len : glm::dvec3(0.0);
}

// True when the quad q is strictly convex and turns the same way as n.
bool strictlyConvex(const std::array<glm::dvec3, 4>& q, const glm::dvec3& n) {
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 e1 = q[(i + 1) % 4] - q[i];
        const glm::dvec3 e2 = q[(i + 2) % 4] - q[(i + 1) % 4];
        // sin of the turning angle must be clearly positive: a straight
        // corner would make a quad that is really a triangle.
        if (glm::dot(glm::cross(e1, e2), n) <= 1e-9 * glm::length(e1) * glm::length(e2))
            return false;
    }
    return true;
}

// Whether the texture coordinates of the quad q are one affine map of its
// positions (those of its first three corners predict the fourth): a quad's
// points and coordinates are both bilinear in its parameters, so the texture
// then lies on the merged quad as it lay on the two triangles.
bool affineTexture(const std::array<glm::dvec3, 4>& q, const std::array<glm::vec2, 4>& uv) {
    const glm::dvec3 e1 = q[1] - q[0], e2 = q[3] - q[0], d = q[2] - q[0];
    // d in the basis e1, e2 (least squares; the four are coplanar).
    const double a11 = glm::dot(e1, e1), a12 = glm::dot(e1, e2), a22 = glm::dot(e2, e2);
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 0.0)) return false;
    const double b1 = glm::dot(d, e1), b2 = glm::dot(d, e2);
    const double s = (b1 * a22 - b2 * a12) / det, t = (a11 * b2 - a12 * b1) / det;
    const glm::dvec2 predicted = glm::dvec2(uv[0]) + s * glm::dvec2(uv[1] - uv[0]) + t * glm::dvec2(uv[3] - uv[0]);
    const double scale = std::max({1.0, glm::length(glm::dvec2(uv[1] - uv[0])), glm::length(glm::dvec2(uv[3] - uv[0]))});
    return glm::length(predicted - glm::dvec2(uv[2])) <= 1e-4 * scale;
}

struct MergedQuad {
    std::array<glm::dvec3, 4> v;
    std::array<glm::vec2, 4> uv;
};

// The quad made of a and b when they share an edge (in opposite directions,
// as consistent winding requires), lie in one plane and form a convex union;
// with a texture, only when the shared edge has the same coordinates in both
// and the coordinates are affine over the quad.
std::optional<MergedQuad> mergeToQuad(const WorldTriangle& a, const WorldTriangle& b, bool textured) {
    if (a.material != b.material) return std::nullopt;
    const glm::dvec3 na = triangleNormal(a);
    const glm::dvec3 nb = triangleNormal(b);
    // Positions come as float32: allow for their rounding (1e-4 rad, 0.006 degrees).
    if (glm::length(na - nb) > 1e-4) return std::nullopt;
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3& p = a.v[k];
        const glm::dvec3& q = a.v[(k + 1) % 3];
        for (int j = 0; j < 3; ++j) {
            // b runs q -> p where a runs p -> q.
            if (b.v[j] != q || b.v[(j + 1) % 3] != p) continue;
            const std::array<glm::dvec3, 4> quad = {q, a.v[(k + 2) % 3], p, b.v[(j + 2) % 3]};
            const std::array<glm::vec2, 4> uv = {a.uv[(k + 1) % 3], a.uv[(k + 2) % 3], a.uv[k], b.uv[(j + 2) % 3]};
            if (!strictlyConvex(quad, na)) return std::nullopt;
            if (textured && (b.uv[j] != a.uv[(k + 1) % 3] || b.uv[(j + 1) % 3] != a.uv[k] || !affineTexture(quad, uv)))
                return std::nullopt;
            return MergedQuad{quad, uv};
        }
    }
    return std::nullopt;
}

// A region of coplanar triangles merged into one convex polygon, or one of
// the rectangles a region is cut into.
struct MergedRegion {
    std::array<glm::dvec3, 4> corners{};
    std::uint8_t count = 0;
    std::uint32_t material = 0;
};

// The union of a region as one polygon: its outline (`next`: each outline
// vertex's successor, `at`: their positions) as one loop, with the vertices
// on straight stretches dropped, a convex triangle or quad whose area is the
// triangles' (`area`: nothing overlaps or folds). Its material is left to
// the caller.
std::optional<MergedRegion> convexUnion(const std::map<std::uint32_t, std::uint32_t>& next,
                                        const std::map<std::uint32_t, glm::dvec3>& at, const glm::dvec3& nrm, double area) {
    std::vector<glm::dvec3> loop;
    std::uint32_t v = next.begin()->first;
    for (std::size_t steps = 0; steps < next.size(); ++steps) {
        loop.push_back(at.at(v));
        v = next.at(v);
    }
    if (v != next.begin()->first) return std::nullopt;  // more than one loop: a hole, or pieces
    // Drop the vertices on straight stretches of the outline.
    for (bool dropped = true; dropped && loop.size() > 3;) {
        dropped = false;
        for (std::size_t i = 0; i < loop.size() && loop.size() > 3; ++i) {
            const glm::dvec3 e1 = loop[i] - loop[(i + loop.size() - 1) % loop.size()];
            const glm::dvec3 e2 = loop[(i + 1) % loop.size()] - loop[i];
            if (glm::length(glm::cross(e1, e2)) <= 1e-5 * glm::length(e1) * glm::length(e2) && glm::dot(e1, e2) > 0.0) {
                loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(i));
                dropped = true;
            }
        }
    }
    if (loop.size() > 4) return std::nullopt;
    MergedRegion r;
    r.count = static_cast<std::uint8_t>(loop.size());
    for (std::size_t i = 0; i < loop.size(); ++i) r.corners[i] = loop[i];
    if (r.count == 4 && !strictlyConvex(r.corners, nrm)) return std::nullopt;
    glm::dvec3 vector(0.0);
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) vector += glm::cross(loop[i] - loop[0], loop[i + 1] - loop[0]);
    if (std::abs(0.5 * glm::dot(vector, nrm) - area) > 1e-6 * area) return std::nullopt;
    return r;
}

// Takes out of `tris` every region of two or more triangles of one material,
// in one plane and joined by shared edges (the same two vertices, in
// opposite directions) and holding at least one sliver (kSliverShape),
// whose union is a convex triangle or quad once the
// vertices that lie on a straight stretch of its outline are dropped; returns
// those polygons. CAD tools triangulate a wall with points along its edges
// into long slivers; meshed as slivers, each gets its own elements and the
// display streaks along them, meshed as the wall it is one quadtree. A
// region that is not one convex polygon (a wall with a door or a window cut
// out of it) becomes the rectangles it is made of when its outline runs
// along two perpendicular directions (scene/Rectangles.h); otherwise it keeps
// its triangles (the pair merge still applies).
// A sliver: area under this share of its longest edge squared (about 1:10;
// half a square has 0.25, an equilateral triangle 0.43).
constexpr double kSliverShape = 0.05;

// Textured materials keep their triangles: a merged outline has no texture
// coordinates that would lay the texture as the triangles did.
std::vector<MergedRegion> mergeCoplanarRegions(std::vector<WorldTriangle>& tris, const std::vector<Material>& materials) {
    const std::size_t n = tris.size();
    std::map<std::array<double, 3>, std::uint32_t> ids;
    std::vector<std::array<std::uint32_t, 3>> vid(n);
    for (std::size_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3& p = tris[t].v[k];
            const auto [it, added] = ids.try_emplace({p.x, p.y, p.z}, static_cast<std::uint32_t>(ids.size()));
            vid[t][k] = it->second;
        }
    const auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
    std::unordered_map<std::uint64_t, std::uint32_t> owner;  // directed edge -> triangle
    for (std::uint32_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k) owner[key(vid[t][k], vid[t][(k + 1) % 3])] = t;
    std::vector<std::uint32_t> parent(n);
    for (std::uint32_t t = 0; t < n; ++t) parent[t] = t;
    const auto find = [&](std::uint32_t t) {
        while (parent[t] != t) t = parent[t] = parent[parent[t]];
        return t;
    };
    std::vector<glm::dvec3> normal(n);
    for (std::size_t t = 0; t < n; ++t) normal[t] = triangleNormal(tris[t]);
    // Positions come as float32: normals within 1e-4 rad are one plane's.
    const auto joins = [&](std::uint32_t t, std::uint32_t u) {
        return tris[t].material == tris[u].material && materials[tris[t].material].texture < 0 &&
               glm::length(normal[t] - normal[u]) <= 1e-4;
    };
    for (std::uint32_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k) {
            const auto it = owner.find(key(vid[t][(k + 1) % 3], vid[t][k]));
            if (it != owner.end() && joins(t, it->second)) parent[find(t)] = find(it->second);
        }
    std::map<std::uint32_t, std::vector<std::uint32_t>> regions;
    for (std::uint32_t t = 0; t < n; ++t) regions[find(t)].push_back(t);

    std::vector<MergedRegion> out;
    std::vector<bool> merged(n, false);
    // Only regions with slivers: a tiled wall of well-shaped triangle pairs
    // keeps its tiles (quads, by the pair merge), as its author laid them.
    const auto sliver = [&](std::uint32_t t) {
        double longest = 0.0;
        for (int k = 0; k < 3; ++k) longest = std::max(longest, glm::length(tris[t].v[(k + 1) % 3] - tris[t].v[k]));
        return triangleArea(tris[t]) < kSliverShape * longest * longest;
    };
    for (const auto& [root, members] : regions) {
        if (members.size() < 2 || std::none_of(members.begin(), members.end(), sliver)) continue;
        // The outline: the directed edges whose reverse is not in the region.
        std::map<std::uint32_t, std::uint32_t> next;
        std::map<std::uint32_t, glm::dvec3> at;
        bool manifold = true;
        double area = 0.0;
        glm::dvec3 sum(0.0);
        for (std::uint32_t t : members) {
            area += triangleArea(tris[t]);
            sum += triangleArea(tris[t]) * normal[t];
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t a = vid[t][k], b = vid[t][(k + 1) % 3];
                const auto rev = owner.find(key(b, a));
                if (rev != owner.end() && find(rev->second) == root) continue;
                manifold = manifold && next.emplace(a, b).second;
                at[a] = tris[t].v[k];
            }
        }
        if (!manifold || next.empty() || glm::length(sum) <= 0.0) continue;
        const glm::dvec3 nrm = glm::normalize(sum);
        const std::uint32_t material = tris[members[0]].material;
        if (const std::optional<MergedRegion> whole = convexUnion(next, at, nrm, area)) {
            out.push_back(*whole);
            out.back().material = material;
        } else {
            // Not one convex polygon (a wall with a door or a window cut
            // out of it): the rectangles it is made of, when its outline
            // runs along two directions.
            std::vector<std::pair<glm::dvec3, glm::dvec3>> edges;
            for (const auto& [a, b] : next) edges.emplace_back(at[a], at[b]);
            const auto rectangles = rectanglesOf(edges, nrm, area);
            if (!rectangles) continue;
            for (const std::array<glm::dvec3, 4>& q : *rectangles) out.push_back(MergedRegion{q, 4, material});
        }
        for (std::uint32_t t : members) merged[t] = true;
    }
    std::vector<WorldTriangle> rest;
    for (std::size_t t = 0; t < n; ++t)
        if (!merged[t]) rest.push_back(tris[t]);
    tris.swap(rest);
    return out;
}

// A cell of the grid that finds duplicate polygons (Importer::dropDuplicates).
struct CellKey {
    std::int64_t x, y, z;
    bool operator==(const CellKey&) const = default;
};
struct CellKeyHash {
    std::size_t operator()(const CellKey& c) const {
        // Large odd multipliers spread neighbouring cells over the table.
        const std::uint64_t h = static_cast<std::uint64_t>(c.x) * 0x9E3779B97F4A7C15ull ^
                                static_cast<std::uint64_t>(c.y) * 0xC2B2AE3D27D4EB4Full ^
                                static_cast<std::uint64_t>(c.z) * 0x165667B19E3779F9ull;
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

// A typed, range-checked view of an accessor's elements.
struct AccessorView {
    const unsigned char* base = nullptr;
    std::size_t stride = 0;
    std::size_t count = 0;
    const unsigned char* element(std::size_t i) const { return base + i * stride; }
};

class Importer {
  public:
    Importer(const std::string& path, ImportNotes& notes) : path_(path), notes_(notes) {}

    Scene run() {
        load();
        noteUnsupportedTopLevel();
        walkScene();
        Scene scene = finish();
        scene.sourcePath = path_;
        return scene;
    }

  private:
    [[noreturn]] void fail(const std::string& item, const std::string& problem) const {
        throw SceneError(path_ + ": " + item + ": " + problem);
    }

    void note(const std::string& line) { notes_.lines.push_back(line); }

    void load() {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path_, ec))
            fail("file", "does not exist or is not a file");
        const std::string ext = lowerExtension(path_);
        tinygltf::TinyGLTF loader;
        std::string err;
        std::string warn;
        bool ok = false;
        if (ext == ".glb") {
            ok = loader.LoadBinaryFromFile(&model_, &err, &warn, path_);
        } else if (ext == ".gltf") {
            ok = loader.LoadASCIIFromFile(&model_, &err, &warn, path_);
        } else {
            fail("file", "unknown extension '" + ext + "', expected .gltf or .glb");
        }
        if (!warn.empty()) note("tinygltf: " + oneLine(warn));
        if (!ok) fail("glTF", err.empty() ? "could not be parsed" : oneLine(err));
    }

    void noteUnsupportedTopLevel() {
        if (!model_.animations.empty())
            note(std::to_string(model_.animations.size()) + " animation(s) ignored");
        if (!model_.skins.empty()) note(std::to_string(model_.skins.size()) + " skin(s) ignored");
        const auto known = [](const std::string& ext) {
            return ext == "KHR_materials_emissive_strength" || ext == "KHR_materials_unlit" ||
                   ext == "KHR_lights_punctual" || ext == "KHR_texture_transform";
        };
        // A required extension changes what the file's data means (Draco- or
        // meshopt-compressed buffers, quantized positions): read without it,
        // the scene would be wrong.
        for (const std::string& ext : model_.extensionsRequired)
            if (!known(ext)) fail("file", "requires extension " + ext + ", which is not supported");
        for (const std::string& ext : model_.extensionsUsed)
            if (!known(ext)) note("extension " + ext + " ignored");
    }

    // Depth-first, pre-order: that order decides which camera is "first".
    void walkScene() {
        std::vector<int> roots;
        if (!model_.scenes.empty()) {
            // No "scene" (-1): the first. One that names no scene is an
            // error, not the first one silently.
            int sceneIndex = model_.defaultScene;
            if (sceneIndex >= static_cast<int>(model_.scenes.size()))
                fail("scene", "refers to scene " + std::to_string(sceneIndex) + " which does not exist (the file has " +
                                  std::to_string(model_.scenes.size()) + ")");
            if (sceneIndex < 0) sceneIndex = 0;
            if (model_.scenes.size() > 1)
                note("file has " + std::to_string(model_.scenes.size()) +
                     " scenes; imported scene " + std::to_string(sceneIndex));
            roots = model_.scenes[sceneIndex].nodes;
        } else {
            // No scene: every node that is nobody's child is a root.
            std::vector<bool> isChild(model_.nodes.size(), false);
            for (const tinygltf::Node& n : model_.nodes)
                for (int c : n.children)
                    if (c >= 0 && c < static_cast<int>(isChild.size())) isChild[c] = true;
            for (std::size_t i = 0; i < isChild.size(); ++i)
                if (!isChild[i]) roots.push_back(static_cast<int>(i));
            note("file has no scene; imported all root nodes");
        }
        visited_.assign(model_.nodes.size(), false);
        for (int r : roots) visitNode(r, glm::dmat4(1.0), std::nullopt);
    }

    const tinygltf::Node& nodeAt(int index, const std::string& from) const {
        if (index < 0 || index >= static_cast<int>(model_.nodes.size()))
            fail(from, "refers to node " + std::to_string(index) + " which does not exist");
        return model_.nodes[index];
    }

    std::string nodeItem(int index) const {
        return quoted("node", model_.nodes[index].name, static_cast<std::size_t>(index));
    }

    glm::dmat4 localTransform(const tinygltf::Node& node, const std::string& item) const {
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) fail(item, "matrix must have 16 numbers");
            if (!allFinite(node.matrix)) fail(item, "matrix contains NaN or Inf");
            glm::dmat4 m(1.0);
            // glTF matrices are column-major, as glm's are.
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[4 * c + r];
            // glTF's node matrices are affine (translation, rotation and
            // scale): a last row other than 0 0 0 1 is a projection, which
            // no rigid scene has.
            const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-6; };
            if (!near(m[0][3], 0.0) || !near(m[1][3], 0.0) || !near(m[2][3], 0.0) || !near(m[3][3], 1.0))
                fail(item, "matrix is not affine: its last row must be 0 0 0 1");
            return m;
        }
        if (!allFinite(node.translation) || !allFinite(node.rotation) || !allFinite(node.scale))
            fail(item, "translation, rotation or scale contains NaN or Inf");
        glm::dmat4 t(1.0);
        glm::dmat4 r(1.0);
        glm::dmat4 s(1.0);
        if (node.translation.size() == 3)
            t[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
        if (node.rotation.size() == 4) {
            // glTF stores x, y, z, w; glm's constructor takes w first.
            glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
            const double len = glm::length(q);
            if (len == 0.0) fail(item, "rotation quaternion has zero length");
            r = glm::mat4_cast(q / len);
        }
        if (node.scale.size() == 3) {
            s[0][0] = node.scale[0];
            s[1][1] = node.scale[1];
            s[2][2] = node.scale[2];
        }
        return t * r * s;
    }

    // `group`: the pending object of a marked ancestor (extras.dynamic or
    // extras.object), which takes the meshes of its whole subtree.
    void visitNode(int index, const glm::dmat4& parentWorld, std::optional<std::size_t> group) {
        const tinygltf::Node& node = nodeAt(index, "scene");
        const std::string item = nodeItem(index);
        if (visited_[index])
            fail(item, "is reached twice in the node tree (cycle or shared child)");
        visited_[index] = true;
        nodePath_.push_back(static_cast<std::uint32_t>(index));

        const glm::dmat4 world = parentWorld * localTransform(node, item);
        if (!allFinite(world)) fail(item, "world transform overflows to NaN or Inf");

        if (node.camera >= 0) visitCamera(node.camera, world, item);
        if (node.skin >= 0) note(item + ": skin ignored");
        if (!node.weights.empty()) note(item + ": morph weights ignored");
        for (const auto& [name, value] : node.extensions)
            if (name == "KHR_lights_punctual")
                visitLight(index, value, world, item, group ? pending_[*group].object.name : std::string());
            else
                note(item + ": node extension " + name + " ignored");
        const bool dynamic = extrasFlag(node, "dynamic", item);
        const bool marked = dynamic || extrasFlag(node, "object", item);
        if (group) {
            if (marked)
                note(item + ": marked as an object inside '" + pending_[*group].object.name +
                     "', part of it");
        } else if (marked) {
            // A chair made of legs, seat and back under one node moves as one.
            PendingObject pending;
            pending.item = item;
            pending.object.name = uniqueName(index);
            pending.object.worldFromLocal = world;
            pending.object.dynamic = dynamic;
            pending.object.nodePath = nodePath_;
            pending_.push_back(std::move(pending));
            group = pending_.size() - 1;
        }
        if (node.mesh >= 0) addMesh(index, world, group);

        for (int child : node.children) {
            nodeAt(child, item);
            visitNode(child, world, group);
        }
        nodePath_.pop_back();
    }

    // A node's KHR_lights_punctual light: point and spot lights become
    // lights of the scene, named after the node; directional ones have no
    // position and are left out with a note.
    void visitLight(int nodeIndex, const tinygltf::Value& ext, const glm::dmat4& world, const std::string& item,
                    const std::string& object) {
        if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsNumber())
            fail(item, "KHR_lights_punctual has no light index");
        const int index = ext.Get("light").GetNumberAsInt();
        if (index < 0 || index >= static_cast<int>(model_.lights.size()))
            fail(item, "refers to light " + std::to_string(index) + " which does not exist");
        const tinygltf::Light& l = model_.lights[index];
        const std::string lightItem = quoted("light", l.name, static_cast<std::size_t>(index));
        if (l.type == "directional") {
            note(item + ": directional " + lightItem + " ignored: only point and spot lights have a position");
            return;
        }
        PunctualLight light;
        if (l.type == "point")
            light.type = PunctualLight::Type::Point;
        else if (l.type == "spot")
            light.type = PunctualLight::Type::Spot;
        else
            fail(lightItem, "type '" + l.type + "' is not point, spot or directional");
        glm::dvec3 color(1.0);
        if (!l.color.empty()) {
            if (l.color.size() != 3) fail(lightItem, "color must have 3 numbers");
            color = glm::dvec3(l.color[0], l.color[1], l.color[2]);
        }
        if (!allFinite(l.color) || !(color.x >= 0.0 && color.y >= 0.0 && color.z >= 0.0))
            fail(lightItem, "color must be finite and at least 0 in each channel");
        if (!std::isfinite(l.intensity) || l.intensity < 0.0)
            fail(lightItem, "intensity " + std::to_string(l.intensity) + " must be finite and at least 0");
        if (l.range > 0.0) note(lightItem + ": range ignored: light falls off as 1/r^2 at every distance");
        if (light.type == PunctualLight::Type::Spot) {
            const double inner = l.spot.innerConeAngle, outer = l.spot.outerConeAngle;
            if (!std::isfinite(inner) || !std::isfinite(outer) || inner < 0.0 || !(inner < outer) ||
                outer > 0.5 * std::numbers::pi + 1e-9)
                fail(lightItem, "spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
            light.innerCone = inner;
            light.outerCone = std::min(outer, 0.5 * std::numbers::pi);
        }
        light.name = uniqueName(nodeIndex);
        light.intensity = color * l.intensity;
        light.worldFromLocal = world;
        light.object = object;
        light.nodePath = nodePath_;
        light.position = glm::dvec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
        const glm::dvec3 axis = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
        if (!(glm::length(axis) > 0.0)) fail(item, "transform collapses the light's direction");
        light.direction = glm::normalize(axis);
        lights_.push_back(light);
    }

    // true, or a number other than 0: Blender writes a custom property set
    // to True as 1 (its properties have no boolean type). Anything else is
    // noted and read as false.
    bool extrasFlag(const tinygltf::Node& node, const char* key, const std::string& item) {
        if (!node.extras.IsObject() || !node.extras.Has(key)) return false;
        const tinygltf::Value& v = node.extras.Get(key);
        if (v.IsBool()) return v.Get<bool>();
        if (v.IsNumber()) return v.GetNumberAsDouble() != 0.0;
        note(item + ": extras." + key + " is not true, false or a number: ignored");
        return false;
    }

    void visitCamera(int cameraIndex, const glm::dmat4& world, const std::string& item) {
        if (cameraIndex >= static_cast<int>(model_.cameras.size()))
            fail(item, "refers to camera " + std::to_string(cameraIndex) + " which does not exist");
        const tinygltf::Camera& cam = model_.cameras[cameraIndex];
        if (cam.type != "perspective") {
            note(item + ": " + cam.type + " camera ignored, only perspective cameras are used");
            return;
        }
        if (camera_) {
            note(item + ": camera ignored, the first perspective camera is used");
            return;
        }
        const glm::dmat3 basis(world);
        Camera c;
        c.position = glm::dvec3(world[3]);
        c.forward = glm::normalize(basis * glm::dvec3(0.0, 0.0, -1.0));
        const glm::dvec3 up = basis * glm::dvec3(0.0, 1.0, 0.0);
        c.up = glm::normalize(up - glm::dot(up, c.forward) * c.forward);
        if (!std::isfinite(c.forward.x + c.forward.y + c.forward.z + c.up.x + c.up.y + c.up.z))
            fail(item, "camera transform is degenerate");
        const tinygltf::PerspectiveCamera& p = cam.perspective;
        if (!(p.yfov > 0.0) || !std::isfinite(p.yfov)) fail(item, "camera yfov must be positive");
        c.yfov = p.yfov;
        if (p.aspectRatio > 0.0 && std::isfinite(p.aspectRatio)) c.aspectRatio = p.aspectRatio;
        if (p.znear > 0.0 && std::isfinite(p.znear)) c.znear = p.znear;
        camera_ = c;
    }

    std::string uniqueName(int nodeIndex) {
        const tinygltf::Node& node = model_.nodes[nodeIndex];
        std::string base = node.name.empty() ? "node" + std::to_string(nodeIndex) : node.name;
        std::string name = base;
        for (int k = 2; usedNames_.count(name) != 0; ++k) name = base + "#" + std::to_string(k);
        if (name != base) note(nodeItem(nodeIndex) + ": name repeats, renamed '" + name + "'");
        usedNames_.insert(name);
        return name;
    }

    // The node's mesh: an object of its own, or part of `group`'s.
    void addMesh(int nodeIndex, const glm::dmat4& world, std::optional<std::size_t> group) {
        const tinygltf::Node& node = model_.nodes[nodeIndex];
        const std::string item = nodeItem(nodeIndex);
        if (node.mesh >= static_cast<int>(model_.meshes.size()))
            fail(item, "refers to mesh " + std::to_string(node.mesh) + " which does not exist");

        if (!group) {
            PendingObject pending;
            pending.item = item;
            pending.object.name = uniqueName(nodeIndex);
            pending.object.worldFromLocal = world;
            pending.object.nodePath = nodePath_;
            pending_.push_back(std::move(pending));
            group = pending_.size() - 1;
        }
        std::vector<WorldTriangle>& triangles = pending_[*group].triangles;

        const tinygltf::Mesh& mesh = model_.meshes[node.mesh];
        const std::string meshItem = quoted("mesh", mesh.name, static_cast<std::size_t>(node.mesh));
        // A mirroring transform turns counter-clockwise into clockwise; swap
        // two vertices so the front stays the front.
        const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            addPrimitive(mesh.primitives[p], meshItem + " primitive " + std::to_string(p), world,
                         mirrored, triangles);
        }
    }

    AccessorView viewAccessor(int accessorIndex, const std::string& item, int type,
                              std::size_t componentSize) const {
        if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model_.accessors.size()))
            fail(item, "accessor " + std::to_string(accessorIndex) + " does not exist");
        const tinygltf::Accessor& acc = model_.accessors[accessorIndex];
        const std::string accItem = item + " accessor " + std::to_string(accessorIndex);
        if (acc.type != type) fail(accItem, "has the wrong type");
        if (acc.sparse.isSparse) fail(accItem, "sparse accessors are not supported");
        if (acc.bufferView < 0 || acc.bufferView >= static_cast<int>(model_.bufferViews.size()))
            fail(accItem, "has no valid bufferView");
        const tinygltf::BufferView& bv = model_.bufferViews[acc.bufferView];
        const std::string bvItem = accItem + " bufferView " + std::to_string(acc.bufferView);
        if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model_.buffers.size()))
            fail(bvItem, "has no valid buffer");
        const tinygltf::Buffer& buf = model_.buffers[bv.buffer];
        if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
            fail(bvItem, "range [" + std::to_string(bv.byteOffset) + ", " +
                             std::to_string(bv.byteOffset + bv.byteLength) + ") exceeds buffer " +
                             std::to_string(bv.buffer) + " of " + std::to_string(buf.data.size()) +
                             " bytes (truncated buffer?)");

        const std::size_t elementSize =
            componentSize * static_cast<std::size_t>(tinygltf::GetNumComponentsInType(type));
        const std::size_t stride = bv.byteStride != 0 ? bv.byteStride : elementSize;
        if (stride < elementSize) fail(bvItem, "byteStride is smaller than one element");
        AccessorView view;
        view.stride = stride;
        view.count = acc.count;
        if (acc.count == 0) return view;
        // Overflow-safe form of byteOffset + (count-1)*stride + elementSize <= byteLength.
        const std::size_t available = bv.byteLength;
        const bool fits = acc.byteOffset <= available &&
                          elementSize <= available - acc.byteOffset &&
                          (acc.count - 1) <= (available - acc.byteOffset - elementSize) / stride;
        if (!fits)
            fail(accItem, std::to_string(acc.count) + " elements at byteOffset " +
                              std::to_string(acc.byteOffset) + " exceed bufferView " +
                              std::to_string(acc.bufferView) + " of " + std::to_string(available) +
                              " bytes (truncated buffer?)");
        view.base = buf.data.data() + bv.byteOffset + acc.byteOffset;
        return view;
    }

    std::vector<glm::dvec3> readPositions(const tinygltf::Primitive& prim,
                                          const std::string& item) const {
        const auto it = prim.attributes.find("POSITION");
        if (it == prim.attributes.end()) fail(item, "has no POSITION attribute");
        const int index = it->second;
        if (index >= 0 && index < static_cast<int>(model_.accessors.size()) &&
            model_.accessors[index].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
            fail(item + " POSITION accessor " + std::to_string(index),
                 "component type must be FLOAT");
        const AccessorView view = viewAccessor(index, item + " POSITION", TINYGLTF_TYPE_VEC3, 4);
        std::vector<glm::dvec3> out(view.count);
        for (std::size_t i = 0; i < view.count; ++i) {
            float xyz[3];
            std::memcpy(xyz, view.element(i), sizeof xyz);  // may be unaligned
            if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
                fail(item, "POSITION " + std::to_string(i) + " is NaN or Inf");
            out[i] = glm::dvec3(xyz[0], xyz[1], xyz[2]);
        }
        return out;
    }

    // TEXCOORD_set, one per vertex (FLOAT, or normalised UNSIGNED_BYTE or
    // UNSIGNED_SHORT as glTF allows); empty when the primitive has none.
    std::vector<glm::vec2> readTexCoords(const tinygltf::Primitive& prim, int set, std::size_t vertices,
                                         const std::string& item) const {
        const std::string name = "TEXCOORD_" + std::to_string(set);
        const auto it = prim.attributes.find(name);
        if (it == prim.attributes.end()) return {};
        const int index = it->second;
        if (index < 0 || index >= static_cast<int>(model_.accessors.size()))
            fail(item, name + " accessor " + std::to_string(index) + " does not exist");
        const tinygltf::Accessor& acc = model_.accessors[index];
        std::size_t size = 0;
        double scale = 1.0;
        switch (acc.componentType) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: size = 4; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; scale = 1.0 / 255.0; break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; scale = 1.0 / 65535.0; break;
            default: fail(item + " " + name + " accessor " + std::to_string(index), "component type must be FLOAT, UNSIGNED_BYTE or UNSIGNED_SHORT");
        }
        if (size != 4 && !acc.normalized)
            fail(item + " " + name + " accessor " + std::to_string(index), "integer texture coordinates must be normalized");
        const AccessorView view = viewAccessor(index, item + " " + name, TINYGLTF_TYPE_VEC2, size);
        if (view.count != vertices)
            fail(item, name + " has " + std::to_string(view.count) + " elements for " + std::to_string(vertices) + " vertices");
        std::vector<glm::vec2> out(view.count);
        for (std::size_t i = 0; i < view.count; ++i) {
            double uv[2];
            for (int c = 0; c < 2; ++c) {
                const unsigned char* at = view.element(i) + c * size;
                if (size == 4) {
                    float f;
                    std::memcpy(&f, at, 4);
                    uv[c] = f;
                } else if (size == 2) {
                    std::uint16_t v;
                    std::memcpy(&v, at, 2);
                    uv[c] = v * scale;
                } else {
                    uv[c] = *at * scale;
                }
            }
            if (!std::isfinite(uv[0]) || !std::isfinite(uv[1])) fail(item, name + " " + std::to_string(i) + " is NaN or Inf");
            out[i] = glm::vec2(float(uv[0]), float(uv[1]));
        }
        return out;
    }

    // A base colour texture's KHR_texture_transform, baked into the texture
    // coordinates at import: uv' = offset + R(rotation) (scale * uv), with
    // the rotation as glTF's implementations and sample model turn it (the
    // image clockwise in the spec's v-down texture space; KhronosGroup/glTF
    // issue 1563), and the extension's texCoord replacing the texture's.
    struct UvTransform {
        int set = 0;
        glm::dvec2 offset{0.0}, scale{1.0};
        double rotation = 0.0;
        glm::dvec2 apply(glm::dvec2 uv) const {
            const glm::dvec2 s = scale * uv;
            const double c = std::cos(rotation), n = std::sin(rotation);
            return offset + glm::dvec2(c * s.x + n * s.y, -n * s.x + c * s.y);
        }
    };
    UvTransform uvTransform(const tinygltf::TextureInfo& info, const std::string& item) const {
        UvTransform t;
        t.set = info.texCoord;
        const auto ext = info.extensions.find("KHR_texture_transform");
        if (ext == info.extensions.end()) return t;
        const tinygltf::Value& v = ext->second;
        const std::string where = item + " KHR_texture_transform";
        const auto pair = [&](const char* key, glm::dvec2& out) {
            if (!v.Has(key)) return;
            const tinygltf::Value& a = v.Get(key);
            if (!a.IsArray() || a.ArrayLen() != 2 || !a.Get(0).IsNumber() || !a.Get(1).IsNumber() ||
                !std::isfinite(a.Get(0).GetNumberAsDouble()) || !std::isfinite(a.Get(1).GetNumberAsDouble()))
                fail(where, std::string(key) + " must be two finite numbers");
            out = glm::dvec2(a.Get(0).GetNumberAsDouble(), a.Get(1).GetNumberAsDouble());
        };
        pair("offset", t.offset);
        pair("scale", t.scale);
        if (v.Has("rotation")) {
            const tinygltf::Value& r = v.Get("rotation");
            if (!r.IsNumber() || !std::isfinite(r.GetNumberAsDouble())) fail(where, "rotation must be a finite number");
            t.rotation = r.GetNumberAsDouble();
        }
        if (v.Has("texCoord")) {
            const tinygltf::Value& c = v.Get("texCoord");
            if (!c.IsInt() || c.GetNumberAsInt() < 0) fail(where, "texCoord must be a non-negative integer");
            t.set = c.GetNumberAsInt();
        }
        return t;
    }

    // The same material without its texture (reflectance its mean), for
    // primitives that give no texture coordinates.
    std::uint32_t untexturedCopy(std::uint32_t material) {
        const auto found = untextured_.find(material);
        if (found != untextured_.end()) return found->second;
        Material m = materials_[material];
        m.texture = -1;
        m.textureMean = glm::dvec3(1.0);
        const auto index = static_cast<std::uint32_t>(materials_.size());
        materials_.push_back(m);
        if (doubleSided_.count(material)) doubleSided_.insert(index);
        if (const auto found = alphaMode_.find(material); found != alphaMode_.end()) alphaMode_[index] = found->second;
        untextured_[material] = index;
        return index;
    }

    std::vector<std::uint32_t> readIndices(int accessorIndex, const std::string& item) const {
        if (accessorIndex >= static_cast<int>(model_.accessors.size()))
            fail(item, "indices accessor " + std::to_string(accessorIndex) + " does not exist");
        const int componentType = model_.accessors[accessorIndex].componentType;
        std::size_t size = 0;
        switch (componentType) {
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                size = 1;
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
                size = 2;
                break;
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
                size = 4;
                break;
            default:
                fail(item + " indices accessor " + std::to_string(accessorIndex),
                     "component type " + std::to_string(componentType) +
                         " is not an unsigned byte, short or int");
        }
        const AccessorView view =
            viewAccessor(accessorIndex, item + " indices", TINYGLTF_TYPE_SCALAR, size);
        std::vector<std::uint32_t> out(view.count);
        for (std::size_t i = 0; i < view.count; ++i) {
            const unsigned char* p = view.element(i);
            if (size == 1) {
                out[i] = *p;
            } else if (size == 2) {
                std::uint16_t v;
                std::memcpy(&v, p, 2);
                out[i] = v;
            } else {
                std::memcpy(&out[i], p, 4);
            }
        }
        return out;
    }

    // A strip's or fan's vertices as a list of triangles, in glTF's order
    // and winding (glTF 2.0, 3.7.2.1: strip triangle i is {i, i + 1 + i % 2,
    // i + 2 - i % 2}, fan triangle i is {i + 1, i + 2, 0}).
    std::vector<std::uint32_t> triangleList(int mode, const std::vector<std::uint32_t>& v, const std::string& item) {
        if (v.size() < 3) fail(item, std::to_string(v.size()) + " vertices do not make a triangle");
        std::vector<std::uint32_t> out;
        out.reserve(3 * (v.size() - 2));
        for (std::size_t i = 0; i + 2 < v.size(); ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
                out.insert(out.end(), {v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]});
            else
                out.insert(out.end(), {v[i + 1], v[i + 2], v[0]});
        }
        return out;
    }

    void addPrimitive(const tinygltf::Primitive& prim, const std::string& item,
                      const glm::dmat4& world, bool mirrored, std::vector<WorldTriangle>& out) {
        const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP ||
            mode == TINYGLTF_MODE_LINE_STRIP) {
            // Points and lines have no area to light (a CAD export's edges).
            note(item + ": mode " + modeName(mode) + " has no area, skipped");
            return;
        }
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN)
            fail(item, std::string("mode ") + modeName(mode) + " (" + std::to_string(mode) + ") is not supported");
        if (!prim.targets.empty()) note(item + ": morph targets ignored");
        if (prim.attributes.count("COLOR_0"))
            note(item + ": COLOR_0 (vertex colours) ignored: the reflectance is the material's base colour alone");
        std::uint32_t material = materialIndex(prim.material, item);
        const std::vector<glm::dvec3> local = readPositions(prim, item);
        std::vector<glm::vec2> uv;
        if (materials_[material].texture >= 0) {
            const tinygltf::TextureInfo& info = model_.materials[prim.material].pbrMetallicRoughness.baseColorTexture;
            const UvTransform transform = uvTransform(info, quoted("material", model_.materials[prim.material].name,
                                                                   static_cast<std::size_t>(prim.material)));
            uv = readTexCoords(prim, transform.set, local.size(), item);
            if (uv.empty()) {
                note(item + ": no TEXCOORD_" + std::to_string(transform.set) +
                     " for its base colour texture; the texture counts as its mean");
                material = untexturedCopy(material);
            }
            for (glm::vec2& t : uv) t = glm::vec2(transform.apply(t));
        }
        std::vector<std::uint32_t> indices;
        if (prim.indices >= 0) {
            indices = readIndices(prim.indices, item);
        } else {
            indices.resize(local.size());
            for (std::size_t i = 0; i < indices.size(); ++i)
                indices[i] = static_cast<std::uint32_t>(i);
        }
        if (mode != TINYGLTF_MODE_TRIANGLES) indices = triangleList(mode, indices, item);
        if (indices.size() % 3 != 0)
            fail(item, std::to_string(indices.size()) + " vertices do not make whole triangles");

        std::vector<glm::dvec3> worldPos(local.size());
        const glm::dvec3 nodeOrigin(world[3]);
        for (std::size_t i = 0; i < local.size(); ++i) {
            worldPos[i] = glm::dvec3(world * glm::dvec4(local[i], 1.0));
            storedReach_ = std::max(storedReach_, glm::length(worldPos[i] - nodeOrigin));
        }

        for (std::size_t t = 0; t < indices.size(); t += 3) {
            WorldTriangle tri;
            tri.material = material;
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t idx = indices[t + k];
                if (idx >= worldPos.size())
                    fail(item, "index " + std::to_string(idx) + " is out of range (" +
                                   std::to_string(worldPos.size()) + " vertices)");
                tri.v[k] = worldPos[idx];
                if (!uv.empty()) tri.uv[k] = uv[idx];
            }
            if (mirrored) {
                std::swap(tri.v[1], tri.v[2]);
                std::swap(tri.uv[1], tri.uv[2]);
            }
            out.push_back(tri);
        }
    }

    std::uint32_t materialIndex(int gltfIndex, const std::string& item) {
        if (gltfIndex < 0) {
            if (!defaultMaterial_) {
                defaultMaterial_ = static_cast<std::uint32_t>(materials_.size());
                materials_.push_back({"default", glm::dvec3(0.5), glm::dvec3(0.0)});
            }
            return *defaultMaterial_;
        }
        if (gltfIndex >= static_cast<int>(model_.materials.size()))
            fail(item, "material " + std::to_string(gltfIndex) + " does not exist");
        const auto found = materialMap_.find(gltfIndex);
        if (found != materialMap_.end()) return found->second;
        const auto index = static_cast<std::uint32_t>(materials_.size());
        materials_.push_back(convertMaterial(gltfIndex));
        if (model_.materials[gltfIndex].doubleSided) doubleSided_.insert(index);
        if (const std::string& mode = model_.materials[gltfIndex].alphaMode; !mode.empty() && mode != "OPAQUE")
            alphaMode_[index] = mode;
        materialMap_[gltfIndex] = index;
        return index;
    }

    Material convertMaterial(int index) {
        const tinygltf::Material& m = model_.materials[index];
        const std::string item = quoted("material", m.name, static_cast<std::size_t>(index));
        Material out;
        out.name = m.name.empty() ? "material" + std::to_string(index) : m.name;

        const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() < 3 || !allFinite(pbr.baseColorFactor))
            fail(item, "baseColorFactor is missing numbers or contains NaN or Inf");
        glm::dvec3 rho(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2]);
        if (pbr.baseColorTexture.index >= 0) {
            if (const std::optional<std::uint32_t> t = texture(pbr.baseColorTexture.index, item)) {
                out.texture = static_cast<std::int32_t>(*t);
                out.textureMean = textures_[*t]->mean();
                rho *= out.textureMean;
            }
        }
        for (int c = 0; c < 3; ++c) {
            if (!(rho[c] >= 0.0 && rho[c] <= 1.0)) {
                std::ostringstream s;
                s << "reflectance " << rho[c] << " in channel " << c
                  << " is outside [0,1] (baseColorFactor times base colour texture mean)";
                fail(item, s.str());
            }
        }
        const double largest = std::max({rho.x, rho.y, rho.z});
        if (largest > kMaxReflectance) {
            notes_.clampedReflectance.push_back({out.name, largest});
            rho = glm::min(rho, glm::dvec3(kMaxReflectance));
        }
        out.reflectance = rho;

        if (m.emissiveFactor.size() < 3 || !allFinite(m.emissiveFactor))
            fail(item, "emissiveFactor is missing numbers or contains NaN or Inf");
        double strength = 1.0;
        const auto ext = m.extensions.find("KHR_materials_emissive_strength");
        if (ext != m.extensions.end() && ext->second.Has("emissiveStrength")) {
            const tinygltf::Value& v = ext->second.Get("emissiveStrength");
            if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble()))
                fail(item, "emissiveStrength is not a finite number");
            strength = v.GetNumberAsDouble();
        }
        out.emission =
            glm::dvec3(m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2]) * strength;
        for (int c = 0; c < 3; ++c) {
            if (out.emission[c] < 0.0) {
                std::ostringstream s;
                s << "emission " << out.emission[c] << " in channel " << c << " is negative";
                fail(item, s.str());
            }
            if (!(out.emission[c] <= kMaxEmission)) {
                std::ostringstream s;
                s << "emission " << out.emission[c] << " in channel " << c
                  << " (emissiveFactor times emissiveStrength) is above the largest accepted, " << kMaxEmission;
                fail(item, s.str());
            }
        }
        noteIgnoredMaterialParts(m, item);
        return out;
    }

    void noteIgnoredMaterialParts(const tinygltf::Material& m, const std::string& item) {
        if (m.emissiveTexture.index >= 0) note(item + ": emissiveTexture ignored");
        if (m.normalTexture.index >= 0) note(item + ": normalTexture ignored");
        if (m.occlusionTexture.index >= 0) note(item + ": occlusionTexture ignored");
        if (m.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0)
            note(item + ": metallicRoughnessTexture ignored");
        // Glass, foliage cut-outs: the engine has no transmission, so say
        // what the surface became.
        if (!m.alphaMode.empty() && m.alphaMode != "OPAQUE") {
            std::ostringstream s;
            s << item << ": alphaMode " << m.alphaMode << " (base colour alpha "
              << (m.pbrMetallicRoughness.baseColorFactor.size() == 4 ? m.pbrMetallicRoughness.baseColorFactor[3] : 1.0)
              << ") read as opaque: it reflects its base colour and lets no light through";
            note(s.str());
        }
        for (const auto& [name, value] : m.extensions) {
            if (name != "KHR_materials_emissive_strength")
                note(item + ": extension " + name + " ignored");
        }
    }

    // The scene texture of a glTF texture: its image as sRGB RGBA8 (16-bit
    // channels rounded, grey repeated into r, g and b) and its sampler's
    // wrap modes. Empty, with a note, when it has no decodable image.
    std::optional<std::uint32_t> texture(int textureIndex, const std::string& item) {
        if (textureIndex >= static_cast<int>(model_.textures.size()))
            fail(item, "baseColorTexture " + std::to_string(textureIndex) + " does not exist");
        const auto cached = textureMap_.find(textureIndex);
        if (cached != textureMap_.end()) return cached->second;
        const tinygltf::Texture& t = model_.textures[textureIndex];
        std::optional<std::uint32_t> result;
        const int source = t.source;
        const tinygltf::Image* img = source >= 0 && source < static_cast<int>(model_.images.size()) ? &model_.images[source] : nullptr;
        const std::size_t bytesPerChannel = img && img->bits == 16 ? 2 : 1;
        const std::size_t texels = img && img->width > 0 && img->height > 0
                                       ? static_cast<std::size_t>(img->width) * static_cast<std::size_t>(img->height)
                                       : 0;
        if (!img || texels == 0 || img->component < 1 || (img->bits != 8 && img->bits != 16) ||
            img->image.size() < texels * img->component * bytesPerChannel) {
            note(item + ": baseColorTexture has no image that could be decoded, ignored");
        } else {
            auto out = std::make_shared<Texture>();
            out->name = img->name.empty() ? (img->uri.empty() ? "image" + std::to_string(source) : img->uri) : img->name;
            out->width = static_cast<std::uint32_t>(img->width);
            out->height = static_cast<std::uint32_t>(img->height);
            out->srgba.resize(texels * 4);
            for (std::size_t i = 0; i < texels; ++i)
                for (int c = 0; c < 4; ++c) {
                    // Grey images (1 or 2 components) use channel 0 for r, g and b; alpha is not used.
                    const int from = c == 3 ? -1 : img->component < 3 ? 0 : c;
                    std::uint32_t v = 255;
                    if (from >= 0) {
                        const std::size_t offset = (i * img->component + from) * bytesPerChannel;
                        if (bytesPerChannel == 2) {
                            std::uint16_t v16;
                            std::memcpy(&v16, &img->image[offset], 2);
                            v = (v16 + 128u) / 257u;
                        } else {
                            v = img->image[offset];
                        }
                    }
                    out->srgba[i * 4 + c] = static_cast<std::uint8_t>(v);
                }
            if (t.sampler >= 0 && t.sampler < static_cast<int>(model_.samplers.size())) {
                const auto wrap = [](int mode) {
                    return mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? Texture::Wrap::Clamp
                           : mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? Texture::Wrap::Mirror
                                                                           : Texture::Wrap::Repeat;
                };
                out->wrapU = wrap(model_.samplers[t.sampler].wrapS);
                out->wrapV = wrap(model_.samplers[t.sampler].wrapT);
            }
            result = static_cast<std::uint32_t>(textures_.size());
            textures_.push_back(std::move(out));
        }
        textureMap_[textureIndex] = result;
        return result;
    }

    static std::string squareMetres(double a) {
        std::ostringstream text;
        text.precision(3);
        text << a << " m^2";
        return text.str();
    }

    // The (at most) three objects with the most area left out, and theirs.
    std::string mostAreas(const std::vector<double>& areaLeftOut) const {
        std::vector<std::size_t> order(pending_.size());
        std::iota(order.begin(), order.end(), std::size_t(0));
        std::stable_sort(order.begin(), order.end(),
                         [&](std::size_t a, std::size_t b) { return areaLeftOut[a] > areaLeftOut[b]; });
        std::string most;
        for (std::size_t k = 0; k < std::min<std::size_t>(3, order.size()); ++k)
            if (areaLeftOut[order[k]] > 0.0)
                most += (most.empty() ? "" : ", ") + pending_[order[k]].item + " " + squareMetres(areaLeftOut[order[k]]);
        return most;
    }

    // A note for each light inside one of object i's closed meshes (its
    // `closed` solids), another's: a punctual light or an emitting triangle.
    // None of its light leaves the mesh, which is opaque (a bulb in a glass
    // globe: the room stays dark, and the solve's back_faces warning blames
    // the globe's normals).
    // `emitters`: the centre of each emitting triangle and its object, in
    // object order.
    void noteEnclosedLights(std::size_t i, const std::vector<WorldTriangle>& kept,
                            const std::vector<ClosedSolid>& closed,
                            const std::vector<std::pair<glm::dvec3, std::size_t>>& emitters) {
        if (closed.empty()) return;
        const auto holds = [&](const glm::dvec3& p) {
            return std::any_of(closed.begin(), closed.end(), [&](const ClosedSolid& s) { return s.holds(p); });
        };
        std::vector<std::string> held;
        for (const PunctualLight& l : lights_)
            if (holds(l.position)) held.push_back("light '" + l.name + "'");
        std::size_t last = pending_.size();  // the emitting object named last: each once
        for (const auto& [centre, j] : emitters)
            if (j != i && j != last && holds(centre)) {
                held.push_back("the light of " + pending_[j].item);
                last = j;
            }
        if (held.empty()) return;
        std::string alpha;
        for (const WorldTriangle& t : kept)
            if (const auto found = alphaMode_.find(t.material); found != alphaMode_.end()) {
                alpha = " (its alphaMode " + found->second + " is read as opaque: glass is not modelled)";
                break;
            }
        std::string lights;
        for (std::size_t k = 0; k < held.size(); ++k) lights += (k == 0 ? "" : ", ") + held[k];
        note(pending_[i].item + " is a closed mesh around " + lights + ": none of its light leaves the mesh" + alpha);
    }

    // One note line for a cutting step: the polygons cut, the area left out
    // and the objects that lost most. Returns that area.
    double noteCut(std::size_t polygonsCut, const std::vector<double>& areaLeftOut, const std::string& where,
                   const std::string& leftOut) {
        double total = 0.0;
        for (double a : areaLeftOut) total += a;
        note(std::to_string(polygonsCut) + " polygon(s) of static objects cut " + where + "; " + squareMetres(total) +
             " " + leftOut + " (most: " + mostAreas(areaLeftOut) + ")");
        return total;
    }

    // Nothing may lie so far from the scene's detail that the rays and the
    // plane tests lose it (scene/Placement.h).
    void failOutOfReach(const Placement& placement) const {
        const auto check = [&](const glm::dvec3& p, const std::string& item) {
            if (placement.reaches(p)) return;
            std::ostringstream out;
            out << std::setprecision(3) << "lies " << glm::length(p - placement.centre)
                << " m from the rest of the scene, over " << kMaxReach << " times the size of its detail ("
                << placement.size << " m): is the node misplaced, or in other units?";
            fail(item, out.str());
        };
        for (const PendingObject& o : pending_)
            for (const WorldTriangle& t : o.triangles)
                for (const glm::dvec3& v : t.v) check(v, o.item);
        for (const PunctualLight& l : lights_) check(l.position, "light '" + l.name + "'");
    }

    // A scene that its nodes' translations place far out, its positions
    // stored small, is moved near the origin (Scene::fileOrigin): the plane
    // tests allow for float32 rounding where a polygon lies
    // (positionTolerance), 10 cm 1000 km out, which cut most of
    // `lamp-room`'s bookcase as covered when a parent node moved it there.
    // Positions stored far out keep where they are and their allowance.
    // Returns the shift, in the file's coordinates: whole metres.
    glm::dvec3 bringNearOrigin(const Placement& placement) {
        const double far = glm::length(placement.centre);
        if (!(far > kFarOut * std::max(placement.size, storedReach_))) return glm::dvec3(0.0);
        const glm::dvec3 shift = glm::round(placement.centre);
        const glm::dmat4 back = glm::translate(glm::dmat4(1.0), -shift);
        for (PendingObject& o : pending_) {
            o.object.worldFromLocal = back * o.object.worldFromLocal;
            for (WorldTriangle& t : o.triangles)
                for (glm::dvec3& v : t.v) v -= shift;
        }
        for (PunctualLight& l : lights_) {
            l.position -= shift;
            l.worldFromLocal = back * l.worldFromLocal;
        }
        if (camera_) camera_->position -= shift;
        return shift;
    }
    // How many times its size (and its stored positions' reach) a scene's
    // detail must lie from the origin to be moved near it: ordinary scenes,
    // a few sizes off the origin, are left as they are.
    static constexpr double kFarOut = 1000.0;

    // Drops degenerate triangles, merges quads, drops duplicate polygons and
    // lays the polygons out object by object.
    Scene finish() {
        std::vector<glm::dvec3> points;
        for (const PendingObject& o : pending_)
            for (const WorldTriangle& t : o.triangles) points.insert(points.end(), t.v.begin(), t.v.end());
        const Placement placement = placementOf(points);
        failOutOfReach(placement);
        const glm::dvec3 fileOrigin = bringNearOrigin(placement);
        Aabb box;
        for (const PendingObject& o : pending_)
            for (const WorldTriangle& t : o.triangles)
                for (const glm::dvec3& v : t.v) box.extend(v);
        const double diagonal2 = box.empty() ? 0.0 : glm::dot(box.extent(), box.extent());

        // Each pending object's polygons; Polygon::object is the pending
        // index until the objects without polygons are left out.
        std::vector<std::vector<Polygon>> polygons(pending_.size());
        // Where light comes from: the punctual lights, and the corners and
        // centres of emitting triangles (with their object), for the backs
        // of closed doubleSided meshes (scene/ClosedBackFaces.h).
        constexpr std::size_t kNoObject = std::size_t(-1);
        std::vector<std::pair<glm::dvec3, std::size_t>> lightAt;
        for (const PunctualLight& l : lights_) lightAt.emplace_back(l.position, kNoObject);
        for (std::size_t i = 0; i < pending_.size(); ++i)
            for (const WorldTriangle& t : pending_[i].triangles)
                if (glm::any(glm::greaterThan(materials_[t.material].emission, glm::dvec3(0.0)))) {
                    for (const glm::dvec3& v : t.v) lightAt.emplace_back(v, i);
                    lightAt.emplace_back((t.v[0] + t.v[1] + t.v[2]) / 3.0, i);
                }
        // An emitter's triangles share their corners: each point once.
        std::sort(lightAt.begin(), lightAt.end(), [](const auto& a, const auto& b) {
            return std::tie(a.first.x, a.first.y, a.first.z, a.second) <
                   std::tie(b.first.x, b.first.y, b.first.z, b.second);
        });
        lightAt.erase(std::unique(lightAt.begin(), lightAt.end()), lightAt.end());
        std::vector<char> emits(materials_.size(), 0);  // per material
        for (std::size_t m = 0; m < materials_.size(); ++m)
            emits[m] = glm::any(glm::greaterThan(materials_[m].emission, glm::dvec3(0.0)));
        std::vector<std::pair<glm::dvec3, std::size_t>> emitterCentres;
        for (std::size_t i = 0; i < pending_.size(); ++i)
            for (const WorldTriangle& t : pending_[i].triangles)
                if (emits[t.material]) emitterCentres.emplace_back((t.v[0] + t.v[1] + t.v[2]) / 3.0, i);
        std::size_t frontOnly = 0;
        std::string closedWhere;
        int closedListed = 0;
        std::size_t dropped = 0;
        std::string where;  // the first objects with degenerate triangles
        int listed = 0;
        // The closed solids of static objects, which cut the parts of
        // static polygons buried in them (scene/Buried.h).
        std::vector<ClosedSolid> solids;
        std::vector<char> cut(pending_.size(), 0);
        for (std::size_t i = 0; i < pending_.size(); ++i) {
            std::vector<WorldTriangle> kept;
            std::size_t here = 0;
            for (const WorldTriangle& t : pending_[i].triangles) {
                if (degenerate(t)) {
                    ++here;
                } else {
                    kept.push_back(t);
                }
            }
            std::vector<std::array<glm::dvec3, 3>> surface;
            for (const WorldTriangle& t : kept) surface.push_back(t.v);
            std::vector<ClosedSolid> closed = closedSolids(surface);
            noteEnclosedLights(i, kept, closed, emitterCentres);
            if (!pending_[i].object.dynamic) {
                cut[i] = 1;
                for (ClosedSolid& s : closed) {
                    // A solid with a light inside holds lit space.
                    const bool lit = std::any_of(lightAt.begin(), lightAt.end(), [&](const auto& light) {
                        return light.second != i && s.holds(light.first);
                    });
                    if (!lit) solids.push_back(std::move(s));
                }
            }
            bool backs = true;
            if (std::any_of(kept.begin(), kept.end(), [&](const WorldTriangle& t) {
                    return doubleSided_.count(t.material) > 0;
                })) {
                std::vector<std::array<glm::dvec3, 3>> surface;
                for (const WorldTriangle& t : kept) surface.push_back(t.v);
                std::vector<glm::dvec3> others;
                for (const auto& [x, object] : lightAt)
                    if (object != i) others.push_back(x);
                backs = !backFacesFaceNoLight(surface, others);
                if (!backs && ++closedListed <= 3)
                    closedWhere += (closedWhere.empty() ? "" : ", ") + pending_[i].item;
                else if (!backs && closedListed == 4)
                    closedWhere += ", ...";
            }
            const std::size_t before = polygons[i].size();
            appendPolygons(kept, static_cast<std::uint32_t>(i), polygons[i], backs);
            if (!backs)
                for (std::size_t k = before; k < polygons[i].size(); ++k)
                    frontOnly += doubleSided_.count(polygons[i][k].material);
            if (here > 0 && ++listed <= 3)
                where += (where.empty() ? "" : ", ") + pending_[i].item + " " + std::to_string(here);
            else if (here > 0 && listed == 4)
                where += ", ...";
            dropped += here;
        }
        notes_.degenerateTriangles += dropped;
        if (dropped > 0)
            note(std::to_string(dropped) + " degenerate triangle(s) dropped (area under 1e-12 of their longest edge "
                 "squared; " + where + ")");
        if (notes_.mergedRegionTriangles > 0)
            note(std::to_string(notes_.mergedRegionTriangles) +
                 " triangle(s) merged with their coplanar neighbours into convex polygons or rectangles");
        if (backFaces_ > 0)
            note(std::to_string(backFaces_) + " polygon(s) of doubleSided materials given a back face of their own");
        if (frontOnly > 0)
            note(std::to_string(frontOnly) +
                 " polygon(s) of doubleSided materials on closed meshes left one-sided: their "
                 "backs face a closed space no light is in (" +
                 closedWhere + ")");
        const std::vector<std::size_t> duplicates = dropDuplicates(polygons, 1e-9 * std::sqrt(diagonal2));
        // After the duplicates (a copy covers the same area, and would cut
        // its original away) and before the solids' cuts (a cut polygon is
        // no longer the one that covers).
        const CoveredParts covered = cutCoveredParts(polygons, cut);
        if (covered.polygonsCut > 0) {
            notes_.coveredPolygons += covered.polygonsCut;
            notes_.coveredArea += noteCut(covered.polygonsCut, covered.areaLeftOut,
                                          "where a smaller one (or an equal, earlier one) lies in their plane facing "
                                          "the same way",
                                          "under them left out");
        }
        // After the duplicates: a copy in place of a solid is inside nothing.
        const BuriedParts buried = cutBuriedParts(polygons, cut, solids);
        if (buried.polygonsCut > 0) {
            notes_.buriedPolygons += buried.polygonsCut;
            notes_.buriedArea += noteCut(buried.polygonsCut, buried.areaLeftOut, "where they pass into closed solids",
                                         "inside them left out, neither lit nor drawn");
        }
        // No split leaves a side narrower than two elements at the default
        // area threshold (of the whole scene: a room's may be finer).
        double area = 0.0;
        for (const std::vector<Polygon>& object : polygons)
            for (const Polygon& p : object) area += p.area();
        const std::size_t splitAtContact =
            splitAtContacts(polygons, cut, 2.0 * std::sqrt(kDefaultMinAreaShare * area), emits);
        notes_.contactPolygons += splitAtContact;
        if (splitAtContact > 0)
            note(std::to_string(splitAtContact) +
                 " polygon(s) of static objects split along where another object stands on them or passes "
                 "through them");

        Scene scene;
        scene.fileOrigin = fileOrigin;
        scene.materials = std::move(materials_);
        scene.textures = std::move(textures_);
        scene.camera = camera_;
        scene.lights = std::move(lights_);
        for (std::size_t i = 0; i < pending_.size(); ++i) {
            if (polygons[i].empty()) {
                note(pending_[i].item +
                     (duplicates[i] > 0          ? ": every polygon repeats an earlier one in place, not imported as an object"
                      : covered.areaLeftOut[i] > 0 && buried.areaLeftOut[i] == 0
                          ? ": every polygon is covered by others lying in its plane, not imported as an object"
                      : buried.areaLeftOut[i] > 0 ? ": every polygon lies inside closed solids, not imported as an object"
                                                  : ": no polygons, not imported as an object"));
                continue;
            }
            Object object = pending_[i].object;
            object.cutArea = covered.areaLeftOut[i] + buried.areaLeftOut[i];
            object.firstPolygon = static_cast<std::uint32_t>(scene.polygons.size());
            object.polygonCount = static_cast<std::uint32_t>(polygons[i].size());
            const auto objectIndex = static_cast<std::uint32_t>(scene.objects.size());
            for (Polygon& p : polygons[i]) {
                p.object = objectIndex;
                scene.polygons.push_back(p);
            }
            scene.objects.push_back(std::move(object));
        }
        if (scene.polygons.empty())
            fail("scene", dropped > 0 ? "contains no polygons: all " + std::to_string(dropped) +
                                            " triangles are degenerate (area under 1e-12 of their longest edge squared)"
                                      : "contains no polygons");
        return scene;
    }

    // Drops every polygon that repeats an earlier one (in object order, then
    // polygon order) in place and facing the same way: the same vertex
    // count, and each vertex within `tolerance` of the other's after a
    // cyclic shift. Reversed order faces the other way and is kept (a
    // zero-thickness slab). Returns the count dropped per object; fills the
    // notes.
    //
    // Linear time: kept polygons are hashed by their vertex mean on a grid of
    // cells much larger than the tolerance. A repeat's mean lies within the
    // tolerance of the original's, so only the cells that reach, usually
    // one, are searched.
    std::vector<std::size_t> dropDuplicates(std::vector<std::vector<Polygon>>& polygons, double tolerance) {
        std::vector<std::size_t> droppedPer(polygons.size(), 0);
        double largest = 0.0;
        for (const auto& list : polygons)
            for (const Polygon& p : list)
                for (int k = 0; k < p.vertexCount; ++k)
                    largest = std::max({largest, std::abs(p.vertices[k].x), std::abs(p.vertices[k].y),
                                        std::abs(p.vertices[k].z)});
        // 1024 tolerances wide, and coarse enough that cell indices stay far
        // inside 64 bits (at most 2^40 cells across the largest coordinate).
        const double cell = std::max({1024.0 * tolerance, largest * 0x1p-40, std::numeric_limits<double>::min()});
        // How far a repeat's vertex mean can be from the original's: the
        // tolerance, and the rounding of sums taken in another vertex order.
        const double reach = tolerance + 16.0 * std::numeric_limits<double>::epsilon() * largest;
        const auto meanOf = [](const Polygon& p) {
            glm::dvec3 sum(0.0);
            for (int k = 0; k < p.vertexCount; ++k) sum += p.vertices[k];
            return sum / static_cast<double>(p.vertexCount);
        };
        const auto cellIndex = [cell](double x) { return static_cast<std::int64_t>(std::floor(x / cell)); };
        const auto same = [tolerance](const Polygon& a, const Polygon& b) {
            if (a.vertexCount != b.vertexCount) return false;
            const int n = a.vertexCount;
            for (int shift = 0; shift < n; ++shift) {
                bool all = true;
                for (int k = 0; k < n && all; ++k)
                    all = glm::length(a.vertices[k] - b.vertices[(k + shift) % n]) <= tolerance;
                if (all) return true;
            }
            return false;
        };

        struct Kept {
            std::uint32_t object, index;
        };
        std::unordered_map<CellKey, std::vector<Kept>, CellKeyHash> kept;
        std::size_t count = 0;
        for (const auto& list : polygons) count += list.size();
        kept.reserve(count);
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> pairIndex;  // (kept, dropped) -> notes
        for (std::uint32_t o = 0; o < polygons.size(); ++o) {
            std::vector<Polygon> keep;
            // The object of the earlier polygon that `p` repeats, if any: one
            // in the cells its mean can reach.
            const auto findOriginal = [&](const Polygon& p, const glm::dvec3& mean) -> std::optional<std::uint32_t> {
                for (std::int64_t x = cellIndex(mean.x - reach); x <= cellIndex(mean.x + reach); ++x)
                    for (std::int64_t y = cellIndex(mean.y - reach); y <= cellIndex(mean.y + reach); ++y)
                        for (std::int64_t z = cellIndex(mean.z - reach); z <= cellIndex(mean.z + reach); ++z) {
                            const auto found = kept.find(CellKey{x, y, z});
                            if (found == kept.end()) continue;
                            for (const Kept& k : found->second)
                                if (same(k.object == o ? keep[k.index] : polygons[k.object][k.index], p))
                                    return k.object;
                        }
                return std::nullopt;
            };
            for (const Polygon& p : polygons[o]) {
                const glm::dvec3 mean = meanOf(p);
                const std::optional<std::uint32_t> original = findOriginal(p, mean);
                if (!original) {
                    kept[CellKey{cellIndex(mean.x), cellIndex(mean.y), cellIndex(mean.z)}].push_back(
                        {o, static_cast<std::uint32_t>(keep.size())});
                    keep.push_back(p);
                    continue;
                }
                ++droppedPer[o];
                const auto [at, added] = pairIndex.try_emplace({*original, o}, notes_.duplicates.size());
                if (added)
                    notes_.duplicates.push_back(
                        {pending_[*original].object.name, pending_[o].object.name, 0});
                ++notes_.duplicates[at->second].count;
            }
            polygons[o] = std::move(keep);
        }
        std::size_t total = 0;
        for (std::size_t n : droppedPer) total += n;
        notes_.duplicatePolygons += total;
        if (total > 0)
            note(std::to_string(total) + " duplicate polygon(s) dropped (the same vertices, facing the same way, as an "
                                         "earlier polygon) between " +
                 std::to_string(notes_.duplicates.size()) + " pair(s) of objects");
        return droppedPer;
    }

    // `backs`: doubleSided materials give their polygons back faces.
    void appendPolygons(std::vector<WorldTriangle> tris, std::uint32_t object,
                        std::vector<Polygon>& out, bool backs) {
        const auto emit = [&](Polygon p) {
            out.push_back(p);
            if (backs && doubleSided_.count(p.material)) {
                // Both faces reflect: the back is a polygon of its own, the
                // same vertices in reverse order (a zero-thickness slab,
                // which visibility separates), lit and drawn from its side.
                std::reverse(p.vertices.begin(), p.vertices.begin() + p.vertexCount);
                std::reverse(p.uv.begin(), p.uv.begin() + p.vertexCount);
                out.push_back(p);
                ++backFaces_;
            }
        };
        const std::size_t before = tris.size();
        for (const MergedRegion& r : mergeCoplanarRegions(tris, materials_)) {
            Polygon p;
            p.material = r.material;
            p.object = object;
            p.vertexCount = r.count;
            p.vertices = r.corners;
            emit(p);
        }
        notes_.mergedRegionTriangles += before - tris.size();
        for (std::size_t i = 0; i < tris.size();) {
            Polygon p;
            p.material = tris[i].material;
            p.object = object;
            const auto quad = i + 1 < tris.size()
                                  ? mergeToQuad(tris[i], tris[i + 1], materials_[tris[i].material].texture >= 0)
                                  : std::nullopt;
            if (quad) {
                p.vertexCount = 4;
                p.vertices = quad->v;
                p.uv = quad->uv;
                ++notes_.mergedQuads;
                i += 2;
            } else {
                p.vertexCount = 3;
                p.vertices = {tris[i].v[0], tris[i].v[1], tris[i].v[2], glm::dvec3(0.0)};
                p.uv = {tris[i].uv[0], tris[i].uv[1], tris[i].uv[2], glm::vec2(0.0f)};
                i += 1;
            }
            emit(p);
        }
    }

    std::string path_;
    ImportNotes& notes_;
    tinygltf::Model model_;
    std::vector<bool> visited_;
    std::set<std::string> usedNames_;
    std::vector<PendingObject> pending_;
    std::vector<Material> materials_;
    std::map<int, std::uint32_t> materialMap_;
    std::optional<std::uint32_t> defaultMaterial_;
    std::set<std::uint32_t> doubleSided_;  // scene material indices
    std::map<std::uint32_t, std::string> alphaMode_;  // scene material indices not OPAQUE: their alphaMode
    std::size_t backFaces_ = 0;
    // How far from their nodes' origins the stored positions lie, in world
    // units: their float32 rounding is relative to that (bringNearOrigin).
    double storedReach_ = 0.0;
    std::map<int, std::optional<std::uint32_t>> textureMap_;  // glTF texture -> Scene::textures
    std::vector<std::shared_ptr<const Texture>> textures_;
    std::map<std::uint32_t, std::uint32_t> untextured_;  // material -> its copy without texture
    std::optional<Camera> camera_;
    std::vector<PunctualLight> lights_;
    std::vector<std::uint32_t> nodePath_;  // the nodes from the root to the one visited
};

}  // namespace

Scene loadGltf(const std::string& path, ImportNotes* notes) {
    ImportNotes local;
    Importer importer(path, notes != nullptr ? *notes : local);
    return importer.run();
}

}  // namespace rad
