// raykit — fresnel.glsl: Fresnel reflectance for dielectrics, conductors and window glass.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/fresnel.hpp.
// Source: Fahlén 2005, "Illumination for Real-Time Rendering of Large Architectural
// Environments", §3.1.1 (Fresnel, Schlick) and §3.1.2 (multiple reflections in a pane, Eq. 3.7-3.8);
// corrections to the thesis (cos form instead of its sin/tan form, which is 0/0 at normal incidence;
// per-polarisation slab; TIR at 41.14° for n = 1.52, where the thesis says about 41.8°).
//
// Conventions, used by every function here:
//   cos_i  cosine of the angle between the surface normal and the direction towards the viewer
//          (or light), on the side the light arrives from. Clamped to [0, 1]: a caller whose
//          normal faces away passes abs(dot) and the matching eta.
//   eta    relative index of refraction n_t / n_i (transmitted over incident side): 1.52 for
//          air -> glass, 1/1.52 for glass -> air. Clamped to [RK_FRESNEL_ETA_MIN, RK_FRESNEL_ETA_MAX].
//          NOTE: GLSL's built-in refract() takes the inverse ratio n_i / n_t; rk_refract takes eta.
// Every function returns finite values for every finite input (denormals, ±0, huge values).
// Errors quoted are against the float64 formulas in tests/reference/fresnel_ref.hpp, measured by
// tests/test_fresnel.cpp and bench/bench_fresnel.cpp (docs/benchmarks.md).
//
// Feature macros:
//   RK_FRESNEL_WINDOW_MODE  which reflectance rk_fresnel_window() returns (default 2):
//                           0 single surface, exact;  1 the thesis's slab 2R/(1+R) applied to the
//                           polarisation average (Eq. 3.8);  2 slab applied per polarisation
//                           (physically right order);  3 N panes per polarisation.
//
// @rk-es 310
// @rk-es300
// @rk-variants RK_FRESNEL_WINDOW_MODE=0 | RK_FRESNEL_WINDOW_MODE=1 | RK_FRESNEL_WINDOW_MODE=2 | RK_FRESNEL_WINDOW_MODE=3
#ifndef RK_FRESNEL_GLSL
#define RK_FRESNEL_GLSL

#ifdef __cplusplus
#define RK_NS_FRESNEL_WINDOW RK_PP_CAT(fresnel_window_mode, RK_FRESNEL_WINDOW_MODE)
#endif

#include "common.glsl"

#ifndef RK_FRESNEL_WINDOW_MODE
#define RK_FRESNEL_WINDOW_MODE 2
#endif
#if RK_FRESNEL_WINDOW_MODE < 0 || RK_FRESNEL_WINDOW_MODE > 3
#error "RK_FRESNEL_WINDOW_MODE must be 0 (single surface), 1 (thesis slab), 2 (per-polarisation slab) or 3 (N panes)"
#endif
RK_OPTION_CHECK(rk_option_fresnel_window_mode, RK_FRESNEL_WINDOW_MODE);

#define RK_FRESNEL_ETA_MIN 0.000244140625f  // 1/4096
#define RK_FRESNEL_ETA_MAX 4096.0f
// Extinction coefficients below this (2^-60) count as 0 in rk_fresnel_conductor: their square
// would be subnormal, which GPUs flush to zero.
#define RK_FRESNEL_K_MIN 8.673617379884035e-19f

/// rk_fresnel_clamp_eta: eta clamped to [1/4096, 4096], the domain of every function here.
/// Cost: 1 clamp.
RK_INLINE float rk_fresnel_clamp_eta(float eta)
{
    return clamp(eta, RK_FRESNEL_ETA_MIN, RK_FRESNEL_ETA_MAX);
}

/// rk_f0_from_ior: reflectance at normal incidence ((n1 - n2) / (n1 + n2))^2 between media of
/// indices n1 and n2. Domain: n1, n2 > 0 (clamped to [RK_FLT_MIN, 1e30]).
/// Max error: 5.5 ulp (9e7 random (n1, n2) + refinement). Cost: 1 add, 1 sub, 1 div, 1 clamp,
/// 1 mul. F0(1, 1.52) = 0.0425800. Range [0, 1] (the ratio is clamped: a driver's division may
/// be 2.5 ulp off, NVIDIA's gave 1.0000002 for n1 = 1e20).
RK_INLINE float rk_f0_from_ior(float n1, float n2)
{
    float a = clamp(n1, RK_FLT_MIN, 1e30f);
    float b = clamp(n2, RK_FLT_MIN, 1e30f);
    return rk_sqr(clamp((a - b) / (a + b), -1.0f, 1.0f));
}

