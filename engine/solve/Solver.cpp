#include "solve/Solver.h"

#include <cmath>

#include <tbb/parallel_for.h>

#include "refine/Refiner.h"

namespace rad {

void Solver::gatherAll() {
    for (ElementId id = 0; id < h_.size(); ++id) h_[id].gathered = h_[id].radiosity;
    tbb::parallel_for(ElementId(0), static_cast<ElementId>(h_.size()), [&](ElementId id) {
        HElement& e = h_[id];
        glm::dvec3 irradiance(0.0);
        for (LinkId l : e.links) {
            Link& link = links_[l];
            link.gathered = link.formFactor();
            irradiance += link.gathered * h_[link.source].gathered;
        }
        e.irradiance = irradiance;
    });
}

glm::dvec3 Solver::pushPull(ElementId id, const glm::dvec3& down, double& change, double& total) {
    HElement& e = h_[id];
    const glm::dvec3 arriving = down + e.irradiance;
    glm::dvec3 b(0.0);
    if (e.isLeaf()) {
        b = e.isSurface() ? e.emission + e.reflectance * arriving : glm::dvec3(0.0);
        change += e.area * std::abs(luminance(b - e.radiosity));
        total += e.area * std::abs(luminance(b));
    } else {
        double area = 0.0;
        for (ElementId c : e.children) {
            const glm::dvec3 cb = pushPull(c, arriving, change, total);
            b += h_[c].area * cb;
            area += h_[c].area;
        }
        if (area > 0.0) b /= area;
    }
    h_[id].radiosity = b;
    h_[id].changed = h_[id].dirty = false;
    return b;
}

double Solver::pushPull() {
    double change = 0.0, total = 0.0;
    pushPull(h_.root(), glm::dvec3(0.0), change, total);
    return total > 0.0 ? change / total : 0.0;
}

std::vector<ElementId> Solver::partialPushPull(const std::vector<ElementId>& dirty) {
    for (ElementId e : dirty)
        for (ElementId a = e; a != kNone && !h_[a].changed; a = h_[a].parent) h_[a].changed = true;
    std::vector<ElementId> visited;
    partialPushPull(h_.root(), glm::dvec3(0.0), false, 0, visited);
    return visited;
}

glm::dvec3 Solver::partialPushPull(ElementId id, const glm::dvec3& down, bool forced, int depth,
                                   std::vector<ElementId>& visited) {
    HElement& e = h_[id];
    if (!forced && !e.changed) return e.radiosity;
    visited.push_back(id);
    const glm::dvec3 arriving = down + e.irradiance;
    glm::dvec3 b(0.0);
    if (e.isLeaf()) {
        if (e.isSurface()) b = e.emission + e.reflectance * arriving;
    } else {
        const bool below = forced || e.dirty;
        const std::vector<ElementId>& children = e.children;
        // The clusters near the root split the work between the cores: their
        // subtrees are disjoint. Each child's visits and mean are gathered
        // apart and then taken in order, as the serial descent would.
        double area = 0.0;
        if (!e.isSurface() && depth < kParallelDepth && children.size() > 1) {
            std::vector<glm::dvec3> childB(children.size());
            std::vector<std::vector<ElementId>> childVisited(children.size());
            tbb::parallel_for(std::size_t(0), children.size(), [&](std::size_t i) {
                childB[i] = partialPushPull(children[i], arriving, below, depth + 1, childVisited[i]);
            });
            for (std::size_t i = 0; i < children.size(); ++i) {
                b += h_[children[i]].area * childB[i];
                area += h_[children[i]].area;
                visited.insert(visited.end(), childVisited[i].begin(), childVisited[i].end());
            }
        } else {
            // The walk is bound by memory: ask for the children's fields before the first is read.
            for (ElementId c : children) {
                const HElement& k = h_[c];
                __builtin_prefetch(&k.children);
                __builtin_prefetch(&k.area);
                __builtin_prefetch(&k.irradiance);
                __builtin_prefetch(&k.changed);
            }
            for (ElementId c : children) {
                b += h_[c].area * partialPushPull(c, arriving, below, depth + 1, visited);
                area += h_[c].area;
            }
        }
        if (area > 0.0) b /= area;
    }
    e.radiosity = b;
    e.changed = e.dirty = false;
    return b;
}

SolveResult Solver::solve(const SolveSettings& settings, const std::function<void(int, double)>& progress) {
    SolveResult result;
    double previous = 0.0;
    for (int it = 1; it <= settings.maxIterations; ++it) {
        gatherAll();
        const double delta = pushPull();
        result.iterations = it;
        result.lastChange = delta;
        if (progress) progress(it, delta);
        if (delta == 0.0) {
            result.converged = true;
            result.estimatedError = 0.0;
            return result;
        }
        if (it >= 2 && previous > 0.0) {
            const double r = delta / previous;
            if (r < 1.0) {
                result.estimatedError = delta * r / (1.0 - r);
                if (result.estimatedError < settings.tolerance) {
                    result.converged = true;
                    return result;
                }
            } else {
                result.estimatedError = INFINITY;
            }
        }
        previous = delta;
    }
    return result;
}

EnergyBalance Solver::energy() const {
    EnergyBalance balance;
    // Walk down accumulating irradiance; only leaves absorb and reflect.
    struct Item {
        ElementId id;
        glm::dvec3 down;
    };
    std::vector<Item> stack{{h_.root(), glm::dvec3(0.0)}};
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        const HElement& e = h_[item.id];
        const glm::dvec3 arriving = item.down + e.irradiance;
        if (e.isLeaf()) {
            if (!e.isSurface()) continue;
            balance.emitted += e.area * luminance(e.emission);
            balance.received += e.area * luminance(arriving);
            balance.absorbed += e.area * luminance((glm::dvec3(1.0) - e.reflectance) * arriving);
            balance.reflected += e.area * luminance(e.reflectance * arriving);
        } else {
            for (ElementId c : e.children) stack.push_back({c, arriving});
        }
    }
    balance.escaped = balance.emitted - balance.absorbed;
    return balance;
}

}  // namespace rad
