// svo_secondary.glsl (C++ build) against float64 optics:
//   - light through a slab of voxels obeys Snell's law: the ray inside bends to
//     sin(t) = sin(i) / n, leaves parallel to the incident ray, displaced by the textbook offset,
//     with Fresnel reflectance and (1 - R_in)(1 - R_out) exp(-a L) transmittance from the float64
//     formulas, at angles from 0 to 85 degrees, for indices 1.0 (no bend), 1.33, 1.5 and 2.4;
//   - total internal reflection inside the slab: the ray bounces between the faces until a side
//     face lets it out at the refraction angle of 1.5 sin(30 deg);
//   - Wilks's test: a sphere of index 1.5 with a hollow core, and the same sphere with a core of
//     index 1.0, send every ray out in the same direction from the same place;
//   - shadow rays: blocked by a one-voxel wall, never by the flat surface they leave, even at a
//     grazing 0.5 degrees;
//   - no NaN or Inf for hostile inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <random>
#include <vector>

#include "raykit/svo_secondary.hpp"
#include "reference/fresnel_ref.hpp"
#include "svo_test_pack.hpp"

using namespace raykit;

namespace {

/// A tree from a cell predicate at `depth` in the root [0, 2^depth]^3 (voxel = 1), with a material
/// stream from `material(cell)`.
template <class Inside, class Material>
SvoTree make_tree(uint32_t depth, Inside inside, Material material, std::vector<uint32_t>& material_ids)
{
    std::vector<glm::uvec3> cells;
    const uint32_t side = 1u << depth;
    for (uint32_t z = 0; z < side; ++z)
        for (uint32_t y = 0; y < side; ++y)
            for (uint32_t x = 0; x < side; ++x)
                if (inside(glm::uvec3(x, y, z))) cells.push_back(glm::uvec3(x, y, z));
    svotest::PackOptions po;
    po.root_min = glm::vec3(0.0f);
    po.root_size = float(side);
    SvoTree t = svotest::pack_cells(depth, cells, po);
    material_ids.assign(size_t(t.attr_count), 0u);
    svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t a) { material_ids[size_t(a)] = material(c); });
    return t;
}

}  // namespace

