// raykit — lightshafts.glsl: screen-space light shafts (van Dongen, "Interior Mapping: A new
// technique for rendering realistic buildings", §4.5, after Mitchell, "Volumetric Light Scattering
// as a Post-Process", GPU Gems 3 ch. 13): an occlusion buffer holds the light's bright disk where
// the sky is seen and black where geometry is; each pixel accumulates samples of it along the
// screen-space line towards the light's screen position, with a geometric decay; the sum is added
// to the image. It is not physically correct (no depth, no light behind the viewer), but it is
// cheap and convincing; rk_ls_fade removes it smoothly where it would be wrong.
//
// Shared GLSL/C++ source (include/raykit/lightshafts.hpp is the C++ build, with LsMapCpu, the CPU
// twin of the texture read). The occlusion buffer is read through rk_ls_read(map, uv): in GLSL
// textureLod(sampler2D, uv, 0).rgb (LINEAR filtering, CLAMP_TO_EDGE, as the half-resolution buffer
// usually is), in C++ the bilinear twin of that.
//
// Features (compile time):
//   RK_LS_MAX_SAMPLES (default 128, a plain integer in 1..1024): the loop bound of
//   rk_ls_accumulate (its n is clamped to it).
//
// @rk-variants RK_LS_MAX_SAMPLES=128 | RK_LS_MAX_SAMPLES=32
// @rk-es 310
#ifndef RK_LIGHTSHAFTS_GLSL
#define RK_LIGHTSHAFTS_GLSL

#ifdef __cplusplus
#define RK_NS_LIGHTSHAFTS RK_PP_CAT(lightshafts_samples, RK_LS_MAX_SAMPLES)
#endif

#include "common.glsl"

#ifndef RK_LS_MAX_SAMPLES
#define RK_LS_MAX_SAMPLES 128
#endif
#if RK_LS_MAX_SAMPLES < 1 || RK_LS_MAX_SAMPLES > 1024
#error "RK_LS_MAX_SAMPLES must be in 1..1024"
#endif
RK_OPTION_CHECK(rk_option_ls_max_samples, RK_LS_MAX_SAMPLES);

#ifndef __cplusplus
#ifdef GL_ES
precision highp sampler2D;
#endif
#define RK_LS_MAP sampler2D
/// rk_ls_read: the occlusion buffer's colour at uv (level 0; the sampler's filter applies).
RK_INLINE vec3 rk_ls_read(sampler2D m, vec2 uv)
{
    vec4 t = textureLod(m, uv, 0.0f);
    return vec3(t.x, t.y, t.z);
}
#endif

/// rk_ls_light_uv: the light's screen position (texture coordinates, 0.5 + 0.5 NDC) from its
/// clip-space position c (P V times (position, 1) for a point light, P V times (direction to the
/// light, 0) for a directional one). Behind the camera (c.w <= 0) the projection mirrors; the
/// result is then the mirrored point, which rk_ls_fade zeroes. Clamped to [-1e6, 1e6]. Cost: 1 div.
RK_INLINE vec2 rk_ls_light_uv(vec4 c)
{
    float w = abs(c.w) > RK_FLT_MIN ? c.w : RK_FLT_MIN;
    // The quotient first: 0.5 c.x underflows for |c.x| near RK_FLT_MIN (flushed to 0 on some drivers).
    // rk_div: |w| may exceed 2^126, where a driver dividing by a reciprocal (NVIDIA) returns 0.
    return vec2(clamp(0.5f + 0.5f * rk_div(c.x, w), -1.0e6f, 1.0e6f), clamp(0.5f + 0.5f * rk_div(c.y, w), -1.0e6f, 1.0e6f));
}

