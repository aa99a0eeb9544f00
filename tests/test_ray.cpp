// Tests of shaders/raykit/ray.glsl (C++ build): ray/plane, ray/sphere, ray/box and ray/ellipsoid
// intervals and normals against long double references written here (closest-approach sphere,
// per-axis slabs, the plane's quotient: none calls the functions under test), analytic cases
// (tangent rays, origins inside, on faces, edges and corners, parallel rays, zero, denormal and
// huge directions), distant spheres where the textbook quadratic breaks down (shown alongside),
// random sweeps that measure the error bounds stated in the doc comments, adversarial finite
// inputs (no NaN or Inf anywhere), and the impostor helpers' window depth against the projection
// matrices of every depth convention.
//
// RK_RAY_SCALE=n multiplies the random sample counts (the doc comments' figures come from n = 80,
// about 10^7 rays per primitive; the default runs 2^17 per set).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/ray.hpp"
#include "raykit/svo_hybrid.hpp"

using namespace raykit;

namespace {

using LD = long double;
constexpr double kEps = 5.9604644775390625e-8;  // 2^-24

struct LV {
    LD x = 0, y = 0, z = 0;
};
LV lv(vec3 v) { return {LD(v.x), LD(v.y), LD(v.z)}; }
LV sub(LV a, LV b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
LV add(LV a, LV b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
LV mul(LV a, LD s) { return {a.x * s, a.y * s, a.z * s}; }
LD dotl(LV a, LV b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
LD lenl(LV a) { return std::sqrt(dotl(a, a)); }
LV matl(const mat3& m, LV v)  // column-major m * v in long double
{
    return {LD(m[0][0]) * v.x + LD(m[1][0]) * v.y + LD(m[2][0]) * v.z, LD(m[0][1]) * v.x + LD(m[1][1]) * v.y + LD(m[2][1]) * v.z,
            LD(m[0][2]) * v.x + LD(m[1][2]) * v.y + LD(m[2][2]) * v.z};
}

long scale()
{
    const char* s = std::getenv("RK_RAY_SCALE");
    const long n = s ? std::atol(s) : 1;
    return n > 0 ? n : 1;
}

bool is_miss(vec2 t) { return t.x == RK_FLT_MAX && t.y == -RK_FLT_MAX; }
bool finite3(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
std::string str(vec3 v)
{
    char b[128];
    std::snprintf(b, sizeof b, "(%.9g, %.9g, %.9g)", double(v.x), double(v.y), double(v.z));
    return b;
}

/// Long double reference of a ray against the ball |p - c| <= r, in units of d: the closest
/// approach first, then the half-chord. hit = false for a miss; h is the half-chord's length.
struct SphereRef {
    bool hit = false;
    LD t0 = 0, t1 = 0, h = 0;
};
SphereRef sphere_ref(LV w, LV d, LD r)  // w = o - c
{
    SphereRef s;
    const LD a = dotl(d, d);
    const LD tc = -dotl(w, d) / a;
    const LV f = add(w, mul(d, tc));
    const LD h2 = r * r - dotl(f, f);
    if (h2 < 0) return s;
    s.hit = true;
    s.h = std::sqrt(h2);
    const LD ht = s.h / std::sqrt(a);
    s.t0 = tc - ht;
    s.t1 = tc + ht;
    return s;
}

/// The textbook quadratic in float: t = -b ∓ sqrt(b² - c), b = w·u, c = |w|² - r², u unit.
vec2 sphere_naive(vec3 o, vec3 d, vec3 c, float r)
{
    const vec3 u = glm::normalize(d);
    const vec3 w = o - c;
    const float b = glm::dot(w, u), cc = glm::dot(w, w) - r * r;
    const float disc = b * b - cc;
    if (disc < 0.0f) return RK_RAY_MISS;
    const float h = std::sqrt(disc), l = glm::length(d);
    return vec2((-b - h) / l, (-b + h) / l);
}

std::mt19937_64& rng()
{
    static std::mt19937_64 g(20260316u);
    return g;
}
double uni(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng()); }
double loguni(double lo, double hi) { return lo * std::pow(hi / lo, uni(0.0, 1.0)); }
vec3 rand_unit()
{
    for (;;) {
        const glm::dvec3 v(uni(-1, 1), uni(-1, 1), uni(-1, 1));
        const double l = glm::length(v);
        if (l > 0.05 && l <= 1.0) return vec3(v / l);
    }
}
vec3 rand_ball() { return rand_unit() * float(std::cbrt(uni(0.0, 1.0))); }
vec3 rand_box(double s) { return vec3(float(uni(-s, s)), float(uni(-s, s)), float(uni(-s, s))); }

/// Max of a normalised error, remembering the worst case.
struct Worst {
    double v = 0;
    std::string where;
    void add(double e, const std::string& w)
    {
        if (e > v || std::isnan(e)) {
            v = std::isnan(e) ? INFINITY : e;
            where = w;
        }
    }
};

// ---------------------------------------------------------------------------------------------
// Sphere

TEST(RaySphere, AnalyticCases)
{
    vec3 ne, nx;
    // Through the centre, unit and non-unit directions.
    vec2 t = rk_ray_sphere_normals(vec3(0, 0, -5), vec3(0, 0, 1), vec3(0), 1.0f, ne, nx);
    EXPECT_EQ(t, vec2(4.0f, 6.0f));
    EXPECT_EQ(ne, vec3(0, 0, -1));
    EXPECT_EQ(nx, vec3(0, 0, 1));
    EXPECT_EQ(rk_ray_sphere(vec3(0, 0, -5), vec3(0, 0, 2), vec3(0), 1.0f), vec2(2.0f, 3.0f));
    EXPECT_EQ(rk_ray_sphere(vec3(0, 0, -5), vec3(0, 0, 0.25f), vec3(0), 1.0f), vec2(16.0f, 24.0f));
    // Behind the origin: the whole line's interval, both negative.
    t = rk_ray_sphere(vec3(0, 0, 5), vec3(0, 0, 1), vec3(0), 1.0f);
    EXPECT_EQ(t, vec2(-6.0f, -4.0f));
    EXPECT_FALSE(rk_ray_hit(t));
    // Origin inside, at the centre and off-centre.
    t = rk_ray_sphere(vec3(0), vec3(1, 0, 0), vec3(0), 2.0f);
    EXPECT_EQ(t, vec2(-2.0f, 2.0f));
    EXPECT_TRUE(rk_ray_hit(t));
    EXPECT_EQ(rk_ray_nearest(t), 2.0f);
    t = rk_ray_sphere(vec3(0.5f, 0, 0), vec3(1, 0, 0), vec3(0), 1.0f);
    EXPECT_EQ(t, vec2(-1.5f, 0.5f));
    // On the surface, leaving and entering.
    EXPECT_EQ(rk_ray_sphere(vec3(1, 0, 0), vec3(1, 0, 0), vec3(0), 1.0f), vec2(-2.0f, 0.0f));
    EXPECT_EQ(rk_ray_sphere(vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0), 1.0f), vec2(0.0f, 2.0f));
    // Tangent: one point; just outside: a miss.
    t = rk_ray_sphere_normals(vec3(1, 0, -5), vec3(0, 0, 1), vec3(0), 1.0f, ne, nx);
    EXPECT_EQ(t, vec2(5.0f, 5.0f));
    EXPECT_EQ(ne, vec3(1, 0, 0));
    EXPECT_EQ(nx, vec3(1, 0, 0));
    EXPECT_TRUE(is_miss(rk_ray_sphere(vec3(std::nextafter(1.0f, 2.0f), 0, -5), vec3(0, 0, 1), vec3(0), 1.0f)));
    t = rk_ray_sphere_normals(vec3(3, 0, -5), vec3(0, 0, 1), vec3(0), 1.0f, ne, nx);
    EXPECT_TRUE(is_miss(t));
    EXPECT_EQ(ne, vec3(0));
    EXPECT_EQ(nx, vec3(0));
    // Radius 0: only a ray through the centre touches it; a negative radius reads as 0.
    EXPECT_EQ(rk_ray_sphere(vec3(0, 0, -5), vec3(0, 0, 1), vec3(0), 0.0f), vec2(5.0f, 5.0f));
    EXPECT_EQ(rk_ray_sphere(vec3(0, 0, -5), vec3(0, 0, 1), vec3(0), -3.0f), vec2(5.0f, 5.0f));
    EXPECT_TRUE(is_miss(rk_ray_sphere(vec3(0, 1, -5), vec3(0, 0, 1), vec3(0), -3.0f)));
    // Zero and denormal directions: a point, inside or not.
    for (vec3 d : {vec3(0.0f), vec3(-0.0f, 0.0f, -0.0f), vec3(1e-40f, -1e-45f, 1e-39f)}) {
        t = rk_ray_sphere_normals(vec3(0.5f, 0, 0), d, vec3(0), 1.0f, ne, nx);
        EXPECT_EQ(t, vec2(-RK_FLT_MAX, RK_FLT_MAX)) << str(d);
        EXPECT_EQ(ne, vec3(0));
        EXPECT_TRUE(is_miss(rk_ray_sphere(vec3(1.5f, 0, 0), d, vec3(0), 1.0f))) << str(d);
    }
    // Tiny and huge (non-denormal) directions scale t.
    t = rk_ray_sphere(vec3(0, 0, -5), vec3(0, 0, 1e-30f), vec3(0), 1.0f);
    EXPECT_NEAR(t.x, 4e30f, 4e30f * 1e-6f);
    EXPECT_NEAR(t.y, 6e30f, 6e30f * 1e-6f);
    t = rk_ray_sphere(vec3(0, 0, -5), vec3(0, 0, 1e35f), vec3(0), 1.0f);
    EXPECT_NEAR(t.x, 4e-35f, 4e-35f * 1e-6f);
    t = rk_ray_sphere(vec3(0, 0, -5), vec3(0, 0, 3e38f), vec3(0), 1.0f);
    EXPECT_NEAR(double(t.x), 4.0 / 3e38, 4.0 / 3e38 * 1e-6);
    // Huge and tiny scenes (positions scaled internally by 2^-80 and 2^80).
    t = rk_ray_sphere(vec3(0, 0, -5e30f), vec3(0, 0, 1), vec3(0), 1e30f);
    EXPECT_NEAR(t.x, 4e30f, 4e30f * 1e-6f);
    EXPECT_NEAR(t.y, 6e30f, 6e30f * 1e-6f);
    t = rk_ray_sphere(vec3(0, 0, -5e-30f), vec3(0, 0, 1), vec3(0), 1e-30f);
    EXPECT_NEAR(t.x, 4e-30f, 4e-30f * 1e-6f);
    EXPECT_NEAR(t.y, 6e-30f, 6e-30f * 1e-6f);
    // Beyond the float range: clamped, ordered, finite.
    t = rk_ray_sphere(vec3(0, 0, -3e38f), vec3(0, 0, 1e-30f), vec3(0), 1e38f);
    EXPECT_EQ(t, vec2(RK_FLT_MAX, RK_FLT_MAX));
}

/// A random ray for the sphere sweep: |o - c| = dist * r in a random direction, aimed at a random
/// point of the ball grown by 20 % (about two thirds hit), direction length 1e-3..1e3.
void sphere_ray(double dist_lo, double dist_hi, bool far_centre, vec3& o, vec3& d, vec3& c, float& r)
{
    r = far_centre ? 1.0f : float(loguni(0.01, 100.0));
    const double dist = uni(dist_lo, dist_hi);
    if (far_centre) {
        // A unit sphere far away, the origin near (0, 0, 0): c carries all the magnitude.
        o = rand_box(1.0);
        c = rand_unit() * float(dist);
    } else {
        c = rand_box(10.0);
        o = c + rand_unit() * float(dist * r);
    }
    const vec3 aim = c + rand_ball() * (1.2f * r);
    d = glm::normalize(aim - o) * float(loguni(1e-3, 1e3));
}

struct SphereSweep {
    Worst t_err, n_err;
    long hits = 0, rays = 0, band = 0;
};

void sweep_sphere(long n, double dlo, double dhi, bool far, SphereSweep& s)
{
    for (long i = 0; i < n; ++i) {
        vec3 o, d, c;
        float r;
        sphere_ray(dlo, dhi, far, o, d, c, r);
        vec3 ne, nx;
        const vec2 t = rk_ray_sphere_normals(o, d, c, r, ne, nx);
        const LV w = sub(lv(o), lv(c));
        const SphereRef ref = sphere_ref(w, lv(d), LD(r));
        const LD wl = lenl(w), dl = lenl(lv(d));
        const std::string where = "o " + str(o) + " d " + str(d) + " c " + str(c) + " r " + std::to_string(r);
        ++s.rays;
        ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && finite3(ne) && finite3(nx)) << where;
        const bool hit = !is_miss(t);
        ASSERT_TRUE(hit || (t.x > t.y)) << where;
        if (hit != ref.hit) {
            // Allowed only within the rounding band of tangency: exact h² below 4 ε (|w| + r) r.
            const LD h2 = ref.hit ? ref.h * ref.h : 0;
            ++s.band;
            ASSERT_LE(double(h2), 4.0 * kEps * double(wl + r) * r) << "hit/miss away from tangency: " << where;
            continue;
        }
        if (!hit) continue;
        ++s.hits;
        // |Δt| |d| against ε (|w| + r) (1 + r / h).
        const double norm = kEps * double(wl + r) * (1.0 + double(r / std::max(ref.h, LD(1e-300))));
        s.t_err.add(double(std::abs(LD(t.x) - ref.t0) * dl) / norm, "t_enter " + where);
        s.t_err.add(double(std::abs(LD(t.y) - ref.t1) * dl) / norm, "t_exit " + where);
        // Normals at h >= 0.01 r: the angle against ε (1 + |w| / h).
        if (ref.h >= 0.01L * r) {
            const LV pe = add(w, mul(lv(d), ref.t0)), px = add(w, mul(lv(d), ref.t1));
            for (int k = 0; k < 2; ++k) {
                const LV pr = k == 0 ? pe : px;
                const vec3 nv = k == 0 ? ne : nx;
                const LD pl = lenl(pr);
                const LD cosang = dotl(pr, lv(nv)) / (pl * lenl(lv(nv)));
                const LV cr = {pr.y * LD(nv.z) - pr.z * LD(nv.y), pr.z * LD(nv.x) - pr.x * LD(nv.z), pr.x * LD(nv.y) - pr.y * LD(nv.x)};
                const double ang = double(std::atan2(lenl(cr) / (pl * lenl(lv(nv))), cosang));
                s.n_err.add(ang / (kEps * (1.0 + double(wl / ref.h))), "normal " + where);
            }
        }
    }
}

TEST(RaySphere, RandomAgainstLongDouble)
{
    const long n = (1L << 17) * scale();
    SphereSweep near_set, far_set;
    sweep_sphere(n, 0.0, 100.0, false, near_set);
    sweep_sphere(n, 1e4, 1e6, true, far_set);
    for (const SphereSweep* s : {&near_set, &far_set}) {
        std::printf("[ray] sphere %s: %ld rays, %ld hits, %ld in the tangency band; max |Δt||d| / (ε (|w| + r)(1 + r/h)) = %.3g\n"
                    "      worst %s\n      max normal angle / (ε (1 + |w|/h)) = %.3g (h >= 0.01 r)\n      worst %s\n",
                    s == &near_set ? "|o-c| <= 100 r" : "|o-c| in [1e4, 1e6] r", s->rays, s->hits, s->band, s->t_err.v,
                    s->t_err.where.c_str(), s->n_err.v, s->n_err.where.c_str());
        EXPECT_LE(s->t_err.v, 3.9) << s->t_err.where;
        EXPECT_LE(s->n_err.v, 5.2) << s->n_err.where;
        EXPECT_GT(s->hits, s->rays / 3);
    }
}

// A unit sphere 1e4..1e6 away from an origin near (0, 0, 0): the stable form keeps t to a few ulps;
// the textbook b² - c, where b² and c are both ~|w|² and their difference ~r², loses ε |w|² / r²
// relative in the discriminant (everything beyond |w| ~ 4e3 r).
TEST(RaySphere, DistantSpheresStableVersusTextbook)
{
    for (double dist : {1e4, 1e5, 1e6}) {
        Worst stable, naive;
        long naive_wrong_class = 0, n = 20000;
        for (long i = 0; i < n; ++i) {
            const vec3 c = rand_unit() * float(dist);
            const vec3 o = rand_box(1.0);
            // Aim inside the central 90 % of the disk: h >= 0.43 r, t well-conditioned.
            const vec3 aim = c + rand_ball() * 0.9f;
            const vec3 d = glm::normalize(aim - o);
            const SphereRef ref = sphere_ref(sub(lv(o), lv(c)), lv(d), 1.0L);
            if (!ref.hit || ref.h < 0.43L) continue;
            const vec2 t = rk_ray_sphere(o, d, c, 1.0f);
            const vec2 tn = sphere_naive(o, d, c, 1.0f);
            const LD dl = lenl(lv(d));
            ASSERT_FALSE(is_miss(t)) << dist;
            stable.add(double(std::abs(LD(t.x) - ref.t0) * dl / (ref.t0 * dl)), str(o) + str(d) + str(c));
            if (is_miss(tn)) {
                ++naive_wrong_class;
            } else {
                naive.add(double(std::abs(LD(tn.x) - ref.t0) * dl / (ref.t0 * dl)), str(o) + str(d) + str(c));
            }
        }
        std::printf("[ray] unit sphere at %.0e: relative error of t_enter, stable %.3g, textbook %.3g where it hits "
                    "(and %ld of %ld rays it misses)\n",
                    dist, stable.v, naive.v, naive_wrong_class, n);
        EXPECT_LE(stable.v, 5.0e-7) << stable.where;
        // The contrast: the textbook formula visibly fails here (misses rays through the disc's
        // middle 90 %, and is far off where it hits).
        EXPECT_GE(naive.v, 1e-4) << "textbook";
        EXPECT_GT(naive_wrong_class, n / 20);
    }
}

// ---------------------------------------------------------------------------------------------
// Ellipsoids

TEST(RayEllipsoid, AnalyticCases)
{
    vec3 ne, nx;
    vec2 t = rk_ray_ellipsoid_normals(vec3(-5, 0, 0), vec3(1, 0, 0), vec3(0), vec3(2, 1, 0.5f), ne, nx);
    EXPECT_EQ(t, vec2(3.0f, 7.0f));
    EXPECT_EQ(ne, vec3(-1, 0, 0));
    EXPECT_EQ(nx, vec3(1, 0, 0));
    t = rk_ray_ellipsoid(vec3(1, 2, -5), vec3(0, 0, 1), vec3(1, 2, 3), vec3(2, 1, 0.5f));
    EXPECT_EQ(t, vec2(7.5f, 8.5f));
    // Tangent along y at x = 2 (the x semi-axis).
    EXPECT_EQ(rk_ray_ellipsoid(vec3(2, -5, 0), vec3(0, 1, 0), vec3(0), vec3(2, 1, 0.5f)), vec2(5.0f, 5.0f));
    // A tangent ray off the axes: t is sqrt(ε)-conditioned there (a square root of a rounding).
    const float s = 1.0f / std::sqrt(2.0f);
    t = rk_ray_ellipsoid(vec3(2 * s, 1 * s, -5), vec3(0, 0, 1), vec3(0), vec3(2, 1, 0.5f));
    EXPECT_NEAR(t.x, 5.0f, 5e-4f);
    EXPECT_NEAR(t.y, 5.0f, 5e-4f);
    // Off-axis hit: p = (1, 0.5, -sqrt(0.5) / 2) on the (2, 1, 0.5) ellipsoid, normal ∝ (x/a², y/b², z/c²).
    const float pz = -0.5f * std::sqrt(0.5f);
    t = rk_ray_ellipsoid_normals(vec3(1, 0.5f, -5), vec3(0, 0, 1), vec3(0), vec3(2, 1, 0.5f), ne, nx);
    EXPECT_NEAR(t.x, 5.0f + pz, 2e-6f);
    EXPECT_NEAR(t.y, 5.0f - pz, 2e-6f);
    const vec3 g = glm::normalize(vec3(1.0f / 4, 0.5f, pz / 0.25f));
    EXPECT_LT(glm::length(ne - g), 1e-6f);
    // Negative radii read as their magnitude.
    EXPECT_EQ(rk_ray_ellipsoid(vec3(-5, 0, 0), vec3(1, 0, 0), vec3(0), vec3(-2, 1, -0.5f)), vec2(3.0f, 7.0f));
    // A thin disc (z semi-axis 1e-3) and a flat one (0, floored at RK_FLT_MIN): finite, near z = 0.
    t = rk_ray_ellipsoid_normals(vec3(0.5f, 0.25f, -5), vec3(0, 0, 1), vec3(0), vec3(2, 1, 1e-3f), ne, nx);
    EXPECT_NEAR(t.x, 5.0f - 1e-3f * std::sqrt(0.875f), 1e-6f);
    EXPECT_NEAR(t.y, 5.0f + 1e-3f * std::sqrt(0.875f), 1e-6f);
    EXPECT_LT(glm::length(ne - vec3(0, 0, -1)), 1e-3f);
    EXPECT_LT(glm::length(nx - vec3(0, 0, 1)), 1e-3f);
    t = rk_ray_ellipsoid_normals(vec3(0.5f, 0.25f, -5), vec3(0, 0, 1), vec3(0), vec3(2, 1, 0), ne, nx);
    EXPECT_NEAR(t.x, 5.0f, 1e-5f);
    EXPECT_NEAR(t.y, 5.0f, 1e-5f);
    EXPECT_TRUE(finite3(ne) && finite3(nx));
    EXPECT_TRUE(is_miss(rk_ray_ellipsoid(vec3(0.5f, 0.25f, -5), vec3(1, 0, 0), vec3(0), vec3(2, 1, 0))));
    // The matrix form: a rotation by 90° about z of the (2, 1, 0.5) ellipsoid is the (1, 2, 0.5) one.
    const mat3 m(vec3(0, 2, 0), vec3(-1, 0, 0), vec3(0, 0, 0.5f));  // columns: M maps the unit ball
    const mat3 inv = glm::inverse(m);
    t = rk_ray_ellipsoid_m_normals(vec3(0, -5, 0), vec3(0, 1, 0), vec3(0), inv, ne, nx);
    EXPECT_NEAR(t.x, 3.0f, 1e-6f);
    EXPECT_NEAR(t.y, 7.0f, 1e-6f);
    EXPECT_NEAR(ne.y, -1.0f, 1e-6f);
    EXPECT_NEAR(nx.y, 1.0f, 1e-6f);
    EXPECT_EQ(rk_ray_ellipsoid_m(vec3(0, -5, 0), vec3(0, 1, 0), vec3(0), inv), t);
    // A singular map (a slab |z| <= 1 through the flattening): finite.
    const mat3 sing(vec3(0), vec3(0), vec3(0, 0, 1));
    t = rk_ray_ellipsoid_m(vec3(0, 0, -5), vec3(0, 0, 1), vec3(0), sing);
    EXPECT_EQ(t, vec2(4.0f, 6.0f));
    EXPECT_EQ(rk_ray_ellipsoid_m(vec3(0, 0, 0), vec3(1, 0, 0), vec3(0), sing), vec2(-RK_FLT_MAX, RK_FLT_MAX));
}

/// A random rotation times a diagonal scale in [0.1, 10], as columns (the map of the unit ball).
mat3 rand_ellipsoid_map()
{
    const glm::dvec3 a = glm::normalize(glm::dvec3(rand_unit()));
    glm::dvec3 b = glm::normalize(glm::cross(a, glm::dvec3(rand_unit())));
    const glm::dvec3 cc = glm::cross(a, b);
    return mat3(glm::dmat3(a * loguni(0.1, 10), b * loguni(0.1, 10), cc * loguni(0.1, 10)));
}

TEST(RayEllipsoid, RandomAgainstLongDouble)
{
    const long n = (1L << 17) * scale();
    for (int mode = 0; mode < 2; ++mode) {
        Worst err;
        long hits = 0, band = 0;
        for (long i = 0; i < n; ++i) {
            const vec3 c = rand_box(10.0);
            vec3 radii(float(loguni(0.1, 10)), float(loguni(0.1, 10)), float(loguni(0.1, 10)));
            const mat3 m = mode == 0 ? mat3(vec3(radii.x, 0, 0), vec3(0, radii.y, 0), vec3(0, 0, radii.z)) : rand_ellipsoid_map();
            const mat3 inv = glm::inverse(m);
            const float rmax = std::max(std::max(radii.x, radii.y), radii.z);
            const vec3 o = c + rand_unit() * float(uni(0.0, 100.0) * rmax);
            const vec3 aim = c + m * (rand_ball() * 1.2f);
            const vec3 d = glm::normalize(aim - o) * float(loguni(1e-3, 1e3));
            const vec2 t = mode == 0 ? rk_ray_ellipsoid(o, d, c, radii) : rk_ray_ellipsoid_m(o, d, c, inv);
            // Reference: the ray in the unit ball's space, in long double (radii divided exactly for
            // the axis-aligned case; the float inverse matrix applied exactly for the other).
            LV ws, ds;
            if (mode == 0) {
                const LV w = sub(lv(o), lv(c));
                ws = {w.x / radii.x, w.y / radii.y, w.z / radii.z};
                ds = {LD(d.x) / radii.x, LD(d.y) / radii.y, LD(d.z) / radii.z};
            } else {
                ws = matl(inv, sub(lv(o), lv(c)));
                ds = matl(inv, lv(d));
            }
            const SphereRef ref = sphere_ref(ws, ds, 1.0L);
            const std::string where = "o " + str(o) + " d " + str(d) + " c " + str(c) + " mode " + std::to_string(mode);
            ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y)) << where;
            const LD wl = lenl(ws), dl = lenl(ds);
            if (is_miss(t) != !ref.hit) {
                ++band;
                const LD h2 = ref.hit ? ref.h * ref.h : 0;
                ASSERT_LE(double(h2), 8.0 * kEps * double(wl + 1)) << where;
                continue;
            }
            if (!ref.hit) continue;
            ++hits;
            // The matrix form: the product's rounding scales with |A| |w| and |A| |d| (absolute values
            // componentwise), not with |A w|: the conditioning of the map, not of the method.
            LD aw = wl, ad = dl;
            if (mode == 1) {
                mat3 am;
                for (int a = 0; a < 3; ++a) am[a] = abs(inv[a]);
                const LV wabs = {std::abs(LD(o.x) - c.x), std::abs(LD(o.y) - c.y), std::abs(LD(o.z) - c.z)};
                aw = lenl(matl(am, wabs));
                ad = lenl(matl(am, lv(abs(d))));
            }
            const double cond = double(1 / std::max(ref.h, LD(1e-300)));
            for (int k = 0; k < 2; ++k) {
                const LD tr = k == 0 ? ref.t0 : ref.t1;
                const double norm = kEps * double(aw + std::abs(tr) * ad + 1) * (1.0 + cond);
                err.add(double(std::abs(LD(k == 0 ? t.x : t.y) - tr) * dl) / norm, where);
            }
        }
        std::printf("[ray] ellipsoid %s: %ld rays, %ld hits, %ld in the band; max |Δt||d'| / (ε (|A||w| + |t||A||d| + 1)(1 + 1/h')) = %.3g\n"
                    "      worst %s\n",
                    mode == 0 ? "axis-aligned" : "matrix", n, hits, band, err.v, err.where.c_str());
        EXPECT_LE(err.v, mode == 0 ? 2.0 : 2.1) << err.where;
        EXPECT_GT(hits, n / 3);
    }
}

