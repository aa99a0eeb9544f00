// raykit — tonemap.glsl: HDR -> display tone-mapping operators.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/tonemap.hpp.
// Input: scene-referred linear Rec.709 RGB, exposure already applied (see exposure.glsl).
// Output: display-linear RGB in [0, 1]; encode with rk_srgb_encode (color.glsl) for an sRGB
// display, or write to an *_SRGB render target.
// Every operator first passes its input through rk_hdr_sanitize: negative values, NaN and -Inf
// map to 0, +Inf and values above RK_HDR_MAX (1e18) to RK_HDR_MAX, so no input whatsoever
// produces NaN/Inf.
//
// Sources: Reinhard et al. 2002 (thesis Eq. 3.15-3.17); Narkowicz 2015 "ACES Filmic Tone Mapping
// Curve"; Hill's ACES RRT+ODT fit (BakingLab ACES.hlsl matrices); Wrensch's minimal AgX (Sobotka's
// AgX inset matrix, log2 range [-12.47393, 4.026069], 6th-order contrast fit) with the ASC CDL
// looks used by Blender/Filament; the Khronos PBR Neutral specification
// (KhronosGroup/ToneMapping, PBR_Neutral/README.md); Hable 2010 (Uncharted 2); Lottes 2016
// (GDC "Advanced Techniques and Optimization of HDR Color Pipelines"); Uchimura 2017 (GT).
// The accuracy column in docs/benchmarks.md compares each with a float64 evaluation of its
// published formula (tests/reference/tonemap_ref.hpp); the two ACES fits are also compared with the
// ACES 1.0 RRT + sRGB 100-nit ODT itself (ref::aces_rrt_odt_srgb, written from the Academy's CTL).
//
// Feature macros:
//   RK_TONEMAP_OPERATOR  operator used by rk_tonemap() (default 4, AgX):
//       0 clamp (no tone mapping)  1 Reinhard extended (luminance)  2 ACES Narkowicz
//       3 ACES Hill  4 AgX  5 Khronos PBR Neutral  6 Hable  7 Lottes  8 Uchimura
//   RK_AGX_LOOK          0 default, 1 golden, 2 punchy (default 0)
//
// @rk-es 310
// @rk-es300
// @rk-variants RK_TONEMAP_OPERATOR=0 | RK_TONEMAP_OPERATOR=1 | RK_TONEMAP_OPERATOR=2 | RK_TONEMAP_OPERATOR=3 | RK_TONEMAP_OPERATOR=4 RK_AGX_LOOK=1 | RK_TONEMAP_OPERATOR=4 RK_AGX_LOOK=2 | RK_TONEMAP_OPERATOR=5 | RK_TONEMAP_OPERATOR=6 | RK_TONEMAP_OPERATOR=7 | RK_TONEMAP_OPERATOR=8
#ifndef RK_TONEMAP_GLSL
#define RK_TONEMAP_GLSL

#ifdef __cplusplus
#define RK_NS_TONEMAP RK_PP_CAT(RK_PP_CAT(tonemap_operator, RK_TONEMAP_OPERATOR), RK_PP_CAT(_agx_look, RK_AGX_LOOK))
#endif

#include "common.glsl"
#include "color.glsl"

#ifndef RK_TONEMAP_OPERATOR
#define RK_TONEMAP_OPERATOR 4
#endif
#if RK_TONEMAP_OPERATOR < 0 || RK_TONEMAP_OPERATOR > 8
#error "RK_TONEMAP_OPERATOR must be 0 (clamp), 1 (Reinhard), 2 (ACES Narkowicz), 3 (ACES Hill), 4 (AgX), 5 (PBR Neutral), 6 (Hable), 7 (Lottes) or 8 (Uchimura)"
#endif
RK_OPTION_CHECK(rk_option_tonemap_operator, RK_TONEMAP_OPERATOR);
#ifndef RK_AGX_LOOK
#define RK_AGX_LOOK 0
#endif
#if RK_AGX_LOOK < 0 || RK_AGX_LOOK > 2
#error "RK_AGX_LOOK must be 0 (default), 1 (golden) or 2 (punchy)"
#endif
RK_OPTION_CHECK(rk_option_agx_look, RK_AGX_LOOK);

// ---------------------------------------------------------------------------------------------
// Reinhard (thesis Eq. 3.15-3.17)

