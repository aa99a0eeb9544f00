// raykit — bloom.hpp: the CPU build of shaders/raykit/bloom.glsl plus the CPU-only parts of bloom:
// Gaussian weights, merged linear-sampling taps, the sizes of the downsample chain, CPU mirrors of
// GL's bilinear sampler and a CPU reference of the whole bloom (bright pass -> downsamples ->
// separable Gaussian per level -> magnify, sum and composite) on a float image.
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_bloom.cpp checks both builds agree on a real driver, and runs the GPU chain of
// samples/common/rk_bloom_gl.hpp against bloom_reference().
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "raykit/color.hpp"
#include "raykit/common.hpp"
#include "raykit/status.hpp"

namespace raykit {
#include "raykit/bloom.glsl"

/// One merged blur tap: a bilinear fetch at `offset` texels from the centre (both sides), weighted
/// by `weight`.
struct BloomTap {
    float offset;
    float weight;
};

/// gaussian_weights: the one-sided weights w[0..radius] of the discrete Gaussian
/// exp(-i^2 / 2 sigma^2), normalised so that w[0] + 2 (w[1] + ... + w[radius]) = 1 (the full kernel
/// of 2 radius + 1 taps is symmetric by construction). Computed in float64, rounded once.
/// sigma = 3, radius = 9 (3 sigma; the sigma of Fahlén, "Illumination for Real-Time Rendering of Large
/// Architectural Environments" (2005), §3.4.2, which does not state a radius): w0 = 0.13318,
/// w1 = 0.12598, ..., w9 = 0.00148.
/// Requires sigma finite in (0, 1e4] and radius in [0, 4096]; otherwise returns an empty vector and
/// describes the violation in *st (status.hpp).
inline std::vector<float> gaussian_weights(float sigma, int radius, Status* st = nullptr)
{
    detail::reset(st);
    if (!(sigma > 0.0f) || !(sigma <= 1e4f) || radius < 0 || radius > 4096) {
        detail::report(st, "raykit::gaussian_weights: sigma must be in (0, 1e4], radius in [0, 4096]");
        return {};
    }
    const double s = static_cast<double>(sigma);
    std::vector<double> w(static_cast<size_t>(radius) + 1);
    double sum = 0.0;
    for (int i = 0; i <= radius; ++i) {
        const double x = static_cast<double>(i);
        w[static_cast<size_t>(i)] = std::exp(-x * x / (2.0 * s * s));
        sum += (i == 0 ? 1.0 : 2.0) * w[static_cast<size_t>(i)];
    }
    std::vector<float> out(w.size());
    for (size_t i = 0; i < w.size(); ++i) out[i] = static_cast<float>(w[i] / sum);
    return out;
}

/// linear_sampled_taps: merges the one-sided discrete weights w[0..r] (from gaussian_weights) into
/// bilinear fetches (GPU Gems 2 ch. 20; Fahlén 2005 §3.4.2): the centre (0, w0), then for each pair of
/// adjacent weights a = w[i], b = w[i+1] (i = 1, 3, 5, ...) one fetch at offset i + b / (a + b) with
/// weight a + b, and a lone last weight (odd r) as (r, w[r]). A bilinear fetch there returns
/// (a f(i) + b f(i+1)) / (a + b), so the sum reproduces the discrete convolution exactly up to
/// float rounding (and the GPU's filtering precision: 8-bit sub-texel weights on most hardware
/// quantise b / (a + b) to 1/256). A pair with a + b = 0 keeps offset i. Valid for non-negative
/// weights (then 0 <= b / (a + b) <= 1). sigma = 3, radius = 9: (0, 0.13318), (1.4584, 0.23262),
/// (3.4040, 0.13553), (5.3518, 0.05123), (7.3029, 0.01256), (9, 0.00148): 6 one-sided taps,
/// 11 fetches instead of 19. Returns an empty vector for empty input. Offsets and weights are
/// computed in float64 and rounded once.
inline std::vector<BloomTap> linear_sampled_taps(const std::vector<float>& weights)
{
    std::vector<BloomTap> taps;
    if (weights.empty()) return taps;
    taps.push_back({0.0f, weights[0]});
    const size_t r = weights.size() - 1;
    for (size_t i = 1; i <= r; i += 2) {
        const double a = weights[i];
        if (i + 1 > r) {
            taps.push_back({static_cast<float>(i), weights[i]});
            break;
        }
        const double b = weights[i + 1];
        const double ab = a + b;
        const double offset = static_cast<double>(i) + (ab > 0.0 ? b / ab : 0.0);
        taps.push_back({static_cast<float>(offset), static_cast<float>(ab)});
    }
    return taps;
}

/// linear_tap_fetches: texture fetches one blur pass makes with `taps` (one-sided, centre first):
/// 2 n - 1 (0 for none).
inline int linear_tap_fetches(const std::vector<BloomTap>& taps)
{
    return taps.empty() ? 0 : 2 * static_cast<int>(taps.size()) - 1;
}

/// The sizes of the downsample chain.
struct BloomChain {
    /// Target size of every downsample pass, in order: the first (the prefilter, which also runs the
    /// bright pass) halves the full size unless first_div = 1, then each pass halves the previous
    /// size, rounded up (ceil: every source texel is covered, a 1-texel side stays 1).
    std::vector<ivec2> downsamples;
    /// The blurred levels: the last `levels` entries of `downsamples` (1/first_div, 1/(2 first_div) ...).
    std::vector<ivec2> levels;
};

/// bloom_chain: the pass sizes of the bloom chain for a width x height image whose largest blurred
/// level is 1/first_div of it, with `levels` levels (thesis: 1/8 and 4 levels: 1024x768 gives
/// 128x96, 64x48, 32x24, 16x12 after the 512x384 and 256x192 passes). Odd sizes round up at each
/// halving: 1023x767 -> 512x384 -> ... -> 128x96, 64x48, 32x24, 16x12; 5x3 -> 3x2 -> 2x1 -> 1x1...
/// Requires width, height in [1, 65536], first_div a power of two in [1, 32768] and levels in
/// [1, 16]; otherwise returns an empty chain and describes the violation in *st (status.hpp).
inline BloomChain bloom_chain(int width, int height, int first_div = 8, int levels = 4, Status* st = nullptr)
{
    detail::reset(st);
    if (width < 1 || height < 1 || width > 65536 || height > 65536) {
        detail::report(st, "raykit::bloom_chain: width and height must be in [1, 65536]");
        return {};
    }
    if (first_div < 1 || first_div > 32768 || (first_div & (first_div - 1)) != 0) {
        detail::report(st, "raykit::bloom_chain: first_div must be a power of two in [1, 32768]");
        return {};
    }
    if (levels < 1 || levels > 16) {
        detail::report(st, "raykit::bloom_chain: levels must be in [1, 16]");
        return {};
    }
    int halvings = 0;
    while ((1 << halvings) < first_div) ++halvings;
    const int passes = std::max(halvings, 1) + levels - 1;
    BloomChain chain;
    ivec2 size(width, height);
    for (int p = 0; p < passes; ++p) {
        if (p > 0 || first_div > 1) size = ivec2((size.x + 1) / 2, (size.y + 1) / 2);
        chain.downsamples.push_back(size);
    }
    chain.levels.assign(chain.downsamples.end() - levels, chain.downsamples.end());
    return chain;
}

/// Parameters of the whole bloom (CPU reference and samples/common/rk_bloom_gl.hpp).
/// The defaults are the thesis's (Fahlén 2005 §3.4): hard threshold 1.5, 4 levels from 1/8,
/// sigma 3, levels added to the HDR image with weight 1.
struct BloomParams {
    float threshold = RK_BLOOM_THRESHOLD;   ///< luminance threshold T
    float knee = 0.0f;                      ///< knee half-width K (clamped to [0, T]); knee modes only
    int mode = RK_BLOOM_MODE_HARD;          ///< RK_BLOOM_MODE_*
    bool karis = false;                     ///< Karis-weighted first downsample (anti-firefly)
    float sigma = 3.0f;                     ///< Gaussian sigma in texels of each level
    int radius = 9;                         ///< kernel radius in texels (<= 2 (RK_BLOOM_MAX_TAPS - 1))
    int first_div = 8;                      ///< largest level is 1/first_div of the image
    int levels = 4;                         ///< blurred levels, 1..4
    int composite = RK_BLOOM_COMPOSITE_ADD; ///< RK_BLOOM_COMPOSITE_*
    float strength = 1.0f;                  ///< composite strength
    vec4 level_weights = vec4(1.0f);        ///< per-level weights (normalised for MIX / CONSERVE)

