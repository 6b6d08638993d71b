// The energy guard (Solver::arriving): a leaf whose links' form factors sum
// past one over-counts its view. The excess is taken from what clusters and
// what surfaces send in proportion to how uncertain each sum is; the
// surfaces' links are divided whole only when they alone sum past one.

#include <gtest/gtest.h>

#include "hierarchy/Hierarchy.h"
#include "links/Link.h"
#include "radiosity/Engine.h"
#include "solve/Solver.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;

struct OneLeaf {
    Scene scene = test::parallelSquares(0.5);
    Hierarchy h{scene, 1e-6};
    LinkStore links;
    Solver solver{h, links};
};

Solver::Down arrives(double surfaces, double clusters) {
    Solver::Down d;
    d.irradiance = V(2.0) * surfaces;  // from surfaces of radiosity 2
    d.formFactorSum = surfaces;
    d.clusterIrradiance = V(5.0) * clusters;  // from clusters of radiosity 5
    d.clusterSum = clusters;
    return d;
}

// The excess divides as the two sums' variances, (k S_c)^2 against S_s^2.
V expected(double surfaces, double clusters) {
    const double k = Solver::kClusterUncertainty;
    const double excess = surfaces + clusters - 1.0;
    const double vc = k * k * clusters * clusters, vs = surfaces * surfaces;
    const double fromClusters = excess * vc / (vc + vs);
    return V(2.0 * (surfaces - (excess - fromClusters)) + 5.0 * (clusters - fromClusters));
}

TEST(EnergyGuard, CoarseClusterLinksGiveWayToTheSurfacesLinks) {
    OneLeaf leaf;
    // 0.9 from surfaces, 0.3 from clusters: the clusters give 92% of the
    // excess, the surfaces' light is nearly whole.
    const V got = leaf.solver.arriving(arrives(0.9, 0.3), 0);
    EXPECT_NEAR(got.x, expected(0.9, 0.3).x, 1e-12);
    EXPECT_GT(got.x, 2.0 * 0.9 * 0.98);
    EXPECT_LT(got.x, 2.0 * 0.9 + 5.0 * 0.3 * 0.4);
    // The surfaces alone past one: everything is divided by the sum, as an
    // enclosure of those radiosities would send at most.
    const V over = leaf.solver.arriving(arrives(1.2, 0.3), 0);
    EXPECT_NEAR(over.x, (2.0 * 1.2 + 5.0 * 0.3) / 1.5, 1e-12);
    // Under one, nothing is scaled (and with no closure measured, nothing
    // is filled).
    EXPECT_EQ(leaf.solver.arriving(arrives(0.6, 0.3), 0), V(2.0 * 0.6 + 5.0 * 0.3));
    // Without the guard, nothing either.
    leaf.solver.setEnergyGuard(false);
    EXPECT_EQ(leaf.solver.arriving(arrives(0.9, 0.3), 0), V(2.0 * 0.9 + 5.0 * 0.3));
}

// A lamp whose light arrives on a cluster link of small form factor (a grid
// of small LEDs seen from below) is barely cut by the surfaces' slight
// excess: cut first, 0.006 of view against an excess of 0.004 lost two
// thirds of the lamp's light.
TEST(EnergyGuard, ALampOnASmallClusterLinkKeepsItsLight) {
    OneLeaf leaf;
    const V got = leaf.solver.arriving(arrives(0.998, 0.006), 0);
    EXPECT_NEAR(got.x, expected(0.998, 0.006).x, 1e-12);
    const double lamp = got.x - 2.0 * 0.998 * (1.0 - 0.004);  // at most all the excess from the surfaces
    EXPECT_GT(lamp, 5.0 * 0.006 * 0.99);
    // And never more than the links bring without the guard.
    EXPECT_LE(got.x, 2.0 * 0.998 + 5.0 * 0.006);
}

// A closed room (reflectance 0.7) with a table, lit either by one ceiling
// panel or by a grid of small LEDs over the same area with the same power,
// 1 mm under the ceiling and facing down. Each LED is under the area
// threshold, so their light reaches the room on links from their cluster.
// From the table 2.25 m below, the grid is the panel: the same light, and
// the guard takes little of it. (With the clusters cut first, the grid lost
// 8.9% of its light and the table got 24% less than under the panel.)
Scene ledRoom(int nx, int nz) {
    Scene s;
    s.sourcePath = "led-room";
    const auto wall = test::addMaterial(s, V(0.7), V(0.0), "wall");
    const auto wood = test::addMaterial(s, V(0.5, 0.35, 0.2), V(0.0), "wood");
    test::addQuadObject(s, "room", wall, test::boxFaces(V(0.0), V(5.0, 3.0, 4.0), true));
    test::addQuadObject(s, "table", wood, test::boxFaces(V(1.5, 0.0, 1.2), V(3.5, 0.75, 2.8), false));
    // The lit area: x in [1, 4], z in [1, 3]; 120 W in all.
    const double y = 2.999, size = 0.02;
    const bool panel = nx == 0;
    const double each = panel ? 6.0 : size * size;
    const auto glow = test::addMaterial(s, V(0.8), V(120.0 / (each * (panel ? 1 : nx * nz))), "glow");
    std::vector<std::array<V, 4>> quads;
    const auto down = [&](double x0, double x1, double z0, double z1) {
        quads.push_back({V(x0, y, z0), V(x1, y, z0), V(x1, y, z1), V(x0, y, z1)});
    };
    if (panel) down(1.0, 4.0, 1.0, 3.0);
    for (int i = 0; i < nx; ++i)
        for (int k = 0; k < nz; ++k) {
            const double x = 1.0 + (i + 0.5) * 3.0 / nx, z = 1.0 + (k + 0.5) * 2.0 / nz;
            down(x - size / 2, x + size / 2, z - size / 2, z + size / 2);
        }
    test::addQuadObject(s, "lamp", glow, quads);
    return s;
}

TEST(EnergyGuard, AGridOfSmallLedsLightsTheRoomAsOnePanel) {
    struct Lit {
        double table = 0.0, lost = 0.0;  // the table's radiosity, the share of the light lost
    };
    const auto solve = [](const Scene& scene, bool guard) {
        EngineSettings settings;
        settings.energyGuard = guard;
        Engine engine(scene, settings);
        EXPECT_TRUE(engine.solve().converged);
        const EnergyBalance e = engine.energy();
        Lit lit;
        lit.lost = e.lost / e.emitted;
        for (const ObjectRadiosity& o : engine.objectRadiosity())
            if (o.name == "table") lit.table = luminance(o.radiosity);
        return lit;
    };
    const Lit panel = solve(ledRoom(0, 0), true);
    const Lit leds = solve(ledRoom(10, 8), true);
    const Lit unguarded = solve(ledRoom(10, 8), false);
    EXPECT_NEAR(leds.table, panel.table, 0.05 * panel.table);
    // The guard takes little of the grid's light: 0.4% of it beside the
    // 0.7% its coarse links lose (8.2% beside them with the clusters cut
    // first).
    EXPECT_LT(std::abs(panel.lost), 0.01);
    EXPECT_LT(leds.lost, 0.015);
    EXPECT_LT(leds.lost - unguarded.lost, 0.005);
}

}  // namespace
}  // namespace rad