// ---------------------------------------------------------------------------------------------
// Box

TEST(RayBox, AnalyticCases)
{
    const vec3 lo(-1, -2, -3), hi(1, 2, 3);
    vec3 ne, nx;
    vec2 t = rk_ray_box_normals(vec3(-5, 0, 0), vec3(1, 0, 0), lo, hi, ne, nx);
    EXPECT_EQ(t, vec2(4.0f, 6.0f));
    EXPECT_EQ(ne, vec3(-1, 0, 0));
    EXPECT_EQ(nx, vec3(1, 0, 0));
    // Corners given in either order.
    EXPECT_EQ(rk_ray_box(vec3(-5, 0, 0), vec3(2, 0, 0), hi, lo), vec2(2.0f, 3.0f));
    // Inside, and behind.
    t = rk_ray_box_normals(vec3(0), vec3(0, 0, -1), lo, hi, ne, nx);
    EXPECT_EQ(t, vec2(-3.0f, 3.0f));
    EXPECT_EQ(ne, vec3(0, 0, 1));
    EXPECT_EQ(nx, vec3(0, 0, -1));
    EXPECT_FALSE(rk_ray_hit(rk_ray_box(vec3(0, 0, 5), vec3(0, 0, 1), lo, hi)));
    // Parallel to a slab: inside it (including on its planes) or not.
    EXPECT_EQ(rk_ray_box(vec3(-5, 1.5f, 0), vec3(1, 0, 0), lo, hi), vec2(4.0f, 6.0f));
    EXPECT_EQ(rk_ray_box(vec3(-5, 2.0f, 0), vec3(1, 0, 0), lo, hi), vec2(4.0f, 6.0f));   // along the face y = 2
    EXPECT_EQ(rk_ray_box(vec3(-5, -2.0f, 3), vec3(1, 0, 0), lo, hi), vec2(4.0f, 6.0f));  // along an edge
    EXPECT_TRUE(is_miss(rk_ray_box(vec3(-5, std::nextafter(2.0f, 3.0f), 0), vec3(1, 0, 0), lo, hi)));
    // -0 and denormal components are parallel too.
    EXPECT_EQ(rk_ray_box(vec3(-5, 0, 0), vec3(1, -0.0f, 1e-40f), lo, hi), vec2(4.0f, 6.0f));
    EXPECT_TRUE(is_miss(rk_ray_box(vec3(-5, 2.5f, 0), vec3(1, -1e-45f, 0), lo, hi)));
    // A tiny (normal) component is not: the y slab is then 2.5e30 away.
    t = rk_ray_box(vec3(-5, 0, 0), vec3(1, 1e-30f, 0), lo, hi);
    EXPECT_EQ(t, vec2(4.0f, 6.0f));
    // Origins on faces, edges and corners, leaving, entering and running along: never NaN, t = 0 exact.
    const vec3 on[] = {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(1, 2, 0), vec3(1, -2, 3), vec3(-1, -2, -3), vec3(1, 2, 3)};
    const vec3 dirs[] = {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, 0, -1), vec3(1, 1, 1), vec3(-1, -1, -1),
                         vec3(-1, 0.5f, 0.25f), vec3(0, 0, 0), vec3(0, -0.0f, 1e-42f)};
    for (vec3 p : on) {
        for (vec3 d : dirs) {
            t = rk_ray_box_normals(p, d, lo, hi, ne, nx);
            const std::string w = "o " + str(p) + " d " + str(d);
            ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y) && finite3(ne) && finite3(nx)) << w;
            // The origin is on the closed box: t_enter <= 0 <= t_exit unless the line only grazes
            // it from outside (which it cannot: the origin itself is a point of the box).
            EXPECT_LE(t.x, 0.0f) << w;
            EXPECT_GE(t.y, 0.0f) << w;
            // One end is exactly 0 (the origin is on the surface) unless the ray runs inside a face.
            bool along = false;  // parallel to a face plane the origin lies on
            for (int a = 0; a < 3; ++a)
                if ((p[a] == lo[a] || p[a] == hi[a]) && !(std::abs(d[a]) >= RK_FLT_MIN)) along = true;
            if (!along) {
                EXPECT_TRUE(t.x == 0.0f || t.y == 0.0f) << w << " t " << t.x << " " << t.y;
                EXPECT_NEAR(glm::length(ne), 1.0f, 1e-6f) << w;
            }
        }
    }
    // Entering through an edge (1, 2) diagonally: both faces tie; the steeper (here y) is reported.
    t = rk_ray_box_normals(vec3(3, 4, 0), vec3(-1, -1, 0), lo, hi, ne, nx);
    EXPECT_EQ(t.x, 2.0f);
    t = rk_ray_box_normals(vec3(2, 4, 0), vec3(-1, -2, 0), lo, hi, ne, nx);
    EXPECT_EQ(t.x, 1.0f);
    EXPECT_EQ(ne, vec3(0, 1, 0));
    // Zero direction: a point.
    EXPECT_EQ(rk_ray_box(vec3(0), vec3(0), lo, hi), vec2(-RK_FLT_MAX, RK_FLT_MAX));
    EXPECT_TRUE(is_miss(rk_ray_box(vec3(5, 0, 0), vec3(0), lo, hi)));
    // A degenerate (flat) box: still a closed set.
    EXPECT_EQ(rk_ray_box(vec3(0, 0, -5), vec3(0, 0, 1), vec3(-1, -1, 0), vec3(1, 1, 0)), vec2(5.0f, 5.0f));
}

