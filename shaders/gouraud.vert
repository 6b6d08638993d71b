#version 450
// Gouraud shading: the per-vertex radiosity is interpolated across each triangle.
// The push constants are MeshRenderer's DrawPushConstants, shared with gouraud.frag.
// The vertex layout is MeshRenderer's MeshVertex (surfaces and overlay lines).
layout(push_constant) uniform PushConstants {
    mat4 viewProjection;
    float exposureScale;  // used by the fragment shader
} pc;

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inColor;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec3 inTexelScale;
layout(location = 4) in int inLayer;  // texture array layer, -1: untextured
layout(location = 0) out vec3 outColor;
layout(location = 1) out vec2 outUv;
layout(location = 2) out vec3 outTexelScale;
// Not interpolated: one texture per triangle (its vertices share the layer).
layout(location = 3) flat out int outLayer;

void main() {
    gl_Position = pc.viewProjection * vec4(inPosition, 1.0);
    outColor = inColor;
    outUv = inUv;
    outTexelScale = inTexelScale;
    outLayer = inLayer;
}
