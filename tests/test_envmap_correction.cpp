// CPU tests of raykit/envmap_correction.hpp and raykit/window_glass.hpp (the C++ builds of
// shaders/raykit/envmap_correction.glsl and window_glass.glsl) against float64 geometry and values
// from Fahlén, "Illumination for Real-Time Rendering of Large Architectural Environments" (2005),
// §3.1.2 and §3.2.4.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "raykit/envmap_correction.hpp"
#include "raykit/window_glass.hpp"
#include "reference/fresnel_ref.hpp"
#include "test_util.hpp"

using namespace raykit;
using rktest::ErrorStats;
using rktest::fmt;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct D3 {
    double x, y, z;
};
D3 dd(vec3 v) { return {v.x, v.y, v.z}; }
double ddot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 dsub(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 dadd(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 dmul(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dlen(D3 a) { return std::sqrt(ddot(a, a)); }
/// Sine of the angle between two vectors (0 when parallel or antiparallel).
double sin_between(D3 a, D3 b)
{
    const D3 c{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return dlen(c) / std::max(dlen(a) * dlen(b), 1e-300);
}

struct DirGen {
    std::mt19937 rng;
    std::normal_distribution<double> n{0.0, 1.0};
    explicit DirGen(unsigned seed) : rng(seed) {}
    vec3 operator()()
    {
        for (;;) {
            const double x = n(rng), y = n(rng), z = n(rng);
            const double l = std::sqrt(x * x + y * y + z * z);
            if (l > 1e-6) return vec3(static_cast<float>(x / l), static_cast<float>(y / l), static_cast<float>(z / l));
        }
    }
};

const float kAdversarial[] = {0.0f,  -0.0f,  1e-45f, -1e-45f, 1e-40f,        1.17549435e-38f,
                              1.0f,  -1.0f,  0.5f,   2.0f,    1e-20f,        -1e-20f,
                              1e20f, -1e20f, 1e30f,  -1e30f,  3.4028235e38f, -3.4028235e38f};
bool finite3(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

// ---------------------------------------------------------------------------------------------
// The thesis's sigmoid (§3.2.4; x = angle in radians: the thesis leaves x unstated)

TEST(EnvmapCorrection, SigmoidPublishedValues)
{
    const float a = RK_ENVMAP_FAHLEN_A, k = RK_ENVMAP_FAHLEN_K;
    EXPECT_NEAR(rk_envmap_sigmoid(0.9f, a, k), 0.5, 1e-7);
    EXPECT_NEAR(rk_envmap_sigmoid(0.0f, a, k), 0.98566, 5e-6);
    EXPECT_NEAR(rk_envmap_sigmoid(static_cast<float>(kPi / 2), a, k), 0.04098, 5e-6);
    EXPECT_NEAR(rk_envmap_sigmoid(0.5f, a, k), 0.8676, 5e-5);
    EXPECT_NEAR(rk_envmap_sigmoid(1.2f, a, k), 0.1962, 5e-5);
    EXPECT_EQ(RK_ENVMAP_FAHLEN_D, 8.0f);
    // Against float64 over the range, and the weight is σ(acos(N·R)).
    ErrorStats s, w;
    for (int i = 0; i <= 10000; ++i) {
        const double x = kPi * i / 10000.0;
        s.add(rk_envmap_sigmoid(static_cast<float>(x), a, k),
              1.0 / (1.0 + std::exp(-(-4.7) * (static_cast<float>(x) - 0.9))), fmt("x", x));
        const float c = static_cast<float>(std::cos(x));
        w.add(rk_envmap_fahlen_weight(c, a, k), 1.0 / (1.0 + std::exp(4.7 * (std::acos(static_cast<double>(c)) - 0.9))),
              fmt("cos", c));
    }
    std::printf("sigmoid vs float64: %s\nfahlen weight vs float64: %s\n", s.str().c_str(), w.str().c_str());
    EXPECT_LT(s.max_abs, 3e-7);
    EXPECT_LT(w.max_abs, 1e-6);
    // Approximates cos at small angles, below it towards grazing (closer to cos^2).
    EXPECT_NEAR(rk_envmap_fahlen_weight(std::cos(0.3f), a, k), std::cos(0.3), 0.03);
    EXPECT_LT(rk_envmap_fahlen_weight(std::cos(1.4f), a, k), std::cos(1.4));
}

// ---------------------------------------------------------------------------------------------
// The thesis's correction with an offset (CP != 0), against float64

namespace {

/// Float64 reference of the thesis's street-plane correction, written here from Fahlén 2005
/// §3.2.4 (x, unstated there, read as the angle between N and R in radians), not from
/// envmap_correction.glsl:
///   R' = R + CP sigma(x) / d,   x = acos(N.R),   sigma(x) = 1 / (1 + e^(-a (x - k))),
/// thesis constants a = -4.7, k = 0.9, d = 8 m. N.R is clamped to [-1, 1] (acos's domain) and
/// nothing else: the inputs of the tests below are unit vectors and moderate offsets. `scale`
/// receives |R| + |CP| sigma / d, the size of the two terms.
D3 fahlen_ref_at(D3 r, double cos_nr, D3 cp, double d, double a, double k, double& scale)
{
    const double x = std::acos(std::max(-1.0, std::min(1.0, cos_nr)));
    const double sigma = 1.0 / (1.0 + std::exp(-a * (x - k)));
    scale = dlen(r) + dlen(cp) * sigma / d;
    return dadd(r, dmul(cp, sigma / d));
}
D3 fahlen_ref(D3 r, D3 n, D3 cp, double d, double a, double k, double& scale)
{
    return fahlen_ref_at(r, ddot(n, r), cp, d, a, k, scale);
}

/// Normwise relative error of a float vector against a float64 one: |got - want| / |want|.
double rel_err(vec3 got, D3 want) { return dlen(dsub(dd(got), want)) / std::max(dlen(want), 1e-300); }

}  // namespace

TEST(EnvmapCorrection, FahlenMatchesFloat64ThesisFormula)
{
    // Random unit N and R over the whole sphere (N.R in [-1, 1]: grazing and back-facing R
    // included), offsets CP up to 50 m in every direction; the thesis overload and the explicit
    // one with random parameters. A quarter of the cases have R within 0.05 rad of N (near-normal
    // viewing of a window), where acos is ill-conditioned: the float N.R (a rounding of 6e-8 near
    // 1) moves the angle by up to sqrt(2 * 6e-8) = 3.5e-4 rad. The error is measured relative to
    // the size of the terms, |R| + |CP| sigma / d: R' itself can cancel to 0 (CP sigma / d = -R),
    // where any rounding is a large fraction of |R'|. The same error relative to |R'| is printed
    // for |R'| >= 0.5. Near normal, the error against the float64 formula evaluated at the float
    // N.R (the input rounding taken out) is printed too.
    DirGen gen(13);
    std::mt19937 rng(14);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    ErrorStats thesis, thesis_rel, params, near_normal, near_params, near_at_float_dot;
    for (int i = 0; i < 200000; ++i) {
        const vec3 n = gen();
        vec3 r = gen();
        const bool near = i % 4 == 0;
        if (near) r = glm::normalize(n + 0.05f * u01(rng) * gen());
        const vec3 cp = gen() * (50.0f * u01(rng));
        const std::string where = fmt("R", r.x, r.y, r.z, "N", n.x, n.y, n.z, "CP", cp.x, cp.y, cp.z);
        // Thesis constants (the 3-argument overload).
        const vec3 got = rk_reflect_correct_fahlen(r, n, cp);
        double scale = 0;
        const D3 want = fahlen_ref(dd(r), dd(n), dd(cp), 8.0, -4.7, 0.9, scale);
        const double e = dlen(dsub(dd(got), want)) / scale;
        (near ? near_normal : thesis).add(e, 0.0, where);
        if (!near && dlen(want) >= 0.5) thesis_rel.add(rel_err(got, want), 0.0, where);
        if (near) {
            double s2 = 0;
            const D3 w2 = fahlen_ref_at(dd(r), glm::dot(n, r), dd(cp), 8.0, -4.7, 0.9, s2);
            near_at_float_dot.add(dlen(dsub(dd(got), w2)) / s2, 0.0, where);
        }
        // The 3-argument overload is the 6-argument one at the thesis's constants, bit for bit.
        const vec3 same = rk_reflect_correct_fahlen(r, n, cp, 8.0f, -4.7f, 0.9f);
        ASSERT_EQ(got.x, same.x);
        ASSERT_EQ(got.y, same.y);
        ASSERT_EQ(got.z, same.z);
        // Other parameters: d in [2, 40] m, slope a in [-8, -1], midpoint k in [0.3, 1.5] rad.
        const float d = 2.0f + 38.0f * u01(rng), a = -1.0f - 7.0f * u01(rng), k = 0.3f + 1.2f * u01(rng);
        const vec3 gp = rk_reflect_correct_fahlen(r, n, cp, d, a, k);
        const D3 wp = fahlen_ref(dd(r), dd(n), dd(cp), d, a, k, scale);
        (near ? near_params : params).add(dlen(dsub(dd(gp), wp)) / scale, 0.0, where + fmt("d a k", d, a, k));
    }
    std::printf(
        "fahlen vs float64 R + CP sigma(acos(N.R)) / d, |err| / (|R| + |CP| sigma / d):\n"
        "  thesis constants, random N, R:              %s\n"
        "  (the same relative to |R'|, |R'| >= 0.5:     %s)\n"
        "  random d, a, k, random N, R:                %s\n"
        "  thesis constants, R within 0.05 rad of N:   %s\n"
        "  random d, a, k, R within 0.05 rad of N:     %s\n"
        "  thesis constants, near N, at the float N.R: %s\n",
        thesis.str().c_str(), thesis_rel.str().c_str(), params.str().c_str(), near_normal.str().c_str(),
        near_params.str().c_str(), near_at_float_dot.str().c_str());
    EXPECT_LT(thesis.max_abs, 4e-7) << thesis.worst;
    EXPECT_LT(thesis_rel.max_abs, 2e-6) << thesis_rel.worst;
    EXPECT_LT(params.max_abs, 1e-6) << params.worst;
    // Near normal the input rounding dominates: |sigma'(x)| <= 4.7 sigma(0) (1 - sigma(0)) = 0.0664
    // near x = 0 times 3.5e-4 rad is 2.3e-5 of the weight, 2.4e-5 of the scale (sigma >= 0.96
    // there); for a = -8, |sigma'| <= 2 (|a| / 4) allows up to 7e-4 of the weight.
    EXPECT_LT(near_normal.max_abs, 3e-5) << near_normal.worst;
    EXPECT_LT(near_params.max_abs, 3e-4) << near_params.worst;
    EXPECT_LT(near_at_float_dot.max_abs, 4e-7) << near_at_float_dot.worst;

    // Hand-computed values (N = +z, CP = (8, -16, 4) m, so CP / d = (1, -2, 0.5) for d = 8):
    //  (1) R at 3-4-5 angles, R = (0.6, 0, 0.8): x = acos(0.8) = atan(3/4) = 0.6435011088 rad;
    //      -a (x - k) = 4.7 (0.6435011088 - 0.9) = -1.2055447887; e^-1.2055447887 = 0.2995287752;
    //      sigma = 1 / 1.2995287752 = 0.7695097016, so
    //      R' = (0.6 + sigma, -2 sigma, 0.8 + 0.5 sigma) = (1.3695097016, -1.5390194032, 1.1847548508).
    //      The mutations give: cos for sigma 0.8 (R'.x = 1.4); sigma of cos x instead of x 0.6154;
    //      a and k swapped 0.9919; +a instead of -a 0.2305; CP negated R'.x = -0.1695; CP d for
    //      CP / d R'.x = 0.6 + 64 sigma. All at least 0.03 away from 1.3695097.
    //  (2) x = k exactly gives sigma = 1/2 whatever a is: R = (sin 0.9, 0, cos 0.9) =
    //      (0.7833269096, 0, 0.6216099683), R' = R + (0.5, -1, 0.25).
    const vec3 z(0.0f, 0.0f, 1.0f), cp(8.0f, -16.0f, 4.0f);
    const vec3 h1 = rk_reflect_correct_fahlen(vec3(0.6f, 0.0f, 0.8f), z, cp);
    EXPECT_NEAR(h1.x, 1.3695097016, 2e-6);
    EXPECT_NEAR(h1.y, -1.5390194032, 2e-6);
    EXPECT_NEAR(h1.z, 1.1847548508, 2e-6);
    const vec3 h2 = rk_reflect_correct_fahlen(vec3(0.7833269096f, 0.0f, 0.6216099683f), z, cp);
    EXPECT_NEAR(h2.x, 0.7833269096 + 0.5, 2e-6);
    EXPECT_NEAR(h2.y, -1.0, 2e-6);
    EXPECT_NEAR(h2.z, 0.6216099683 + 0.25, 2e-6);
    // Explicit parameters, same case (1) with d = 4 (CP / d doubles) and k = 0.6435011088 (= x, so
    // sigma = 1/2 for any a): R' = (0.6 + 1, -2, 0.8 + 0.5).
    const vec3 h3 = rk_reflect_correct_fahlen(vec3(0.6f, 0.0f, 0.8f), z, cp, 4.0f, -4.7f, 0.6435011088f);
    EXPECT_NEAR(h3.x, 1.6, 2e-6);
    EXPECT_NEAR(h3.y, -2.0, 2e-6);
    EXPECT_NEAR(h3.z, 1.3, 2e-6);
}

TEST(EnvmapCorrection, FahlenIsThePlaneModelWithSigmaForCos)
{
    // envmap_correction.glsl documents rk_reflect_correct_fahlen as rk_reflect_correct_plane_cos
    // with N.R replaced by sigma(angle(N, R)): both move R along CP, by sigma(x) / d and cos(x) / d.
    // Check the ratio of the two offsets against float64 sigma(x) / cos(x) where N.R >= 0.05, and
    // that behind the window (N.R < 0) plane_cos's weight is clamped to 0 while the sigmoid's
    // continues (sigma(pi/2) = 0.04098 down to sigma(pi) = 2.66e-5).
    DirGen gen(15);
    std::mt19937 rng(16);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    ErrorStats ratio, plane;
    for (int i = 0; i < 100000; ++i) {
        const vec3 n = gen(), r = gen();
        const vec3 cp = gen() * (1.0f + 49.0f * u01(rng));
        const vec3 f = rk_reflect_correct_fahlen(r, n, cp);
        const vec3 p = rk_reflect_correct_plane_cos(r, n, cp, 8.0f);
        const double c = ddot(dd(n), dd(r));
        // plane_cos against its float64 formula R + CP max(N.R, 0) / d (the thesis's un-tweaked model).
        const D3 pw = dadd(dd(r), dmul(dd(cp), std::max(c, 0.0) / 8.0));
        const std::string where = fmt("R", r.x, r.y, r.z, "N", n.x, n.y, n.z, "CP", cp.x, cp.y, cp.z);
        plane.add(dlen(dsub(dd(p), pw)) / (1.0 + dlen(dd(cp)) * std::max(c, 0.0) / 8.0), 0.0, where);
        const D3 df = dsub(dd(f), dd(r)), dp = dsub(dd(p), dd(r));
        if (c < -1e-6) {
            ASSERT_EQ(dlen(dp), 0.0) << where;  // plane_cos returns R itself
            // The sigmoid's weight in (sigma(pi), sigma(pi/2)), read back from the float result
            // (whose rounding is up to 3% of the offset for the smallest |CP| here).
            const double w = ddot(df, dd(cp)) / ddot(dd(cp), dd(cp)) * 8.0;
            ASSERT_GT(w, 2.0e-5) << where;
            ASSERT_LT(w, 0.0411) << where;
            continue;
        }
        if (c < 0.05) continue;
        const double x = std::acos(std::min(c, 1.0));
        const double want = (1.0 / (1.0 + std::exp(4.7 * (x - 0.9)))) / c;
        // ratio of the offsets along CP (both are multiples of CP up to rounding)
        ratio.add(ddot(df, dd(cp)) / ddot(dp, dd(cp)) / want - 1.0, 0.0, where);
    }
    std::printf(
        "plane_cos vs float64 R + CP max(N.R, 0) / d, |err| / (|R| + |CP| max(N.R, 0) / d): %s\n"
        "fahlen offset / plane_cos offset vs float64 sigma(x) / cos(x), relative: %s\n",
        plane.str().c_str(), ratio.str().c_str());
    EXPECT_LT(plane.max_abs, 1e-6) << plane.worst;
    EXPECT_LT(ratio.max_abs, 2e-5) << ratio.worst;
    // sigma < cos below 87.04 degrees (1.5191 rad), sigma > cos beyond: at grazing the thesis's
    // weight stays sigma(pi/2) = 0.04098 where plane_cos's reaches 0.
    const vec3 z(0.0f, 0.0f, 1.0f), cp(8.0f, 0.0f, 0.0f);
    EXPECT_LT(rk_reflect_correct_fahlen(vec3(std::sin(1.5f), 0.0f, std::cos(1.5f)), z, cp).x,
              rk_reflect_correct_plane_cos(vec3(std::sin(1.5f), 0.0f, std::cos(1.5f)), z, cp, 8.0f).x);
    EXPECT_GT(rk_reflect_correct_fahlen(vec3(std::sin(1.54f), 0.0f, std::cos(1.54f)), z, cp).x,
              rk_reflect_correct_plane_cos(vec3(std::sin(1.54f), 0.0f, std::cos(1.54f)), z, cp, 8.0f).x);
    EXPECT_NEAR(rk_reflect_correct_fahlen(vec3(1.0f, 0.0f, 0.0f), z, cp).x, 1.0 + 0.0409833, 1e-6);
    EXPECT_EQ(rk_reflect_correct_plane_cos(vec3(1.0f, 0.0f, 0.0f), z, cp, 8.0f).x, 1.0f);
}

TEST(EnvmapCorrection, ZeroOffsetKeepsTheDirection)
{
    DirGen gen(3);
    for (int i = 0; i < 1000; ++i) {
        const vec3 r = gen(), n = gen(), zero(0.0f);
        const vec3 c = gen() * 3.0f;
        EXPECT_LT(sin_between(dd(rk_reflect_correct_sphere(r, zero, 5.0f)), dd(r)), 1e-7);
        EXPECT_LT(sin_between(dd(rk_reflect_correct_plane_cos(r, n, zero, 8.0f)), dd(r)), 1e-7);
        EXPECT_LT(sin_between(dd(rk_reflect_correct_fahlen(r, n, zero)), dd(r)), 1e-7);
        if (glm::dot(r, n) > 0.0f) {
            EXPECT_LT(sin_between(dd(rk_reflect_correct_plane(r, c, c, n, 8.0f)), dd(r)), 1e-6);
        }
        EXPECT_LT(sin_between(dd(rk_reflect_correct_box(r, c, c, c - vec3(4.0f), c + vec3(5.0f, 6.0f, 7.0f))), dd(r)),
                  1e-6);
    }
    // Brennan: R + CP / r.
    const vec3 b = rk_reflect_correct_sphere(vec3(0.0f, 0.0f, 1.0f), vec3(2.0f, -4.0f, 0.0f), 8.0f);
    EXPECT_FLOAT_EQ(b.x, 0.25f);
    EXPECT_FLOAT_EQ(b.y, -0.5f);
    EXPECT_FLOAT_EQ(b.z, 1.0f);
}

TEST(EnvmapCorrection, ExactPlaneHitsThePlane)
{
    DirGen gen(5);
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    ErrorStats on_plane, on_ray;
    for (int i = 0; i < 100000; ++i) {
        const vec3 n = gen();
        vec3 r = gen();
        if (glm::dot(r, n) <= 0.0f) r = -r;
        const float d = 2.0f + 30.0f * (u(rng) + 1.0f);
        const vec3 c = vec3(u(rng), u(rng), u(rng)) * 50.0f;
        // P in front of the plane: anywhere on the window side, up to d from C along N.
        const vec3 p = c + vec3(u(rng), u(rng), u(rng)) * 10.0f;
        if (glm::dot(p - c, n) >= d) continue;
        const vec3 v = rk_reflect_correct_plane(r, p, c, n, d);
        const double w = ddot(dd(glm::normalize(r)), dd(n));
        if (w < 1e-3) continue;  // near-grazing: the hit is far away; checked for finiteness below
        const D3 hit = dadd(dd(c), dmul(dd(v), 1.0 / w));            // v = (H - C) (R·N)
        const double scale = std::max(1.0, dlen(dsub(hit, dd(c))));  // the hit's distance from C
        on_plane.add((ddot(dsub(hit, dd(c)), dd(n)) - d) / scale, 0.0, fmt("i", i));
        on_ray.add(sin_between(dsub(hit, dd(p)), dd(r)) * dlen(dsub(hit, dd(p))) / scale, 0.0, fmt("i", i));
    }
    std::printf("exact plane: ((H - C).N - d) / |H - C| %s\n             distance of H from the ray (relative) %s\n",
                on_plane.str().c_str(), on_ray.str().c_str());
    // These samples stay below 2e-6; the documented ~1.2e-7 |CP.N| / (R.N |H - C|) reaches 4.9e-5
    // in this set-up for P within a few cm of the plane at R.N ~ 2e-3 (the rounding of R.N).
    EXPECT_LT(on_plane.max_abs, 2e-6);
    EXPECT_LT(on_ray.max_abs, 2e-6);
}

TEST(EnvmapCorrection, ExactPlaneEqualsThesisPlaneModelForPointsOnTheWindow)
{
    // P on the window plane through C (CP·N = 0): the exact correction and the thesis's un-tweaked
    // R + CP (N·R) / d give the same direction.
    DirGen gen(7);
    std::mt19937 rng(8);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        const vec3 n = gen();
        vec3 r = gen();
        if (glm::dot(r, n) <= 0.01f) continue;
        vec3 cp = vec3(u(rng), u(rng), u(rng)) * 6.0f;
        cp -= glm::dot(cp, n) * n;
        const vec3 c(1.0f, 2.0f, 3.0f);
        const vec3 exact = rk_reflect_correct_plane(r, c + cp, c, n, 8.0f);
        const vec3 thesis = rk_reflect_correct_plane_cos(r, n, cp, 8.0f);
        worst = std::max(worst, sin_between(dd(exact), dd(thesis)));
        ASSERT_GT(glm::dot(exact, thesis), 0.0f);
    }
    EXPECT_LT(worst, 2e-6);
}

TEST(EnvmapCorrection, BoxProjectionHitsTheBox)
{
    DirGen gen(9);
    std::mt19937 rng(10);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    ErrorStats surface, ray;
    for (int i = 0; i < 100000; ++i) {
        const vec3 lo(-10.0f * u(rng) - 1.0f, -5.0f * u(rng) - 1.0f, -20.0f * u(rng) - 1.0f);
        const vec3 hi(10.0f * u(rng) + 1.0f, 5.0f * u(rng) + 1.0f, 20.0f * u(rng) + 1.0f);
        const vec3 p = lo + (hi - lo) * vec3(u(rng), u(rng), u(rng));
        const vec3 c = lo + (hi - lo) * vec3(u(rng), u(rng), u(rng));
        const vec3 r = gen();
        const vec3 v = rk_reflect_correct_box(r, p, c, lo, hi);
        const D3 hit = dadd(dd(c), dd(v));
        // float64 slab method: the exit point of the ray from P.
        double t = 1e300;
        const double pd[3] = {p.x, p.y, p.z}, rd[3] = {r.x, r.y, r.z}, lod[3] = {lo.x, lo.y, lo.z},
                     hid[3] = {hi.x, hi.y, hi.z};
        for (int a = 0; a < 3; ++a) {
            if (rd[a] > 0) t = std::min(t, (hid[a] - pd[a]) / rd[a]);
            if (rd[a] < 0) t = std::min(t, (lod[a] - pd[a]) / rd[a]);
        }
        const D3 want = dadd(dd(p), dmul(dd(r), t));
        const double size = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
        // On the box surface: inside the box and on one of its faces.
        const double h[3] = {hit.x, hit.y, hit.z};
        double face = 1e300, outside = 0;
        for (int a = 0; a < 3; ++a) {
            face = std::min({face, std::abs(h[a] - lod[a]), std::abs(h[a] - hid[a])});
            outside = std::max({outside, lod[a] - h[a], h[a] - hid[a]});
        }
        surface.add(std::max(face, outside) / size, 0.0, fmt("i", i));
        ray.add(dlen(dsub(hit, want)) / size, 0.0, fmt("i", i));
    }
    std::printf(
        "box: distance of C + result from the box surface / size %s\n     from the float64 exit point / size %s\n",
        surface.str().c_str(), ray.str().c_str());
    EXPECT_LT(surface.max_abs, 1e-6);
    EXPECT_LT(ray.max_abs, 2e-6);
    // Axis-aligned rays hit exactly.
    const vec3 lo(-2.0f, -3.0f, -4.0f), hi(5.0f, 6.0f, 7.0f), p(1.0f, 1.0f, 1.0f), c(0.5f, -1.0f, 2.0f);
    const vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    const vec3 hits[6] = {{5, 1, 1}, {-2, 1, 1}, {1, 6, 1}, {1, -3, 1}, {1, 1, 7}, {1, 1, -4}};
    for (int a = 0; a < 6; ++a) {
        const vec3 hit = c + rk_reflect_correct_box(axes[a], p, c, lo, hi);
        EXPECT_EQ(hit.x, hits[a].x);
        EXPECT_EQ(hit.y, hits[a].y);
        EXPECT_EQ(hit.z, hits[a].z);
    }
}

TEST(EnvmapCorrection, GrazingAndAdversarialInputsStayFinite)
{
    // Grazing: R in the window plane (N·R = 0, ±0, tiny, slightly negative).
    const vec3 n(0.0f, 0.0f, 1.0f), cp(1.0f, 2.0f, 0.0f);
    for (float z : {0.0f, -0.0f, 1e-45f, 1e-30f, 1e-7f, -1e-7f, -1e-30f}) {
        const vec3 r = glm::normalize(vec3(1.0f, 0.3f, 0.0f)) + vec3(0.0f, 0.0f, z);
        EXPECT_TRUE(finite3(rk_reflect_correct_plane(r, cp, vec3(0.0f), n, 8.0f))) << z;
        EXPECT_TRUE(finite3(rk_reflect_correct_plane_cos(r, n, cp, 8.0f))) << z;
        EXPECT_TRUE(finite3(rk_reflect_correct_fahlen(r, n, cp))) << z;
        EXPECT_TRUE(finite3(rk_reflect_correct_box(r, cp, vec3(0.0f), vec3(-5.0f), vec3(5.0f)))) << z;
        // Exactly grazing: the exact plane correction tends to R (hit at infinity).
        if (z <= 0.0f) {
            EXPECT_LT(sin_between(dd(rk_reflect_correct_plane(r, cp, vec3(0.0f), n, 8.0f)), dd(r)), 1e-6) << z;
        }
    }
    EXPECT_TRUE(finite3(rk_reflect_correct_plane(vec3(0.0f), vec3(0.0f), vec3(0.0f), vec3(0.0f), 0.0f)));
    long checked = 0;
    for (float a : kAdversarial) {
        for (float b : kAdversarial) {
            for (float c : kAdversarial) {
                const vec3 v(a, b, c), w(c, a, b), x(b, c, a);
                ASSERT_TRUE(std::isfinite(rk_envmap_sigmoid(a, b, c)));
                ASSERT_TRUE(std::isfinite(rk_envmap_fahlen_weight(a, b, c)));
                ASSERT_TRUE(std::isfinite(rk_envmap_angle(a)));
                ASSERT_TRUE(finite3(rk_envmap_normalize(v, vec3(0.0f))));
                ASSERT_TRUE(finite3(rk_reflect_correct_sphere(v, w, c))) << fmt(a, b, c);
                ASSERT_TRUE(finite3(rk_reflect_correct_plane_cos(v, w, x, a))) << fmt(a, b, c);
                ASSERT_TRUE(finite3(rk_reflect_correct_fahlen(v, w, x, b, c, a))) << fmt(a, b, c);
                ASSERT_TRUE(finite3(rk_reflect_correct_fahlen(v, w, x))) << fmt(a, b, c);
                ASSERT_TRUE(finite3(rk_reflect_correct_plane(v, w, x, v, a))) << fmt(a, b, c);
                ASSERT_TRUE(finite3(rk_reflect_correct_box(v, w, x, vec3(-a), vec3(b)))) << fmt(a, b, c);
                ASSERT_TRUE(finite3(rk_reflect_correct_box(v, w, x, v, w))) << fmt(a, b, c);
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 5000);
}

// ---------------------------------------------------------------------------------------------
// Window glass (window_glass.glsl)

TEST(WindowGlass, ReflectanceModels)
{
    // One pane, n = 1.52, per-polarisation slab (Fahlén 2005 Eq. 3.8 applied per polarisation).
    EXPECT_NEAR(rk_window_glass_reflectance_exact(1.0f, 1.52f, 1.0f), 0.0816820, 2e-7);
    EXPECT_NEAR(rk_window_glass_reflectance_exact(std::cos(60.0f * 3.14159265f / 180.0f), 1.52f, 1.0f), 0.15653, 1e-5);
    EXPECT_NEAR(rk_window_glass_reflectance_exact(std::cos(85.0f * 3.14159265f / 180.0f), 1.52f, 1.0f), 0.75435, 1e-5);
    EXPECT_NEAR(rk_window_glass_reflectance_exact(1.0f, 1.52f, 2.0f), 0.1510277, 2e-7);  // double glazing
    // The default build (RK_WINDOW_GLASS_FRESNEL 0, RK_FRESNEL_WINDOW_MODE 2) is rk_fresnel_window.
    ErrorStats fast1, fast2, order;
    const vec3 params = rk_fresnel_fast_params(1.52f);
    for (int i = 0; i <= 100000; ++i) {
        const float c = static_cast<float>(i) / 100000.0f;
        EXPECT_EQ(rk_window_glass_reflectance(c, 1.52f, 1.0f), rk_fresnel_window(c, 1.52f, 1.0f));
        fast1.add(rk_window_glass_reflectance_fast(c, params, 1.0f), rk_window_glass_reflectance_exact(c, 1.52f, 1.0f),
                  fmt("cos", c));
        fast2.add(rk_window_glass_reflectance_fast(c, params, 2.0f), rk_window_glass_reflectance_exact(c, 1.52f, 2.0f),
                  fmt("cos", c));
        // The part of the fast model's error that is the thesis's order (slab of the average).
        order.add(rk_fresnel_slab(rk_fresnel_dielectric(c, 1.52f)), rk_window_glass_reflectance_exact(c, 1.52f, 1.0f),
                  fmt("cos", c));
    }
    std::printf(
        "window glass fast vs exact, 1 pane: %s\n                            2 panes: %s\n"
        "thesis order (slab of the exact average) vs exact, 1 pane: %s\n",
        fast1.str().c_str(), fast2.str().c_str(), order.str().c_str());
    EXPECT_LT(fast1.max_abs, 0.0225);
    EXPECT_LT(fast2.max_abs, 0.0625);
    EXPECT_NEAR(order.max_abs, 0.0236, 5e-4);
}

TEST(WindowGlass, CombineAndShade)
{
    const vec3 refl(0.9f, 0.5f, 0.1f), inter(0.2f, 0.4f, 0.8f), tint(0.8f, 0.9f, 1.0f);
    // R = 0: interior through the tint; R = 1: the reflection.
    const vec3 a = rk_window_glass_combine(refl, inter, 0.0f, tint);
    EXPECT_FLOAT_EQ(a.x, 0.16f);
    EXPECT_FLOAT_EQ(a.z, 0.8f);
    const vec3 b = rk_window_glass_combine(refl, inter, 1.0f, tint);
    EXPECT_FLOAT_EQ(b.y, 0.5f);
    // Energy: untinted, equal radiance on both sides -> unchanged.
    for (int i = 0; i <= 100; ++i) {
        const float r = static_cast<float>(i) / 100.0f;
        const vec3 e = rk_window_glass_combine(vec3(0.7f), vec3(0.7f), r, vec3(1.0f));
        EXPECT_NEAR(e.x, 0.7, 1e-7);
    }
    // Shade = combine at the pane's reflectance for |N·V|, same from both sides.
    const vec3 nrm(0.0f, 0.0f, 1.0f);
    const vec3 v = glm::normalize(vec3(0.6f, 0.0f, 0.8f));
    const float c = 0.8f;
    const vec3 s = rk_window_glass_shade(nrm, v, refl, inter, tint, 1.52f, 1.0f);
    const vec3 want = rk_window_glass_combine(refl, inter, rk_fresnel_window(c, 1.52f, 1.0f), tint);
    EXPECT_NEAR(s.x, want.x, 1e-6);
    const vec3 back = rk_window_glass_shade(nrm, vec3(v.x, v.y, -v.z), refl, inter, tint, 1.52f, 1.0f);
    EXPECT_NEAR(back.y, s.y, 1e-7);
    EXPECT_NEAR(rk_window_glass_cos(nrm, v), 0.8, 1e-7);
}

namespace {
/// Float64 pane reflectance, per polarisation (the default build's model, RK_FRESNEL_WINDOW_MODE 2):
/// the complex-amplitude Fresnel of reference/fresnel_ref.hpp, then the slab 2R / (1 + R) of each
/// polarisation (thesis Eq. 3.8, which the thesis applies to the average instead), averaged.
double pane_ref(double c, double eta)
{
    const auto sp = ref::fresnel_sp(c, ref::cd(eta, 0.0));
    return 0.5 * (2.0 * sp.first / (1.0 + sp.first) + 2.0 * sp.second / (1.0 + sp.second));
}
}  // namespace

TEST(WindowGlass, AgainstFloat64)
{
    DirGen gen(23);
    std::mt19937 rng(24);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    // rk_window_glass_reflectance (default build) against the float64 pane, n = 1.52 and n in
    // [1.2, 2.4], cos over [0, 1].
    ErrorStats refl152, refl_any;
    for (int i = 0; i <= 100000; ++i) {
        const float c = static_cast<float>(i) / 100000.0f;
        refl152.add(rk_window_glass_reflectance(c, 1.52f, 1.0f), pane_ref(c, 1.52), fmt("cos", c));
        const float eta = 1.2f + 1.2f * u01(rng), c2 = u01(rng);
        refl_any.add(rk_window_glass_reflectance(c2, eta, 1.0f), pane_ref(c2, eta), fmt("cos", c2, "eta", eta));
    }
    // rk_window_glass_cos against float64 |N.V| of the same float unit vectors.
    ErrorStats cosv;
    for (int i = 0; i < 100000; ++i) {
        const vec3 n = gen(), v = gen();
        const float got = rk_window_glass_cos(n, v);
        const double want = std::abs(ddot(dd(n), dd(v)));
        cosv.add(got, want, fmt("N", n.x, n.y, n.z, "V", v.x, v.y, v.z));
    }
    // rk_window_glass_combine against float64 r refl + (1 - r) tint interior (HDR radiances up to
    // 1e4, every term >= 0: no cancellation, so the relative error per channel is meaningful), and
    // rk_window_glass_shade against the whole chain in float64 (|N.V|, pane_ref, combine).
    ErrorStats comb, shade;
    for (int i = 0; i < 100000; ++i) {
        const vec3 refl = vec3(u01(rng), u01(rng), u01(rng)) * std::exp2(-10.0f + 23.0f * u01(rng));
        const vec3 inter = vec3(u01(rng), u01(rng), u01(rng)) * std::exp2(-10.0f + 23.0f * u01(rng));
        const vec3 tint(u01(rng), u01(rng), u01(rng));
        const float r = u01(rng);
        const vec3 got = rk_window_glass_combine(refl, inter, r, tint);
        for (int ch = 0; ch < 3; ++ch) {
            const double want = static_cast<double>(r) * refl[ch] +
                                (1.0 - static_cast<double>(r)) * static_cast<double>(tint[ch]) * inter[ch];
            comb.add(std::abs(got[ch] - want) / std::max(want, 1e-300), 0.0, fmt("ch", ch, "r", r),
                     rktest::ulp_error(got[ch], want));
        }
        const vec3 n = gen(), v = gen();
        const vec3 sh = rk_window_glass_shade(n, v, refl, inter, tint, 1.52f, 1.0f);
        const double rr = pane_ref(std::abs(ddot(dd(n), dd(v))), 1.52);
        for (int ch = 0; ch < 3; ++ch) {
            const double want = rr * refl[ch] + (1.0 - rr) * static_cast<double>(tint[ch]) * inter[ch];
            // Relative to refl + tint interior, the largest the output can be: near grazing 1 - R is
            // small and its relative error large (the float N.V's rounding of 1e-7 alone is 0.1% of
            // 1 - R at N.V = 1e-4), but its absolute error stays that of R.
            const double bound = static_cast<double>(refl[ch]) + static_cast<double>(tint[ch]) * inter[ch];
            shade.add(std::abs(sh[ch] - want) / std::max(bound, 1e-300), 0.0,
                      fmt("ch", ch, "N.V", glm::dot(n, v), "refl", refl[ch], "inter", inter[ch], "tint", tint[ch]));
        }
    }
    std::printf(
        "window glass vs float64:\n  reflectance, n = 1.52, abs: %s\n  reflectance, n in [1.2, 2.4], abs: %s\n"
        "  cos |N.V|, abs: %s\n  combine, relative: %s\n  shade (n = 1.52), |err| / (refl + tint interior): %s\n",
        refl152.str().c_str(), refl_any.str().c_str(), cosv.str().c_str(), comb.str().c_str(), shade.str().c_str());
    EXPECT_LT(refl152.max_abs, 1e-6) << refl152.worst;
    EXPECT_LT(refl_any.max_abs, 1e-6) << refl_any.worst;
    EXPECT_LT(cosv.max_abs, 2e-7) << cosv.worst;
    EXPECT_LT(comb.max_ulp, 4.0) << comb.worst_ulp;
    EXPECT_LT(shade.max_abs, 1e-6) << shade.worst;
}

TEST(WindowGlass, AbsorbingSlabMatchesSeries)
{
    for (float r : {0.0f, 0.04258f, 0.2f, 0.6f, 0.95f}) {
        for (float tau : {1.0f, 0.9f, 0.5f, 0.0f}) {
            // Series: R + T^2 tau^2 R (1 + (R tau)^2 + ...), transmission T^2 tau (1 + (R tau)^2 + ...).
            double rs = r, ts = 0, term = static_cast<double>(tau);
            const double t2 = (1.0 - r) * (1.0 - r);
            for (int k = 0; k < 400; ++k) {
                ts += t2 * term;
                rs += t2 * term * tau * r;
                term *= static_cast<double>(r) * r * tau * tau;
            }
            vec3 refl(0.0f), trans(0.0f);
            rk_window_glass_slab_absorbing(vec2(r), vec3(tau), refl, trans);
            EXPECT_NEAR(refl.x, rs, 2e-7) << r << " " << tau;
            EXPECT_NEAR(trans.x, ts, 2e-7) << r << " " << tau;
            if (tau == 1.0f) {  // the slab of fresnel.glsl
                EXPECT_NEAR(refl.x, rk_fresnel_slab(r), 2e-7);
                EXPECT_NEAR(trans.x, 1.0 - rk_fresnel_slab(r), 2e-7);
            }
        }
    }
    vec3 refl(0.0f), trans(0.0f);
    rk_window_glass_slab_absorbing(vec2(1.0f), vec3(1.0f), refl, trans);
    EXPECT_EQ(refl.x, 1.0f);
    EXPECT_EQ(trans.x, 0.0f);
}

TEST(WindowGlass, AdversarialInputsStayFinite)
{
    for (float a : kAdversarial) {
        for (float b : kAdversarial) {
            for (float c : kAdversarial) {
                const vec3 v(a, b, c), w(c, a, b);
                ASSERT_TRUE(std::isfinite(rk_window_glass_cos(v, w)));
                ASSERT_TRUE(std::isfinite(rk_window_glass_reflectance(a, b, c)));
                ASSERT_TRUE(std::isfinite(rk_window_glass_reflectance_exact(a, b, c)));
                ASSERT_TRUE(std::isfinite(rk_window_glass_reflectance_fast(a, rk_fresnel_fast_params(b), c)));
                ASSERT_TRUE(finite3(rk_window_glass_combine(v, w, a, vec3(b))));
                ASSERT_TRUE(finite3(rk_window_glass_shade(v, w, v, w, vec3(a), b, c)));
                vec3 r(0.0f), t(0.0f);
                rk_window_glass_slab_absorbing(vec2(a, b), v, r, t);
                ASSERT_TRUE(finite3(r) && finite3(t));
            }
        }
    }
}