/// rk_reinhard_scale: the scaling operator L_s = (key / L_avg) L (Eq. 3.15, with the log-average
/// L_avg the thesis's text garbles). key is the target middle grey (0.18 typical). lum and key
/// are sanitised (rk_hdr_sanitize), L_avg is clamped to [1e-20, RK_HDR_MAX] (NaN -> 1e-20), and the
/// result to [0, RK_HDR_MAX]: finite for every input. 2 roundings (1.5 ulp) below the clamp.
/// Cost: 1 div, 1 mul, 2 compares.
RK_INLINE float rk_reinhard_scale(float lum, float key, float log_average)
{
    float avg = log_average > 1e-20f ? min(log_average, RK_HDR_MAX) : 1e-20f;
    return min(rk_hdr_sanitize(lum) * (rk_hdr_sanitize(key) / avg), RK_HDR_MAX);
}

/// rk_reinhard: L / (1 + L) (Eq. 3.16). Monotonic, 0 -> 0, -> 1 as L -> inf. Domain: sanitised.
/// Max error: 2 ulp. Cost: 1 add, 1 div.
RK_INLINE float rk_reinhard(float x)
{
    float v = rk_hdr_sanitize(x);
    // min: a no-op where division is correctly rounded; a driver dividing by a reciprocal (NVIDIA)
    // gave 1 + 2^-23 for L = 6e13.
    return min(v / (1.0f + v), 1.0f);
}

/// rk_reinhard_extended: L (1 + L / W^2) / (1 + L) (Eq. 3.17): L = W maps exactly to 1; values
/// above W (which the formula maps above 1, "burn-out") are clamped to 1. white is clamped to
/// [1e-9, RK_HDR_MAX]; a NaN white is RK_HDR_MAX (no white point: the simple operator); white >=
/// 1e9 is the simple operator to float precision. Max error: 4.2 ulp (4e7 random (x, W) +
/// refinement). Cost: 1 div, 4 flops.
RK_INLINE float rk_reinhard_extended(float x, float white)
{
    float v = rk_hdr_sanitize(x);
    float w = white >= 1e-9f ? min(white, RK_HDR_MAX) : (white < 1e-9f ? 1e-9f : RK_HDR_MAX);
    if (v >= w) {
        return 1.0f;
    }
    // For w >= 1e9, v / w^2 < 1e-9 is below half an ulp of 1: skipping the term changes no result
    // and keeps (v / w) / w out of the denormal range (slow on CPUs).
    float k = (w >= 1e9f) ? 0.0f : (v / w) / w;
    return min(v * (1.0f + k) / (1.0f + v), 1.0f);
}

/// rk_tonemap_reinhard: Reinhard applied to luminance with the colour ratio kept,
/// rgb * L_d / L (the practice the thesis leaves implicit), clamped to [0, 1] per channel.
/// Pre-scale rgb by key / L_avg (rk_reinhard_scale's factor). white = RK_HDR_MAX gives Eq. 3.16.
/// Max error vs float64: 3.8e-7 (6e7 random colours + refinement). Cost: 1 dot, 2 div, ~8 flops.
RK_INLINE vec3 rk_tonemap_reinhard(vec3 rgb, float white)
{
    vec3 c = rk_hdr_sanitize(rgb);
    float lum = rk_luminance(c);
    float ld = rk_reinhard_extended(lum, white);
    return clamp(c * (ld / max(lum, 1e-30f)), vec3(0.0f), vec3(1.0f));
}

// ---------------------------------------------------------------------------------------------
// ACES fits

