#include "geometry/RayCaster.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace rad {

// The triangles of one Embree geometry: the static layer's, or one instance
// of the dynamic layer. (Outside the anonymous namespace: they are members
// of a class with linkage, and a unity build includes this file into
// another.)
struct RayCasterSceneRelease {
    void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using RayCasterScenePtr = std::unique_ptr<RTCSceneTy, RayCasterSceneRelease>;

struct RayCasterPart {
    std::vector<std::uint32_t> polygonOfTri;  // Embree primID -> scene polygon id
    std::vector<glm::dvec4> planes;           // primID -> plane in double, where it is now
    double magnitude = 0.0;                   // largest absolute vertex coordinate, where it is now
    // An instance: its own scene, and its planes and vertices in the pose
    // it was added in (the transform of a move starts from them).
    RayCasterScenePtr scene;
    std::vector<glm::dvec4> addedPlanes;
    std::vector<glm::dvec3> addedVertices;
};

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

double maxAbs(const glm::dvec3& p) {
    return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

// A segment a -> a + d in double precision: the window of its parameter in
// which any hit blocks it, the tolerance for coincidence at its ends, and the
// polygons its ends lie on.
struct PlacedSegment {
    glm::dvec3 a;
    glm::dvec3 d;
    double tMin, tMax;
    double tolerance;
    std::uint32_t fromPolygon, toPolygon;
};

// Embree finds candidate hits in float; each candidate of an occlusion query is then placed here
// in double precision against the triangle's plane (RayCaster::blocked says what blocks). An
// Embree 3 intersect context extended by the query's data (the documented way to pass per-ray
// data to a filter function; the base must come first); a ray's id indexes its segment.
struct SegmentContext {
    RTCIntersectContext base;
    const std::vector<RayCasterPart>* parts;
    const PlacedSegment* segments;
    const std::vector<std::uint32_t>* frontRank;  // per polygon (RayCaster::Impl::frontRank)
};

// The part a hit is on: an instance's (the dynamic layer), or the layer's
// only one (the static layer, whose triangles are not instanced).
const RayCasterPart& partOf(const std::vector<RayCasterPart>& parts, unsigned instance) {
    return parts[instance == RTC_INVALID_GEOMETRY_ID ? 0 : instance];
}

// Whether polygon `other`, coincident with the end polygon `end` near the end
// point p and met by the segment from the side its front faces (`facing`),
// stands in front of it: the lower rank wins (the smaller polygon, see
// RayCaster::blocked), so of coincident surfaces exactly one is seen.
bool coincidentInFront(const glm::dvec4& plane, const glm::dvec3& p, double tolerance, bool facing,
                       std::uint32_t other, std::uint32_t end, const std::vector<std::uint32_t>& rank) {
    if (end == RayCaster::kNoPolygon || !facing) return false;
    if (other < rank.size() && end < rank.size() ? rank[other] > rank[end] : other > end) return false;
    const glm::dvec3 n(plane);
    return std::abs(glm::dot(n, p) - plane.w) <= tolerance * glm::length(n);
}

// The context of a nearest-hit query: with frontOnly, hits on the back of a
// polygon are passed over.
struct PickContext {
    RTCIntersectContext base;
    const std::vector<RayCasterPart>* parts;
    glm::dvec3 direction;
    bool frontOnly;
};

void filterBacks(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const PickContext*>(args->context);
    if (!ctx->frontOnly) return;
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const RayCasterPart& part = partOf(*ctx->parts, RTCHitN_instID(args->hit, args->N, i, 0));
        const glm::dvec4& plane = part.planes[RTCHitN_primID(args->hit, args->N, i)];
        if (glm::dot(glm::dvec3(plane), ctx->direction) >= 0.0) args->valid[i] = 0;
    }
}

void filterHits(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const SegmentContext*>(args->context);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const PlacedSegment& s = ctx->segments[RTCRayN_id(args->ray, args->N, i)];
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const RayCasterPart& part = partOf(*ctx->parts, RTCHitN_instID(args->hit, args->N, i, 0));
        const std::uint32_t polygon = part.polygonOfTri[prim];
        bool blocks = false;
        if (polygon != s.fromPolygon && polygon != s.toPolygon) {
            const glm::dvec4& plane = part.planes[prim];
            const glm::dvec3 n(plane);
            const double nd = glm::dot(n, s.d);
            // A segment in the triangle's plane (nd 0) is not blocked by it:
            // such a segment joins two points of one surface and carries no
            // energy anyway.
            const double t = (plane.w - glm::dot(n, s.a)) / nd;
            if (t > s.tMin && t < s.tMax)
                blocks = true;
            else if (t >= s.tMax)  // at the receiving end: it faces the segment's start
                blocks = coincidentInFront(plane, s.a + s.d, s.tolerance, nd < 0.0, polygon, s.toPolygon, *ctx->frontRank);
            else if (t <= s.tMin)  // at the sending end: it faces the way the segment leaves
                blocks = coincidentInFront(plane, s.a, s.tolerance, nd > 0.0, polygon, s.fromPolygon, *ctx->frontRank);
        }
        if (!blocks) args->valid[i] = 0;
    }
}

}  // namespace

