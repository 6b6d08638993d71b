#include "solve/Diagnosis.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "scene/Contacts.h"
#include "scene/Pieces.h"

namespace rad {
namespace {

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string quoted(const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", '" : "'") + names[i] + "'";
    return out;
}

// The objects with the highest radiosity (non-finite first), at most three.
std::vector<std::string> runaways(const Scene& scene, const Hierarchy& h) {
    std::vector<std::pair<double, std::string>> ranked;
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o) {
        const ElementId c = h.objectCluster(o);
        if (c == kNone) continue;
        const glm::dvec3& b = h[c].radiosity;
        ranked.emplace_back(finite(b) ? luminance(b) : INFINITY, scene.objects[o].name);
    }
    std::sort(ranked.begin(), ranked.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<std::string> names;
    for (std::size_t i = 0; i < ranked.size() && i < 3; ++i) names.push_back(ranked[i].second);
    return names;
}

// The material with the highest reflectance and the objects using it.
std::string reflectanceCause(const Scene& scene) {
    double rho = 0.0;
    std::string object;
    for (const Polygon& p : scene.polygons) {
        const glm::dvec3& r = scene.materials[p.material].reflectance;
        const double m = std::max({r.x, r.y, r.z});
        if (m > rho) {
            rho = m;
            object = scene.objects[p.object].name;
        }
    }
    std::ostringstream out;
    if (rho >= 1.0)
        out << "reflectance " << rho << " in '" << object
            << "' absorbs nothing, so light is never used up";
    else if (rho >= 0.95)
        out << "reflectance " << rho << " in '" << object << "' is near 1: light takes about "
            << std::lround(std::log(1e-4) / std::log(rho)) << " bounces to die out";
    return out.str();
}

// The objects that take most of `perObject` (the largest first, at most
// three, each at least a tenth of the whole), as ", N% of it <where> 'name'"
// phrases joined by "and", and the whole.
struct Shares {
    double total = 0.0;
    std::string phrase;
    std::vector<std::string> objects;
};
Shares largestShares(const Scene& scene, const std::vector<double>& perObject, const char* where) {
    Shares out;
    std::vector<std::pair<double, std::uint32_t>> by;
    for (std::uint32_t o = 0; o < perObject.size() && o < scene.objects.size(); ++o)
        if (perObject[o] > 0.0) {
            by.emplace_back(perObject[o], o);
            out.total += perObject[o];
        }
    std::sort(by.begin(), by.end(), std::greater<>());
    std::ostringstream m;
    for (const auto& [power, o] : by) {
        if (out.objects.size() == 3 || power < 0.1 * out.total) break;
        m << (out.objects.empty() ? ", " : " and ") << std::lround(100.0 * power / out.total) << "% of it " << where
          << " '" << scene.objects[o].name << "'";
        out.objects.push_back(scene.objects[o].name);
    }
    out.phrase = m.str();
    return out;
}

}  // namespace

std::string diagnoseFailure(const Scene& scene, const Hierarchy& h, const Solver& solver,
                            const SolveResult& r, const SolveSettings& settings) {
    using Status = SolveResult::Status;
    std::ostringstream m;
    const std::vector<std::string> names = runaways(scene, h);
    switch (r.status) {
        case Status::NonFinite:
            m << "the solution became non-finite (NaN or infinite) after " << r.iterations
              << " sweeps in " << quoted(names);
            break;
        case Status::Diverged:
            m << "the solution diverged after " << r.iterations << " sweeps: the radiosity of "
              << quoted(names) << " grows without bound";
            break;
        case Status::IterationLimit:
            // The remaining error is estimated from how fast the change
            // falls: two sweeps at least.
            if (r.iterations < 2)
                m << "did not converge: after " << r.iterations << " sweep the change was " << r.lastChange
                  << " (tolerance " << settings.tolerance << "), and telling what remains takes two sweeps";
            else
                m << "did not converge: after " << r.iterations << " sweeps the estimated remaining error is "
                  << r.estimatedError << " (tolerance " << settings.tolerance << ")";
            break;
        case Status::Converged:
            return {};
    }
    // The likely cause: form factors summing above 1 (where the guard would
    // have acted), or a reflectance that leaves light too long.
    const std::vector<GuardAction> excess = solver.guardActions(0.01);
    std::string cause;
    if (!excess.empty() && r.status != Status::IterationLimit) {
        const GuardAction worst = *std::max_element(
            excess.begin(), excess.end(),
            [](const GuardAction& a, const GuardAction& b) { return a.largestSum < b.largestSum; });
        std::ostringstream c;
        c << "form factors sum to " << worst.largestSum << " (above 1) at '"
          << scene.objects[worst.object].name << "': it receives more light than any point can see";
        cause = c.str();
    }
    if (cause.empty()) cause = reflectanceCause(scene);
    if (!cause.empty()) m << "; likely cause: " << cause;
    if (r.status == Status::IterationLimit) m << "; raise the iteration limit (--max-iterations)";
    return m.str();
}

std::vector<Warning> guardWarnings(const Scene& scene, const Solver& solver, double threshold) {
    std::vector<Warning> out;
    for (const GuardAction& a : solver.guardActions(threshold)) {
        const std::string& name = scene.objects[a.object].name;
        std::ostringstream m;
        m << "form factors at '" << name << "' sum to up to " << a.largestSum
          << ": the energy guard scaled down the light arriving at " << a.area << " m^2 of it";
        out.push_back({"energy_guard", m.str(), {name}, a.largestSum});
    }
    return out;
}

