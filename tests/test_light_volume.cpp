// Tests of shaders/raykit/light_volume.glsl (C++ build) and include/raykit/light_volume.hpp: the
// falloff and spot factor against float64 formulas and at their boundaries; the volume meshes
// (closed, convex, containing the lit region); the face-culling rule against a brute-force test of
// the near plane's rectangle against the mesh; the sphere's screen rectangle and depth range against
// projected samples of the clipped sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/light_volume.hpp"
#include "raykit/svo_hybrid.hpp"

using namespace raykit;
using glm::dvec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Falloff, spot factor, radius

TEST(LightVolumeFalloff, WindowedInverseSquare)
{
    EXPECT_EQ(rk_lv_window(0.0f), 1.0f);
    EXPECT_EQ(rk_lv_window(1.0f), 0.0f);
    EXPECT_EQ(rk_lv_window(7.0f), 0.0f);
    EXPECT_EQ(rk_lv_window(-3.0f), 1.0f);
    EXPECT_EQ(rk_lv_window(std::nanf("")), 1.0f);
    const float r = 5.0f, inv_r2 = 1.0f / (r * r), min2 = 1e-4f;
    float prev = INFINITY;
    for (int i = 0; i <= 20000; ++i) {
        const double d = 6.0 * i / 20000.0, d2 = d * d;
        const float f = rk_lv_point_falloff(static_cast<float>(d2), inv_r2, min2);
        const double x = std::min(d2 / (double(r) * r), 1.0), w = (1.0 - x * x) * (1.0 - x * x);
        const double want = w / std::max(d2, double(min2));
        // Float rounding of x = d² / r² (a few ulps) moves the window by its slope 4 x (1 - x²).
        const double slack = 4e-7 * 4.0 * x * (1.0 - x * x) / std::max(d2, double(min2));
        ASSERT_NEAR(f, want, 4e-7 * want + slack + 1e-30) << d;
        ASSERT_LE(f, 1.0 / std::max(d2, double(min2)) * (1.0 + 1e-6)) << "never above the unwindowed falloff";
        ASSERT_LE(f, prev) << "monotone";
        if (d >= r) {
            ASSERT_EQ(f, 0.0f) << "exactly 0 from the radius on";
        }
        prev = f;
    }
    EXPECT_TRUE(std::isfinite(rk_lv_point_falloff(0.0f, inv_r2, 0.0f)));
    EXPECT_TRUE(std::isfinite(rk_lv_point_falloff(0.0f, inv_r2, -5.0f)));
}

TEST(LightVolumeFalloff, SpotFactor)
{
    const float co = std::cos(0.6f), ci = std::cos(0.4f);
    EXPECT_EQ(rk_lv_spot_factor(std::cos(0.7f), co, ci), 0.0f);
    EXPECT_EQ(rk_lv_spot_factor(std::cos(0.3f), co, ci), 1.0f);
    EXPECT_EQ(rk_lv_spot_factor(co, co, ci), 0.0f);
    EXPECT_EQ(rk_lv_spot_factor(ci, co, ci), 1.0f);
    float prev = -1.0f;
    for (int i = 0; i <= 1000; ++i) {
        const float c = co + (ci - co) * static_cast<float>(i) / 1000.0f;
        const float s = rk_lv_spot_factor(c, co, ci);
        const double t = (double(c) - co) / (double(ci) - co);
        ASSERT_NEAR(s, t * t, 2e-5) << c;
        ASSERT_GE(s, prev);
        prev = s;
    }
    // Equal cones: a hard edge at the outer angle.
    EXPECT_EQ(rk_lv_spot_factor(0.5f, 0.5f, 0.5f), 0.0f);
    EXPECT_EQ(rk_lv_spot_factor(std::nextafter(0.5f, 1.0f), 0.5f, 0.5f), 1.0f);
    EXPECT_EQ(rk_lv_spot_factor(0.4f, 0.5f, 0.5f), 0.0f);
}

TEST(LightVolumeFalloff, RadiusForACutoff)
{
    for (float I : {1.0f, 100.0f, 1e6f})
        for (float c : {1e-3f, 0.01f, 0.5f}) {
            const float r = point_light_radius(I, c);
            EXPECT_NEAR(double(I) / (double(r) * r), c, c * 1e-6) << I << " " << c;
        }
    EXPECT_EQ(point_light_radius(0.0f, 0.1f), 0.0f);
    EXPECT_EQ(point_light_radius(10.0f, 0.0f), 0.0f);
    EXPECT_EQ(point_light_radius(-1.0f, 0.1f), 0.0f);
    EXPECT_TRUE(std::isfinite(point_light_radius(3e38f, 1e-38f)));
}

