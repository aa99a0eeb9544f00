// Tests of shaders/raykit/shadow.glsl (C++ build) and include/raykit/shadow.hpp: the shadow
// matrix against a float64 composition, the biases against their trigonometric definitions, the
// penumbra width against the geometry of a spherical light over a plane, cascade splits, the
// texel-snapped cascade fit (sub-texel camera moves leave the texel grid fixed in world space, and
// the box contains the slice), and the sample patterns (inside the disk, stratified, spaced,
// deterministic).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "adversarial_checks.hpp"
#include "raykit/shadow.hpp"

using namespace raykit;
using glm::dvec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Shadow, BiasAndShadowMatrix)
{
    const mat4 bgl = shadow_bias_matrix(false), bzo = shadow_bias_matrix(true);
    EXPECT_EQ(bgl * vec4(-1, -1, -1, 1), vec4(0, 0, 0, 1));
    EXPECT_EQ(bgl * vec4(1, 1, 1, 1), vec4(1, 1, 1, 1));
    EXPECT_EQ(bzo * vec4(-1, 1, 0.25f, 1), vec4(0, 1, 0.25f, 1));
    // A spot light's shadow matrix: the point on its axis maps to the map's centre, and every point
    // matches the float64 composition B P V Vc^-1.
    const mat4 lv = glm::lookAt(vec3(3, 8, 2), vec3(0, 0, 0), vec3(0, 1, 0));
    const mat4 lp = glm::perspective(0.9f, 1.0f, 0.5f, 40.0f);
    const mat4 cv = glm::lookAt(vec3(-5, 2, 9), vec3(0, 1, 0), vec3(0, 1, 0));
    for (bool zo : {false, true}) {
        const mat4 s = shadow_matrix(lp, lv, glm::inverse(cv), zo);
        const vec3 on_axis = vec3(cv * vec4(vec3(3, 8, 2) * 0.4f, 1.0f));  // camera view space
        const vec3 uvz = rk_sh_project(s, on_axis);
        EXPECT_NEAR(uvz.x, 0.5f, 2e-6f);
        EXPECT_NEAR(uvz.y, 0.5f, 2e-6f);
        std::mt19937 rng(1u);
        std::uniform_real_distribution<double> u(-4.0, 4.0);
        for (int i = 0; i < 1000; ++i) {
            const glm::dvec4 pw(u(rng), u(rng) * 0.5, u(rng), 1.0);
            const glm::dvec4 c = glm::dmat4(lp) * glm::dmat4(lv) * pw;
            const dvec3 ndc = dvec3(c) / c.w;
            const dvec3 want(0.5 * ndc.x + 0.5, 0.5 * ndc.y + 0.5, zo ? ndc.z : 0.5 * ndc.z + 0.5);
            const vec3 got = rk_sh_project(s, vec3(glm::dmat4(cv) * pw));
            ASSERT_NEAR(got.x, want.x, 2e-5) << i;
            ASSERT_NEAR(got.y, want.y, 2e-5) << i;
            ASSERT_NEAR(got.z, want.z, 2e-5) << i;
        }
    }
    // A point in the light's plane (w = 0): finite.
    const vec3 r = rk_sh_project(mat4(0.0f), vec3(1.0f));
    EXPECT_TRUE(std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z));
}

TEST(Shadow, Biases)
{
    const float c0 = 1e-4f, slope = 2e-3f, mx = 0.01f;
    EXPECT_EQ(rk_sh_slope_bias(1.0f, c0, slope, mx), c0);
    EXPECT_EQ(rk_sh_slope_bias(0.0f, c0, slope, mx), mx);
    EXPECT_EQ(rk_sh_slope_bias(-0.5f, c0, slope, mx), mx);
    float prev = 0.0f;
    for (int i = 1000; i >= 1; --i) {
        const double ndl = i / 1000.0;
        const float b = rk_sh_slope_bias(float(ndl), c0, slope, mx);
        const double want = std::min(c0 + slope * std::tan(std::acos(ndl)), double(mx));
        ASSERT_NEAR(b, want, 1e-6 * want + 1e-9) << ndl;
        ASSERT_GE(b, prev);
        prev = b;
    }
    const vec3 p(1, 2, 3), n(0, 1, 0);
    EXPECT_EQ(rk_sh_normal_offset(p, n, 1.0f, 0.1f, 1.5f), p);
    const vec3 q = rk_sh_normal_offset(p, n, 0.0f, 0.1f, 1.5f);
    EXPECT_NEAR(q.y, 2.15f, 1e-6f);
    const vec3 h = rk_sh_normal_offset(p, n, 0.5f, 0.1f, 1.0f);
    EXPECT_NEAR(h.y - 2.0f, 0.1f * std::sqrt(0.75f), 1e-6f);
}

