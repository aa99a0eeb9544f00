// raykit — window_glass.glsl: shading of a window pane: the environment reflection weighted by the
// pane's Fresnel reflectance (exact or fast, with the multiple reflections inside the pane), plus
// the interior seen through the tinted glass.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/window_glass.hpp.
// Source: Fahlén 2005, "Illumination for Real-Time Rendering of Large Architectural Environments",
// §3.1-3.2 (reflections in building windows: Fresnel with the slab's multiple reflections,
// Eq. 3.7-3.8, weighting an environment-map reflection); beyond the thesis: the slab applied per
// polarisation, N panes. The reflection colour comes from the caller (a dual-paraboloid
// or cube lookup, see paraboloid_sample.glsl and envmap_correction.glsl), the interior colour
// from interior mapping or any other source.
//
// The model, per RGB channel:
//   colour = R reflection + (1 - R) tint interior
// R is the pane's reflectance at the viewing angle (non-absorbing panes, incoherent multiple
// reflections), 1 - R the light the pane transmits, and tint in [0, 1] the glass's colour filter
// applied once to the transmitted light. Absorption is not fed back into R (the internal bounces
// carry R_slab - R_surface = 0.039 of the light at normal incidence for n = 1.52, before
// absorption); rk_window_glass_slab_absorbing gives the exact absorbing slab where that matters.
// Reflections are not tinted (the first surface, which dominates, reflects before any absorption).
//
// Feature macros:
//   RK_WINDOW_GLASS_FRESNEL  which reflectance rk_window_glass_reflectance() returns (default 0):
//       0 exact: rk_fresnel_window (fresnel.glsl), i.e. the pane model of RK_FRESNEL_WINDOW_MODE
//         (default 2: one pane, multiple reflections summed per polarisation; 3: `panes` panes).
//       1 fast: rk_fresnel_dielectric_fast (no square root) then rk_fresnel_glazing over `panes`
//         panes (the slab applied to the polarisation average, the thesis's order). Max abs error
//         against rk_window_glass_reflectance_exact (per-polarisation glazing), n = 1.52: 0.023
//         for one pane (the thesis's order alone accounts for 0.0236, partly cancelled by the fast
//         Fresnel's own error), 0.063 for two panes (every 4th cos float + refinement).
//
// @rk-es 310
// @rk-es300
// @rk-variants RK_WINDOW_GLASS_FRESNEL=0 | RK_WINDOW_GLASS_FRESNEL=1 | RK_WINDOW_GLASS_FRESNEL=0 RK_FRESNEL_WINDOW_MODE=3 | RK_WINDOW_GLASS_FRESNEL=1 RK_FRESNEL_WINDOW_MODE=1
#ifndef RK_WINDOW_GLASS_GLSL
#define RK_WINDOW_GLASS_GLSL

#ifdef __cplusplus
#define RK_NS_WINDOW_GLASS RK_PP_CAT(RK_PP_CAT(window_glass_fresnel, RK_WINDOW_GLASS_FRESNEL), RK_PP_CAT(_mode, RK_FRESNEL_WINDOW_MODE))
#endif

#include "common.glsl"
#include "color.glsl"
#include "fresnel.glsl"

#ifndef RK_WINDOW_GLASS_FRESNEL
#define RK_WINDOW_GLASS_FRESNEL 0
#endif
#if RK_WINDOW_GLASS_FRESNEL < 0 || RK_WINDOW_GLASS_FRESNEL > 1
#error "RK_WINDOW_GLASS_FRESNEL must be 0 (single surface) or 1 (pane model of fresnel.glsl)"
#endif
RK_OPTION_CHECK(rk_option_window_glass_fresnel, RK_WINDOW_GLASS_FRESNEL);

// Relative index of uncoated window glass (thesis §3.1.1, after Wloka).
#define RK_WINDOW_GLASS_ETA 1.52f

/// rk_window_glass_cos: |N·V|, the cosine of the viewing angle on either side of the pane (a pane
/// reflects the same from both sides). normal and to_eye (from the surface towards the eye) are
/// unit vectors; their components are clamped to [-1, 1] so no input overflows. Result in [0, 1]
/// (non-unit inputs are not normalised: the result is then no cosine, only capped at 1).
/// Max error vs float64 |N·V| of the same float unit vectors: 1.2e-7 absolute (relative error
/// grows towards grazing, where the dot cancels; 2e7 random + refinement;
/// tests/test_envmap_correction.cpp WindowGlass.AgainstFloat64 asserts 2e-7).
/// Cost: 1 dot, 1 abs, 1 min, 2 clamps.
RK_INLINE float rk_window_glass_cos(vec3 normal, vec3 to_eye)
{
    vec3 n = clamp(normal, vec3(-1.0f), vec3(1.0f));
    vec3 v = clamp(to_eye, vec3(-1.0f), vec3(1.0f));
    return min(abs(dot(n, v)), 1.0f);
}