/// rk_f0_from_eta: F0 for a relative index eta = n_t / n_i: ((eta - 1) / (eta + 1))^2.
/// Domain: eta >= 0 (clamped to [0, 1e30]). Max error: 4.5 ulp (every 4th float in [0, 1e30] +
/// refinement). Cost: 1 div, 4 flops. Range [0, 1] (ratio clamped, as in rk_f0_from_ior).
RK_INLINE float rk_f0_from_eta(float eta)
{
    float e = clamp(eta, 0.0f, 1e30f);
    return rk_sqr(clamp((e - 1.0f) / (e + 1.0f), -1.0f, 1.0f));
}

/// rk_eta_from_f0: the relative index eta >= 1 whose F0 is f0 (inverse of rk_f0_from_eta on its
/// external branch): (1 + sqrt(F0)) / (1 - sqrt(F0)). Domain: f0 in [0, 1), clamped to
/// [0, 0.9999990]; f0 -> 1 gives eta ~ 4e6 instead of inf. Max error: 2.7 ulp for f0 <= 0.5;
/// within 8 + kappa ulp, kappa = sqrt(f0) / (1 - f0) the conditioning of the inverse near f0 = 1
/// (every 4th float + refinement). Cost: 1 sqrt, 1 div.
RK_INLINE float rk_eta_from_f0(float f0)
{
    float s = sqrt(clamp(f0, 0.0f, 0.9999990f));
    return (1.0f + s) / (1.0f - s);
}

/// rk_fresnel_schlick: Schlick's approximation F0 + (1 - F0)(1 - cos)^5 (thesis Eq. 3.6).
/// Domain: cos_i and f0 clamped to [0, 1]. Error vs the exact dielectric: 0.0345 max for glass
/// n = 1.52 (near 85°), 0.060 for water (1.33); exact at 0° and 90°. Max error vs float64 of its own
/// formula: 3.4e-7 at small cos (the rounding of 1 - cos, x5 through the fifth power; dense cos
/// sweeps for 7 f0 + 6e7 random (cos, f0) + refinement). Cost: 5 flops, no division.
RK_INLINE float rk_fresnel_schlick(float cos_i, float f0)
{
    float f = rk_saturate(f0);
    return f + (1.0f - f) * rk_pow5(1.0f - rk_saturate(cos_i));
}

/// rk_fresnel_schlick (RGB F0): per-channel Schlick, e.g. for metals' F0 colour.
/// Same domain, error and cost (x3 lanes) as the scalar form: each channel is the scalar form's
/// arithmetic, bit for bit (max error vs float64 3.4e-7).
RK_INLINE vec3 rk_fresnel_schlick(float cos_i, vec3 f0)
{
    vec3 f = clamp(f0, vec3(0.0f), vec3(1.0f));
    return f + (vec3(1.0f) - f) * rk_pow5(1.0f - rk_saturate(cos_i));
}

/// rk_fresnel_schlick (with f90): F0 + (F90 - F0)(1 - cos)^5, the generalisation used for
/// specular occlusion / energy terms. f0, f90 and cos_i clamped to [0, 1]; f90 = 1 gives the
/// two-argument form bit for bit; f90 < f0 is allowed (reflectance falls toward grazing).
/// Max error vs float64: 3.1e-7 (6e7 random (cos, f0, f90) + refinement). Cost: 5 flops.
RK_INLINE float rk_fresnel_schlick(float cos_i, float f0, float f90)
{
    float a = rk_saturate(f0);
    return a + (rk_saturate(f90) - a) * rk_pow5(1.0f - rk_saturate(cos_i));
}

/// rk_fresnel_schlick (RGB F0 and F90): the f90 form per channel, bit for bit; same domain and
/// max error (3.1e-7 vs float64). Cost: 5 flops x3 lanes.
RK_INLINE vec3 rk_fresnel_schlick(float cos_i, vec3 f0, vec3 f90)
{
    vec3 a = clamp(f0, vec3(0.0f), vec3(1.0f));
    vec3 b = clamp(f90, vec3(0.0f), vec3(1.0f));
    return a + (b - a) * rk_pow5(1.0f - rk_saturate(cos_i));
}

