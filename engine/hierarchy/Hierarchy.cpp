#include "hierarchy/Hierarchy.h"

#include "radiosity/Gltf.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace rad {
namespace {

// A cluster holds at most this many children before it is split in two.
constexpr std::size_t kClusterFanout = 4;

// Area-weighted centroid of a convex patch (fan from its first vertex).
glm::dvec3 patchCentroid(const PatchGeometry& patch) {
    glm::dvec3 c(0.0);
    double total = 0.0;
    for (int i = 1; i + 1 < patch.n; ++i) {
        const double a = glm::length(glm::cross(patch.v[i] - patch.v[0], patch.v[i + 1] - patch.v[0]));
        c += a * (patch.v[0] + patch.v[i] + patch.v[i + 1]) / 3.0;
        total += a;
    }
    return total > 0.0 ? c / total : patch.v[0];
}

template <class CenterOf>
void splitMedian(std::vector<std::uint32_t>& items, CenterOf centerOf, std::vector<std::uint32_t>& left,
                 std::vector<std::uint32_t>& right) {
    Aabb box;
    for (std::uint32_t i : items) box.extend(centerOf(i));
    // Positions on a grid relative to the box, ties broken by index: the same
    // scene at another scale (where rounding moves "equal" values by an ulp)
    // then splits the same way, and so refines the same way.
    const glm::dvec3 e = box.extent();
    const double size = std::max({e.x, e.y, e.z});
    auto grid = [&](double v, int axis) {
        return size > 0.0 ? std::llround((v - box.lo[axis]) / size * 1e9) : 0LL;
    };
    const long long gx = grid(box.hi.x, 0), gy = grid(box.hi.y, 1), gz = grid(box.hi.z, 2);
    const int axis = (gx >= gy && gx >= gz) ? 0 : (gy >= gz ? 1 : 2);
    const auto mid = items.begin() + static_cast<std::ptrdiff_t>(items.size() / 2);
    std::nth_element(items.begin(), mid, items.end(), [&](std::uint32_t a, std::uint32_t b) {
        const long long ka = grid(centerOf(a)[axis], axis), kb = grid(centerOf(b)[axis], axis);
        return ka != kb ? ka < kb : a < b;
    });
    left.assign(items.begin(), mid);
    right.assign(mid, items.end());
}

}  // namespace

glm::dvec2 polygonTexCoord(const Polygon& p, const glm::dvec2& uv) {
    const auto t = [&](int k) { return glm::dvec2(p.uv[k]); };
    if (p.vertexCount == 3) return t(0) + uv.x * (t(1) - t(0)) + uv.y * (t(2) - t(0));
    return glm::mix(glm::mix(t(0), t(1), uv.x), glm::mix(t(3), t(2), uv.x), uv.y);
}

glm::dvec3 surfaceReflectance(const Scene& scene, std::uint32_t polygon, const std::array<glm::dvec2, 4>& param) {
    const Polygon& p = scene.polygons[polygon];
    const Material& m = scene.materials[p.material];
    if (m.texture < 0 || static_cast<std::size_t>(m.texture) >= scene.textures.size() || !scene.textures[m.texture])
        return m.reflectance;
    const Texture& texture = *scene.textures[m.texture];
    // The element's corners in texture space, for how many texels it covers.
    std::array<glm::dvec2, 4> corners{};
    for (int k = 0; k < p.vertexCount; ++k) corners[k] = polygonTexCoord(p, param[k]);
    const glm::dvec2 e1 = corners[1] - corners[0], e2 = corners[p.vertexCount - 1] - corners[0];
    const double texels = std::abs(e1.x * e2.y - e1.y * e2.x) * texture.width * texture.height;
    // A grid of samples, about one per texel (2 x 2 to 16 x 16), each the
    // texel it falls on: the mean of the texels under the element.
    const int n = std::clamp(static_cast<int>(std::ceil(std::sqrt(texels))), 2, 16);
    glm::dvec3 sum(0.0);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            double s = (i + 0.5) / n, t = (j + 0.5) / n;
            glm::dvec2 at;
            if (p.vertexCount == 3) {
                // Folded onto the triangle: cell centres above the diagonal
                // fall on cell centres below it.
                if (s + t > 1.0) s = 1.0 - s, t = 1.0 - t;
                at = param[0] + s * (param[1] - param[0]) + t * (param[2] - param[0]);
            } else {
                at = glm::mix(glm::mix(param[0], param[1], s), glm::mix(param[3], param[2], s), t);
            }
            sum += texture.texel(polygonTexCoord(p, at));
        }
    const glm::dvec3 local = sum / double(n * n);
    glm::dvec3 rho(0.0);
    for (int c = 0; c < 3; ++c)
        rho[c] = m.textureMean[c] > 0.0 ? std::min(m.reflectance[c] * local[c] / m.textureMean[c], kMaxReflectance) : 0.0;
    return rho;
}

