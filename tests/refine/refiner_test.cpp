// Which end of a link refinement splits (refine/Refiner.h): the larger one,
// unless the link's visibility rays show a shadow boundary across one end
// only. Then that end is split, whatever the areas: splitting the other
// would leave every child link partly visible, each carrying the mean of
// the lit and the hidden parts (the light through a door 2 mm in front of a
// doorway's edge).

#include <gtest/gtest.h>

#include <vector>

#include "geometry/RayCaster.h"
#include "hierarchy/Hierarchy.h"
#include "refine/Refiner.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;

// An axis-aligned rectangle in the plane y = `y`, facing up or down.
std::array<V, 4> horizontal(double y, double x0, double x1, double z0, double z1, bool up) {
    if (up) return {V(x0, y, z0), V(x0, y, z1), V(x1, y, z1), V(x1, y, z0)};
    return {V(x0, y, z0), V(x1, y, z0), V(x1, y, z1), V(x0, y, z1)};
}

struct Split {
    bool source = false;    // every new link's source is a child of the old source
    bool receiver = false;  // every new link's receiver is a child of the old receiver
    double visibility = 0.0;
};

// A scene's hierarchy and a refiner, every polygon in the static layer.
struct Refining {
    Hierarchy h;
    LinkStore links;
    RayCaster rays;
    Refiner refiner;
    Refining(const Scene& scene, double minArea) : h(scene, minArea), refiner(h, links, rays, RefineSettings{}) {
        std::vector<std::uint32_t> all(scene.polygons.size());
        for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
        rays.setLayer(Layer::Static, scene, all);
    }
};

// Refines the link from the emitter (facing down, y = 2) to the floor
// (facing up, y = 0) once, with a black blocker in the static scene.
Split refineOnce(const Scene& scene, double minArea = 1e-6) {
    Refining r0(scene, minArea);
    Hierarchy& h = r0.h;
    LinkStore& links = r0.links;
    Refiner& refiner = r0.refiner;
    const ElementId s = h.polygonElement(0), r = h.polygonElement(1);
    const LinkId id = refiner.attach(refiner.compute(s, r));
    Split out;
    out.visibility = links[id].visibility();
    std::vector<LinkId> created;
    refiner.refine({id}, created);
    EXPECT_FALSE(created.empty());
    out.source = out.receiver = !created.empty();
    for (LinkId c : created) {
        out.source = out.source && links[c].receiver == r && h[links[c].source].parent == s;
        out.receiver = out.receiver && links[c].source == s && h[links[c].receiver].parent == r;
    }
    return out;
}

Scene emitterFloorBlocker(double emitterSide, double floorSide, const std::array<V, 4>& blocker) {
    Scene s;
    s.sourcePath = "split";
    const auto light = test::addMaterial(s, V(0.0), V(1.0), "light");
    const auto grey = test::addMaterial(s, V(0.5), V(0.0), "grey");
    const auto black = test::addMaterial(s, V(0.0), V(0.0), "black");
    test::addQuadObject(s, "emitter", light, {horizontal(2.0, 0.0, emitterSide, 0.0, emitterSide, false)});
    test::addQuadObject(s, "floor", grey, {horizontal(0.0, 0.0, floorSide, 0.0, floorSide, true)});
    test::addQuadObject(s, "blocker", black, {blocker});
    return s;
}

// A small emitter half covered by a blocker 1 cm below it: whether a ray is
// blocked depends on its emitter point only. The floor is 25 times larger,
// yet the emitter is split.
TEST(Refiner, SplitsTheSourceWhenTheShadowBoundaryCrossesIt) {
    const Split split = refineOnce(emitterFloorBlocker(1.0, 5.0, horizontal(1.99, -1.0, 0.5, -1.0, 2.0, true)));
    EXPECT_GT(split.visibility, 0.0);
    EXPECT_LT(split.visibility, 1.0);
    EXPECT_TRUE(split.source);
}

// A small floor half covered by a blocker 1 cm above it, under a large
// emitter: the boundary crosses the receiver, which is split although it is
// the smaller end.
TEST(Refiner, SplitsTheReceiverWhenTheShadowBoundaryCrossesIt) {
    const Split split = refineOnce(emitterFloorBlocker(5.0, 1.0, horizontal(0.01, -1.0, 0.5, -1.0, 2.0, false)));
    EXPECT_GT(split.visibility, 0.0);
    EXPECT_LT(split.visibility, 1.0);
    EXPECT_TRUE(split.receiver);
}

// The same floor at the area threshold (its children would be smaller): a
// boundary cast by a blocker right at it is split one level further.
TEST(Refiner, SplitsAShadowBoundaryRightAtTheReceiverBelowTheAreaThreshold) {
    const Split split = refineOnce(emitterFloorBlocker(5.0, 1.0, horizontal(0.01, -1.0, 0.5, -1.0, 2.0, false)), 0.5);
    EXPECT_GT(split.visibility, 0.0);
    EXPECT_LT(split.visibility, 1.0);
    EXPECT_TRUE(split.receiver);
}

