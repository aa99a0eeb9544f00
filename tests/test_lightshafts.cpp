// lightshafts.glsl (C++ build) against a ray-marched reference with shadow rays (issue 16 item 5):
// a camera looking towards a low sun through a row of pillars over a ground plane, in homogeneous
// fog. The reference in-scattered radiance of each pixel marches the camera ray through the fog
// (single scattering, Henyey-Greenstein phase, extinction) and casts a shadow ray to the sun from
// every step, in double. The screen-space shafts (occlusion buffer: the sun's disk where the sky is
// seen, 0 on geometry; radial accumulation) are compared with it after the best-fit scale (the
// effect's gain is an artistic parameter): correlation and relative RMS error. Printed numbers are
// docs/lightshafts.md's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/lightshafts.hpp"

using namespace raykit;
using glm::dvec3;

namespace {

constexpr int W = 160, H = 120;

struct Box {
    dvec3 lo, hi;
};

struct Scene {
    std::vector<Box> boxes;
    double ground = -3.0;
    bool hit(dvec3 o, dvec3 d, double tmax, double& t) const
    {
        t = tmax;
        bool any = false;
        if (d.y < 0.0) {
            const double tg = (ground - o.y) / d.y;
            if (tg > 1e-9 && tg < t) {
                t = tg;
                any = true;
            }
        }
        for (const Box& b : boxes) {
            double t0 = 1e-9, t1 = t;
            bool ok = true;
            for (int a = 0; a < 3 && ok; ++a) {
                if (d[a] == 0.0) {
                    ok = o[a] >= b.lo[a] && o[a] <= b.hi[a];
                    continue;
                }
                double ta = (b.lo[a] - o[a]) / d[a], tb = (b.hi[a] - o[a]) / d[a];
                if (ta > tb) std::swap(ta, tb);
                t0 = std::max(t0, ta);
                t1 = std::min(t1, tb);
                ok = t0 <= t1;
            }
            if (ok && t0 < t) {
                t = t0;
                any = true;
            }
        }
        return any;
    }
};

Scene pillars()
{
    Scene s;
    for (int i = -4; i <= 4; ++i) s.boxes.push_back({dvec3(3.0 * i - 0.6, -3.0, -31.0), dvec3(3.0 * i + 0.6, 9.0, -29.0)});
    s.boxes.push_back({dvec3(-14.0, 9.0, -31.0), dvec3(14.0, 10.0, -29.0)});  // a lintel over them
    return s;
}

struct View {
    glm::dmat4 view, proj;
    dvec3 eye;
};

View camera()
{
    View v;
    v.eye = dvec3(0.0, 0.0, 0.0);
    v.view = glm::lookAt(v.eye, dvec3(0.0, 1.0, -10.0), dvec3(0, 1, 0));
    v.proj = glm::perspective(1.1, double(W) / H, 0.1, 1000.0);
    return v;
}

dvec3 pixel_dir(const View& v, int x, int y)
{
    const glm::dmat4 inv = glm::inverse(v.proj * v.view);
    const glm::dvec4 q = inv * glm::dvec4((x + 0.5) / W * 2 - 1, (y + 0.5) / H * 2 - 1, 0.5, 1.0);
    return glm::normalize(dvec3(q) / q.w - v.eye);
}

/// Single-scattered radiance along a pixel's ray in homogeneous fog (sigma_s = sigma_t = 0.02 per
/// unit), Henyey-Greenstein g = 0.8, sun of unit irradiance, 400 steps to the first surface or 80.
double reference(const Scene& sc, dvec3 o, dvec3 d, dvec3 L)
{
    const double sigma = 0.02, g = 0.8, pi = 3.14159265358979323846;
    double tmax;
    if (!sc.hit(o, d, 80.0, tmax)) tmax = 80.0;
    const double c = glm::dot(d, L), phase = (1.0 - g * g) / (4.0 * pi * std::pow(1.0 + g * g - 2.0 * g * c, 1.5));
    const int steps = 400;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double t = (i + 0.5) / steps * tmax;
        double th;
        if (!sc.hit(o + t * d, L, 1e9, th)) sum += sigma * phase * std::exp(-sigma * t) * (tmax / steps);
    }
    return sum;
}

struct Fit {
    double corr = 0.0, rel_rms = 0.0, scale = 0.0;
};