// ---------------------------------------------------------------------------------------------
// Meshes

/// Face planes (outward normal, offset) of a mesh, in double, and checks that it is closed,
/// consistently wound and convex with outward normals.
std::vector<std::pair<dvec3, double>> planes_of(const LightVolumeMesh& m, dvec3 inside)
{
    std::vector<std::pair<dvec3, double>> pl;
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        const uint32_t i[3] = {m.indices[t], m.indices[t + 1], m.indices[t + 2]};
        const dvec3 a(m.positions[i[0]]), b(m.positions[i[1]]), c(m.positions[i[2]]);
        const dvec3 n = glm::normalize(glm::cross(b - a, c - a));
        pl.push_back({n, glm::dot(n, a)});
        EXPECT_GT(glm::dot(n, a - inside), 0.0) << "face " << t / 3 << " faces inwards";
        for (int k = 0; k < 3; ++k) ++edges[{i[k], i[(k + 1) % 3]}];
    }
    for (const auto& e : edges) {
        EXPECT_EQ(e.second, 1) << "edge used twice in one direction";
        EXPECT_EQ(edges.count({e.first.second, e.first.first}), 1u) << "open edge";
    }
    for (const auto& p : pl)
        for (const vec3& v : m.positions) EXPECT_LE(glm::dot(p.first, dvec3(v)), p.second + 1e-6) << "not convex";
    return pl;
}

bool inside(const std::vector<std::pair<dvec3, double>>& pl, dvec3 p, double eps = 0.0)
{
    for (const auto& f : pl)
        if (glm::dot(f.first, p) > f.second + eps) return false;
    return true;
}

TEST(LightVolumeMesh, SphereContainsTheBall)
{
    const double expect_radius[] = {1.26, 1.07, 1.02};
    for (int s = 0; s <= 3; ++s) {
        const LightVolumeMesh m = light_volume_sphere(s);
        EXPECT_EQ(m.indices.size(), 3u * 20u * (1u << (2 * s)));
        const auto pl = planes_of(m, dvec3(0.0));
        double min_plane = 1e9, max_vertex = 0.0;
        for (const auto& f : pl) min_plane = std::min(min_plane, f.second);
        for (const vec3& v : m.positions) max_vertex = std::max(max_vertex, glm::length(dvec3(v)));
        EXPECT_GE(min_plane, 1.0) << s << ": every face plane at least 1 from the centre";
        EXPECT_LE(min_plane, 1.0 + 1e-5) << s << ": and the closest exactly there";
        if (s < 3) {
            EXPECT_NEAR(max_vertex, expect_radius[s], 0.005) << s << ": the documented vertex radius";
        }
    }
}

TEST(LightVolumeMesh, ConeContainsTheSector)
{
    std::mt19937 rng(3u);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int n : {3, 6, 16, 64})
        for (double deg : {5.0, 30.0, 45.0, 80.0}) {
            const double a = deg * kPi / 180.0;
            const LightVolumeMesh m = light_volume_cone(n, static_cast<float>(a));
            const auto pl = planes_of(m, dvec3(0.0, 0.0, -0.5));
            for (int i = 0; i < 20000; ++i) {
                // Points of the sector (distance <= 1 from the apex, within `a` of -z), the cap and
                // the cone's rim included.
                const double r = i % 4 == 0 ? 1.0 : std::cbrt(u(rng));
                const double th = i % 3 == 0 ? a : std::acos(1.0 - u(rng) * (1.0 - std::cos(a)));
                const double phi = 2.0 * kPi * u(rng);
                const dvec3 p = r * dvec3(std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), -std::cos(th));
                ASSERT_TRUE(inside(pl, p, 1e-7)) << n << " sides, " << deg << " deg, point " << p.x << " " << p.y << " " << p.z;
            }
        }
}

// ---------------------------------------------------------------------------------------------
// The culling rule against the near plane's rectangle

