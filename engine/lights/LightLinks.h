#pragma once
// Punctual lights (KHR_lights_punctual) in the hierarchy. A light is a point
// with an intensity per direction, not a surface: it has no H-element, and
// its light reaches surface elements through light links, one per receiver.
// A light link holds the irradiance the light sends to its receiver per unit
// of intensity, I cos(theta) falloff / r^2 averaged over the receiver's
// quadrature points, each point counted only when its visibility ray to the
// light is free in both layers (sec. 3.4). A receiver is subdivided while
// that irradiance varies across it by more than the refinement threshold
// allows: the paper's B F A_r criterion becomes the spread of the irradiance
// times the receiver's area. Shadow edges, spot rims and walls near a light
// refine; a floor far from it does not.
//
// What the links bring is each element's `direct` irradiance. The solver adds
// it under the energy guard's reach (a light is not a surface that form
// factors see) and pushes it down the quadtree whole.

#include <chrono>
#include <cstdint>
#include <optional>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geometry/RayCaster.h"
#include "hierarchy/Hierarchy.h"
#include "radiosity/Scene.h"

namespace rad {

class LightLinks {
public:
    // `scene` and `hierarchy` must outlive it; the lights are read from the
    // scene each time (moves and edits change them there).
    LightLinks(const Scene& scene, Hierarchy& hierarchy, const RayCaster& rays)
        : scene_(scene), h_(hierarchy), rays_(rays) {}

    // The refinement threshold: epsilon times the reference power. A receiver
    // is subdivided while luminance(I) times the spread of its irradiance
    // times its area exceeds it.
    void setThreshold(double power) { threshold_ = power; }

    using Clock = std::chrono::steady_clock;

    // Links every light to every polygon, from scratch; sets every element's
    // direct irradiance.
    void linkAll();
    // Links the given polygons again (after they or something between them
    // and a light moved), to every light or to `light` only. Returns the
    // polygons' surface elements whose direct light changed. On a deadline,
    // refinement stops at the level it has reached when the clock passes it
    // (every polygon is linked, coarser than the threshold asks where it
    // stopped), and those polygons wait, pending, to be linked again.
    std::vector<ElementId> relink(const std::vector<std::uint32_t>& polygons,
                                  std::optional<std::uint32_t> light = std::nullopt,
                                  std::optional<Clock::time_point> deadline = std::nullopt);
    // After objects moved (`boxes`: each one's box before and after), their
    // polygons (`moved`) are linked again whole, and the polygons they shade
    // or shaded (shadedBy) where an element's shaft toward a light meets a
    // box: below an element whose shaft meets none, the links stay as they
    // were (its rays and their occluders are as they were), which is what
    // linking it again would give. Returns what relink returns.
    std::vector<ElementId> relinkAround(const std::vector<std::uint32_t>& moved, const std::vector<Aabb>& boxes,
                                        std::optional<Clock::time_point> deadline = std::nullopt);
    // The elements whose links the last relinkAround kept (not estimated again).
    std::size_t keptLastRelink() const { return keptLast_; }
    // Every polygon, for one light (it moved).
    std::vector<ElementId> relinkLight(std::uint32_t light, std::optional<Clock::time_point> deadline = std::nullopt);
    // Links the pending polygons again, refined to the threshold, a few at a
    // time until the deadline (at least a few, so that idle time converges).
    // Returns the elements whose direct light changed.
    std::vector<ElementId> refinePending(std::optional<Clock::time_point> deadline);
    // Polygons a deadline left linked coarser than the threshold asks, over all lights.
    std::size_t pendingCount() const;
    // The direct light summed again after `light`'s intensity changed.
    // Returns the polygon elements it reaches.
    std::vector<ElementId> refreshIntensity(std::uint32_t light);
    // After an edit (an intensity, or the threshold with the emitted power):
    // the lights whose share of the light stepped (see judgedIntensity), at
    // their new level; each is to be linked again (relinkLight).
    std::vector<std::uint32_t> stepShares();
    // The polygons in front of some light whose shaft toward it meets one of
    // the boxes.
    std::vector<std::uint32_t> shadedBy(const std::vector<Aabb>& boxes) const;

