// raykit — exposure.glsl: log-average luminance terms, Reinhard 2002 automatic key and white point,
// EV100 exposure, frame-rate-independent eye adaptation and luminance-histogram helpers.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/exposure.hpp, which adds the
// CPU references (log_average_luminance, luminance_histogram, reinhard_auto_params) and the
// reduction-chain planner. The GPU reduction kernels are in luminance_reduce.glsl.
// Sources: Fahlén 2005, "Illumination for Real-Time Rendering of Large Architectural Environments",
// §3.3.1 (Eq. 3.14, log-average with a small delta), Reinhard 2002 "Parameter estimation for
// photographic tone reproduction" (Eq. 3.18-3.19 of the thesis, read with Reinhard's exponents),
// Lagarde & de Rousiers 2014 "Moving Frostbite to PBR" §5.1 (EV100, exposure = 1 / (1.2 * 2^EV100)),
// Pattanaik et al. 2000 / Krawczyk et al. 2005 (exponential adaptation
// L_a += (L_t - L_a)(1 - exp(-dt / tau))).
//
// Conventions:
//   lum        relative luminance (rk_luminance of linear Rec.709), scene-referred, >= 0.
//   log2 term  every average here is a geometric mean, computed on log2(delta + lum); log2 rather
//              than the thesis's natural log (the same mean: exp(mean ln x) = exp2(mean log2 x)),
//              because histograms and EV are in stops.
//   delta      Eq. 3.14's "small value" that keeps log(0) finite. Default RK_LOG_LUM_DELTA = 1e-4:
//              a black pixel counts as 1e-4 (-13.29 stops below diffuse white, darker than
//              starlight in cd/m^2), so no pixel can pull the average below that floor, a pixel
//              of luminance L >> delta enters with the factor (1 + delta / L), and zero,
//              denormal and flushed-to-zero pixels give the same term on every backend.
// Inputs: every function is total over ALL floats, NaN and +-Inf included (the issue's clamping
// contract, stronger than the dialect's "finite inputs"): luminances go through rk_hdr_sanitize
// (negative, -Inf, NaN -> 0; +Inf -> RK_HDR_MAX), other parameters through rk_exposure_clamp
// (NaN -> the lower bound). Outputs are always finite.
// Errors quoted are measured by tests/test_exposure.cpp (vs float64) and tests/gpu/parity_exposure.cpp
// (GPU vs this file's C++ build on Mesa llvmpipe).
//
// @rk-es 310
// @rk-es300
#ifndef RK_EXPOSURE_GLSL
#define RK_EXPOSURE_GLSL

#include "color.glsl"

/// Default delta of the log-average (Eq. 3.14): see the file header.
#define RK_LOG_LUM_DELTA 1.0e-4f
/// Range of log2 luminance the functions work in: log2(RK_FLT_MIN) and just below log2(RK_HDR_MAX).
#define RK_LOG2_LUM_MIN (-126.0f)
#define RK_LOG2_LUM_MAX 59.79f
/// Reinhard 2002's middle grey, the key for an image whose log-average is its geometric mid-range.
#define RK_EXPOSURE_MIDDLE_GREY 0.18f
/// Smallest log2 dynamic range (stops) the automatic key divides by; below it the key tends to
/// 0.18 continuously instead of dividing 0 by 0 on flat images.
#define RK_REINHARD_MIN_RANGE 0.01f
/// Smallest luminance the Reinhard estimates take (so that Lmax / Lmin <= 1e36 stays finite).
#define RK_REINHARD_LUM_MIN 1.0e-18f
/// Lagarde & de Rousiers 2014: ISO S = 100 and reflected-light meter constant K = 12.5 (S/K = 8).
#define RK_EV100_S 100.0f
#define RK_EV100_K 12.5f
/// |EV100| limit of the exposure functions: exposures lie in [2^-64/1.2, 2^64/1.2].
#define RK_EV100_LIMIT 64.0f
/// Adaptation: dt and tau are clamped to [0, RK_ADAPT_TIME_MAX] and [RK_ADAPT_TAU_MIN, RK_ADAPT_TIME_MAX]
/// seconds; tau at its minimum means "instant" for any frame time above ~1e-4 s.
#define RK_ADAPT_TAU_MIN 1.0e-6f
#define RK_ADAPT_TIME_MAX 1.0e30f

