// GPU parity for shaders/raykit/exposure.glsl (every shared function, NaN and +-Inf inputs
// included) and the luminance reduction chain of luminance_reduce.glsl run by
// samples/common/rk_luminance_gl.hpp against the CPU references of raykit/exposure.hpp:
// 3840x2160 with zeros, 1e-30, denormals, 1e6-bright and NaN/Inf/negative pixels (1e-4 relative),
// a non-multiple 1023x767 and 1x1, texture and buffer sources, histogram and adaptation.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/exposure.hpp"
#include "rk_luminance_gl.hpp"

using namespace raykit;
using parity::Domain;
namespace dom = parity::dom;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

/// A domain whose specials also hold NaN and +-Inf: the exposure functions promise finite results
/// for those too (documented clamping).
Domain with_nonfinite(Domain d)
{
    d.specials.insert(d.specials.end(), {kNaN, -kNaN, kInf, -kInf});
    return d;
}
Domain lum() { return with_nonfinite({1e-8f, 1e8f, true, {0.0f, 1e-30f, 1e-40f, 1e6f, 1e18f, RK_LOG_LUM_DELTA}}); }
Domain wide_lum() { return with_nonfinite({1e-20f, 1e20f, true, {0.0f, 1e-40f, 1e18f}}); }
Domain stops() { return with_nonfinite({-40.0f, 60.0f, false, {-126.0f, 0.0f, 59.79f}}); }
Domain seconds() { return with_nonfinite({1e-4f, 10.0f, true, {0.0f, 1.0f / 60.0f, 1.0f / 30.0f}}); }
Domain dom_any(float lo, float hi) { return with_nonfinite({lo, hi, false, {}}); }

