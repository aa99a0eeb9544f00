// The probe of tests/test_odr.cpp: every translation unit of test_odr (test_odr.cpp with the
// defaults, tests/parts/test_odr/*.cpp with other values) expands RK_ODR_PROBE_BODY after setting
// its macros. Each check calls one macro-configured function (the C++ build of a shared .glsl that
// lives in an RK_CONFIGURED_BEGIN inline namespace, or a whole svo_* file wrapped in one) and
// computes, independently, what that translation unit's configuration must give: a direct formula
// or macro-free functions (namespace odr below), picked at run time from the macro values the
// translation unit was compiled with. Each check records those values (as written), so the test
// knows which translation units differ in which macro.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "raykit/interior_compose.hpp"
#include "raykit/lightshafts.hpp"
#include "raykit/relief.hpp"
#include "raykit/shadow_filter.hpp"
#include "raykit/ssao.hpp"
#include "raykit/svo_secondary.hpp"
#include "raykit/tonemap.hpp"
#include "raykit/volume.hpp"
#include "svo_test_pack.hpp"

/// One configured function on fixed inputs.
struct OdrCheck {
    std::string name;
    /// The option macros the function's result depends on, with their values in this translation
    /// unit (as the preprocessor spells them).
    std::vector<std::pair<std::string, std::string>> macros;
    std::vector<float> got, want;
    float tol = 0.0f;  ///< |got - want| allowed per component (0: bit-exact)
};
using OdrProbe = std::vector<OdrCheck>;

