#pragma once
// Visibility by ray casting with Embree 3, split in two layers (paper sec. 3.4): occlusion by
// the static scene is computed once per link, occlusion by the dynamic objects again each frame.
// The dynamic objects are instances, moved by their transforms.

#include <cstddef>
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
    // objects. For Dynamic, the polygons become the layer's only instance, where they are now.
    // Not to be called, nor any of the instance calls below, while queries run.
    void setLayer(Layer layer, const Scene& scene, std::span<const std::uint32_t> polygonIds);

    // The dynamic layer holds one Embree instance per dynamic object: its
    // triangles are built once, in the pose the polygons have when added,
    // and a move only sets the instance's transform (no rebuild). Returns
    // the instance's index. Queries see adds and moves after commitInstances().
    std::size_t addInstance(const Scene& scene, std::span<const std::uint32_t> polygonIds);
    // Places an instance by a rigid motion (rotation and translation) from
    // the pose it was added in.
    void moveInstance(std::size_t instance, const glm::dmat4& fromAdded);
    void commitInstances();
    void clearInstances();
    // The region the layers live in (the scene's bounds): set before the
    // layers, it makes the float ray casting independent of the scene's scale.
    // With `detail` (Scene::detailCentre and detailBounds), Embree's
    // coordinates are taken from that centre and in that box's size, so that
    // they are as precise as the scene's detail wherever its bounds reach
    // (Embree's own tolerances are absolute: in a frame a stray polygon made
    // 100 km wide they were centimetres); the bounds' otherwise.
    void setFrame(const Aabb& bounds);
    void setFrame(const Aabb& bounds, const glm::dvec3& detailCentre, const Aabb& detail);
    // How far `p` lies from the frame's centre, in the frame's size (its
    // largest extent), along the farthest axis.
    double framesFromCentre(const glm::dvec3& p) const;
    double frameSize() const;
    // The distance under which Embree's single precision may not tell two
    // points near `p` apart, with a margin: a millionth of p's distance from
    // the frame's origin (16 of a float's steps there).
    double resolutionAt(const glm::dvec3& p) const;

    // A visibility ray: a segment between two points on surfaces, and the
    // input polygons they lie on (kNoPolygon when not on one).
    struct Segment {
        glm::dvec3 from{0.0}, to{0.0};
        std::uint32_t fromPolygon = kNoPolygon, toPolygon = kNoPolygon;
    };
    static constexpr std::uint32_t kNoPolygon = 0xffffffffu;
    static constexpr std::size_t kMaxSegments = 16;  // one Embree packet

    // Which of the segments (at most kMaxSegments) the layer blocks: bit i set
    // when segment i is blocked. Thread-safe.
    //
    // A polygon blocks a segment when the segment crosses it strictly between
    // its ends, farther than the coincidence tolerance from both: a fixed
    // fraction (coincidenceOfSize) of the larger of the polygons the ends lie
    // on, so that it means the same at every scale and in every part of a
    // scene (of the frame's size when they lie on none). The polygons the ends lie on never block it. Near an end, a
    // polygon coincident with the end's polygon (its plane within the
    // tolerance of the end point) and facing the same way stands in front of
    // it exactly when its area is smaller (equal: when its index is lower):
    // of a stack of coincident surfaces (overlapping coplanar slabs, a rug
    // laid at a floor's height) one is seen, so a receiver sees their union
    // and not their sum, and what lies on a surface is seen, not the surface
    // (as the import cuts a static surface under a smaller one, scene/Covered.h). Embree finds candidates in float;
    // each is placed on the segment in double precision.
    std::uint16_t blocked(Layer layer, std::span<const Segment> segments) const;

    // Distance under which two surfaces count as coincident in the frame as
    // a whole (for picking, and for where light goes): a fixed fraction of
    // the frame's size, so that it means the same at every scale.
    double coincidenceTolerance() const;

    // Nearest hit along a ray in either layer (for picking, and for where light goes): polygon
    // id, the ray parameter t (hit = origin + t * direction, so a distance when direction is
    // unit), with 0 <= t <= tmax, and whether the ray meets the polygon's front. Of coincident
    // polygons at the nearest hit, a front is preferred to a back (a zero-thickness slab seen
    // from either side shows the face on that side).
    struct Hit {
        std::uint32_t polygon;
        double t;
        bool front;
    };
    std::optional<Hit> intersect(const glm::dvec3& origin, const glm::dvec3& direction,
                                 double tmax) const;

    // The coincidence tolerance as a fraction of a size (see blocked()),
    // and a floor of it relative to the largest absolute coordinate (double
    // rounding of the end points far from the origin).
    static constexpr double coincidenceOfSize = 1e-6;
    static constexpr double coincidenceOfMagnitude = 1e-9;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace rad