    // The polygon elements whose direct light relink, relinkLight,
    // refinePending or refreshIntensity changed since the last call, each
    // with how much that moves its radiosity once pushed (the sum over its
    // elements of (rho dE)^2 A): what a push a deadline defers leaves off.
    std::vector<std::pair<ElementId, double>> takeChanges() { return std::exchange(changes_, {}); }
    // An upper bound, per channel, of the direct irradiance at any point.
    glm::dvec3 directBound() const;
    std::size_t linkCount() const;
    std::size_t memoryBytes() const;

    // Quadrature order over a receiver: order^2 points, one visibility ray each.
    static constexpr int kOrder = 4;
    // A polygon whose whole area, seen at its nearest distance head-on,
    // would bring less than this share of the threshold is not linked: it
    // spares the rays toward the far rooms of a building, where the light
    // could bring almost nothing even unoccluded.
    static constexpr double kNegligible = 1e-3;

private:
    struct LightLink {
        ElementId receiver = kNone;
        float irradiance = 0.0f;  // per unit intensity, mean over the receiver, visibility included
        float peak = 0.0f;        // the largest value at a quadrature point
        bool operator==(const LightLink&) const = default;
    };
    struct Estimate {
        double mean = 0.0, spread = 0.0, peak = 0.0;
    };
    // The irradiance per unit intensity at the receiver's quadrature points.
    Estimate estimate(const PunctualLight& light, ElementId receiver) const;
    // The intensity (luminance) a light's links are refined by. A light's
    // links are made again when its share of the threshold, I / T, has
    // stepped: the level, the number of steps of kStep (update/OracleSteps.h)
    // it stands from its share when linkAll ran, I0 / T0, moves only when
    // the share is more than kHysteresis steps from it. Away from level 0 the
    // links are refined by the light's intensity, as a solve at it would
    // refine them; at level 0 by the anchor's share, I0 T / T0, so that a
    // light set back gets the solve's links again. (Refined by I0 (T / T0)
    // kStep^level instead, a bulb brightened from a hundredth of another's
    // intensity to the other's, 11 steps, was judged 10% dim and came 2.0%
    // rms from a solve of the brightened scene; by its intensity, 0.) A light
    // dark when linked takes its first positive intensity as its anchor.
    double judgedIntensity(std::uint32_t light) const;
    // The level the light's share now calls for (its current level when
    // within kHysteresis steps of it).
    int shareLevel(std::uint32_t light) const;
    // Refines the links of one light to the given polygons, level by level:
    // the estimates of a level on all cores, its subdivisions in order.
    // With `around`, polygons not flagged in `around->whole` (not pending)
    // keep their links below elements whose shaft misses `around->boxes`.
    struct Around {
        const std::vector<Aabb>& boxes;
        const std::vector<std::uint8_t>& whole;  // per polygon
    };
    void link(std::uint32_t light, const std::vector<std::uint32_t>& polygons,
              std::optional<Clock::time_point> deadline, const Around* around = nullptr);
    std::vector<ElementId> relink(const std::vector<std::uint32_t>& polygons, std::optional<std::uint32_t> light,
                                  std::optional<Clock::time_point> deadline, const Around* around);
    // Clears the direct light of a polygon's quadtree and adds every light's
    // links to it; whether anything changed is for the caller to know.
    // Returns how much it moves the polygon's radiosity once pushed: the sum
    // over its elements of (rho dE)^2 A, dE the change of their direct
    // irradiance (luminance).
    double sumDirect(std::uint32_t polygon);
    // The polygons summed again since takeChanges(), with sumDirect's measure.
    std::vector<std::pair<ElementId, double>> changes_;
    bool facesLight(const PunctualLight& light, std::uint32_t polygon) const;
    void sizeTables();

    const Scene& scene_;
    Hierarchy& h_;
    const RayCaster& rays_;
    std::size_t keptLast_ = 0;
    double threshold_ = 0.0;
    // Per light, the links of each polygon it reaches (sparse: a lamp in one
    // room of a building reaches a few of its polygons).
    std::vector<std::unordered_map<std::uint32_t, std::vector<LightLink>>> links_;
    // Per light, the polygons a deadline left coarse.
    std::vector<std::set<std::uint32_t>> pending_;
    // Per light: its intensity (luminance) and the threshold when it was
    // anchored (linkAll, or its first positive intensity), and the level of
    // its share its links were made at.
    struct Anchor {
        double intensity = 0.0, threshold = 0.0;
        int level = 0;
    };
    std::vector<Anchor> anchors_;
    const std::vector<LightLink>& linksOf(std::size_t light, std::uint32_t polygon) const;
};

}  // namespace rad
