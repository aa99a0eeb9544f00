// raykit — envmap_correction.glsl: reflection-vector correction for environment maps captured at a
// finite distance ("parallax correction"): Brennan's sphere, the thesis's street-plane
// approximation with its sigmoid, the exact ray-plane correction, and the box projection.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/envmap_correction.hpp.
// Source: Fahlén 2005, "Illumination for Real-Time Rendering of Large Architectural Environments",
// §3.2.4 "Accurate Reflections" (Brennan, ShaderX 2002: R' = R + CP / r; the plane at d = 8 m whose
// hypotenuse is d / (N·R); the sigmoid with a = -4.7, k = 0.9, whose x the thesis leaves unstated:
// the angle between N and R in radians fits its description; the un-tweaked plane model is exactly
// a ray-plane parallax correction); Bjorke, GPU Gems ch. 19
// (2004) and Lagarde & Zanuttini, "Local image-based lighting with parallax-corrected cubemap"
// (SIGGRAPH 2012) for the box projection.
//
// Conventions, used by every function here:
//   R   the reflection vector (direction of the reflected ray), e.g. reflect(-to_eye, N).
//   P   the shaded surface point; C the centre the environment map was captured from;
//       CP = P - C. All in one space (world, or the box's local space for an oriented box).
//   N   the unit normal of the reflector (a window), pointing out of the building, towards the
//       reflected surroundings.
// The corrected vectors are directions for a cube-map or paraboloid lookup and are NOT unit
// length (both lookups normalise; rk_paraboloid_encode accepts any length). The exact corrections
// return the vector from C to the hit point H (times a positive factor where documented), so
// C + result is on the plane or the box.
// Positions and vectors are clamped component-wise to ±RK_ENVMAP_POS_MAX (1e18), which keeps
// every product finite: every function returns finite values for every finite input, including
// grazing reflections (N·R = 0), zero vectors, denormals and ±0.
//
// @rk-es 310
// @rk-es300
#ifndef RK_ENVMAP_CORRECTION_GLSL
#define RK_ENVMAP_CORRECTION_GLSL

#include "common.glsl"

// The thesis's constants (§3.2.4): the sigmoid's slope a and midpoint k (radians), and the
// distance d to the plane of the facades across the street (metres, the model's street width).
#define RK_ENVMAP_FAHLEN_A (-4.7f)
#define RK_ENVMAP_FAHLEN_K 0.9f
#define RK_ENVMAP_FAHLEN_D 8.0f
#define RK_ENVMAP_POS_MAX 1.0e18f

/// rk_envmap_clamp_pos: v clamped component-wise to ±RK_ENVMAP_POS_MAX. Exact. Cost: 1 clamp.
RK_INLINE vec3 rk_envmap_clamp_pos(vec3 v)
{
    return clamp(v, vec3(-RK_ENVMAP_POS_MAX), vec3(RK_ENVMAP_POS_MAX));
}

/// rk_envmap_normalize: v / |v| for any finite v without overflow or underflow (components are
/// first scaled by the largest |component|, brought below 2.7e8 by the exact factor 2^-100 so that
/// its reciprocal is a normal float); `fallback` when every |component| is below RK_FLT_MIN.
/// Result components below RK_FLT_MIN (over 2^126 times smaller than the largest) are 0, as a GPU
/// that flushes subnormals makes them. Max error: 3.8 ulp per component against float64 (4e7
/// random + refinement), plus that flush. Cost: 7 max/abs, 3 select, 1 div, 1 dot, 1 rsqrt.
RK_INLINE vec3 rk_envmap_normalize(vec3 v, vec3 fallback)
{
    float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    if (m < RK_FLT_MIN) {
        return fallback;
    }
    float pre = m > 1.0e30f ? 7.8886090522101181e-31f : 1.0f;
    vec3 q = (v * pre) / (m * pre);
    return rk_flush_subnormal(q * inversesqrt(dot(q, q)));
}

/// rk_envmap_angle: the angle in [0, π] radians whose cosine is cos_nr (clamped to [-1, 1]),
/// evaluated as atan(sqrt(1 - c^2), c): GLSL leaves acos's precision to the driver (Mesa's asin
/// is 4e-4 rad off, see fresnel.glsl), atan agrees to 4e-6. Max error: 4e-6 rad on llvmpipe,
/// 2.3 ulp on the CPU (every 4th float in [-1, 1] + refinement). Cost: 1 sqrt, 1 atan.
RK_INLINE float rk_envmap_angle(float cos_nr)
{
    float c = clamp(cos_nr, -1.0f, 1.0f);
    return atan(sqrt((1.0f - c) * (1.0f + c)), c);
}

