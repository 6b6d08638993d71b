#include "lights/LightLinks.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "geometry/Shaft.h"
#include "links/FormFactor.h"
#include "update/OracleSteps.h"

namespace rad {

void LightLinks::sizeTables() {
    links_.resize(scene_.lights.size());
    pending_.resize(scene_.lights.size());
    anchors_.resize(scene_.lights.size());
}

double LightLinks::judgedIntensity(std::uint32_t light) const {
    const double now = luminance(scene_.lights[light].intensity);
    const Anchor& a = anchors_[light];
    if (!(a.intensity > 0.0) || !(now > 0.0) || a.level != 0) return now;
    // At the anchor's level: the anchor's share, exactly its intensity under its threshold.
    return threshold_ == a.threshold ? a.intensity : a.intensity * (threshold_ / a.threshold);
}

int LightLinks::shareLevel(std::uint32_t light) const {
    const double now = luminance(scene_.lights[light].intensity);
    const Anchor& a = anchors_[light];
    if (!(a.intensity > 0.0) || !(now > 0.0) || !(threshold_ > 0.0)) return a.level;
    const double steps = std::log((now / threshold_) / (a.intensity / a.threshold)) / std::log(OracleSteps::kStep);
    return std::abs(steps - a.level) > OracleSteps::kHysteresis ? static_cast<int>(std::lround(steps)) : a.level;
}

std::vector<std::uint32_t> LightLinks::stepShares() {
    sizeTables();
    std::vector<std::uint32_t> stepped;
    for (std::uint32_t l = 0; l < scene_.lights.size(); ++l) {
        Anchor& a = anchors_[l];
        if (!(a.intensity > 0.0)) {
            // Dark when linked: its first positive intensity is its anchor
            // (refreshIntensity links it at that intensity).
            const double now = luminance(scene_.lights[l].intensity);
            if (now > 0.0) a = Anchor{now, threshold_, 0};
            continue;
        }
        const int level = shareLevel(l);
        if (level == a.level) continue;
        a.level = level;
        stepped.push_back(l);
    }
    return stepped;
}

const std::vector<LightLinks::LightLink>& LightLinks::linksOf(std::size_t light, std::uint32_t polygon) const {
    static const std::vector<LightLink> none;
    if (light >= links_.size()) return none;
    const auto it = links_[light].find(polygon);
    return it == links_[light].end() ? none : it->second;
}

bool LightLinks::facesLight(const PunctualLight& light, std::uint32_t polygon) const {
    const Polygon& p = scene_.polygons[polygon];
    return glm::dot(p.normal(), light.position - p.vertices[0]) > 0.0;
}

LightLinks::Estimate LightLinks::estimate(const PunctualLight& light, ElementId receiver) const {
    const HElement& e = h_[receiver];
    const PatchGeometry patch = h_.patch(receiver);
    const SampleSet points = patchSamples(patch, kOrder);
    // Per point: cos(theta) falloff / r^2, unoccluded; the distance kept off
    // zero for a light that sits on the surface (its cosine is zero there).
    const double floor2 = 1e-6 * e.area;
    const PunctualLight::Cone falloff = light.cone();
    const auto unoccluded = [&](const glm::dvec3& p) {
        const glm::dvec3 d = light.position - p;
        const double r2 = std::max(glm::dot(d, d), floor2);
        const glm::dvec3 toward = d / std::sqrt(r2);
        const double cosTheta = glm::dot(h_.normal(e), toward);
        return cosTheta > 0.0 ? falloff(-toward) * cosTheta / r2 : 0.0;
    };
    std::array<RayCaster::Segment, RayCaster::kMaxSegments> segments;
    // Bit k: the k-th of the first n segments meets something, in either layer.
    const auto blocked = [&](std::size_t n) -> std::uint16_t {
        if (n == 0) return 0;
        const std::span<const RayCaster::Segment> span(segments.data(), n);
        return rays_.blocked(Layer::Static, span) | rays_.blocked(Layer::Dynamic, span);
    };
    std::array<double, kMaxOrder * kMaxOrder> g{};
    std::array<std::size_t, RayCaster::kMaxSegments> of{};
    std::size_t rays = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        g[i] = unoccluded(points[i].p);
        if (g[i] > 0.0 && rays < segments.size()) {
            segments[rays] = {points[i].p, light.position, e.polygon, RayCaster::kNoPolygon};
            of[rays++] = i;
        }
    }
    const std::uint16_t shadowed = blocked(rays);
    for (std::size_t k = 0; k < rays; ++k)
        if (shadowed & (1u << k)) g[of[k]] = 0.0;
    Estimate out;
    // Every point in shadow: a lit band between them would be missed, and
    // its light with it, the element left unlinked and never refined (a
    // random room's floor between a floating box's shadow and a table's:
    // 2.3% of a spot's light). The element's corners, edge midpoints and
    // centre are looked at too; where one of them sees the light, the
    // element is refined as for the light it would get there.
    if (rays > 0 && shadowed == (1u << rays) - 1u) {
        std::array<double, RayCaster::kMaxSegments> probeG{};
        std::size_t probes = 0;
        const auto probe = [&](const glm::dvec3& at) {
            const glm::dvec3 p = glm::mix(at, e.center, 0.02);  // just inside the element
            const double v = unoccluded(p);
            if (!(v > 0.0) || probes >= segments.size()) return;
            probeG[probes] = v;
            segments[probes++] = {p, light.position, e.polygon, RayCaster::kNoPolygon};
        };
        const int n = patch.n;
        for (int k = 0; k < n; ++k) {
            probe(patch.v[k]);
            probe(0.5 * (patch.v[k] + patch.v[(k + 1) % n]));
        }
        probe(e.center);
        const std::uint16_t probeShadowed = blocked(probes);
        for (std::size_t k = 0; k < probes; ++k)
            if (!(probeShadowed & (1u << k))) out.spread = std::max(out.spread, probeG[k]);
    }
    double lo = INFINITY, weight = 0.0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        out.mean += points[i].w * g[i];
        weight += points[i].w;
        lo = std::min(lo, g[i]);
        out.peak = std::max(out.peak, g[i]);
    }
    if (weight > 0.0) out.mean /= weight;
    out.spread = std::max(out.spread, points.size() > 0 ? out.peak - lo : 0.0);
    return out;
}

