#include "solve/Solver.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <map>

namespace rad {

void Solver::gatherAll() {
    for (ElementId id = 0; id < h_.size(); ++id) {
        HElement& e = h_[id];
        e.gathered = e.radiosity;
        if (e.shape != kNone) {
            h_.shape(id).gathered = h_.shape(id).power;
            h_.shape(id).ownValid = false;  // summed from the links when pushed
        }
    }
    const SourceStates states(h_);
    tbb::parallel_for(ElementId(0), static_cast<ElementId>(h_.size()), [&](ElementId id) {
        HElement& e = h_[id];
        LinkSums sums;
        for (std::size_t k = 0; k < e.links.size(); ++k) {
            links_.prefetchAhead(e.links, k);
            Link& link = links_[e.links[k]];
            link.gathered = link.formFactor();
            if (!e.isSurface()) continue;  // a cluster's arrivals are resolved when it is pushed
            sums.add(double(link.gathered) * states.sent(link, e.center), link.gathered, !h_[link.source].isSurface());
        }
        sums.storeIn(e);
        e.stale = false;
    });
    tbb::parallel_for(std::uint32_t(0), static_cast<std::uint32_t>(h_.polygonCount()),
                      [&](std::uint32_t p) {
                          if (h_.polygonElement(p) != kNone)
                              h_.refreshQuadtreeCoverage(h_.polygonElement(p));
                      });
}

double Solver::meanUncovered(const HElement& e) const {
    double area = 0.0, uncovered = 0.0;
    for (ElementId c : e.children) {
        area += h_[c].area;
        uncovered += h_[c].area * (1.0 - std::min(1.0, h_[c].coverage));
    }
    return area > 0.0 ? uncovered / area : 0.0;
}

Solver::Down Solver::shareOf(const Down& down, const HElement& child, double meanUncovered) {
    if (!(meanUncovered > 1e-6)) return down;
    const double w = (1.0 - std::min(1.0, child.coverage)) / meanUncovered;
    return Down{w * down.irradiance, w * down.formFactorSum, w * down.clusterIrradiance, w * down.clusterSum,
                down.direct};
}

Solver::Down Solver::surfaceDown(ElementId id, const Down& down) const {
    const HElement& e = h_[id];
    Down d = down;
    d.irradiance += e.irradiance - e.clusterIrradiance;
    d.formFactorSum += e.formFactorSum - e.clusterSum;
    d.clusterIrradiance += e.clusterIrradiance;
    d.clusterSum += e.clusterSum;
    d.direct += h_.direct(id);
    return d;
}

bool Solver::pastPushDeadline(const HElement& e, bool forced, Walk& walk) {
    // A dirty element waits when its subtree's push, by its area at the
    // last pushes' rate, would end past the stop. Inside a subtree pushed
    // whole, an element with a large subtree of its own, or the
    // kPushClockEvery-th since the clock was read, waits when the stop has
    // passed: the estimate by area is of the scene's mean density, and
    // around a moving object, where the hierarchy is finest, building-floor
    // pushes ran up to 20 ms past it (5 ms with the large subtrees alone).
    // Once the clock has passed, every element after it waits.
    if (!forced && !e.dirty) return false;
    if (walk.late) return true;
    const PushDeadline& deadline = *walk.deadline;
    const double expected = e.area * deadline.secondsPerArea;
    if (forced && expected < kPushClockSeconds && ++walk.sinceClock < kPushClockEvery) return false;
    walk.sinceClock = 0;
    const auto now = deadline.now();
    walk.late = now > deadline.stop;
    if (forced) return walk.late;
    return now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(expected)) >
           deadline.stop;
}

