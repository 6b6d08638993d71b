#include "support/Motion.h"

#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

namespace rad::test {

glm::dmat4 translation(const glm::dvec3& t) { return glm::translate(glm::dmat4(1.0), t); }

glm::dmat4 rotationAbout(const glm::dvec3& centre, const glm::dvec3& axis, double degrees) {
    return translation(centre) * glm::rotate(glm::dmat4(1.0), glm::radians(degrees), axis) * translation(-centre);
}

std::uint32_t objectIndex(const Engine& engine, const std::string& name) {
    const auto o = engine.scene().findObject(name);
    if (!o) throw std::runtime_error("no object " + name);
    return *o;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool allFinite(const RadiositySamples& samples) {
    for (double v : samples.luminance)
        if (!std::isfinite(v)) return false;
    return !samples.luminance.empty();
}

SolutionError compareWithFullSolve(const Engine& engine, const EngineSettings& settings, double* fullSeconds) {
    const auto start = std::chrono::steady_clock::now();
    Engine full(engine.scene(), settings);
    full.solve();
    if (fullSeconds) *fullSeconds = secondsSince(start);
    return compareSamples(engine.samples(), full.samples());
}

RadiositySamples finerSolve(const Scene& scene, EngineSettings settings) {
    settings.epsilon /= 8.0;
    Engine finer(scene, settings);
    if (!finer.solve().converged) throw std::runtime_error("finerSolve: the finer solve did not converge");
    return finer.samples();
}

EngineSettings coarse() {
    EngineSettings settings;
    settings.epsilon = 1e-3;
    return settings;
}

}  // namespace rad::test