    /// The thesis's setting (the defaults).
    static BloomParams thesis() { return BloomParams{}; }
    /// Cheap, standard improvements: soft knee of half-width 0.5 (ramp over luminance 1..2) and the
    /// Karis average on the first downsample; composite still additive.
    static BloomParams recommended()
    {
        BloomParams p;
        p.mode = RK_BLOOM_MODE_SOFT_KNEE;
        p.knee = 0.5f;
        p.karis = true;
        return p;
    }
};

/// validate_bloom_params: true when the parameters are usable; otherwise false, with *st naming the
/// first bad field: sigma/radius as gaussian_weights, radius <= 2 (RK_BLOOM_MAX_TAPS - 1) = 30,
/// first_div as bloom_chain, levels in [1, 4], mode and composite among the RK_BLOOM_* values.
/// Threshold, knee, strength and weights are not checked: the shared functions sanitise them
/// (NaN -> 0).
inline bool validate_bloom_params(const BloomParams& p, Status* st = nullptr)
{
    detail::reset(st);
    auto fail = [st](const char* what) { return detail::report(st, std::string("raykit::BloomParams: ") + what); };
    if (!(p.sigma > 0.0f) || !(p.sigma <= 1e4f)) return fail("sigma must be in (0, 1e4]");
    if (p.radius < 0 || p.radius > 2 * (RK_BLOOM_MAX_TAPS - 1)) return fail("radius must be in [0, 30]");
    if (p.first_div < 1 || p.first_div > 32768 || (p.first_div & (p.first_div - 1)) != 0) {
        return fail("first_div must be a power of two in [1, 32768]");
    }
    if (p.levels < 1 || p.levels > 4) return fail("levels must be in [1, 4]");
    if (p.mode < RK_BLOOM_MODE_HARD || p.mode > RK_BLOOM_MODE_SUBTRACT) return fail("unknown mode");
    if (p.composite < RK_BLOOM_COMPOSITE_ADD || p.composite > RK_BLOOM_COMPOSITE_CONSERVE) return fail("unknown composite");
    return true;
}

/// bloom_level_weights: the weights rk_bloom_sum_levels gets: level_weights sanitised (NaN,
/// negative -> 0), levels beyond p.levels set to 0, and for the MIX and CONSERVE composites divided by
/// their sum (all zero stays zero), so the summed bloom is a normalised blur.
inline vec4 bloom_level_weights(const BloomParams& p)
{
    vec4 w(0.0f);
    float sum = 0.0f;
    for (int i = 0; i < 4; ++i) {
        w[i] = i < p.levels ? min(rk_bloom_sanitize(p.level_weights[i]), RK_BLOOM_WEIGHT_MAX) : 0.0f;
        sum += w[i];
    }
    if (p.composite != RK_BLOOM_COMPOSITE_ADD && sum > 0.0f) w /= sum;
    return w;
}

/// An RGB float image, rows bottom to top as GL stores them (pixel (0, 0) is GL's texel (0, 0)).
struct BloomImage {
    int width = 0, height = 0;
    std::vector<vec3> pixels;