glm::dvec3 Solver::push(ElementId id, const Down& down, const FacetArrivals& facets, bool forced,
                        int depth, Walk& walk) {
    HElement& e = h_[id];
    if (!forced && !e.changed) return e.radiosity;
    if (walk.deadline && pastPushDeadline(e, forced, walk)) {
        // Marked again by the next partial push-pull; meanwhile it is an
        // element like any other (a link update may mark it dirty, and so
        // have its irradiance summed again before that push).
        walk.unpushed->push_back(id);
        e.changed = e.dirty = false;
        return e.radiosity;
    }
    if (walk.visited) walk.visited->push_back(id);
    const bool below = forced || e.dirty;
    glm::dvec3 b(0.0);
    if (!e.isSurface()) {
        ClusterShape& shape = h_.shape(id);
        if (!shape.ownValid) {
            FacetArrivals own{};
            addArrivals(h_, links_, id, own);
            shape.keepOwn(own);
        }
        FacetArrivals arrivals = facets;
        shape.addOwn(arrivals);
        const IdList& children = e.children;
        // What each child inherits from this cluster's facets, in order.
        std::vector<Down> surfaceDown(children.size());
        std::vector<FacetArrivals> clusterDown(children.size());
        ChildArrivals inherit(h_, id, arrivals);
        for (std::size_t i = 0; i < children.size(); ++i) {
            if (h_[children[i]].isSurface())
                inherit.surface(surfaceDown[i].clusterIrradiance, surfaceDown[i].clusterSum);
            else
                clusterDown[i] = inherit.cluster(children[i]);
        }
        double area = 0.0;
        if (depth < kParallelDepth && children.size() > 1) {
            // The clusters near the root split the work between the cores:
            // their subtrees are disjoint. Each child's walk is kept apart and
            // taken in order, as the serial descent would.
            std::vector<glm::dvec3> childB(children.size());
            std::vector<Walk> walks(children.size());
            std::vector<std::vector<ElementId>> visited(children.size()), unpushed(children.size());
            std::vector<std::vector<std::uint32_t>> polygons(walk.polygons ? children.size() : 0);
            tbb::parallel_for(std::size_t(0), children.size(), [&](std::size_t i) {
                walks[i].visited = walk.visited ? &visited[i] : nullptr;
                walks[i].deadline = walk.deadline;
                walks[i].unpushed = walk.unpushed ? &unpushed[i] : nullptr;
                walks[i].polygons = walk.polygons ? &polygons[i] : nullptr;
                walks[i].late = walk.late;
                childB[i] =
                    push(children[i], surfaceDown[i], clusterDown[i], below, depth + 1, walks[i]);
            });
            for (std::size_t i = 0; i < children.size(); ++i) {
                b += h_[children[i]].area * childB[i];
                area += h_[children[i]].area;
                walk.change += walks[i].change;
                walk.total += walks[i].total;
                walk.late = walk.late || walks[i].late;
                if (walk.visited)
                    walk.visited->insert(walk.visited->end(), visited[i].begin(), visited[i].end());
                if (walk.unpushed)
                    walk.unpushed->insert(walk.unpushed->end(), unpushed[i].begin(), unpushed[i].end());
                if (walk.polygons)
                    walk.polygons->insert(walk.polygons->end(), polygons[i].begin(), polygons[i].end());
            }
        } else {
            for (std::size_t i = 0; i < children.size(); ++i) {
                b += h_[children[i]].area *
                     push(children[i], surfaceDown[i], clusterDown[i], below, depth + 1, walk);
                area += h_[children[i]].area;
            }
        }
        if (area > 0.0) b /= area;
        e.radiosity = b;
        h_.pullPower(id);
    } else {
        const Down here = surfaceDown(id, down);
        if (e.isLeaf()) {
            // A polygon's leaves come one after another.
            if (walk.polygons && (walk.polygons->empty() || walk.polygons->back() != e.polygon))
                walk.polygons->push_back(e.polygon);
            b = h_.emission(e) +
                glm::dvec3(e.reflectance) * (arriving(here, e.polygon) + here.direct);
            if (b != e.radiosity) h_.touchMesh(e.polygon);
            walk.change += e.area * std::abs(luminance(b - e.radiosity));
            walk.total += e.area * std::abs(luminance(b));
            e.peak = luminance(b);
        } else {
            // The walk down a quadtree is bound by memory: ask for the
            // children's fields before the first is read.
            for (ElementId c : e.children) {
                const HElement& k = h_[c];
                __builtin_prefetch(&k.children);
                __builtin_prefetch(&k.irradiance);
                __builtin_prefetch(&k.changed);
            }
            const double uncovered = meanUncovered(e);
            double area = 0.0;
            e.peak = 0.0;
            for (ElementId c : e.children) {
                b += h_[c].area * push(c, shareOf(here, h_[c], uncovered), FacetArrivals{}, below,
                                       depth + 1, walk);
                area += h_[c].area;
                e.peak = std::max(e.peak, h_[c].peak);
            }
            if (area > 0.0) b /= area;
        }
        e.radiosity = b;
    }
    e.changed = e.dirty = false;
    return b;
}

double Solver::pushPull() {
    Walk walk;
    push(h_.root(), Down{}, FacetArrivals{}, true, 0, walk);
    if (!std::isfinite(walk.change) || !std::isfinite(walk.total)) return NAN;
    return walk.total > 0.0 ? walk.change / walk.total : 0.0;
}

