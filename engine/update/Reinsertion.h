#pragma once
// Choosing any object as the dynamic one (paper sec. 3.3): "each potential
// dynamic object must be included in a cluster of its own. When the user
// selects a dynamic object, the corresponding cluster is attached to the root
// of the hierarchy."
//
// An object inside the static cluster tree is reached by the links of its
// ancestor clusters, and by line-space children of theirs below it. Moving
// its cluster under the root takes it out of what those ancestors stand for,
// so:
//   1. every link and p-link with an end in the object's subtree goes (they
//      are all line-space descendants of links at its ancestors, so what is
//      left still covers the ancestors, now without the object), and the
//      subdivision this leaves without links;
//   2. the cluster moves under the root (Hierarchy::attachToRoot), and the
//      links at its former ancestors get the form factors and visibility of
//      their smaller clusters;
//   3. the object is linked anew as the root's new child, with every other
//      child of the root and with itself (the line-space children of the
//      root's p-link that it now lacks), and those links are refined to the
//      criterion.
// Only the object's own links and those at its ancestors are touched: the
// rest of the solution stays, and the caller's line-space traversal then
// splits the visibility of the links around the old and new dynamic object.

#include <cstddef>

#include "hierarchy/Hierarchy.h"
#include "links/Link.h"
#include "radiosity/Stats.h"

namespace rad {

class Refiner;

// Attaches the object cluster `cluster` to the root and relinks it; the
// receivers whose irradiance changed are left dirty in the refiner for the
// caller's partial push-pull. A movable cluster (Hierarchy::movableClusters)
// is left as it is.
ReinsertionStats reinsertUnderRoot(Hierarchy& hierarchy, LinkStore& links, Refiner& refiner, ElementId cluster);

}  // namespace rad
