#pragma once
// Gather and push-pull (Hanrahan et al. 1991; with clusters, Sillion 1995),
// iterated to convergence in double precision.

#include <functional>

#include "hierarchy/Hierarchy.h"
#include "links/Link.h"
#include "radiosity/Settings.h"
#include "radiosity/Stats.h"

namespace rad {

struct SolveResult {
    int iterations = 0;
    bool converged = false;
    double lastChange = 0.0;      // relative change in the last sweep
    double estimatedError = 0.0;  // relative, extrapolated
};

class Solver {
public:
    Solver(Hierarchy& hierarchy, LinkStore& links) : h_(hierarchy), links_(links) {}

    // I_r = sum over active links of F B_s, for every element; records the
    // form factor gathered on each link.
    void gatherAll();
    // Pushes irradiance down, computes leaf radiosity, pulls area-weighted
    // means up. Returns the area-weighted relative change of leaf radiosity.
    double pushPull();
    // Partial push-pull (Fig. 7): only the paths to the dirty elements and the
    // subtrees below them are visited; elsewhere the stored B stands. Clears
    // the marks. Returns the elements visited.
    std::vector<ElementId> partialPushPull(const std::vector<ElementId>& dirty);
    // Iterates gather and push-pull until converged or maxIterations.
    SolveResult solve(const SolveSettings& settings, const std::function<void(int, double)>& progress = {});

    EnergyBalance energy() const;

private:
    glm::dvec3 pushPull(ElementId e, const glm::dvec3& down, double& change, double& total);
    // Cluster levels (from the root) whose children are pushed and pulled in parallel.
    static constexpr int kParallelDepth = 8;
    glm::dvec3 partialPushPull(ElementId e, const glm::dvec3& down, bool forced, int depth,
                               std::vector<ElementId>& visited);
    Hierarchy& h_;
    LinkStore& links_;
};

}  // namespace rad