TEST(Shadow, PenumbraAgainstTheGeometryOfALightOverAPlane)
{
    // A spherical light of diameter w at height H over the receiver plane y = 0, a blocker's edge at
    // height hb: the penumbra on the receiver spans the points that see the light's far side past the
    // edge but not its near side. For a straight edge under a sphere the extreme rays touch the
    // sphere's silhouette seen from the edge; in the small-angle limit its width is w (H - ... ) by
    // similar triangles: w_p = w hb / (H - hb). Exact geometry (tangent rays to the sphere) below.
    for (double H : {4.0, 10.0})
        for (double hb : {0.5, 1.0, 2.0})
            for (double w : {0.05, 0.2, 0.5}) {
                // Edge at x = 0, height hb; light centre at (0, H). The two tangent lines from the edge
                // point to the light's circle hit y = 0 at x_a and x_b.
                const double dx = 0.0, dy = H - hb, dist = std::sqrt(dx * dx + dy * dy), rr = 0.5 * w;
                const double half = std::asin(rr / dist);
                const double width = hb * (std::tan(half) + std::tan(half));  // both tangents, symmetric
                const float got = rk_sh_pcss_penumbra(float(H), float(H - hb), float(w));
                // The similar-triangles estimate against the tangent-ray width: equal to first order
                // in w / (H - hb).
                const double rel = std::abs(double(got) - width) / width;
                ASSERT_LE(rel, 0.5 * (w / (H - hb)) * (w / (H - hb)) + 1e-6) << H << " " << hb << " " << w;
            }
    EXPECT_EQ(rk_sh_pcss_penumbra(5.0f, 5.0f, 1.0f), 0.0f) << "at contact";
    EXPECT_EQ(rk_sh_pcss_penumbra(4.0f, 5.0f, 1.0f), 0.0f) << "receiver in front of the blocker";
    EXPECT_TRUE(std::isfinite(rk_sh_pcss_penumbra(5.0f, 0.0f, 1.0f)));
}

TEST(Shadow, VogelDiskAndRotation)
{
    for (uint32_t n : {1u, 8u, 16u, 64u}) {
        const std::vector<vec2> v = vogel_disk(int(n));
        ASSERT_EQ(v.size(), n);
        for (uint32_t i = 0; i < n; ++i) {
            const double r = glm::length(glm::dvec2(v[i]));
            ASSERT_LE(r, 1.0 + 1e-7);
            ASSERT_NEAR(r, std::sqrt((i + 0.5) / n), 1e-6) << "equal areas hold equal counts";
        }
    }
    // Rotation: in [0, 2 pi), about uniform over a tile.
    int bins[8] = {};
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const float a = rk_sh_rotation(uvec2(x, y));
            ASSERT_GE(a, 0.0f);
            ASSERT_LT(a, 6.2831855f);
            ++bins[std::min(int(a / (2.0 * kPi) * 8.0), 7)];
        }
    for (int b : bins) EXPECT_NEAR(b, 512, 80);
    const vec2 r = rk_sh_rotate(vec2(1, 0), float(kPi / 2));
    EXPECT_NEAR(r.x, 0.0f, 1e-6f);
    EXPECT_NEAR(r.y, 1.0f, 1e-6f);
}

