// Tests of shaders/raykit/edge_aa.glsl (C++ build): on a G-buffer rendered analytically (a floor, a
// back wall and a sphere, perspective, float depth of each convention), flat surfaces are never
// edges however steep, the sphere's silhouette and the wall-floor crease are; on constructed
// windows, a crease whose depth kink is slight defeats depth alone and the thesis's product of the
// two terms, and the normal term catches it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/edge_aa.hpp"
#include "raykit/svo_hybrid.hpp"

using namespace raykit;
using glm::dvec3;

namespace {

struct Gbuf {
    int w = 0, h = 0;
    std::vector<float> depth;
    std::vector<vec3> normal;
    std::vector<int> id;  // 0 floor, 1 wall, 2 sphere, -1 sky
};

/// Camera at (0, 1.5, 0) looking down -z and slightly down; floor y = 0, wall z = -12, a sphere.
Gbuf render(int w, int h, SvoDepthConvention conv)
{
    Gbuf g;
    g.w = w;
    g.h = h;
    const mat4 view = glm::lookAt(vec3(0.0f, 1.5f, 0.0f), vec3(0.0f, 0.8f, -10.0f), vec3(0, 1, 0));
    const mat4 proj = svo_perspective(1.1f, float(w) / float(h), 0.1f, conv == SvoDepthConvention::reversed_zero_to_one ? INFINITY : 100.0f, conv);
    const glm::dmat4 vp = glm::dmat4(proj) * glm::dmat4(view), inv = glm::inverse(vp);
    const dvec3 eye(0.0, 1.5, 0.0), sc(1.2, 1.0, -7.0);
    const double sr = 1.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double nx = (x + 0.5) / w * 2.0 - 1.0, ny = (y + 0.5) / h * 2.0 - 1.0;
            const glm::dvec4 far4 = inv * glm::dvec4(nx, ny, 0.5, 1.0);
            const dvec3 dir = glm::normalize(dvec3(far4) / far4.w - eye);
            double t = 1e30;
            int id = -1;
            dvec3 n(0.0);
            if (dir.y < 0.0) { const double tf = -eye.y / dir.y; if (tf < t) { t = tf; id = 0; n = dvec3(0, 1, 0); } }
            if (dir.z < 0.0) { const double tw = (-12.0 - eye.z) / dir.z; if (tw < t && eye.y + tw * dir.y >= 0.0) { t = tw; id = 1; n = dvec3(0, 0, 1); } }
            const dvec3 oc = eye - sc;
            const double b = glm::dot(oc, dir), c = glm::dot(oc, oc) - sr * sr, disc = b * b - c;
            if (disc > 0.0) { const double ts = -b - std::sqrt(disc); if (ts > 0.0 && ts < t) { t = ts; id = 2; n = glm::normalize(eye + ts * dir - sc); } }
            g.id.push_back(id);
            g.normal.push_back(vec3(n));
            float d = conv == SvoDepthConvention::reversed_zero_to_one ? 0.0f : 1.0f;
            if (id >= 0) d = rk_svo_window_depth(mat4(vp), vec3(eye + t * dir), conv == SvoDepthConvention::gl_minus_one_to_one ? vec2(0.5f, 0.5f) : vec2(1.0f, 0.0f));
            g.depth.push_back(d);
        }
    return g;
}

