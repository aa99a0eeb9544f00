// Tests of shaders/raykit/shadow.glsl (C++ build) and include/raykit/shadow.hpp: the shadow
// matrix against a float64 composition, the biases against their trigonometric definitions, the
// penumbra width against the geometry of a spherical light over a plane, cascade splits, the
// texel-snapped cascade fit (sub-texel camera moves leave the texel grid fixed in world space, and
// the box contains the slice), and the sample patterns (inside the disk, stratified, spaced,
// deterministic); for point lights, the cube-map face rule against GL's table and the faces'
// projections, the distance compare, the dual-paraboloid lookup and the texel widths against float64
// geometry, and every omnidirectional function on NaN, infinities and degenerate ranges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "adversarial_checks.hpp"
#include "raykit/shadow.hpp"

using namespace raykit;
using glm::dvec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// One unit in the last place of the float nearest |x| (at least that of the smallest normal).
double ulp_at(double x)
{
    const float f = std::max(float(std::abs(x)), std::numeric_limits<float>::min());
    return double(std::nextafter(f, std::numeric_limits<float>::infinity())) - double(f);
}

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
    // Degenerate inputs: NaN, infinities, n >= f, the largest floats.
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (const vec3& v : {vec3(nan), vec3(inf, -inf, 1.0f), vec3(3.4028235e38f), vec3(-3.4028235e38f, 0.0f, 1.0f), vec3(1e-40f)})
        for (const glm::vec2& nf : {glm::vec2(n, f), glm::vec2(f, n), glm::vec2(nan, nan), glm::vec2(inf, -inf), glm::vec2(3.4028235e38f)}) {
            EXPECT_TRUE(std::isfinite(rk_sh_cube_ref_depth(v, nf.x, nf.y))) << v.x << " " << nf.x << " " << nf.y;
            EXPECT_TRUE(std::isfinite(rk_sh_cube_ref_distance(v, nf.x, nf.y))) << v.x << " " << nf.x << " " << nf.y;
        }
    EXPECT_NEAR(rk_sh_cube_ref_depth(vec3(0.0f, 1e30f, 0.0f), n, f), double(f) / (double(f) - n), 1e-6) << "the limit beyond 1e18";
}

/// A float vector from a float64 one, each component rounded to float. Not inlined: at -O2/-O3,
/// GCC 12.2's vectoriser was seen to use the unrounded float64 values of an inlined conversion
/// later in the loop (a float member read back with 53 bits; right with -fno-tree-vectorize or
/// -fsanitize=undefined), which made the float64 references disagree with the inputs.
[[gnu::noinline]] vec3 to_float(const dvec3& d) { return vec3(float(d.x), float(d.y), float(d.z)); }

/// The GL cube-map table (GL 4.6 Table 8.19) in float64: the face of v and its (s, t).
glm::dvec3 gl_cube_face_uv(dvec3 v)
{
    const dvec3 a = glm::abs(v);
    int ax = 0;
    if (!(a.x >= a.y && a.x >= a.z)) ax = a.y >= a.z ? 1 : 2;
    double sc = 0.0, tc = 0.0, face = 0.0;
    if (ax == 0) {
        face = v.x < 0.0 ? 1.0 : 0.0;
        sc = v.x < 0.0 ? v.z : -v.z;
        tc = -v.y;
    } else if (ax == 1) {
        face = v.y < 0.0 ? 3.0 : 2.0;
        sc = v.x;
        tc = v.y < 0.0 ? -v.z : v.z;
    } else {
        face = v.z < 0.0 ? 5.0 : 4.0;
        sc = v.z < 0.0 ? -v.x : v.x;
        tc = -v.y;
    }
    return glm::dvec3(0.5 * (sc / a[ax] + 1.0), 0.5 * (tc / a[ax] + 1.0), face);
}