/// rk_fresnel_dielectric_sp: exact reflectances (Rs, Rp) of the s- and p-polarised components at
/// a smooth dielectric interface, and (1, 1) under total internal reflection.
/// Written in the cancellation-free cos form: with g^2 = eta^2 - sin^2 = eta^2 - 1 + cos^2,
///   rs = (1 - eta^2) / (cos + g)^2,   rp = (eta^2 - 1)(eta^2 cos^2 - sin^2) / (eta^2 cos + g)^2,
/// g^2 formed as eta^2 - sin^2 near normal incidence and as (eta^2 - 1) + cos^2 elsewhere, so it
/// holds over the whole eta domain [1/4096, 4096] (the single form lost Rp at eta << 1, cos ~ 1),
/// which is algebraically the textbook (cos_i - eta cos_t)/(cos_i + eta cos_t) pair but has no
/// 0/0 at normal incidence and keeps full relative precision at matched indices (eta -> 1), where
/// it returns exactly 0 (including the grazing limit cos = 0, eta = 1).
/// Domain: all finite cos_i, eta (see the file header). Max error vs float64, external reflection:
/// 8.5e-7 absolute for eta = 1.52 (every 4th cos float + refinement; mean 2.9e-8), 9.5e-7 for any
/// eta > 1 (6e7 random + refinement). Near the critical angle of internal reflection R is
/// infinitely steep in cos, so the error at a given float input grows to 3.7e-3 there (3.6e-4 for
/// glass -> air); measured against the float64 range over cos +- 1 ulp (the input's own rounding)
/// it stays below 1.5e-6 (tests/test_fresnel.cpp prints the worst input).
/// Cost: 1 sqrt, 2 div, ~14 flops.
/// TIR: when eta < 1 and cos_i < sqrt(1 - eta^2), i.e. above rk_critical_angle(eta).
RK_INLINE vec2 rk_fresnel_dielectric_sp(float cos_i, float eta)
{
    float c = rk_saturate(cos_i);
    float e = rk_fresnel_clamp_eta(eta);
    float e2 = e * e;
    RK_PRECISE float e2m1 = (e - 1.0f) * (e + 1.0f);  // eta^2 - 1 without cancellation near eta = 1
    RK_PRECISE float s2 = (1.0f - c) * (1.0f + c);    // sin^2 without cancellation near normal incidence
    // g^2 = eta^2 - sin^2, formed where it does not cancel: near normal incidence (small sin^2)
    // as eta^2 - sin^2 (eta^2 - 1 + cos^2 would subtract ~1 from ~1 for small eta), elsewhere as
    // (eta^2 - 1) + cos^2 (exact at matched indices).
    RK_PRECISE float g2 = s2 < 0.5f ? e2 - s2 : e2m1 + c * c;
    if (g2 < 0.0f) {
        return vec2(1.0f);  // total internal reflection
    }
    float g = sqrt(g2);
    float rs = -e2m1 / max(rk_sqr(c + g), RK_FLT_MIN);
    // (eta^2 + 1) cos^2 - 1 = eta^2 cos^2 - sin^2: no 1 - 1 near normal incidence.
    float rp = e2m1 * (e2 * c * c - s2) / max(rk_sqr(e2 * c + g), RK_FLT_MIN);
    return vec2(min(rs * rs, 1.0f), min(rp * rp, 1.0f));
}

/// rk_fresnel_dielectric: exact unpolarised reflectance (Rs + Rp) / 2 of a smooth dielectric
/// interface; 1 under total internal reflection. Same domain, error and cost as
/// rk_fresnel_dielectric_sp. F(cos 0°, 1.52) = 0.0425800, F(cos 85°, 1.52) = 0.61492.
RK_INLINE float rk_fresnel_dielectric(float cos_i, float eta)
{
    vec2 r = rk_fresnel_dielectric_sp(cos_i, eta);
    return 0.5f * (r.x + r.y);
}

