// CPU tests of raykit/exposure.hpp (the C++ build of shaders/raykit/exposure.glsl and the CPU
// references of the luminance reduction) against float64 formulas written out here, test vectors
// of Eq. 3.18-3.19 of Fahlén, "Illumination for Real-Time Rendering of Large Architectural
// Environments" (2005), §3.3.1, and the properties the issue asks for: frame-rate-independent
// adaptation, no NaN/Inf for any input (NaN and +-Inf included).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "raykit/exposure.hpp"
#include "test_util.hpp"

using namespace raykit;
using rktest::ErrorStats;
using rktest::fmt;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// ---- float64 references, written from the published formulas (not from exposure.glsl) ----

/// Per-channel sanitising as documented: NaN/negative/-Inf -> 0, +Inf and > 1e18 -> 1e18.
double ref_sanitize(double x) { return x > 0.0 ? std::min(x, 1e18) : 0.0; }
double ref_luminance(double r, double g, double b)
{
    return 0.2126 * ref_sanitize(r) + 0.7152 * ref_sanitize(g) + 0.0722 * ref_sanitize(b);
}
/// Reinhard 2002 (thesis Eq. 3.18) with the documented clamps: ratio in [-1, 1], range >= 0.01 stops.
double ref_key(double lavg, double lmin, double lmax)
{
    const double a = std::log2(std::min(lmin, lmax)), b = std::log2(std::max(lmin, lmax));
    const double r = (2.0 * std::log2(lavg) - a - b) / std::max(b - a, 0.01);
    return 0.18 * std::pow(4.0, std::min(std::max(r, -1.0), 1.0));
}
double ref_white(double lmin, double lmax)
{
    return 1.5 * std::pow(2.0, std::min(std::abs(std::log2(lmax) - std::log2(lmin)) - 5.0, 59.0));
}
double ref_ev100(double lavg) { return std::log2(lavg * 100.0 / 12.5); }
double ref_exposure(double ev100) { return 1.0 / (1.2 * std::pow(2.0, ev100)); }

double rel(double got, double want) { return std::abs(got - want) / std::max(std::abs(want), 1e-300); }

