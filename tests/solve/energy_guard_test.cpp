// The energy guard (Solver::arriving): a leaf whose links' form factors sum
// past one over-counts its view. What clusters send gives way first; the
// surfaces' links are divided only when they alone sum past one.

#include <gtest/gtest.h>

#include "hierarchy/Hierarchy.h"
#include "links/Link.h"
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

TEST(EnergyGuard, WhatClustersSendGivesWayToTheSurfacesLinks) {
    OneLeaf leaf;
    // 0.9 from surfaces, 0.3 from clusters: the clusters' share is cut to
    // 0.1, the surfaces' light is whole.
    EXPECT_NEAR(leaf.solver.arriving(arrives(0.9, 0.3), 0).x, 2.0 * 0.9 + 5.0 * 0.1, 1e-12);
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

}  // namespace
}  // namespace rad