TEST(RayBox, RandomAgainstLongDouble)
{
    const long n = (1L << 17) * scale();
    for (int far = 0; far < 2; ++far) {
        Worst rel;
        long hits = 0, band = 0, zero_checks = 0;
        for (long i = 0; i < n; ++i) {
            const double span = far ? 1e6 : 1e3;
            const vec3 lo = rand_box(span);
            const vec3 size(float(loguni(1e-3, 1e3)), float(loguni(1e-3, 1e3)), float(loguni(1e-3, 1e3)));
            const vec3 hi = lo + size;
            vec3 o = lo + size * vec3(float(uni(-2, 3)), float(uni(-2, 3)), float(uni(-2, 3)));
            const int kind = int(rng()() % 8u);
            if (kind == 0) o.x = lo.x;  // on a face plane
            if (kind == 1) {            // on an edge
                o.y = hi.y;
                o.z = lo.z;
            }
            vec3 aim = lo + size * vec3(float(uni(-0.1, 1.1)), float(uni(-0.1, 1.1)), float(uni(-0.1, 1.1)));
            vec3 d = (aim - o) * float(loguni(1e-3, 1e3));
            const int dk = int(rng()() % 10u);
            if (dk == 0) d.y = 0.0f;
            if (dk == 1) d.z = -0.0f;
            if (dk == 2) d.x = 1e-30f;
            if (dk == 3) d.y = -1e-40f;
            const vec2 t = rk_ray_box(o, d, lo, hi);
            // Reference: per-axis slabs in long double; |d_i| < FLT_MIN is parallel (the contract).
            LD t0 = -LD(RK_FLT_MAX), t1 = LD(RK_FLT_MAX);
            bool miss = false;
            const float oc[3] = {o.x, o.y, o.z}, dc[3] = {d.x, d.y, d.z}, lc[3] = {lo.x, lo.y, lo.z}, hc[3] = {hi.x, hi.y, hi.z};
            for (int a = 0; a < 3; ++a) {
                if (!(std::abs(dc[a]) >= RK_FLT_MIN)) {
                    if (oc[a] < lc[a] || oc[a] > hc[a]) miss = true;
                    continue;
                }
                const LD ta = (LD(lc[a]) - oc[a]) / dc[a], tb = (LD(hc[a]) - oc[a]) / dc[a];
                t0 = std::max(t0, std::min(ta, tb));
                t1 = std::min(t1, std::max(ta, tb));
            }
            const bool ref_hit = !miss && t0 <= t1;
            const std::string where = "o " + str(o) + " d " + str(d) + " lo " + str(lo) + " hi " + str(hi);
            ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y)) << where;
            if (ref_hit != !is_miss(t)) {
                ++band;  // an edge or corner graze: t0 and t1 within rounding of each other
                ASSERT_FALSE(miss) << where;
                ASSERT_LE(double(std::abs(t1 - t0)), 4.0 * kEps * double(std::max(std::abs(t0), std::abs(t1)))) << where;
                continue;
            }
            if (!ref_hit) continue;
            ++hits;
            for (int k = 0; k < 2; ++k) {
                const LD r = k == 0 ? t0 : t1;
                const float g = k == 0 ? t.x : t.y;
                if (r == 0) {
                    ++zero_checks;
                    ASSERT_EQ(g, 0.0f) << where;
                } else {
                    rel.add(double(std::abs(LD(g) - r) / std::abs(r)) / kEps, where);
                }
            }
        }
        std::printf("[ray] box %s: %ld rays, %ld hits, %ld edge grazes, %ld exact zeros; max |Δt| / (ε |t|) = %.3g\n      worst %s\n",
                    far ? "at 1e6" : "within 1e3", n, hits, band, zero_checks, rel.v, rel.where.c_str());
        EXPECT_LE(rel.v, 2.0) << rel.where;
        EXPECT_GT(zero_checks, 0);
    }
}

