// raykit — relief.glsl: displacement in the pixel shader (van Dongen, "Interior Mapping", ch. 4):
// a depth map marched along the tangent-space view ray. Steep parallax and parallax occlusion
// mapping (Tatarchuk 2006: a linear march, then the secant between the last two layers), relief
// mapping (Policarpo & Oliveira 2005: a linear march, then a binary search), cone step mapping
// (Dummer 2006: each step jumps to the boundary of the empty cone stored at the texel) and relaxed
// cone stepping (Policarpo & Oliveira, GPU Gems 3 ch. 18, 2007: wider cones that the ray may pierce
// once, then a binary search), self-shadowing by a march towards the light, and one-read parallax
// with offset limiting (Welsh 2004, rk_nm_parallax_offset of normalmap.glsl).
//
// Shared GLSL/C++ source (include/raykit/relief.hpp is the C++ build, with the CPU map, the normal-
// and cone-map generators). The map is read through one function, rk_relief_read(map, uv): in GLSL
// textureLod(sampler2D, uv, 0.0).xy (bilinear filtering, no mipmaps; the sampler's wrap mode is the
// user's: REPEAT for tiling maps), in C++ the bilinear twin of relief.hpp (REPEAT or CLAMP_TO_EDGE,
// as ReliefMapCpu::wrap says), which tests/gpu/parity_relief.cpp checks against the driver.
//
// Conventions (Policarpo & Oliveira's): channel x is the DEPTH d in [0, 1] below the polygon
// (0 = on the polygon, 1 = the deepest, depth_scale below it; a height map h gives d = 1 - h), and
// channel y, for the cone methods, the cone ratio in [0, 1]: the horizontal uv distance per unit of
// depth of the cone opening upwards from the texel's surface point (relief.hpp builds it). v_ts is
// the unit tangent-space vector from the surface towards the eye (as rk_nm_parallax_offset takes
// it); depth_scale is the depth of d = 1 in uv units (e.g. 0.05). The ray is p(t) = uv + t · delta,
// t the ray's depth in [0, 1], delta = -v_ts.xy / v_ts.z · depth_scale (rk_relief_delta). Every
// method returns vec3(hit u, hit v, hit t): t · depth_scale is the hit's depth in uv units.
//
// Features (compile time):
//   RK_RELIEF_MAX_STEPS (default 64, a plain integer): the loop bound of every march (the step
//   counts passed in are clamped to it). Binary and secant refinements are bounded by 24.
//
// @rk-variants RK_RELIEF_MAX_STEPS=64 | RK_RELIEF_MAX_STEPS=1 | RK_RELIEF_MAX_STEPS=256
// @rk-es 310
#ifndef RK_RELIEF_GLSL
#define RK_RELIEF_GLSL

#ifdef __cplusplus
#define RK_NS_RELIEF RK_PP_CAT(relief_steps, RK_RELIEF_MAX_STEPS)
#endif

#include "common.glsl"
#include "normalmap.glsl"

#ifndef RK_RELIEF_MAX_STEPS
#define RK_RELIEF_MAX_STEPS 64
#endif
#if RK_RELIEF_MAX_STEPS < 1 || RK_RELIEF_MAX_STEPS > 1024
#error "RK_RELIEF_MAX_STEPS must be in 1..1024"
#endif
RK_OPTION_CHECK(rk_option_relief_max_steps, RK_RELIEF_MAX_STEPS);

/// The smallest view cosine the marches use (89.1 degrees from the normal): a grazing or
/// back-facing v_ts is treated as this, so delta stays finite (|delta| <= 64 depth_scale).
#define RK_RELIEF_MIN_COS 0.015625f

#ifndef __cplusplus
#ifdef GL_ES
precision highp sampler2D;
#endif
#define RK_RELIEF_MAP sampler2D
/// rk_relief_read: the map at uv, (depth, cone ratio), bilinear, level 0 (GLSL build).
RK_INLINE vec2 rk_relief_read(sampler2D m, vec2 uv)
{
    vec4 t = textureLod(m, uv, 0.0f);
    return vec2(t.x, t.y);
}
#endif

