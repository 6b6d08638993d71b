#pragma once
// What the programs tell the user besides their results: the warnings of the
// import (duplicate polygons dropped) and of the solve (energy guard, memory
// limit). The CLI prints them on stderr and lists them in the solve report
// (cli/Report.h), the viewer in its panel.

#include <string>
#include <vector>

#include "radiosity/Gltf.h"
#include "radiosity/Stats.h"

namespace rad::cli {

// One warning of kind "duplicates" per pair of objects whose polygons
// repeated in place (objects: the one kept, then the one the copies came
// from; amount: how many polygons were dropped).
std::vector<Warning> importWarnings(const ImportNotes& notes);

// One warning of kind "moved_cut_object" per object in `moved` (names of
// objects or lights) not marked dynamic that the import cut where it passes
// into or lies under static objects (Object::cutArea, the amount): moved,
// it shows those holes, and the objects it was sunk into keep theirs.
std::vector<Warning> movedCutObjects(const Scene& scene, const std::vector<std::string>& moved);

// "note: <line>" on stderr for what the import ignored, skipped or dropped
// (ImportNotes::lines: an animation, a LINES primitive, a normal texture,
// degenerate triangles), the first ten and then how many more.
void printImportNotes(const ImportNotes& notes);

// "warning: <message>" on stderr, one line per warning; a kind with more
// than three prints only its largest (by amount) and how many more there are.
void printWarnings(const std::vector<Warning>& warnings);

// Why a solve did not converge, to follow "... did not converge: ": its
// message without the engine's own "did not converge: " (the iteration
// limit's), or "no reason given".
std::string whyNotConverged(const SolveStats& stats);

}  // namespace rad::cli
