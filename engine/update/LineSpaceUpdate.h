#pragma once
// The interactive update after the dynamic object moves (paper sec. 4 and 5):
// the line-space traversal finds the links whose shafts the object touched
// before or after the move (findModifiedLinks, Fig. 6), reinstates p-links
// that would no longer be refined and removes their line-space children; the
// candidates are updated with the in-place gather and refined from a heap
// ordered by potential power transfer; a partial push-pull (Fig. 7) and
// further bounces (sec. 5.3.2) finish the frame.

#include <chrono>
#include <cstddef>
#include <map>
#include <optional>
#include <ranges>
#include <array>
#include <cstdint>
#include <deque>
#include <queue>
#include <span>
#include <utility>
#include <vector>

#include "hierarchy/ChunkedArray.h"
#include "hierarchy/Hierarchy.h"
#include "links/Link.h"
#include "radiosity/Settings.h"
#include "radiosity/Stats.h"
#include "update/EditResponse.h"
#include "update/LinkBits.h"
#include "update/UnsentSet.h"

namespace rad {

class Refiner;
class Solver;

// One object's move in a frame: its boxes before and after, and the index
// range of its cluster (links with an end inside get new form factors and
// static visibility too).
struct ObjectMotion {
    Aabb oldBox;
    Aabb newBox;
    IndexRange range;
};

class LineSpaceUpdate {
public:
    LineSpaceUpdate(Hierarchy& hierarchy, LinkStore& links, Refiner& refiner, Solver& solver,
                    double referenceRadiosity)
        : h_(hierarchy), links_(links), refiner_(refiner), solver_(solver), referenceRadiosity_(referenceRadiosity) {}

    // The geometry has already moved (hierarchy boxes, ray-caster layer).
    // `oldBox` and `newBox`: the dynamic object's boxes before and after.
    // `moved`: the index range of whatever moved (its cluster): links with an
    // end inside it get new form factors and static visibility too.
    FrameStats update(const Aabb& oldBox, const Aabb& newBox, const IndexRange& moved,
                      const UpdateSettings& settings) {
        return update(std::vector<ObjectMotion>{{oldBox, newBox, moved}}, settings);
    }
    // Several objects moved in one frame: one traversal finds the links any
    // of them touched.
    FrameStats update(const std::vector<ObjectMotion>& motions, const UpdateSettings& settings);
    // An object joined the dynamic layer (Engine::setDynamicObject); nothing
    // moved. The rays it blocks move from the static part of the visibility
    // to the dynamic one, so both parts of every link whose shaft meets its
    // box are cast again; no form factor changes. `relinked`: its links were
    // just made with the layers as they now are (Reinsertion.h), so the
    // links with an end in it, and their line-space children, are left as
    // they are.
    FrameStats chooseObject(const Aabb& box, const IndexRange& range, bool relinked, const UpdateSettings& settings);
    // For the next update only: static geometry inside the moving object
    // (see Obstacles.h); links with both ends on it whose shafts meet one
    // are updated too.
    void setObstacles(std::vector<Aabb> obstacles) { obstacles_ = std::move(obstacles); }
    // An object's cluster moved, its shape and those of its ancestors built
    // again (Hierarchy::updateGeometry, refreshAncestors): what they have to
    // send may have changed (a turned object's facets regroup).
    void clustersMoved(ElementId objectCluster);
    // The emission or reflectance of `elements` (and their subtrees)
    // changed: their radiosity is pushed again, the change goes out through
    // further bounces, and refinement follows the light, within the budget.
    // `emission`: the edit changed emission only, by this much; c times the
    // last such edit's change sends c times its light at once
    // (EditResponse.h). None: reflectance changed too.
    FrameStats propagate(const std::vector<ElementId>& elements, const UpdateSettings& settings,
                         const EmissionChange* emission = nullptr);
    // After such a change, refinement follows the light as after a move
    // (followTheLight: the oracles of what changed step, and the links of
    // those that stepped are judged again, within the budget). Adds to
    // `stats` and finishes the frame that propagate began.
    void judgeAgain(const UpdateSettings& settings, FrameStats& stats);
    // The solve's emitted power over the current one (edits change it): the
    // oracles' levels follow each element's B times this, its share of the
    // light (OracleSteps.h), so that a scene dimmed as a whole keeps its
    // refinement, as a solve of it would. When it changed, every element is
    // stepped at the next followTheLight.
    void setLightScale(double scale);
    // On a deadline, the share of the frame (what the updater was given of
    // it, less the mesh's fixed part) the first traversal may take and
    // leave the rest to the link updates it finds. A traversal that ends
    // later leaves its frame nothing but what it found (FrameStats::
    // foundOnly): the traversal stays under way, and the next frame's
    // resume defers every link it found, stale, and catches up on them (as
    // refinePending does, on the clock); the engine's next moves catch up
    // too while stale links are left. A drag whose traversal nearly fills a
    // frame so alternates a frame that finds and frames that update.
    static constexpr double kTraversalShare = 0.5;
    // A traversal that has not ended at this share of its frame stops there
    // (FrameStats::traversing) and goes on at the next call to resume, so
    // that a traversal longer than a frame (a large object's, or any at a
    // high frame rate) is spread over frames: the light follows a few
    // frames late instead of waiting for idle time. (Before, a frame that
    // could not leave the traversal the time it last took deferred the
    // move; the drag's light then stayed where it was.)
    static constexpr double kTraversalMost = 0.8;
    // Goes on with a traversal a deadline stopped, in a new frame on
    // `settings`' deadline, with the objects where it found them: once it
    // ends (and unless that took more than kTraversalShare of this frame),
    // every link it found waits, stale, and the frame catches up on them on
    // the clock. `idle`: a frame of idle time (refinePending's). The frame
    // has no estimated error: the engine makes it, with the moving objects'
    // links (their moves wait).
    FrameStats resume(const UpdateSettings& settings, bool idle = false);
    bool traversing() const { return traversing_; }
    // Drops a traversal a deadline stopped: nothing it found was changed,
    // and the engine defers its move again, for a later traversal. Anything
    // else the updater does (an edit, a choice of object) comes after this.
    void abandonTraversal();
    // Refines, within the budget, the links a budget left coarse, with no
    // motion (what an idle viewer does between moves). `idle` false: a
    // frame of a drag that catches up on the clock (Engine::moveObjects),
    // its first batch and bounce held to the deadline like the rest.
    FrameStats refinePending(const UpdateSettings& settings, bool idle = true);
    // After a solve: reinstates the p-links the criterion no longer asks for
    // (their source's radiosity fell after they were refined), so that the
    // solution is a fixed point of the traversal's decisions and a move that
    // moves nothing changes nothing. Returns how many.
    std::size_t reinstateUnneeded();

