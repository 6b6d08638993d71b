#pragma once
// Gather and push-pull (Hanrahan et al. 1991; with clusters, Sillion 1995),
// iterated to convergence in double precision.
//
// The energy guard: a point's form factors toward everything it sees sum to
// at most one. Where the links gathered at a leaf and its ancestors sum to
// more (coincident geometry the visibility did not separate, quadrature and
// point-approximation errors), the leaf's irradiance is divided by that sum:
// no leaf reflects more light than a closed enclosure would send it, so the
// iteration cannot diverge for reflectance below one.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "links/Link.h"
#include "radiosity/Settings.h"
#include "radiosity/Stats.h"
#include "solve/ClusterTransfer.h"

namespace rad {

struct SolveResult {
    enum class Status {
        Converged,
        IterationLimit,  // still changing after maxIterations sweeps
        Diverged,        // the residual kept growing, or more power than can be
        NonFinite,       // a radiosity became NaN or infinite
    };
    Status status = Status::IterationLimit;
    int iterations = 0;
    bool converged = false;
    double lastChange = 0.0;      // relative change in the last sweep
    double estimatedError = 0.0;  // relative, extrapolated
};

// Where the energy guard acted, per object.
struct GuardAction {
    std::uint32_t object = 0;
    double area = 0.0;        // of its leaves whose form factors summed above 1 + threshold
    double largestSum = 0.0;  // the largest sum met
};

class Solver {
  public:
    Solver(Hierarchy& hierarchy, LinkStore& links) : h_(hierarchy), links_(links) {}

    // Every element's gathered state becomes its current one, every link's
    // held transfer its form factor, and every surface's irradiance the sum
    // over its links.
    void gatherAll();
    // Pushes irradiance down, computes leaf radiosity, pulls area-weighted
    // means (and cluster facet powers) up. Returns the area-weighted relative
    // change of leaf radiosity.
    double pushPull();
    // Partial push-pull (Fig. 7): only the paths to the dirty elements and the
    // subtrees below them are visited; elsewhere the stored B stands. Clears
    // the marks. Returns the elements visited.
    //
    // On a deadline (`stop`), a dirty element whose subtree's push is
    // expected to end after it waits, unpushed: its subtree keeps its B, and
    // the next partial push-pull pushes it (or lets it wait again). The
    // expected cost is the element's share of the scene's surface area
    // times `secondsPerArea`: a dirty cluster near the root
    // (a chair's light reaching most of a building floor through one coarse
    // link) is a push of most of the scene. Inside a subtree pushed whole,
    // an element whose own subtree is expected to take more than
    // kPushClockSeconds, and every kPushClockEvery-th element, reads the
    // clock, and once it has passed `stop` they and every element after them
    // wait, unpushed. (A clock read costs about a fifth of an element's
    // push. The expectation is by the scene's mean density, and the
    // hierarchy is finest where an object moves: with the clock read only
    // by it, the building floor's pushes ran up to 5 ms past their stop.)
    static constexpr double kPushClockSeconds = 50e-6;
    static constexpr std::uint32_t kPushClockEvery = 16;
    struct PushDeadline {
        std::chrono::steady_clock::time_point stop;
        double secondsPerArea = 0.0;
        // The clock (a test's own, to pass the stop at a chosen moment).
        std::function<std::chrono::steady_clock::time_point()> now = [] { return std::chrono::steady_clock::now(); };
    };
    // `polygons`, when given, gets the polygons of the leaves visited (a
    // polygon may come more than once).
    std::vector<ElementId> partialPushPull(const std::vector<ElementId>& dirty,
                                           std::optional<PushDeadline> deadline = std::nullopt,
                                           std::vector<std::uint32_t>* polygons = nullptr);
    // The dirty elements the last deadline left unpushed.
    const std::vector<ElementId>& unpushed() const { return unpushed_; }
    // Iterates gather and push-pull until converged or maxIterations. Every
    // sweep checks that the radiosity is finite and not running away: no
    // radiosity can exceed the largest emission over (1 - the largest
    // reflectance), and a residual that grows sweep after sweep never
    // converges.
    SolveResult solve(const SolveSettings& settings,
                      const std::function<void(int, double)>& progress = {});
    // The energy guard (on by default; off only to show what it prevents).
    void setEnergyGuard(bool on) { guard_ = on; }
    // The fill (see arriving()): each polygon's closure (solve/Closure.h),
    // indexed by polygon; empty: no fill.
    void setClosure(std::vector<float> closure) {
        closure_ = std::move(closure);
        allClosed_ = std::all_of(closure_.begin(), closure_.end(), [](float c) { return c >= 1.0f; });
    }
    std::vector<float>& closure() { return closure_; }
    // Whether every polygon's view was closed at the solve: then moves
    // leave every closure at 1 and measure none again.
    bool allClosed() const { return allClosed_; }
    // The most the fill raises what a leaf's links bring: 8%. With 10%,
    // `furnished-room` absorbed 0.15% more light than it emits; with 8%,
    // none of the shipped scenes does. A point whose links cover little of
    // its view and see a light among them is not lit by that light over
    // what they miss.
    static constexpr double kMaxFill = 1.08;
    // How much more uncertain a cluster link's form factor is than a
    // surface link's, per unit, for the energy guard (arriving()). With 10
    // the Cycles comparisons are within 0.3 points of what cutting clusters
    // first gave, but for the stair hall (1.0 points further); 30 and 100
    // came closer to it but left a grid of 1,200 small LEDs losing 3.7% and
    // 20% of its light, against none with 10.
    static constexpr double kClusterUncertainty = 10.0;
    // Closure from which the fill starts (none below, all from 1).
    static constexpr double kClosedFrom = 0.95;
    // The largest direct irradiance from punctual lights at any point, per
    // channel: it raises the bound no radiosity can exceed.
    void setDirectBound(const glm::dvec3& bound) { directBound_ = bound; }