// A wall element across an uplight's plane (a panel facing up 1 cm above a
// cabinet top, the wall from 40 cm below it to 9 cm above): the element's
// sample points all lie below the panel's plane, behind the cabinet's top,
// yet its upper strip sees the whole panel with nothing between. The rays
// run between the parts of the two in front of each other.
TEST(Refiner, SurfacesThatSeeEachOtherOnlyBetweenTheirPointsAreJudgedByTheirFacingParts) {
    Scene s;
    s.sourcePath = "uplight-wall";
    const auto light = test::addMaterial(s, V(0.0), V(10.0), "light");
    const auto grey = test::addMaterial(s, V(0.5), V(0.0), "grey");
    test::addQuadObject(s, "uplight", light, {horizontal(2.01, 0.05, 0.4, 0.0, 0.7, true)});
    test::addQuadObject(s, "wall", grey, {{V(0.0, 1.6, 0.0), V(0.0, 2.1, 0.0), V(0.0, 2.1, 0.7), V(0.0, 1.6, 0.7)}});
    test::addQuadObject(s, "cabinet", grey, test::boxFaces(V(0.0, 0.0, -0.1), V(0.45, 2.0, 0.8), false));
    Refining r(s, 1e-6);
    const Link link = r.refiner.compute(r.h.polygonElement(0), r.h.polygonElement(1));
    EXPECT_GT(link.unoccluded, 0.0f);
    EXPECT_EQ(link.visibility(), 1.0);  // 0 when the rays ran from the wall's points behind the cabinet
}

// A glowing panel standing on a unit floor at the area threshold, across
// it (a lamp's side on the wall it hangs on): its light falls off steeply
// from where they meet, and the floor splits one level below the threshold.
// Lifted 20 cm off the floor, or dark, it leaves the floor whole.
Scene panelOnFloor(double lift, double emission, double floorEmission = 0.0) {
    Scene s;
    s.sourcePath = "panel-on-floor";
    const auto panel = test::addMaterial(s, V(0.5), V(emission), "panel");
    const auto grey = test::addMaterial(s, V(0.5), V(floorEmission), "grey");
    // In the plane x = 0.5, facing +x.
    test::addQuadObject(s, "panel", panel,
                        {{V(0.5, lift, 0.3), V(0.5, lift + 0.3, 0.3), V(0.5, lift + 0.3, 0.7), V(0.5, lift, 0.7)}});
    test::addQuadObject(s, "floor", grey, {horizontal(0.0, 0.0, 1.0, 0.0, 1.0, true)});
    return s;
}

TEST(Refiner, AnEmitterStandingOnTheReceiverSplitsItBelowTheAreaThreshold) {
    const auto wouldSplitFloor = [](const Scene& scene) {
        Refining r(scene, 0.5);
        const ElementId panel = r.h.polygonElement(0);
        r.h[panel].oracle =
            float(luminance(r.h.emission(r.h[panel])));  // the radiosity refinement judges by
        const Link link = r.refiner.compute(panel, r.h.polygonElement(1));
        EXPECT_GT(link.formFactor(), 0.0f) << scene.sourcePath;
        return r.refiner.wouldRefine(link);
    };
    EXPECT_TRUE(wouldSplitFloor(panelOnFloor(0.0, 10.0)));
    EXPECT_FALSE(wouldSplitFloor(panelOnFloor(0.2, 10.0)));
    EXPECT_FALSE(wouldSplitFloor(panelOnFloor(0.0, 0.0)));
    // A floor that glows itself (a furnace's faces meet so) keeps the threshold.
    EXPECT_FALSE(wouldSplitFloor(panelOnFloor(0.0, 10.0, 10.0)));
    const Split split = refineOnce(panelOnFloor(0.0, 10.0), 0.5);
    EXPECT_TRUE(split.receiver);
}

// Along an emitter the receiver may go two levels below the area threshold:
// the unit floor (at a threshold of 0.5, so that its quarters are one level
// below it) splits, the quarter in front of the panel splits again, and its
// own quarters (a sixteenth) no more. A strip under a cupboard 2 cm from its
// wall lights the wall in a band a few centimetres tall; with one level,
// elements twice that drew it (an untuned kitchen's image 18.6% from Cycles,
// 5.2% with two; bench/untuned/kitchen_room.py).
TEST(Refiner, AnEmitterStandingOnTheReceiverSplitsItTwoLevelsBelowTheAreaThreshold) {
    const Scene scene = panelOnFloor(0.0, 10.0);  // the hierarchy keeps a reference to it
    Refining r(scene, 0.5);
    const ElementId panel = r.h.polygonElement(0), floor = r.h.polygonElement(1);
    r.h[panel].oracle = float(luminance(r.h.emission(r.h[panel])));
    EXPECT_TRUE(r.refiner.wouldRefine(r.refiner.compute(panel, floor)));
    r.h.subdivide(floor);
    ElementId lit = kNone;
    for (ElementId c : r.h[floor].children)
        if (r.h[c].center.x > 0.5 && r.h[c].center.z < 0.5) lit = c;
    ASSERT_NE(lit, kNone);
    EXPECT_TRUE(r.refiner.wouldRefine(r.refiner.compute(panel, lit)));
    r.h.subdivide(lit);
    ASSERT_EQ(r.h[lit].children.size(), 4u);
    for (ElementId c : r.h[lit].children) EXPECT_FALSE(r.refiner.wouldRefine(r.refiner.compute(panel, c)));
}

