// GPU parity for shaders/raykit/light_volume.glsl (see parity.hpp): the falloff, the spot factor, a
// sphere's screen rectangle and depth range, on the driver against the C++ build.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/light_volume.hpp"

using namespace raykit;
namespace dom = parity::dom;

namespace {

parity::Domain coord() { return {-8.0f, 8.0f, false, {0.0f, 1.0f, -1.0f}}; }
parity::Domain radius() { return {0.0f, 6.0f, false, {0.0f, 1.0f, 2.0f}}; }
parity::Domain dist2() { return {0.0f, 50.0f, false, {0.0f, 25.0f, 24.99f, 25.01f}}; }

}  // namespace

TEST(GpuParity, LightVolume)
{
    const char* L = "raykit/light_volume.glsl";
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_lv_window / rk_lv_point_falloff", L, (dist2(), dom::unit()), 2,
                  o[0] = rk_lv_window(a[0] * 0.04f);
                  o[1] = rk_lv_point_falloff(a[0], 0.04f, 1e-4f + 0.01f * a[1]);),
        RK_PARITY("rk_lv_spot_factor", L, (dom::signed_unit(), dom::signed_unit(), dom::unit()), 1,
                  float co = clamp(a[1], -1.0f, 1.0f);
                  o[0] = rk_lv_spot_factor(a[0], co, min(co + clamp(a[2], 0.0f, 1.0f), 1.0f));),
        // Views down -z: centres in front, behind and around the near plane.
        RK_PARITY("rk_lv_sphere_ndc_rect", L, (coord(), coord(), coord(), radius()), 4,
                  vec4 rc = rk_lv_sphere_ndc_rect(vec3(clamp(a[0], -8.0f, 8.0f), clamp(a[1], -8.0f, 8.0f), clamp(a[2], -8.0f, 8.0f)),
                                                  clamp(a[3], 0.0f, 6.0f), vec4(1.2f, 1.6f, 0.05f, -0.03f), 0.1f);
                  o[0] = rc.x; o[1] = rc.y; o[2] = rc.z; o[3] = rc.w;),
        RK_PARITY("rk_gb_window_depth / rk_lv_sphere_depth_range", L, (coord(), radius(), dom::unit()), 5,
                  vec3 k = rk_gb_depth_params(0.1f, 50.0f, a[2] > 0.5f);
                  o[0] = rk_gb_window_depth(abs(a[0]) + 0.1f, k);
                  vec2 d = rk_lv_sphere_depth_range(a[0], a[1], k);
                  o[1] = d.x; o[2] = d.y;
                  vec2 di = rk_lv_sphere_depth_range(a[0], a[1], rk_gb_depth_params(0.1f, 0.0f, true));
                  o[3] = di.x; o[4] = di.y;),
    };
    for (parity::Case& c : cases) {
        // Near the tangent rays and the near-plane chord the rectangle's bounds are ill-conditioned
        // (a square root of a difference): compare them at 1e-5 (its outward margin is 3e-5).
        if (c.name == "rk_lv_sphere_ndc_rect") c.abs_tol = 1e-5;
        const parity::Result r = parity::run(c, parity::shader_dir(), 8192);
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
}
