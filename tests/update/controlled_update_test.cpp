// The controlled update (paper sec. 6.1): whatever the link-update budget, the
// links must still cover line space completely (one link for every pair of
// points that face each other), an unlimited budget must be the plain update,
// a small budget must be coarser but catch up once the viewer idles, and the
// budget must follow a target frame time.

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "radiosity/Engine.h"
#include "radiosity/Gltf.h"
#include "support/Coverage.h"
#include "support/Motion.h"
#include "support/TestScenes.h"

namespace rad {
namespace {

using V = glm::dvec3;
using Clock = std::chrono::steady_clock;
using test::allFinite;
using test::finerSolve;
using test::objectIndex;
using test::secondsSince;
using test::translation;

UpdateSettings withBudget(std::size_t budget) {
    UpdateSettings u;
    u.budget = budget;
    return u;
}

std::string budgetName(std::size_t budget) { return budget == kUnlimited ? "unlimited" : std::to_string(budget); }

using test::checkCoverage;
using test::coarse;
using test::CoverageResult;
using test::roomWithBlock;

// Sec. 6.1: "no matter how much time is allocated for the update, a
// consistent solution is computed": the links cover line space completely.
// The energy balance of the closed room: the hierarchical solution itself
// leaks energy through coarse links (measured absorbed/emitted after the
// solve: 0.35 at epsilon 1e-2, 0.92 at 1e-3, 0.964 at 2e-4, 0.988 at 1e-4), so
// the balance is checked at epsilon 1e-4. Under a small budget the reinstated
// coarse p-links leak more (measured 0.90 for budgets 0..30): bounded loosely
// there, and within 2% once refinePending() has caught up.
TEST(ConsistencyControlledUpdate, ConsistentForEveryBudget) {
    const auto start = Clock::now();
    EngineSettings settings;
    settings.epsilon = 1e-4;
    const std::size_t budgets[] = {0, 1, 30, 3000, kUnlimited};
    for (std::size_t budget : budgets) {
        Engine engine(roomWithBlock(), settings);
        ASSERT_TRUE(engine.solve().converged);
        const double solvedRatio = engine.energy().absorbed / engine.energy().emitted;
        if (budget == 0) {
            const CoverageResult solved = checkCoverage(engine, 7u, 300);
            EXPECT_EQ(solved.missing + solved.doubled, 0) << "after the solve: " << solved.firstBad;
        }

        const V steps[] = {V(0.3, 0.0, 0.0), V(0.6, 0.1, -0.2), V(0.2, 0.3, -0.6), V(-0.5, 0.0, 0.4)};
        std::size_t spent = 0, reinstated = 0, pending = 0, stale = 0;
        for (const V& s : steps) {
            const FrameStats f = engine.moveDynamicObject(translation(s), withBudget(budget));
            spent += f.spent;
            reinstated += f.budgetReinstated;
            pending = f.pending;
            stale = std::max(stale, f.stale);
            EXPECT_EQ(f.budget, budget);
        }
        const CoverageResult c = checkCoverage(engine, 20240611u, 300);
        const EnergyBalance e = engine.energy();
        const double ratio = e.absorbed / e.emitted;
        const std::size_t links = engine.linkCount();
        const FrameStats idle = engine.refinePending();
        const CoverageResult caughtUp = checkCoverage(engine, 99u, 100);
        const double idleRatio = engine.energy().absorbed / engine.energy().emitted;
        std::printf("  budget %s: %d facing pairs, %d without a link, %d with several; absorbed/emitted %.4f "
                    "(solve %.4f, after refinePending %.4f); spent %zu, reinstated for budget %zu, pending %zu, "
                    "stale %zu, links %zu (%zu after refining %zu pending)\n",
                    budgetName(budget).c_str(), c.pairs, c.missing, c.doubled, ratio, solvedRatio, idleRatio, spent,
                    reinstated, pending, stale, links, engine.linkCount(), idle.refined);
        EXPECT_GE(c.pairs, 300) << "budget " << budgetName(budget);
        EXPECT_EQ(c.missing, 0) << "budget " << budgetName(budget) << ": " << c.firstBad;
        EXPECT_EQ(c.doubled, 0) << "budget " << budgetName(budget) << ": " << c.firstBad;
        EXPECT_EQ(caughtUp.missing + caughtUp.doubled, 0) << "after refinePending: " << caughtUp.firstBad;
        EXPECT_NEAR(solvedRatio, 1.0, 0.02);
        if (budget == kUnlimited) {
            EXPECT_NEAR(ratio, 1.0, 0.02);
            EXPECT_EQ(reinstated + stale, 0u) << "no budget leaves nothing coarse or stale";
        } else {
            // The budget did something: p-links made coarse, or links left
            // stale, to save updates.
            EXPECT_GT(reinstated + stale, 0u) << "budget " << budgetName(budget);
        }
        EXPECT_EQ(idle.stale, 0u) << "an unlimited idle frame works off every stale link";
        // Coarser links lose some energy, but never create any.
        EXPECT_GT(ratio, 0.85) << "budget " << budgetName(budget);
        EXPECT_LT(ratio, 1.02) << "budget " << budgetName(budget);
        EXPECT_NEAR(idleRatio, 1.0, 0.02) << "budget " << budgetName(budget);
        EXPECT_TRUE(allFinite(engine.samples()));
    }
    std::printf("  test time %.2f s\n", secondsSince(start));
}

TEST(ConsistencyControlledUpdate, UnlimitedBudgetEqualsPlainUpdate) {
    Engine plain(roomWithBlock(), coarse());
    Engine huge(roomWithBlock(), coarse());
    ASSERT_TRUE(plain.solve().converged);
    ASSERT_TRUE(huge.solve().converged);
    const V moves[] = {V(0.2, 0.0, 0.0), V(0.4, 0.1, 0.1), V(0.4, 0.3, -0.3), V(-0.6, 0.2, 0.5), V(0.05, 0.0, 0.05)};
    for (int i = 0; i < 5; ++i) {
        const FrameStats a = plain.moveDynamicObject(translation(moves[i]));
        const FrameStats b = huge.moveDynamicObject(translation(moves[i]), withBudget(kUnlimited - 1));
        EXPECT_EQ(a.budget, kUnlimited);
        EXPECT_EQ(b.budget, kUnlimited - 1);
        EXPECT_EQ(a.linksUpdated, b.linksUpdated) << "move " << i;
        EXPECT_EQ(a.refined, b.refined) << "move " << i;
        EXPECT_EQ(b.budgetReinstated, 0u) << "move " << i;
        EXPECT_EQ(b.pending, 0u) << "move " << i;
        const RadiositySamples sa = plain.samples(), sb = huge.samples();
        ASSERT_EQ(sa.luminance.size(), sb.luminance.size());
        int differ = 0;
        for (std::size_t k = 0; k < sa.luminance.size(); ++k) {
            EXPECT_EQ(sa.luminance[k], sb.luminance[k]) << "move " << i << " sample " << k;
            differ += sa.luminance[k] != sb.luminance[k];
            if (differ > 5) break;
        }
        std::printf("  move %d: links %zu / %zu, linksUpdated %zu / %zu\n", i, plain.linkCount(), huge.linkCount(),
                    a.linksUpdated, b.linksUpdated);
    }
    EXPECT_EQ(plain.linkCount(), huge.linkCount());
}

TEST(StabilityControlledUpdate, SmallBudgetIsCoarserThenCatchesUp) {
    const auto start = Clock::now();
    EngineSettings settings;
    settings.epsilon = 5e-4;
    const Scene office = loadGltf(test::sourcePath("scenes/office.gltf"));
    Engine limited(office, settings);
    Engine unlimited(office, settings);
    limited.setDynamicObject("chair");
    unlimited.setDynamicObject("chair");
    ASSERT_TRUE(limited.solve().converged);
    ASSERT_TRUE(unlimited.solve().converged);
    const std::uint32_t chair = objectIndex(limited, "chair");
    const glm::dmat4 start0 = limited.scene().objects[chair].worldFromLocal;
    std::printf("  office solve: %zu links, %.2f s for both\n", limited.linkCount(), secondsSince(start));

    for (int step = 1; step <= 3; ++step) {
        const glm::dmat4 to = translation(V(0.5 * step / 3.0, 0.0, 0.0)) * start0;
        const FrameStats a = limited.moveDynamicObject(to, withBudget(0));
        const FrameStats b = unlimited.moveDynamicObject(to);
        std::printf("  step %d: budget 0 spent %zu (reinstated %zu, pending %zu, linksUpdated %zu, %.3f s); "
                    "unlimited spent %zu (linksUpdated %zu, refined %zu, %.3f s)\n",
                    step, a.spent, a.budgetReinstated, a.pending, a.linksUpdated, a.totalSeconds, b.spent,
                    b.linksUpdated, b.refined, b.totalSeconds);
        EXPECT_EQ(a.budget, 0u);
        EXPECT_EQ(b.budget, kUnlimited);
    }
    Engine full(limited.scene(), settings);
    ASSERT_TRUE(full.solve().converged);
    const RadiositySamples reference = full.samples();
    const SolutionError eLimited = compareSamples(limited.samples(), reference);
    const SolutionError eUnlimited = compareSamples(unlimited.samples(), reference);
    const FrameStats idle = limited.refinePending();
    const SolutionError eCaughtUp = compareSamples(limited.samples(), reference);
    std::printf("  rms vs full solve: budget 0 %.5f (max %.4f), unlimited %.5f (max %.4f); after refinePending "
                "(refined %zu, spent %zu, pending %zu) %.5f (max %.4f); test %.2f s\n",
                eLimited.rms, eLimited.max, eUnlimited.rms, eUnlimited.max, idle.refined, idle.spent, idle.pending,
                eCaughtUp.rms, eCaughtUp.max, secondsSince(start));
    RecordProperty("rms_budget0", std::to_string(eLimited.rms));
    RecordProperty("rms_unlimited", std::to_string(eUnlimited.rms));
    RecordProperty("rms_caught_up", std::to_string(eCaughtUp.rms));
    EXPECT_GT(eLimited.rms, eUnlimited.rms);
    EXPECT_LE(eCaughtUp.rms, 0.01);
    EXPECT_EQ(idle.pending, 0u);
    EXPECT_EQ(idle.stale, 0u);
    // Idle time converges to what the unlimited frames computed.
    const SolutionError toUnlimited = compareSamples(limited.samples(), unlimited.samples());
    EXPECT_LT(toUnlimited.rms, 1e-3) << "caught up, budget 0 is " << toUnlimited.rms << " from the unlimited frames";
    EXPECT_TRUE(allFinite(limited.samples()));
}

UpdateSettings withDeadline(double seconds) {
    UpdateSettings u;
    u.deadlineSeconds = seconds;
    return u;
}

// The test room solved twice: one engine for frames on deadlines, one for
// the same moves unlimited. At the end the first must cover line space
// once and give the second's solution.
struct LateAndFree {
    Engine late{roomWithBlock(), coarse()};
    Engine free{roomWithBlock(), coarse()};
    LateAndFree() {
        EXPECT_TRUE(late.solve().converged);
        EXPECT_TRUE(free.solve().converged);
    }
    void expectTheSameSolution() {
        const CoverageResult c = checkCoverage(late, 5u, 200);
        EXPECT_EQ(c.missing + c.doubled, 0) << c.firstBad;
        // The same solution but for the leaves along the block's shadow,
        // which the two paths mesh a little otherwise: no further from a
        // finer solve than the unlimited frames.
        const RadiositySamples finer = finerSolve(late.scene(), coarse());
        const double lateToFiner = compareSamples(late.samples(), finer).rms;
        const double freeToFiner = compareSamples(free.samples(), finer).rms;
        const double apart = compareSamples(late.samples(), free.samples()).rms;
        std::printf("  late against free: rms %.2e; against an 8x finer solve: late %.2e, free %.2e\n", apart,
                    lateToFiner, freeToFiner);
        EXPECT_LT(apart, 0.01);
        EXPECT_LT(lateToFiner, 1.1 * freeToFiner) << "the unlimited frames: " << freeToFiner;
    }
};

// Idle frames until nothing waits (at most 10 after the first).
FrameStats idleUntilNothingWaits(Engine& engine) {
    FrameStats idle = engine.refinePending();
    for (int k = 0; k < 10 && idle.deferred + idle.stale + idle.pending + idle.unsent > 0; ++k) idle = engine.refinePending();
    EXPECT_EQ(idle.deferred + idle.stale + idle.pending + idle.unsent, 0u);
    return idle;
}

// Frames on a deadline: the mechanism, not the wall clock. A deadline
// already past when the frame starts stops the first traversal after one
// run of visits (LineSpaceUpdate::kTraversalMost): it goes on, a run a
// frame, where it stopped (its shaft tests over the frames are those of the
// same traversal made at once), and no link is updated. Once it has ended,
// everything it found waits, stale, and an idle frame on such a deadline
// does nothing more; without one, idle time catches up to what an
// unlimited frame computes.
TEST(StabilityControlledUpdate, DeadlineStopsTheWorkAndTheRestWaits) {
    LateAndFree engines;
    Engine& late = engines.late;
    const UpdateSettings past = withDeadline(0.0);
    FrameStats f = late.moveDynamicObject(translation(V(0.4, 0.0, 0.2)), past);
    const FrameStats whole = engines.free.moveDynamicObject(translation(V(0.4, 0.0, 0.2)));
    EXPECT_TRUE(f.traversing);
    EXPECT_EQ(f.deferred, 1u);  // its links wait
    EXPECT_GT(f.estimatedError, 0.0);
    std::size_t tests = f.shaftTests;
    int frames = 1;
    for (; frames < 1000 && f.traversing; ++frames) {
        EXPECT_EQ(f.spent, 0u);
        EXPECT_EQ(f.refined, 0u);
        f = late.refinePending(past);
        tests += f.shaftTests;
    }
    EXPECT_FALSE(f.traversing);
    EXPECT_GT(frames, 2) << "a run of visits a frame";
    EXPECT_EQ(tests, whole.shaftTests) << "going on where it stopped, in " << frames << " frames";
    EXPECT_EQ(f.spent, 0u);
    EXPECT_GT(f.stale, 0u);
    EXPECT_EQ(f.deferred, 0u);
    EXPECT_GT(f.estimatedError, 0.0);
    const FrameStats still = late.refinePending(past);
    EXPECT_EQ(still.spent, 0u);
    EXPECT_EQ(still.stale, f.stale);
    const FrameStats idle = late.refinePending();
    EXPECT_EQ(idle.stale, 0u);
    EXPECT_EQ(idle.estimatedError, 0.0);
    engines.expectTheSameSolution();
}

// The deadline covers the further bounces too: a frame past its deadline
// begins no bounce, and the changed elements wait, unsent (counted, and in
// the estimated error); idle time sends them, and the solution is then the
// one an unlimited frame gives. An idle frame makes at least one bounce
// whatever its deadline, so idle frames on a deadline already past finish
// too (a viewer whose target frame time is shorter than a bounce still
// converges); there the refinement that the arriving light asks for is made
// in other steps, which leaves a slightly different hierarchy (measured:
// 17,414 links against 17,442, 0.44% rms).
TEST(StabilityControlledUpdate, DeadlineLeavesBouncesUnsentUntilIdle) {
    Engine late(roomWithBlock(), coarse());
    Engine slow(roomWithBlock(), coarse());
    Engine free(roomWithBlock(), coarse());
    ASSERT_TRUE(late.solve().converged);
    ASSERT_TRUE(slow.solve().converged);
    ASSERT_TRUE(free.solve().converged);
    UpdateSettings past;
    past.deadlineSeconds = 0.0;
    const FrameStats f = late.editMaterial("light", V(20.0), std::nullopt, past);
    slow.editMaterial("light", V(20.0), std::nullopt, past);
    const FrameStats unlimited = free.editMaterial("light", V(20.0), std::nullopt);
    EXPECT_GT(unlimited.bounces, 0);
    EXPECT_EQ(f.bounces, 0);
    EXPECT_GT(f.unsent, 0u);
    EXPECT_GT(f.estimatedError, 0.0);
    // The only light doubled: every element's share of the light is what it
    // was, so no oracle steps and the refinement stays, that of a solve of
    // the edited scene (each of its decisions doubled on both sides).
    EXPECT_EQ(unlimited.refined + unlimited.reinstated, 0u);
    Engine solved(free.scene(), coarse());
    ASSERT_TRUE(solved.solve().converged);
    EXPECT_EQ(free.linkCount(), solved.linkCount());
    // The first push of the edited light is made: the picture is brighter
    // at once, but not yet as bright as with its bounces.
    const double lateRms = compareSamples(late.samples(), free.samples()).rms;
    EXPECT_GT(lateRms, 1e-3);
    const FrameStats idle = late.refinePending();
    EXPECT_GT(idle.bounces, 0);
    EXPECT_EQ(idle.unsent, 0u);
    EXPECT_EQ(idle.pending, 0u);
    EXPECT_LT(compareSamples(late.samples(), free.samples()).rms, 1e-3) << "before idle: " << lateRms;
    const CoverageResult c = checkCoverage(late, 5u, 200);
    EXPECT_EQ(c.missing + c.doubled, 0) << c.firstBad;

    FrameStats step = slow.refinePending(past);
    EXPECT_GE(step.bounces, 1);
    int frames = 1;
    for (; frames < 200 && step.unsent + step.pending > 0; ++frames) step = slow.refinePending(past);
    EXPECT_EQ(step.unsent + step.pending, 0u) << "after " << frames << " idle frames";
    EXPECT_EQ(step.estimatedError, 0.0);
    EXPECT_LT(compareSamples(slow.samples(), free.samples()).rms, 0.01);
}

// On a deadline a bounce goes out in runs of senders, the most powerful
// first, with the clock looked at between runs (LineSpaceUpdate::bounce:
// the rate learnt from earlier bounces misjudged large ones by 3 to 9
// times). Whatever the clock says: with an ample deadline every run is
// sent (the light doubled sends from every element, over 16,384 links a
// bounce: two runs at least), with short ones a share of the senders or
// the runs the clock leaves wait, unsent; either way idle time then gives
// the solution of the unlimited frame, and line space stays covered once.
// (Which short deadline stops a bounce between runs is the clock's: in a
// run with a message there, the 5 ms one, once in eleven deadlines from 1
// to 12 ms.)
TEST(StabilityControlledUpdate, ABounceOnADeadlineGoesOutInRunsAndIdleTimeSendsTheRest) {
    Engine free(roomWithBlock(), coarse());
    ASSERT_TRUE(free.solve().converged);
    const FrameStats unlimited = free.editMaterial("light", V(20.0), std::nullopt);
    idleUntilNothingWaits(free);
    ASSERT_GT(unlimited.transfers, 2u * 8192u);
    for (const double deadline : {600.0, 3e-3, 5e-3, 8e-3}) {
        Engine late(roomWithBlock(), coarse());
        ASSERT_TRUE(late.solve().converged);
        const FrameStats f = late.editMaterial("light", V(20.0), std::nullopt, withDeadline(deadline));
        if (deadline > 1.0) {
            EXPECT_GT(f.bounces, 0);
            EXPECT_GT(f.transfers, 2u * 8192u);
        }
        idleUntilNothingWaits(late);
        EXPECT_LT(compareSamples(late.samples(), free.samples()).rms, 1e-3) << "deadline " << deadline << " s";
        const CoverageResult c = checkCoverage(late, 5u, 200);
        EXPECT_EQ(c.missing + c.doubled, 0) << c.firstBad;
    }
}

// Moves made while a traversal goes on over frames wait: each frame goes on
// with the traversal, with the object where it was found, then moves the
// object and defers its move. The frame that ends it (here, past its
// deadline: it only found) keeps what it found; the next ones defer it,
// stale, a run of links a frame past the deadline (the traversal still under
// way), and the one that ends that catches up on the clock (here on
// nothing); the next catches up again (nothing: no further frame does), then
// a traversal from where the links were found to where the object is
// begins. Idle frames then
// give what the same moves give unlimited: line space covered once, the
// same solution. (Against one move from the start to the end, 0.40% rms,
// as the same 40 moves unlimited are: the links the object crossed on its
// way are judged again, and one such move never looks at them.)
TEST(StabilityControlledUpdate, MovesWhileTheTraversalGoesOnWaitAndCoalesce) {
    LateAndFree engines;
    const UpdateSettings past = withDeadline(0.0);
    std::vector<FrameStats> frames;
    for (int k = 1; k <= 40; ++k) {
        const double x = 0.4 * k / 40.0;
        frames.push_back(engines.late.moveDynamicObject(translation(V(x, 0.0, x / 2.0)), past));
    }
    EXPECT_TRUE(frames[0].traversing);
    EXPECT_EQ(frames[0].deferred, 1u);
    std::size_t found = frames.size();
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const FrameStats& f = frames[k];
        EXPECT_EQ(f.spent, 0u) << "frame " << k;
        EXPECT_EQ(f.deferred, 1u) << "frame " << k;
        EXPECT_GT(f.estimatedError, 0.0) << "frame " << k;
        if (found == frames.size() && f.foundOnly) found = k;
    }
    ASSERT_LT(found + 3, frames.size()) << "the traversal never ended";
    EXPECT_GT(found, 1u) << "a run of visits a frame";
    // While the traversal goes on no link changes, and the estimate grows
    // with how far the object has moved since its links were right (what
    // its links carry is summed once, then scaled by that share).
    for (std::size_t k = 1; k <= found; ++k)
        EXPECT_GT(frames[k].estimatedError, frames[k - 1].estimatedError) << "frame " << k;
    EXPECT_TRUE(frames[found].traversing) << "what it found is kept";
    EXPECT_GT(frames[found].shaftTests, 0u);
    EXPECT_EQ(frames[found].stale, 0u);
    std::size_t deferred = found + 1;  // the frame that has deferred all it found
    for (; deferred < frames.size() && frames[deferred].traversing; ++deferred) {
        EXPECT_TRUE(frames[deferred].resumed) << "frame " << deferred;
        EXPECT_EQ(frames[deferred].shaftTests, 0u) << "frame " << deferred;
        EXPECT_GT(frames[deferred].stale, frames[deferred - 1].stale) << "frame " << deferred;
    }
    ASSERT_LT(deferred + 2, frames.size()) << "the deferring never ended";
    EXPECT_GT(deferred, found + 1) << "more links found than a run: deferred over frames";
    EXPECT_TRUE(frames[deferred].resumed);
    EXPECT_EQ(frames[deferred].shaftTests, 0u);
    EXPECT_GT(frames[deferred].stale, frames[deferred - 1].stale);
    EXPECT_TRUE(frames[deferred + 1].caughtUp);
    EXPECT_EQ(frames[deferred + 1].stale, frames[deferred].stale);
    EXPECT_TRUE(frames[deferred + 2].traversing) << "a traversal for the moves since";
    idleUntilNothingWaits(engines.late);
    for (int k = 1; k <= 40; ++k) {
        const double x = 0.4 * k / 40.0;
        engines.free.moveDynamicObject(translation(V(x, 0.0, x / 2.0)));
    }
    engines.expectTheSameSolution();
}

// A frame's total is the wall clock of the whole engine call, whatever no
// phase times (the live estimate of a deferred move took 1 to 12 ms of the
// building floor's frames that the total left out), and holds the phases
// it lists, the estimate's among them. Frames on a short deadline go through every kind of frame:
// traversals cut and resumed, deferred moves, catching up, idle ones.
TEST(StabilityControlledUpdate, AFrameTotalIsTheWholeCall) {
    Engine engine(roomWithBlock(), coarse());
    engine.solve();
    const auto check = [](const FrameStats& f, double wall, int k) {
        EXPECT_LE(f.totalSeconds, wall + 1e-6) << "frame " << k;
        EXPECT_GE(f.totalSeconds, wall - (1e-3 + 0.02 * wall)) << "frame " << k;
        EXPECT_LE(f.traversalSeconds + f.updateSeconds + f.pushPullSeconds + f.moveSeconds + f.estimateSeconds +
                      f.snapshotSeconds,
                  f.totalSeconds * (1.0 + 1e-9) + 1e-9)
            << "frame " << k;
    };
    int estimated = 0;  // frames that timed their estimate
    for (int k = 1; k <= 30; ++k) {
        const double x = 0.4 * k / 30.0;
        const auto start = std::chrono::steady_clock::now();
        const FrameStats f = engine.moveDynamicObject(translation(V(x, 0.0, x / 2.0)), withDeadline(0.002));
        check(f, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), k);
        estimated += f.estimateSeconds > 0.0;
    }
    EXPECT_GT(estimated, 0) << "the estimate's time is a phase of the frame";
    for (int k = 31; k <= 40; ++k) {
        const auto start = std::chrono::steady_clock::now();
        const FrameStats f = engine.refinePending(withDeadline(0.002));
        check(f, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), k);
    }
}

