// CPU tests of raykit/interior_compose.hpp (the C++ build of shaders/raykit/interior_compose.glsl)
// against float64 formulas written here: the pane reflectance from the complex-amplitude Fresnel
// reference (tests/reference/fresnel_ref.hpp) summed as a series per polarisation, the
// composition, the smoothstep fade and the light model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "raykit/interior_compose.hpp"
#include "reference/fresnel_ref.hpp"
#include "test_util.hpp"

using namespace raykit;
using rktest::ErrorStats;
using rktest::fmt;

namespace {

/// One non-absorbing pane, per polarisation, the sum of the multiple-reflection series
/// R + (1-R)^2 R / (1 - R^2) = 2R / (1 + R), then averaged (the default RK_FRESNEL_WINDOW_MODE 2
/// model). (The series summed term by term, ref::slab_series, agrees where it converges.)
double ref_pane(double c, double eta)
{
    const auto sp = ref::fresnel_sp(c, ref::cd(eta, 0.0));
    auto slab = [](double r) { return 2.0 * r / (1.0 + r); };
    return 0.5 * (slab(sp.first) + slab(sp.second));
}

double ref_window(double interior, double reflection, double c, double tint)
{
    const double r = ref_pane(c, 1.52);
    return r * reflection + (1.0 - r) * tint * interior;
}

}  // namespace

TEST(InteriorCompose, MaskConvention)
{
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.0f, 8.0f);
    for (int i = 0; i < 10000; ++i) {
        const vec3 ext(u(rng), u(rng), u(rng)), win(u(rng), u(rng), u(rng));
        // mask 0 (and anything up to half an 8-bit step) -> the exterior exactly.
        EXPECT_EQ(rk_im_compose(ext, 0.0f, win), ext);
        EXPECT_EQ(rk_im_compose(ext, -1.0f, win), ext);
        EXPECT_EQ(rk_im_compose(ext, RK_IM_MASK_MIN, win), ext);
        EXPECT_EQ(rk_im_compose(vec4(ext, 0.0f), win), ext);
        EXPECT_FALSE(rk_im_needs_interior(0.0f));
        EXPECT_FALSE(rk_im_needs_interior(RK_IM_MASK_MIN));
        // mask 1 (and above) -> the window exactly.
        EXPECT_EQ(rk_im_compose(ext, 1.0f, win), win);
        EXPECT_EQ(rk_im_compose(ext, 7.0f, win), win);
        EXPECT_EQ(rk_im_compose(vec4(ext, 1.0f), win), win);
        EXPECT_TRUE(rk_im_needs_interior(1.0f / 255.0f));
        // Fractional: the float64 lerp, and within [min, max] of the inputs.
        const float m = std::uniform_real_distribution<float>(0.0f, 1.0f)(rng);
        const vec3 c = rk_im_compose(ext, m, win);
        for (int k = 0; k < 3; ++k) {
            const double w = m > RK_IM_MASK_MIN ? m : 0.0;
            const double e = ext[k] * (1.0 - w) + win[k] * w;
            EXPECT_NEAR(c[k], e, 4e-7 * std::max(1.0, std::abs(e)));
            EXPECT_LE(c[k], std::max(ext[k], win[k]) * (1.0f + 1.2e-7f));
            EXPECT_GE(c[k], std::min(ext[k], win[k]) * (1.0f - 1.2e-7f));
        }
    }
}