    // What the frame does after the update, predicted from the surface
    // leaves the update changed: building the lit mesh (the engine fits it from its
    // frames). A deadline is for the whole frame, so the update stops early
    // enough to leave it that time.
    struct FrameTail {
        double base = 0.0;
        double perLeaf = 0.0;
        // Per leaf of the polygons meshed anew (Hierarchy::reshapedLeaves):
        // counted as the frame subdivides and moves, apart from the leaves
        // whose light changed.
        double perReshapedLeaf = 0.0;
        double seconds(std::size_t changedLeaves) const { return base + perLeaf * double(changedLeaves); }
    };
    void setFrameTail(const FrameTail& tail) { tail_ = tail; }
    // After a solve: the per-link marks sized to the links, so that the first
    // frame of a drag does not pay for touching them (in the building floor,
    // 7M links, it paid 35 ms).
    void prepare();
    // What the update keeps beside the hierarchy and the links: its marks
    // and sums per element, and per link slot (the stamps and stale marks).
    std::size_t memoryBytes() const;
    // What that takes, for refinement to leave it room under the memory
    // limit: whatever the scene, and per element and link.
    static RefineSettings::Beside memoryBeside();
    // What a further bounce (per link leaving its senders), and the push of
    // the receivers waiting for one, are expected to cost before one was
    // measured: a sweep of the solve, `seconds` over `links` active links.
    // The same sweep over `elements` elements is the first guess of a push's
    // cost per element, and of what sending an edit's scaled light costs.
    void guessBounceSeconds(double seconds, std::size_t links, std::size_t elements) {
        if (bounceSecondsPerLink_ == 0.0) bounceSecondsPerLink_ = seconds / double(std::max<std::size_t>(1, links));
        if (waitingPushSeconds_ == 0.0) waitingPushSeconds_ = seconds;
        if (guessSeconds_ == 0.0) guessSeconds_ = guessLeast_ = seconds;  // every link summed, everything pushed
        if (pushSecondsPerElement_ == 0.0) pushSecondsPerElement_ = seconds / double(std::max<std::size_t>(1, elements));
    }

