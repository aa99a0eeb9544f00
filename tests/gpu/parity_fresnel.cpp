// GPU parity cases for shaders/raykit/common.glsl and fresnel.glsl (see parity.hpp).
#include <gtest/gtest.h>

#include <string>

#include "parity.hpp"
#include "parity_fresnel_ties.hpp"
#include "raykit/fresnel.hpp"

using namespace raykit;
using parity::Domain;
namespace dom = parity::dom;

namespace {

std::vector<parity::Case> fresnel_cases()
{
    const char* F = "raykit/fresnel.glsl";
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_saturate", "raykit/common.glsl", (dom::signed_unit()), 1, o[0] = rk_saturate(a[0]);),
        RK_PARITY("rk_flush_subnormal", "raykit/common.glsl", (dom::signed_unit(), dom::signed_unit(), dom::signed_unit()), 3,
                  vec3 v = rk_flush_subnormal(vec3(a[0], a[1], a[2])); o[0] = v.x; o[1] = v.y; o[2] = v.z;),
        // rk_div: divisors up to ±FLT_MAX (the adversarial values reach both inputs); NVIDIA's
        // reciprocal division returns 0 for a divisor above 2^126, rk_div the quotient.
        RK_PARITY("rk_div / rk_div3 / rk_div4", "raykit/common.glsl", (dom::range(-1e30f, 1e30f), dom::range(-1e38f, 1e38f)), 3,
                  // Divisors of magnitude at least 1, numerators at most 1e30: finite quotients.
                  float b = abs(a[1]) >= 1.0f ? a[1] : 1.0f;
                  float n = clamp(a[0], -1e30f, 1e30f);
                  o[0] = rk_div(n, b);
                  vec3 q3 = rk_div3(vec3(n, 1.0f, -b), b); o[1] = q3.z;
                  vec4 q4 = rk_div4(vec4(b, n, 0.5f, 2.0f), b); o[2] = q4.x + q4.w;),
        RK_PARITY("rk_pow5", "raykit/common.glsl", (dom::range(-8.0f, 8.0f)), 1, o[0] = rk_pow5(rk_saturate(a[0]));),
        RK_PARITY("rk_safe_sqrt", "raykit/common.glsl", (dom::range(-1.0f, 100.0f)), 1, o[0] = rk_safe_sqrt(min(a[0], 1e30f));),
        RK_PARITY("rk_safe_rcp_pos", "raykit/common.glsl", (dom::range(0.0f, 100.0f)), 1,
                  o[0] = rk_safe_rcp_pos(max(a[0], 1e-30f));),
        RK_PARITY("rk_fresnel_clamp_eta", F, (dom::eta()), 1, o[0] = rk_fresnel_clamp_eta(a[0]);),
        RK_PARITY("rk_f0_from_ior", F, (dom::eta(), dom::eta()), 1, o[0] = rk_f0_from_ior(a[0], a[1]);),
        RK_PARITY("rk_f0_from_eta", F, (dom::eta()), 1, o[0] = rk_f0_from_eta(a[0]);),
        RK_PARITY("rk_eta_from_f0", F, (dom::unit()), 1, o[0] = rk_eta_from_f0(a[0]);),
        RK_PARITY("rk_fresnel_schlick(float,float)", F, (dom::cosine(), dom::unit()), 1,
                  o[0] = rk_fresnel_schlick(a[0], a[1]);),
        RK_PARITY("rk_fresnel_schlick(float,vec3)", F, (dom::cosine(), dom::unit(), dom::unit(), dom::unit()), 3,
                  vec3 r = rk_fresnel_schlick(a[0], vec3(a[1], a[2], a[3])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_fresnel_schlick(float,float,float)", F, (dom::cosine(), dom::unit(), dom::unit()), 1,
                  o[0] = rk_fresnel_schlick(a[0], a[1], a[2]);),
        RK_PARITY("rk_fresnel_schlick(float,vec3,vec3)", F, (dom::cosine(), dom::unit(), dom::unit()), 3,
                  vec3 r = rk_fresnel_schlick(a[0], vec3(a[1], a[2], 0.5f), vec3(a[2], 1.0f, a[1]));
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_fresnel_dielectric_sp", F, (dom::cosine(), dom::eta()), 2,
                  vec2 r = rk_fresnel_dielectric_sp(a[0], a[1]); o[0] = r.x; o[1] = r.y;),
        RK_PARITY("rk_fresnel_dielectric", F, (dom::cosine(), dom::eta()), 1, o[0] = rk_fresnel_dielectric(a[0], a[1]);),
        RK_PARITY("rk_fresnel_fast_params", F, (dom::eta()), 3,
                  vec3 r = rk_fresnel_fast_params(a[0]); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_fresnel_dielectric_fast(float,vec3)", F, (dom::cosine(), dom::eta()), 1,
                  o[0] = rk_fresnel_dielectric_fast(a[0], rk_fresnel_fast_params(a[1]));),
        RK_PARITY("rk_fresnel_dielectric_fast(float,float)", F, (dom::cosine(), dom::eta()), 1,
                  o[0] = rk_fresnel_dielectric_fast(a[0], a[1]);),
        // Constants of rk_fresnel_poly_params(1.52) (a C++-only helper), then arbitrary constants.
        RK_PARITY("rk_fresnel_dielectric_poly(glass)", F, (dom::cosine()), 1,
                  o[0] = rk_fresnel_dielectric_poly(a[0], vec4(0.04258f, 0.954106f, -4.5249f, 10.1282f),
                                                    vec2(-11.4591f, 5.03045f));),
        RK_PARITY("rk_fresnel_dielectric_poly", F,
                  (dom::cosine(), dom::unit(), dom::range(-20.0f, 20.0f), dom::range(-20.0f, 20.0f),
                   dom::range(-20.0f, 20.0f), dom::range(-20.0f, 20.0f), dom::range(-20.0f, 20.0f)), 1,
                  o[0] = rk_fresnel_dielectric_poly(a[0], vec4(a[1], a[2], a[3], a[4]), vec2(a[5], a[6]));),
        RK_PARITY("rk_fresnel_conductor(float,vec3,vec3)", F,
                  (dom::cosine(), dom::range(0.05f, 4.0f), dom::range(0.0f, 8.0f), dom::range(0.05f, 4.0f), dom::range(0.0f, 8.0f)), 3,
                  vec3 r = rk_fresnel_conductor(a[0], vec3(a[1], a[3], 1.0f), vec3(a[2], a[4], 0.0f));
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_fresnel_conductor(float,float,float)", F, (dom::cosine(), dom::range(0.05f, 4.0f), dom::range(0.0f, 8.0f)), 1,
                  o[0] = rk_fresnel_conductor(a[0], a[1], a[2]);),
        RK_PARITY("rk_critical_cos", F, (dom::eta()), 1, o[0] = rk_critical_cos(a[0]);),
        RK_PARITY("rk_critical_angle", F, (dom::eta()), 1, o[0] = rk_critical_angle(a[0]);),
        RK_PARITY("rk_brewster_angle", F, (dom::eta()), 1, o[0] = rk_brewster_angle(a[0]);),
        RK_PARITY("rk_refract", F,
                  (dom::signed_unit(), dom::signed_unit(), dom::signed_unit(), dom::signed_unit(), dom::signed_unit(), dom::eta()), 4,
                  vec3 d = vec3(a[0], a[1], -abs(a[2]) - 0.001f);
                  vec3 n = vec3(0.3f * a[3], 0.3f * a[4], 1.0f);
                  d = normalize(d); n = normalize(n); vec3 t = vec3(0.0f);
                  bool refracted = rk_refract(d, n, a[5], t);
                  o[0] = refracted ? 1.0f : 0.0f; o[1] = t.x; o[2] = t.y; o[3] = t.z;),
        RK_PARITY("rk_fresnel_slab", F, (dom::unit()), 1, o[0] = rk_fresnel_slab(a[0]);),
        RK_PARITY("rk_fresnel_slab_sp", F, (dom::unit(), dom::unit()), 1, o[0] = rk_fresnel_slab_sp(vec2(a[0], a[1]));),
        RK_PARITY("rk_fresnel_glazing", F, (dom::unit(), dom::range(0.0f, 8.0f)), 1, o[0] = rk_fresnel_glazing(a[0], a[1]);),
        RK_PARITY("rk_fresnel_glazing_sp", F, (dom::unit(), dom::unit(), dom::range(0.0f, 8.0f)), 1,
                  o[0] = rk_fresnel_glazing_sp(vec2(a[0], a[1]), a[2]);),
        RK_PARITY("rk_fresnel_window", F, (dom::cosine(), dom::eta(), dom::range(1.0f, 4.0f)), 1,
                  o[0] = rk_fresnel_window(a[0], a[1], a[2]);),
    };
    // Inverse trigonometry is implementation-defined in GLSL (llvmpipe's atan: 3.3e-6 rad off);
    // refraction inherits the driver's sqrt/division and denormal flushing (6.7e-6 seen).
    for (parity::Case& c : cases) {
        if (c.name == "rk_fresnel_window") c.tie = parity::hw_glazing_tie();  // mode 3: the glazing sum
        // Constants whose Horner terms overflow float: the documented result is only "in [0, 1]"
        // (a driver's fused multiply-adds overflow elsewhere than the C++ build's products).
        if (c.name == "rk_fresnel_dielectric_poly")
            c.tie = [](const float* in, const float* g, const float*) {
                const double cs = std::min(std::max(static_cast<double>(in[0]), 0.0), 1.0);
                double q = in[6], big = std::abs(q);
                for (int k : {5, 4, 3, 2}) {
                    q = in[k] + cs * q;
                    big = std::max(big, std::abs(q));
                }
                big = std::max(big, std::abs(in[1] + (1.0 - cs) * q));
                return big > 1e37 && g[0] >= 0.0f && g[0] <= 1.0f;
            };
        if (c.name == "rk_critical_angle" || c.name == "rk_brewster_angle") c.abs_tol = 1e-5;
        if (c.name == "rk_refract") c.abs_tol = 1e-5;
    }
    return cases;
}

}  // namespace

