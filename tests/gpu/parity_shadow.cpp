// GPU parity for shaders/raykit/shadow.glsl (see parity.hpp): projection into the map, biases, the
// sample patterns, the penumbra width and cascade selection, and the omnidirectional lights' cube
// and dual-paraboloid lookups and texel widths, on the driver against the C++ build.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/shadow.hpp"

using namespace raykit;
namespace dom = parity::dom;

namespace {

parity::Domain coord() { return {-10.0f, 10.0f, false, {0.0f, 1.0f, -1.0f}}; }
parity::Domain dist() { return {0.0f, 120.0f, false, {0.0f, 10.0f, 30.0f, 60.0f, 120.0f}}; }
parity::Domain texels() { return {1.0f, 4096.0f, true, {256.0f, 1024.0f, 1.0f}}; }
parity::Domain guard() { return {0.5f, 1.0f, false, {1.0f, 0.99609375f, 0.96875f, 0.0f}}; }

}  // namespace

TEST(GpuParity, Shadow)
{
    const char* S = "raykit/shadow.glsl";
    std::vector<parity::Case> cases = {
        // A fixed spot-light shadow matrix built in the body (both languages), a point from the inputs.
        RK_PARITY("rk_sh_project", S, (coord(), coord(), coord()), 3,
                  mat4 m = mat4(vec4(0.6f, 0.1f, 0.2f, 0.0f), vec4(-0.1f, 0.7f, 0.1f, 0.0f), vec4(0.3f, -0.2f, -0.5f, -1.0f),
                                vec4(0.5f, 0.5f, 2.0f, 12.0f));
                  vec3 r = rk_sh_project(m, vec3(clamp(a[0], -10.0f, 10.0f), clamp(a[1], -10.0f, 10.0f), clamp(a[2], -10.0f, 10.0f)));
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_sh_slope_bias / rk_sh_normal_offset", S, (dom::signed_unit(), dom::unit()), 4,
                  o[0] = rk_sh_slope_bias(a[0], 1e-4f, 2e-3f, 0.01f);
                  vec3 p = rk_sh_normal_offset(vec3(1.0f, 2.0f, 3.0f), vec3(0.0f, 1.0f, 0.0f), a[0], 0.05f, 1.0f + a[1]);
                  o[1] = p.x; o[2] = p.y; o[3] = p.z;),
        // sin / cos of the angle: GLSL leaves their precision to the driver (compared at 1e-5).
        RK_PARITY("rk_sh_vogel_disk / rk_sh_rotate", S, (dom::unit(), dom::unit()), 4,
                  uint n = 16u; uint i = uint(clamp(a[0], 0.0f, 1.0f) * 15.0f);
                  vec2 v = rk_sh_vogel_disk(i, n, 6.2831853f * clamp(a[1], 0.0f, 1.0f));
                  vec2 r = rk_sh_rotate(vec2(0.3f, -0.4f), 6.2831853f * clamp(a[1], 0.0f, 1.0f));
                  o[0] = v.x; o[1] = v.y; o[2] = r.x; o[3] = r.y;),
        RK_PARITY("rk_sh_rotation", S, (dom::unit(), dom::unit()), 1,
                  o[0] = rk_sh_rotation(uvec2(uint(clamp(a[0], 0.0f, 1.0f) * 4000.0f), uint(clamp(a[1], 0.0f, 1.0f) * 4000.0f)));),
        RK_PARITY("rk_sh_pcss_penumbra", S, (dist(), dist(), dom::unit()), 1,
                  o[0] = rk_sh_pcss_penumbra(a[0], a[1], a[2]);),
        RK_PARITY("rk_sh_cube_ref_depth", S, (coord(), coord(), coord()), 1,
                  o[0] = rk_sh_cube_ref_depth(vec3(clamp(a[0], -10.0f, 10.0f), clamp(a[1], -10.0f, 10.0f), clamp(a[2], -10.0f, 10.0f)), 0.05f, 80.0f);),
        // The omnidirectional functions take raw inputs: the harness's adversarial values (±0,
        // denormals, 1e20, 1e30, ±FLT_MAX) reach every component of v and every parameter.
        RK_PARITY("rk_sh_finite / rk_sh_omni_distance", S, (coord(), coord(), coord()), 4,
                  o[0] = rk_sh_finite(a[0]);
                  o[1] = rk_sh_omni_distance(vec3(a[0], a[1], a[2]));
                  vec3 w = rk_sh_finite3(vec3(a[2], a[1], a[0]));
                  o[2] = w.x; o[3] = w.z;),
        RK_PARITY("rk_sh_omni_toward_light", S, (coord(), coord(), coord(), dom::range(0.0f, 20.0f)), 3,
                  vec3 r = rk_sh_omni_toward_light(vec3(a[0], a[1], a[2]), a[3]);
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_sh_cube_face_uv", S, (coord(), coord(), coord()), 3,
                  vec3 r = rk_sh_cube_face_uv(vec3(a[0], a[1], a[2]));
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_sh_cube_ref_depth (raw)", S, (coord(), coord(), coord(), dist(), dist()), 1,
                  o[0] = rk_sh_cube_ref_depth(vec3(a[0], a[1], a[2]), a[3], a[4]);),
        RK_PARITY("rk_sh_cube_ref_distance", S, (coord(), coord(), coord(), dist(), dist()), 2,
                  o[0] = rk_sh_cube_ref_distance(vec3(a[0], a[1], a[2]), min(a[3], a[4]), max(a[3], a[4]) + 1.0f);
                  o[1] = rk_sh_cube_ref_distance(vec3(a[0], a[1], a[2]), 0.05f, 80.0f);),
        RK_PARITY("rk_sh_cube_texel_world", S, (coord(), coord(), coord(), texels()), 1,
                  o[0] = rk_sh_cube_texel_world(vec3(a[0], a[1], a[2]), a[3]);),
        RK_PARITY("rk_sh_dp_lookup", S, (coord(), coord(), coord(), guard()), 3,
                  vec3 r = rk_sh_dp_lookup(vec3(a[0], a[1], a[2]), 0.05f, 80.0f, a[3]);
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_sh_dp_texel_world", S, (coord(), coord(), coord(), texels(), guard()), 1,
                  o[0] = rk_sh_dp_texel_world(vec3(a[0], a[1], a[2]), a[3], a[4]);),
        RK_PARITY("rk_sh_cascade_index / rk_sh_cascade_blend", S, (dist(), dom::unit()), 2,
                  o[0] = float(rk_sh_cascade_index(a[0], vec4(10.0f, 30.0f, 60.0f, 120.0f)));
                  o[1] = rk_sh_cascade_blend(a[0], 30.0f, 8.0f * a[1]);),
    };
    for (parity::Case& c : cases) {
        if (c.name == "rk_sh_vogel_disk / rk_sh_rotate" || c.name == "rk_sh_rotation") c.abs_tol = 1e-5;
        // rk_sh_rotation is fract() of a sum of products, RK_PRECISE so that no driver fuses it (the
        // H200 without it: fma(a, x, b y) in all 1,922 rows that moved, by up to 0.01 rad; bit-exact
        // with it). Angles a whole turn apart are one rotation: such rows are ties.
        if (c.name == "rk_sh_rotation")
            c.tie = [](const float*, const float* g, const float* h) { return std::abs(std::abs(g[0] - h[0]) - 6.2831853f) < 1e-3f; };
        const parity::Result r = parity::run(c, parity::shader_dir(), 8192);
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
}