    // The live error estimate (FrameStats::estimatedError), in the units of
    // SolutionError::rms: what the stale and pending links and the unsent
    // elements could change, receiver by receiver, and for each deferred
    // (cluster, share) the links with an end in the cluster's subtree in
    // that share (a deferred move: the light its links carry, in the share
    // of its size the object has moved).
    double estimatedError(const std::vector<std::pair<ElementId, double>>& deferred = {}) const;
    // What making the estimate is expected to take at the end of a frame:
    // part of the frame's tail, as the mesh is. A running mean of the last
    // ones (each new one weighs a quarter), and for each object cluster in
    // `carrying` (objects whose links will wait) whose sums over the links
    // it carries are not kept (or are made again: `traversal`, a traversal
    // begins), what making them takes at the last rate per link. Left to the
    // mean, the first frame of each traversal in `office` at 120 fps made
    // them (107,000 links, 4.7 ms) after a frame's worth of work, and ran
    // 3 ms over.
    double estimateSeconds(std::span<const ElementId> carrying = {}, bool traversal = false) const;
    // What the last estimate took (FrameStats::estimateSeconds).
    double lastEstimateSeconds() const { return lastEstimateSeconds_; }
    // What waits for later frames and idle time: FrameStats::pending, stale
    // and unsent as they stand.
    void countWaiting(FrameStats& stats) const;
    // Elements whose direct light (punctual lights) changed, each with how
    // much that moves its radiosity once pushed (LightLinks::takeChanges):
    // while a deadline defers their push, the estimate counts it.
    void noteLightChanges(const std::vector<std::pair<ElementId, double>>& changes) {
        for (const auto& [e, moved] : changes) lightChanges_[e] += moved;
    }
    // How far a move took an object, in its size: the larger distance its
    // box's corners moved over the box's diagonal (a turn moves them too).
    static double motionShare(const Aabb& from, const Aabb& to);