std::vector<parity::Case> exposure_cases()
{
    const char* E = "raykit/exposure.glsl";
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_exposure_clamp", E, (dom_any(-10.0f, 10.0f)), 1, o[0] = rk_exposure_clamp(a[0], -1.0f, 2.0f);),
        RK_PARITY("rk_log2_luminance(float)", E, (lum(), with_nonfinite({1e-6f, 1e-2f, true, {0.0f, RK_LOG_LUM_DELTA}})), 1,
                  o[0] = rk_log2_luminance(a[0], a[1]);),
        RK_PARITY("rk_log2_luminance(vec3)", E, (lum(), lum(), lum()), 1,
                  o[0] = rk_log2_luminance(vec3(a[0], a[1], a[2]), RK_LOG_LUM_DELTA);),
        RK_PARITY("rk_log_average_from_sum", E, (dom_any(-1e8f, 1e8f), with_nonfinite({1.0f, 1e7f, true, {0.0f, 1.0f}})), 1,
                  o[0] = rk_log_average_from_sum(a[0], a[1]);),
        RK_PARITY("rk_reinhard_auto_key", E, (wide_lum(), wide_lum(), wide_lum()), 1,
                  o[0] = rk_reinhard_auto_key(a[0], a[1], a[2]);),
        RK_PARITY("rk_reinhard_auto_white", E, (wide_lum(), wide_lum()), 1, o[0] = rk_reinhard_auto_white(a[0], a[1]);),
        RK_PARITY("rk_ev100_from_luminance", E, (wide_lum()), 1, o[0] = rk_ev100_from_luminance(a[0]);),
        RK_PARITY("rk_ev100_from_camera", E,
                  (with_nonfinite({1.0f, 22.0f, true, {16.0f}}), seconds(), with_nonfinite({50.0f, 12800.0f, true, {100.0f}})), 1,
                  o[0] = rk_ev100_from_camera(a[0], a[1], a[2]);),
        RK_PARITY("rk_exposure_from_ev100", E, (dom_any(-70.0f, 70.0f)), 1, o[0] = rk_exposure_from_ev100(a[0]);),
        RK_PARITY("rk_exposure_from_luminance", E, (wide_lum(), dom_any(-5.0f, 5.0f)), 1,
                  o[0] = rk_exposure_from_luminance(a[0], a[1]);),
        RK_PARITY("rk_adapt_exponent", E, (seconds(), seconds()), 1, o[0] = rk_adapt_exponent(a[0], a[1]);),
        RK_PARITY("rk_adapt_retain", E, (seconds(), seconds()), 1, o[0] = rk_adapt_retain(a[0], a[1]);),
        RK_PARITY("rk_adapt_factor", E, (seconds(), seconds()), 1, o[0] = rk_adapt_factor(a[0], a[1]);),
        RK_PARITY("rk_adapt_log2", E, (stops(), stops(), seconds(), seconds(), seconds()), 3,
                  o[0] = rk_adapt_log2(a[0], a[1], a[2], a[3], a[4]);
                  // The frame-rate identity on the GPU: two steps of dt and one of 2 dt.
                  o[1] = rk_adapt_log2(rk_adapt_log2(a[0], a[1], a[2], a[3], a[4]), a[1], a[2], a[3], a[4]);
                  o[2] = rk_adapt_log2(a[0], a[1], 2.0f * a[2], a[3], a[4]);),
        RK_PARITY("rk_adapt_luminance", E, (lum(), lum(), seconds(), seconds(), seconds()), 1,
                  o[0] = rk_adapt_luminance(a[0], a[1], a[2], a[3], a[4]);),
        RK_PARITY("rk_adapt_luminance_linear", E, (lum(), lum(), seconds(), seconds(), seconds()), 1,
                  o[0] = rk_adapt_luminance_linear(a[0], a[1], a[2], a[3], a[4]);),
        RK_PARITY("rk_reduce_cover", E, (dom::range(0.0f, 300.0f), dom::range(1.0f, 70.0f), dom::range(1.0f, 4000.0f)), 1,
                  uint i = uint(rk_exposure_clamp(a[0], 0.0f, 1.0e6f));
                  uint span = uint(rk_exposure_clamp(a[1], 1.0f, 4096.0f));
                  uint size = uint(rk_exposure_clamp(a[2], 1.0f, 1.0e6f));
                  o[0] = float(rk_reduce_cover(i, span, size));),
        // A power-of-two scale (4 bins per stop): bins are exact on both sides.
        RK_PARITY("rk_histogram_bin (fixed range)", E, (dom_any(-40.0f, 60.0f)), 1,
                  o[0] = float(rk_histogram_bin(a[0], -24.0f, 40.0f, 256u));),
        RK_PARITY("rk_histogram_bin (any range)", E, (dom_any(-40.0f, 60.0f), dom_any(-30.0f, 0.0f), dom_any(1.0f, 50.0f)), 1,
                  o[0] = float(rk_histogram_bin(a[0], a[1], a[2], 64u));),
        RK_PARITY("rk_histogram_bin_edge", E, (dom_any(0.0f, 300.0f), dom_any(-30.0f, 0.0f), dom_any(1.0f, 50.0f)), 1,
                  o[0] = rk_histogram_bin_edge(a[0], a[1], a[2], 256u);),
        RK_PARITY("rk_histogram_rank_in_bin", E, (dom_any(0.0f, 100.0f), dom_any(0.0f, 100.0f), dom_any(0.0f, 50.0f), dom_any(-10.0f, 10.0f)), 1,
                  o[0] = rk_histogram_rank_in_bin(a[0], a[1], a[2], a[3], a[3] + 0.25f);),
        RK_PARITY("rk_histogram_scan_init/_bin/_average", E,
                  (dom_any(0.0f, 100.0f), dom_any(0.0f, 150.0f), dom_any(0.0f, 250.0f), dom_any(0.0f, 200.0f), dom_any(0.0f, 200.0f), dom_any(0.0f, 100.0f)), 8,
                  rk_histogram_scan s = rk_histogram_scan_init();
                  rk_histogram_scan_bin(s, a[0], -1.0f, 0.0f, a[1], a[2], a[3], a[4]);
                  rk_histogram_scan_bin(s, a[5], 0.0f, 1.0f, a[1], a[2], a[3], a[4]);
                  o[0] = s.below; o[1] = s.weight; o[2] = s.weighted_log2; o[3] = s.low_log2; o[4] = s.high_log2;
                  o[5] = s.low_found; o[6] = s.high_found; o[7] = rk_histogram_scan_average(s);),
    };
    for (parity::Case& c : cases) {
        // Ranges of an arbitrary bin range can put a value within an ulp of a bin edge, where the
        // driver's division may round the other way (documented): one bin of slack there only.
        if (c.name == "rk_histogram_bin (any range)") c.abs_tol = 1.0;
        // log2/exp2 outputs up to ~60 stops and exposures up to 2^64: llvmpipe's log2/exp2 differ
        // from glibc's by a few ulp (measured numbers are printed per case).
        if (c.name == "rk_ev100_from_camera" || c.name == "rk_adapt_log2") c.abs_tol = 1e-5;
    }
    return cases;
}

}  // namespace

