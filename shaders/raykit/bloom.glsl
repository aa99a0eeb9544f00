// raykit — bloom.glsl: the per-pixel math of bloom: bright pass (the thesis's hard threshold, a C1
// soft knee, and the threshold-subtracting knee), Karis firefly weights, the weighted 2x2 average of
// the first downsample, the sum of the blurred levels and the composites.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/bloom.hpp, which also holds the
// CPU-only parts (Gaussian weights, merged linear-sampling taps, the chain sizes and a CPU reference
// of the whole bloom). The texture-sampling pass code is GLSL only: raykit/bloom_passes.glsl.
// Source: Fahlén 2005, "Illumination for Real-Time Rendering of Large Architectural Environments",
// §3.4: bloom = low-pass of the thresholded HDR image (luminance > 1.5), 4 levels from 1/8 size,
// Gaussian sigma = 3, added to the original. Beyond the thesis: soft knee against popping, Karis
// average against fireflies (Karis 2013, Jimenez 2014), energy-preserving composites.
//
// Conventions, used by every function here:
//   - Colours are linear, scene-referred RGB. Every colour or luminance input is first sanitised by
//     rk_bloom_sanitize: NaN, negative values and -Inf become 0, +Inf and values above RK_HDR_MAX
//     become RK_HDR_MAX (1e18), and denormals become 0 (so a CPU, which keeps denormals, takes the
//     same threshold decisions as a GPU that flushes them). Thresholds and knees are sanitised alike.
//   - Luminance is rk_luminance (BT.709 weights; the thesis's 0.2125/0.7154/0.0721 differ by
//     < 2e-4 per weight, < 1.4e-3 relative in Y) of the sanitised colour.
//   - The knee is clamped to [0, threshold], so the bright pass is exactly 0 at luminance 0 and
//     never amplifies a colour (every weight lies in [0, 1]).
// Every function returns finite values in [0, RK_HDR_MAX] (per channel) for every input, NaN and
// ±Inf included. Errors quoted are maxima against float64 formulas over dense samples
// (docs/dialect.md); tests/test_bloom.cpp checks them. GPU
// agreement (tests/gpu/parity_bloom.cpp, Mesa llvmpipe): bit-exact for every function except those
// built on the luminance's dot, which a GPU may fuse (2 ulp), and the knee bright passes, which
// scale that ulp by the knee's slope 1/K.
//
// @rk-es 310
// @rk-es300
#ifndef RK_BLOOM_GLSL
#define RK_BLOOM_GLSL

#include "color.glsl"

/// The thesis's bright-pass threshold (luminance, scene-referred units where 1 = diffuse white).
#define RK_BLOOM_THRESHOLD 1.5f

/// Bright-pass modes (the `mode` argument of rk_bloom_weight / rk_bloom_bright_pass).
#define RK_BLOOM_MODE_HARD 0       // thesis: keep the pixel when Y > threshold, else 0 (pops)
#define RK_BLOOM_MODE_SOFT_KNEE 1  // C1 quadratic ramp of the keep weight over [T - K, T + K]
#define RK_BLOOM_MODE_SUBTRACT 2   // keep only the part above the threshold, quadratic knee

/// Composite modes (the `mode` argument of rk_bloom_composite).
#define RK_BLOOM_COMPOSITE_ADD 0       // thesis: hdr + strength * bloom (adds energy)
#define RK_BLOOM_COMPOSITE_MIX 1       // mix(hdr, bloom, strength) (Jimenez 2014)
#define RK_BLOOM_COMPOSITE_CONSERVE 2  // hdr + strength * (bloom - bright): moves energy only

/// Most one-sided taps a blur pass takes (centre included): 2 * 16 - 1 = 31 fetches, enough for
/// radius 30 (sigma 10 at 3 sigma).
#define RK_BLOOM_MAX_TAPS 16

/// Largest strength / level weight the composites accept (larger values are clamped).
#define RK_BLOOM_WEIGHT_MAX 1.0e6f

/// rk_bloom_sanitize: rk_hdr_sanitize with denormals flushed: x in [RK_FLT_MIN, RK_HDR_MAX] is
/// kept, larger values and +Inf give RK_HDR_MAX, anything else (NaN, -Inf, negative, ±0,
/// denormals) gives 0. Written with a comparison, which is false for NaN. Exact.
/// Cost: 1 compare + 1 min + 1 select.
RK_INLINE float rk_bloom_sanitize(float x) { return x >= RK_FLT_MIN ? min(x, RK_HDR_MAX) : 0.0f; }

