#include "hierarchy/ClusterShape.h"

#include <algorithm>
#include <cmath>

#include "radiosity/Scene.h"

namespace rad {

// The octahedral map: the unit sphere onto the octahedron |x|+|y|+|z| = 1,
// its lower half folded over the upper, then onto the square [-1,1]^2.
namespace {
double signNotZero(double v) { return v < 0.0 ? -1.0 : 1.0; }
}  // namespace

std::uint32_t ClusterShape::Sample::encode(const glm::dvec3& n) {
    const double l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    if (!(l1 > 0.0)) return 0;
    glm::dvec2 o(n.x / l1, n.y / l1);
    if (n.z < 0.0)
        o = glm::dvec2((1.0 - std::abs(o.y)) * signNotZero(o.x), (1.0 - std::abs(o.x)) * signNotZero(o.y));
    const auto fixed = [](double v) {
        return static_cast<std::uint32_t>(static_cast<std::uint16_t>(
            static_cast<std::int16_t>(std::lround(std::clamp(v, -1.0, 1.0) * 32767.0))));
    };
    return fixed(o.x) | (fixed(o.y) << 16);
}

double ClusterShape::projectedArea(const glm::dvec3& dir) const {
    double a = 0.0;
    for (int k = 0; k < facetCount(); ++k)
        a += facets[k].area * std::max(0.0, glm::dot(facets[k].normal, dir));
    return a;
}

void ClusterShape::arrivalWeights(const glm::dvec3& u, std::array<double, kMaxFacets>& w,
                                  std::array<double, kMaxFacets>& c) const {
    double projected = 0.0, exposed = 0.0;
    for (int k = 0; k < facetCount(); ++k) {
        c[k] = std::max(0.0, glm::dot(facets[k].normal, u));
        w[k] = c[k] * facets[k].exposure;
        projected += facets[k].area * c[k];
        exposed += facets[k].area * w[k];
    }
    // Nothing exposed that faces u (or every exposure 0): by orientation alone.
    const double s = exposed > 1e-6 * projected ? projected / exposed : 0.0;
    for (int k = 0; k < facetCount(); ++k) w[k] = s > 0.0 ? s * w[k] : c[k];
}

glm::dvec3 ClusterShape::radiosityToward(std::span<const Facet> facets, const glm::dvec3& dir,
                                         std::span<const glm::dvec3> powers) {
    glm::dvec3 sent(0.0);
    double area = 0.0;
    for (std::size_t k = 0; k < facets.size(); ++k) {
        const double c = std::max(0.0, glm::dot(facets[k].normal, dir));
        if (c <= 0.0 || facets[k].area <= 0.0) continue;
        // A facet's B is its power over its area; weighted by its projected area A c.
        sent += c * powers[k];
        area += c * facets[k].area;
    }
    return area > 0.0 ? sent / area : glm::dvec3(0.0);
}

double ClusterShape::peakLuminance(std::span<const glm::dvec3> powers) const {
    double peak = 0.0;
    for (int k = 0; k < facetCount(); ++k)
        if (facets[k].area > 0.0) peak = std::max(peak, luminance(powers[k]) / facets[k].area);
    return peak;
}

void ClusterShape::keepOwn(const Arrivals& own) {
    ownIrradiance.assign(own.irradiance.begin(), own.irradiance.begin() + facetCount());
    ownFormFactorSum.assign(own.formFactorSum.begin(), own.formFactorSum.begin() + facetCount());
    ownValid = true;
}

void ClusterShape::addOwn(Arrivals& arrivals) const {
    for (int k = 0; k < facetCount(); ++k) {
        arrivals.irradiance[k] += ownIrradiance[k];
        arrivals.formFactorSum[k] += ownFormFactorSum[k];
    }
}

std::size_t ClusterShape::heapBytes() const {
    return facets.capacity() * sizeof(Facet) +
           (power.capacity() + gathered.capacity() + ownIrradiance.capacity()) *
               sizeof(glm::dvec3) +
           ownFormFactorSum.capacity() * sizeof(double) + childFacet.capacity();
}

void buildShape(std::span<const ShapePart> children, ClusterShape& shape) {
    // Facets: equal normals share one; then the closest pairs merge until
    // kMaxFacets remain. `owner` maps every child facet to its facet.
    struct Entry {
        glm::dvec3 vectorArea;  // sum of A n: its direction is the facet's normal
        double area;
    };
    std::vector<Entry> merged;
    std::vector<int> owner;
    for (const ShapePart& part : children)
        for (const ClusterShape::Facet& f : part.facets) {
            int found = -1;
            for (std::size_t k = 0; k < merged.size() && found < 0; ++k) {
                const glm::dvec3 n = glm::normalize(merged[k].vectorArea);
                if (glm::dot(n, f.normal) > 1.0 - 1e-9) found = static_cast<int>(k);
            }
            if (found < 0) {
                merged.push_back({f.normal * f.area, f.area});
                found = static_cast<int>(merged.size() - 1);
            } else {
                merged[found].vectorArea += f.normal * f.area;
                merged[found].area += f.area;
            }
            owner.push_back(found);
        }
    const auto normalOf = [](const Entry& e, const glm::dvec3& fallback) {
        const double len = glm::length(e.vectorArea);
        return len > 1e-12 * e.area && len > 0.0 ? e.vectorArea / len : fallback;
    };
    while (merged.size() > static_cast<std::size_t>(ClusterShape::kMaxFacets)) {
        std::size_t bi = 0, bj = 1;
        double best = -2.0;
        for (std::size_t i = 0; i < merged.size(); ++i)
            for (std::size_t j = i + 1; j < merged.size(); ++j) {
                const double d = glm::dot(normalOf(merged[i], glm::dvec3(0.0)),
                                          normalOf(merged[j], glm::dvec3(0.0)));
                if (d > best) {
                    best = d;
                    bi = i;
                    bj = j;
                }
            }
        merged[bi].vectorArea += merged[bj].vectorArea;
        merged[bi].area += merged[bj].area;
        merged.erase(merged.begin() + static_cast<std::ptrdiff_t>(bj));
        for (int& o : owner) {
            if (o == static_cast<int>(bj))
                o = static_cast<int>(bi);
            else if (o > static_cast<int>(bj))
                --o;
        }
    }
    shape.facets.assign(merged.size(), ClusterShape::Facet{});
    for (std::size_t k = 0; k < merged.size(); ++k) {
        // Opposite normals merged to nothing keep the direction of the first.
        glm::dvec3 fallback(0.0, 1.0, 0.0);
        for (std::size_t i = 0; i < owner.size(); ++i)
            if (owner[i] == static_cast<int>(k)) {
                std::size_t c = 0, seen = 0;
                while (seen + children[c].facets.size() <= i) seen += children[c++].facets.size();
                fallback = children[c].facets[i - seen].normal;
                break;
            }
        shape.facets[k] = {normalOf(merged[k], fallback), merged[k].area, 1.0f, 0};
    }
    shape.childFacet.assign(owner.begin(), owner.end());

    // Sample points: kSamples of the children's, stratified by the area each
    // stands for.
    double total = 0.0;
    for (const ShapePart& part : children) total += part.sampleWeight * double(part.samples.size());
    shape.sampleCount = 0;
    shape.sampleWeight = 0.0f;
    if (!(total > 0.0)) return;
    int k = 0;
    double cumulative = 0.0;
    for (const ShapePart& part : children)
        for (const ClusterShape::Sample& s : part.samples) {
            cumulative += part.sampleWeight;
            while (k < ClusterShape::kSamples &&
                   (k + 0.5) / ClusterShape::kSamples * total <= cumulative) {
                shape.samples[k] = s;
                shape.samples[k++].p = glm::vec3(glm::dvec3(s.p) + part.offset);
            }
        }
    // Rounding may leave the last targets unmet: they repeat the last point.
    for (; k < ClusterShape::kSamples && k > 0; ++k) shape.samples[k] = shape.samples[k - 1];
    shape.sampleCount = ClusterShape::kSamples;
    shape.sampleWeight = static_cast<float>(total / ClusterShape::kSamples);
}

}  // namespace rad
