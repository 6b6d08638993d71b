#pragma once
// What a user of the engine can set: the accuracy of the solve and the budget
// of an update.

#include <cstddef>
#include <optional>

namespace rad {

struct SolveSettings {
    // Converged when the remaining error, extrapolated from the last two
    // sweeps as a geometric series (delta * r / (1 - r)), is below this
    // fraction of the mean radiosity.
    double tolerance = 1e-4;
    int maxIterations = 5000;
    // Once each channel's change falls by a steady ratio r per sweep, the
    // slowest mode is taken out in one step (Aitken's extrapolation):
    // B += (B - B_before) r / (1 - r). A closed room of reflectance 0.99
    // converges in tens of sweeps instead of hundreds; where the ratio is not
    // steady nothing is extrapolated. Off: plain sweeps.
    bool extrapolate = true;
};

// A point in one room of a building sees a fifth or more of its room's
// area (0.25 in `office`, 0.23 in `dark-room`, 0.45 to 0.67 in the other
// shipped rooms): a scene whose points see less is taken as several rooms.
inline constexpr double kRoomShare = 0.2;

// The default area threshold A_e: this share of the scene's polygon area,
// so that it suits any scene scale.
inline constexpr double kDefaultMinAreaShare = 2e-5;

struct EngineSettings {
    double epsilon = 5e-5;  // BF threshold, relative to the total emitted power
    // Area threshold A_e in square metres; 0 picks kDefaultMinAreaShare of
    // the scene's total polygon area.
    double minArea = 0.0;
    // Thresholds relative to a room, not to the whole scene: where a point
    // sees less than kRoomShare of the scene's area (measureSurroundings, in
    // refine/Surroundings.h), epsilon's reference power and the default area
    // threshold are scaled by that share over kRoomShare, rounded down to a
    // power of two. A building of 60 rooms is then refined in each room as
    // the room alone would be, not 60 times more coarsely. A scene open to
    // the sky (kOpenShare of the rays leave it) keeps the whole scene's.
    // With it too, polygons that the first round finds lit under a quarter
    // of the scene's mean receive on thresholds up to four times finer
    // (refine/ReceiverLight.h).
    bool localThresholds = true;
    SolveSettings solve;
    int maxRefineRounds = 16;  // refine / solve rounds before giving up
    // Refinement stops before links and elements take more than this many
    // bytes (the solve then says so: SolveStats::stoppedBy). 0: half of the
    // memory the machine has available when the engine starts
    // (defaultMemoryLimit()).
    std::size_t maxMemoryBytes = 0;
    // Visibility sample points per element; a link casts the product of its
    // two ends' counts (16 x 16 at most).
    int samplesPerElement = 4;
    // The energy guard: a point whose form factors sum above one reflects no
    // more than a closed enclosure would send it (solve/Solver.h). Off only
    // to show what it prevents.
    bool energyGuard = true;
    // The fill: where a polygon's view is closed, what its links leave
    // uncovered is lit as what they cover (solve/Solver.h). Off only to
    // show what it adds.
    bool fill = true;
};

// Half of the memory available on this machine (Linux: MemAvailable in
// /proc/meminfo), or 4 GiB when that cannot be read.
std::size_t defaultMemoryLimit();

inline constexpr std::size_t kUnlimited = static_cast<std::size_t>(-1);

struct UpdateSettings {
    // Link updates allowed per frame (sec. 6.1): recomputed links, reinstated
    // p-links and links created by refinement each count one. None: no limit.
    std::optional<std::size_t> budget;
    // Frames on a deadline: the frame, the lit mesh included, is to end this
    // many seconds after it began. Link updates get half of the time left
    // when they begin (the clock is read between levels of the second
    // traversal and between batches of about a thousand link updates), the
    // push-pull and further bounces of what they changed the other half: a
    // bounce is not begun once the time left would not cover it and the
    // mesh. What is left waits (stale, pending or unsent) for later frames
    // and idle time. The first traversal and the push-pull of what was
    // updated always run. None: no limit.
    std::optional<double> deadlineSeconds;
    // Further bounces stop when no element's radiosity moved by more than
    // this fraction of the scene's mean emitted radiosity.
    double bounceThreshold = 7e-4;
    // While objects move, a change under this larger fraction waits, unsent,
    // for the next frame or idle time, which sends it down to
    // bounceThreshold (edits always bounce to bounceThreshold). Each further
    // bounce of a chair's move reaches most of `office` and pushes it; at
    // 3e-3 a frame makes two thirds of the bounces, and its distance from a
    // full solve moves by under 0.01 point (README, "The update after a
    // move").
    double moveBounceThreshold = 2e-3;
    int maxBounces = 100;
    // Once the change a bounce sends falls by a steady ratio r, each sender
    // sends the change of every bounce to come at once (Aitken's
    // extrapolation, as SolveSettings::extrapolate; update/LineSpaceUpdate.h).
    // Off: plain bounces.
    bool extrapolateBounces = true;
    // Radiosity is linear in the emission: an edit that changes the same
    // emitters by c times the last edit's change (channel by channel, as a
    // light dimmed on a slider) sends c times that edit's light at once,
    // and the bounces send only what that misses (update/EditResponse.h).
    // Off: bounces only.
    bool scaleLastEdit = true;
};

}  // namespace rad