TEST(SvoSecondary, SlabObeysSnellsLaw)
{
    // A slab z in [60, 64) of a 128^3 grid (voxel = 1), all one medium: 4 voxels thick, so even a
    // ray at 85 degrees through index 1.0 leaves through the bottom face.
    std::vector<uint32_t> ids;
    const SvoTree t = make_tree(7, [](glm::uvec3 c) { return c.z >= 60u && c.z < 64u; }, [](glm::uvec3) { return 0u; }, ids);
    const std::vector<uint32_t> words = t.gpu_words();
    const rk_svo_tree tree = svo_trace_tree(t);
    double worst_dir = 0.0, worst_pos = 0.0, worst_T = 0.0, worst_R = 0.0, worst_in = 0.0;
    int cases = 0;
    for (double n : {1.0, 1.33, 1.5, 2.4}) {
        const glm::vec3 absorb(0.01f, 0.02f, 0.0f);
        const std::vector<glm::vec4> media = {glm::vec4(float(n), absorb.x, absorb.y, absorb.z)};
        const rk_svo_media_ref mref{ids.data(), media.data()};
        for (double deg : {0.0, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0}) {
            for (double az : {0.0, 0.7, 2.0}) {
                const double th = deg * RK_PI / 180.0;
                const glm::dvec3 d(std::sin(th) * std::cos(az), std::sin(th) * std::sin(az), -std::cos(th));
                const glm::dvec3 o = glm::dvec3(64.3, 63.7, 64.0) - 10.0 * d;
                const rk_svo_refraction r = rk_svo_refract_through(words.data(), tree, mref, glm::vec3(o), glm::vec3(d), 1.0f, 4u);
                ASSERT_TRUE(r.hit && r.complete) << n << " " << deg;
                ++cases;
                // Analytic: entry at z = 64, inside sin(t) = sin(i)/n, exit at z = 60, out parallel.
                const double te = (o.z - 64.0) / -d.z;
                const glm::dvec3 pe = o + te * d;
                const double st = std::sin(th) / n, ct = std::sqrt(1.0 - st * st);
                const glm::dvec3 din(st * std::cos(az), st * std::sin(az), -ct);
                const glm::dvec3 px = pe + (4.0 / ct) * din;
                worst_dir = std::max(worst_dir, glm::length(glm::dvec3(r.dir) - d));
                // The outgoing ray starts 1/64 voxel below the exit face: compare on the face.
                const glm::dvec3 ro(r.origin);
                const glm::dvec3 on_face = ro + ((60.0 - ro.z) / d.z) * d;
                worst_pos = std::max(worst_pos, glm::length(on_face - px));
                // Inside direction, from a march started at the entry (Snell's law itself).
                rk_svo_interface f = rk_svo_interface_at(glm::vec3(d), glm::vec3(0.0f, 0.0f, 1.0f), 1.0f, float(n));
                worst_in = std::max(worst_in, glm::length(glm::dvec3(glm::normalize(f.transmitted)) - din));
                // Fresnel and transmittance.
                const double R_in = ref::fresnel(std::cos(th), n), R_out = ref::fresnel(ct, 1.0 / n);
                worst_R = std::max(worst_R, std::abs(double(r.reflectance) - R_in));
                const double L = 4.0 / ct;
                for (int ch = 0; ch < 3; ++ch) {
                    const double T = (1.0 - R_in) * (1.0 - R_out) * std::exp(-double(absorb[ch]) * L);
                    worst_T = std::max(worst_T, std::abs(double(r.transmittance[ch]) - T) / T);
                }
                EXPECT_EQ(r.interfaces, n == 1.0 ? 0u + 1u : 2u) << n << " " << deg;  // entry (+ exit when bent)
            }
        }
    }
    std::printf("[secondary] slab, %d rays: outgoing direction within %.1e of the incident one, exit point within %.1e "
                "voxels of Snell's, inside direction within %.1e, Fresnel R within %.1e, transmittance within %.1e "
                "relative\n",
                cases, worst_dir, worst_pos, worst_in, worst_R, worst_T);
    EXPECT_LT(worst_dir, 2e-6);
    // Float positions in a 128-voxel root (ulp 7.6e-6 voxel at 64), amplified up to 11x by the
    // 85-degree entries; the traversal's own bound is 2e-6 root sizes = 2.6e-4 voxels per hit.
    EXPECT_LT(worst_pos, 1.5e-3);
    EXPECT_LT(worst_in, 2e-6);
    EXPECT_LT(worst_R, 2e-6);
    EXPECT_LT(worst_T, 2e-5);
}