TEST(GpuParity, Exposure)
{
    long rows = 0;
    for (const parity::Case& c : exposure_cases()) {
        const parity::Result r = parity::run(c, parity::shader_dir(), 2048);
        rows += r.rows;
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
    std::printf("[parity] exposure: %ld input rows in total\n", rows);
}

// ---------------------------------------------------------------------------------------------
// The reduction chain on the GPU vs the CPU references.

namespace {

std::uint32_t hash32(std::uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

/// RGBA (alpha 1) or RGB/luminance test image: ~4% zeros, 1.5% 1e-30, 1.5% denormals (1e-40),
/// 1.5% 1e6-bright, 0.3% NaN, 0.3% +Inf, 0.3% -Inf, 0.4% negative, the rest log-uniform over
/// [2^-20, 2^20] per channel (a smooth gradient plus noise, like a rendered frame).
std::vector<float> make_image(int w, int h, int channels, std::uint32_t seed)
{
    std::vector<float> px(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(channels));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
            const std::uint32_t r = hash32(static_cast<std::uint32_t>(i) * 2654435761u ^ seed);
            const std::uint32_t k = r % 1000u;
            float special = -1.0f;
            bool use_special = true;
            if (k < 40) special = 0.0f;
            else if (k < 55) special = 1e-30f;
            else if (k < 70) special = 1e-40f;
            else if (k < 85) special = 1e6f;
            else if (k < 88) special = kNaN;
            else if (k < 91) special = kInf;
            else if (k < 94) special = -kInf;
            else if (k < 98) special = -0.25f;
            else use_special = false;
            const float base = -20.0f + 40.0f * (static_cast<float>(x) / static_cast<float>(w) * 0.5f +
                                                 static_cast<float>(y) / static_cast<float>(h) * 0.5f);
            float* p = &px[i * static_cast<size_t>(channels)];
            for (int c = 0; c < channels; ++c) {
                if (c == 3) {
                    p[c] = 1.0f;
                    continue;
                }
                const float noise = static_cast<float>(hash32(r + static_cast<std::uint32_t>(c) * 77u) % 4096u) / 4096.0f;
                p[c] = use_special ? special : std::exp2(base + 8.0f * (noise - 0.5f));
            }
        }
    }
    return px;
}

GLuint upload_texture(const std::vector<float>& px, int w, int h, int channels)
{
    const GLenum internal = channels == 1 ? GL_R32F : channels == 3 ? GL_RGB32F : GL_RGBA32F;
    const GLenum format = channels == 1 ? GL_RED : channels == 3 ? GL_RGB : GL_RGBA;
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, internal, w, h);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(tex, 0, 0, 0, w, h, format, GL_FLOAT, px.data());
    return tex;
}

double rel(double got, double want) { return std::abs(got - want) / std::max(std::abs(want), 1e-300); }

struct Compared {
    double log_average_rel = 0, mean_log2_abs = 0, hist_avg_rel = 0;
    long hist_l1 = 0;
};