TEST(Shadow, CascadeSplitsIndexAndBlend)
{
    const vec4 u = cascade_splits(1.0f, 101.0f, 4, 0.0f), l = cascade_splits(1.0f, 10001.0f, 4, 1.0f);
    EXPECT_EQ(u, vec4(26, 51, 76, 101));
    EXPECT_NEAR(l.x, std::pow(10001.0, 0.25), 1e-3);
    EXPECT_NEAR(l.z, std::pow(10001.0, 0.75), 1e-2);
    EXPECT_EQ(l.w, 10001.0f);
    for (float lambda : {0.0f, 0.3f, 0.75f, 1.0f}) {
        const vec4 s = cascade_splits(0.1f, 500.0f, 3, lambda);
        EXPECT_LT(s.x, s.y);
        EXPECT_LT(s.y, s.z);
        EXPECT_EQ(s.z, 500.0f);
        EXPECT_EQ(s.w, 500.0f) << "unused cascades repeat far";
    }
    EXPECT_EQ(rk_sh_cascade_index(0.5f, u), 0u);
    EXPECT_EQ(rk_sh_cascade_index(26.0f, u), 1u);
    EXPECT_EQ(rk_sh_cascade_index(100.9f, u), 3u);
    EXPECT_EQ(rk_sh_cascade_index(101.0f, u), 4u);
    EXPECT_EQ(rk_sh_cascade_blend(20.0f, 26.0f, 4.0f), 0.0f);
    EXPECT_EQ(rk_sh_cascade_blend(24.0f, 26.0f, 4.0f), 0.5f);
    EXPECT_EQ(rk_sh_cascade_blend(26.0f, 26.0f, 4.0f), 1.0f);
    EXPECT_EQ(rk_sh_cascade_blend(25.0f, 26.0f, 0.0f), 0.0f);
}

mat4 camera_at(dvec3 eye, double yaw, double pitch)
{
    const dvec3 f(std::cos(pitch) * std::sin(yaw), std::sin(pitch), -std::cos(pitch) * std::cos(yaw));
    return glm::inverse(mat4(glm::lookAt(eye, eye + f, dvec3(0, 1, 0))));
}

TEST(Shadow, CascadeFitContainsTheSliceAndItsTexelGridStaysPut)
{
    const vec3 light = glm::normalize(vec3(0.4f, -1.0f, 0.3f));
    const int res = 1024;
    std::mt19937 rng(12u);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (bool zo : {false, true}) {
        const dvec3 eye0(120.0, 1.7, -340.0);
        const CascadeFit f0 = fit_cascade(camera_at(eye0, 0.3, -0.1), 1.0f, 1.6f, 2.0f, 30.0f, light, res, 50.0f, zo);
        EXPECT_NEAR(f0.size, f0.texel * res, 1e-9);
        for (int i = 0; i < 500; ++i) {
            // Sub-texel and multi-texel moves of the camera (no turn).
            const double step = (i % 2 ? 0.999 : 7.3) * f0.texel;
            const dvec3 eye = eye0 + step * dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
            const CascadeFit f = fit_cascade(camera_at(eye, 0.3, -0.1), 1.0f, 1.6f, 2.0f, 30.0f, light, res, 50.0f, zo);
            ASSERT_EQ(f.texel, f0.texel) << "the texel size never changes";
            const double kx = (f.left - f0.left) / f.texel, ky = (f.bottom - f0.bottom) / f.texel;
            ASSERT_NEAR(kx, std::round(kx), 1e-6) << "texel grid moved in world space";
            ASSERT_NEAR(ky, std::round(ky), 1e-6) << "texel grid moved in world space";
        }
        // Turning the camera changes the box position, never its size.
        for (int i = 0; i < 100; ++i) {
            const CascadeFit f = fit_cascade(camera_at(eye0, 6.0 * u(rng), u(rng) - 0.5), 1.0f, 1.6f, 2.0f, 30.0f, light, res, 50.0f, zo);
            ASSERT_EQ(f.texel, f0.texel) << i;
        }
        // The box contains every corner of the slice, with the caster margin towards the light.
        for (int i = 0; i < 200; ++i) {
            const mat4 cw = camera_at(eye0 + dvec3(u(rng), u(rng), u(rng)) * 50.0, 6.0 * u(rng), u(rng) - 0.5);
            const CascadeFit f = fit_cascade(cw, 1.0f, 1.6f, 2.0f, 30.0f, light, res, 50.0f, zo);
            const double ty = std::tan(0.5), tx = ty * 1.6;
            for (double d : {2.0, 30.0})
                for (int sy : {-1, 1})
                    for (int sx : {-1, 1}) {
                        const glm::dvec4 pw = glm::dmat4(cw) * glm::dvec4(sx * tx * d, sy * ty * d, -d, 1.0);
                        const glm::dvec4 c = glm::dmat4(f.projection) * glm::dmat4(f.view) * pw;
                        ASSERT_LE(std::abs(c.x / c.w), 1.0 + 1e-5);
                        ASSERT_LE(std::abs(c.y / c.w), 1.0 + 1e-5);
                        ASSERT_GE(c.z / c.w, (zo ? 0.0 : -1.0) - 1e-5);
                        ASSERT_LE(c.z / c.w, 1.0 + 1e-5);
                        // A caster 50 units towards the light is in front of the near plane too.
                        const glm::dvec4 cc = glm::dmat4(f.projection) * glm::dmat4(f.view) * (pw - glm::dvec4(dvec3(light) * 49.9, 0.0));
                        ASSERT_GE(cc.z / cc.w, (zo ? 0.0 : -1.0) - 1e-5);
                    }
        }
    }
}

