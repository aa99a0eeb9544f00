// CPU tests of raykit/fresnel.hpp (the C++ build of shaders/raykit/fresnel.glsl) against the
// float64 references of tests/reference/fresnel_ref.hpp and the published values of
// shared/reference/notes/seed002.md §3.2 / §8.1.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "raykit/fresnel.hpp"
#include "reference/fresnel_ref.hpp"
#include "test_util.hpp"

using namespace raykit;
using rktest::ErrorStats;
using rktest::fmt;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

float cosd(double deg) { return static_cast<float>(std::cos(deg * kDeg)); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Published numbers (seed002.md §3.2 table for n = 1.52, §8.1 unit-test values).

TEST(Fresnel, PublishedScalars)
{
    EXPECT_NEAR(rk_f0_from_ior(1.0f, 1.52f), 0.0425800, 5e-8);
    EXPECT_NEAR(rk_f0_from_eta(1.52f), 0.0425800, 5e-8);
    EXPECT_NEAR(rk_fresnel_slab(rk_f0_from_eta(1.52f)), 0.0816820, 5e-8);
    EXPECT_NEAR(rk_fresnel_glazing(rk_f0_from_eta(1.52f), 2.0f), 0.1510277, 5e-8);
    EXPECT_NEAR(rk_fresnel_dielectric(1.0f, 1.52f), 0.0425800, 5e-8);
    EXPECT_NEAR(rk_critical_angle(1.0f / 1.52f) / kDeg, 41.1395, 5e-5);
    EXPECT_NEAR(rk_brewster_angle(1.52f) / kDeg, 56.6593, 5e-5);
    EXPECT_NEAR(rk_eta_from_f0(0.04f), 1.5f, 1e-6);
}

TEST(Fresnel, PublishedTableN152)
{
    struct Row {
        double deg, rs, rp, r, schlick, slab, slab_sp;
    };
    const Row rows[] = {
        {0, 0.04258, 0.04258, 0.04258, 0.04258, 0.08168, 0.08168},
        {30, 0.06121, 0.02708, 0.04414, 0.04262, 0.08455, 0.08404},
        {45, 0.09673, 0.00936, 0.05305, 0.04464, 0.10075, 0.09747},
        {60, 0.18344, 0.00153, 0.09248, 0.07250, 0.16931, 0.15653},
        {75, 0.40785, 0.10558, 0.25672, 0.25673, 0.40855, 0.38519},
        {85, 0.73767, 0.49217, 0.61492, 0.64944, 0.76155, 0.75435},
        {89, 0.94084, 0.86854, 0.90469, 0.91932, 0.94996, 0.94958},
    };
    const float f0 = rk_f0_from_eta(1.52f);
    for (const Row& row : rows) {
        const float c = cosd(row.deg);
        const vec2 sp = rk_fresnel_dielectric_sp(c, 1.52f);
        SCOPED_TRACE(fmt("theta =", row.deg));
        EXPECT_NEAR(sp.x, row.rs, 1e-5);
        EXPECT_NEAR(sp.y, row.rp, 1e-5);
        EXPECT_NEAR(rk_fresnel_dielectric(c, 1.52f), row.r, 1e-5);
        EXPECT_NEAR(rk_fresnel_schlick(c, f0), row.schlick, 1e-5);
        EXPECT_NEAR(rk_fresnel_slab(rk_fresnel_dielectric(c, 1.52f)), row.slab, 1e-5);
        EXPECT_NEAR(rk_fresnel_slab_sp(sp), row.slab_sp, 1e-5);
        if (row.deg > 0) {  // the thesis's sin/tan form, singular at 0°, agrees away from it
            auto ang = ref::fresnel_sp_angles(row.deg * kDeg, 1.52);
            EXPECT_NEAR(sp.x, ang.first, 1e-6);
            EXPECT_NEAR(sp.y, ang.second, 1e-6);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Exact dielectric vs float64 over a dense grid of angles and indices, both sides of the interface.

TEST(Fresnel, DielectricMatchesFloat64)
{
    ErrorStats stats, plain;
    const float etas[] = {1.0f / 4.0f, 1.0f / 2.4f, 1.0f / 1.52f, 1.0f / 1.33f, 0.999f, 0.9999999f, 1.0f,
                          1.0000001f, 1.001f, 1.1f, 1.33f, 1.5f, 1.52f, 2.0f, 2.4f, 4.0f, 100.0f};
    for (float eta : etas) {
        for (int i = 0; i <= 20000; ++i) {
            const float c = static_cast<float>(i) / 20000.0f;
            const vec2 sp = rk_fresnel_dielectric_sp(c, eta);
            const std::string in = fmt("cos", c, "eta", eta);
            // Near the critical angle R is infinitely steep in cos, so the float rounding of cos
            // itself (and of cos^2 inside) moves the exact value by more than 1e-6. Compare with the
            // range the float64 function takes over cos +- 1 ulp: the error the input can explain
            // is not charged to the implementation.
            auto rs = [&](double x) { return eta == 1.0f ? 0.0 : ref::fresnel_sp(x, ref::cd(eta, 0.0)).first; };
            auto rp = [&](double x) { return eta == 1.0f ? 0.0 : ref::fresnel_sp(x, ref::cd(eta, 0.0)).second; };
            const double lo = std::nextafter(c, 0.0f), hi = std::min(1.0f, std::nextafter(c, 2.0f));
            stats.add(sp.x, rktest::nearest_in(sp.x, {rs(lo), rs(c), rs(hi)}), in, rktest::ulp_error(sp.x, rs(c)));
            stats.add(sp.y, rktest::nearest_in(sp.y, {rp(lo), rp(c), rp(hi)}), in, rktest::ulp_error(sp.y, rp(c)));
            plain.add(sp.x, rs(c), in);
        }
    }
    std::printf("rk_fresnel_dielectric_sp vs float64 (cos +- 1 ulp): %s\n", stats.str().c_str());
    std::printf("rk_fresnel_dielectric_sp vs float64 at the rounded cos: %s\n", plain.str().c_str());
    EXPECT_LT(stats.max_abs, 2.0e-6) << stats.str();
    EXPECT_LT(stats.mean_abs(), 5.0e-8) << stats.str();
}

TEST(Fresnel, SchlickAndFastErrorAgainstExact)
{
    // The documented error numbers in fresnel.glsl: Schlick's max error for glass is 0.0345
    // (near 85°); the fast form must beat it clearly.
    struct Case {
        float eta;
        double schlick_max, fast_bound;
    };
    const Case cases[] = {{1.1f, 0.21, 1.4e-2}, {1.33f, 0.060, 3.8e-3}, {1.52f, 0.0345, 1.75e-3},
                          {2.0f, 0.0444, 3.6e-4}, {2.4f, 0.074, 1.3e-4}};
    for (const Case& cs : cases) {
        ErrorStats schlick, fast;
        const float f0 = rk_f0_from_eta(cs.eta);
        const vec3 params = rk_fresnel_fast_params(cs.eta);
        double worst_deg = 0, worst = 0;
        for (int i = 0; i <= 100000; ++i) {
            const float c = static_cast<float>(i) / 100000.0f;
            const double exact = ref::fresnel(c, cs.eta);
            const double es = std::abs(rk_fresnel_schlick(c, f0) - exact);
            if (es > worst) {
                worst = es;
                worst_deg = std::acos(static_cast<double>(c)) / kDeg;
            }
            schlick.add(rk_fresnel_schlick(c, f0), exact, fmt("cos", c));
            fast.add(rk_fresnel_dielectric_fast(c, params), exact, fmt("cos", c));
        }
        std::printf("eta %.2f: Schlick %s\n          fast    %s\n", static_cast<double>(cs.eta), schlick.str().c_str(),
                    fast.str().c_str());
        EXPECT_NEAR(schlick.max_abs, cs.schlick_max, 0.01 * cs.schlick_max + 1e-4);
        EXPECT_LT(fast.max_abs, cs.fast_bound);
        EXPECT_LT(fast.max_abs * 10.0, schlick.max_abs);  // at least 10x better everywhere listed
        if (cs.eta == 1.52f) {
            EXPECT_NEAR(worst_deg, 85.0, 1.5);  // "near 85°"
        }
        EXPECT_NEAR(rk_fresnel_dielectric_fast(1.0f, params), f0, 1e-7);  // exact at both ends
        EXPECT_NEAR(rk_fresnel_dielectric_fast(0.0f, params), 1.0, 1e-6);
    }
}

// ---------------------------------------------------------------------------------------------
// Properties.

TEST(Fresnel, Reciprocity)
{
    // R(air->glass at theta_i) == R(glass->air at theta_t), with sin theta_t = sin theta_i / n.
    for (float eta : {1.33f, 1.52f, 2.4f}) {
        // Near grazing, cos_t sits at the reverse direction's critical angle where R is infinitely
        // steep, so b is compared as the range it takes over cos_t +- 1 ulp (the rounding of cos_t);
        // below cos_i = 0.01 the float rounding of 1/eta itself moves that critical angle too much.
        for (int i = 10; i <= 1000; ++i) {
            const double ci = i / 1000.0;
            const double st = std::sqrt(1.0 - ci * ci) / eta;
            const float ct = static_cast<float>(std::sqrt(1.0 - st * st));
            const float a = rk_fresnel_dielectric(static_cast<float>(ci), eta);
            const float b = rk_fresnel_dielectric(ct, 1.0f / eta);
            const float b_lo = rk_fresnel_dielectric(std::nextafter(ct, 0.0f), 1.0f / eta);
            const float b_hi = rk_fresnel_dielectric(std::nextafter(ct, 2.0f), 1.0f / eta);
            ASSERT_NEAR(a, rktest::nearest_in(a, {b_lo, b, b_hi}), 2e-6) << fmt("eta", eta, "cos_i", ci);
        }
    }
}

TEST(Fresnel, MonotonicForExternalReflection)
{
    // Holds up to eta ~ 3.5; above it the p-polarised dip at Brewster's angle makes the average
    // non-monotonic (float64: eta = 4 rises again from cos 0.538, eta = 10 from cos 0.108).
    for (float eta : {1.0001f, 1.1f, 1.33f, 1.52f, 2.4f, 3.5f}) {
        float prev = 2.0f;
        for (int i = 0; i <= 100000; ++i) {  // cos from 0 (grazing) to 1 (normal): R decreases
            const float c = static_cast<float>(i) / 100000.0f;
            const float r = rk_fresnel_dielectric(c, eta);
            ASSERT_LE(r, prev * (1.0f + 1e-6f)) << fmt("eta", eta, "cos", c);
            prev = r;
        }
    }
}

TEST(Fresnel, LimitsAndBrewster)
{
    for (float eta : {1.1f, 1.33f, 1.52f, 2.4f}) {
        const float f0 = rk_f0_from_eta(eta);
        EXPECT_NEAR(rk_fresnel_dielectric(1.0f, eta), f0, 4e-7 * f0);
        EXPECT_FLOAT_EQ(rk_fresnel_dielectric(0.0f, eta), 1.0f);
        EXPECT_FLOAT_EQ(rk_fresnel_schlick(1.0f, f0), f0);
        EXPECT_FLOAT_EQ(rk_fresnel_schlick(0.0f, f0), 1.0f);
        EXPECT_NEAR(rk_fresnel_dielectric(1e-4f, eta), 1.0, 1e-3);  // continuous towards grazing
        const float cb = std::cos(rk_brewster_angle(eta));
        EXPECT_LT(rk_fresnel_dielectric_sp(cb, eta).y, 1e-12f) << eta;
        EXPECT_NEAR(rk_fresnel_dielectric_sp(cb, eta).x, ref::fresnel_sp(cb, ref::cd(eta, 0)).first, 1e-6);
    }
    // Matched indices: no interface, no reflection — including the grazing 0/0 of textbook forms.
    for (float c : {0.0f, -0.0f, 1e-40f, 1e-7f, 0.5f, 1.0f}) {
        EXPECT_EQ(rk_fresnel_dielectric(c, 1.0f), 0.0f) << c;
        EXPECT_EQ(rk_fresnel_conductor(c, 1.0f, 0.0f), 0.0f) << c;
    }
    // Conductor limits: k = 0 is a dielectric; normal incidence is ((n-1)^2 + k^2) / ((n+1)^2 + k^2).
    for (float n : {1.2f, 1.52f, 2.4f}) {
        for (float c : {0.0f, 0.2f, 0.7f, 1.0f}) {
            EXPECT_NEAR(rk_fresnel_conductor(c, n, 0.0f), rk_fresnel_dielectric(c, n), 2e-6) << n << " " << c;
        }
    }
    const float n = 0.2f, k = 3.9f;
    EXPECT_NEAR(rk_fresnel_conductor(1.0f, n, k), ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k), 2e-6);
}

TEST(Fresnel, TotalInternalReflection)
{
    const float eta = 1.0f / 1.52f;  // glass -> air
    const double crit = std::asin(1.0 / 1.52);
    EXPECT_NEAR(rk_critical_angle(eta), crit, 1e-6);
    EXPECT_NEAR(rk_critical_cos(eta), std::cos(crit), 1e-6);
    EXPECT_EQ(rk_critical_angle(1.52f), static_cast<float>(RK_HALF_PI));  // no TIR going into glass
    EXPECT_EQ(rk_critical_cos(1.52f), 0.0f);
    for (double deg = 41.15; deg < 90.0; deg += 0.01) {
        EXPECT_EQ(rk_fresnel_dielectric(cosd(deg), eta), 1.0f) << deg;
    }
    EXPECT_LT(rk_fresnel_dielectric(cosd(41.13), eta), 1.0f);
    // Just below the critical angle R is continuous up to 1.
    EXPECT_GT(rk_fresnel_dielectric(cosd(41.139), eta), 0.8f);

    vec3 t(0.0f);
    const vec3 nrm(0.0f, 0.0f, 1.0f);
    const double th = 60.0 * kDeg;
    const vec3 inc(static_cast<float>(std::sin(th)), 0.0f, static_cast<float>(-std::cos(th)));
    EXPECT_FALSE(rk_refract(inc, nrm, eta, t));
    EXPECT_NEAR(t.x, inc.x, 1e-7);
    EXPECT_NEAR(t.z, -inc.z, 1e-7);  // the mirror direction, not a zero vector
}

TEST(Fresnel, RefractObeysSnell)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    ErrorStats stats;
    int tir = 0;
    for (int i = 0; i < 200000; ++i) {
        glm::dvec3 n(u(rng), u(rng), u(rng)), d(u(rng), u(rng), u(rng));
        if (glm::length(n) < 1e-3 || glm::length(d) < 1e-3) continue;
        n = glm::normalize(n);
        d = glm::normalize(d);
        if (glm::dot(n, d) > 0) d = -d;
        const double eta = i % 2 ? 1.52 : 1.0 / 1.52;
        // Reference: Snell in vector form, float64.
        const double ci = -glm::dot(n, d);
        const double k = 1.0 - (1.0 - ci * ci) / (eta * eta);
        vec3 t;
        const bool ok = rk_refract(vec3(d), vec3(n), static_cast<float>(eta), t);
        if (k < -1e-6) {
            ASSERT_FALSE(ok);
            ++tir;
            continue;
        }
        if (k < 1e-6) continue;  // within float rounding of the critical angle: either answer is right
        ASSERT_TRUE(ok);
        const glm::dvec3 tr = d / eta + (ci / eta - std::sqrt(k)) * n;
        const glm::dvec3 td(t);
        // sqrt(k) amplifies the rounding of k (~1e-7) by 1/(2 sqrt(k)) near the critical angle.
        const double err = glm::length(td - tr) / (1.0 + 0.5 / std::sqrt(k));
        stats.add(err, 0.0, fmt("eta", eta, "cos_i", ci));
        ASSERT_NEAR(glm::length(td), 1.0, 4e-7);
    }
    std::printf("rk_refract vs float64 Snell: %s, TIR %d\n", stats.str().c_str(), tir);
    EXPECT_LT(stats.max_abs, 1e-6);
    EXPECT_GT(tir, 1000);
}

TEST(Fresnel, SlabAndGlazingMatchSeriesAndLayerAdding)
{
    for (int i = 0; i <= 1000; ++i) {
        const double r = i / 1000.0 * 0.7;  // 50 terms leave 0.7^100 ~ 3e-16 of the series out
        const float rf = static_cast<float>(r);
        EXPECT_NEAR(rk_fresnel_slab(rf), ref::slab_series(r, 50), 2e-7) << r;
        for (int panes = 1; panes <= 4; ++panes) {
            EXPECT_NEAR(rk_fresnel_glazing(rf, static_cast<float>(panes)), ref::stack_surfaces(r, 2 * panes), 3e-7)
                << r << " panes " << panes;
        }
    }
    // Per-polarisation slab: the thesis's order overestimates by up to 0.0236 for n = 1.52.
    double max_diff = 0, at = 0;
    for (int i = 0; i <= 9000; ++i) {
        const float c = cosd(i / 100.0);
        const vec2 sp = rk_fresnel_dielectric_sp(c, 1.52f);
        const double d = rk_fresnel_slab(0.5f * (sp.x + sp.y)) - rk_fresnel_slab_sp(sp);
        if (d > max_diff) {
            max_diff = d;
            at = i / 100.0;
        }
    }
    std::printf("slab(avg) - slab_sp max %.5f at %.2f deg\n", max_diff, at);
    EXPECT_NEAR(max_diff, 0.0236, 5e-4);
    EXPECT_GT(at, 60.0);
    EXPECT_LT(at, 75.0);
    EXPECT_EQ(rk_fresnel_window(1.0f, 1.52f, 1.0f), rk_fresnel_slab_sp(rk_fresnel_dielectric_sp(1.0f, 1.52f)));
}

TEST(Fresnel, EtaFromF0RoundTrip)
{
    for (float eta = 1.0f; eta < 100.0f; eta *= 1.01f) {
        EXPECT_NEAR(rk_eta_from_f0(rk_f0_from_eta(eta)), eta, 2e-6 * eta * eta) << eta;
    }
    EXPECT_TRUE(std::isfinite(rk_eta_from_f0(1.0f)));
}

TEST(Fresnel, LutAtTexelCentresAndInterpolation)
{
    const float eta = 1.52f;
    for (int size : {64, 128, 256}) {
        const auto lut = bake_fresnel_lut_1d(size, eta, FresnelLutMode::slab_polarised);
        ASSERT_EQ(lut.size(), static_cast<size_t>(size));
        double worst_centre = 0, worst_interp = 0;
        for (int i = 0; i < size; ++i) {
            const double c = (i + 0.5) / size;
            auto sp = ref::fresnel_sp(c, ref::cd(eta, 0));
            const double exact = 0.5 * (2 * sp.first / (1 + sp.first) + 2 * sp.second / (1 + sp.second));
            worst_centre = std::max(worst_centre, std::abs(lut[static_cast<size_t>(i)] - exact));
            worst_centre = std::max(worst_centre, std::abs(sample_fresnel_lut_1d(lut, static_cast<float>(c)) - exact));
        }
        for (int j = 0; j <= 20000; ++j) {
            const double c = j / 20000.0;
            auto sp = ref::fresnel_sp(c, ref::cd(eta, 0));
            const double exact = 0.5 * (2 * sp.first / (1 + sp.first) + 2 * sp.second / (1 + sp.second));
            worst_interp = std::max(worst_interp, std::abs(sample_fresnel_lut_1d(lut, static_cast<float>(c)) - exact));
        }
        std::printf("LUT %d texels: centre error %.2e, interpolation error %.2e\n", size, worst_centre, worst_interp);
        EXPECT_LT(worst_centre, 2e-7);
        const double bound = size == 64 ? 2.3e-2 : size == 128 ? 1.15e-2 : 5.7e-3;
        EXPECT_LT(worst_interp, bound);
    }
    EXPECT_THROW(bake_fresnel_lut_1d(1, eta, FresnelLutMode::single_surface), std::invalid_argument);
    const auto two = bake_fresnel_lut_1d(16, eta, FresnelLutMode::glazing_polarised, 2.0f);
    EXPECT_NEAR(two.back(), rk_fresnel_glazing_sp(rk_fresnel_dielectric_sp(31.0f / 32.0f, eta), 2.0f), 1e-7);
}

// ---------------------------------------------------------------------------------------------
// Stress: >= 10^6 inputs drawn from the whole finite float range plus special values; no output
// may be NaN or Inf, and reflectances stay in [0, 1].

namespace {

float random_finite(std::mt19937& rng)
{
    for (;;) {
        const std::uint32_t bits = static_cast<std::uint32_t>(rng());
        float f;
        std::memcpy(&f, &bits, sizeof f);
        if (std::isfinite(f)) return f;
    }
}

const float kSpecials[] = {0.0f, -0.0f, 1e-45f, -1e-45f, 1e-40f, 1.17549435e-38f, -1.17549435e-38f, 1.0f,
                           std::nextafter(1.0f, 0.0f), std::nextafter(1.0f, 2.0f), -1.0f, 0.5f, 2.0f,
                           1e-20f, 1e20f, -1e20f, 3.4028235e38f, -3.4028235e38f, 1.52f, 1.0f / 1.52f,
                           0.7597f /* ~cos of the glass->air critical angle */};

}  // namespace

TEST(Fresnel, StressNoNanNoInf)
{
    std::mt19937 rng(1234);
    long n = 0;
    auto draw = [&](int i, int k) {
        // Mix whole-range random floats, specials, and in-domain values.
        const int sel = (i * 7 + k * 3) % 5;
        if (sel == 0) return kSpecials[static_cast<size_t>(rng()) % (sizeof kSpecials / sizeof kSpecials[0])];
        if (sel == 1) return std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
        if (sel == 2) return std::uniform_real_distribution<float>(0.2f, 5.0f)(rng);
        return random_finite(rng);
    };
    auto in01 = [](float v) { return std::isfinite(v) && v >= 0.0f && v <= 1.0f; };
    for (int i = 0; i < 1000000; ++i) {
        const float a = draw(i, 0), b = draw(i, 1), c = draw(i, 2);
        const vec2 sp = rk_fresnel_dielectric_sp(a, b);
        const vec3 cond = rk_fresnel_conductor(a, vec3(b), vec3(c));
        const vec3 sch = rk_fresnel_schlick(a, vec3(b), vec3(c));
        const float vals01[] = {sp.x, sp.y, rk_fresnel_dielectric(a, b), rk_fresnel_schlick(a, b), rk_fresnel_schlick(a, b, c),
                                sch.x, rk_fresnel_dielectric_fast(a, b), rk_fresnel_dielectric_fast(a, rk_fresnel_fast_params(b)),
                                cond.x, rk_fresnel_conductor(a, b, c), rk_fresnel_slab(a), rk_fresnel_slab_sp(vec2(a, b)),
                                rk_fresnel_glazing(a, b), rk_fresnel_glazing_sp(vec2(a, b), c), rk_fresnel_window(a, b, c),
                                rk_f0_from_ior(a, b), rk_f0_from_eta(a), rk_critical_cos(a)};
        for (float v : vals01) {
            ASSERT_TRUE(in01(v)) << "output " << v << " for inputs " << fmt(a, b, c);
            ++n;
        }
        const float finite[] = {rk_eta_from_f0(a), rk_critical_angle(a), rk_brewster_angle(a)};
        for (float v : finite) {
            ASSERT_TRUE(std::isfinite(v)) << fmt(a, b, c);
            ++n;
        }
        // Refraction: any direction components up to 1e18 in magnitude (documented domain).
        const float s = 1e18f;
        const vec3 d(glm::clamp(a, -s, s), glm::clamp(b, -s, s), glm::clamp(c, -s, s));
        const vec3 nn(glm::clamp(c, -s, s), glm::clamp(a, -s, s), 1.0f);
        vec3 t;
        rk_refract(d, nn, b, t);
        ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z)) << fmt(a, b, c);
        ++n;
    }
    std::printf("stress: %ld outputs checked, all finite and in range\n", n);
}
