// GPU parity for shaders/raykit/interior_furniture.glsl and interior_compose.glsl (see parity.hpp),
// plus a smoke test of the complete material samples/common/interior_building.{vert,frag}: every
// documented macro combination compiles and links on the driver and renders a building quad into an
// RGBA32F target with no NaN/Inf, a window pixel showing the interior and an opaque pixel the exterior.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "parity.hpp"
#include "raykit/interior_compose.hpp"
#include "raykit/interior_features.hpp"
#include "raykit/gpu_layout.hpp"
#include "raykit/interior_furniture.hpp"
#include "raykit/interior_params.hpp"
#include "raykit/interior_surface.hpp"
#include "raykit/shader_source.hpp"

using namespace raykit;
using parity::Domain;
namespace dom = parity::dom;

namespace {

// Input domains: object-space coordinates, depths, room sizes (with grazing/degenerate specials).
Domain coord() { return {-60.0f, 60.0f, false, {0.0f, 4.0f, -4.0f, 100.0f, -100.0f}}; }
Domain depth() { return {0.0f, 6.0f, false, {0.0f, 1.0f}}; }
Domain size() { return {0.5f, 8.0f, false, {1e-4f, 3.0f}}; }
Domain big() { return {-1e4f, 1e4f, false, {}}; }
Domain colour() { return {0.0f, 4.0f, false, {0.0f, 1.0f, 65504.0f}}; }

// The furniture cases map the parity harness's raw inputs (adversarial values included) into the
// documented domain the same way in both languages: clamp coordinates to +-100 (the adversarial
// extremes become the edge of the box), and output the wrapped uv as two triangle waves (continuous
// across the wrap seam, where a one-ulp difference would flip 0 <-> 0.99999994). t, pos, uv and
// derivatives are compared where the problem is well conditioned (t < 20, |grid coordinate| < 1000
// rooms): near grazing, t = 1 + D / |dot(n, p - cam)| amplifies the rounding of the dot product
// (which a GPU may fuse) without bound, in any implementation; validity (and t >= 20) is compared
// everywhere. The room index is reported only away from cell boundaries (within 1e-3 + 1e-5 |q|
// rooms it is -9999 on both sides).
#define RK_FURN_SETUP                                                                                          \
    vec3 p = clamp(vec3(a[0], a[1], a[2]), vec3(-100.0f), vec3(100.0f));                                       \
    vec3 cam = p + clamp(vec3(a[3], a[4], a[5]), vec3(-100.0f), vec3(100.0f));                                 \
    vec3 n = clamp(vec3(a[6], a[7], 1.0f), vec3(-100.0f), vec3(100.0f));                                       \
    vec3 tn = vec3(1.0f, 0.0f, -n.x);                                                                          \
    vec3 bn = vec3(0.0f, 1.0f, -n.y);                                                                          \
    rk_im_grid g;                                                                                              \
    g.room_size = vec3(clamp(a[9], 1e-4f, 10.0f), 3.0f, clamp(a[10], 1e-4f, 10.0f));                           \
    g.origin = vec3(0.25f, -0.5f, 0.125f);                                                                     \
    float D = clamp(a[8], -1.0f, 10.0f);

#define RK_FURN_OUT(h)                                                                                         \
    {                                                                                                          \
        vec3 gq = rk_im_grid_coord(h.pos, g);                                                                  \
        bool ok = h.valid && h.t < 20.0f && max(max(abs(gq.x), abs(gq.y)), abs(gq.z)) < 1000.0f;               \
        vec3 fr = abs(gq - floor(gq + vec3(0.5f)));                                                            \
        vec3 tol = vec3(1e-3f) + abs(gq) * 1e-5f;                                                              \
        bool near_plane = !ok || fr.x < tol.x || fr.y < tol.y || fr.z < tol.z;                                 \
        o[0] = h.valid ? 1.0f : 0.0f;                                                                          \
        o[1] = ok ? h.t : 0.0f;                                                                                \
        o[2] = ok ? min(h.uv.x, 1.0f - h.uv.x) : 0.0f;                                                         \
        o[3] = ok ? min(fract(h.uv.x + 0.25f), 1.0f - fract(h.uv.x + 0.25f)) : 0.0f;                          \
        o[4] = ok ? min(h.uv.y, 1.0f - h.uv.y) : 0.0f;                                                         \
        o[5] = ok ? min(fract(h.uv.y + 0.25f), 1.0f - fract(h.uv.y + 0.25f)) : 0.0f;                          \
        o[6] = ok ? h.uv_dx.x : 0.0f;                                                                          \
        o[7] = ok ? h.uv_dx.y : 0.0f;                                                                          \
        o[8] = ok ? h.uv_dy.x : 0.0f;                                                                          \
        o[9] = ok ? h.uv_dy.y : 0.0f;                                                                          \
        o[10] = ok ? h.pos.x : 0.0f;                                                                           \
        o[11] = ok ? h.pos.y : 0.0f;                                                                           \
        o[12] = ok ? h.pos.z : 0.0f;                                                                           \
        o[13] = near_plane ? -9999.0f : float(h.room.x);                                                       \
        o[14] = near_plane ? -9999.0f : float(h.room.y);                                                       \
        o[15] = near_plane ? -9999.0f : float(h.room.z);                                                       \
        o[16] = h.valid && h.t >= 20.0f ? 1.0f : 0.0f;                                                         \
    }

#define RK_FURN_STR(...) #__VA_ARGS__
#define RK_FURN_XSTR(...) RK_FURN_STR(__VA_ARGS__)

std::vector<parity::Case> interior_shading_cases()
{
    const char* F = "raykit/interior_furniture.glsl";
    const char* C = "raykit/interior_compose.glsl";
    const std::vector<Domain> furn_in = {coord(), coord(), coord(), coord(), coord(), coord(),
                                         dom::signed_unit(), dom::signed_unit(), depth(), size(), size()};
    std::vector<parity::Case> cases = {
        // ---- interior_params.glsl: the defaults of the material's parameter structs (constants, so
        // the input only varies which fields are read).
        RK_PARITY("rk_im_*_default", "raykit/interior_params.glsl", (dom::unit()), 12,
                  rk_im_window_params p = rk_im_window_params_default();
                  rk_im_building_frame fr = rk_im_building_frame_default();
                  rk_im_building_vertex v = rk_im_building_vertex_default();
                  int k = int(clamp(a[0], 0.0f, 1.0f) * 2.99f);  // 0..2 for every (finite) input
                  o[0] = p.grid.room_size[k]; o[1] = p.atlas[k]; o[2] = p.light_warm[k]; o[3] = p.glass_tint[k];
                  o[4] = float(p.seed) + float(p.flipbook[k]) + p.furniture_depth[k]; o[5] = p.unlit + p.glass_eta;
                  o[6] = fr.facade_color[k]; o[7] = fr.sky_color[k]; o[8] = fr.reinhard_white + fr.exposure;
                  o[9] = v.sun_dir[k]; o[10] = v.ambient[k]; o[11] = v.clip_from_world[k][k] + v.uv_scale.x;),
        // ---- interior_furniture.glsl
        RK_PARITY("rk_im_furniture_unit", F, (big(), big(), big()), 3,
                  vec3 u = rk_im_furniture_unit(vec3(a[0], a[1], a[2]), vec3(0.0f, 0.0f, 1.0f));
                  o[0] = u.x; o[1] = u.y; o[2] = u.z;),
        RK_PARITY("rk_im_furniture_clamp_coord", F, (big(), big(), big()), 3,
                  vec3 u = rk_im_furniture_clamp_coord(vec3(a[0], a[1], a[2]) * 1e12f);
                  o[0] = u.x; o[1] = u.y; o[2] = u.z;),
        RK_PARITY("rk_im_furniture_wrap", F, (dom::range(-20.0f, 20.0f)), 2,
                  float w = rk_im_furniture_wrap(clamp(a[0], -1e6f, 1e6f));
                  o[0] = min(w, 1.0f - w); o[1] = min(fract(w + 0.25f), 1.0f - fract(w + 0.25f));),
        parity::Case{"rk_im_furniture_plane_grad", F, furn_in, 17, "", nullptr, 2e-6, 2e-5, {}, true, {}},
        parity::Case{"rk_im_furniture_plane", F, furn_in, 17, "", nullptr, 2e-6, 2e-5, {}, true, {}},
        RK_PARITY("rk_im_furniture_visible", F, (depth(), dom::range(0.5f, 8.0f), dom::unit(), dom::unit()), 1,
                  rk_im_grid g; g.room_size = vec3(3.0f); g.origin = vec3(0.0f);
                  rk_im_furniture_hit f = rk_im_furniture_plane(vec3(1.0f, 1.0f, 0.0f), vec3(0.3f, 1.7f, 4.0f),
                                                                vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 0.0f),
                                                                vec3(0.0f, 1.0f, 0.0f), a[0], g);
                  o[0] = rk_im_furniture_visible(f, a[1], a[2], a[3]) ? 1.0f : 0.0f;),
        RK_PARITY("rk_im_furniture_take", F, (depth(), depth(), dom::unit(), dom::unit(), dom::range(1.0f, 4.0f)), 3,
                  rk_im_grid g; g.room_size = vec3(3.0f); g.origin = vec3(0.0f);
                  float nearest = a[4];
                  rk_im_furniture_hit f0 = rk_im_furniture_plane(vec3(1.0f, 1.0f, 0.0f), vec3(0.3f, 1.7f, 4.0f),
                                                                 vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 0.0f),
                                                                 vec3(0.0f, 1.0f, 0.0f), a[0], g);
                  rk_im_furniture_hit f1 = rk_im_furniture_plane(vec3(1.0f, 1.0f, 0.0f), vec3(0.3f, 1.7f, 4.0f),
                                                                 vec3(0.0f, 0.0f, 1.0f), vec3(1.0f, 0.0f, 0.0f),
                                                                 vec3(0.0f, 1.0f, 0.0f), a[1], g);
                  o[0] = rk_im_furniture_take(f0, a[2], 0.5f, nearest) ? 1.0f : 0.0f;
                  o[1] = rk_im_furniture_take(f1, a[3], 0.5f, nearest) ? 1.0f : 0.0f;
                  o[2] = nearest;),
        RK_PARITY("rk_im_flipbook_frame", F, (dom::range(-1000.0f, 1000.0f), dom::range(0.0f, 60.0f),
                                                 dom::range(1.0f, 64.0f), dom::unit()), 1,
                  o[0] = float(rk_im_flipbook_frame(a[0], a[1], int(clamp(a[2], -1e6f, 1e6f)), a[3]));),
        RK_PARITY("rk_im_flipbook_uv", F, (dom::unit(), dom::unit(), dom::range(0.0f, 80.0f), dom::range(0.0f, 9.0f),
                                              dom::range(0.0f, 9.0f)), 2,
                  vec2 u = rk_im_flipbook_uv(vec2(a[0], a[1]), int(clamp(a[2], -1e6f, 1e6f)), int(clamp(a[3], -1e6f, 1e6f)),
                                             int(clamp(a[4], -1e6f, 1e6f)));
                  o[0] = u.x; o[1] = u.y;),
        RK_PARITY("rk_im_flipbook_room_uv", F, (dom::unit(), dom::unit(), dom::range(-50.0f, 50.0f), dom::range(-100.0f, 100.0f)), 2,
                  ivec3 r = ivec3(int(clamp(a[3], -1e6f, 1e6f)), 2, -3);
                  vec2 u = rk_im_flipbook_room_uv(vec2(a[0], a[1]), r, a[2], 12.0f, 16, 4, 4, 99u);
                  o[0] = u.x; o[1] = u.y;),
        // ---- interior_compose.glsl
        RK_PARITY("rk_im_needs_interior", C, (dom::unit()), 1, o[0] = rk_im_needs_interior(a[0]) ? 1.0f : 0.0f;),
        RK_PARITY("rk_im_window_weight", C, (dom::unit()), 1, o[0] = rk_im_window_weight(a[0]);),
        RK_PARITY("rk_im_window_fresnel", C, (colour(), colour(), dom::cosine(), dom::unit(), dom::eta(), dom::range(1.0f, 3.0f)), 3,
                  vec3 w = rk_im_window_fresnel(vec3(a[0], a[1], 0.5f), vec3(a[1], 0.25f, a[0]), a[2], vec3(a[3], 1.0f, 0.8f), a[4], a[5]);
                  o[0] = w.x; o[1] = w.y; o[2] = w.z;),
        RK_PARITY("rk_im_window_additive", C, (colour(), colour()), 3,
                  vec3 w = rk_im_window_additive(vec3(a[0], a[1], -a[0]), vec3(a[1], 0.25f, a[0]));
                  o[0] = w.x; o[1] = w.y; o[2] = w.z;),
        RK_PARITY("rk_im_window", C, (colour(), colour(), dom::cosine()), 3,
                  vec3 w = rk_im_window(vec3(a[0], 0.5f, 0.25f), vec3(a[1], 0.25f, a[0]), a[2], vec3(0.9f), 1.52f, 1.0f);
                  o[0] = w.x; o[1] = w.y; o[2] = w.z;),
        RK_PARITY("rk_im_compose(vec3,float,vec3)", C, (colour(), colour(), dom::unit()), 3,
                  vec3 w = rk_im_compose(vec3(a[0], a[1], 0.5f), a[2], vec3(a[1], 0.25f, a[0]));
                  o[0] = w.x; o[1] = w.y; o[2] = w.z;),
        RK_PARITY("rk_im_compose(vec4,vec3)", C, (colour(), colour(), dom::unit()), 3,
                  vec3 w = rk_im_compose(vec4(a[0], a[1], 0.5f, a[2]), vec3(a[1], 0.25f, a[0]));
                  o[0] = w.x; o[1] = w.y; o[2] = w.z;),
        RK_PARITY("rk_im_room_light", C, (dom::range(-1000.0f, 1000.0f), dom::range(-1000.0f, 1000.0f), dom::unit(),
                                             colour(), dom::range(0.0f, 4.0f), dom::unit()), 3,
                  ivec3 r = ivec3(int(clamp(a[0], -1e6f, 1e6f)), int(clamp(a[1], -1e6f, 1e6f)), 7);
                  vec3 l = rk_im_room_light(r, a[2], 4242u, vec3(a[3], 0.8f, 0.6f), vec3(0.7f, 0.8f, a[3]),
                                            vec2(0.5f, a[4]), a[5]);
                  o[0] = l.x; o[1] = l.y; o[2] = l.z;),
        RK_PARITY("rk_im_room_lanes", C, (dom::range(-1000.0f, 1000.0f), dom::range(-1000.0f, 1000.0f)), 3,
                  vec3 l = rk_im_room_lanes(ivec3(int(clamp(a[0], -1e6f, 1e6f)), int(clamp(a[1], -1e6f, 1e6f)), -9), 77u);
                  o[0] = l.x; o[1] = l.y; o[2] = l.z;),
        RK_PARITY("rk_im_room_tint", C, (dom::range(-1000.0f, 1000.0f), dom::unit()), 3,
                  vec3 t = rk_im_room_tint(ivec3(int(clamp(a[0], -1e6f, 1e6f)), 3, -4), 17u, a[1]);
                  o[0] = t.x; o[1] = t.y; o[2] = t.z;),
        RK_PARITY("rk_im_fade_weight", C, (dom::range(0.0f, 500.0f), dom::range(0.0f, 300.0f), dom::range(0.0f, 600.0f)), 1,
                  o[0] = rk_im_fade_weight(a[0], a[1], a[2]);),
        RK_PARITY("rk_im_fade_flat", C, (colour(), colour()), 3,
                  vec3 f = rk_im_fade_flat(vec3(a[0], a[1], 0.5f), vec3(a[1], 1.0f, a[0]));
                  o[0] = f.x; o[1] = f.y; o[2] = f.z;),
        RK_PARITY("rk_im_fade", C, (colour(), colour(), dom::unit()), 3,
                  vec3 f = rk_im_fade(vec3(a[0], a[1], 0.5f), vec3(a[1], 1.0f, a[0]), a[2]);
                  o[0] = f.x; o[1] = f.y; o[2] = f.z;),
    };
    // The two plane cases share their body (a macro expanded once for GLSL, once for C++).
    for (parity::Case& c : cases) {
        if (c.name == "rk_im_furniture_plane_grad") {
            c.glsl_body = RK_FURN_XSTR(RK_FURN_SETUP vec3 dx = vec3(0.01f, 0.002f, 0.0f); vec3 dy = vec3(0.0f, 0.01f, 0.003f);
                                        rk_im_furniture_hit h = rk_im_furniture_plane_grad(p, cam, n, tn, bn, D, dx, dy, g);
                                        RK_FURN_OUT(h));
            c.cpu = [](const float* a, float* o) {
                RK_FURN_SETUP vec3 dx = vec3(0.01f, 0.002f, 0.0f);
                vec3 dy = vec3(0.0f, 0.01f, 0.003f);
                rk_im_furniture_hit h = rk_im_furniture_plane_grad(p, cam, n, tn, bn, D, dx, dy, g);
                RK_FURN_OUT(h)
            };
        }
        if (c.name == "rk_im_furniture_plane") {
            c.glsl_body = RK_FURN_XSTR(RK_FURN_SETUP rk_im_furniture_hit h = rk_im_furniture_plane(p, cam, n, tn, bn, D, g);
                                        RK_FURN_OUT(h));
            c.cpu = [](const float* a, float* o) {
                RK_FURN_SETUP rk_im_furniture_hit h = rk_im_furniture_plane(p, cam, n, tn, bn, D, g);
                RK_FURN_OUT(h)
            };
        }
        // Planes and their derivatives go through divisions (2.5 ulp on GPUs) and dot products that
        // the driver may fuse. Relative tolerance 2e-5, absolute 3e-3 room
        // units on uv: |u| up to 1000 rooms has an ulp of 6e-5, times the conditioning t < 20
        // (measured: 5.5e-4 once in 6832 rows, typically < 1e-5).
        if (c.name.rfind("rk_im_furniture_plane", 0) == 0) {
            c.abs_tol = 3e-3;
            c.rel_tol = 2e-5;
        }
        if (c.name == "rk_im_furniture_unit") c.abs_tol = 4e-7;
        // Beyond |time fps| = 2^24 the documented result is "some frame in range" (float time has no
        // frame resolution left): a driver's fused f - fc floor(f / fc) picks another one.
        if (c.name == "rk_im_flipbook_frame")
            c.tie = [](const float* in, const float* g, const float*) {
                const double x = std::min(std::abs(static_cast<double>(in[0])), 1e30) *
                                 std::min(std::max(static_cast<double>(in[1]), 0.0), 1e6);
                const double count = std::min(std::max(std::floor(static_cast<double>(in[2])), 1.0), 65536.0);
                return x >= 16777216.0 && g[0] >= 0.0f && g[0] < count && g[0] == std::floor(g[0]);
            };
        if (c.name == "rk_im_window_fresnel" || c.name == "rk_im_window") c.abs_tol = 8e-6;
        // Colours up to RK_HDR_MAX (1e18) mixed by Fresnel weights: a driver's fused multiply-adds
        // round the 1e18 terms differently, so a small channel next to a huge one moves by ~1e-7 of
        // the huge one (NVIDIA: 6e10 next to 1e18). On hardware, within 1e-6 of the row's largest.
        if (c.name == "rk_im_window_fresnel") c.tie = parity::hw_row_scale_tie(c.n_out, 1e-6);
    }
    return cases;
}

}  // namespace

