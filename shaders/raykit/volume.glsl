// raykit — volume.glsl: raytraced volumes, "soft particles" (van Dongen, "Interior Mapping: A new
// technique for rendering realistic buildings", chapter 6): a billboard's pixel casts its view ray
// through a volume primitive, the part of the ray inside it that lies in front of the scene (the
// depth buffer) is its visible length, and a thickness → opacity function turns that length into
// alpha, so a smoke puff meets geometry without a hard intersection line. Also the thesis's slices:
// the vertex-shader uv correction that makes every slice sample like the centre one, and the
// per-slice alpha that makes N slices compose to a target opacity.
//
// Primitives (spans = vec2(t_in, t_out) along a unit-length view ray, a miss is t_in > t_out as in
// ray.glsl): the thesis's constant thickness and thickness from the texture's alpha
// (rk_vol_span_slab), linearly decreasing thickness (rk_vol_span_pyramid) and the true sphere
// (rk_ray_sphere), and beyond it the box and the ellipsoid (rk_ray_box, rk_ray_ellipsoid of
// ray.glsl, used as they are).
//
// Non-uniform density: rk_vol_optical_depth_falloff (a radial falloff, exact), or a bounded march
// through a density texture, rk_vol_march_box, read through rk_vol_density(map, uvw): in GLSL
// textureLod(sampler3D, uvw, 0).x (LINEAR, CLAMP_TO_EDGE), in C++ the trilinear twin of
// volume.hpp's VolDensityCpu.
//
// Shared GLSL/C++ source (include/raykit/volume.hpp is the C++ build, with the slice layout
// generator).
//
// Features (compile time):
//   RK_VOL_MAX_STEPS (default 64, a plain integer in 1..1024): the loop bound of rk_vol_march_box.
//
// @rk-variants RK_VOL_MAX_STEPS=64 | RK_VOL_MAX_STEPS=8
// @rk-es 310
#ifndef RK_VOLUME_GLSL
#define RK_VOLUME_GLSL

#ifdef __cplusplus
#define RK_NS_VOLUME RK_PP_CAT(volume_steps, RK_VOL_MAX_STEPS)
#endif

#include "common.glsl"
#include "gbuffer.glsl"
#include "ray.glsl"

#ifndef RK_VOL_MAX_STEPS
#define RK_VOL_MAX_STEPS 64
#endif
#if RK_VOL_MAX_STEPS < 1 || RK_VOL_MAX_STEPS > 1024
#error "RK_VOL_MAX_STEPS must be in 1..1024"
#endif
RK_OPTION_CHECK(rk_option_vol_max_steps, RK_VOL_MAX_STEPS);

#ifndef __cplusplus
#ifdef GL_ES
precision highp sampler3D;
#endif
#define RK_VOL_DENSITY_MAP sampler3D
/// rk_vol_density: the density texture's first channel at uvw (level 0; the sampler's filter).
RK_INLINE float rk_vol_density(sampler3D m, vec3 uvw) { return textureLod(m, uvw, 0.0f).x; }
#endif

// ---------------------------------------------------------------------------------------------
// Spans

/// rk_vol_span_slab: the span of a volume of thickness `thickness` centred on the billboard, whose
/// plane the pixel's ray meets at distance t_bb: (t_bb - T/2, t_bb + T/2), the same depth in front
/// and behind (the thesis's constant thickness, and its thickness texture with T = T0 · alpha).
/// Rays fan out from the eye, so the solid is slightly tapered, not a box. T < RK_FLT_MIN (or
/// NaN) is a miss: a denormal thickness reads as 0 on drivers that flush denormals, so it is a miss
/// everywhere. Clamped to ±RK_FLT_MAX. Cost: 3 flops.
RK_INLINE vec2 rk_vol_span_slab(float t_bb, float thickness)
{
    if (!(thickness >= RK_FLT_MIN)) return RK_RAY_MISS;
    float h = 0.5f * min(thickness, RK_FLT_MAX);
    float t = clamp(t_bb, -RK_FLT_MAX, RK_FLT_MAX);
    return vec2(clamp(t - h, -RK_FLT_MAX, RK_FLT_MAX), clamp(t + h, -RK_FLT_MAX, RK_FLT_MAX));
}