// ---------------------------------------------------------------------------------------------
// Plane

TEST(RayPlane, AnalyticCases)
{
    // The half-space z <= 1 (normal +z through (0, 0, 1)).
    EXPECT_EQ(rk_ray_plane(vec3(0, 0, 5), vec3(0, 0, -1), vec3(0, 0, 1), vec3(0, 0, 1)), vec2(4.0f, RK_FLT_MAX));
    EXPECT_EQ(rk_ray_plane(vec3(0, 0, 0), vec3(0, 0, 2), vec3(0, 0, 1), vec3(0, 0, 3)), vec2(-RK_FLT_MAX, 0.5f));
    EXPECT_EQ(rk_ray_plane_t(vec3(0, 0, 5), vec3(0, 0, -1), vec3(0, 0, 1), vec3(0, 0, 1)), 4.0f);
    EXPECT_EQ(rk_ray_plane_t(vec3(0, 0, 5), vec3(0, 0, 1), vec3(0, 0, 1), vec3(0, 0, 1)), -4.0f);  // behind
    // Parallel: inside, on the plane, outside.
    EXPECT_EQ(rk_ray_plane(vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 0, 1), vec3(0, 0, 1)), vec2(-RK_FLT_MAX, RK_FLT_MAX));
    EXPECT_EQ(rk_ray_plane(vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 0, 1), vec3(0, 0, 1)), vec2(-RK_FLT_MAX, RK_FLT_MAX));
    EXPECT_TRUE(is_miss(rk_ray_plane(vec3(0, 0, 2), vec3(1, 1e-40f, 0), vec3(0, 0, 1), vec3(0, 0, 1))));
    EXPECT_EQ(rk_ray_plane_t(vec3(0, 0, 2), vec3(1, 0, 0), vec3(0, 0, 1), vec3(0, 0, 1)), RK_FLT_MAX);
    EXPECT_EQ(rk_ray_plane_t(vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 0, 1), vec3(0, 0, 1)), RK_FLT_MAX);
    // Origin on the plane: t = 0 exactly.
    EXPECT_EQ(rk_ray_plane(vec3(3, 4, 1), vec3(0, 1, 1), vec3(0, 0, 1), vec3(0, 0, 7)), vec2(-RK_FLT_MAX, 0.0f));
    // Zero normal reads as +z; denormal direction is parallel.
    EXPECT_EQ(rk_ray_plane(vec3(0, 0, 5), vec3(0, 0, -1), vec3(0, 0, 1), vec3(0)), vec2(4.0f, RK_FLT_MAX));
    EXPECT_TRUE(is_miss(rk_ray_plane(vec3(0, 0, 5), vec3(0, 0, -1e-40f), vec3(0, 0, 1), vec3(0, 0, 1))));
    // Tiny direction: t huge but finite.
    EXPECT_EQ(rk_ray_plane(vec3(0, 0, 5), vec3(0, 0, -1e-37f), vec3(0, 0, -1e37f), vec3(0, 0, 1)).x, RK_FLT_MAX);
}