std::vector<glm::dvec2> polygonSampleParams(int vertexCount, int n) {
    std::vector<glm::dvec2> uv;
    uv.reserve(std::size_t(n) * std::size_t(n));
    if (vertexCount == 4) {
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) uv.emplace_back((i + 0.5) / n, (j + 0.5) / n);
        return uv;
    }
    for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
            uv.emplace_back((i + 1.0 / 3.0) / n, (j + 1.0 / 3.0) / n);  // upward
            if (i + j < n - 1) uv.emplace_back((i + 2.0 / 3.0) / n, (j + 2.0 / 3.0) / n);  // downward
        }
    return uv;
}

const std::array<glm::dvec2, 16>& polygonSampleParams(int vertexCount) {
    const auto four = [](int count) {
        const std::vector<glm::dvec2> uv = polygonSampleParams(count, 4);
        std::array<glm::dvec2, 16> out{};
        std::copy(uv.begin(), uv.end(), out.begin());
        return out;
    };
    static const std::array<glm::dvec2, 16> quad = four(4), triangle = four(3);
    return vertexCount == 4 ? quad : triangle;
}

Hierarchy::Hierarchy(const Scene& scene, double minArea, std::vector<double> objectMinArea)
    : scene_(scene),
      polygonElements_(scene.polygons.size(), kNone),
      polygonNormals_(scene.polygons.size()),
      polygonLeaves_(scene.polygons.size(), 0),
      meshTouched_(scene.polygons.size(), 1),
      reshapedMark_(scene.polygons.size(), 0),
      objectClusters_(scene.objects.size(), kNone),
      minArea_(minArea),
      objectMinArea_(std::move(objectMinArea)) {
    std::vector<std::uint32_t> dynamicObjects, staticObjects;
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o) {
        if (scene.objects[o].polygonCount == 0) continue;
        (scene.objects[o].dynamic ? dynamicObjects : staticObjects).push_back(o);
    }
    root_ = add(HElement{});
    std::vector<ElementId> top;
    // Each object that may become dynamic sits in its own cluster right under the root.
    for (std::uint32_t o : dynamicObjects) top.push_back(buildObjectCluster(scene, o));
    movable_ = top;
    if (!staticObjects.empty()) {
        std::vector<glm::dvec3> centers(scene.objects.size());
        for (std::uint32_t o : staticObjects) centers[o] = scene.objectBounds(o).center();
        const ElementId s = buildTree(
            staticObjects, kNone, [&](std::uint32_t o) { return centers[o]; },
            [&](std::uint32_t o) { return buildObjectCluster(scene, o); });
        // Avoid a chain of single-child clusters.
        if (dynamicObjects.empty()) {
            top.assign(elements_[s].children.begin(), elements_[s].children.end());
            for (ElementId c : top) elements_[c].parent = root_;
            release(s);
        } else {
            top.push_back(s);
        }
    }
    elements_[root_].children.assign(top.begin(), top.end());
    for (ElementId c : top) elements_[c].parent = root_;
    finishCluster(root_);
    assignRanges(root_, 0, false);
}

void Hierarchy::addDirect(ElementId id, const glm::dvec3& irradiance) {
    if (direct_.size() < elements_.size()) direct_.resize(elements_.capacity());
    HElement& e = elements_[id];
    direct_[id] = e.lit ? direct_[id] + irradiance : irradiance;
    e.lit = true;
}

ElementId Hierarchy::add(HElement e, const ElementBounds& bounds) {
    if (e.kind == ElementKind::Cluster) {
        if (!freeShapes_.empty()) {
            e.shape = freeShapes_.back();
            freeShapes_.pop_back();
            shapes_[e.shape] = ClusterShape{};
        } else {
            e.shape = static_cast<std::uint32_t>(shapes_.size());
            shapes_.emplace_back();
        }
    }
    if (!free_.empty()) {
        const ElementId id = free_.back();
        free_.pop_back();
        elements_[id] = std::move(e);
        bounds_[id] = bounds;
        quadrature_[id] = {};  // a surface's are made with its patch
        return id;
    }
    elements_.push_back(std::move(e));
    bounds_.push_back(bounds);
    quadrature_.push_back({});
    return static_cast<ElementId>(elements_.size() - 1);
}

