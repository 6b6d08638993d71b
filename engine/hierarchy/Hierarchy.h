#pragma once
// The H-element hierarchy of a scene: a root cluster; below it one cluster per
// object marked dynamic, and a tree of clusters over the others; each object's
// polygons under a cluster of their own, so that any object can be chosen to
// move (paper sec. 3.3); polygons subdivided into quadtrees on demand during
// refinement.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "hierarchy/ChunkedArray.h"
#include "hierarchy/ClusterShape.h"
#include "hierarchy/HElement.h"
#include "links/FormFactor.h"
#include "radiosity/Scene.h"

namespace rad {

// The point with parametric coordinates uv on a polygon (as in HElement::param:
// bilinear on a quad, barycentric-like on a triangle).
inline glm::dvec3 polygonPoint(const Polygon& p, const glm::dvec2& uv) {
    if (p.vertexCount == 3)
        return p.vertices[0] + uv.x * (p.vertices[1] - p.vertices[0]) +
               uv.y * (p.vertices[2] - p.vertices[0]);
    // Bilinear over the quad; a planar convex quad maps sub-squares to planar convex quads.
    const glm::dvec3 a = glm::mix(p.vertices[0], p.vertices[1], uv.x);
    const glm::dvec3 b = glm::mix(p.vertices[3], p.vertices[2], uv.x);
    return glm::mix(a, b, uv.y);
}
// The texture coordinates at parametric uv (the same interpolation).
glm::dvec2 polygonTexCoord(const Polygon& p, const glm::dvec2& uv);
// The reflectance of the part of a polygon with the given parametric corners
// (HElement::param): its material's, or with a base colour texture, that
// scaled by the mean of the texels under the part over the texture's mean
// (each channel at most kMaxReflectance).
glm::dvec3 surfaceReflectance(const Scene& scene, std::uint32_t polygon, const std::array<glm::dvec2, 4>& param);
// n^2 fixed parametric points spread evenly over a polygon: an n x n grid
// of cell centres on quads, the centroids of the n^2 sub-triangles of an
// n-way split on triangles.
std::vector<glm::dvec2> polygonSampleParams(int vertexCount, int n);
// The same for n = 4, the 16 points most users take.
const std::array<glm::dvec2, 16>& polygonSampleParams(int vertexCount);
// Van der Corput's radical inverse of k in base `base`, in [0, 1): with bases
// 2 and 3, the Halton points the fixed ray sets are jittered by
// (solve/Closure.cpp, refine/Surroundings.cpp).
inline double radicalInverse(std::uint32_t k, std::uint32_t base) {
    double r = 0.0, f = 1.0 / base;
    for (; k != 0; k /= base, f /= base) r += f * (k % base);
    return r;
}

class Hierarchy {
public:
    // `scene` must outlive the hierarchy. minArea: the area threshold A_e; objectMinArea, when given (one per
    // object), each object's own (an object closed in a room of an open scene: refine/Surroundings.h). Throws
    // IndexRangeOverflow when the numbering would not fit 64 bits.
    Hierarchy(const Scene& scene, double minArea, std::vector<double> objectMinArea = {});