/// Runs the GPU chain on `px` (texture or buffer) and compares with the CPU references.
Compared check(rkgl::LuminanceReducer& reducer, const std::vector<float>& px, int w, int h, int channels, bool buffer,
               const char* label, bool print)
{
    using clock = std::chrono::steady_clock;
    rkgl::LuminanceReduceOptions opt;
    opt.reset_adaptation = true;
    const auto t0 = clock::now();
    LogAverageOptions cpu_opt;
    cpu_opt.delta = opt.delta;
    const LuminanceStats cpu = log_average_luminance(px, static_cast<size_t>(w), static_cast<size_t>(h), channels, cpu_opt);
    const std::vector<std::uint32_t> cpu_hist =
        luminance_histogram(px.data(), static_cast<size_t>(w), static_cast<size_t>(h), channels,
                            rkgl::LuminanceReducer::kBins, opt.hist_min_log2, opt.hist_max_log2, opt.delta);
    const HistogramStats hs = histogram_stats(cpu_hist, opt.hist_min_log2, opt.hist_max_log2, opt.window_low,
                                              opt.window_high, opt.robust_low, opt.robust_high);
    const auto t1 = clock::now();

    GLuint src = buffer ? rkgl::make_buffer(px.size() * sizeof(float), px.data()) : upload_texture(px, w, h, channels);
    glFinish();
    const auto t2 = clock::now();
    const rkgl::LuminanceReduceResult gpu =
        buffer ? reducer.reduce_buffer(src, w, h, channels, opt) : reducer.reduce_texture(src, w, h, channels, opt);
    const auto t3 = clock::now();
    if (buffer) glDeleteBuffers(1, &src);
    else glDeleteTextures(1, &src);

    Compared c;
    c.log_average_rel = rel(gpu.log_average, cpu.log_average);
    c.mean_log2_abs = std::abs(gpu.mean_log2 - cpu.mean_log2);
    c.hist_avg_rel = rel(gpu.histogram_average, hs.average);
    std::uint64_t total = 0;
    for (size_t b = 0; b < gpu.histogram.size(); ++b) {
        total += gpu.histogram[b];
        c.hist_l1 += std::labs(static_cast<long>(gpu.histogram[b]) - static_cast<long>(cpu_hist[b]));
    }
    EXPECT_EQ(total, static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h)) << label;
    const double ms = [](clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }(t3 - t2);
    if (print) {
        std::printf("[lumreduce] %-28s %5dx%-5d ch %d  GPU log-average %.9g  CPU %.9g  rel diff %.2e  (mean log2 GPU %.7f "
                    "CPU %.7f)\n"
                    "            histogram L1 %ld px, trimmed avg GPU %.7g CPU %.7g (rel %.2e), robust min %.4g/%.4g "
                    "max %.4g/%.4g, key %.5f/%.5f, white %.5g/%.5g\n"
                    "            CPU reference %.0f ms, upload %.0f ms, GPU chain + read-back %.0f ms; %zu sanitised px\n",
                    label, w, h, channels, static_cast<double>(gpu.log_average), static_cast<double>(cpu.log_average),
                    c.log_average_rel, static_cast<double>(gpu.mean_log2), cpu.mean_log2, c.hist_l1,
                    static_cast<double>(gpu.histogram_average), static_cast<double>(hs.average), c.hist_avg_rel,
                    static_cast<double>(gpu.robust_min), static_cast<double>(hs.low), static_cast<double>(gpu.robust_max),
                    static_cast<double>(hs.high), static_cast<double>(gpu.key),
                    static_cast<double>(rk_reinhard_auto_key(cpu.log_average, hs.low, hs.high)), static_cast<double>(gpu.white),
                    static_cast<double>(rk_reinhard_auto_white(hs.low, hs.high)),
                    std::chrono::duration<double, std::milli>(t1 - t0).count(),
                    std::chrono::duration<double, std::milli>(t2 - t1).count(), ms, cpu.sanitized);
    }
    EXPECT_TRUE(std::isfinite(gpu.log_average) && std::isfinite(gpu.histogram_average) && std::isfinite(gpu.key) &&
                std::isfinite(gpu.white) && std::isfinite(gpu.exposure))
        << label;
    EXPECT_LT(c.log_average_rel, 1e-4) << label << " GPU " << gpu.log_average << " CPU " << cpu.log_average;
    // Histogram: a term within an ulp of a bin edge may land in the neighbouring bin (llvmpipe's
    // log2 vs glibc's); anything beyond 1e-5 of the pixels would be a real difference.
    EXPECT_LE(static_cast<double>(c.hist_l1), 2.0 + 1e-5 * w * h) << label;
    EXPECT_LT(c.hist_avg_rel, 1e-4) << label;
    const double bin = (opt.hist_max_log2 - opt.hist_min_log2) / rkgl::LuminanceReducer::kBins;
    EXPECT_NEAR(std::log2(gpu.robust_min), std::log2(hs.low), 1e-3 * bin) << label;
    EXPECT_NEAR(std::log2(gpu.robust_max), std::log2(hs.high), 1e-3 * bin) << label;
    // The histogram's robust extremes approximate the exact percentiles within a bin (on images
    // large enough that the rank conventions, p N vs (N - 1) p, pick the same order statistic).
    if (static_cast<long>(w) * h >= 10000) {
        EXPECT_NEAR(std::log2(gpu.robust_min), std::log2(cpu.robust_min), bin) << label;
        EXPECT_NEAR(std::log2(gpu.robust_max), std::log2(cpu.robust_max), bin) << label;
    }
    EXPECT_NEAR(gpu.key, rk_reinhard_auto_key(cpu.log_average, hs.low, hs.high), 1e-4 * gpu.key) << label;
    EXPECT_NEAR(gpu.white, rk_reinhard_auto_white(hs.low, hs.high), 1e-4 * gpu.white) << label;
    // Adaptation was reset: adapted == target, EV100 and exposure of it.
    EXPECT_EQ(gpu.adapted, gpu.log_average) << label;
    EXPECT_NEAR(gpu.ev100, rk_ev100_from_luminance(gpu.log_average), 1e-5) << label;
    EXPECT_NEAR(gpu.exposure, rk_exposure_from_luminance(gpu.log_average, 0.0f), 2e-5 * gpu.exposure) << label;
    return c;
}

}  // namespace

