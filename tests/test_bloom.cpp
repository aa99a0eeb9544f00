// CPU tests of raykit/bloom.hpp (the C++ build of shaders/raykit/bloom.glsl plus the CPU-only
// helpers) against values that follow from the bloom of Fahlén, "Illumination for Real-Time
// Rendering of Large Architectural Environments" (2005), §3.4 (sigma = 3, 4 levels from 1/8), and
// float64 re-implementations of every shared function. The numbers printed here are the "max error
// vs float64" quoted in bloom.glsl.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "raykit/bloom.hpp"
#include "test_util.hpp"

using namespace raykit;
using rktest::ErrorStats;
using rktest::fmt;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();

/// Inputs no shared function may turn into NaN/Inf: NaN, ±Inf, negatives, ±0, denormals, huge.
const std::vector<float>& hostile()
{
    static const std::vector<float> v = {kNaN, -kNaN, kInf, -kInf, -1.0f, -1e30f, -3.4028235e38f, 0.0f, -0.0f,
                                         1e-45f, 1e-40f, 1.17549435e-38f, 1e-20f, 0.5f, 1.5f, 2.0f, 1e18f, 1e20f,
                                         3.4028235e38f};
    return v;
}

bool finite_in_range(vec3 c)
{
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(c[i]) || c[i] < 0.0f || c[i] > RK_HDR_MAX) return false;
    }
    return true;
}

