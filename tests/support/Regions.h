#pragma once
// The light of objects and regions of a solved scene, by name, for tests
// that compare rooms (a lit one, a dark one behind a door or partition).

#include <gtest/gtest.h>

#include <string>

#include "radiosity/Engine.h"

namespace rad::test {

// The luminance of the object's area-weighted mean radiosity.
inline double objectLuminance(const Engine& engine, const std::string& name) {
    for (const ObjectRadiosity& o : engine.objectRadiosity())
        if (o.name == name) return rad::luminance(o.radiosity);
    ADD_FAILURE() << "no object " << name;
    return 0.0;
}

// The area-weighted mean luminance of the objects whose names start with `prefix`.
inline double regionLuminance(const Engine& engine, const std::string& prefix) {
    double sum = 0.0, area = 0.0;
    for (const ObjectRadiosity& o : engine.objectRadiosity())
        if (o.name.rfind(prefix, 0) == 0) {
            sum += o.area * rad::luminance(o.radiosity);
            area += o.area;
        }
    return area > 0.0 ? sum / area : 0.0;
}

// The area-weighted mean luminance of the mesh the viewer draws (smoothed
// vertex colours, interpolated over each triangle), over the triangles whose
// centroid `inside` accepts: a region as it is seen, the surfaces a door
// hides from it left out.
template <class Inside>
double drawnLuminance(const Engine& engine, const Inside& inside) {
    const MeshSnapshot m = compactMesh(engine.snapshot());
    double sum = 0.0, area = 0.0;
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        glm::dvec3 q[3];
        double l = 0.0;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = m.indices[t + k];
            q[k] = glm::dvec3(m.positions[i]) + m.origin;
            l += rad::luminance(glm::dvec3(m.colors[i])) / 3.0;
        }
        const double a = 0.5 * glm::length(glm::cross(q[1] - q[0], q[2] - q[0]));
        if (a > 0.0 && inside((q[0] + q[1] + q[2]) / 3.0)) {
            sum += a * l;
            area += a;
        }
    }
    return area > 0.0 ? sum / area : 0.0;
}

// Expects each object whose name starts with `prefix` under `fraction` of
// the luminance of the object `lit` (which must be lit).
inline void expectDarkBeside(const Engine& engine, const std::string& prefix,
                             const std::string& lit, double fraction) {
    const double reference = objectLuminance(engine, lit);
    ASSERT_GT(reference, 0.0) << lit;
    for (const ObjectRadiosity& o : engine.objectRadiosity())
        if (o.name.rfind(prefix, 0) == 0) {
            EXPECT_LT(rad::luminance(o.radiosity), fraction * reference) << o.name;
        }
}

}  // namespace rad::test
