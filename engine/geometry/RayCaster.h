#pragma once
// Visibility by ray casting with Embree 3, split in two layers (paper sec. 3.4): occlusion by
// the static scene is computed once per link, occlusion by the dynamic object again each frame.

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <span>

#include "radiosity/Scene.h"

namespace rad {

enum class Layer { Static, Dynamic };  // two-part visibility (paper sec. 3.4)

class RayCaster {
  public:
    RayCaster();  // owns an RTCDevice; throws std::runtime_error when Embree cannot start
    ~RayCaster();
    RayCaster(RayCaster&&) noexcept;
    RayCaster& operator=(RayCaster&&) noexcept;
    RayCaster(const RayCaster&) = delete;
    RayCaster& operator=(const RayCaster&) = delete;

    // Replace the geometry of a layer: the given polygons of `scene` (ids index scene.polygons,
    // std::out_of_range otherwise), triangulated. Static is built once per choice of dynamic
    // object; Dynamic again after each move. Not to be called while queries run.
    void setLayer(Layer layer, const Scene& scene, std::span<const std::uint32_t> polygonIds);
    // The region the layers live in (the scene's bounds): set before the
    // layers, it makes the float ray casting independent of the scene's scale.
    void setFrame(const Aabb& bounds);

    // Fraction of the segments from[i] -> to[i] that are NOT blocked in the layer (1 for an empty
    // set). Hits within a small margin of either end are ignored (the segment ends lie on
    // surfaces); Embree finds candidates in float, each is then placed on the segment in double
    // and kept only if it is farther than the margin from both ends. Thread-safe.
    double unoccludedFraction(Layer layer, std::span<const glm::dvec3> from,
                              std::span<const glm::dvec3> to) const;

    // Nearest hit along a ray in either layer (for picking): polygon id and the ray parameter t
    // (hit = origin + t * direction, so a distance when direction is unit), with 0 <= t <= tmax.
    struct Hit {
        std::uint32_t polygon;
        double t;
    };
    std::optional<Hit> intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                 double tmax) const;

    // End margins (see unoccludedFraction), applied in double precision to Embree's candidate
    // hits: a fraction of the segment length (tolerates sample points slightly off slightly
    // non-planar polygons), and a fraction of the largest absolute coordinate of the layer and
    // the segment (double rounding of the end points; matters only for very short segments).
    static constexpr double endMarginOfLength = 1e-5;
    static constexpr double endMarginOfMagnitude = 1e-9;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace rad