/// rk_window_glass_reflectance_exact: the exact reflectance of `panes` identical non-absorbing
/// panes (two surfaces each), incoherent multiple reflections summed per polarisation:
/// rk_fresnel_glazing_sp(rk_fresnel_dielectric_sp(cos_i, eta), panes). One pane, n = 1.52:
/// 0.081682 at normal incidence, 0.15653 at 60°, 0.75435 at 85°. Domain as in
/// fresnel.glsl (cos_i in [0, 1], eta clamped, panes in [0, 1e6]). Max error vs float64: 3.8e-7
/// for n = 1.52 and 1 to 4 panes (every 16th cos float + refinement); 2.5e-5 over eta in
/// (1, 4096], panes in [0.01, 1e6] (at huge eta with fractional panes); up to 1.1e-3 for eta < 1
/// near the critical angle, where R is ill-conditioned (2e7 random + refinement each).
/// Cost: 1 sqrt, 4 div, ~30 flops.
RK_INLINE float rk_window_glass_reflectance_exact(float cos_i, float eta, float panes)
{
    return rk_fresnel_glazing_sp(rk_fresnel_dielectric_sp(cos_i, eta), panes);
}

/// rk_window_glass_reflectance_fast: the cheap pane reflectance: the square-root-free
/// rk_fresnel_dielectric_fast (params from rk_fresnel_fast_params(eta), a per-material constant),
/// then rk_fresnel_glazing over `panes` panes applied to the polarisation average (the thesis's
/// order, Eq. 3.8). Max abs error against rk_window_glass_reflectance_exact, n = 1.52: 0.023 for
/// one pane (worst near 75°), 0.063 for two (every 4th cos float + refinement).
/// Cost: 2 div, ~20 flops, no sqrt.
RK_INLINE float rk_window_glass_reflectance_fast(float cos_i, vec3 params, float panes)
{
    return rk_fresnel_glazing(rk_fresnel_dielectric_fast(cos_i, params), panes);
}

// C++: the functions below depend on RK_WINDOW_GLASS_FRESNEL and RK_FRESNEL_WINDOW_MODE; their C++ build lives in an
// inline namespace named after the values (docs/dialect.md), so translation units with other
// values never share it.
RK_CONFIGURED_BEGIN(RK_NS_WINDOW_GLASS)
/// rk_window_glass_reflectance: the reflectance selected by RK_WINDOW_GLASS_FRESNEL (see the
/// file header). `panes` is read by the fast mode and by fresnel.glsl's RK_FRESNEL_WINDOW_MODE 3.
/// The fast mode builds its params inline (one sqrt, folded when eta is a constant).
/// Domain: cos_i clamped to [0, 1], panes clamped to [0, 1e6]. eta: the exact mode takes
/// fresnel.glsl's domain (eta < 1 gives total internal reflection, 1, past the critical angle); the
/// fast mode models external reflection only and clamps eta to [1, RK_FRESNEL_ETA_MAX]
/// (rk_fresnel_fast_params), so it never reports total internal reflection: eta < 1 there is
/// treated as eta = 1, where the chord is no model at all (((1 - cos) / (1 + cos))^2 for
/// cos_i > ~1e-10 instead of 0; see rk_fresnel_dielectric_fast). Edge cases: grazing (cos_i = 0)
/// gives 1 where the model has an interface (eta != 1 after its clamping) and, in the models that
/// read panes, panes >= RK_FLT_MIN (0 panes give 0; denormal panes, 0 on a GPU that flushes
/// them, give between 0 and 1 on the CPU); normal incidence 0.0816820 for one pane of n = 1.52.
/// Max error, default build (exact mode 0 with RK_FRESNEL_WINDOW_MODE 2: one pane, the series
/// summed per polarisation; equal bit for bit to rk_fresnel_window), vs the float64
/// complex-amplitude Fresnel with the slab 2R / (1 + R) per polarisation: 3.8e-7 absolute for
/// n = 1.52 (every 4th cos float + refinement), 4.1e-7 for n in [1.2, 2.4] over cos in [0, 1] (2e7
/// random + refinement; tests/test_envmap_correction.cpp WindowGlass.AgainstFloat64 asserts 1e-6).
/// The fast mode is a model 0.023 (one pane) / 0.063 (two) away from the exact pane (file header).
/// Cost: default 1 sqrt, 4 div, ~20 flops; fast 2 div, ~20 flops (+ 1 sqrt for the params).
RK_INLINE float rk_window_glass_reflectance(float cos_i, float eta, float panes)
{
#if RK_WINDOW_GLASS_FRESNEL == 1
    return rk_window_glass_reflectance_fast(cos_i, rk_fresnel_fast_params(eta), panes);
#else
    return rk_fresnel_window(cos_i, eta, panes);
#endif
}

