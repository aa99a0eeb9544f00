// raykit — ssao.glsl: screen-space ambient occlusion from a depth buffer (van Dongen, "Interior
// Mapping: A new technique for rendering realistic buildings", §4.4): the thesis's depth-only
// counting (Crytek: points of a sphere around the pixel that lie behind the depth buffer), a
// normal-oriented hemisphere variant with a range check, and a depth-aware blur.
//
// Shared GLSL/C++ source (include/raykit/ssao.hpp is the C++ build, with the kernel and
// rotation-noise generators and AoMapCpu, the CPU twin of the texture reads). The buffers are read
// through one function, rk_ao_read(map, uv): in GLSL textureLod(sampler2D, uv, 0).x (set NEAREST
// filtering on a depth buffer), in C++ the nearest texel of an AoMapCpu (clamp to edge). Positions
// are rebuilt from the window depth by gbuffer.glsl (rk_gb_linear_depth with k from
// rk_gb_depth_params, rk_gb_view_pos with ray from gbuffer_view_ray), so every depth convention of
// OpenGL, Vulkan and reversed-Z works. View space: camera at the origin looking down -z.
//
// Features (compile time):
//   RK_AO_MAX_SAMPLES (default 64, a plain integer in 1..256): the kernel arrays' size and the loop
//   bound of the occlusion functions (n is clamped to it).
//
// @rk-variants RK_AO_MAX_SAMPLES=64 | RK_AO_MAX_SAMPLES=16
// @rk-es 310
#ifndef RK_SSAO_GLSL
#define RK_SSAO_GLSL

#ifdef __cplusplus
#define RK_NS_SSAO RK_PP_CAT(ssao_samples, RK_AO_MAX_SAMPLES)
#endif

#include "common.glsl"
#include "gbuffer.glsl"

#ifndef RK_AO_MAX_SAMPLES
#define RK_AO_MAX_SAMPLES 64
#endif
#if RK_AO_MAX_SAMPLES < 1 || RK_AO_MAX_SAMPLES > 256
#error "RK_AO_MAX_SAMPLES must be in 1..256"
#endif
RK_OPTION_CHECK(rk_option_ao_max_samples, RK_AO_MAX_SAMPLES);

#ifndef __cplusplus
#ifdef GL_ES
precision highp sampler2D;
#endif
#define RK_AO_MAP sampler2D
/// rk_ao_read: the first channel of the texel at uv (level 0; the sampler's filter applies).
RK_INLINE float rk_ao_read(sampler2D m, vec2 uv) { return textureLod(m, uv, 0.0f).x; }
#endif

/// rk_ao_project: the texture coordinates of view-space point p for a projection with
/// proj = (P[0][0], P[1][1], P[2][0], P[2][1]) (lv_projection_params): 0.5 + 0.5 NDC. A point at or
/// behind the eye (p.z >= -RK_FLT_MIN) maps far outside [0, 1] (a sample no depth texel covers).
/// Cost: 1 div, 6 flops.
RK_INLINE vec2 rk_ao_project(vec3 p, vec4 proj)
{
    if (!(p.z < -RK_FLT_MIN)) return vec2(-2.0f, -2.0f);
    float w = -p.z;
    float x = clamp((proj.x * p.x + proj.z * p.z) / w, -4.0f, 4.0f);
    float y = clamp((proj.y * p.y + proj.w * p.z) / w, -4.0f, 4.0f);
    return vec2(0.5f + 0.5f * x, 0.5f + 0.5f * y);
}

/// rk_ao_clamp3_: internal. Componentwise clamp to [-RK_FLT_MAX, RK_FLT_MAX].
RK_INLINE vec3 rk_ao_clamp3_(vec3 v) { return clamp(v, vec3(-RK_FLT_MAX), vec3(RK_FLT_MAX)); }

/// rk_ao_inside: whether uv lies in the texture ([0, 1]², NaN excluded).
RK_INLINE bool rk_ao_inside(vec2 uv) { return uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f; }

RK_CONFIGURED_BEGIN(RK_NS_SSAO)

/// rk_ao_view_pos: the view-space position of the depth texel at uv (window depth -> distance by
/// rk_gb_linear_depth, -> position by rk_gb_view_pos with ndc = 2 uv - 1). k, ray: as gbuffer.glsl.
/// Cost: one read, rk_gb_linear_depth, rk_gb_view_pos.
RK_INLINE vec3 rk_ao_view_pos(RK_AO_MAP depth, vec2 uv, vec3 k, vec4 ray)
{
    float d = rk_ao_read(depth, uv);
    return rk_gb_view_pos(vec2(2.0f * uv.x - 1.0f, 2.0f * uv.y - 1.0f), rk_gb_linear_depth(d, k), ray);
}