// ---- float64 references of the shared functions -------------------------------------------------
double lum64(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
double soft64(double y, double t, double k)
{
    if (y <= t - k) return 0.0;
    if (y >= t + k) return 1.0;
    const double u = (y - (t - k)) / (2.0 * k);
    return u <= 0.5 ? 2.0 * u * u : 1.0 - 2.0 * (1.0 - u) * (1.0 - u);
}
double sub64(double y, double t, double k)
{
    if (y <= t - k) return 0.0;
    const double q = k > 0.0 ? std::pow(std::min(y - (t - k), 2.0 * k), 2.0) / (4.0 * k) : 0.0;
    return std::min(std::max(q, y - t) / y, 1.0);
}

// ---- 1-D CPU simulation of a GL_LINEAR fetch with a black border ---------------------------------
float fetch1(const std::vector<float>& s, int i) { return i < 0 || i >= static_cast<int>(s.size()) ? 0.0f : s[static_cast<size_t>(i)]; }
float bilinear1(const std::vector<float>& s, double x)  // x in texel units, texel i centred at i
{
    const double f = std::floor(x);
    const float t = static_cast<float>(x - f);
    const int i = static_cast<int>(f);
    return (1.0f - t) * fetch1(s, i) + t * fetch1(s, i + 1);
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// Gaussian weights and merged linear taps (Fahlén 2005 §3.4.2: sigma = 3; radius 9 = 3 sigma is ours).

TEST(BloomWeights, PublishedSigma3Radius9)
{
    const std::vector<float> w = gaussian_weights(3.0f, 9);
    ASSERT_EQ(w.size(), 10u);
    const double published[10] = {0.13318, 0.12598, 0.10664, 0.08078, 0.05475, 0.03321, 0.01802, 0.00875, 0.00380, 0.00148};
    for (size_t i = 0; i < 10; ++i) EXPECT_NEAR(w[i], published[i], 1e-5) << "w" << i;
    double sum = w[0];
    for (size_t i = 1; i < w.size(); ++i) sum += 2.0 * w[i];
    EXPECT_NEAR(sum, 1.0, 1e-6);
    // Full 19-tap kernel: symmetric by construction, monotonically decreasing from the centre.
    std::vector<float> full;
    for (int k = -9; k <= 9; ++k) full.push_back(w[static_cast<size_t>(std::abs(k))]);
    for (size_t i = 0; i < full.size(); ++i) EXPECT_EQ(full[i], full[full.size() - 1 - i]);
    for (size_t i = 1; i < w.size(); ++i) EXPECT_LT(w[i], w[i - 1]);
}

TEST(BloomWeights, SumToOneAndSymmetricForManySigmas)
{
    for (float sigma : {0.01f, 0.5f, 1.0f, 2.0f, 3.0f, 4.5f, 10.0f, 100.0f}) {
        for (int radius : {0, 1, 2, 8, 9, 30}) {
            const std::vector<float> w = gaussian_weights(sigma, radius);
            double sum = w[0];
            for (size_t i = 1; i < w.size(); ++i) sum += 2.0 * w[i];
            EXPECT_NEAR(sum, 1.0, 2e-6) << fmt("sigma", sigma, "radius", radius);
            for (float x : w) EXPECT_TRUE(std::isfinite(x) && x >= 0.0f);
        }
    }
    // Broken preconditions: an empty result and an invalid_argument status naming the function.
    for (const auto& bad : {std::pair<float, int>{0.0f, 9}, {kNaN, 9}, {kInf, 9}, {3.0f, -1}, {3.0f, 4097}}) {
        Status st;
        EXPECT_TRUE(gaussian_weights(bad.first, bad.second, &st).empty());
        EXPECT_EQ(st.code, Error::invalid_argument);
        EXPECT_NE(st.message.find("gaussian_weights"), std::string::npos) << st.message;
        EXPECT_TRUE(gaussian_weights(bad.first, bad.second).empty());  // no status: still empty, no crash
    }
    Status ok_st;
    ok_st.code = Error::io;  // a stale status is cleared by a successful call
    EXPECT_EQ(gaussian_weights(3.0f, 9, &ok_st).size(), 10u);
    EXPECT_TRUE(ok_st.ok());
}

TEST(BloomWeights, PublishedLinearTaps)
{
    const std::vector<BloomTap> taps = linear_sampled_taps(gaussian_weights(3.0f, 9));
    ASSERT_EQ(taps.size(), 6u);
    EXPECT_EQ(linear_tap_fetches(taps), 11);  // instead of 19
    const double off[6] = {0.0, 1.4584, 3.4040, 5.3518, 7.3029, 9.0};
    const double wt[6] = {0.13318, 0.23262, 0.13553, 0.05123, 0.01256, 0.00148};
    for (size_t i = 0; i < 6; ++i) {
        EXPECT_NEAR(taps[i].offset, off[i], 5e-5) << "tap " << i;  // published to 4 decimals
        EXPECT_NEAR(taps[i].weight, wt[i], 1e-5) << "tap " << i;
        if (i > 0 && i < 5) {
            EXPECT_GE(taps[i].offset, static_cast<float>(2 * i - 1));  // between texels i and i + 1
            EXPECT_LE(taps[i].offset, static_cast<float>(2 * i));
        }
    }
    double sum = taps[0].weight;
    for (size_t i = 1; i < taps.size(); ++i) sum += 2.0 * taps[i].weight;
    EXPECT_NEAR(sum, 1.0, 1e-6);
    // Even radius: no lone last tap.
    EXPECT_EQ(linear_sampled_taps(gaussian_weights(3.0f, 8)).size(), 5u);
    EXPECT_EQ(linear_sampled_taps(gaussian_weights(3.0f, 0)).size(), 1u);
    EXPECT_TRUE(linear_sampled_taps({}).empty());
    // Weights that underflow to 0 keep a finite offset.
    const std::vector<BloomTap> tiny = linear_sampled_taps(gaussian_weights(0.01f, 4));
    for (const BloomTap& t : tiny) EXPECT_TRUE(std::isfinite(t.offset) && std::isfinite(t.weight));
}

// The merge claim: 11 bilinear fetches reproduce the 19-tap discrete convolution (zero outside the
// signal, as GL_CLAMP_TO_BORDER black) on random signals.
TEST(BloomWeights, LinearTapsReproduceDiscreteConvolution)
{
    std::mt19937 rng(7);
    struct Kernel {
        float sigma;
        int radius;
        double bound;  // on signals in [0, 1]
    };
    const Kernel kernels[] = {{3.0f, 9, 1e-6}, {1.0f, 3, 1e-6}, {2.0f, 6, 1e-6}, {5.0f, 15, 1e-6}, {10.0f, 30, 1e-6}};
    for (const Kernel& k : kernels) {
        const std::vector<float> w = gaussian_weights(k.sigma, k.radius);
        const std::vector<BloomTap> taps = linear_sampled_taps(w);
        ErrorStats stats, stats_fpos;
        for (int sig = 0; sig < 200; ++sig) {
            std::uniform_real_distribution<float> u(0.0f, 1.0f);
            std::vector<float> s(static_cast<size_t>(16 + sig % 64));
            for (float& v : s) v = u(rng);
            if (sig % 5 == 0) {  // sparse spikes: the bloom case
                for (float& v : s) v = u(rng) < 0.9f ? 0.0f : v;
            }
            for (int x = 0; x < static_cast<int>(s.size()); ++x) {
                double exact = 0.0;
                for (int j = -k.radius; j <= k.radius; ++j) exact += static_cast<double>(w[static_cast<size_t>(std::abs(j))]) * fetch1(s, x + j);
                // The sampler at x +- offset computed exactly (as texel x plus the offset's fraction), the
                // filtering and the sum in float; and with the position itself rounded to float.
                const double xd = static_cast<double>(x);
                const float xf = static_cast<float>(x);
                float merged = taps[0].weight * bilinear1(s, xd);
                float merged_fpos = merged;
                for (size_t t = 1; t < taps.size(); ++t) {
                    const double o = taps[t].offset;
                    merged += taps[t].weight * (bilinear1(s, xd + o) + bilinear1(s, xd - o));
                    merged_fpos += taps[t].weight * (bilinear1(s, static_cast<double>(xf + taps[t].offset)) +
                                                     bilinear1(s, static_cast<double>(xf - taps[t].offset)));
                }
                stats.add(merged, exact, fmt("signal", sig, "x", x));
                stats_fpos.add(merged_fpos, exact, fmt("signal", sig, "x", x));
            }
        }
        std::printf("merged taps sigma %.1f radius %d (%d fetches vs %d): %s\n  with float positions: %s\n",
                    static_cast<double>(k.sigma), k.radius, linear_tap_fetches(taps), 2 * k.radius + 1, stats.str().c_str(),
                    stats_fpos.str().c_str());
        EXPECT_LT(stats.max_abs, k.bound) << stats.str();
        // Rounding x + offset to float (ulp 7.6e-6 at x ~ 64..128) moves the fraction: small extra error.
        EXPECT_LT(stats_fpos.max_abs, 4e-6) << stats_fpos.str();
    }
}

// ---------------------------------------------------------------------------------------------
// Chain sizes.

// Texel coordinates and composites under adversarial inputs: NaN / infinite / huge coordinates and
// sizes give coordinates inside the source and weights in [0, 1]; the mix composite stays at or
// below RK_HDR_MAX when both colours sit at it.
TEST(BloomHelpers, AdversarialCoordinatesAndCompositeRange)
{
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    const float specials[] = {nan, inf, -inf, 0.0f, -0.0f, 1e-40f, 0.5f, 1.0f, 3.0f, 4096.0f, 1e7f, 1e30f, -1e30f};
    for (float f : specials) {
        for (float d : specials) {
            for (float s : specials) {
                const float t = rk_bloom_source_texel(f, d, s);
                const float src = s > 1.0f ? std::min(s, 65536.0f) : 1.0f;
                ASSERT_TRUE(t >= -0.5f && t <= src - 0.5f) << f << " " << d << " " << s << " -> " << t;
            }
        }
        for (float g : specials) {
            const vec4 w = rk_bloom_bilinear_weights(vec2(f, g));
            for (int k = 0; k < 4; ++k) ASSERT_TRUE(w[k] >= 0.0f && w[k] <= 1.0f) << f << " " << g;
            ASSERT_NEAR(w.x + w.y + w.z + w.w, 1.0f, 1e-6f) << f << " " << g;
        }
    }
    std::mt19937 rng(3);
    for (int i = 0; i < 100000; ++i) {
        const float s = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
        const vec3 top(RK_HDR_MAX), near_top(std::nextafter(RK_HDR_MAX, 0.0f));
        for (const vec3 c : {rk_bloom_composite_mix(top, top, s), rk_bloom_composite_mix(top, near_top, s),
                             rk_bloom_composite_add(top, top, s)}) {
            ASSERT_TRUE(c.x <= RK_HDR_MAX && c.x >= 0.0f) << s << " -> " << c.x;
        }
    }
}

TEST(BloomChain, ThesisSizes)
{
    const BloomChain c = bloom_chain(1024, 768);
    ASSERT_EQ(c.levels.size(), 4u);
    EXPECT_EQ(c.levels[0], ivec2(128, 96));
    EXPECT_EQ(c.levels[1], ivec2(64, 48));
    EXPECT_EQ(c.levels[2], ivec2(32, 24));
    EXPECT_EQ(c.levels[3], ivec2(16, 12));
    ASSERT_EQ(c.downsamples.size(), 6u);
    EXPECT_EQ(c.downsamples[0], ivec2(512, 384));
    EXPECT_EQ(c.downsamples[1], ivec2(256, 192));
    EXPECT_EQ(c.downsamples[2], ivec2(128, 96));
}

TEST(BloomChain, OddAndTinySizes)
{
    const BloomChain c = bloom_chain(1023, 767);
    EXPECT_EQ(c.downsamples[0], ivec2(512, 384));
    EXPECT_EQ(c.levels[0], ivec2(128, 96));
    EXPECT_EQ(c.levels[3], ivec2(16, 12));
    const BloomChain d = bloom_chain(1920, 1080);
    EXPECT_EQ(d.levels[0], ivec2(240, 135));
    EXPECT_EQ(d.levels[1], ivec2(120, 68));  // ceil(135 / 2)
    EXPECT_EQ(d.levels[2], ivec2(60, 34));
    EXPECT_EQ(d.levels[3], ivec2(30, 17));
    const BloomChain e = bloom_chain(5, 3);
    EXPECT_EQ(e.downsamples[0], ivec2(3, 2));
    EXPECT_EQ(e.downsamples[1], ivec2(2, 1));
    EXPECT_EQ(e.levels[0], ivec2(1, 1));
    EXPECT_EQ(e.levels[3], ivec2(1, 1));
    const BloomChain one = bloom_chain(1, 1);
    for (const ivec2& s : one.downsamples) EXPECT_EQ(s, ivec2(1, 1));
    // first_div = 1: the first level is the full-size bright pass; 2: half size.
    const BloomChain f1 = bloom_chain(64, 32, 1, 3);
    ASSERT_EQ(f1.downsamples.size(), 3u);
    EXPECT_EQ(f1.levels[0], ivec2(64, 32));
    EXPECT_EQ(f1.levels[2], ivec2(16, 8));
    const BloomChain f2 = bloom_chain(64, 32, 2, 2);
    ASSERT_EQ(f2.downsamples.size(), 2u);
    EXPECT_EQ(f2.levels[0], ivec2(32, 16));
    const BloomChain f16 = bloom_chain(1024, 768, 16, 1);
    ASSERT_EQ(f16.downsamples.size(), 4u);
    EXPECT_EQ(f16.levels[0], ivec2(64, 48));
    struct Bad { int w, h, div, levels; const char* what; };
    for (const Bad& b : {Bad{0, 10, 8, 4, "width"}, Bad{10, 65537, 8, 4, "width"}, Bad{10, 10, 3, 4, "first_div"},
                         Bad{10, 10, 0, 4, "first_div"}, Bad{10, 10, 8, 0, "levels"}, Bad{10, 10, 8, 17, "levels"}}) {
        Status st;
        const BloomChain bad = bloom_chain(b.w, b.h, b.div, b.levels, &st);
        EXPECT_TRUE(bad.downsamples.empty() && bad.levels.empty());
        EXPECT_EQ(st.code, Error::invalid_argument);
        EXPECT_NE(st.message.find(b.what), std::string::npos) << st.message;
    }
}

// ---------------------------------------------------------------------------------------------
// Bright pass.

TEST(BloomBrightPass, HardThresholdOfTheThesis)
{
    const float t = RK_BLOOM_THRESHOLD;
    EXPECT_EQ(t, 1.5f);
    // Grey of luminance exactly at, just below and above the threshold (grey: Y = value).
    EXPECT_EQ(rk_bloom_bright_pass_hard(vec3(1.5f), t), vec3(0.0f));
    EXPECT_EQ(rk_bloom_bright_pass_hard(vec3(1.4f), t), vec3(0.0f));
    EXPECT_EQ(rk_bloom_bright_pass_hard(vec3(0.0f), t), vec3(0.0f));
    EXPECT_EQ(rk_bloom_bright_pass_hard(vec3(1.6f), t), vec3(1.6f));
    // Luminance, not the max channel: pure blue of 10 has Y = 0.722 < 1.5.
    EXPECT_EQ(rk_bloom_bright_pass_hard(vec3(0.0f, 0.0f, 10.0f), t), vec3(0.0f));
    EXPECT_EQ(rk_bloom_bright_pass_hard(vec3(0.0f, 3.0f, 0.0f), t), vec3(0.0f, 3.0f, 0.0f));
    for (int i = 0; i < 1000; ++i) {
        const float y = 3.0f * static_cast<float>(i) / 1000.0f;
        const vec3 out = rk_bloom_bright_pass_hard(vec3(y), t);
        EXPECT_EQ(out, rk_luminance(vec3(y)) > t ? vec3(y) : vec3(0.0f));
    }
    EXPECT_EQ(rk_bloom_weight(1.6f, t, 0.5f, RK_BLOOM_MODE_HARD), 1.0f);
    EXPECT_EQ(rk_bloom_weight(1.6f, t, 0.5f, 77), 1.0f);  // unknown mode = hard
    EXPECT_EQ(rk_bloom_cutoff(t, 0.5f, RK_BLOOM_MODE_HARD), 1.5f);
    EXPECT_EQ(rk_bloom_cutoff(t, 0.5f, RK_BLOOM_MODE_SOFT_KNEE), 1.0f);
    EXPECT_EQ(rk_bloom_cutoff(t, 9.0f, RK_BLOOM_MODE_SUBTRACT), 0.0f);  // knee clamped to T
}

TEST(BloomBrightPass, SoftKneeIsC1AndEqualsHardOutsideTheKnee)
{
    const float t = 1.5f, k = 0.5f;
    // Exactly the hard pass outside [T - K, T + K] (both sides), 1/2 at T.
    for (int i = 0; i <= 4000; ++i) {
        const float y = 10.0f * static_cast<float>(i) / 4000.0f;
        if (y <= t - k || y >= t + k) {
            EXPECT_EQ(rk_bloom_weight_soft_knee(y, t, k), y >= t + k ? 1.0f : 0.0f) << y;
            EXPECT_EQ(rk_bloom_bright_pass_soft_knee(vec3(y), t, k) == rk_bloom_bright_pass_hard(vec3(y), t),
                      rk_luminance(vec3(y)) <= t - k || rk_luminance(vec3(y)) >= t + k) << y;
        }
    }
    EXPECT_EQ(rk_bloom_weight_soft_knee(t, t, k), 0.5f);
    EXPECT_EQ(rk_bloom_weight_soft_knee(2.5f, t, 0.0f), 1.0f);   // K = 0: the hard pass
    EXPECT_EQ(rk_bloom_weight_soft_knee(1.5f, t, 0.0f), 0.0f);
    EXPECT_EQ(rk_bloom_weight_soft_knee(1.5000001f, t, 0.0f), 1.0f);

    // C0: no jump larger than the maximal slope 1/K allows; C1: one-sided difference quotients agree
    // at the three junctions T - K, T, T + K. The hard pass has a jump of 1 at T.
    const float h = 1e-3f;
    double max_jump = 0.0;
    for (int i = 0; i < 3000; ++i) {
        const float y = 0.5f + h * static_cast<float>(i);
        max_jump = std::max(max_jump, std::abs(static_cast<double>(rk_bloom_weight_soft_knee(y + h, t, k)) -
                                               rk_bloom_weight_soft_knee(y, t, k)));
    }
    std::printf("soft knee: max step over dY = 1e-3: %.3g (bound h / K = %.3g); hard: %.3g\n", max_jump,
                static_cast<double>(h / k),
                static_cast<double>(rk_bloom_weight_hard(1.5001f, t) - rk_bloom_weight_hard(1.5f, t)));
    EXPECT_LE(max_jump, static_cast<double>(h / k) * 1.001);
    for (float j : {t - k, t, t + k}) {
        const double left = (static_cast<double>(rk_bloom_weight_soft_knee(j, t, k)) - rk_bloom_weight_soft_knee(j - h, t, k)) / h;
        const double right = (static_cast<double>(rk_bloom_weight_soft_knee(j + h, t, k)) - rk_bloom_weight_soft_knee(j, t, k)) / h;
        std::printf("soft knee slope at Y = %.2f: left %.5f right %.5f\n", static_cast<double>(j), left, right);
        EXPECT_NEAR(left, right, 5e-3) << "kink at " << j;
    }
    // Same energy on average as the hard step: the integral of (w - step) over the knee is 0.
    double diff = 0.0;
    for (int i = 0; i < 100000; ++i) {
        const float y = t - k + 2.0f * k * (static_cast<float>(i) + 0.5f) / 100000.0f;
        diff += (static_cast<double>(rk_bloom_weight_soft_knee(y, t, k)) - rk_bloom_weight_hard(y, t)) * (2.0 * k / 100000.0);
    }
    EXPECT_NEAR(diff, 0.0, 1e-6);
}

TEST(BloomBrightPass, SubtractKnee)
{
    const float t = 1.5f, k = 0.5f;
    // Output luminance f(Y) = Y w(Y): 0 below T - K, Y - T above T + K, C1 at both ends.
    auto f = [&](float y) { return static_cast<double>(y) * rk_bloom_weight_subtract(y, t, k); };
    for (int i = 0; i <= 2000; ++i) {
        const float y = 10.0f * static_cast<float>(i) / 2000.0f;
        if (y <= t - k) {
            EXPECT_EQ(f(y), 0.0);
        }
        if (y >= t + k) {
            EXPECT_NEAR(f(y), static_cast<double>(y) - t, 1e-6 * y);
        }
        EXPECT_LE(rk_bloom_weight_subtract(y, t, k), 1.0f);
    }
    const float h = 1e-3f;
    for (float j : {t - k, t + k}) {
        const double left = (f(j) - f(j - h)) / h, right = (f(j + h) - f(j)) / h;
        EXPECT_NEAR(left, right, 5e-3) << j;
    }
    // K = 0: max(Y - T, 0) / Y, continuous but with a kink.
    EXPECT_NEAR(rk_bloom_weight_subtract(3.0f, t, 0.0f), 0.5f, 1e-7);
    EXPECT_EQ(rk_bloom_weight_subtract(1.5f, t, 0.0f), 0.0f);
    EXPECT_EQ(rk_bloom_bright_pass_subtract(vec3(1.0f), t, k), vec3(0.0f));
    // Colour keeps its chromaticity.
    const vec3 c = rk_bloom_bright_pass_subtract(vec3(4.0f, 2.0f, 1.0f), t, k);
    EXPECT_NEAR(c.x / c.y, 2.0f, 1e-6f);
}

TEST(BloomBrightPass, ErrorVsFloat64)
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    ErrorStats lum, soft, soft_any, sub, bright_soft, bright_sub;
    double soft_scaled = 0.0;  // error / (eps32 (T + K) / K): the conditioning of T - K through slope 1/K
    for (int i = 0; i < 200000; ++i) {
        const vec3 c(4.0f * u(rng), 4.0f * u(rng), 4.0f * u(rng));
        const float t = 3.0f * u(rng), k = u(rng);
        const double kk = std::min<double>(k, t);
        const std::string in = fmt(c.x, c.y, c.z, "T", t, "K", k);
        const double y64 = lum64(c.x, c.y, c.z);
        const float y = rk_bloom_luminance(c);
        lum.add(y, y64, in, rktest::ulp_error(y, y64));
        // The weights at the float luminance (the input's own rounding is not the weight's error).
        const float ws32 = rk_bloom_weight_soft_knee(y, t, k);
        soft_any.add(ws32, soft64(y, t, kk), in);
        if (kk >= 0.1 * t) soft.add(ws32, soft64(y, t, kk), in);
        if (kk > 0.0) soft_scaled = std::max(soft_scaled, std::abs(ws32 - soft64(y, t, kk)) / (5.96e-8 * (t + kk) / kk));
        sub.add(rk_bloom_weight_subtract(y, t, k), sub64(y, t, kk), in);
        // The full bright pass vs float64 end to end, relative to the channel.
        const vec3 bs = rk_bloom_bright_pass_soft_knee(c, t, k), bu = rk_bloom_bright_pass_subtract(c, t, k);
        const double ws = soft64(y64, t, kk), wu = sub64(y64, t, kk);
        // Near the ends of the knee the float64 weight of the float64 luminance can differ by the
        // luminance rounding times the slope; compare with the range over Y +- 1 ulp.
        const double ylo = std::nextafter(y, 0.0f), yhi = std::nextafter(y, 10.0f);
        for (int ch = 0; ch < 3; ++ch) {
            const double cc = c[ch] > 0.0f ? c[ch] : 1.0;
            bright_soft.add(bs[ch] / cc, rktest::nearest_in(bs[ch] / cc, {soft64(ylo, t, kk), ws, soft64(yhi, t, kk)}), in);
            bright_sub.add(bu[ch] / cc, rktest::nearest_in(bu[ch] / cc, {sub64(ylo, t, kk), wu, sub64(yhi, t, kk)}), in);
        }
    }
    std::printf("rk_bloom_luminance vs float64: %s\n", lum.str().c_str());
    std::printf("rk_bloom_weight_soft_knee vs float64, K >= T / 10: %s\n  any K: %s\n  max error / (eps (T + K) / K) = %.3g\n",
                soft.str().c_str(), soft_any.str().c_str(), soft_scaled);
    std::printf("rk_bloom_weight_subtract vs float64: %s\n", sub.str().c_str());
    std::printf("rk_bloom_bright_pass_soft_knee / channel vs float64 (Y +- 1 ulp): %s\n", bright_soft.str().c_str());
    std::printf("rk_bloom_bright_pass_subtract / channel vs float64 (Y +- 1 ulp): %s\n", bright_sub.str().c_str());
    EXPECT_LE(lum.max_ulp, 2.0) << lum.str();
    EXPECT_LT(soft.max_abs, 5e-7) << soft.str();
    EXPECT_LT(soft_scaled, 2.0);
    EXPECT_LT(sub.max_abs, 2e-7) << sub.str();
    EXPECT_LT(bright_soft.max_abs, 2e-7) << bright_soft.str();
    EXPECT_LT(bright_sub.max_abs, 3e-7) << bright_sub.str();
}

// ---------------------------------------------------------------------------------------------
// Sanitising: every shared function is total, also for NaN and ±Inf.

TEST(BloomSanitize, NoNanOrInfFromAnyInput)
{
    EXPECT_EQ(rk_bloom_sanitize(kNaN), 0.0f);
    EXPECT_EQ(rk_bloom_sanitize(-kInf), 0.0f);
    EXPECT_EQ(rk_bloom_sanitize(kInf), RK_HDR_MAX);
    EXPECT_EQ(rk_bloom_sanitize(-2.0f), 0.0f);
    EXPECT_EQ(rk_bloom_sanitize(1e-40f), 0.0f);  // denormals flushed like an FTZ GPU
    EXPECT_EQ(rk_bloom_sanitize(2.5f), 2.5f);
    // Documented values: NaN and negative pixels never bloom; +Inf blooms as RK_HDR_MAX.
    EXPECT_EQ(rk_bloom_bright_pass_hard(vec3(kNaN, -5.0f, -kInf), 1.5f), vec3(0.0f));
    EXPECT_EQ(rk_bloom_bright_pass_hard(vec3(kInf, 0.0f, 0.0f), 1.5f), vec3(RK_HDR_MAX, 0.0f, 0.0f));
    EXPECT_EQ(rk_bloom_bright_pass_hard(vec3(2.0f), kNaN), vec3(2.0f));  // NaN threshold = 0
    EXPECT_NEAR(rk_bloom_karis_weight(vec3(kInf)), 1e-18, 1e-24);

    long checked = 0;
    for (float a : hostile()) {
        for (float b : hostile()) {
            for (float c : {0.0f, 1.5f, kNaN, kInf, -1.0f}) {
                const vec3 v(a, b, c);
                const vec3 w3(b, c, a);
                const vec4 w4(a, b, c, 0.25f);
                for (int mode = 0; mode < 3; ++mode) {
                    for (float t : {a, 1.5f}) {
                        const float wt = rk_bloom_weight(rk_bloom_luminance(v), t, b, mode);
                        EXPECT_TRUE(std::isfinite(wt) && wt >= 0.0f && wt <= 1.0f) << fmt(a, b, c, mode);
                        EXPECT_TRUE(finite_in_range(rk_bloom_bright_pass(v, t, b, mode))) << fmt(a, b, c, mode);
                        const float cut = rk_bloom_cutoff(t, b, mode);
                        EXPECT_TRUE(std::isfinite(cut) && cut >= 0.0f);
                        // The cutoff promise: luminance <= cutoff gives exactly black.
                        if (rk_bloom_luminance(v) <= cut) {
                            EXPECT_EQ(rk_bloom_bright_pass(v, t, b, mode), vec3(0.0f)) << fmt(a, b, c, mode);
                        }
                    }
                    EXPECT_TRUE(finite_in_range(rk_bloom_composite(v, w3, vec3(c), a, mode))) << fmt(a, b, c, mode);
                }
                EXPECT_TRUE(finite_in_range(rk_bloom_bright_pass_hard(v, a)));
                EXPECT_TRUE(finite_in_range(rk_bloom_bright_pass_soft_knee(v, a, b)));
                EXPECT_TRUE(finite_in_range(rk_bloom_bright_pass_subtract(v, a, b)));
                const float kw = rk_bloom_karis_weight(v);
                EXPECT_TRUE(std::isfinite(kw) && kw > 0.0f && kw <= 1.0f);
                EXPECT_TRUE(finite_in_range(rk_bloom_karis_average(v, w3, vec3(c), vec3(a), w4)));
                EXPECT_TRUE(finite_in_range(rk_bloom_weighted_average(v, w3, vec3(c), vec3(a), w4)));
                EXPECT_TRUE(finite_in_range(rk_bloom_sum_levels(v, w3, vec3(c), vec3(a), w4)));
                EXPECT_TRUE(finite_in_range(rk_bloom_composite_add(v, w3, c)));
                EXPECT_TRUE(finite_in_range(rk_bloom_composite_mix(v, w3, c)));
                EXPECT_TRUE(finite_in_range(rk_bloom_composite_conserve(v, w3, vec3(a), c)));
                const float l = rk_bloom_luminance(v);
                EXPECT_TRUE(std::isfinite(l) && l >= 0.0f && l <= RK_HDR_MAX);
                // Geometry helpers: finite inputs only (the harness's domain), any finite value.
                if (std::isfinite(a) && std::isfinite(b) && std::isfinite(c)) {
                    const float s = rk_bloom_source_texel(a, b, c);
                    EXPECT_TRUE(std::isfinite(s));
                    const vec4 bw = rk_bloom_bilinear_weights(vec2(a, b));
                    for (int i = 0; i < 4; ++i) EXPECT_TRUE(std::isfinite(bw[i]) && bw[i] >= 0.0f && bw[i] <= 1.0f);
                }
                ++checked;
            }
        }
    }
    std::printf("sanitising: %ld hostile input combinations, every output finite and in [0, RK_HDR_MAX]\n", checked);
}

// ---------------------------------------------------------------------------------------------
// Karis average, weights, composites.

TEST(BloomKaris, AverageAndFireflies)
{
    const vec3 c(0.3f, 2.0f, 7.0f);
    const vec4 box(0.25f);
    const vec3 same = rk_bloom_karis_average(c, c, c, c, box);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(same[i], c[i], 1e-6f * c[i]);
    // A lone firefly among black texels: the box passes 1/4 of it, Karis about 1/(1 + Y) of that.
    const vec3 fly(1000.0f);
    const vec3 boxed = rk_bloom_weighted_average(fly, vec3(0.0f), vec3(0.0f), vec3(0.0f), box);
    const vec3 karis = rk_bloom_karis_average(fly, vec3(0.0f), vec3(0.0f), vec3(0.0f), box);
    EXPECT_NEAR(boxed.x, 250.0f, 1e-3f);
    EXPECT_NEAR(karis.x, (1000.0 / 1001.0) / (1.0 / 1001.0 + 3.0), 1e-5);  // 0.3329
    EXPECT_LT(karis.x, 0.34f);
    // Bounded by 1 / (weight of the firefly's smallest luminance coefficient) per channel: even +Inf.
    const vec3 inf = rk_bloom_karis_average(vec3(kInf), vec3(0.0f), vec3(0.0f), vec3(0.0f), box);
    EXPECT_TRUE(finite_in_range(inf));
    EXPECT_LT(inf.x, 1.0f);
    EXPECT_EQ(rk_bloom_weighted_average(c, c, c, c, vec4(0.0f)), vec3(0.0f));
    const vec4 bw = rk_bloom_bilinear_weights(vec2(2.5f, -0.25f));
    EXPECT_NEAR(bw.x + bw.y + bw.z + bw.w, 1.0f, 1e-7f);
    EXPECT_EQ(bw, vec4(0.5f * 0.25f, 0.5f * 0.25f, 0.5f * 0.75f, 0.5f * 0.75f));
    // Source texel of a 2:1 reduction: the corner between texels 2x and 2x + 1.
    EXPECT_EQ(rk_bloom_source_texel(3.5f, 64.0f, 128.0f), 6.5f);
    EXPECT_NEAR(rk_bloom_source_texel(0.5f, 3.0f, 5.0f), 5.0 / 6.0 - 0.5, 1e-7);
}

TEST(BloomKaris, ErrorVsFloat64)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    ErrorStats kw, avg, kavg, sum, add, mix, cons, cons_terms;
    auto rnd = [&]() { return vec3(8.0f * u(rng), 8.0f * u(rng), 8.0f * u(rng)); };
    for (int i = 0; i < 100000; ++i) {
        const vec3 c[4] = {rnd(), rnd(), rnd(), rnd()};
        const vec4 w(u(rng), u(rng), u(rng), u(rng));
        const float s = u(rng);
        const std::string in = fmt("i", i);
        double k64[4], den = 0, kden = 0;
        for (int j = 0; j < 4; ++j) {
            k64[j] = 1.0 / (1.0 + lum64(c[j].x, c[j].y, c[j].z));
            den += w[j];
            kden += w[j] * k64[j];
        }
        kw.add(rk_bloom_karis_weight(c[0]), k64[0], in, rktest::ulp_error(rk_bloom_karis_weight(c[0]), k64[0]));
        const vec3 a = rk_bloom_weighted_average(c[0], c[1], c[2], c[3], w);
        const vec3 ka = rk_bloom_karis_average(c[0], c[1], c[2], c[3], w);
        const vec3 sl = rk_bloom_sum_levels(c[0], c[1], c[2], c[3], w);
        const vec3 ad = rk_bloom_composite_add(c[0], c[1], s);
        const vec3 mx = rk_bloom_composite_mix(c[0], c[1], s);
        const vec3 br = c[0] * u(rng);  // a bright part of hdr
        const vec3 cs = rk_bloom_composite_conserve(c[0], br, c[1], s);
        for (int ch = 0; ch < 3; ++ch) {
            double na = 0, nk = 0, ns = 0;
            for (int j = 0; j < 4; ++j) {
                na += w[j] * static_cast<double>(c[j][ch]);
                nk += w[j] * k64[j] * static_cast<double>(c[j][ch]);
                ns += w[j] * static_cast<double>(c[j][ch]);
            }
            const double h = c[0][ch], b = c[1][ch];
            avg.add(a[ch] / (na / den), 1.0, in);
            kavg.add(ka[ch] / (nk / kden), 1.0, in);
            sum.add(sl[ch] / ns, 1.0, in);
            add.add(ad[ch] / (h + s * b), 1.0, in);
            mix.add(mx[ch] / (h * (1.0 - s) + b * s), 1.0, in);
            cons.add(cs[ch] / (h - s * br[ch] + s * b), 1.0, in);
            const double want_cons = h - static_cast<double>(s) * br[ch] + s * b;
            cons_terms.add((cs[ch] - want_cons) / (h + s * b), 0.0, in);
        }
    }
    std::printf("rk_bloom_karis_weight vs float64: %s\n", kw.str().c_str());
    std::printf("relative errors vs float64:\n  weighted_average %s\n  karis_average %s\n  sum_levels %s\n"
                "  composite_add %s\n  composite_mix %s\n  composite_conserve %s\n"
                "  composite_conserve / (hdr + s bloom) %s\n",
                avg.str().c_str(), kavg.str().c_str(), sum.str().c_str(), add.str().c_str(), mix.str().c_str(),
                cons.str().c_str(), cons_terms.str().c_str());
    EXPECT_LE(kw.max_ulp, 3.0) << kw.str();
    EXPECT_LT(avg.max_abs, 5e-7);
    EXPECT_LT(kavg.max_abs, 5e-7);
    EXPECT_LT(sum.max_abs, 3e-7);
    EXPECT_LT(add.max_abs, 2.5e-7);
    EXPECT_LT(mix.max_abs, 3e-7);
    // Relative to the result the conserve error has no bound (hdr - s bright can cancel): a
    // regression check on these samples. The documented bound is relative to hdr + s bloom.
    EXPECT_LT(cons.max_abs, 2.5e-7);
    EXPECT_LT(cons_terms.max_abs, 1.2e-7);
}

