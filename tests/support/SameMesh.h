#pragma once
// What the snapshot tests share: a frame's mesh against one made from
// scratch.

#include <gtest/gtest.h>

#include "radiosity/Snapshot.h"

namespace rad::test {

// `kept` (a frame's mesh, with the room its slots keep to grow in) is the
// mesh `fresh` made from scratch, vertex for vertex, once that room is
// dropped (compactMesh). `after`: what happened before, for the message.
inline void expectSameMesh(const MeshSnapshot& kept, const MeshSnapshot& fresh, const char* after) {
    const MeshSnapshot compact = compactMesh(kept);
    ASSERT_EQ(compactMesh(fresh).positions.size(), fresh.positions.size()) << "a mesh from scratch has no room to grow";
    ASSERT_EQ(compact.positions, fresh.positions) << after;
    ASSERT_EQ(compact.normals, fresh.normals) << after;
    ASSERT_EQ(compact.colors, fresh.colors) << after;
    ASSERT_EQ(compact.indices, fresh.indices) << after;
    ASSERT_EQ(compact.uvs, fresh.uvs) << after;
    ASSERT_EQ(compact.textureLayer, fresh.textureLayer) << after;
    ASSERT_EQ(compact.texelScale, fresh.texelScale) << after;
}

}  // namespace rad::test