std::vector<Warning> backFaceWarnings(const Scene& scene, const EnergyBalance& energy, double threshold) {
    // What the objects' backs take (not light that goes into the surface a
    // punctual light sits on).
    const Shares backs = largestShares(scene, energy.backFacesByObject, "at");
    if (!(energy.emitted > 0.0) || !(backs.total > threshold * energy.emitted)) return {};
    const double share = backs.total / energy.emitted;
    std::ostringstream m;
    m << std::lround(100.0 * share) << "% of the emitted light meets the back of one-sided polygons" << backs.phrase
      << ": " << (backs.objects.size() == 1 ? "are its normals" : "are their normals")
      << " flipped? (a doubleSided material lights both sides)";
    return {{"back_faces", m.str(), backs.objects, share}};
}

std::vector<Warning> escapingLightWarnings(const Scene& scene, const EnergyBalance& energy, double threshold) {
    const Shares leaving = largestShares(scene, energy.escapedEmissionByObject, "from");
    if (!(energy.emitted > 0.0) || !(leaving.total > threshold * energy.emitted)) return {};
    const double share = leaving.total / energy.emitted;
    std::ostringstream m;
    m << std::lround(100.0 * share) << "% of the emitted light leaves the scene straight from glowing faces"
      << leaving.phrase << ": does a face look out of the scene (flush with a wall or ceiling, facing away)? It lights nothing";
    return {{"light_leaves", m.str(), leaving.objects, share}};
}

std::vector<Warning> lostLightWarnings(const EnergyBalance& energy, double threshold) {
    if (!(energy.emitted > 0.0) || !(energy.lost > threshold * energy.emitted)) return {};
    const double share = energy.lost / energy.emitted;
    std::ostringstream m;
    m << std::lround(100.0 * share)
      << "% of the emitted light is lost, neither absorbed, escaped nor taken by back faces: is a light "
         "source hidden under another surface, or are the links too coarse (a smaller --epsilon)?";
    return {{"lost_light", m.str(), {}, share}};
}

std::vector<Warning> madeLightWarnings(const EnergyBalance& energy, double threshold) {
    if (!(energy.emitted > 0.0) || !(-energy.lost > threshold * energy.emitted)) return {};
    const double share = -energy.lost / energy.emitted;
    std::ostringstream m;
    m.precision(2);
    m << "the solution made " << 100.0 * share
      << "% of the emitted light (what is absorbed, escapes and meets back faces adds up to more), the fill adding "
      << 100.0 * energy.filled / energy.emitted
      << "% where links left a closed view uncovered: it is about that much too bright";
    return {{"made_light", m.str(), {}, share}};
}

std::vector<Warning> trappedLightWarnings(const Scene& scene) {
    std::vector<std::uint32_t> emitting;
    for (std::uint32_t i = 0; i < scene.polygons.size(); ++i)
        if (luminance(scene.materials[scene.polygons[i].material].emission) > 0.0) emitting.push_back(i);
    if (emitting.empty()) return {};
    std::vector<Aabb> boxes;
    for (const Polygon& p : scene.polygons) boxes.push_back(boxOf(p));
    BoxGrid grid(boxes);
    std::vector<double> power(scene.objects.size(), 0.0), trapped(scene.objects.size(), 0.0);
    std::vector<std::uint32_t> facing(scene.objects.size(), 0);  // the object in front, for the message
    double total = 0.0;
    for (std::uint32_t e : emitting) {
        const Polygon& lamp = scene.polygons[e];
        const double area = lamp.area();
        const double p = area * luminance(scene.materials[lamp.material].emission);
        power[lamp.object] += p;
        total += p;
        const glm::dvec3 n = lamp.normal(), centre = lamp.centroid();
        for (std::uint32_t q : grid.near(reachingAhead(boxes[e], n, kTrappedGapShare * std::sqrt(area)))) {
            const Polygon& other = scene.polygons[q];
            if (other.object == lamp.object) continue;
            const double gap = trappingGap(lamp, other);
            if (gap < 0.0) continue;
            // The lamp's centre, seen across the gap, lies on the other.
            const glm::dvec3 m = other.normal(), x = centre + gap * n;
            bool inside = true;
            for (int k = 0; k < other.vertexCount && inside; ++k)
                inside = glm::dot(glm::cross(other.vertices[(k + 1) % other.vertexCount] - other.vertices[k],
                                             x - other.vertices[k]),
                                  m) >= 0.0;
            if (!inside) continue;
            trapped[lamp.object] += p;
            facing[lamp.object] = other.object;
            break;
        }
    }
    std::vector<Warning> out;
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o) {
        if (!(trapped[o] > 0.5 * power[o])) continue;
        const std::string& lamp = scene.objects[o].name;
        const std::string& other = scene.objects[facing[o]].name;
        std::ostringstream m;
        m << std::lround(100.0 * trapped[o] / power[o]) << "% of the light of '" << lamp << "' leaves it facing '"
          << other << "' close in front of it, which faces back: the light is trapped between them (is the normal of '"
          << lamp << "' flipped?)";
        out.push_back({"trapped_light", m.str(), {lamp, other}, trapped[o] / total});
    }
    return out;
}

std::size_t clearNonFinite(Hierarchy& h) {
    std::size_t cleared = 0;
    const auto clear = [&](glm::dvec3& v) {
        if (finite(v)) return;
        v = glm::dvec3(0.0);
        ++cleared;
    };
    for (ElementId e = 0; e < h.size(); ++e) {
        HElement& el = h[e];
        clear(el.radiosity);
        clear(el.irradiance);
        clear(el.gathered);
        if (el.shape == kNone) continue;
        ClusterShape& shape = h.shape(e);
        for (int k = 0; k < shape.facetCount(); ++k) {
            clear(shape.power[k]);
            clear(shape.gathered[k]);
        }
    }
    return cleared;
}

}  // namespace rad