// Layout of the result buffer written by luminance_reduce.glsl's rk_luminance_reduce_finish (floats),
// shared here so that the C++ host reads the same indices.
#define RK_LUM_RESULT_LOG_AVERAGE 0     // exp2(mean log2(delta + L))
#define RK_LUM_RESULT_MEAN_LOG2 1       // mean log2(delta + L)
#define RK_LUM_RESULT_HIST_AVERAGE 2    // exp2 of the histogram's percentile-window mean (0 without histogram)
#define RK_LUM_RESULT_ROBUST_MIN 3      // histogram percentile luminances (0 without histogram)
#define RK_LUM_RESULT_ROBUST_MAX 4
#define RK_LUM_RESULT_KEY 5             // Reinhard 2002 alpha (0.18 without histogram)
#define RK_LUM_RESULT_WHITE 6           // Reinhard 2002 L_white (RK_HDR_MAX without histogram)
#define RK_LUM_RESULT_ADAPTED 7         // adapted luminance (also the adaptation state)
#define RK_LUM_RESULT_EV100 8           // EV100 of the adapted luminance
#define RK_LUM_RESULT_EXPOSURE 9        // exposure of the adapted luminance with compensation
#define RK_LUM_RESULT_COUNT 10

/// rk_exposure_clamp: x clamped to [lo, hi] (lo <= hi), with NaN -> lo and +-Inf -> hi / lo.
/// Written with a comparison (false for NaN) because GLSL leaves clamp()/max() of NaN undefined.
/// Exact. Cost: 1 compare + 1 min + 1 select.
RK_INLINE float rk_exposure_clamp(float x, float lo, float hi) { return x > lo ? min(x, hi) : lo; }

/// rk_log2_luminance: the per-pixel term log2(delta + L) of the log-average (Eq. 3.14 in stops).
/// Domain: any float lum (sanitised: negative/NaN -> 0, +Inf -> RK_HDR_MAX); delta clamped to
/// [0, RK_HDR_MAX] (NaN -> 0); delta + L is floored at RK_FLT_MIN, so delta = 0 maps black to
/// -126 instead of -Inf. Range: [-126, 60.8].
/// Max error vs float64 log2(delta + L): 1.5e-7 * max(1, |result|) on the CPU (1 ulp of log2 plus
/// the rounding of delta + L; every float L for 4 deltas + 4e7 random + refinement); llvmpipe's
/// log2 is within 1.9e-6 absolute of the CPU build at 20 stops (parity_exposure.cpp).
/// Cost: 1 add, 1 max, 1 log2, sanitise.
RK_INLINE float rk_log2_luminance(float lum, float delta)
{
    float d = rk_exposure_clamp(delta, 0.0f, RK_HDR_MAX);
    return log2(max(rk_hdr_sanitize(lum) + d, RK_FLT_MIN));
}

/// rk_log2_luminance (RGB): the term for a linear Rec.709 colour: channels sanitised first (so a
/// NaN or negative channel counts as 0, not the whole pixel), then BT.709 luminance.
/// Same domain, range and error as the scalar form (plus 2.2 ulp of the dot).
/// Cost: 1 dot + scalar form.
RK_INLINE float rk_log2_luminance(vec3 rgb, float delta)
{
    return rk_log2_luminance(rk_luminance(rk_hdr_sanitize(rgb)), delta);
}