TEST(EdgeAA, FlatSurfacesAreNotEdgesSilhouettesAndCreasesAre)
{
    for (SvoDepthConvention conv : {SvoDepthConvention::gl_minus_one_to_one, SvoDepthConvention::reversed_zero_to_one}) {
        const Gbuf g = render(320, 240, conv);
        int flat = 0, flat_edges = 0, sil = 0, sil_found = 0, crease = 0, crease_normal = 0;
        for (int y = 1; y < g.h - 1; ++y)
            for (int x = 1; x < g.w - 1; ++x) {
                auto D = [&](int dx, int dy) { return g.depth[size_t(y + dy) * size_t(g.w) + size_t(x + dx)]; };
                auto N = [&](int dx, int dy) { return g.normal[size_t(y + dy) * size_t(g.w) + size_t(x + dx)]; };
                auto I = [&](int dx, int dy) { return g.id[size_t(y + dy) * size_t(g.w) + size_t(x + dx)]; };
                const float de = rk_aa_depth_edge(D(-1, -1), D(0, -1), D(1, -1), D(-1, 0), D(0, 0), D(1, 0), D(-1, 1), D(0, 1), D(1, 1), 0.2f, 1e-5f);
                const float ne = rk_aa_normal_edge(N(0, 0), N(-1, 0), N(1, 0), N(0, -1), N(0, 1), 0.1f);
                bool same = true, has_sky = false;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        same = same && I(dx, dy) == I(0, 0);
                        has_sky = has_sky || I(dx, dy) < 0;
                    }
                if (has_sky) continue;
                if (same && I(0, 0) != 2) {  // a window inside one plane
                    ++flat;
                    if (rk_aa_combine(de, ne, 0u) > 0.0f) ++flat_edges;
                }
                const bool sphere_rim = I(0, 0) == 2 && (I(-1, 0) != 2 || I(1, 0) != 2 || I(0, -1) != 2 || I(0, 1) != 2);
                if (sphere_rim) {
                    ++sil;
                    if (rk_aa_combine(de, ne, 0u) > 0.5f) ++sil_found;
                }
                const bool wall_floor = (I(0, 0) == 0 && (I(0, -1) == 1 || I(0, 1) == 1)) || (I(0, 0) == 1 && (I(0, -1) == 0 || I(0, 1) == 0));
                if (wall_floor) {
                    ++crease;
                    if (ne == 1.0f) ++crease_normal;
                }
            }
        EXPECT_GT(flat, 50000);
        EXPECT_EQ(flat_edges, 0) << "a plane is never an edge (" << flat << " windows)";
        EXPECT_GT(sil, 100);
        EXPECT_GE(sil_found, sil * 95 / 100) << "sphere silhouette found in " << sil_found << " of " << sil;
        EXPECT_GT(crease, 300);
        EXPECT_EQ(crease_normal, crease) << "the 90-degree crease is a full normal edge";
    }
}

TEST(EdgeAA, SlightDepthKinkDefeatsDepthAloneAndTheProduct)
{
    // A crease between two planes of 1/z slope 1.0 and 1.15 per pixel (a kink ratio of 0.07):
    // depth says smooth, the normals (90 degrees apart) say edge.
    const float s1 = 1e-4f, s2 = 1.15e-4f, c = 0.5f;
    auto d = [&](int x) { return x <= 0 ? c + s1 * float(x) : c + s2 * float(x); };
    const float de = rk_aa_depth_edge(d(-1), d(0), d(1), d(-1), d(0), d(1), d(-1), d(0), d(1), 0.2f, 1e-5f);
    const vec3 floor_n(0, 1, 0), wall_n(0, 0, 1);
    const float ne = rk_aa_normal_edge(floor_n, floor_n, wall_n, floor_n, floor_n, 0.1f);
    EXPECT_EQ(de, 0.0f) << "depth alone misses it";
    EXPECT_EQ(ne, 1.0f);
    EXPECT_EQ(rk_aa_combine(de, ne, 1u), 0.0f) << "the thesis's product misses it";
    EXPECT_EQ(rk_aa_combine(de, ne, 0u), 1.0f) << "the maximum catches it";
    // A step is a full depth edge; a plane none; the kink measure itself.
    EXPECT_EQ(rk_aa_kink(0.5f, 0.5f, 0.9f), 1.0f);
    EXPECT_EQ(rk_aa_kink(0.4f, 0.5f, 0.6f), 0.0f);
    EXPECT_NEAR(rk_aa_kink(0.4f, 0.5f, 0.62f), 0.02f / 0.22f, 1e-6f);
    EXPECT_EQ(rk_aa_depth_edge(0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.2f, 1e-5f), 0.0f);
}

TEST(EdgeAA, BlurOffsets)
{
    for (uint32_t k = 0; k < 4; ++k) {
        const vec2 z = rk_aa_blur_offset(k, 0.0f);
        EXPECT_TRUE(z.x == 0.0f && z.y == 0.0f) << "weight 0 reads the pixel itself";
        const vec2 o = rk_aa_blur_offset(k, 1.0f);
        EXPECT_EQ(std::abs(o.x), 0.5f);
        EXPECT_EQ(std::abs(o.y), 0.5f);
    }
    // The four offsets are symmetric: their mean is 0 (no shift of the image).
    vec2 sum(0.0f);
    for (uint32_t k = 0; k < 4; ++k) sum += rk_aa_blur_offset(k, 0.7f);
    EXPECT_EQ(sum, vec2(0.0f));
    EXPECT_EQ(rk_aa_blur_offset(0u, 5.0f), vec2(-0.5f, -0.5f)) << "edge clamped to 1";
    const vec2 nan_o = rk_aa_blur_offset(3u, std::nanf(""));
    EXPECT_TRUE(nan_o.x == 0.0f && nan_o.y == 0.0f) << "NaN edge reads the pixel";
}

}  // namespace