/// rk_ao_sphere_count: the thesis's (Crytek's) depth-only SSAO: the fraction of n kernel points
/// p + radius · reflect(kernel[i], plane) (kernel in the unit ball, ao_kernel_sphere; `plane` a unit
/// vector per pixel from ao_rotation_noise, which scrambles the pattern) that lie behind the depth
/// buffer by more than `bias` (view units). Samples outside the screen count as unoccluded. With
/// range_check, a sample only counts when the surface in front of it is within `radius` of it (so a
/// near object does not darken a far background: the thesis's "only what the camera sees" problem
/// made local). A flat, fully visible surface gives about 0.5 (half the ball lies behind it):
/// rk_ao_sphere_occlusion maps that to 0. Returns [0, 1]. Cost: n (projection + read + rebuild).
RK_INLINE float rk_ao_sphere_count(RK_AO_MAP depth, vec3 p, float radius, vec3 kernel[RK_AO_MAX_SAMPLES], uint n, vec3 plane,
                                   float bias, bool range_check, vec3 k, vec4 ray, vec4 proj)
{
    uint nn = clamp(n, 1u, uint(RK_AO_MAX_SAMPLES));
    vec3 pl = rk_normalize_safe(plane, vec3(0.0f, 0.0f, 1.0f));
    float r = clamp(radius, 0.0f, RK_FLT_MAX);
    float hits = 0.0f;
    for (uint i = 0u; i < uint(RK_AO_MAX_SAMPLES); ++i) {
        if (i >= nn) break;
        vec3 s = p + r * reflect(kernel[i], pl);
        vec2 uv = rk_ao_project(s, proj);
        if (!rk_ao_inside(uv)) continue;
        float scene = -rk_ao_view_pos(depth, uv, k, ray).z;
        float gap = -s.z - scene;  // > 0: the surface is in front of the sample
        if (gap > bias && (!range_check || gap < r)) hits += 1.0f;
    }
    return hits / float(nn);
}

/// rk_ao_sphere_occlusion: the sphere count mapped so that a flat surface reads 0 and a fully
/// enclosed point 1: saturate(2 count - 1). Cost: 2 flops.
RK_INLINE float rk_ao_sphere_occlusion(float count) { return rk_saturate(2.0f * count - 1.0f); }

