#pragma once
// What the engine hands to a renderer or an exporter: an immutable triangle
// mesh with one linear RGB value per vertex (radiosity B, or a material
// preview), plus optional overlay lines. Single precision: it is for display.
// And fixed sample points of a solution, for comparing two solutions of the
// same scene.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace rad {

struct Texture;

struct MeshSnapshot {
    // positions and linePositions are relative to this point (world
    // coordinates, double precision): a float is 6 cm coarse 1000 km from
    // the world's origin, and as fine as the scene is small near its own.
    // Renderers add it back in double (MeshRenderer folds it into the
    // view-projection). 0 for a scene around the origin (displayOrigin).
    glm::dvec3 origin{0.0};
    // Scene::fileOrigin: exported meshes are moved back by it.
    glm::dvec3 fileOrigin{0.0};
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec3> colors;  // linear RGB, same units as B
    std::vector<std::uint32_t> indices;  // triangles, counter-clockwise front faces

    // Textured display. `colors` is the radiosity the solution computed,
    // with each element's mean reflectance; a textured surface shows its
    // detail by drawing colors * texel * texelScale, where texel is the
    // linear RGB of textures[textureLayer] at uv (bilinear, repeated): the
    // irradiance carried by the vertex colour, times the reflectance at the
    // texel. textureLayer -1: untextured, drawn as colors. All three are
    // either empty (nothing textured) or one per vertex. Emitters are never
    // textured.
    std::vector<glm::vec2> uvs;
    std::vector<std::int32_t> textureLayer;
    std::vector<glm::vec3> texelScale;
    std::vector<std::shared_ptr<const Texture>> textures;  // Scene::textures

    // Overlay line segments: pairs of points, one colour per point.
    std::vector<glm::vec3> linePositions;
    std::vector<glm::vec3> lineColors;
    // The modified links the last update recorded, and how many of them are
    // drawn (every k-th, at most SnapshotOverlays::maxLinks).
    std::size_t modifiedLinks = 0, modifiedLinksShown = 0;
};

// The mesh without what holds room for growth in a frame's mesh: its
// degenerate triangles (three equal indices) and the vertices no triangle
// uses, the rest in order. A frame's mesh keeps slots for polygons to grow
// in (the engine's snapshot cache); a mesh made from scratch has none.
MeshSnapshot compactMesh(const MeshSnapshot& mesh);

struct SnapshotOverlays {
    bool modifiedLinks = false;
    bool changedElements = false;
    // Modified links drawn at most, spread evenly over those recorded: each
    // runs across the scene, and a software rasteriser (lavapipe) takes about
    // half a second for 30,000 of them (README, "Known limits").
    std::size_t maxLinks = 5'000;
};

struct Scene;

// The origin of a scene's snapshots: 0 for a scene whose bounds hold the
// world's origin; else where its detail is (Scene::detailCentre) rounded to
// a multiple of the power of two at or above the size of its detail
// (Scene::detailBounds).
glm::dvec3 displayOrigin(const Scene& scene);

// Material-preview colours (reflectance + emission) per polygon, flat.
MeshSnapshot makePreviewSnapshot(const Scene& scene);

// Leaf radiosity at 16 fixed points of every input polygon: a 4 x 4 grid of
// cell centres on quads, the centroids of the 16 sub-triangles of a 4-level
// split on triangles.
struct RadiositySamples {
    std::vector<double> luminance;       // per sample: luminance of the leaf's B there
    std::vector<double> weight;          // per sample: the area it stands for
    std::vector<std::uint32_t> object;   // per sample: its polygon's object (Scene::objects); may be empty
    std::vector<std::uint32_t> polygon;  // per sample: its polygon (Scene::polygons); may be empty
};

// An object is dark when its mean luminance in the reference is below this
// share of the scene's: its own normalisation would turn noise into large
// errors, so it is left out of SolutionError::worstObjectRms.
inline constexpr double kDarkObjectShare = 1e-3;

// One object's samples compared, normalised by the object's own mean, so that
// a dim room behind a bright corridor shows its error (issue 12).
struct ObjectError {
    std::uint32_t object = 0;  // index in Scene::objects
    double mean = 0.0;  // area-weighted mean luminance of the reference over the object's samples
    // Area-weighted RMS difference and largest absolute difference, both over
    // `mean`. An object black in the reference (mean 0) has 0 where the
    // solution is black too, and infinity where it is not.
    double rms = 0.0;
    double max = 0.0;
    bool dark = false;  // mean < kDarkObjectShare times the scene's mean
};

struct SolutionError {
    double rms = 0.0;  // area-weighted RMS difference / area-weighted mean of the reference
    double max = 0.0;  // largest absolute difference / that same mean
    // Per object that has samples, in object order; empty when the samples
    // carry no objects.
    std::vector<ObjectError> objects;
    double worstObjectRms = 0.0;  // the largest ObjectError::rms among objects not dark; 0 if none
};
// Throws std::invalid_argument when the two sets are not of the same scene
// (different sizes, or different objects per sample).
SolutionError compareSamples(const RadiositySamples& solution, const RadiositySamples& reference);

}  // namespace rad