// A traversal stopped by one frame's deadline and ended in the next, which
// has the time: everything it found waits, stale, behind what earlier frames
// left, and the frame catches up on it on the clock (here all of it). The
// frame's own move is deferred, for the next traversal.
TEST(StabilityControlledUpdate, ATraversalEndedWithTimeLeftCatchesUpInItsFrame) {
    LateAndFree engines;
    Engine& late = engines.late;
    const UpdateSettings past = withDeadline(0.0), ample = withDeadline(600.0);
    const FrameStats stops = late.moveDynamicObject(translation(V(0.2, 0.0, 0.1)), past);
    EXPECT_TRUE(stops.traversing);
    const FrameStats ends = late.moveDynamicObject(translation(V(0.4, 0.0, 0.2)), ample);
    EXPECT_FALSE(ends.traversing);
    EXPECT_FALSE(ends.foundOnly);
    EXPECT_GT(ends.shaftTests, 0u);
    EXPECT_GT(ends.spent, 0u);
    EXPECT_EQ(ends.stale, 0u);
    EXPECT_EQ(ends.deferred, 1u);
    // The next frame traverses the deferred move and updates its links.
    const FrameStats next = late.moveDynamicObject(translation(V(0.4, 0.0, 0.2)), ample);
    EXPECT_EQ(next.deferred, 0u);
    EXPECT_GT(next.spent, 0u);
    engines.free.moveDynamicObject(translation(V(0.4, 0.0, 0.2)));
    late.refinePending();
    engines.expectTheSameSolution();
}

