// CPU tests of raykit/interior_furniture.hpp (the C++ build of shaders/raykit/interior_furniture.glsl)
// against an independent float64 ray-plane intersection written here (plane through p - D n with
// normal n, ray cam + t (p - cam)), brute-force layer selection and integer flipbook arithmetic.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include "raykit/interior_furniture.hpp"
#include "test_util.hpp"

using namespace raykit;
using rktest::ErrorStats;
using rktest::fmt;

namespace {

struct D3 {
    double x, y, z;
};
D3 d3(vec3 v) { return {v.x, v.y, v.z}; }
D3 sub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 add(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 mul(double s, D3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dotd(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 unitd(D3 a) { return mul(1.0 / std::sqrt(dotd(a, a)), a); }
D3 absd(D3 a) { return {std::abs(a.x), std::abs(a.y), std::abs(a.z)}; }

/// Float64 reference of one furniture-plane hit.
struct RefHit {
    bool hit;
    double t;
    D3 pos;
    double u, v;  // unwrapped facade coordinates in room units
};

RefHit ref_plane(D3 p, D3 cam, D3 n, D3 tan, D3 bit, double depth, D3 size, D3 origin)
{
    const D3 nn = unitd(n), tt = unitd(tan), bb = unitd(bit);
    const D3 dir = sub(p, cam);
    const double den = dotd(nn, dir);
    RefHit r{};
    if (!(den < 0.0)) return r;
    const D3 p0 = sub(p, mul(depth, nn));                // a point of the plane
    r.t = dotd(nn, sub(p0, cam)) / den;                   // ray-plane, textbook form
    r.hit = true;
    r.pos = add(cam, mul(r.t, dir));
    const D3 rel = sub(r.pos, origin);
    r.u = dotd(rel, tt) / dotd(absd(tt), size);
    r.v = dotd(rel, bb) / dotd(absd(bb), size);
    return r;
}

double frac(double x) { return x - std::floor(x); }
// Distance between two values on the unit circle (wrap-aware).
double wrap_dist(double a, double b)
{
    const double d = std::abs(frac(a) - frac(b));
    return std::min(d, 1.0 - d);
}

rk_im_grid make_grid(vec3 size, vec3 origin)
{
    rk_im_grid g;
    g.room_size = size;
    g.origin = origin;
    return g;
}

/// A random facade frame: outward normal n, tangent, bitangent (right-handed, orthonormal).
void random_frame(std::mt19937& rng, bool axis_aligned, vec3& n, vec3& t, vec3& b)
{
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    if (axis_aligned) {
        const int k = static_cast<int>(rng() % 4u);
        const vec3 ns[4] = {vec3(0, 0, 1), vec3(0, 0, -1), vec3(1, 0, 0), vec3(-1, 0, 0)};
        n = ns[k];
    } else {
        n = glm::normalize(vec3(u(rng), 0.3f * u(rng), u(rng)) + vec3(0.0f, 0.0f, 0.01f));
    }
    t = glm::normalize(glm::cross(vec3(0, 1, 0), n));
    b = glm::cross(n, t);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The hit against the float64 ray-plane intersection, axis-aligned and rotated facades.

TEST(InteriorFurniture, RayPlaneVsFloat64)
{
    std::mt19937 rng(4242);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f), u11(-1.0f, 1.0f);
    ErrorStats et, ep, euv;
    long rooms_checked = 0, seams_skipped = 0;
    for (int i = 0; i < 200000; ++i) {
        const bool aligned = (i % 2) == 0;
        vec3 n, tan, bit;
        random_frame(rng, aligned, n, tan, bit);
        const vec3 size(2.0f + 3.0f * u01(rng), 3.0f + u01(rng), 2.0f + 3.0f * u01(rng));
        const vec3 origin(u11(rng) * 5.0f, u11(rng) * 2.0f, u11(rng) * 5.0f);
        const vec3 p = vec3(u11(rng), u11(rng), u11(rng)) * 40.0f;
        // Camera outside: in front of the facade, 0.5 to 200 units away, any direction within 85°.
        vec3 off = n + 3.0f * (u11(rng) * tan + u11(rng) * bit);
        if (glm::dot(glm::normalize(off), n) < 0.0872f) off = n + 0.5f * off;
        const vec3 cam = p + glm::normalize(off) * (0.5f + 200.0f * u01(rng) * u01(rng));
        const float depth = 4.0f * u01(rng);
        const rk_im_furniture_hit h = rk_im_furniture_plane(p, cam, n, tan, bit, depth, make_grid(size, origin));
        const RefHit r = ref_plane(d3(p), d3(cam), d3(n), d3(tan), d3(bit), depth, d3(size), d3(origin));
        ASSERT_TRUE(r.hit);
        ASSERT_TRUE(h.valid) << fmt(i);
        const std::string in = fmt("p", p.x, p.y, p.z, "cam", cam.x, cam.y, cam.z, "D", depth);
        et.add(h.t, r.t, in, rktest::ulp_error(h.t, r.t));
        const double pe = std::sqrt(dotd(sub(d3(h.pos), r.pos), sub(d3(h.pos), r.pos)));
        ep.add(pe, 0.0, in);
        euv.add(std::max(wrap_dist(h.uv.x, r.u), wrap_dist(h.uv.y, r.v)), 0.0, in);
        EXPECT_GE(h.uv.x, 0.0f);
        EXPECT_LT(h.uv.x, 1.0f);
        EXPECT_GE(h.uv.y, 0.0f);
        EXPECT_LT(h.uv.y, 1.0f);
        EXPECT_GE(h.t, 1.0f);
        // Room index: floor of the float64 hit in room units, away from cell boundaries.
        const D3 g = {(r.pos.x - origin.x) / size.x, (r.pos.y - origin.y) / size.y, (r.pos.z - origin.z) / size.z};
        const double eps = 1e-4;
        if (std::abs(g.x - std::round(g.x)) > eps && std::abs(g.y - std::round(g.y)) > eps &&
            std::abs(g.z - std::round(g.z)) > eps) {
            ++rooms_checked;
            EXPECT_EQ(h.room.x, static_cast<int>(std::floor(g.x))) << in;
            EXPECT_EQ(h.room.y, static_cast<int>(std::floor(g.y))) << in;
            EXPECT_EQ(h.room.z, static_cast<int>(std::floor(g.z))) << in;
        } else {
            ++seams_skipped;
        }
        // Per-room tile: on a grid-aligned facade, uv.x is the hit's position inside its room along
        // the tangent axis (mirrored when the tangent points along -axis).
        if (aligned) {
            const bool along_x = std::abs(tan.x) > 0.5f;
            const double cell = along_x ? g.x : g.z;
            const double sgn = along_x ? tan.x : tan.z;
            EXPECT_LT(wrap_dist(h.uv.x, sgn > 0 ? cell : -cell), 1e-3) << in;
        }
    }
    std::printf("[furniture] t: %s\n[furniture] pos (object units): %s\n[furniture] uv (room units): %s\n"
                "[furniture] rooms checked %ld, near a cell boundary (skipped) %ld\n",
                et.str().c_str(), ep.str().c_str(), euv.str().c_str(), rooms_checked, seams_skipped);
    // Measured: t 3.6 ulp, pos 5.4e-6 units (|pos| ~ 100), uv 3.2e-6 room units.
    EXPECT_LT(et.max_ulp, 8.0);
    EXPECT_LT(ep.max_abs, 2e-5);
    EXPECT_LT(euv.max_abs, 1e-5);
}

TEST(InteriorFurniture, PerpendicularRayIntoWindow)
{
    // Facade z = 0 facing +z, rooms 4 x 3 x 5 from the origin; camera straight in front of a point.
    const rk_im_grid g = make_grid(vec3(4.0f, 3.0f, 5.0f), vec3(0.0f));
    const vec3 p(6.0f, 4.5f, 0.0f), cam(6.0f, 4.5f, 10.0f);
    const rk_im_furniture_hit h = rk_im_furniture_plane(p, cam, vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0), 2.5f, g);
    ASSERT_TRUE(h.valid);
    EXPECT_FLOAT_EQ(h.t, 1.25f);  // 1 + D / |d| = 1 + 2.5 / 10
    EXPECT_FLOAT_EQ(h.pos.z, -2.5f);
    EXPECT_FLOAT_EQ(h.uv.x, 0.5f);  // 6 / 4 = 1.5 -> middle of room 1
    EXPECT_FLOAT_EQ(h.uv.y, 0.5f);  // 4.5 / 3 = 1.5
    EXPECT_EQ(h.room, ivec3(1, 1, -1));
    // D = 0: the facade plane itself, t = 1 exactly, pos = p.
    const rk_im_furniture_hit h0 = rk_im_furniture_plane(p, cam, vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0), 0.0f, g);
    EXPECT_TRUE(h0.valid);
    EXPECT_EQ(h0.t, 1.0f);
    EXPECT_EQ(h0.pos, p);
}

// ---------------------------------------------------------------------------------------------
// Derivatives against float64 central differences of the unwrapped UV.

TEST(InteriorFurniture, UvDerivativesVsFiniteDifferences)
{
    std::mt19937 rng(99);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f), u11(-1.0f, 1.0f);
    ErrorStats e;
    for (int i = 0; i < 20000; ++i) {
        vec3 n, tan, bit;
        random_frame(rng, (i % 2) == 0, n, tan, bit);
        const vec3 size(3.0f, 3.0f, 3.0f), origin(0.0f);
        const vec3 p = vec3(u11(rng), u11(rng), u11(rng)) * 20.0f;
        vec3 off = n + 2.0f * (u11(rng) * tan + u11(rng) * bit);
        const vec3 cam = p + glm::normalize(off) * (2.0f + 50.0f * u01(rng));
        const vec3 dx = (u11(rng) * tan + u11(rng) * bit) * 0.01f;  // one pixel along the facade
        const vec3 dy = (u11(rng) * tan + u11(rng) * bit) * 0.01f;
        const float depth = 3.0f * u01(rng);
        const rk_im_furniture_hit h =
            rk_im_furniture_plane_grad(p, cam, n, tan, bit, depth, dx, dy, make_grid(size, origin));
        ASSERT_TRUE(h.valid);
        const double hstep = 1e-4;
        auto uv_at = [&](D3 q) {
            const RefHit r = ref_plane(q, d3(cam), d3(n), d3(tan), d3(bit), depth, d3(size), d3(origin));
            return std::array<double, 2>{r.u, r.v};
        };
        for (int k = 0; k < 2; ++k) {
            const D3 d = d3(k == 0 ? dx : dy);
            const auto a = uv_at(add(d3(p), mul(hstep, d)));
            const auto b = uv_at(sub(d3(p), mul(hstep, d)));
            const vec2 got = k == 0 ? h.uv_dx : h.uv_dy;
            const double gu = (a[0] - b[0]) / (2 * hstep), gv = (a[1] - b[1]) / (2 * hstep);
            const double scale = std::max(1e-3, std::max(std::abs(gu), std::abs(gv)));
            e.add(std::max(std::abs(got.x - gu), std::abs(got.y - gv)) / scale, 0.0, fmt(i, k));
        }
    }
    std::printf("[furniture] uv derivative relative error: %s\n", e.str().c_str());
    EXPECT_LT(e.max_abs, 2e-6);  // measured 3.2e-7
}

// ---------------------------------------------------------------------------------------------
// Visibility: hidden behind the room wall, alpha test, several layers.

TEST(InteriorFurniture, HiddenWhenRoomWallIsNearer)
{
    // Perpendicular view into rooms 5 deep whose back wall is at z = -5 (facade at z = 0 on the grid).
    const rk_im_grid g = make_grid(vec3(4.0f, 3.0f, 5.0f), vec3(0.0f));
    const vec3 n(0, 0, 1), p(6.0f, 4.5f, 0.0f), cam(6.0f, 4.5f, 10.0f);
    const rk_im_hit room = rk_im_trace(p, cam, n, g);
    ASSERT_TRUE(room.valid);
    EXPECT_NEAR(room.t, 1.5f, 1e-5f);  // back wall 5 behind, camera 10 in front
    const rk_im_furniture_hit in_room = rk_im_furniture_plane(p, cam, n, vec3(1, 0, 0), vec3(0, 1, 0), 2.0f, g);
    const rk_im_furniture_hit behind = rk_im_furniture_plane(p, cam, n, vec3(1, 0, 0), vec3(0, 1, 0), 6.0f, g);
    EXPECT_TRUE(rk_im_furniture_visible(in_room, room.t, 1.0f, 0.5f));
    EXPECT_FALSE(rk_im_furniture_visible(behind, room.t, 1.0f, 0.5f));  // beyond the back wall
    // Tie: a plane exactly at the wall is hidden (strictly nearer only).
    rk_im_furniture_hit tie = in_room;
    tie.t = room.t;
    EXPECT_FALSE(rk_im_furniture_visible(tie, room.t, 1.0f, 0.5f));
    // Oblique rays: random cameras, visible iff the float64 plane t is below the room t.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u11(-1.0f, 1.0f), u01(0.0f, 1.0f);
    long shown = 0, hidden = 0;
    for (int i = 0; i < 20000; ++i) {
        const vec3 q(u11(rng) * 20.0f, u11(rng) * 20.0f, 0.0f);
        const vec3 c = q + vec3(u11(rng) * 8.0f, u11(rng) * 8.0f, 1.0f + 10.0f * u01(rng));
        const float depth = 6.0f * u01(rng);
        const rk_im_hit rh = rk_im_trace(q, c, n, g);
        const rk_im_furniture_hit f = rk_im_furniture_plane(q, c, n, vec3(1, 0, 0), vec3(0, 1, 0), depth, g);
        const RefHit r = ref_plane(d3(q), d3(c), d3(n), {1, 0, 0}, {0, 1, 0}, depth, {4, 3, 5}, {0, 0, 0});
        if (std::abs(r.t - rh.t) < 1e-4 * r.t) continue;  // too close to call in float
        const bool expect = r.t < rh.t;
        EXPECT_EQ(rk_im_furniture_visible(f, rh.t, 0.9f, 0.5f), expect) << fmt(i, r.t, rh.t);
        (expect ? shown : hidden) += 1;
    }
    std::printf("[furniture] oblique visibility: %ld shown, %ld hidden by the room\n", shown, hidden);
    EXPECT_GT(shown, 1000);
    EXPECT_GT(hidden, 1000);
}

TEST(InteriorFurniture, AlphaDiscard)
{
    const rk_im_grid g = make_grid(vec3(4.0f), vec3(0.0f));
    const rk_im_furniture_hit f =
        rk_im_furniture_plane(vec3(1, 1, 0), vec3(1, 1, 5), vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0), 1.0f, g);
    EXPECT_FALSE(rk_im_furniture_visible(f, 10.0f, 0.0f, 0.5f));
    EXPECT_FALSE(rk_im_furniture_visible(f, 10.0f, 0.5f, 0.5f));  // strictly above the threshold
    EXPECT_TRUE(rk_im_furniture_visible(f, 10.0f, 0.50001f, 0.5f));
    EXPECT_TRUE(rk_im_furniture_visible(f, 10.0f, 1.0f, 0.0f));
    EXPECT_FALSE(rk_im_furniture_visible(f, 10.0f, 0.0f, 0.0f));  // fully transparent never shows
}

