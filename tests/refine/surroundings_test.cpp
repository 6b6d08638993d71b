// How much of the scene a point sees (refine/Surroundings.h), and the
// thresholds taken relative to it (EngineSettings::localThresholds): a row of
// closed rooms is refined in each room about as the room alone is.

#include "refine/Surroundings.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "geometry/RayCaster.h"
#include "radiosity/Engine.h"
#include "support/Motion.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

// `count` copies of roomWithBlock side by side along x, 1 m apart, each
// closed; the objects of copy k are named "room-k-NAME".
Scene rowOfRooms(int count) {
    const Scene room = test::roomWithBlock();
    Scene row;
    row.sourcePath = "row-of-rooms";
    row.materials = room.materials;
    for (int k = 0; k < count; ++k) {
        const glm::dvec3 offset(5.0 * k, 0.0, 0.0);
        for (const Object& o : room.objects) {
            Object copy = o;
            copy.name = "room-" + std::to_string(k) + "-" + o.name;
            copy.firstPolygon = static_cast<std::uint32_t>(row.polygons.size());
            const auto object = static_cast<std::uint32_t>(row.objects.size());
            for (std::uint32_t i = 0; i < o.polygonCount; ++i) {
                Polygon p = room.polygons[o.firstPolygon + i];
                p.object = object;
                for (int v = 0; v < p.vertexCount; ++v) p.vertices[v] += offset;
                row.polygons.push_back(p);
            }
            row.objects.push_back(copy);
        }
    }
    return row;
}

Surroundings surroundingsOf(const Scene& scene) {
    RayCaster rays;
    rays.setFrame(scene.bounds());
    std::vector<std::uint32_t> all(scene.polygons.size());
    for (std::uint32_t p = 0; p < all.size(); ++p) all[p] = p;
    rays.setLayer(Layer::Static, scene, all);
    return measureSurroundings(scene, rays);
}

double shareOf(const Scene& scene) { return surroundingsOf(scene).visibleShare; }

// A point on a face of a closed cube sees the other five faces: 5/6 of the
// area (a little less: a grazing hit counts for at most five times its
// head-on area).
TEST(Surroundings, APointInAClosedBoxSeesTheOtherFaces) {
    EXPECT_NEAR(shareOf(test::closedBox(0.5)), 5.0 / 6.0, 0.08);
}

// Rooms that cannot see one another: each point sees its own room, so the
// share of the whole falls as the rooms multiply.
TEST(Surroundings, RoomsSideBySideEachSeeTheirOwn) {
    const double one = shareOf(rowOfRooms(1));
    EXPECT_GT(one, 0.5);
    for (int count : {2, 8})
        EXPECT_NEAR(shareOf(rowOfRooms(count)) * count, one, 0.1 * one) << count << " rooms";
}

// A ground plane 100 m wide with a box and a lamp on it: a point sees
// little of the scene because it sees the sky, not because walls close it
// in. Its thresholds stay the whole scene's (they would be 256 times finer).
TEST(Surroundings, AnOpenSceneKeepsTheWholeScenesThresholds) {
    using V = glm::dvec3;
    Scene s;
    const auto grey = test::addMaterial(s, V(0.5), V(0.0), "grey");
    const auto lamp = test::addMaterial(s, V(0.0), V(10.0), "lamp");
    test::addQuadObject(s, "ground", grey,
                        {{V(-50, 0, -50), V(-50, 0, 50), V(50, 0, 50), V(50, 0, -50)}});
    test::addQuadObject(s, "box", grey, test::boxFaces(V(0.0), V(1.0), false));
    test::addQuadObject(s, "lamp", lamp, {{V(0, 3, 0), V(1, 3, 0), V(1, 3, 1), V(0, 3, 1)}});
    const Surroundings open = surroundingsOf(s);
    EXPECT_LT(open.visibleShare, 0.01);
    EXPECT_GT(open.escapedShare, kOpenShare);
    EXPECT_EQ(thresholdScale(open), 1.0);
    // Closed rooms leave nothing: their share decides.
    const Surroundings row = surroundingsOf(rowOfRooms(8));
    EXPECT_EQ(row.escapedShare, 0.0);
    EXPECT_LT(thresholdScale(row), 1.0);
}

