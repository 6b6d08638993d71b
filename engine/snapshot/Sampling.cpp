#include "snapshot/Sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>


namespace rad {

RadiositySamples sampleRadiosity(const Scene& scene, const Hierarchy& hierarchy) {
    RadiositySamples out;
    for (std::uint32_t p = 0; p < scene.polygons.size(); ++p) {
        const ElementId top = hierarchy.polygonElement(p);
        const auto& uv = polygonSampleParams(scene.polygons[p].vertexCount);
        const double w = scene.polygons[p].area() / static_cast<double>(uv.size());
        for (const glm::dvec2& s : uv) {
            out.luminance.push_back(top == kNone ? 0.0 : luminance(hierarchy[hierarchy.pathTo(p, s).back()].radiosity));
            out.weight.push_back(w);
        }
    }
    return out;
}

SolutionError compareSamples(const RadiositySamples& solution, const RadiositySamples& reference) {
    if (solution.luminance.size() != reference.luminance.size())
        throw std::invalid_argument("compareSamples: the two solutions are of different scenes");
    double area = 0.0, mean = 0.0, squared = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < reference.luminance.size(); ++i) {
        const double w = reference.weight[i], d = solution.luminance[i] - reference.luminance[i];
        area += w;
        mean += w * reference.luminance[i];
        squared += w * d * d;
        largest = std::max(largest, std::abs(d));
    }
    SolutionError e;
    if (area <= 0.0 || mean <= 0.0) return e;
    mean /= area;
    e.rms = std::sqrt(squared / area) / mean;
    e.max = largest / mean;
    return e;
}

}  // namespace rad