struct RayCaster::Impl {
    struct LayerData {
        RayCasterScenePtr scene;         // null when the layer is empty
        std::vector<RayCasterPart> parts;  // static: one; dynamic: one per instance, by its geometry id
        double magnitude = 0.0;          // largest absolute vertex coordinate
        bool instanced = false;          // the dynamic layer: its parts are instances
        // The dynamic layer's committed box in Embree's frame, grown by a
        // little: a packet whose rays all pass outside it cannot be blocked.
        glm::vec3 lower{0.0f}, upper{0.0f};
    };

    RTCDevice device = nullptr;
    LayerData layers[2];
    // Embree works in float with some absolute tolerances; it sees the scene
    // moved to the origin and scaled to unit size, so that a millimetre and a
    // kilometre version of one scene give the same answers. The double
    // precision filter works in world coordinates.
    glm::dvec3 origin{0.0};
    double scale = 1.0;
    double size = 1.0;  // the frame's largest extent
    // Per scene polygon, its place when ordered by area, smallest first
    // (ties: by index): of coincident surfaces the smaller is seen, as the
    // import cuts a larger one under a smaller one (scene/Covered.h).
    std::vector<std::uint32_t> frontRank;

    void rankPolygons(const Scene& scene) {
        std::vector<std::pair<double, std::uint32_t>> byArea;
        byArea.reserve(scene.polygons.size());
        for (std::uint32_t i = 0; i < scene.polygons.size(); ++i) byArea.emplace_back(scene.polygons[i].area(), i);
        std::sort(byArea.begin(), byArea.end());
        frontRank.resize(byArea.size());
        for (std::uint32_t k = 0; k < byArea.size(); ++k) frontRank[byArea[k].second] = k;
    }
    // Per scene polygon given to a layer: the diagonal of its box, the scale
    // of coincidence at a segment's end on it (0: not given).
    std::vector<double> extent;
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
        for (LayerData& l : layers) l = LayerData{};  // scenes before their device
        rtcReleaseDevice(device);
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    const LayerData& layer(Layer l) const { return layers[l == Layer::Static ? 0 : 1]; }
    LayerData& layer(Layer l) { return layers[l == Layer::Static ? 0 : 1]; }

    RayCasterScenePtr newScene(const char* what) {
        RayCasterScenePtr scene(rtcNewScene(device));
        throwOnError(device, what);
        // Robust traversal: no missed hits on shared edges, which would let light leak through
        // the seams of a triangulated blocker.
        rtcSetSceneFlags(scene.get(), RTC_SCENE_FLAG_ROBUST);
        return scene;
    }