TEST(LocalThresholds, ARoomIsRefinedAsItWasAlone) {
    const EngineSettings settings;
    Engine alone(rowOfRooms(1), settings);
    ASSERT_TRUE(alone.solve().converged);
    EXPECT_EQ(alone.stats().thresholdScale, 1.0)
        << "a single room keeps the whole scene's thresholds";
    constexpr int kRooms = 8;
    Engine row(rowOfRooms(kRooms), settings);
    ASSERT_TRUE(row.solve().converged);
    EngineSettings whole = settings;
    whole.localThresholds = false;
    Engine coarse(rowOfRooms(kRooms), whole);
    ASSERT_TRUE(coarse.solve().converged);
    EXPECT_EQ(coarse.stats().thresholdScale, 1.0);
    // The row's thresholds: its share over a room's, rounded down to a
    // power of two.
    const double scale = row.stats().thresholdScale,
                 share = shareOf(rowOfRooms(kRooms)) / kRoomShare;
    EXPECT_LE(scale, share);
    EXPECT_GT(scale, 0.5 * share);
    // Links per room: near the room alone's, where the whole scene's
    // thresholds make far fewer. (A point of this room sees 0.72 of it,
    // more than kRoomShare: the row's reference power is twice a room's.)
    const double linksAlone = double(alone.stats().links);
    EXPECT_GT(double(row.stats().links) / kRooms, 0.5 * linksAlone);
    EXPECT_LT(double(coarse.stats().links) / kRooms, 0.25 * linksAlone);
    // Each object of a room against the room alone.
    // "room-k-NAME" -> NAME
    const auto part = [](const std::string& name) { return name.substr(name.find('-', 5) + 1); };
    std::map<std::string, double> reference;
    for (const ObjectRadiosity& o : alone.objectRadiosity())
        reference[part(o.name)] = luminance(o.radiosity);
    const auto worst = [&](const Engine& e) {
        double w = 0.0;
        for (const ObjectRadiosity& o : e.objectRadiosity()) {
            const double b = reference.at(part(o.name));
            if (b > 0.0) w = std::max(w, std::abs(luminance(o.radiosity) - b) / b);
        }
        return w;
    };
    const double local = worst(row), global = worst(coarse);
    // Measured: 0.22% against 1.23% with the whole scene's thresholds.
    EXPECT_LT(local, 0.005) << "whole-scene thresholds: " << global;
    EXPECT_GT(global, 2.0 * local);
}

// A closed room on a ground plane 1 km wide: the plane makes the scene open
// and 10,000 times larger, so the whole scene's area threshold (20 m^2)
// would leave the room's walls and block whole. The room's objects see the
// room, not the sky: they take the scene's closed part's threshold, near the
// room's alone, and their light is the room's alone; the plane keeps the
// whole scene's.
TEST(LocalThresholds, AClosedRoomOnAWidePlaneIsMeshedAsItWasAlone) {
    using V = glm::dvec3;
    const EngineSettings settings;
    // Its light hangs 1 mm under the ceiling: that once counted as touching
    // it on the site, a millionth of the plane's 1 km (the coincidence
    // tolerance is now the end polygons' own: geometry/RayCaster.h), and
    // the room was 75% darker.
    const Scene room = rowOfRooms(1);
    Engine alone(room, settings);
    ASSERT_TRUE(alone.solve().converged);
    Scene site = room;
    const auto ground = test::addMaterial(site, V(0.3), V(0.0), "ground");
    test::addQuadObject(site, "ground", ground,
                        {{V(-500, -0.01, -500), V(-500, -0.01, 500), V(500, -0.01, 500), V(500, -0.01, -500)}});
    Engine local(site, settings);
    ASSERT_TRUE(local.solve().converged);
    EngineSettings whole = settings;
    whole.localThresholds = false;
    Engine coarse(site, whole);
    ASSERT_TRUE(coarse.solve().converged);
    EXPECT_EQ(local.stats().thresholdScale, 1.0) << "an open scene keeps the whole scene's reference power";
    EXPECT_EQ(local.stats().minArea, coarse.stats().minArea) << "and, on the plane, its area threshold";
    const double roomArea = alone.stats().minArea, closedPart = local.stats().minAreaSmallest;
    EXPECT_GT(closedPart, 0.25 * roomArea);
    EXPECT_LT(closedPart, 4.0 * roomArea);
    std::map<std::string, double> reference;
    for (const ObjectRadiosity& o : alone.objectRadiosity()) reference[o.name] = luminance(o.radiosity);
    const auto worst = [&](const Engine& e) {
        double w = 0.0;
        for (const ObjectRadiosity& o : e.objectRadiosity())
            if (const auto it = reference.find(o.name); it != reference.end() && it->second > 0.0)
                w = std::max(w, std::abs(luminance(o.radiosity) - it->second) / it->second);
        return w;
    };
    const double near = worst(local), far = worst(coarse);
    std::printf("  area thresholds: room alone %.3g m^2, its part of the site %.3g, the site %.3g; worst object "
                "%.2f%% from alone (whole-scene thresholds: %.2f%%)\n",
                roomArea, closedPart, local.stats().minArea, 100.0 * near, 100.0 * far);
    // Measured: 2.2% (two walls' form factors sum to 1.12 on the site, and
    // the energy guard scales them down) against 7.8% with the whole
    // scene's thresholds, and 75% with the frame's coincidence tolerance.
    EXPECT_LT(near, 0.03);
    EXPECT_GT(far, 2.0 * near);
}

}  // namespace
}  // namespace rad