TEST(Shadow, OmniDistanceTowardTheLightAndSanitising)
{
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(rk_sh_finite(nan), 0.0f);
    EXPECT_EQ(rk_sh_finite(inf), 3.4028235e38f);
    EXPECT_EQ(rk_sh_finite(-inf), -3.4028235e38f);
    EXPECT_EQ(rk_sh_finite(-2.5f), -2.5f);
    EXPECT_EQ(rk_sh_finite(1e-40f), 1e-40f);
    std::mt19937 rng(31u);
    std::uniform_real_distribution<double> u(-1.0, 1.0), e(-60.0, 58.0), ul(0.0, 1.0);
    double worst_d = 0.0, worst_t = 0.0, worst_tv = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const vec3 v = to_float(dvec3(u(rng), u(rng), u(rng)) * std::exp2(e(rng)));
        const dvec3 vd(v);
        const double len = glm::length(vd);
        worst_d = std::max(worst_d, std::abs(double(rk_sh_omni_distance(v)) - len) / ulp_at(len));
        const float b = float(ul(rng) * len);
        const dvec3 want = vd * (1.0 - double(b) / len);
        const vec3 got = rk_sh_omni_toward_light(v, b);
        worst_tv = std::max(worst_tv, glm::length(dvec3(got) - want) / ulp_at(len));
        if (double(b) <= 0.5 * len)
            for (int k = 0; k < 3; ++k) worst_t = std::max(worst_t, std::abs(double(got[k]) - want[k]) / ulp_at(want[k]));
    }
    std::printf("rk_sh_omni_distance %.2f ulp; rk_sh_omni_toward_light %.2f ulp per component (bias <= |v|/2), %.2f ulp of |v|\n", worst_d,
                worst_t, worst_tv);
    EXPECT_LE(worst_d, 2.4);
    EXPECT_LE(worst_t, 4.5);
    EXPECT_LE(worst_tv, 2.2);
    // Edge cases.
    EXPECT_EQ(rk_sh_omni_distance(vec3(0.0f)), 0.0f);
    EXPECT_EQ(rk_sh_omni_distance(vec3(1e-40f, -1e-39f, 0.0f)), 0.0f) << "denormals count as zero";
    EXPECT_EQ(rk_sh_omni_distance(vec3(3.0f, -4.0f, 0.0f)), 5.0f);
    EXPECT_EQ(rk_sh_omni_distance(vec3(3.4028235e38f)), 1e18f) << "capped";
    EXPECT_EQ(rk_sh_omni_distance(vec3(nan, 3.0f, 4.0f)), 5.0f) << "NaN counts as 0";
    EXPECT_EQ(rk_sh_omni_distance(vec3(inf, 0.0f, 0.0f)), 1e18f);
    const vec3 v(0.3f, -2.0f, 1.7f);
    EXPECT_EQ(rk_sh_omni_toward_light(v, 0.0f), v) << "no bias, no move";
    EXPECT_EQ(rk_sh_omni_toward_light(v, nan), v) << "a NaN bias counts as 0";
    EXPECT_EQ(rk_sh_omni_toward_light(v, -1.0f), v) << "negative biases clamp to 0";
    EXPECT_EQ(rk_sh_omni_toward_light(v, 100.0f), vec3(0.0f)) << "never past the light";
    EXPECT_EQ(rk_sh_omni_toward_light(vec3(0.0f), 1.0f), vec3(0.0f));
    EXPECT_TRUE(rktest::adv::finite(rk_sh_omni_toward_light(vec3(inf, nan, -inf), inf)));
}

