// GPU parity for shaders/raykit/edge_aa.glsl (see parity.hpp): the depth and normal edge terms,
// their combination and the blur offsets, on the driver against the C++ build.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/edge_aa.hpp"

using namespace raykit;
namespace dom = parity::dom;

TEST(GpuParity, EdgeAA)
{
    const char* E = "raykit/edge_aa.glsl";
    std::vector<parity::Case> cases = {
        // Nine depths around 0.5 from the inputs: planes, kinks and steps, all multiples of 2^-20 so
        // that the body's own sums are exact in both languages (a fused multiply-add would otherwise
        // round them differently and the kink ratio of a plane would measure that).
        RK_PARITY("rk_aa_depth_edge / rk_aa_kink", E, (dom::unit(), dom::unit(), dom::unit(), dom::unit(), dom::unit()), 2,
                  float q = 9.5367431640625e-7f;
                  float c = 0.5f; float gx = q * floor(1000.0f * (clamp(a[0], 0.0f, 1.0f) - 0.5f));
                  float gy = q * floor(1000.0f * (clamp(a[1], 0.0f, 1.0f) - 0.5f));
                  float k = a[2] > 0.5f ? q * floor(4000.0f * (clamp(a[3], 0.0f, 1.0f) - 0.5f)) : 0.0f;
                  float d00 = c - gx - gy; float d10 = c - gy; float d20 = c + gx - gy + k;
                  float d01 = c - gx; float d21 = c + gx + k; float d02 = c - gx + gy; float d12 = c + gy;
                  float d22 = c + gx + gy + k;
                  o[0] = rk_aa_depth_edge(d00, d10, d20, d01, c, d21, d02, d12, d22, 0.1f + 0.4f * clamp(a[4], 0.0f, 1.0f), 1e-5f);
                  o[1] = rk_aa_kink(d01, c, d21);),
        RK_PARITY("rk_aa_normal_edge / rk_aa_combine", E, (dom::signed_unit(), dom::signed_unit(), dom::unit()), 3,
                  vec3 n0 = vec3(0.0f, 1.0f, 0.0f);
                  vec3 n1 = normalize(vec3(clamp(a[0], -1.0f, 1.0f), 1.0f, clamp(a[1], -1.0f, 1.0f)));
                  float ne = rk_aa_normal_edge(n0, n0, n1, n0, n0, 0.1f);
                  o[0] = ne; o[1] = rk_aa_combine(clamp(a[2], 0.0f, 1.0f), ne, 0u); o[2] = rk_aa_combine(clamp(a[2], 0.0f, 1.0f), ne, 1u);),
        RK_PARITY("rk_aa_blur_offset", E, (dom::unit(), dom::unit()), 2,
                  vec2 v = rk_aa_blur_offset(uint(clamp(a[0], 0.0f, 1.0f) * 3.0f), a[1]);
                  o[0] = v.x; o[1] = v.y;),
    };
    for (parity::Case& c : cases) {
        // smoothstep and the kink's division at the thresholds: a few ulps (1e-5 absolute).
        c.abs_tol = 1e-5;
        const parity::Result r = parity::run(c, parity::shader_dir(), 8192);
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
}