/// rk_fresnel_fast_params: per-material constants for rk_fresnel_dielectric_fast:
/// (eta^2, g0 = sqrt(eta^2 - 1), eta - g0). Compute once per material (CPU uniform, or a
/// constant the shader compiler folds). eta is clamped to [1, RK_FRESNEL_ETA_MAX]: the fast form
/// is for external reflection only. Cost: 1 sqrt.
RK_INLINE vec3 rk_fresnel_fast_params(float eta)
{
    float e = clamp(eta, 1.0f, RK_FRESNEL_ETA_MAX);
    float g0 = sqrt((e - 1.0f) * (e + 1.0f));
    return vec3(e * e, g0, e - g0);
}

/// rk_fresnel_dielectric_fast: unpolarised dielectric reflectance for external reflection
/// (eta >= 1) with the per-pixel square root replaced by its chord: g(cos) = sqrt(eta^2-1+cos^2)
/// ~ g0 + (eta - g0) cos^2, which is exact at 0° and 90° (so F0 and the grazing 1 are exact),
/// then the textbook rs, rp fused over one division.
/// Max abs error vs exact (measured over cos in [0,1]): 1.7e-3 for eta = 1.52 (Schlick: 3.45e-2),
/// 3.7e-3 for 1.33 (Schlick: 6.0e-2), 3.5e-4 for 2.0, 1.4e-2 for 1.1 (Schlick: 0.22); it grows
/// without bound as eta -> 1: at eta = 1 the chord gives ((1 - cos) / (1 + cos))^2 (0.67 at cos
/// 0.1) for cos > ~1e-10, where the exact reflectance is 0. Range [0, 1] for every input.
/// Cost: 1 div + ~16 flops, no sqrt (params precomputed). Domain: cos_i clamped to [0, 1];
/// params from rk_fresnel_fast_params. Never NaN: the denominator is floored.
RK_INLINE float rk_fresnel_dielectric_fast(float cos_i, vec3 params)
{
    float c = rk_saturate(cos_i);
    float e2 = params.x;
    float g = params.y + params.z * c * c;
    float a = c + g;
    float b = e2 * c + g;
    float ns = (c - g) * b;   // rs * (a b)
    float np = (e2 * c - g) * a;  // rp * (a b)
    // min: 1 + 2^-23 on a driver that divides by a reciprocal (NVIDIA), 1 at most elsewhere.
    return min(0.5f * (ns * ns + np * np) / max(rk_sqr(a * b), RK_FLT_MIN), 1.0f);
}

/// rk_fresnel_dielectric_fast (eta form): convenience that builds the params inline; costs one
/// sqrt more unless eta is a compile-time constant.
RK_INLINE float rk_fresnel_dielectric_fast(float cos_i, float eta)
{
    return rk_fresnel_dielectric_fast(cos_i, rk_fresnel_fast_params(eta));
}

/// rk_fresnel_dielectric_poly: unpolarised dielectric reflectance for external reflection
/// (eta >= 1) as a per-material polynomial F ~ f0 + (1 - cos) q(cos), q of degree 4 fitted minimax
/// to the exact reflectance; exact at normal incidence (F0). Params p0 = (f0, q0, q1, q2),
/// p1 = (q3, q4) come from the CPU helper rk_fresnel_poly_params (fresnel.hpp), which also returns
/// the fit's measured max error. Max abs error vs exact (float evaluation; every 4th cos float +
/// refinement): 3.4e-3 for eta 1.52 (Schlick 3.45e-2), 3.6e-3 for 1.33 (Schlick 6.0e-2), 4.7e-3 for
/// 2.0, 5.4e-3 for 1.2, 7.2e-3 for 2.5; at most 5.0e-3 for eta in [1.25, 2.05] (every 0.001 +
/// refinement). Cost: 1 add + 5 multiply-adds (Schlick: 5 flops), no division or sqrt. Domain:
/// cos_i clamped to [0, 1]; any finite constants; result in [0, 1] (0 where huge constants overflow
/// to NaN).
RK_INLINE float rk_fresnel_dielectric_poly(float cos_i, vec4 p0, vec2 p1)
{
    float c = rk_saturate(cos_i);
    float q = p0.y + c * (p0.z + c * (p0.w + c * (p1.x + c * p1.y)));
    float r = p0.x + (1.0f - c) * q;
    return r > 0.0f ? min(r, 1.0f) : 0.0f;  // also 0 for the NaN of 0 * inf from huge constants
}