/// rk_log_average_from_sum: the log-average luminance exp2(sum / count) from a sum of
/// rk_log2_luminance terms over `count` pixels (the final step of the reduction).
/// Domain: any floats; count clamped to [1, RK_FLT_MAX] (an empty image gives exp2(sum)), the mean
/// to [RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX] (NaN -> the minimum). Range: [RK_FLT_MIN, ~1e18].
/// The result still contains delta (Eq. 3.14 as written; subtract it for images without black).
/// Max error (CPU): 2 (1 + 0.35 |mean|) ulp relative, the rounding of sum / count amplified by exp2
/// (0.85 ulp for |mean| <= 1, 45 ulp at |mean| ~ 85-126; 2.5e7 random + refinement); llvmpipe
/// adds ~1 ulp. Cost: 1 div, 1 exp2.
RK_INLINE float rk_log_average_from_sum(float sum_log2, float count)
{
    float n = rk_exposure_clamp(count, 1.0f, RK_FLT_MAX);
    float m = rk_exposure_clamp(rk_div(sum_log2, n), RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX);  // n may exceed 2^126
    return exp2(m);
}

/// rk_reinhard_auto_key: Reinhard 2002's automatic key (thesis Eq. 3.18, exponents restored):
///   alpha = 0.18 * 4^((2 log2 Lavg - log2 Lmin - log2 Lmax) / (log2 Lmax - log2 Lmin)).
/// A log-average at the geometric mid-range gives 0.18, at Lmax 0.72, at Lmin 0.045.
/// Evaluated as (log2(Lavg / Lmin) + log2(Lavg / Lmax)) / log2(Lmax / Lmin): logs of ratios keep
/// full relative precision on narrow ranges, where differences of logs cancel.
/// Domain: luminances clamped to [RK_REINHARD_LUM_MIN, RK_HDR_MAX] = [1e-18, 1e18] (NaN and
/// negatives -> 1e-18, +Inf -> 1e18; so every ratio stays a normal float); Lmin/Lmax may come in
/// either order; the ratio is clamped to [-1, 1] (a log-average outside the robust [Lmin, Lmax]
/// saturates the key to [0.045, 0.72]); the range is floored at RK_REINHARD_MIN_RANGE stops, so flat
/// images give ~0.18 instead of 0/0. Use Lmin/Lmax of the same delta + L term as the log-average.
/// Test vectors (Fahlén 2005 Eq. 3.18, Lmin 0.01, Lmax 100): Lavg 1 -> 0.18, 10 -> 0.36, 0.1 -> 0.09.
/// Max error vs float64 (4e7 random + refinement): 6.1e-7 relative for ranges >= 1 stop; on
/// narrower ranges it grows as ~5.5e-7 / range (stops), the size of the change a 1-ulp perturbation
/// of the inputs causes (the function is that ill-conditioned there). Cost: 3 div, 3 log2, 1 exp2.
RK_INLINE float rk_reinhard_auto_key(float log_average, float lum_min, float lum_max)
{
    float la = rk_exposure_clamp(log_average, RK_REINHARD_LUM_MIN, RK_HDR_MAX);
    float a = rk_exposure_clamp(lum_min, RK_REINHARD_LUM_MIN, RK_HDR_MAX);
    float b = rk_exposure_clamp(lum_max, RK_REINHARD_LUM_MIN, RK_HDR_MAX);
    float lo = min(a, b);
    float hi = max(a, b);
    float range = max(log2(hi / lo), RK_REINHARD_MIN_RANGE);
    float t = clamp((log2(la / lo) + log2(la / hi)) / range, -1.0f, 1.0f);
    return RK_EXPOSURE_MIDDLE_GREY * exp2(2.0f * t);
}

