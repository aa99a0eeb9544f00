// raykit — shadow.glsl: shadow-map lookups' math (Fahlén, "Illumination for Real-Time Rendering of
// Large Architectural Environments", ch. 5): projecting a point into the map (the shadow matrix of
// Eq. 5.1 comes from shadow.hpp), depth biases (constant, slope-scaled, normal offset), the sample
// patterns of percentage-closer filtering (Vogel's spiral, rotated per pixel), the penumbra width of
// PCSS, and cascade selection and blending.
//
// Shared GLSL/C++ source (include/raykit/shadow.hpp is the C++ build, with the shadow matrix, the
// cascade splits and the texel-snapped light fit, and the CPU pattern generators). The texture
// fetches themselves (sampler2DShadow compares) belong to the application's shader; this file gives
// each fetch's coordinates and compare depth.
//
// @rk-es 310
// @rk-es300
#ifndef RK_SHADOW_GLSL
#define RK_SHADOW_GLSL

#include "common.glsl"

// The golden angle, pi (3 - sqrt(5)), in radians.
#define RK_SH_GOLDEN_ANGLE 2.39996322972865332f

/// rk_sh_project: the shadow-map coordinates of point p: (u, v, compare depth) = (S p).xyz / (S p).w
/// for the shadow matrix S of shadow.hpp (bias matrix · light projection · light view, times the
/// inverse camera view when p is in the camera's view space). w is floored at RK_FLT_MIN in
/// magnitude (a point in the light's plane: far outside the map, never NaN). Domain: entries of s
/// and coordinates of p within 1e15 (so S p cannot overflow). Cost: 1 mat4 * vec4, 1 div.
RK_INLINE vec3 rk_sh_project(mat4 s, vec3 p)
{
    vec4 c = s * vec4(p.x, p.y, p.z, 1.0f);
    float w = abs(c.w) >= RK_FLT_MIN ? c.w : RK_FLT_MIN;
    return clamp(vec3(c.x, c.y, c.z) / w, vec3(-RK_FLT_MAX), vec3(RK_FLT_MAX));
}

/// rk_sh_slope_bias: the depth bias for a surface whose normal makes cos(theta) = n_dot_l with the
/// light: constant + slope · tan(theta), at most max_bias (tan grows without bound at grazing light).
/// In the map's depth units (one texel's depth change over a slope of 45 degrees is the usual
/// `slope`). n_dot_l <= 0 (facing away) gives max_bias. Cost: 1 sqrt, 1 div.
RK_INLINE float rk_sh_slope_bias(float n_dot_l, float constant_bias, float slope, float max_bias)
{
    float c = clamp(n_dot_l, 0.0f, 1.0f);
    if (!(c >= RK_FLT_MIN)) return max_bias;  // a denormal N.L is grazing light too
    float t = sqrt(max(1.0f - c * c, 0.0f)) / c;
    return min(constant_bias + slope * t, max_bias);
}

/// rk_sh_normal_offset: the normal-offset lookup position: p moved along the unit surface normal n
/// by `scale` shadow-map texels (texel_world: one texel's width in world units at p) times
/// sin(theta) = sqrt(1 - n_dot_l²): no move where the light is head-on, a full texel-scale move at
/// grazing light, where acne comes from. Cost: 1 sqrt, 4 fma.
RK_INLINE vec3 rk_sh_normal_offset(vec3 p, vec3 n, float n_dot_l, float texel_world, float scale)
{
    float c = clamp(n_dot_l, -1.0f, 1.0f);
    float s = sqrt(max(1.0f - c * c, 0.0f));
    return p + n * (scale * texel_world * s);
}

/// rk_sh_vogel_disk: sample i (0 <= i < n) of Vogel's golden-angle spiral in the unit disk, turned
/// by `phi` radians: radius sqrt((i + 0.5) / n), angle i · golden angle + phi. Every sample is inside
/// the unit disk, equal areas hold equal counts, and any n works without a table; a per-pixel phi
/// (rk_sh_rotation) turns the pattern's banding into noise. Cost: 1 sqrt, 1 sin, 1 cos.
RK_INLINE vec2 rk_sh_vogel_disk(uint i, uint n, float phi)
{
    float r = sqrt((float(i) + 0.5f) / float(max(n, 1u)));
    float a = float(i) * RK_SH_GOLDEN_ANGLE + phi;
    return vec2(r * cos(a), r * sin(a));
}

