// The viewer's P key (app/viewer/SelectionWidening.h): the selection widened
// to the glTF node its objects share, then to that node's parent, up to the
// whole scene.
#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include "viewer/SelectionWidening.h"

namespace rad::viewer {
namespace {

using Ids = std::vector<std::uint32_t>;

// Node tree (glTF node indices):
//   0 room            5 floor (mesh)      8 sofa (mesh)
//   |- 1 lamp                             |- 9 cushion (mesh)
//   |  |- 2 base (mesh)
//   |  `- 3 shade (mesh)
//   `- 4 table (mesh)
// Objects: 0 base, 1 shade, 2 table, 3 floor, 4 sofa, 5 cushion, 6 a light
// (no path), 7 an object without polygons under the lamp (no path either).
std::vector<std::optional<NodePath>> scene() {
    return {NodePath{0, 1, 2}, NodePath{0, 1, 3}, NodePath{0, 4}, NodePath{5}, NodePath{8}, NodePath{8, 9},
            std::nullopt, std::nullopt};
}

TEST(SelectionWidening, EachPressGoesOneNodeUpToTheWholeScene) {
    const auto paths = scene();
    // The base alone is everything under its own node: up to the lamp.
    auto w = widenSelection(paths, {0});
    ASSERT_TRUE(w);
    EXPECT_EQ(w->prefix, (NodePath{0, 1}));
    EXPECT_EQ(w->selection, (Ids{0, 1}));
    // The lamp's whole subtree: up to the room.
    w = widenSelection(paths, w->selection);
    ASSERT_TRUE(w);
    EXPECT_EQ(w->prefix, (NodePath{0}));
    EXPECT_EQ(w->selection, (Ids{0, 1, 2}));
    // The room: up past the roots, the whole scene (lights and objects
    // without polygons never join).
    w = widenSelection(paths, w->selection);
    ASSERT_TRUE(w);
    EXPECT_TRUE(w->prefix.empty());
    EXPECT_EQ(w->selection, (Ids{0, 1, 2, 3, 4, 5}));
    EXPECT_FALSE(widenSelection(paths, w->selection)) << "nothing wider than everything";
}

TEST(SelectionWidening, ObjectsInTwoBranchesTakeTheirCommonNode) {
    const auto paths = scene();
    // Shade and table meet at the room: the room's subtree, not just the two.
    const auto w = widenSelection(paths, {2, 1});
    ASSERT_TRUE(w);
    EXPECT_EQ(w->prefix, (NodePath{0}));
    EXPECT_EQ(w->selection, (Ids{0, 1, 2}));
    // Objects under different roots share no node: the whole scene.
    const auto roots = widenSelection(paths, {3, 4});
    ASSERT_TRUE(roots);
    EXPECT_TRUE(roots->prefix.empty());
    EXPECT_EQ(roots->selection, (Ids{0, 1, 2, 3, 4, 5}));
}

TEST(SelectionWidening, AnObjectWithChildrenTakesThemFirst) {
    const auto paths = scene();
    // The sofa's node carries the cushion below it: its own subtree first.
    const auto w = widenSelection(paths, {4});
    ASSERT_TRUE(w);
    EXPECT_EQ(w->prefix, (NodePath{8}));
    EXPECT_EQ(w->selection, (Ids{4, 5}));
    // The cushion alone: its node holds nothing else, so up to the sofa's.
    const auto up = widenSelection(paths, {5});
    ASSERT_TRUE(up);
    EXPECT_EQ(up->prefix, (NodePath{8}));
    EXPECT_EQ(up->selection, (Ids{4, 5}));
}

TEST(SelectionWidening, LightsStaySelectedAndTakeNoPart) {
    const auto paths = scene();
    const auto w = widenSelection(paths, {6, 0});
    ASSERT_TRUE(w);
    EXPECT_EQ(w->prefix, (NodePath{0, 1}));
    EXPECT_EQ(w->selection, (Ids{0, 1, 6}));
    EXPECT_FALSE(widenSelection(paths, {6})) << "a light alone has no node to widen to";
    EXPECT_FALSE(widenSelection(paths, {})) << "nothing selected";
}

TEST(SelectionWidening, RepeatsAndUnknownIdsAreIgnored) {
    const auto paths = scene();
    const auto w = widenSelection(paths, {1, 1, 99});
    ASSERT_TRUE(w);
    EXPECT_EQ(w->prefix, (NodePath{0, 1}));
    EXPECT_EQ(w->selection, (Ids{0, 1}));
    // Objects without a path at all (a scene built in code) sit under the
    // empty prefix: widening one selects every one of them.
    const std::vector<std::optional<NodePath>> flat = {NodePath{}, NodePath{}, NodePath{}};
    const auto all = widenSelection(flat, {1});
    ASSERT_TRUE(all);
    EXPECT_EQ(all->selection, (Ids{0, 1, 2}));
}

}  // namespace
}  // namespace rad::viewer