/// rk_aces_narkowicz: Narkowicz 2015 fit of the ACES RRT+ODT (his post: sampled from the Rec.709
/// 100-nit ODT with its 2.4 gamma removed, i.e. display-linear sRGB/Rec.709),
/// x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14), clamped to [0, 1]. Per channel (no hue
/// preservation). Narkowicz suggests pre-multiplying the input by 0.6 to match ACES exposure; this
/// function applies no scale (do it in the exposure). Max error vs float64 of the formula: 3.0e-7
/// (every 4th float in [0, 1e9] + refinement).
/// Max error vs ACES itself (the float64 ACES 1.0 RRT + sRGB 100-nit ODT of
/// tests/reference/tonemap_ref.hpp; display-linear, peak channel 1e-3..1e2; test_tonemap
/// AcesFitsAgainstAcesReference): with the input x 0.6, 0.0635 on grey (at 0.44), 0.37 on mild
/// colours; with x 0.5, the best scale on grey, 0.0138 (at 3.6: the fit error his post states) and
/// 0.42 on mild colours; unscaled, 0.25 on grey. Bright saturated colours stay saturated where
/// ACES goes to white: error up to 1.0 (e.g. pure green 66). Cost: 2 mad + 1 div per channel.
RK_INLINE vec3 rk_aces_narkowicz(vec3 rgb)
{
    vec3 x = rk_hdr_sanitize(rgb);
    // For x above ~1e9 the terms' ratio is 2.51/2.43 > 1 and clamps to 1; cap to avoid overflow.
    x = min(x, vec3(1e9f));
    return clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), vec3(0.0f), vec3(1.0f));
}

/// rk_aces_hill_curve: the RRT+ODT rational fit of Stephen Hill's ACES approximation, in ACES AP1
/// space: (v (v + 0.0245786) - 0.000090537) / (v (0.983729 v + 0.4329510) + 0.238081).
/// Domain: v >= 0 (negative v clamped to 0, capped at 1e9). Range: -3.8e-4 at 0 (negative below
/// v = 0.00325; rk_aces_hill clamps after its output matrix) rising to 1 / 0.983729 = 1.0165401,
/// which float rounding overshoots by up to 2 ulp (largest output 1.0165403).
/// Max error vs float64: 3.7e-7 (3.1 ulp of the asymptote) over {0} and the floats in [1e-5, 1e4]
/// (every 4th + refinement; also over [0, 1e9]). Cost: 2 mad + 1 div per channel.
RK_INLINE vec3 rk_aces_hill_curve(vec3 v)
{
    vec3 x = min(max(v, vec3(0.0f)), vec3(1e9f));
    return (x * (x + 0.0245786f) - 0.000090537f) / (x * (0.983729f * x + 0.4329510f) + 0.238081f);
}

/// rk_aces_hill: Hill's fitted ACES (sRGB -> AP1 with the RRT saturation, the rational
/// RRT+ODT fit, ODT saturation -> sRGB), clamped to [0, 1]. Matrices from BakingLab's ACES.hlsl,
/// transposed into GLSL's column-major mat3 constructor (they equal the products derived from the
/// ACES chromaticities, Bradford CAT and RRT/ODT_SAT to 4.6e-6, i.e. to their 5 printed decimals).
/// No exposure boost (some ports divide the input by 0.6). Max error vs float64 of the same
/// formula: 5.6e-7 (6e7 random colours + refinement). Max error vs ACES itself (the float64 ACES
/// 1.0 RRT + sRGB 100-nit ODT of tests/reference/tonemap_ref.hpp; display-linear, peak channel
/// 1e-3..1e2; test_tonemap AcesFitsAgainstAcesReference): 0.0101 on grey (at 2.56; 0.0061 after
/// sRGB encoding), 0.067 on mild colours, 0.081 on saturated ones (pure red 0.88: the fit has no
/// glow, red modifier or dim-surround step). Cost: 2 mat3*vec3, 6 mad, 3 div.
RK_INLINE vec3 rk_aces_hill(vec3 rgb)
{
    mat3 aces_in = mat3(vec3(0.59719f, 0.07600f, 0.02840f), vec3(0.35458f, 0.90834f, 0.13383f),
                        vec3(0.04823f, 0.01566f, 0.83777f));
    mat3 aces_out = mat3(vec3(1.60475f, -0.10208f, -0.00327f), vec3(-0.53108f, 1.10813f, -0.07276f),
                         vec3(-0.07367f, -0.00605f, 1.07602f));
    vec3 v = aces_in * rk_hdr_sanitize(rgb);
    return clamp(aces_out * rk_aces_hill_curve(v), vec3(0.0f), vec3(1.0f));
}

// ---------------------------------------------------------------------------------------------
// AgX (minimal polynomial form)

/// rk_agx_contrast: the 6th-order polynomial fit of AgX's default sigmoid on [0, 1] (mean squared
/// error 3.67e-6 vs the LUT, per Wrensch). Domain: x in [0, 1]. Cost: 6 mad per channel.
RK_INLINE vec3 rk_agx_contrast(vec3 x)
{
    vec3 x2 = x * x;
    vec3 x4 = x2 * x2;
    return 15.5f * x4 * x2 - 40.14f * x4 * x + 31.96f * x4 - 6.868f * x2 * x + 0.4298f * x2 + 0.1191f * x -
           vec3(0.00232f);
}