/// rk_bloom_sanitize (RGB): per channel. Cost: 3 lanes.
RK_INLINE vec3 rk_bloom_sanitize(vec3 c)
{
    return vec3(rk_bloom_sanitize(c.x), rk_bloom_sanitize(c.y), rk_bloom_sanitize(c.z));
}

/// rk_bloom_luminance: BT.709 luminance of the sanitised colour, itself sanitised (a luminance
/// below RK_FLT_MIN is 0). Range [0, RK_HDR_MAX]. Max error vs float64: 2.2 ulp (4e7 random +
/// refinement); the GPU's dot may fuse multiply-adds and differ by 2 ulp (llvmpipe: 2).
/// Cost: 1 dot + 4 sanitize.
RK_INLINE float rk_bloom_luminance(vec3 rgb) { return rk_bloom_sanitize(rk_luminance(rk_bloom_sanitize(rgb))); }

/// rk_bloom_knee: the knee actually used, min(sanitize(knee), sanitize(threshold)). Exact. Cost: 1 min.
RK_INLINE float rk_bloom_knee(float threshold, float knee)
{
    return min(rk_bloom_sanitize(knee), rk_bloom_sanitize(threshold));
}

/// rk_bloom_cutoff: the luminance at or below which the bright pass of `mode` is exactly 0:
/// T for RK_BLOOM_MODE_HARD (and any unknown mode), T - K for the two knee modes (T, K sanitised,
/// K clamped to [0, T], so the cutoff is in [0, T]). The reduction that decides whether to skip
/// bloom counts pixels with rk_bloom_luminance > cutoff. Exact (T - K is one rounding, and the bright
/// pass compares against the very same expression). Cost: 1 sub + 2 sanitize.
RK_INLINE float rk_bloom_cutoff(float threshold, float knee, int mode)
{
    float t = rk_bloom_sanitize(threshold);
    float k = min(rk_bloom_sanitize(knee), t);
    return (mode == RK_BLOOM_MODE_SOFT_KNEE || mode == RK_BLOOM_MODE_SUBTRACT) ? t - k : t;
}

/// rk_bloom_weight_hard: the thesis's hard threshold: 1 when lum > threshold, else 0. Both inputs
/// sanitised (NaN threshold = 0: everything with lum > 0 passes). Discontinuous at the threshold,
/// which is why bloom pops when a pixel crosses it. Exact. Cost: 1 compare.
RK_INLINE float rk_bloom_weight_hard(float lum, float threshold)
{
    return rk_bloom_sanitize(lum) > rk_bloom_sanitize(threshold) ? 1.0f : 0.0f;
}

/// rk_bloom_weight_soft_knee: the hard step smoothed over [T - K, T + K] by two quadratic pieces:
/// with u = (lum - (T - K)) / 2K, w = 2u^2 for u <= 1/2 and 1 - 2(1 - u)^2 above. It is 0 for
/// lum <= T - K and 1 for lum >= T + K (K > 0; with K = 0, 1 for lum > T), i.e. exactly the hard
/// weight outside the knee; C1 everywhere
/// (slopes 0 at both ends, 1/K at lum = T where w = 1/2); its integral over lum equals the hard
/// step's, so on average it passes the same energy. K = 0 gives the hard weight exactly.
/// Domain: all inputs sanitised, K clamped to [0, T]. Range [0, 1].
/// Max error vs float64 (4e7 random + refinement): 6.4e-7 absolute for K >= T / 10; in general
/// 0.68 FLT_EPSILON (T + K) / K (the rounding of T - K amplified by the slope 1/K: 4.5e-5 at
/// K = T / 750). A luminance that differs by an ulp
/// (GPU fma) moves w by up to ulp / K. Cost: 1 div + ~8 flops + 2 branches.
RK_INLINE float rk_bloom_weight_soft_knee(float lum, float threshold, float knee)
{
    float y = rk_bloom_sanitize(lum);
    float t = rk_bloom_sanitize(threshold);
    float k = min(rk_bloom_sanitize(knee), t);
    float lo = t - k;
    if (y <= lo) {
        return 0.0f;
    }
    if (y >= t + k) {
        return 1.0f;  // also every y > t when k = 0
    }
    // Here lo < y < t + k, so k >= RK_FLT_MIN (k is sanitised); the floor only guards round-off.
    float u = rk_saturate((y - lo) / max(2.0f * k, RK_FLT_MIN));
    return u <= 0.5f ? 2.0f * u * u : 1.0f - 2.0f * rk_sqr(1.0f - u);
}

