// Known answers from ../shared/reference/KNOWN-ANSWERS.md: a lone receiver
// under an emitter reads rho E F; a closed glowing box reads E / (1 - rho).

#include <gtest/gtest.h>

#include <algorithm>

#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

double receiverMean(const Engine& engine) {
    for (const ObjectRadiosity& o : engine.objectRadiosity())
        if (o.name == "receiver") return o.radiosity.x;
    return -1.0;
}

double solvedReceiver(const Scene& scene, double epsilon) {
    EngineSettings settings;
    settings.epsilon = epsilon;
    Engine engine(scene, settings);
    engine.solve();
    EXPECT_TRUE(engine.stats().converged) << engine.stats().message;
    return receiverMean(engine);
}

// One link between the two whole squares already carries the exact transfer
// (the form factor is integrated, not approximated), so coarse and fine
// solutions both read rho E F.
TEST(KnownAnswers, ParallelSquaresReadRhoEF) {
    const double rho = 0.5, f = 0.199825;
    for (double epsilon : {1e-1, 1e-4, 1e-5})
        EXPECT_NEAR(solvedReceiver(test::parallelSquares(rho), epsilon), rho * f, 0.001 * rho * f) << epsilon;
}

TEST(KnownAnswers, PerpendicularSquaresReadRhoEFAndConvergeWithEpsilon) {
    const double rho = 0.8, f = 0.200044;
    std::vector<double> errors;
    for (double eps : {3e-2, 3e-3, 3e-4})
        errors.push_back(std::abs(solvedReceiver(test::perpendicularSquares(rho), eps) / (rho * f) - 1.0));
    EXPECT_LT(errors.back(), 0.01);
    // The coarsest solve is one link between the whole squares, whose form
    // factor is integrated to about 1e-7; the finer ones add the quadrature
    // error of many smaller pairs, which must stay within 1e-5.
    EXPECT_LT(errors.back(), std::max(errors.front(), 1e-5));
}

// A fine epsilon with a moderate area threshold (3 cm elements): the links
// then reach the leaves everywhere, and pushing a link's mean transfer down a
// coarser receiver (the hierarchical approximation, coarse next to the box's
// edges) no longer biases the answer. Measured: rho 0.9 reads 10.024.
void expectClosedBox(double rho, double meanTolerance, double vertexTolerance) {
    EngineSettings settings;
    settings.epsilon = 3e-5;
    settings.minArea = 1e-3;
    Engine engine(test::closedBox(rho), settings);
    const SolveStats& st = engine.solve();
    ASSERT_TRUE(st.converged) << st.message;
    const double expected = 1.0 / (1.0 - rho);
    EXPECT_NEAR(engine.objectRadiosity()[0].radiosity.x, expected, meanTolerance * expected);
    const MeshSnapshot mesh = compactMesh(engine.snapshot());
    for (const glm::vec3& c : mesh.colors) ASSERT_NEAR(c.x, expected, vertexTolerance * expected);
    // Closed: everything emitted is absorbed.
    EXPECT_NEAR(st.energy.absorbed / st.energy.emitted, 1.0, meanTolerance);
}

TEST(KnownAnswers, ClosedBoxHalfReflectiveReadsTwo) { expectClosedBox(0.5, 0.005, 0.04); }
TEST(KnownAnswers, ClosedBoxNinetyPercentReadsTen) { expectClosedBox(0.9, 0.005, 0.04); }

TEST(KnownAnswers, ClosedBoxNinetyNinePercentConvergesOrSaysSo) {
    EngineSettings settings;
    settings.epsilon = 1e-3;
    settings.minArea = 1e-2;
    // Plain sweeps fall by 0.99 each: 200 are too few, and the solve says so.
    settings.solve.extrapolate = false;
    settings.solve.maxIterations = 200;
    Engine engine(test::closedBox(0.99), settings);
    const SolveStats& st = engine.solve();
    EXPECT_FALSE(st.converged);
    EXPECT_NE(st.message.find("did not converge"), std::string::npos);

    settings.solve.maxIterations = 20000;
    Engine patient(test::closedBox(0.99), settings);
    const SolveStats& plain = patient.solve();
    ASSERT_TRUE(plain.converged);
    for (const ObjectRadiosity& o : patient.objectRadiosity()) EXPECT_NEAR(o.radiosity.x, 100.0, 1.0);  // 1%

    // Extrapolated (the default), the ratio 0.99 is taken out in a few steps:
    // far fewer sweeps, and closer to the answer than the plain sweeps'
    // tolerance allows.
    settings.solve.extrapolate = true;
    settings.solve.maxIterations = 200;
    Engine quick(test::closedBox(0.99), settings);
    const SolveStats& fast = quick.solve();
    ASSERT_TRUE(fast.converged) << fast.message;
    EXPECT_LT(fast.iterations * 10, plain.iterations) << fast.iterations << " vs " << plain.iterations << " sweeps";
    for (const ObjectRadiosity& o : quick.objectRadiosity()) EXPECT_NEAR(o.radiosity.x, 100.0, 0.01);  // 0.01%
}

// Extrapolation changes how fast the sweeps converge, not where to: with the
// links fixed (one round), the coloured Cornell box solved both ways agrees
// within the tolerance, in every channel.
TEST(KnownAnswers, ExtrapolatedSweepsConvergeToThePlainOnes) {
    EngineSettings settings;
    settings.maxRefineRounds = 1;
    settings.solve.tolerance = 1e-6;
    settings.solve.extrapolate = false;
    Engine plain(loadGltf(test::sourcePath("scenes/cornell-box.gltf")), settings);
    ASSERT_TRUE(plain.solve().converged);
    settings.solve.extrapolate = true;
    Engine quick(loadGltf(test::sourcePath("scenes/cornell-box.gltf")), settings);
    ASSERT_TRUE(quick.solve().converged);
    ASSERT_EQ(quick.linkCount(), plain.linkCount());
    const std::vector<ObjectRadiosity> a = plain.objectRadiosity(), b = quick.objectRadiosity();
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(b[i].radiosity[c], a[i].radiosity[c], 1e-4 * std::max(1e-3, a[i].radiosity[c])) << a[i].name;
    EXPECT_LT(compareSamples(quick.samples(), plain.samples()).rms, 1e-5);
}

TEST(Engine, RefusesASceneWithNothingThatEmits) {
    Scene s = test::parallelSquares(0.5);
    s.materials[0].emission = glm::dvec3(0.0);
    EXPECT_THROW(Engine(s, EngineSettings{}), SceneError);
}

}  // namespace
}  // namespace rad