TEST(BloomComposite, ModesAndLevelWeights)
{
    const vec3 h(1.0f, 2.0f, 3.0f), b(4.0f, 4.0f, 4.0f);
    EXPECT_EQ(rk_bloom_composite_add(h, b, 0.5f), vec3(3.0f, 4.0f, 5.0f));
    EXPECT_EQ(rk_bloom_composite_mix(h, b, 0.25f), vec3(1.75f, 2.5f, 3.25f));
    EXPECT_EQ(rk_bloom_composite_mix(h, b, 7.0f), b);  // strength clamped to 1
    EXPECT_EQ(rk_bloom_composite_conserve(h, vec3(0.0f), b, 0.5f), rk_bloom_composite_add(h, b, 0.5f));
    EXPECT_EQ(rk_bloom_composite_conserve(h, h, b, 0.25f), rk_bloom_composite_mix(h, b, 0.25f));
    EXPECT_EQ(rk_bloom_composite(h, h, b, 0.25f, RK_BLOOM_COMPOSITE_MIX), rk_bloom_composite_mix(h, b, 0.25f));
    EXPECT_EQ(rk_bloom_composite(h, h, b, 0.25f, 42), rk_bloom_composite_add(h, b, 0.25f));

    BloomParams p;
    EXPECT_EQ(bloom_level_weights(p), vec4(1.0f));
    p.levels = 2;
    EXPECT_EQ(bloom_level_weights(p), vec4(1.0f, 1.0f, 0.0f, 0.0f));
    p.composite = RK_BLOOM_COMPOSITE_MIX;
    p.level_weights = vec4(3.0f, 1.0f, 5.0f, kNaN);
    EXPECT_EQ(bloom_level_weights(p), vec4(0.75f, 0.25f, 0.0f, 0.0f));
    p.level_weights = vec4(-1.0f);
    EXPECT_EQ(bloom_level_weights(p), vec4(0.0f));
    BloomParams bad;
    bad.radius = 31;
    Status st;
    EXPECT_FALSE(validate_bloom_params(bad, &st));
    EXPECT_NE(st.message.find("radius"), std::string::npos) << st.message;
    bad = BloomParams{};
    bad.levels = 5;
    EXPECT_FALSE(validate_bloom_params(bad, &st));
    EXPECT_NE(st.message.find("levels"), std::string::npos) << st.message;
    bad = BloomParams{};
    bad.composite = 7;
    EXPECT_FALSE(validate_bloom_params(bad));
    EXPECT_TRUE(bloom_reference(BloomImage(4, 4), bad, &st).output.pixels.empty());
    EXPECT_EQ(st.code, Error::invalid_argument);
    EXPECT_TRUE(bloom_reference(BloomImage{}, BloomParams{}, &st).output.pixels.empty());
    EXPECT_NE(st.message.find("empty image"), std::string::npos) << st.message;
    EXPECT_TRUE(validate_bloom_params(BloomParams::recommended(), &st));
    EXPECT_TRUE(st.ok());
}