/// rk_bloom_weight_subtract: the scale factor of the threshold-subtracting bright pass with a
/// quadratic knee (the curve of Unity's and Unreal's bloom): output luminance
/// f(lum) = max(q, lum - T) with q = min(lum - (T - K), 2K)^2 / 4K, and 0 for lum <= T - K; the
/// factor is f / lum. f is C1 (f = 0, f' = 0 at T - K; f = K, f' = 1 at T + K) and equals lum - T
/// above the knee, so the colour keeps only its part above the threshold. K = 0 gives the hard
/// subtract max(lum - T, 0) / lum (C0, a kink at T).
/// Domain: all inputs sanitised, K clamped to [0, T] (then f <= lum, so the factor is in [0, 1]).
/// Max error vs float64: 1.3e-7 absolute over T in [0, 3], K in [0, 1] (4e7 random + refinement).
/// Cost: 3 div + ~8 flops.
RK_INLINE float rk_bloom_weight_subtract(float lum, float threshold, float knee)
{
    float y = rk_bloom_sanitize(lum);
    float t = rk_bloom_sanitize(threshold);
    float k = min(rk_bloom_sanitize(knee), t);
    float lo = t - k;
    if (y <= lo) {
        return 0.0f;
    }
    // y > lo >= 0 and y is sanitised, so y >= RK_FLT_MIN: the divisions are safe. q / y is taken
    // as (m / y)(m / 4K), two ratios in [0, 1], rather than m^2 / 4K / y: for tiny T and K, m^2 and
    // q are denormal, and zero on drivers that flush denormals.
    float m = min(y - lo, 2.0f * k);
    float q_y = (m / max(y, RK_FLT_MIN)) * (m / max(4.0f * k, RK_FLT_MIN));
    return min(max(q_y, (y - t) / max(y, RK_FLT_MIN)), 1.0f);
}

/// rk_bloom_weight: the bright-pass weight of `mode` (RK_BLOOM_MODE_*; unknown modes act as
/// RK_BLOOM_MODE_HARD). `knee` is ignored by the hard mode. Same domain, error and cost as the
/// selected function (plus a uniform branch on the GPU).
RK_INLINE float rk_bloom_weight(float lum, float threshold, float knee, int mode)
{
    if (mode == RK_BLOOM_MODE_SOFT_KNEE) {
        return rk_bloom_weight_soft_knee(lum, threshold, knee);
    }
    if (mode == RK_BLOOM_MODE_SUBTRACT) {
        return rk_bloom_weight_subtract(lum, threshold, knee);
    }
    return rk_bloom_weight_hard(lum, threshold);
}

/// rk_bloom_bright_pass_hard: the thesis's bright pass: the sanitised colour where its luminance
/// exceeds the threshold (RK_BLOOM_THRESHOLD = 1.5 in the thesis), black elsewhere. Exact (a select).
/// Cost: 1 dot + 1 compare + sanitising (7 compares).
RK_INLINE vec3 rk_bloom_bright_pass_hard(vec3 rgb, float threshold)
{
    vec3 c = rk_bloom_sanitize(rgb);
    return c * rk_bloom_weight_hard(rk_bloom_luminance(c), threshold);
}

/// rk_bloom_bright_pass_soft_knee: the sanitised colour times rk_bloom_weight_soft_knee of its
/// luminance: no pop when a pixel crosses the threshold, identical to the hard pass outside
/// [T - K, T + K]. Max error vs float64: 9.0e-8 relative per channel (against the float64 weight at
/// the float luminance +- 1 ulp; 4e7 random + refinement; see rk_bloom_weight_soft_knee for small
/// K). GPU vs CPU: the luminance's fma ulp times the slope 1/K (6.7e-6 seen at K = 0.2).
/// Cost: 1 dot + 1 div + ~12 flops.
RK_INLINE vec3 rk_bloom_bright_pass_soft_knee(vec3 rgb, float threshold, float knee)
{
    vec3 c = rk_bloom_sanitize(rgb);
    return c * rk_bloom_weight_soft_knee(rk_bloom_luminance(c), threshold, knee);
}