std::vector<ElementId> Solver::partialPushPull(const std::vector<ElementId>& dirty,
                                               std::optional<PushDeadline> deadline,
                                               std::vector<std::uint32_t>* polygons) {
    // What waited is pushed now, unless it waits again (freed since it
    // began waiting, a removed subdivision: nothing to push).
    std::vector<ElementId> waited;
    waited.swap(unpushed_);
    const auto markPath = [&](ElementId e) {
        for (ElementId a = e; a != kNone && !h_[a].changed; a = h_[a].parent) h_[a].changed = true;
    };
    for (ElementId e : dirty) markPath(e);
    for (ElementId e : waited)
        if (h_.isLive(e)) {
            h_[e].dirty = true;
            markPath(e);
        }
    std::vector<ElementId> visited;
    Walk walk;
    walk.visited = &visited;
    walk.deadline = deadline ? &*deadline : nullptr;
    walk.unpushed = &unpushed_;
    walk.polygons = polygons;
    push(h_.root(), Down{}, FacetArrivals{}, false, 0, walk);
    return visited;
}

glm::dvec3 Solver::radiosityBound() const {
    // With the guard, no leaf receives more than the brightest leaf sends, so
    // in each channel B <= E_max + rho_max B_max: B_max <= E_max / (1 - rho_max).
    glm::dvec3 emission(0.0), rho(0.0);
    for (std::uint32_t p = 0; p < h_.polygonCount(); ++p) {
        const ElementId e = h_.polygonElement(p);
        if (e == kNone) continue;
        emission = glm::max(emission, h_.emission(h_[e]));
        rho = glm::max(rho, glm::dvec3(h_[e].reflectance));
    }
    glm::dvec3 bound(INFINITY);
    for (int c = 0; c < 3; ++c)
        if (guard_ && rho[c] < 1.0) bound[c] = (emission[c] + rho[c] * directBound_[c]) / (1.0 - rho[c]);
    return bound;
}

bool Solver::finiteAndBounded() const {
    // The polygons' means stay under the bound too.
    const glm::dvec3 bound = radiosityBound();
    for (std::uint32_t p = 0; p < h_.polygonCount(); ++p) {
        const ElementId e = h_.polygonElement(p);
        if (e == kNone) continue;
        const glm::dvec3& b = h_[e].radiosity;
        for (int c = 0; c < 3; ++c) {
            if (!std::isfinite(b[c])) return false;
            if (b[c] > bound[c] * (1.0 + 1e-6) + 1e-300) return false;
        }
    }
    return true;
}

void Solver::saveRadiosity(std::vector<glm::dvec3>& into) const {
    into.resize(h_.size());
    for (ElementId id = 0; id < h_.size(); ++id) into[id] = h_[id].radiosity;
}

glm::dvec3 Solver::leafChange(const std::vector<glm::dvec3>& before) const {
    glm::dvec3 change(0.0);
    for (ElementId id = 0; id < h_.size(); ++id) {
        const HElement& e = h_[id];
        if (e.isSurface() && e.isLeaf()) change += e.area * glm::abs(e.radiosity - before[id]);
    }
    return change;
}

void Solver::pullClusterPowers(ElementId id) {
    for (ElementId c : h_[id].children)
        if (!h_[c].isSurface()) pullClusterPowers(c);
    h_.pullPower(id);
}

void Solver::extrapolate(const std::vector<glm::dvec3>& before, const glm::dvec3& factor) {
    const glm::dvec3 bound = radiosityBound();
    for (ElementId id = 0; id < h_.size(); ++id) {
        HElement& e = h_[id];
        e.radiosity = glm::clamp(e.radiosity + factor * (e.radiosity - before[id]), glm::dvec3(0.0), bound);
    }
    h_.touchAllMeshes();
    if (!h_[h_.root()].isSurface()) pullClusterPowers(h_.root());
}

