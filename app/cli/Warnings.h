#pragma once
// What the CLI tells the user besides its results: the warnings of the
// import (duplicate polygons dropped) and of the solve (energy guard, memory
// limit), printed on stderr and listed in the solve report.

#include <vector>

#include "cli/Report.h"
#include "radiosity/Gltf.h"
#include "radiosity/Stats.h"

namespace rad::cli {

// One warning of kind "duplicates" per pair of objects whose polygons
// repeated in place (objects: the one kept, then the one the copies came
// from; amount: how many polygons were dropped).
std::vector<Warning> importWarnings(const ImportNotes& notes);

// "warning: <message>" on stderr, one line per warning; a kind with more
// than three prints only its largest (by amount) and how many more there are.
void printWarnings(const std::vector<Warning>& warnings);

// The report's `warnings`: an array of {kind, message, objects, amount}.
Report warningsReport(const std::vector<Warning>& warnings);

}  // namespace rad::cli