// No boundary that one end alone carries (nothing blocks): the larger end.
TEST(Refiner, SplitsTheLargerEndOtherwise) {
    const Split split = refineOnce(emitterFloorBlocker(1.0, 5.0, horizontal(5.0, 10.0, 11.0, 10.0, 11.0, true)));
    EXPECT_EQ(split.visibility, 1.0);
    EXPECT_TRUE(split.receiver);
}

// A plate 2 mm above the floor's edge strip (x from 0.9 to 1.1 of a unit
// floor): the floor's Gauss points (at x = 0.21 and 0.79) hardly see it,
// its corners under it see almost nothing else. The form factor's
// variation across the floor counts the corners (measured 0.96); for the
// plate 20 cm up, no longer close, only the Gauss points count (0.15).
struct PlateOverFloor {
    Scene scene;
    Hierarchy h;
    LinkStore links;
    RayCaster rays;
    Refiner refiner;
    explicit PlateOverFloor(double height)
        : scene(build(height)), h(scene, 1e-4), refiner(h, links, rays, RefineSettings{}) {}
    static Scene build(double height) {
        Scene s;
        s.sourcePath = "plate";
        const auto grey = test::addMaterial(s, V(0.5), V(0.0), "grey");
        test::addQuadObject(s, "floor", grey, {horizontal(0.0, 0.0, 1.0, 0.0, 1.0, true)});
        test::addQuadObject(s, "plate", grey, {horizontal(height, 0.9, 1.1, 0.0, 1.0, false)});
        return s;
    }
    Link plateToFloor() const { return refiner.compute(h.polygonElement(1), h.polygonElement(0)); }
};

TEST(Refiner, ACloseFacingSurfaceOverAStripTheGaussPointsMissCountsInTheVariation) {
    PlateOverFloor close(0.002), far(0.2);
    EXPECT_GT(close.plateToFloor().spread, 0.5f);
    EXPECT_LT(far.plateToFloor().spread, 0.2f);
}

// The floor subdivided, its light bright: the close plate's link goes down
// to the floor's children, whatever its own transfer (the plate is black),
// so that the children under the plate count it in their coverage. A dark
// floor keeps the link where it is.
TEST(Refiner, ACloseFacingSourceReachesTheReceiversChildrenWhereTheReceiverIsBright) {
    PlateOverFloor p(0.002);
    const ElementId floor = p.h.polygonElement(0);
    p.h.subdivide(floor);
    Link link = p.plateToFloor();
    ASSERT_GT(link.unoccluded, 0.0f);
    EXPECT_FALSE(p.refiner.wouldRefine(link)) << "a dark floor";
    p.h[floor].oracle = 1.0f;
    ASSERT_TRUE(p.refiner.wouldRefine(link));
    const LinkId id = p.refiner.attach(link);
    std::vector<LinkId> created;
    p.refiner.refine({id}, created);
    ASSERT_FALSE(created.empty());
    for (LinkId c : created) {
        EXPECT_EQ(p.links[c].source, p.h.polygonElement(1));
        EXPECT_EQ(p.h[p.links[c].receiver].parent, floor);
    }
}

// The count of active links the frames report is kept as links come and
// go: it equals every receiver's list summed, after links are attached,
// refined (unseen ones included), reinstated and removed.
TEST(Refiner, KeepsTheCountOfActiveLinks) {
    const Scene scene = emitterFloorBlocker(1.0, 5.0, horizontal(1.0, -1.0, 0.5, -1.0, 2.0, true));
    Refining r(scene, 1e-6);
    const Hierarchy& h = r.h;
    Refiner& refiner = r.refiner;
    const auto summed = [&] {
        std::size_t n = 0;
        for (ElementId e = 0; e < h.size(); ++e) n += h[e].links.size();
        return n;
    };
    EXPECT_EQ(refiner.activeLinks(), 0u);
    const LinkId first = refiner.attach(refiner.compute(h.polygonElement(0), h.polygonElement(1)));
    const LinkId second = refiner.attach(refiner.compute(h.polygonElement(0), h.polygonElement(2)));
    EXPECT_EQ(refiner.activeLinks(), 2u);
    std::vector<LinkId> created;
    refiner.refine({first}, created, true);  // the children's rays deferred
    ASSERT_FALSE(created.empty());
    EXPECT_EQ(refiner.activeLinks(), summed());
    refiner.castPendingRays(created);
    EXPECT_EQ(refiner.activeLinks(), summed());
    // Reinstated: the children go, the p-link is active again.
    for (LinkId c : created) refiner.remove(c);
    refiner.activate(first);
    EXPECT_EQ(refiner.activeLinks(), 2u);
    EXPECT_EQ(refiner.activeLinks(), summed());
    refiner.remove(second);
    refiner.remove(first);
    EXPECT_EQ(refiner.activeLinks(), 0u);
    EXPECT_EQ(summed(), 0u);
}

}  // namespace
}  // namespace rad