TEST(Shadow, CubeFaceUvIsTheGlRuleAndTheFaceRender)
{
    // Against the GL table in float64, and against the render of each face: lookAt(0, axis, up)
    // with up = -y for the side faces, +z for +Y, -z for -Y, and a 90-degree perspective: the
    // face's NDC (x, y) is (2 s - 1, 2 t - 1), so window row 0 is t = 0.
    const dvec3 axes[6] = {dvec3(1, 0, 0), dvec3(-1, 0, 0), dvec3(0, 1, 0), dvec3(0, -1, 0), dvec3(0, 0, 1), dvec3(0, 0, -1)};
    const dvec3 ups[6] = {dvec3(0, -1, 0), dvec3(0, -1, 0), dvec3(0, 0, 1), dvec3(0, 0, -1), dvec3(0, -1, 0), dvec3(0, -1, 0)};
    const glm::dmat4 proj = glm::perspective(glm::radians(90.0), 1.0, 0.05, 80.0);
    std::mt19937 rng(5u);
    std::uniform_real_distribution<double> u(-1.0, 1.0), e(-40.0, 40.0);
    double worst_table = 0.0, worst_render = 0.0;
    int per_face[6] = {};
    for (int i = 0; i < 200000; ++i) {
        const vec3 v = to_float(dvec3(u(rng), u(rng), u(rng)) * std::exp2(e(rng)));
        const vec3 got = rk_sh_cube_face_uv(v);
        const glm::dvec3 want = gl_cube_face_uv(dvec3(v));
        ASSERT_EQ(double(got.z), want.z) << v.x << " " << v.y << " " << v.z;
        worst_table = std::max({worst_table, std::abs(got.x - want.x), std::abs(got.y - want.y)});
        const int face = int(got.z);
        ++per_face[face];
        const glm::dvec4 c = proj * glm::lookAt(dvec3(0.0), axes[face], ups[face]) * glm::dvec4(dvec3(v) / std::exp2(std::floor(std::log2(glm::length(dvec3(v))))), 1.0);
        worst_render = std::max({worst_render, std::abs(0.5 * c.x / c.w + 0.5 - got.x), std::abs(0.5 * c.y / c.w + 0.5 - got.y)});
    }
    for (int c : per_face) EXPECT_GT(c, 30000);
    std::printf("rk_sh_cube_face_uv: %.3g against the GL table, %.3g against the faces' projections\n", worst_table, worst_render);
    EXPECT_LE(worst_table, 4.5e-8);
    EXPECT_LE(worst_render, 2e-7);
    // Texel centres of every face come back to their texel.
    for (int face = 0; face < 6; ++face)
        for (int j = 0; j < 16; ++j)
            for (int i = 0; i < 16; ++i) {
                const dvec3 right = glm::cross(axes[face], ups[face]), up = glm::cross(right, axes[face]);
                const double sc = (i + 0.5) / 8.0 - 1.0, tc = (j + 0.5) / 8.0 - 1.0;
                const vec3 got = rk_sh_cube_face_uv(vec3(axes[face] + sc * right + tc * up));
                ASSERT_EQ(int(got.z), face);
                ASSERT_EQ(int(std::floor(got.x * 16.0f)), i) << face;
                ASSERT_EQ(int(std::floor(got.y * 16.0f)), j) << face;
            }
    // Ties and degenerate input.
    EXPECT_EQ(rk_sh_cube_face_uv(vec3(1.0f, 1.0f, 1.0f)).z, 0.0f) << "x before y before z";
    EXPECT_EQ(rk_sh_cube_face_uv(vec3(0.0f, -1.0f, 1.0f)).z, 3.0f);
    EXPECT_EQ(rk_sh_cube_face_uv(vec3(-0.0f, 0.0f, 0.0f)), vec3(0.5f, 0.5f, 0.0f));
    EXPECT_EQ(rk_sh_cube_face_uv(vec3(-1e-40f, 0.0f, 0.0f)), vec3(0.5f, 0.5f, 0.0f)) << "all-denormal counts as zero";
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(rk_sh_cube_face_uv(vec3(nan, -2.0f, 1.0f)), vec3(0.5f, 0.25f, 3.0f)) << "NaN counts as 0";
    EXPECT_EQ(rk_sh_cube_face_uv(vec3(0.0f, 0.0f, -inf)), vec3(0.5f, 0.5f, 5.0f));
    EXPECT_EQ(rk_sh_cube_face_uv(vec3(3.4028235e38f, -3.4028235e38f, 1.0f)).z, 0.0f);
}

/// The largest singular value of the unit direction's derivative with respect to (a, b), by
/// central differences in float64: the angle one unit of (a, b) spans along its longer axis.
template <class F>
double angular_scale(F&& dir, double a, double b)
{
    const double h = 1e-6;
    const dvec3 da = (glm::normalize(dir(a + h, b)) - glm::normalize(dir(a - h, b))) / (2.0 * h);
    const dvec3 db = (glm::normalize(dir(a, b + h)) - glm::normalize(dir(a, b - h))) / (2.0 * h);
    const double p = glm::dot(da, da), q = glm::dot(da, db), r = glm::dot(db, db);
    return std::sqrt(0.5 * (p + r) + std::sqrt(0.25 * (p - r) * (p - r) + q * q));
}