// ---------------------------------------------------------------------------------------------
// The CPU reference of the whole chain.

namespace {
BloomImage test_image(int w, int h, unsigned seed)
{
    BloomImage img(w, h);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (vec3& c : img.pixels) c = vec3(u(rng), u(rng), u(rng));
    return img;
}
int hdr_area(const BloomImage& img) { return img.width * img.height; }
double energy(const BloomImage& img)
{
    double e = 0;
    for (const vec3& c : img.pixels) e += static_cast<double>(rk_bloom_sanitize(c.x)) + rk_bloom_sanitize(c.y) + rk_bloom_sanitize(c.z);
    return e;
}
}  // namespace

TEST(BloomReference, SkipsWhenNothingIsAboveTheThreshold)
{
    BloomImage img = test_image(64, 48, 1);  // all luminances < 1
    img.at(3, 3) = vec3(kNaN, -1.0f, -kInf);  // sanitised away, never bright
    const BloomResult r = bloom_reference(img, BloomParams::thesis());
    EXPECT_FALSE(r.chain_run);
    EXPECT_FALSE(r.composited);
    EXPECT_TRUE(r.levels.empty());
    EXPECT_EQ(r.reduction.count_above, 0u);
    EXPECT_LT(r.reduction.max_luminance, 1.0f);
    EXPECT_EQ(std::memcmp(r.output.pixels.data(), img.pixels.data(), img.pixels.size() * sizeof(vec3)), 0);
    // The soft knee lowers the cutoff to T - K = 0.6: now some pixels pass.
    BloomParams soft = BloomParams::recommended();
    soft.knee = 0.9f;
    const BloomResult rs = bloom_reference(img, soft);
    EXPECT_TRUE(rs.chain_run);
    EXPECT_GT(rs.reduction.count_above, 0u);
    // MIX is not skipped: with zero bloom it still scales hdr by (1 - s).
    BloomParams mix;
    mix.composite = RK_BLOOM_COMPOSITE_MIX;
    mix.strength = 0.25f;
    const BloomResult rm = bloom_reference(img, mix);
    EXPECT_FALSE(rm.chain_run);
    EXPECT_TRUE(rm.composited);
    EXPECT_EQ(rm.output.at(10, 10), img.at(10, 10) * 0.75f);
}