    // The polygons' triangles (a fan of each convex polygon) as one Embree
    // geometry in `part`, attached to `scene` (not committed); false when
    // there are none.
    bool addTriangles(const Scene& scene, std::span<const std::uint32_t> polygonIds, RTCScene into,
                      RayCasterPart& part) {
        std::vector<glm::vec3> vertices;
        std::vector<std::uint32_t> indices;
        for (std::uint32_t id : polygonIds) {
            if (id >= scene.polygons.size())
                throw std::out_of_range("RayCaster: polygon id " + std::to_string(id) + " >= " +
                                        std::to_string(scene.polygons.size()));
            const Polygon& p = scene.polygons[id];
            if (p.vertexCount < 3 || p.vertexCount > 4) continue;
            Aabb box;
            for (int k = 0; k < p.vertexCount; ++k) box.extend(p.vertices[k]);
            if (extent.size() <= id) extent.resize(id + 1, 0.0);
            extent[id] = glm::length(box.extent());
            const auto base = static_cast<std::uint32_t>(vertices.size());
            for (int k = 0; k < p.vertexCount; ++k) {
                vertices.push_back(toEmbree(p.vertices[k]));
                part.magnitude = std::max(part.magnitude, maxAbs(p.vertices[k]));
            }
            for (int k = 1; k + 1 < p.vertexCount; ++k) {
                indices.insert(indices.end(), {base, base + k, base + k + 1});
                part.polygonOfTri.push_back(id);
                const glm::dvec3 n = glm::cross(p.vertices[k] - p.vertices[0], p.vertices[k + 1] - p.vertices[0]);
                part.planes.emplace_back(n, glm::dot(n, p.vertices[0]));
            }
        }
        if (part.polygonOfTri.empty()) return false;
        RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
        throwOnError(device, "creating the triangle geometry");
        auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), vertices.size()));
        auto* ib = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), part.polygonOfTri.size()));
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
        rtcSetGeometryOccludedFilterFunction(geometry, filterHits);
        rtcSetGeometryIntersectFilterFunction(geometry, filterBacks);
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(into, geometry);
        rtcReleaseGeometry(geometry);  // the scene holds it now
        throwOnError(device, "attaching the triangle geometry");
        return true;
    }

    // The size coincidence is measured against at a segment's ends: the
    // larger of the polygons they lie on (the frame's when on none). Not the
    // frame's: a 1 km site plane made a ceiling lamp 1 mm under its ceiling
    // coincident with it, and the room dark.
    double localSize(const Segment& in) const {
        double s = 0.0;
        for (std::uint32_t p : {in.fromPolygon, in.toPolygon})
            if (p < extent.size()) s = std::max(s, extent[p]);
        return s > 0.0 ? s : size;
    }

    double tolerance(const LayerData& l, const Segment& in) const {
        const double magnitude = std::max({l.magnitude, maxAbs(in.from), maxAbs(in.to)});
        return std::max(coincidenceOfSize * localSize(in), coincidenceOfMagnitude * magnitude);
    }

    // The segment with its tolerance; false when its ends are closer than
    // twice the tolerance (then nothing lies between them).
    bool place(const LayerData& l, const Segment& in, PlacedSegment& s) const {
        const glm::dvec3 d = in.to - in.from;
        const double len = glm::length(d);
        const double tol = tolerance(l, in);
        if (!(len > 2.0 * tol)) return false;
        s = PlacedSegment{in.from, d, tol / len, 1.0 - tol / len, tol, in.fromPolygon, in.toPolygon};
        return true;
    }

    // Unnormalised direction: t in [0, 1] spans the segment. The float window
    // reaches a tolerance and a half beyond both ends, so that surfaces
    // coincident with an end are met; the filter decides in double.
    void setRay(RTCRay16& ray, unsigned lane, const PlacedSegment& s) const {
        const double reach = 1.5 * s.tMin;
        const glm::vec3 org = toEmbree(s.a - reach * s.d);
        const glm::vec3 dir(s.d * scale);
        ray.org_x[lane] = org.x;
        ray.org_y[lane] = org.y;
        ray.org_z[lane] = org.z;
        ray.dir_x[lane] = dir.x;
        ray.dir_y[lane] = dir.y;
        ray.dir_z[lane] = dir.z;
        ray.tnear[lane] = 0.0f;
        ray.tfar[lane] = static_cast<float>(1.0 + 2.0 * reach);
        ray.mask[lane] = std::numeric_limits<unsigned>::max();
        ray.time[lane] = 0.0f;
        ray.id[lane] = lane;  // the filter's index into the segments
        ray.flags[lane] = 0;
    }

    // Whether the box of the packet's valid rays meets the layer's box: the
    // dynamic layer (a chair in a room) misses most links' packets, and an
    // instanced packet is traced incoherently. (The static layer is the
    // scene: every packet meets its box.)
    static bool reaches(const LayerData& l, const RTCRay16& rays, const std::array<int, 16>& valid) {
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (unsigned i = 0; i < 16; ++i) {
            if (valid[i] != -1) continue;
            const glm::vec3 a(rays.org_x[i], rays.org_y[i], rays.org_z[i]);
            const glm::vec3 b = a + rays.tfar[i] * glm::vec3(rays.dir_x[i], rays.dir_y[i], rays.dir_z[i]);
            lo = glm::min(lo, glm::min(a, b));
            hi = glm::max(hi, glm::max(a, b));
        }
        return glm::all(glm::lessThanEqual(lo, l.upper)) && glm::all(glm::lessThanEqual(l.lower, hi));
    }

    // Sets l's box from its committed scene.
    static void setBounds(LayerData& l) {
        RTCBounds b;
        rtcGetSceneBounds(l.scene.get(), &b);
        // Embree's frame is the scene at unit size: 1e-4 is far beyond a float's rounding there.
        const float margin = 1e-4f;
        l.lower = glm::vec3(b.lower_x, b.lower_y, b.lower_z) - margin;
        l.upper = glm::vec3(b.upper_x, b.upper_y, b.upper_z) + margin;
    }

    // The segments (at most 16) traced as one packet.
    std::uint16_t blockedMask(const LayerData& l, std::span<const Segment> in) const {
        std::array<PlacedSegment, kMaxSegments> segments;
        alignas(64) std::array<int, 16> valid{};
        RTCRay16 rays{};
        bool any = false;
        for (unsigned i = 0; i < in.size(); ++i) {
            if (!place(l, in[i], segments[i])) continue;
            setRay(rays, i, segments[i]);
            valid[i] = -1;
            any = true;
        }
        if (!any) return 0;
        if (l.instanced && !reaches(l, rays, valid)) return 0;
        SegmentContext context;
        rtcInitIntersectContext(&context.base);
        // Coherent: the segments of a link run between two small patches, so
        // they travel the same BVH nodes. Not through instances: Embree 3.13's
        // coherent packets hang there (seen in the tests, after a first device).
        context.base.flags = l.instanced ? RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT : RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        context.parts = &l.parts;
        context.segments = segments.data();
        context.frontRank = &frontRank;
        rtcOccluded16(valid.data(), l.scene.get(), &context.base, &rays);
        std::uint16_t mask = 0;
        // Embree marks an occluded ray by setting tfar to -inf.
        for (unsigned i = 0; i < in.size(); ++i)
            if (valid[i] == -1 && rays.tfar[i] < 0.0f) mask |= std::uint16_t(1u << i);
        return mask;
    }
};

