// Deferred against forward shading on the CPU: an analytic scene (a floor, a back wall, a sphere)
// lit by 16 windowed point lights, shaded once from the exact surface attributes (forward) and once
// from the compact G-buffer preset (gbuffer_layout_compact: albedo in RGBA8, the normal octahedral in
// RG16 SNORM, position rebuilt from a reversed-Z float depth by rk_gb_linear_depth and
// rk_gb_view_pos), with the same lights (light_volume.glsl's falloff). The images must agree within
// the encodings' own error: the albedo's half step of 1/255 dominates.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/gbuffer.hpp"
#include "raykit/light_volume.hpp"
#include "raykit/svo_hybrid.hpp"

using namespace raykit;
using glm::dvec3;

namespace {

struct Light {
    vec3 pos;  // view space
    vec3 colour;
    float radius;
};

vec3 shade(vec3 p, vec3 n, vec3 albedo, const std::vector<Light>& lights)
{
    vec3 sum(0.0f);
    for (const Light& l : lights) {
        const vec3 d = l.pos - p;
        const float d2 = glm::dot(d, d);
        const float ndl = std::max(glm::dot(n, d * (1.0f / std::sqrt(std::max(d2, 1e-12f)))), 0.0f);
        sum += albedo * l.colour * (ndl * rk_lv_point_falloff(d2, 1.0f / (l.radius * l.radius), 1e-4f));
    }
    return sum;
}

TEST(Deferred, CompactGbufferReproducesForwardShading)
{
    const int w = 320, h = 240;
    const float near = 0.1f;
    const mat4 view = glm::lookAt(vec3(0.0f, 1.6f, 0.0f), vec3(0.0f, 0.9f, -10.0f), vec3(0, 1, 0));
    const mat4 proj = svo_perspective(1.1f, float(w) / float(h), near, INFINITY, SvoDepthConvention::reversed_zero_to_one);
    const glm::dmat4 inv = glm::inverse(glm::dmat4(proj));
    const vec4 ray = gbuffer_view_ray(proj);
    const vec3 k = gbuffer_depth_params(near, INFINITY, true);
    Status st;
    ASSERT_TRUE(validate_gbuffer_layout(gbuffer_layout_compact(), GbLayoutRules{}, st)) << st.message;
    // Lights in view space.
    std::vector<Light> lights;
    std::mt19937 rng(4u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 16; ++i) {
        const vec3 world(-5.0f + 10.0f * u(rng), 0.2f + 2.5f * u(rng), -11.0f + 9.0f * u(rng));
        lights.push_back({vec3(view * vec4(world, 1.0f)), vec3(1.0f + 4.0f * u(rng), 1.0f + 4.0f * u(rng), 1.0f + 4.0f * u(rng)),
                          2.0f + 4.0f * u(rng)});
    }
    // The scene in view space: floor y = 0, wall z = -12 (world), a sphere.
    const glm::dmat4 v2w = glm::inverse(glm::dmat4(view));
    const dvec3 eye(0.0, 1.6, 0.0), sc(1.0, 1.0, -6.0);
    double worst = 0.0, sum = 0.0, peak = 0.0;
    long n = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double nx = (x + 0.5) / w * 2.0 - 1.0, ny = (y + 0.5) / h * 2.0 - 1.0;
            const glm::dvec4 q = inv * glm::dvec4(nx, ny, 0.5, 1.0);
            const dvec3 dv = glm::normalize(dvec3(q) / q.w);                 // view-space ray
            const dvec3 dw = glm::normalize(dvec3(v2w * glm::dvec4(dv, 0.0)));  // world-space ray
            double t = 1e30;
            dvec3 nw(0.0);
            if (dw.y < 0.0 && -eye.y / dw.y < t) { t = -eye.y / dw.y; nw = dvec3(0, 1, 0); }
            if (dw.z < 0.0) { const double tz = (-12.0 - eye.z) / dw.z; if (tz < t && eye.y + tz * dw.y >= 0.0) { t = tz; nw = dvec3(0, 0, 1); } }
            const dvec3 oc = eye - sc;
            const double b = glm::dot(oc, dw), c = glm::dot(oc, oc) - 1.0, disc = b * b - c;
            if (disc > 0.0 && -b - std::sqrt(disc) > 0.0 && -b - std::sqrt(disc) < t) { t = -b - std::sqrt(disc); nw = glm::normalize(eye + t * dw - sc); }
            if (t >= 1e30) continue;
            const dvec3 pw = eye + t * dw;
            const vec3 p = vec3(dvec3(glm::dmat4(view) * glm::dvec4(pw, 1.0)));
            const vec3 nv = glm::normalize(vec3(glm::dmat3(glm::dmat4(view)) * nw));
            const vec3 albedo(0.55f + 0.45f * float(std::sin(3.0 * pw.x)), 0.5f + 0.4f * float(std::cos(2.0 * pw.z)), 0.6f);  // >= 0.1
            const vec3 fwd = shade(p, nv, albedo, lights);
            // The G-buffer: RGBA8 albedo, RG16 SNORM octahedral normal, reversed-Z float depth.
            vec3 a8;
            for (int ch = 0; ch < 3; ++ch) a8[ch] = std::round(albedo[ch] * 255.0f) / 255.0f;
            const vec3 n16 = rk_gb_oct_unpack_snorm(rk_gb_oct_pack_snorm(nv, 16u), 16u);
            const vec4 clip = proj * vec4(p, 1.0f);
            const float d = clip.z / clip.w;  // the float a D32F buffer stores
            const vec2 ndc{static_cast<float>(nx), static_cast<float>(ny)};
            const vec3 pr = rk_gb_view_pos(ndc, rk_gb_linear_depth(d, k), ray);
            const vec3 def = shade(pr, n16, a8, lights);
            // Compared as displayed, after x / (1 + x): a relative radiance error matters where the
            // pixel is visible, not where it is 1e-6 or 500.
            for (int ch = 0; ch < 3; ++ch) {
                const double da = double(fwd[ch]) / (1.0 + double(fwd[ch])), db = double(def[ch]) / (1.0 + double(def[ch]));
                const double e = std::abs(da - db);
                worst = std::max(worst, e);
                sum += e;
                peak = std::max(peak, double(fwd[ch]));
            }
            ++n;
        }
    const double mean = sum / (3.0 * double(n));
    std::printf("deferred vs forward over %ld pixels, displayed as x / (1 + x): max difference %.3g, mean %.3g (peak radiance %.3g)\n", n,
                worst, mean, peak);
    EXPECT_GT(n, 60000);
    // The albedo's half step (0.5 / 255 of an albedo of at least 0.1: 2 % of the radiance) is at most
    // 0.02 x / (1 + x)^2 <= 0.005 displayed; the normal (6.5e-5 rad) and position (3e-7) add far less.
    EXPECT_LE(worst, 0.006);
    EXPECT_LE(mean, 1e-3);
}

}  // namespace
