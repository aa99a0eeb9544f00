// raykit — exposure.hpp: the CPU build of shaders/raykit/exposure.glsl plus the CPU references of
// the GPU luminance reduction (shaders/raykit/luminance_reduce.glsl, host in
// samples/common/rk_luminance_gl.hpp):
//   log_average_luminance   Eq. 3.14 over a float image, with percentile-robust min/max
//   reinhard_auto_params    Reinhard 2002's automatic key and white point from those
//   luminance_histogram / histogram_stats   the histogram option, bin for bin as the GPU does it
//   reduction_chain / reduce_chain_mean     the pass planner with edge weights for sizes that are
//                                           not multiples of the block, and a float simulation of
//                                           a mean-of-blocks chain (the thesis's 4x4 reduction)
// Every rk_* function is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_exposure.cpp checks both builds agree on a real driver.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "raykit/color.hpp"
#include "raykit/status.hpp"

namespace raykit {
#include "raykit/exposure.glsl"

// ---------------------------------------------------------------------------------------------
// Log-average luminance (CPU reference)

/// Options of log_average_luminance. Percentiles are fractions in [0, 1].
struct LogAverageOptions {
    float delta = RK_LOG_LUM_DELTA;  ///< Eq. 3.14's delta (see exposure.glsl)
    float low_percentile = 0.01f;    ///< robust minimum: this percentile of delta + L
    float high_percentile = 0.99f;   ///< robust maximum
};

/// Result of log_average_luminance. Luminances are of the term delta + L (so the minimum of an
/// image with black pixels is delta, never 0, and all three feed rk_reinhard_auto_key consistently).
struct LuminanceStats {
    float log_average = 0.0f;     ///< exp2(mean log2(delta + L)), clamped as rk_log_average_from_sum
    double mean_log2 = 0.0;       ///< mean of the log2 terms (float64 accumulation)
    double sum_log2 = 0.0;        ///< their sum
    float min = 0.0f, max = 0.0f;                ///< exact extremes of delta + L
    float robust_min = 0.0f, robust_max = 0.0f;  ///< the low/high percentiles of delta + L
    std::size_t count = 0;        ///< pixels
    std::size_t sanitized = 0;    ///< pixels with a negative, NaN or infinite channel (clamped, counted)
};

namespace detail {

inline bool check_image(const float* pixels, std::size_t width, std::size_t height, int channels, const char* who,
                        Status* st)
{
    reset(st);
    if (!pixels && width * height > 0) return report(st, std::string(who) + ": null pixels");
    if (channels != 1 && channels != 3 && channels != 4) {
        return report(st, std::string(who) + ": channels must be 1 (luminance), 3 (RGB) or 4 (RGBA)");
    }
    return true;
}

/// The log2(delta + L) term of pixel i, exactly as luminance_reduce.glsl computes it.
inline float pixel_log2(const float* pixels, std::size_t i, int channels, float delta)
{
    const float* p = pixels + i * static_cast<std::size_t>(channels);
    return channels == 1 ? rk_log2_luminance(p[0], delta) : rk_log2_luminance(vec3(p[0], p[1], p[2]), delta);
}

inline bool pixel_needs_sanitizing(const float* pixels, std::size_t i, int channels)
{
    const float* p = pixels + i * static_cast<std::size_t>(channels);
    const int n = channels == 1 ? 1 : 3;
    for (int c = 0; c < n; ++c) {
        if (!(p[c] >= 0.0f) || !std::isfinite(p[c])) return true;
    }
    return false;
}

/// Percentile p of `v` (modified: partially sorted) with linear interpolation between order
/// statistics (h = (n - 1) p; "type 7", numpy's default).
inline double percentile_inplace(std::vector<float>& v, double p)
{
    if (v.empty()) return 0.0;
    const double h = (static_cast<double>(v.size()) - 1.0) * std::min(std::max(p, 0.0), 1.0);
    const std::size_t lo = static_cast<std::size_t>(h);
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(lo), v.end());
    const double a = v[lo];
    if (lo + 1 >= v.size()) return a;
    const double b = *std::min_element(v.begin() + static_cast<std::ptrdiff_t>(lo) + 1, v.end());
    return a + (h - static_cast<double>(lo)) * (b - a);
}

inline float exp2_clamped(double log2_value)
{
    const double m = std::min(std::max(log2_value, static_cast<double>(RK_LOG2_LUM_MIN)), static_cast<double>(RK_LOG2_LUM_MAX));
    return static_cast<float>(std::exp2(m));
}

}  // namespace detail