TEST(RayPlane, RandomAgainstLongDouble)
{
    const long n = (1L << 17) * scale();
    for (int far = 0; far < 2; ++far) {
        Worst err;
        for (long i = 0; i < n; ++i) {
            const double span = far ? 1e6 : 1e3;
            const vec3 p0 = rand_box(span), o = rand_box(span);
            const vec3 nrm = rand_unit() * float(loguni(1e-3, 1e3));
            const vec3 d = rand_unit() * float(loguni(1e-3, 1e3));
            const vec2 t = rk_ray_plane(o, d, p0, nrm);
            const LV w = sub(lv(p0), lv(o));
            const LD num = dotl(lv(nrm), w), den = dotl(lv(nrm), lv(d));
            const std::string where = "o " + str(o) + " d " + str(d) + " p0 " + str(p0) + " n " + str(nrm);
            ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y)) << where;
            const LD tr = num / den;
            const float g = den < 0 ? t.x : t.y;
            // The side must agree unless num is within rounding of 0 (o within rounding of the plane).
            const LD nl = lenl(lv(nrm)), wl = lenl(w), dl = lenl(lv(d));
            if ((den < 0) != (std::abs(t.x) < RK_FLT_MAX)) {
                ASSERT_LE(double(std::abs(den) / nl), 4.0 * kEps * double(dl)) << where;
                continue;
            }
            const double e = double(std::abs(LD(g) - tr) * std::abs(den / nl) / (wl + std::abs(tr) * dl)) / kEps;
            err.add(e, where);
        }
        std::printf("[ray] plane %s: %ld rays; max |Δt| |n̂·d| / (ε (|p0 - o| + |t||d|)) = %.3g\n      worst %s\n",
                    far ? "at 1e6" : "within 1e3", n, err.v, err.where.c_str());
        EXPECT_LE(err.v, 2.4) << err.where;
    }
}