/// rk_agx_look: ASC CDL look applied in AgX's encoded space, then saturation about BT.709 luma:
/// look 0 default (identity), 1 golden (slope 1, 0.9, 0.5; power 0.8; saturation 1.3),
/// 2 punchy (power 1.35; saturation 1.4). Domain: x in [0, 1]. Max error vs float64 of the CDL
/// formula over [0, 1]^3: 0 (look 0, returns x), 2.1e-7 (golden), 2.0e-7 (punchy) on the CPU
/// (2e7 random inputs + refinement; pow is driver-defined on a GPU).
/// Cost: 0 (look 0) or 3 pow + 6 flops.
RK_INLINE vec3 rk_agx_look(vec3 x, int look)
{
    vec3 slope = vec3(1.0f);
    vec3 power = vec3(1.0f);
    float sat = 1.0f;
    if (look == 1) {
        slope = vec3(1.0f, 0.9f, 0.5f);
        power = vec3(0.8f);
        sat = 1.3f;
    } else if (look == 2) {
        power = vec3(1.35f);
        sat = 1.4f;
    } else {
        return x;
    }
    float luma = rk_luminance(x);
    vec3 c = pow(max(x * slope, vec3(0.0f)), power);
    return vec3(luma) + sat * (c - vec3(luma));
}

/// rk_agx: Sobotka's AgX in Wrensch's minimal form: inset matrix, log2 encoding over
/// [-12.47393, 4.026069] EV around 0.18, the contrast polynomial, an optional look (RK_AGX_LOOK
/// when called through rk_tonemap), the outset (inverse) matrix, and display linearisation
/// x^2.2. Values are clamped to [0, 1] before the power (the polynomial is -0.00232 at 0 and the
/// outset matrix can go negative). Max error vs float64 of the same formula: 1.9e-5 (default
/// look), 1.5e-5 (golden), 3.6e-5 (punchy) (2e7 random colours + grey floats + refinement), from
/// float cancellation between the polynomial's alternating coefficients; the looks lift black to
/// ~2e-7. Cost: 2 mat3*vec3, 3 log2, 3 pow, 18 mad.
RK_INLINE vec3 rk_agx(vec3 rgb, int look)
{
    mat3 inset = mat3(vec3(0.842479062253094f, 0.0423282422610123f, 0.0423756549057051f),
                      vec3(0.0784335999999992f, 0.878468636469772f, 0.0784336f),
                      vec3(0.0792237451477643f, 0.0791661274605434f, 0.879142973793104f));
    mat3 outset = mat3(vec3(1.19687900512017f, -0.0528968517574562f, -0.0529716355144438f),
                       vec3(-0.0980208811401368f, 1.15190312990417f, -0.0980434501171241f),
                       vec3(-0.0990297440797205f, -0.0989611768448433f, 1.15107367264116f));
    float min_ev = -12.47393f;
    float max_ev = 4.026069f;
    vec3 v = inset * rk_hdr_sanitize(rgb);
    v = clamp(log2(max(v, vec3(1e-10f))), vec3(min_ev), vec3(max_ev));
    v = (v - vec3(min_ev)) / (max_ev - min_ev);
    v = rk_agx_look(rk_agx_contrast(v), look);
    v = outset * v;
    return pow(clamp(v, vec3(0.0f), vec3(1.0f)), vec3(2.2f));
}

// ---------------------------------------------------------------------------------------------
// Khronos PBR Neutral

#define RK_NEUTRAL_START_COMPRESSION 0.76f  // 0.8 - F90 (0.04)
#define RK_NEUTRAL_DESATURATION 0.15f