TEST(GpuParity, InteriorFurnitureCompose)
{
    long rows = 0;
    for (const parity::Case& c : interior_shading_cases()) {
        const parity::Result r = parity::run(c, parity::shader_dir());
        rows += r.rows;
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
    std::printf("[parity] interior furniture/compose: %ld input rows in total\n", rows);
}

TEST(GpuParity, InteriorComposeAdditiveMode)
{
    parity::Case c{"rk_im_window (RK_IM_COMPOSE_MODE=1)", "raykit/interior_compose.glsl", {colour(), colour(), dom::cosine()}, 3,
                   "vec3 w = rk_im_window(vec3(a[0], 0.5f, 0.25f), vec3(a[1], 0.25f, a[0]), a[2], vec3(0.9f), 1.52f, 1.0f);"
                   "o[0] = w.x; o[1] = w.y; o[2] = w.z;",
                   [](const float* a, float* o) {
                       const vec3 w = rk_im_window_additive(vec3(a[0], 0.5f, 0.25f), vec3(a[1], 0.25f, a[0]));
                       o[0] = w.x;
                       o[1] = w.y;
                       o[2] = w.z;
                   },
                   2e-6, 2e-5, {{"RK_IM_COMPOSE_MODE", "1"}}, true, {}};
    const parity::Result r = parity::run(c, parity::shader_dir(), 2048);
    EXPECT_TRUE(r.ok) << r.worst;
}

// ---------------------------------------------------------------------------------------------
// Smoke test of the building material on the driver.

namespace {

struct Smoke {
    GLuint tex2d = 0, facade = 0, array = 0, cubes = 0, sprites = 0, env = 0, env_white = 0;
    GLuint vao = 0, vbo = 0, fbo = 0, colour = 0;
};

GLuint make_tex(GLenum target, int w, int h, int layers, const std::vector<float>& texel_fn_rgba, bool per_texel)
{
    GLuint t = 0;
    glCreateTextures(target, 1, &t);
    if (target == GL_TEXTURE_2D) {
        glTextureStorage2D(t, 1, GL_RGBA32F, w, h);
    } else {
        glTextureStorage3D(t, 1, GL_RGBA32F, w, h, layers);
    }
    std::vector<float> data;
    const size_t n = static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(std::max(layers, 1));
    if (per_texel) {
        data = texel_fn_rgba;
    } else {
        for (size_t i = 0; i < n; ++i) data.insert(data.end(), texel_fn_rgba.begin(), texel_fn_rgba.end());
    }
    if (target == GL_TEXTURE_2D) {
        glTextureSubImage2D(t, 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, data.data());
    } else {
        glTextureSubImage3D(t, 0, 0, 0, 0, w, h, layers, GL_RGBA, GL_FLOAT, data.data());
    }
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
}

std::string variant_name(const std::vector<ShaderDefine>& d)
{
    std::string s;
    for (const ShaderDefine& x : d) s += x.name.substr(3) + "=" + x.value + " ";
    return s.empty() ? "<defaults>" : s;
}

}  // namespace

TEST(GpuSmoke, InteriorBuildingMaterial)
{
    const std::string dir = parity::shader_dir();
    const std::string samples = dir + "/../samples/common/";
    const int W = 128, H = 128;
    const vec3 yellow(0.9f, 0.8f, 0.1f), magenta(0.8f, 0.1f, 0.7f), tint(0.9f, 0.95f, 0.95f);
    const vec3 facade_rgb(0.55f, 0.5f, 0.45f);

    Smoke k;
    k.tex2d = make_tex(GL_TEXTURE_2D, 4, 4, 1, {yellow.x, yellow.y, yellow.z, 1.0f}, false);
    k.array = make_tex(GL_TEXTURE_2D_ARRAY, 4, 4, 12, {yellow.x, yellow.y, yellow.z, 1.0f}, false);
    k.cubes = make_tex(GL_TEXTURE_CUBE_MAP_ARRAY, 4, 4, 12, {yellow.x, yellow.y, yellow.z, 1.0f}, false);
    k.sprites = make_tex(GL_TEXTURE_2D_ARRAY, 4, 4, 4, {magenta.x, magenta.y, magenta.z, 1.0f}, false);
    k.env = make_tex(GL_TEXTURE_2D, 8, 8, 1, {0.0f, 0.0f, 0.0f, 1.0f}, false);
    k.env_white = make_tex(GL_TEXTURE_2D, 8, 8, 1, {1.0f, 1.0f, 1.0f, 1.0f}, false);
    {
        // Facade texture: one room face per texture repeat, window mask 1 in the central 8 x 8 texels.
        std::vector<float> f;
        for (int y = 0; y < 16; ++y) {
            for (int x = 0; x < 16; ++x) {
                const bool win = x >= 4 && x < 12 && y >= 4 && y < 12;
                f.insert(f.end(), {facade_rgb.x, facade_rgb.y, facade_rgb.z, win ? 1.0f : 0.0f});
            }
        }
        k.facade = make_tex(GL_TEXTURE_2D, 16, 16, 1, f, true);
    }
    glBindTextureUnit(0, k.facade);
    for (GLuint u = 1; u <= 4; ++u) glBindTextureUnit(u, k.tex2d);
    glBindTextureUnit(5, k.tex2d);  // atlas (2D), array and cube array: three targets on one unit
    glBindTextureUnit(5, k.array);
    glBindTextureUnit(5, k.cubes);
    glBindTextureUnit(6, k.sprites);
    glBindTextureUnit(7, k.env);

    // One facade quad, z = 0 facing +z, 8 x 6 units = 2 x 2 rooms of 4 x 3; uv in room units.
    const float verts[] = {0, 0, 0, 0, 0, 1, 0, 0, 8, 0, 0, 0, 0, 1, 2, 0, 8, 6, 0, 0, 0, 1, 2, 2,
                           0, 0, 0, 0, 0, 1, 0, 0, 8, 6, 0, 0, 0, 1, 2, 2, 0, 6, 0, 0, 0, 1, 0, 2};
    glCreateBuffers(1, &k.vbo);
    glNamedBufferStorage(k.vbo, sizeof verts, verts, 0);
    glCreateVertexArrays(1, &k.vao);
    glVertexArrayVertexBuffer(k.vao, 0, k.vbo, 0, 8 * sizeof(float));
    for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(k.vao, a);
        glVertexArrayAttribFormat(k.vao, a, a == 2 ? 2 : 3, GL_FLOAT, GL_FALSE, a == 0 ? 0 : (a == 1 ? 12 : 24));
        glVertexArrayAttribBinding(k.vao, a, 0);
    }
    glCreateTextures(GL_TEXTURE_2D, 1, &k.colour);
    glTextureStorage2D(k.colour, 1, GL_RGBA32F, W, H);
    glCreateFramebuffers(1, &k.fbo);
    glNamedFramebufferTexture(k.fbo, GL_COLOR_ATTACHMENT0, k.colour, 0);
    ASSERT_EQ(glCheckNamedFramebufferStatus(k.fbo, GL_FRAMEBUFFER), static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));

    const glm::vec3 cam(4.0f, 3.0f, 10.0f);
    const glm::mat4 proj = glm::perspective(glm::radians(60.0f), 1.0f, 0.1f, 100.0f);
    const glm::mat4 view = glm::lookAt(cam, glm::vec3(4.0f, 3.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::mat4 vp = proj * view;
    auto pixel_of = [&](glm::vec3 w) {
        const glm::vec4 c = vp * glm::vec4(w, 1.0f);
        const float x = (c.x / c.w * 0.5f + 0.5f) * static_cast<float>(W);
        const float y = (c.y / c.w * 0.5f + 0.5f) * static_cast<float>(H);
        return glm::ivec2(static_cast<int>(x), static_cast<int>(y));
    };
    const glm::vec3 window_point(2.0f, 1.5f, 0.0f), wall_point(0.5f, 0.4f, 0.0f);
    const glm::ivec2 pw = pixel_of(window_point), pe = pixel_of(wall_point);

    // Expected colours (sky and environment black; every room surface and sprite yellow; lights,
    // tint, fade arranged to be neutral), computed with the CPU build.
    const vec3 light = vec3(0.3f, 0.3f, 0.4f) + vec3(1.0f, 1.0f, 0.9f) * glm::dot(vec3(0, 0, 1), glm::normalize(vec3(0.5f, 0.33166f, 0.8f)));
    const vec3 exterior = facade_rgb * light;
    const glm::vec3 pw_obj = [&] {  // the object-space point actually under the window pixel's centre
        const glm::mat4 inv = glm::inverse(vp);
        const glm::vec4 ndc((static_cast<float>(pw.x) + 0.5f) / W * 2.0f - 1.0f, (static_cast<float>(pw.y) + 0.5f) / H * 2.0f - 1.0f, 0.0f, 1.0f);
        glm::vec4 a = inv * ndc;
        const glm::vec3 ray = glm::vec3(a) / a.w - cam;
        return cam + ray * (-cam.z / ray.z);
    }();
    const float cos_view = rk_window_glass_cos(vec3(0, 0, 1), glm::normalize(cam - pw_obj));
    const float R = rk_window_glass_reflectance(cos_view, 1.52f, 1.0f);

    std::vector<std::vector<ShaderDefine>> variants = {
        {},
        {{"RK_IM_SHADING", "1"}},
        {{"RK_IM_SHADING", "2"}},
        {{"RK_IM_SHADING", "3"}},
        {{"RK_IM_ROOM_LIGHTS", "1"}},
        {{"RK_IM_FURNITURE_LAYERS", "1"}},
        {{"RK_IM_FURNITURE_LAYERS", "4"}},
        {{"RK_IM_FURNITURE_LAYERS", "2"}, {"RK_IM_FURNITURE_FLIPBOOK", "0"}},
        {{"RK_IM_VARYING_WALLS", "1"}},
        {{"RK_IM_REFLECTION", "1"}},
        {{"RK_IM_FADE", "1"}},
        {{"RK_IM_COMPOSE_MODE", "1"}},
        {{"RK_IM_BUILDING_FACADE", "1"}},
        {{"RK_IM_BUILDING_OUTPUT", "1"}},
    };
    // Every feature on at once, with each room-texture mode; and the scene descriptions' macro sets.
    for (int mode = 0; mode < 4; ++mode) {
        InteriorSceneDesc d;
        d.textures = static_cast<InteriorTextures>(mode);
        d.room_lights = true;
        d.furniture_layers = 4 - mode % 2;
        d.varying_walls = true;
        d.reflections = true;
        d.fade_distance = 1e4f;
        d.textured_facade = mode % 2 == 1;
        d.furniture_flipbook = mode < 2;
        variants.push_back(interior_defines(d));
    }
    variants.push_back(interior_defines(InteriorSceneDesc::thesis()));  // the benchmark's minimal variant

    // Renders one variant; `extra` sets more uniforms. Returns false on a compile/link failure.
    struct Shot {
        vec3 win, ext;
        long covered = 0, bad = 0;
        std::vector<float> image;
    };
    auto render = [&](const std::vector<ShaderDefine>& defs, const std::function<void(GLuint)>& extra, Shot& out) {
        std::string vs, fs;
        GLuint prog = 0;
        try {
            vs = rkgl::shader_file(samples + "interior_building.vert", {dir}, defs);
            fs = rkgl::shader_file(samples + "interior_building.frag", {dir}, defs);
            prog = rkgl::build_program({{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, fs}});
        } catch (const std::exception& e) {
            ADD_FAILURE() << variant_name(defs) << ": " << e.what();
            return false;
        }
        glUseProgram(prog);
        bool block = false;
        for (const ShaderDefine& d : defs) block = block || (d.name == "RK_IM_BUILDING_BLOCK" && d.value == "1");
        GLuint ubo[2] = {0, 0};
        if (block) {
            // The uniform-block form: the same values, packed with raykit::gpu_pack (std140).
            rk_im_window_params prm = rk_im_window_params_default();
            prm.lit_probability = 1.0f;
            prm.light_warm = prm.light_cool = vec3(1.0f);
            prm.light_level = glm::vec2(1.0f);
            prm.fade_range = glm::vec2(1e4f, 2e4f);
            prm.tint_amount = 0.0f;
            prm.variants = 2.0f;
            prm.time = 1.25f;
            rk_im_building_frame frame = rk_im_building_frame_default();
            frame.camera_world = cam;
            frame.sky_color = vec3(0.0f);
            rk_im_building_vertex vert = rk_im_building_vertex_default();
            vert.clip_from_world = vp;
            vert.camera_world = cam;
            const size_t a = gpu_size<rk_im_window_params>(GpuLayout::std140);
            std::vector<uint8_t> frag_block(a + gpu_size<rk_im_building_frame>(GpuLayout::std140));
            gpu_pack(prm, GpuLayout::std140, frag_block.data());
            gpu_pack(frame, GpuLayout::std140, frag_block.data() + a);  // a is a multiple of 16
            const std::vector<uint8_t> vert_block = gpu_pack(vert, GpuLayout::std140);
            ubo[0] = rkgl::make_buffer(frag_block.size(), frag_block.data());
            ubo[1] = rkgl::make_buffer(vert_block.size(), vert_block.data());
            glBindBufferBase(GL_UNIFORM_BUFFER, 8, ubo[0]);
            glBindBufferBase(GL_UNIFORM_BUFFER, 9, ubo[1]);
        }
        auto loc = [&](const char* n) { return glGetUniformLocation(prog, n); };
        const glm::mat4 id(1.0f);
        glUniformMatrix4fv(loc("u_world_from_object"), 1, GL_FALSE, &id[0][0]);
        glUniformMatrix4fv(loc("u_clip_from_world"), 1, GL_FALSE, &vp[0][0]);
        glUniform3f(loc("u_camera_world"), cam.x, cam.y, cam.z);
        glUniform3f(loc("u_sky_color"), 0.0f, 0.0f, 0.0f);
        glUniform1f(loc("u_lit_probability"), 1.0f);
        glUniform3f(loc("u_light_warm"), 1.0f, 1.0f, 1.0f);
        glUniform3f(loc("u_light_cool"), 1.0f, 1.0f, 1.0f);
        glUniform2f(loc("u_light_level"), 1.0f, 1.0f);
        glUniform2f(loc("u_fade_range"), 1e4f, 2e4f);
        glUniform1f(loc("u_tint_amount"), 0.0f);
        glUniform1f(loc("u_variants"), 2.0f);
        glUniform1f(loc("u_time"), 1.25f);
        if (extra) extra(prog);
        glBindFramebuffer(GL_FRAMEBUFFER, k.fbo);
        glViewport(0, 0, W, H);
        const float clear[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
        glClearNamedFramebufferfv(k.fbo, GL_COLOR, 0, clear);
        glBindVertexArray(k.vao);
        glDrawArrays(GL_TRIANGLES, 0, 6);
        std::vector<float> img(static_cast<size_t>(W) * H * 4);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, img.data());
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDeleteProgram(prog);
        if (block) glDeleteBuffers(2, ubo);
        EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
        out = Shot{};
        out.image = img;
        for (size_t i = 0; i < img.size(); i += 4) {
            if (img[i + 3] < 0.0f) continue;  // background
            ++out.covered;
            for (int c = 0; c < 4; ++c) out.bad += std::isfinite(img[i + static_cast<size_t>(c)]) ? 0 : 1;
        }
        auto px = [&](glm::ivec2 q) {
            const size_t i = (static_cast<size_t>(q.y) * W + static_cast<size_t>(q.x)) * 4;
            return vec3(img[i], img[i + 1], img[i + 2]);
        };
        out.win = px(pw);
        out.ext = px(pe);
        std::printf("[smoke] %-100s window (%.4f %.4f %.4f) wall (%.4f %.4f %.4f)\n", variant_name(defs).c_str(),
                    out.win.x, out.win.y, out.win.z, out.ext.x, out.ext.y, out.ext.z);
        return true;
    };
    auto expect_near3 = [](vec3 got, vec3 want, const char* what) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 2e-3f) << what << ", channel " << c;
    };

    long pixels = 0;
    for (const auto& defs : variants) {
        SCOPED_TRACE(variant_name(defs));
        Shot shot;
        if (!render(defs, nullptr, shot)) continue;
        pixels += shot.covered;
        EXPECT_EQ(shot.bad, 0);
        EXPECT_GT(shot.covered, W * H / 4);
        bool tonemapped = false, additive = false, furniture = false;
        for (const ShaderDefine& d : defs) {
            if (d.name == "RK_IM_BUILDING_OUTPUT" && d.value == "1") tonemapped = true;
            if (d.name == "RK_IM_COMPOSE_MODE" && d.value == "1") additive = true;
            if (d.name == "RK_IM_FURNITURE_LAYERS" && d.value != "0") furniture = true;
        }
        // The nearest furniture plane (0.6 behind the glass, in front of the back wall 4 behind)
        // shows its magenta sprite instead of the yellow room.
        const vec3 inside = furniture ? magenta : yellow;
        if (tonemapped) {
            EXPECT_GT(shot.win.x, shot.win.z);  // yellow interior
            EXPECT_GT(shot.win.y, shot.win.z);
            EXPECT_GT(glm::length(shot.win - shot.ext), 0.05f);
        } else {
            expect_near3(shot.win, additive ? inside : (1.0f - R) * tint * inside, "window pixel");
            expect_near3(shot.ext, exterior, "facade pixel");
        }
    }
    // The uniform-block form (RK_IM_BUILDING_BLOCK 1, the SPIR-V / HLSL / MSL one) renders the same
    // image as the loose uniforms, bit for bit, for every variant: the packed blocks hold the same
    // values at the offsets the driver reads.
    for (std::vector<ShaderDefine> defs : variants) {
        SCOPED_TRACE("block form of " + variant_name(defs));
        Shot loose, blocked;
        if (!render(defs, nullptr, loose)) continue;
        defs.push_back({"RK_IM_BUILDING_BLOCK", "1"});
        if (!render(defs, nullptr, blocked)) continue;
        ASSERT_EQ(loose.image.size(), blocked.image.size());
        long differ = 0;
        for (size_t i = 0; i < loose.image.size(); ++i) differ += loose.image[i] == blocked.image[i] ? 0 : 1;
        EXPECT_EQ(differ, 0) << "of " << loose.image.size() << " channels";
        EXPECT_GT(blocked.covered, W * H / 4);
    }
    // Each feature's effect, with uniforms that make it visible.
    {
        SCOPED_TRACE("room lights, all off");
        Shot shot;
        if (render({{"RK_IM_ROOM_LIGHTS", "1"}}, [](GLuint prog) { glUniform1f(glGetUniformLocation(prog, "u_lit_probability"), 0.0f); }, shot))
            expect_near3(shot.win, (1.0f - R) * tint * yellow * RK_IM_UNLIT_DEFAULT, "unlit window");
    }
    {
        SCOPED_TRACE("fade, fully faded");
        Shot shot;
        if (render({{"RK_IM_FADE", "1"}}, [](GLuint prog) { glUniform2f(glGetUniformLocation(prog, "u_fade_range"), 0.0f, 1.0f); }, shot))
            expect_near3(shot.win, (1.0f - R) * tint * vec3(0.45f, 0.4f, 0.35f), "faded window");
    }
    {
        SCOPED_TRACE("furniture, sprites alpha-tested away");
        Shot shot;
        if (render({{"RK_IM_FURNITURE_LAYERS", "2"}}, [](GLuint prog) { glUniform1f(glGetUniformLocation(prog, "u_alpha_threshold"), 1.0f); }, shot))
            expect_near3(shot.win, (1.0f - R) * tint * yellow, "window without furniture");
    }
    {
        SCOPED_TRACE("furniture planes behind the back wall");
        Shot shot;
        if (render({{"RK_IM_FURNITURE_LAYERS", "4"}}, [](GLuint prog) {
                glUniform4f(glGetUniformLocation(prog, "u_furniture_depth"), 4.5f, 5.0f, 6.0f, 7.0f); }, shot))
            expect_near3(shot.win, (1.0f - R) * tint * yellow, "window, furniture hidden by the room");
    }
    {
        SCOPED_TRACE("reflection: white environment");
        glBindTextureUnit(7, k.env_white);
        Shot shot;
        if (render({{"RK_IM_REFLECTION", "1"}}, nullptr, shot))
            expect_near3(shot.win, vec3(R) + (1.0f - R) * tint * yellow, "window reflecting white");
        glBindTextureUnit(7, k.env);
    }
    std::printf("[smoke] %zu variants + 5 feature checks rendered, %ld covered pixels, no NaN/Inf\n", variants.size(), pixels);
    glDeleteFramebuffers(1, &k.fbo);
    const GLuint texs[] = {k.colour, k.tex2d, k.facade, k.array, k.cubes, k.sprites, k.env, k.env_white};
    glDeleteTextures(8, texs);
    glDeleteBuffers(1, &k.vbo);
    glDeleteVertexArrays(1, &k.vao);
}