/// rk_reinhard_auto_white: Reinhard 2002's white point (thesis Eq. 3.19, exponents restored):
///   L_white = 1.5 * 2^(log2 Lmax - log2 Lmin - 5),
/// in the units of the scaled luminance L_s. 5 stops of range give 1.5; Lmin 0.01, Lmax 100 give
/// 468.75. Domain: as rk_reinhard_auto_key (either order); the exponent is clamped to [-5, 59],
/// so the result lies in [0.046875, 1.5 * 2^59 ~ 8.6e17]. Max error vs float64 (2e7 random +
/// refinement): 8.2e-7 relative for Lmin in [1e-6, 1e3], Lmax / Lmin <= 1e8 (test_exposure's
/// domain), 1.5e-6 over [1e-18, 1e18] (exp2 of a larger exponent). Cost: 1 div, 1 log2, 1 exp2.
RK_INLINE float rk_reinhard_auto_white(float lum_min, float lum_max)
{
    float a = rk_exposure_clamp(lum_min, RK_REINHARD_LUM_MIN, RK_HDR_MAX);
    float b = rk_exposure_clamp(lum_max, RK_REINHARD_LUM_MIN, RK_HDR_MAX);
    return 1.5f * exp2(min(log2(max(a, b) / min(a, b)) - 5.0f, 59.0f));
}

/// rk_ev100_from_luminance: exposure value at ISO 100 of an average scene luminance (cd/m^2),
/// EV100 = log2(L * S / K) = log2(8 L) (Lagarde & de Rousiers 2014, Eq. 12; S = 100, K = 12.5).
/// Domain: lum sanitised and floored at RK_FLT_MIN; range [-123, 62.8]. Max error vs float64:
/// 2.0e-6 absolute over every float L in [1e-12, 1e12] (half an ulp of log2 at 38 EV; the scaling
/// by 8 is exact). Cost: 1 mul, 1 log2.
RK_INLINE float rk_ev100_from_luminance(float lum)
{
    return log2(max(rk_hdr_sanitize(lum), RK_FLT_MIN) * (RK_EV100_S / RK_EV100_K));
}

/// rk_ev100_from_camera: EV100 of physical camera settings, log2(N^2 / t * 100 / S) for f-number
/// N, shutter time t (s) and ISO S (Lagarde & de Rousiers 2014, Eq. 7). Domain: each clamped to
/// [1e-6, 1e6] (NaN -> 1e-6). f/16, 1/100 s, ISO 100 gives 14.64. Max error vs float64: 1.3e-6
/// absolute over f/1-f/22, 1e-4-10 s, ISO 50-12800 (2e7 random + refinement).
/// Cost: 3 mul/div, 1 log2.
RK_INLINE float rk_ev100_from_camera(float aperture, float shutter_time, float iso)
{
    float n = rk_exposure_clamp(aperture, 1.0e-6f, 1.0e6f);
    float t = rk_exposure_clamp(shutter_time, 1.0e-6f, 1.0e6f);
    float s = rk_exposure_clamp(iso, 1.0e-6f, 1.0e6f);
    return log2((n * n) / t * (100.0f / s));
}

/// rk_exposure_from_ev100: the scale that maps scene luminance to the sensor's [0, 1] range,
/// 1 / (1.2 * 2^EV100) (Lagarde & de Rousiers 2014, Eq. 19: 1.2 * 2^EV100 is the saturating
/// luminance, q = 0.65, 78 / (q S) * N^2 / t). Domain: EV100 clamped to [-64, 64] (NaN -> -64),
/// result in [4.5e-20, 1.5e19]. Max error: 1.9 ulp (exp2, 1 division and the rounding of 1.2f;
/// every float in [-64, 64]). Cost: 1 exp2, 1 div.
RK_INLINE float rk_exposure_from_ev100(float ev100)
{
    return exp2(-rk_exposure_clamp(ev100, -RK_EV100_LIMIT, RK_EV100_LIMIT)) / 1.2f;
}