/// log_average_luminance: the reference log-average exp(mean(log(delta + L))) (thesis Eq. 3.14)
/// of a float image, with the exact and percentile-robust extremes of delta + L.
/// `pixels` holds width * height pixels of `channels` floats, row-major: 1 = luminance, 3 = linear
/// Rec.709 RGB, 4 = RGBA (alpha ignored). Each pixel's term is rk_log2_luminance (the shared
/// function the GPU runs: channels sanitised, so NaN/negative/-Inf count as 0 and +Inf as
/// RK_HDR_MAX); the terms are summed in float64 and the percentiles are exact order statistics
/// (linear interpolation, "type 7"). An empty image gives log_average 1 (mean 0).
/// Other channel counts, or null pixels: the empty image's result (count 0), described in *st
/// (status.hpp). Cost: one log2 per pixel plus two nth_element over a copy of the terms (4 bytes
/// per pixel): ~0.2 s for 3840x2160 on one core.
inline LuminanceStats log_average_luminance(const float* pixels, std::size_t width, std::size_t height, int channels,
                                            const LogAverageOptions& options = {}, Status* st = nullptr)
{
    LuminanceStats s;
    if (!detail::check_image(pixels, width, height, channels, "raykit::log_average_luminance", st)) {
        s.log_average = 1.0f;
        return s;
    }
    s.count = width * height;
    if (s.count == 0) {
        s.log_average = 1.0f;
        return s;
    }
    std::vector<float> terms(s.count);
    double sum = 0.0;
    float lo = RK_FLT_MAX, hi = -RK_FLT_MAX;
    for (std::size_t i = 0; i < s.count; ++i) {
        const float t = detail::pixel_log2(pixels, i, channels, options.delta);
        terms[i] = t;
        sum += t;
        lo = std::min(lo, t);
        hi = std::max(hi, t);
        s.sanitized += detail::pixel_needs_sanitizing(pixels, i, channels) ? 1u : 0u;
    }
    s.sum_log2 = sum;
    s.mean_log2 = sum / static_cast<double>(s.count);
    s.log_average = detail::exp2_clamped(s.mean_log2);
    s.min = std::exp2(lo);
    s.max = std::exp2(hi);
    s.robust_min = detail::exp2_clamped(detail::percentile_inplace(terms, options.low_percentile));
    s.robust_max = detail::exp2_clamped(detail::percentile_inplace(terms, options.high_percentile));
    return s;
}

/// log_average_luminance over a std::vector holding width * height * channels floats
/// (a size that does not match: the empty image's result, described in *st).
inline LuminanceStats log_average_luminance(const std::vector<float>& pixels, std::size_t width, std::size_t height,
                                            int channels, const LogAverageOptions& options = {}, Status* st = nullptr)
{
    if (pixels.size() != width * height * static_cast<std::size_t>(channels > 0 ? channels : 0)) {
        detail::report(st, "raykit::log_average_luminance: pixels.size() != width * height * channels");
        LuminanceStats s;
        s.log_average = 1.0f;
        return s;
    }
    return log_average_luminance(pixels.data(), width, height, channels, options, st);
}

/// Reinhard 2002's automatic parameters (thesis Eq. 3.18-3.19).
struct ReinhardParams {
    float key = RK_EXPOSURE_MIDDLE_GREY;  ///< alpha, in [0.045, 0.72]
    float white = 1.5f;                   ///< L_white, in scaled-luminance units
};

/// reinhard_auto_params: alpha and L_white from a log-average and (robust) min/max luminance,
/// through the shared rk_reinhard_auto_key / rk_reinhard_auto_white (see their domains).
inline ReinhardParams reinhard_auto_params(float log_average, float lum_min, float lum_max)
{
    ReinhardParams p;
    p.key = rk_reinhard_auto_key(log_average, lum_min, lum_max);
    p.white = rk_reinhard_auto_white(lum_min, lum_max);
    return p;
}

/// reinhard_auto_params from log_average_luminance's result: uses the percentile-robust min/max
/// (Reinhard 2002 excludes the darkest and lightest few pixels; the options' 1%/99% by default).
inline ReinhardParams reinhard_auto_params(const LuminanceStats& stats)
{
    return reinhard_auto_params(stats.log_average, stats.robust_min, stats.robust_max);
}

// ---------------------------------------------------------------------------------------------
// Histogram option (CPU mirror of luminance_reduce.glsl's histogram and finish pass)

