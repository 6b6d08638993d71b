// Numerical stability of the solve and the update at the extremes: error
// thresholds far too coarse or far too fine (memory cap), reflectance near 1,
// scenes a thousand times smaller or larger, and moves of a micrometre or of
// a hundred scene sizes.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "radiosity/Engine.h"
#include "refine/Refiner.h"  // luminance()
#include "radiosity/Gltf.h"
#include "support/Motion.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;
using Clock = std::chrono::steady_clock;
using test::allFinite;
using test::secondsSince;
using test::translation;

bool finiteEnergy(const EnergyBalance& e) {
    return std::isfinite(e.emitted) && std::isfinite(e.absorbed) && std::isfinite(e.received) &&
           std::isfinite(e.reflected) && e.emitted > 0.0;
}

using test::roomWithBlock;

Scene cornellBox() { return loadGltf(test::sourcePath("scenes/cornell-box.gltf")); }

TEST(Stability, EpsilonExtremes) {
    const auto start = Clock::now();
    // Far too coarse: only the links that cluster pairs force are refined.
    EngineSettings coarse;
    coarse.epsilon = 10.0;
    Engine rough(cornellBox(), coarse);
    const SolveStats& r = rough.solve();
    std::printf("  epsilon 10: converged %d, %zu links, %zu elements, %d rounds, message '%s'\n", r.converged,
                rough.linkCount(), r.elements, r.refineRounds, r.message.c_str());
    EXPECT_TRUE(r.converged) << r.message;
    EXPECT_TRUE(allFinite(rough.samples()));
    EXPECT_TRUE(finiteEnergy(rough.energy()));
    EngineSettings normal;
    normal.epsilon = 1e-3;
    Engine reference(cornellBox(), normal);
    ASSERT_TRUE(reference.solve().converged);
    EXPECT_LT(rough.linkCount(), reference.linkCount());

    // Far too fine: the memory limit stops the refinement, and the solve says
    // it did not converge.
    EngineSettings fine;
    fine.epsilon = 1e-9;
    fine.maxMemoryBytes = 32u << 20;
    Engine capped(cornellBox(), fine);
    const auto t = Clock::now();
    const SolveStats& c = capped.solve();
    std::printf("  epsilon 1e-9, limit %zu MiB: converged %d, %zu links (%zu active, %zu passive), %zu elements, "
                "%d rounds, %.2f s, %zu MiB, message '%s'\n",
                fine.maxMemoryBytes >> 20, c.converged, capped.linkCount(), c.links, c.passiveLinks, c.elements,
                c.refineRounds, secondsSince(t), capped.memory().total() >> 20, c.message.c_str());
    EXPECT_EQ(c.stoppedBy, "memory_limit");
    EXPECT_FALSE(c.converged);
    // The limit is checked before each refinement batch, on what the
    // containers hold (their capacities add some slack).
    EXPECT_LE(capped.memory().total(), 2 * fine.maxMemoryBytes);
    EXPECT_TRUE(allFinite(capped.samples()));
    EXPECT_TRUE(finiteEnergy(capped.energy()));
    const SolutionError e = compareSamples(capped.samples(), reference.samples());
    std::printf("  capped vs epsilon 1e-3: rms %.4f; test %.2f s\n", e.rms, secondsSince(start));
    EXPECT_TRUE(std::isfinite(e.rms));
}

// Reflectance near 1 needs many sweeps: with too few, the solve must say so,
// never report a converged wrong answer.
TEST(Stability, ReflectanceNearOne) {
    const auto start = Clock::now();
    for (double rho : {0.99, 0.999}) {
        for (int maxIterations : {100, 2000, 20000}) {
            if (rho == 0.99 && maxIterations > 2000) continue;
            EngineSettings settings;
            settings.epsilon = 1e-3;
            settings.minArea = 1e-2;
            settings.solve.maxIterations = maxIterations;
            Engine engine(test::closedBox(rho), settings);
            const SolveStats& st = engine.solve();
            const double expected = 1.0 / (1.0 - rho);
            const double b = engine.objectRadiosity()[0].radiosity.x;
            std::printf("  rho %.3f, at most %d sweeps: converged %d after %d sweeps, B %.3f (exact %.1f, %+.3f%%), "
                        "message '%s'\n",
                        rho, maxIterations, st.converged, st.iterations, b, expected, 100.0 * (b / expected - 1.0),
                        st.message.c_str());
            EXPECT_TRUE(std::isfinite(b));
            if (st.converged) {
                EXPECT_NEAR(b, expected, 0.01 * expected) << "rho " << rho << ": converged to a wrong answer";
            } else {
                EXPECT_NE(st.message.find("did not converge"), std::string::npos) << st.message;
            }
        }
    }
    std::printf("  test %.2f s\n", secondsSince(start));
}

