#include "geometry/RayCaster.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace rad {

namespace {

const char* errorName(RTCError e) {
    switch (e) {
        case RTC_ERROR_NONE:
            return "none";
        case RTC_ERROR_UNKNOWN:
            return "unknown error";
        case RTC_ERROR_INVALID_ARGUMENT:
            return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION:
            return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY:
            return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU:
            return "unsupported CPU";
        case RTC_ERROR_CANCELLED:
            return "cancelled";
    }
    return "unrecognised error";
}

void throwOnError(RTCDevice device, const char* what) {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree: ") + errorName(e) + " while " + what);
}

struct SceneRelease {
    void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using ScenePtr = std::unique_ptr<RTCSceneTy, SceneRelease>;

double maxAbs(const glm::dvec3& p) {
    return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

// Embree finds candidate hits in float; each candidate of an occlusion query is then checked
// here in double precision against the triangle's plane, so that hits at the segment's own end
// points (which lie on surfaces) are rejected however grazing the segment is. An Embree 3
// intersect context extended by the query's data (the documented way to pass per-ray data to a
// filter function; the base must come first).
struct SegmentContext {
    RTCIntersectContext base;
    const std::vector<glm::dvec4>* planes;  // per triangle: unnormalised normal n, and n . v0
    glm::dvec3 a;                           // segment start
    glm::dvec3 d;                           // segment end minus start
    double tMin, tMax;                      // accepted window of the segment parameter
};

void rejectHitsAtEnds(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const SegmentContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const glm::dvec4& plane = (*ctx->planes)[RTCHitN_primID(args->hit, args->N, i)];
        const glm::dvec3 n(plane);
        const double denom = glm::dot(n, ctx->d);
        // A segment in the triangle's plane (denom 0) is not blocked by it: such a segment
        // joins two points of one surface and carries no energy anyway.
        const double t = (plane.w - glm::dot(n, ctx->a)) / denom;
        if (!(t > ctx->tMin && t < ctx->tMax)) args->valid[i] = 0;
    }
}

}  // namespace

struct RayCaster::Impl {
    struct LayerData {
        ScenePtr scene;                           // null when the layer is empty
        std::vector<std::uint32_t> polygonOfTri;  // Embree primID -> scene polygon id
        std::vector<glm::dvec4> planes;           // Embree primID -> plane in double
        double magnitude = 0.0;                   // largest absolute vertex coordinate
    };

    RTCDevice device = nullptr;
    LayerData layers[2];
    // Embree works in float with some absolute tolerances; it sees the scene
    // moved to the origin and scaled to unit size, so that a millimetre and a
    // kilometre version of one scene give the same answers. The double
    // precision filter works in world coordinates.
    glm::dvec3 origin{0.0};
    double scale = 1.0;
    glm::vec3 toEmbree(const glm::dvec3& p) const { return glm::vec3((p - origin) * scale); }

