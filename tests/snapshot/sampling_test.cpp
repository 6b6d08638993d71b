// compareSamples (radiosity/Snapshot.h) on hand-made sample sets: the scene
// figures as before, and per object the error over the object's own mean.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "radiosity/Snapshot.h"

namespace rad {
namespace {

struct Sample {
    std::uint32_t object;
    double weight;
    double reference;
    double solution;
};

// The two sample sets of one scene.
struct Pair {
    RadiositySamples solution, reference;
};

Pair samples(const std::vector<Sample>& list) {
    Pair p;
    for (const Sample& s : list) {
        p.reference.luminance.push_back(s.reference);
        p.solution.luminance.push_back(s.solution);
        for (RadiositySamples* set : {&p.reference, &p.solution}) {
            set->weight.push_back(s.weight);
            set->object.push_back(s.object);
        }
    }
    return p;
}

// A bright object 0 (reference 10 everywhere, one sample 1 off) and a dim
// object 1 (reference 0.5 and 1.5 on equal areas, mean 1, both 0.2 off).
TEST(Sampling, PerObjectErrorsUseTheObjectsOwnMean) {
    const Pair p = samples({
        {0, 1.0, 10.0, 10.0},
        {0, 1.0, 10.0, 11.0},
        {1, 0.5, 0.5, 0.7},
        {1, 0.5, 1.5, 1.3},
    });
    const SolutionError e = compareSamples(p.solution, p.reference);
    // The scene: mean (10 + 10 + 0.25 + 0.75) / 3 = 7; RMS sqrt((1 + 0.02 + 0.02) / 3).
    EXPECT_NEAR(e.rms, std::sqrt(1.04 / 3.0) / 7.0, 1e-12);
    EXPECT_NEAR(e.max, 1.0 / 7.0, 1e-12);

    ASSERT_EQ(e.objects.size(), 2u);
    const ObjectError& bright = e.objects[0];
    EXPECT_EQ(bright.object, 0u);
    EXPECT_NEAR(bright.mean, 10.0, 1e-12);
    EXPECT_NEAR(bright.rms, std::sqrt(0.5) / 10.0, 1e-12);
    EXPECT_NEAR(bright.max, 0.1, 1e-12);
    EXPECT_FALSE(bright.dark);
    // The dim object's 0.2 is 20% of its own light, 3% of the scene's.
    const ObjectError& dim = e.objects[1];
    EXPECT_EQ(dim.object, 1u);
    EXPECT_NEAR(dim.mean, 1.0, 1e-12);
    EXPECT_NEAR(dim.rms, 0.2, 1e-12);
    EXPECT_NEAR(dim.max, 0.2, 1e-12);
    EXPECT_FALSE(dim.dark);
    EXPECT_NEAR(e.worstObjectRms, 0.2, 1e-12);
}

TEST(Sampling, DarkObjectsAreLeftOutOfTheWorst) {
    // Object 1 holds 1e-4 of the scene's mean (< 1e-3): dark; its error is
    // large over its own mean, and reported, but not the worst.
    const Pair p = samples({
        {0, 1.0, 1.0, 1.01},
        {1, 1.0, 2e-4, 4e-4},
        {2, 1.0, 0.0, 0.0},   // black in both: no error
        {3, 1.0, 0.0, 1e-6},  // black in the reference only: infinitely off
    });
    const SolutionError e = compareSamples(p.solution, p.reference);
    ASSERT_EQ(e.objects.size(), 4u);
    EXPECT_FALSE(e.objects[0].dark);
    EXPECT_TRUE(e.objects[1].dark);
    EXPECT_NEAR(e.objects[1].rms, 1.0, 1e-9);
    EXPECT_TRUE(e.objects[2].dark);
    EXPECT_EQ(e.objects[2].rms, 0.0);
    EXPECT_EQ(e.objects[2].max, 0.0);
    EXPECT_TRUE(e.objects[3].dark);
    EXPECT_EQ(e.objects[3].rms, std::numeric_limits<double>::infinity());
    EXPECT_NEAR(e.worstObjectRms, 0.01, 1e-9);
    // Just above the threshold an object counts: 5.1e-4 against 1e-3 of the
    // scene's mean (1 + 5.1e-4) / 2, about 5.003e-4.
    const Pair lit = samples({{0, 1.0, 1.0, 1.0}, {1, 1.0, 5.1e-4, 10.2e-4}});
    const SolutionError l = compareSamples(lit.solution, lit.reference);
    ASSERT_EQ(l.objects.size(), 2u);
    EXPECT_FALSE(l.objects[1].dark);
    EXPECT_NEAR(l.worstObjectRms, 1.0, 1e-9);
}

TEST(Sampling, ObjectsWithoutSamplesAreSkippedAndTheOrderIsTheObjects) {
    const Pair p = samples({{4, 1.0, 2.0, 2.0}, {1, 1.0, 2.0, 3.0}, {4, 1.0, 2.0, 2.0}});
    const SolutionError e = compareSamples(p.solution, p.reference);
    ASSERT_EQ(e.objects.size(), 2u);
    EXPECT_EQ(e.objects[0].object, 1u);
    EXPECT_EQ(e.objects[1].object, 4u);
    EXPECT_NEAR(e.objects[0].rms, 0.5, 1e-12);
    EXPECT_EQ(e.objects[1].rms, 0.0);
}

TEST(Sampling, IdenticalSolutionsHaveNoError) {
    const Pair p = samples({{0, 2.0, 3.0, 3.0}, {1, 1.0, 5.0, 5.0}});
    const SolutionError e = compareSamples(p.solution, p.reference);
    EXPECT_EQ(e.rms, 0.0);
    EXPECT_EQ(e.max, 0.0);
    EXPECT_EQ(e.worstObjectRms, 0.0);
    for (const ObjectError& o : e.objects) EXPECT_EQ(o.rms, 0.0);
}

TEST(Sampling, SamplesWithoutObjectsGiveTheSceneFiguresOnly) {
    Pair p = samples({{0, 1.0, 2.0, 3.0}});
    p.solution.object.clear();
    p.reference.object.clear();
    const SolutionError e = compareSamples(p.solution, p.reference);
    EXPECT_NEAR(e.rms, 0.5, 1e-12);
    EXPECT_TRUE(e.objects.empty());
    EXPECT_EQ(e.worstObjectRms, 0.0);
}

TEST(Sampling, SetsOfDifferentScenesAreRefused) {
    Pair p = samples({{0, 1.0, 2.0, 3.0}, {1, 1.0, 2.0, 3.0}});
    RadiositySamples shorter = p.solution;
    shorter.luminance.pop_back();
    shorter.weight.pop_back();
    shorter.object.pop_back();
    EXPECT_THROW(compareSamples(shorter, p.reference), std::invalid_argument);
    p.solution.object[1] = 0;
    EXPECT_THROW(compareSamples(p.solution, p.reference), std::invalid_argument);
}

}  // namespace
}  // namespace rad