TEST(InteriorFurniture, NearestVisibleLayerWinsInAnyOrder)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    const rk_im_grid g = make_grid(vec3(3.0f), vec3(0.0f));
    for (int i = 0; i < 5000; ++i) {
        const vec3 p(u01(rng) * 9.0f, u01(rng) * 9.0f, 0.0f);
        const vec3 cam = p + vec3(u01(rng) - 0.5f, u01(rng) - 0.5f, 1.0f + u01(rng));
        const float room_t = 1.0f + 3.0f * u01(rng);
        const int layers = 1 + static_cast<int>(rng() % 4u);
        std::array<rk_im_furniture_hit, 4> f{};
        std::array<float, 4> alpha{};
        std::array<int, 4> order{0, 1, 2, 3};
        for (int l = 0; l < layers; ++l) {
            f[static_cast<size_t>(l)] = rk_im_furniture_plane(p, cam, vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0),
                                                               3.0f * u01(rng), g);
            alpha[static_cast<size_t>(l)] = u01(rng) < 0.3f ? 0.0f : u01(rng);
        }
        // Brute force: the visible layer of smallest t (ties: the lowest index).
        int best = -1;
        for (int l = 0; l < layers; ++l) {
            const rk_im_furniture_hit& c = f[static_cast<size_t>(l)];
            if (c.valid && c.t < room_t && alpha[static_cast<size_t>(l)] > 0.25f &&
                (best < 0 || c.t < f[static_cast<size_t>(best)].t))
                best = l;
        }
        for (int perm = 0; perm < 6; ++perm) {
            std::shuffle(order.begin(), order.begin() + layers, rng);
            float nearest = room_t;
            int won = -1;
            for (int k = 0; k < layers; ++k) {
                const size_t l = static_cast<size_t>(order[static_cast<size_t>(k)]);
                if (rk_im_furniture_take(f[l], alpha[l], 0.25f, nearest)) won = static_cast<int>(l);
            }
            if (best < 0) {
                EXPECT_EQ(won, -1);
                EXPECT_EQ(nearest, room_t);
            } else {
                ASSERT_GE(won, 0);
                EXPECT_EQ(f[static_cast<size_t>(won)].t, f[static_cast<size_t>(best)].t);  // equal t = same plane
                EXPECT_EQ(nearest, f[static_cast<size_t>(best)].t);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Grazing rays, D = 0, camera inside, adversarial inputs: never NaN/Inf.

TEST(InteriorFurniture, GrazingAndDegenerateInputsAreFinite)
{
    const rk_im_grid g = make_grid(vec3(3.0f), vec3(0.0f));
    const vec3 n(0, 0, 1), t(1, 0, 0), b(0, 1, 0);
    // Exactly grazing (d = 0), with D = 0 (the 0/0 case) and D > 0.
    for (float D : {0.0f, 1.0f}) {
        const rk_im_furniture_hit h = rk_im_furniture_plane(vec3(1, 1, 0), vec3(-5, 1, 0), n, t, b, D, g);
        EXPECT_FALSE(h.valid);
        EXPECT_EQ(h.t, RK_IM_FURNITURE_T_NONE);
        EXPECT_TRUE(std::isfinite(h.uv.x) && std::isfinite(h.uv.y));
    }
    // Nearly grazing: valid while D / |d| <= 1e6, then reported as not hit.
    const rk_im_furniture_hit near_graze = rk_im_furniture_plane(vec3(1, 1, 0), vec3(-5, 1, 1e-5f), n, t, b, 1.0f, g);
    EXPECT_TRUE(near_graze.valid);
    EXPECT_NEAR(near_graze.t, 1.0 + 1e5, 2.0);
    const rk_im_furniture_hit too_far = rk_im_furniture_plane(vec3(1, 1, 0), vec3(-5, 1, 1e-7f), n, t, b, 1.0f, g);
    EXPECT_FALSE(too_far.valid);
    // Camera on the inner side of the facade: not hit.
    EXPECT_FALSE(rk_im_furniture_plane(vec3(1, 1, 0), vec3(1, 1, -3), n, t, b, 1.0f, g).valid);
    // Zero normal: not hit.
    EXPECT_FALSE(rk_im_furniture_plane(vec3(1, 1, 0), vec3(1, 1, 3), vec3(0.0f), t, b, 1.0f, g).valid);

    // Adversarial: every component from a list of extreme finite values.
    const float vals[] = {0.0f, -0.0f, 1e-45f, -1e-40f, 1.17549435e-38f, 1.0f, -1.0f, 1e-20f, 1e20f, -1e30f,
                          3.4028235e38f, -3.4028235e38f, 0.5f, 7.0f};
    std::mt19937 rng(5);
    auto pick = [&]() { return vals[rng() % (sizeof vals / sizeof vals[0])]; };
    auto v3 = [&]() { return vec3(pick(), pick(), pick()); };
    long valid = 0;
    for (int i = 0; i < 200000; ++i) {
        rk_im_grid gg;
        gg.room_size = v3();
        gg.origin = v3();
        const rk_im_furniture_hit h = rk_im_furniture_plane_grad(v3(), v3(), v3(), v3(), v3(), pick(), v3(), v3(), gg);
        const float out[] = {h.t, h.uv.x, h.uv.y, h.uv_dx.x, h.uv_dx.y, h.uv_dy.x, h.uv_dy.y, h.pos.x, h.pos.y, h.pos.z};
        for (float o : out) ASSERT_TRUE(std::isfinite(o)) << i << " " << fmt(h.t, h.uv.x, h.uv.y, h.uv_dx.x, h.uv_dx.y, h.uv_dy.x, h.uv_dy.y, h.pos.x, h.pos.y, h.pos.z);
        ASSERT_GE(h.uv.x, 0.0f);
        ASSERT_LT(h.uv.x, 1.0f);
        valid += h.valid ? 1 : 0;
        if (h.valid) {
            ASSERT_GE(h.t, 1.0f);
        }
    }
    std::printf("[furniture] adversarial: 200000 inputs, %ld valid hits, all outputs finite\n", valid);
}

// ---------------------------------------------------------------------------------------------
// Flipbook arithmetic against integer references.

TEST(InteriorFurniture, FlipbookFrame)
{
    // Integer reference: floored modulo of the exact frame number.
    auto ref = [](double time, double fps, long count, double phase) {
        const double f = std::floor(time * fps);
        const long m = static_cast<long>(f - static_cast<double>(count) * std::floor(f / static_cast<double>(count)));
        const long off = static_cast<long>(std::floor(phase * static_cast<double>(count)));
        return static_cast<int>((m + off) % count);
    };
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> ut(-3000.0f, 3000.0f), u01(0.0f, 1.0f);
    long checked = 0;
    for (int i = 0; i < 200000; ++i) {
        const int count = 1 + static_cast<int>(rng() % 64u);
        const float fps = (i % 3 == 0) ? 24.0f : (i % 3 == 1 ? 12.5f : 60.0f);
        const float time = ut(rng);
        const float phase = u01(rng);
        const double x = static_cast<double>(time) * fps;
        const double ph = static_cast<double>(phase) * count;
        // Float products may round across an integer: skip those (rare) inputs.
        if (std::abs(x - std::round(x)) < 1e-3 + std::abs(x) * 1.2e-7 || std::abs(ph - std::round(ph)) < 1e-4) continue;
        ++checked;
        ASSERT_EQ(rk_im_flipbook_frame(time, fps, count, phase), ref(time, fps, count, phase)) << fmt(time, fps, count, phase);
    }
    // Exact frame numbers up to 2^24 (fps = 1, integer times): the float division's rounding is corrected.
    for (int k = 0; k < 100000; ++k) {
        const float time = static_cast<float>(16777215 - k * 97);
        for (int count : {3, 7, 24, 1000, 65536}) {
            ASSERT_EQ(rk_im_flipbook_frame(time, 1.0f, count, 0.0f), ref(time, 1.0, count, 0.0)) << fmt(time, count);
            ASSERT_EQ(rk_im_flipbook_frame(-time, 1.0f, count, 0.0f), ref(-time, 1.0, count, 0.0)) << fmt(-time, count);
        }
    }
    // Negative time runs backwards continuously: one frame before 0 is the last frame.
    EXPECT_EQ(rk_im_flipbook_frame(-1.0f / 24.0f, 24.0f, 8, 0.0f), 7);
    EXPECT_EQ(rk_im_flipbook_frame(-0.0f, 24.0f, 8, 0.0f), 0);
    EXPECT_EQ(rk_im_flipbook_frame(0.0f, 24.0f, 8, 0.999f), 7);  // phase shifts by floor(phase * count)
    // Huge, zero and degenerate inputs: some frame in range, never UB.
    for (float time : {1e20f, -1e20f, 3.4e38f, -3.4e38f, 1e-45f, 16777217.0f, -16777217.0f}) {
        for (float fps : {0.0f, 1.0f, 24.0f, 1e10f, -5.0f}) {
            for (int count : {-3, 0, 1, 5, 1 << 20}) {
                const int f = rk_im_flipbook_frame(time, fps, count, 0.5f);
                EXPECT_GE(f, 0);
                EXPECT_LT(f, std::max(1, std::min(count, 65536)));
            }
        }
    }
    EXPECT_EQ(rk_im_flipbook_frame(123.4f, 0.0f, 8, 0.0f), 0);  // fps 0: frozen on the phase frame
    std::printf("[furniture] flipbook: %ld random frames checked exactly\n", checked);
    EXPECT_GT(checked, 190000);
}

TEST(InteriorFurniture, FlipbookSheetUv)
{
    // 4 x 3 sheet: frame 5 is column 1, row 1.
    const vec2 a = rk_im_flipbook_uv(vec2(0.0f, 0.0f), 5, 4, 3);
    EXPECT_FLOAT_EQ(a.x, 0.25f);
    EXPECT_FLOAT_EQ(a.y, 1.0f / 3.0f);
    const vec2 b = rk_im_flipbook_uv(vec2(0.5f, 0.5f), 11, 4, 3);
    EXPECT_FLOAT_EQ(b.x, 3.5f / 4.0f);
    EXPECT_FLOAT_EQ(b.y, 2.5f / 3.0f);
    // Every frame's cell: uv in [0,1)^2 maps inside [col/c, (col+1)/c) x [row/r, (row+1)/r].
    for (int c = 1; c <= 8; ++c) {
        for (int r = 1; r <= 8; ++r) {
            for (int f = 0; f < c * r; ++f) {
                for (float s : {0.0f, 0.3f, 0.99999994f}) {
                    const vec2 uv = rk_im_flipbook_uv(vec2(s, 1.0f - s - 1e-7f), f, c, r);
                    const int col = f % c, row = f / c;
                    EXPECT_GE(uv.x * static_cast<float>(c), static_cast<float>(col) - 1e-5f);
                    EXPECT_LE(uv.x * static_cast<float>(c), static_cast<float>(col + 1) + 1e-5f);
                    EXPECT_GE(uv.y * static_cast<float>(r), static_cast<float>(row) - 1e-5f);
                    EXPECT_LE(uv.y * static_cast<float>(r), static_cast<float>(row + 1) + 1e-5f);
                }
            }
        }
    }
    // Out-of-range frame and sheet sizes are clamped.
    const vec2 z = rk_im_flipbook_uv(vec2(0.5f), 99, 0, -2);
    EXPECT_FLOAT_EQ(z.x, 0.5f);
    EXPECT_FLOAT_EQ(z.y, 0.5f);
    // Per-room phase: rooms differ, the same room is deterministic.
    const vec2 r1 = rk_im_flipbook_room_uv(vec2(0.5f), ivec3(1, 2, 3), 10.0f, 8.0f, 16, 4, 4, 77u);
    const vec2 r2 = rk_im_flipbook_room_uv(vec2(0.5f), ivec3(1, 2, 3), 10.0f, 8.0f, 16, 4, 4, 77u);
    EXPECT_EQ(r1, r2);
    int distinct = 0;
    for (int k = 0; k < 64; ++k)
        distinct += rk_im_flipbook_room_uv(vec2(0.5f), ivec3(k, 0, 0), 10.0f, 8.0f, 16, 4, 4, 77u) != r1 ? 1 : 0;
    EXPECT_GT(distinct, 48);  // 15/16 of rooms expected on another frame
}