TEST(Shadow, CubeRefDistanceAndTexelWidthAgainstFloat64)
{
    std::mt19937 rng(8u);
    std::uniform_real_distribution<double> u(-1.0, 1.0), ul(0.0, 1.0);
    double worst_ref = 0.0, worst_tw = 0.0, worst_jac = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const float n = float(0.01 + ul(rng)), f = n + float(0.001 + 100.0 * ul(rng));
        const vec3 v = to_float(glm::normalize(dvec3(u(rng), u(rng), u(rng))) * (2.0 * f * ul(rng)));
        const dvec3 vd(v);
        const double len = glm::length(vd), want = (len - n) / (double(f) - n);
        const double err = std::abs(double(rk_sh_cube_ref_distance(v, n, f)) - want);
        worst_ref = std::max(worst_ref, (err - 2.3 * ulp_at(len) / (double(f) - n)) / ulp_at(want));
        const float size = float(1 + int(ul(rng) * 4096.0));
        const double z = std::max({std::abs(vd.x), std::abs(vd.y), std::abs(vd.z)});
        const float tw = rk_sh_cube_texel_world(v, size);
        worst_tw = std::max(worst_tw, std::abs(double(tw) - 2.0 * z / size) / ulp_at(2.0 * z / size));
        // The texel's width across the ray from the face's geometry: |v| times the angle one texel
        // (1 / size of s or t) spans along its longer axis.
        if (len > 1e-3) {
            const glm::dvec3 ft = gl_cube_face_uv(vd);
            const int face = int(ft.z);
            const dvec3 axes[6] = {dvec3(1, 0, 0), dvec3(-1, 0, 0), dvec3(0, 1, 0), dvec3(0, -1, 0), dvec3(0, 0, 1), dvec3(0, 0, -1)};
            const dvec3 scs[6] = {dvec3(0, 0, -1), dvec3(0, 0, 1), dvec3(1, 0, 0), dvec3(1, 0, 0), dvec3(1, 0, 0), dvec3(-1, 0, 0)};
            const dvec3 tcs[6] = {dvec3(0, -1, 0), dvec3(0, -1, 0), dvec3(0, 0, 1), dvec3(0, 0, -1), dvec3(0, -1, 0), dvec3(0, -1, 0)};
            auto dir = [&](double s, double t) { return axes[face] + (2.0 * s - 1.0) * scs[face] + (2.0 * t - 1.0) * tcs[face]; };
            const double geom = len * angular_scale(dir, ft.x, ft.y) / size;
            worst_jac = std::max(worst_jac, std::abs(double(tw) / geom - 1.0));
        }
    }
    std::printf("rk_sh_cube_ref_distance: %.2f ulp beyond 2.3 ulp of |v| / (f - n); rk_sh_cube_texel_world %.2f ulp of 2 z / N, "
                "%.2g relative to the face geometry's texel width\n",
                worst_ref, worst_tw, worst_jac);
    EXPECT_LE(worst_ref, 1.9);
    EXPECT_LE(worst_tw, 0.5);
    EXPECT_LE(worst_jac, 1e-6);
    // The two ends of the face: 2 d / N at the centre, 2 d / (sqrt(3) N) at a corner.
    EXPECT_FLOAT_EQ(rk_sh_cube_texel_world(vec3(0.0f, 0.0f, -3.0f), 512.0f), 6.0f / 512.0f);
    EXPECT_NEAR(rk_sh_cube_texel_world(vec3(1.0f, 1.0f, 1.0f), 1.0f), 2.0 * glm::length(dvec3(1.0)) / std::sqrt(3.0), 1e-6);
    // Ends of the distance compare and degenerate ranges.
    EXPECT_EQ(rk_sh_cube_ref_distance(vec3(0.0f, 0.0f, 2.0f), 2.0f, 10.0f), 0.0f);
    EXPECT_EQ(rk_sh_cube_ref_distance(vec3(6.0f, 0.0f, -8.0f), 2.0f, 10.0f), 1.0f);
    EXPECT_EQ(rk_sh_cube_ref_distance(vec3(0.0f), 0.0f, 10.0f), 0.0f);
    EXPECT_EQ(rk_sh_cube_ref_distance(vec3(1.0f, 0.0f, 0.0f), 5.0f, 5.0f), -1e6f) << "n >= f: finite";
    EXPECT_TRUE(std::isfinite(rk_sh_cube_texel_world(vec3(3.4028235e38f), 0.0f)));
    EXPECT_EQ(rk_sh_cube_texel_world(vec3(std::numeric_limits<float>::quiet_NaN()), 512.0f), 0.0f);
}