    BloomImage() = default;
    /// A black w x h image; a negative size gives an empty image (0 x 0).
    BloomImage(int w, int h)
        : width(w > 0 && h > 0 ? w : 0), height(w > 0 && h > 0 ? h : 0),
          pixels(static_cast<size_t>(width) * static_cast<size_t>(height), vec3(0.0f)) {}
    vec3& at(int x, int y) { return pixels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)]; }
    const vec3& at(int x, int y) const
    {
        return pixels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
    }
};

/// How the CPU sampler treats coordinates outside the image (GL's wrap modes).
enum class BloomWrap {
    clamp_to_edge,   ///< GL_CLAMP_TO_EDGE
    border_black,    ///< GL_CLAMP_TO_BORDER with border colour 0
};

/// bloom_texel: texel (x, y) of `img` under `wrap` (texelFetch after clamping, or 0 outside).
inline vec3 bloom_texel(const BloomImage& img, int x, int y, BloomWrap wrap)
{
    if (wrap == BloomWrap::border_black) {
        if (x < 0 || y < 0 || x >= img.width || y >= img.height) return vec3(0.0f);
        return img.at(x, y);
    }
    return img.at(std::clamp(x, 0, img.width - 1), std::clamp(y, 0, img.height - 1));
}

/// sample_bilinear: the CPU mirror of a GL_LINEAR texture() fetch at `uv` from level 0 of `img`:
/// position uv * size - 0.5, weights rk_bloom_bilinear_weights (exact float weights; GPUs quantise the
/// fraction, typically to 1/256).
inline vec3 sample_bilinear(const BloomImage& img, vec2 uv, BloomWrap wrap)
{
    const vec2 p(uv.x * static_cast<float>(img.width) - 0.5f, uv.y * static_cast<float>(img.height) - 0.5f);
    const vec4 w = rk_bloom_bilinear_weights(p);
    const int x = static_cast<int>(std::floor(glm::clamp(p.x, -1e7f, 1e7f)));
    const int y = static_cast<int>(std::floor(glm::clamp(p.y, -1e7f, 1e7f)));
    return w.x * bloom_texel(img, x, y, wrap) + w.y * bloom_texel(img, x + 1, y, wrap) +
           w.z * bloom_texel(img, x, y + 1, wrap) + w.w * bloom_texel(img, x + 1, y + 1, wrap);
}

