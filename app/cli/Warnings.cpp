#include "cli/Warnings.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>
#include <string>

namespace rad::cli {

std::vector<Warning> importWarnings(const ImportNotes& notes) {
    std::vector<Warning> out;
    for (const DuplicatePolygons& d : notes.duplicates) {
        const std::string count = std::to_string(d.count) + (d.count == 1 ? " polygon" : " polygons");
        const std::string message =
            d.kept == d.dropped
                ? count + " of '" + d.kept + "' repeated in place within the object: dropped at import"
                : count + " of '" + d.dropped + "' repeated polygons of '" + d.kept +
                      "' in place (the same geometry twice): dropped at import";
        out.push_back({"duplicates", message, {d.kept, d.dropped}, static_cast<double>(d.count)});
    }
    for (const ClampedReflectance& c : notes.clampedReflectance) {
        char message[256];
        std::snprintf(message, sizeof message,
                      "material '%s' has a base colour of %g: its reflectance is clamped to %g (no surface "
                      "reflects all its light)",
                      c.material.c_str(), c.largest, kMaxReflectance);
        out.push_back({"reflectance_clamped", message, {}, c.largest});
    }
    return out;
}

std::vector<Warning> movedCutObjects(const Scene& scene, const std::vector<std::string>& moved) {
    std::vector<Warning> out;
    for (const std::string& name : moved) {
        const std::optional<std::uint32_t> o = scene.findObject(name);
        if (!o || scene.objects[*o].dynamic || !(scene.objects[*o].cutArea > 0.0)) continue;
        if (std::any_of(out.begin(), out.end(), [&](const Warning& w) { return w.objects.front() == name; })) continue;
        char area[32];
        std::snprintf(area, sizeof area, "%.3g", scene.objects[*o].cutArea);
        out.push_back({"moved_cut_object",
                       "'" + name + "' is not marked dynamic and the import left " + area +
                           " m^2 of it out where it passes into or lies under other objects: moved, it shows "
                           "those holes, and what it was sunk into keeps its own (mark it extras.dynamic to "
                           "import both whole)",
                       {name},
                       scene.objects[*o].cutArea});
    }
    return out;
}

void printImportNotes(const ImportNotes& notes) {
    constexpr std::size_t kShown = 10;
    for (std::size_t i = 0; i < notes.lines.size() && i < kShown; ++i)
        std::fprintf(stderr, "note: %s\n", notes.lines[i].c_str());
    if (notes.lines.size() > kShown)
        std::fprintf(stderr, "note: %zu more import notes (the solve report lists them all)\n", notes.lines.size() - kShown);
}

void printWarnings(const std::vector<Warning>& warnings) {
    // A kind that fires at many objects (the energy guard in a furnished
    // scene) prints its largest case and a count; the report lists them all.
    constexpr std::size_t kPerKind = 3;
    std::map<std::string, std::vector<const Warning*>> byKind;
    for (const Warning& w : warnings) byKind[w.kind].push_back(&w);
    for (const Warning& w : warnings) {
        const std::vector<const Warning*>& same = byKind[w.kind];
        if (same.size() <= kPerKind) {
            std::fprintf(stderr, "warning: %s\n", w.message.c_str());
            continue;
        }
        const Warning* largest = *std::max_element(same.begin(), same.end(), [](const Warning* a, const Warning* b) {
            return a->amount < b->amount;
        });
        if (&w != largest) continue;
        std::fprintf(stderr, "warning: %s (and %zu more '%s' warnings, listed in the report's warnings)\n",
                     w.message.c_str(), same.size() - 1, w.kind.c_str());
    }
}

std::string whyNotConverged(const SolveStats& stats) {
    const std::string said = "did not converge: ";
    const std::string why = stats.message.rfind(said, 0) == 0 ? stats.message.substr(said.size()) : stats.message;
    return why.empty() ? "no reason given" : why;
}

}  // namespace rad::cli