float log_uniform(std::mt19937& rng, double lo, double hi)
{
    std::uniform_real_distribution<double> u(std::log(lo), std::log(hi));
    return static_cast<float>(std::exp(u(rng)));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Test vectors of Fahlén 2005 Eq. 3.18-3.19 (Reinhard's exponents) and the EV100 definitions.

TEST(Exposure, ReinhardAutoParamsTestVectors)
{
    EXPECT_NEAR(rk_reinhard_auto_key(1.0f, 0.01f, 100.0f), 0.18, 1e-6);
    EXPECT_NEAR(rk_reinhard_auto_key(10.0f, 0.01f, 100.0f), 0.36, 2e-6);
    EXPECT_NEAR(rk_reinhard_auto_key(0.1f, 0.01f, 100.0f), 0.09, 1e-6);
    EXPECT_NEAR(rk_reinhard_auto_white(0.01f, 100.0f), 468.75, 468.75 * 2e-6);
    EXPECT_NEAR(rk_reinhard_auto_white(1.0f, 32.0f), 1.5, 1e-6);  // exactly 5 stops
    EXPECT_FLOAT_EQ(rk_reinhard_auto_white(100.0f, 0.01f), rk_reinhard_auto_white(0.01f, 100.0f));  // either order
    // Geometric midpoint -> 0.18 exactly; log-average at the extremes -> 0.72 / 0.045.
    EXPECT_NEAR(rk_reinhard_auto_key(2.0f, 0.5f, 8.0f), 0.18, 1e-7);
    EXPECT_NEAR(rk_reinhard_auto_key(8.0f, 0.5f, 8.0f), 0.72, 1e-6);
    EXPECT_NEAR(rk_reinhard_auto_key(0.5f, 0.5f, 8.0f), 0.045, 1e-7);
    EXPECT_NEAR(rk_reinhard_auto_key(1e6f, 0.5f, 8.0f), 0.72, 1e-6);  // outside the range: saturates
    // Flat image: no 0/0, the key is ~0.18.
    EXPECT_NEAR(rk_reinhard_auto_key(0.3f, 0.3f, 0.3f), 0.18, 1e-5);
    const ReinhardParams p = reinhard_auto_params(10.0f, 0.01f, 100.0f);
    EXPECT_NEAR(p.key, 0.36, 2e-6);
    EXPECT_NEAR(p.white, 468.75, 1e-3);
}

TEST(Exposure, Ev100AndExposureDefinitions)
{
    EXPECT_FLOAT_EQ(rk_ev100_from_luminance(1.0f), 3.0f);     // log2(1 * 100 / 12.5)
    EXPECT_FLOAT_EQ(rk_ev100_from_luminance(0.125f), 0.0f);
    EXPECT_NEAR(rk_ev100_from_camera(16.0f, 0.01f, 100.0f), std::log2(25600.0), 2e-6);  // f/16 1/100 s ISO 100
    EXPECT_NEAR(rk_ev100_from_camera(1.0f, 1.0f, 100.0f), 0.0, 1e-7);
    EXPECT_NEAR(rk_ev100_from_camera(1.0f, 1.0f, 200.0f), -1.0, 1e-6);  // doubling ISO = one stop less light needed
    EXPECT_NEAR(rk_exposure_from_ev100(0.0f), 1.0 / 1.2, 1e-7);
    EXPECT_NEAR(rk_exposure_from_ev100(3.0f), 1.0 / 9.6, 1e-8);
    // Automatic exposure puts the average at 1 / 9.6 of the saturating luminance, any scene.
    for (float l : {1e-6f, 0.01f, 0.18f, 1.0f, 300.0f, 1e5f}) {
        EXPECT_NEAR(l * rk_exposure_from_luminance(l, 0.0f), 1.0 / 9.6, 1e-6) << l;
        EXPECT_NEAR(l * rk_exposure_from_luminance(l, 1.0f), 2.0 / 9.6, 2e-6) << l;  // +1 stop brighter
    }
}

// ---------------------------------------------------------------------------------------------
// Scalar functions vs float64 over their domains, on these samples (exposure.glsl quotes the
// maxima of denser sampling, docs/dialect.md).

TEST(Exposure, ScalarFunctionsMatchFloat64)
{
    std::mt19937 rng(11);
    ErrorStats term, key, key_narrow, white, ev, cam, expo, expo_l, factor, retain;
    for (int i = 0; i < 200000; ++i) {
        const float l = log_uniform(rng, 1e-38, 1e18);
        const float d = (i % 3 == 0) ? RK_LOG_LUM_DELTA : log_uniform(rng, 1e-30, 1.0);
        const double t = std::log2(static_cast<double>(l) + static_cast<double>(d));
        term.add(rk_log2_luminance(l, d) / std::max(1.0, std::abs(t)), t / std::max(1.0, std::abs(t)), fmt(l, d));

        const float lmin = log_uniform(rng, 1e-6, 1e3), lmax = lmin * log_uniform(rng, 1.01, 1e8);
        const float lavg = log_uniform(rng, lmin, lmax);
        // Below 1 stop of range the key is ill-conditioned (a 1-ulp change of an input moves it by
        // ~1e-7 / range): there the error is charged per stop of range.
        const double range = std::log2(static_cast<double>(lmax) / lmin);
        const double ek = rel(rk_reinhard_auto_key(lavg, lmin, lmax), ref_key(lavg, lmin, lmax));
        if (range >= 1.0) key.add(ek, 0.0, fmt(lavg, lmin, lmax));
        else key_narrow.add(ek * range, 0.0, fmt(lavg, lmin, lmax));
        white.add(rel(rk_reinhard_auto_white(lmin, lmax), ref_white(lmin, lmax)), 0.0, fmt(lmin, lmax));

        const float fn = log_uniform(rng, 1.0, 22.0), ft = log_uniform(rng, 1e-4, 10.0), fs = log_uniform(rng, 50.0, 12800.0);
        cam.add(rk_ev100_from_camera(fn, ft, fs), std::log2(static_cast<double>(fn) * fn / ft * 100.0 / fs), fmt(fn, ft, fs));
        const float la = log_uniform(rng, 1e-12, 1e12);
        ev.add(rk_ev100_from_luminance(la), ref_ev100(la), fmt(la));
        const float e = std::uniform_real_distribution<float>(-64.0f, 64.0f)(rng);
        expo.add(rel(rk_exposure_from_ev100(e), ref_exposure(e)), 0.0, fmt(e));
        expo_l.add(rel(rk_exposure_from_luminance(la, 0.0f), ref_exposure(ref_ev100(la))), 0.0, fmt(la));

        const float dt = log_uniform(rng, 1e-7, 10.0), tau = log_uniform(rng, 1e-3, 10.0);
        const double dd = static_cast<double>(dt) / tau;
        factor.add(rel(rk_adapt_factor(dt, tau), -std::expm1(-dd)), 0.0, fmt(dt, tau));
        // exp(-d) amplifies the rounding of d = dt / tau by d: charged per unit of d.
        if (dd < 80.0) retain.add(rel(rk_adapt_retain(dt, tau), std::exp(-dd)) / std::max(1.0, dd), 0.0, fmt(dt, tau));
        else ASSERT_LT(rk_adapt_retain(dt, tau), 2e-35f);
    }
    std::printf("log2 term (abs / max(1,|t|)): %s\n", term.str().c_str());
    std::printf("auto key (rel, range >= 1 stop): %s\nauto key (rel * range, < 1 stop): %s\nauto white (rel): %s\n",
                key.str().c_str(), key_narrow.str().c_str(), white.str().c_str());
    std::printf("EV100 camera abs: %s\n", cam.str().c_str());
    std::printf("EV100 (abs):      %s\nexposure(EV) rel: %s\nexposure(L) rel:  %s\n", ev.str().c_str(),
                expo.str().c_str(), expo_l.str().c_str());
    std::printf("adapt factor rel: %s\nadapt retain rel: %s\n", factor.str().c_str(), retain.str().c_str());
    EXPECT_LT(term.max_abs, 3e-7);
    EXPECT_LT(key.max_abs, 5e-7);
    EXPECT_LT(key_narrow.max_abs, 4e-7);
    EXPECT_LT(white.max_abs, 1e-6);
    EXPECT_LT(ev.max_abs, 2e-6);
    EXPECT_LT(cam.max_abs, 1.5e-6);
    EXPECT_LT(expo.max_abs, 3e-7);
    EXPECT_LT(expo_l.max_abs, 1.5e-6);
    EXPECT_LT(factor.max_abs, 2.5e-7);
    EXPECT_LT(retain.max_abs, 1.2e-7);
    // Documented edge cases.
    EXPECT_EQ(rk_log2_luminance(0.0f, 0.0f), -126.0f);                     // delta 0: floored, not -Inf
    EXPECT_FLOAT_EQ(rk_log2_luminance(0.0f, RK_LOG_LUM_DELTA), std::log2(1e-4f));
    EXPECT_EQ(rk_log2_luminance(1e-40f, RK_LOG_LUM_DELTA), rk_log2_luminance(0.0f, RK_LOG_LUM_DELTA));  // denormal = 0
    EXPECT_EQ(rk_log2_luminance(kNaN, RK_LOG_LUM_DELTA), rk_log2_luminance(0.0f, RK_LOG_LUM_DELTA));
    EXPECT_EQ(rk_log2_luminance(-5.0f, RK_LOG_LUM_DELTA), rk_log2_luminance(0.0f, RK_LOG_LUM_DELTA));
    EXPECT_EQ(rk_log2_luminance(kInf, RK_LOG_LUM_DELTA), rk_log2_luminance(RK_HDR_MAX, RK_LOG_LUM_DELTA));
    EXPECT_EQ(rk_log2_luminance(vec3(kNaN, 1.0f, -kInf), 0.0f), rk_log2_luminance(0.7152f, 0.0f));
    EXPECT_EQ(rk_log_average_from_sum(0.0f, 0.0f), 1.0f);                  // empty image
    EXPECT_FLOAT_EQ(rk_log_average_from_sum(-3.0f * 7.0f, 7.0f), 0.125f);
    EXPECT_EQ(rk_log_average_from_sum(kNaN, 10.0f), RK_FLT_MIN);
    EXPECT_EQ(rk_adapt_factor(0.0f, 1.0f), 0.0f);
    EXPECT_EQ(rk_adapt_factor(-1.0f, 1.0f), 0.0f);
    EXPECT_EQ(rk_adapt_factor(kNaN, 1.0f), 0.0f);
    EXPECT_EQ(rk_adapt_factor(1.0f / 60.0f, 0.0f), 1.0f);  // tau 0: instant
    EXPECT_EQ(rk_adapt_factor(kInf, 1.0f), 1.0f);
}

// ---------------------------------------------------------------------------------------------
// Adaptation: frame-rate independence, monotone convergence, dt = 0.

TEST(Exposure, AdaptationIsFrameRateIndependent)
{
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> stops(-20.0f, 30.0f);
    double worst_log2_ulps = 0, worst_lin_ulps = 0, worst_lum_rel = 0, worst_many = 0;
    for (int i = 0; i < 200000; ++i) {
        const float x = stops(rng), t = stops(rng);
        const float dt = log_uniform(rng, 1e-4, 2.0), up = log_uniform(rng, 0.05, 5.0), down = log_uniform(rng, 0.05, 5.0);
        // log2 state: two steps of dt == one step of 2 dt.
        const float two = rk_adapt_log2(rk_adapt_log2(x, t, dt, up, down), t, dt, up, down);
        const float one = rk_adapt_log2(x, t, 2.0f * dt, up, down);
        const double scale = std::max({std::abs(x), std::abs(t), 1.0f});
        const double ulps = std::abs(static_cast<double>(two) - one) / (scale * std::numeric_limits<float>::epsilon());
        ASSERT_LE(ulps, 4.0) << fmt(x, t, dt, up, down, two, one);
        worst_log2_ulps = std::max(worst_log2_ulps, ulps);
        // Linear form.
        const float lx = std::exp2(x * 0.5f), lt = std::exp2(t * 0.5f);
        const float ltwo = rk_adapt_luminance_linear(rk_adapt_luminance_linear(lx, lt, dt, up, down), lt, dt, up, down);
        const float lone = rk_adapt_luminance_linear(lx, lt, 2.0f * dt, up, down);
        const double lulps = std::abs(static_cast<double>(ltwo) - lone) /
                             (std::max(lx, lt) * static_cast<double>(std::numeric_limits<float>::epsilon()));
        ASSERT_LE(lulps, 4.0) << fmt(lx, lt, dt, ltwo, lone);
        worst_lin_ulps = std::max(worst_lin_ulps, lulps);
        // Luminance (log-space) form: the identity up to the log2/exp2 round trip.
        const float mtwo = rk_adapt_luminance(rk_adapt_luminance(lx, lt, dt, up, down), lt, dt, up, down);
        const float mone = rk_adapt_luminance(lx, lt, 2.0f * dt, up, down);
        const double lum_bound = 4.0 * std::numeric_limits<float>::epsilon() *
                                 (std::log(2.0) * std::max({std::abs(std::log2(lx)), std::abs(std::log2(lt)), 1.0f}) + 1.0);
        worst_lum_rel = std::max(worst_lum_rel, rel(mtwo, mone) / lum_bound);
        ASSERT_LE(rel(mtwo, mone), lum_bound) << fmt(lx, lt, dt, mtwo, mone);
        // Ten frames of dt / 10 == one frame of dt (within 10 x the two-step tolerance).
        if (i % 10 == 0) {
            float s = x;
            for (int k = 0; k < 10; ++k) s = rk_adapt_log2(s, t, dt / 10.0f, up, down);
            const double mu = std::abs(static_cast<double>(s) - rk_adapt_log2(x, t, dt, up, down)) /
                              (scale * std::numeric_limits<float>::epsilon());
            worst_many = std::max(worst_many, mu);
            ASSERT_LE(mu, 24.0) << fmt(x, t, dt);
        }
    }
    std::printf("two steps of dt vs one of 2dt: log2 form %.2f ulp of max(|x|,|t|,1), linear form %.2f ulp, "
                "luminance form %.2f of its bound; 10 steps of dt/10 vs 1 of dt: %.2f ulp\n",
                worst_log2_ulps, worst_lin_ulps, worst_lum_rel, worst_many);
}

TEST(Exposure, AdaptationMatchesFloat64AndUsesTheRightTau)
{
    ErrorStats e;
    for (float x : {-10.0f, -1.0f, 0.0f, 3.0f, 12.0f}) {
        for (float t : {-8.0f, 0.5f, 3.0f, 20.0f}) {
            for (float dt : {0.001f, 1.0f / 60.0f, 0.1f, 1.0f, 10.0f}) {
                const double tau = t > x ? 0.4 : 2.5;
                const double want = x + (t - static_cast<double>(x)) * -std::expm1(-dt / tau);
                e.add(rk_adapt_log2(x, t, dt, 0.4f, 2.5f), want, fmt(x, t, dt));
            }
        }
    }
    std::printf("rk_adapt_log2 vs float64: %s\n", e.str().c_str());
    EXPECT_LT(e.max_abs, 4e-6);
    // After one time constant the gap shrinks to 1/e, with tau_up brightening and tau_down darkening.
    EXPECT_NEAR(rk_adapt_log2(0.0f, 1.0f, 0.4f, 0.4f, 2.5f), 1.0 - std::exp(-1.0), 1e-6);
    EXPECT_NEAR(rk_adapt_log2(1.0f, 0.0f, 2.5f, 0.4f, 2.5f), std::exp(-1.0), 1e-6);
    EXPECT_NEAR(rk_adapt_luminance(1.0f, 2.0f, 0.4f, 0.4f, 2.5f), std::exp2(1.0 - std::exp(-1.0)), 2e-6);
    EXPECT_NEAR(rk_adapt_luminance_linear(1.0f, 2.0f, 0.4f, 0.4f, 2.5f), 2.0 - std::exp(-1.0), 1e-6);
}

TEST(Exposure, AdaptationConvergesMonotonicallyAndDtZeroChangesNothing)
{
    for (float target : {-12.0f, 0.0f, 7.5f, 40.0f}) {
        for (float start : {-20.0f, -1.0f, 5.0f, 50.0f}) {
            float x = start, gap = std::abs(target - start);
            for (int frame = 0; frame < 4000; ++frame) {
                const float nx = rk_adapt_log2(x, target, 1.0f / 60.0f, 0.4f, 2.5f);
                const float ngap = std::abs(target - nx);
                ASSERT_LE(ngap, gap) << fmt(start, target, frame);  // never moves away
                ASSERT_TRUE(start <= target ? (nx >= x && nx <= target) : (nx <= x && nx >= target))  // never overshoots
                    << fmt(start, target, frame, x, nx);
                x = nx;
                gap = ngap;
            }
            // 66 s >> 2.5 s: settled, up to the documented float resolution 0.5 ulp / (1 - exp(-dt / tau)).
            const double ulp = std::nextafter(std::abs(target), kInf) - std::abs(target);
            const double tau = target > start ? 0.4 : 2.5;
            const double settle = 0.5 * ulp / -std::expm1(-(1.0 / 60.0) / tau) + ulp +
                                  1.01 * std::abs(start - target) * std::exp(-4000.0 / 60.0 / tau);
            EXPECT_NEAR(x, target, settle) << fmt(start, target);
        }
    }
    // Linear luminance, huge ratios: no overshoot from rounding of (t - c).
    float l = 1.0f;
    for (int frame = 0; frame < 200; ++frame) {
        const float nl = rk_adapt_luminance_linear(l, 1e-8f, 0.1f, 0.4f, 0.05f);
        ASSERT_LE(nl, l);
        ASSERT_GE(nl, 1e-8f);
        l = nl;
    }
    // dt = 0 (and negative / NaN dt): the state is returned bit for bit.
    std::mt19937 rng(3);
    for (int i = 0; i < 10000; ++i) {
        const float x = std::uniform_real_distribution<float>(-100.0f, 50.0f)(rng);
        const float t = std::uniform_real_distribution<float>(-100.0f, 50.0f)(rng);
        const float lx = log_uniform(rng, 1e-30, 1e17), lt = log_uniform(rng, 1e-30, 1e17);
        for (float dt : {0.0f, -0.0f, -1.0f, kNaN}) {
            ASSERT_EQ(rk_adapt_log2(x, t, dt, 0.4f, 2.5f), x);
            ASSERT_EQ(rk_adapt_luminance(lx, lt, dt, 0.4f, 2.5f), lx);
            ASSERT_EQ(rk_adapt_luminance_linear(lx, lt, dt, 0.4f, 2.5f), lx);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Log-average luminance of images (the CPU reference) vs an independent float64 evaluation.

namespace {

/// RGB test image with every kind of pixel the GPU test uses: zeros, 1e-30, denormals, ordinary
/// values over 12 decades, 1e6-bright pixels, and NaN / +-Inf / negative channels.
std::vector<float> make_image(int w, int h, int channels, unsigned seed)
{
    std::mt19937 rng(seed);
    std::vector<float> px(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(channels));
    std::uniform_int_distribution<int> kind(0, 999);
    for (size_t i = 0; i < px.size(); i += static_cast<size_t>(channels)) {
        const int k = kind(rng);
        for (int c = 0; c < channels; ++c) {
            float v;
            if (k < 40) v = 0.0f;
            else if (k < 55) v = 1e-30f;
            else if (k < 70) v = 1e-40f;
            else if (k < 85) v = 1e6f;
            else if (k < 88) v = kNaN;
            else if (k < 91) v = kInf;
            else if (k < 94) v = -kInf;
            else if (k < 98) v = -0.5f;
            else v = log_uniform(rng, 1e-6, 1e6);
            px[i + static_cast<size_t>(c)] = v;
        }
    }
    return px;
}

double ref_log_average(const std::vector<float>& px, int channels, double delta, std::vector<double>* terms = nullptr)
{
    double s = 0.0;
    const size_t n = px.size() / static_cast<size_t>(channels);
    for (size_t i = 0; i < n; ++i) {
        const float* p = &px[i * static_cast<size_t>(channels)];
        const double l = channels == 1 ? ref_sanitize(p[0]) : ref_luminance(p[0], p[1], p[2]);
        const double t = std::log(l + delta);  // Eq. 3.14 as printed: natural log, exp at the end
        s += t;
        if (terms) terms->push_back(t / std::log(2.0));
    }
    return std::exp(s / static_cast<double>(n));
}

double ref_percentile(std::vector<double> v, double p)
{
    std::sort(v.begin(), v.end());
    const double h = (static_cast<double>(v.size()) - 1.0) * p;
    const size_t lo = static_cast<size_t>(h);
    const size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

}  // namespace

TEST(Exposure, LogAverageMatchesFloat64)
{
    double worst = 0, worst_pct = 0;
    for (int channels : {1, 3, 4}) {
        for (double delta : {1e-4, 1e-6, 0.01}) {
            const std::vector<float> px = make_image(257, 131, channels, static_cast<unsigned>(channels * 7 + 1));
            LogAverageOptions o;
            o.delta = static_cast<float>(delta);
            const LuminanceStats s = log_average_luminance(px, 257, 131, channels, o);
            std::vector<double> terms;
            const double want = ref_log_average(px, channels, static_cast<float>(delta), &terms);
            worst = std::max(worst, rel(s.log_average, want));
            EXPECT_LT(rel(s.log_average, want), 1e-6) << channels << " " << delta;
            EXPECT_EQ(s.count, 257u * 131u);
            EXPECT_GT(s.sanitized, 0u);
            const double pmin = std::exp2(ref_percentile(terms, 0.01)), pmax = std::exp2(ref_percentile(terms, 0.99));
            worst_pct = std::max({worst_pct, rel(s.robust_min, pmin), rel(s.robust_max, pmax)});
            EXPECT_LT(rel(s.robust_min, pmin), 1e-6);
            EXPECT_LT(rel(s.robust_max, pmax), 1e-6);
            EXPECT_LE(s.min, s.robust_min);
            EXPECT_GE(s.max, s.robust_max);
            EXPECT_NEAR(s.min, static_cast<float>(delta), 2e-6 * delta);  // black pixels: delta, not 0
        }
    }
    std::printf("log_average_luminance vs float64 exp(mean ln(delta + L)): max rel %.2e; percentiles %.2e\n", worst,
                worst_pct);
}

TEST(Exposure, LogAverageEdgeCases)
{
    // All black: finite, = delta (the thesis's -Inf pitfall).
    const std::vector<float> black(64 * 48 * 3, 0.0f);
    const LuminanceStats b = log_average_luminance(black, 64, 48, 3);
    EXPECT_TRUE(std::isfinite(b.log_average));
    EXPECT_NEAR(b.log_average, 1e-4, 1e-10);
    // All NaN / -Inf: treated as black. All +Inf: RK_HDR_MAX.
    EXPECT_NEAR(log_average_luminance(std::vector<float>(30, kNaN), 10, 3, 1).log_average, 1e-4, 1e-10);
    EXPECT_NEAR(log_average_luminance(std::vector<float>(30, -kInf), 10, 3, 1).log_average, 1e-4, 1e-10);
    EXPECT_NEAR(log_average_luminance(std::vector<float>(30, kInf), 10, 3, 1).log_average, 9.96e17, 1e15);  // 2^59.79
    // Uniform image: delta + L.
    EXPECT_NEAR(log_average_luminance(std::vector<float>(12, 0.5f), 4, 1, 3).log_average, 0.5001, 1e-7);
    // Two pixels: the geometric mean.
    EXPECT_NEAR(log_average_luminance(std::vector<float>{0.01f, 100.0f}, 2, 1, 1).log_average,
                std::sqrt((0.01 + 1e-4) * (100 + 1e-4)), 1e-6);
    // 1x1, empty, bad arguments.
    EXPECT_NEAR(log_average_luminance(std::vector<float>{2.0f}, 1, 1, 1).log_average, 2.0001, 1e-6);
    EXPECT_EQ(log_average_luminance(std::vector<float>{}, 0, 0, 1).log_average, 1.0f);
    {
        Status st;
        const LuminanceStats bad_channels = log_average_luminance(std::vector<float>(4, 1.0f), 2, 1, 2, {}, &st);
        EXPECT_EQ(st.code, Error::invalid_argument);
        EXPECT_NE(st.message.find("channels"), std::string::npos) << st.message;
        EXPECT_EQ(bad_channels.count, 0u);
        EXPECT_EQ(bad_channels.log_average, 1.0f);
        EXPECT_EQ(log_average_luminance(std::vector<float>(5, 1.0f), 2, 1, 3, {}, &st).count, 0u);
        EXPECT_NE(st.message.find("pixels.size()"), std::string::npos) << st.message;
        EXPECT_EQ(log_average_luminance(nullptr, 2, 2, 1, {}, &st).count, 0u);
        EXPECT_NE(st.message.find("null pixels"), std::string::npos) << st.message;
        const std::vector<float> px(16, 1.0f);
        EXPECT_TRUE(luminance_histogram(px.data(), 2, 1, 1, 0u, -4.0f, 4.0f, RK_LOG_LUM_DELTA, &st).empty());
        EXPECT_NE(st.message.find("bins"), std::string::npos) << st.message;
        EXPECT_TRUE(luminance_histogram(px.data(), 2, 1, 5, 8u, -4.0f, 4.0f, RK_LOG_LUM_DELTA, &st).empty());
        EXPECT_EQ(log_average_luminance(px.data(), 2, 1, 1, {}, &st).count, 2u);
        EXPECT_TRUE(st.ok());
    }
    // The CPU-only parameter estimate uses the robust extremes.
    std::vector<float> ramp;
    for (int i = 0; i < 1000; ++i) ramp.push_back(static_cast<float>(std::pow(10.0, -2.0 + 4.0 * i / 999.0)));
    ramp[0] = 1e-20f;  // one outlier each side: ignored by the 1% / 99% percentiles
    ramp[999] = 1e20f;
    const LuminanceStats rs = log_average_luminance(ramp, 1000, 1, 1);
    const ReinhardParams rp = reinhard_auto_params(rs);
    EXPECT_NEAR(rp.key, 0.18, 0.01);  // log-uniform ramp: its log-average is the geometric mid-range
    EXPECT_NEAR(rp.white, ref_white(rs.robust_min, rs.robust_max), 1e-3);
    EXPECT_GT(rs.robust_min, 0.009f);
    EXPECT_LT(rs.robust_max, 120.0f);
}

// ---------------------------------------------------------------------------------------------
// Histogram option.

TEST(Exposure, HistogramBinsAndStats)
{
    // Bin index vs float64 floor over a range with an exact scale (4 bins per stop).
    for (float x = -30.0f; x < 45.0f; x += 0.0371f) {
        const double u = std::floor((static_cast<double>(x) + 24.0) * 4.0);
        const uint want = static_cast<uint>(std::min(std::max(u, 0.0), 255.0));
        ASSERT_EQ(rk_histogram_bin(x, -24.0f, 40.0f, 256u), want) << x;
    }
    EXPECT_EQ(rk_histogram_bin(kNaN, -24.0f, 40.0f, 256u), 0u);
    EXPECT_EQ(rk_histogram_bin(kInf, -24.0f, 40.0f, 256u), 255u);
    EXPECT_EQ(rk_histogram_bin(-kInf, -24.0f, 40.0f, 256u), 0u);
    EXPECT_EQ(rk_histogram_bin(1.0f, 5.0f, 5.0f, 0u), 0u);  // degenerate range and zero bins
    EXPECT_FLOAT_EQ(rk_histogram_bin_edge(256.0f, -24.0f, 40.0f, 256u), 40.0f);
    EXPECT_FLOAT_EQ(rk_histogram_bin_edge(96.0f, -24.0f, 40.0f, 256u), 0.0f);

    // Stats vs the exact trimmed geometric mean and percentiles of the terms.
    const int w = 400, h = 300;
    const std::vector<float> px = make_image(w, h, 3, 99);
    std::vector<double> terms;
    ref_log_average(px, 3, static_cast<float>(1e-4), &terms);
    const std::vector<std::uint32_t> hist = luminance_histogram(px.data(), w, h, 3, 256u, -24.0f, 40.0f);
    const HistogramStats hs = histogram_stats(hist, -24.0f, 40.0f, 0.05f, 0.95f, 0.01f, 0.99f);
    EXPECT_EQ(hs.total, static_cast<double>(w * h));
    std::vector<double> sorted = terms;
    std::sort(sorted.begin(), sorted.end());
    const size_t n = sorted.size(), a = n / 20, b = n - n / 20;
    double m = 0;
    for (size_t i = a; i < b; ++i) m += sorted[i];
    m /= static_cast<double>(b - a);
    const double bin_width = 64.0 / 256.0;
    std::printf("histogram: trimmed mean log2 %.4f (exact %.4f), p1 %.3f (%.3f), p99 %.3f (%.3f), bin %.3f stops\n",
                std::log2(hs.average), m, std::log2(hs.low), ref_percentile(terms, 0.01), std::log2(hs.high),
                ref_percentile(terms, 0.99), bin_width);
    EXPECT_NEAR(std::log2(hs.average), m, 0.5 * bin_width);
    EXPECT_NEAR(std::log2(hs.low), ref_percentile(terms, 0.01), bin_width);
    EXPECT_NEAR(std::log2(hs.high), ref_percentile(terms, 0.99), bin_width);
    EXPECT_NEAR(hs.window_pixels, 0.9 * w * h, 1.0);
    // Degenerate: empty histogram, window of width 0.
    const HistogramStats e = histogram_stats(std::vector<std::uint32_t>(256, 0u), -24.0f, 40.0f, 0.05f, 0.95f, 0.01f, 0.99f);
    EXPECT_EQ(e.average, 1.0f);
    EXPECT_EQ(e.window_pixels, 0.0f);
    const HistogramStats z = histogram_stats(hist, -24.0f, 40.0f, 0.5f, 0.5f, 0.5f, 0.5f);
    EXPECT_NEAR(std::log2(z.average), ref_percentile(terms, 0.5), bin_width);  // the median
    // A single bin holding everything: the window average is inside that bin.
    std::vector<std::uint32_t> one(256, 0u);
    one[100] = 1000u;
    const HistogramStats o1 = histogram_stats(one, -24.0f, 40.0f, 0.0f, 1.0f, 0.0f, 1.0f);
    EXPECT_NEAR(std::log2(o1.average), -24.0 + 100.5 / 4.0, 1e-5);
    EXPECT_NEAR(std::log2(o1.low), -24.0 + 100.0 / 4.0, 1e-5);
    EXPECT_NEAR(std::log2(o1.high), -24.0 + 101.0 / 4.0, 1e-5);
}

// ---------------------------------------------------------------------------------------------
// Reduction-chain planner and the mean-of-blocks chain.

TEST(Exposure, ReductionChainSizesAndWeights)
{
    const std::vector<ReductionPass> c = reduction_chain(1024, 768, 4);
    const int sizes[][2] = {{256, 192}, {64, 48}, {16, 12}, {4, 3}, {1, 1}};
    ASSERT_EQ(c.size(), 5u);
    for (size_t k = 0; k < c.size(); ++k) {
        EXPECT_EQ(c[k].out_width, sizes[k][0]);
        EXPECT_EQ(c[k].out_height, sizes[k][1]);
    }
    EXPECT_FALSE(c[3].partial_x || c[3].partial_y);
    EXPECT_EQ(c[4].in_width, 4);
    EXPECT_EQ(c[4].in_height, 3);  // the partial 4x3 -> 1x1 pass
    EXPECT_EQ(c[4].last_cover_x, 1024);
    EXPECT_EQ(c[4].last_cover_y, 768);
    EXPECT_FALSE(c[4].partial_x);  // 4 texels of 256 = 1024 columns: complete
    EXPECT_TRUE(c[4].partial_y);   // 3 texels of 256 rows of a 1024-row span

    EXPECT_EQ(reduction_chain(1, 1, 4).size(), 1u);
    EXPECT_EQ(reduction_chain(3840, 2160, 64).size(), 2u);  // 60x34, then 1x1
    EXPECT_EQ(reduction_chain(3840, 2160, 64)[0].out_height, 34);
    EXPECT_EQ(reduction_chain(3840, 2160, 64)[0].last_cover_y, 2160 - 33 * 64);
    Status st;
    EXPECT_TRUE(reduction_chain(0, 5, 4, &st).empty());
    EXPECT_NE(st.message.find("width and height"), std::string::npos) << st.message;
    EXPECT_TRUE(reduction_chain(5, 5, 1, &st).empty());
    EXPECT_NE(st.message.find("block"), std::string::npos) << st.message;
    EXPECT_EQ(reduce_chain_mean(std::vector<float>(6, 1.0f), 5, 1, 4, true, &st), 0.0f);
    EXPECT_NE(st.message.find("values.size()"), std::string::npos) << st.message;
    EXPECT_EQ(reduce_chain_mean(std::vector<float>(5, 1.0f), 5, 1, 4, true, &st), 1.0f);
    EXPECT_TRUE(st.ok());

    EXPECT_EQ(rk_reduce_cover(0u, 4u, 10u), 4u);
    EXPECT_EQ(rk_reduce_cover(2u, 4u, 10u), 2u);
    EXPECT_EQ(rk_reduce_cover(3u, 4u, 10u), 0u);
    for (auto wh : {std::pair<int, int>{1023, 767}, {1024, 768}, {997, 991}, {1, 1}, {5, 3}, {1, 1000}}) {
        for (const ReductionPass& p : reduction_chain(wh.first, wh.second, 4)) {
            double sum = 0;
            for (int j = 0; j < p.out_height; ++j) {
                for (int i = 0; i < p.out_width; ++i) sum += reduction_texel_weight(p, i, j, wh.first, wh.second);
            }
            ASSERT_EQ(sum, static_cast<double>(wh.first) * wh.second) << wh.first << "x" << wh.second;
        }
    }
}

TEST(Exposure, ReduceChainMeanMatchesDirectMean)
{
    std::mt19937 rng(17);
    double worst = 0, naive_worst = 0;
    for (auto wh : {std::pair<int, int>{1024, 768}, {1023, 767}, {997, 991}, {1, 1}, {5, 3}, {1, 1000}, {641, 1}}) {
        const int w = wh.first, h = wh.second;
        std::vector<float> v(static_cast<size_t>(w) * static_cast<size_t>(h));
        double mean = 0;
        for (size_t i = 0; i < v.size(); ++i) {
            const int x = static_cast<int>(i % static_cast<size_t>(w));
            // log2 terms with a gradient so that edge over-weighting shows.
            v[i] = rk_log2_luminance(log_uniform(rng, 1e-5, 1e5) * (1.0f + 100.0f * static_cast<float>(x) / static_cast<float>(w)),
                                     RK_LOG_LUM_DELTA);
            mean += v[i];
        }
        mean /= static_cast<double>(v.size());
        const double weighted = reduce_chain_mean(v, w, h, 4, true);
        const double naive = reduce_chain_mean(v, w, h, 4, false);
        worst = std::max(worst, std::abs(weighted - mean));
        EXPECT_NEAR(weighted, mean, 1e-5) << w << "x" << h;
        if (w % 4 != 0 || h % 4 != 0) naive_worst = std::max(naive_worst, std::abs(naive - mean));
        if (w == 1024 && h == 768) {
            // 4x3 -> 1x1 with CLAMP_TO_EDGE repeats the last row: the naive chain is biased even here.
            EXPECT_GT(std::abs(naive - mean), 1e-3);
        }
    }
    std::printf("weighted 4x4 chain vs direct mean: max abs %.2e (log2 units); naive chain on non-multiples: %.3f\n",
                worst, naive_worst);
    EXPECT_GT(naive_worst, 1e-2);
}

// ---------------------------------------------------------------------------------------------
// Stress: every shared function, inputs from the whole float range plus NaN and +-Inf: outputs
// finite and inside their documented ranges.

TEST(Exposure, StressNoNanNoInfForAnyInput)
{
    std::mt19937 rng(77);
    const float specials[] = {0.0f, -0.0f, 1e-45f, -1e-45f, 1e-40f, 1.17549435e-38f, 1.0f, -1.0f, 1e-30f, 1e6f, 1e18f,
                              1e30f, -1e30f, 3.4028235e38f, -3.4028235e38f, kNaN, -kNaN, kInf, -kInf, RK_LOG_LUM_DELTA};
    auto draw = [&](int i) {
        const int sel = static_cast<int>(rng() % 4u);
        if (sel == 0) return specials[static_cast<size_t>(rng()) % (sizeof specials / sizeof specials[0])];
        if (sel == 1) return std::uniform_real_distribution<float>(-10.0f, 10.0f)(rng);
        const std::uint32_t bits = static_cast<std::uint32_t>(rng()) ^ static_cast<std::uint32_t>(i);
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return f;  // includes NaN and Inf bit patterns
    };
    long n = 0;
    for (int i = 0; i < 300000; ++i) {
        const float a = draw(i), b = draw(i + 1), c = draw(i + 2), d = draw(i + 3), e = draw(i + 4);
        const std::string in = fmt(a, b, c, d, e);
        auto finite = [&](float v, float lo, float hi) {
            ASSERT_TRUE(std::isfinite(v) && v >= lo && v <= hi) << v << " for " << in;
            ++n;
        };
        finite(rk_exposure_clamp(a, -1.0f, 1.0f), -1.0f, 1.0f);
        finite(rk_log2_luminance(a, b), -126.0f, 60.8f);
        finite(rk_log2_luminance(vec3(a, b, c), d), -126.0f, 60.8f);
        finite(rk_log_average_from_sum(a, b), RK_FLT_MIN, 1e18f);
        finite(rk_reinhard_auto_key(a, b, c), 0.045f, 0.72f);
        finite(rk_reinhard_auto_white(a, b), 0.046875f, 8.7e17f);
        finite(rk_ev100_from_luminance(a), -124.0f, 63.0f);
        finite(rk_ev100_from_camera(a, b, c), -200.0f, 200.0f);
        finite(rk_exposure_from_ev100(a), 4e-20f, 1.6e19f);
        finite(rk_exposure_from_luminance(a, b), 4e-20f, 1.6e19f);
        finite(rk_adapt_factor(a, b), 0.0f, 1.0f);
        finite(rk_adapt_log2(a, b, c, d, e), RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX);
        finite(rk_adapt_luminance(a, b, c, d, e), 0.0f, RK_HDR_MAX);
        finite(rk_adapt_luminance_linear(a, b, c, d, e), 0.0f, RK_HDR_MAX);
        finite(static_cast<float>(rk_histogram_bin(a, b, c, 256u)), 0.0f, 255.0f);
        const uint any_bins = static_cast<uint>(rng());
        finite(static_cast<float>(rk_histogram_bin(a, b, c, any_bins)), 0.0f, 16777215.0f);
        finite(rk_histogram_bin_edge(a, b, c, any_bins), -256.0f, 512.0f);
        finite(rk_histogram_bin_edge(a, b, c, 256u), -256.0f, 512.0f);
        finite(rk_histogram_rank_in_bin(a, b, c, -24.0f, -23.75f), -24.0f, -23.75f);
        rk_histogram_scan s = rk_histogram_scan_init();
        rk_histogram_scan_bin(s, a, -1.0f, 0.0f, b, c, d, e);
        rk_histogram_scan_bin(s, b, 0.0f, 1.0f, b, c, d, e);
        rk_histogram_scan t = rk_histogram_scan_init();
        rk_histogram_scan_bin(t, a, c, d, 0.0f, 1e30f, 0.0f, 1e30f);  // any edges, NaN included
        rk_histogram_scan_bin(t, b, d, e, 0.0f, 1e30f, 0.0f, 1e30f);
        finite(t.weighted_log2, -3e33f, 3e33f);
        finite(rk_histogram_scan_average(t), 0.0f, RK_HDR_MAX);
        finite(rk_histogram_rank_in_bin(a, b, c, d, e), -1024.0f, 1024.0f);
        finite(rk_adapt_exponent(a, b), 0.0f, 100.0f);
        finite(rk_adapt_retain(a, b), 0.0f, 1.0f);
        finite(s.below, 0.0f, 2e30f);
        finite(s.weight, 0.0f, 2e30f);
        finite(s.weighted_log2, -2e30f, 2e30f);
        finite(s.low_log2, -1.0f, 1.0f);
        finite(s.high_log2, -1.0f, 1.0f);
        finite(rk_histogram_scan_average(s), 0.0f, 2.0f);
    }
    std::printf("stress: %ld outputs checked, all finite and in range\n", n);
}
