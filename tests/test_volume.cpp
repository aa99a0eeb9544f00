// volume.glsl (C++ build) against float64 (issue 16 item 2): the visible length of a sphere's chord
// against the scene depth (in front, inside, behind, the eye inside), the depth-buffer conversion
// for every convention, the opacity functions, the non-uniform sphere's optical depth against a
// quadrature, slice alphas composing to their target, the slice uv correction against its
// definition, and the thesis's two sphere pitfalls reproduced with their fixes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/volume.hpp"

using namespace raykit;
using glm::dvec3;

namespace {

TEST(Volume, SphereVisibleLengthAgainstFloat64)
{
    std::mt19937 rng(4u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double worst = 0.0;
    int cases[3] = {0, 0, 0};
    for (int i = 0; i < 100000; ++i) {
        const dvec3 c(u(rng) * 20.0, u(rng) * 20.0, -30.0 + u(rng) * 20.0);
        const double r = 0.5 + 4.0 * (u(rng) + 1.0);
        // A unit ray from the eye towards a point near the sphere.
        const dvec3 target = c + dvec3(u(rng), u(rng), u(rng)) * r * 1.2;
        const dvec3 d = glm::normalize(target);
        const double tc = glm::dot(c, d), b2 = glm::dot(c, c) - tc * tc, h2 = r * r - b2;
        const double t_scene = std::abs(u(rng)) * 60.0;
        double want = 0.0;
        if (h2 > 0.0) {
            const double h = std::sqrt(h2), a = std::max(tc - h, 0.0), b = std::min(tc + h, t_scene);
            want = std::max(b - a, 0.0);
            cases[t_scene < tc - h ? 0 : (t_scene > tc + h ? 2 : 1)]++;
        }
        const vec2 span = rk_ray_sphere(vec3(0.0f), vec3(d), vec3(c), float(r));
        const float got = rk_vol_visible_length(span, float(t_scene), 0.0f);
        // Near tangency the chord is ill-conditioned, as rk_ray_sphere documents: its bound is
        // 2.4 eps (|o - c| + r) (1 + r / h) per end; the visible length adds the two ends.
        if (h2 > 0.0 && h2 < 1e-8 * r * r) continue;
        const double bound = 2.0 * 2.4 * 5.96e-8 * (glm::length(c) + r) * (1.0 + r / std::sqrt(std::max(h2, 1e-300))) + 1e-6 * want;
        worst = std::max(worst, std::abs(double(got) - want) / bound);
    }
    std::printf("sphere visible length: max |error| %.3g of rk_ray_sphere's bound (both ends); scene in front %d, inside %d, behind %d\n",
                worst, cases[0], cases[1], cases[2]);
    EXPECT_LT(worst, 1.0);
    EXPECT_GT(cases[0], 1000);
    EXPECT_GT(cases[1], 1000);
    EXPECT_GT(cases[2], 1000);
    // Exact cases: a ray through the centre of a sphere at distance 10, radius 2.
    const vec2 s = rk_ray_sphere(vec3(0.0f), vec3(0, 0, -1), vec3(0, 0, -10), 2.0f);
    EXPECT_NEAR(rk_vol_visible_length(s, 100.0f, 0.0f), 4.0f, 1e-5f);  // behind: the whole chord
    EXPECT_NEAR(rk_vol_visible_length(s, 9.0f, 0.0f), 1.0f, 1e-5f);    // inside
    EXPECT_EQ(rk_vol_visible_length(s, 7.5f, 0.0f), 0.0f);             // in front
    // The eye inside: from the near plane on.
    const vec2 in = rk_ray_sphere(vec3(0.0f), vec3(0, 0, -1), vec3(0, 0, -1), 2.0f);
    EXPECT_NEAR(rk_vol_visible_length(in, 100.0f, 0.1f), 2.9f, 1e-5f);
    EXPECT_NEAR(rk_vol_visible_length(in, 2.0f, 0.1f), 1.9f, 1e-5f);
    // The miss path.
    const vec2 miss = rk_ray_sphere(vec3(0.0f), vec3(0, 0, -1), vec3(5, 0, -10), 2.0f);
    EXPECT_EQ(rk_vol_visible_length(miss, 100.0f, 0.0f), 0.0f);
    EXPECT_EQ(rk_vol_sphere_edge_fade(miss, 2.0f), 0.0f);
}

TEST(Volume, SlabAndPyramidSpans)
{
    const vec2 s = rk_vol_span_slab(10.0f, 4.0f);
    EXPECT_EQ(s, vec2(8.0f, 12.0f));
    EXPECT_GT(rk_vol_span_slab(10.0f, 0.0f).x, rk_vol_span_slab(10.0f, 0.0f).y);
    EXPECT_GT(rk_vol_span_slab(10.0f, -1.0f).x, rk_vol_span_slab(10.0f, -1.0f).y);
    EXPECT_EQ(rk_vol_span_pyramid(10.0f, 4.0f, vec2(0.0f)), vec2(8.0f, 12.0f));
    EXPECT_EQ(rk_vol_span_pyramid(10.0f, 4.0f, vec2(0.5f, -0.25f)), vec2(9.0f, 11.0f));  // T = 4 (1 - 0.5)
    EXPECT_GT(rk_vol_span_pyramid(10.0f, 4.0f, vec2(1.0f, 0.0f)).x, rk_vol_span_pyramid(10.0f, 4.0f, vec2(1.0f, 0.0f)).y);
    EXPECT_NEAR(rk_vol_visible_length(rk_vol_span_slab(10.0f, 4.0f), 11.0f, 0.0f), 3.0f, 1e-6f);
}

TEST(Volume, SceneDistanceFromEveryDepthConvention)
{
    const double n = 0.1, f = 500.0;
    std::mt19937 rng(8u);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    struct Conv {
        const char* name;
        bool reversed, infinite;
    };
    for (const Conv& cv : {Conv{"usual", false, false}, Conv{"reversed-Z", true, false}, Conv{"reversed-Z infinite", true, true}}) {
        const vec3 k = gbuffer_depth_params(n, cv.infinite ? std::numeric_limits<double>::infinity() : f, cv.reversed);
        double worst = 0.0;
        for (int i = 0; i < 20000; ++i) {
            const dvec3 d = glm::normalize(dvec3(u(rng) - 0.5, u(rng) - 0.5, -1.0));
            const double t = n / -d.z + u(rng) * 300.0;  // the along-ray distance
            const double z = t * -d.z;                     // along the view axis
            const double win = (1.0 / n - 1.0 / z) / (1.0 / n - (cv.infinite ? 0.0 : 1.0 / f));
            const float depth = float(cv.reversed ? 1.0 - win : win);
            const float got = rk_vol_scene_distance(depth, k, vec3(d));
            worst = std::max(worst, std::abs(double(got) - t) / t);
        }
        std::printf("scene distance from %s float depth: max relative error %.3g\n", cv.name, worst);
        // Reversed-Z float depth keeps ~3e-7 relative; the usual convention ~dist / n ulps.
        EXPECT_LT(worst, cv.reversed ? 1e-6 : 5e-3) << cv.name;
    }
    EXPECT_EQ(rk_vol_scene_distance(0.5f, gbuffer_depth_params(n, f, true), vec3(1, 0, 0)), RK_FLT_MAX);
    EXPECT_NEAR(rk_vol_near_distance(0.1f, glm::normalize(vec3(0.0f, 0.6f, -0.8f))), 0.125f, 1e-7f);
}

TEST(Volume, OpacityFunctions)
{
    for (int fn = 0; fn < 3; ++fn) {
        float prev = -1.0f;
        for (int i = 0; i <= 2000; ++i) {
            const float l = 3.0f * float(i) / 1000.0f;  // 0..6, l_full = 2
            const float a = fn == 0 ? rk_vol_opacity_linear(l, 2.0f) : fn == 1 ? rk_vol_opacity_log(l, 2.0f) : rk_vol_opacity_sqrt(l, 2.0f);
            EXPECT_GE(a, prev) << fn << " " << l;
            EXPECT_GE(a, 0.0f);
            EXPECT_LE(a, 1.0f);
            prev = a;
        }
    }
    EXPECT_EQ(rk_vol_opacity_linear(0.0f, 2.0f), 0.0f);
    EXPECT_EQ(rk_vol_opacity_log(0.0f, 2.0f), 0.0f);
    EXPECT_EQ(rk_vol_opacity_sqrt(0.0f, 2.0f), 0.0f);
    EXPECT_NEAR(rk_vol_opacity_log(2.0f, 2.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(rk_vol_opacity_log(1.0f, 2.0f), std::log(5.5) / std::log(10.0), 1e-6);
    EXPECT_NEAR(rk_vol_opacity_sqrt(0.5f, 2.0f), 0.5f, 1e-7f);
    for (float l : {0.0f, 0.01f, 1.0f, 10.0f, 1e30f})
        EXPECT_NEAR(rk_vol_opacity_beer(l, 0.7f), 1.0 - std::exp(-std::min(0.7 * double(l), 100.0)), 1e-7) << l;
}

TEST(Volume, FalloffSphereOpticalDepthAgainstQuadrature)
{
    std::mt19937 rng(2u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const dvec3 c(u(rng) * 3.0, u(rng) * 3.0, -10.0 + u(rng) * 3.0);
        const double r = 1.0 + 2.0 * std::abs(u(rng));
        const dvec3 d = glm::normalize(c + dvec3(u(rng), u(rng), u(rng)) * r);
        const double t0 = std::abs(u(rng)) * 8.0, t1 = t0 + std::abs(u(rng)) * 10.0;
        // Midpoint quadrature of rho0 (1 - |p - c|² / r²) inside the sphere, 20,000 steps.
        double want = 0.0;
        const int steps = 20000;
        for (int k = 0; k < steps; ++k) {
            const double t = t0 + (k + 0.5) * (t1 - t0) / steps;
            const double q = glm::dot(t * d - c, t * d - c) / (r * r);
            if (q < 1.0) want += 1.5 * (1.0 - q) * (t1 - t0) / steps;
        }
        const float got = rk_vol_optical_depth_falloff(vec3(0.0f), vec3(d), vec3(c), float(r), 1.5f, float(t0), float(t1));
        worst = std::max(worst, std::abs(double(got) - want) / (1.5 * r));
    }
    std::printf("falloff sphere optical depth: max |error| %.3g of rho0 r\n", worst);
    EXPECT_LT(worst, 2e-6);
}

TEST(Volume, SliceAlphasComposeToTheTarget)
{
    // A dense sweep: 2e5 values of a, log-spaced from 1e-30 to 0.5 and from 0.5 to 1 - 1e-7 in
    // 1 - a, each with slice counts 1..1024 of every shape; composed in double.
    double worst = 0.0;
    double worst_a = 0.0;
    uint worst_n = 0;
    std::mt19937 rng(17u);
    std::uniform_int_distribution<uint> nd(1u, 1024u);
    for (int i = 0; i < 200000; ++i) {
        const double f = double(i) / 199999.0;
        const double a = i < 100000 ? std::pow(10.0, -30.0 + 29.7 * (2.0 * f)) : 1.0 - std::pow(10.0, -0.301 - 6.7 * (2.0 * f - 1.0));
        const float af = float(std::min(a, 0.9999999));
        for (uint n : {1u, 2u, 5u, 9u, 79u, nd(rng)}) {
            const double s = rk_vol_slice_alpha(af, n);
            const double composed = -std::expm1(n * std::log1p(-s));
            const double e = std::abs(composed - double(af)) / double(af);
            if (e > worst) {
                worst = e;
                worst_a = double(af);
                worst_n = n;
            }
        }
    }
    std::printf("slice alphas composed (dense sweep): max relative error %.3g at a = %.9g, n = %u\n", worst, worst_a, worst_n);

    EXPECT_LT(worst, 5e-7);
    EXPECT_EQ(rk_vol_slice_alpha(1.0f, 5u), 1.0f);
    EXPECT_EQ(rk_vol_slice_alpha(0.0f, 5u), 0.0f);
    EXPECT_EQ(rk_vol_slice_alpha(0.5f, 0u), 0.0f);
    const std::vector<VolumeSlice> sl = volume_slices(9, 2.0f, 0.8f);
    ASSERT_EQ(sl.size(), 9u);
    EXPECT_NEAR(sl[4].offset, 0.0f, 1e-6f);
    EXPECT_NEAR(sl[4].half_size, 2.0f, 1e-6f);
    EXPECT_NEAR(sl[0].half_size, std::sqrt(4.0 - sl[0].offset * sl[0].offset), 1e-6);
    EXPECT_NEAR(sl[0].offset, -sl[8].offset, 1e-6f);
}

TEST(Volume, SliceUvCorrectionMapsAVertexToItsProjectionOnTheCentrePlane)
{
    std::mt19937 rng(6u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 20000; ++i) {
        const dvec3 eye(u(rng) * 5.0, u(rng) * 5.0, 10.0 + u(rng) * 3.0), s(u(rng), u(rng), u(rng));
        const dvec3 nrm = glm::normalize(eye - s);  // the slices face the eye
        const dvec3 au = glm::normalize(glm::cross(dvec3(0, 1, 0), nrm)), av = glm::cross(nrm, au);
        const double hw = 1.5, hh = 1.2;
        // A vertex of a slice offset along the normal.
        const dvec3 v = s + nrm * (u(rng) * 1.4) + au * (u(rng) * hw) + av * (u(rng) * hh);
        // Independent reference: the projection of v from the eye onto the centre plane, in double.
        const double t = glm::dot(s - eye, nrm) / glm::dot(v - eye, nrm);
        const dvec3 x = eye + t * (v - eye);
        const double wu = glm::dot(x - s, au) / (2.0 * hw) + 0.5, wv = glm::dot(x - s, av) / (2.0 * hh) + 0.5;
        const vec2 got = rk_vol_slice_uv(vec3(v), vec3(eye), vec3(s), vec3(nrm), vec3(au), vec3(av), vec2(float(hw), float(hh)));
        worst = std::max({worst, std::abs(double(got.x) - wu), std::abs(double(got.y) - wv)});
        // The centre slice's own vertices map to their planar coordinates.
        const dvec3 vc = s + au * (0.3 * hw) + av * (-0.2 * hh);
        const vec2 gc = rk_vol_slice_uv(vec3(vc), vec3(eye), vec3(s), vec3(nrm), vec3(au), vec3(av), vec2(float(hw), float(hh)));
        EXPECT_NEAR(gc.x, 0.65f, 2e-6f);
        EXPECT_NEAR(gc.y, 0.4f, 2e-6f);
    }
    std::printf("slice uv correction: max |uv error| %.3g\n", worst);
    EXPECT_LT(worst, 5e-6);
    // A vertex whose eye ray is parallel to the plane: the orthogonal projection, finite.
    const vec2 par = rk_vol_slice_uv(vec3(1, 0, 0), vec3(0, 0, 0), vec3(0, 0, -1), vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0), vec2(1.0f));
    EXPECT_NEAR(par.x, 1.0f, 1e-6f);
    EXPECT_NEAR(par.y, 0.5f, 1e-6f);
}

TEST(Volume, TheSpheresTwoPitfallsAndTheirFixes)
{
    // 1. The hard circular cut-off: a sphere of radius 1 at distance 10, rendered 400 pixels across
    // its billboard; opacity = log(L) with L of the chord (l_full = 2 r), along the scanline through
    // the centre. Without the edge fade the opacity jumps at the silhouette's pixel.
    const float r = 1.0f;
    const vec3 c(0.0f, 0.0f, -10.0f);
    float worst_plain = 0.0f, worst_fade = 0.0f, prev_plain = 0.0f, prev_fade = 0.0f;
    const double half = rk_vol_billboard_half_size(r, 10.0f);
    for (int i = 0; i <= 400; ++i) {
        const double x = -half + 2.0 * half * i / 400.0;
        const vec3 d = glm::normalize(vec3(float(x), 0.0f, -10.0f));
        const vec2 span = rk_ray_sphere(vec3(0.0f), d, c, r);
        const float l = rk_vol_visible_length(span, 1e30f, 0.0f);
        const float plain = rk_vol_opacity_log(l, 2.0f * r), faded = plain * rk_vol_sphere_edge_fade(span, r);
        if (i > 0) {
            worst_plain = std::max(worst_plain, std::abs(plain - prev_plain));
            worst_fade = std::max(worst_fade, std::abs(faded - prev_fade));
        }
        prev_plain = plain;
        prev_fade = faded;
    }
    std::printf("sphere silhouette: largest opacity step between neighbouring pixels %.3f plain, %.3f with rk_vol_sphere_edge_fade\n",
                double(worst_plain), double(worst_fade));
    EXPECT_GT(worst_plain, 0.15f) << "the thesis's cut-off is reproduced";
    EXPECT_LT(worst_fade, 0.04f);
    // 2. The billboard clipping the sphere: a billboard of half-size r (the thesis's) through the
    // centre, facing the eye at distance 3 r: some rays hit the sphere but pass outside the square.
    // With rk_vol_billboard_half_size none do.
    const float dist = 3.0f;
    const vec3 cc(0.0f, 0.0f, -dist);
    int clipped_thesis = 0, clipped_fixed = 0, hits = 0;
    const float fixed_half = rk_vol_billboard_half_size(r, dist);
    EXPECT_NEAR(fixed_half, r * 3.0 / std::sqrt(8.0), 1e-6);
    for (int j = -300; j <= 300; ++j)
        for (int i = -300; i <= 300; ++i) {
            const vec3 p(float(i) / 200.0f, float(j) / 200.0f, -dist);  // a point of the centre plane
            const vec3 d = glm::normalize(p);
            if (!rk_ray_hit(rk_ray_sphere(vec3(0.0f), d, cc, r))) continue;
            ++hits;
            if (std::max(std::abs(p.x), std::abs(p.y)) > r) ++clipped_thesis;
            if (std::max(std::abs(p.x), std::abs(p.y)) > fixed_half) ++clipped_fixed;
        }
    std::printf("billboard at the centre plane, eye at 3 r: %d of %d sphere-hitting rays pass outside a billboard of half-size r, %d outside "
                "rk_vol_billboard_half_size (%.4f r)\n",
                clipped_thesis, hits, clipped_fixed, double(fixed_half));
    EXPECT_GT(clipped_thesis, 100);
    EXPECT_EQ(clipped_fixed, 0);
    EXPECT_EQ(rk_vol_billboard_half_size(1.0f, 1.0f), RK_FLT_MAX);
    EXPECT_EQ(rk_vol_billboard_half_size(1.0f, 0.5f), RK_FLT_MAX);
}

TEST(Volume, MarchThroughADensityTexture)
{
    // A constant density: sigma times the chord inside the box, exactly (up to rounding).
    VolDensityCpu c;
    c.w = c.h = c.d = 4;
    c.v.assign(64, 0.5f);
    const vec3 lo(-1.0f), hi(1.0f);
    const vec3 dir = glm::normalize(vec3(0.1f, 0.05f, -1.0f));
    const vec3 o(0.0f, 0.0f, 5.0f);
    const vec2 span = rk_ray_box(o, dir, lo, hi);
    ASSERT_TRUE(rk_ray_hit(span));
    EXPECT_NEAR(rk_vol_march_box(c, o, dir, lo, hi, 0.0f, 100.0f, 2.0f, 7u, 0.5f), 2.0f * 0.5f * (span.y - span.x), 2e-6f);
    EXPECT_NEAR(rk_vol_march_box(c, o, dir, lo, hi, 0.0f, span.x + 0.25f, 2.0f, 7u, 0.5f), 0.25f, 2e-6f);  // cut by the scene
    EXPECT_EQ(rk_vol_march_box(c, o, dir, lo, hi, 0.0f, span.x - 0.1f, 2.0f, 7u, 0.5f), 0.0f);           // scene in front
    // A density linear in x (trilinear reproduces it exactly between the outer texel centres): the
    // midpoint rule is exact for it.
    VolDensityCpu ramp;
    ramp.w = ramp.h = ramp.d = 16;
    for (int z = 0; z < 16; ++z)
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) ramp.v.push_back((float(x) + 0.5f) / 16.0f);
    // A ray inside the middle of the box (x within the outer texel centres), density = (x + 1) / 2.
    const vec3 o2(-0.8f, 0.1f, 0.2f), d2 = glm::normalize(vec3(1.0f, 0.1f, -0.05f));
    const float t_end = 1.6f / d2.x;  // x from -0.8 to 0.8
    const double exact = double(t_end) * 0.5;  // the mean of (x + 1) / 2 over x in [-0.8, 0.8] is 0.5
    for (uint n : {1u, 3u, 17u})
        EXPECT_NEAR(rk_vol_march_box(ramp, o2, d2, lo, hi, 0.0f, t_end, 1.0f, n, 0.5f), exact, 3e-6 * exact) << n;
    // The falloff sphere sampled on a 64^3 grid against its exact optical depth: error by steps.
    VolDensityCpu sph;
    sph.w = sph.h = sph.d = 64;
    for (int z = 0; z < 64; ++z)
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) {
                const double px = (x + 0.5) / 32.0 - 1.0, py = (y + 0.5) / 32.0 - 1.0, pz = (z + 0.5) / 32.0 - 1.0;
                sph.v.push_back(float(std::max(0.0, 1.0 - (px * px + py * py + pz * pz))));
            }
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::printf("march through a 64^3 falloff sphere against its exact optical depth (rk_vol_optical_depth_falloff), 2,000 rays:\n");
    double prev = 1e9;
    for (uint n : {4u, 8u, 16u, 32u, 64u}) {
        double worst = 0.0, sum = 0.0;
        std::mt19937 r2(12u);
        for (int i = 0; i < 2000; ++i) {
            const vec3 oo(u(r2) * 0.9f, u(r2) * 0.9f, 4.0f), dd = glm::normalize(vec3(u(r2) * 0.1f, u(r2) * 0.1f, -1.0f));
            const float want = rk_vol_optical_depth_falloff(oo, dd, vec3(0.0f), 1.0f, 1.0f, 0.0f, 100.0f);
            const float got = rk_vol_march_box(sph, oo, dd, lo, hi, 0.0f, 100.0f, 1.0f, n, 0.5f);
            worst = std::max(worst, double(std::abs(got - want)));
            sum += std::abs(got - want);
        }
        std::printf("  %2u steps: max |error| %.4f, mean %.5f (of a centre chord's 1.333)\n", n, worst, sum / 2000.0);
        EXPECT_LT(worst, prev + 1e-3) << n;
        prev = worst;
        if (n == 16u) {
            EXPECT_LT(worst, 0.005);
        }
        if (n == 64u) {
            EXPECT_LT(worst, 0.005);
        }
    }
    // Bad input: finite.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (float a : {0.0f, 1e30f, -1e30f, 1e-40f})
        EXPECT_TRUE(std::isfinite(rk_vol_march_box(c, vec3(a), glm::normalize(vec3(1.0f, 1.0f, -1.0f)), vec3(a), vec3(-a), a, -a, a, 5000u, nan)));
    // A huge (finite) box, a ray along its diagonal, zero sigma or zero jitter: finite.
    const vec3 huge(3.0e38f), dg = glm::normalize(vec3(1.0f));
    for (float sg : {0.0f, 1.0f, 3.4028235e38f})
        for (float jt : {0.0f, 0.5f}) {
            const float tau = rk_vol_march_box(c, -huge, dg, -huge, huge, -3.4028235e38f, 3.4028235e38f, sg, 8u, jt);
            EXPECT_TRUE(std::isfinite(tau) && tau >= 0.0f) << sg << " " << jt;
        }
    const VolDensityCpu empty;
    EXPECT_EQ(rk_vol_density(empty, vec3(0.5f)), 0.0f);
}

TEST(Volume, BadInputGivesFiniteResults)
{
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const float vals[] = {0.0f, -0.0f, 1e-40f, -1e-40f, 1.0f, -1.0f, 1e30f, -1e30f, 3.4028235e38f, -3.4028235e38f};
    // NaN where a function documents it: the visible length and the slice alpha read it as 0.
    EXPECT_EQ(rk_vol_visible_length(vec2(0.0f, 1.0f), nan, 0.0f), 0.0f);
    EXPECT_EQ(rk_vol_visible_length(vec2(nan, 1.0f), 5.0f, 0.0f), 0.0f);
    EXPECT_EQ(rk_vol_slice_alpha(nan, 3u), 0.0f);
    EXPECT_EQ(rk_vol_opacity_beer(inf, 1.0f), 1.0f);
    for (float a : vals)
        for (float b : vals) {
            EXPECT_TRUE(std::isfinite(rk_vol_visible_length(vec2(a, b), a, b)));
            EXPECT_TRUE(std::isfinite(rk_vol_opacity_linear(a, b)) && std::isfinite(rk_vol_opacity_log(a, b)) &&
                        std::isfinite(rk_vol_opacity_sqrt(a, b)) && std::isfinite(rk_vol_opacity_beer(a, b)));
            EXPECT_TRUE(std::isfinite(rk_vol_billboard_half_size(a, b)));
            EXPECT_TRUE(std::isfinite(rk_vol_slice_alpha(a, 7u)));
            const vec2 s = rk_vol_span_slab(a, b);
            EXPECT_TRUE(std::isfinite(s.x) && std::isfinite(s.y));
            EXPECT_TRUE(std::isfinite(rk_vol_sphere_edge_fade(vec2(a, b), b)));
        }
    // Finite inputs to the functions taking vectors.
    const float fin[] = {0.0f, 1e-40f, 1.0f, -1.0f, 1e30f, -1e30f};
    for (float a : fin)
        for (float b : fin) {
            const float tau = rk_vol_optical_depth_falloff(vec3(a, b, 0.0f), glm::normalize(vec3(1.0f, 2.0f, -3.0f)), vec3(b, a, -1.0f), a, b, a, b);
            EXPECT_TRUE(std::isfinite(tau)) << a << " " << b;
            const vec2 uv = rk_vol_slice_uv(vec3(a), vec3(b), vec3(0.0f), vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0), vec2(a, b));
            EXPECT_TRUE(std::isfinite(uv.x) && std::isfinite(uv.y)) << a << " " << b;
            EXPECT_TRUE(std::isfinite(rk_vol_scene_distance(a, vec3(10.0f, 0.0f, 0.0f), vec3(0.0f, 0.0f, b))));
        }
}

}  // namespace