/// rk_exposure_from_luminance: automatic EV100 exposure for an average luminance with an exposure
/// compensation in stops (positive brightens): rk_exposure_from_ev100(EV100(L) - compensation).
/// Without compensation, lum * exposure = 1 / 9.6 = 0.104 (the average lands at ~10% of the
/// saturating luminance). Domain: lum as rk_ev100_from_luminance, compensation clamped to [-64, 64]
/// (NaN -> -64). Max error vs float64 (the log2/exp2 round trip): 1.5e-6 relative for every float
/// L in [1e-12, 1e12] with compensation 0; 2.8e-6 with any compensation (2e7 random + refinement).
/// Cost: 1 log2, 1 exp2, 1 div.
RK_INLINE float rk_exposure_from_luminance(float lum, float compensation)
{
    float c = rk_exposure_clamp(compensation, -RK_EV100_LIMIT, RK_EV100_LIMIT);
    return rk_exposure_from_ev100(rk_ev100_from_luminance(lum) - c);
}

/// rk_adapt_exponent: dt / tau of one adaptation step, the exponent of exp(-dt / tau); exactly 0
/// for dt <= 0 (and NaN dt). Domain: dt clamped to [0, RK_ADAPT_TIME_MAX], tau to
/// [RK_ADAPT_TAU_MIN, RK_ADAPT_TIME_MAX] (NaN -> the minimum: instant), the ratio to <= 100
/// (beyond, exp(-100) ~ 4e-44 is a denormal a GPU may flush: the gap is gone either way).
/// Max error: 1 division. Cost: 1 div, 2 compare.
RK_INLINE float rk_adapt_exponent(float dt, float tau)
{
    float t = rk_exposure_clamp(dt, 0.0f, RK_ADAPT_TIME_MAX);
    float tc = rk_exposure_clamp(tau, RK_ADAPT_TAU_MIN, RK_ADAPT_TIME_MAX);
    return t > 0.0f ? min(t / tc, 100.0f) : 0.0f;
}

/// rk_adapt_retain: the fraction exp(-dt / tau) of the gap to the target that remains after a
/// frame of dt seconds of exponential adaptation with time constant tau seconds. Exactly 1 for
/// dt <= 0; 0 (or a denormal) for dt / tau >= ~100. Domain as rk_adapt_exponent. Range [0, 1].
/// Max error vs float64: 1.2e-7 * max(1, dt / tau) relative (1 ulp of exp, plus the rounding of
/// dt / tau amplified by the exponent; test_exposure). Cost: 1 div, 1 exp.
RK_INLINE float rk_adapt_retain(float dt, float tau)
{
    float d = rk_adapt_exponent(dt, tau);
    return d > 0.0f ? exp(-d) : 1.0f;
}

/// rk_adapt_factor: the complementary fraction 1 - exp(-dt / tau) that a frame closes, with full
/// relative precision also for short frames (dt / tau < 0.5: the alternating series
/// d (1 - d/2 (1 - d/3 (... (1 - d/8)))), i.e. expm1, which GLSL lacks; 1 - exp(-d) would lose
/// 6e-8 / d relative). Exactly 0 for dt <= 0. Range [0, 1]. Domain as rk_adapt_exponent.
/// Max error vs float64: 1.5e-7 relative (test_exposure). Cost: 1 div + 8 mul-add, or 1 exp.
RK_INLINE float rk_adapt_factor(float dt, float tau)
{
    float d = rk_adapt_exponent(dt, tau);
    if (d >= 0.5f) {
        return 1.0f - exp(-d);
    }
    float p = 1.0f - d * 0.125f;
    p = 1.0f - d * (1.0f / 7.0f) * p;
    p = 1.0f - d * (1.0f / 6.0f) * p;
    p = 1.0f - d * 0.2f * p;
    p = 1.0f - d * 0.25f * p;
    p = 1.0f - d * (1.0f / 3.0f) * p;
    p = 1.0f - d * 0.5f * p;
    return d * p;
}

