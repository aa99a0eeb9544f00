// GPU parity for shaders/raykit/normalmap.glsl (see parity.hpp): tangent frames (stored tangent and
// derivative-based), perturbation, two-channel unpacking and parallax, on the driver against the C++
// build.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/normalmap.hpp"

using namespace raykit;
namespace dom = parity::dom;

namespace {

parity::Domain comp() { return {-2.0f, 2.0f, false, {0.0f, 1.0f, -1.0f}}; }

}  // namespace

TEST(GpuParity, NormalMap)
{
    const char* M = "raykit/normalmap.glsl";
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_nm_tbn / rk_nm_perturb", M, (comp(), comp(), comp(), comp(), comp(), comp(), dom::signed_unit()), 12,
                  mat3 f = rk_nm_tbn(vec3(a[0], a[1], a[2]), vec4(a[3], a[4], a[5], a[6]));
                  vec3 p = rk_nm_perturb(f, vec3(0.3f, -0.4f, 0.8f));
                  o[0] = f[0].x; o[1] = f[0].y; o[2] = f[0].z; o[3] = f[1].x; o[4] = f[1].y; o[5] = f[1].z;
                  o[6] = f[2].x; o[7] = f[2].y; o[8] = f[2].z; o[9] = p.x; o[10] = p.y; o[11] = p.z;),
        RK_PARITY("rk_nm_basis_tangent", M, (comp(), comp(), comp()), 3,
                  vec3 n = rk_normalize_safe(vec3(a[0], a[1], a[2]), vec3(0.0f, 0.0f, 1.0f));
                  vec3 t = rk_nm_basis_tangent(n);
                  o[0] = t.x; o[1] = t.y; o[2] = t.z;),
        RK_PARITY("rk_nm_cotangent_frame", M, (comp(), comp(), comp(), comp(), comp(), comp(), comp()), 9,
                  vec3 n = vec3(0.0f, 0.0f, 1.0f);
                  mat3 f = rk_nm_cotangent_frame(n, vec3(a[0], a[1], 0.1f * a[6]), vec3(a[2], a[3], 0.0f), vec2(a[4], a[5]),
                                                 vec2(a[5] - a[4], a[4] + 0.5f));
                  o[0] = f[0].x; o[1] = f[0].y; o[2] = f[0].z; o[3] = f[1].x; o[4] = f[1].y; o[5] = f[1].z;
                  o[6] = f[2].x; o[7] = f[2].y; o[8] = f[2].z;),
        RK_PARITY("rk_nm_unpack_rg", M, (dom::unit(), dom::unit()), 3,
                  vec3 n = rk_nm_unpack_rg(vec2(a[0], a[1]));
                  o[0] = n.x; o[1] = n.y; o[2] = n.z;),
        RK_PARITY("rk_nm_parallax_offset", M, (dom::unit(), dom::unit(), dom::unit(), comp(), comp()), 2,
                  vec3 v = rk_normalize_safe(vec3(a[3], a[4], 1.0f), vec3(0.0f, 0.0f, 1.0f));
                  vec2 uv = rk_nm_parallax_offset(vec2(a[0], a[1]), a[2], v, 0.04f, -0.02f);
                  o[0] = uv.x; o[1] = uv.y;),
    };
    for (parity::Case& c : cases) {
        // Frames of nearly parallel inputs and z near the unit circle are ill-conditioned (a
        // Gram-Schmidt residue, a square root of a difference): absolute 1e-5 there.
        c.abs_tol = 1e-5;
        const parity::Result r = parity::run(c, parity::shader_dir(), 8192);
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
}