TEST(Shadow, DualParaboloidLookupAndTexelWidthAgainstFloat64)
{
    std::mt19937 rng(9u);
    std::uniform_real_distribution<double> u(-1.0, 1.0), e(-30.0, 30.0), ul(0.0, 1.0);
    double worst_uv = 0.0, worst_depth = 0.0, worst_tw = 0.0, worst_geom = 0.0;
    const float n = 0.05f, f = 40.0f;
    for (int i = 0; i < 200000; ++i) {
        const vec3 v = to_float(dvec3(u(rng), u(rng), u(rng)) * (i % 2 ? 40.0 * ul(rng) : std::exp2(e(rng))));
        const float g = float(0.5 + 0.5 * ul(rng)), half = float(1 + int(ul(rng) * 4096.0));
        const dvec3 vd(v);
        const double len = glm::length(vd);
        if (len < 1e-30) continue;
        const double hemi = v.z > -1.17549435e-38f ? 1.0 : -1.0;
        const dvec3 d = vd / len;
        const double s = d.x / (1.0 + hemi * d.z), t = d.y / (1.0 + hemi * d.z);
        const double uu = 0.5 * (0.5 + 0.5 * g * s) + (hemi > 0.0 ? 0.0 : 0.5), vv = 0.5 + 0.5 * g * t;
        const vec3 got = rk_sh_dp_lookup(v, n, f, g);
        worst_uv = std::max({worst_uv, std::abs(got.x - uu), std::abs(got.y - vv)});
        const double depth = (len - n) / (double(f) - n);
        if (depth < 1e6)  // rk_paraboloid_depth_encode clamps there
            worst_depth = std::max(worst_depth, (std::abs(got.z - depth) - 2.3 * ulp_at(len) / (double(f) - n)) / ulp_at(depth));
        const double tw = len * 4.0 / ((1.0 + s * s + t * t) * g * half);
        const float tw_got = rk_sh_dp_texel_world(v, half, g);
        worst_tw = std::max(worst_tw, std::abs(double(tw_got) - tw) / ulp_at(tw));
        // The texel's width from the atlas's geometry: one texel is 1 / half of the half's uv; the
        // map is conformal, so the angle is the same along both axes.
        auto dir = [&](double a, double b) {
            const double ss = (2.0 * a - 1.0) / g, tt = (2.0 * b - 1.0) / g, r2 = ss * ss + tt * tt;
            return dvec3(2.0 * ss, 2.0 * tt, hemi * (1.0 - r2)) / (1.0 + r2);
        };
        const double geom = len * angular_scale(dir, 0.5 + 0.5 * g * s, 0.5 + 0.5 * g * t) / half;
        worst_geom = std::max(worst_geom, std::abs(double(tw_got) / geom - 1.0));
    }
    std::printf("rk_sh_dp_lookup: uv %.3g, depth %.2f ulp beyond 2.3 ulp of |v| / (f - n); rk_sh_dp_texel_world %.2f ulp, %.2g relative "
                "to the atlas geometry's texel width\n",
                worst_uv, worst_depth, worst_tw, worst_geom);
    EXPECT_LE(worst_uv, 1.2e-7);
    EXPECT_LE(worst_depth, 1.9);
    EXPECT_LE(worst_tw, 7.4);
    EXPECT_LE(worst_geom, 1e-6);
    // Texel centres of the atlas, disks and guard band: the lookup of the direction stored there
    // (rk_dual_paraboloid_dir) lands in that texel, or, past the rim, in the other half at the same
    // direction (the guard band holds the continuation).
    const int hs = 64;
    const float g = rk_dual_paraboloid_guard_scale(float(hs), 0.5f);
    int inside = 0, continued = 0;
    for (int j = 0; j < hs; ++j)
        for (int i = 0; i < 2 * hs; ++i) {
            const vec2 uv((float(i) + 0.5f) / float(2 * hs), (float(j) + 0.5f) / float(hs));
            const vec3 dir = rk_dual_paraboloid_dir(uv, g);
            const vec3 l = rk_sh_dp_lookup(dir * 7.0f, n, f, g);
            ASSERT_NEAR(l.z, (7.0 - n) / (double(f) - n), 1e-6);
            if (int(std::floor(l.x * float(2 * hs))) == i && int(std::floor(l.y * float(hs))) == j) {
                ++inside;
            } else {
                ASSERT_NE(i < hs, l.x < 0.5f) << "past the rim: the other half";
                ASSERT_LE(glm::length(dvec3(rk_dual_paraboloid_dir(vec2(l.x, l.y), g)) - dvec3(dir)), 1e-6);
                ++continued;
            }
        }
    EXPECT_GT(inside, int(0.75 * 2 * hs * hs));
    EXPECT_GT(continued, 0);
    // Degenerate input.
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const vec3 zero = rk_sh_dp_lookup(vec3(0.0f), n, f, g);
    EXPECT_EQ(zero.x, 0.25f);
    EXPECT_EQ(zero.y, 0.5f);
    EXPECT_LT(zero.z, 0.0f) << "the light's own position is lit";
    EXPECT_EQ(rk_sh_dp_texel_world(vec3(0.0f), 512.0f, g), 0.0f);
    for (const vec3& v : {vec3(nan), vec3(inf, -inf, nan), vec3(3.4028235e38f), vec3(1e-40f, -1e-40f, -1e-45f)}) {
        EXPECT_TRUE(rktest::adv::finite(rk_sh_dp_lookup(v, nan, inf, nan))) << v.x;
        EXPECT_TRUE(rktest::adv::finite(rk_sh_dp_lookup(v, f, n, 2.0f))) << v.x;
        EXPECT_TRUE(std::isfinite(rk_sh_dp_texel_world(v, nan, inf))) << v.x;
    }
    // The pole (largest texel) and the rim (half of it).
    EXPECT_NEAR(rk_sh_dp_texel_world(vec3(0.0f, 0.0f, -2.0f), 256.0f, 1.0f), 2.0 * 4.0 / 256.0, 1e-7);
    EXPECT_NEAR(rk_sh_dp_texel_world(vec3(2.0f, 0.0f, 0.0f), 256.0f, 1.0f), 2.0 * 2.0 / 256.0, 1e-7);
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
    // The omnidirectional functions take any float, NaN and infinities included.
    const Floats all = Floats::all();
    const Vecs allv = Vecs::all();
    ADV("rk_sh_finite / rk_sh_omni_distance / rk_sh_omni_toward_light", {
        const float x = G.f(all);
        const float fx = rk_sh_finite(x);
        CHECK(std::isfinite(fx) && (!std::isfinite(x) || fx == x), S(fx));
        const vec3 v = G.v3(allv);
        const float d = rk_sh_omni_distance(v);
        CHECK(std::isfinite(d) && d >= 0.0f && d <= 1e18f, S(d));
        const vec3 t = rk_sh_omni_toward_light(v, G.f(all));
        CHECK(finite(t), S(t));
    });
    ADV("rk_sh_cube_face_uv / rk_sh_cube_ref_depth / rk_sh_cube_ref_distance / rk_sh_cube_texel_world", {
        const vec3 v = G.v3(allv);
        const vec3 fu = rk_sh_cube_face_uv(v);
        CHECK(fu.x >= 0.0f && fu.x <= 1.0f && fu.y >= 0.0f && fu.y <= 1.0f && (fu.z == 0.0f || fu.z == 1.0f || fu.z == 2.0f ||
              fu.z == 3.0f || fu.z == 4.0f || fu.z == 5.0f), S(fu));
        const float n = G.f(all), f = G.f(all);
        const float rd = rk_sh_cube_ref_depth(v, n, f), rl = rk_sh_cube_ref_distance(v, n, f);
        CHECK(std::isfinite(rd) && std::isfinite(rl), S(rd) + " " + S(rl));
        const float tw = rk_sh_cube_texel_world(v, G.f(all));
        CHECK(std::isfinite(tw) && tw >= 0.0f, S(tw));
    });
    ADV("rk_sh_dp_lookup / rk_sh_dp_texel_world", {
        const vec3 v = G.v3(allv);
        const float n = G.f(all), f = G.f(all), g = G.f(all);
        const vec3 l = rk_sh_dp_lookup(v, n, f, g);
        CHECK(finite(l) && l.x >= 0.0f && l.x <= 1.0f && l.y >= 0.0f && l.y <= 1.0f, S(l));
        const float tw = rk_sh_dp_texel_world(v, G.f(all), g);
        CHECK(std::isfinite(tw) && tw >= 0.0f, S(tw));
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