/// rk_adapt_log2: one frame of exponential eye adaptation in log space (stops):
///   x += (target - x)(1 - exp(-dt / tau)),  tau = tau_up when brightening, else tau_down.
/// The factor is rk_adapt_factor (full relative precision for short frames), so the rounding
/// error is a few ulp of max(|x|, |target|) whatever the frame time.
/// Frame-rate independent: with a fixed target, two steps of dt equal one step of 2 dt (the state
/// never crosses the target, so both steps use the same tau, and exp(-dt/tau)^2 = exp(-2 dt/tau));
/// measured difference <= 4 ulp of max(|x|, |target|, 1) (test_exposure). Monotone: the result lies
/// between x and target (clamped, so rounding can never overshoot). dt <= 0 (or NaN) returns x
/// exactly. Float resolution: a step below half an ulp rounds to no move, so the state settles
/// within ~0.5 ulp / (1 - exp(-dt / tau)) of the target (2.9e-4 stops at 40 stops, 60 fps,
/// tau 2.5 s; 1.4e-4 at 20 stops). Domain: x and target clamped to [RK_LOG2_LUM_MIN,
/// RK_LOG2_LUM_MAX] (NaN -> minimum); dt, tau as rk_adapt_exponent. Max error vs float64: 5.5e-6
/// absolute on |x|, |target| <= 20 (~1.5 ulp of |target - x|; 2e7 random + refinement).
/// Cost: 1 exp (or the series), 1 div, ~8 flops.
RK_INLINE float rk_adapt_log2(float current_log2, float target_log2, float dt, float tau_up, float tau_down)
{
    float c = rk_exposure_clamp(current_log2, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX);
    float t = rk_exposure_clamp(target_log2, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX);
    float x = c + (t - c) * rk_adapt_factor(dt, t > c ? tau_up : tau_down);
    return dt > 0.0f ? clamp(x, min(c, t), max(c, t)) : c;
}

/// rk_adapt_luminance: rk_adapt_log2 on luminances (adaptation in log space, which is how the eye
/// and photographic exposure behave: equal times for equal ratios up or down). Luminances are
/// sanitised and floored at RK_FLT_MIN; dt <= 0 returns the sanitised current value exactly.
/// Frame-rate independence holds up to the log2/exp2 round trip: two steps of dt and one of 2 dt
/// differ by <= 4 ulp of the log2 state plus the exp2 rounding, i.e. <= 2^-21 (ln2 max(|log2 L|, 1)
/// + 1) relative (2.3e-6 at 15 stops; test_exposure). Cost: 2 log2, 1 exp2, 1 exp, 1 div.
RK_INLINE float rk_adapt_luminance(float current, float target, float dt, float tau_up, float tau_down)
{
    float c = max(rk_hdr_sanitize(current), RK_FLT_MIN);
    float x = rk_adapt_log2(log2(c), log2(max(rk_hdr_sanitize(target), RK_FLT_MIN)), dt, tau_up, tau_down);
    return dt > 0.0f ? min(exp2(x), RK_HDR_MAX) : c;
}

/// rk_adapt_luminance_linear: the same exponential step on linear luminance (the formula as usually
/// quoted, L_a += (L_t - L_a)(1 - exp(-dt / tau)), evaluated like rk_adapt_log2 as a sum of two
/// non-negative terms, so the relative error stays at a few ulp even when the target is 1e8 times
/// the state): brightening and darkening by the same ratio take different times, which the
/// separate tau_up / tau_down can compensate. Frame-rate independent and monotone like
/// rk_adapt_log2 (difference <= 4 ulp of max(L_a, L_t)); dt <= 0 returns the sanitised current
/// value exactly. Domain: luminances sanitised to [0, RK_HDR_MAX]. Cost: 1 exp (or the series),
/// 1 div, ~8 flops.
RK_INLINE float rk_adapt_luminance_linear(float current, float target, float dt, float tau_up, float tau_down)
{
    float c = rk_hdr_sanitize(current);
    float t = rk_hdr_sanitize(target);
    bool rising = t > c;
    float tau = rising ? tau_up : tau_down;
    float x = rising ? c + (t - c) * rk_adapt_factor(dt, tau) : t + (c - t) * rk_adapt_retain(dt, tau);
    return dt > 0.0f ? clamp(x, min(c, t), max(c, t)) : c;
}