// ---------------------------------------------------------------------------------------------
// Which texel each room-texture mode fetches, on the driver: every 2D texture, array layer, atlas
// tile and cube face holds its own exact colour (a palette of RGBA32F values, NEAREST, one level),
// the window is the thesis's additive one over a black sky (so a window pixel is exactly the room
// texel), and every window pixel is compared with the texel the CPU build of the same trace and
// selection (interior_mapping.glsl + interior_surface.glsl) picks for the point under the pixel
// centre. Regular and displaced walls; three cameras that see walls, floors and ceilings.

namespace {

/// A facade quad (z = 0 facing +z, 12 x 9 units = 3 x 3 rooms of 4 x 3 on a grid plane) rendered
/// with samples/common/interior_building.{vert,frag} into a W x H RGBA32F target.
struct FacadeRig {
    int W, H;
    GLuint vbo = 0, vao = 0, colour = 0, fbo = 0;
    rk_im_grid grid;
    FacadeRig(int w, int h) : W(w), H(h)
    {
        const float verts[] = {0, 0, 0, 0, 0, 1, 0, 0, 12, 0, 0, 0, 0, 1, 3, 0, 12, 9, 0, 0, 0, 1, 3, 3,
                               0, 0, 0, 0, 0, 1, 0, 0, 12, 9, 0, 0, 0, 1, 3, 3, 0, 9, 0, 0, 0, 1, 0, 3};
        glCreateBuffers(1, &vbo);
        glNamedBufferStorage(vbo, sizeof verts, verts, 0);
        glCreateVertexArrays(1, &vao);
        glVertexArrayVertexBuffer(vao, 0, vbo, 0, 8 * sizeof(float));
        for (GLuint a = 0; a < 3; ++a) {
            glEnableVertexArrayAttrib(vao, a);
            glVertexArrayAttribFormat(vao, a, a == 2 ? 2 : 3, GL_FLOAT, GL_FALSE, a == 0 ? 0 : (a == 1 ? 12 : 24));
            glVertexArrayAttribBinding(vao, a, 0);
        }
        glCreateTextures(GL_TEXTURE_2D, 1, &colour);
        glTextureStorage2D(colour, 1, GL_RGBA32F, W, H);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, colour, 0);
        grid.room_size = vec3(4.0f, 3.0f, 4.0f);
        grid.origin = vec3(0.0f);
    }
    ~FacadeRig()
    {
        glDeleteFramebuffers(1, &fbo);
        glDeleteTextures(1, &colour);
        glDeleteBuffers(1, &vbo);
        glDeleteVertexArrays(1, &vao);
    }
    bool complete() const { return glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE; }
    /// The building material with `defs`, in use; grid, seed, jitter and a window of `window_size`
    /// of each room face set, the sky black. 0 (and a test failure) on a compile or link error.
    GLuint program(const std::vector<ShaderDefine>& defs, uint32_t seed, vec3 jitter, float window_size) const
    {
        const std::string dir = parity::shader_dir(), samples = dir + "/../samples/common/";
        GLuint prog = 0;
        try {
            prog = rkgl::build_program({{GL_VERTEX_SHADER, rkgl::shader_file(samples + "interior_building.vert", {dir}, defs)},
                                        {GL_FRAGMENT_SHADER, rkgl::shader_file(samples + "interior_building.frag", {dir}, defs)}});
        } catch (const std::exception& e) {
            ADD_FAILURE() << variant_name(defs) << ": " << e.what();
            return 0;
        }
        glUseProgram(prog);
        auto loc = [&](const char* nm) { return glGetUniformLocation(prog, nm); };
        const glm::mat4 id(1.0f);
        glUniformMatrix4fv(loc("u_world_from_object"), 1, GL_FALSE, &id[0][0]);
        glUniform3f(loc("u_room_size"), grid.room_size.x, grid.room_size.y, grid.room_size.z);
        glUniform3f(loc("u_grid_origin"), grid.origin.x, grid.origin.y, grid.origin.z);
        glUniform1ui(loc("u_seed"), seed);
        glUniform3f(loc("u_wall_jitter"), jitter.x, jitter.y, jitter.z);
        glUniform2f(loc("u_window_size"), window_size, window_size);
        glUniform3f(loc("u_sky_color"), 0.0f, 0.0f, 0.0f);
        glUniform1f(loc("u_tint_amount"), 0.0f);
        return prog;
    }
    glm::mat4 view_proj(glm::vec3 cam) const
    {
        return glm::perspective(glm::radians(75.0f), static_cast<float>(W) / static_cast<float>(H), 0.05f, 100.0f) *
               glm::lookAt(cam, glm::vec3(6.0f, 4.5f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    }
    /// Renders with `prog` (already in use) from `cam`; RGBA floats, background alpha -1.
    std::vector<float> render(GLuint prog, glm::vec3 cam) const
    {
        const glm::mat4 vp = view_proj(cam);
        glUniformMatrix4fv(glGetUniformLocation(prog, "u_clip_from_world"), 1, GL_FALSE, &vp[0][0]);
        glUniform3f(glGetUniformLocation(prog, "u_camera_world"), cam.x, cam.y, cam.z);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glViewport(0, 0, W, H);
        const float clear[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
        glClearNamedFramebufferfv(fbo, GL_COLOR, 0, clear);
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, 6);
        std::vector<float> img(static_cast<size_t>(W) * static_cast<size_t>(H) * 4);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, img.data());
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        return img;
    }
    /// The facade point (z = 0) under the window position (px, py) in pixels.
    static glm::vec3 point_at(const glm::mat4& inv_vp, glm::vec3 cam, float px, float py, int w, int h)
    {
        const glm::vec4 ndc(px / static_cast<float>(w) * 2.0f - 1.0f, py / static_cast<float>(h) * 2.0f - 1.0f, 0.0f, 1.0f);
        const glm::vec4 a = inv_vp * ndc;
        const glm::vec3 ray = glm::vec3(a) / a.w - cam;
        return cam + ray * (-cam.z / ray.z);
    }
    /// Whether the pixel centre lies well inside a window, where the material's antialiased mask is
    /// exactly 1: |room cell fraction - 1/2| - window / 2 below -0.6 of the pixel footprint in cells
    /// (the shader's fwidth; its mask is 1 below -0.5).
    bool deep_in_window(const glm::mat4& inv_vp, glm::vec3 cam, int x, int y, float window_size) const
    {
        const float xf = static_cast<float>(x) + 0.5f, yf = static_cast<float>(y) + 0.5f;
        auto cell_of = [&](glm::vec3 q) { return glm::vec2(q.x / grid.room_size.x, q.y / grid.room_size.y); };
        const glm::vec2 c0 = cell_of(point_at(inv_vp, cam, xf, yf, W, H));
        const glm::vec2 foot = glm::abs(cell_of(point_at(inv_vp, cam, xf + 1.0f, yf, W, H)) - c0) +
                               glm::abs(cell_of(point_at(inv_vp, cam, xf, yf + 1.0f, W, H)) - c0);
        const glm::vec2 dist = glm::abs(c0 - glm::floor(c0) - 0.5f) - 0.5f * window_size;
        return dist.x <= -0.6f * foot.x && dist.y <= -0.6f * foot.y;
    }
};

}  // namespace