/// luminance_histogram: counts of the pixels' log2(delta + L) terms in `bins` equal bins over
/// [min_log2, max_log2] (rk_histogram_bin: out-of-range values land in the end bins). Same pixel
/// layout as log_average_luminance. bins == 0 or bad channels: an empty vector, described in *st.
inline std::vector<std::uint32_t> luminance_histogram(const float* pixels, std::size_t width, std::size_t height,
                                                      int channels, std::uint32_t bins, float min_log2, float max_log2,
                                                      float delta = RK_LOG_LUM_DELTA, Status* st = nullptr)
{
    if (!detail::check_image(pixels, width, height, channels, "raykit::luminance_histogram", st)) return {};
    if (bins == 0) {
        detail::report(st, "raykit::luminance_histogram: bins must be >= 1");
        return {};
    }
    std::vector<std::uint32_t> counts(bins, 0u);
    const std::size_t n = width * height;
    for (std::size_t i = 0; i < n; ++i) {
        ++counts[rk_histogram_bin(detail::pixel_log2(pixels, i, channels, delta), min_log2, max_log2, bins)];
    }
    return counts;
}

/// What histogram_stats derives from a histogram.
struct HistogramStats {
    float average = 0.0f;    ///< exp2 of the mean log2 inside the percentile window
    float low = 0.0f;        ///< luminance at the low robust percentile (interpolated in its bin)
    float high = 0.0f;       ///< luminance at the high robust percentile
    float window_pixels = 0.0f;  ///< pixels inside the window (its weight)
    double total = 0.0;      ///< pixels in the histogram
};

/// histogram_stats: the percentile-trimmed average over the window [window_low, window_high]
/// (fractions of the pixels, e.g. 0.05 / 0.95; Unreal's "low/high percent" are 0.80 / 0.983) and
/// the robust extremes at percentiles robust_low / robust_high, by one rk_histogram_scan pass —
/// the same shared code the GPU's finish pass runs over its histogram. Ranks: p * total.
/// An empty histogram gives total 0, window_pixels 0 and average = low = high = 1 (log2 0).
inline HistogramStats histogram_stats(const std::vector<std::uint32_t>& counts, float min_log2, float max_log2,
                                      float window_low, float window_high, float robust_low, float robust_high)
{
    HistogramStats r;
    for (std::uint32_t c : counts) r.total += c;
    const float total = static_cast<float>(r.total);
    const uint bins = static_cast<uint>(counts.size());
    rk_histogram_scan s = rk_histogram_scan_init();
    for (uint b = 0; b < bins; ++b) {
        const float e0 = rk_histogram_bin_edge(static_cast<float>(b), min_log2, max_log2, bins);
        const float e1 = rk_histogram_bin_edge(static_cast<float>(b + 1u), min_log2, max_log2, bins);
        rk_histogram_scan_bin(s, static_cast<float>(counts[b]), e0, e1, rk_saturate(window_low) * total,
                              rk_saturate(window_high) * total, rk_saturate(robust_low) * total,
                              rk_saturate(robust_high) * total);
    }
    r.average = rk_histogram_scan_average(s);
    r.low = exp2(rk_exposure_clamp(s.low_log2, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX));
    r.high = exp2(rk_exposure_clamp(s.high_log2, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX));
    r.window_pixels = s.weight;
    return r;
}

// ---------------------------------------------------------------------------------------------
// Reduction-chain planner

/// One pass of a block reduction: reads an in_width x in_height level, writes an
/// out_width x out_height level where each output texel reduces a block x block tile
/// (out = ceil(in / block)). Output texel (i, j) stands for `span` x `span` source pixels
/// (span = block^(pass + 1)) except in the last column / row, which cover last_cover_x /
/// last_cover_y source pixels when the source size is not a multiple of span.
struct ReductionPass {
    int in_width = 0, in_height = 0;
    int out_width = 0, out_height = 0;
    int block = 0;
    long long span = 0;
    int last_cover_x = 0, last_cover_y = 0;
    bool partial_x = false, partial_y = false;  ///< the last column / row covers less than span
};

