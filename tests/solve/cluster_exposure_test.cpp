// How light arriving at a cluster divides among its facets when some of
// them are hidden inside it (solve/ClusterExposure.h): a row of books 4 mm
// apart has most of its area on the sides that face the slots, and its
// spines must still take the light a spine alone would.

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <numeric>
#include <vector>

#include "geometry/RayCaster.h"
#include "radiosity/Engine.h"
#include "solve/ClusterExposure.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;

// Twelve closed books, 3 cm thick, 4 mm apart, standing against the wall
// z = 0 of a 4 x 3 x 4 m room (1 cm from it), their spines facing +z; or their spines
// alone.
constexpr int kBooks = 12;
Scene bookRoom(bool spinesOnly) {
    Scene s;
    s.sourcePath = spinesOnly ? "spines" : "books";
    const auto white = test::addMaterial(s, V(0.7), V(0.0), "white");
    const auto paper = test::addMaterial(s, V(0.6), V(0.0), "paper");
    const auto light = test::addMaterial(s, V(0.0), V(10.0), "light");
    const auto faces = test::boxFaces(V(0.0), V(4.0, 3.0, 4.0), true);
    const char* names[] = {"floor", "ceiling", "wall-x0", "wall-x4", "wall-z0", "wall-z4"};
    for (int i = 0; i < 6; ++i) test::addQuadObject(s, names[i], white, {faces[i]});
    test::addQuadObject(
        s, "light", light,
        {{V(1.5, 2.999, 1.5), V(2.5, 2.999, 1.5), V(2.5, 2.999, 2.5), V(1.5, 2.999, 2.5)}});
    std::vector<std::array<V, 4>> books;
    for (int b = 0; b < kBooks; ++b) {
        const V lo(1.0 + b * 0.034, 0.0, 0.01), hi = lo + V(0.03, 0.22, 0.18);
        if (spinesOnly)
            books.push_back({V(lo.x, lo.y, hi.z), V(hi.x, lo.y, hi.z), V(hi.x, hi.y, hi.z),
                             V(lo.x, hi.y, hi.z)});
        else
            for (const auto& q : test::boxFaces(lo, hi, false)) books.push_back(q);
    }
    test::addQuadObject(s, "books", paper, books);
    return s;
}

// The area-weighted mean radiosity (luminance) of the polygons of object
// `name` whose normal is `normal` (within 8 degrees), all but those that
// end the row (x below 1.01 or above 1.40).
double radiosityFacing(const Engine& engine, const std::string& name, const V& normal) {
    const Scene& s = engine.scene();
    const RadiositySamples samples = engine.samples();
    const std::uint32_t object = *s.findObject(name);
    double sum = 0.0, area = 0.0;
    for (std::size_t k = 0; k < samples.luminance.size(); ++k) {
        const Polygon& p = s.polygons[samples.polygon[k]];
        const double x = p.centroid().x;
        if (p.object == object && glm::dot(p.normal(), normal) > 0.99 && x > 1.01 && x < 1.40) {
            sum += samples.weight[k] * samples.luminance[k];
            area += samples.weight[k];
        }
    }
    return area > 0.0 ? sum / area : 0.0;
}

TEST(ClusterExposure, ArrivalWeightsMoveLightToExposedFacetsAndKeepItsSum) {
    ClusterShape shape;
    shape.facets = {{V(0, 0, 1), 1.0, 1.0}, {V(1, 0, 0), 4.0, 0.1}, {V(0, 0, -1), 1.0, 1.0}};
    const V u = glm::normalize(V(1, 0, 1));
    std::array<double, ClusterShape::kMaxFacets> w{}, c{};
    shape.arrivalWeights(u, w, c);
    EXPECT_EQ(w[2], 0.0);  // facing away
    // What the cluster catches is its projected area's: sum A w = sum A c.
    EXPECT_NEAR(1.0 * w[0] + 4.0 * w[1], shape.projectedArea(u), 1e-12);
    // Divided by exposure among facets of equal cosine.
    EXPECT_NEAR(w[1] / w[0], 0.1, 1e-7);  // exposure is a float
    // Nothing that faces u exposed: by orientation alone.
    shape.facets[0].exposure = shape.facets[1].exposure = 0.0;
    shape.arrivalWeights(u, w, c);
    EXPECT_NEAR(w[0], glm::dot(shape.facets[0].normal, u), 1e-12);
    EXPECT_NEAR(w[1], glm::dot(shape.facets[1].normal, u), 1e-12);
}