// ---------------------------------------------------------------------------------------------
// Adversarial finite inputs: ±0, denormals, 1e-30, 1e30, ±FLT_MAX in every argument.

float adv(std::mt19937_64& g)
{
    static const float v[] = {0.0f, -0.0f, 1e-45f, -1e-45f, 1e-40f, -1e-40f, 1.17549435e-38f, -1.17549435e-38f, 1e-30f, -1e-30f,
                              1.0f, -1.0f, 0.5f, -2.0f, 3.0f, 1e30f, -1e30f, 3.4028235e38f, -3.4028235e38f, 1e20f, -1e-20f};
    const uint64_t r = g();
    if (r % 4u == 0u) return float(std::uniform_real_distribution<double>(-10.0, 10.0)(g));
    return v[(r >> 8) % (sizeof v / sizeof v[0])];
}

void check_interval(vec2 t, const std::string& what)
{
    ASSERT_TRUE(std::isfinite(t.x) && std::isfinite(t.y)) << what;
    ASSERT_TRUE(is_miss(t) || t.x <= t.y) << what << " t " << t.x << " " << t.y;
}
void check_normal(vec3 n, const std::string& what)
{
    ASSERT_TRUE(finite3(n)) << what;
    const float l = glm::length(n);
    ASSERT_TRUE(l == 0.0f || std::abs(l - 1.0f) < 1e-5f) << what << " |n| " << l;
}