template <class CenterOf, class MakeLeaf>
ElementId Hierarchy::buildTree(std::vector<std::uint32_t> items, std::uint32_t object, const CenterOf& centerOf,
                               const MakeLeaf& makeLeaf) {
    HElement cluster;
    cluster.kind = ElementKind::Cluster;
    cluster.object = object;
    const ElementId id = add(cluster);
    std::vector<ElementId> children;
    if (items.size() <= kClusterFanout) {
        for (std::uint32_t i : items) children.push_back(makeLeaf(i));
    } else {
        std::vector<std::uint32_t> left, right;
        splitMedian(items, centerOf, left, right);
        children.push_back(buildTree(std::move(left), object, centerOf, makeLeaf));
        children.push_back(buildTree(std::move(right), object, centerOf, makeLeaf));
    }
    for (ElementId c : children) elements_[c].parent = id;
    elements_[id].children.assign(children.begin(), children.end());
    finishCluster(id);
    return id;
}

ElementId Hierarchy::buildObjectCluster(const Scene& scene, std::uint32_t object) {
    const Object& o = scene.objects[object];
    std::vector<std::uint32_t> polygons(o.polygonCount);
    std::iota(polygons.begin(), polygons.end(), o.firstPolygon);
    // The tree splits along the object's own axes (its node's rotation,
    // without its scale), not the world's: an object turned by a few
    // degrees keeps the same clusters, and so the same light. Split along
    // the world's axes, the office chair turned by 5 degrees was 14% rms
    // from itself unturned in two full solves (2.6% so).
    glm::dmat3 axes(o.worldFromLocal);
    for (int k = 0; k < 3; ++k)
        if (const double n = glm::length(axes[k]); n > 0.0) axes[k] /= n;
    const glm::dmat3 toAxes = glm::determinant(axes) != 0.0 ? glm::inverse(axes) : glm::dmat3(1.0);
    const ElementId id = buildTree(
        std::move(polygons), object,
        [&](std::uint32_t p) { return toAxes * scene.polygons[p].centroid(); },
        [&](std::uint32_t p) { return makeSurface(scene, p); });
    objectClusters_[object] = id;
    return id;
}

ElementId Hierarchy::makeSurface(const Scene& scene, std::uint32_t polygon) {
    const Polygon& p = scene.polygons[polygon];
    HElement e;
    e.kind = ElementKind::Surface;
    e.polygon = polygon;
    e.object = p.object;
    e.param = p.vertexCount == 3 ? std::array<glm::vec2, 4>{glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(0)}
                                 : std::array<glm::vec2, 4>{glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)};
    polygonNormals_[polygon] = p.normal();
    e.area = p.area();
    PatchGeometry patch;
    patch.n = p.vertexCount;
    for (int i = 0; i < p.vertexCount; ++i) patch.v[i] = p.vertices[i];
    e.center = patchCentroid(patch);
    ElementBounds bounds;
    for (int i = 0; i < p.vertexCount; ++i) bounds.box.extend(p.vertices[i]);
    e.reflectance = surfaceReflectance(scene, polygon, e.corners());
    const ElementId id = add(std::move(e), bounds);
    quadrature_[id] = pack(quadraturePoints(this->patch(id)), firstCorner(id));
    polygonElements_[polygon] = id;
    polygonLeaves_[polygon] = 1;
    meshTouched_[polygon] = 1;
    return id;
}

void Hierarchy::release(ElementId id) {
    if (elements_[id].isSurface()) meshTouched_[elements_[id].polygon] = 1;
    if (elements_[id].shape != kNone) freeShapes_.push_back(elements_[id].shape);
    elements_[id] = HElement{};
    bounds_[id] = ElementBounds{};
    free_.push_back(id);
    logRelease(id);
}

void Hierarchy::logRelease(ElementId id) {
    ++releases_;
    if (releaseLog_.size() == 2 * kReleaseLog) {
        releaseLog_.erase(releaseLog_.begin(), releaseLog_.begin() + kReleaseLog);
        releaseLogStart_ += kReleaseLog;
    }
    releaseLog_.push_back(id);
}