    EnergyBalance energy() const;
    // The objects where the energy guard divided by more than 1 + threshold.
    std::vector<GuardAction> guardActions(double threshold) const;
    // What a surface element receives from above, and a leaf in all: the
    // irradiance and the sum of the form factors it came through, apart for
    // links from surfaces (a form factor integrated over both patches) and
    // for what clusters send (on links from a cluster, and a cluster's
    // arrivals shared among its members by orientation: estimates).
    struct Down {
        glm::dvec3 irradiance{0.0};
        double formFactorSum = 0.0;
        glm::dvec3 clusterIrradiance{0.0};
        double clusterSum = 0.0;
        // From punctual lights (lights/LightLinks.h): not shared by
        // coverage, not under the energy guard.
        glm::dvec3 direct{0.0};

        glm::dvec3 totalIrradiance() const { return irradiance + clusterIrradiance; }
        double totalSum() const { return formFactorSum + clusterSum; }
    };
    // Visits every surface leaf with what arrives there on links (before
    // the guard and the fill) and the irradiance punctual lights send it.
    void forEachLeaf(const std::function<void(const HElement&, const Down&)>& f) const;
    // What arrives at a leaf of input polygon `polygon` from what its links
    // (and those above it) bring, d:
    //   - the energy guard: a form-factor sum above one over-counts the view
    //     (no point receives more than a closed enclosure sends it). The
    //     excess is taken from the two kinds of links in proportion to how
    //     uncertain each sum is (the least change, weighed by each one's
    //     variance): a cluster link's form factor (a few points, 16 rays) is
    //     taken as kClusterUncertainty times as uncertain, per unit, as a
    //     surface link's (integrated over the receiver, the inner integral
    //     exact). So coarse cluster links over-counting a view give way
    //     almost alone (dividing all, the exact light of a lamp was cut
    //     there: the stair hall's lower storey 19.7% from Cycles against
    //     18.4% with clusters cut first), while the light of a lamp that
    //     arrives on a cluster link of small form factor is barely cut by
    //     the surfaces' small excess (cut first, a grid of 300 small LEDs
    //     under a ceiling lost 17% of its light and a table under it 44%).
    //     When the surfaces' links alone sum past one, all is divided by
    //     the sum.
    //   - the fill: below one the links leave part of the view uncovered
    //     (their visibility rays and point approximations miss what lies
    //     between them), and light is lost: 7.4% of what `office` emits,
    //     most of it on the floor under the furniture, in the bookcases and
    //     on the desks, whose views its links covered by 0.82 to 0.92 on
    //     average. Where the polygon's view is closed (no direction leaves
    //     the scene), the uncovered part sees what the covered part sees on
    //     average: the irradiance is divided by the sum, by at most
    //     kMaxFill. Between kClosedFrom and a closed view the fill grows
    //     from none to all, so that a polygon glimpsing an opening is not
    //     lit unlike its neighbour.
    glm::dvec3 arriving(const Down& d, std::uint32_t polygon) const {
        const glm::dvec3 irradiance = d.totalIrradiance();
        const double formFactorSum = d.totalSum();
        if (guard_ && formFactorSum > 1.0) {
            // The surfaces' links alone over one: all divided; else the
            // excess divides as the two sums' variances.
            if (d.formFactorSum >= 1.0 || !(d.clusterSum > 0.0)) return irradiance / formFactorSum;
            const double excess = formFactorSum - 1.0;
            const double clusters = kClusterUncertainty * kClusterUncertainty * d.clusterSum * d.clusterSum;
            const double surfaces = d.formFactorSum * d.formFactorSum;
            const double fromClusters = std::min(d.clusterSum, excess * clusters / (clusters + surfaces));
            const double fromSurfaces = excess - fromClusters;
            const glm::dvec3 kept = d.clusterIrradiance * ((d.clusterSum - fromClusters) / d.clusterSum);
            if (!(d.formFactorSum > 0.0)) return kept;
            return kept + d.irradiance * ((d.formFactorSum - fromSurfaces) / d.formFactorSum);
        }
        if (!(formFactorSum > 0.0) || polygon >= closure_.size()) return irradiance;
        const double closure = closure_[polygon];
        const double weight = std::clamp((closure - kClosedFrom) / (1.0 - kClosedFrom), 0.0, 1.0);
        return irradiance * (1.0 + weight * (std::clamp(closure / formFactorSum, 1.0, kMaxFill) - 1.0));
    }