/// rk_relief_delta: the ray's uv displacement per unit of depth t, -v.xy / v.z · depth_scale, v the
/// normalised v_ts (zero or NaN: the normal), v.z at least RK_RELIEF_MIN_COS, depth_scale clamped
/// to [0, 1] (NaN: 0). Exact to float rounding. Cost: 1 rsqrt, 1 div, ~10 flops.
RK_INLINE vec2 rk_relief_delta(vec3 v_ts, float depth_scale)
{
    vec3 v = rk_normalize_safe(v_ts, vec3(0.0f, 0.0f, 1.0f));
    float vz = max(v.z, RK_RELIEF_MIN_COS);
    float s = depth_scale > 0.0f ? min(depth_scale, 1.0f) : 0.0f;
    float k = s / vz;
    return vec2(-v.x * k, -v.y * k);
}

/// rk_relief_depth_at: the map's depth at uv clamped to [0, 1] (a NaN texel reads as 0).
/// Cost: 1 bilinear read.
RK_INLINE float rk_relief_depth_at(RK_RELIEF_MAP m, vec2 uv)
{
    float d = rk_relief_read(m, uv).x;
    return d > 0.0f ? min(d, 1.0f) : 0.0f;
}

/// rk_relief_parallax: one-read parallax mapping with offset limiting (Welsh 2004, through
/// rk_nm_parallax_offset): uv - d(uv) · depth_scale · v.xy, depth guess d(uv). The baseline: exact
/// only on a flat map; the offset never exceeds depth_scale. Cost: 1 read.
RK_INLINE vec3 rk_relief_parallax(RK_RELIEF_MAP m, vec2 uv, vec3 v_ts, float depth_scale)
{
    float d = rk_relief_depth_at(m, uv);
    vec3 v = rk_normalize_safe(v_ts, vec3(0.0f, 0.0f, 1.0f));
    float s = depth_scale > 0.0f ? min(depth_scale, 1.0f) : 0.0f;
    vec2 o = rk_nm_parallax_offset(uv, d, v, -s, 0.0f);
    return vec3(o.x, o.y, d);
}

/// rk_relief_secant: the depth where the line through (ta, fa) and (tb, fb) crosses 0, for
/// fa < 0 <= fb (f = ray depth - surface depth); ta when fb - fa vanishes. Within [ta, tb].
RK_INLINE float rk_relief_secant(float ta, float fa, float tb, float fb)
{
    float w = clamp(-fa / max(fb - fa, RK_FLT_MIN), 0.0f, 1.0f);
    return ta + (tb - ta) * w;
}

RK_CONFIGURED_BEGIN(RK_NS_RELIEF)

/// rk_relief_linear: the linear search of steep parallax, POM and relief mapping: layers
/// t_k = k / n (n = steps clamped to 1..RK_RELIEF_MAX_STEPS, k = 1..n), the first where the ray is
/// at or below the surface. Returns vec4(t_above, f_above, t_below, f_below), f = t - d(p(t))
/// (f_above < 0 <= f_below; both t 0 when the surface is at the top at uv). Always finds one: at
/// t = 1 no depth is deeper. A feature thinner than the layer spacing can be stepped over (the
/// thesis's "thin spikes are skipped"). Cost: n + 1 reads at most.
RK_INLINE vec4 rk_relief_linear(RK_RELIEF_MAP m, vec2 uv, vec2 delta, uint steps)
{
    uint n = clamp(steps, 1u, uint(RK_RELIEF_MAX_STEPS));
    float fa = -rk_relief_depth_at(m, uv);
    if (fa >= 0.0f) return vec4(0.0f, fa, 0.0f, fa);
    float ta = 0.0f;
    float inv = 1.0f / float(n);
    for (uint k = 1u; k <= uint(RK_RELIEF_MAX_STEPS); ++k) {
        float t = k >= n ? 1.0f : float(k) * inv;
        float f = t - rk_relief_depth_at(m, uv + delta * t);
        if (f >= 0.0f || k >= n) return vec4(ta, fa, t, max(f, 0.0f));
        ta = t;
        fa = f;
    }
    return vec4(ta, fa, 1.0f, 0.0f);
}

/// rk_relief_steep: steep parallax mapping (the linear search alone): the first layer at or below
/// the surface. Hit-uv error up to one layer's uv step |delta| / steps (measured: docs/relief.md).
/// Cost: steps + 1 reads at most.
RK_INLINE vec3 rk_relief_steep(RK_RELIEF_MAP m, vec2 uv, vec3 v_ts, float depth_scale, uint steps)
{
    vec2 delta = rk_relief_delta(v_ts, depth_scale);
    vec4 s = rk_relief_linear(m, uv, delta, steps);
    vec2 p = uv + delta * s.z;
    return vec3(p.x, p.y, s.z);
}

