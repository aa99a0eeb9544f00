// GPU parity cases for shaders/raykit/color.glsl and tonemap.glsl (see parity.hpp).
#include <gtest/gtest.h>

#include "parity.hpp"
#include "raykit/tonemap.hpp"

using namespace raykit;
namespace dom = parity::dom;

namespace {

// HDR input: log-uniform over 1e-4..1e5 plus the adversarial set (negative, denormal, huge).
parity::Domain hdr() { return {1e-4f, 1e5f, true, {0.18f, 1.0f, 0.76f, 0.08f, 11.2f, 8.0f, 1e18f}}; }

std::vector<parity::Case> tonemap_cases()
{
    const char* C = "raykit/color.glsl";
    const char* T = "raykit/tonemap.glsl";
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_luminance", C, (hdr(), hdr(), hdr()), 1, o[0] = rk_luminance(vec3(min(a[0], 1e30f), min(a[1], 1e30f), min(a[2], 1e30f)));),
        RK_PARITY("rk_luminance_thesis", C, (hdr(), hdr(), hdr()), 1,
                  o[0] = rk_luminance_thesis(vec3(min(a[0], 1e30f), min(a[1], 1e30f), min(a[2], 1e30f)));),
        RK_PARITY("rk_hdr_sanitize", C, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_hdr_sanitize(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_srgb_encode", C, (dom::unit(), dom::unit(), dom::unit()), 3,
                  vec3 r = rk_srgb_encode(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_srgb_decode", C, (dom::unit(), dom::unit(), dom::unit()), 3,
                  vec3 r = rk_srgb_decode(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_reinhard_scale", T, (hdr(), dom::unit(), hdr()), 1, o[0] = rk_reinhard_scale(a[0], a[1], a[2]);),
        RK_PARITY("rk_reinhard", T, (hdr()), 1, o[0] = rk_reinhard(a[0]);),
        RK_PARITY("rk_reinhard_extended", T, (hdr(), hdr()), 1, o[0] = rk_reinhard_extended(a[0], a[1]);),
        RK_PARITY("rk_tonemap_reinhard", T, (hdr(), hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_tonemap_reinhard(vec3(a[0], a[1], a[2]), a[3]); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_aces_narkowicz", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_aces_narkowicz(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_aces_hill_curve", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_aces_hill_curve(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_aces_hill", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_aces_hill(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_agx_contrast", T, (dom::unit(), dom::unit(), dom::unit()), 3,
                  vec3 r = rk_agx_contrast(vec3(rk_saturate(a[0]), rk_saturate(a[1]), rk_saturate(a[2])));
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_agx_look golden", T, (dom::unit(), dom::unit(), dom::unit()), 3,
                  vec3 r = rk_agx_look(vec3(rk_saturate(a[0]), rk_saturate(a[1]), rk_saturate(a[2])), 1);
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_agx default", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_agx(vec3(a[0], a[1], a[2]), 0); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_agx golden", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_agx(vec3(a[0], a[1], a[2]), 1); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_agx punchy", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_agx(vec3(a[0], a[1], a[2]), 2); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_pbr_neutral", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_pbr_neutral(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_pbr_neutral_inverse", T, (dom::unit(), dom::unit(), dom::unit()), 3,
                  vec3 r = rk_pbr_neutral_inverse(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_hable_curve", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_hable_curve(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_hable", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_hable(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_lottes_params", T, (dom::range(1.0f, 2.0f), dom::range(0.9f, 1.0f)), 2,
                  vec2 r = rk_lottes_params(a[0], a[1], 8.0f, 0.18f, 0.267f); o[0] = r.x; o[1] = r.y;),
        RK_PARITY("rk_lottes", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_lottes(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_uchimura_curve", T, (dom::range(0.0f, 10.0f), dom::range(0.0f, 10.0f), dom::range(0.0f, 10.0f)), 3,
                  vec3 x = max(vec3(a[0], a[1], a[2]), vec3(0.0f));
                  vec3 r = rk_uchimura_curve(min(x, vec3(100.0f)), 1.0f, 1.0f, 0.22f, 0.4f, 1.33f, 0.0f);
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_uchimura", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_uchimura(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_tonemap (default AgX)", T, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_tonemap(vec3(a[0], a[1], a[2]), 4.0f); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
    };
    // pow/log2/exp precision is driver-defined in GLSL (llvmpipe: a few ulp); AgX's polynomial
    // amplifies its input's error by ~40.
    for (parity::Case& c : cases) {
        c.abs_tol = 2e-6;
        c.rel_tol = 2e-5;
        if (c.name.find("agx") != std::string::npos || c.name.find("rk_tonemap") != std::string::npos) c.abs_tol = 2e-5;
        if (c.name == "rk_pbr_neutral_inverse") c.rel_tol = 1e-3;  // ill-conditioned as the peak -> 1
    }
    return cases;
}

}  // namespace

TEST(GpuParity, Tonemap)
{
    for (const parity::Case& c : tonemap_cases()) {
        const parity::Result r = parity::run(c, parity::shader_dir());
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
}

TEST(GpuParity, TonemapOperatorMacro)
{
    // rk_tonemap compiled with each RK_TONEMAP_OPERATOR (and AgX look) matches the CPU dispatch.
    for (int op = 0; op <= 8; ++op) {
        for (int look = 0; look <= (op == 4 ? 2 : 0); ++look) {
            parity::Case c{"rk_tonemap op " + std::to_string(op) + " look " + std::to_string(look), "raykit/tonemap.glsl",
                           {hdr(), hdr(), hdr()}, 3,
                           "vec3 r = rk_tonemap(vec3(a[0], a[1], a[2]), 4.0f); o[0] = r.x; o[1] = r.y; o[2] = r.z;",
                           [op, look](const float* a, float* o) {
                               const vec3 r = tonemap(static_cast<ToneOperator>(op), vec3(a[0], a[1], a[2]), look, 4.0f);
                               o[0] = r.x;
                               o[1] = r.y;
                               o[2] = r.z;
                           },
                           2e-5, 2e-5, tonemap_defines(static_cast<ToneOperator>(op), look), true, {}};
            const parity::Result r = parity::run(c, parity::shader_dir(), 1024);
            EXPECT_TRUE(r.ok) << c.name << ": worst " << r.worst;
        }
    }
}

// An adversarial sample on the driver: 4096 rows per function from tests/adversarial.hpp's stream
// (the CPU sweeps of tests/test_adversarial.cpp, >= 1e5 rows each, use the same generator); every
// GPU output must be finite and inside the function's documented range. Finite inputs only: GLSL
// does not require NaN or Inf to be supported, so the promises about them are CPU-only. Denormals
// are kept: a driver that flushes them reads ±0, which lies inside every domain here, so the
// range must hold either way. Inputs: a[0..2] a colour of any finite channels, a[3] a white point.
TEST(GpuParity, TonemapAdversarialRanges)
{
    using rktest::adv::Floats;
    using rktest::adv::Vecs;
    const Vecs rgb = Vecs::any();
    const Floats white = Floats::any().mark({1e-9f, 1e9f, RK_HDR_MAX});
    auto draw = [&](rktest::adv::Gen& g, float* a) {
        const vec3 c = g.v3(rgb);
        a[0] = c.x;
        a[1] = c.y;
        a[2] = c.z;
        a[3] = g.f(white);
    };
    auto in = [](float lo, float hi) { return [lo, hi](int, float v) { return v >= lo && v <= hi; }; };
    const char* C = "raykit/color.glsl";
    const char* T = "raykit/tonemap.glsl";
#define RK_ADV_TONEMAP(NAME, INCLUDE, ...) RK_PARITY(NAME, INCLUDE, (hdr(), hdr(), hdr(), hdr()), 3, __VA_ARGS__)
    const std::vector<std::pair<parity::Case, std::function<bool(int, float)>>> cases = {
        {RK_ADV_TONEMAP("rk_hdr_sanitize", C, vec3 r = rk_hdr_sanitize(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, RK_HDR_MAX)},
        {RK_ADV_TONEMAP("rk_srgb_encode", C, vec3 r = rk_srgb_encode(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_srgb_decode", C, vec3 r = rk_srgb_decode(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_reinhard_scale", T, o[0] = rk_reinhard_scale(a[0], a[1], a[2]);), in(0.0f, RK_HDR_MAX)},
        {RK_ADV_TONEMAP("rk_reinhard", T, o[0] = rk_reinhard(a[0]);), in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_reinhard_extended", T, o[0] = rk_reinhard_extended(a[0], a[3]);), in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_tonemap_reinhard", T,
                        vec3 r = rk_tonemap_reinhard(vec3(a[0], a[1], a[2]), a[3]); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_aces_narkowicz", T, vec3 r = rk_aces_narkowicz(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_aces_hill_curve", T,
                        vec3 r = rk_aces_hill_curve(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(-3.81e-4f, 1.0165403f)},
        {RK_ADV_TONEMAP("rk_aces_hill", T, vec3 r = rk_aces_hill(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_agx default", T, vec3 r = rk_agx(vec3(a[0], a[1], a[2]), 0); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_agx golden", T, vec3 r = rk_agx(vec3(a[0], a[1], a[2]), 1); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_agx punchy", T, vec3 r = rk_agx(vec3(a[0], a[1], a[2]), 2); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_pbr_neutral", T, vec3 r = rk_pbr_neutral(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_pbr_neutral_inverse", T,
                        vec3 r = rk_pbr_neutral_inverse(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, RK_FLT_MAX)},
        {RK_ADV_TONEMAP("rk_hable_curve", T, vec3 r = rk_hable_curve(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f - 0.02f / 0.30f)},
        {RK_ADV_TONEMAP("rk_hable", T, vec3 r = rk_hable(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;), in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_lottes", T, vec3 r = rk_lottes(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;), in(0.0f, 1.0f)},
        {RK_ADV_TONEMAP("rk_uchimura", T, vec3 r = rk_uchimura(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         in(0.0f, 1.0f)},
    };
#undef RK_ADV_TONEMAP
    long bad = 0;
    for (const auto& [c, ok] : cases) bad += parity::run_adversarial(c, parity::shader_dir(), 4096, draw, ok);
    // rk_tonemap under every RK_TONEMAP_OPERATOR (and AgX look).
    for (int op = 0; op <= 8; ++op) {
        for (int look = 0; look <= (op == 4 ? 2 : 0); ++look) {
            parity::Case c{"rk_tonemap op " + std::to_string(op) + " look " + std::to_string(look), T, {hdr(), hdr(), hdr(), hdr()}, 3,
                           "vec3 r = rk_tonemap(vec3(a[0], a[1], a[2]), a[3]); o[0] = r.x; o[1] = r.y; o[2] = r.z;",
                           [](const float*, float*) {}, 0.0, 0.0, tonemap_defines(static_cast<ToneOperator>(op), look), true, {}};
            bad += parity::run_adversarial(c, parity::shader_dir(), 4096, draw, in(0.0f, 1.0f));
        }
    }
    EXPECT_EQ(bad, 0);
}