    // What the last frame touched, for display (paper Fig. 5 b, c): the links
    // it modified (the centres of their two H-elements) and the surface
    // leaves the push-pull changed (their outlines, each edge once), as
    // segments, made when asked.
    std::vector<std::array<glm::dvec3, 2>> modifiedLinks() const;
    std::size_t modifiedLinkCount() const;  // the segments modifiedLinks() would make
    std::vector<std::array<glm::dvec3, 2>> changedOutlines() const;

private:
    // The affected p-links of a visit with nested source ranges, descended
    // together: a run of the visit's `affected`, and a run of visits (its
    // line-space children) below. Runs, not lists: a frame makes tens of
    // thousands of groups, and their lists were a fifth of a budget-0
    // frame's time in allocation.
    struct Group {
        IndexRange range;
        std::uint32_t firstPlink = 0, plinkCount = 0;  // in the visit's `affected`
        std::size_t firstVisit = 0, visitCount = 0;    // the child visits
        std::size_t work = 0;                          // link updates below, pulled up
        auto visits() const { return std::views::iota(firstVisit, firstVisit + visitCount); }
    };
    // A node of the first traversal and the source range it looks at.
    struct Visit {
        ElementId he;
        IndexRange ind;
        std::vector<LinkId> affected;    // p-links on he from ind whose shafts the object cut
        std::vector<LinkId> candidates;  // active links on he from ind likewise (stamped)
        std::vector<Group> groups;
        std::size_t work = 0;  // own() plus everything below
        std::size_t own() const { return affected.size() + candidates.size(); }
        std::span<const LinkId> plinks(const Group& g) const {
            return std::span(affected).subspan(g.firstPlink, g.plinkCount);
        }
    };
    // Starts the visit record `visitCount_` (reusing the record and its
    // lists' storage from earlier frames) and returns its index.
    std::size_t addVisit(ElementId he, const IndexRange& ind);
    // Fig. 6: the first traversal, from the root (visit record 0). It only
    // finds (shaft tests, index ranges) and pulls up the work each visit's
    // links and its groups' line-space children call for (sec. 6.1).
    // Begun, then gone on with level by level until it ends (true) or,
    // after a run of visits, the clock passes `stop` (false: where it is in
    // its level is kept).
    void beginTraversal();
    bool traverse(std::optional<std::chrono::steady_clock::time_point> stop);
    // Where a traversal under way is: the visits of its current level, how
    // many of them are done, and the next level's visits so far.
    std::vector<std::size_t> traversalLevel_, nextLevel_;
    std::size_t levelDone_ = 0;
    bool traversing_ = false;
    static constexpr std::size_t kVisitsPerLook = 256;
    // A frame once its traversal has begun: the traversal on the clock,
    // then the link updates, push-pull and bounces (run's steps 1 to 4).
    // `resumed`: the traversal began in an earlier frame.
    FrameStats goOn(FrameStats stats, const UpdateSettings& settings, std::chrono::steady_clock::time_point start,
                    bool mayFindOnly, bool resumed);
    // Throws if a stopped traversal waits (it must be resumed or abandoned
    // first: the links it found would change under it).
    void checkNotTraversing(const char* what) const;
    // One node of it: its affected p-links, candidates (stamped) and groups,
    // and the child visits (node, source range) in the groups' order; returns
    // the shaft tests made. Visits of a level run concurrently.
    std::size_t visitNode(Visit& visit, std::vector<std::pair<ElementId, IndexRange>>& children);
    // Fig. 8: the second traversal, spending the budget top-down over the
    // visits (ControlledUpdate.cpp); returns the link updates made.
    std::size_t controlledUpdate(std::size_t budget, FrameStats& stats);
    // One visit of it, given its budget: reinstates, then shares what is
    // left among its groups (child visits and their shares go to `next`).
    void spendOn(std::size_t visit, std::size_t budget, std::vector<std::pair<std::size_t, std::size_t>>& next,
                 FrameStats& stats);
    // Puts the links of a visit and everything below it in the stale queue.
    void defer(std::size_t visit);
    // The same for everything a resumed traversal found, on the clock: a
    // deadline stops it between runs of kDeadlineChunk links (false), and
    // the next call goes on from there (deferStack_).
    bool deferFound();
    // Defers the visits on `stack` and those below them; on the clock, stops
    // past the link updates' deadline (false), the rest left on `stack`.
    bool deferFrom(std::vector<std::size_t>& stack, bool onTheClock);
    // Recomputes up to `budget` stale links at the current position; returns
    // how many.
    std::size_t catchUp(std::size_t budget, FrameStats& stats);
    // Counts its shaft tests in `tests`.
    bool affectedByMotion(ElementId s, ElementId r, std::size_t& tests) const;
    // Whether the object's old box cut the shaft of s -> r.
    bool cutBefore(ElementId s, ElementId r) const;
    // Recomputes a link's form factor and visibility for the new position
    // (`full`: both visibility parts and the form factor, whatever moved).
    void recompute(LinkId id, bool full = false);
    void reinstate(LinkId id);
    void removeLineSpaceChildren(ElementId e, const IndexRange& sources, LinkId keep);
    using RefineHeap = std::priority_queue<std::pair<double, LinkId>>;
    void updateCandidates(FrameStats& stats, std::size_t budget);
    // Sec. 5.2: the link with the highest potential power transfer first.
    void refineFromHeap(RefineHeap& heap, FrameStats& stats, std::size_t budget);
    void prunePending();
    void setDeadline(std::chrono::steady_clock::time_point start, const UpdateSettings& settings);
    // What a budget (kUnlimited: none) leaves after `spent` link updates.
    static std::size_t budgetLeft(std::size_t budget, std::size_t spent);
    // `estimate` false: the engine makes the frame's estimated error.
    void finish(FrameStats& stats, std::chrono::steady_clock::time_point start, bool estimate = true);
    // Sec. 6.2: heap key factor for a link whose shaft the object just entered.
    static constexpr double kEnteringBoost = 4.0;
    double heapKey(const Link& l) const;
    void bounce(std::vector<ElementId> visited, const UpdateSettings& settings, FrameStats& stats);
    // Steps the oracles of the elements this frame's push-pulls visited
    // (OracleSteps.h) and judges again the links of those that moved: the
    // links their new oracle asks to refine are refined within the budget,
    // and their p-links it no longer asks for are reinstated (`coarsen`),
    // or queued for idle time (coarsenLater_).
    void followTheLight(const UpdateSettings& settings, FrameStats& stats, std::size_t budget, bool coarsen = true);
    // Elements whose oracle an edit stepped, with p-links their new oracle
    // may no longer ask for: an edit's frames refine where the light grew
    // and leave the coarsening to idle time (refinePending), except where
    // an element's oracle is back at the solve's (an edit taken back
    // returns the solve's hierarchy at once). A light dimmed
    // on a slider in `office` reinstated 2,000 p-links a frame, and sent
    // what each changed: 50 to 60 ms of a 90 ms frame.
    std::vector<ElementId> coarsenLater_;
    std::vector<char> coarsenQueued_;  // per element: in coarsenLater_
    // Elements whose oracle stepped and whose links a deadline left to be
    // judged at a later frame or in idle time, and what judging took per
    // link (the links leaving what rose).
    std::vector<ElementId> judgeLater_;
    double judgeSecondsPerLink_ = 0.0;
    // What coarsening took per p-link it looked at (followTheLight), and a
    // guess until it is measured.
    double coarsenSecondsPerPlink_ = 0.0;
    static constexpr double kCoarsenGuess = 1e-6;
    // The oracles' floor, as a fraction of the scene's mean emitted radiosity.
    static constexpr double kOracleFloor = 1e-3;
    // The partial push-pull of what is marked dirty (Fig. 7); counts the
    // elements it visits in `stats`. Returns them.
    // `onTheClock`: the push of what a move's link updates changed, which a
    // deadline may leave waiting (Solver::PushDeadline). Not an edit's first
    // push: refinement then judges by the edited light, which must be there.
    std::vector<ElementId> pushPull(FrameStats& stats, bool onTheClock = false);
    // Elements the frame's push-pulls visited, each once (a frame's pushes
    // and bounces visit `office`'s 24,000 elements up to six times: sorting
    // them took 1.3 to 5.5 ms).
    std::vector<ElementId> touched_;
    ChunkedArray<char, 16> isTouched_;  // per element: in touched_
    void touch(std::span<const ElementId> elements);
    void clearTouched();
    // Per element: how much the bounces could have moved its radiosity since
    // its last push; negative when it waits for none.
    ChunkedArray<double, 12> waitingChange_;
    // The receivers whose arrivals could not yet move their radiosity by the
    // threshold wait here instead of pushing their subtrees at every bounce
    // (a cluster's push walks all of its members); one push at the end of
    // the bounces takes it all in, unless a deadline leaves it to a later
    // frame. What that push took, the meshing of its leaves included.
    std::vector<ElementId> waiting_;
    double waitingPushSeconds_ = 0.0;
    // A source's change of radiosity sent along one of its links.
    struct Transfer {
        ElementId receiver;
        ElementId source;
        glm::dvec3 irradiance;
    };
    // Aitken's extrapolation of the further bounces (as the solve's,
    // SolveSettings::extrapolate). Once the change the senders send falls by
    // a steady ratio r per bounce, channel by channel (one mode of the
    // interreflection is left), each sender sends at once the change of
    // every bounce to come, 1 / (1 - r) times its own (once a frame, and
    // only a sender whose change is that of the last bounce), and holds that
    // as gathered: its radiosity then rises to what it sent, and what the
    // guess missed goes out with the next bounces (negative where it sent
    // too much). A receiver's irradiance stays the sum over its links of
    // what their sources hold as gathered, so a frame converges to the same
    // solution whether or not it extrapolated. `office`'s light dimmed:
    // the ratio holds at 0.57 from the third bounce on (each channel's
    // moves by under 3% of 1 - r).
    struct BounceSeries {
        glm::dvec3 last{-1.0};   // the change sent by the last bounce, per channel
        glm::dvec3 ratio{-1.0};  // its ratio to the one before
        bool done = false;       // extrapolated once: the rest are plain bounces
        std::vector<ElementId> lastSenders;  // the last bounce's, sorted
        std::vector<ElementId> sentAhead;    // the senders that sent ahead
    };
    // noteLightChanges' elements, kept while their push waits (finish()).
    std::map<ElementId, double> lightChanges_;
    // Steady: |r - r_before| <= kSteadyBounceRatio (1 - r) (looser than the
    // solve's: only the senders above the threshold send). Below the
    // smallest ratio the bounces to come add under half of the last one
    // (a chair's change, local, falls by 0.1 to 0.2 a bounce): not worth a
    // guess. Above the largest, 1 / (1 - r) magnifies the ratio's error.
    static constexpr double kSteadyBounceRatio = 0.1;
    static constexpr double kSmallestBounceRatio = 0.3, kLargestBounceRatio = 0.95;
    struct Thresholds {
        double send, hold;  // changes of radiosity
        double share;       // of the radiosity sent: a change above it is sent down to `hold`
    };
    // Sends the change of the visited elements whose radiosity moved by
    // more than the threshold since they were last gathered, in the order
    // of `visited` and of their links, and marks them gathered: finds the
    // transfers (collectTransfers) and adds them to their receivers
    // (applyTransfers), a block of senders at a time; their count is added
    // to `sentCount`. With a series (all of the bounce's senders send), the
    // change is sent ahead once it falls steadily. False if none moved.
    // Those that moved by more than `hold` only are appended to `held`.
    bool sendTransfers(const std::vector<ElementId>& visited, Thresholds threshold, BounceSeries* series,
                       std::vector<ElementId>& held, std::size_t& sentCount);
    // The transfers of the given senders (their first transfer's place in
    // the bounce in `first`) into transfers_, and the senders marked
    // gathered; those in `sendsAhead` send `ahead` times their change.
    void collectTransfers(std::span<const ElementId> sources, std::span<const std::size_t> first,
                          std::span<const char> sendsAhead, const glm::dvec3& ahead);
    // Adds the transfers to their receivers, in order, and marks dirty each
    // whose radiosity may have moved by more than `threshold` since its last
    // push (the others wait, in waiting_).
    void applyTransfers(const std::vector<Transfer>& transfers, double threshold);
    // The buffer transfers are found in, made with the update's marks
    // (prepare) and kept: a block of transferBlock_ transfers, unless one
    // sender alone has more links. A sixty-fourth of the links, from 1,024
    // to 16,384 transfers (512 KiB): at most half a byte a link (a
    // thirty-second was half a byte a link more in small rooms, which
    // stand near the 64 bytes a link the scale issue allows).
    static constexpr std::size_t kLinksPerTransfer = 64, kLeastTransfers = 1024, kMostTransfers = 16384;
    std::vector<Transfer> transfers_;
    std::size_t transferBlock_ = kLeastTransfers;

