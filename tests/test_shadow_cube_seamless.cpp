// The CPU reference of seamless cube-map filtering (tests/reference/cube_seamless.hpp) checked on
// its own, before the GPU test (tests/gpu/parity_shadow_cube_seamless.cpp) holds the driver to it
// and tests/test_shadow_omni.cpp uses it: the texel taken across an edge is the mirror image of the
// edge texel in the plane between the two faces (and the mapping goes back); away from the edges,
// and everywhere without seamless filtering, it is the 2-D compare of shadow_filter.hpp on the
// face (rk_sh_compare at rk_sh_cube_face_uv); with it, the filtered value is continuous across
// every edge and at every corner, which the per-face clamp is not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "raykit/shadow_filter.hpp"
#include "reference/cube_seamless.hpp"

using glm::dvec3;
using rkref::CubeTexel;

namespace {

/// Six N x N faces of random depths in [0, 1].
struct RandomCube {
    int n;
    std::vector<float> d;
    RandomCube(int size, unsigned seed) : n(size), d(size_t(6 * size * size))
    {
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        for (float& x : d) x = u(rng);
    }
    float operator()(int f, int i, int j) const { return d[size_t((f * n + j) * n + i)]; }
};

dvec3 mirror(dvec3 x, dvec3 a, dvec3 b)
{
    const dvec3 nrm = glm::normalize(a - b);
    return x - 2.0 * glm::dot(x, nrm) * nrm;
}

}  // namespace

TEST(CubeSeamless, TexelAcrossIsTheMirrorImageOfTheEdgeTexel)
{
    long checked = 0;
    for (int n : {1, 2, 3, 8, 17}) {
        for (int f = 0; f < 6; ++f) {
            for (int k = 0; k < n; ++k) {
                const int out[4][2] = {{-1, k}, {n, k}, {k, -1}, {k, n}};
                for (const auto& o : out) {
                    const CubeTexel r = rkref::cube_texel_across(f, o[0], o[1], n);
                    const CubeTexel e{f, std::min(std::max(o[0], 0), n - 1), std::min(std::max(o[1], 0), n - 1)};
                    ASSERT_NE(r.face, f);
                    ASSERT_NE(r.face, f ^ 1) << "the opposite face";
                    ASSERT_TRUE(r.i == 0 || r.i == n - 1 || r.j == 0 || r.j == n - 1) << "on the neighbour's border";
                    // The two faces' texels along the shared edge are mirror images in the plane
                    // between the faces' axes (both faces are the same gnomonic grid).
                    const dvec3 de = glm::normalize(rkref::cube_texel_dir(e.face, e.i, e.j, n));
                    const dvec3 dr = glm::normalize(rkref::cube_texel_dir(r.face, r.i, r.j, n));
                    const dvec3 m = mirror(de, rkref::cube_ma(f), rkref::cube_ma(r.face));
                    ASSERT_LT(glm::length(m - dr), 1e-12) << "n " << n << " face " << f << " (" << o[0] << ", " << o[1] << ")";
                    // And back: r's out-of-face neighbour towards f is e.
                    int back = 0;
                    const int nb[4][2] = {{r.i - 1, r.j}, {r.i + 1, r.j}, {r.i, r.j - 1}, {r.i, r.j + 1}};
                    for (const auto& b : nb) {
                        if (b[0] >= 0 && b[0] < n && b[1] >= 0 && b[1] < n) continue;
                        const CubeTexel q = rkref::cube_texel_across(r.face, b[0], b[1], n);
                        if (q.face != f) continue;
                        EXPECT_EQ(q.i, e.i);
                        EXPECT_EQ(q.j, e.j);
                        ++back;
                    }
                    EXPECT_EQ(back, 1);
                    ++checked;
                }
            }
        }
    }
    EXPECT_EQ(checked, 6 * 4 * (1 + 2 + 3 + 8 + 17));
}

