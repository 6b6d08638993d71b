// The lit mesh a frame ends with is built from the polygons the frame
// touched (Hierarchy::meshTouched): after moves, budgeted and deadline
// frames, idle time and edits, it is the mesh made from scratch, vertex for
// vertex, once the room its slots keep to grow in is dropped (compactMesh).

#include <gtest/gtest.h>

#include "radiosity/Engine.h"
#include "support/Motion.h"
#include "support/SameMesh.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

void expectMadeFromScratch(const Engine& engine, const char* after) {
    test::expectSameMesh(engine.snapshot(), engine.snapshotFromScratch(), after);
}

TEST(FrameMesh, FramesKeepTheMeshMadeFromScratch) {
    Engine engine(test::roomWithBlock(), test::coarse());
    ASSERT_TRUE(engine.solve().converged);
    expectMadeFromScratch(engine, "the solve");
    const glm::dmat4 start =
        engine.scene().objects[test::objectIndex(engine, "block")].worldFromLocal;
    for (int f = 1; f <= 3; ++f) {
        engine.moveDynamicObject(test::translation(glm::dvec3(0.2 * f, 0.0, 0.1 * f)) * start);
        expectMadeFromScratch(engine, "a move");
    }
    UpdateSettings none;
    none.budget = 0;
    engine.moveDynamicObject(test::translation(glm::dvec3(0.8, 0.0, 0.4)) * start, none);
    expectMadeFromScratch(engine, "a move at budget 0");
    // A deadline already past: polygons wait, unmeshed, for idle time.
    UpdateSettings late;
    late.deadlineSeconds = 1e-9;
    engine.moveDynamicObject(test::translation(glm::dvec3(1.0, 0.0, 0.6)) * start, late);
    for (int idle = 0; idle < 20; ++idle) {
        const FrameStats f = engine.refinePending();
        if (f.pending == 0 && f.unmeshed == 0 && f.deferred == 0) break;
    }
    expectMadeFromScratch(engine, "idle time after a late frame");
    engine.editMaterial("light", glm::dvec3(4.0), std::nullopt);
    expectMadeFromScratch(engine, "the light dimmed");
    engine.editMaterial("wall-x0", std::nullopt, glm::dvec3(0.2, 0.5, 0.3));
    expectMadeFromScratch(engine, "a wall recoloured");
}

}  // namespace
}  // namespace rad