    ElementId root() const { return root_; }
    HElement& operator[](ElementId id) { return elements_[id]; }
    const HElement& operator[](ElementId id) const { return elements_[id]; }
    // An element's index range (sec. 3.2) and box, kept apart (ElementBounds).
    const IndexRange& range(ElementId id) const { return bounds_[id].range; }
    const Aabb& box(ElementId id) const { return bounds_[id].box; }
    // A surface's patch: its parametric corners (HElement::param) on its
    // polygon, made when asked rather than kept (104 bytes an element); an
    // empty patch for a cluster.
    PatchGeometry patch(ElementId id) const {
        const HElement& e = elements_[id];
        PatchGeometry g;
        if (!e.isSurface()) return g;
        const Polygon& p = scene_.polygons[e.polygon];
        g.n = p.vertexCount;
        for (int i = 0; i < g.n; ++i) g.v[i] = polygonPoint(p, glm::dvec2(e.param[i]));
        return g;
    }
    // Its first corner, where its quadrature points are kept from.
    glm::dvec3 firstCorner(ElementId id) const {
        const HElement& e = elements_[id];
        return e.isSurface() ? polygonPoint(scene_.polygons[e.polygon], glm::dvec2(e.param[0]))
                             : glm::dvec3(0.0);
    }
    // A surface's unit normal and emission: its polygon's (zero for a
    // cluster), kept once per polygon rather than per element.
    glm::dvec3 normal(const HElement& e) const {
        return e.isSurface() ? polygonNormals_[e.polygon] : glm::dvec3(0.0);
    }
    glm::dvec3 emission(const HElement& e) const {
        return e.isSurface() ? scene_.materials[scene_.polygons[e.polygon].material].emission
                             : glm::dvec3(0.0);
    }
    // How many corners a surface has (3 or 4).
    int cornerCount(ElementId id) const {
        return scene_.polygons[elements_[id].polygon].vertexCount;
    }
    // A surface's quadraturePoints, made with its patch (none for a cluster);
    // kept packed (PackedQuadrature).
    QuadraturePoints quadrature(ElementId id) const {
        return unpack(quadrature_[id], firstCorner(id));
    }
    std::size_t size() const { return elements_.size(); }
    std::size_t liveCount() const { return elements_.size() - free_.size(); }
    // Not freed (every element but the root has a parent until release()).
    bool isLive(ElementId id) const { return id == root_ || elements_[id].parent != kNone; }
    // How many elements were ever freed: what keeps a value per element
    // (an id may be freed, and given again) knows by it whether any was.
    std::uint64_t releases() const { return releases_; }
    // The ids freed since releases() read `count`, oldest first; nullopt when
    // the log no longer reaches back so far (it keeps the last kReleaseLog
    // to 2 kReleaseLog, and none after a compact(0)). What keeps a value per
    // element makes it again for these only (the live estimate's sums: on
    // the building floor a frame frees a few to a few dozen elements, and
    // making again the terms of 110,000 to 330,000 unsent elements took 2
    // to 8 ms of a 33 ms frame).
    std::optional<std::span<const ElementId>> releasedSince(std::uint64_t count) const {
        if (count < releaseLogStart_ || count > releases_) return std::nullopt;
        return std::span<const ElementId>(releaseLog_).subspan(count - releaseLogStart_);
    }
    static constexpr std::size_t kReleaseLog = 4096;
    double minArea() const { return minArea_; }
    // The area threshold of an object's polygons: its own, or minArea().
    double minArea(std::uint32_t object) const {
        return object < objectMinArea_.size() ? objectMinArea_[object] : minArea_;
    }

    // The surface element of each input polygon (quadtree root).
    ElementId polygonElement(std::uint32_t polygon) const { return polygonElements_[polygon]; }
    std::size_t polygonCount() const { return polygonElements_.size(); }
    // How many leaves a polygon's quadtree has (what meshing it writes),
    // kept through subdivision and removal.
    std::uint32_t polygonLeaves(std::uint32_t polygon) const { return polygonLeaves_[polygon]; }
    // Appends the leaves under e to out, depth first, children in order.
    void collectLeaves(ElementId e, std::vector<ElementId>& out) const {
        if (elements_[e].isLeaf()) {
            out.push_back(e);
            return;
        }
        for (ElementId c : elements_[e].children) collectLeaves(c, out);
    }
    // Which polygons' meshes may have changed since the snapshot last looked
    // (its leaves, their corners or their radiosity): set here by every
    // subdivision, removal and move, and by the solver for the leaves whose
    // radiosity it changes; read and cleared by makeRadiositySnapshot, so
    // that a frame hashes only these polygons' leaves, not every leaf.
    void touchMesh(std::uint32_t polygon) { meshTouched_[polygon] = 1; }
    void touchAllMeshes() { std::fill(meshTouched_.begin(), meshTouched_.end(), std::uint8_t(1)); }
    std::vector<std::uint8_t>& meshTouched() { return meshTouched_; }
    // The leaves of the polygons whose leaves changed (a subdivision, a
    // removal) or moved since clearReshaped(): the snapshot meshes those
    // polygons anew, at ten times the cost a leaf of colouring one again,
    // so a frame on a deadline leaves their time (Engine::buildMesh). A
    // polygon counts its leaves when first marked, and three more for each
    // subdivision after. Marked serially: by subdivide and removeChildren,
    // and by the engine for the polygons a move carries.
    void markReshaped(std::uint32_t polygon) {
        if (std::exchange(reshapedMark_[polygon], std::uint8_t(1))) return;
        reshapedPolygons_.push_back(polygon);
        reshapedLeaves_ += polygonLeaves_[polygon];
    }
    std::size_t reshapedLeaves() const { return reshapedLeaves_; }
    // After a snapshot: the polygons it meshed are forgotten; those a stop
    // left (still marked in meshTouched) stay, counted with their leaves.
    void clearReshaped() {
        reshapedLeaves_ = 0;
        std::erase_if(reshapedPolygons_, [&](std::uint32_t p) {
            if (meshTouched_[p]) {
                reshapedLeaves_ += polygonLeaves_[p];
                return false;
            }
            reshapedMark_[p] = 0;
            return true;
        });
    }
    // The cluster holding all of one object's polygons.
    ElementId objectCluster(std::uint32_t object) const { return objectClusters_[object]; }
    // The object clusters right under the root: those that can move without
    // changing any cluster above them but the root.
    const std::vector<ElementId>& movableClusters() const { return movable_; }
    bool isMovable(ElementId cluster) const;