    // The last emission edit's light (propagate), while nothing but
    // emission changes: a move or a change of reflectance drops it.
    EditResponse response_;
    // What sending the last guess took, its push included, and the fastest
    // one sent (before one, a sweep of the solve: guessBounceSeconds).
    double guessSeconds_ = 0.0, guessLeast_ = 0.0;
    bool guessSent_ = false;
    // The work of an emission edit's frame, in bounce transfers: its
    // transfers, and the elements its pushes reached, each as five (pushed,
    // then stepped and meshed again: in `office` 24,000 elements pushed in
    // 5.3 ms, 1.7 million transfers in 130 ms).
    static constexpr double kPushedPerTransfer = 5.0;
    static double editWork(const FrameStats& stats) {
        return double(stats.transfers) + kPushedPerTransfer * double(stats.changedElements);
    }
    // The power an edit changes: emission times area, a punctual light's
    // intensity times 4 pi.
    double changedPower(const EmissionChange& emission) const;
    // The last edit frame's work per unit of the power it changed, with a
    // guess (negative: none yet) and without one.
    double guessWork_ = -1.0, bounceAloneWork_ = 0.0;

    Hierarchy& h_;
    LinkStore& links_;
    Refiner& refiner_;
    Solver& solver_;
    double referenceRadiosity_;  // the solve's mean emitted radiosity
    // The mean emitted radiosity now, which the bounces' thresholds are
    // relative to: a light dimmed a hundredfold is bounced as finely as a
    // scene solved at that light. (Relative to the solve's, the Cornell
    // box's only light dimmed to 1% in one frame was 2.9% rms from a full
    // solve, to 0.01% 83%: what each element had left to send, under the
    // solve's threshold, outshone the light.)
    double reference() const { return referenceRadiosity_ / lightScale_; }