void LightLinks::link(std::uint32_t lightIndex, const std::vector<std::uint32_t>& polygons,
                      std::optional<Clock::time_point> deadline, const Around* around) {
    const PunctualLight& light = scene_.lights[lightIndex];
    const double intensity = judgedIntensity(lightIndex);
    struct Item {
        std::uint32_t polygon;
        ElementId element;
        bool mayKeep;  // its links may stay where its shaft misses the boxes
    };
    // The links of the polygons that may keep theirs, as they were; an
    // element whose shaft misses every box, and which holds one of them or
    // lies above one (`reached`: the last linking came down to it, and so
    // would this one), keeps those below it (kept). One with none there may
    // lie below an element linked whole then and divided now: it is
    // estimated again.
    std::unordered_map<std::uint32_t, std::vector<LightLink>> old;
    std::unordered_set<ElementId> reached;
    std::vector<ElementId> kept;
    std::vector<Item> frontier;
    for (std::uint32_t p : polygons) {
        bool mayKeep = around && !around->whole[p] && !pending_[lightIndex].contains(p);
        if (mayKeep) {
            std::vector<LightLink> was;
            if (const auto it = links_[lightIndex].find(p); it != links_[lightIndex].end()) was = it->second;
            mayKeep = std::all_of(was.begin(), was.end(), [&](const LightLink& l) { return h_.isLive(l.receiver); });
            if (mayKeep) {
                // Each receiver and its ancestors in the polygon, each once.
                for (const LightLink& l : was)
                    for (ElementId a = l.receiver; reached.insert(a).second && a != h_.polygonElement(p);)
                        a = h_[a].parent;
                old.emplace(p, std::move(was));
            }
        }
        links_[lightIndex].erase(p);
        pending_[lightIndex].erase(p);
        if (!(intensity > 0.0) || h_.polygonElement(p) == kNone || !facesLight(light, p)) continue;
        const Polygon& poly = scene_.polygons[p];
        Aabb box;
        for (int k = 0; k < poly.vertexCount; ++k) box.extend(poly.vertices[k]);
        const glm::dvec3 nearest = glm::clamp(light.position, box.lo, box.hi);
        const double d2 = glm::dot(nearest - light.position, nearest - light.position);
        if (d2 > 0.0 && intensity * poly.area() / d2 < kNegligible * threshold_) continue;
        frontier.push_back({p, h_.polygonElement(p), mayKeep});
    }
    const Aabb at{light.position, light.position};
    const auto missesBoxes = [&](ElementId e) {
        for (const Aabb& b : around->boxes)
            if (!b.empty() && Shaft::hullMeets(at, h_.box(e), b) && Shaft(at, h_.box(e)).intersects(b)) return false;
        return true;
    };
    std::vector<Estimate> estimates;
    std::vector<std::uint8_t> keeps;
    while (!frontier.empty()) {
        estimates.assign(frontier.size(), Estimate{});
        keeps.assign(frontier.size(), 0);
        tbb::parallel_for(std::size_t(0), frontier.size(), [&](std::size_t i) {
            if (frontier[i].mayKeep && reached.contains(frontier[i].element) && missesBoxes(frontier[i].element))
                keeps[i] = 1;
            else
                estimates[i] = estimate(light, frontier[i].element);
        });
        std::vector<Item> next;
        // Past the deadline, this level is the last: what it would refine
        // is linked as it is and waits.
        const bool late = deadline && Clock::now() > *deadline;
        for (std::size_t i = 0; i < frontier.size(); ++i) {
            const auto [polygon, e, mayKeep] = frontier[i];
            if (keeps[i]) {
                kept.push_back(e);
                continue;
            }
            const Estimate& est = estimates[i];
            bool refine = intensity * est.spread * h_[e].area > threshold_ && h_.canSubdivide(e);
            if (refine && late) {
                pending_[lightIndex].insert(polygon);
                refine = false;
            }
            if (refine) {
                h_.subdivide(e);
                for (ElementId c : h_[e].children) next.push_back({polygon, c, mayKeep});
            } else if (est.mean > 0.0) {
                links_[lightIndex][polygon].push_back(
                    {e, static_cast<float>(est.mean), static_cast<float>(est.peak)});
            }
        }
        frontier = std::move(next);
    }
    // The links kept: those of a polygon that lie below (or on) a kept element.
    keptLast_ += kept.size();
    if (kept.empty()) return;
    std::sort(kept.begin(), kept.end());
    for (const auto& [p, was] : old)
        for (const LightLink& l : was)
            for (ElementId a = l.receiver; a != kNone; a = h_[a].parent) {
                if (std::binary_search(kept.begin(), kept.end(), a)) {
                    links_[lightIndex][p].push_back(l);
                    break;
                }
                if (a == h_.polygonElement(p)) break;
            }
}