TEST(GpuRender, InteriorRoomTexturesFetchTheSelectedTexel)
{
    FacadeRig rig(160, 120);
    ASSERT_TRUE(rig.complete());
    const int W = rig.W, H = rig.H;
    auto pal = [](int i) { return vec3(static_cast<float>(i % 5 + 1) / 8.0f, static_cast<float>((i / 5) % 5 + 1) / 8.0f,
                                       static_cast<float>((i / 25) % 5 + 1) / 8.0f); };
    auto solid = [&](int i, int texels) {
        std::vector<float> d;
        for (int t = 0; t < texels; ++t) d.insert(d.end(), {pal(i).x, pal(i).y, pal(i).z, 1.0f});
        return d;
    };
    const float V = 3.0f, N = 3.0f;
    const int grid = 4, cell = 16, pad = 2;
    const uint32_t seed = 7u;
    // Mode 0: four textures, palette 0..3. Mode 1: 3 V layers, palette 10 + layer. Mode 2: a grid x
    // grid atlas, cell k (pad included) palette 30 + k. Mode 3: N cubes, face f of cube c palette
    // 50 + 6 c + f (GL face order +X, -X, +Y, -Y, +Z, -Z).
    GLuint four[4];
    for (int i = 0; i < 4; ++i) four[i] = make_tex(GL_TEXTURE_2D, 4, 4, 1, solid(i, 16), true);
    std::vector<float> layers;
    for (int l = 0; l < 3 * static_cast<int>(V); ++l) {
        const std::vector<float> t = solid(10 + l, 16);
        layers.insert(layers.end(), t.begin(), t.end());
    }
    const GLuint array = make_tex(GL_TEXTURE_2D_ARRAY, 4, 4, 3 * static_cast<int>(V), layers, true);
    std::vector<float> atlas_texels;
    for (int y = 0; y < grid * cell; ++y)
        for (int x = 0; x < grid * cell; ++x) {
            const vec3 c = pal(30 + (y / cell) * grid + x / cell);
            atlas_texels.insert(atlas_texels.end(), {c.x, c.y, c.z, 1.0f});
        }
    const GLuint atlas = make_tex(GL_TEXTURE_2D, grid * cell, grid * cell, 1, atlas_texels, true);
    std::vector<float> faces;
    for (int f = 0; f < 6 * static_cast<int>(N); ++f) {
        const std::vector<float> t = solid(50 + f, 16);
        faces.insert(faces.end(), t.begin(), t.end());
    }
    const GLuint cubes = make_tex(GL_TEXTURE_CUBE_MAP_ARRAY, 4, 4, 6 * static_cast<int>(N), faces, true);

    const rk_im_grid g = rig.grid;
    const vec3 jitter(0.4f, 0.3f, 0.4f);
    const glm::vec3 cams[] = {{6.0f, 4.5f, 14.0f}, {1.0f, 8.0f, 2.0f}, {11.0f, 0.8f, 1.6f}};
    const float window_size = 0.9f;
    long total_checked = 0;
    for (int mode = 0; mode < 4; ++mode) {
        for (int varying = 0; varying < 2; ++varying) {
            const std::vector<ShaderDefine> defs = {{"RK_IM_SHADING", std::to_string(mode)},
                                                    {"RK_IM_VARYING_WALLS", std::to_string(varying)},
                                                    {"RK_IM_COMPOSE_MODE", "1"}};
            SCOPED_TRACE(variant_name(defs));
            const GLuint prog = rig.program(defs, seed, jitter, window_size);
            if (!prog) continue;
            glUniform1f(glGetUniformLocation(prog, "u_variants"), mode == 3 ? N : V);
            glUniform4f(glGetUniformLocation(prog, "u_atlas"), static_cast<float>(grid), static_cast<float>(cell), static_cast<float>(pad), 0.0f);
            for (GLuint u = 1; u <= 4; ++u) glBindTextureUnit(u, four[u - 1]);
            glBindTextureUnit(5, mode == 1 ? array : (mode == 2 ? atlas : (mode == 3 ? cubes : 0)));
            long checked = 0, wrong = 0, skipped_edge = 0;
            std::string first_wrong;
            for (const glm::vec3& cam : cams) {
                const std::vector<float> img = rig.render(prog, cam);
                const glm::mat4 inv = glm::inverse(rig.view_proj(cam));
                for (int y = 0; y < H; ++y)
                    for (int x = 0; x < W; ++x) {
                        const size_t i = (static_cast<size_t>(y) * W + static_cast<size_t>(x)) * 4;
                        if (img[i + 3] < 0.0f) continue;  // background
                        if (!rig.deep_in_window(inv, cam, x, y, window_size)) continue;
                        const glm::vec3 p = FacadeRig::point_at(inv, cam, static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, W, H);
                        const rk_im_hit h = varying ? rk_im_trace_varying(p, cam, vec3(0, 0, 1), g, jitter, seed)
                                                    : rk_im_trace(p, cam, vec3(0, 0, 1), g);
                        if (!h.valid) continue;
                        // A hit within rounding of the face's edge may go to the neighbouring face.
                        const float e = 0.004f;
                        if (h.uv.x < e || h.uv.x > 1.0f - e || h.uv.y < e || h.uv.y > 1.0f - e) {
                            ++skipped_edge;
                            continue;
                        }
                        int index = 0;
                        if (mode == 0) index = h.family == 1 ? (h.side > 0 ? 0 : 1) : (h.family == 0 ? 2 : 3);
                        if (mode == 1) index = 10 + static_cast<int>(rk_im_array_layer(h, V, seed));
                        if (mode == 2) index = 30 + static_cast<int>(rk_im_array_layer(h, V, seed));
                        if (mode == 3) {
                            const rk_im_cube_coord c = rk_im_cube_lookup(h, N, seed);
                            const glm::vec3 ad = glm::abs(c.dir);
                            const int ax = ad.x >= ad.y && ad.x >= ad.z ? 0 : (ad.y >= ad.z ? 1 : 2);
                            index = 50 + 6 * static_cast<int>(c.layer) + 2 * ax + (c.dir[ax] < 0.0f ? 1 : 0);
                        }
                        const vec3 want = pal(index), got(img[i], img[i + 1], img[i + 2]);
                        ++checked;
                        if (glm::length(got - want) > 1e-5f) {
                            if (first_wrong.empty())
                                first_wrong = rktest::fmt("pixel", x, y, "cam", cam.x, cam.y, cam.z, "family", h.family, "side", h.side,
                                                          "room", h.room.x, h.room.y, h.room.z, "want", want.x, want.y, want.z, "got",
                                                          got.x, got.y, got.z);
                            ++wrong;
                        }
                    }
            }
            glDeleteProgram(prog);
            std::printf("[render] %-60s window pixels checked %6ld, wrong texel %ld, near a face edge (skipped) %ld%s%s\n",
                        variant_name(defs).c_str(), checked, wrong, skipped_edge, first_wrong.empty() ? "" : "; first wrong: ",
                        first_wrong.c_str());
            EXPECT_GT(checked, 5000);
            EXPECT_EQ(wrong, 0);
            total_checked += checked;
        }
    }
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    const GLuint texs[] = {four[0], four[1], four[2], four[3], array, atlas, cubes};
    glDeleteTextures(7, texs);
    std::printf("[render] room textures: %ld window pixels checked in total\n", total_checked);
}