void Hierarchy::finishCluster(ElementId id, bool turned) {
    HElement& c = elements_[id];
    Aabb& box = bounds_[id].box;
    box = Aabb{};
    c.area = 0.0;
    glm::dvec3 weighted(0.0);
    for (ElementId k : c.children) {
        const HElement& child = elements_[k];
        box.extend(bounds_[k].box);
        c.area += child.area;
        weighted += child.area * child.center;
    }
    c.center = c.area > 0.0 ? weighted / c.area : box.center();
    if (!turned) {
        shapes_[c.shape].ownValid = false;  // its centre moved: summed again from its links
        return;
    }

    // The orientation: surfaces give their normal and 16 points on their
    // input polygon; clusters their own shape.
    std::vector<ClusterShape::Facet> surfaceFacets;
    std::vector<std::array<ClusterShape::Sample, 16>> surfaceSamples;
    surfaceFacets.reserve(c.children.size());
    surfaceSamples.reserve(c.children.size());
    std::vector<ShapePart> parts;
    for (ElementId k : c.children) {
        const HElement& child = elements_[k];
        if (child.isSurface()) {
            const Polygon& p = scene_.polygons[child.polygon];
            surfaceFacets.push_back({normal(child), child.area, 1.0f, 0});
            auto& samples = surfaceSamples.emplace_back();
            const auto& uv = polygonSampleParams(p.vertexCount);
            const std::uint32_t encoded = ClusterShape::Sample::encode(normal(child));
            for (int i = 0; i < 16; ++i)
                samples[i] = {glm::vec3(polygonPoint(p, uv[i]) - c.center), encoded, child.polygon};
            parts.push_back({std::span(&surfaceFacets.back(), 1), std::span(samples), child.area / 16.0});
        } else {
            const ClusterShape& cs = shapes_[child.shape];
            parts.push_back({std::span(cs.facets), std::span(cs.samples.data(), cs.sampleCount), cs.sampleWeight,
                             child.center - c.center});
        }
    }
    ClusterShape& shape = shapes_[c.shape];
    const int facetsBefore = shape.facetCount();
    const std::vector<std::uint8_t> mapBefore = shape.childFacet;
    std::array<ClusterShape::Facet, ClusterShape::kMaxFacets> facetsBeforeBuild{};
    std::copy(shape.facets.begin(), shape.facets.end(), facetsBeforeBuild.begin());
    buildShape(parts, shape);
    pullPower(id);
    // What receivers hold stays valid while the facets stand for the same
    // surfaces (a rigid move); otherwise it starts from the current powers.
    // So does the facets' exposure until it is measured again (the engine
    // measures the clusters a move may change: solve/ClusterExposure.h).
    if (shape.facetCount() != facetsBefore || shape.childFacet != mapBefore) {
        shape.gathered = shape.power;
        shape.exposureMeasured = false;
    } else
        for (int k = 0; k < facetsBefore; ++k) {
            shape.facets[k].exposure = facetsBeforeBuild[k].exposure;
            shape.facets[k].staticBlocked = facetsBeforeBuild[k].staticBlocked;
        }
    shape.ownValid = false;  // its facets and centre moved: summed again from its links
}

namespace {

template <class Elements>
double ownCoverage(const Elements& elements, const HElement& e) {
    double below = 0.0, area = 0.0;
    for (ElementId k : e.children) {
        below += elements[k].area * elements[k].coverage;
        area += elements[k].area;
    }
    return e.formFactorSum + (area > 0.0 ? below / area : 0.0);
}

}  // namespace

void Hierarchy::refreshCoverage(ElementId id) {
    // Up the quadtree while it changes: an element whose coverage is what it
    // was leaves its parent's as it was (when an edit's light is summed
    // again at every receiver, no sum of form factors changes, and walking
    // every element's path up took 1.0 to 1.5 ms of `office`'s frame).
    for (ElementId e = id; e != kNone && elements_[e].isSurface(); e = elements_[e].depth == 0 ? kNone : elements_[e].parent) {
        const double coverage = ownCoverage(elements_, elements_[e]);
        if (coverage == elements_[e].coverage) return;
        elements_[e].coverage = coverage;
    }
}