/// rk_fresnel_conductor: exact unpolarised reflectance of a conductor with complex relative index
/// eta + i k per RGB channel (e.g. gold ~ (0.143, 0.374, 1.442) + i (3.983, 2.385, 1.603)).
/// Standard closed form with a^2 + b^2 = |eta^2 - k^2 - sin^2 + 2 i eta k|. With k = 0 it equals
/// rk_fresnel_dielectric for eta >= 1. Domain: cos_i clamped to [0, 1]; eta, k clamped to [0,
/// 4096], and k below RK_FRESNEL_K_MIN (2^-60) counts as 0: k^2 would be subnormal, which a GPU
/// flushes, and with k that small R differs from the k = 0 value only within cos < ~k of grazing
/// (at eta = 1 exactly, where R jumps to 1 at cos = 0). Max error vs the float64 complex-amplitude
/// form (tests/reference/fresnel_ref.hpp; test_fresnel ConductorMatchesFloat64): 2.7e-7 absolute
/// for gold, 2.4e-7 silver, 2.7e-7 copper, 2.4e-7 aluminium (their RGB n, k; every 16th cos float +
/// refinement); over n in [0.1, 3], k in [0, 5], cos in [0, 1], against the float64 range over cos
/// +- 1 ulp (R is infinitely steep at the critical angle for k = 0, n < 1, as for
/// rk_fresnel_dielectric_sp): 4.4e-6, reached for small k > 0 with n < 1 near the critical angle,
/// where R is ill-conditioned (4e7 random + refinement; mean 3.4e-8). a = Re sqrt(z), z = eta^2 -
/// k^2 - sin^2 + 2 i eta k, is computed without the cancellation of (|z| + Re z) / 2 when Re z < 0
/// (that form was 3.3e-6 off at n = k = 0.1); 2e-6 asserted vs rk_fresnel_dielectric over n in
/// [1.2, 2.4], k = 0. Cost: 3 sqrt, 3 div, ~32 flops per channel; on the CPU ~13x Schlick (bench),
/// so use rk_fresnel_dielectric when k = 0.
RK_INLINE vec3 rk_fresnel_conductor(float cos_i, vec3 eta, vec3 k)
{
    float c = rk_saturate(cos_i);
    float c2 = c * c;
    RK_PRECISE float s2 = (1.0f - c) * (1.0f + c);
    vec3 n = clamp(eta, vec3(0.0f), vec3(RK_FRESNEL_ETA_MAX));
    vec3 kk = clamp(k, vec3(0.0f), vec3(RK_FRESNEL_ETA_MAX));
    kk = mix(kk, vec3(0.0f), lessThan(kk, vec3(RK_FRESNEL_K_MIN)));
    vec3 n2 = n * n;
    vec3 k2 = kk * kk;
    // eta^2 - k^2 - sin^2 written as (eta - 1)(eta + 1) - k^2 + cos^2: no cancellation at
    // matched indices near grazing, where 1 - cos^2 rounds to 1.
    RK_PRECISE vec3 t0 = (n - vec3(1.0f)) * (n + vec3(1.0f)) - k2 + vec3(c2);
    vec3 a2b2 = sqrt(t0 * t0 + 4.0f * n2 * k2);
    // a = Re sqrt(z), z = t0 + 2 i eta k: a^2 = (|z| + t0) / 2, which cancels when t0 < 0; there
    // the same value is (Im z)^2 / (2 (|z| - t0)) = 2 eta^2 k^2 / (|z| - t0), cancellation-free.
    vec3 a2_pos = 0.5f * (a2b2 + t0);
    vec3 a2_neg = (2.0f * n2 * k2) / max(a2b2 - t0, vec3(RK_FLT_MIN));
    vec3 a = sqrt(max(mix(a2_pos, a2_neg, lessThan(t0, vec3(0.0f))), vec3(0.0f)));
    vec3 t1 = a2b2 + vec3(c2);
    vec3 t2 = (2.0f * c) * a;
    RK_PRECISE vec3 rs = (t1 - t2) / max(t1 + t2, vec3(RK_FLT_MIN));
    vec3 t3 = c2 * a2b2 + vec3(s2 * s2);
    vec3 t4 = t2 * s2;
    RK_PRECISE vec3 rp = rs * (t3 - t4) / max(t3 + t4, vec3(RK_FLT_MIN));
    return clamp(0.5f * (rs + rp), vec3(0.0f), vec3(1.0f));
}

