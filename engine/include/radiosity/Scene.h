#pragma once
// The scene model: what a glTF file becomes once imported. Everything is in
// world space, metres, Y up, double precision.

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace rad {

// One-line error about a scene, naming the file and the offending item.
struct SceneError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Luminance of linear RGB (Rec. 709): the scalar of power balances, error
// estimates and refinement decisions.
inline double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// A base colour texture: sRGB-encoded RGBA, 8 bits a channel, rows from the
// top of the image. Texture coordinates follow glTF: (0, 0) is the first
// texel of the first row, and u runs along a row.
struct Texture {
    enum class Wrap : std::uint8_t { Repeat, Clamp, Mirror };
    std::string name;
    std::uint32_t width = 0, height = 0;
    std::vector<std::uint8_t> srgba;  // width * height * 4
    Wrap wrapU = Wrap::Repeat, wrapV = Wrap::Repeat;

    // Linear RGB of the texel under uv, wrapped as the glTF sampler says
    // (no filtering: element reflectances are means of whole texels).
    glm::dvec3 texel(const glm::dvec2& uv) const;
    glm::dvec3 mean() const;  // linear RGB, over the whole image
};

// The brightest emission accepted, per channel of E: far above any real
// light (the sun's surface emits about 6e7 W/m^2), and far enough below the
// double range that power summed over a scene, and squared in the error
// estimate, stays finite. Files, edits and scripts above it are refused.
inline constexpr double kMaxEmission = 1e12;

struct Material {
    std::string name;
    glm::dvec3 reflectance{0.0};  // rho, each channel in [0,1)
    glm::dvec3 emission{0.0};     // E, each channel in [0, kMaxEmission]
    // A base colour texture (index into Scene::textures), or -1. Then
    // `reflectance` is the mean over the whole texture (glTF's
    // baseColorFactor times the texture's mean), and each surface element
    // reflects reflectance * (mean of the texels under it) / textureMean.
    std::int32_t texture = -1;
    glm::dvec3 textureMean{1.0};  // linear RGB mean of the texture's texels
};

// A planar convex polygon: a triangle or a quad. Counter-clockwise seen from
// the front, which is the only side that emits and reflects.
struct Polygon {
    std::array<glm::dvec3, 4> vertices{};
    std::uint8_t vertexCount = 3;
    std::uint32_t material = 0;
    std::uint32_t object = 0;
    // Texture coordinates per vertex (glTF TEXCOORD of the material's
    // texture); zero when the material has no texture.
    std::array<glm::vec2, 4> uv{};
    // Bit k: the edge from vertex k to k + 1 lies where a sheet stands on
    // the polygon (scene/Contacts.h). The display shares no values across
    // it: the two sides are lit apart.
    std::uint8_t creases = 0;

    glm::dvec3 normal() const;  // unit, from the winding
    double area() const;
    glm::dvec3 centroid() const;  // of the area
};

struct Aabb {
    glm::dvec3 lo{std::numeric_limits<double>::infinity()};
    glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
    void extend(const glm::dvec3& p) { lo = glm::min(lo, p); hi = glm::max(hi, p); }
    void extend(const Aabb& b) { lo = glm::min(lo, b.lo); hi = glm::max(hi, b.hi); }
    bool empty() const { return lo.x > hi.x; }
    glm::dvec3 center() const { return 0.5 * (lo + hi); }
    glm::dvec3 extent() const { return hi - lo; }
};

// One object per named glTF node that carries a mesh. Its polygons are the
// contiguous range [firstPolygon, firstPolygon + polygonCount) of Scene::polygons.
struct Object {
    std::string name;
    glm::dmat4 worldFromLocal{1.0};
    bool dynamic = false;  // extras.dynamic: a candidate for the dynamic object
    std::uint32_t firstPolygon = 0;
    std::uint32_t polygonCount = 0;
    // The glTF nodes from a scene root down to the object's node (indices
    // into the file's nodes): objects under one node share its prefix, so a
    // selection can be widened to a parent's whole subtree.
    std::vector<std::uint32_t> nodePath;
    // The area the import left out of it, covered by or buried in static
    // objects (scene/Covered.h, scene/Buried.h): moved, it shows the holes.
    double cutArea = 0.0;
};

// A KHR_lights_punctual light: a point that sends radiant intensity
// I(dir) = intensity * falloff(dir), in the scene's units of power per
// steradian. A surface at distance r whose normal makes angle theta with the
// direction to the light receives the irradiance I cos(theta) / r^2.
struct PunctualLight {
    enum class Type : std::uint8_t { Point, Spot };
    std::string name;
    Type type = Type::Point;
    glm::dvec3 position{0.0};
    glm::dvec3 direction{0.0, 0.0, -1.0};  // spot axis (the node's -Z), unit
    glm::dvec3 intensity{0.0};             // colour times intensity, each channel >= 0
    double innerCone = 0.0;                // spot, radians, 0 <= inner < outer <= pi/2
    double outerCone = 0.7853981633974483;
    glm::dmat4 worldFromLocal{1.0};  // the node's world transform (moves replace it)
    // The glTF nodes from a scene root down to the light's node, as
    // Object::nodePath: widening a selection to a node takes its lights too.
    std::vector<std::uint32_t> nodePath;
    // The object whose subtree holds the light's node (a lamp marked
    // extras.object, its bulb a child node): the light moves with it. Empty
    // for a light of its own.
    std::string object;

    // glTF's cone falloff toward `toward` (unit, from the light): 1 inside
    // the inner cone, 0 outside the outer one, and between them the square
    // of the linear ramp in cos(angle), as the extension's reference code.
    // 1 everywhere for a point light.
    double falloff(const glm::dvec3& toward) const;
    // The same falloff with the cone's cosines computed once, for many
    // directions (std::cos at each call was 5% of a spot-lit room's frames).
    struct Cone {
        glm::dvec3 direction{0.0, 0.0, -1.0};
        double cosInner = -1.0, cosOuter = -1.0;
        bool spot = false;
        double operator()(const glm::dvec3& toward) const;
    };
    Cone cone() const;
    // The integral of the falloff over the sphere of directions: the power
    // sent is luminance(intensity) times it.
    double solidAngle() const;
    double power() const { return luminance(intensity) * solidAngle(); }
};

// A perspective camera looking down its local -Z axis.
struct Camera {
    glm::dvec3 position{0.0};
    glm::dvec3 forward{0.0, 0.0, -1.0};  // unit
    glm::dvec3 up{0.0, 1.0, 0.0};        // unit, orthogonal to forward
    double yfov = 0.7;                   // radians
    std::optional<double> aspectRatio;   // width / height, when the file gives one
    double znear = 0.01;
};

struct Scene {
    std::string sourcePath;
    std::vector<Material> materials;
    std::vector<Object> objects;
    std::vector<Polygon> polygons;
    std::vector<PunctualLight> lights;
    std::optional<Camera> camera;
    // Where this scene's origin lies in the file's coordinates. The import
    // brings a scene that its nodes' translations place far out (a
    // georeferenced site 1000 km from the file's origin) near the origin:
    // its plane tests allow for float32 rounding where a polygon lies, which
    // there would be 10 cm though its positions were stored small. The lit
    // mesh's export puts the scene back where the file had it.
    glm::dvec3 fileOrigin{0.0};
    // Shared, not copied: a scene is copied per engine and per frame's
    // reference, its images are not.
    std::vector<std::shared_ptr<const Texture>> textures;

    Aabb bounds() const;
    double area() const;  // of all polygons' front faces
    // Where the scene's detail is: per axis, the median of its polygons'
    // centroids, and the box from the 1st to the 99th percentile of them
    // (the bounds' centre and the bounds when it has no polygons). What is
    // kept in single precision is kept relative to them, so that a stray
    // polygon far away (a CAD export's leftover 100 km out) leaves the rest
    // its precision.
    glm::dvec3 detailCentre() const;
    Aabb detailBounds() const;
    Aabb objectBounds(std::uint32_t object) const;
    // Index of the object with this name, or nullopt.
    std::optional<std::uint32_t> findObject(const std::string& name) const;
    std::optional<std::uint32_t> findLight(const std::string& name) const;
    // Whether an emissive polygon or a punctual light sends any light.
    bool hasEmitter() const;
};

// Each object's box, kept while its transform stays: moving an object
// rewrites its polygons and its transform together, so only the objects
// that moved are measured again. Measuring all of them walks every polygon
// (1 ms on the building floor's 114,509), which the lit mesh's smoothing
// grid and the viewer's object list would otherwise pay every frame. For
// one scene at a time: another scene (or another object count) starts over.
class ObjectBoxes {
  public:
    const Aabb& of(const Scene& scene, std::uint32_t object);
    Aabb all(const Scene& scene);  // Scene::bounds(), from the objects' boxes

  private:
    const Scene* scene_ = nullptr;
    std::vector<Aabb> boxes_;
    std::vector<glm::dmat4> at_;  // the transform each box was measured at
};

}  // namespace rad
