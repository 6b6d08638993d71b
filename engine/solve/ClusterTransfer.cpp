#include "solve/ClusterTransfer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <tuple>

#include "links/FormFactor.h"

namespace rad {

glm::dvec3 centreDirection(const Hierarchy& h, ElementId from, ElementId to) {
    const glm::dvec3 d = h[to].center - h[from].center;
    const double len = glm::length(d);
    return len > 0.0 ? d / len : glm::dvec3(0.0);
}

glm::dvec3 sentRadiosity(const Hierarchy& h, const Link& link) {
    const HElement& s = h[link.source];
    if (s.isSurface()) return s.gathered;
    const ClusterShape& shape = h.shape(link.source);
    return shape.radiosityToward(centreDirection(h, link.source, link.receiver), shape.gathered);
}

glm::dvec3 sentChange(const Hierarchy& h, const Link& link, const glm::dvec3& surfaceChange,
                      const ClusterShape::Powers& facetChange) {
    if (h[link.source].isSurface()) return surfaceChange;
    return h.shape(link.source)
        .radiosityToward(centreDirection(h, link.source, link.receiver), facetChange);
}

double SourcePoints::totalArea() const {
    double a = 0.0;
    for (int k = 0; k < n; ++k) a += area[k];
    return a;
}

SourcePoints sourcePoints(const Hierarchy& h, ElementId source, const glm::dvec3& toward,
                          int surfaceOrder) {
    SourcePoints out;
    const HElement& s = h[source];
    if (s.isSurface()) {
        for (const SamplePoint& q : patchSamples(s.patch, surfaceOrder)) {
            if (out.n == SourcePoints::kMax) break;
            out.p[out.n] = q.p;
            out.normal[out.n] = s.normal;
            out.polygon[out.n] = s.polygon;
            out.area[out.n++] = q.w * s.area;
        }
        return out;
    }
    // The cluster's points on surfaces facing `toward`, evenly picked from
    // its stratified order; each stands for its share of the facing area.
    const ClusterShape& shape = h.shape(source);
    std::array<int, ClusterShape::kSamples> facing{};
    int count = 0;
    double facingArea = 0.0;
    for (int k = 0; k < shape.sampleCount; ++k)
        if (glm::dot(shape.samples[k].normal, toward - shape.samples[k].p) > 0.0) {
            facing[count++] = k;
            facingArea += shape.samples[k].weight;
        }
    const int n = std::min(count, SourcePoints::kMax);
    for (int i = 0; i < n; ++i) {
        const ClusterShape::Sample& q = shape.samples[facing[i * count / n]];
        out.p[out.n] = q.p;
        out.normal[out.n] = q.normal;
        out.polygon[out.n] = q.polygon;
        out.area[out.n++] = facingArea / n;
    }
    return out;
}

double pointToSource(const SourcePoints& source, const glm::dvec3& x, const glm::dvec3& nx) {
    double f = 0.0;
    for (int k = 0; k < source.n; ++k) {
        const glm::dvec3 d = source.p[k] - x;
        const double r2 = glm::dot(d, d);
        if (!(r2 > 0.0)) continue;
        const double cx = glm::dot(nx, d), cs = -glm::dot(source.normal[k], d);
        if (cx <= 0.0 || cs <= 0.0) continue;  // one-sided at both ends
        f += source.area[k] * cx * cs / (std::numbers::pi * r2 * r2);
    }
    return std::min(f, 1.0);
}

std::size_t ArrivalTable::memoryBytes() const {
    return sizeof(ArrivalTable) + links.capacity() * sizeof(LinkId) +
           formFactors.capacity() * sizeof(float);
}

void buildArrivalTable(const Hierarchy& h, const LinkStore& links, ElementId cluster,
                       ArrivalTable& table) {
    const HElement& c = h[cluster];
    table.links.clear();
    for (LinkId id : c.links)
        if (links[id].unoccluded > 0.0) table.links.push_back(id);
    std::tie(table.firstMember, table.memberCount) = h.memberSpan(cluster);
    const std::size_t n = table.links.size();
    table.formFactors.assign(std::size_t(table.memberCount) * n, 0.0f);
    for (std::size_t l = 0; l < n; ++l) {
        const SourcePoints source = sourcePoints(h, links[table.links[l]].source, c.center);
        for (std::uint32_t m = 0; m < table.memberCount; ++m) {
            const HElement& member = h[h.polygonElement(h.memberPolygon(table.firstMember + m))];
            table.formFactors[m * n + l] =
                static_cast<float>(pointToSource(source, member.center, member.normal));
        }
    }
    table.built = true;
}

std::size_t Arrivals::add(const Hierarchy& h, const LinkStore& links, const ArrivalTable& table) {
    const std::size_t mark = levels_.size();
    levels_.push_back({&table, strength_.size()});
    for (LinkId id : table.links) {
        const Link& l = links[id];
        // The held transfer over the unoccluded one: the visibility as gathered.
        const double visibility = l.unoccluded > 0.0 ? l.gathered / l.unoccluded : 0.0;
        visibility_.push_back(visibility);
        strength_.push_back(visibility * sentRadiosity(h, l));
    }
    return mark;
}

void Arrivals::drop(std::size_t mark) {
    if (mark >= levels_.size()) return;
    strength_.resize(levels_[mark].first);
    visibility_.resize(levels_[mark].first);
    levels_.resize(mark);
}

void Arrivals::resolve(const Hierarchy& h, const HElement& member, glm::dvec3& irradiance,
                       double& formFactorSum) const {
    const std::uint32_t ordinal = h.memberOrdinal(member.polygon);
    for (const Level& level : levels_) {
        const ArrivalTable& t = *level.table;
        const std::size_t n = t.links.size();
        const float* f = t.formFactors.data() + std::size_t(ordinal - t.firstMember) * n;
        for (std::size_t l = 0; l < n; ++l) {
            irradiance += double(f[l]) * strength_[level.first + l];
            formFactorSum += double(f[l]) * visibility_[level.first + l];
        }
    }
}

}  // namespace rad