/// rk_window_glass_combine: reflectance * reflection + (1 - reflectance) * tint * interior, the
/// pane's colour from its two incoming radiances. Colours are sanitised (rk_hdr_sanitize: negative
/// and NaN to 0, +Inf and above RK_HDR_MAX to RK_HDR_MAX), reflectance and tint clamped to [0, 1].
/// With tint = 1 and equal inputs the output equals the input (energy conserving); reflectance 0
/// gives tint * interior, 1 the reflection.
/// Max error vs float64 of the same formula: 3.0 ulp per channel (radiances 1e-3..8e3, all terms
/// >= 0 so no cancellation; 2e7 random + refinement; tests/test_envmap_correction.cpp
/// WindowGlass.AgainstFloat64 asserts < 4 ulp).
/// Cost: 9 mul, 1 sub, 3 add, 2 clamps, 6 compare/select (sanitize).
RK_INLINE vec3 rk_window_glass_combine(vec3 reflection, vec3 interior, float reflectance, vec3 tint)
{
    float r = rk_saturate(reflectance);
    vec3 t = clamp(tint, vec3(0.0f), vec3(1.0f));
    return r * rk_hdr_sanitize(reflection) + ((1.0f - r) * t) * rk_hdr_sanitize(interior);
}

/// rk_window_glass_shade: the whole pane: cos from normal and to_eye, the reflectance of
/// rk_window_glass_reflectance(cos, eta, panes), then rk_window_glass_combine. `reflection` is the
/// environment looked up along the (corrected) reflection vector, `interior` the colour behind the
/// glass. Domain and edge cases: those of rk_window_glass_cos (unit normal and to_eye; both sides
/// of the pane shade alike), rk_window_glass_reflectance and rk_window_glass_combine.
/// Max error, default build, vs float64 (|N·V|, the float64 pane of rk_window_glass_reflectance,
/// the combine): 5.4e-7 of reflection + tint * interior per channel (n = 1.52, 2e7 random unit N,
/// V + refinement; tests/test_envmap_correction.cpp WindowGlass.AgainstFloat64 asserts 1e-6).
/// Relative to the output the transmitted part is less accurate towards grazing, where 1 - R
/// shrinks with N·V and the float N·V's rounding becomes a sizeable fraction of it (2.5e-4 of the
/// output at N·V = 7e-5).
/// Cost: that of the reflectance + ~19 flops (default: 1 sqrt, 4 div, ~40 flops).
RK_INLINE vec3 rk_window_glass_shade(vec3 normal, vec3 to_eye, vec3 reflection, vec3 interior, vec3 tint, float eta,
                                     float panes)
{
    float c = rk_window_glass_cos(normal, to_eye);
    return rk_window_glass_combine(reflection, interior, rk_window_glass_reflectance(c, eta, panes), tint);
}
RK_CONFIGURED_END

/// rk_window_glass_slab_absorbing: reflectance and transmittance of one absorbing pane per RGB
/// channel, incoherent multiple reflections summed exactly: with the single-surface reflectance R
/// (per polarisation in rsp, averaged at the end; pass vec2(R) for unpolarised) and the internal
/// transmittance tau of one pass through the glass,
///   R_pane = R + (1 - R)^2 tau^2 R / (1 - R^2 tau^2),   T_pane = (1 - R)^2 tau / (1 - R^2 tau^2).
/// tau = 1 gives the slab 2R / (1 + R) and 1 - 2R / (1 + R). rsp and tau clamped to [0, 1]; the
/// divisor is floored at RK_FLT_MIN (R = tau = 1 gives R_pane = 1, T_pane = 0). Use
/// colour = R_pane reflection + T_pane interior. Max error: 3.1 ulp on R_pane; on T_pane
/// ~1 / (1 - R^2 tau^2) ulp, from the cancellation in the divisor (290 ulp at R, tau ~ 0.999,
/// 2.4e3 at 0.99996; 4e7 random + refinement). Cost: 2 x (1 div, ~12 flops) x3.
RK_INLINE void rk_window_glass_slab_absorbing(vec2 rsp, vec3 tau, RK_OUT(vec3) reflectance, RK_OUT(vec3) transmittance)
{
    vec3 t = clamp(tau, vec3(0.0f), vec3(1.0f));
    vec3 t2 = t * t;
    float rs = rk_saturate(rsp.x);
    float rp = rk_saturate(rsp.y);
    float ts = (1.0f - rs) * (1.0f - rs);
    float tp = (1.0f - rp) * (1.0f - rp);
    vec3 ds = max(vec3(1.0f) - (rs * rs) * t2, vec3(RK_FLT_MIN));
    vec3 dp = max(vec3(1.0f) - (rp * rp) * t2, vec3(RK_FLT_MIN));
    reflectance = 0.5f * (vec3(rs) + (ts * rs) * t2 / ds + vec3(rp) + (tp * rp) * t2 / dp);
    transmittance = 0.5f * (ts * t / ds + tp * t / dp);
}

#endif  // RK_WINDOW_GLASS_GLSL
