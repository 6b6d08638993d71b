#pragma once
// The interactive update after the dynamic object moves (paper sec. 4 and 5):
// the line-space traversal finds the links whose shafts the object touched
// before or after the move (findModifiedLinks, Fig. 6), reinstates p-links
// that would no longer be refined and removes their line-space children; the
// candidates are updated with the in-place gather and refined from a heap
// ordered by potential power transfer; a partial push-pull (Fig. 7) and
// further bounces (sec. 5.3.2) finish the frame.

#include <cstddef>
#include <cstdint>
#include <queue>
#include <utility>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "links/Link.h"

namespace rad {

class Refiner;
class Solver;

struct FrameStats {
    double traversalSeconds = 0.0;
    double updateSeconds = 0.0;  // link update and refinement
    double pushPullSeconds = 0.0;  // partial push-pull and further bounces
    double totalSeconds = 0.0;
    std::size_t shaftTests = 0;
    std::size_t candidates = 0;
    std::size_t linksUpdated = 0;
    std::size_t reinstated = 0;
    std::size_t refined = 0;
    std::size_t changedElements = 0;  // visited by the partial push-pull
    std::size_t links = 0;
    std::size_t elements = 0;
    int bounces = 0;
};

struct UpdateSettings {
    // Further bounces stop when no element's radiosity moved by more than
    // this fraction of the scene's mean emitted radiosity.
    double bounceThreshold = 1e-4;
    int maxBounces = 100;
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
    // `layersChanged`: the choice of dynamic object changed, so both parts of
    // the visibility of every link the traversal finds are recomputed.
    FrameStats update(const Aabb& oldBox, const Aabb& newBox, const IndexRange& moved,
                      const UpdateSettings& settings, bool layersChanged = false);

private:
    void findModifiedLinks(ElementId he, const IndexRange& ind);
    void checkAddLinks(ElementId he, const IndexRange& ind);
    bool affectedByMotion(ElementId s, ElementId r);
    // Recomputes a link's form factor and visibility for the new position.
    void recompute(LinkId id);
    void reinstate(LinkId id);
    void removeLineSpaceChildren(ElementId e, const IndexRange& sources, LinkId keep);
    bool subtreeUnlinked(ElementId e) const;
    using RefineHeap = std::priority_queue<std::pair<double, LinkId>>;
    void updateCandidates(FrameStats& stats);
    // Sec. 5.2: the link with the highest potential power transfer first.
    void refineFromHeap(RefineHeap& heap, FrameStats& stats);
    double heapKey(const Link& l) const;
    void bounce(std::vector<ElementId> visited, const UpdateSettings& settings, FrameStats& stats);

    Hierarchy& h_;
    LinkStore& links_;
    Refiner& refiner_;
    Solver& solver_;
    double referenceRadiosity_;

    // Per frame.
    Aabb oldBox_, newBox_;
    IndexRange moved_;
    bool layersChanged_ = false;
    std::uint32_t frame_ = 0;
    std::vector<std::uint32_t> linkStamp_;  // frame in which a link became a candidate
    std::vector<LinkId> candidates_;
    std::size_t shaftTests_ = 0;
    std::size_t reinstated_ = 0;
};

}  // namespace rad