TEST(CubeSeamless, FaceInteriorsAndPerFaceClampAreThe2DCompare)
{
    // Against an independent implementation: shadow_filter.hpp's rk_sh_compare (the 2-D LINEAR
    // compare with CLAMP_TO_EDGE) on the face rk_sh_cube_face_uv picks. Per face it must agree
    // everywhere; seamless only where the footprint stays on the face.
    const int n = 8;
    const RandomCube cube(n, 7u);
    raykit::ShadowMapCpu face[6];
    for (int f = 0; f < 6; ++f) {
        face[f].width = face[f].height = n;
        face[f].depth.assign(cube.d.begin() + f * n * n, cube.d.begin() + (f + 1) * n * n);
    }
    std::mt19937 rng(5u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double worst_clamp = 0.0, worst_seamless = 0.0;
    long interior = 0, crossing = 0;
    for (int k = 0; k < 200000; ++k) {
        const dvec3 v(u(rng), u(rng), u(rng));
        const float ref = float(0.5 + 0.5 * u(rng));
        const raykit::vec3 st = raykit::rk_sh_cube_face_uv(raykit::vec3(v));
        const double twod = double(raykit::rk_sh_compare(face[int(st.z)], raykit::vec2(st.x, st.y), ref));
        worst_clamp = std::max(worst_clamp, std::abs(rkref::cube_compare(v, ref, n, false, cube) - twod));
        if (rkref::cube_footprint_crosses_edge(v, n)) {
            ++crossing;
            continue;
        }
        ++interior;
        worst_seamless = std::max(worst_seamless, std::abs(rkref::cube_compare(v, ref, n, true, cube) - twod));
    }
    std::printf("per-face clamp vs rk_sh_compare: max diff %.3g over 200000 directions; seamless, %ld interior lookups: %.3g (%ld cross an edge)\n",
                worst_clamp, interior, worst_seamless, crossing);
    // rk_sh_compare reads float (s, t) (4.5e-8 off, times N texels) and weighs in float.
    EXPECT_LT(worst_clamp, 1e-6);
    EXPECT_LT(worst_seamless, 1e-6);
    // Half a texel on either side of each of the four edges of an 8-texel face: 1 - (7/8)^2 = 23 %.
    EXPECT_GT(crossing, 200000 / 5);
    EXPECT_LT(crossing, 200000 / 4);
}

TEST(CubeSeamless, ContinuousAcrossEdgesAndCornersWhereThePerFaceClampJumps)
{
    // Points on the 12 edges, stepped 1e-9 to either side (the faces differ), and points near the 8
    // corners, perturbed by 1e-9 (three faces): seamless filtering is continuous, per-face clamping
    // is not.
    std::mt19937 rng(9u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int n : {2, 8, 16}) {
        const RandomCube cube(n, unsigned(100 + n));
        double seam_jump = 0.0, clamp_jump = 0.0, corner_seam = 0.0, corner_clamp = 0.0;
        for (int k = 0; k < 20000; ++k) {
            // An edge: two axes at +-1, the third free.
            const int free_axis = k % 3;
            dvec3 p;
            p[free_axis] = u(rng);
            p[(free_axis + 1) % 3] = u(rng) < 0.0 ? -1.0 : 1.0;
            p[(free_axis + 2) % 3] = u(rng) < 0.0 ? -1.0 : 1.0;
            dvec3 a = p, b = p;
            a[(free_axis + 1) % 3] *= 1.0 + 1e-9;  // this axis major
            b[(free_axis + 2) % 3] *= 1.0 + 1e-9;  // the other
            const double ref = 0.5 + 0.5 * u(rng);
            seam_jump = std::max(seam_jump, std::abs(rkref::cube_compare(a, ref, n, true, cube) - rkref::cube_compare(b, ref, n, true, cube)));
            clamp_jump = std::max(clamp_jump, std::abs(rkref::cube_compare(a, ref, n, false, cube) - rkref::cube_compare(b, ref, n, false, cube)));
            // A corner: each of the three axes major in turn.
            const dvec3 c(u(rng) < 0.0 ? -1.0 : 1.0, u(rng) < 0.0 ? -1.0 : 1.0, u(rng) < 0.0 ? -1.0 : 1.0);
            double vs[3], vc[3];
            for (int ax = 0; ax < 3; ++ax) {
                dvec3 q = c;
                q[ax] *= 1.0 + 1e-9;
                q[(ax + 1) % 3] *= 1.0 - 1e-9 * (0.5 + 0.5 * u(rng));
                vs[ax] = rkref::cube_compare(q, ref, n, true, cube);
                vc[ax] = rkref::cube_compare(q, ref, n, false, cube);
            }
            corner_seam = std::max({corner_seam, std::abs(vs[0] - vs[1]), std::abs(vs[1] - vs[2]), std::abs(vs[0] - vs[2])});
            corner_clamp = std::max({corner_clamp, std::abs(vc[0] - vc[1]), std::abs(vc[1] - vc[2]), std::abs(vc[0] - vc[2])});
        }
        std::printf("N %2d: largest jump across an edge, seamless %.3g, per-face clamp %.3g; at a corner %.3g, %.3g\n", n, seam_jump, clamp_jump,
                    corner_seam, corner_clamp);
        EXPECT_LT(seam_jump, 1e-7) << n;
        EXPECT_LT(corner_seam, 1e-7) << n;
        EXPECT_GT(clamp_jump, 0.4) << n << ": the test sees a jump where there is one";
        EXPECT_GT(corner_clamp, 0.4) << n;
    }
}

TEST(CubeSeamless, WeightsAndCorners)
{
    // The weights sum to 1; a constant cube reads its compare exactly, corners included, under both
    // corner rules; at a corner direction the three faces' texels count a third each.
    std::mt19937 rng(13u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = 4;
    long corners = 0;
    for (int k = 0; k < 100000; ++k) {
        dvec3 v(u(rng), u(rng), u(rng));
        if (k % 2) v = dvec3(v.x < 0 ? -1.0 : 1.0, v.y < 0 ? -1.0 : 1.0, v.z < 0 ? -1.0 : 1.0) + 0.1 * v;  // near a corner
        double w = 0.0;
        bool corner = false;
        for (const rkref::CubeTap& t : rkref::cube_linear_taps(v, n, true)) {
            w += t.weight;
            corner = corner || t.corner;
            ASSERT_GE(t.weight, 0.0);
        }
        corners += corner;
        ASSERT_NEAR(w, 1.0, 1e-12);
        for (auto rule : {rkref::CornerRule::average_results, rkref::CornerRule::average_depths}) {
            auto half = [](int, int, int) { return 0.5; };
            ASSERT_NEAR(rkref::cube_compare(v, 0.25, n, true, half, rule), 1.0, 1e-12);
            ASSERT_EQ(rkref::cube_compare(v, 0.75, n, true, half, rule), 0.0);
        }
    }
    EXPECT_GT(corners, 1000);
    // Exactly at the corner (1, 1, 1), read on +X (ties go to x): texels (0, 0) of +X, (N-1, N-1) of
    // +Y, (N-1, 0) of +Z, a quarter each, and the missing fourth from them.
    auto one_lit = [n](int f, int i, int j) { return f == 2 && i == n - 1 && j == n - 1 ? 1.0 : 0.0; };
    EXPECT_NEAR(rkref::cube_compare(dvec3(1, 1, 1), 0.5, n, true, one_lit), 1.0 / 3.0, 1e-15);
    EXPECT_NEAR(rkref::cube_compare(dvec3(1, 1, 1), 0.5, n, true, one_lit, rkref::CornerRule::average_depths), 0.25, 1e-15);
}