void Hierarchy::refreshQuadtreeCoverage(ElementId id) {
    for (ElementId k : elements_[id].children) refreshQuadtreeCoverage(k);
    elements_[id].coverage = ownCoverage(elements_, elements_[id]);
}

void Hierarchy::pullPower(ElementId id) {
    const HElement& c = elements_[id];
    ClusterShape& shape = shapes_[c.shape];
    ClusterShape::Powers power{};
    std::size_t entry = 0;
    for (ElementId k : c.children) {
        const HElement& child = elements_[k];
        if (child.isSurface()) {
            power[shape.childFacet[entry++]] += child.radiosity * child.area;
        } else {
            const ClusterShape& cs = shapes_[child.shape];
            for (int f = 0; f < cs.facetCount(); ++f) power[shape.childFacet[entry++]] += cs.power[f];
        }
    }
    shape.power.assign(power.begin(), power.begin() + shape.facetCount());
}

std::uint64_t Hierarchy::assignRanges(ElementId id, std::uint64_t first, bool renumber) {
    HElement& e = elements_[id];
    if (e.isSurface()) {
        const std::string what = "polygon " + std::to_string(e.polygon);
        // Numbered again (attachToRoot), a surface keeps the size it had: its
        // area after a move may differ by a rounding error, and the depth of
        // its existing quadtree must stay allowed.
        const std::uint64_t count =
            renumber ? bounds_[id].range.size() : quadtreeIndexCount(e.area, minArea(e.object) / 16.0, what);
        bounds_[id].range = {first, checkedAdd(first, count - 1, what)};
        assignQuadtreeRanges(id);
        return bounds_[id].range.last;
    }
    std::uint64_t last = first;
    for (ElementId c : IdList(e.children))
        last = assignRanges(c, checkedAdd(last, 1, "cluster"), renumber);
    bounds_[id].range = {first, last};
    return last;
}

void Hierarchy::assignQuadtreeRanges(ElementId surface) {
    const IdList& kids = elements_[surface].children;
    for (std::size_t k = 0; k < kids.size(); ++k) {
        bounds_[kids[k]].range = quadtreeChildRange(bounds_[surface].range, static_cast<int>(k));
        assignQuadtreeRanges(kids[k]);
    }
}

bool Hierarchy::isMovable(ElementId cluster) const {
    return std::find(movable_.begin(), movable_.end(), cluster) != movable_.end();
}

std::vector<ElementId> Hierarchy::ancestorsBelowRoot(ElementId id) const {
    std::vector<ElementId> out;
    for (ElementId a = elements_[id].parent; a != kNone && a != root_; a = elements_[a].parent) out.push_back(a);
    return out;
}

std::vector<ElementId> Hierarchy::emptiedBy(ElementId cluster) const {
    std::vector<ElementId> out;
    for (ElementId a = elements_[cluster].parent; a != kNone && a != root_ && elements_[a].children.size() == 1;
         a = elements_[a].parent)
        out.push_back(a);
    return out;
}

void Hierarchy::attachToRoot(ElementId cluster) {
    if (!isMovable(cluster)) movable_.push_back(cluster);
    if (elements_[cluster].parent == root_) return;
    // Detach from the lowest ancestor that keeps other children; the empty
    // ones in between go.
    const std::vector<ElementId> emptied = emptiedBy(cluster);
    const ElementId top = emptied.empty() ? cluster : emptied.back();
    const ElementId parent = elements_[top].parent;
    elements_[parent].children.eraseValue(top);
    for (ElementId e : emptied) release(e);
    finishCluster(parent);
    refreshAncestors(parent);
    elements_[cluster].parent = root_;
    elements_[root_].children.push_back(cluster);
    finishCluster(root_);
    assignRanges(root_, 0, true);
}

// A leaf at the area threshold has a range of 21: itself, its 4 children and
// 16 grandchildren (kLevelsBelowThreshold); one a level below, 5.
bool Hierarchy::canSubdivide(ElementId id, int below) const {
    const HElement& e = elements_[id];
    std::uint64_t atThreshold = 1;  // (4^(levels + 1) - 1) / 3, levels numbered below a leaf there
    for (int k = 0; k < kLevelsBelowThreshold - below; ++k) atThreshold = 4 * atThreshold + 1;
    return e.isSurface() && bounds_[id].range.size() > atThreshold && e.depth < HElement::kMaxDepth;
}