    Impl() {
        device = rtcNewDevice(nullptr);
        if (!device) throwOnError(nullptr, "creating the device");
        if (rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED) == 0) {
            rtcReleaseDevice(device);
            throw std::runtime_error("Embree: this build has no filter function support");
        }
    }
    ~Impl() {
        for (LayerData& l : layers) l.scene.reset();  // scenes before their device
        rtcReleaseDevice(device);
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    const LayerData& layer(Layer l) const { return layers[l == Layer::Static ? 0 : 1]; }
    LayerData& layer(Layer l) { return layers[l == Layer::Static ? 0 : 1]; }

    // True when a hit lies strictly inside the segment a -> b, away from both ends.
    bool blocked(const LayerData& l, const glm::dvec3& a, const glm::dvec3& b) const {
        if (!l.scene) return false;
        const glm::dvec3 d = b - a;
        const double len = glm::length(d);
        const double magnitude = std::max({l.magnitude, maxAbs(a), maxAbs(b)});
        const double margin = std::max(endMarginOfLength * len, endMarginOfMagnitude * magnitude);
        if (!(len > 2.0 * margin)) return false;  // ends closer than the noise: nothing between
        const double tMargin = margin / len;

        SegmentContext context;
        rtcInitIntersectContext(&context.base);
        context.planes = &l.planes;
        context.a = a;
        context.d = d;
        context.tMin = tMargin;
        context.tMax = 1.0 - tMargin;
        RTCRay ray{};
        const glm::vec3 org = toEmbree(a);
        const glm::vec3 dir(d * scale);
        ray.org_x = org.x;
        ray.org_y = org.y;
        ray.org_z = org.z;
        // Unnormalised direction: t in [0, 1] spans the segment. The float window is the whole
        // segment; the filter applies the end margins in double.
        ray.dir_x = dir.x;
        ray.dir_y = dir.y;
        ray.dir_z = dir.z;
        ray.tnear = 0.0f;
        ray.tfar = 1.0f;
        ray.mask = std::numeric_limits<unsigned>::max();
        ray.time = 0.0f;
        ray.flags = 0;
        rtcOccluded1(l.scene.get(), &context.base, &ray);
        // Embree marks an occluded ray by setting tfar to -inf.
        return ray.tfar < 0.0f;
    }
};

RayCaster::RayCaster() : impl_(std::make_unique<Impl>()) {}
RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

void RayCaster::setFrame(const Aabb& bounds) {
    if (bounds.empty()) return;
    const glm::dvec3 e = bounds.extent();
    const double size = std::max({e.x, e.y, e.z});
    impl_->origin = bounds.center();
    impl_->scale = size > 0.0 ? 1.0 / size : 1.0;
}

void RayCaster::setLayer(Layer layer, const Scene& scene,
                         std::span<const std::uint32_t> polygonIds) {
    Impl::LayerData fresh;
    std::vector<glm::vec3> vertices;
    std::vector<std::uint32_t> indices;
    for (std::uint32_t id : polygonIds) {
        if (id >= scene.polygons.size())
            throw std::out_of_range("RayCaster::setLayer: polygon id " + std::to_string(id) +
                                    " >= " + std::to_string(scene.polygons.size()));
        const Polygon& p = scene.polygons[id];
        if (p.vertexCount < 3 || p.vertexCount > 4) continue;
        const auto base = static_cast<std::uint32_t>(vertices.size());
        for (int k = 0; k < p.vertexCount; ++k) {
            vertices.push_back(impl_->toEmbree(p.vertices[k]));
            fresh.magnitude = std::max(fresh.magnitude, maxAbs(p.vertices[k]));
        }
        // Fan triangulation of a convex polygon.
        for (int k = 1; k + 1 < p.vertexCount; ++k) {
            indices.insert(indices.end(), {base, base + k, base + k + 1});
            fresh.polygonOfTri.push_back(id);
            const glm::dvec3 n =
                glm::cross(p.vertices[k] - p.vertices[0], p.vertices[k + 1] - p.vertices[0]);
            fresh.planes.emplace_back(n, glm::dot(n, p.vertices[0]));
        }
    }

    if (!fresh.polygonOfTri.empty()) {
        RTCDevice device = impl_->device;
        fresh.scene.reset(rtcNewScene(device));
        throwOnError(device, "creating a scene");
        // Robust traversal: no missed hits on shared edges, which would let light leak through
        // the seams of a triangulated blocker.
        rtcSetSceneFlags(fresh.scene.get(), RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(fresh.scene.get(), layer == Layer::Static
                                                       ? RTC_BUILD_QUALITY_HIGH
                                                       : RTC_BUILD_QUALITY_MEDIUM);
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        throwOnError(device, "creating the triangle geometry");
        auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               vertices.size()));
        auto* ib = static_cast<std::uint32_t*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(std::uint32_t), fresh.polygonOfTri.size()));
        if (!vb || !ib) {
            rtcReleaseGeometry(geometry);
            throwOnError(device, "allocating geometry buffers");
            throw std::runtime_error("Embree: could not allocate geometry buffers");
        }
        for (std::size_t i = 0; i < vertices.size(); ++i) {
            vb[3 * i + 0] = vertices[i].x;
            vb[3 * i + 1] = vertices[i].y;
            vb[3 * i + 2] = vertices[i].z;
        }
        std::copy(indices.begin(), indices.end(), ib);
        rtcSetGeometryOccludedFilterFunction(geometry, rejectHitsAtEnds);
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(fresh.scene.get(), geometry);
        rtcReleaseGeometry(geometry);  // the scene holds it now
        rtcCommitScene(fresh.scene.get());
        throwOnError(device, "building the scene");
    }
    impl_->layer(layer) = std::move(fresh);
}

double RayCaster::unoccludedFraction(Layer layer, std::span<const glm::dvec3> from,
                                     std::span<const glm::dvec3> to) const {
    const std::size_t n = std::min(from.size(), to.size());
    if (n == 0) return 1.0;
    const Impl::LayerData& l = impl_->layer(layer);
    if (!l.scene) return 1.0;
    std::size_t open = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (!impl_->blocked(l, from[i], to[i])) ++open;
    return static_cast<double>(open) / static_cast<double>(n);
}

bool RayCaster::occluded(Layer layer, const glm::dvec3& a, const glm::dvec3& b) const {
    return impl_->blocked(impl_->layer(layer), a, b);
}

std::optional<RayCaster::Hit> RayCaster::intersect(const glm::dvec3& origin,
                                                   const glm::dvec3& direction, double tmax) const {
    if (!(tmax > 0.0) || direction == glm::dvec3(0.0)) return std::nullopt;
    std::optional<Hit> best;
    for (const Impl::LayerData& l : impl_->layers) {
        if (!l.scene) continue;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit rh{};
        // Same t as in world space: origin and direction both scaled.
        const glm::vec3 org = impl_->toEmbree(origin);
        const glm::vec3 dir(direction * impl_->scale);
        rh.ray.org_x = org.x;
        rh.ray.org_y = org.y;
        rh.ray.org_z = org.z;
        rh.ray.dir_x = dir.x;
        rh.ray.dir_y = dir.y;
        rh.ray.dir_z = dir.z;
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = static_cast<float>(std::min(tmax, double(std::numeric_limits<float>::max())));
        rh.ray.mask = std::numeric_limits<unsigned>::max();
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(l.scene.get(), &context, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
        const double t = rh.ray.tfar;
        if (!best || t < best->t) best = Hit{l.polygonOfTri.at(rh.hit.primID), t};
    }
    return best;
}

}  // namespace rad
