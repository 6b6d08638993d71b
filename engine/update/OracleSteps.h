#pragma once
// Refinement that follows the light, without remembering the path.
//
// BF refinement judges a link by its source's radiosity (the oracle). Frozen
// at the first solve, a room that was dark then is never refined when a door
// opens onto it (the paper's Fig. 10); following B exactly, a refinement
// made while a region was bright is kept after it goes dark again, and moving
// an object away and back no longer returns the solution it started from.
//
// So the oracle follows B in steps: it only takes the values
// (anchor + f) * kStep^level - f, where the anchor is the oracle the solve
// refined by and f a small floor (so that a region dark at the solve can
// still brighten). The level is the number of steps B stands from its value
// when the solve ended (anchorLight), and changes only when B is more than
// kHysteresis steps away from the current level. When B returns to its value
// at the solve, the level returns to 0 and the oracle to exactly the one the
// hierarchy was built with; the links of an element whose level moved are
// judged again (refined, or their p-links reinstated), so the hierarchy
// returns too.

#include <span>
#include <vector>

#include "hierarchy/Hierarchy.h"

namespace rad {

struct OracleSteps {
    static constexpr double kStep = 1.4142135623730951;  // sqrt(2): the oracle is within 19% of B
    static constexpr double kHysteresis = 0.75;  // in steps: B back at the anchor is level 0
};

// The luminance refinement judges an element's links by: for a surface the
// B of its brightest leaf (a link sends the mean, and a bright strip that
// the receiver cannot see must not pass for light it does), and for a
// cluster its brightest facet (a lamp in a dark cluster counts).
double oracleOf(const Hierarchy& hierarchy, ElementId e);

// After a solve: every element's anchor becomes its oracle and its anchor
// light its current B (oracleOf), at level 0. Moves and edits step from
// there.
void anchorOracles(Hierarchy& hierarchy);

// Moves the oracles of the given elements to the level nearest their current
// B times `scale` when it is more than kHysteresis steps away. `floor`: f
// above. `scale`: the emitted power at the solve over the current one (an
// edit of a light changes it), so that the level follows an element's share
// of the light: dimming every light alike changes no level, as it changes no
// refinement of a solve. Returns the elements whose oracle moved, in the
// given order, and among them those whose oracle rose: a link is refined
// for its source's oracle, and one that fell asks for no refinement its
// links did not ask for before (only, later, for coarsening). Each element
// at most once: they step on all cores.
struct SteppedOracles {
    std::vector<ElementId> moved;
    std::vector<ElementId> rose;
};
SteppedOracles stepOracles(Hierarchy& hierarchy, std::span<const ElementId> elements, double floor, double scale);

}  // namespace rad