// The same room at 1e-3, 1 and 1e3 scale gives the same per-object radiosity.
// It guards a fixed bug: the block's sub-clusters depend on rounding at each
// scale, and when all rays from the light's cluster to the block cluster's
// sample points were blocked, the link got visibility 0 and was never
// refined, leaving the block's top face unlit at most scales. Links with a
// cluster end are now judged by their unoccluded transfer (Refiner::wouldRefine).
TEST(Stability, ScaleInvariance) {
    const auto start = Clock::now();
    const EngineSettings settings;
    std::vector<ObjectRadiosity> base;
    std::size_t baseLinks = 0;
    for (double scale : {1.0, 1e-3, 1e3}) {
        Engine engine(roomWithBlock(scale), settings);
        const SolveStats& st = engine.solve();
        ASSERT_TRUE(st.converged) << "scale " << scale << ": " << st.message;
        const std::vector<ObjectRadiosity> objects = engine.objectRadiosity();
        if (scale == 1.0) {
            base = objects;
            baseLinks = engine.linkCount();
            std::printf("  scale 1: %zu links, %zu elements, minArea %.3g\n", baseLinks, st.elements, st.minArea);
            continue;
        }
        ASSERT_EQ(objects.size(), base.size());
        double worst = 0.0;
        std::string worstName;
        for (std::size_t i = 0; i < objects.size(); ++i) {
            const double ref = luminance(base[i].radiosity);
            const double d = std::abs(luminance(objects[i].radiosity) - ref) / std::max(ref, 1e-12);
            if (d > worst) {
                worst = d;
                worstName = objects[i].name;
            }
            EXPECT_NEAR(luminance(objects[i].radiosity), ref, 1e-3 * ref) << "scale " << scale << ", " << objects[i].name;
        }
        std::printf("  scale %g: %zu links (scale 1: %zu), %zu elements, minArea %.3g; largest relative difference "
                    "%.2e (%s)\n",
                    scale, engine.linkCount(), baseLinks, st.elements, st.minArea, worst, worstName.c_str());
    }
    std::printf("  test %.2f s\n", secondsSince(start));
}

// A room lit by a point light inside a lampshade: an open cylinder of 16
// sides, each a quad with a back face of its own (as a doubleSided material
// is imported), moved `offset` from the origin.
Scene roomWithLampshade(const V& offset) {
    Scene s;
    s.sourcePath = "room-with-lampshade";
    const auto white = test::addMaterial(s, V(0.8), V(0.0), "white");
    const auto shade = test::addMaterial(s, V(0.9, 0.85, 0.7), V(0.0), "shade");
    test::addQuadObject(s, "room", white, test::boxFaces(V(0.0), V(4.0, 2.6, 3.5), true));
    std::vector<std::array<V, 4>> sides;
    const V centre(3.0, 1.4, 2.5);
    const double r = 0.2, h = 0.3, step = 2.0 * std::numbers::pi / 16.0;
    for (int k = 0; k < 16; ++k) {
        const V a = centre + V(r * std::cos(k * step), 0.0, r * std::sin(k * step));
        const V b = centre + V(r * std::cos((k + 1) * step), 0.0, r * std::sin((k + 1) * step));
        sides.push_back({a, a + V(0, h, 0), b + V(0, h, 0), b});  // facing out
        sides.push_back({b, b + V(0, h, 0), a + V(0, h, 0), a});  // its back, facing in
    }
    test::addQuadObject(s, "shade", shade, sides);
    PunctualLight bulb;
    bulb.name = "bulb";
    bulb.position = centre + V(0.0, 0.5 * h, 0.0);
    bulb.intensity = V(5.0);
    s.lights.push_back(bulb);
    for (Polygon& p : s.polygons)
        for (int k = 0; k < p.vertexCount; ++k) p.vertices[k] += offset;
    for (PunctualLight& l : s.lights) l.position += offset;
    return s;
}