/// rk_relief_pom: parallax occlusion mapping (Tatarchuk 2006): the linear search, then the depth
/// where the line between the last layer above and the first below meets the surface (the secant
/// of f, no extra read). Exact where the surface is linear between the two layers.
/// Cost: steps + 1 reads at most, 1 div.
RK_INLINE vec3 rk_relief_pom(RK_RELIEF_MAP m, vec2 uv, vec3 v_ts, float depth_scale, uint steps)
{
    vec2 delta = rk_relief_delta(v_ts, depth_scale);
    vec4 s = rk_relief_linear(m, uv, delta, steps);
    float t = rk_relief_secant(s.x, s.y, s.z, s.w);
    vec2 p = uv + delta * t;
    return vec3(p.x, p.y, t);
}

/// rk_relief_bisect: binary search of the crossing between ta (above) and tb (below), nb halvings
/// (clamped to 0..24), then the secant of the last bracket. Cost: nb reads.
RK_INLINE float rk_relief_bisect(RK_RELIEF_MAP m, vec2 uv, vec2 delta, float ta0, float fa0, float tb0, float fb0, uint nb)
{
    float ta = ta0;
    float fa = fa0;
    float tb = tb0;
    float fb = fb0;
    uint n = min(nb, 24u);
    for (uint i = 0u; i < 24u; ++i) {
        if (i >= n) break;
        float t = 0.5f * (ta + tb);
        float f = t - rk_relief_depth_at(m, uv + delta * t);
        if (f >= 0.0f) {
            tb = t;
            fb = f;
        } else {
            ta = t;
            fa = f;
        }
    }
    return fa < 0.0f ? rk_relief_secant(ta, fa, tb, fb) : ta;
}

/// rk_relief_relief: relief mapping (Policarpo & Oliveira 2005): the linear search of `steps`
/// layers, then `binary_steps` halvings (0..24) of the bracket and its secant. Like POM it can step
/// over a feature thinner than a layer; the binary search then converges on the crossing found.
/// Cost: steps + 1 + binary_steps reads at most.
RK_INLINE vec3 rk_relief_relief(RK_RELIEF_MAP m, vec2 uv, vec3 v_ts, float depth_scale, uint steps, uint binary_steps)
{
    vec2 delta = rk_relief_delta(v_ts, depth_scale);
    vec4 s = rk_relief_linear(m, uv, delta, steps);
    float t = rk_relief_bisect(m, uv, delta, s.x, s.y, s.z, s.w, binary_steps);
    vec2 p = uv + delta * t;
    return vec3(p.x, p.y, t);
}

/// rk_relief_cone_march: cone steps (ratios read from channel y, clamped to [0, 1]) from t = 0:
/// each step moves to where the ray leaves the cone of the texel under it, t += r (d - t) /
/// (|delta| + r). Stops after `steps` (1..RK_RELIEF_MAX_STEPS) reads or at the first read at or
/// below the surface. Returns vec4(t_above, f_above, t_last, f_last) (f = t - d; f_last >= 0: the
/// last step crossed the surface, which a conservative cone never does except by the bilinear
/// interpolation of the cones, or a relaxed cone by design).
RK_INLINE vec4 rk_relief_cone_march(RK_RELIEF_MAP m, vec2 uv, vec2 delta, uint steps)
{
    uint n = clamp(steps, 1u, uint(RK_RELIEF_MAX_STEPS));
    float len = length(delta);
    float ta = 0.0f;
    float fa = -1.0f;
    float t = 0.0f;
    for (uint k = 0u; k < uint(RK_RELIEF_MAX_STEPS); ++k) {
        if (k >= n) break;
        vec2 c = rk_relief_read(m, uv + delta * t);
        float d = c.x > 0.0f ? min(c.x, 1.0f) : 0.0f;
        float r = c.y > 0.0f ? min(c.y, 1.0f) : 0.0f;
        float gap = d - t;
        if (gap <= 0.0f) return vec4(ta, fa, t, -gap);
        ta = t;
        fa = -gap;
        // Vertical ray (len = 0): straight to the surface.
        float adv = len > 0.0f ? gap * r / max(len + r, RK_FLT_MIN) : gap;
        t = min(t + adv, 1.0f);
    }
    return vec4(ta, fa, t, t - rk_relief_depth_at(m, uv + delta * t));
}

