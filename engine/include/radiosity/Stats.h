#pragma once
// What the engine reports about a solve and about each frame of an update.

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/Settings.h"

namespace rad {

// Power balance (luminance, in scene units of power). Where the light that
// leaves the surfaces goes is measured twice: by the links (what the
// surfaces receive) and by rays cast from every polygon (what leaves the
// scene through openings, or ends on the back of a one-sided polygon, which
// absorbs it). What neither accounts for is the solution's own error.
struct EnergyBalance {
    double emitted = 0.0;    // sum E A
    double received = 0.0;   // sum H A, H the irradiance arriving at front sides
    // Of `received`, what the fill added where links left a closed view
    // uncovered (solve/Solver.h, Solver::arriving).
    double filled = 0.0;
    double absorbed = 0.0;   // sum (1 - rho) H A
    double reflected = 0.0;  // sum rho H A
    // Measured by rays: the light leaving the surfaces (sum B A) that
    // meets nothing, and that meets the back of a polygon.
    double escaped = 0.0;
    double backFaces = 0.0;
    // backFaces by the object whose polygons' backs the light meets (by
    // index in Scene::objects): a room whose normals point out shows here.
    std::vector<double> backFacesByObject;
    // Of `escaped`, the emitted light that leaves the scene straight from
    // glowing faces most of whose rays meet nothing, by object: a face that
    // looks out of a closed room (the top of a lamp box flush with its
    // ceiling) shows here, an open room's lamp seen through the opening not.
    std::vector<double> escapedEmissionByObject;
    // emitted - absorbed - escaped - backFaces: light the solution lost
    // (positive) or made (negative), and max(0, absorbed - emitted).
    double lost = 0.0;
    double created = 0.0;
};

// Something the user should know about a solve: one line, the objects it is
// about and a figure (what the figure is depends on the kind).
struct Warning {
    std::string kind;     // "energy_guard", "memory_limit", "duplicates", ...
    std::string message;  // one line
    std::vector<std::string> objects;
    double amount = 0.0;
};

struct MemoryStats {
    std::size_t elements = 0;  // H-elements and their link lists
    std::size_t links = 0;     // links and p-links, the light links of punctual lights
    std::size_t update = 0;    // the update's marks and sums per element, and its marks per link slot
    std::size_t total() const { return elements + links + update; }
};

struct SolveStats {
    std::size_t polygons = 0;
    std::size_t elements = 0;
    std::size_t links = 0;          // active
    std::size_t passiveLinks = 0;   // p-links
    int iterations = 0;             // gather/push-pull sweeps, all rounds
    int refineRounds = 0;
    bool converged = false;
    std::string message;            // why it did not converge, or notes
    // What stopped refinement before the criterion held everywhere (empty:
    // nothing), and the share of the emitted power that the links left
    // coarser than the criterion asks carry.
    std::string stoppedBy;
    double unrefinedPowerShare = 0.0;
    std::vector<Warning> warnings;
    double hierarchySeconds = 0.0;
    double refineSeconds = 0.0;
    double solveSeconds = 0.0;
    double minArea = 0.0;
    // The smallest area threshold of any object: minArea, unless objects of
    // an open scene closed in from the sky took their own (refine/Surroundings.h).
    double minAreaSmallest = 0.0;
    // The share of the scene's emitted power and area the thresholds are
    // relative to (EngineSettings::localThresholds): 1, or a power of two
    // below it in a scene of many rooms.
    double thresholdScale = 1.0;
    MemoryStats memory;
    EnergyBalance energy;
};

// What choosing an object not yet under the root cost (sec. 3.3).
struct ReinsertionStats {
    std::size_t removed = 0;     // links and p-links with an end in the object
    std::size_t recomputed = 0;  // links at its former ancestors
    std::size_t created = 0;     // the object's new links, refinement included
    std::size_t refined = 0;
};

struct FrameStats {
    double traversalSeconds = 0.0;  // shaft tests and descent (sec. 4.1)
    double updateSeconds = 0.0;     // every link recompute, and refinement
    double pushPullSeconds = 0.0;  // partial push-pull and further bounces
    // Of that, the further bounces: on a deadline they take what the frame
    // has left, so the link-update budget's fit leaves them out.
    double bounceSeconds = 0.0;
    // Before those: the object's polygons, H-elements, cluster sample points
    // and ray-casting layer moved, the obstacles found (Engine).
    double moveSeconds = 0.0;
    // After them: the live estimate (estimatedError) and the lit mesh the
    // viewer draws (Engine::snapshot hands it out).
    double estimateSeconds = 0.0;
    double snapshotSeconds = 0.0;
    // All of the frame: the wall clock of the engine call, the snapshot included.
    double totalSeconds = 0.0;
    std::size_t shaftTests = 0;
    std::size_t candidates = 0;
    std::size_t linksUpdated = 0;
    std::size_t reinstated = 0;
    std::size_t refined = 0;
    std::size_t changedElements = 0;  // visited by the partial push-pull
    std::size_t changedLeaves = 0;    // the leaves of the polygons with a changed leaf (meshed again), once each
    std::size_t budget = 0;            // link updates allowed (kUnlimited: no limit)
    std::size_t budgetReinstated = 0;  // p-links reinstated for lack of budget
    std::size_t pending = 0;           // links left coarser than the criterion asks (and polygons' light links)
    std::size_t stale = 0;             // links a budget left with the transfers of an earlier position
    std::size_t unsent = 0;            // elements whose change a deadline kept from bouncing
    // Elements an edit left with links finer than its light now asks
    // (a dimmed light's): idle time (refinePending) coarsens them.
    std::size_t finer = 0;
    std::size_t unmeshed = 0;          // polygons whose meshing the deadline left for a later frame (drawn with their last light)
    std::size_t deferred = 0;          // objects whose move a deadline left for a later frame (links not yet updated, or still being found)
    // On a deadline: the frame's traversal ended after half of it, and
    // what it found waits for the next frame, which defers every link found,
    // stale, and catches up on them first (resumed, then caughtUp in the
    // frames after while stale links are left) and defers its own move.
    bool foundOnly = false;
    // On a deadline: the frame first updated stale links (a traversal's,
    // or those the last frame's budget left), then deferred its own move.
    bool caughtUp = false;
    // On a deadline: the frame's traversal did not end in the time it may
    // take of the frame (kTraversalMost), and the next frame goes on with
    // it where it stopped; its moving objects count in `deferred`.
    bool traversing = false;
    // The frame went on with a traversal an earlier frame's deadline
    // stopped (before its own move, which it then defers).
    bool resumed = false;
    // A live estimate of how far the frame is from what an unlimited update
    // gives, in the units of SolutionError::rms: the power the stale and
    // pending links could still change (each link's potential transfer,
    // B_s F A_r with the unoccluded F) and the unsent elements could still
    // send (their change of B times their area), over the scene's B A.
    double estimatedError = 0.0;
    std::size_t spent = 0;             // link updates made, in budget units
    std::size_t links = 0;
    std::size_t elements = 0;
    int bounces = 0;
    std::size_t transfers = 0;  // a sender's change carried by one link, over the bounces
    ReinsertionStats reinsertion;  // choosing a new dynamic object only
};

struct ObjectRadiosity {
    std::string name;
    double area = 0.0;
    glm::dvec3 radiosity{0.0};  // area-weighted mean B over its surfaces
};

}  // namespace rad