// A frame on a deadline whose budget leaves links stale: the next frame
// catches up on them first (the deadline, not the budget, deciding how
// many: here all), with the block where they were found, and defers its own
// move; the one after traverses from where the links were last updated.
// Left to the budget, frame after frame, they piled up (`office` at 30 fps).
TEST(StabilityControlledUpdate, LinksABudgetLeftStaleAreCaughtUpOnBeforeTheNextMove) {
    LateAndFree engines;
    Engine& late = engines.late;
    UpdateSettings starved = withDeadline(600.0);
    starved.budget = 10;
    const FrameStats first = late.moveDynamicObject(translation(V(0.2, 0.0, 0.1)), starved);
    ASSERT_FALSE(first.traversing);
    ASSERT_GT(first.stale, 0u);
    EXPECT_LE(first.spent, 10u);
    const FrameStats second = late.moveDynamicObject(translation(V(0.4, 0.0, 0.2)), starved);
    EXPECT_TRUE(second.caughtUp);
    EXPECT_EQ(second.stale, 0u);
    EXPECT_GT(second.spent, 10u);
    EXPECT_EQ(second.shaftTests, 0u) << "no traversal: the move waits";
    EXPECT_EQ(second.deferred, 1u);
    const FrameStats third = late.moveDynamicObject(translation(V(0.4, 0.0, 0.2)), starved);
    EXPECT_FALSE(third.caughtUp);
    EXPECT_GT(third.shaftTests, 0u);
    EXPECT_EQ(third.deferred, 0u);
    idleUntilNothingWaits(late);
    engines.free.moveDynamicObject(translation(V(0.2, 0.0, 0.1)));
    engines.free.moveDynamicObject(translation(V(0.4, 0.0, 0.2)));
    engines.expectTheSameSolution();
}