TEST(RayAdversarial, NoNanOrInfForFiniteInputs)
{
    std::mt19937_64 g(77u);
    const long n = 200000 * scale();
    const vec3 kk[3] = {rk_gb_depth_params(0.1f, 100.0f, false), rk_gb_depth_params(0.1f, 0.0f, true), rk_gb_depth_params(1e-3f, 1e6f, true)};
    for (long i = 0; i < n; ++i) {
        const vec3 o(adv(g), adv(g), adv(g)), d(adv(g), adv(g), adv(g)), c(adv(g), adv(g), adv(g)), e(adv(g), adv(g), adv(g));
        const float r = adv(g);
        const mat3 m(adv(g), adv(g), adv(g), adv(g), adv(g), adv(g), adv(g), adv(g), adv(g));
        const std::string w = "o " + str(o) + " d " + str(d) + " c " + str(c) + " e " + str(e) + " r " + std::to_string(r);
        vec3 ne, nx;
        check_interval(rk_ray_sphere_normals(o, d, c, r, ne, nx), "sphere " + w);
        check_normal(ne, "sphere " + w);
        check_normal(nx, "sphere " + w);
        check_interval(rk_ray_ellipsoid_normals(o, d, c, e, ne, nx), "ellipsoid " + w);
        check_normal(ne, "ellipsoid " + w);
        check_normal(nx, "ellipsoid " + w);
        check_interval(rk_ray_ellipsoid_m_normals(o, d, c, m, ne, nx), "ellipsoid_m " + w);
        check_normal(ne, "ellipsoid_m " + w);
        check_normal(nx, "ellipsoid_m " + w);
        check_interval(rk_ray_box_normals(o, d, c, e, ne, nx), "box " + w);
        check_normal(ne, "box " + w);
        check_normal(nx, "box " + w);
        check_interval(rk_ray_plane(o, d, c, e), "plane " + w);
        ASSERT_TRUE(std::isfinite(rk_ray_plane_t(o, d, c, e))) << w;
        vec3 p, nn;
        float depth;
        rk_ray_impostor_sphere(o, d, c, r, kk[i % 3], p, nn, depth);
        ASSERT_TRUE(finite3(p) && std::isfinite(depth) && depth >= 0.0f && depth <= 1.0f) << "impostor sphere " << w;
        check_normal(nn, "impostor sphere " + w);
        rk_ray_impostor_box(o, d, c, m, e, kk[i % 3], p, nn, depth);
        ASSERT_TRUE(finite3(p) && std::isfinite(depth) && depth >= 0.0f && depth <= 1.0f) << "impostor box " << w;
        check_normal(nn, "impostor box " + w);
    }
}

// ---------------------------------------------------------------------------------------------
// Impostors

/// Window depth of view-space point p through the column-major projection P in double, for NDC z
/// in [-1, 1] (OpenGL: depth = z/2 + 1/2) or [0, 1] (Vulkan, reversed-Z).
double window_depth_ref(const glm::dmat4& P, glm::dvec3 p, bool minus_one_to_one)
{
    const glm::dvec4 c = P * glm::dvec4(p, 1.0);
    const double z = c.z / c.w;
    return minus_one_to_one ? 0.5 * z + 0.5 : z;
}

