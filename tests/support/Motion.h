#pragma once
// What the update tests share: rigid motions, object lookup, timing.

#include <chrono>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "radiosity/Engine.h"

namespace rad::test {

glm::dmat4 translation(const glm::dvec3& t);
// A rotation by `degrees` about the axis through `centre`.
glm::dmat4 rotationAbout(const glm::dvec3& centre, const glm::dvec3& axis, double degrees);
// The index of the named object; throws std::runtime_error when there is none.
std::uint32_t objectIndex(const Engine& engine, const std::string& name);
double secondsSince(std::chrono::steady_clock::time_point start);
// Every sample finite, and some samples.
bool allFinite(const RadiositySamples& samples);
// The engine's solution against a from-scratch solve of its current scene at
// `settings`; the solve's time in *fullSeconds if given.
SolutionError compareWithFullSolve(const Engine& engine, const EngineSettings& settings,
                                   double* fullSeconds = nullptr);
// The samples of a from-scratch solve of `scene` at `settings` with an
// eighth of their epsilon. A state reached by another path (moves away and
// back, frames on a deadline) can be meshed differently from the one it is
// compared with; it is as good when it is no further from this finer solve.
RadiositySamples finerSolve(const Scene& scene, EngineSettings settings);
// The default settings at epsilon 1e-3: fast enough for many solves.
EngineSettings coarse();

}  // namespace rad::test