SolveResult Solver::solve(const SolveSettings& settings,
                          const std::function<void(int, double)>& progress) {
    using Status = SolveResult::Status;
    SolveResult result;
    double previous = 0.0;
    int growing = 0;  // consecutive sweeps whose change grew
    // Aitken's extrapolation: the state before the sweep, the last change
    // and its ratio per channel, and the sweeps since the last step.
    std::vector<glm::dvec3> before;
    glm::dvec3 lastChange(0.0), lastRatio(-1.0);
    int sweepsSinceStep = 0;
    double slowest = 0.0;  // the largest ratio an extrapolation used
    for (int it = 1; it <= settings.maxIterations; ++it) {
        if (settings.extrapolate) saveRadiosity(before);
        gatherAll();
        const double delta = pushPull();
        result.iterations = it;
        result.lastChange = delta;
        if (progress) progress(it, delta);
        if (!std::isfinite(delta)) {
            result.status = Status::NonFinite;
            return result;
        }
        if (!finiteAndBounded()) {
            // Rounding aside, radiosity above the bound is light made from nothing.
            result.status = Status::Diverged;
            return result;
        }
        if (delta == 0.0) {
            result.status = Status::Converged;
            result.converged = true;
            result.estimatedError = 0.0;
            return result;
        }
        growing = previous > 0.0 && delta >= previous * (1.0 - 1e-9) ? growing + 1 : 0;
        // The first sweeps after a refinement may rise; a change that does not
        // fall for this long is an iteration that amplifies (a converging one
        // falls geometrically, however slowly).
        if (growing >= kGrowingSweeps) {
            result.status = Status::Diverged;
            return result;
        }
        if (it >= 2 && previous > 0.0) {
            // After an extrapolation the first sweeps fall fast (the faster
            // modes), while what the step left of the slowest one falls at
            // its own ratio: the estimate takes the slower of the two.
            const double r = std::max(delta / previous, slowest);
            if (r < 1.0) {
                result.estimatedError = delta * r / (1.0 - r);
                if (result.estimatedError < settings.tolerance) {
                    result.status = Status::Converged;
                    result.converged = true;
                    return result;
                }
            } else {
                result.estimatedError = INFINITY;
            }
        }
        previous = delta;
        if (!settings.extrapolate) continue;
        const glm::dvec3 change = leafChange(before);
        glm::dvec3 ratio(-1.0), factor(0.0);
        bool steady = ++sweepsSinceStep > kSweepsBeforeExtrapolating;
        for (int c = 0; c < 3; ++c) {
            if (!(change[c] > 0.0)) continue;  // a channel without light
            ratio[c] = lastChange[c] > 0.0 ? change[c] / lastChange[c] : -1.0;
            steady = steady && ratio[c] > 0.0 && ratio[c] < 1.0 &&
                     std::abs(ratio[c] - lastRatio[c]) <= kSteadyRatio * (1.0 - ratio[c]);
            if (ratio[c] > 0.0 && ratio[c] < 1.0) factor[c] = ratio[c] / (1.0 - ratio[c]);
        }
        lastChange = change;
        lastRatio = ratio;
        if (!steady) continue;
        extrapolate(before, factor);
        for (int c = 0; c < 3; ++c) slowest = std::max(slowest, ratio[c]);
        // The next sweeps measure what the step left: no ratio spans it.
        previous = 0.0;
        growing = 0;
        lastChange = glm::dvec3(0.0);
        sweepsSinceStep = 0;
    }
    result.status = Status::IterationLimit;
    return result;
}

void Solver::forEachLeaf(const std::function<void(const HElement&, const Down&)>& f) const {
    const std::function<void(ElementId, const Down&, const FacetArrivals&)> visit =
        [&](ElementId id, const Down& down, const FacetArrivals& facets) {
            const HElement& e = h_[id];
            if (!e.isSurface()) {
                FacetArrivals arrivals = facets;
                addArrivals(h_, links_, id, arrivals);
                ChildArrivals inherit(h_, id, arrivals);
                for (ElementId c : e.children) {
                    if (h_[c].isSurface()) {
                        Down d;
                        inherit.surface(d.clusterIrradiance, d.clusterSum);
                        visit(c, d, FacetArrivals{});
                    } else {
                        visit(c, Down{}, inherit.cluster(c));
                    }
                }
                return;
            }
            const Down here = surfaceDown(id, down);
            if (e.isLeaf()) {
                f(e, here);
                return;
            }
            const double uncovered = meanUncovered(e);
            for (ElementId c : e.children)
                visit(c, shareOf(here, h_[c], uncovered), FacetArrivals{});
        };
    visit(h_.root(), Down{}, FacetArrivals{});
}

EnergyBalance Solver::energy() const {
    EnergyBalance balance;
    forEachLeaf([&](const HElement& e, const Down& d) {
        const glm::dvec3 filled = this->arriving(d, e.polygon);
        balance.filled += e.area * std::max(0.0, luminance(filled - d.totalIrradiance()));
        const glm::dvec3 arriving = filled + d.direct;
        balance.emitted += e.area * luminance(h_.emission(e));
        balance.received += e.area * luminance(arriving);
        balance.absorbed +=
            e.area * luminance((glm::dvec3(1.0) - glm::dvec3(e.reflectance)) * arriving);
        balance.reflected += e.area * luminance(glm::dvec3(e.reflectance) * arriving);
    });
    return balance;
}

std::vector<GuardAction> Solver::guardActions(double threshold) const {
    std::map<std::uint32_t, GuardAction> byObject;
    forEachLeaf([&](const HElement& e, const Down& d) {
        const double sum = d.totalSum();
        if (!(sum > 1.0 + threshold)) return;
        GuardAction& a = byObject[e.object];
        a.object = e.object;
        a.area += e.area;
        a.largestSum = std::max(a.largestSum, sum);
    });
    std::vector<GuardAction> out;
    for (const auto& [object, action] : byObject) out.push_back(action);
    return out;
}

}  // namespace rad