/// Points of the near plane's rectangle (grid) for an eye at `eye` looking along `fwd`.
std::vector<dvec3> near_rect(dvec3 eye, dvec3 fwd, double near, double tx, double ty)
{
    const dvec3 up0 = std::abs(fwd.y) < 0.9 ? dvec3(0, 1, 0) : dvec3(1, 0, 0);
    const dvec3 right = glm::normalize(glm::cross(fwd, up0)), up = glm::cross(right, fwd);
    std::vector<dvec3> pts;
    for (int i = 0; i <= 8; ++i)
        for (int j = 0; j <= 8; ++j)
            pts.push_back(eye + near * (fwd + (i / 4.0 - 1.0) * tx * right + (j / 4.0 - 1.0) * ty * up));
    return pts;
}

TEST(LightVolumeCull, SphereRuleIsConservative)
{
    const LightVolumeMesh m = light_volume_sphere(1);
    double mesh_radius = 0.0;
    for (const vec3& v : m.positions) mesh_radius = std::max(mesh_radius, glm::length(dvec3(v)));
    const dvec3 c(1.0, -2.0, 3.0);
    const double r = 2.5, near = 0.3;
    LightVolumeMesh world = m;
    for (vec3& v : world.positions) v = vec3(dvec3(v) * r + c);
    const auto pl = planes_of(world, c);
    const mat4 P = glm::perspective(1.2f, 1.6f, float(near), 100.0f);
    const float reach = near_plane_reach(float(near), P[0][0], P[1][1]);
    std::mt19937 rng(7u);
    std::normal_distribution<double> g;
    int front = 0, back = 0;
    for (int i = 0; i < 20000; ++i) {
        const dvec3 dir = glm::normalize(dvec3(g(rng), g(rng), g(rng)));
        const double dist = (r * mesh_radius + reach) * (0.6 + 0.8 * (i % 1000) / 1000.0);
        const dvec3 eye = c + dir * std::max(dist, 0.0);
        const dvec3 fwd = glm::normalize(dvec3(g(rng), g(rng), g(rng)));
        bool touches = inside(pl, eye);
        for (const dvec3& p : near_rect(eye, fwd, near, 1.0 / P[0][0], 1.0 / P[1][1])) touches = touches || inside(pl, p);
        const LightVolumeCull rule = light_volume_cull_sphere(vec3(c), float(r), float(mesh_radius), vec3(eye), reach);
        if (touches) {
            ASSERT_EQ(rule, LightVolumeCull::front) << "near plane inside the mesh at eye distance " << dist;
        }
        (rule == LightVolumeCull::front ? front : back)++;
    }
    EXPECT_GT(front, 1000);
    EXPECT_GT(back, 1000);
    // At the boundary.
    const double lim = r * mesh_radius + reach;
    EXPECT_EQ(light_volume_cull_sphere(vec3(c), float(r), float(mesh_radius), vec3(c + dvec3(lim * 0.9999, 0, 0)), reach), LightVolumeCull::front);
    EXPECT_EQ(light_volume_cull_sphere(vec3(c), float(r), float(mesh_radius), vec3(c + dvec3(0, lim * 1.0001, 0)), reach), LightVolumeCull::back);
}