RayCaster::RayCaster() : impl_(std::make_unique<Impl>()) {}
RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

void RayCaster::setFrame(const Aabb& bounds) { setFrame(bounds, bounds.center(), bounds); }

void RayCaster::setFrame(const Aabb& bounds, const glm::dvec3& detailCentre, const Aabb& detail) {
    if (bounds.empty()) return;
    const glm::dvec3 e = detail.empty() ? glm::dvec3(0.0) : detail.extent(), whole = bounds.extent();
    const double size = std::max({e.x, e.y, e.z}) > 0.0 ? std::max({e.x, e.y, e.z}) : std::max({whole.x, whole.y, whole.z});
    impl_->origin = detailCentre;
    impl_->scale = size > 0.0 ? 1.0 / size : 1.0;
    impl_->size = size > 0.0 ? size : 1.0;
}

void RayCaster::setLayer(Layer layer, const Scene& scene, std::span<const std::uint32_t> polygonIds) {
    if (layer == Layer::Static || impl_->frontRank.size() != scene.polygons.size()) impl_->rankPolygons(scene);
    if (layer == Layer::Dynamic) {
        clearInstances();
        addInstance(scene, polygonIds);
        commitInstances();
        return;
    }
    Impl::LayerData fresh;
    fresh.parts.resize(1);
    RayCasterScenePtr built = impl_->newScene("creating a scene");
    rtcSetSceneBuildQuality(built.get(), RTC_BUILD_QUALITY_HIGH);
    if (impl_->addTriangles(scene, polygonIds, built.get(), fresh.parts[0])) {
        rtcCommitScene(built.get());
        throwOnError(impl_->device, "building the scene");
        fresh.scene = std::move(built);
        fresh.magnitude = fresh.parts[0].magnitude;
    }
    impl_->layer(layer) = std::move(fresh);
}