/// rk_reduce_cover: how many source texels along one axis the output texel `index` of a block
/// reduction covers, where each output texel spans `span` source texels (block^level) of a source
/// axis of `source_size` texels: min(span, source_size - index * span), 0 past the end. An edge
/// texel of a size that is not a multiple of the span covers fewer: a mean-of-blocks chain must
/// weight each fetched texel by cover_x * cover_y (and divide by the weights' sum), or the edge
/// is over-weighted (the thesis's 4x4 chain on 1024x768 ends with a partial 4x3 -> 1x1 pass).
/// Exact, uint arithmetic (no overflow for index * span < 2^32). Cost: 1 mul, 1 compare, 1 min.
RK_INLINE uint rk_reduce_cover(uint index, uint span, uint source_size)
{
    uint start = index * span;
    return start < source_size ? min(span, source_size - start) : 0u;
}

/// rk_histogram_bin: bin of a log2-luminance value in `bins` equal bins over [min_log2, max_log2]:
/// floor((x - min) * bins / (max - min)), values below the range in bin 0 and above it in the last
/// bin (so every pixel is counted; NaN -> bin 0). Domain: bins clamped to [1, 2^24]; min_log2 clamped to
/// [-256, 256] and max_log2 to >= min_log2 + 1e-3. Exact up to the rounding of the scale (a value
/// within 1 ulp of a bin edge may fall on either side on another backend). Cost: 1 div, 2 flops, 1 cvt.
RK_INLINE uint rk_histogram_bin(float x_log2, float min_log2, float max_log2, uint bins)
{
    uint n = clamp(bins, 1u, 16777216u);
    float lo = rk_exposure_clamp(min_log2, -256.0f, 256.0f);
    float hi = rk_exposure_clamp(max_log2, lo + 1.0e-3f, 512.0f);
    float u = (x_log2 - lo) * (float(n) / (hi - lo));
    return uint(rk_exposure_clamp(u, 0.0f, float(n - 1u)));
}

/// rk_histogram_bin_edge: the log2 luminance of the lower edge of bin `edge` (bin `bins` gives the
/// upper edge of the range): min + edge * (max - min) / bins. Same clamping of the range as
/// rk_histogram_bin; never above max_log2. Max error: 3.6 ulp of max(|min_log2|, |max_log2|) (not
/// of the result, which may be near 0; 2e7 random + refinement). Cost: 1 div, 3 flops.
RK_INLINE float rk_histogram_bin_edge(float edge, float min_log2, float max_log2, uint bins)
{
    uint n = clamp(bins, 1u, 16777216u);
    float lo = rk_exposure_clamp(min_log2, -256.0f, 256.0f);
    float hi = rk_exposure_clamp(max_log2, lo + 1.0e-3f, 512.0f);
    return min(lo + rk_exposure_clamp(edge, 0.0f, float(n)) * ((hi - lo) / float(n)), hi);
}

/// rk_histogram_scan: running state of one pass over a luminance histogram, lowest bin first
/// (rk_histogram_scan_init, then rk_histogram_scan_bin per bin). Ranks are pixel counts from the
/// dark end: percentile p of N pixels is rank p * N.
///   below          pixels in the bins scanned so far
///   weight         pixels inside the rank window [win_lo, win_hi] scanned so far
///   weighted_log2  sum over those pixels of their log2 luminance (uniform spread within each bin)
///   low_log2, high_log2   log2 luminance at the robust ranks (interpolated inside their bin)
///   low_found, high_found 1 once the robust rank has been reached
struct rk_histogram_scan {
    float below;
    float weight;
    float weighted_log2;
    float low_log2;
    float high_log2;
    float low_found;
    float high_found;
};

/// rk_histogram_scan_init: the empty scan state (everything 0). Cost: none.
RK_INLINE rk_histogram_scan rk_histogram_scan_init()
{
    rk_histogram_scan s;
    s.below = 0.0f;
    s.weight = 0.0f;
    s.weighted_log2 = 0.0f;
    s.low_log2 = 0.0f;
    s.high_log2 = 0.0f;
    s.low_found = 0.0f;
    s.high_found = 0.0f;
    return s;
}

