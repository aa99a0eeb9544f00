// raykit — color.glsl: luminance, sRGB transfer functions and HDR input sanitising.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/color.hpp.
// Working space: linear Rec.709/sRGB primaries, D65, scene-referred (1.0 = diffuse white).
//
// @rk-es 310
// @rk-es300
#ifndef RK_COLOR_GLSL
#define RK_COLOR_GLSL

#include "common.glsl"

// Largest HDR value the tone-mapping code passes on: large enough for any physical scene in
// cd/m^2-like units (the sun's disk is ~1.6e9), small enough that x^2 stays finite in float.
#define RK_HDR_MAX 1.0e18f

/// Rec. ITU-R BT.709 luma/luminance weights (item 3.2: 0.2126, 0.7152, 0.0722), the Y row of the
/// sRGB/Rec.709 RGB -> XYZ matrix rounded as the standard states it.
#define RK_LUMA_BT709 vec3(0.2126f, 0.7152f, 0.0722f)
/// The weights the thesis uses (Fahlén 2005, Eq. 3.13; also DirectX SDK samples): 0.2125,
/// 0.7154, 0.0721. They differ from BT.709 by at most 2e-4 per channel; Y differs by up to 1.4e-3
/// relative (pure blue; 6e-8 for grey).
#define RK_LUMA_THESIS vec3(0.2125f, 0.7154f, 0.0721f)

/// rk_luminance: relative luminance Y of linear Rec.709 RGB with the exact BT.709 weights.
/// Domain: any finite rgb (negative channels are not clamped: Y of out-of-gamut colours may be
/// negative). Max error: 2.2 ulp of |r| w_r + |g| w_g + |b| w_b (one dot; 3e7 random inputs +
/// refinement); for rgb >= 0 that is 2.2 ulp of Y. Cost: 1 dot.
RK_INLINE float rk_luminance(vec3 rgb) { return dot(rgb, RK_LUMA_BT709); }

/// rk_luminance_thesis: luminance with the thesis's 0.2125/0.7154/0.0721 weights (Eq. 3.13),
/// for reproducing its figures. Domain: any finite rgb (no clamping, as rk_luminance). Max error
/// vs the float64 dot with the decimal weights: within 3 ulp of |r| w_r + |g| w_g + |b| w_b (the
/// weights' float rounding and a 3-term dot); it differs from rk_luminance by at most
/// 2.1e-4 (r + g + b) for non-negative rgb (test_tonemap Color.LuminanceAndSrgb). Cost: 1 dot.
RK_INLINE float rk_luminance_thesis(vec3 rgb) { return dot(rgb, RK_LUMA_THESIS); }

/// rk_hdr_sanitize: maps any input to [0, RK_HDR_MAX]: negative values, -Inf and NaN become 0,
/// +Inf and huge values become RK_HDR_MAX. Written with comparisons (false for NaN) rather than
/// max(), whose NaN behaviour GLSL leaves undefined. Every tone operator calls it first.
/// Exact. Cost: 1 compare + 1 min + 1 select.
RK_INLINE float rk_hdr_sanitize(float x) { return x > 0.0f ? min(x, RK_HDR_MAX) : 0.0f; }

/// rk_hdr_sanitize (RGB): per channel, as the scalar form. Cost: 3 lanes.
RK_INLINE vec3 rk_hdr_sanitize(vec3 c)
{
    return vec3(rk_hdr_sanitize(c.x), rk_hdr_sanitize(c.y), rk_hdr_sanitize(c.z));
}

/// rk_srgb_encode: the exact IEC 61966-2-1 sRGB transfer function, linear -> non-linear:
/// 12.92 x for x <= 0.0031308, else 1.055 x^(1/2.4) - 0.055. Input sanitised and clamped to [0, 1].
/// Max error vs float64: 3e-7 on the CPU; on the GPU that of pow (GLSL: undefined, ~1e-6 on
/// llvmpipe). Cost: 1 pow (exp2 + log2) + 4 flops.
RK_INLINE float rk_srgb_encode(float x)
{
    float v = min(rk_hdr_sanitize(x), 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * pow(v, 1.0f / 2.4f) - 0.055f;
}

/// rk_srgb_encode (RGB): per channel. Cost: 3 pow.
RK_INLINE vec3 rk_srgb_encode(vec3 c)
{
    return vec3(rk_srgb_encode(c.x), rk_srgb_encode(c.y), rk_srgb_encode(c.z));
}

/// rk_srgb_decode: sRGB non-linear -> linear: x / 12.92 for x <= 0.04045, else
/// ((x + 0.055) / 1.055)^2.4. Input sanitised and clamped to [0, 1]. rk_srgb_decode(rk_srgb_encode(x))
/// returns x within 4e-7 (CPU). Cost: 1 pow + 3 flops.
RK_INLINE float rk_srgb_decode(float x)
{
    float v = min(rk_hdr_sanitize(x), 1.0f);
    return v <= 0.04045f ? v / 12.92f : pow((v + 0.055f) / 1.055f, 2.4f);
}

/// rk_srgb_decode (RGB): per channel. Cost: 3 pow.
RK_INLINE vec3 rk_srgb_decode(vec3 c)
{
    return vec3(rk_srgb_decode(c.x), rk_srgb_decode(c.y), rk_srgb_decode(c.z));
}

#endif  // RK_COLOR_GLSL
