// Which closed meshes' back faces face no light (scene/ClosedBackFaces.h).

#include <gtest/gtest.h>

#include <vector>

#include "scene/ClosedBackFaces.h"

namespace rad {
namespace {

using Tri = std::array<glm::dvec3, 3>;
using V = glm::dvec3;

// The twelve triangles of a box, counter-clockwise seen from the side they
// face: outside (`out`) or inside (a room).
std::vector<Tri> box(const V& lo, const V& hi, bool out) {
    const auto corner = [&](int k) {
        return V(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
    };
    const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    std::vector<Tri> tris;
    for (const auto& f : faces)
        for (const auto& t : {Tri{corner(f[0]), corner(f[1]), corner(f[2])},
                              Tri{corner(f[0]), corner(f[2]), corner(f[3])}})
            tris.push_back(out ? t : Tri{t[0], t[2], t[1]});
    return tris;
}

bool unlit(const std::vector<Tri>& tris, std::vector<V> lights) {
    return backFacesFaceNoLight(tris, lights);
}

TEST(ClosedBackFaces, ABoxFacingOutHidesItsBacksUnlessALightIsInside) {
    const auto b = box(V(0.0), V(1.0), true);
    EXPECT_TRUE(unlit(b, {V(5.0, 0.5, 0.5)}));
    EXPECT_TRUE(unlit(b, {V(0.5, 0.5, 1.2)}));  // above it, within its box's reach
    EXPECT_FALSE(unlit(b, {V(5.0, 0.5, 0.5), V(0.5, 0.4, 0.6)}));
    // On a face: counted as behind it.
    EXPECT_FALSE(unlit(b, {V(0.5, 0.5, 1.0)}));
}

TEST(ClosedBackFaces, ARoomFacingInHidesItsBacksUnlessALightIsOutside) {
    const auto room = box(V(0.0), V(4.0, 3.0, 5.0), false);
    EXPECT_TRUE(unlit(room, {V(2.0, 2.9, 2.5)}));
    EXPECT_FALSE(unlit(room, {V(2.0, 2.9, 2.5), V(2.0, 2.9, 7.0)}));
    EXPECT_FALSE(unlit(room, {V(2.0, 3.0, 2.5)}));  // a downlight in the ceiling's plane
}

TEST(ClosedBackFaces, OnlyClosedConsistentSurfacesCount) {
    auto open = box(V(0.0), V(1.0), true);
    open.pop_back();
    open.pop_back();  // no top
    EXPECT_FALSE(unlit(open, {V(5.0)}));
    auto flipped = box(V(0.0), V(1.0), true);
    std::swap(flipped[3][1], flipped[3][2]);  // one triangle turned the other way
    EXPECT_FALSE(unlit(flipped, {V(5.0)}));
    // A sheet closed on itself (a quad and its back): no inside.
    const std::vector<Tri> sheet = {
        Tri{V(0, 0, 0), V(1, 0, 0), V(1, 1, 0)}, Tri{V(0, 0, 0), V(1, 1, 0), V(0, 1, 0)},
        Tri{V(0, 0, 0), V(1, 1, 0), V(1, 0, 0)}, Tri{V(0, 0, 0), V(0, 1, 0), V(1, 1, 0)}};
    EXPECT_FALSE(unlit(sheet, {V(5.0)}));
    EXPECT_FALSE(unlit({}, {V(5.0)}));
}

TEST(ClosedBackFaces, EachClosedPartIsJudgedOnItsOwn) {
    // A table: a top and a leg, apart, both facing out.
    auto table = box(V(0.0, 0.0, 0.7), V(1.0, 1.0, 0.74), true);
    for (const Tri& t : box(V(0.0), V(0.05, 0.05, 0.69), true)) table.push_back(t);
    EXPECT_TRUE(unlit(table, {V(0.5, 0.5, 2.5)}));
    EXPECT_FALSE(unlit(table, {V(0.5, 0.5, 2.5), V(0.02, 0.02, 0.3)}));  // a light in the leg
}

// Each light point in a part's box costs a pass over its triangles: past
// the cap, the backs are kept (the answer is false), whatever the rest says.
TEST(ClosedBackFaces, PastItsWorkCapItKeepsTheBacks) {
    const auto room = box(V(0.0), V(4.0, 3.0, 5.0), false);
    const std::vector<V> lights = {V(1.0, 2.9, 1.0), V(3.0, 2.9, 1.0), V(1.0, 2.9, 4.0), V(3.0, 2.9, 4.0)};
    EXPECT_TRUE(backFacesFaceNoLight(room, lights, 4 * 12));
    EXPECT_FALSE(backFacesFaceNoLight(room, lights, 4 * 12 - 1));
}

TEST(ClosedBackFaces, FarFromTheOrigin) {
    const V o(1.0e5, -2.0e5, 3.0e4);
    const auto b = box(o, o + V(0.01), true);
    EXPECT_TRUE(unlit(b, {o + V(0.005, 0.005, 0.02)}));
    EXPECT_FALSE(unlit(b, {o + V(0.005)}));
}

}  // namespace
}  // namespace rad