/// rk_bloom_bright_pass_subtract: the sanitised colour scaled to keep only the luminance above the
/// threshold (quadratic knee of width 2K around T). Max error vs float64: 1.5e-7 relative per
/// channel (weight at the float luminance +- 1 ulp; 4e7 random + refinement).
/// Cost: 1 dot + 2 div + ~12 flops.
RK_INLINE vec3 rk_bloom_bright_pass_subtract(vec3 rgb, float threshold, float knee)
{
    vec3 c = rk_bloom_sanitize(rgb);
    return c * rk_bloom_weight_subtract(rk_bloom_luminance(c), threshold, knee);
}

/// rk_bloom_bright_pass: the bright pass of `mode` (RK_BLOOM_MODE_*). Output in [0, RK_HDR_MAX]^3,
/// never brighter than the sanitised input. Exactly 0 when rk_bloom_luminance(rgb) <=
/// rk_bloom_cutoff(threshold, knee, mode). Same error and cost as the selected function.
RK_INLINE vec3 rk_bloom_bright_pass(vec3 rgb, float threshold, float knee, int mode)
{
    vec3 c = rk_bloom_sanitize(rgb);
    return c * rk_bloom_weight(rk_bloom_luminance(c), threshold, knee, mode);
}

/// rk_bloom_karis_weight: Karis's firefly weight 1 / (1 + luminance) of the sanitised colour.
/// Weighting samples by it before averaging (rk_bloom_karis_average) bounds what one extremely
/// bright texel contributes (c * w < 1 / 0.0722 per channel), so sub-pixel highlights do not flicker
/// into big blobs. Range [1e-18, 1]. Max error vs float64: 4.9 ulp (3.1 for channels <= 8; 4e7
/// random + refinement). Cost: 1 dot + 1 div.
RK_INLINE float rk_bloom_karis_weight(vec3 rgb) { return 1.0f / (1.0f + rk_bloom_luminance(rgb)); }

/// rk_bloom_weighted_average: sum(w_i c_i) / sum(w_i) of four sanitised colours; the filter weights
/// w (e.g. rk_bloom_bilinear_weights, or vec4(1) for a 2x2 box) are sanitised and clamped to [0, 1];
/// all-zero weights give black. The weights are divided by their sum before the products, so
/// tiny weights never make a product denormal (a GPU would flush it). Result within the
/// channel-wise range of the c_i with a positive weight, up to rounding: 1e-6 relative, plus
/// RK_FLT_MIN absolute where a product falls below RK_FLT_MIN (a small weight times a colour near
/// RK_FLT_MIN). Max error vs float64: 4.5e-7 relative (4e7 random + refinement). Cost: 1 div,
/// 4 mul, 4 madd (vec3), 3 add.
RK_INLINE vec3 rk_bloom_weighted_average(vec3 c0, vec3 c1, vec3 c2, vec3 c3, vec4 w)
{
    float w0 = min(rk_bloom_sanitize(w.x), 1.0f);
    float w1 = min(rk_bloom_sanitize(w.y), 1.0f);
    float w2 = min(rk_bloom_sanitize(w.z), 1.0f);
    float w3 = min(rk_bloom_sanitize(w.w), 1.0f);
    float inv = 1.0f / max(w0 + w1 + w2 + w3, RK_FLT_MIN);
    vec3 sum = (w0 * inv) * rk_bloom_sanitize(c0) + (w1 * inv) * rk_bloom_sanitize(c1) +
               (w2 * inv) * rk_bloom_sanitize(c2) + (w3 * inv) * rk_bloom_sanitize(c3);
    return min(sum, vec3(RK_HDR_MAX));
}

