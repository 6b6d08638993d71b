#pragma once
// The viewer's P key: widen the selection to the glTF node above it, so a
// subtree (a lamp made of several meshes under one node, a table and what
// stands on it) moves as one. Pure: it sees only the objects' node paths.
//
//   paths[i]: item i's Object::nodePath or PunctualLight::nodePath (the glTF
//   nodes from a scene root down to its node), or nullopt for an item that
//   cannot join (an object without polygons).
//   widenSelection(paths, {3})       -> every object under object 3's node...
//   widenSelection(paths, that)      -> ...then under its parent, and so on.
//
// The rule: take the deepest common prefix of the selected objects' paths;
// while every object under that prefix is selected already, go one node up
// (so each press selects more, or says there is nothing more); then select
// every object whose path starts with the prefix. The empty prefix stands
// for the whole scene. Selected items without a path stay selected and take
// no part in the prefix.

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

namespace rad::viewer {

using NodePath = std::vector<std::uint32_t>;

struct Widening {
    NodePath prefix;                       // the node whose subtree is now selected; empty: the whole scene
    std::vector<std::uint32_t> selection;  // the new selection, ascending
};

inline bool startsWith(const NodePath& path, const NodePath& prefix) {
    return path.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), path.begin());
}

// Nullopt when nothing selected has a path, or when the selection is every
// object already (nothing wider to go to).
inline std::optional<Widening> widenSelection(const std::vector<std::optional<NodePath>>& paths,
                                              const std::vector<std::uint32_t>& selection) {
    std::vector<std::uint32_t> selected = selection;
    std::sort(selected.begin(), selected.end());
    selected.erase(std::unique(selected.begin(), selected.end()), selected.end());
    std::erase_if(selected, [&](std::uint32_t i) { return i >= paths.size(); });

    // The deepest common prefix of the selected paths.
    std::optional<NodePath> prefix;
    std::vector<std::uint32_t> kept;  // selected, without a path: they stay
    for (std::uint32_t i : selected) {
        if (!paths[i]) {
            kept.push_back(i);
            continue;
        }
        const NodePath& p = *paths[i];
        if (!prefix) {
            prefix = p;
            continue;
        }
        const auto mismatch = std::mismatch(prefix->begin(), prefix->end(), p.begin(), p.end());
        prefix->erase(mismatch.first, prefix->end());
    }
    if (!prefix) return std::nullopt;

    const auto under = [&](const NodePath& node) {
        std::vector<std::uint32_t> out = kept;
        for (std::uint32_t i = 0; i < paths.size(); ++i)
            if (paths[i] && startsWith(*paths[i], node)) out.push_back(i);
        std::sort(out.begin(), out.end());
        return out;
    };
    std::vector<std::uint32_t> widened = under(*prefix);
    while (widened == selected && !prefix->empty()) {
        prefix->pop_back();
        widened = under(*prefix);
    }
    if (widened == selected) return std::nullopt;
    return Widening{std::move(*prefix), std::move(widened)};
}

}  // namespace rad::viewer