double LightLinks::sumDirect(std::uint32_t polygon) {
    const ElementId top = h_.polygonElement(polygon);
    if (top == kNone) return 0.0;
    std::vector<std::pair<ElementId, glm::dvec3>> before;
    for (std::vector<ElementId> stack{top}; !stack.empty();) {
        const ElementId e = stack.back();
        stack.pop_back();
        before.emplace_back(e, h_.direct(e));
        h_.clearDirect(e);
        for (ElementId c : h_[e].children) stack.push_back(c);
    }
    for (std::size_t l = 0; l < links_.size(); ++l)
        for (const LightLink& link : linksOf(l, polygon))
            h_.addDirect(link.receiver, scene_.lights[l].intensity * double(link.irradiance));
    double squares = 0.0;
    for (const auto& [e, was] : before) {
        const double moved = luminance(h_[e].reflectance) * luminance(h_.direct(e) - was);
        squares += moved * moved * h_[e].area;
    }
    return squares;
}

void LightLinks::linkAll() {
    sizeTables();
    for (std::uint32_t l = 0; l < scene_.lights.size(); ++l)
        anchors_[l] = Anchor{luminance(scene_.lights[l].intensity), threshold_, 0};
    std::vector<std::uint32_t> all(scene_.polygons.size());
    for (std::uint32_t p = 0; p < all.size(); ++p) all[p] = p;
    for (std::uint32_t l = 0; l < scene_.lights.size(); ++l) link(l, all, std::nullopt);
    for (std::uint32_t p : all) sumDirect(p);
}