TEST(InteriorCompose, FresnelGlassVsFloat64)
{
    // Normal, grazing and everything between: the window colour against the float64 pane.
    ErrorStats e;
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const float cosines[] = {1.0f, 0.9999f, 0.5f, 0.2588190f, 0.0871557f, 0.01f, 1e-4f, 0.0f};
    for (int i = 0; i < 100000; ++i) {
        const float c = i < 8 ? cosines[i] : u(rng);
        const vec3 interior(u(rng) * 4.0f, u(rng), 0.25f), refl(u(rng) * 2.0f, 0.5f, u(rng) * 10.0f);
        const vec3 tint(u(rng), 1.0f, 0.8f);
        const vec3 w = rk_im_window_fresnel(interior, refl, c, tint, 1.52f, 1.0f);
        for (int k = 0; k < 3; ++k) {
            const double exact = ref_window(interior[k], refl[k], c, tint[k]);
            e.add(w[k], exact, fmt("cos", c, "k", k));
            // Energy: never more than the brightest input.
            EXPECT_LE(w[k], std::max(interior[k], refl[k]) * (1.0f + 3e-7f)) << fmt(c, k);
        }
    }
    std::printf("[compose] Fresnel window vs float64 pane: %s\n", e.str().c_str());
    EXPECT_LT(e.max_abs, 5e-6);  // measured 2.5e-6 (reflectance ~1e-6 times colours up to 10)
    EXPECT_NEAR(ref_pane(1.0, 1.52), ref::slab_series(ref::fresnel(1.0, 1.52), 60), 1e-15);
    // The published anchors: one pane of n = 1.52 reflects 8.1682 % at normal incidence, all at grazing.
    const vec3 white(1.0f), black(0.0f);
    EXPECT_NEAR(rk_im_window_fresnel(black, white, 1.0f, white, 1.52f, 1.0f).x, 0.0816820, 2e-7);
    EXPECT_NEAR(rk_im_window_fresnel(white, black, 1.0f, white, 1.52f, 1.0f).x, 1.0 - 0.0816820, 2e-7);
    EXPECT_NEAR(rk_im_window_fresnel(black, white, 0.0f, white, 1.52f, 1.0f).x, 1.0, 1e-6);
    EXPECT_NEAR(rk_im_window_fresnel(white, black, 0.0f, white, 1.52f, 1.0f).x, 0.0, 1e-6);
    // Matches rk_window_glass_reflectance (shared with window_glass.glsl) exactly.
    for (float c : cosines) {
        const float r = rk_window_glass_reflectance(c, 1.52f, 1.0f);
        EXPECT_EQ(rk_im_window_fresnel(black, white, c, white, 1.52f, 1.0f).x, r);
        EXPECT_NEAR(r, ref_pane(c, 1.52), 1e-6) << c;
    }
    // rk_im_window is the Fresnel mode by default.
    EXPECT_EQ(rk_im_window(vec3(0.3f), vec3(0.7f), 0.4f, vec3(0.9f), 1.52f, 1.0f),
              rk_im_window_fresnel(vec3(0.3f), vec3(0.7f), 0.4f, vec3(0.9f), 1.52f, 1.0f));
}

TEST(InteriorCompose, ThesisAdditiveMode)
{
    const vec3 a = rk_im_window_additive(vec3(0.3f, 0.5f, 2.0f), vec3(0.2f, 0.6f, 1.0f));
    EXPECT_FLOAT_EQ(a.x, 0.5f);
    EXPECT_FLOAT_EQ(a.y, 1.1f);  // brighter than both inputs: the thesis's addition is not energy conserving
    EXPECT_FLOAT_EQ(a.z, 3.0f);
    EXPECT_EQ(rk_im_window_additive(vec3(-1.0f), vec3(0.5f)), vec3(0.5f));  // sanitised
}