/// rk_envmap_sigmoid: the thesis's logistic weight σ(x) = 1 / (1 + e^(-a (x - k))). With the
/// thesis's a = -4.7, k = 0.9 and x the angle between N and R in radians (x is unstated there):
/// σ(0) = 0.98566, σ(0.5) = 0.8676, σ(0.9) = 0.5, σ(1.2) = 0.1962, σ(π/2) = 0.04098, i.e. close to
/// cos x at small angles and closer to cos^2 x towards grazing. Domain: x, a, k clamped to ±1e6,
/// the exponent to ±80 (σ stays in [1.8e-35, 1]). Max error: that of the driver's exp; on the CPU
/// ~1.2e-7 (1 + |a (x - k)|) relative, the rounding of x - k amplified by the exponent (1.2e-6
/// for the thesis a, k on [0, π]; dense x + 2e7 random + refinement). Cost: 1 exp, 1 div, 3 flops.
RK_INLINE float rk_envmap_sigmoid(float x, float a, float k)
{
    float xc = clamp(x, -1.0e6f, 1.0e6f);
    float ac = clamp(a, -1.0e6f, 1.0e6f);
    float kc = clamp(k, -1.0e6f, 1.0e6f);
    float e = clamp(-ac * (xc - kc), -80.0f, 80.0f);
    return 1.0f / (1.0f + exp(e));
}

/// rk_envmap_fahlen_weight: σ(angle(N, R)) = rk_envmap_sigmoid(rk_envmap_angle(cos_nr), a, k),
/// the thesis's replacement for N·R in the plane correction. cos_nr = dot(N, R) for unit vectors.
/// Domain: cos_nr clamped to [-1, 1]; a, k as rk_envmap_sigmoid. With the thesis's a, k:
/// cos_nr = 1 gives σ(0) = 0.98566, 0 (grazing) σ(π/2) = 0.04098, -1 σ(π) = 2.66e-5: positive and
/// decreasing over the whole range, never 0.
/// Max error vs float64 σ(acos(cos_nr)) at the float cos_nr: 1.9e-7 absolute on the CPU (thesis
/// a, k; every 4th float + refinement; tests/test_envmap_correction.cpp SigmoidPublishedValues
/// asserts 1e-6); on llvmpipe the driver's atan adds up to 2.8e-6 (a in [-8, 8]; GPU parity).
/// Near cos_nr = 1 acos is ill-conditioned: a rounding δ of cos_nr (6e-8 for a float dot of unit
/// vectors) moves the angle by up to sqrt(2 δ) = 3.5e-4 rad, the weight by up to 2.3e-5
/// (|σ'(0)| = 0.066).
/// Cost: 1 sqrt, 1 atan, 1 exp, 1 div, ~6 flops, 5 clamps.
RK_INLINE float rk_envmap_fahlen_weight(float cos_nr, float a, float k)
{
    return rk_envmap_sigmoid(rk_envmap_angle(cos_nr), a, k);
}

/// rk_reflect_correct_sphere: Brennan's correction for an environment at a finite radius r around
/// C: R' = R + CP / r (from R' = R r + CP; exact for a sphere of radius r only when |CP| << r).
/// Works when the reflected objects are at a roughly constant distance; fails for a street
/// (thesis). R should be unit. r clamped to [1e-18, 1e18], vectors to ±RK_ENVMAP_POS_MAX.
/// Exact (2 roundings per component). Cost: 1 div, 3 fma.
RK_INLINE vec3 rk_reflect_correct_sphere(vec3 r_dir, vec3 cp, float radius)
{
    float inv_r = 1.0f / clamp(radius, 1.0e-18f, 1.0e18f);
    return rk_envmap_clamp_pos(r_dir) + rk_envmap_clamp_pos(cp) * inv_r;
}