TEST(BloomReference, ThesisChainOnASpot)
{
    // A bright square in the middle of a dark image: bloom spreads around it, nothing is bright far
    // away from it, levels have the chain's sizes, and the output is finite everywhere.
    BloomImage img(256, 192);
    for (int y = 88; y < 104; ++y) {
        for (int x = 120; x < 136; ++x) img.at(x, y) = vec3(20.0f, 10.0f, 5.0f);
    }
    img.at(0, 0) = vec3(kNaN);
    img.at(1, 0) = vec3(-kInf);
    const BloomResult r = bloom_reference(img, BloomParams::thesis());
    ASSERT_TRUE(r.chain_run);
    ASSERT_EQ(r.levels.size(), 4u);
    EXPECT_EQ(r.levels[0].width, 32);
    EXPECT_EQ(r.levels[3].width, 4);
    for (const vec3& c : r.output.pixels) EXPECT_TRUE(finite_in_range(c));
    EXPECT_GT(r.output.at(100, 96).x, 0.01f);    // glow 20 px left of the square
    EXPECT_EQ(r.output.at(128, 96).x > 20.0f, true);
    // The NaN pixel came out sanitised: 0 plus the (weak) glow of the coarsest levels.
    EXPECT_LT(r.output.at(0, 0).x, 0.1f);
    // Downsampling and blurring preserve the spot's energy (per unit area) while the kernel stays
    // inside the level; at the coarse levels the black border (CLAMP_TO_BORDER, the thesis's
    // setting) swallows part of it: 4 levels added with weight 1 give < 4x the spot's energy.
    const double spot = 16.0 * 16.0 * 35.0;
    double total = 0.0;
    for (size_t i = 0; i < r.levels.size(); ++i) {
        const double area = static_cast<double>(hdr_area(img)) / (r.levels[i].width * r.levels[i].height);
        const double frac = energy(r.levels[i]) * area / spot;
        total += frac;
        std::printf("level %zu (%dx%d): %.4f of the spot's energy\n", i, r.levels[i].width, r.levels[i].height, frac);
        if (i == 0) {
            EXPECT_NEAR(frac, 1.0, 1e-5);  // kernel radius 9 fits inside 32x24 around the spot
        }
    }
    const double e_out = energy(r.output) - energy(img);
    std::printf("thesis bloom on a 16x16 spot: added energy %.4g = %.4f x the spot's (sum of levels %.4f)\n", e_out,
                e_out / spot, total);
    EXPECT_NEAR(e_out / spot, total, 1e-3 * total);  // the magnification preserves energy too
    EXPECT_GT(total, 2.0);
    EXPECT_LT(total, 4.0);
}