/// reduction_chain: the passes that reduce a width x height image to 1x1 by block x block tiles
/// (block 4 for the thesis's fragment chain, RK_LUMINANCE_REDUCE_TILE = 64 for the compute chain
/// of luminance_reduce.glsl). 1024x768 by 4: 256x192, 64x48, 16x12, 4x3, 1x1 (the last pass is a
/// partial 4x3 block: its texels cover 256 x 256 source pixels each, the output 1024 x 768).
/// A 1x1 image still gets one pass (1x1 -> 1x1). Sizes < 1, block < 2 or a size above 2^30: no
/// passes, described in *st (status.hpp).
inline std::vector<ReductionPass> reduction_chain(int width, int height, int block, Status* st = nullptr)
{
    detail::reset(st);
    if (width < 1 || height < 1 || width > (1 << 30) || height > (1 << 30)) {
        detail::report(st, "raykit::reduction_chain: width and height must be in [1, 2^30]");
        return {};
    }
    if (block < 2) {
        detail::report(st, "raykit::reduction_chain: block must be >= 2");
        return {};
    }
    std::vector<ReductionPass> passes;
    int w = width, h = height;
    long long span = 1;
    do {
        ReductionPass p;
        p.in_width = w;
        p.in_height = h;
        p.out_width = (w - 1) / block + 1;  // ceil(w / block) without overflow for any block
        p.out_height = (h - 1) / block + 1;
        p.block = block;
        span *= block;
        p.span = span;
        p.last_cover_x = static_cast<int>(width - (p.out_width - 1) * span);
        p.last_cover_y = static_cast<int>(height - (p.out_height - 1) * span);
        p.partial_x = p.last_cover_x < span;
        p.partial_y = p.last_cover_y < span;
        passes.push_back(p);
        w = p.out_width;
        h = p.out_height;
        if (span > (1ll << 31)) span = 1ll << 31;  // further levels are 1x1; keep the product bounded
    } while (w > 1 || h > 1);
    return passes;
}

/// reduction_texel_weight: source pixels covered by output texel (i, j) of `pass` (what a
/// weighted mean-of-blocks chain must weight that texel by when the next pass reads it):
/// cover_x(i) * cover_y(j) with rk_reduce_cover. The weights of one level sum to width * height.
inline double reduction_texel_weight(const ReductionPass& pass, int i, int j, int width, int height)
{
    const uint span = static_cast<uint>(std::min<long long>(pass.span, 1ll << 31));
    return static_cast<double>(rk_reduce_cover(static_cast<uint>(i), span, static_cast<uint>(width))) *
           static_cast<double>(rk_reduce_cover(static_cast<uint>(j), span, static_cast<uint>(height)));
}

/// reduce_chain_mean: float simulation of a GPU mean-of-blocks chain (fragment-shader style: each
/// pass writes the mean of its block) over `values` (width * height, row-major), as planned by
/// reduction_chain. edge_weighted = true weights each fetched texel by the source pixels it covers
/// (rk_reduce_cover) and divides by the weights' sum: the exact mean up to float rounding.
/// edge_weighted = false is the naive chain (CLAMP_TO_EDGE fetches, every block divided by
/// block^2), which over-weights the last row/column whenever a level is not a multiple of block.
/// Values: finite with |v| <= FLT_MAX / (2 max(width * height, block^2)), so that no block's sum
/// overflows, rounding included. Bad sizes (as reduction_chain) or values.size() != width * height:
/// returns 0, described in *st.
inline float reduce_chain_mean(const std::vector<float>& values, int width, int height, int block, bool edge_weighted,
                               Status* st = nullptr)
{
    const std::vector<ReductionPass> chain = reduction_chain(width, height, block, st);
    if (chain.empty()) return 0.0f;
    if (values.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
        detail::report(st, "raykit::reduce_chain_mean: values.size() != width * height");
        return 0.0f;
    }
    std::vector<float> level = values, next;
    long long child_span = 1;
    for (const ReductionPass& p : chain) {
        next.assign(static_cast<std::size_t>(p.out_width) * static_cast<std::size_t>(p.out_height), 0.0f);
        const uint cs = static_cast<uint>(std::min<long long>(child_span, 1ll << 31));
        for (int oy = 0; oy < p.out_height; ++oy) {
            for (int ox = 0; ox < p.out_width; ++ox) {
                float sum = 0.0f, wsum = 0.0f;
                for (int by = 0; by < block; ++by) {
                    for (int bx = 0; bx < block; ++bx) {
                        int x = ox * block + bx, y = oy * block + by;
                        float w = 1.0f;
                        if (edge_weighted) {
                            w = static_cast<float>(rk_reduce_cover(static_cast<uint>(x), cs, static_cast<uint>(width))) *
                                static_cast<float>(rk_reduce_cover(static_cast<uint>(y), cs, static_cast<uint>(height)));
                            if (w == 0.0f) continue;
                        } else {
                            x = std::min(x, p.in_width - 1);
                            y = std::min(y, p.in_height - 1);
                        }
                        sum += w * level[static_cast<std::size_t>(y) * static_cast<std::size_t>(p.in_width) + static_cast<std::size_t>(x)];
                        wsum += w;
                    }
                }
                next[static_cast<std::size_t>(oy) * static_cast<std::size_t>(p.out_width) + static_cast<std::size_t>(ox)] =
                    sum / wsum;
            }
        }
        level.swap(next);
        child_span = std::min<long long>(child_span * block, 1ll << 31);
    }
    return level[0];
}

}  // namespace raykit