TEST(GpuParity, Fresnel)
{
    long rows = 0;
    for (const parity::Case& c : fresnel_cases()) {
        const parity::Result r = parity::run(c, parity::shader_dir());
        rows += r.rows;
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
    std::printf("[parity] %ld input rows in total\n", rows);
}

TEST(GpuParity, FresnelWindowModes)
{
    // The compile-time switch selects the documented model in the shader as in C++.
    auto expect = [](int mode, float c, float eta, float panes) {
        const vec2 sp = rk_fresnel_dielectric_sp(c, eta);
        switch (mode) {
        case 0: return 0.5f * (sp.x + sp.y);
        case 1: return rk_fresnel_slab(0.5f * (sp.x + sp.y));
        case 2: return rk_fresnel_slab_sp(sp);
        default: return rk_fresnel_glazing_sp(sp, panes);
        }
    };
    for (int mode = 0; mode < 4; ++mode) {
        parity::Case c{"rk_fresnel_window mode " + std::to_string(mode), "raykit/fresnel.glsl",
                       {dom::cosine(), dom::eta(), dom::range(1.0f, 4.0f)}, 1,
                       "o[0] = rk_fresnel_window(a[0], a[1], a[2]);",
                       [mode, expect](const float* a, float* o) { o[0] = expect(mode, a[0], a[1], a[2]); },
                       2e-6, 2e-5, {{"RK_FRESNEL_WINDOW_MODE", std::to_string(mode)}}, true, {}};
        if (mode == 3) c.tie = parity::hw_glazing_tie();
        const parity::Result r = parity::run(c, parity::shader_dir(), 2048);
        EXPECT_TRUE(r.ok) << c.name << ": worst " << r.worst;
    }
}


// An adversarial sample on the driver: 4096 rows per function from tests/adversarial.hpp's stream
// (the CPU sweeps of tests/test_adversarial.cpp, >= 1e5 rows each, use the same generator); every
// GPU output must be finite and inside the function's documented range. Finite inputs only (GLSL
// does not require NaN or Inf); denormals are kept: a driver that flushes them reads ±0, inside
// every domain here. Angles may exceed pi/2 by the driver's atan error (documented: 4e-6 rad on
// llvmpipe). Inputs: a[0] cos_i, a[1] eta, a[2], a[3] reflectances / F0, F90 / k, a[4] panes.
TEST(GpuParity, FresnelAdversarialRanges)
{
    using rktest::adv::Floats;
    const Floats cosine = Floats::any().mark({0.0f, 1.0f, 0.7597469f});
    const Floats eta = Floats::any().mark({1.0f, 1.52f, 1.0f / 1.52f, RK_FRESNEL_ETA_MIN, RK_FRESNEL_ETA_MAX});
    const Floats panes = Floats::any().mark({0.0f, 1.0f, 2.0f, 1e6f});
    auto draw = [&](rktest::adv::Gen& g, float* a) {
        a[0] = g.f(cosine);
        a[1] = g.f(eta);
        a[2] = g.f(Floats::any());
        a[3] = g.f(Floats::any());
        a[4] = g.f(panes);
    };
    auto in = [](float lo, float hi) { return [lo, hi](int, float v) { return v >= lo && v <= hi; }; };
    const auto unit = in(0.0f, 1.0f);
    const auto angle = in(0.0f, RK_HALF_PI + 4e-6f);
    const char* F = "raykit/fresnel.glsl";
    const Domain d = dom::unit();
#define RK_ADV_FRESNEL(NAME, NOUT, ...) RK_PARITY(NAME, F, (d, d, d, d, d), NOUT, __VA_ARGS__)
    const std::vector<std::pair<parity::Case, std::function<bool(int, float)>>> cases = {
        {RK_ADV_FRESNEL("rk_fresnel_clamp_eta", 1, o[0] = rk_fresnel_clamp_eta(a[1]);), in(RK_FRESNEL_ETA_MIN, RK_FRESNEL_ETA_MAX)},
        {RK_ADV_FRESNEL("rk_f0_from_ior", 1, o[0] = rk_f0_from_ior(a[1], a[2]);), unit},
        {RK_ADV_FRESNEL("rk_f0_from_eta", 1, o[0] = rk_f0_from_eta(a[1]);), unit},
        {RK_ADV_FRESNEL("rk_eta_from_f0", 1, o[0] = rk_eta_from_f0(a[2]);), in(1.0f, 4.1e6f)},
        {RK_ADV_FRESNEL("rk_fresnel_schlick(float,float)", 1, o[0] = rk_fresnel_schlick(a[0], a[2]);), unit},
        {RK_ADV_FRESNEL("rk_fresnel_schlick(float,vec3)", 3,
                        vec3 r = rk_fresnel_schlick(a[0], vec3(a[2], a[3], a[1])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
         unit},
        {RK_ADV_FRESNEL("rk_fresnel_schlick(float,float,float)", 1, o[0] = rk_fresnel_schlick(a[0], a[2], a[3]);), unit},
        {RK_ADV_FRESNEL("rk_fresnel_schlick(float,vec3,vec3)", 3,
                        vec3 r = rk_fresnel_schlick(a[0], vec3(a[2], a[3], a[1]), vec3(a[3], a[1], a[2])); o[0] = r.x; o[1] = r.y;
                        o[2] = r.z;),
         unit},
        {RK_ADV_FRESNEL("rk_fresnel_dielectric_sp", 2, vec2 r = rk_fresnel_dielectric_sp(a[0], a[1]); o[0] = r.x; o[1] = r.y;), unit},
        {RK_ADV_FRESNEL("rk_fresnel_dielectric", 1, o[0] = rk_fresnel_dielectric(a[0], a[1]);), unit},
        {RK_ADV_FRESNEL("rk_fresnel_dielectric_fast(float,vec3)", 1,
                        o[0] = rk_fresnel_dielectric_fast(a[0], rk_fresnel_fast_params(a[1]));),
         unit},
        {RK_ADV_FRESNEL("rk_fresnel_dielectric_fast(float,float)", 1, o[0] = rk_fresnel_dielectric_fast(a[0], a[1]);), unit},
        {RK_ADV_FRESNEL("rk_fresnel_dielectric_poly", 1,
                        o[0] = rk_fresnel_dielectric_poly(a[0], vec4(a[1], a[2], a[3], a[4]), vec2(a[4], a[2]));),
         unit},
        {RK_ADV_FRESNEL("rk_fresnel_conductor(float,vec3,vec3)", 3,
                        vec3 r = rk_fresnel_conductor(a[0], vec3(a[1], a[2], a[3]), vec3(a[3], a[1], a[2])); o[0] = r.x; o[1] = r.y;
                        o[2] = r.z;),
         unit},
        {RK_ADV_FRESNEL("rk_fresnel_conductor(float,float,float)", 1, o[0] = rk_fresnel_conductor(a[0], a[1], a[2]);), unit},
        {RK_ADV_FRESNEL("rk_critical_cos", 1, o[0] = rk_critical_cos(a[1]);), unit},
        {RK_ADV_FRESNEL("rk_critical_angle", 1, o[0] = rk_critical_angle(a[1]);), angle},
        {RK_ADV_FRESNEL("rk_brewster_angle", 1, o[0] = rk_brewster_angle(a[1]);), angle},
        {RK_ADV_FRESNEL("rk_fresnel_slab", 1, o[0] = rk_fresnel_slab(a[2]);), unit},
        {RK_ADV_FRESNEL("rk_fresnel_slab_sp", 1, o[0] = rk_fresnel_slab_sp(vec2(a[2], a[3]));), unit},
        {RK_ADV_FRESNEL("rk_fresnel_glazing", 1, o[0] = rk_fresnel_glazing(a[2], a[4]);), unit},
        {RK_ADV_FRESNEL("rk_fresnel_glazing_sp", 1, o[0] = rk_fresnel_glazing_sp(vec2(a[2], a[3]), a[4]);), unit},
        {RK_ADV_FRESNEL("rk_fresnel_window", 1, o[0] = rk_fresnel_window(a[0], a[1], a[4]);), unit},
    };
#undef RK_ADV_FRESNEL
    long bad = 0;
    for (const auto& [c, ok] : cases) bad += parity::run_adversarial(c, parity::shader_dir(), 4096, draw, ok);
    // rk_refract: vectors with components up to 1e15 in magnitude (its domain) give finite outputs.
    parity::Case refract = RK_PARITY("rk_refract", F, (d, d, d, d, d, d, d), 4,
                                     vec3 t = vec3(0.0f); bool refracted = rk_refract(vec3(a[0], a[1], a[2]), vec3(a[3], a[4], a[5]), a[6], t);
                                     o[0] = refracted ? 1.0f : 0.0f; o[1] = t.x; o[2] = t.y; o[3] = t.z;);
    const rktest::adv::Vecs lim = rktest::adv::Vecs::of(Floats::range(-1e15f, 1e15f));
    bad += parity::run_adversarial(
        refract, parity::shader_dir(), 4096,
        [&](rktest::adv::Gen& g, float* a) {
            const vec3 i = g.v3(lim), n = g.v3(lim);
            a[0] = i.x, a[1] = i.y, a[2] = i.z, a[3] = n.x, a[4] = n.y, a[5] = n.z;
            a[6] = g.f(eta);
        },
        [](int, float) { return true; });
    EXPECT_EQ(bad, 0);
}