namespace odr {
inline std::vector<float> v(float x) { return {x}; }
inline std::vector<float> v(glm::vec3 x) { return {x.x, x.y, x.z}; }

inline raykit::rk_im_grid grid()
{
    raykit::rk_im_grid g;
    g.room_size = glm::vec3(4.0f, 3.0f, 4.0f);
    g.origin = glm::vec3(0.0f);
    return g;
}
// The inputs of the tone map, window and trace checks.
const glm::vec3 kHdr(2.0f, 1.0f, 0.5f);
const glm::vec3 kP(2.3f, 1.7f, 0.0f), kCam(5.0f, 2.5f, 9.0f), kN(0.0f, 0.0f, 1.0f), kJitter(0.4f, 0.0f, 0.4f);
const glm::vec3 kInterior(0.2f, 0.3f, 0.4f), kReflection(0.9f, 0.8f, 0.7f), kTint(0.9f);

// Macro-free twins, chosen by value (what each configured function's #if selects).
inline glm::vec3 tonemap(glm::vec3 rgb, float white, int op, int look)
{
    using namespace raykit;
    switch (op) {
    case 0: return glm::clamp(rk_hdr_sanitize(rgb), glm::vec3(0.0f), glm::vec3(1.0f));
    case 1: return rk_tonemap_reinhard(rgb, white);
    case 2: return rk_aces_narkowicz(rgb);
    case 3: return rk_aces_hill(rgb);
    case 4: return rk_agx(rgb, look);
    case 5: return rk_pbr_neutral(rgb);
    case 6: return rk_hable(rgb);
    case 7: return rk_lottes(rgb);
    default: return rk_uchimura(rgb);
    }
}
inline float fresnel_window(float c, float eta, float panes, int mode)
{
    using namespace raykit;
    switch (mode) {
    case 0: return rk_fresnel_dielectric(c, eta);
    case 1: return rk_fresnel_slab(rk_fresnel_dielectric(c, eta));
    case 2: return rk_fresnel_slab_sp(rk_fresnel_dielectric_sp(c, eta));
    default: return rk_fresnel_glazing_sp(rk_fresnel_dielectric_sp(c, eta), panes);
    }
}
inline float glass(float c, float eta, float panes, int fast, int mode)
{
    return fast == 1 ? raykit::rk_window_glass_reflectance_fast(c, raykit::rk_fresnel_fast_params(eta), panes)
                     : fresnel_window(c, eta, panes, mode);
}
inline glm::vec3 window(glm::vec3 interior, glm::vec3 reflection, float c, glm::vec3 tint, float eta, float panes, int compose,
                        int fast, int mode)
{
    using namespace raykit;
    if (compose == 1) return rk_hdr_sanitize(interior) + rk_hdr_sanitize(reflection);
    const float r = rk_saturate(glass(c, eta, panes, fast, mode));
    return r * rk_hdr_sanitize(reflection) + ((1.0f - r) * glm::clamp(tint, glm::vec3(0.0f), glm::vec3(1.0f))) * rk_hdr_sanitize(interior);
}

// The facade z = 0 of rooms 1 unit deep whose walls of constant z lie at z = -0.125 - k, seen
// head-on from z = 5 (x and y are parallel families): the wall 0.125 behind the facade is within
// a nudge of 0.25 (skipped: the room behind it is seen, t = 1 + 1.125 / 5) but not of 2^-10
// (t = 1 + 0.125 / 5).
inline raykit::rk_im_grid nudge_grid()
{
    raykit::rk_im_grid g;
    g.room_size = glm::vec3(1.0f);
    g.origin = glm::vec3(0.5f, 0.5f, -0.125f);
    return g;
}
inline float nudge_t(float nudge) { return 1.0f + (nudge < 0.125f ? 0.125f : 1.125f) / 5.0f; }

// A 1x1 depth map whose linear depth is 1 everywhere (k = (1, 0, 0): reversed-Z window depth 1).
// A kernel point reflected to (0, 0, -1.5) lies 0.5 behind it (a hit); one at x = 50 projects off
// screen (skipped). The first 16 of 64 kernel points are hits: count = 16 / min(n, max).
inline raykit::AoMapCpu ao_depth()
{
    raykit::AoMapCpu m;
    m.width = m.height = 1;
    m.v = {1.0f};
    return m;
}
inline std::vector<glm::vec3> ao_kernel()
{
    std::vector<glm::vec3> k(64, glm::vec3(100.0f, 0.0f, 0.0f));
    for (size_t i = 0; i < 16; ++i) k[i] = glm::vec3(0.0f, 0.0f, 1.0f);
    return k;
}

// A 2x2 occlusion buffer of 1: every light-shaft sample reads 1, so the sum is the sample count.
inline raykit::LsMapCpu ls_ones()
{
    raykit::LsMapCpu m;
    m.width = m.height = 2;
    m.v.assign(4, glm::vec3(1.0f));
    return m;
}

// A density texture of 2 x 1 x 1 texels (0, 1): along the box's x axis the density is 2 u - 0.5 on
// u in [0.25, 0.75]. Marching that part with jitter 0 (left Riemann sum of n steps) gives
// sum_{i<n} (i / n) (0.5 / n) = (n - 1) / (4 n).
inline raykit::VolDensityCpu vol_ramp()
{
    raykit::VolDensityCpu m;
    m.w = 2;
    m.h = m.d = 1;
    m.v = {0.0f, 1.0f};
    return m;
}

// A flat relief map of depth 0.3: the linear search's first layer at or below it is
// ceil(0.3 n) / n of n layers.
inline raykit::ReliefMapCpu relief_flat()
{
    raykit::ReliefMapCpu m;
    m.width = m.height = 2;
    m.texels.assign(4, glm::vec2(0.3f, 0.0f));
    return m;
}

// A 16 x 16 shadow map whose stored depth rises with x (column i: i / 16): a reference of 0.5 is lit
// on the right half. The Vogel filter's lit fraction, written with the macro-free tap positions
// and compares.
inline raykit::ShadowMapCpu sh_ramp()
{
    raykit::ShadowMapCpu m;
    m.width = m.height = 16;
    m.depth.resize(256);
    for (size_t i = 0; i < 256; ++i) m.depth[i] = static_cast<float>(i % 16) / 16.0f;
    return m;
}
inline float sh_vogel(const raykit::ShadowMapCpu& m, glm::vec3 uvz, float radius, unsigned n, float phi)
{
    float sum = 0.0f;
    for (unsigned i = 0; i < n; ++i) {
        const glm::vec2 d = raykit::rk_sh_vogel_disk(i, n, phi);
        sum += raykit::rk_sh_compare(m, glm::vec2(uvz.x + radius * d.x, uvz.y + radius * d.y), uvz.z);
    }
    return sum / static_cast<float>(n);
}

// An octree of depth 3 over [0, 8)^3 (voxels of 1) with three voxels in a row, x = 5..7 at
// (y, z) = (3, 3). The ray from (-1, 3.5, 3.5) along +x enters the root at t = 1 and the first
// voxel at t = 6.
inline raykit::SvoTree svo_row()
{
    svotest::PackOptions o;
    o.root_min = glm::vec3(0.0f);
    o.root_size = 8.0f;
    return svotest::pack_cells(3, {glm::uvec3(5, 3, 3), glm::uvec3(6, 3, 3), glm::uvec3(7, 3, 3)}, o);
}
}  // namespace odr