/// Result of the skip reduction: the image's largest rk_bloom_luminance and how many pixels exceed
/// the cutoff (rk_bloom_cutoff). Bloom is skipped when count_above == 0: the bright pass is then 0
/// everywhere, so the chain would produce exactly 0.
struct BloomReduction {
    float max_luminance = 0.0f;
    std::uint32_t count_above = 0;
};

/// bloom_reduce: the CPU mirror of the GPU max/count reduction in rk_bloom_gl.hpp.
inline BloomReduction bloom_reduce(const BloomImage& hdr, float cutoff)
{
    BloomReduction r;
    for (const vec3& c : hdr.pixels) {
        const float y = rk_bloom_luminance(c);
        r.max_luminance = std::max(r.max_luminance, y);
        r.count_above += y > cutoff ? 1u : 0u;
    }
    return r;
}

/// bloom_blur_discrete: one direction (horizontal when `horizontal`) of the discrete Gaussian with
/// the full 2 r + 1 taps of `weights` (one-sided, from gaussian_weights), zero outside the image
/// (the black border), accumulated in float64. The definition that the GPU's merged taps reproduce.
inline BloomImage bloom_blur_discrete(const BloomImage& src, const std::vector<float>& weights, bool horizontal)
{
    BloomImage out(src.width, src.height);
    const int r = static_cast<int>(weights.size()) - 1;
    for (int y = 0; y < src.height; ++y) {
        for (int x = 0; x < src.width; ++x) {
            double acc[3] = {0.0, 0.0, 0.0};
            for (int k = -r; k <= r; ++k) {
                const vec3 c = horizontal ? bloom_texel(src, x + k, y, BloomWrap::border_black)
                                          : bloom_texel(src, x, y + k, BloomWrap::border_black);
                const double w = weights[static_cast<size_t>(std::abs(k))];
                for (int ch = 0; ch < 3; ++ch) acc[ch] += w * static_cast<double>(c[ch]);
            }
            out.at(x, y) = vec3(static_cast<float>(acc[0]), static_cast<float>(acc[1]), static_cast<float>(acc[2]));
        }
    }
    return out;
}

/// What bloom_reference returns.
struct BloomResult {
    BloomImage output;               ///< the composite (a copy of the input when skipped)
    std::vector<BloomImage> levels;  ///< the blurred levels (empty when the chain was skipped)
    BloomReduction reduction;        ///< the skip reduction over the input
    bool chain_run = false;          ///< false: nothing above the cutoff, downsample/blur skipped
    bool composited = false;         ///< false: output is the input, untouched (ADD and CONSERVE skip)
};