/// rk_ls_fade: the strength factor of the effect for a light at clip position c: 0 when the light
/// is behind the camera (c.w <= 0, where screen-space shafts would point the wrong way), 1 while its
/// screen position is inside the view, falling smoothly to 0 as it moves `margin` (in uv units,
/// e.g. 0.3) beyond the screen's edge (shafts from an off-screen light are cut by the screen's
/// edge: fading hides the cut). Also scaled by a smoothstep of c.w / |c| from 0 to 0.1, so that the
/// light does not pop when it crosses the camera plane. Cost: ~20 flops, 4 div, 1 sqrt.
RK_INLINE float rk_ls_fade(vec4 c, float margin)
{
    if (!(c.w > 0.0f)) return 0.0f;
    vec2 uv = rk_ls_light_uv(c);
    float m = max(margin, 1.0e-6f);
    float dx = max(max(-uv.x, uv.x - 1.0f), 0.0f);
    float dy = max(max(-uv.y, uv.y - 1.0f), 0.0f);
    float out_d = sqrt(dx * dx + dy * dy);
    float edge = 1.0f - smoothstep(0.0f, m, out_d);
    // c.w / |c| with c scaled by its largest component first, so neither the squares overflow nor
    // tiny components underflow (to zero on drivers that flush denormals): dot(s, s) is in [1, 4].
    float mc = max(max(abs(c.x), abs(c.y)), max(abs(c.z), abs(c.w)));
    vec4 sc = rk_div4(c, max(mc, RK_FLT_MIN));  // rk_div4: mc may exceed 2^126
    float facing = smoothstep(0.0f, 0.1f, sc.w / sqrt(max(dot(sc, sc), 1.0f)));
    return edge * facing;
}

/// rk_ls_disk: the light's disk in the occlusion buffer: 1 at the light's screen position, falling
/// smoothly to 0 at `radius` (uv units, measured with the aspect ratio `aspect` = width / height
/// applied to x so the disk is round), for sky pixels; geometry pixels write 0. Cost: ~8 flops.
RK_INLINE float rk_ls_disk(vec2 uv, vec2 light_uv, float radius, float aspect)
{
    float dx = (uv.x - light_uv.x) * aspect;
    float dy = uv.y - light_uv.y;
    float r = max(radius, RK_FLT_MIN);
    return 1.0f - smoothstep(0.0f, r, sqrt(min(dx * dx + dy * dy, RK_FLT_MAX)));
}

RK_CONFIGURED_BEGIN(RK_NS_LIGHTSHAFTS)

/// rk_ls_accumulate: the shafts at pixel uv (Mitchell's post-process): n samples (1..RK_LS_MAX_SAMPLES)
/// at uv - i · delta, i = 1..n, with delta = (uv - light_uv) · density / n (density in (0, 1]: the
/// fraction of the way to the light covered), each weighted by weight · decay^(i-1):
/// exposure · sum. Samples leave the buffer only past the light when density > 1; they read the
/// clamped edge. The result is added to the lit image (times the light's colour when the buffer
/// holds 1 for the disk). Parameters: weight > 0 sets the gain per sample, decay in (0, 1] how
/// fast far samples lose influence (1: none), exposure the final scale; nothing is normalised, so
/// the sum grows with n · weight (Mitchell's own constants: n = 100, density 0.84, weight 5.65,
/// decay 1.0, exposure 0.0034 for a bright buffer). NaN or negative parameters read as 0.
/// Cost: n buffer reads, ~6 flops each.
RK_INLINE vec3 rk_ls_accumulate(RK_LS_MAP occ, vec2 uv, vec2 light_uv, uint n, float density, float weight, float decay,
                                float exposure)
{
    uint nn = clamp(n, 1u, uint(RK_LS_MAX_SAMPLES));
    float dens = density > 0.0f ? min(density, 4.0f) : 0.0f;
    float w = weight > 0.0f ? min(weight, RK_FLT_MAX) : 0.0f;
    float dec = decay > 0.0f ? min(decay, 1.0f) : 0.0f;
    float ex = exposure > 0.0f ? min(exposure, RK_FLT_MAX) : 0.0f;
    vec2 lu = vec2(clamp(light_uv.x, -1.0e6f, 1.0e6f), clamp(light_uv.y, -1.0e6f, 1.0e6f));
    vec2 delta = vec2((uv.x - lu.x) * dens / float(nn), (uv.y - lu.y) * dens / float(nn));
    vec2 coord = uv;
    float fall = 1.0f;
    vec3 sum = vec3(0.0f);
    for (uint i = 0u; i < uint(RK_LS_MAX_SAMPLES); ++i) {
        if (i >= nn) break;
        coord = vec2(coord.x - delta.x, coord.y - delta.y);
        vec3 s = rk_ls_read(occ, coord);
        sum += clamp(s, vec3(0.0f), vec3(RK_FLT_MAX)) * (fall * w);
        fall *= dec;
    }
    // An overflowing sum is held at RK_FLT_MAX first (Inf times a zero exposure would be NaN).
    vec3 held = clamp(sum, vec3(0.0f), vec3(RK_FLT_MAX));
    return clamp(held * ex, vec3(0.0f), vec3(RK_FLT_MAX));
}

RK_CONFIGURED_END

#endif  // RK_LIGHTSHAFTS_GLSL