void RayCaster::clearInstances() { impl_->layer(Layer::Dynamic) = Impl::LayerData{}; }

std::size_t RayCaster::addInstance(const Scene& scene, std::span<const std::uint32_t> polygonIds) {
    if (impl_->frontRank.size() != scene.polygons.size()) impl_->rankPolygons(scene);
    Impl::LayerData& l = impl_->layer(Layer::Dynamic);
    RayCasterPart part;
    RayCasterScenePtr triangles = impl_->newScene("creating an instance's scene");
    // Built once, moved by its transform: worth a good tree.
    rtcSetSceneBuildQuality(triangles.get(), RTC_BUILD_QUALITY_HIGH);
    const std::size_t index = l.parts.size();
    if (impl_->addTriangles(scene, polygonIds, triangles.get(), part)) {
        rtcCommitScene(triangles.get());
        throwOnError(impl_->device, "building an instance's scene");
        if (!l.scene) {
            l.scene = impl_->newScene("creating the dynamic layer's scene");
            // Its few instances move every frame: rebuilt fast.
            rtcSetSceneBuildQuality(l.scene.get(), RTC_BUILD_QUALITY_LOW);
            rtcSetSceneFlags(l.scene.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC);
            l.instanced = true;
        }
        RTCGeometry instance = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_INSTANCE);
        throwOnError(impl_->device, "creating an instance");
        rtcSetGeometryInstancedScene(instance, triangles.get());
        rtcSetGeometryTimeStepCount(instance, 1);
        rtcAttachGeometryByID(l.scene.get(), instance, static_cast<unsigned>(index));
        rtcReleaseGeometry(instance);  // the layer's scene holds it now
        throwOnError(impl_->device, "attaching an instance");
        for (std::uint32_t id : polygonIds) {
            const Polygon& p = scene.polygons[id];
            if (p.vertexCount >= 3 && p.vertexCount <= 4)
                part.addedVertices.insert(part.addedVertices.end(), p.vertices.begin(), p.vertices.begin() + p.vertexCount);
        }
        part.addedPlanes = part.planes;
        part.scene = std::move(triangles);
    }
    l.parts.push_back(std::move(part));
    moveInstance(index, glm::dmat4(1.0));
    return index;
}

void RayCaster::moveInstance(std::size_t index, const glm::dmat4& fromAdded) {
    Impl::LayerData& l = impl_->layer(Layer::Dynamic);
    if (index >= l.parts.size())
        throw std::out_of_range("RayCaster::moveInstance: instance " + std::to_string(index) + " >= " +
                                std::to_string(l.parts.size()));
    RayCasterPart& part = l.parts[index];
    if (!part.scene) return;
    // The planes in world space, in double (the filter places hits on them):
    // a rigid motion turns a normal by its rotation, and moves the offset by
    // the translation along the turned normal.
    const glm::dmat3 r(fromAdded);
    const glm::dvec3 t(fromAdded[3]);
    for (std::size_t i = 0; i < part.planes.size(); ++i) {
        const glm::dvec3 n = r * glm::dvec3(part.addedPlanes[i]);
        part.planes[i] = glm::dvec4(n, part.addedPlanes[i].w + glm::dot(n, t));
    }
    part.magnitude = 0.0;
    for (const glm::dvec3& v : part.addedVertices) part.magnitude = std::max(part.magnitude, maxAbs(glm::dvec3(fromAdded * glm::dvec4(v, 1.0))));
    // Embree's frame is the world moved to `origin` and scaled: there the
    // motion p -> R p + t becomes q -> R q + scale (R origin + t - origin).
    const glm::dvec3 shift = impl_->scale * (r * impl_->origin + t - impl_->origin);
    float xfm[12];
    for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 3; ++k) xfm[3 * c + k] = static_cast<float>(r[c][k]);
    for (int k = 0; k < 3; ++k) xfm[9 + k] = static_cast<float>(shift[k]);
    RTCGeometry instance = rtcGetGeometry(l.scene.get(), static_cast<unsigned>(index));
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcCommitGeometry(instance);
    throwOnError(impl_->device, "moving an instance");
}