// The same room 1 km and 1000 km from the origin gives the light it gets at
// the origin. It guards fixed bugs: polygon normals taken from absolute
// coordinates (Newell's sum, rounded by the distance squared), cluster
// sample points stored as floats in world coordinates (6e-5 m coarse at
// 1 km), and a point on a back face 1e-10 m off its twin (rounded at 1000
// km) seeing it as a hemisphere. The lampshade took up to 12% more light
// than the bulb sent.
TEST(Stability, FarFromTheOriginSolvesAsAtIt) {
    const auto start = Clock::now();
    std::vector<ObjectRadiosity> base;
    for (double distance : {0.0, 1e3, 1e6}) {
        Engine engine(roomWithLampshade(V(distance, 0.5 * distance, -distance)), EngineSettings{});
        const SolveStats& st = engine.solve();
        ASSERT_TRUE(st.converged) << distance << " m: " << st.message;
        const EnergyBalance e = engine.energy();
        const std::vector<ObjectRadiosity> objects = engine.objectRadiosity();
        std::printf("  %g m: %zu elements, absorbed %.4f created %.2e of the emitted;", distance, st.elements,
                    e.absorbed / e.emitted, e.created / e.emitted);
        for (const ObjectRadiosity& o : objects) std::printf(" %s %.4f", o.name.c_str(), luminance(o.radiosity));
        std::printf("\n");
        EXPECT_LE(e.created, 1e-6 * e.emitted) << distance << " m";
        EXPECT_LE(e.absorbed, e.emitted) << distance << " m";
        if (distance == 0.0) {
            base = objects;
            continue;
        }
        // The vertices round differently at each distance (doubles are 1e-10 m coarse 1000 km out),
        // and a few refinement decisions with them: 5e-4 and 1.5e-3 apart in the runs measured,
        // 3.3e-3 on the shade since the energy guard cuts what clusters send before the surfaces'
        // links (a link to the shade's inside refined or not is then treated apart).
        const double within = 4e-3;
        ASSERT_EQ(objects.size(), base.size());
        for (std::size_t i = 0; i < objects.size(); ++i) {
            const double ref = luminance(base[i].radiosity);
            EXPECT_NEAR(luminance(objects[i].radiosity), ref, within * ref) << distance << " m, " << objects[i].name;
        }
    }
    std::printf("  test %.2f s\n", secondsSince(start));
}

// The same room with a 10 cm triangle 10 km and 100 km away (a CAD export's
// leftover): the light is the room's alone, and so is the energy audit. It
// guards fixed bugs: Embree's frame followed the bounds, so its float
// coordinates and absolute tolerances were those of a 100 km scene, and the
// audit's rays started a millionth of the bounds (10 cm at 100 km) off
// their surfaces, behind the lampshade.
TEST(Stability, AStrayPolygonFarAwayChangesNothing) {
    // Four times the default epsilon: the bugs were in the frame of the rays
    // and the audit's offsets, which any refinement meets (16 s under the
    // sanitizers at the default).
    EngineSettings coarser;
    coarser.epsilon *= 4.0;
    const auto withStray = [](double distance) {
        Scene s = roomWithLampshade(V(0.0));
        if (distance > 0.0)
            test::addQuadObject(s, "stray", 0,
                                {{V(distance, 0, 0), V(distance + 0.1, 0, 0), V(distance + 0.1, 0.1, 0), V(distance, 0.1, 0)}});
        return s;
    };
    Engine alone(withStray(0.0), coarser);
    ASSERT_TRUE(alone.solve().converged);
    const std::vector<ObjectRadiosity> base = alone.objectRadiosity();
    const EnergyBalance baseEnergy = alone.energy();
    for (double distance : {1e4, 1e5}) {
        Engine engine(withStray(distance), coarser);
        ASSERT_TRUE(engine.solve().converged) << distance;
        const EnergyBalance e = engine.energy();
        std::printf("  stray %g m away: absorbed %.4f back faces %.4f of the emitted (alone %.4f, %.4f)\n", distance,
                    e.absorbed / e.emitted, e.backFaces / e.emitted, baseEnergy.absorbed / baseEnergy.emitted,
                    baseEnergy.backFaces / baseEnergy.emitted);
        EXPECT_NEAR(e.absorbed / e.emitted, baseEnergy.absorbed / baseEnergy.emitted, 2e-3) << distance;
        EXPECT_NEAR(e.backFaces / e.emitted, baseEnergy.backFaces / baseEnergy.emitted, 2e-3) << distance;
        const std::vector<ObjectRadiosity> objects = engine.objectRadiosity();
        for (std::size_t i = 0; i < base.size(); ++i) {
            const double ref = luminance(base[i].radiosity);
            EXPECT_NEAR(luminance(objects[i].radiosity), ref, 3e-3 * ref) << distance << " m, " << base[i].name;
        }
    }
}