/// rk_histogram_rank_in_bin: the log2 value at rank r inside a bin of `count` pixels that starts at
/// rank `below`, assuming the pixels spread uniformly over [edge_lo, edge_hi]. Domain: the fraction
/// (r - below) / count is clamped to [0, 1] (count floored at 1, NaN -> 0); edges clamped to
/// [-1024, 1024] (NaN -> -1024). Max error: 3.1 ulp of the edges (2e7 random + refinement).
/// Cost: 1 div, 3 flops.
RK_INLINE float rk_histogram_rank_in_bin(float rank, float below, float count, float edge_lo, float edge_hi)
{
    float f = rk_exposure_clamp((rank - below) / rk_exposure_clamp(count, 1.0f, RK_FLT_MAX), 0.0f, 1.0f);
    float e0 = rk_exposure_clamp(edge_lo, -1024.0f, 1024.0f);
    float e1 = rk_exposure_clamp(edge_hi, -1024.0f, 1024.0f);
    return e0 + (e1 - e0) * f;
}

/// rk_histogram_scan_bin: adds one bin (`count` pixels in [edge_lo, edge_hi] log2) to the scan:
/// the part of the bin inside the rank window [win_lo, win_hi] (the percentile-trimmed average of
/// engines such as Unreal's "low/high percent") with the mean log2 of that part, and the robust
/// min/max at ranks low_rank and high_rank (first bin whose cumulative count reaches the rank).
/// Domain: counts and ranks clamped to [0, 1e30] (NaN -> 0), edges to [-1024, 1024]; empty bins
/// change nothing but `below`.
/// Exact to float rounding of the running sums (counts are exact below 2^24 pixels). Cost: ~25 flops.
RK_INLINE void rk_histogram_scan_bin(RK_INOUT(rk_histogram_scan) s, float count, float edge_lo, float edge_hi,
                                     float win_lo, float win_hi, float low_rank, float high_rank)
{
    float c = rk_exposure_clamp(count, 0.0f, 1.0e30f);
    float b = s.below;
    float wl = rk_exposure_clamp(win_lo, 0.0f, 1.0e30f);
    float wh = rk_exposure_clamp(win_hi, wl, 1.0e30f);
    float r0 = max(b, wl);
    float r1 = min(b + c, wh);
    if (r1 > r0) {
        s.weight += r1 - r0;
        s.weighted_log2 += (r1 - r0) * rk_histogram_rank_in_bin(0.5f * (r0 + r1), b, c, edge_lo, edge_hi);
    }
    float lr = rk_exposure_clamp(low_rank, 0.0f, 1.0e30f);
    float hr = rk_exposure_clamp(high_rank, 0.0f, 1.0e30f);
    if (c > 0.0f && s.low_found == 0.0f && lr <= b + c) {
        s.low_log2 = rk_histogram_rank_in_bin(lr, b, c, edge_lo, edge_hi);
        s.low_found = 1.0f;
    }
    if (c > 0.0f && s.high_found == 0.0f && hr <= b + c) {
        s.high_log2 = rk_histogram_rank_in_bin(hr, b, c, edge_lo, edge_hi);
        s.high_found = 1.0f;
    }
    s.below = b + c;
}

/// rk_histogram_scan_average: the percentile-window average luminance exp2(weighted_log2 / weight)
/// of a finished scan; when the window holds no pixels (empty histogram or win_lo == win_hi), the
/// robust low value. Range [RK_FLT_MIN, ~1e18]. Cost: 1 div, 1 exp2.
RK_INLINE float rk_histogram_scan_average(rk_histogram_scan s)
{
    float m = s.weight > 0.0f ? s.weighted_log2 / s.weight : s.low_log2;
    return exp2(rk_exposure_clamp(m, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX));
}

#endif  // RK_EXPOSURE_GLSL
