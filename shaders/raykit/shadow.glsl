// raykit — shadow.glsl: shadow-map lookups' math (Fahlén, "Illumination for Real-Time Rendering of
// Large Architectural Environments", ch. 5): projecting a point into the map (the shadow matrix of
// Eq. 5.1 comes from shadow.hpp), depth biases (constant, slope-scaled, normal offset), the sample
// patterns of percentage-closer filtering (Vogel's spiral, rotated per pixel), the penumbra width of
// PCSS, and cascade selection and blending; for omnidirectional (point) lights, the coordinates,
// compare values and texel sizes of cube shadow maps (window depth or linear distance) and of
// dual-paraboloid shadow maps in a 2:1 atlas (through paraboloid.glsl).
//
// Shared GLSL/C++ source (include/raykit/shadow.hpp is the C++ build, with the shadow matrix, the
// cascade splits and the texel-snapped light fit, and the CPU pattern generators). The texture
// fetches themselves (sampler2DShadow / samplerCubeShadow compares) belong to the application's
// shader; this file gives each fetch's coordinates and compare depth.
//
// @rk-es 310
// @rk-es300
#ifndef RK_SHADOW_GLSL
#define RK_SHADOW_GLSL

#include "common.glsl"
#include "paraboloid.glsl"

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
/// The C++ build's bits where GLSL has `precise` (4.00+, ES 3.20); elsewhere (ES 3.00 / 3.10) a
/// driver may fuse the first sum, which moves the angle by up to 0.12 rad (still in [0, 2 pi)).
/// Cost: ~6 flops.
RK_INLINE float rk_sh_rotation(uvec2 pixel)
{
    float x = float(pixel.x & 4095u);
    float y = float(pixel.y & 4095u);
    // RK_PRECISE: fract() of the sum amplifies its rounding 333 times; a fused multiply-add (which a
    // driver may use unless told not to: NVIDIA computed fma(0.0671.., x, 0.0058.. y)) moves the
    // angle by up to 0.12 rad over the 4096 x 4096 tile.
    RK_PRECISE float g = 0.06711056f * x + 0.00583715f * y;
    RK_PRECISE float f = 52.9829189f * fract(g);
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
/// parallel to the receiver and the light. The ratio gap / d_blocker is taken first, so tiny
/// distances do not underflow (or flush to zero on a driver that flushes denormals). Cost: 1 div,
/// 3 flops.
RK_INLINE float rk_sh_pcss_penumbra(float d_receiver, float d_blocker, float w_light)
{
    float db = max(d_blocker, RK_FLT_MIN);
    float gap = min(max(d_receiver - d_blocker, 0.0f), RK_FLT_MAX);  // an overflowing difference held finite
    // The ratio held finite too (it reaches 2^254 for gap FLT_MAX over FLT_MIN), so a zero width
    // gives 0, never Inf * 0.
    return clamp(min(gap / db, RK_FLT_MAX) * max(w_light, 0.0f), 0.0f, RK_FLT_MAX);
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
    return rk_saturate(rk_div(dist - (split_far - b), b));  // rk_div: b may exceed 2^126
}

// ---------------------------------------------------------------------------------------------
// Omnidirectional lights
//
// A point light's shadow map is looked up with v = p - light position, in the map's frame (world
// axes, or the light's rotation applied to v). Two layouts:
//   cube   six N x N faces in OpenGL's cube-map layout (rk_sh_cube_face_uv; Vulkan and D3D use
//          the same), each storing either the window depth of a 90-degree perspective projection
//          (rk_sh_cube_ref_depth: a depth-only render pass) or the linear distance |v| mapped to
//          [0, 1] over [n, f] (rk_sh_cube_ref_distance: a colour or depth value written by the
//          fragment shader, the "distance compare"). Render face i with
//          lookAt(light, light + axis_i, up_i), up = -y for the four side faces, +z for +Y and -z
//          for -Y, and perspective(90 degrees, 1, n, f): its window (x, y) is then (s, t) of
//          rk_sh_cube_face_uv, row 0 at t = 0 (tests/test_shadow.cpp checks it).
//   dual paraboloid   a 2H x H atlas (paraboloid.glsl's layout: the left half is the +z hemisphere,
//          the right half -z, a guard ring of continuation directions around each disk), each
//          texel storing rk_paraboloid_depth_encode(|v|, n, f) of the first hit (render with
//          rk_paraboloid_project, + rk_paraboloid_clip_distance; mind its tessellation caveat).
//          Read with rk_sh_dp_lookup. The atlas's seam is the plane z = 0 of the map's frame.
// Compare LEQUAL (lit where reference <= stored) for all three.
//
// Bias for a point light: a texel's width in world units grows with the distance, so a bias is a
// number of texels of the width where the receiver is, tw = rk_sh_cube_texel_world(v, N) or
// rk_sh_dp_texel_world(v, H, g): slope-scaled, b = rk_sh_slope_bias(N.L, c tw, s tw, max tw) world
// units, applied as rk_sh_omni_toward_light(v, b) before the lookup (the same for depth and
// distance maps); normal offset, p moved by rk_sh_normal_offset(p, n, N.L, tw, k) before v is
// formed. tests/test_shadow_omni.cpp measures both against exact visibility (c = 0.5, s = 1,
// max = 10; k = 1.5 plus 0.5 tw).

/// rk_sh_finite: x with NaN replaced by 0 and +-Inf by +-RK_FLT_MAX (comparisons, false for NaN;
/// a driver that does not keep NaNs never produces one). Every finite x unchanged. Exact.
/// Cost: 3 compares, 2 selects.
RK_INLINE float rk_sh_finite(float x)
{
    return abs(x) <= RK_FLT_MAX ? x : (x > 0.0f ? RK_FLT_MAX : (x < 0.0f ? -RK_FLT_MAX : 0.0f));
}

/// rk_sh_finite3: rk_sh_finite of each component. Exact. Cost: 9 compares, 6 selects.
RK_INLINE vec3 rk_sh_finite3(vec3 v) { return vec3(rk_sh_finite(v.x), rk_sh_finite(v.y), rk_sh_finite(v.z)); }

/// rk_sh_omni_distance: |v|, the distance from the light, for any v: components scaled by the
/// largest first (no overflow or underflow of the squares), denormal components counted as 0 (as
/// GPUs that flush them see them), NaN as 0 and +-Inf as +-RK_FLT_MAX (rk_sh_finite). The result
/// is capped at RK_PARABOLOID_POS_MAX (1e18). Edge cases: v = 0 (or all-denormal) gives 0.
/// Max error: 2.4 ulp against float64 (|v| in 2^-60..2^58; 1e7 random + 1e6 within 2048 ulp per
/// component of the worst). Cost: 1 div, 1 sqrt, ~14 flops.
RK_INLINE float rk_sh_omni_distance(vec3 v)
{
    vec3 w = rk_sh_finite3(v);
    w = rk_flush_subnormal(w);
    float m = rk_paraboloid_max_abs(w);
    if (m < RK_FLT_MIN) {
        return 0.0f;
    }
    float pre = rk_paraboloid_prescale(m);
    vec3 q = (w * pre) / (m * pre);  // largest component +-1: dot(q, q) in [1, 3]
    return min(min(m, RK_PARABOLOID_POS_MAX) * sqrt(dot(q, q)), RK_PARABOLOID_POS_MAX);
}

/// rk_sh_omni_toward_light: v moved `bias` world units towards the light (the origin), not past
/// it: v (1 - b / |v|) with b = bias clamped to [0, |v|]. A depth bias in world units for any of
/// the omnidirectional references below (their depth units are not linear in the distance for
/// rk_sh_cube_ref_depth). Edge cases: bias 0 returns v unchanged (NaN/Inf sanitised by
/// rk_sh_finite3); v = 0 or all-denormal returns 0; bias >= |v| returns 0; NaN bias counts as 0.
/// Domain: |v| up to 1e18 (beyond, |v| is taken as 1e18). Max error against float64: 4.5 ulp per
/// component for bias <= |v| / 2; for any bias, |error| <= 2.2 ulp of |v| (d - b cancels as b
/// nears |v|) (1e7 random + 1e6 within 2048 ulp of the worst, as for the others below).
/// Cost: rk_sh_omni_distance + 1 div, 4 flops.
RK_INLINE vec3 rk_sh_omni_toward_light(vec3 v, float bias)
{
    vec3 w = rk_sh_finite3(v);
    float d = rk_sh_omni_distance(w);
    if (d < RK_FLT_MIN) {
        return vec3(0.0f);
    }
    float b = clamp(rk_sh_finite(bias), 0.0f, d);
    return w * ((d - b) / d);
}

/// rk_sh_cube_face_uv: the cube-map face v points at and the position on it, (s, t, face), by
/// OpenGL's rule (GL 4.6 §8.13, Table 8.19; Vulkan and D3D agree): the major axis picks the face,
/// 0..5 = +X, -X, +Y, -Y, +Z, -Z (the layer order of a cube map), and (sc, tc) = (-z, -y) on +X,
/// (z, -y) on -X, (x, z) on +Y, (x, -z) on -Y, (x, -y) on +Z, (-x, -y) on -Z give
/// s = (sc / |ma| + 1) / 2, t = (tc / |ma| + 1) / 2 in [0, 1], t = 0 the face image's first row.
/// For a cube kept in a 2-D array or atlas, or filtered by hand. Ties between axes (cube edges and
/// corners, which GL leaves to the implementation): x before y before z, and +0 / -0 count as +;
/// either face gives the same point of the shared edge. Edge cases: v = 0 (or all-denormal) gives
/// (0.5, 0.5, 0); NaN counts as 0, +-Inf as +-RK_FLT_MAX. Max error: 4.5e-8 in s, t (one rounding
/// of sc / |ma| and one of the sum; 1e7 random + refinement). Cost: 3 abs, ~8 compares/selects,
/// 1 div, 2 fma.
RK_INLINE vec3 rk_sh_cube_face_uv(vec3 v)
{
    vec3 w = rk_sh_finite3(v);
    float ax = abs(w.x);
    float ay = abs(w.y);
    float az = abs(w.z);
    float face;
    float ma;
    float sc;
    float tc;
    if (ax >= ay && ax >= az) {
        face = w.x < 0.0f ? 1.0f : 0.0f;
        ma = ax;
        sc = w.x < 0.0f ? w.z : -w.z;
        tc = -w.y;
    } else if (ay >= az) {
        face = w.y < 0.0f ? 3.0f : 2.0f;
        ma = ay;
        sc = w.x;
        tc = w.y < 0.0f ? -w.z : w.z;
    } else {
        face = w.z < 0.0f ? 5.0f : 4.0f;
        ma = az;
        sc = w.z < 0.0f ? -w.x : w.x;
        tc = -w.y;
    }
    if (ma < RK_FLT_MIN) {
        return vec3(0.5f, 0.5f, 0.0f);
    }
    float pre = rk_paraboloid_prescale(ma);
    float m = ma * pre;
    float s = clamp((sc * pre) / m, -1.0f, 1.0f);
    float t = clamp((tc * pre) / m, -1.0f, 1.0f);
    return vec3(0.5f + 0.5f * s, 0.5f + 0.5f * t, face);
}

/// rk_sh_cube_ref_depth: the compare depth of light-relative vector v for a cube shadow map whose
/// six faces are rendered with a 90-degree perspective projection of near n and far f (usual
/// depth; OpenGL's [-1, 1] NDC and Vulkan's [0, 1] store the same window value): the face is v's
/// major axis, its view depth z = max(|v.x|, |v.y|, |v.z|), and the stored depth
/// (1/n - 1/z) / (1/n - 1/f) = f (z - n) / (z (f - n)). Pass it as the reference of a
/// samplerCubeShadow lookup in direction v (compare LEQUAL). Domain: 0 < n < f; z below n gives a
/// negative depth (always lit), beyond f above 1. Edge cases (all finite): n is clamped to
/// [RK_FLT_MIN, 1e18], f to at least max(n (1 + 1e-7), n + RK_FLT_MIN) and at most 2e18, z to 1e18 (beyond, the limit
/// f / (f - n) to float precision); NaN counts as 0, +-Inf as +-RK_FLT_MAX. Max error: 4.2 ulp for
/// z >= n (a cancellation-free form; 1e7 random + refinement). Cost: 3 abs, 2 max, 1 div, 3 flops, 4 clamps.
RK_INLINE float rk_sh_cube_ref_depth(vec3 v, float n, float f)
{
    float z = min(rk_paraboloid_max_abs(rk_sh_finite3(v)), RK_PARABOLOID_POS_MAX);
    float nn = clamp(rk_sh_finite(n), RK_FLT_MIN, RK_PARABOLOID_POS_MAX);
    // f - n stays >= RK_FLT_MIN: a denormal difference is zero on drivers that flush denormals.
    float ff = clamp(rk_sh_finite(f), max(nn * 1.0000001f, nn + RK_FLT_MIN), 2.0f * RK_PARABOLOID_POS_MAX);
    // The quotient before the product: ff (z - nn) underflows for tiny n and z.
    return clamp(ff * ((z - nn) / max(z * (ff - nn), RK_FLT_MIN)), -RK_FLT_MAX, RK_FLT_MAX);
}

/// rk_sh_cube_ref_distance: the compare value of v for a cube map that stores linear distance,
/// (|v| - n) / (f - n) (rk_paraboloid_depth_encode of rk_sh_omni_distance): the "distance compare"
/// of cube shadow maps, where the fragment shader writes the same expression of its own v. Unlike
/// the window depth it has the same precision at every distance and one value per point whatever
/// the face (a receiver on a face edge compares alike in both faces). n = 0 gives the common
/// |v| / f. Domain: 0 <= n < f (both clamped to [0, 1e18]); |v| below n gives a negative value
/// (lit), beyond f above 1. Edge cases (finite): n >= f floors the range at 1e-18 (results clamped
/// to +-1e6); v = 0 gives -n / (f - n); NaN counts as 0, +-Inf as +-RK_FLT_MAX.
/// Max error against float64: 1.9 ulp of the result plus 2.3 ulp of |v| / (f - n) (the distance's
/// rounding; relative error is unbounded where |v| nears n) (1e7 random + refinement). Cost: rk_sh_omni_distance + 1 div, 2 flops.
RK_INLINE float rk_sh_cube_ref_distance(vec3 v, float n, float f)
{
    return rk_paraboloid_depth_encode(rk_sh_omni_distance(v), rk_sh_finite(n), rk_sh_finite(f));
}

/// rk_sh_cube_texel_world: the width, in world units, of the cube-map texel v falls in, measured
/// across the ray at v's distance, along the texel's longer side: 2 z / N for z the major-axis
/// component max(|v.x|, |v.y|, |v.z|) and N = face_size texels. Exact for the perspective of the
/// face (the gnomonic projection's angular scales at face coordinates (s, t), r = sqrt(1 + s^2 +
/// t^2), are 1/r and 1/r^2 per unit of face, and the distance is r z): 2 d / N at a face centre
/// (d = |v|), the largest for a given d, and at a corner 2 d / (sqrt(3) N) = 1.15 d / N along the
/// longer side, 2 d / (3 N) along the shorter: cube texels are smaller, and anisotropic, towards
/// the corners. The unit of biases for a point light (see above). Domain: face_size clamped to
/// [1, 2^24], z to 1e18; NaN counts as 0, +-Inf as +-RK_FLT_MAX. Max error: 0.5 ulp (one rounding).
/// Cost: 3 abs, 2 max, 1 div, 1 mul.
RK_INLINE float rk_sh_cube_texel_world(vec3 v, float face_size)
{
    float z = min(rk_paraboloid_max_abs(rk_sh_finite3(v)), RK_PARABOLOID_POS_MAX);
    float n = clamp(rk_sh_finite(face_size), 1.0f, 16777216.0f);
    return 2.0f * z / n;
}

/// rk_sh_dp_lookup: where to read a dual-paraboloid shadow atlas for light-relative v and what to
/// compare: (u, v) = rk_dual_paraboloid_uv(v, guard_scale) (the half by the sign of v.z, -0 and
/// denormals to the +z half) and the linear-distance depth rk_paraboloid_depth_encode(|v|, n, f),
/// which the atlas must store (Brabec et al. 2002). Pass (u, v, depth) to a sampler2DShadow
/// (compare LEQUAL). With guard_scale from rk_dual_paraboloid_guard_scale(H, footprint of the
/// filter), every tap of a bilinear compare stays in v's half, and taps past the rim read the
/// continuation texels the baker stored there, so receivers on the seam (v.z near 0) compare
/// correctly from either half. Domain: any finite v (|v| capped at 1e18), 0 <= n < f, guard_scale
/// in [RK_PARABOLOID_GUARD_MIN, 1] (clamped). Edge cases (finite): v = 0 reads the centre of the
/// +z half with depth -n / (f - n) (lit); n >= f as rk_sh_cube_ref_distance; NaN counts as 0,
/// +-Inf as +-RK_FLT_MAX. Max error: 1.2e-7 in uv (1e7 random + refinement), the depth as
/// rk_sh_cube_ref_distance. Cost: rk_dual_paraboloid_uv + rk_sh_omni_distance + 1 div, 2 flops.
RK_INLINE vec3 rk_sh_dp_lookup(vec3 v, float n, float f, float guard_scale)
{
    vec3 w = rk_sh_finite3(v);
    vec2 uv = rk_dual_paraboloid_uv(w, rk_sh_finite(guard_scale));
    float depth = rk_paraboloid_depth_encode(rk_sh_omni_distance(w), rk_sh_finite(n), rk_sh_finite(f));
    return vec3(uv.x, uv.y, depth);
}

/// rk_sh_dp_texel_world: the width, in world units, of the dual-paraboloid texel v falls in,
/// across the ray at v's distance: |v| rk_paraboloid_texel_angle(st, H, g) =
/// 4 |v| / ((1 + s^2 + t^2) g H) for st the paraboloid coordinates of v in its half: the same in
/// every direction across the ray (the map is conformal), 4 |v| / (g H) at the pole (v along +-z),
/// the largest, and half that on the rim (the seam). With the cube's texel count (2 H^2 = 6 N^2,
/// H = sqrt(3) N) that is 2.31 |v| / (g N) at the poles against the cube's 2 |v| / N at its face
/// centres, and 1.15 |v| / (g N) at the seam. The unit of biases (see above). Domain: half_size
/// clamped to [1, 2^24], guard_scale to [RK_PARABOLOID_GUARD_MIN, 1], |v| to 1e18; NaN counts as
/// 0, +-Inf as +-RK_FLT_MAX; v = 0 gives 0. Max error: 7.4 ulp against float64 (1e7 random +
/// refinement). Cost: rk_paraboloid_encode + rk_sh_omni_distance + 2 div, ~8 flops.
RK_INLINE float rk_sh_dp_texel_world(vec3 v, float half_size, float guard_scale)
{
    vec3 w = rk_sh_finite3(v);
    vec2 st = rk_paraboloid_encode(w, rk_dual_paraboloid_hemi(w));
    return rk_sh_omni_distance(w) * rk_paraboloid_texel_angle(st, rk_sh_finite(half_size), rk_sh_finite(guard_scale));
}

#endif  // RK_SHADOW_GLSL