TEST(BloomReference, ConserveKeepsTheEnergy)
{
    BloomImage img(128, 128);
    for (int y = 60; y < 68; ++y) {
        for (int x = 60; x < 68; ++x) img.at(x, y) = vec3(8.0f, 6.0f, 4.0f);
    }
    for (int y = 0; y < 128; ++y) {
        for (int x = 0; x < 128; ++x) img.at(x, y) += vec3(0.1f);
    }
    BloomParams p;
    p.composite = RK_BLOOM_COMPOSITE_CONSERVE;
    p.strength = 0.5f;
    p.first_div = 2;
    p.levels = 2;  // 64x64 and 32x32: the kernel stays far from the border
    const BloomResult r = bloom_reference(img, p);
    const double rel = (energy(r.output) - energy(img)) / energy(img);
    p.composite = RK_BLOOM_COMPOSITE_ADD;
    const double rel_add = (energy(bloom_reference(img, p).output) - energy(img)) / energy(img);
    std::printf("energy change: conserve %.3g, add %.3g (relative)\n", rel, rel_add);
    EXPECT_LT(std::abs(rel), 1e-4);
    EXPECT_GT(rel_add, 0.1);
    // Below the threshold nothing is removed: far from the spot the pixel only gains glow.
    EXPECT_GE(r.output.at(5, 5).x, 0.1f - 1e-7f);
}

TEST(BloomReference, KarisTamesAnInfinitePixel)
{
    BloomImage img = test_image(64, 64, 5);
    img.at(30, 30) = vec3(kInf);
    BloomParams p = BloomParams::thesis();
    const BloomResult plain = bloom_reference(img, p);
    p.karis = true;
    const BloomResult karis = bloom_reference(img, p);
    float max_plain = 0.0f, max_karis = 0.0f;
    for (size_t i = 0; i < img.pixels.size(); ++i) {
        if (i == 30 * 64 + 30) continue;
        ASSERT_TRUE(finite_in_range(plain.output.pixels[i]));
        ASSERT_TRUE(finite_in_range(karis.output.pixels[i]));
        max_plain = std::max(max_plain, plain.output.pixels[i].y);
        max_karis = std::max(max_karis, karis.output.pixels[i].y);
    }
    std::printf("+Inf pixel: largest neighbour without Karis %.3g, with Karis %.3g\n", static_cast<double>(max_plain),
                static_cast<double>(max_karis));
    EXPECT_GT(max_plain, 1e12f);
    EXPECT_LT(max_karis, 2.0f);
}