/// rk_ao_hemisphere: normal-oriented SSAO: n kernel points in the unit hemisphere around +z
/// (ao_kernel_hemisphere), turned into the frame of the unit view-space normal nrm (the geometric
/// normal of what the depth buffer holds, not a normal-mapped one) and rotated about it by the unit
/// 2-D vector `rot` (ao_rotation_noise, per pixel), placed at p + radius · frame · kernel[i]; a point
/// behind the depth buffer by more than the bias occludes, weighted by the range check
/// smoothstep(0, 1, radius / |p.z - surface z|) (a surface far in front of the point, e.g. a
/// foreground object over a background, counts little). The bias is `bias` (view units) plus a
/// footprint term per sample: the depth buffer holds each texel's centre, so a sample is compared
/// with a surface point up to half a texel away from where it projects, and on the receiving plane
/// that half texel spans t |n.x| / |n . r| · (1/width) / P[0][0] (+ the same in y) of depth, t and r
/// the plane's distance and the view ray at the sample (inv_size = (1/width, 1/height)); at grazing
/// angles that is metres, which a constant bias cannot cover. With it a flat surface reads 0
/// (tests/test_ssao.cpp: every pixel of a floor out to 100 units, kernels of 8 to 64 samples).
/// Returns the occluded fraction in [0, 1] (ambient light factor = 1 - it). Cost: n (projection +
/// read + rebuild + 2 dot + 1 div) + a frame (1 rsqrt, 1 cross).
RK_INLINE float rk_ao_hemisphere(RK_AO_MAP depth, vec3 p, vec3 nrm, float radius, vec3 kernel[RK_AO_MAX_SAMPLES], uint n, vec2 rot,
                                 float bias, vec2 inv_size, vec3 k, vec4 ray, vec4 proj)
{
    uint nn = clamp(n, 1u, uint(RK_AO_MAX_SAMPLES));
    vec3 nz = rk_normalize_safe(nrm, vec3(0.0f, 0.0f, 1.0f));
    // The plane through p with normal nz meets the view ray t (a, b, -1) at t = (nz . p) / (nz . r);
    // over half a texel, a changes by inv_size.x / P[0][0] (b likewise), and t by
    // t |nz.x| / |nz . r| times that (+ the y term).
    float reach = abs(nz.x) * abs(inv_size.x) / max(abs(proj.x), RK_FLT_MIN) + abs(nz.y) * abs(inv_size.y) / max(abs(proj.y), RK_FLT_MIN);
    float np = clamp(dot(nz, rk_ao_clamp3_(p)), -RK_FLT_MAX, RK_FLT_MAX);
    float b0 = max(bias, 0.0f);
    vec3 rv = vec3(rot.x, rot.y, 0.0f);
    vec3 t = rv - nz * dot(rv, nz);
    // A rotation vector (almost) along the normal: any perpendicular axis.
    vec3 alt = abs(nz.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    t = dot(t, t) > 1.0e-6f ? rk_normalize_safe(t, alt) : rk_normalize_safe(alt - nz * dot(alt, nz), vec3(1.0f, 0.0f, 0.0f));
    vec3 b = cross(nz, t);
    float r = clamp(radius, 0.0f, RK_FLT_MAX);
    float occ = 0.0f;
    for (uint i = 0u; i < uint(RK_AO_MAX_SAMPLES); ++i) {
        if (i >= nn) break;
        vec3 kv = kernel[i];
        vec3 s = rk_ao_clamp3_(p + r * (t * kv.x + b * kv.y + nz * kv.z));
        vec2 uv = rk_ao_project(s, proj);
        if (!rk_ao_inside(uv)) continue;
        // The footprint at the sample's own ray (s lies in front of the eye: rk_ao_project checked).
        vec3 rs = s / max(-s.z, RK_FLT_MIN);
        float nr = abs(dot(nz, rs));
        float ts = nr > 1.0e-6f ? abs(np) / nr : RK_FLT_MAX;
        float foot = nr > 1.0e-6f ? min(ts / nr * reach, RK_FLT_MAX) : RK_FLT_MAX;
        float sz = rk_ao_view_pos(depth, uv, k, ray).z;
        if (sz > s.z + min(b0 + foot, RK_FLT_MAX)) {
            float dz = abs(p.z - sz);
            occ += dz > r ? smoothstep(0.0f, 1.0f, r / max(dz, RK_FLT_MIN)) : 1.0f;
        }
    }
    return occ / float(nn);
}

/// rk_ao_blur: a depth-aware blur of an AO buffer along one axis (run it twice, `step` = (1/width, 0)
/// then (0, 1/height)): 2 taps + 1 samples at uv + i · step, i in [-taps, taps] (taps <= 8), weighted
/// by a Gaussian of i (sigma = taps / 2 + 0.5) times exp(-(relative depth difference · sharpness)²)
/// against the centre's distance, so occlusion does not bleed across depth edges (the thesis's fix
/// for noisy SSAO). The depth buffer is read as rk_ao_view_pos does; AO texels are clamped to [0, 1]
/// (NaN reads as 0), so the result is in [0, 1]. Cost: 2 taps + 1 reads of each buffer, as many exp.
RK_INLINE float rk_ao_blur(RK_AO_MAP ao, RK_AO_MAP depth, vec2 uv, vec2 step, int taps, float sharpness, vec3 k)
{
    int tn = clamp(taps, 0, 8);
    float dc = rk_gb_linear_depth(rk_ao_read(depth, uv), k);
    float sigma = 0.5f * float(tn) + 0.5f;
    float sum = 0.0f;
    float wsum = 0.0f;
    for (int i = -8; i <= 8; ++i) {
        if (i < -tn || i > tn) continue;
        vec2 q = vec2(uv.x + float(i) * step.x, uv.y + float(i) * step.y);
        float d = rk_gb_linear_depth(rk_ao_read(depth, q), k);
        float rel = clamp((d - dc) / max(dc, RK_FLT_MIN), -1.0e18f, 1.0e18f) * min(max(sharpness, 0.0f), 1.0e18f);
        float w = exp(-0.5f * float(i * i) / (sigma * sigma)) * exp(-min(rel * rel, 80.0f));
        float a = rk_ao_read(ao, q);
        sum += w * (a >= 0.0f ? min(a, 1.0f) : 0.0f);  // AO is in [0, 1]; NaN reads as 0
        wsum += w;
    }
    return wsum > 0.0f ? sum / wsum : 0.0f;
}

RK_CONFIGURED_END

#endif  // RK_SSAO_GLSL