// Anything else that changes links drops a traversal under way (an edit, a
// choice of another object): nothing it found has changed, and the move
// waits again from where the links were, for idle time or the next move.
TEST(StabilityControlledUpdate, AnEditDropsATraversalUnderWayAndTheMoveWaits) {
    LateAndFree engines;
    Engine& late = engines.late;
    ASSERT_TRUE(late.moveDynamicObject(translation(V(0.4, 0.0, 0.2)), withDeadline(0.0)).traversing);
    const FrameStats edit = late.editMaterial("light", V(20.0), std::nullopt);
    EXPECT_FALSE(edit.traversing);
    EXPECT_GT(late.refinePending().shaftTests, 0u) << "the move's traversal, from the start";
    idleUntilNothingWaits(late);
    engines.free.moveDynamicObject(translation(V(0.4, 0.0, 0.2)));
    engines.free.editMaterial("light", V(20.0), std::nullopt);
    engines.free.refinePending();
    engines.expectTheSameSolution();
}

// The live estimate is in the units of the measured error (the rms
// against a solution whose links are all up to date) and follows it: a
// block dragged with budget 0 leaves more light wrong frame after frame,
// and the estimate grows with it, from the links it left stale, each in
// the share of the block's size the block has moved since the link was
// last right.
TEST(StabilityControlledUpdate, EstimatedErrorFollowsTheMeasuredOneInItsUnits) {
    Engine starved(roomWithBlock(), coarse());
    Engine free(roomWithBlock(), coarse());
    ASSERT_TRUE(starved.solve().converged);
    ASSERT_TRUE(free.solve().converged);
    UpdateSettings none;
    none.budget = 0;
    double lastEstimate = 0.0, lastMeasured = 0.0;
    for (int frame = 1; frame <= 5; ++frame) {
        const glm::dmat4 m = translation(V(0.08 * frame, 0.0, 0.04 * frame));
        const FrameStats f = starved.moveDynamicObject(m, none);
        free.moveDynamicObject(m);
        const double measured = compareSamples(starved.samples(), free.samples()).rms;
        EXPECT_GT(f.estimatedError, lastEstimate) << "frame " << frame;
        EXPECT_GT(measured, lastMeasured) << "frame " << frame;
        EXPECT_GT(f.estimatedError, 0.2 * measured) << "frame " << frame;
        EXPECT_LT(f.estimatedError, 5.0 * measured) << "frame " << frame;
        lastEstimate = f.estimatedError;
        lastMeasured = measured;
    }
}