TEST(InteriorCompose, RoomLightsDeterministicAndMonotone)
{
    const vec3 warm(1.0f, 0.8f, 0.6f), cool(0.7f, 0.8f, 1.0f);
    const vec2 level(0.5f, 2.0f);
    long lit_total = 0, rooms = 0;
    std::set<long> distinct;
    for (int x = -20; x < 20; ++x) {
        for (int y = 0; y < 30; ++y) {
            for (int z = 0; z < 3; ++z) {
                const ivec3 r(x, y, z);
                const vec3 l = rk_im_room_light(r, 0.6f, 1234u, warm, cool, level, RK_IM_UNLIT_DEFAULT);
                EXPECT_EQ(l, rk_im_room_light(r, 0.6f, 1234u, warm, cool, level, RK_IM_UNLIT_DEFAULT));
                const bool lit = rk_im_room_lit(r, 0.6f, 1234u);
                ++rooms;
                if (!lit) {
                    EXPECT_EQ(l, vec3(RK_IM_UNLIT_DEFAULT));
                    continue;
                }
                ++lit_total;
                // The float64 model with the documented hash: lanes y and z of one PCG3D call.
                const uvec3 w = rk_pcg3d(uvec3(uint(r.x), uint(r.y), uint(r.z) ^ rk_hash_u32(1234u)));
                const double h = static_cast<double>(w.y >> 8u) / 16777216.0;
                const double k = static_cast<double>(w.z >> 8u) / 16777216.0;
                const double lv = 0.5 + 1.5 * k;
                for (int c = 0; c < 3; ++c) {
                    const double e = (warm[c] + (cool[c] - warm[c]) * h) * lv;
                    EXPECT_NEAR(l[c], e, 4e-7 * e);
                    EXPECT_GE(l[c], std::min(warm[c], cool[c]) * 0.5f - 1e-6f);  // min(warm, cool) * level.x
                    EXPECT_LE(l[c], 2.0f + 1e-6f);
                }
                distinct.insert(static_cast<long>(l.x * 1e5f));
                // Monotone in the probability: lit at 0.6 stays lit above.
                EXPECT_NE(rk_im_room_light(r, 0.61f, 1234u, warm, cool, level, 0.0f), vec3(0.0f));
            }
        }
    }
    const double frac = static_cast<double>(lit_total) / static_cast<double>(rooms);
    std::printf("[compose] room lights: %ld of %ld lit (%.3f, c = 0.6), %zu distinct light levels\n", lit_total, rooms,
                frac, distinct.size());
    EXPECT_NEAR(frac, 0.6, 0.05);
    EXPECT_GT(distinct.size(), 500u);
    // Independence of on/off, hue and level (the three lanes of one PCG3D call): lane x is
    // rk_im_room_random bit for bit, and the sample correlations between the lanes over 64,000
    // rooms are those of independent uniforms (|r| < 4 / sqrt(n) = 0.016).
    {
        double sx = 0, sy = 0, sz = 0, sxx = 0, syy = 0, szz = 0, sxy = 0, sxz = 0, syz = 0;
        const double n = 40.0 * 40.0 * 40.0;
        for (int x = 0; x < 40; ++x) {
            for (int y = 0; y < 40; ++y) {
                for (int z = 0; z < 40; ++z) {
                    const vec3 l = rk_im_room_lanes(ivec3(x - 20, y, z * 7), 99u);
                    ASSERT_EQ(l.x, rk_im_room_random(ivec3(x - 20, y, z * 7), 99u));
                    const double a = l.x, b = l.y, c = l.z;
                    sx += a; sy += b; sz += c; sxx += a * a; syy += b * b; szz += c * c;
                    sxy += a * b; sxz += a * c; syz += b * c;
                }
            }
        }
        auto corr = [n](double s_ab, double s_a, double s_b, double s_aa, double s_bb) {
            const double cov = s_ab / n - (s_a / n) * (s_b / n);
            return cov / std::sqrt((s_aa / n - (s_a / n) * (s_a / n)) * (s_bb / n - (s_b / n) * (s_b / n)));
        };
        const double rxy = corr(sxy, sx, sy, sxx, syy), rxz = corr(sxz, sx, sz, sxx, szz), ryz = corr(syz, sy, sz, syy, szz);
        std::printf("[compose] room lanes: correlations x-y %.4f, x-z %.4f, y-z %.4f (64000 rooms)\n", rxy, rxz, ryz);
        EXPECT_LT(std::abs(rxy), 0.016);
        EXPECT_LT(std::abs(rxz), 0.016);
        EXPECT_LT(std::abs(ryz), 0.016);
    }
    // Extremes: c = 0 none lit, c = 1 all lit; unlit factor clamped.
    EXPECT_EQ(rk_im_room_light(ivec3(5), 0.0f, 1u, warm, cool, level, 7.0f), vec3(1.0f));
    EXPECT_NE(rk_im_room_light(ivec3(5), 1.0f, 1u, warm, cool, level, 0.0f), vec3(0.0f));
    // Room tint: each channel in (1 - amount, 1], deterministic.
    for (int i = 0; i < 1000; ++i) {
        const vec3 t = rk_im_room_tint(ivec3(i, 2 * i, -i), 9u, 0.3f);
        for (int c = 0; c < 3; ++c) {
            EXPECT_GT(t[c], 0.7f - 1e-7f);
            EXPECT_LE(t[c], 1.0f);
        }
    }
}