/// rk_fresnel_conductor (scalar): one channel of the RGB form (same math, 1/3 of the lanes used).
RK_INLINE float rk_fresnel_conductor(float cos_i, float eta, float k)
{
    return rk_fresnel_conductor(cos_i, vec3(eta), vec3(k)).x;
}

/// rk_critical_cos: cosine of the critical angle for eta = n_t / n_i < 1, i.e. sqrt(1 - eta^2);
/// 0 when eta >= 1 (no total internal reflection before grazing). A ray with cos_i below it is
/// totally reflected. Cheaper than comparing angles. Max error: 2 ulp. Cost: 1 sqrt.
RK_INLINE float rk_critical_cos(float eta)
{
    float e = rk_saturate(eta);
    return sqrt((1.0f - e) * (1.0f + e));
}

/// rk_critical_angle: critical angle asin(eta) in radians for eta = n_t / n_i < 1
/// (glass -> air, n = 1.52: 0.718023 rad = 41.1395°); pi/2 when eta >= 1 (no TIR).
/// Evaluated as atan(eta, sqrt(1 - eta^2)): GLSL leaves asin's precision to the driver, and
/// Mesa llvmpipe's asin is off by up to 3.9e-4 rad (tests/gpu parity found it), while atan agrees
/// to 4e-6. Max error: 4e-6 rad on llvmpipe, 2.6 ulp on the CPU (every 4th float + refinement).
/// Cost: 1 sqrt, 1 atan.
RK_INLINE float rk_critical_angle(float eta)
{
    float e = rk_saturate(eta);
    return atan(e, sqrt((1.0f - e) * (1.0f + e)));
}

/// rk_brewster_angle: angle where Rp = 0, atan(eta) in radians (n = 1.52: 0.988898 rad =
/// 56.6593°). Domain: eta clamped to [1/4096, 4096]. Max error: 0.86 ulp (9.2e-8 rad) vs float64
/// atan over the whole domain on the CPU (every 4th float + refinement); GLSL leaves atan's
/// precision to the driver (llvmpipe: 4e-6, see rk_critical_angle). Cost: 1 atan.
RK_INLINE float rk_brewster_angle(float eta)
{
    return atan(rk_fresnel_clamp_eta(eta));
}

/// rk_refract: refraction direction through an interface with relative index eta = n_t / n_i
/// (the inverse of GLSL refract()'s argument). `incident` is the direction of travel and
/// `normal` the unit normal on the incident side (dot(incident, normal) <= 0). Returns true and
/// writes the refracted direction to `transmitted`; under total internal reflection returns false
/// and writes the mirror direction reflect(incident, normal) instead of a zero vector, so the
/// caller always has a usable ray. Unit inputs give a unit output within 4 ulp for eta >= 1/1.52
/// (external refraction, and leaving glass or water); below, within 2 ulp / eta^2, as eta^2 - sin^2
/// cancels towards total internal reflection (3.8e-6 relative at eta = 1/4).
/// Domain: vectors with components of magnitude <= 1e15 (unit vectors intended; larger ones
/// overflow the dot product or, divided by a small eta, the result), eta clamped to
/// [RK_FRESNEL_ETA_MIN, RK_FRESNEL_ETA_MAX]: the output is finite there. cos is clamped to [0, 1]
/// (a normal facing the wrong way is treated as grazing incidence). Cost: 1 sqrt, 1 div, ~15 flops.
RK_INLINE bool rk_refract(vec3 incident, vec3 normal, float eta, RK_OUT(vec3) transmitted)
{
    float c = rk_saturate(-dot(normal, incident));
    float e = rk_fresnel_clamp_eta(eta);
    float g2 = (e - 1.0f) * (e + 1.0f) + c * c;
    if (g2 < 0.0f) {
        transmitted = incident + (2.0f * c) * normal;
        return false;
    }
    transmitted = (incident + (c - sqrt(g2)) * normal) / e;
    return true;
}