TEST(ClusterExposure, ABookRowsSlotSidesAreHiddenAndItsSpinesOpen) {
    Scene s = bookRoom(false);
    Hierarchy h(s, 1e-4);
    RayCaster rays;
    rays.setFrame(s.bounds());
    std::vector<std::uint32_t> all(s.polygons.size());
    std::iota(all.begin(), all.end(), 0u);
    rays.setLayer(Layer::Static, s, all);
    const ElementId books = h.objectCluster(*s.findObject("books"));
    measureExposure(h, rays, std::span(&books, 1));
    const ClusterShape& shape = h.shape(books);
    double spine = -1.0, side = -1.0, back = -1.0;
    for (const ClusterShape::Facet& f : shape.facets) {
        if (f.normal.z > 0.99) spine = f.exposure;
        if (f.normal.x > 0.99) side = f.exposure;
        if (f.normal.z < -0.99) back = f.exposure;
    }
    // Spines face the room; of the 12 sides facing +x, 11 face a slot 4 mm
    // wide and 18 cm deep (the last faces the room); the backs face the
    // wall 1 cm behind them.
    EXPECT_GT(spine, 0.9);
    EXPECT_LT(side, 0.3);
    EXPECT_LT(back, 0.1);
}

// A move measures again what a measure of everything would change: the
// block slides along the floor toward a crate, and after each step every
// cluster's exposure is as a new measure of all of them finds it, but for
// those that hold the block, which keep theirs (ClusterExposure.h).
TEST(ClusterExposure, AMoveMeasuresAgainWhatAMeasureOfEverythingFinds) {
    Scene s = test::roomWithBlock();
    test::addQuadObject(s, "crate", test::addMaterial(s, V(0.5), V(0.0), "crate"),
                        test::boxFaces(V(2.5, 0.0, 1.4), V(3.2, 0.7, 2.3), false));
    Hierarchy h(s, 1e-4);
    RayCaster rays;
    rays.setFrame(s.bounds());
    const std::uint32_t block = *s.findObject("block");
    std::vector<std::uint32_t> fixed, moving;
    for (std::uint32_t p = 0; p < s.polygons.size(); ++p)
        (s.polygons[p].object == block ? moving : fixed).push_back(p);
    rays.setLayer(Layer::Static, s, fixed);
    const std::size_t instance = rays.addInstance(s, moving);
    rays.commitInstances();
    measureExposure(h, rays);
    const std::vector<Polygon> start(s.polygons.begin(), s.polygons.end());
    const ElementId cluster = h.objectCluster(block);
    std::size_t changedInAll = 0;
    for (int step = 1; step <= 3; ++step) {
        const V shift(0.09, 0.0, 0.0);
        const Aabb before = s.objectBounds(block);
        for (std::uint32_t p : moving)
            for (int k = 0; k < s.polygons[p].vertexCount; ++k)
                s.polygons[p].vertices[k] = start[p].vertices[k] + double(step) * shift;
        h.updateGeometry(cluster, false);
        h.refreshAncestors(cluster);
        rays.moveInstance(instance, glm::translate(glm::dmat4(1.0), double(step) * shift));
        rays.commitInstances();
        const ExposureMotion motion{cluster, before, s.objectBounds(block), shift, false};
        changedInAll += measureExposureAround(h, rays, std::span(&motion, 1)).size();
        std::vector<std::vector<float>> kept(h.size());
        for (ElementId e = 0; e < h.size(); ++e)
            if (h.isLive(e) && !h[e].isSurface())
                for (const ClusterShape::Facet& f : h.shape(e).facets)
                    kept[e].push_back(f.exposure);
        measureExposure(h, rays);
        for (ElementId e = 0; e < h.size(); ++e) {
            const bool holdsBlock = e != cluster && h.range(e).contains(h.range(cluster));
            if (!h.isLive(e) || h[e].isSurface() || holdsBlock) continue;
            for (int k = 0; k < h.shape(e).facetCount(); ++k)
                EXPECT_EQ(kept[e][k], h.shape(e).facets[k].exposure)
                    << "step " << step << ", cluster " << e;
        }
    }
    EXPECT_GT(changedInAll, 0u);  // the crate's side toward the block is hidden more and more
}

// End to end at the default settings: the room's light reaches the books
// through cluster links, and by orientation alone the slots' sides took
// much of it. Measured: by orientation alone the spines read 0.52 of the
// spines alone and the slots' sides 0.22 of the spines; with exposure 0.72
// and 0.04; at epsilon 2e-6, 0.95 and 0.008 (the rest of the spines' gap
// is the cluster links' visibility, judged from the cluster's 16 points,
// most of them on the slots' sides).
TEST(ClusterExposure, ABookRowsSpinesTakeTheLightItsSlotsSidesDoNot) {
    Engine row(bookRoom(false), EngineSettings{});
    row.solve();
    Engine alone(bookRoom(true), EngineSettings{});
    alone.solve();
    const double spines = radiosityFacing(row, "books", V(0, 0, 1));
    EXPECT_GT(spines / radiosityFacing(alone, "books", V(0, 0, 1)), 0.65);
    EXPECT_LT(radiosityFacing(row, "books", V(1, 0, 0)), 0.1 * spines);
    EXPECT_LT(radiosityFacing(row, "books", V(-1, 0, 0)), 0.1 * spines);
}

}  // namespace
}  // namespace rad