/// rk_sh_rotation: a per-pixel rotation angle in [0, 2 pi) from integer pixel coordinates
/// (interleaved gradient noise, Jimenez 2014), for rk_sh_vogel_disk or a rotated Poisson disk.
/// Cost: ~6 flops.
RK_INLINE float rk_sh_rotation(uvec2 pixel)
{
    float x = float(pixel.x & 4095u);
    float y = float(pixel.y & 4095u);
    float f = 52.9829189f * fract(0.06711056f * x + 0.00583715f * y);
    return 6.28318530717958648f * fract(f);
}

/// rk_sh_rotate: the 2-D offset o turned by angle phi (for a Poisson pattern rotated per pixel).
/// Cost: 1 sin, 1 cos, 4 flops.
RK_INLINE vec2 rk_sh_rotate(vec2 o, float phi)
{
    float c = cos(phi);
    float s = sin(phi);
    return vec2(c * o.x - s * o.y, s * o.x + c * o.y);
}

/// rk_sh_pcss_penumbra: the penumbra width on the receiver by similar triangles (Fernando 2005):
/// w_penumbra = (d_receiver - d_blocker) · w_light / d_blocker, with distances from the light
/// (d_blocker the average blocker distance of the search, > 0) and w_light the light's width, all
/// in the same units. 0 when the receiver is not behind the blocker. Exact for a planar blocker
/// parallel to the receiver and the light. Cost: 1 div, 2 flops.
RK_INLINE float rk_sh_pcss_penumbra(float d_receiver, float d_blocker, float w_light)
{
    float db = max(d_blocker, RK_FLT_MIN);
    float gap = min(max(d_receiver - d_blocker, 0.0f), RK_FLT_MAX);  // an overflowing difference held finite
    return clamp(gap * max(w_light, 0.0f) / db, 0.0f, RK_FLT_MAX);
}

/// rk_sh_cascade_index: the cascade of a point at view distance `dist` (along the view axis), with
/// cascade i covering [splits[i - 1], splits[i]) (splits from cascade_splits: the far ends of
/// cascades 0..3; unused cascades have their far end at the last used one's). Beyond the last split
/// it returns 4 (no shadow map: treat as lit, or fade). Cost: 4 compares.
RK_INLINE uint rk_sh_cascade_index(float dist, vec4 splits)
{
    uint i = 0u;
    if (dist >= splits.x) i = 1u;
    if (dist >= splits.y) i = 2u;
    if (dist >= splits.z) i = 3u;
    if (dist >= splits.w) i = 4u;
    return i;
}

/// rk_sh_cascade_blend: the weight of the next cascade in a band of width `band` (view units)
/// before the current cascade's far end `split_far`: 0 up to split_far - band, rising linearly to 1
/// at split_far (blend the two lookups as mix(this, next, weight) to hide the seam). band <= 0:
/// no blending (0). Cost: 1 div, 2 flops.
RK_INLINE float rk_sh_cascade_blend(float dist, float split_far, float band)
{
    if (!(band > 0.0f)) return 0.0f;
    float b = min(band, RK_FLT_MAX);  // an infinite band: its limit, 1
    return rk_saturate((dist - (split_far - b)) / b);
}

// ---------------------------------------------------------------------------------------------
// Omnidirectional lights

/// rk_sh_cube_ref_depth: the compare depth of light-relative vector v for a cube shadow map whose
/// six faces are rendered with a 90-degree perspective projection of near n and far f (usual
/// depth; OpenGL's [-1, 1] NDC and Vulkan's [0, 1] store the same window value): the face is v's
/// major axis, its view depth z = max(|v.x|, |v.y|, |v.z|), and the stored depth
/// (1/n - 1/z) / (1/n - 1/f) = f (z - n) / (z (f - n)). Pass it as the reference of a
/// samplerCubeShadow lookup in direction v (compare LEQUAL). Domain: 0 < n < f; z below n gives a
/// negative depth (always lit), beyond f above 1. Max error: 3 ulp (two roundings of a
/// cancellation-free form). Cost: 3 abs, 2 max, 1 div, 3 flops.
RK_INLINE float rk_sh_cube_ref_depth(vec3 v, float n, float f)
{
    float z = max(max(abs(v.x), abs(v.y)), abs(v.z));
    float nn = max(n, RK_FLT_MIN);
    float ff = max(f, nn * 1.0000001f);
    return clamp(ff * (z - nn) / max(z * (ff - nn), RK_FLT_MIN), -RK_FLT_MAX, RK_FLT_MAX);
}

#endif  // RK_SHADOW_GLSL