/// rk_fresnel_slab: reflectance of a non-absorbing pane (two parallel surfaces, incoherent
/// multiple reflections) from the single-surface reflectance R: 2R / (1 + R) (thesis Eq. 3.8).
/// Domain: R clamped to [0, 1]. Exact (3 ulp). Cost: 1 div, 2 flops. Slab(F0(1.52)) = 0.0816820.
RK_INLINE float rk_fresnel_slab(float r)
{
    float x = rk_saturate(r);
    return 2.0f * x / (1.0f + x);
}

/// rk_fresnel_slab_sp: the pane reflectance with the series summed per polarisation,
/// (slab(Rs) + slab(Rp)) / 2: the physically right order. The thesis's slab of the average
/// overestimates by up to 0.0236 for n = 1.52 (60°-75°). Domain: Rs, Rp clamped to [0, 1].
/// Max error vs float64: 9.0e-8 over [0, 1]^2 (6e7 random + refinement). Cost: 2 div, 6 flops.
RK_INLINE float rk_fresnel_slab_sp(vec2 rsp)
{
    return 0.5f * (rk_fresnel_slab(rsp.x) + rk_fresnel_slab(rsp.y));
}

/// rk_fresnel_glazing: N identical non-absorbing panes (2N surfaces, incoherent):
/// 2N R / (1 + (2N - 1) R). N = 1 is rk_fresnel_slab; two panes at 0° for n = 1.52: 0.1510277.
/// Domain: R clamped to [0, 1], panes to [0, 1e6] (real-valued N allowed; 0 gives 0).
/// Exact (4 ulp). Cost: 1 div, 5 flops.
RK_INLINE float rk_fresnel_glazing(float r, float panes)
{
    float x = rk_saturate(r);
    float n2 = 2.0f * clamp(panes, 0.0f, 1e6f);
    // 1 + (2N - 1) R as (1 - R) + 2N R: no cancellation when R -> 1 with few panes.
    RK_PRECISE float den = (1.0f - x) + n2 * x;
    // min: a no-op where division is correctly rounded; 1 + 2^-23 on a driver dividing by a
    // reciprocal (NVIDIA) for R = 1.
    return min(n2 * x / max(den, RK_FLT_MIN), 1.0f);
}

/// rk_fresnel_glazing_sp: N panes with the series summed per polarisation,
/// (glazing(Rs, N) + glazing(Rp, N)) / 2. Domain: as rk_fresnel_glazing (Rs, Rp clamped to [0, 1],
/// panes to [0, 1e6]). Max error vs float64: 1.2e-7 over [0, 1]^2 and N = 1..4 (3e7 random
/// per N + refinement). Cost: 2 div, 12 flops.
RK_INLINE float rk_fresnel_glazing_sp(vec2 rsp, float panes)
{
    return 0.5f * (rk_fresnel_glazing(rsp.x, panes) + rk_fresnel_glazing(rsp.y, panes));
}

// C++: the functions below depend on RK_FRESNEL_WINDOW_MODE; their C++ build lives in an
// inline namespace named after the values (docs/dialect.md), so translation units with other
// values never share it.
RK_CONFIGURED_BEGIN(RK_NS_FRESNEL_WINDOW)
/// rk_fresnel_window: window-glass reflectance selected at compile time by
/// RK_FRESNEL_WINDOW_MODE (see the file header), so a shader pays only for the model it uses.
/// `panes` is read by mode 3 only. Cost: that of rk_fresnel_dielectric_sp plus the slab.
RK_INLINE float rk_fresnel_window(float cos_i, float eta, float panes)
{
#if RK_FRESNEL_WINDOW_MODE != 3
    RK_UNUSED(panes);
#endif
#if RK_FRESNEL_WINDOW_MODE == 0
    return rk_fresnel_dielectric(cos_i, eta);
#elif RK_FRESNEL_WINDOW_MODE == 1
    return rk_fresnel_slab(rk_fresnel_dielectric(cos_i, eta));
#elif RK_FRESNEL_WINDOW_MODE == 2
    return rk_fresnel_slab_sp(rk_fresnel_dielectric_sp(cos_i, eta));
#else
    return rk_fresnel_glazing_sp(rk_fresnel_dielectric_sp(cos_i, eta), panes);
#endif
}
RK_CONFIGURED_END

#endif  // RK_FRESNEL_GLSL
