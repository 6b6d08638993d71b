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
        if (o.name == name) return luminance(o.radiosity);
    ADD_FAILURE() << "no object " << name;
    return 0.0;
}

// The area-weighted mean luminance of the objects whose names start with `prefix`.
inline double regionLuminance(const Engine& engine, const std::string& prefix) {
    double sum = 0.0, area = 0.0;
    for (const ObjectRadiosity& o : engine.objectRadiosity())
        if (o.name.rfind(prefix, 0) == 0) {
            sum += o.area * luminance(o.radiosity);
            area += o.area;
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
            EXPECT_LT(luminance(o.radiosity), fraction * reference) << o.name;
        }
}

}  // namespace rad::test