/// rk_vol_span_pyramid: the thesis's linearly decreasing thickness: T = T0 (1 - max(|q.x|, |q.y|))
/// at the billboard coordinates q in [-1, 1]² (0 at the centre), a pyramid towards the viewer and
/// its mirror behind, through rk_vol_span_slab. Outside the square, a miss. Cost: ~8 flops.
RK_INLINE vec2 rk_vol_span_pyramid(float t_bb, float t0, vec2 q)
{
    float m = max(abs(q.x), abs(q.y));
    return rk_vol_span_slab(t_bb, t0 * (1.0f - min(m, 1.0f)));
}

/// rk_vol_visible_length: how much of a span lies between the near limit t_near (0 for the eye, or
/// the near plane's distance along the ray: rk_vol_near_distance) and the scene at t_scene (the
/// depth buffer's surface: rk_vol_scene_distance): max(min(t_out, t_scene) - max(t_in, t_near), 0).
/// Scene in front of the volume: 0; behind it: the whole chord; inside: the part before it; the eye
/// inside the volume: from t_near on. A miss and NaN input give 0. Cost: 4 min/max.
RK_INLINE float rk_vol_visible_length(vec2 span, float t_scene, float t_near)
{
    if (!(span.x <= span.y)) return 0.0f;
    float ts = t_scene >= 0.0f ? min(t_scene, RK_FLT_MAX) : 0.0f;  // NaN reads as 0: nothing visible
    float tn = t_near > 0.0f ? min(t_near, RK_FLT_MAX) : 0.0f;
    float a = max(span.x, tn);
    float b = min(span.y, ts);
    return b > a ? min(b - a, RK_FLT_MAX) : 0.0f;
}

// ---------------------------------------------------------------------------------------------
// Depth buffer -> distance along the ray

/// rk_vol_scene_distance: the distance along the unit view-space ray direction dir (camera looking
/// down -z) to the surface a depth buffer holds at that pixel: rk_gb_linear_depth(depth, k) gives
/// the distance along the view axis, divided by -dir.z (the ray's cosine with the axis), so the
/// comparison with a span is made in one parametrisation. k from rk_gb_depth_params (OpenGL,
/// Vulkan, reversed-Z, infinite far). A ray at or beyond 90 degrees from the axis (-dir.z <=
/// RK_FLT_MIN) gives RK_FLT_MAX. Cost: rk_gb_linear_depth + 1 div.
RK_INLINE float rk_vol_scene_distance(float depth, vec3 k, vec3 dir)
{
    float z = rk_gb_linear_depth(depth, k);
    float c = -dir.z;
    return c > RK_FLT_MIN ? min(z / c, RK_FLT_MAX) : RK_FLT_MAX;
}

/// rk_vol_near_distance: the distance along the unit view-space ray direction dir to the near plane
/// at view distance `near` (the start of what is drawn when the eye is inside a volume): near / -dir.z.
/// Cost: 1 div.
RK_INLINE float rk_vol_near_distance(float near, vec3 dir)
{
    float c = -dir.z;
    return c > RK_FLT_MIN ? clamp(near / c, 0.0f, RK_FLT_MAX) : 0.0f;
}

// ---------------------------------------------------------------------------------------------
// Thickness -> opacity

/// rk_vol_opacity_linear / _log / _sqrt: the thesis's three functions of the visible length L,
/// normalised so that the opacity is 0 at L = 0 and reaches 1 at L = l_full (the thesis gives no
/// constants; these are raykit's): x = L / l_full, then x, ln(1 + 9x) / ln 10 and sqrt(x), each
/// clamped to [0, 1]. All are monotone; log and sqrt are concave (thin parts more opaque). l_full <= 0
/// reads as RK_FLT_MIN (any positive L is opaque). Cost: 1 div + (0 | 1 log | 1 sqrt).
RK_INLINE float rk_vol_opacity_linear(float l, float l_full) { return rk_saturate(max(l, 0.0f) / max(l_full, RK_FLT_MIN)); }
RK_INLINE float rk_vol_opacity_log(float l, float l_full)
{
    float x = rk_saturate(max(l, 0.0f) / max(l_full, RK_FLT_MIN));
    return rk_saturate(log(1.0f + 9.0f * x) * 0.43429448190325182f);
}
RK_INLINE float rk_vol_opacity_sqrt(float l, float l_full) { return sqrt(rk_saturate(max(l, 0.0f) / max(l_full, RK_FLT_MIN))); }