/// rk_relief_cone: cone step mapping (Dummer 2006) on a conservative cone map (relief.hpp's
/// relief_build_cones): `steps` cone steps; the ray approaches the surface from above and never
/// steps over a feature, however thin, but converges geometrically where cones are narrow, so an
/// exhausted budget leaves the hit short of the surface (error: docs/relief.md). A step that lands
/// below (only through the cones' bilinear interpolation) is refined by the secant.
/// Cost: steps + 1 reads at most, 1 div per step.
RK_INLINE vec3 rk_relief_cone(RK_RELIEF_MAP m, vec2 uv, vec3 v_ts, float depth_scale, uint steps)
{
    vec2 delta = rk_relief_delta(v_ts, depth_scale);
    vec4 s = rk_relief_cone_march(m, uv, delta, steps);
    float t = s.w > 0.0f && s.y < 0.0f ? rk_relief_secant(s.x, s.y, s.z, s.w) : s.z;
    vec2 p = uv + delta * t;
    return vec3(p.x, p.y, t);
}

/// rk_relief_relaxed_cone: relaxed cone stepping (Policarpo & Oliveira 2007) on a relaxed cone map
/// (relief_build_relaxed_cones): cone steps that may land below the surface (a relaxed cone lets
/// the ray pierce it once), then `binary_steps` halvings (0..24) of the last step. A budget
/// exhausted above the surface leaves the hit short, as for rk_relief_cone.
/// Cost: steps + 1 + binary_steps reads at most.
RK_INLINE vec3 rk_relief_relaxed_cone(RK_RELIEF_MAP m, vec2 uv, vec3 v_ts, float depth_scale, uint steps, uint binary_steps)
{
    vec2 delta = rk_relief_delta(v_ts, depth_scale);
    vec4 s = rk_relief_cone_march(m, uv, delta, steps);
    float t = s.w >= 0.0f && s.y < 0.0f ? rk_relief_bisect(m, uv, delta, s.x, s.y, s.z, s.w, binary_steps) : s.z;
    vec2 p = uv + delta * t;
    return vec3(p.x, p.y, t);
}

/// rk_relief_shadow: self-shadowing: the segment from the hit (vec3(u, v, t), as the methods
/// return) up to the polygon towards l_ts (tangent-space vector towards the light, normalised
/// here) is sampled at the n - 1 depths t (1 - k / n), k = 1..n - 1 (n = steps clamped to
/// 1..RK_RELIEF_MAX_STEPS); 0 (shadowed) when one sample has the surface more than `bias` (depth
/// units, clamped to [0, 1], e.g. 0.02) above the segment, else 1. 0 for a light at or below the
/// horizon (l.z <= 0, or NaN). A blocker thinner than the sample spacing can be missed.
/// Cost: n - 1 reads at most.
RK_INLINE float rk_relief_shadow(RK_RELIEF_MAP m, vec3 hit, vec3 l_ts, float depth_scale, uint steps, float bias)
{
    vec3 l = rk_normalize_safe(l_ts, vec3(0.0f, 0.0f, 1.0f));
    if (!(l.z > 0.0f)) return 0.0f;
    vec2 dl = rk_relief_delta(vec3(-l.x, -l.y, l.z), depth_scale);
    float th = hit.z > 0.0f ? min(hit.z, 1.0f) : 0.0f;
    float b = bias > 0.0f ? min(bias, 1.0f) : 0.0f;
    uint n = clamp(steps, 1u, uint(RK_RELIEF_MAX_STEPS));
    vec2 p0 = vec2(hit.x, hit.y);
    float inv = 1.0f / float(n);
    for (uint k = 1u; k <= uint(RK_RELIEF_MAX_STEPS); ++k) {
        if (k >= n) break;
        float e = th * (1.0f - float(k) * inv);
        if (rk_relief_depth_at(m, p0 + dl * (th - e)) < e - b) return 0.0f;
    }
    return 1.0f;
}

RK_CONFIGURED_END

#endif  // RK_RELIEF_GLSL