void Hierarchy::subdivide(ElementId id) {
    if (!elements_[id].isLeaf() || !canSubdivide(id, kLevelsBelowThreshold)) return;
    const HElement parent = elements_[id];  // copy: add() may reallocate
    const IndexRange parentRange = bounds_[id].range;
    // Parametric corners of the four children. Quads: the four sub-squares.
    // Triangles: three corner triangles and the middle one (same winding).
    std::array<std::array<glm::dvec2, 4>, 4> params;
    const std::array<glm::dvec2, 4> q = parent.corners();
    if (cornerCount(id) == 4) {
        const glm::dvec2 m01 = 0.5 * (q[0] + q[1]), m12 = 0.5 * (q[1] + q[2]), m23 = 0.5 * (q[2] + q[3]),
                         m30 = 0.5 * (q[3] + q[0]), mc = 0.25 * (q[0] + q[1] + q[2] + q[3]);
        params = {{{q[0], m01, mc, m30}, {m01, q[1], m12, mc}, {mc, m12, q[2], m23}, {m30, mc, m23, q[3]}}};
    } else {
        const glm::dvec2 m01 = 0.5 * (q[0] + q[1]), m12 = 0.5 * (q[1] + q[2]), m20 = 0.5 * (q[2] + q[0]);
        params = {{{q[0], m01, m20, {}}, {m01, q[1], m12, {}}, {m20, m12, q[2], {}}, {m01, m12, m20, {}}}};
    }
    std::vector<ElementId> kids;
    for (int k = 0; k < 4; ++k) {
        HElement c;
        c.kind = ElementKind::Surface;
        c.parent = id;
        c.polygon = parent.polygon;
        c.object = parent.object;
        c.depth = static_cast<std::uint8_t>(parent.depth + 1);
        for (int i = 0; i < 4; ++i) c.param[i] = glm::vec2(params[k][i]);
        c.reflectance = surfaceReflectance(scene_, parent.polygon, params[k]);
        c.radiosity = parent.radiosity;
        c.peak = luminance(parent.radiosity);
        c.gathered = parent.gathered;
        c.oracle = parent.oracle;
        c.anchor = parent.anchor;
        c.anchorLight = parent.anchorLight;
        c.level = parent.level;
        kids.push_back(add(std::move(c), ElementBounds{quadtreeChildRange(parentRange, k), Aabb{}}));
    }
    elements_[id].children.assign(kids.begin(), kids.end());
    markReshaped(parent.polygon);
    polygonLeaves_[parent.polygon] += 3;  // a leaf became four
    reshapedLeaves_ += 3;
    updateGeometry(id);  // touches the polygon's mesh
}

void Hierarchy::removeChildren(ElementId id) {
    const bool surface = elements_[id].isSurface();
    const std::uint32_t polygon = elements_[id].polygon;
    if (surface) {
        touchMesh(polygon);
        markReshaped(polygon);
    }
    std::vector<ElementId> stack(elements_[id].children.begin(), elements_[id].children.end());
    elements_[id].children = IdList();
    if (surface && !stack.empty()) ++polygonLeaves_[polygon];  // a leaf now
    while (!stack.empty()) {
        const ElementId e = stack.back();
        stack.pop_back();
        if (surface && elements_[e].isLeaf()) --polygonLeaves_[polygon];
        for (ElementId c : elements_[e].children) stack.push_back(c);
        elements_[e] = HElement{};
        bounds_[e] = ElementBounds{};
        free_.push_back(e);
        logRelease(e);
    }
}

bool Hierarchy::subtreeUnlinked(ElementId id) const {
    const HElement& e = elements_[id];
    if (e.lit || !e.links.empty() || !e.plinks.empty() || !e.outLinks.empty() || !e.outPlinks.empty()) return false;
    for (ElementId c : e.children)
        if (!subtreeUnlinked(c)) return false;
    return true;
}