/// Inverse of concentric_disk (for the stratification check).
glm::dvec2 concentric_inverse(glm::dvec2 p)
{
    const double r = glm::length(p);
    if (r == 0.0) return glm::dvec2(0.0);
    double phi = std::atan2(p.y, p.x);
    if (phi < -kPi / 4.0) phi += 2.0 * kPi;
    if (phi < kPi / 4.0) return glm::dvec2(r, r * phi / (kPi / 4.0));
    if (phi < 3.0 * kPi / 4.0) return glm::dvec2(-r * (phi - kPi / 2.0) / (kPi / 4.0), r);
    if (phi < 5.0 * kPi / 4.0) return glm::dvec2(-r, -r * (phi - kPi) / (kPi / 4.0));
    return glm::dvec2(r * (phi - 3.0 * kPi / 2.0) / (kPi / 4.0), -r);
}

TEST(Shadow, SamplePatterns)
{
    // The thesis's pattern: 2 x 4 strata, one sample each, inside the disk, deterministic.
    for (uint32_t seed : {1u, 2u, 99u}) {
        const std::vector<vec2> g = pcf_jittered_grid(2, 4, seed);
        ASSERT_EQ(g.size(), 8u);
        int cells[2][4] = {};
        for (const vec2& p : g) {
            ASSERT_LE(glm::length(glm::dvec2(p)), 1.0 + 1e-6);
            const glm::dvec2 s = concentric_inverse(glm::dvec2(p));
            const int i = std::min(int((s.x + 1.0) / 2.0 * 4.0), 3), j = std::min(int((s.y + 1.0) / 2.0 * 2.0), 1);
            ++cells[j][i];
        }
        for (auto& row : cells)
            for (int c : row) EXPECT_EQ(c, 1) << "one sample per stratum";
        EXPECT_EQ(pcf_jittered_grid(2, 4, seed), g) << "deterministic";
    }
    EXPECT_NE(pcf_jittered_grid(2, 4, 1u), pcf_jittered_grid(2, 4, 2u));
    // Poisson (best candidate): inside the disk, spaced, deterministic.
    for (int n : {4, 8, 16, 32, 64, 128, 256}) {
        const std::vector<vec2> p = poisson_disk(n, 7u);
        ASSERT_EQ(p.size(), size_t(n));
        double dmin = 1e9;
        for (size_t i = 0; i < p.size(); ++i) {
            ASSERT_LE(glm::length(glm::dvec2(p[i])), 1.0 + 1e-6);
            for (size_t j = 0; j < i; ++j) dmin = std::min(dmin, glm::length(glm::dvec2(p[i]) - glm::dvec2(p[j])));
        }
        EXPECT_GE(dmin, 0.6 / std::sqrt(double(n))) << n;
        EXPECT_EQ(poisson_disk(n, 7u), p);
    }
}