/// rk_reflect_correct_plane_cos: the thesis's un-tweaked plane model: Brennan's correction with the
/// radius replaced by the hypotenuse d / (N·R) to a plane parallel to the window at distance d:
/// R' = R + CP (N·R) / d. Equal in direction to the exact ray-plane correction
/// (rk_reflect_correct_plane) when P lies in the plane through C parallel to the window (CP·N = 0).
/// Artefacts at grazing angles (thesis); see rk_reflect_correct_fahlen.
/// Domain: R, N unit (dot(N, R) is used as the cosine as it is); N·R clamped to [0, 1], d to
/// [1e-18, 1e18], vectors to ±RK_ENVMAP_POS_MAX: finite for every finite input. Edge cases: R
/// parallel to or behind the window (N·R < RK_FLT_MIN) and CP = 0 return R exactly.
/// Max error vs float64 R + CP max(N·R, 0) / d: 4.4e-7 of |R| + |CP| N·R / d (relative to the
/// terms because R' itself cancels to 0 where CP N·R / d = -R; 2e7 random unit R, N, |CP| <= 50 +
/// refinement; tests/test_envmap_correction.cpp FahlenIsThePlaneModelWithSigmaForCos asserts 1e-6).
/// Cost: 1 dot, 1 div, 3 mul, 3 add, 5 clamps, 1 select.
RK_INLINE vec3 rk_reflect_correct_plane_cos(vec3 r_dir, vec3 n, vec3 cp, float d)
{
    vec3 r = rk_envmap_clamp_pos(r_dir);
    float c = clamp(dot(rk_envmap_clamp_pos(n), r), 0.0f, 1.0f);
    c = c < RK_FLT_MIN ? 0.0f : c;  // a subnormal cosine is 0, as on a flushing GPU
    return r + rk_envmap_clamp_pos(cp) * (c / clamp(d, 1.0e-18f, 1.0e18f));
}

/// rk_reflect_correct_fahlen: the thesis's correction (§3.2.4), the plane model with N·R replaced
/// by the sigmoid of the angle between N and R: R' = R + CP σ(angle(N, R)) / d, with parameters a,
/// k (thesis: RK_ENVMAP_FAHLEN_A = -4.7, RK_ENVMAP_FAHLEN_K = 0.9, d = RK_ENVMAP_FAHLEN_D = 8 m).
/// An empirical fix of the grazing artefacts of rk_reflect_correct_plane_cos (and of a "tilted
/// ground" when C is far above the camera); not exact for any geometry.
/// Relation to rk_reflect_correct_plane_cos (same d): the same offset along CP, scaled by
/// σ(x) / cos x (thesis a, k: 0.9857 at x = 0, below 1 up to 87.04° = 1.519 rad, above beyond).
/// Unlike it, the weight does not vanish at grazing (σ(π/2) = 0.04098) and keeps decreasing
/// behind the window (N·R < 0, down to σ(π) = 2.66e-5), where plane_cos returns R.
/// Domain: R, N unit (dot(N, R) is clamped to [-1, 1] and used as the cosine); d clamped to
/// [1e-18, 1e18], a and k as rk_envmap_sigmoid, vectors to ±RK_ENVMAP_POS_MAX: finite for every
/// finite input. CP = 0 returns R.
/// Max error vs float64 R + CP σ(acos(N·R)) / d, relative to |R| + |CP| σ / d (R' itself can
/// cancel to 0), random unit R, N and |CP| <= 50 m (2e7 each + refinement): 5.0e-7 with the
/// thesis's constants; with d in [2, 40], a in [-8, -1], k in [0.3, 1.5], 1.6e-6 for angles in
/// [0.05, π - 0.05] (acos is ill-conditioned near π: up to 8.3e-5 there). Near normal incidence
/// (angle < 0.05 rad) the rounding of the float N·R dominates (see rk_envmap_fahlen_weight):
/// 2.7e-5 (thesis constants), 3.0e-4 (a down to -8), and 1.7e-7 against float64 at the float N·R
/// (tests/test_envmap_correction.cpp FahlenMatchesFloat64ThesisFormula prints the worst inputs).
/// Cost: 1 dot, 1 sqrt, 1 atan, 1 exp, 2 div, ~17 flops, 9 clamps.
RK_INLINE vec3 rk_reflect_correct_fahlen(vec3 r_dir, vec3 n, vec3 cp, float d, float a, float k)
{
    vec3 r = rk_envmap_clamp_pos(r_dir);
    float w = rk_envmap_fahlen_weight(dot(rk_envmap_clamp_pos(n), r), a, k);
    return r + rk_envmap_clamp_pos(cp) * (w / clamp(d, 1.0e-18f, 1.0e18f));
}

/// rk_reflect_correct_fahlen (thesis constants): a = -4.7, k = 0.9, d = 8 m; bit-identical to the
/// 6-argument form with those values. Example: N = +z, R = (0.6, 0, 0.8), CP = (8, -16, 4) give
/// σ(acos 0.8) = 0.76951 and R' = (1.36951, -1.53902, 1.18475). Domain, edge cases, max error
/// (5.0e-7 of |R| + |CP| σ / d; 2.7e-5 within 0.05 rad of normal incidence) and cost as above.
RK_INLINE vec3 rk_reflect_correct_fahlen(vec3 r_dir, vec3 n, vec3 cp)
{
    return rk_reflect_correct_fahlen(r_dir, n, cp, RK_ENVMAP_FAHLEN_D, RK_ENVMAP_FAHLEN_A, RK_ENVMAP_FAHLEN_K);
}