/// rk_pbr_neutral: the Khronos PBR Neutral tone mapper exactly as its specification defines it:
/// offset f(x) = x - 6.25 x^2 for x < 0.08 else 0.04 of the minimum channel is subtracted; below
/// the peak 0.76 colours pass unchanged (base colours 0.08..0.8 reproduce exactly as c - 0.04);
/// above it the peak is compressed to 1 - d^2 / (p + d - 0.76), d = 0.24, and the colour mixes
/// toward the grey of the NEW PEAK (vec3(newPeak), the spec; the first published GLSL mixed
/// toward vec3(1)) by g = 1 - 1 / (0.15 (p - newPeak) + 1). Output in [0, 1]: below 1 in exact
/// arithmetic, but float32 rounds the compressed peak up to exactly 1 for peaks above about
/// 1.9e6 (1 - 0.0576 / (p - 0.52) is then within half an ulp of 1). Hue-preserving.
/// Max error vs float64 of the spec formula: 2.2e-7 (6e7 random colours + refinement).
/// Cost: ~20 flops, 2 div.
RK_INLINE vec3 rk_pbr_neutral(vec3 rgb)
{
    vec3 c = rk_hdr_sanitize(rgb);
    float x = min(c.x, min(c.y, c.z));
    float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    c = c - vec3(offset);
    float peak = max(c.x, max(c.y, c.z));
    if (peak < RK_NEUTRAL_START_COMPRESSION) {
        return c;
    }
    float d = 1.0f - RK_NEUTRAL_START_COMPRESSION;
    float new_peak = 1.0f - d * d / (peak + d - RK_NEUTRAL_START_COMPRESSION);
    c = c * (new_peak / peak);
    float g = 1.0f - 1.0f / (RK_NEUTRAL_DESATURATION * (peak - new_peak) + 1.0f);
    return mix(c, vec3(new_peak), g);
}

/// rk_pbr_neutral_inverse: the analytic inverse of rk_pbr_neutral (the spec states the mapping is
/// invertible): newPeak = max channel; p = d^2 / (1 - newPeak) - d + 0.76; undo the mix and the
/// scale; then undo the offset, whose inverse on the minimum channel y is x = 0.4 sqrt(y) for
/// y < 0.04 else x = y + 0.04. Domain: outputs of rk_pbr_neutral, [0, 1) (inputs clamped to
/// [0, 1 - 2^-20]: the largest output float32 can hold before the inverse diverges). The
/// inverse is ill-conditioned as newPeak -> 1 (d input / d output ~ 1 / (1 - newPeak)^2): GPU
/// and CPU agree to 1e-3 relative there, 2e-6 absolute below the compression start.
/// Round trip error: 2e-6 absolute below the compression start; above it the forward map mixes
/// toward grey (g -> 1), so channels much smaller than the peak come back with an error of up to
/// 4.9e-4 of the peak (mean 3.2e-5) for peaks up to 100 — float cancellation, not the formula.
/// Cost: 1 sqrt, 3 div.
RK_INLINE vec3 rk_pbr_neutral_inverse(vec3 display)
{
    vec3 c = min(rk_hdr_sanitize(display), vec3(1.0f - 9.5367431640625e-7f));
    float new_peak = max(c.x, max(c.y, c.z));
    if (new_peak >= RK_NEUTRAL_START_COMPRESSION) {
        float d = 1.0f - RK_NEUTRAL_START_COMPRESSION;
        float peak = d * d / (1.0f - new_peak) - d + RK_NEUTRAL_START_COMPRESSION;
        float g = 1.0f - 1.0f / (RK_NEUTRAL_DESATURATION * (peak - new_peak) + 1.0f);
        // Display colours outside the forward map's image (a channel below g * newPeak) would
        // come back negative; they are clamped to the grey axis' foot instead.
        c = max(c - vec3(g * new_peak), vec3(0.0f)) / (1.0f - g) * (peak / new_peak);
    }
    float y = max(min(c.x, min(c.y, c.z)), 0.0f);
    float x = y < 0.04f ? 0.4f * sqrt(y) : y + 0.04f;
    return c + vec3(x - y);
}

// ---------------------------------------------------------------------------------------------
// Filmic curves

/// rk_hable_curve: Hable's Uncharted 2 curve ((x (A x + C B) + D E) / (x (A x + B) + D F)) - E / F
/// with A 0.15, B 0.50, C 0.10, D 0.20, E 0.02, F 0.30. Domain: x >= 0 (negative x clamped to 0,
/// capped at 1e9). Range: 0 at 0 rising to 1 - E / F = 0.9333. Max error vs float64: 2.5e-7 over
/// {0} and the floats in [1e-5, 1e4] (every 4th + refinement). Cost: 4 mad, 1 div, 1 min (the
/// quotient is below 1, but a driver's division may be 2.5 ulp off: NVIDIA's left the range).
RK_INLINE vec3 rk_hable_curve(vec3 x)
{
    vec3 v = min(max(x, vec3(0.0f)), vec3(1e9f));
    return min((v * (0.15f * v + 0.05f) + 0.004f) / (v * (0.15f * v + 0.50f) + 0.06f), vec3(1.0f)) - 0.02f / 0.30f;
}