TEST(GpuLuminanceReduce, Matches4KCpuReference)
{
    const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    std::printf("[lumreduce] renderer: %s\n", renderer ? renderer : "?");
    rkgl::LuminanceReducer reducer(parity::shader_dir());
    const int w = 3840, h = 2160;
    const std::vector<float> px = make_image(w, h, 4, 12345u);
    const Compared c = check(reducer, px, w, h, 4, false, "3840x2160 RGBA32F texture", true);
    std::printf("[lumreduce] 4K: GPU vs CPU log-average relative difference %.3e (limit 1e-4), mean log2 %.3e stops\n",
                c.log_average_rel, c.mean_log2_abs);
}

TEST(GpuLuminanceReduce, NonMultipleAndTinySizes)
{
    rkgl::LuminanceReducer reducer(parity::shader_dir());
    struct Size {
        int w, h, channels;
        bool buffer;
        const char* label;
    };
    const Size sizes[] = {{1023, 767, 4, false, "1023x767 RGBA32F texture"}, {1023, 767, 3, true, "1023x767 RGB SSBO"},
                          {1023, 767, 1, false, "1023x767 R32F texture (L)"}, {1, 1, 4, false, "1x1 texture"},
                          {1, 1, 1, true, "1x1 SSBO (L)"},                   {65, 1, 3, true, "65x1 SSBO"},
                          {1, 4097, 4, false, "1x4097 texture (3 passes)"}};
    for (const Size& s : sizes) {
        const std::vector<float> px = make_image(s.w, s.h, s.channels, static_cast<std::uint32_t>(s.w * 31 + s.h));
        check(reducer, px, s.w, s.h, s.channels, s.buffer, s.label, true);
    }
    // 1x1 with each kind of special pixel: the sanitised value, never NaN/Inf.
    for (float v : {0.0f, 1e-40f, kNaN, kInf, -kInf, -1.0f, 1e6f, 0.18f}) {
        const std::vector<float> one = {v};
        GLuint buf = rkgl::make_buffer(sizeof(float), one.data());
        const rkgl::LuminanceReduceResult r = reducer.reduce_buffer(buf, 1, 1, 1, {});
        glDeleteBuffers(1, &buf);
        const float want = log_average_luminance(one, 1, 1, 1).log_average;
        EXPECT_NEAR(r.log_average, want, 2e-5 * want) << v;
    }
}