TEST(Stability, TinyAndHugeMoves) {
    const auto start = Clock::now();
    EngineSettings settings;
    settings.epsilon = 1e-3;
    // With the block's edges exactly on the light's edge lines and on the
    // binary subdivision grid (the room of line_space_update_test.cpp), a
    // micrometre flips visibility rays that pass exactly through its edges
    // (measured rms 3.5e-4, then 2e-8 for the next micrometre): moved off.
    Engine engine(roomWithBlock(1.0, V(0.0123, 0.0086, 0.0161)), settings);
    ASSERT_TRUE(engine.solve().converged);
    const RadiositySamples solved = engine.samples();

    // A move to where it already is. Engine issue (reported): it is not a
    // no-op: it reinstates a few p-links that the solve left refined (in the
    // unshifted room: 3, the block's bottom changes by up to 2.5%, rms 3.5e-4;
    // here 5, rms 1.9e-4), so the tiny move is compared with the state after it.
    FrameStats f = engine.moveDynamicObject(glm::dmat4(1.0));
    const SolutionError null = compareSamples(engine.samples(), solved);
    std::printf("  no motion: rms %.2e max %.2e (reinstated %zu, refined %zu)\n", null.rms, null.max, f.reinstated,
                f.refined);
    const RadiositySamples original = engine.samples();

    // A micrometre.
    f = engine.moveDynamicObject(translation(V(1e-6, 0.0, 0.0)));
    const SolutionError tiny = compareSamples(engine.samples(), original);
    std::printf("  1e-6 m: rms %.2e max %.2e (linksUpdated %zu, refined %zu); vs the solve rms %.2e\n", tiny.rms,
                tiny.max, f.linksUpdated, f.refined, compareSamples(engine.samples(), solved).rms);
    EXPECT_LT(tiny.rms, 1e-4);
    ASSERT_TRUE(allFinite(engine.samples()));

    // Across the room (block x, z 1.5..2.2 to 0.1..0.8, then to 3.2..3.9),
    // then a hundred room sizes away, and back.
    const V path[] = {V(-1.4, 0.0, -1.4), V(1.7, 0.5, 1.7), V(400.0, 0.0, 0.0), V(-400.0, 300.0, 400.0),
                      V(1.7, 0.0, -1.4)};
    for (const V& p : path) {
        f = engine.moveDynamicObject(translation(p));
        const RadiositySamples s = engine.samples();
        const SolutionError e = compareSamples(s, original);
        std::printf("  at (%g, %g, %g): rms vs start %.4f, linksUpdated %zu, bounces %d\n", p.x, p.y, p.z, e.rms,
                    f.linksUpdated, f.bounces);
        ASSERT_TRUE(allFinite(s)) << p.x << " " << p.y << " " << p.z;
        EXPECT_TRUE(finiteEnergy(engine.energy()));
    }
    engine.moveDynamicObject(glm::dmat4(1.0));
    const FrameStats idle = engine.refinePending();
    const SolutionError back = compareSamples(engine.samples(), original);
    std::printf("  back (refinePending refined %zu): rms %.2e max %.2e; test %.2f s\n", idle.refined, back.rms,
                back.max, secondsSince(start));
    RecordProperty("rms_tiny", std::to_string(tiny.rms));
    RecordProperty("rms_back", std::to_string(back.rms));
    EXPECT_LT(back.rms, 1e-3);
    EXPECT_LT(compareSamples(engine.samples(), solved).rms, 1e-3);
    EXPECT_TRUE(allFinite(engine.samples()));
}

}  // namespace
}  // namespace rad
