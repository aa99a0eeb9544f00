// GPU parity for shaders/raykit/volume.glsl (see parity.hpp): spans, visible length, the depth
// conversion, the opacity functions, the falloff sphere's optical depth, the sphere's edge fade and
// billboard size, the slice uv correction and alpha, on the driver against the C++ build.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/volume.hpp"

using namespace raykit;
namespace dom = parity::dom;

namespace {
parity::Domain coord() { return {-4.0f, 4.0f, false, {0.0f, 1.0f, -1.0f}}; }
parity::Domain dist() { return {0.0f, 40.0f, false, {0.0f, 1.0f, 10.0f}}; }
}  // namespace

TEST(GpuParity, Volume)
{
    const char* S = "raykit/volume.glsl";
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_vol_span_slab / rk_vol_span_pyramid / rk_vol_visible_length", S, (dist(), dist(), dom::signed_unit(), dom::signed_unit()), 3,
                  vec2 s = rk_vol_span_slab(a[0], 0.25f * a[1]);
                  vec2 p = rk_vol_span_pyramid(a[0], 0.25f * a[1], vec2(a[2], a[3]));
                  o[0] = rk_vol_visible_length(s, a[1], 0.5f); o[1] = rk_vol_visible_length(p, a[1], 0.0f);
                  o[2] = s.y;),
        RK_PARITY("sphere: visible length, edge fade, optical depth", S, (coord(), coord(), dist(), dom::unit()), 3,
                  vec3 d = rk_normalize_safe(vec3(0.1f * a[0], 0.1f * a[1], -1.0f), vec3(0.0f, 0.0f, -1.0f));
                  vec2 sp = rk_ray_sphere(vec3(0.0f), d, vec3(0.3f, -0.2f, -12.0f), 1.0f + a[3]);
                  o[0] = rk_vol_visible_length(sp, a[2], 0.0f);
                  o[1] = rk_vol_sphere_edge_fade(sp, 1.0f + a[3]);
                  o[2] = rk_vol_optical_depth_falloff(vec3(0.0f), d, vec3(0.3f, -0.2f, -12.0f), 1.0f + a[3], 2.0f, 0.0f, a[2]);),
        RK_PARITY("rk_vol_scene_distance / rk_vol_near_distance", S, (dom::unit(), coord(), coord()), 2,
                  vec3 d = rk_normalize_safe(vec3(0.2f * a[1], 0.2f * a[2], -1.0f), vec3(0.0f, 0.0f, -1.0f));
                  o[0] = rk_vol_scene_distance(a[0], vec3(10.0f, 0.002f, 0.0f), d);
                  o[1] = rk_vol_near_distance(0.1f, d);),
        RK_PARITY("opacity functions", S, (dist(), dom::unit()), 4,
                  o[0] = rk_vol_opacity_linear(a[0], 10.0f * a[1]); o[1] = rk_vol_opacity_log(a[0], 10.0f * a[1]);
                  o[2] = rk_vol_opacity_sqrt(a[0], 10.0f * a[1]); o[3] = rk_vol_opacity_beer(a[0], a[1]);),
        RK_PARITY("rk_vol_billboard_half_size / rk_vol_slice_alpha", S, (dom::unit(), dist(), dom::unit()), 2,
                  o[0] = rk_vol_billboard_half_size(a[0], a[1]);
                  o[1] = rk_vol_slice_alpha(a[2], uint(1.0f + 78.0f * clamp(a[0], 0.0f, 1.0f)));),
        RK_PARITY("rk_vol_slice_uv", S, (coord(), coord(), coord()), 2,
                  vec3 n = rk_normalize_safe(vec3(0.1f, 0.2f, 1.0f), vec3(0.0f, 0.0f, 1.0f));
                  vec3 au = rk_normalize_safe(cross(vec3(0.0f, 1.0f, 0.0f), n), vec3(1.0f, 0.0f, 0.0f));
                  vec3 av = cross(n, au);
                  vec2 uv = rk_vol_slice_uv(vec3(a[0], a[1], 0.3f * a[2]), vec3(0.5f, 0.5f, 12.0f), vec3(0.0f), n, au, av, vec2(2.0f, 1.5f));
                  o[0] = uv.x; o[1] = uv.y;),
    };
    for (parity::Case& c : cases) {
        // log, exp, sqrt and division: the driver's precision (GLSL leaves it to the implementation);
        // the harness's default tolerances (2e-6 absolute + 2e-5 relative).
        const parity::Result r = parity::run(c, parity::shader_dir(), 8192);
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
}
