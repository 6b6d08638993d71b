#version 450
// Gouraud shading: the per-vertex radiosity is interpolated across each triangle.
// The push constants are MeshRenderer's DrawPushConstants, shared with gouraud.frag.
layout(push_constant) uniform PushConstants {
    mat4 viewProjection;
    float exposureScale;  // used by the fragment shader
} pc;

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inColor;
layout(location = 0) out vec3 outColor;

void main() {
    gl_Position = pc.viewProjection * vec4(inPosition, 1.0);
    outColor = inColor;
}
