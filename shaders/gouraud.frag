#version 450
// Linear radiosity times the exposure (2^EV, a push constant, so changing it
// re-uploads nothing). Scaled after interpolation, as a CPU scaling of the
// rendered image would be, so the two agree to the bit.
//
// A textured surface (layer >= 0) shows its detail: the interpolated colour
// times the texel's linear RGB (the array is *_SRGB: sampling decodes) times
// texelScale (MeshSnapshot: colour * texel * texelScale).
//
// ENCODE_SRGB (a specialization constant) is set for 8-bit UNORM targets,
// which show the values as written; float targets and *_SRGB formats (whose
// hardware encodes on store) take linear values.
layout(constant_id = 0) const bool ENCODE_SRGB = false;

layout(push_constant) uniform PushConstants {
    mat4 viewProjection;  // used by the vertex shader
    float exposureScale;
} pc;

// GpuTextures: one layer per texture, bilinear, repeated.
layout(set = 0, binding = 0) uniform sampler2DArray textures;

layout(location = 0) in vec3 inColor;
layout(location = 1) in vec2 inUv;
layout(location = 2) in vec3 inTexelScale;
layout(location = 3) flat in int inLayer;
layout(location = 0) out vec4 outColor;

// The sRGB curve, as image/Image.cpp's encodeSrgb (without its rounding to 8 bits).
vec3 encodeSrgb(vec3 linear) {
    vec3 c = clamp(linear, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
    vec3 c = inColor;
    // Level 0 explicitly: the image has no mipmaps, and texture() would take
    // derivatives inside a branch that neighbouring triangles may not take.
    if (inLayer >= 0) c *= textureLod(textures, vec3(inUv, float(inLayer)), 0.0).rgb * inTexelScale;
    vec3 color = c * pc.exposureScale;
    outColor = vec4(ENCODE_SRGB ? encodeSrgb(color) : color, 1.0);
}