TEST(StabilityControlledUpdate, BudgetFromTargetFrameRate) {
    Engine engine(roomWithBlock(), coarse());
    ASSERT_TRUE(engine.solve().converged);
    const std::size_t initial = engine.budgetFor(0.1);
    for (int i = 1; i <= 6; ++i) engine.moveDynamicObject(translation(V(0.1 * i, 0.02 * (i % 3), -0.05 * i)));
    const std::size_t b1 = engine.budgetFor(1.0), b01 = engine.budgetFor(0.1), b0001 = engine.budgetFor(0.001),
                      b0 = engine.budgetFor(1e-9);
    std::printf("  budgetFor: 0.1 s before moving %zu; after 6 frames 1 s %zu, 0.1 s %zu, 1 ms %zu, 1 ns %zu, 0 s %zu\n",
                initial, b1, b01, b0001, b0, engine.budgetFor(0.0));
    EXPECT_GT(b1, b01);
    EXPECT_GE(b01, b0001);
    EXPECT_EQ(b0, 0u);
    EXPECT_EQ(engine.budgetFor(0.0), 0u);
    EXPECT_EQ(engine.budgetFor(-1.0), 0u);
    EXPECT_GT(b01, 0u) << "a tenth of a second must allow some link updates on this small scene";
}

TEST(StabilityControlledUpdate, ThousandBackAndForthUnderSmallBudget) {
    const auto start = Clock::now();
    Engine engine(roomWithBlock(), coarse());
    ASSERT_TRUE(engine.solve().converged);
    const RadiositySamples original = engine.samples();
    const std::size_t links0 = engine.linkCount();
    const std::size_t memory0 = engine.memory().total();

    const glm::dmat4 a = translation(V(0.25, 0.0, -0.15)), b = translation(V(-0.2, 0.15, 0.3));
    const UpdateSettings small = withBudget(30);
    std::size_t maxSpent = 0, maxPending = 0, maxLinks = 0;
    constexpr int kMoves = 1000;
    for (int i = 0; i < kMoves; ++i) {
        const FrameStats f = engine.moveDynamicObject(i % 2 == 0 ? a : b, small);
        maxSpent = std::max(maxSpent, f.spent);
        maxPending = std::max(maxPending, f.pending);
        maxLinks = std::max(maxLinks, engine.linkCount());
    }
    const double walkSeconds = secondsSince(start);
    engine.moveDynamicObject(glm::dmat4(1.0), small);
    const FrameStats idle = engine.refinePending();
    const RadiositySamples back = engine.samples();
    ASSERT_TRUE(allFinite(back));
    const SolutionError e = compareSamples(back, original);
    const RadiositySamples finer = finerSolve(engine.scene(), coarse());
    const double backToFiner = compareSamples(back, finer).rms, originalToFiner = compareSamples(original, finer).rms;
    const std::size_t links1 = engine.linkCount();
    const std::size_t memory1 = engine.memory().total();
    std::printf("  %d moves under budget 30: at most %zu spent and %zu pending per frame, at most %zu links; "
                "back + refinePending (refined %zu): rms %.2e max %.2e; links %zu -> %zu, memory %zu -> %zu bytes; "
                "%.2f s; against an 8x finer solve: back %.2e, first %.2e\n",
                kMoves, maxSpent, maxPending, maxLinks, idle.refined, e.rms, e.max, links0, links1, memory0, memory1,
                walkSeconds, backToFiner, originalToFiner);
    RecordProperty("rms", std::to_string(e.rms));
    // Back where it began, meshed a little otherwise along the block's
    // shadow, and no further from a finer solve than the first solve.
    EXPECT_LT(e.rms, 5e-3);
    EXPECT_LT(backToFiner, 1.1 * originalToFiner);
    EXPECT_LE(static_cast<double>(links1), 1.05 * static_cast<double>(links0));
    EXPECT_LE(static_cast<double>(memory1), 1.05 * static_cast<double>(memory0));
}

}  // namespace
}  // namespace rad