/// rk_bloom_karis_average: rk_bloom_weighted_average with every weight multiplied by
/// rk_bloom_karis_weight of its colour (Karis 2013; used on the first downsample only, Jimenez
/// 2014). Equal colours average to themselves; a lone texel of luminance L among black ones
/// contributes ~1/(1 + L) of its weight instead of all of it. Not energy-preserving by design.
/// The filter weights are scaled so that the largest is 1 before the Karis factors (>= 1e-18)
/// multiply them, so tiny weights cannot underflow to zero; the range promise is the weighted
/// average's. Max error vs float64: 7.4e-7 relative (4e7 random + refinement).
/// Cost: 4 dot + 5 div + 3 max + the weighted average.
RK_INLINE vec3 rk_bloom_karis_average(vec3 c0, vec3 c1, vec3 c2, vec3 c3, vec4 w)
{
    vec4 k = vec4(rk_bloom_karis_weight(c0), rk_bloom_karis_weight(c1), rk_bloom_karis_weight(c2),
                  rk_bloom_karis_weight(c3));
    vec4 ws = vec4(min(rk_bloom_sanitize(w.x), 1.0f), min(rk_bloom_sanitize(w.y), 1.0f),
                   min(rk_bloom_sanitize(w.z), 1.0f), min(rk_bloom_sanitize(w.w), 1.0f));
    float top = max(max(ws.x, ws.y), max(ws.z, ws.w));
    return rk_bloom_weighted_average(c0, c1, c2, c3, ws * (1.0f / max(top, RK_FLT_MIN)) * k);
}

/// rk_bloom_source_texel: the position, in texel units of a source of `src_size` texels (texel i
/// centred at i), that a fragment at window coordinate `frag` (pixel centres at i + 0.5) of a
/// `dst_size` target samples when both cover the same [0, 1] range: frag / dst * src - 0.5, as a
/// GL_LINEAR fetch at u = frag / dst would. For a 2:1 reduction it lands on the corner between
/// four texels (a 2x2 box). Domain: any float: sizes clamped to [1, 65536] and frag to
/// [0, dst_size], NaN taken as the lower bound (every result is in [-0.5, src_size - 0.5]). Max
/// error: 2 roundings (< 2.5e-4 texel for sizes < 4096; 2e7 random + refinement).
/// Cost: 1 div + 1 madd, 3 compares.
RK_INLINE float rk_bloom_source_texel(float frag, float dst_size, float src_size)
{
    float d = dst_size > 1.0f ? min(dst_size, 65536.0f) : 1.0f;
    float s = src_size > 1.0f ? min(src_size, 65536.0f) : 1.0f;
    float f = frag > 0.0f ? min(frag, d) : 0.0f;
    return f / d * s - 0.5f;
}

/// rk_bloom_bilinear_weights: the four bilinear weights of a fetch at texel position p, for the
/// texels floor(p) + (0,0), (1,0), (0,1), (1,1), in that order. The fraction is p - floor(p) (not
/// fract(), to read the same in both languages). Sum 1 up to one rounding, each weight in [0, 1].
/// Domain: any float: p clamped to [-1e7, 1e7], NaN taken as -1e7 (weights (1, 0, 0, 0)). Max
/// error: 9.0e-8 absolute per weight (2 roundings; not in ulps of a weight near 0; 4e7 random +
/// refinement). Cost: 2 floor + 6 flops.
RK_INLINE vec4 rk_bloom_bilinear_weights(vec2 p)
{
    float px = p.x > -1.0e7f ? min(p.x, 1.0e7f) : -1.0e7f;
    float py = p.y > -1.0e7f ? min(p.y, 1.0e7f) : -1.0e7f;
    float tx = px - floor(px);
    float ty = py - floor(py);
    return vec4((1.0f - tx) * (1.0f - ty), tx * (1.0f - ty), (1.0f - tx) * ty, tx * ty);
}

/// rk_bloom_sum_levels: w.x l0 + w.y l1 + w.z l2 + w.w l3 of the (magnified) blurred levels. Colours
/// sanitised, weights sanitised and clamped to [0, RK_BLOOM_WEIGHT_MAX]; result clamped to
/// RK_HDR_MAX. The thesis adds the 4 levels with weight 1; the energy-preserving composites want
/// weights summing to 1. Max error vs float64: 2.4e-7 relative (4e7 random + refinement).
/// Cost: 4 madd (vec3).
RK_INLINE vec3 rk_bloom_sum_levels(vec3 l0, vec3 l1, vec3 l2, vec3 l3, vec4 w)
{
    vec3 s = min(rk_bloom_sanitize(w.x), RK_BLOOM_WEIGHT_MAX) * rk_bloom_sanitize(l0) +
             min(rk_bloom_sanitize(w.y), RK_BLOOM_WEIGHT_MAX) * rk_bloom_sanitize(l1) +
             min(rk_bloom_sanitize(w.z), RK_BLOOM_WEIGHT_MAX) * rk_bloom_sanitize(l2) +
             min(rk_bloom_sanitize(w.w), RK_BLOOM_WEIGHT_MAX) * rk_bloom_sanitize(l3);
    return min(s, vec3(RK_HDR_MAX));
}