TEST(GpuRender, InteriorRoomSeamsHaveNoMipSpikes)
{
    // Every mip level of the room texture array holds its own level number (red = level / 8), so
    // with trilinear filtering the red channel is the LOD the driver chose from the gradients the
    // material passes to textureGrad. That LOD must be the one the CPU build's analytic uv
    // derivatives give, log2(512 max(|d uv/dx|, |d uv/dy|)), at every window pixel, room seams
    // included: a material using implicit derivatives of the room uv would see a jump of ~1 room
    // across a seam's 2x2 quad and pick the coarsest level there (a one-pixel line). Since a driver
    // may use one LOD per quad, a pixel's LOD may lie anywhere between its quad's predictions,
    // +-0.5 level (GL allows approximating rho).
    FacadeRig rig(160, 120);
    ASSERT_TRUE(rig.complete());
    const int W = rig.W, H = rig.H, size = 512, levels = 10;
    GLuint mips = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &mips);
    glTextureStorage3D(mips, levels, GL_RGBA32F, size, size, 3);
    for (int l = 0; l < levels; ++l) {
        const int n = size >> l;
        const std::vector<float> texels(static_cast<size_t>(n * n * 3) * 4, static_cast<float>(l) / 8.0f);
        glTextureSubImage3D(mips, l, 0, 0, 0, n, n, 3, GL_RGBA, GL_FLOAT, texels.data());
    }
    glTextureParameteri(mips, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(mips, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(mips, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(mips, GL_TEXTURE_WRAP_T, GL_REPEAT);
    glBindTextureUnit(5, mips);
    const uint32_t seed = 3u;
    const vec3 jitter(0.4f, 0.3f, 0.4f);
    const float window_size = 0.9f;
    // A 512-texel room texture seen over a few dozen pixels per room face: minified (LOD ~2..6), so
    // a wrong LOD would show (a magnified LOD would clamp at level 0 and hide it).
    const glm::vec3 cams[] = {{6.0f, 4.5f, 14.0f}, {1.0f, 8.0f, 2.0f}, {11.0f, 0.8f, 1.6f}};
    for (int varying = 0; varying < 2; ++varying) {
        const std::vector<ShaderDefine> defs = {{"RK_IM_SHADING", "1"}, {"RK_IM_VARYING_WALLS", std::to_string(varying)},
                                                {"RK_IM_COMPOSE_MODE", "1"}};
        SCOPED_TRACE(variant_name(defs));
        const GLuint prog = rig.program(defs, seed, jitter, window_size);
        if (!prog) continue;
        glUniform1f(glGetUniformLocation(prog, "u_variants"), 1.0f);
        long checked = 0, seam_checked = 0, wrong = 0;
        double worst = 0, lod_min = 1e9, lod_max = -1e9;
        std::string first_wrong;
        for (const glm::vec3& cam : cams) {
            const std::vector<float> img = rig.render(prog, cam);
            const glm::mat4 inv = glm::inverse(rig.view_proj(cam));
            // Per pixel: the room face it sees and the LOD its analytic derivatives give (CPU trace,
            // dp from the neighbouring pixel centres as dFdx/dFdy), -1 outside the windows.
            std::vector<int> face(static_cast<size_t>(W * H), -1);
            std::vector<double> want(static_cast<size_t>(W * H), 0.0);
            for (int y = 0; y + 1 < H; ++y)
                for (int x = 0; x + 1 < W; ++x) {
                    const size_t i = static_cast<size_t>(y * W + x);
                    if (img[4 * i + 3] < 0.0f || !rig.deep_in_window(inv, cam, x, y, window_size)) continue;
                    const float xf = static_cast<float>(x) + 0.5f, yf = static_cast<float>(y) + 0.5f;
                    const glm::vec3 p = FacadeRig::point_at(inv, cam, xf, yf, W, H);
                    const glm::vec3 dpx = FacadeRig::point_at(inv, cam, xf + 1.0f, yf, W, H) - p;
                    const glm::vec3 dpy = FacadeRig::point_at(inv, cam, xf, yf + 1.0f, W, H) - p;
                    const rk_im_hit h = varying ? rk_im_trace_varying_grad(p, cam, vec3(0, 0, 1), dpx, dpy, rig.grid, jitter, seed)
                                                : rk_im_trace_grad(p, cam, vec3(0, 0, 1), dpx, dpy, rig.grid);
                    if (!h.valid) continue;
                    face[i] = ((h.room.x * 31 + h.room.y) * 31 + h.room.z) * 8 + h.family * 2 + (h.side > 0 ? 1 : 0);
                    const double rho = size * std::max(glm::length(glm::dvec2(h.uv_dx)), glm::length(glm::dvec2(h.uv_dy)));
                    want[i] = std::clamp(std::log2(std::max(rho, 1e-30)), 0.0, static_cast<double>(levels - 1));
                }
            for (int y = 0; y + 1 < H; y += 2)
                for (int x = 0; x + 1 < W; x += 2) {
                    const size_t q[4] = {static_cast<size_t>(y * W + x), static_cast<size_t>(y * W + x + 1),
                                         static_cast<size_t>((y + 1) * W + x), static_cast<size_t>((y + 1) * W + x + 1)};
                    if (face[q[0]] < 0 || face[q[1]] < 0 || face[q[2]] < 0 || face[q[3]] < 0) continue;
                    double lo = 1e9, hi = -1e9;
                    bool seam = false;
                    for (size_t k : q) {
                        lo = std::min(lo, want[k]);
                        hi = std::max(hi, want[k]);
                        seam = seam || face[k] != face[q[0]];
                    }
                    for (size_t k : q) {
                        const double lod = 8.0 * static_cast<double>(img[4 * k]);
                        lod_min = std::min(lod_min, lod);
                        lod_max = std::max(lod_max, lod);
                        const double off = lod > hi ? lod - hi : (lod < lo ? lo - lod : 0.0);
                        ++checked;
                        seam_checked += seam ? 1 : 0;
                        if (off > worst) worst = off;
                        if (off > 0.5) {
                            if (first_wrong.empty())
                                first_wrong = rktest::fmt("pixel", static_cast<int>(k % static_cast<size_t>(W)), static_cast<int>(k / static_cast<size_t>(W)),
                                                          "cam", cam.x, cam.y, cam.z, "lod", lod, "quad predicts", lo, hi, "seam", seam ? 1 : 0);
                            ++wrong;
                        }
                    }
                }
        }
        glDeleteProgram(prog);
        std::printf("[render] mip LOD vs the analytic derivatives, %-40s %ld window pixels (LOD %.2f..%.2f), %ld in quads across "
                    "a room seam; worst distance from the quad's predicted range %.3f levels, beyond 0.5: %ld%s%s\n",
                    variant_name(defs).c_str(), checked, lod_min, lod_max, seam_checked, worst, wrong,
                    first_wrong.empty() ? "" : "; first: ", first_wrong.c_str());
        EXPECT_GT(seam_checked, 200);
        EXPECT_GT(lod_max, 2.0);  // minified: a wrong LOD could show
        EXPECT_EQ(wrong, 0);
    }
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    glDeleteTextures(1, &mips);
}