std::vector<ElementId> LightLinks::relink(const std::vector<std::uint32_t>& polygons,
                                          std::optional<std::uint32_t> light,
                                          std::optional<Clock::time_point> deadline) {
    return relink(polygons, light, deadline, nullptr);
}

std::vector<ElementId> LightLinks::relinkAround(const std::vector<std::uint32_t>& moved, const std::vector<Aabb>& boxes,
                                                std::optional<Clock::time_point> deadline) {
    std::vector<std::uint8_t> whole(scene_.polygons.size(), 0);
    for (std::uint32_t p : moved) whole[p] = 1;
    std::vector<std::uint32_t> polygons = moved;
    for (std::uint32_t p : shadedBy(boxes)) polygons.push_back(p);
    std::sort(polygons.begin(), polygons.end());
    polygons.erase(std::unique(polygons.begin(), polygons.end()), polygons.end());
    const Around around{boxes, whole};
    keptLast_ = 0;
    return relink(polygons, std::nullopt, deadline, &around);
}

std::vector<ElementId> LightLinks::relink(const std::vector<std::uint32_t>& polygons, std::optional<std::uint32_t> light,
                                          std::optional<Clock::time_point> deadline, const Around* around) {
    sizeTables();
    std::vector<ElementId> changed;
    if (scene_.lights.empty()) return changed;
    // What each polygon held before, to tell which changed.
    std::vector<std::vector<std::vector<LightLink>>> before(links_.size());
    for (std::size_t l = 0; l < links_.size(); ++l)
        for (std::uint32_t p : polygons) before[l].push_back(linksOf(l, p));
    for (std::uint32_t l = 0; l < scene_.lights.size(); ++l)
        if (!light || *light == l) link(l, polygons, deadline, around);
    // Around a move, as sets: links kept below an element come after those
    // made anew (a receiver has one link per light, so its direct light is
    // the same sum).
    const auto sorted = [](std::vector<LightLink> v) {
        std::sort(v.begin(), v.end(), [](const LightLink& a, const LightLink& b) { return a.receiver < b.receiver; });
        return v;
    };
    const auto sameLinks = [&](const std::vector<LightLink>& a, const std::vector<LightLink>& b) {
        return a == b || (around && a.size() == b.size() && sorted(a) == sorted(b));
    };
    for (std::size_t i = 0; i < polygons.size(); ++i) {
        bool same = true;
        for (std::size_t l = 0; l < links_.size(); ++l) same = same && sameLinks(before[l][i], linksOf(l, polygons[i]));
        if (same) continue;
        changes_.emplace_back(h_.polygonElement(polygons[i]), sumDirect(polygons[i]));
        changed.push_back(h_.polygonElement(polygons[i]));
    }
    return changed;
}

std::vector<ElementId> LightLinks::relinkLight(std::uint32_t light, std::optional<Clock::time_point> deadline) {
    std::vector<std::uint32_t> all(scene_.polygons.size());
    for (std::uint32_t p = 0; p < all.size(); ++p) all[p] = p;
    return relink(all, light, deadline);
}