Fit fit(const std::vector<double>& a, const std::vector<double>& r)
{
    double sa = 0, sr = 0, saa = 0, srr = 0, sar = 0;
    const double n = double(a.size());
    for (size_t i = 0; i < a.size(); ++i) {
        sa += a[i];
        sr += r[i];
        saa += a[i] * a[i];
        srr += r[i] * r[i];
        sar += a[i] * r[i];
    }
    Fit f;
    const double va = saa - sa * sa / n, vr = srr - sr * sr / n;
    f.corr = va > 0 && vr > 0 ? (sar - sa * sr / n) / std::sqrt(va * vr) : 0.0;
    f.scale = saa > 0 ? sar / saa : 0.0;
    double e = 0.0;
    for (size_t i = 0; i < a.size(); ++i) e += (f.scale * a[i] - r[i]) * (f.scale * a[i] - r[i]);
    f.rel_rms = srr > 0 ? std::sqrt(e / srr) : 0.0;
    return f;
}

TEST(LightShafts, AgainstARayMarchedReference)
{
    const Scene sc = pillars(), empty_scene;
    const View v = camera();
    const dvec3 L = glm::normalize(dvec3(0.05, 0.16, -1.0));
    const glm::dvec4 c = v.proj * v.view * glm::dvec4(L, 0.0);
    const vec2 luv = rk_ls_light_uv(vec4(c));
    ASSERT_GT(luv.x, 0.0f);
    ASSERT_LT(luv.x, 1.0f);
    ASSERT_GT(luv.y, 0.0f);
    ASSERT_LT(luv.y, 1.0f);
    EXPECT_NEAR(rk_ls_fade(vec4(c), 0.3f), 1.0f, 1e-6f);
    // Occlusion buffers: the sun's disk where the sky is seen; the same without the pillars.
    LsMapCpu occ, open;
    occ.width = open.width = W;
    occ.height = open.height = H;
    std::vector<double> ref, ref_open;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const dvec3 d = pixel_dir(v, x, y);
            double t;
            const vec2 uv((float(x) + 0.5f) / float(W), (float(y) + 0.5f) / float(H));
            const float disk = rk_ls_disk(uv, luv, 0.25f, float(W) / float(H));
            occ.v.push_back(vec3(sc.hit(v.eye, d, 1e9, t) ? 0.0f : disk));
            open.v.push_back(vec3(empty_scene.hit(v.eye, d, 1e9, t) ? 0.0f : disk));
            ref.push_back(reference(sc, v.eye, d, L));
            ref_open.push_back(reference(empty_scene, v.eye, d, L));
        }
    // The pillars' own contribution: what they take away from the fog's glow (reference with and
    // without them), against what they take away from the screen-space glow.
    std::vector<double> ref_shadow;
    for (size_t i = 0; i < ref.size(); ++i) ref_shadow.push_back(ref_open[i] - ref[i]);
    std::printf("screen-space shafts against the ray-marched reference (%dx%d, best-fit scale): correlation and relative RMS error of the "
                "image, and correlation of the pillars' shadow in the fog (without minus with them)\n",
                W, H);
    std::printf("%7s %8s %12s %12s %14s %22s\n", "samples", "decay", "correlation", "rel. RMS", "shadow corr.", "glow-only correlation");
    Fit at64, open64, shadow64;
    for (uint n : {16u, 32u, 64u, 128u})
        for (float decay : {1.0f, 0.97f}) {
            std::vector<double> a, b, sh;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    const vec2 uv((float(x) + 0.5f) / float(W), (float(y) + 0.5f) / float(H));
                    const double ao = rk_ls_accumulate(occ, uv, luv, n, 0.9f, 1.0f / float(n), decay, 1.0f).x;
                    const double bo = rk_ls_accumulate(open, uv, luv, n, 0.9f, 1.0f / float(n), decay, 1.0f).x;
                    a.push_back(ao);
                    b.push_back(bo);
                    sh.push_back(bo - ao);
                }
            const Fit fa = fit(a, ref), fb = fit(b, ref), fs = fit(sh, ref_shadow);
            std::printf("%7u %8.2f %12.3f %12.3f %14.3f %22.3f\n", n, double(decay), fa.corr, fa.rel_rms, fs.corr, fb.corr);
            if (n == 64u && decay == 0.97f) {
                at64 = fa;
                open64 = fb;
                shadow64 = fs;
            }
        }
    // The image follows the reference (most of it is the forward-scattering glow around the sun,
    // which even a buffer without occluders reproduces); the shafts themselves, the pillars'
    // shadow in the fog, follow the reference's shadow.
    EXPECT_GT(at64.corr, 0.85);
    EXPECT_GT(at64.corr, open64.corr);
    EXPECT_LT(at64.rel_rms, open64.rel_rms);
    EXPECT_GT(shadow64.corr, 0.6);
}