    // Per frame.
    std::vector<ObjectMotion> motions_;
    std::chrono::steady_clock::time_point editStart_;  // when propagate began the frame judgeAgain ends
    double lightScale_ = 1.0;  // setLightScale
    // Whether an element lies in, or holds, a moving object's cluster.
    bool movedEnd(ElementId e) const;
    std::vector<Aabb> obstacles_;
    // A frame of update or chooseObject; `mayFindOnly`: a move's, which may
    // leave what it found to the next frame (kTraversalShare).
    FrameStats run(const std::vector<ObjectMotion>& motions, const UpdateSettings& settings,
                   bool mayFindOnly);
    // Set by chooseObject for its frame: the layers changed, and the object
    // whose links are new, if they are.
    bool layersChanged_ = false;
    std::optional<IndexRange> fresh_;
    std::uint32_t frame_ = 0;
    // The frame that last counted a polygon's leaves (pushPull), and the
    // count of frames begun (setDeadline): not frame_, which a resumed
    // traversal keeps.
    std::vector<std::uint32_t> polygonStamp_;
    std::uint32_t pushFrame_ = 0;
    // Per link slot, set if the link became a candidate in this frame
    // (cleared by nextFrame; set by concurrent visits of the traversal).
    LinkBits stamps_;
    void stamp(LinkId id);
    void nextFrame();  // ++frame_, and no link stamped
    std::vector<LinkId> candidates_;
    std::size_t shaftTests_ = 0;
    std::size_t reinstated_ = 0;
    // This frame's deadline (UpdateSettings::deadlineSeconds), if any, and
    // the time link updates stop at: half of what is left before the
    // deadline and its tail when they begin, the other half being for the
    // push-pull and the bounces of what they changed.
    std::optional<std::chrono::steady_clock::time_point> deadline_, linkDeadline_;
    FrameTail tail_;
    mutable double estimateSeconds_ = 0.0, lastEstimateSeconds_ = 0.0;  // estimateSeconds, lastEstimateSeconds
    double estimateNow(const std::vector<std::pair<ElementId, double>>& deferred) const;  // estimatedError, untimed
    // The tail of the frame as it stands: the mesh's for `changedLeaves`,
    // and the meshing anew of the polygons reshaped so far.
    double tailSeconds(std::size_t changedLeaves) const {
        return tail_.seconds(changedLeaves) + tail_.perReshapedLeaf * double(h_.reshapedLeaves());
    }
    bool pastDeadline() const { return linkDeadline_ && std::chrono::steady_clock::now() > *linkDeadline_; }
    // Link updates begin now: they get half of the time left.
    void startLinkUpdates();
    // The share of work expected to take `seconds` that leaves the frame,
    // its tail included, within the deadline (1: all of it, or no deadline),
    // after `first` seconds of work that must come before it.
    double shareThatFits(std::size_t changedLeaves, double seconds, double first = 0.0) const;
    // Below this share a bounce or push is not begun.
    static constexpr double kLeastShare = 0.1;
    // What the last bounce took per link leaving its senders, the push and
    // meshing of what it changed included. Apart for a bounce the deadline
    // cut to a share of its senders: it keeps those with the most power,
    // whose links nearly all carry a transfer, where a whole bounce's links
    // mostly fall under the threshold (in `office`, 48 ns a link against
    // 17, about 60 ns a transfer in both). Until a cut bounce is measured,
    // it is expected at kCutBounceGuess times the whole bounce's rate (at
    // the whole rate, the first cut bounce of `office`'s chair dragged at 60
    // fps was expected to take 0.9 to 1.3 ms and took 2.9 to 4.0 ms).
    double bounceSecondsPerLink_ = 0.0;
    double cutBounceSecondsPerLink_ = 0.0;
    static constexpr double kCutBounceGuess = 3.0;
    // On a deadline a bounce is sent in runs of about this many links, the
    // clock looked at between them (bounce()): a run takes 0.1 to 0.7 ms
    // (10 to 80 ns a link).
    static constexpr std::size_t kBounceRunLinks = 8192;
    // What a partial push-pull took per element it visited, measured on
    // pushes of at least kPushSample elements.
    double pushSecondsPerElement_ = 0.0;
    static constexpr std::size_t kPushSample = 1000;
    // What stepping the oracles took per element touched, measured likewise.
    double followSecondsPerElement_ = 0.0;
    // An idle frame (refinePending) begins its first batch of refinement
    // and its first bounce whatever the clock says, so that idle time
    // converges even on a deadline shorter than they take.
    bool idle_ = false;
    // A move's frame (run): its bounces send only the changes above
    // UpdateSettings::moveBounceThreshold.
    bool moving_ = false;
    // Elements whose change of radiosity a deadline kept from being sent
    // (bounced): the next bounce, in a later frame or idle time, sends it.
    // Mutable for the sum of what they have to send, which estimatedError
    // keeps up to date (unsentPower).
    mutable UnsentSet unsent_;
    std::size_t unsentLinks_ = 0;  // leaving them, counted (or estimated: holdUnsent) as they joined
    mutable std::uint64_t unsentReleases_ = 0;  // h_.releases() at unsent_'s last sum
    void joinUnsent(ElementId e, std::size_t links);
    // All of them join, their lists of links not read.
    void holdUnsent(const std::vector<ElementId>& elements);
    // The sum of unsentPowerOf(e, false) over the unsent elements.
    double unsentPower() const;
    // What choosing a bounce's senders took per element considered.
    double chooseSecondsPerSender_ = 0.0;
    // The power one of them has yet to send: the sum of its changes
    // (a cluster's, facet by facet) in size, or with their signs.
    double unsentPowerOf(ElementId e, bool absolute = true) const;
    // Link updates made between two looks at the clock.
    static constexpr std::size_t kDeadlineChunk = 1024;
    // Catching up (catchUp): the fewest stale links a chunk holds, what a
    // link recomputed in full costs against one whose dynamic visibility
    // only is (about 4 to 5 times, measured), and what the last chunk took
    // per unit of that cost.
    static constexpr std::size_t kLeastChunk = 64;
    static constexpr double kFullRecompute = 4.0;
    double catchUpSecondsPerUnit_ = 0.0;
    std::vector<LinkId> pending_;
    // Links a budget left with the transfers of an earlier position, in the
    // order deferred; marked so that none is queued twice. With each, the
    // frame that found it (frame_), the motion clock when it was last right,
    // and its potential transfer then, which the estimate reads (made again
    // each frame for 50,000 stale links of `office`'s chair, it took 3 ms of
    // 8). The link itself is not read when it is deferred (65,000 links
    // scattered in memory took 5 to 7 ms in `two-offices`).
    struct StaleLink {
        LinkId id;
        std::uint32_t frame;
        double at;
        double transfer;
    };
    std::deque<StaleLink> stale_;
    // The visits deferFound has yet to defer, while it goes on over frames
    // (deferringFound_); a p-link's visit before those below it.
    std::vector<std::size_t> deferStack_;
    bool deferringFound_ = false;
    // Per moving object (its cluster's range), the last frame it moved in;
    // and the last frame the layers changed in (chooseObject). A stale link
    // whose end moved, or whose layers changed, since the frame that found
    // it gets a new form factor and both visibility parts; otherwise only
    // its dynamic visibility changed (three times cheaper).
    std::vector<std::pair<IndexRange, std::uint32_t>> lastMoved_;
    std::uint32_t layersChangedFrame_ = 0;
    bool changedSince(const Link& l, std::uint32_t frame) const;
    // The motion clock: the sum over moves of the largest motionShare of the
    // objects moved; and its value before the last move.
    double motion_ = 0.0, motionBefore_ = 0.0;
    // Per link slot, set if in stale_ (serial: defer() and catchUp()).
    LinkBits staleMarks_;
    bool isStale(LinkId id) const { return staleMarks_.test(id); }
    void markStale(LinkId id, bool stale);
    mutable ChunkedArray<double, 12> powerScratch_;  // estimatedError's per-element sums, zero between calls
    ChunkedArray<char, 16> sending_;                // bounce()'s per-element marks, zero between calls
    mutable std::optional<double> meanReflectance_;  // estimatedError's, over the polygons' area
    // What a deferred object's links carry (estimatedError): per object
    // cluster, the potential transfer of the active links with an end in its
    // subtree, summed per receiver. Made when first asked for, and kept until
    // a traversal begins (or an edit, a choice of object, a solve, elements
    // freed): the
    // frames of a drag that defer their moves asked for it each, and walking
    // the `office` chair's 107,000 links took 2.5 to 3.5 ms of every
    // 8.3 ms frame at 120 fps. What the catch-up changes on those links
    // meanwhile is left out, as a stale link keeps its transfer as found.
    const std::vector<std::pair<ElementId, double>>& carriedBy(ElementId top) const;
    void dropCarriedOfFreed() const;                  // the sums that freed elements made wrong
    std::size_t linksCarriedBy(ElementId top) const;  // walked by carriedBy: its cost
    mutable std::map<ElementId, std::vector<std::pair<ElementId, double>>> carried_;
    mutable double carriedSecondsPerLink_ = 0.0;  // what carriedBy last took per link walked
    mutable double carriedSeconds_ = 0.0;         // and in all, this frame's estimate
    mutable std::vector<double> carriedScratch_;  // carriedBy's sums, zero between calls
    mutable std::uint64_t carriedReleases_ = 0;   // Hierarchy::releases() when they were made
    // This frame's are the first visitCount_. In chunks (ChunkedArray):
    // as a vector, a traversal that outgrew it copied every record into
    // fresh memory, a page fault per 4 KiB (a random room's 57,000 visits
    // ran a traversal 7 ms past its stop at 60 fps).
    ChunkedArray<Visit, 12> visits_;
    std::size_t visitCount_ = 0;
    // Per visit of a level: its child visits (node, source range), kept
    // with their storage from frame to frame.
    std::vector<std::vector<std::pair<ElementId, IndexRange>>> childVisits_;
    std::vector<LinkId> doomed_;  // removeLineSpaceChildren's, kept to spare an allocation per node
    std::vector<LinkId> modified_;  // this frame's modified links, for the overlay
    std::vector<LinkId> overlayLinks_;       // what modifiedLinks() draws
    bool overlayLinkLive(LinkId id) const { return id < links_.slots() && links_[id].live; }
    std::vector<ElementId> overlayChanged_;  // changedOutlines() draws the leaves among them
    // The overlay segments of this frame's modified links and changed
    // elements; `append`: added to those on show (catching up after a move).
    void recordOverlay(const std::vector<ElementId>& changed, bool append);
};

}  // namespace rad
