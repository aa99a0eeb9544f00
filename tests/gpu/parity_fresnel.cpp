// GPU parity cases for shaders/raykit/common.glsl and fresnel.glsl (see parity.hpp).
#include <gtest/gtest.h>

#include <string>

#include "parity.hpp"
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
                       2e-6, 2e-5, {{"RK_FRESNEL_WINDOW_MODE", std::to_string(mode)}}};
        const parity::Result r = parity::run(c, parity::shader_dir(), 2048);
        EXPECT_TRUE(r.ok) << c.name << ": worst " << r.worst;
    }
}