/// rk_vol_opacity_beer: Beer–Lambert, 1 - exp(-sigma L), the physical answer for a uniform medium
/// of extinction sigma (not in the thesis). sigma and L below 0 read as 0. Cost: 1 exp.
RK_INLINE float rk_vol_opacity_beer(float l, float sigma)
{
    float tau = min(max(l, 0.0f) * max(sigma, 0.0f), 100.0f);
    return 1.0f - exp(-tau);
}

/// rk_vol_optical_depth_falloff: the optical depth of a sphere (centre c, radius r) whose density
/// falls from rho0 at the centre to 0 at the surface as rho0 (1 - |p - c|² / r²), along the unit ray
/// o + t dir over [t0, t1] (e.g. the visible part: max(t_in, t_near), min(t_out, t_scene)), exactly:
/// with b² the squared distance of the line from c and s = t - t_c measured from the closest point,
/// the integral of rho0 (1 - (b² + s²) / r²) ds. A non-uniform volume without a march; use it with
/// rk_vol_opacity_beer(tau, 1). Cost: ~25 flops.
RK_INLINE float rk_vol_optical_depth_falloff(vec3 o, vec3 dir, vec3 c, float r, float rho0, float t0, float t1)
{
    vec2 span = rk_ray_sphere(o, dir, c, r);
    float a = max(t0, span.x);
    float b = min(t1, span.y);
    if (!(b > a)) return 0.0f;
    float rr = max(r, RK_FLT_MIN);
    vec3 w = rk_ray_clamp3_(o - c);
    float tc = clamp(-dot(w, dir), -RK_FLT_MAX, RK_FLT_MAX);  // the closest point's t (dir is unit)
    // In units of r (so nothing overflows): the closest point's offset f / r, and s / r in [-1, 1]
    // (a and b lie inside the sphere's span).
    vec3 fr = rk_div3(rk_ray_clamp3_(w + tc * dir), rr);  // rk_div: r may exceed 2^126
    float beta = min(dot(fr, fr), 1.0f);
    float u0 = clamp(rk_div(a - tc, rr), -1.0f, 1.0f);
    float u1 = clamp(rk_div(b - tc, rr), -1.0f, 1.0f);
    // The integral is (u1 - u0) r [(1 - beta) - (u1² + u0 u1 + u0²) / 3], and (u1 - u0) r is the
    // chord b - a: taking it directly keeps a short chord of a huge sphere from going through
    // quotients that underflow (flushed to zero on some drivers), and the bracket is in [0, 1].
    float bracket = (1.0f - beta) - (u1 * u1 + u0 * u1 + u0 * u0) / 3.0f;
    float tau = min(max(rho0, 0.0f) * min(b - a, RK_FLT_MAX), RK_FLT_MAX) * max(bracket, 0.0f);
    return clamp(tau, 0.0f, RK_FLT_MAX);
}

// ---------------------------------------------------------------------------------------------
// The sphere's two pitfalls (thesis §6.3.3)

/// rk_vol_sphere_edge_fade: (half-chord / r)², the factor that removes the "hard circular cut-off"
/// of a raytraced sphere: the chord length rises as the square root of the distance from the
/// silhouette, so any opacity of it jumps within the silhouette's pixel; times this factor
/// (1 - b²/r², b the ray's distance from the centre) it rises linearly. span from rk_ray_sphere with
/// a unit direction; a miss gives 0. Cost: 3 flops.
RK_INLINE float rk_vol_sphere_edge_fade(vec2 span, float r)
{
    if (!(span.x <= span.y)) return 0.0f;
    float h = 0.5f * rk_div(span.y - span.x, max(r, RK_FLT_MIN));  // rk_div: r may exceed 2^126
    return rk_saturate(h * h);
}

