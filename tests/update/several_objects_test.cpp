// Several objects moving in one frame (Engine::moveObjects): every object
// chosen stays in the dynamic visibility layer, one traversal finds what any
// of them touched, and the result matches a from-scratch solve.

#include <gtest/gtest.h>

#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "radiosity/Engine.h"
#include "support/Coverage.h"
#include "support/Motion.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;

glm::dmat4 shifted(const Engine& engine, const char* name, const V& by) {
    return test::translation(by) * engine.scene().objects[test::objectIndex(engine, name)].worldFromLocal;
}

TEST(SeveralObjects, TwoChairsMovingAtOnceMatchAFullSolve) {
    const EngineSettings settings;
    Engine engine(test::office(), settings);
    ASSERT_TRUE(engine.solve().converged);
    // Two frames, then one full solve (about 15 s under the sanitizers):
    // what the first frame got wrong and the second did not mend shows.
    for (int f = 1; f <= 2; ++f) {
        const FrameStats frame =
            engine.moveObjects({{"chair", shifted(engine, "chair", V(0.3, 0.0, 0.0))},
                                {"chair-2", shifted(engine, "chair-2", V(0.0, 0.0, -0.25))}});
        EXPECT_GT(frame.candidates, 0u) << "frame " << f;
    }
    const SolutionError e = test::compareWithFullSolve(engine, settings);
    EXPECT_LT(e.rms, 0.01);
    // The bookcases' rows of small books are refined differently by any
    // small change: two full solves at epsilon x0.98 and x1.02 differ by
    // up to 4.9% rms over a bookcase (5.5% without the fill). Their own
    // noise is what bounds the worst object here.
    EXPECT_LT(e.worstObjectRms, 0.05);
    EXPECT_TRUE(test::allFinite(engine.samples()));
    const test::CoverageResult c = test::checkCoverage(engine, 7u, 300);
    EXPECT_EQ(c.missing + c.doubled, 0) << c.firstBad;
}

TEST(SeveralObjects, MovingAnObjectChosenBeforeNeedsNoNewSplit) {
    const EngineSettings settings = test::coarse();
    Scene scene = test::roomWithBlock();
    const std::uint32_t grey = scene.polygons[scene.objects[*scene.findObject("block")].firstPolygon].material;
    test::addQuadObject(scene, "crate", grey,
                        {{V(0.5, 0.01, 3.0), V(1.0, 0.01, 3.0), V(1.0, 0.01, 3.5), V(0.5, 0.01, 3.5)}});
    Engine engine(scene, settings);
    ASSERT_TRUE(engine.solve().converged);
    const FrameStats first = engine.setDynamicObject("crate");
    EXPECT_GT(first.shaftTests, 0u) << "the crate's first choice splits the layers around it";
    engine.moveObjects({{"crate", shifted(engine, "crate", V(0.4, 0.0, 0.0))}});
    const FrameStats again = engine.setDynamicObject("block");
    EXPECT_EQ(again.shaftTests, 0u) << "the block (marked dynamic) was in the dynamic layer from the start";
    EXPECT_EQ(again.totalSeconds, 0.0);
    engine.moveObjects({{"block", shifted(engine, "block", V(-0.5, 0.0, 0.3))},
                        {"crate", shifted(engine, "crate", V(0.2, 0.0, -0.6))}});
    const SolutionError e = test::compareWithFullSolve(engine, settings);
    EXPECT_LT(e.rms, 0.01);
    const test::CoverageResult c = test::checkCoverage(engine, 3u, 300);
    EXPECT_EQ(c.missing + c.doubled, 0) << c.firstBad;
}

TEST(SeveralObjects, BadMovesAreRefusedByName) {
    Engine engine(test::roomWithBlock(), test::coarse());
    ASSERT_TRUE(engine.solve().converged);
    const auto message = [&](const std::vector<std::pair<std::string, glm::dmat4>>& moves) {
        try {
            engine.moveObjects(moves);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({{"nobody", glm::dmat4(1.0)}}).find("nobody"), std::string::npos);
    EXPECT_NE(message({{"block", glm::dmat4(1.0)}, {"block", glm::dmat4(1.0)}}).find("twice"), std::string::npos);
    EXPECT_NE(message({{"block", glm::scale(glm::dmat4(1.0), V(2.0))}}).find("rigid"), std::string::npos);
    const std::string far = message({{"block", glm::translate(glm::dmat4(1.0), V(1e30, 0.0, 0.0))}});
    EXPECT_NE(far.find("'block'"), std::string::npos) << far;
    EXPECT_NE(far.find("cannot be traced"), std::string::npos) << far;
}

}  // namespace
}  // namespace rad