    // Paper sec. 3.3: "When the user selects a dynamic object, the
    // corresponding cluster is attached to the root of the hierarchy." Moves
    // an object's cluster from the cluster tree to the root, frees the
    // clusters this leaves empty (see emptiedBy), recomputes the geometry of
    // its former ancestors and numbers every index range again. The caller
    // removes the links of the emptied clusters first.
    void attachToRoot(ElementId cluster);
    // The former ancestors that attachToRoot(cluster) would leave without
    // any child, lowest first.
    std::vector<ElementId> emptiedBy(ElementId cluster) const;
    // The clusters strictly between `id` and the root, lowest first.
    std::vector<ElementId> ancestorsBelowRoot(ElementId id) const;

    // The elements holding the point with parametric coordinates uv on an
    // input polygon (the corners' (u,v) as in HElement::param), from the root
    // down to the leaf.
    std::vector<ElementId> pathTo(std::uint32_t polygon, const glm::dvec2& uv) const;

    // A cluster's orientation (see ClusterShape.h).
    // The irradiance punctual lights send through the light links that end
    // at a surface (lights/LightLinks.h): zero unless the element is `lit`.
    // A side table, sized only once a light link exists: most scenes have
    // no punctual lights, and in those that do most elements are not lit.
    glm::dvec3 direct(ElementId id) const { return elements_[id].lit ? direct_[id] : glm::dvec3(0.0); }
    void addDirect(ElementId id, const glm::dvec3& irradiance);
    void clearDirect(ElementId id) { elements_[id].lit = false; }

    ClusterShape& shape(ElementId cluster) { return shapes_[elements_[cluster].shape]; }
    const ClusterShape& shape(ElementId cluster) const { return shapes_[elements_[cluster].shape]; }
    // Sums a cluster's facet powers from its children's radiosity (a pull).
    void pullPower(ElementId cluster);
    // Recomputes HElement::coverage of a surface element from its own
    // formFactorSum and its children's coverage, then up its quadtree.
    void refreshCoverage(ElementId surface);
    // The same for a whole quadtree, bottom-up.
    void refreshQuadtreeCoverage(ElementId surface);

    // Surfaces: whether children may be made, each keeping at least minArea,
    // or `below` levels further (children of at least minArea / 4^below):
    // one for a shadow boundary cast by a blocker right at the surface, or a
    // surface shining on another close in front of it; two for a surface an
    // emitter shines along (Refiner::chooseSplit). The index ranges number
    // kLevelsBelowThreshold levels below the area threshold.
    static constexpr int kLevelsBelowThreshold = 2;
    bool canSubdivide(ElementId id, int below = 0) const;
    // Makes the four children of a surface leaf (no-op if they exist).
    void subdivide(ElementId id);
    // Removes the children (and their subtrees) of a surface element.
    void removeChildren(ElementId id);
    // Whether no link, p-link, outgoing link or light link touches the subtree of `id`:
    // subdivision that serves nothing.
    bool subtreeUnlinked(ElementId id) const;