/// rk_vol_billboard_half_size: the half-size of a camera-facing billboard through a sphere's centre
/// that contains the sphere's whole silhouette, seen from `dist` (eye to centre): r · dist /
/// sqrt(dist² - r²) (the tangent cone's radius at the centre plane). A billboard of half-size r (the
/// thesis's) cuts the silhouette off at its edge: its edge subtends atan(r / dist), the silhouette
/// asin(r / dist). The eye inside or on the sphere (dist <= r · 1.0001) gives RK_FLT_MAX: draw it
/// full screen. Cost: 1 sqrt, 1 div.
RK_INLINE float rk_vol_billboard_half_size(float r, float dist)
{
    float rr = max(r, 0.0f);
    float d = max(dist, 0.0f);
    if (!(d > rr * 1.0001f)) return RK_FLT_MAX;
    float q = rr / d;  // < 1 / 1.0001: no overflow below, none in d² - r² either
    return min(rr / sqrt((1.0f - q) * (1.0f + q)), RK_FLT_MAX);
}

// ---------------------------------------------------------------------------------------------
// Slices

/// rk_vol_slice_uv: the thesis's vertex-shader uv correction for a slice vertex v (world or view
/// space, as the rest): the eye's ray through v meets the centre slice's plane (through s, unit
/// normal n) at x = eye + t (v - eye), t = dot(s - eye, n) / dot(v - eye, n), and the texture
/// coordinate is x's position in the centre slice: (dot(x - s, axis_u) / (2 half.x) + 0.5,
/// dot(x - s, axis_v) / (2 half.y) + 0.5) (axis_u, axis_v unit, in the plane). Every slice then
/// samples the texture where the centre slice would, so the texture no longer stretches towards
/// the centre in perspective. A ray parallel to the plane (|dot(v - eye, n)| below 1e-12 of its
/// length² · |s - eye|) falls back to v's orthogonal projection on the plane. Exact up to float
/// rounding. For a slice parallel to the centre plane (the thesis's layout), dot(v - eye, n) is the
/// same at every vertex, so the uv is an affine function of the position and the rasteriser's
/// perspective-correct interpolation of the per-vertex values is exact; a tilted slice would not
/// have that. Cost: 4 dot, 1 div.
RK_INLINE vec2 rk_vol_slice_uv(vec3 v, vec3 eye, vec3 s, vec3 n, vec3 axis_u, vec3 axis_v, vec2 half_size)
{
    vec3 e = v - eye;
    float den = dot(e, n);
    float num = dot(s - eye, n);
    vec3 x;
    if (abs(den) > 1.0e-12f * dot(e, e) * max(length(s - eye), 1.0f) && abs(den) > RK_FLT_MIN) {
        x = rk_ray_clamp3_(eye + e * clamp(num / den, -RK_FLT_MAX, RK_FLT_MAX));
    } else {
        x = rk_ray_clamp3_(v - n * clamp(dot(rk_ray_clamp3_(v - s), n), -RK_FLT_MAX, RK_FLT_MAX));
    }
    vec3 dx = rk_ray_clamp3_(x - s);
    float u = dot(dx, axis_u) / max(2.0f * abs(half_size.x), RK_FLT_MIN) + 0.5f;
    float v2 = dot(dx, axis_v) / max(2.0f * abs(half_size.y), RK_FLT_MIN) + 0.5f;
    return vec2(clamp(u, -RK_FLT_MAX, RK_FLT_MAX), clamp(v2, -RK_FLT_MAX, RK_FLT_MAX));
}