/// rk_hable: Uncharted 2 filmic, curve(x) / curve(W) with linear white W = 11.2, clamped to [0, 1].
/// Hable's demo multiplies the input by an exposure bias of 2; do that in the exposure.
/// Max error vs float64: 2.9e-7 (every 4th float in [0, 1e9] + refinement).
/// Cost: 8 mad, 2 div (curve(W) folds to a constant).
RK_INLINE vec3 rk_hable(vec3 rgb)
{
    vec3 white = rk_hable_curve(vec3(11.2f));
    return clamp(rk_hable_curve(rk_hdr_sanitize(rgb)) / white, vec3(0.0f), vec3(1.0f));
}

/// rk_lottes_params: the (b, c) of Lottes' curve x^a / (x^(a d) b + c) that place mid grey
/// mid_in -> mid_out and hdr_max -> 1, for contrast a and shoulder d. Compute once (CPU or
/// constant-folded). Domain (clamped, so any input gives finite b, c): a in [0.1, 4],
/// d in [0.1, 1], mid_in in [1e-4, 1], hdr_max in [2 mid_in, 1e4], mid_out in [1e-4, 0.9999].
/// Max error vs float64 (relative): 4.5e-7 on b, 7.3e-7 on c over a in [1, 2], d in [0.9, 1] with
/// hdr_max 8, and over hdr_max in [1, 1e3] with a 1.6, d 0.977 (mid 0.18 -> 0.267; CPU pow;
/// 2e7 random (a, d) + every 4th float hdr_max + refinement). Cost: 4 pow.
RK_INLINE vec2 rk_lottes_params(float a, float d, float hdr_max, float mid_in, float mid_out)
{
    float ac = clamp(a, 0.1f, 4.0f);
    float dc = clamp(d, 0.1f, 1.0f);
    float mi = clamp(mid_in, 1e-4f, 1.0f);
    float hm = clamp(hdr_max, 2.0f * mi, 1e4f);
    float mo = clamp(mid_out, 1e-4f, 0.9999f);
    float ma = pow(mi, ac);
    float mad = pow(mi, ac * dc);
    float ha = pow(hm, ac);
    float had = pow(hm, ac * dc);
    float den = max((had - mad) * mo, 1e-30f);
    float b = (-ma + ha * mo) / den;
    float c = (had * ma - ha * mad * mo) / den;
    vec2 r = vec2(b, c);
    return r;
}

/// rk_lottes: Lottes 2016 per channel with contrast 1.6, shoulder 0.977, hdrMax 8, mid grey
/// 0.18 -> 0.267, clamped to [0, 1]. Max error vs float64: 2.5e-7 on the CPU (every 16th float in
/// [0, 1e9] + refinement; pow on the GPU is driver-defined). Cost: 2 pow + 2 flops per channel
/// (params fold).
RK_INLINE vec3 rk_lottes(vec3 rgb)
{
    float a = 1.6f;
    float d = 0.977f;
    vec2 bc = rk_lottes_params(a, d, 8.0f, 0.18f, 0.267f);
    vec3 x = min(rk_hdr_sanitize(rgb), vec3(1e9f));
    vec3 num = pow(x, vec3(a));
    vec3 den = pow(x, vec3(a * d)) * bc.x + vec3(bc.y);
    return clamp(num / den, vec3(0.0f), vec3(1.0f));
}