/// bloom_reference: a CPU reference of the whole bloom, mirroring the GPU passes of
/// rk_bloom_gl.hpp step by step with the shared rk_bloom_* functions:
///   0. reduction: rk_bloom_luminance max and count above rk_bloom_cutoff; when none exceeds it the
///      chain is skipped, and so is the composite for ADD and CONSERVE (output = input, untouched:
///      the result would be the sanitised input); MIX still composites with zero bloom ((1 - s) hdr).
///   1. prefilter to bloom_chain().downsamples[0]: bright pass of the 4 texels around
///      rk_bloom_source_texel (clamped to edge), rk_bloom_weighted_average / rk_bloom_karis_average;
///   2. each further downsample: sample_bilinear at the target texel centre, clamp to edge;
///   3. each level: bloom_blur_discrete horizontally then vertically (the full 2 r + 1 taps in
///      float64, black border; the GPU uses the merged taps);
///   4. per full-size pixel: sample_bilinear (clamp to edge) of every level at the pixel centre,
///      rk_bloom_sum_levels with bloom_level_weights, rk_bloom_composite with the pixel's bright pass.
/// Bad params (validate_bloom_params) or an empty / inconsistent image: returns an empty result
/// (output.width == 0) and describes it in *st (status.hpp).
inline BloomResult bloom_reference(const BloomImage& hdr, const BloomParams& p, Status* st = nullptr)
{
    if (!validate_bloom_params(p, st)) return {};
    if (hdr.width < 1 || hdr.height < 1 ||
        hdr.pixels.size() != static_cast<size_t>(hdr.width) * static_cast<size_t>(hdr.height)) {
        detail::report(st, "raykit::bloom_reference: empty image or pixel count != width * height");
        return {};
    }
    BloomResult res;
    res.reduction = bloom_reduce(hdr, rk_bloom_cutoff(p.threshold, p.knee, p.mode));
    res.chain_run = res.reduction.count_above > 0;
    if (!res.chain_run && p.composite != RK_BLOOM_COMPOSITE_MIX) {
        res.output = hdr;
        return res;
    }
    const BloomChain chain = bloom_chain(hdr.width, hdr.height, p.first_div, p.levels);
    const vec4 lw = bloom_level_weights(p);
    if (res.chain_run) {
        // 1. Prefilter.
        std::vector<BloomImage> down;
        {
            const ivec2 d = chain.downsamples[0];
            BloomImage img(d.x, d.y);
            for (int y = 0; y < d.y; ++y) {
                for (int x = 0; x < d.x; ++x) {
                    const vec2 q(rk_bloom_source_texel(static_cast<float>(x) + 0.5f, static_cast<float>(d.x),
                                                       static_cast<float>(hdr.width)),
                                 rk_bloom_source_texel(static_cast<float>(y) + 0.5f, static_cast<float>(d.y),
                                                       static_cast<float>(hdr.height)));
                    const vec4 w = rk_bloom_bilinear_weights(q);
                    const int ix = static_cast<int>(std::floor(q.x));
                    const int iy = static_cast<int>(std::floor(q.y));
                    auto bright = [&](int dx, int dy) {
                        return rk_bloom_bright_pass(bloom_texel(hdr, ix + dx, iy + dy, BloomWrap::clamp_to_edge),
                                                    p.threshold, p.knee, p.mode);
                    };
                    const vec3 c0 = bright(0, 0), c1 = bright(1, 0), c2 = bright(0, 1), c3 = bright(1, 1);
                    img.at(x, y) = p.karis ? rk_bloom_karis_average(c0, c1, c2, c3, w)
                                           : rk_bloom_weighted_average(c0, c1, c2, c3, w);
                }
            }
            down.push_back(std::move(img));
        }
        // 2. Downsamples.
        for (size_t i = 1; i < chain.downsamples.size(); ++i) {
            const ivec2 d = chain.downsamples[i];
            BloomImage img(d.x, d.y);
            for (int y = 0; y < d.y; ++y) {
                for (int x = 0; x < d.x; ++x) {
                    const vec2 uv((static_cast<float>(x) + 0.5f) / static_cast<float>(d.x),
                                  (static_cast<float>(y) + 0.5f) / static_cast<float>(d.y));
                    img.at(x, y) = sample_bilinear(down.back(), uv, BloomWrap::clamp_to_edge);
                }
            }
            down.push_back(std::move(img));
        }
        // 3. Blur the last `levels` images.
        const std::vector<float> weights = gaussian_weights(p.sigma, p.radius);
        for (size_t i = down.size() - static_cast<size_t>(p.levels); i < down.size(); ++i) {
            res.levels.push_back(bloom_blur_discrete(bloom_blur_discrete(down[i], weights, true), weights, false));
        }
    }
    // 4. Composite.
    res.composited = true;
    res.output = BloomImage(hdr.width, hdr.height);
    for (int y = 0; y < hdr.height; ++y) {
        for (int x = 0; x < hdr.width; ++x) {
            const vec2 uv((static_cast<float>(x) + 0.5f) / static_cast<float>(hdr.width),
                          (static_cast<float>(y) + 0.5f) / static_cast<float>(hdr.height));
            vec3 l[4] = {vec3(0.0f), vec3(0.0f), vec3(0.0f), vec3(0.0f)};
            for (size_t i = 0; i < res.levels.size(); ++i) l[i] = sample_bilinear(res.levels[i], uv, BloomWrap::clamp_to_edge);
            const vec3 bloom = rk_bloom_sum_levels(l[0], l[1], l[2], l[3], lw);
            const vec3 h = hdr.at(x, y);
            res.output.at(x, y) = rk_bloom_composite(h, rk_bloom_bright_pass(h, p.threshold, p.knee, p.mode), bloom,
                                                     p.strength, p.composite);
        }
    }
    return res;
}

}  // namespace raykit