void Hierarchy::updateGeometry(ElementId id, bool turned) {
    HElement& e = elements_[id];
    if (e.isSurface()) {
        const Polygon& p = scene_.polygons[e.polygon];
        const PatchGeometry patch = this->patch(id);
        // Once per polygon, at its quadtree's root: a move reaches every
        // root, and a subdivision (from below the root) turns nothing.
        if (polygonElements_[e.polygon] == id) polygonNormals_[e.polygon] = p.normal();
        e.area = polygonArea(patch);
        Aabb& box = bounds_[id].box;
        box = Aabb{};
        for (int i = 0; i < patch.n; ++i) box.extend(patch.v[i]);
        e.center = patchCentroid(patch);
        quadrature_[id] = pack(quadraturePoints(patch), patch.v[0]);
        meshTouched_[e.polygon] = 1;  // the same polygon from one thread only: disjoint subtrees
    }
    // The subtrees are disjoint: a moved object's clusters, whose
    // orientation is rebuilt, on all cores.
    const IdList& children = e.children;
    if (!e.isSurface() && children.size() > 1)
        tbb::parallel_for(std::size_t(0), children.size(), [&](std::size_t i) { updateGeometry(children[i], turned); });
    else
        for (ElementId c : children) updateGeometry(c, turned);
    if (!elements_[id].isSurface()) finishCluster(id, turned);
}

namespace {

// Whether uv lies in the convex parametric polygon of an element (edges count).
bool paramContains(const HElement& e, int corners, const glm::dvec2& uv) {
    for (int k = 0; k < corners; ++k) {
        const glm::dvec2 a(e.param[k]), b(e.param[(k + 1) % corners]);
        if ((b.x - a.x) * (uv.y - a.y) - (b.y - a.y) * (uv.x - a.x) < -1e-12) return false;
    }
    return true;
}

}  // namespace

std::vector<ElementId> Hierarchy::pathTo(std::uint32_t polygon, const glm::dvec2& uv) const {
    std::vector<ElementId> path;
    for (ElementId e = polygonElements_[polygon]; e != kNone; e = elements_[e].parent) path.push_back(e);
    std::reverse(path.begin(), path.end());
    for (ElementId e = polygonElements_[polygon]; !elements_[e].isLeaf();) {
        ElementId next = kNone;
        for (ElementId c : elements_[e].children)
            if (paramContains(elements_[c], cornerCount(c), uv)) {
                next = c;
                break;
            }
        if (next == kNone) break;
        path.push_back(e = next);
    }
    return path;
}

void Hierarchy::refreshAncestors(ElementId id) {
    for (ElementId a = elements_[id].parent; a != kNone; a = elements_[a].parent) finishCluster(a);
}

void Hierarchy::compact(double slack) {
    // After a solve (slack 0) every list is made exact, and the element
    // arrays keep no chunk past their last item: with the 25% of slack kept
    // before, `office` held 1.3 bytes per link more, and the copies cost the
    // same 67 ms there (in the building floor, a 15 s solve, 0.96 s instead
    // of 0.51 s). Idle frames keep some slack, so that the lists a drag
    // grows are not copied back and forth.
    const auto shrink = [slack](auto& v, std::size_t spare) {
        if (double(v.capacity() - v.size()) > double(spare) + slack * double(v.size())) v.shrink_to_fit();
    };
    const std::size_t spare = slack > 0.0 ? 4 : 0;
    shrink(elements_, 0);
    shrink(bounds_, 0);
    shrink(quadrature_, 0);
    if (slack == 0.0) {  // after a solve: who reads the log next makes every value
        releaseLog_ = {};
        releaseLogStart_ = releases_;
    }
    if (direct_.size() > elements_.size()) direct_.resize(elements_.size());
    shrink(direct_, 0);
    shrink(shapes_, 0);
    tbb::parallel_for(std::size_t(0), elements_.size(), [&](std::size_t i) {
        HElement& e = elements_[i];
        shrink(e.links, spare);
        shrink(e.plinks, spare);
        shrink(e.outLinks, spare);
        shrink(e.outPlinks, spare);
    });
}

std::size_t Hierarchy::memoryBytes() const {
    std::size_t bytes = elements_.memoryBytes() + bounds_.memoryBytes() + quadrature_.memoryBytes() +
                        direct_.memoryBytes() +
                        (free_.capacity() + releaseLog_.capacity()) * sizeof(ElementId) +
                        shapes_.capacity() * sizeof(ClusterShape) + freeShapes_.capacity() * sizeof(std::uint32_t);
    for (const ClusterShape& s : shapes_) bytes += s.heapBytes();
    for (std::size_t i = 0; i < elements_.size(); ++i) {
        const HElement& e = elements_[i];
        bytes += (e.children.capacity() + e.links.capacity() + e.plinks.capacity() + e.outLinks.capacity() +
                  e.outPlinks.capacity()) *
                 sizeof(std::uint32_t);
    }
    return bytes;
}

}  // namespace rad