/// rk_uchimura_curve: Uchimura 2017 (Gran Turismo) toe / linear / shoulder curve with max
/// brightness P, contrast a, linear start m, linear length l, black tightness c, pedestal b.
/// Domain: x >= 0 up to FLT_MAX (each segment is evaluated on its own range, min(x, m) for the toe,
/// min(x, S0) for the line and the shoulder's exponent capped at 0, which it never exceeds where
/// its weight is non-zero, so no infinity meets a zero weight). The parameters are not clamped:
/// the formula needs m > 0 (x / m), a > 0, m < P and l < 1 (it divides by P - S1 = (P - m)(1 - l)),
/// and the output is finite for P in [1e-3, 1e3], m in [1e-4 P, 0.999 P], l in [0, 0.999],
/// a in [1e-3, 1e3], c in [0.01, 100], b in [-P, P] (test_adversarial; nearer those limits
/// P - S1 rounds to 0 or an intermediate overflows). Max error vs float64: 6.8e-8 with the
/// defaults, 1.2e-7 with P 1.5, a 1.2, m 0.3, l 0.3, c 1.5, b 0.01, over the floats x in
/// [1e-5, 1e4] on the CPU (every 4th + refinement). Cost: 1 pow, 1 exp, 1 smoothstep, ~15 flops
/// per channel.
RK_INLINE vec3 rk_uchimura_curve(vec3 x, float P, float a, float m, float l, float c, float b)
{
    float l0 = ((P - m) * l) / a;
    float S0 = m + l0;
    float S1 = m + a * l0;
    float C2 = (a * P) / (P - S1);
    float CP = -C2 / P;
    vec3 w0 = vec3(1.0f) - smoothstep(vec3(0.0f), vec3(m), x);
    vec3 w2 = step(vec3(m + l0), x);
    vec3 w1 = vec3(1.0f) - w0 - w2;
    vec3 T = m * pow(min(x, vec3(m)) / m, vec3(c)) + vec3(b);
    vec3 S = vec3(P) - (P - S1) * exp(min(CP * (x - vec3(S0)), vec3(0.0f)));
    vec3 L = vec3(m) + a * (min(x, vec3(S0)) - vec3(m));
    return T * w0 + L * w1 + S * w2;
}

/// rk_uchimura: the GT curve with its published defaults P 1, a 1, m 0.22, l 0.4, c 1.33, b 0,
/// clamped to [0, 1]. Max error vs float64: 6.8e-8 (every 4th float in [0, 1e9] + refinement).
/// Cost: see rk_uchimura_curve.
RK_INLINE vec3 rk_uchimura(vec3 rgb)
{
    vec3 x = min(rk_hdr_sanitize(rgb), vec3(1e9f));
    return clamp(rk_uchimura_curve(x, 1.0f, 1.0f, 0.22f, 0.4f, 1.33f, 0.0f), vec3(0.0f), vec3(1.0f));
}

// ---------------------------------------------------------------------------------------------

// C++: the functions below depend on RK_TONEMAP_OPERATOR and RK_AGX_LOOK; their C++ build lives in an
// inline namespace named after the values (docs/dialect.md), so translation units with other
// values never share it.
RK_CONFIGURED_BEGIN(RK_NS_TONEMAP)
/// rk_tonemap: the operator chosen by RK_TONEMAP_OPERATOR at compile time (a shader pays only for
/// it). `reinhard_white` is read by operator 1 only (RK_HDR_MAX for the simple operator).
/// Output display-linear in [0, 1]. Domain, max error and cost: exactly those of the selected
/// operator's function (the dispatch is a preprocessor choice: no run-time cost); operator 0 is
/// exact (clamp of the sanitised input).
RK_INLINE vec3 rk_tonemap(vec3 rgb, float reinhard_white)
{
#if RK_TONEMAP_OPERATOR != 1
    RK_UNUSED(reinhard_white);
#endif
#if RK_TONEMAP_OPERATOR == 0
    return clamp(rk_hdr_sanitize(rgb), vec3(0.0f), vec3(1.0f));
#elif RK_TONEMAP_OPERATOR == 1
    return rk_tonemap_reinhard(rgb, reinhard_white);
#elif RK_TONEMAP_OPERATOR == 2
    return rk_aces_narkowicz(rgb);
#elif RK_TONEMAP_OPERATOR == 3
    return rk_aces_hill(rgb);
#elif RK_TONEMAP_OPERATOR == 4
    return rk_agx(rgb, RK_AGX_LOOK);
#elif RK_TONEMAP_OPERATOR == 5
    return rk_pbr_neutral(rgb);
#elif RK_TONEMAP_OPERATOR == 6
    return rk_hable(rgb);
#elif RK_TONEMAP_OPERATOR == 7
    return rk_lottes(rgb);
#else
    return rk_uchimura(rgb);
#endif
}
RK_CONFIGURED_END

#endif  // RK_TONEMAP_GLSL