#define RK_ODR_STR_(x) #x
#define RK_ODR_STR(x) RK_ODR_STR_(x)
/// {"RK_X", value of RK_X}
#define RK_ODR_MACRO(m) std::make_pair(std::string(#m), std::string(RK_ODR_STR(m)))

/// The probe of the calling translation unit's configuration (the body of a function returning
/// OdrProbe).
#define RK_ODR_PROBE_BODY                                                                                               \
    using namespace raykit;                                                                                             \
    OdrProbe r;                                                                                                         \
    r.push_back({"rk_tonemap", {RK_ODR_MACRO(RK_TONEMAP_OPERATOR), RK_ODR_MACRO(RK_AGX_LOOK)},                         \
                 odr::v(rk_tonemap(odr::kHdr, 4.0f)), odr::v(odr::tonemap(odr::kHdr, 4.0f, RK_TONEMAP_OPERATOR, RK_AGX_LOOK)), \
                 0.0f});                                                                                                \
    r.push_back({"rk_fresnel_window", {RK_ODR_MACRO(RK_FRESNEL_WINDOW_MODE)}, odr::v(rk_fresnel_window(0.7f, 1.5f, 2.0f)), \
                 odr::v(odr::fresnel_window(0.7f, 1.5f, 2.0f, RK_FRESNEL_WINDOW_MODE)), 0.0f});                         \
    r.push_back({"rk_window_glass_reflectance", {RK_ODR_MACRO(RK_WINDOW_GLASS_FRESNEL), RK_ODR_MACRO(RK_FRESNEL_WINDOW_MODE)}, \
                 odr::v(rk_window_glass_reflectance(0.7f, 1.5f, 2.0f)),                                                 \
                 odr::v(odr::glass(0.7f, 1.5f, 2.0f, RK_WINDOW_GLASS_FRESNEL, RK_FRESNEL_WINDOW_MODE)), 0.0f});         \
    r.push_back({"rk_im_window",                                                                                        \
                 {RK_ODR_MACRO(RK_IM_COMPOSE_MODE), RK_ODR_MACRO(RK_WINDOW_GLASS_FRESNEL), RK_ODR_MACRO(RK_FRESNEL_WINDOW_MODE)}, \
                 odr::v(rk_im_window(odr::kInterior, odr::kReflection, 0.7f, odr::kTint, 1.5f, 2.0f)),                  \
                 odr::v(odr::window(odr::kInterior, odr::kReflection, 0.7f, odr::kTint, 1.5f, 2.0f, RK_IM_COMPOSE_MODE, \
                                    RK_WINDOW_GLASS_FRESNEL, RK_FRESNEL_WINDOW_MODE)),                                  \
                 0.0f});                                                                                                \
    {                                                                                                                   \
        /* rk_im_trace_auto is one of the two traces of its namespace, as RK_IM_VARYING_WALLS says. */                  \
        const glm::vec3 dx(0.01f, 0.0f, 0.0f), dy(0.0f, 0.01f, 0.0f);                                                   \
        r.push_back({"rk_im_trace_auto", {RK_ODR_MACRO(RK_IM_VARYING_WALLS)},                                           \
                     odr::v(rk_im_trace_auto(odr::kP, odr::kCam, odr::kN, dx, dy, odr::grid(), odr::kJitter, 7u).t),    \
                     odr::v(RK_IM_VARYING_WALLS == 1                                                                    \
                                ? rk_im_trace_varying_grad(odr::kP, odr::kCam, odr::kN, dx, dy, odr::grid(), odr::kJitter, 7u).t \
                                : rk_im_trace_grad(odr::kP, odr::kCam, odr::kN, dx, dy, odr::grid()).t),                \
                     0.0f});                                                                                            \
    }                                                                                                                   \
    r.push_back({"rk_im_trace (nudge)", {RK_ODR_MACRO(RK_IM_NUDGE)},                                                    \
                 odr::v(rk_im_trace(glm::vec3(0.25f, 0.25f, 0.0f), glm::vec3(0.25f, 0.25f, 5.0f), odr::kN, odr::nudge_grid()).t), \
                 odr::v(odr::nudge_t(RK_IM_NUDGE)), 1e-6f});                                                            \
    {                                                                                                                   \
        const AoMapCpu depth = odr::ao_depth();                                                                         \
        std::vector<glm::vec3> kernel = odr::ao_kernel();                                                               \
        r.push_back({"rk_ao_sphere_count", {RK_ODR_MACRO(RK_AO_MAX_SAMPLES)},                                           \
                     odr::v(rk_ao_sphere_count(depth, glm::vec3(0.0f, 0.0f, -1.0f), 0.5f, kernel.data(), 64u,            \
                                               glm::vec3(0.0f, 0.0f, 1.0f), 0.01f, false, glm::vec3(1.0f, 0.0f, 0.0f),   \
                                               glm::vec4(1.0f, 1.0f, 0.0f, 0.0f), glm::vec4(1.0f, 1.0f, 0.0f, 0.0f))),   \
                     odr::v(16.0f / static_cast<float>(std::min(64, RK_AO_MAX_SAMPLES))), 0.0f});                       \
    }                                                                                                                   \
    r.push_back({"rk_ls_accumulate", {RK_ODR_MACRO(RK_LS_MAX_SAMPLES)},                                                 \
                 odr::v(rk_ls_accumulate(odr::ls_ones(), glm::vec2(0.8f, 0.5f), glm::vec2(0.2f, 0.5f), 100u, 0.5f, 1.0f, \
                                         1.0f, 1.0f)),                                                                  \
                 odr::v(glm::vec3(static_cast<float>(std::min(100, RK_LS_MAX_SAMPLES)))), 0.0f});                       \
    {                                                                                                                   \
        const float n = static_cast<float>(std::min(64, RK_VOL_MAX_STEPS));                                             \
        r.push_back({"rk_vol_march_box", {RK_ODR_MACRO(RK_VOL_MAX_STEPS)},                                              \
                     odr::v(rk_vol_march_box(odr::vol_ramp(), glm::vec3(-1.0f, 0.5f, 0.5f), glm::vec3(1.0f, 0.0f, 0.0f), \
                                             glm::vec3(0.0f), glm::vec3(1.0f), 1.25f, 1.75f, 1.0f, 64u, 0.0f)),          \
                     odr::v((n - 1.0f) / (4.0f * n)), 1e-6f});                                                          \
    }                                                                                                                   \
    {                                                                                                                   \
        const double n = std::min(64, RK_RELIEF_MAX_STEPS);                                                             \
        r.push_back({"rk_relief_linear", {RK_ODR_MACRO(RK_RELIEF_MAX_STEPS)},                                           \
                     odr::v(rk_relief_linear(odr::relief_flat(), glm::vec2(0.5f), glm::vec2(0.0f), 64u).z),              \
                     odr::v(static_cast<float>(std::ceil(0.3 * n) / n)), 0.0f});                                        \
    }                                                                                                                   \
    r.push_back({"rk_sh_blocks", {RK_ODR_MACRO(RK_SH_REVERSED_Z)}, odr::v(rk_sh_blocks(0.3f, 0.5f) ? 1.0f : 0.0f),      \
                 odr::v(RK_SH_REVERSED_Z == 1 ? 0.0f : 1.0f), 0.0f});                                                   \
    {                                                                                                                   \
        const ShadowMapCpu m = odr::sh_ramp();                                                                          \
        const glm::vec3 uvz(0.5f, 0.5f, 0.5f);                                                                          \
        r.push_back({"rk_sh_pcf_vogel", {RK_ODR_MACRO(RK_SH_MAX_TAPS)}, odr::v(rk_sh_pcf_vogel(m, uvz, 0.3f, 64u, 0.4f)), \
                     odr::v(odr::sh_vogel(m, uvz, 0.3f, static_cast<unsigned>(std::min(64, RK_SH_MAX_TAPS)), 0.4f)),    \
                     1e-6f});                                                                                           \
    }                                                                                                                   \
    /* svo_format.hpp: a default argument is the caller's, so each translation unit passes its own. */                  \
    r.push_back({"svo_texture_extent", {RK_ODR_MACRO(RK_SVO_TEXTURE_WIDTH)},                                            \
                 {static_cast<float>(svo_texture_extent(5000).x), static_cast<float>(svo_texture_extent(5000).y)},      \
                 {static_cast<float>(RK_SVO_TEXTURE_WIDTH),                                                             \
                  static_cast<float>((5000 + RK_SVO_TEXTURE_WIDTH - 1) / RK_SVO_TEXTURE_WIDTH)},                        \
                 0.0f});                                                                                                \
    {                                                                                                                   \
        const SvoTree t = odr::svo_row();                                                                               \
        const std::vector<uint32_t> words = t.gpu_words();                                                              \
        const rk_svo_tree tree = svo_trace_tree(t);                                                                     \
        const glm::vec3 o(-1.0f, 3.5f, 3.5f), d(1.0f, 0.0f, 0.0f);                                                      \
        /* No cone: full detail. A voxel is 3 levels down, one push per level: fewer iterations cannot reach it. */     \
        const rk_svo_trace_hit h0 = rk_svo_trace(words.data(), tree, o, d, 100.0f, glm::vec2(0.0f));                    \
        const bool reach = RK_SVO_TRAVERSE_MAX_ITER == 0 || RK_SVO_TRAVERSE_MAX_ITER >= 3;                               \
        r.push_back({"rk_svo_trace (no cone)", {RK_ODR_MACRO(RK_SVO_TRAVERSE_MAX_ITER)},                                \
                     {h0.hit ? 1.0f : 0.0f, h0.hit ? h0.t : -1.0f, h0.hit ? static_cast<float>(h0.level) : -1.0f},       \
                     {reach ? 1.0f : 0.0f, reach ? 6.0f : -1.0f, reach ? 3.0f : -1.0f}, 1e-5f});                        \
        /* A cone wider than the root: the level-of-detail build stops at the root (t = 1). */                          \
        const rk_svo_trace_hit h1 = rk_svo_trace(words.data(), tree, o, d, 100.0f, glm::vec2(100.0f, 0.0f));            \
        const bool lod = RK_SVO_TRAVERSE_LOD == 1, hit1 = lod || reach;                                                 \
        r.push_back({"rk_svo_trace (wide cone)", {RK_ODR_MACRO(RK_SVO_TRAVERSE_LOD), RK_ODR_MACRO(RK_SVO_TRAVERSE_MAX_ITER)}, \
                     {h1.hit ? 1.0f : 0.0f, h1.hit ? h1.t : -1.0f, h1.hit ? static_cast<float>(h1.level) : -1.0f},       \
                     {hit1 ? 1.0f : 0.0f, hit1 ? (lod ? 1.0f : 6.0f) : -1.0f, hit1 ? (lod ? 0.0f : 3.0f) : -1.0f}, 1e-5f}); \
        /* The medium march through the row (absorption 0.5 per unit, index 1 inside and out: no */                     \
        /* interface): 3 voxels crossed, transmittance exp(-0.5 * 3) with absorption. */                                \
        const std::vector<uint32_t> ids(512, 0u);                                                                       \
        const std::vector<glm::vec4> media = {glm::vec4(1.0f, 0.5f, 0.5f, 0.5f)};                                       \
        const rk_svo_media_ref mref{ids.data(), media.data()};                                                          \
        const rk_svo_march_result m = rk_svo_march(words.data(), tree, mref, glm::vec3(5.0f, 3.5f, 3.5f), d,            \
                                                   glm::uvec3(5, 3, 3), 1.0f, glm::vec3(0.5f), 1.0f);                   \
        const float steps = static_cast<float>(std::min(3, RK_SVO_SECONDARY_MAX_STEPS));                                \
        r.push_back({"rk_svo_march", {RK_ODR_MACRO(RK_SVO_SECONDARY_ABSORPTION), RK_ODR_MACRO(RK_SVO_SECONDARY_MAX_STEPS)}, \
                     {m.left ? 1.0f : 0.0f, static_cast<float>(m.steps), m.path, m.transmittance.x},                    \
                     {steps >= 3.0f ? 1.0f : 0.0f, steps, steps,                                                        \
                      RK_SVO_SECONDARY_ABSORPTION == 1 ? std::exp(-0.5f * steps) : 1.0f},                               \
                     1e-6f});                                                                                           \
    }                                                                                                                   \
    {                                                                                                                   \
        /* 0.6, -0.8 onto the normal (0, 1, 0): cos 0.8, from index 1 into 1.5. */                                      \
        const rk_svo_interface f = rk_svo_interface_at(glm::vec3(0.6f, -0.8f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f), 1.0f, 1.5f); \
        r.push_back({"rk_svo_interface_at", {RK_ODR_MACRO(RK_SVO_SECONDARY_FRESNEL_FAST)}, odr::v(f.reflectance),       \
                     odr::v(RK_SVO_SECONDARY_FRESNEL_FAST == 1 ? rk_fresnel_dielectric_fast(0.8f, rk_fresnel_fast_params(1.5f)) \
                                                              : rk_fresnel_dielectric(0.8f, 1.5f)),                     \
                     1e-6f});                                                                                           \
    }                                                                                                                   \
    return r;
