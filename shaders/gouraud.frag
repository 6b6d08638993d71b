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

// GpuTextures: one layer per texture, bilinear; the sampler repeats, and
// the texture's own wrap modes (MeshVertex::layer's bits 16-17 for u,
// 18-19 for v: 0 repeat, 1 clamp to edge, 2 mirrored repeat) are applied here.
layout(set = 0, binding = 0) uniform sampler2DArray textures;

// One coordinate wrapped as the texture says, `size` texels wide. Clamped
// and mirrored coordinates stay half a texel inside the edges, where the
// repeating sampler's bilinear filter does not reach across.
float wrapCoordinate(float t, int mode, float size) {
    if (mode == 0) return t;
    if (mode == 2) t = 1.0 - abs(mod(t, 2.0) - 1.0);
    return clamp(t, 0.5 / size, 1.0 - 0.5 / size);
}

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
    if (inLayer >= 0) {
        vec2 size = vec2(textureSize(textures, 0).xy);
        vec2 uv = vec2(wrapCoordinate(inUv.x, (inLayer >> 16) & 3, size.x),
                             wrapCoordinate(inUv.y, (inLayer >> 18) & 3, size.y));
        c *= textureLod(textures, vec3(uv, float(inLayer & 0xFFFF)), 0.0).rgb * inTexelScale;
    }
    vec3 color = c * pc.exposureScale;
    outColor = vec4(ENCODE_SRGB ? encodeSrgb(color) : color, 1.0);
}