    // Recomputes the geometry of a subtree from the scene's polygons (after
    // subdivision, or after the object moved), then the enclosing boxes.
    // `turned` false: the subtree was only translated since its clusters'
    // shapes were built, and they are kept (their facets, and their samples
    // relative to the centre, do not change; building them was a sixth of a
    // frame at 120 fps).
    void updateGeometry(ElementId id, bool turned = true);
    // Recomputes the boxes, areas and centres of the clusters above `id`.
    void refreshAncestors(ElementId id);

    // Drops the growth slack of the element arrays and the link lists: all
    // of it, or where a list holds more than `slack` of its size (and 4) spare.
    void compact(double slack = 0.0);

    // Bytes held by elements and their link lists.
    std::size_t memoryBytes() const;
    // What one more element holds, its link lists and a cluster's shape
    // left out: its record, bounds and quadrature points, and its slot in
    // the side table of punctual lights' irradiance once that exists.
    std::size_t bytesPerElement() const {
        return sizeof(HElement) + sizeof(ElementBounds) + sizeof(PackedQuadrature) +
               (direct_.size() > 0 ? sizeof(glm::dvec3) : 0);
    }

private:
    ElementId add(HElement e, const ElementBounds& bounds = {});
    void release(ElementId id);  // frees an element and its shape
    void logRelease(ElementId id);  // counts it in releases_ and the log
    // A median-split tree of clusters over `items` (objects or polygons), at
    // most a few leaves per cluster; makeLeaf turns an item into an element.
    template <class CenterOf, class MakeLeaf>
    ElementId buildTree(std::vector<std::uint32_t> items, std::uint32_t object, const CenterOf& centerOf,
                        const MakeLeaf& makeLeaf);
    ElementId buildObjectCluster(const Scene& scene, std::uint32_t object);
    ElementId makeSurface(const Scene& scene, std::uint32_t polygon);
    // renumber: keep each surface's range size (see attachToRoot).
    std::uint64_t assignRanges(ElementId id, std::uint64_t first, bool renumber);
    // Gives the existing quadtree below a surface the ranges of its own.
    void assignQuadtreeRanges(ElementId surface);
    void finishCluster(ElementId id, bool turned = true);

    const Scene& scene_;  // outlives the hierarchy; polygons move with the dynamic object
    // In chunks of 256 (ChunkedArray.h): a frame that subdivides does not
    // copy them all.
    ChunkedArray<HElement, 8> elements_;
    ChunkedArray<ElementBounds, 8> bounds_;          // parallel to elements_
    ChunkedArray<PackedQuadrature, 8> quadrature_;  // parallel to elements_
    ChunkedArray<glm::dvec3, 8> direct_;            // parallel to elements_ once a light link exists
    std::vector<ElementId> free_;
    std::uint64_t releases_ = 0;
    std::vector<ElementId> releaseLog_;  // the last ids freed (releasedSince)
    std::uint64_t releaseLogStart_ = 0;  // releases_ when releaseLog_[0] was freed
    std::vector<ClusterShape> shapes_;
    std::vector<std::uint32_t> freeShapes_;
    std::vector<ElementId> polygonElements_;
    std::vector<glm::dvec3> polygonNormals_;    // per polygon, as it stands (normal)
    std::vector<std::uint32_t> polygonLeaves_;  // per polygon (polygonLeaves)
    std::vector<std::uint8_t> meshTouched_;  // per polygon (touchMesh)
    std::vector<std::uint8_t> reshapedMark_;  // per polygon (markReshaped)
    std::vector<std::uint32_t> reshapedPolygons_;
    std::size_t reshapedLeaves_ = 0;
    std::vector<ElementId> objectClusters_;
    std::vector<ElementId> movable_;
    ElementId root_ = kNone;
    double minArea_;
    std::vector<double> objectMinArea_;  // per object, or empty
};

}  // namespace rad