/// rk_reflect_correct_plane: the exact ray-plane parallax correction. The reflected surroundings
/// are the plane {X : (X - C)·N = d} (N towards them, d > 0 its distance from C); the reflected ray
/// P + t R hits it at H with t = (d - CP·N) / (R·N), and the environment is looked up towards H -
/// C. Returned as (H - C)(R̂·N) = CP (R̂·N) + (d - CP·N) R̂ (R̂ = R normalised), which needs no
/// division: at grazing reflections (R·N -> 0) it tends continuously to a multiple of R (the hit
/// recedes to infinity) instead of dividing by zero. Rays leaving the plane (R·N <= 0) return a
/// multiple of R (hit at infinity; so do R·N below RK_FLT_MIN); P on or beyond the plane returns CP
/// (R̂·N) (H = P). When the result would be zero (R = 0 or both cases at once) R is returned. With
/// CP·N = 0 the direction equals the thesis's plane model rk_reflect_correct_plane_cos. N is
/// normalised internally (N = 0 counts as +z); R any non-zero length. Max error: the hit C + result
/// / (R̂·N) lies on the plane to ~1.2e-7 |CP·N| / (R̂·N |H - C|) of its distance from C, the
/// rounding of R̂·N (4.9e-5 for R̂·N >= 1e-3, P near the plane, in the test's set-up: 2e7 random +
/// refinement; tests/test_envmap_correction.cpp prints it). Cost: 2 normalisations, 2 dot, 6 fma.
RK_INLINE vec3 rk_reflect_correct_plane(vec3 r_dir, vec3 p, vec3 c, vec3 n, float d)
{
    vec3 r = rk_envmap_normalize(r_dir, vec3(0.0f));
    vec3 nn = rk_envmap_normalize(n, vec3(0.0f, 0.0f, 1.0f));
    vec3 cp = rk_envmap_clamp_pos(p) - rk_envmap_clamp_pos(c);
    float w = dot(r, nn);
    w = w >= RK_FLT_MIN ? w : 0.0f;  // a subnormal cosine is 0, as on a flushing GPU
    float h = max(clamp(d, -RK_ENVMAP_POS_MAX, RK_ENVMAP_POS_MAX) - dot(cp, nn), 0.0f);
    vec3 v = cp * w + h * r;
    float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    return m < RK_FLT_MIN ? rk_envmap_clamp_pos(r_dir) : v;
}

/// rk_reflect_correct_box: the box-projected (local, parallax-corrected) cube-map lookup of
/// Lagarde & Zanuttini 2012 / Bjorke 2004: the reflected ray P + t R̂ leaves the axis-aligned box
/// [box_min, box_max] (the proxy of the room or street the map was captured in, containing P) at
/// H, and the map is looked up towards H - C, which is returned exactly: C + result lies on the box
/// surface. For an oriented box transform R, P, C into its frame first. Per axis the exit distance
/// is (face - P) / |R̂_i| with |R̂_i| floored at 1e-18 (an axis the ray runs parallel to never
/// wins), so grazing and axis-aligned rays need no special case. P outside the box (or on a face
/// it is leaving through) returns CP (H = P); R = 0 returns CP. Box corners are clamped to
/// ±RK_ENVMAP_POS_MAX and box_max to >= box_min. Max error: H on the box to 1e-6 relative to the
/// box size; exact for axis-aligned rays. Cost: 1 normalisation, 3 div, ~20 flops.
RK_INLINE vec3 rk_reflect_correct_box(vec3 r_dir, vec3 p, vec3 c, vec3 box_min, vec3 box_max)
{
    vec3 r = rk_envmap_normalize(r_dir, vec3(0.0f));
    vec3 pc = rk_envmap_clamp_pos(p);
    vec3 lo = rk_envmap_clamp_pos(box_min);
    vec3 hi = max(rk_envmap_clamp_pos(box_max), lo);
    // Exit face per axis; a zero or denormal component (flushed by GPUs) counts as positive.
    vec3 dist = vec3(r.x > -RK_FLT_MIN ? hi.x - pc.x : pc.x - lo.x, r.y > -RK_FLT_MIN ? hi.y - pc.y : pc.y - lo.y,
                     r.z > -RK_FLT_MIN ? hi.z - pc.z : pc.z - lo.z);
    vec3 t3 = max(dist, vec3(0.0f)) / max(abs(r), vec3(1.0e-18f));
    float t = min(min(t3.x, t3.y), t3.z);
    return (pc - rk_envmap_clamp_pos(c)) + t * r;
}

#endif  // RK_ENVMAP_CORRECTION_GLSL