/// rk_vol_slice_alpha: the alpha of each of n equal slices so that all of them composed (over,
/// back to front) give opacity a: 1 - (1 - a)^(1/n) (the thesis gives no formula). Evaluated as
/// 1 - exp(-y), y = -ln(1 - a) / n, each by its series where the direct form would cancel (a < 0.1:
/// -ln(1 - a) to 8 terms, else log2 with Goldberg's correction of 1 - a; y < 0.1: 1 - exp(-y) to 5
/// terms). Relative error of the composition 1 - (1 - alpha)^n against a: 3.7e-7 on the CPU over a
/// dense sweep (2e5 values of a in [1e-30, 1 - 1e-7], n in 1..1024; tests/test_volume.cpp); a GPU's
/// log2 (GLSL: 2^-21 absolute on [0.5, 2]) may add up to ~3e-6 relative near a = 0.1.
/// a >= 1 gives 1, a <= 0 (or NaN) or n = 0 gives 0. Cost: ~20 flops or 1 log2.
RK_INLINE float rk_vol_slice_alpha(float a, uint n)
{
    if (!(a > 0.0f) || n == 0u) return 0.0f;
    if (a >= 1.0f) return 1.0f;
    float nl;  // -ln(1 - a)
    if (a < 0.1f) {
        nl = a * (1.0f + a * (0.5f + a * (1.0f / 3.0f + a * (0.25f + a * (0.2f + a * (1.0f / 6.0f + a * (1.0f / 7.0f + a * 0.125f)))))));
    } else {
        // Goldberg's correction: u = 1 - a is rounded, and a / (1 - u) puts back what the
        // rounding lost (1 - u is exact here), so the log sees the a that was meant.
        float u = 1.0f - a;
        nl = -0.6931471805599453f * log2(u) * (a / (1.0f - u));
    }
    float y = nl / float(n);
    if (y < 0.1f) return y * (1.0f - y * (0.5f - y * (1.0f / 6.0f - y * (1.0f / 24.0f - y / 120.0f))));
    return 1.0f - exp(-y);
}

// ---------------------------------------------------------------------------------------------
// Non-uniform density: a bounded march

RK_CONFIGURED_BEGIN(RK_NS_VOLUME)

/// rk_vol_march_box: the optical depth sigma · integral of the density along the unit ray o + t dir
/// over [t0, t1] (e.g. the visible part: max(t_near, 0) to the scene's distance), where a density
/// texture fills the axis-aligned box [lo, hi] (texture coordinates (p - lo) / (hi - lo); zero
/// outside the box): the part of [t0, t1] inside the box (rk_ray_box) is cut into n equal steps
/// (n = steps clamped to 1..RK_VOL_MAX_STEPS) and each step reads the density once at its fraction
/// `jitter` (0.5: the midpoint rule, exact for a density linear along the ray; a per-pixel value in
/// [0, 1) turns the steps' banding into noise). Densities below 0 (or NaN) read as 0. Use with
/// rk_vol_opacity_beer(tau, 1). Cost: n texture reads + rk_ray_box.
RK_INLINE float rk_vol_march_box(RK_VOL_DENSITY_MAP m, vec3 o, vec3 dir, vec3 lo, vec3 hi, float t0, float t1, float sigma, uint steps,
                                 float jitter)
{
    vec2 span = rk_ray_box(o, dir, lo, hi);
    float a = max(max(t0, span.x), -RK_FLT_MAX);
    float b = min(min(t1, span.y), RK_FLT_MAX);
    if (!(b > a)) return 0.0f;
    uint n = clamp(steps, 1u, uint(RK_VOL_MAX_STEPS));
    float dt = min(b - a, RK_FLT_MAX) / float(n);  // a huge box: held finite
    float j = jitter >= 0.0f ? min(jitter, 1.0f) : 0.5f;
    vec3 ext = max(hi - lo, vec3(RK_FLT_MIN));
    float sum = 0.0f;
    for (uint i = 0u; i < uint(RK_VOL_MAX_STEPS); ++i) {
        if (i >= n) break;
        float ti = clamp(a + (float(i) + j) * dt, -RK_FLT_MAX, RK_FLT_MAX);
        vec3 p = rk_ray_clamp3_(o + dir * ti);
        float d = rk_vol_density(m, rk_ray_clamp3_((p - lo) / ext));
        sum += d > 0.0f ? min(d, RK_FLT_MAX) : 0.0f;
    }
    float tau = min(max(sigma, 0.0f), RK_FLT_MAX) * min(sum * dt, RK_FLT_MAX);
    return tau > 0.0f ? min(tau, RK_FLT_MAX) : 0.0f;  // Inf * 0 = NaN reads as 0
}

RK_CONFIGURED_END

#endif  // RK_VOLUME_GLSL