std::vector<ElementId> LightLinks::refinePending(std::optional<Clock::time_point> deadline) {
    sizeTables();
    // A few polygons at a time, each refined in full: an idle frame always
    // makes progress, however short its deadline.
    constexpr std::size_t kChunk = 16;
    std::vector<ElementId> changed;
    bool first = true;
    for (std::uint32_t l = 0; l < pending_.size(); ++l) {
        while (!pending_[l].empty()) {
            if (!first && deadline && Clock::now() > *deadline) return changed;
            first = false;
            std::vector<std::uint32_t> chunk;
            for (auto it = pending_[l].begin(); it != pending_[l].end() && chunk.size() < kChunk; ++it)
                chunk.push_back(*it);
            for (ElementId e : relink(chunk, l)) changed.push_back(e);
        }
    }
    return changed;
}

std::size_t LightLinks::pendingCount() const {
    std::size_t n = 0;
    for (const auto& polygons : pending_) n += polygons.size();
    return n;
}

std::vector<ElementId> LightLinks::refreshIntensity(std::uint32_t light) {
    sizeTables();
    std::vector<std::uint32_t> lit;
    for (const auto& [p, links] : links_[light])
        if (!links.empty()) lit.push_back(p);
    std::sort(lit.begin(), lit.end());
    std::vector<ElementId> changed;
    for (std::uint32_t p : lit) {
        changes_.emplace_back(h_.polygonElement(p), sumDirect(p));
        changed.push_back(h_.polygonElement(p));
    }
    // A light that was dark has no links yet: it is linked now.
    if (changed.empty() && luminance(scene_.lights[light].intensity) > 0.0) return relinkLight(light);
    return changed;
}

std::vector<std::uint32_t> LightLinks::shadedBy(const std::vector<Aabb>& boxes) const {
    std::vector<std::uint8_t> hit(scene_.polygons.size(), 0);
    tbb::parallel_for(std::uint32_t(0), static_cast<std::uint32_t>(scene_.polygons.size()), [&](std::uint32_t p) {
        const Polygon& poly = scene_.polygons[p];
        Aabb box;
        for (int k = 0; k < poly.vertexCount; ++k) box.extend(poly.vertices[k]);
        for (const PunctualLight& light : scene_.lights) {
            if (!facesLight(light, p)) continue;
            const Aabb at{light.position, light.position};
            for (const Aabb& b : boxes) {
                if (b.empty() || !Shaft::hullMeets(at, box, b)) continue;
                if (Shaft(at, box).intersects(b)) {
                    hit[p] = 1;
                    return;
                }
            }
        }
    });
    std::vector<std::uint32_t> out;
    for (std::uint32_t p = 0; p < hit.size(); ++p)
        if (hit[p]) out.push_back(p);
    return out;
}

glm::dvec3 LightLinks::directBound() const {
    glm::dvec3 bound(0.0);
    for (std::size_t l = 0; l < links_.size(); ++l) {
        double peak = 0.0;
        for (const auto& [p, links] : links_[l])
            for (const LightLink& link : links) peak = std::max(peak, double(link.peak));
        bound += scene_.lights[l].intensity * peak;
    }
    return bound;
}

std::size_t LightLinks::linkCount() const {
    std::size_t n = 0;
    for (const auto& perLight : links_)
        for (const auto& [p, links] : perLight) n += links.size();
    return n;
}

std::size_t LightLinks::memoryBytes() const {
    std::size_t bytes = 0;
    for (const auto& perLight : links_) {
        bytes += perLight.bucket_count() * sizeof(void*);
        for (const auto& [p, links] : perLight)
            bytes += sizeof(std::pair<const std::uint32_t, std::vector<LightLink>>) + 2 * sizeof(void*) +
                     links.capacity() * sizeof(LightLink);
    }
    return bytes;
}

}  // namespace rad