  private:
    // The walk state of one descent: what the ancestor clusters' links bring,
    // and, for partial push-pulls, the elements visited.
    struct Walk {
        std::vector<ElementId>* visited = nullptr;
        double change = 0.0, total = 0.0;
        const PushDeadline* deadline = nullptr;
        std::vector<ElementId>* unpushed = nullptr;  // with a deadline
        std::vector<std::uint32_t>* polygons = nullptr;  // of the leaves visited
        // Elements of subtrees pushed whole since the clock was last read,
        // and whether it had passed the stop then.
        std::uint32_t sinceClock = 0;
        bool late = false;
    };
    // One element of a push-pull: its new B. `forced`: the whole subtree is
    // pushed (full push-pull, or below a dirty element); otherwise only the
    // paths marked changed are.
    // `down`: for a surface, what arrives from above; `facets`: for a
    // cluster, what its ancestors' links bring to its facets.
    glm::dvec3 push(ElementId id, const Down& down, const FacetArrivals& facets, bool forced,
                    int depth, Walk& walk);
    // Whether element `e` of a push on a deadline waits for a later push.
    static bool pastPushDeadline(const HElement& e, bool forced, Walk& walk);
    // Cluster levels (from the root) whose children are pushed in parallel.
    static constexpr int kParallelDepth = 8;
    // Sweeps in a row whose change grows before the solve calls it diverging.
    static constexpr int kGrowingSweeps = 20;
    // What arrives at a surface element: from above, and on its own links.
    Down surfaceDown(ElementId id, const Down& down) const;
    // The push of a surface element's irradiance to its children. What
    // arrives from above came through links coarser than the children's own;
    // at each child it goes to the part of the view that the child's finer
    // links leave uncovered (1 - coverage), not to every child alike: next to
    // a wall, the wall's fine links cover half the view, and the rest of the
    // room is seen over the other half only. The shares keep the area-weighted
    // sum, so no power is made or lost, and in a closed scene every leaf's
    // form factors sum to one, as every point's do.
    double meanUncovered(const HElement& e) const;
    static Down shareOf(const Down& down, const HElement& child, double meanUncovered);
    // Whether every polygon's radiosity is finite and, with the guard, under
    // the bound no solution can exceed (E_max / (1 - rho_max) per channel).
    bool finiteAndBounded() const;
    // That bound per channel (infinite where rho_max >= 1 or without the guard).
    glm::dvec3 radiosityBound() const;

    // Aitken's extrapolation (SolveSettings::extrapolate). The state a sweep
    // starts from, the surface leaves' area-weighted change per channel, and
    // the step B += factor (B - before) on every element, kept within
    // [0, bound], with the clusters' facet powers pulled again from it.
    void saveRadiosity(std::vector<glm::dvec3>& into) const;
    glm::dvec3 leafChange(const std::vector<glm::dvec3>& before) const;
    void extrapolate(const std::vector<glm::dvec3>& before, const glm::dvec3& factor);
    void pullClusterPowers(ElementId id);
    // Sweeps after the start or an extrapolation before the next one, and how
    // steady the ratio must be: |r - r_before| <= kSteadyRatio (1 - r).
    static constexpr int kSweepsBeforeExtrapolating = 3;
    static constexpr double kSteadyRatio = 0.02;

    Hierarchy& h_;
    LinkStore& links_;
    bool guard_ = true;
    std::vector<float> closure_;
    bool allClosed_ = true;
    std::vector<ElementId> unpushed_;
    glm::dvec3 directBound_{0.0};
};

}  // namespace rad