TEST(GpuLuminanceReduce, AdaptationOnTheGpuIsFrameRateIndependent)
{
    const int w = 96, h = 64;
    const std::vector<float> dark(static_cast<size_t>(w * h), 0.01f), bright(static_cast<size_t>(w * h), 50.0f);
    GLuint bd = rkgl::make_buffer(dark.size() * sizeof(float), dark.data());
    GLuint bb = rkgl::make_buffer(bright.size() * sizeof(float), bright.data());
    rkgl::LuminanceReduceOptions o;
    o.histogram = false;
    rkgl::LuminanceReducer r1(parity::shader_dir()), r2(parity::shader_dir());
    // Both start adapted to the dark image (first run: reset to target).
    const float start = r1.reduce_buffer(bd, w, h, 1, o).adapted;
    EXPECT_EQ(r2.reduce_buffer(bd, w, h, 1, o).adapted, start);
    // dt = 0: nothing changes even though the scene changed.
    EXPECT_EQ(r1.reduce_buffer(bb, w, h, 1, o).adapted, start);
    // Two frames of dt on one, one frame of 2 dt on the other.
    o.dt = 0.05f;
    r1.reduce_buffer(bb, w, h, 1, o);
    const rkgl::LuminanceReduceResult two = r1.reduce_buffer(bb, w, h, 1, o);
    o.dt = 0.1f;
    const rkgl::LuminanceReduceResult one = r2.reduce_buffer(bb, w, h, 1, o);
    const float cpu = rk_adapt_luminance(rk_adapt_luminance(start, two.log_average, 0.05f, o.tau_up, o.tau_down),
                                         two.log_average, 0.05f, o.tau_up, o.tau_down);
    std::printf("[lumreduce] adaptation dark %.6g -> bright %.6g: two steps of 0.05 s %.7g, one of 0.1 s %.7g, CPU %.7g; "
                "key %.3f white %.4g (histogram off)\n",
                static_cast<double>(start), static_cast<double>(two.log_average), static_cast<double>(two.adapted),
                static_cast<double>(one.adapted), static_cast<double>(cpu), static_cast<double>(two.key),
                static_cast<double>(two.white));
    EXPECT_NEAR(two.adapted, one.adapted, 2e-5 * one.adapted);
    EXPECT_NEAR(two.adapted, cpu, 2e-5 * cpu);
    EXPECT_GT(two.adapted, start);
    EXPECT_LT(two.adapted, two.log_average);
    // Without the histogram: the documented fallbacks.
    EXPECT_EQ(two.key, RK_EXPOSURE_MIDDLE_GREY);
    EXPECT_EQ(two.white, RK_HDR_MAX);
    EXPECT_EQ(two.histogram_average, 0.0f);
    // Long enough: converged to the bright target, monotonically.
    o.dt = 0.5f;
    float prev = two.adapted;
    for (int i = 0; i < 40; ++i) {
        const float a = r1.reduce_buffer(bb, w, h, 1, o).adapted;
        ASSERT_GE(a, prev);
        ASSERT_LE(a, two.log_average * (1.0f + 1e-5f));
        prev = a;
    }
    EXPECT_NEAR(prev, two.log_average, 1e-4 * two.log_average);
    glDeleteBuffers(1, &bd);
    glDeleteBuffers(1, &bb);
}
