#include "snapshot/Sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>


namespace rad {

RadiositySamples sampleRadiosity(const Scene& scene, const Hierarchy& hierarchy) {
    RadiositySamples out;
    double total = 0.0;
    for (const Polygon& p : scene.polygons) total += p.area();
    const double cell = total / double(kSamplesOverScene);
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const ElementId top = hierarchy.polygonElement(p);
        const double area = scene.polygons[p].area();
        const int n = cell > 0.0 ? std::clamp(int(std::ceil(std::sqrt(area / cell))), kLeastSamplesAcross, kMostSamplesAcross)
                                 : kLeastSamplesAcross;
        const std::vector<glm::dvec2> uv = polygonSampleParams(scene.polygons[p].vertexCount, n);
        const double w = area / static_cast<double>(uv.size());
        for (const glm::dvec2& s : uv) {
            out.luminance.push_back(top == kNone ? 0.0 : luminance(hierarchy[hierarchy.pathTo(p, s).back()].radiosity));
            out.weight.push_back(w);
            out.object.push_back(scene.polygons[p].object);
            out.polygon.push_back(p);
        }
    }
    return out;
}

namespace {

// Sums over a set of samples, in the reference's weights.
struct ErrorSums {
    double area = 0.0;     // sum w
    double weighted = 0.0; // sum w L_ref
    double squared = 0.0;  // sum w d^2
    double largest = 0.0;  // max |d|

    void add(double w, double reference, double d) {
        area += w;
        weighted += w * reference;
        squared += w * d * d;
        largest = std::max(largest, std::abs(d));
    }
    double mean() const { return area > 0.0 ? weighted / area : 0.0; }
    // RMS and largest difference over `scale`. Over a zero scale a
    // difference is infinitely large and no difference is none.
    double rmsOver(double scale) const { return over(area > 0.0 ? std::sqrt(squared / area) : 0.0, scale); }
    double maxOver(double scale) const { return over(largest, scale); }

  private:
    static double over(double value, double scale) {
        if (scale > 0.0) return value / scale;
        return value > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
    }
};

}  // namespace

SolutionError compareSamples(const RadiositySamples& solution, const RadiositySamples& reference) {
    const std::size_t n = reference.luminance.size();
    if (solution.luminance.size() != n || reference.weight.size() != n || solution.weight.size() != n)
        throw std::invalid_argument("compareSamples: the two solutions are of different scenes");
    const bool perObject = !reference.object.empty();
    if (perObject && (reference.object.size() != n || solution.object != reference.object))
        throw std::invalid_argument("compareSamples: the two solutions have different objects per sample");

    ErrorSums scene;
    std::vector<ErrorSums> objects;
    for (std::size_t i = 0; i < n; ++i) {
        const double w = reference.weight[i], d = solution.luminance[i] - reference.luminance[i];
        scene.add(w, reference.luminance[i], d);
        if (!perObject) continue;
        const std::uint32_t o = reference.object[i];
        if (o >= objects.size()) objects.resize(std::size_t(o) + 1);
        objects[o].add(w, reference.luminance[i], d);
    }

    SolutionError e;
    const double mean = scene.mean();
    if (mean <= 0.0) return e;  // a black reference: nothing to normalise by
    e.rms = scene.rmsOver(mean);
    e.max = scene.maxOver(mean);
    for (std::uint32_t o = 0; o < objects.size(); ++o) {
        const ErrorSums& sums = objects[o];
        if (sums.area <= 0.0) continue;  // no samples: an index no sample uses
        ObjectError oe;
        oe.object = o;
        oe.mean = sums.mean();
        oe.rms = sums.rmsOver(oe.mean);
        oe.max = sums.maxOver(oe.mean);
        oe.dark = oe.mean < kDarkObjectShare * mean;
        if (!oe.dark) e.worstObjectRms = std::max(e.worstObjectRms, oe.rms);
        e.objects.push_back(oe);
    }
    return e;
}

}  // namespace rad