TEST(LightVolumeCull, ConeRuleIsConservative)
{
    const int n = 12;
    const double a = 0.5, range = 4.0, near = 0.2;
    const LightVolumeMesh m = light_volume_cone(n, float(a));
    // World placement: apex at A, axis U (the mesh's -z turned onto U).
    const dvec3 A(2.0, 1.0, -1.0), U = glm::normalize(dvec3(1.0, -0.5, 0.3));
    const dvec3 X = glm::normalize(glm::cross(U, dvec3(0, 1, 0))), Y = glm::cross(X, U);
    LightVolumeMesh world = m;
    for (vec3& v : world.positions) {
        const dvec3 p(v);
        v = vec3(A + range * (p.x * X + p.y * Y - p.z * U));
    }
    const auto pl = planes_of(world, A + 0.5 * range * U);
    const mat4 P = glm::perspective(1.0f, 1.0f, float(near), 100.0f);
    const float reach = near_plane_reach(float(near), P[0][0], P[1][1]);
    std::mt19937 rng(8u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::normal_distribution<double> g;
    int front = 0, back = 0;
    for (int i = 0; i < 20000; ++i) {
        // Around the cone: along the axis beyond both ends, out to twice its radius plus the reach.
        const double t = range * (-0.3 + 1.6 * (0.5 * u(rng) + 0.5));
        const double rad = (std::max(t, 0.0) * std::tan(a) + reach) * 2.0 * (0.5 * u(rng) + 0.5);
        const double phi = kPi * u(rng);
        const dvec3 eye = A + t * U + rad * (std::cos(phi) * X + std::sin(phi) * Y);
        const dvec3 fwd = glm::normalize(dvec3(g(rng), g(rng), g(rng)));
        bool touches = inside(pl, eye);
        for (const dvec3& p : near_rect(eye, fwd, near, 1.0 / P[0][0], 1.0 / P[1][1])) touches = touches || inside(pl, p);
        const LightVolumeCull rule = light_volume_cull_cone(vec3(A), vec3(U), float(range), float(a), n, vec3(eye), reach);
        if (touches) {
            ASSERT_EQ(rule, LightVolumeCull::front) << "near plane inside the cone mesh";
        }
        (rule == LightVolumeCull::front ? front : back)++;
    }
    EXPECT_GT(front, 1000);
    EXPECT_GT(back, 1000);
}

// ---------------------------------------------------------------------------------------------
// Screen rectangle and depth range against projected samples

struct SampledRect {
    bool any = false;
    double x0 = 1e30, y0 = 1e30, x1 = -1e30, y1 = -1e30;
    double dmin = 1e30, dmax = -1e30;  // view distance of the visible part
};

SampledRect sample_clipped_sphere(dvec3 c, double r, const mat4& P, double near, int count, std::mt19937& rng)
{
    SampledRect s;
    std::normal_distribution<double> g;
    auto add = [&](dvec3 p) {
        if (p.z > -near) return;
        const glm::dvec4 q = glm::dmat4(P) * glm::dvec4(p, 1.0);
        const double x = std::clamp(q.x / q.w, -1.0, 1.0), y = std::clamp(q.y / q.w, -1.0, 1.0);
        s.any = true;
        s.x0 = std::min(s.x0, x);
        s.x1 = std::max(s.x1, x);
        s.y0 = std::min(s.y0, y);
        s.y1 = std::max(s.y1, y);
        s.dmin = std::min(s.dmin, -p.z);
        s.dmax = std::max(s.dmax, -p.z);
    };
    for (int i = 0; i < count; ++i) add(c + r * glm::normalize(dvec3(g(rng), g(rng), g(rng))));
    // The circle the near plane cuts.
    const double h2 = r * r - (c.z + near) * (c.z + near);
    if (h2 > 0.0)
        for (int i = 0; i < 4096; ++i) {
            const double t = 2.0 * kPi * i / 4096.0;
            add(dvec3(c.x + std::sqrt(h2) * std::cos(t), c.y + std::sqrt(h2) * std::sin(t), -near));
        }
    return s;
}

TEST(LightVolumeRect, ContainsAndIsTightAgainstSamples)
{
    const float near = 0.1f;
    mat4 vk = glm::perspective(1.1f, 1.5f, near, 100.0f);
    vk[1][1] = -vk[1][1];
    const mat4 projs[] = {glm::perspective(1.1f, 1.5f, near, 100.0f), glm::frustum(-0.04f, 0.09f, -0.03f, 0.05f, near, 100.0f), vk};
    std::mt19937 rng(21u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int clipped = 0, empty = 0, full = 0, n = 0;
    double worst_tight = 0.0, worst_out = 0.0;
    for (const mat4& P : projs) {
        const vec4 proj = lv_projection_params(P);
        for (int i = 0; i < 600; ++i) {
            const dvec3 c(u(rng) * 6.0, u(rng) * 4.0, -0.5 + u(rng) * 8.0 - 4.0);
            const double r = 0.05 + 3.0 * (u(rng) * 0.5 + 0.5);
            const vec4 rect = rk_lv_sphere_ndc_rect(vec3(c), float(r), proj, near);
            const SampledRect s = sample_clipped_sphere(c, r, P, near, 10000, rng);
            ++n;
            if (glm::length(c) <= r) {
                EXPECT_EQ(rect, vec4(-1, -1, 1, 1));
                ++full;
                continue;
            }
            if (!s.any) {
                EXPECT_GT(rect.x, rect.z) << "nothing beyond the near plane: empty";
                ++empty;
                continue;
            }
            if (std::abs(c.z + near) < r) ++clipped;
            worst_out = std::max({worst_out, rect.x - s.x0, rect.y - s.y0, s.x1 - rect.z, s.y1 - rect.w});
            worst_tight = std::max({worst_tight, s.x0 - rect.x, s.y0 - rect.y, rect.z - s.x1, rect.w - s.y1});
        }
    }
    EXPECT_LE(worst_out, 0.0) << "a sample outside the rectangle";
    EXPECT_LE(worst_tight, 1e-2) << "as tight as 10,000 samples can tell";
    EXPECT_GT(clipped, 100);
    EXPECT_GT(empty, 20);
    std::printf("sphere rectangles: %d, crossing the near plane %d, empty %d, eye inside %d; loosest side vs samples %.2g, "
                "furthest sample outside %.2g\n", n, clipped, empty, full, worst_tight, worst_out);
}

TEST(LightVolumeRect, TightAtTheTangentPoints)
{
    // A sphere straight ahead: its rectangle's x edge is the tangent plane, at
    // P00 * tan(asin(r / d)) exactly.
    const mat4 P = glm::perspective(1.0f, 1.0f, 0.1f, 100.0f);
    const double d = 10.0, r = 2.0;
    const vec4 rect = rk_lv_sphere_ndc_rect(vec3(0.0f, 0.0f, float(-d)), float(r), lv_projection_params(P), 0.1f);
    const double want = P[0][0] * std::tan(std::asin(r / d)), out = want + 3e-5 * (1.0 + want);  // pushed out by 3e-5 (1 + |b|)
    EXPECT_NEAR(rect.z, out, 2e-7);
    EXPECT_NEAR(rect.x, -out, 2e-7);
    EXPECT_NEAR(rect.w, out, 2e-7);
}

TEST(LightVolumeRect, DepthRange)
{
    for (bool reversed : {false, true}) {
        const vec3 k = gbuffer_depth_params(0.1, 200.0, reversed);
        const mat4 P = glm::perspective(1.0f, 1.0f, 0.1f, 200.0f);
        std::mt19937 rng(4u);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        for (int i = 0; i < 500; ++i) {
            const dvec3 c(u(rng), u(rng), -5.0 + 6.0 * u(rng));
            const double r = 0.1 + 2.0 * (u(rng) + 1.0);
            const vec2 range = rk_lv_sphere_depth_range(float(c.z), float(r), k);
            ASSERT_LE(range.x, range.y);
            const SampledRect s = sample_clipped_sphere(c, r, P, 0.1, 4000, rng);
            if (!s.any) continue;
            for (double dist : {s.dmin, s.dmax}) {
                // The window depth of a visible distance, in float64.
                const double t = (1.0 / dist - 1.0 / 200.0) / (1.0 / 0.1 - 1.0 / 200.0);
                const double dw = reversed ? t : 1.0 - t;
                ASSERT_GE(dw, double(range.x) - 1e-6) << i;
                ASSERT_LE(dw, double(range.y) + 1e-6) << i;
            }
        }
        // Round trip with rk_gb_linear_depth.
        // Round trip with rk_gb_linear_depth: reversed-Z keeps ~1e-7 relative; the usual depth
        // loses dist / n ulps in the stored d (docs/deferred.md).
        for (float dist : {0.1f, 0.5f, 3.0f, 77.0f, 200.0f}) {
            const double tol = reversed ? 1e-6 : 2.4e-7 * dist / 0.1;
            EXPECT_NEAR(rk_gb_linear_depth(rk_gb_window_depth(dist, k), k), dist, dist * tol) << reversed;
        }
    }
}

TEST(LightVolumeRect, AdversarialInputsStayFinite)
{
    const float vals[] = {0.0f, -0.0f, 1e-40f, -1e-40f, 1e-20f, 1.0f, -1.0f, 1e10f, -1e10f, 1e17f, -1e17f};
    const vec4 proj = lv_projection_params(glm::perspective(1.0f, 1.3f, 0.1f, 10.0f));
    for (float x : vals)
        for (float z : vals)
            for (float r : {0.0f, 1e-30f, 0.5f, 1e8f, -1.0f})
                for (float n : {0.1f, 0.0f, 1e-30f}) {
                    const vec4 rect = rk_lv_sphere_ndc_rect(vec3(x, -x, z), r, proj, n);
                    ASSERT_TRUE(std::isfinite(rect.x) && std::isfinite(rect.y) && std::isfinite(rect.z) && std::isfinite(rect.w))
                        << x << " " << z << " " << r << " " << n;
                    const vec2 dr = rk_lv_sphere_depth_range(z, r, rk_gb_depth_params(0.1f, 10.0f, false));
                    ASSERT_TRUE(dr.x >= 0.0f && dr.y <= 1.0f && dr.x <= dr.y) << x << " " << z << " " << r;
                }
}

}  // namespace