TEST(InteriorCompose, FadeContinuity)
{
    // The weight against float64 smoothstep, and continuity / monotonicity across the band.
    ErrorStats e;
    const float start = 100.0f, end = 300.0f;
    float prev = 0.0f;
    double max_jump = 0.0;
    for (int i = 0; i <= 40000; ++i) {
        const float d = 50.0f + static_cast<float>(i) * 0.00725f * 40.0f / 40.0f * 1.0f;  // 50 .. 340
        const float w = rk_im_fade_weight(d, start, end);
        double x = (static_cast<double>(d) - start) / (end - start);
        x = std::clamp(x, 0.0, 1.0);
        e.add(w, x * x * (3.0 - 2.0 * x), fmt(d));
        EXPECT_GE(w, prev) << d;  // monotone
        max_jump = std::max(max_jump, static_cast<double>(w - prev));
        prev = w;
    }
    std::printf("[compose] fade weight vs float64 smoothstep: %s; largest step between samples 0.00725 apart %.3g\n",
                e.str().c_str(), max_jump);
    EXPECT_LT(e.max_abs, 4e-7);
    EXPECT_LT(max_jump, 1.5 * 0.00725 / 200.0 + 1e-6);  // slope <= 1.5 / band
    EXPECT_EQ(rk_im_fade_weight(start, start, end), 0.0f);
    EXPECT_EQ(rk_im_fade_weight(end, start, end), 1.0f);
    EXPECT_EQ(rk_im_fade_weight(0.0f, start, end), 0.0f);
    EXPECT_EQ(rk_im_fade_weight(1e30f, start, end), 1.0f);
    // Degenerate band: a hard switch, no NaN.
    EXPECT_EQ(rk_im_fade_weight(99.0f, 100.0f, 100.0f), 0.0f);
    EXPECT_EQ(rk_im_fade_weight(100.5f, 100.0f, 100.0f), 1.0f);
    EXPECT_EQ(rk_im_fade_weight(100.5f, 100.0f, 50.0f), 1.0f);
    EXPECT_TRUE(std::isfinite(rk_im_fade_weight(1e-45f, 0.0f, 1e-45f)));
    // The blend: exact at both ends, between the inputs inside.
    const vec3 in(0.2f, 0.9f, 3.0f), flat(0.5f, 0.5f, 0.5f);
    EXPECT_EQ(rk_im_fade(in, flat, 0.0f), in);
    EXPECT_EQ(rk_im_fade(in, flat, 1.0f), flat);
    EXPECT_EQ(rk_im_fade_flat(vec3(0.4f, 0.5f, 0.6f), vec3(2.0f)), vec3(0.8f, 1.0f, 1.2f));
    EXPECT_EQ(rk_im_fade_flat(vec3(-1.0f), vec3(2.0f)), vec3(0.0f));
    // Continuity of the composed colour across the band: interior at start, flat at end.
    const vec3 a = rk_im_fade(in, flat, rk_im_fade_weight(std::nextafter(start, 0.0f), start, end));
    const vec3 b = rk_im_fade(in, flat, rk_im_fade_weight(std::nextafter(start, 1e9f), start, end));
    EXPECT_NEAR(glm::length(a - b), 0.0, 1e-9);
    const vec3 c = rk_im_fade(in, flat, rk_im_fade_weight(std::nextafter(end, 0.0f), start, end));
    EXPECT_NEAR(glm::length(c - flat), 0.0, 1e-9);
}

TEST(InteriorCompose, AdversarialInputsAreFinite)
{
    const float vals[] = {0.0f, -0.0f, 1e-45f, -1e-40f, 1.0f, -1.0f, 1e20f, -1e30f, 3.4028235e38f, -3.4028235e38f, 0.5f};
    std::mt19937 rng(8);
    auto u32 = [&]() { return static_cast<uint>(rng()); };
    auto pick = [&]() { return vals[rng() % (sizeof vals / sizeof vals[0])]; };
    auto v3 = [&]() { return vec3(pick(), pick(), pick()); };
    for (int i = 0; i < 100000; ++i) {
        const vec3 w = rk_im_window_fresnel(v3(), v3(), pick(), v3(), pick(), pick());
        const vec3 l = rk_im_room_light(ivec3(static_cast<int>(u32())), pick(), u32(), v3(), v3(), vec2(pick(), pick()), pick());
        const float f = rk_im_fade_weight(pick(), pick(), pick());
        const vec3 fl = rk_im_fade_flat(v3(), v3());
        const vec3 t = rk_im_room_tint(ivec3(1), u32(), pick());
        const vec3 c = rk_im_compose(vec3(pick(), pick(), 1.0f), pick(), w);
        for (float o : {w.x, w.y, w.z, l.x, l.y, l.z, f, fl.x, fl.y, fl.z, t.x, t.y, t.z, c.x, c.y, c.z})
            ASSERT_TRUE(std::isfinite(o)) << i;
        ASSERT_GE(f, 0.0f);
        ASSERT_LE(f, 1.0f);
    }
}