TEST(LightShafts, FadesWhenTheLightLeavesTheViewOrGoesBehind)
{
    const View v = camera();
    const glm::dmat4 vp = v.proj * v.view;
    // A light swept from straight ahead to the side and behind: the fade never rises again once it
    // is falling, is 1 in the middle of the view and 0 behind the camera.
    double prev = 2.0;
    bool was_one = false;
    for (int i = 0; i <= 180; ++i) {
        const double a = i * 3.14159265358979323846 / 180.0;
        const dvec3 L(std::sin(a), 0.1, -std::cos(a));
        const float f = rk_ls_fade(vec4(vp * glm::dvec4(L, 0.0)), 0.3f);
        ASSERT_TRUE(std::isfinite(f));
        EXPECT_LE(double(f), prev + 1e-6) << "angle " << i;
        prev = f;
        if (i == 0) was_one = f == 1.0f;
        if (i >= 90) {
            EXPECT_EQ(f, 0.0f) << "angle " << i;
        }
    }
    EXPECT_TRUE(was_one);
    EXPECT_EQ(rk_ls_fade(vec4(0.0f, 0.0f, 0.0f, -1.0f), 0.3f), 0.0f);
    EXPECT_EQ(rk_ls_fade(vec4(0.0f), 0.3f), 0.0f);
}

TEST(LightShafts, AccumulationMatchesItsDefinitionAndBadInputStaysFinite)
{
    // A buffer whose value is its u coordinate: the sum of the samples' u, exactly (bilinear
    // interpolation of a linear ramp is exact away from the clamped edges).
    LsMapCpu m;
    m.width = 64;
    m.height = 8;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 64; ++x) m.v.push_back(vec3((float(x) + 0.5f) / 64.0f));
    const vec2 uv(0.8f, 0.5f), luv(0.3f, 0.5f);
    double want = 0.0, fall = 1.0;
    for (int i = 1; i <= 20; ++i) {
        want += 0.5 * fall * (0.8 - i * (0.8 - 0.3) * 0.9 / 20.0);
        fall *= 0.95;
    }
    EXPECT_NEAR(rk_ls_accumulate(m, uv, luv, 20u, 0.9f, 0.5f, 0.95f, 2.0f).x, float(2.0 * want), 2e-5f);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (float p : {0.0f, -1.0f, nan, 1e30f, inf})
        for (uint n : {0u, 1u, 5000u}) {
            const vec3 r = rk_ls_accumulate(m, vec2(p, 0.5f), vec2(0.5f, p), n, p, p, p, p);
            const vec3 r2 = rk_ls_accumulate(m, uv, luv, n, 0.9f, p, 0.9f, 1.0f);
            EXPECT_TRUE(std::isfinite(r.x) && std::isfinite(r2.x)) << p << " " << n;
            EXPECT_GE(r.x, 0.0f);
        }
    // An overflowing sum with a zero exposure: held finite, not Inf * 0.
    for (float ex : {0.0f, 1.0f, 3.4028235e38f}) {
        const vec3 big = rk_ls_accumulate(m, uv, luv, 64u, 0.9f, 3.4028235e38f, 1.0f, ex);
        EXPECT_TRUE(std::isfinite(big.x) && big.x >= 0.0f) << ex;
    }
    EXPECT_EQ(rk_ls_disk(vec2(0.5f), vec2(0.5f), 0.2f, 1.5f), 1.0f);
    EXPECT_EQ(rk_ls_disk(vec2(0.9f, 0.5f), vec2(0.5f), 0.2f, 1.0f), 0.0f);
    const vec2 far = rk_ls_light_uv(vec4(1e30f, -1e30f, 0.0f, 1e-30f));
    EXPECT_TRUE(std::isfinite(far.x) && std::isfinite(far.y));
    const LsMapCpu none;
    EXPECT_EQ(rk_ls_read(none, vec2(0.5f)).x, 0.0f);
}

}  // namespace