TEST(SvoSecondary, TotalInternalReflectionInsideTheSlab)
{
    std::vector<uint32_t> ids;
    // Slab z in [24, 40), x in [8, 56), y everything.
    const SvoTree t = make_tree(6, [](glm::uvec3 c) { return c.z >= 24u && c.z < 40u && c.x >= 8u && c.x < 56u; },
                                [](glm::uvec3) { return 0u; }, ids);
    const std::vector<uint32_t> words = t.gpu_words();
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<glm::vec4> media = {glm::vec4(1.5f, 0.0f, 0.0f, 0.0f)};
    const rk_svo_media_ref mref{ids.data(), media.data()};
    // Inside, 60 degrees from the z axis (beyond the critical 41.8): bounces between z faces, then
    // hits the x = 56 side face at 30 degrees and leaves with sin(t) = 1.5 sin(30).
    const double th = 60.0 * RK_PI / 180.0;
    const glm::vec3 d(float(std::sin(th)), 0.0f, float(-std::cos(th)));
    const glm::vec3 p(20.25f, 30.5f, 35.0f);
    const rk_svo_march_result m = rk_svo_march(words.data(), tree, mref, p, d, glm::uvec3(20, 30, 35), 1.5f, glm::vec3(0.0f), 1.0f);
    ASSERT_TRUE(m.left);
    const double so = 1.5 * std::sin(30.0 * RK_PI / 180.0);
    const glm::dvec3 expect(std::sqrt(1.0 - so * so), 0.0, (m.dir.z < 0.0f ? -1.0 : 1.0) * so);
    std::printf("[secondary] TIR: %u interfaces (internal reflections + exit), left through x = %.4f, direction "
                "error %.1e\n",
                m.interfaces, double(m.exit_point.x), glm::length(glm::dvec3(m.dir) - expect));
    EXPECT_NEAR(m.exit_point.x, 56.0f, 1e-4f);
    EXPECT_EQ(m.exit_normal, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_LT(glm::length(glm::dvec3(m.dir) - expect), 2e-6);
    // Down from z = 35 to the z = 24 face (TIR at x = 20.25 + 11 tan 60 = 39.3), then up: the
    // x = 56 face comes first (at z = 24 + 16.7 / tan 60 = 33.6 < 40): one reflection, then the exit.
    EXPECT_EQ(m.interfaces, 2u);
}

TEST(SvoSecondary, HollowCoreEqualsCoreOfIndexOne)
{
    // Wilks: a sphere of index 1.5 (radius 26 voxels) with a core of radius 13 that is empty, or
    // filled with index 1.0: every ray must leave the same way.
    auto r2 = [](glm::uvec3 c) {
        const glm::dvec3 q = glm::dvec3(c) + 0.5 - 32.0;
        return glm::dot(q, q);
    };
    std::vector<uint32_t> ids_hollow, ids_core;
    const SvoTree hollow = make_tree(6, [&](glm::uvec3 c) { return r2(c) <= 26.0 * 26.0 && r2(c) > 13.0 * 13.0; },
                                     [](glm::uvec3) { return 0u; }, ids_hollow);
    const SvoTree core = make_tree(6, [&](glm::uvec3 c) { return r2(c) <= 26.0 * 26.0; },
                                   [&](glm::uvec3 c) { return r2(c) > 13.0 * 13.0 ? 0u : 1u; }, ids_core);
    const std::vector<glm::vec4> media = {glm::vec4(1.5f, 0.0f, 0.0f, 0.0f), glm::vec4(1.0f, 0.0f, 0.0f, 0.0f)};
    const std::vector<uint32_t> wh = hollow.gpu_words(), wc = core.gpu_words();
    const rk_svo_tree th = svo_trace_tree(hollow), tc = svo_trace_tree(core);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    int n = 0, through_core = 0, same = 0;
    double worst = 0.0;
    for (int i = 0; i < 3000; ++i) {
        // Rays from outside aimed at the sphere (some through the core).
        const glm::vec3 target = glm::vec3(32.0f) + 20.0f * glm::vec3(U(rng), U(rng), U(rng));
        const glm::vec3 o = glm::vec3(32.0f) + 60.0f * glm::normalize(glm::vec3(U(rng), U(rng), U(rng)) + glm::vec3(0.01f));
        const glm::vec3 d = glm::normalize(target - o);
        const rk_svo_refraction a = rk_svo_refract_through(wh.data(), th, rk_svo_media_ref{ids_hollow.data(), media.data()}, o, d, 1.0f, 8u);
        const rk_svo_refraction b = rk_svo_refract_through(wc.data(), tc, rk_svo_media_ref{ids_core.data(), media.data()}, o, d, 1.0f, 8u);
        if (!a.hit) continue;
        ++n;
        through_core += a.interfaces > 2u;
        const double e = glm::length(glm::dvec3(a.dir) - glm::dvec3(b.dir));
        worst = std::max(worst, e);
        // Same direction; the ray lines agree to a fraction of a voxel (the hollow path restarts
        // each entry 1/64 voxel off the face).
        const glm::dvec3 off = glm::dvec3(a.origin) - glm::dvec3(b.origin);
        const double line = glm::length(off - glm::dot(off, glm::dvec3(b.dir)) * glm::dvec3(b.dir));
        if (a.complete && b.complete && e < 1e-4 && line < 0.1) ++same;
    }
    std::printf("[secondary] hollow core vs core of index 1.0: %d rays hit (%d through the core), %d leave identically "
                "(direction within 1e-4, line within 0.1 voxel); worst direction difference %.1e\n",
                n, through_core, same, worst);
    EXPECT_GT(through_core, 300);
    EXPECT_GE(same, n - n / 200);  // edge and corner ties may send up to 0.5% differently
}

TEST(SvoSecondary, ShadowRays)
{
    // A floor z in [0, 4) and a one-voxel wall x = 32 on top of it, y in [16, 48), z in [4, 20).
    std::vector<uint32_t> ids;
    const SvoTree t = make_tree(6, [](glm::uvec3 c) { return c.z < 4u || (c.x == 32u && c.y >= 16u && c.y < 48u && c.z < 20u); },
                                [](glm::uvec3) { return 0u; }, ids);
    const std::vector<uint32_t> words = t.gpu_words();
    const rk_svo_tree tree = svo_trace_tree(t);
    int self = 0, blocked = 0, n = 0;
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    for (int i = 0; i < 4000; ++i) {
        // A point on the floor's top face, left of the wall.
        const glm::vec3 p(4.0f + 24.0f * U(rng), 20.0f + 24.0f * U(rng), 4.0f);
        // Light towards -x (away from the wall) at 0.5..60 degrees elevation: never shadowed.
        const float el = (0.5f + 59.5f * U(rng)) * RK_PI / 180.0f;
        const glm::vec3 away(-std::cos(el), 0.0f, std::sin(el));
        self += rk_svo_shadowed(words.data(), tree, p, glm::vec3(0.0f, 0.0f, 1.0f), t.depth, away, RK_FLT_MAX);
        // Light beyond the wall, low enough that the wall is in the way.
        const glm::vec3 lp(60.0f, p.y, 4.0f + (33.0f - p.x) * 0.2f + 2.0f);
        const glm::vec3 tl = lp - p;
        blocked += rk_svo_shadowed(words.data(), tree, p, glm::vec3(0.0f, 0.0f, 1.0f), t.depth, glm::normalize(tl), glm::length(tl));
        ++n;
    }
    std::printf("[secondary] shadow rays: %d of %d self-shadowed at 0.5-60 degrees, %d of %d blocked by a one-voxel wall\n",
                self, n, blocked, n);
    EXPECT_EQ(self, 0);
    EXPECT_EQ(blocked, n);
}

TEST(SvoSecondary, NoNanForHostileInputs)
{
    std::vector<uint32_t> ids;
    const SvoTree t = make_tree(5, [](glm::uvec3 c) { return (c.x + c.y + c.z) % 3u == 0u; }, [](glm::uvec3 c) { return c.x & 1u; }, ids);
    const std::vector<uint32_t> words = t.gpu_words();
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<glm::vec4> media = {glm::vec4(1.5f, 0.5f, 0.0f, 2.0f), glm::vec4(1e-3f, 0.0f, 1e3f, 0.0f)};
    const rk_svo_media_ref mref{ids.data(), media.data()};
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    const float vals[] = {0.0f, -0.0f, 1e-40f, 1.0f, -1.0f, 1e30f};
    for (int i = 0; i < 3000; ++i) {
        glm::vec3 o = glm::vec3(16.0f) + 40.0f * glm::vec3(U(rng), U(rng), U(rng));
        glm::vec3 d(U(rng), U(rng), U(rng));
        if (i % 3 == 0) d[i % 3] = vals[size_t(i) % 6];
        const rk_svo_refraction r = rk_svo_refract_through(words.data(), tree, mref, o, d, 1.0f, 6u);
        for (int k = 0; k < 3; ++k) {
            ASSERT_TRUE(std::isfinite(r.dir[k]) && std::isfinite(r.origin[k]) && std::isfinite(r.transmittance[k]) &&
                        std::isfinite(r.reflect_dir[k]))
                << i;
        }
        ASSERT_TRUE(std::isfinite(r.reflectance));
    }
}

TEST(SvoSecondary, OffsetsHoldAtDepth18AndFromFarCameras)
{
    // Depth 18 (voxel = 2^-18 of the root): a 16 x 16 floor patch at z = 0 and a wall 3 voxels thick
    // (x 8..10) on it. 2e-6 root sizes would be half a voxel here: the offset must come from the
    // voxel, not from the root.
    std::vector<glm::uvec3> cells;
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x) {
            cells.push_back({x, y, 0u});
            if (x >= 8u && x <= 10u)
                for (uint32_t z = 1; z <= 8; ++z) cells.push_back({x, y, z});
        }
    svotest::PackOptions po;
    po.root_min = glm::vec3(-0.5f);
    po.root_size = 1.0f;
    const SvoTree t = svotest::pack_cells(18, cells, po);
    const std::vector<uint32_t> words = t.gpu_words();
    const rk_svo_tree tree = svo_trace_tree(t);
    const float v = 1.0f / 262144.0f;
    int blocked = 0, self = 0, self_far = 0, n = 0, far_hits = 0;
    std::mt19937 rng(18);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 p = po.root_min + v * glm::vec3(5.0f + 2.5f * U(rng), 1.0f + 14.0f * U(rng), 1.0f);
        // Towards the wall, 1.5..3 voxels away, low: must be blocked.
        const glm::vec3 to_wall = glm::normalize(glm::vec3(1.0f, 0.0f, 0.3f * U(rng)));
        blocked += rk_svo_shadowed(words.data(), tree, p, glm::vec3(0.0f, 0.0f, 1.0f), 18u, to_wall, RK_FLT_MAX);
        // Away from the wall, grazing: nothing there.
        const glm::vec3 away = glm::normalize(glm::vec3(-1.0f, 0.0f, 0.01f + 0.5f * U(rng)));
        self += rk_svo_shadowed(words.data(), tree, p, glm::vec3(0.0f, 0.0f, 1.0f), 18u, away, RK_FLT_MAX);
        // The same from a primary hit seen from 100 root sizes away (the hit point carries the far
        // origin's rounding; the offset snaps it onto the face first).
        const glm::vec3 eye = p + 100.0f * glm::normalize(glm::vec3(-0.3f, 0.2f, 1.0f));
        const rk_svo_trace_hit h = rk_svo_trace(words.data(), tree, eye, p - eye, RK_FLT_MAX, glm::vec2(0.0f));
        if (h.hit && h.normal.z > 0.5f) {
            ++far_hits;
            const glm::vec3 q = rk_svo_hit_point(tree, eye, p - eye, h);
            self_far += rk_svo_shadowed(words.data(), tree, q, h.normal, h.level, away, RK_FLT_MAX);
        }
        ++n;
    }
    std::printf("[secondary] depth 18: %d of %d shadow rays blocked by a 3-voxel wall, %d self-shadowed, %d of %d hits "
                "seen from 100 root sizes self-shadowed\n",
                blocked, n, self, self_far, far_hits);
    EXPECT_EQ(blocked, n);
    EXPECT_EQ(self, 0);
    EXPECT_GT(far_hits, n / 2);
    EXPECT_EQ(self_far, 0);
}

TEST(SvoSecondary, ShaderDefaultsMatchTheHeader)
{
    // svo_secondary.hpp names its namespace from the macro defaults before including the .glsl;
    // the shader's own defaults must be the same values.
    std::ifstream f(std::string(RAYKIT_SHADER_DIR) + "/raykit/svo_secondary.glsl");
    ASSERT_TRUE(f.good());
    std::stringstream ss;
    ss << f.rdbuf();
    const std::string src = ss.str();
    EXPECT_NE(src.find("#define RK_SVO_SECONDARY_FRESNEL_FAST 0\n"), std::string::npos);
    EXPECT_NE(src.find("#define RK_SVO_SECONDARY_ABSORPTION 1\n"), std::string::npos);
    EXPECT_NE(src.find("#define RK_SVO_SECONDARY_MAX_STEPS 4096\n"), std::string::npos);
    static_assert(RK_SVO_SECONDARY_FRESNEL_FAST == 0 && RK_SVO_SECONDARY_ABSORPTION == 1 && RK_SVO_SECONDARY_MAX_STEPS == 4096,
                  "this translation unit uses the defaults");
}