void RayCaster::commitInstances() {
    Impl::LayerData& l = impl_->layer(Layer::Dynamic);
    l.magnitude = 0.0;
    for (const RayCasterPart& part : l.parts) l.magnitude = std::max(l.magnitude, part.magnitude);
    if (!l.scene) return;
    rtcCommitScene(l.scene.get());
    throwOnError(impl_->device, "building the dynamic layer");
    Impl::setBounds(l);
}

std::uint16_t RayCaster::blocked(Layer layer, std::span<const Segment> segments) const {
    if (segments.size() > kMaxSegments)
        throw std::invalid_argument("RayCaster::blocked: more than 16 segments in one query");
    const Impl::LayerData& l = impl_->layer(layer);
    if (!l.scene || segments.empty()) return 0;
    return impl_->blockedMask(l, segments);
}

double RayCaster::coincidenceTolerance() const { return coincidenceOfSize * impl_->size; }

double RayCaster::framesFromCentre(const glm::dvec3& p) const {
    const glm::dvec3 d = glm::abs(p - impl_->origin) * impl_->scale;
    return std::max({d.x, d.y, d.z});
}

double RayCaster::frameSize() const { return impl_->size; }

double RayCaster::resolutionAt(const glm::dvec3& p) const {
    const glm::dvec3 d = glm::abs(p - impl_->origin);
    return 1e-6 * std::max({d.x, d.y, d.z});
}

std::optional<RayCaster::Hit> RayCaster::intersect(const glm::dvec3& origin,
                                                   const glm::dvec3& direction, double tmax) const {
    if (!(tmax > 0.0) || direction == glm::dvec3(0.0)) return std::nullopt;
    // The nearest hit in one layer within [tnear, tfar] (world units along direction).
    const auto nearest = [&](const Impl::LayerData& l, double tnear, double tfar,
                             bool frontOnly) -> std::optional<Hit> {
        PickContext context;
        rtcInitIntersectContext(&context.base);
        context.parts = &l.parts;
        context.direction = direction;
        context.frontOnly = frontOnly;
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
        rh.ray.tnear = static_cast<float>(tnear);
        rh.ray.tfar = static_cast<float>(std::min(tfar, double(std::numeric_limits<float>::max())));
        rh.ray.mask = std::numeric_limits<unsigned>::max();
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(l.scene.get(), &context.base, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
        const RayCasterPart& part = partOf(l.parts, rh.hit.instID[0]);
        const bool front = glm::dot(glm::dvec3(part.planes[rh.hit.primID]), direction) < 0.0;
        return Hit{part.polygonOfTri.at(rh.hit.primID), double(rh.ray.tfar), front};
    };
    std::optional<Hit> best;
    for (const Impl::LayerData& l : impl_->layers) {
        if (!l.scene) continue;
        const std::optional<Hit> hit = nearest(l, 0.0, tmax, false);
        if (hit && (!best || hit->t < best->t)) best = hit;
    }
    if (!best || best->front) return best;
    // A back met first: a front coincident with it, within the tolerance,
    // is what the ray sees.
    const double window = 2.0 * coincidenceTolerance() / glm::length(direction);
    for (const Impl::LayerData& l : impl_->layers) {
        if (!l.scene) continue;
        const std::optional<Hit> front = nearest(l, std::max(0.0, best->t - window), best->t + window, true);
        if (front) return front;
    }
    return best;
}

}  // namespace rad