TEST(Shadow, CubeMapReferenceDepthMatchesTheFaceProjection)
{
    // The six faces of a cube shadow map, each rendered with perspective(90 degrees, 1, n, f) looking
    // down its axis: the depth a face stores for a point equals rk_sh_cube_ref_depth of its vector.
    const float n = 0.05f, f = 80.0f;
    const glm::dmat4 proj = glm::perspective(glm::radians(90.0), 1.0, double(n), double(f));
    const dvec3 axes[6] = {dvec3(1, 0, 0), dvec3(-1, 0, 0), dvec3(0, 1, 0), dvec3(0, -1, 0), dvec3(0, 0, 1), dvec3(0, 0, -1)};
    const dvec3 ups[6] = {dvec3(0, -1, 0), dvec3(0, -1, 0), dvec3(0, 0, 1), dvec3(0, 0, -1), dvec3(0, -1, 0), dvec3(0, -1, 0)};
    std::mt19937 rng(17u);
    std::normal_distribution<double> g;
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
        const dvec3 v = glm::normalize(dvec3(g(rng), g(rng), g(rng))) * (double(n) * std::pow(double(f) / n, std::abs(g(rng)) / 3.0));
        int face = 0;
        for (int k = 1; k < 6; ++k)
            if (glm::dot(v, axes[k]) > glm::dot(v, axes[face])) face = k;
        const glm::dvec4 c = proj * glm::lookAt(dvec3(0.0), axes[face], ups[face]) * glm::dvec4(v, 1.0);
        const double want = 0.5 * (c.z / c.w) + 0.5;
        const float got = rk_sh_cube_ref_depth(vec3(v), n, f);
        if (want >= 0.0 && want <= 1.0) worst = std::max(worst, std::abs(double(got) - want));
    }
    EXPECT_LE(worst, 4e-7) << "against the float64 face projection";
    EXPECT_NEAR(rk_sh_cube_ref_depth(vec3(0, f, 0), n, f), 1.0f, 1e-6f);
    EXPECT_NEAR(rk_sh_cube_ref_depth(vec3(0, 0, -n), n, f), 0.0f, 1e-7f);
    EXPECT_TRUE(std::isfinite(rk_sh_cube_ref_depth(vec3(0.0f), n, f)));
    EXPECT_TRUE(std::isfinite(rk_sh_cube_ref_depth(vec3(1.0f), 0.0f, 0.0f)));
}

TEST(Shadow, AdversarialInputsStayFinite)
{
    using rktest::adv::finite;
    using rktest::adv::Floats;
    using rktest::adv::S;
    using rktest::adv::Vecs;
    const Floats any = Floats::any();
    // Its domain: matrix entries and coordinates within 1e15 (the product must not overflow).
    const Vecs big = Vecs::of(Floats::range(-1e15f, 1e15f));
    ADV("rk_sh_project", {
        mat4 m;
        for (int c = 0; c < 4; ++c) m[c] = G.v4(big);
        CHECK(finite(rk_sh_project(m, G.v3(big))), "project");
    });
    ADV("rk_sh_slope_bias / rk_sh_normal_offset / rk_sh_pcss_penumbra", {
        const float ndl = G.f(any), c0 = G.f(Floats::range(0.0f, 1.0f)), sl = G.f(Floats::range(0.0f, 1.0f)), mx = G.f(Floats::range(0.0f, 1.0f));
        const float b = rk_sh_slope_bias(ndl, c0, sl, mx);
        CHECK(std::isfinite(b) && b <= mx, S(b));
        const vec3 q = G.v3(Vecs::of(Floats::range(-1e6f, 1e6f))), nn = G.v3(Vecs::units());
        const float tw = G.f(Floats::range(0.0f, 1e3f)), sc = G.f(Floats::range(0.0f, 10.0f));
        const vec3 p = rk_sh_normal_offset(q, nn, ndl, tw, sc);
        CHECK(finite(p), S(p));
        const float dr = G.f(any), db = G.f(any), wl = G.f(any);
        const float w = rk_sh_pcss_penumbra(dr, db, wl);
        CHECK(std::isfinite(w) && w >= 0.0f, S(w));
    });
    ADV("rk_sh_vogel_disk / rk_sh_rotation / rk_sh_cascade_*", {
        const uint32_t n = G.u(0u, 4096u), i = G.u(0u, 4096u);
        const float phi = G.f(Floats::range(-100.0f, 100.0f));
        const vec2 v = rk_sh_vogel_disk(i, n, phi);
        CHECK(finite(v), S(v));
        if (i < n) CHECK(glm::length(glm::dvec2(v)) <= 1.0 + 1e-6, S(v));
        const uint32_t px = G.u(), py = G.u();
        const float a = rk_sh_rotation(uvec2(px, py));
        CHECK(a >= 0.0f && a < 6.2831855f, S(a));
        const float d = G.f(any), sf = G.f(any), band = G.f(any);
        const float bl = rk_sh_cascade_blend(d, sf, band);
        CHECK(bl >= 0.0f && bl <= 1.0f, S(bl));
        CHECK(rk_sh_cascade_index(G.f(any), G.v4(Vecs::any())) <= 4u, "index");
    });
}

}  // namespace
