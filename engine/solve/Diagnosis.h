#pragma once
// What to tell the user when a solve goes wrong, or when a safeguard had to
// act: the objects concerned and the most likely cause, in one line.

#include <string>
#include <vector>

#include "hierarchy/Hierarchy.h"
#include "radiosity/Scene.h"
#include "radiosity/Stats.h"
#include "solve/Solver.h"

namespace rad {

// One line for a solve that stopped without converging: what happened, the
// objects whose radiosity ran away (or the brightest), and the likely cause.
std::string diagnoseFailure(const Scene& scene, const Hierarchy& hierarchy, const Solver& solver,
                            const SolveResult& result, const SolveSettings& settings);

// Warnings for the objects where the energy guard scaled the light down by
// more than `threshold` (form factors summing above 1 + threshold).
std::vector<Warning> guardWarnings(const Scene& scene, const Solver& solver, double threshold);

// A warning when more than `threshold` of the emitted light meets the backs
// of one-sided polygons (EnergyBalance::backFaces), naming the objects that
// take most of it: a room whose normals point out stays dark and the solve
// converges. None otherwise.
std::vector<Warning> backFaceWarnings(const Scene& scene, const EnergyBalance& energy, double threshold);

// A warning when more than `threshold` of the emitted light leaves the
// scene straight from glowing faces (EnergyBalance::escapedEmissionByObject),
// naming the objects it leaves from: a lamp box flush with a ceiling glows
// out of the room through its top. None otherwise.
std::vector<Warning> escapingLightWarnings(const Scene& scene, const EnergyBalance& energy, double threshold);

// A warning when more than `threshold` of the emitted light is lost
// (EnergyBalance::lost: neither absorbed, escaped nor taken by back faces):
// a light source hidden under another surface, or links that miss much of
// what a point sees. The solve converges all the same. None otherwise.
std::vector<Warning> lostLightWarnings(const EnergyBalance& energy, double threshold);

// A warning when the solution made more than `threshold` of the emitted
// light (EnergyBalance::lost below -threshold: what is absorbed, escapes
// and meets back faces adds up to more than was emitted): it is too bright
// by about that much. The fill makes it where it raises, over the view
// that links leave uncovered, light brighter than what lies there (a
// random room lit by a small bright panel: 1.1%, none with the fill off).
// None otherwise.
std::vector<Warning> madeLightWarnings(const EnergyBalance& energy, double threshold);

// A warning for each emitting object more than half of whose power leaves
// polygons that trap it (scene/Contacts.h, trappingGap: another object's
// surface close in front, facing back, as a lamp panel 1 cm under the
// ceiling with its normal flipped). None otherwise.
std::vector<Warning> trappedLightWarnings(const Scene& scene);

// Sets every non-finite radiosity and irradiance to zero, so that no NaN
// reaches a report, an image or an export. Returns how many were.
std::size_t clearNonFinite(Hierarchy& hierarchy);

}  // namespace rad