TEST(RayImpostor, SphereDepthEveryConvention)
{
    const double n = 0.1, f = 100.0, fovy = 1.0, aspect = 1.5;
    struct Conv {
        const char* name;
        glm::dmat4 P;
        bool m11;
        vec3 k;
        vec2 depth_range;
    };
    glm::dmat4 rev = glm::perspectiveRH_ZO(fovy, aspect, f, n);  // near <-> far: reversed-Z
    // Reversed infinite: z_ndc = n / -z_view, i.e. P[2][2] = 0, P[3][2] = n, w = -z_view.
    glm::dmat4 rev_inf(0.0);
    rev_inf[0][0] = 1.0 / (aspect * std::tan(fovy / 2));
    rev_inf[1][1] = 1.0 / std::tan(fovy / 2);
    rev_inf[2][3] = -1.0;
    rev_inf[3][2] = n;
    const Conv convs[] = {
        {"OpenGL [-1,1]", glm::perspectiveRH_NO(fovy, aspect, n, f), true, rk_gb_depth_params(0.1f, 100.0f, false), vec2(0.5f, 0.5f)},
        {"Vulkan [0,1]", glm::perspectiveRH_ZO(fovy, aspect, n, f), false, rk_gb_depth_params(0.1f, 100.0f, false), vec2(1.0f, 0.0f)},
        {"reversed-Z", rev, false, rk_gb_depth_params(0.1f, 100.0f, true), vec2(1.0f, 0.0f)},
        {"reversed-Z infinite", rev_inf, false, rk_gb_depth_params(0.1f, 0.0f, true), vec2(1.0f, 0.0f)},
    };
    const vec3 c(0.3f, -0.2f, -5.0f);
    const float r = 1.0f;
    for (const Conv& cv : convs) {
        Worst err, svo_err;
        long hits = 0;
        for (int iy = 0; iy < 64; ++iy) {
            for (int ix = 0; ix < 64; ++ix) {
                // The proxy quad's fragment: a view-space point on the plane z = c.z + r facing the camera.
                const vec3 frag(c.x + (float(ix) / 31.5f - 1.0f) * 1.3f, c.y + (float(iy) / 31.5f - 1.0f) * 1.3f, c.z + r);
                vec3 p, nn;
                float depth;
                const bool hit = rk_ray_impostor_sphere(vec3(0), frag, c, r, cv.k, p, nn, depth);
                const SphereRef ref = sphere_ref(sub(LV{}, lv(c)), lv(frag), LD(r));
                if (hit != ref.hit) {
                    ASSERT_LT(double(ref.h), 1e-3) << "hit/miss away from the silhouette";
                    continue;
                }
                if (!hit) {
                    EXPECT_EQ(depth, cv.k.z);
                    EXPECT_EQ(p, vec3(0));
                    continue;
                }
                ++hits;
                EXPECT_NEAR(glm::length(glm::dvec3(p) - glm::dvec3(c)), r, 2e-6) << "on the sphere";
                EXPECT_NEAR(glm::length(nn), 1.0f, 1e-6f);
                EXPECT_GT(glm::dot(nn, -p), -1e-3f) << "facing the camera";
                const glm::dvec3 pr = glm::dvec3(double(frag.x), double(frag.y), double(frag.z)) * double(ref.t0);
                const double want = window_depth_ref(cv.P, pr, cv.m11);
                err.add(std::abs(double(depth) - want) / kEps, cv.name);
                // The alternative (svo_hybrid.glsl) through the float matrix: the same depth to rounding.
                const float sd = rk_svo_window_depth(mat4(cv.P), p, cv.depth_range);
                svo_err.add(std::abs(double(sd) - want) / kEps, cv.name);
            }
        }
        std::printf("[ray] impostor sphere, %s: %ld hits, window depth within %.3g ε of the double projection "
                    "(rk_svo_window_depth through the float matrix: %.3g ε)\n",
                    cv.name, hits, err.v, svo_err.v);
        EXPECT_GT(hits, 1000);
        EXPECT_LE(err.v, 64.0) << cv.name;
    }
}

TEST(RayImpostor, CameraInsideAndBehind)
{
    const vec3 k = rk_gb_depth_params(0.1f, 100.0f, false);
    vec3 p, nn;
    float depth;
    // Camera inside the sphere: the far side, with its outward normal.
    ASSERT_TRUE(rk_ray_impostor_sphere(vec3(0), vec3(0, 0, -1), vec3(0, 0, -1), 3.0f, k, p, nn, depth));
    EXPECT_EQ(p, vec3(0, 0, -4));
    EXPECT_EQ(nn, vec3(0, 0, -1));
    EXPECT_NEAR(depth, rk_gb_window_depth(4.0f, k), 1e-7f);
    // Sphere behind the camera: no hit, the far plane's depth (1 usual, 0 reversed).
    EXPECT_FALSE(rk_ray_impostor_sphere(vec3(0), vec3(0, 0, -1), vec3(0, 0, 5), 1.0f, k, p, nn, depth));
    EXPECT_EQ(depth, 1.0f);
    EXPECT_FALSE(rk_ray_impostor_sphere(vec3(0), vec3(0, 0, -1), vec3(0, 0, 5), 1.0f, rk_gb_depth_params(0.1f, 100.0f, true), p,
                                        nn, depth));
    EXPECT_EQ(depth, 0.0f);
}

TEST(RayImpostor, OrientedBox)
{
    const vec3 k = rk_gb_depth_params(0.1f, 0.0f, true);
    // A box rotated 30° about y and 20° about x, centre (0.5, 0.2, -6), half extents (1, 0.5, 0.75).
    const glm::dmat4 rot = glm::rotate(glm::rotate(glm::dmat4(1.0), 0.52359877559829887, glm::dvec3(0, 1, 0)), 0.3490658503988659,
                                       glm::dvec3(1, 0, 0));
    const mat3 box_to_view = mat3(glm::dmat3(rot));
    const mat3 view_to_box = mat3(glm::transpose(glm::dmat3(rot)));
    const vec3 c(0.5f, 0.2f, -6.0f), e(1.0f, 0.5f, 0.75f);
    long hits = 0;
    for (int iy = 0; iy < 64; ++iy) {
        for (int ix = 0; ix < 64; ++ix) {
            const vec3 frag(float(ix) / 63.0f * 0.8f - 0.3f, float(iy) / 63.0f * 0.8f - 0.3f, -1.0f);
            vec3 p, nn;
            float depth;
            const bool hit = rk_ray_impostor_box(vec3(0), frag, c, view_to_box, e, k, p, nn, depth);
            // Reference: slabs in the box's frame in long double.
            const LV ob = matl(view_to_box, sub(LV{}, lv(c))), db = matl(view_to_box, lv(frag));
            LD t0 = -1e30L, t1 = 1e30L;
            const LD oc[3] = {ob.x, ob.y, ob.z}, dc[3] = {db.x, db.y, db.z}, ec[3] = {LD(e.x), LD(e.y), LD(e.z)};
            for (int a = 0; a < 3; ++a) {
                const LD ta = (-ec[a] - oc[a]) / dc[a], tb = (ec[a] - oc[a]) / dc[a];
                t0 = std::max(t0, std::min(ta, tb));
                t1 = std::min(t1, std::max(ta, tb));
            }
            const bool ref_hit = t0 <= t1 && t1 >= 0;
            if (hit != ref_hit) {
                ASSERT_LT(double(t1 - t0), 1e-5) << "only at the silhouette";
                continue;
            }
            if (!hit) continue;
            ++hits;
            const glm::dvec3 pr = glm::dvec3(frag) * double(t0);
            EXPECT_LT(glm::length(glm::dvec3(p) - pr), 4e-6 * glm::length(pr));
            // The normal is the box axis of the entry face, in view space.
            const vec3 q = view_to_box * (p - c);
            const vec3 rel = abs(q) / e;
            const int ax = rel.x >= rel.y && rel.x >= rel.z ? 0 : (rel.y >= rel.z ? 1 : 2);
            const vec3 want = box_to_view[ax] * (q[ax] > 0 ? 1.0f : -1.0f);
            EXPECT_LT(glm::length(nn - want), 1e-5f) << ix << " " << iy;
            EXPECT_NEAR(depth, rk_gb_window_depth(-p.z, k), 0.0f);
            EXPECT_NEAR(double(depth), 0.1 / double(-pr.z), 1e-6 * 0.1 / double(-pr.z) + 1e-9);
        }
    }
    EXPECT_GT(hits, 500);
}

}  // namespace