/// rk_bloom_composite_add: the thesis's composite hdr + strength * bloom (both sanitised; strength
/// sanitised and clamped to [0, RK_BLOOM_WEIGHT_MAX]; result clamped to RK_HDR_MAX). Adds energy:
/// a scene lit above the threshold gets brighter. Max error vs float64: 1.2e-7 relative (4e7
/// random + refinement).
/// Cost: 1 madd (vec3).
RK_INLINE vec3 rk_bloom_composite_add(vec3 hdr, vec3 bloom, float strength)
{
    float s = min(rk_bloom_sanitize(strength), RK_BLOOM_WEIGHT_MAX);
    return min(rk_bloom_sanitize(hdr) + s * rk_bloom_sanitize(bloom), vec3(RK_HDR_MAX));
}

/// rk_bloom_composite_mix: mix(hdr, bloom, strength) = hdr (1 - s) + bloom s (Jimenez 2014), written
/// out so both languages round alike; s = strength clamped to [0, 1], colours sanitised, result
/// clamped to RK_HDR_MAX (the two products can round one ulp above it). Preserves
/// energy when bloom is a normalised blur of the whole image (threshold 0); with a threshold it
/// also darkens everything below it by (1 - s) — see rk_bloom_composite_conserve.
/// Max error vs float64: 1.8e-7 relative (4e7 random + refinement). Cost: 2 mul + 1 add (vec3).
RK_INLINE vec3 rk_bloom_composite_mix(vec3 hdr, vec3 bloom, float strength)
{
    float s = rk_saturate(rk_bloom_sanitize(strength));
    return min(rk_bloom_sanitize(hdr) * (1.0f - s) + rk_bloom_sanitize(bloom) * s, vec3(RK_HDR_MAX));
}

/// rk_bloom_composite_conserve: hdr + s (bloom - bright), where bright is the bright pass of this
/// pixel and bloom the normalised blur of the bright pass (level weights summing to 1): a fraction s
/// of the light above the threshold is moved to the neighbourhood instead of added, so the image's
/// total energy is kept (up to the black border and the Karis weighting) and pixels below the
/// threshold stay untouched; with threshold 0 and the hard mode it equals rk_bloom_composite_mix.
/// s = strength clamped to [0, 1]; colours sanitised; hdr - s bright floored at 0 (in case bright
/// was not derived from hdr). Max error vs float64: 1.2e-7 of hdr + s bloom per channel (4e7
/// random + refinement; relative to the result it is unbounded where hdr - s bright cancels).
/// tests/test_bloom.cpp
/// measures the energy change of a whole CONSERVE bloom: 1.4e-9 relative (ADD: +19%).
/// Cost: 2 madd + 1 max (vec3).
RK_INLINE vec3 rk_bloom_composite_conserve(vec3 hdr, vec3 bright, vec3 bloom, float strength)
{
    float s = rk_saturate(rk_bloom_sanitize(strength));
    vec3 kept = max(rk_bloom_sanitize(hdr) - s * rk_bloom_sanitize(bright), vec3(0.0f));
    return min(kept + s * rk_bloom_sanitize(bloom), vec3(RK_HDR_MAX));
}

/// rk_bloom_composite: the composite of `mode` (RK_BLOOM_COMPOSITE_*; unknown modes act as ADD).
/// `bright` is read by the CONSERVE mode only. Same error and cost as the selected function.
RK_INLINE vec3 rk_bloom_composite(vec3 hdr, vec3 bright, vec3 bloom, float strength, int mode)
{
    if (mode == RK_BLOOM_COMPOSITE_MIX) {
        return rk_bloom_composite_mix(hdr, bloom, strength);
    }
    if (mode == RK_BLOOM_COMPOSITE_CONSERVE) {
        return rk_bloom_composite_conserve(hdr, bright, bloom, strength);
    }
    return rk_bloom_composite_add(hdr, bloom, strength);
}

#endif  // RK_BLOOM_GLSL
