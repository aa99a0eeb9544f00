// CPU tests of raykit/paraboloid.hpp (the C++ build of shaders/raykit/paraboloid.glsl plus the CPU
// baking) against float64 formulas and values of the paraboloid maps of Fahlén, "Illumination for
// Real-Time Rendering of Large Architectural Environments" (2005), §3.2.3 (Eq. 3.9-3.12),
// and the accuracy-vs-budget comparison of issue 5 item 6 (dual paraboloid vs octahedral vs cube).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "raykit/paraboloid.hpp"
#include "test_util.hpp"

using namespace raykit;
using rktest::ErrorStats;
using rktest::fmt;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct D3 {
    double x, y, z;
};

D3 to_d(vec3 v) { return {v.x, v.y, v.z}; }
double dist(vec3 a, D3 b)
{
    const double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}
double angle_between(vec3 a, vec3 b)
{
    const D3 x = to_d(a), y = to_d(b);
    const double cx = x.y * y.z - x.z * y.y, cy = x.z * y.x - x.x * y.z, cz = x.x * y.y - x.y * y.x;
    return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), x.x * y.x + x.y * y.y + x.z * y.z);
}

/// Uniform random unit vectors (float, normalised in double).
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

float ramp(float x, float a, float b) { return glm::clamp((x - a) / (b - a), 0.0f, 1.0f); }

/// A synthetic environment in [0, 1]: sky gradient over a darker ground (y up) with a soft horizon,
/// a band-limited "facade" pattern and a sharp sun lobe: smooth and sharp content together.
vec3 city_env(vec3 d)
{
    const float y = glm::clamp(d.y, -1.0f, 1.0f);
    const float h = ramp(y, -0.04f, 0.04f);
    const vec3 sky = glm::mix(vec3(0.45f, 0.55f, 0.70f), vec3(0.20f, 0.35f, 0.65f), ramp(y, 0.0f, 1.0f));
    const vec3 ground(0.22f, 0.20f, 0.17f);
    const float phi = std::atan2(d.x, d.z), el = std::asin(y);
    const float facade = 0.5f + 0.5f * std::sin(12.0f * phi) * std::sin(8.0f * el);
    const vec3 base = glm::mix(ground, sky, h) * (0.75f + 0.25f * facade);
    const vec3 sun_dir = glm::normalize(vec3(0.3f, 0.5f, 0.8f));
    const float sun = 0.6f * std::exp(200.0f * (glm::dot(d, sun_dir) - 1.0f));
    return glm::clamp(base + vec3(sun), vec3(0.0f), vec3(1.0f));
}

vec3 identity_env(vec3 d) { return d; }

/// Error statistics of colour lookups: max abs over channels, MSE, PSNR for peak 1.
struct ColourError {
    double max_abs = 0, sse = 0;
    long n = 0;
    void add(vec3 got, vec3 want)
    {
        for (int c = 0; c < 3; ++c) {
            const double e = static_cast<double>(got[c]) - want[c];
            max_abs = std::max(max_abs, std::abs(e));
            sse += e * e;
            ++n;
        }
    }
    double psnr() const { return n ? 10.0 * std::log10(1.0 / std::max(sse / static_cast<double>(n), 1e-30)) : 0.0; }
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// Encode / decode

TEST(Paraboloid, RoundTripBelow1e6BothConventions)
{
    DirGen gen(11);
    for (float hemi : {1.0f, -1.0f}) {
        ErrorStats dir_rt, st_rt, enc;
        for (int i = 0; i < 100000; ++i) {
            vec3 d = gen();
            if (d.z * hemi < 0.0f) d.z = -d.z;  // into the hemisphere
            const vec2 st = rk_paraboloid_encode(d, hemi);
            const vec3 back = rk_paraboloid_decode(st, hemi);
            dir_rt.add(dist(back, to_d(d)), 0.0, fmt(d.x, d.y, d.z));
            // float64 reference of the encode (thesis Eq. 3.12 for hemi = -1)
            const double den = 1.0 + static_cast<double>(hemi) * d.z;
            enc.add(st.x, d.x / den, fmt(d.x, d.y, d.z));
            enc.add(st.y, d.y / den, fmt(d.x, d.y, d.z));
        }
        std::mt19937 rng(5);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        ErrorStats dec, nrm;
        for (int i = 0; i < 200000; ++i) {
            vec2 st(u(rng), u(rng));
            if (glm::dot(st, st) > 1.0f) continue;
            const vec3 d = rk_paraboloid_decode(st, hemi);
            const vec2 back = rk_paraboloid_encode(d, hemi);
            st_rt.add(std::hypot(back.x - st.x, back.y - st.y), 0.0, fmt(st.x, st.y));
            const double q = 1.0 + static_cast<double>(st.x) * st.x + static_cast<double>(st.y) * st.y;
            const double want[3] = {2.0 * st.x / q, 2.0 * st.y / q, hemi * (2.0 - q) / q};
            if (i % 8 != 0) continue;  // (ErrorStats formats every input: keep the test fast)
            for (int c = 0; c < 3; ++c) dec.add(d[c], want[c], fmt(st.x, st.y));
            const vec3 v(u(rng) * 1e3f, u(rng), u(rng) * 1e-3f);
            const vec3 nv = rk_paraboloid_normalize(v, vec3(0.0f));
            const double l = std::sqrt(static_cast<double>(v.x) * v.x + static_cast<double>(v.y) * v.y +
                                       static_cast<double>(v.z) * v.z);
            for (int c = 0; c < 3; ++c)
                nrm.add(nv[c], v[c] / l, fmt(v.x, v.y, v.z), rktest::ulp_error(nv[c], v[c] / l));
        }
        std::printf("          decode vs float64 %s\n          normalize vs float64 %s\n", dec.str().c_str(),
                    nrm.str().c_str());
        EXPECT_LT(dec.max_abs, 2.5e-7) << dec.str();
        EXPECT_LT(nrm.max_abs, 2e-7) << nrm.str();
        std::printf("hemi %+.0f: dir -> st -> dir %s\n          st -> dir -> st %s\n          encode vs float64 %s\n",
                    static_cast<double>(hemi), dir_rt.str().c_str(), st_rt.str().c_str(), enc.str().c_str());
        EXPECT_LE(dir_rt.max_abs, 1e-6) << dir_rt.str();
        EXPECT_LE(st_rt.max_abs, 1e-6) << st_rt.str();
        EXPECT_LE(enc.max_abs, 4e-7) << enc.str();
    }
}

TEST(Paraboloid, CentreRimAndThesisFormulas)
{
    for (float hemi : {1.0f, -1.0f}) {
        const vec2 c = rk_paraboloid_encode(vec3(0.0f, 0.0f, hemi), hemi);
        EXPECT_EQ(c.x, 0.0f);
        EXPECT_EQ(c.y, 0.0f);
        const vec3 d0 = rk_paraboloid_decode(vec2(0.0f), hemi);
        EXPECT_EQ(d0.z, hemi);
        for (int i = 0; i < 360; ++i) {
            const double a = 2.0 * kPi * i / 360.0;
            const vec3 eq(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f);
            const vec2 st = rk_paraboloid_encode(eq, hemi);
            EXPECT_NEAR(std::hypot(st.x, st.y), 1.0, 2e-7) << a;  // the rim is the equator
            const vec3 r =
                rk_paraboloid_decode(vec2(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a))), hemi);
            EXPECT_NEAR(r.z, 0.0, 1e-7);
            EXPECT_NEAR(r.x, std::cos(a), 2e-7);
            EXPECT_NEAR(r.y, std::sin(a), 2e-7);
        }
    }
    // The thesis's front side faces d0 = -z: Eq. 3.10 and 3.12 literally.
    const float s = 0.3f, t = -0.45f;
    const vec3 r = rk_paraboloid_decode(vec2(s, t), -1.0f);
    const double q = s * s + t * t + 1.0;
    EXPECT_NEAR(r.x, 2.0 * s / q, 1e-7);
    EXPECT_NEAR(r.y, 2.0 * t / q, 1e-7);
    EXPECT_NEAR(r.z, (-1.0 + s * s + t * t) / q, 1e-7);
    const vec2 st = rk_paraboloid_encode(r, -1.0f);
    EXPECT_NEAR(st.x, r.x / (1.0 - r.z), 1e-7);
    EXPECT_NEAR(st.y, r.y / (1.0 - r.z), 1e-7);
    // Beyond the rim: the continuation into the other hemisphere, |st| > 1; the antipode is finite.
    const vec2 beyond = rk_paraboloid_encode(vec3(1.0f, 0.0f, -0.1f), 1.0f);
    EXPECT_GT(beyond.x, 1.0f);
    const vec2 anti = rk_paraboloid_encode(vec3(0.0f, 0.0f, -1.0f), 1.0f);
    EXPECT_TRUE(std::isfinite(anti.x) && std::isfinite(anti.y));
    // Unnormalised input is normalised.
    const vec2 big = rk_paraboloid_encode(vec3(3e30f, 4e30f, 0.0f), 1.0f);
    EXPECT_NEAR(big.x, 0.6, 1e-7);
    EXPECT_NEAR(big.y, 0.8, 1e-7);
}

// Past the rim (the other hemisphere, read by the atlas guard band and the seam fade) st grows as
// 1 / (1 + hemi z), which cancels towards the antipode; the encode takes it as (x^2 + y^2) /
// (1 - hemi z) there, so st keeps its relative accuracy. Reference: float64 of the same float
// direction, st = (x, y) (|d| - hemi z) / (x^2 + y^2), checked against the direct (x, y) / (|d| +
// hemi z) where float64 does not cancel.
TEST(Paraboloid, EncodePastTheRimKeepsRelativeAccuracy)
{
    std::mt19937 rng(29);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (float hemi : {1.0f, -1.0f}) {
        ErrorStats rel;
        for (int i = 0; i < 400000; ++i) {
            // Distance r from the antipode's axis, log-uniform in [1e-13, 1]; any length.
            const double r = std::pow(10.0, -13.0 * u(rng));
            const double a = 2.0 * kPi * u(rng);
            const double scale = std::pow(2.0, 40.0 * u(rng) - 20.0);
            const vec3 d(static_cast<float>(scale * r * std::cos(a)), static_cast<float>(scale * r * std::sin(a)),
                         static_cast<float>(-hemi * scale * std::sqrt(std::max(0.0, 1.0 - r * r))));
            if (!(hemi * d.z < 0.0f)) continue;
            const vec2 st = rk_paraboloid_encode(d, hemi);
            const double x = d.x, y = d.y, z = d.z, h = hemi;
            const double len = std::sqrt(x * x + y * y + z * z), xy2 = x * x + y * y;
            const double k = (len - h * z) / xy2;
            if (r > 1e-3) {
                // The identity, where float64's own 1 + hemi z keeps at least 1e-10 relative.
                const double k_direct = 1.0 / (len + h * z);
                ASSERT_NEAR(k / k_direct, 1.0, 1e-9) << fmt(d.x, d.y, d.z);
            }
            const double mag = std::sqrt(xy2) * k;
            rel.add(std::hypot(st.x - x * k, st.y - y * k) / mag, 0.0, fmt(d.x, d.y, d.z));
        }
        std::printf("hemi %+.0f: encode past the rim vs float64, relative to |st| %s\n", static_cast<double>(hemi),
                    rel.str().c_str());
        EXPECT_LE(rel.max_abs, 6e-7) << rel.str();
    }
}

TEST(Paraboloid, SolidAngleDensity)
{
    EXPECT_FLOAT_EQ(rk_paraboloid_solid_angle_density(vec2(0.0f)), 4.0f);
    EXPECT_FLOAT_EQ(rk_paraboloid_solid_angle_density(vec2(1.0f, 0.0f)), 1.0f);
    EXPECT_FLOAT_EQ(rk_paraboloid_solid_angle_density(vec2(0.0f)) /
                        rk_paraboloid_solid_angle_density(vec2(std::sqrt(0.5f), std::sqrt(0.5f))),
                    4.0f);
    // Quadrature of the float function over the unit disk (polar midpoint rule): 2π.
    double integral = 0.0;
    const int nr = 4000, na = 64;
    for (int i = 0; i < nr; ++i) {
        const double r = (i + 0.5) / nr;
        for (int k = 0; k < na; ++k) {
            const double a = 2.0 * kPi * (k + 0.5) / na;
            const vec2 st(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)));
            integral += rk_paraboloid_solid_angle_density(st) * r * (1.0 / nr) * (2.0 * kPi / na);
        }
    }
    std::printf("integral of the density over the unit disk: %.9f (2 pi = %.9f)\n", integral, 2.0 * kPi);
    EXPECT_NEAR(integral, 2.0 * kPi, 1e-5);
    // The density is the Jacobian of the decode: |d(dir)/ds x d(dir)/dt| by central differences.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 200; ++i) {
        const double s = u(rng) * 0.7, t = u(rng) * 0.7, e = 1e-3;
        auto dec = [](double a, double b) {
            const double q = 1.0 + a * a + b * b;
            return D3{2 * a / q, 2 * b / q, (1 - a * a - b * b) / q};
        };
        const D3 ps = dec(s + e, t), ms = dec(s - e, t), pt = dec(s, t + e), mt = dec(s, t - e);
        const D3 ds{(ps.x - ms.x) / (2 * e), (ps.y - ms.y) / (2 * e), (ps.z - ms.z) / (2 * e)};
        const D3 dt{(pt.x - mt.x) / (2 * e), (pt.y - mt.y) / (2 * e), (pt.z - mt.z) / (2 * e)};
        const double cx = ds.y * dt.z - ds.z * dt.y, cy = ds.z * dt.x - ds.x * dt.z, cz = ds.x * dt.y - ds.y * dt.x;
        EXPECT_NEAR(rk_paraboloid_solid_angle_density(vec2(static_cast<float>(s), static_cast<float>(t))),
                    std::sqrt(cx * cx + cy * cy + cz * cz), 2e-5);
    }
    // Discrete: the atlas's texel solid angles inside the disk of one half add up to 2π.
    const int n = 512;
    const float g = rk_dual_paraboloid_guard_scale(static_cast<float>(n), 0.5f);
    double sum = 0.0;
    const double texel_area = std::pow(2.0 / (g * n), 2.0);
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const vec2 st((2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(n) - 1.0f) / g,
                          (2.0f * (static_cast<float>(j) + 0.5f) / static_cast<float>(n) - 1.0f) / g);
            sum += rk_paraboloid_sweet_circle(st) * rk_paraboloid_solid_angle_density(st) * texel_area;
        }
    }
    EXPECT_NEAR(sum, 2.0 * kPi, 2.0 * kPi * 2e-3);
}

TEST(Paraboloid, SweetCircleCoversPiOver4)
{
    const int n = 1024;
    long inside = 0;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const vec2 st(2.0f * (static_cast<float>(i) + 0.5f) / n - 1.0f,
                          2.0f * (static_cast<float>(j) + 0.5f) / n - 1.0f);
            inside += rk_paraboloid_sweet_circle(st) > 0.5f ? 1 : 0;
        }
    }
    EXPECT_NEAR(static_cast<double>(inside) / (n * n), kPi / 4.0, 2.0 / n);
    EXPECT_EQ(rk_paraboloid_sweet_circle(vec2(1.0f, 0.0f)), 1.0f);
    EXPECT_EQ(rk_paraboloid_sweet_circle(vec2(1.0001f, 0.0f)), 0.0f);
    const vec2 uv = rk_paraboloid_uv(vec2(1.0f, -1.0f), 1.0f);
    EXPECT_EQ(uv.x, 1.0f);
    EXPECT_EQ(uv.y, 0.0f);
}

TEST(Paraboloid, EncodeDifferentialMatchesFiniteDifferences)
{
    DirGen gen(17);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (float hemi : {1.0f, -1.0f}) {
        double worst = 0;
        for (int i = 0; i < 2000; ++i) {
            vec3 d = gen();
            if (d.z * hemi < 0.0f) d.z = -d.z;
            const double scale = std::exp2(u(rng) * 20.0);  // unnormalised v: the result is invariant
            const vec3 v = d * static_cast<float>(scale);
            const vec3 dv(static_cast<float>(u(rng) * scale), static_cast<float>(u(rng) * scale),
                          static_cast<float>(u(rng) * scale));
            const vec2 ds = rk_paraboloid_encode_differential(v, dv, hemi);
            auto enc = [&](double e) {
                const double x = v.x + e * dv.x, y = v.y + e * dv.y, z = v.z + e * dv.z;
                const double l = std::sqrt(x * x + y * y + z * z);
                return std::make_pair(x / (l + hemi * z), y / (l + hemi * z));
            };
            const double e = 1e-5;
            const auto p = enc(e), m = enc(-e);
            const double fx = (p.first - m.first) / (2 * e), fy = (p.second - m.second) / (2 * e);
            const double err = std::hypot(ds.x - fx, ds.y - fy) / std::max(1.0, std::hypot(fx, fy));
            worst = std::max(worst, err);
        }
        EXPECT_LT(worst, 2e-5) << hemi;
    }
    const vec2 z = rk_paraboloid_encode_differential(vec3(0.0f), vec3(1.0f), 1.0f);
    EXPECT_EQ(z.x, 0.0f);
}

// ---------------------------------------------------------------------------------------------
// Window frame (Eq. 3.11)

TEST(Paraboloid, WindowFrameMatchesEq311)
{
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> u(-kPi, kPi);
    double worst_angle = 0, worst_map = 0, worst_frame = 0;
    for (int i = 0; i < 10000; ++i) {
        const double phi = u(rng);
        const vec3 n(static_cast<float>(std::cos(phi)), 0.0f, static_cast<float>(std::sin(phi)));
        // Eq. 3.11 literally, in float64 on the float normal normalised in float64 (arccos is
        // ill-conditioned near ±1, so the float's non-unit length must not enter):
        // θ = ±arccos(N·d0), minus when (N x d0)_y > 0, d0 = (0, 0, -1).
        const double len = std::hypot(static_cast<double>(n.x), static_cast<double>(n.z));
        const double nx = n.x / len, nz = n.z / len;
        const double ndot = -nz;
        const double cross_y = nz * 0.0 - nx * -1.0;  // (N x d0)_y = Nz d0x - Nx d0z
        const double theta_ref = cross_y <= 0.0 ? std::acos(ndot) : -std::acos(ndot);
        const float theta = rk_paraboloid_frame_angle(n);
        double diff = std::abs(theta - theta_ref);
        diff = std::min(diff, std::abs(diff - 2.0 * kPi));
        worst_angle = std::max(worst_angle, diff);
        // R_y(θ) d0 = N
        const mat3 m = rk_paraboloid_frame_vertical(theta);
        const vec3 mapped = m * vec3(0.0f, 0.0f, -1.0f);
        worst_map = std::max(worst_map, dist(mapped, to_d(n)));
        // The general basis reproduces R_y(θ) for vertical windows, up = +y, hemi = -1.
        const mat3 g = rk_paraboloid_frame(n, vec3(0.0f, 1.0f, 0.0f), -1.0f);
        for (int c = 0; c < 3; ++c) worst_frame = std::max(worst_frame, dist(g[c], to_d(m[c])));
    }
    std::printf("frame: |atan2 form - Eq. 3.11| %.3g rad, |R_y(theta) d0 - N| %.3g, |basis - R_y| %.3g\n", worst_angle,
                worst_map, worst_frame);
    EXPECT_LT(worst_angle, 1e-6);
    EXPECT_LT(worst_map, 1e-6);
    EXPECT_LT(worst_frame, 1e-6);
    EXPECT_EQ(rk_paraboloid_frame_angle(vec3(0.0f, 1.0f, 0.0f)), 0.0f);  // horizontal window: no angle
    // Normals near +z with a tiny positive x: atan2(-tiny, -1) = -π + tiny, which float rounds to
    // below -π; the documented range (-π, π] holds (+π: the same rotation).
    for (float x : {1e-37f, 1e-30f, 1e-20f, 1e-10f, 1e-8f, 2e-8f, 1e-7f}) {
        for (float z : {1.0f, 0.5f, 1e-3f, 1e10f}) {
            const float a = rk_paraboloid_frame_angle(vec3(x * z, 0.0f, z));
            EXPECT_GT(a, -RK_PI) << x << " " << z;
            EXPECT_LE(a, RK_PI) << x << " " << z;
            EXPECT_GT(std::fabs(a), 3.14159f) << x << " " << z;  // near ±π (the same rotation), not near 0
        }
    }
}

TEST(Paraboloid, GeneralFrameIsOrthonormalAndMapsD0ToN)
{
    DirGen gen(21);
    for (int i = 0; i < 20000; ++i) {
        const vec3 n = i == 0 ? vec3(0.0f, 1.0f, 0.0f) : i == 1 ? vec3(0.0f, -1.0f, 0.0f) : gen();
        for (float hemi : {1.0f, -1.0f}) {
            const mat3 m = rk_paraboloid_frame(n, vec3(0.0f, 1.0f, 0.0f), hemi);
            const vec3 d0 = m * vec3(0.0f, 0.0f, hemi);
            ASSERT_LT(dist(d0, to_d(n)), 1e-6) << fmt(n.x, n.y, n.z);
            for (int a = 0; a < 3; ++a) {
                for (int b = 0; b < 3; ++b) ASSERT_NEAR(glm::dot(m[a], m[b]), a == b ? 1.0 : 0.0, 1e-6);
            }
            ASSERT_NEAR(glm::determinant(m), 1.0, 1e-6);  // right-handed
            // A direction round-trips through local coordinates.
            const vec3 w = gen();
            ASSERT_LT(dist(m * (w * m), to_d(w)), 1e-6);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Dual-paraboloid atlas and the guard band

TEST(DualParaboloid, GuardScaleValues)
{
    EXPECT_FLOAT_EQ(rk_dual_paraboloid_guard_scale(256.0f, rk_paraboloid_filter_footprint(0.0f)), 1.0f - 1.0f / 256.0f);
    EXPECT_FLOAT_EQ(rk_dual_paraboloid_guard_scale(256.0f, rk_paraboloid_filter_footprint(3.0f)), 0.96875f);
    EXPECT_FLOAT_EQ(rk_paraboloid_filter_footprint(2.5f), 4.0f);
    EXPECT_FLOAT_EQ(rk_dual_paraboloid_guard_scale(4.0f, 100.0f), RK_PARABOLOID_GUARD_MIN);
}

TEST(DualParaboloid, UvRoundTripAndHalves)
{
    DirGen gen(31);
    const float g = rk_dual_paraboloid_guard_scale(128.0f, 2.0f);
    ErrorStats rt;
    for (int i = 0; i < 100000; ++i) {
        const vec3 d = gen();
        const vec2 uv = rk_dual_paraboloid_uv(d, g);
        if (d.z >= 0.0f) {
            ASSERT_LT(uv.x, 0.5f);
        } else {
            ASSERT_GT(uv.x, 0.5f);
        }
        rt.add(dist(rk_dual_paraboloid_dir(uv, g), to_d(d)), 0.0, fmt(d.x, d.y, d.z));
    }
    std::printf("atlas uv -> dir round trip: %s\n", rt.str().c_str());
    EXPECT_LT(rt.max_abs, 2e-6);
    // -0 and +0 z both use the left half.
    EXPECT_LT(rk_dual_paraboloid_uv(vec3(1.0f, 0.0f, -0.0f), g).x, 0.5f);
    // Guard band texels hold the continuation of the projection: past the rim, other hemisphere.
    const vec3 guard = rk_dual_paraboloid_dir(vec2(0.2499f * (1.0f + 1.0f / g) + 0.0001f, 0.5f), g);
    EXPECT_LT(guard.z, 0.0f);
}

namespace {
/// Whether every bilinear tap of a lookup at uv, on every level up to ceil(max_lod), lies in the
/// half the lookup belongs to (no clamping needed either).
bool taps_inside_half(vec2 uv, bool left, int half_size, float max_lod)
{
    const int top = static_cast<int>(std::ceil(max_lod));
    for (int l = 0; l <= top; ++l) {
        const int h = half_size >> l;
        const double x = static_cast<double>(uv.x) * 2.0 * h - 0.5, y = static_cast<double>(uv.y) * h - 0.5;
        const long x0 = static_cast<long>(std::floor(x)), y0 = static_cast<long>(std::floor(y));
        const long lo = left ? 0 : h, hi = left ? h - 1 : 2 * h - 1;
        // A tap of zero weight (x exactly on a centre) may fall outside; it reads nothing.
        const bool xw = x - static_cast<double>(x0) > 0.0;
        const bool yw = y - static_cast<double>(y0) > 0.0;
        if (x0 < lo || (xw ? x0 + 1 : x0) > hi) return false;
        if (y0 < 0 || (yw ? y0 + 1 : y0) > h - 1) return false;
    }
    return true;
}
}  // namespace

TEST(DualParaboloid, GuardKeepsEveryTapInItsHalf)
{
    DirGen gen(41);
    std::vector<vec3> dirs;
    for (int i = 0; i < 20000; ++i) dirs.push_back(gen());
    for (int i = 0; i < 3600; ++i) {  // the seam itself, both signs of zero, and just off it
        const double a = 2.0 * kPi * i / 3600.0;
        const float c = static_cast<float>(std::cos(a)), s = static_cast<float>(std::sin(a));
        dirs.push_back(vec3(c, s, 0.0f));
        dirs.push_back(vec3(c, s, -0.0f));
        dirs.push_back(vec3(c, s, 1e-7f));
        dirs.push_back(vec3(c, s, -1e-7f));
    }
    for (int half : {16, 64, 256, 1024}) {
        for (float max_lod : {0.0f, 1.0f, 2.5f, 3.0f}) {
            const float g =
                rk_dual_paraboloid_guard_scale(static_cast<float>(half), rk_paraboloid_filter_footprint(max_lod));
            long bad = 0;
            for (const vec3& d : dirs)
                bad += taps_inside_half(rk_dual_paraboloid_uv(d, g), rk_dual_paraboloid_hemi(d) > 0.0f, half, max_lod)
                           ? 0
                           : 1;
            EXPECT_EQ(bad, 0) << "half " << half << " max_lod " << max_lod << " g " << g;
            // The guard is tight: the next larger scale (one more level-0 texel of radius) fails.
            const float g_loose = rk_dual_paraboloid_guard_scale(static_cast<float>(half),
                                                                 rk_paraboloid_filter_footprint(max_lod) - 0.25f);
            long bad_loose = 0;
            for (const vec3& d : dirs)
                bad_loose += taps_inside_half(rk_dual_paraboloid_uv(d, g_loose), rk_dual_paraboloid_hemi(d) > 0.0f,
                                              half, max_lod)
                                 ? 0
                                 : 1;
            EXPECT_GT(bad_loose, 0) << "half " << half << " max_lod " << max_lod;
        }
    }
    // Torque3D's 0.997 is right for one size only: too small a guard at 256 texels with mips.
    long bad_torque = 0;
    for (const vec3& d : dirs)
        bad_torque +=
            taps_inside_half(rk_dual_paraboloid_uv(d, 0.997f), rk_dual_paraboloid_hemi(d) > 0.0f, 256, 2.0f) ? 0 : 1;
    EXPECT_GT(bad_torque, 0);
}

// ---------------------------------------------------------------------------------------------
// The atlas layout, pinned independently of the code under test

namespace {
/// The unit direction stored at atlas coordinates (u, v), in float64, written from the layout the
/// header of shaders/raykit/paraboloid.glsl documents (not from rk_dual_paraboloid_dir):
///  - a 2H x H texture, left half (u < 0.5) the +z hemisphere (hemi = +1), right half -z;
///  - inside a half uv_half = 0.5 + 0.5 g st, u = uv_half.x / 2 (+ 0.5 for the right half),
///    v = uv_half.y (v = 0 the first row);
///  - st = (x, y) / (1 + hemi z) for the unit direction (x, y, z): the stereographic projection from
///    the pole -hemi z. Its inverse: with q = 1 + s^2 + t^2, (x, y) = 2 (s, t) / q and
///    hemi z = (1 - s^2 - t^2) / q (substitute: 1 + hemi z = 2 / q, so (x, y) = st (1 + hemi z)).
///  Points with |st| > 1 (the guard ring) continue the same formula into the other hemisphere.
D3 atlas_dir_ref(double u, double v, double g)
{
    const bool left = u < 0.5;
    const double hemi = left ? 1.0 : -1.0;
    const double uh = left ? 2.0 * u : 2.0 * u - 1.0;  // u within its half, [0, 1]
    const double s = (2.0 * uh - 1.0) / g, t = (2.0 * v - 1.0) / g;
    const double q = 1.0 + s * s + t * t;
    return {2.0 * s / q, 2.0 * t / q, hemi * (1.0 - s * s - t * t) / q};
}
double angle_between(vec3 a, D3 y)
{
    const D3 x = to_d(a);
    const double cx = x.y * y.z - x.z * y.y, cy = x.z * y.x - x.x * y.z, cz = x.x * y.y - x.y * y.x;
    return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), x.x * y.x + x.y * y.y + x.z * y.z);
}
}  // namespace

TEST(DualParaboloid, AtlasLayoutPinnedByHand)
{
    // Guard scale g = 0.9375 (H = 64, max_lod 2: footprint 0.5 * 2^2 = 2 texels, g = 1 - 2 * 2 / 64).
    // From the layout above, for the six axes (a direction with z = 0 uses the left half):
    //   +z: left, st = (0, 0) / (1 + 1) = (0, 0), uv_half = (0.5, 0.5), u = 0.5 / 2 = 0.25, v = 0.5
    //   -z: right, hemi = -1: st = (0, 0) / (1 + (-1)(-1)) = (0, 0), u = 0.5 + 0.25 = 0.75, v = 0.5
    //   +x: left, st = (1, 0) / (1 + 0) = (1, 0): uv_half.x = 0.5 + 0.5 g = 0.96875, u = 0.484375
    //   -x: left, st = (-1, 0): uv_half.x = 0.5 - 0.5 g = 0.03125, u = 0.015625, v = 0.5
    //   +y: left, st = (0, 1): u = 0.25, v = 0.5 + 0.5 g = 0.96875 (+y towards the last row)
    //   -y: left, st = (0, -1): u = 0.25, v = 0.03125
    // and in the right half, (1, 0, -1) / sqrt 2: st.x = (1 / sqrt 2) / (1 + 1 / sqrt 2) = sqrt 2 - 1
    // = 0.41421356, uv_half.x = 0.5 + 0.5 g (sqrt 2 - 1) = 0.69416261, u = 0.5 + 0.34708130 =
    // 0.84708130: s grows with x in both halves (the +z half is the mirrored one, seen from inside).
    // (0, 1, -1) / sqrt 2 likewise: u = 0.75, v = 0.69416261.
    const float g = rk_dual_paraboloid_guard_scale(64.0f, rk_paraboloid_filter_footprint(2.0f));
    ASSERT_EQ(g, 0.9375f);
    const float r2 = 0.70710678f;
    struct Pin {
        vec3 dir;
        double u, v;
    };
    const Pin pins[] = {{{0.0f, 0.0f, 1.0f}, 0.25, 0.5},        {{0.0f, 0.0f, -1.0f}, 0.75, 0.5},
                        {{1.0f, 0.0f, 0.0f}, 0.484375, 0.5},    {{-1.0f, 0.0f, 0.0f}, 0.015625, 0.5},
                        {{0.0f, 1.0f, 0.0f}, 0.25, 0.96875},    {{0.0f, -1.0f, 0.0f}, 0.25, 0.03125},
                        {{r2, 0.0f, -r2}, 0.84708130, 0.5},     {{0.0f, r2, -r2}, 0.75, 0.69416261}};
    for (const Pin& p : pins) {
        const vec2 uv = rk_dual_paraboloid_uv(p.dir, g);
        EXPECT_NEAR(uv.x, p.u, 1e-7) << fmt(p.dir.x, p.dir.y, p.dir.z);
        EXPECT_NEAR(uv.y, p.v, 1e-7) << fmt(p.dir.x, p.dir.y, p.dir.z);
        // The float64 layout agrees with the pins, and so does the inverse under test.
        EXPECT_LT(angle_between(p.dir, atlas_dir_ref(p.u, p.v, 0.9375)), 1e-7) << fmt(p.dir.x, p.dir.y, p.dir.z);
        const vec3 back = rk_dual_paraboloid_dir(vec2(static_cast<float>(p.u), static_cast<float>(p.v)), g);
        EXPECT_LT(angle_between(back, to_d(p.dir)), 1e-6) << fmt(p.dir.x, p.dir.y, p.dir.z);
    }
    // A guard-band texel: texel (0, 32) of the 128 x 64 atlas, uv = (0.5 / 128, 32.5 / 64): left half,
    // u_half = 1 / 128, s = (2 / 128 - 1) / g = -1.05 = -21/20, t = (65 / 64 - 1) / g = 1/60. q = 1 +
    // 441/400 + 1/3600 = 757/360, so dir = (-756, 12, -37) / 757 (756^2 + 12^2 + 37^2 = 757^2): past
    // the rim, z < 0, stored in the +z half (the continuation).
    const D3 guard{-756.0 / 757.0, 12.0 / 757.0, -37.0 / 757.0};
    EXPECT_LT(angle_between(rk_dual_paraboloid_dir(vec2(0.5f / 128.0f, 32.5f / 64.0f), g), guard), 1e-6);
    EXPECT_LT(dist(rk_dual_paraboloid_dir(vec2(0.5f / 128.0f, 32.5f / 64.0f), g),
                   atlas_dir_ref(0.5 / 128, 32.5 / 64, 0.9375)),
              1e-6);
    // The seam: u just below 0.5 is the left half's right edge (st.x = 1 / g, past +x's rim, z < 0),
    // u just above 0.5 the right half's left edge (st.x = -1 / g, near -x). Not neighbours on the
    // sphere: only the guard keeps filters from mixing them.
    EXPECT_GT(rk_dual_paraboloid_dir(vec2(0.4999f, 0.5f), g).x, 0.99f);
    EXPECT_LT(rk_dual_paraboloid_dir(vec2(0.5001f, 0.5f), g).x, -0.99f);
}

// ---------------------------------------------------------------------------------------------
// Baking

TEST(Bake, SelfDirectionCubeConvertsToSelfDirectionParaboloid)
{
    // A cube map whose texels hold their own centre direction.
    const int f = 64;
    const EnvCubeMap cube = bake_cube_map(f, identity_env, 1);
    for (int face = 0; face < 6; ++face) {
        EXPECT_LT(dist(cube.faces[static_cast<size_t>(face)].texel(5, 9), to_d(cube_texel_direction(face, 5, 9, f))),
                  1e-6);
    }
    DualParaboloidBakeOptions o;
    o.half_size = 64;
    o.max_lod = 2.0f;
    const DualParaboloidMap map = bake_dual_paraboloid(cube, o);
    ASSERT_EQ(map.levels.size(), 3u);
    EXPECT_EQ(map.levels[0].width, 128);
    EXPECT_EQ(map.levels[2].width, 32);
    // Expected texel directions in float64 from the atlas layout documented in the header of
    // shaders/raykit/paraboloid.glsl (not from rk_dual_paraboloid_dir, which the baker uses).
    ASSERT_EQ(map.guard_scale, 0.9375f);  // 1 - 2 footprint / H, footprint 0.5 * 2^ceil(2) = 2 texels
    const double g = 0.9375;
    double worst = 0, worst_rel = 0;
    int worst_i = -1, worst_j = -1;
    for (int j = 0; j < map.levels[0].height; ++j) {
        for (int i = 0; i < map.levels[0].width; ++i) {
            const double u = (i + 0.5) / 128.0, v = (j + 0.5) / 64.0;
            const D3 want = atlas_dir_ref(u, v, g);
            const double err = angle_between(map.levels[0].texel(i, j), want);
            // One texel spans 2 / (g H) of st, one unit of st 2 / (1 + s^2 + t^2) rad at (s, t).
            const double uh = u < 0.5 ? 2.0 * u : 2.0 * u - 1.0;
            const double s = (2.0 * uh - 1.0) / g, t = (2.0 * v - 1.0) / g;
            const double texel = 4.0 / ((1.0 + s * s + t * t) * g * 64.0);
            worst = std::max(worst, err);
            if (err / texel > worst_rel) {
                worst_rel = err / texel;
                worst_i = i;
                worst_j = j;
            }
        }
    }
    std::printf(
        "self-direction cube (64) -> dual paraboloid (2 x 64^2) vs the float64 atlas layout: max angle error %.3g "
        "rad = %.3g texels (worst texel %d, %d)\n",
        worst, worst_rel, worst_i, worst_j);
    EXPECT_LT(worst_rel, 0.1);  // a tenth of a texel, guard band included (the box filter's bias)
    // The hand-derived positions of DualParaboloid.AtlasLayoutPinnedByHand hold those directions in
    // the baked map: +z at uv (0.25, 0.5), -z (0.75, 0.5), +x (0.484375, 0.5), -x (0.015625, 0.5),
    // +y (0.25, 0.96875), -y (0.25, 0.03125) (bilinear between the four nearest texels), and the
    // guard-band texel (0, 32) holds (-756, 12, -37) / 757. Within a tenth of the local texel angle
    // 4 / ((1 + |st|^2) g H): 0.0667 rad at the centre, 0.0333 on the rim, 0.0317 at |st| = 1.05.
    const struct {
        vec2 uv;
        D3 dir;
        double texel;
    } baked_pins[] = {{{0.25f, 0.5f}, {0, 0, 1}, 4.0 / (g * 64)},     {{0.75f, 0.5f}, {0, 0, -1}, 4.0 / (g * 64)},
                      {{0.484375f, 0.5f}, {1, 0, 0}, 2.0 / (g * 64)}, {{0.015625f, 0.5f}, {-1, 0, 0}, 2.0 / (g * 64)},
                      {{0.25f, 0.96875f}, {0, 1, 0}, 2.0 / (g * 64)}, {{0.25f, 0.03125f}, {0, -1, 0}, 2.0 / (g * 64)}};
    for (const auto& p : baked_pins) {
        EXPECT_LT(angle_between(sample_image_bilinear(map.levels[0], p.uv), p.dir), 0.1 * p.texel)
            << fmt(p.uv.x, p.uv.y);
    }
    EXPECT_LT(angle_between(map.levels[0].texel(0, 32), D3{-756.0 / 757.0, 12.0 / 757.0, -37.0 / 757.0}),
              0.1 * 4.0 / ((757.0 / 360.0) * g * 64));
    EnvImage mip1 = downsample_box(map.levels[0]);
    EXPECT_EQ(mip1.rgb, map.levels[1].rgb);
    // And back: paraboloid -> cube, texels decode to their own direction.
    const EnvCubeMap back = cube_from_dual_paraboloid(map, 32, 2);
    double worst_back = 0;
    for (int face = 0; face < 6; ++face) {
        for (int j = 0; j < 32; ++j) {
            for (int i = 0; i < 32; ++i) {
                worst_back = std::max(worst_back, angle_between(back.faces[static_cast<size_t>(face)].texel(i, j),
                                                                cube_texel_direction(face, i, j, 32)));
            }
        }
    }
    std::printf("dual paraboloid -> cube (32): max angle error %.3g rad (cube texel %.3g rad)\n", worst_back,
                2.0 / 32.0);
    EXPECT_LT(worst_back, 0.05 * (2.0 / 32.0));
}

TEST(Bake, WindowFrameMapsAndSingleParaboloid)
{
    // The thesis's per-window map: a single paraboloid (d0 = -z) in the window's frame, whose centre
    // looks along the window normal; and a dual atlas baked in the same frame.
    const EnvCubeMap cube = bake_cube_map(48, identity_env, 1);
    const vec3 n = glm::normalize(vec3(0.6f, 0.0f, -0.8f));
    const mat3 frame = rk_paraboloid_frame(n, vec3(0.0f, 1.0f, 0.0f), -1.0f);
    const EnvImage single = bake_paraboloid(cube, 64, frame, -1.0f);
    DirGen gen(81);
    double worst = 0, worst_dual = 0;
    DualParaboloidBakeOptions o;
    o.half_size = 64;
    o.frame = frame;
    const DualParaboloidMap dual = bake_dual_paraboloid(cube, o);
    for (int i = 0; i < 20000; ++i) {
        vec3 w = gen();
        if (glm::dot(w, n) < 0.05f) w = glm::reflect(w, n);  // the half-space the window reflects
        if (glm::dot(w, n) < 0.05f) continue;
        const vec3 local = w * frame;  // world -> window frame
        worst = std::max(worst, angle_between(sample_paraboloid(single, local, -1.0f), w));
        worst_dual = std::max(worst_dual, angle_between(sample_dual_paraboloid(dual, local), w));
    }
    const vec3 centre = glm::mix(single.texel(31, 31), single.texel(32, 32), 0.5f);
    std::printf(
        "window-frame maps, self-direction content: single paraboloid max angle error %.3g rad, dual %.3g rad; "
        "centre %.3g rad from N\n",
        worst, worst_dual, angle_between(centre, n));
    EXPECT_LT(angle_between(centre, n), 0.01);
    EXPECT_LT(worst, 0.01);
    EXPECT_LT(worst_dual, 0.01);
}

TEST(Bake, MipsAreBoxFiltersAndNeverMixHalves)
{
    DualParaboloidBakeOptions o;
    o.half_size = 32;
    o.max_lod = 3.0f;
    o.supersample = 2;
    // Left half +1 everywhere (guard band included), right half -1: a mip texel that mixed the
    // halves would hold something else.
    EnvImage base(2 * o.half_size, o.half_size);
    for (int j = 0; j < base.height; ++j) {
        for (int i = 0; i < base.width; ++i) base.set(i, j, vec3(i < o.half_size ? 1.0f : -1.0f));
    }
    const std::vector<EnvImage> mips = generate_env_mips(base, 4);
    for (size_t l = 1; l < mips.size(); ++l) {
        const int h = o.half_size >> l;
        for (int j = 0; j < h; ++j) {
            for (int i = 0; i < 2 * h; ++i) ASSERT_EQ(mips[l].texel(i, j).x, i < h ? 1.0f : -1.0f);
        }
    }
    // Broken preconditions: an empty result and a Status naming the function, never a crash.
    Status st;
    EXPECT_EQ(downsample_box(EnvImage(3, 2), &st).width, 0);
    EXPECT_NE(st.message.find("downsample_box"), std::string::npos) << st.message;
    EXPECT_TRUE(generate_env_mips(EnvImage(12, 6), 3, &st).empty());  // 6x3 is odd
    EXPECT_NE(st.message.find("level 2"), std::string::npos) << st.message;
    EXPECT_TRUE(generate_env_mips(base, 0, &st).empty());
    EXPECT_EQ(generate_env_mips(base, 4, &st).size(), 4u);
    EXPECT_TRUE(st.ok());
    o.half_size = 36;  // not a multiple of 2^3
    EXPECT_EQ(bake_dual_paraboloid_fn(identity_env, o, &st).half_size, 0);
    EXPECT_NE(st.message.find("multiple"), std::string::npos) << st.message;
    o.half_size = 8;  // guard would eat the map
    EXPECT_TRUE(bake_dual_paraboloid_fn(identity_env, o, &st).levels.empty());
    EXPECT_NE(st.message.find("guard"), std::string::npos) << st.message;
    EXPECT_EQ(EnvImage(-3, 4).rgb.size(), 0u);  // a negative size is an empty image, not a huge allocation
    EXPECT_EQ(bake_cube_map(0, identity_env, 1, &st).size, 0);
    EXPECT_EQ(bake_cube_map(4, identity_env, 65, &st).size, 0);
    EXPECT_EQ(bake_paraboloid_fn(identity_env, 8, mat3(1.0f), 1.0f, 0.0f, 1, &st).width, 0);
    EXPECT_NE(st.message.find("guard_scale"), std::string::npos) << st.message;
    EXPECT_EQ(bake_octahedral_fn(1, identity_env, 1, &st).size, 0);
    // An empty or inconsistent cube is refused by everything that samples it.
    EnvCubeMap cube;
    EXPECT_TRUE(bake_dual_paraboloid(cube, DualParaboloidBakeOptions{}, &st).levels.empty());
    EXPECT_EQ(bake_paraboloid(cube, 8, mat3(1.0f), 1.0f, 1.0f, 0, &st).width, 0);
    EXPECT_EQ(bake_octahedral(cube, 8, 0, &st).size, 0);
    cube = bake_cube_map(4, identity_env, 1, &st);
    EXPECT_TRUE(st.ok());
    cube.faces[3] = EnvImage(2, 2);
    EXPECT_EQ(bake_octahedral(cube, 8, 0, &st).size, 0);
    EXPECT_NE(st.message.find("inconsistent"), std::string::npos) << st.message;
    EXPECT_EQ(cube_from_dual_paraboloid(DualParaboloidMap{}, 8, 2, &st).size, 0);
}

namespace {
/// The largest angle between lookups just above and just below the seam (z = +-1e-6) over n_phi
/// azimuths (the axes included: the largest jumps are there), and where it is.
struct SeamJump {
    double max = 0, phi = 0;
};
SeamJump seam_jump(const DualParaboloidMap& map, float lod, int n_phi)
{
    SeamJump r;
    for (int k = 0; k < n_phi; ++k) {
        const double phi = 2.0 * kPi * k / n_phi;
        const float c = static_cast<float>(std::cos(phi)), s = static_cast<float>(std::sin(phi));
        const double j = angle_between(sample_dual_paraboloid(map, vec3(c, s, 1e-6f), lod),
                                       sample_dual_paraboloid(map, vec3(c, s, -1e-6f), lod));
        if (j > r.max) {
            r.max = j;
            r.phi = phi;
        }
    }
    return r;
}
}  // namespace

// The seam cross-fade (DualParaboloidBakeOptions::seam_fade): with a band of 2 level-0 texels the
// lookup is continuous across z = 0 (the jump h^2 / 4 of the hard seam goes to float noise), the
// error inside the band stays at the size of the error beside it, and away from the band the
// faded atlas behaves as the plain one. Issue 13 item 6.
TEST(Bake, SeamFadeRemovesTheJump)
{
    const EnvCubeMap cube = bake_cube_map(96, identity_env, 1);
    DualParaboloidBakeOptions o;
    o.half_size = 64;
    o.max_lod = 2.0f;
    const DualParaboloidMap hard = bake_dual_paraboloid(cube, o);
    o.seam_fade = 2.0f;
    const DualParaboloidMap soft = bake_dual_paraboloid(cube, o);
    EXPECT_EQ(soft.guard_scale, 0.875f);  // 1 - 2 (2 + 2) / 64: the fade widens the guard
    const double r = 1.0 + 2.0 * 2.0 / (0.875 * 64.0);  // the guard's outer st radius used by the fade
    EXPECT_NEAR(soft.seam_band, (r * r - 1.0) / (r * r + 1.0), 1e-7);
    // The far edge of the band, read in the other half, lands exactly on that radius.
    const double band = soft.seam_band;
    EXPECT_NEAR(std::sqrt((1.0 + band) / (1.0 - band)), r, 1e-6);
    EXPECT_EQ(hard.seam_band, 0.0f);
    const int n_phi = 2048;
    for (float lod : {0.0f, 1.0f, 1.5f, 2.0f}) {
        const double jump_hard = seam_jump(hard, lod, n_phi).max, jump_soft = seam_jump(soft, lod, n_phi).max;
        double band_err = 0, beside_err = 0, step_max = 0;
        for (int k = 0; k < n_phi; ++k) {
            const double phi = 2.0 * kPi * k / n_phi;
            const float c = static_cast<float>(std::cos(phi)), s = static_cast<float>(std::sin(phi));
            auto dir = [&](double z) {
                const double q = std::sqrt(1.0 - z * z);
                return vec3(static_cast<float>(q * c), static_cast<float>(q * s), static_cast<float>(z));
            };
            // Along the meridian through the band: the error, and the largest change between
            // neighbouring samples 1/64 of the band apart (a jump would show as one big step).
            const double b = soft.seam_band;
            vec3 prev = sample_dual_paraboloid(soft, dir(-1.5 * b), lod), prev_d = dir(-1.5 * b);
            for (int i = 1; i <= 192; ++i) {
                const double z = -1.5 * b + 3.0 * b * i / 192.0;
                const vec3 d = dir(z);
                const vec3 got = sample_dual_paraboloid(soft, d, lod);
                const D3 want{d.x, d.y, d.z};
                const double e = angle_between(got, want);
                (std::fabs(z) < b ? band_err : beside_err) = std::max(std::fabs(z) < b ? band_err : beside_err, e);
                // The content is the direction itself: a step beyond the directions' own step is
                // a discontinuity.
                step_max = std::max(step_max, angle_between(got, D3{prev.x, prev.y, prev.z}) -
                                                  angle_between(d, D3{prev_d.x, prev_d.y, prev_d.z}));
                prev = got;
                prev_d = d;
            }
        }
        std::printf("seam fade, lod %.2f: jump hard %.3g -> faded %.3g rad; error in the band %.3g, beside it %.3g; "
                    "largest step along the meridian beyond the directions' own %.3g\n",
                    static_cast<double>(lod), jump_hard, jump_soft, band_err, beside_err, step_max);
        EXPECT_LT(jump_soft, 3e-6) << lod;  // continuous: the probes themselves are 2e-6 rad apart
        EXPECT_GT(jump_hard, 100 * jump_soft) << lod;
        EXPECT_LE(band_err, 1.25 * beside_err) << lod;  // the mix of two errors of opposite sign
        EXPECT_LT(step_max, 0.5 * jump_hard) << lod;
    }
}

TEST(Bake, SeamIsContinuous)
{
    // Lookups of a dual-paraboloid map baked from a self-direction cube (error = the angle between
    // the lookup and the looked-up direction, float64), at each LOD the guard covers (whole and
    // trilinear). Issue 5 item 5: "the error next to the seam is no larger than elsewhere".
    //
    // A fair baseline is at the same paraboloid radius r = |st|: the error depends on r (a texel
    // spans 4 / ((1 + r^2) g H) rad, twice as much at the centre as on the rim), so the whole
    // sphere is an easy baseline. On a dual atlas every point of the rim is on the seam (r = 1 is
    // z = 0), so "the same radius away from the seam" is the nearest band one texel further in.
    // With h = 2^ceil(lod) 2 / (g H), the size in st of a texel of the (coarser) level read:
    //  - seam band: r in (1 - h, 1], both halves. These lookups read the rim texels, whose other
    //    half lies in the guard band: their content is the seam treatment's (the continuation of
    //    the projection); a wrong guard (too narrow, clamped or mirrored content) shows here;
    //  - rim band: r in (1 - 2h, 1 - h], both halves: the next texel inwards, read from texels
    //    inside the disk.
    // Requirement: seam max <= rim max * 1.02 and seam mean <= rim mean * 1.02. Expected ratio
    // below 1 (the bilinear error along a meridian is h^2 / 8 times |d lambda / dr| of the
    // projection's scale lambda = 2 / (1 + r^2): |lambda'| = 4 r / (1 + r^2)^2 is 1 at the rim and
    // grows inwards to 1.3 at r = 1 / sqrt 3); the 2 % margin covers the deterministic grid's
    // underestimate of a band's maximum: 16 radii per texel leave f (1 - f) at most 0.4 % below
    // its peak 1/4, 4096 azimuths are 1/20 of a level-0 rim texel apart.
    //
    // Across the seam, lookups at z = +1e-6 (the +z half) and z = -1e-6 (the -z half) differ: the
    // halves are mirror images (z -> -z), so their bilinear errors are too, and the component across
    // the seam doubles instead of cancelling. Along an st axis at the rim the direction's z has
    // second derivative +1 radially (d^2 z / dr^2 at r = 1) and -1 along the rim's tangent line, so
    // a lookup halfway between texels errs by h^2 / 8 towards one pole and the other half by as
    // much towards the other: the jump is at most h_l^2 / 4 (trilinear: the mix of the two levels'
    // values, (1 - f) h_l0^2 / 4 + f h_l1^2 / 4), second order in h. It is twice the error on
    // either side and exceeds the rim band's worst error (1.6 to 1.7 times, printed): inherent to
    // two independently interpolated halves (only a cross-fade of the halves over the filter
    // footprint of z = 0 would remove it), so it is bounded by that analytic value (5 % margin:
    // the O(h^4) remainder, 1.8 % at LOD 2 where h = 0.133, and the 96-texel source cube's own
    // interpolation error, 0.6 % at LOD 0), not by the band's error. The old bound, 0.05 rim
    // texel = 0.05 h rad, is 1.4 (LOD 2) to 5.7 (LOD 0) times looser.
    const EnvCubeMap cube = bake_cube_map(96, identity_env, 1);
    DualParaboloidBakeOptions o;
    o.half_size = 64;
    o.max_lod = 2.0f;
    const DualParaboloidMap map = bake_dual_paraboloid(cube, o);
    ASSERT_EQ(map.guard_scale, 0.9375f);  // 1 - 2 * (0.5 * 2^2) / 64
    const double g = 0.9375, texel_st = 2.0 / (g * 64.0);
    // The float64 direction at paraboloid radius r and azimuth phi of the half hemi (the layout's
    // decode: (2 st, hemi (1 - r^2)) / (1 + r^2)).
    auto dir_at = [](double r, double phi, double hemi) {
        const double q = 1.0 + r * r;
        return D3{2.0 * r * std::cos(phi) / q, 2.0 * r * std::sin(phi) / q, hemi * (1.0 - r * r) / q};
    };
    const int n_phi = 4096, n_r = 16;
    for (float lod : {0.0f, 1.0f, 1.5f, 2.0f}) {
        const double h = texel_st * std::exp2(std::ceil(lod));
        struct Band {
            double max = 0, sum = 0;
            long n = 0;
            std::string worst;
        } seam, rim;
        for (int side = 0; side < 2; ++side) {
            const double hemi = side == 0 ? 1.0 : -1.0;
            for (int k = 0; k < n_phi; ++k) {
                const double phi = 2.0 * kPi * (k + 0.5) / n_phi;
                for (int j = 0; j < 2 * n_r; ++j) {
                    const double r = 1.0 - h * (j + 0.5) / n_r;
                    const D3 w = dir_at(r, phi, hemi);
                    const vec3 d(static_cast<float>(w.x), static_cast<float>(w.y), static_cast<float>(w.z));
                    const double e = angle_between(sample_dual_paraboloid(map, d, lod), w);
                    Band& b = j < n_r ? seam : rim;
                    if (e > b.max) {
                        b.max = e;
                        b.worst = fmt("hemi", hemi, "r", r, "phi", phi);
                    }
                    b.sum += e;
                    ++b.n;
                }
            }
        }
        // The jump across the seam, on the rim circle.
        const double l0 = std::floor(lod), f = static_cast<double>(lod) - l0;
        const double h0 = texel_st * std::exp2(l0), h1 = 2.0 * h0;
        const double jump_ref = ((1.0 - f) * h0 * h0 + f * h1 * h1) / 4.0;
        const SeamJump sj = seam_jump(map, lod, n_phi);
        const double jump = sj.max, jump_phi = sj.phi;
        const double seam_mean = seam.sum / static_cast<double>(seam.n);
        const double rim_mean = rim.sum / static_cast<double>(rim.n);
        std::printf(
            "lod %.2f (texel h = %.4g in st and rad at the rim): angle error, seam band r in (1 - h, 1] max %.4g "
            "mean %.4g (worst %s); rim band r in (1 - 2h, 1 - h] max %.4g mean %.4g (worst %s); seam / rim: max "
            "%.3f, mean %.3f\n          jump across the seam %.4g at phi %.4f = %.4f of h^2 / 4 (%.4g), %.2f "
            "times the rim band's max\n",
            static_cast<double>(lod), h, seam.max, seam_mean, seam.worst.c_str(), rim.max, rim_mean,
            rim.worst.c_str(), seam.max / rim.max, seam_mean / rim_mean, jump, jump_phi, jump / jump_ref,
            jump_ref, jump / rim.max);
        EXPECT_LE(seam.max, rim.max * 1.02) << "lod " << lod << " seam worst " << seam.worst;
        EXPECT_LE(seam_mean, rim_mean * 1.02) << "lod " << lod;
        EXPECT_LE(jump, jump_ref * 1.05) << "lod " << lod << " phi " << jump_phi;
    }
    // Without the guard (g = 1, the rim touching the half's edge) the seam leaks: the lookup at the
    // rim reads the other half's texels (Torque3D #2303's light leak).
    DualParaboloidMap plain = map;
    plain.guard_scale = 1.0f;
    plain.max_lod = 0.0f;
    EnvImage base(128, 64);  // texel-centre directions for g = 1 (what a g = 1 bake converges to)
    for (int j = 0; j < 64; ++j) {
        for (int i = 0; i < 128; ++i) {
            const vec2 uv((static_cast<float>(i) + 0.5f) / 128.0f, (static_cast<float>(j) + 0.5f) / 64.0f);
            base.set(i, j, rk_dual_paraboloid_dir(uv, 1.0f));
        }
    }
    plain.levels = {base};
    double leak = 0;
    for (int i = 0; i < 3600; ++i) {
        const double a = 2.0 * kPi * i / 3600.0;
        const vec3 d(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f);
        leak = std::max(leak, angle_between(sample_dual_paraboloid(plain, d, 0.0f), d));
    }
    std::printf("without the guard band (g = 1): max angle error on the seam %.3g rad\n", leak);
    EXPECT_GT(leak, 0.5);
}

namespace {
/// High-frequency test content, float64: R and G are 3-D checkers in direction space (parity of
/// floor(k x) + floor(k y) + floor(k z), cells 1/7 and 1/11 of a unit in each coordinate, about
/// 0.14 and 0.09 rad, i.e. 1.4 to 2.2 and 0.7 to 1.4 texels of the 2 x 32^2 atlas below), B a
/// smooth pattern.
double checker3(double x, double y, double z, double k)
{
    const long n = static_cast<long>(std::floor(k * x)) + static_cast<long>(std::floor(k * y)) +
                   static_cast<long>(std::floor(k * z));
    return (n & 1) != 0 ? 1.0 : 0.0;
}
D3 checker_env_ref(double x, double y, double z)
{
    return {checker3(x, y, z, 7.0), checker3(x, y, z, 11.0),
            0.5 + 0.5 * std::sin(9.0 * x) * std::sin(9.0 * y + 1.0) * std::cos(7.0 * z)};
}
}  // namespace

TEST(Bake, CubeToDualParaboloidTexelsAreSolidAngleMeans)
{
    // The cube -> dual paraboloid bake filters: every texel of level 0 (guard band included) against
    // the solid-angle-weighted mean of the source over the texel's footprint, integrated here in
    // float64 (48 x 48 midpoints per texel in st, each mapped to its direction by the layout's
    // decode and weighted by the solid-angle density).
    // The density, derived: the decode D(s, t) = (2 s, 2 t, hemi (1 - s^2 - t^2)) / q with
    // q = 1 + s^2 + t^2 has dD/ds = (2 (1 + t^2 - s^2), -4 s t, -4 hemi s) / q^2 and, symmetrically,
    // dD/dt = (-4 s t, 2 (1 + s^2 - t^2), -4 hemi t) / q^2: dD/ds . dD/dt = 0 and
    // |dD/ds|^2 = 4 ((1 + t^2 - s^2)^2 + 4 s^2 (1 + t^2)) / q^4 = 4 q^2 / q^4 (as (a - b)^2 + 4 a b =
    // (a + b)^2), so d(omega) = |dD/ds x dD/dt| ds dt = 4 / q^2 ds dt. (In uv the factor (2 / g)^2 is
    // constant and cancels in the mean.)
    // Source: a cube of 128 texels (2 x 2 supersampled) of checker_env_ref; atlas H = 32, LOD 0
    // (g = 0.96875; automatic supersampling, 16 x 16 bilinear cube lookups per texel). Error budget
    // (contrast 1): the baker's box filter is uniform in st, not in solid angle, which moves a 0/1
    // texel's mean by up to the total variation between the two weightings, h / 4 = 0.016 on the
    // rim (ln density falls by 2 h across a texel of h = 2 / (g H) = 0.0645 there; printed as
    // "|solid-angle - st-uniform mean|"); the cube's own resolution (bilinear reconstruction of 2 x 2
    // box texels blurs every edge over a cube texel, 1/4 of an atlas texel on the rim): about 0.04;
    // the 48^2-point reference: 0.007 (against 192^2). Bounds: max 0.1, RMS 0.02. Measured 0.05 and
    // 0.012; one sample per texel gives 0.6 and 0.22, 2 x 2 samples 0.31 and 0.06 (mutated copies
    // of paraboloid.hpp).
    const int cube_size = 128, half = 32, m = 48;
    const EnvCubeMap cube = bake_cube_map(
        cube_size,
        [](vec3 d) {
            const D3 c = checker_env_ref(d.x, d.y, d.z);
            return vec3(static_cast<float>(c.x), static_cast<float>(c.y), static_cast<float>(c.z));
        },
        2);
    DualParaboloidBakeOptions o;
    o.half_size = half;
    const DualParaboloidMap map = bake_dual_paraboloid(cube, o);
    ASSERT_EQ(map.guard_scale, 0.96875f);  // 1 - 2 * 0.5 / 32
    const double g = 0.96875;
    ErrorStats err;
    double sq = 0, weighting = 0;
    for (int j = 0; j < half; ++j) {
        for (int i = 0; i < 2 * half; ++i) {
            // Texel (i, j) covers u in [i, i + 1] / (2H), v in [j, j + 1] / H: in its half
            // (left +z for i < H) st = (2 uv_half - 1) / g.
            const double hemi = i < half ? 1.0 : -1.0;
            const int ih = i % half;
            const double s0 = (2.0 * ih / half - 1.0) / g, s1 = (2.0 * (ih + 1) / half - 1.0) / g;
            const double t0 = (2.0 * j / half - 1.0) / g, t1 = (2.0 * (j + 1) / half - 1.0) / g;
            double sa[3] = {0, 0, 0}, un[3] = {0, 0, 0}, wsum = 0;
            for (int b = 0; b < m; ++b) {
                for (int a = 0; a < m; ++a) {
                    const double s = s0 + (s1 - s0) * (a + 0.5) / m, t = t0 + (t1 - t0) * (b + 0.5) / m;
                    const double q = 1.0 + s * s + t * t, w = 4.0 / (q * q);
                    const D3 c = checker_env_ref(2.0 * s / q, 2.0 * t / q, hemi * (1.0 - s * s - t * t) / q);
                    const double cv[3] = {c.x, c.y, c.z};
                    for (int k = 0; k < 3; ++k) {
                        sa[k] += w * cv[k];
                        un[k] += cv[k];
                    }
                    wsum += w;
                }
            }
            const vec3 got = map.levels[0].texel(i, j);
            for (int k = 0; k < 3; ++k) {
                const double want = sa[k] / wsum;
                err.add(got[k], want,
                        fmt("texel", i, j, "channel", k, "st", 0.5 * (s0 + s1), 0.5 * (t0 + t1), "want", want));
                sq += (got[k] - want) * (got[k] - want);
                weighting = std::max(weighting, std::abs(want - un[k] / (m * m)));
            }
        }
    }
    const double rms = std::sqrt(sq / static_cast<double>(err.count));
    std::printf(
        "cube (%d, checkers) -> dual paraboloid (2 x %d^2) texels vs float64 solid-angle means over their "
        "footprints: %s, RMS %.4g; |solid-angle - st-uniform mean| up to %.4g\n",
        cube_size, half, err.str().c_str(), rms, weighting);
    EXPECT_LT(err.max_abs, 0.1) << err.worst;
    EXPECT_LT(rms, 0.02);
}

// ---------------------------------------------------------------------------------------------
// LOD selection and the Brabec projection

TEST(Paraboloid, LodSelection)
{
    EXPECT_EQ(rk_paraboloid_lod_from_incidence(1.0f, 4.0f), 0.0f);
    EXPECT_EQ(rk_paraboloid_lod_from_incidence(0.0f, 4.0f), 4.0f);
    float prev = -1.0f;
    for (int i = 100; i >= 0; --i) {  // grows monotonically with the angle of incidence
        const float l = rk_paraboloid_lod_from_incidence(static_cast<float>(i) / 100.0f, 3.0f);
        EXPECT_GE(l, prev);
        prev = l;
    }
    // The texel angle matches the angle between the directions of neighbouring texel centres.
    const float g = 0.96875f;
    const int half = 256;
    for (float r : {0.0f, 0.5f, 0.9f}) {
        const vec3 a = rk_paraboloid_decode(vec2(r, 0.0f), 1.0f);
        const vec3 b = rk_paraboloid_decode(vec2(r + 2.0f / (g * half), 0.0f), 1.0f);
        EXPECT_NEAR(angle_between(a, b) / rk_paraboloid_texel_angle(vec2(r + 1.0f / (g * half), 0.0f), half, g), 1.0,
                    1e-3)
            << r;
    }
    const vec2 st(0.3f, 0.4f);
    const float ta = rk_paraboloid_texel_angle(st, 256.0f, g);
    EXPECT_NEAR(rk_paraboloid_lod_for_cone(st, ta, 256.0f, g, 8.0f), 0.0, 1e-5);
    EXPECT_NEAR(rk_paraboloid_lod_for_cone(st, 4.0f * ta, 256.0f, g, 8.0f), 2.0, 1e-5);
    EXPECT_EQ(rk_paraboloid_lod_for_cone(st, 1e6f * ta, 256.0f, g, 3.0f), 3.0f);
    EXPECT_EQ(rk_paraboloid_lod_for_cone(st, 0.0f, 256.0f, g, 3.0f), 0.0f);
}

TEST(Paraboloid, BrabecProjection)
{
    DirGen gen(61);
    const float g = 0.98f, zn = 0.5f, zf = 100.0f;
    for (int i = 0; i < 10000; ++i) {
        const float hemi = i % 2 ? 1.0f : -1.0f;
        vec3 d = gen();
        if (d.z * hemi < 0.0f) d.z = -d.z;
        const float r = 0.5f + 99.5f * static_cast<float>(i) / 10000.0f;
        const vec3 p = d * r;
        const vec4 c = rk_paraboloid_project(p, zn, zf, hemi, g);
        const vec2 st = rk_paraboloid_encode(d, hemi);
        ASSERT_NEAR(c.x, g * st.x, 1e-6);
        ASSERT_NEAR(c.y, g * st.y, 1e-6);
        ASSERT_NEAR(c.z, 2.0 * (r - zn) / (zf - zn) - 1.0, 2e-6);
        ASSERT_EQ(c.w, 1.0f);
        ASSERT_NEAR(rk_paraboloid_depth_decode(rk_paraboloid_depth_encode(r, zn, zf), zn, zf), r, 2e-5);
        ASSERT_GE(rk_paraboloid_clip_distance(p, hemi, g), 0.0f);
        ASSERT_LT(rk_paraboloid_clip_distance(vec3(p.x, p.y, -p.z) + vec3(0.0f, 0.0f, -hemi * r * 0.2f), hemi, g),
                  0.0f);
    }
    // The clip cone passes through the edge of the half: |st| = 1 / g.
    const vec3 edge = rk_paraboloid_decode(vec2(1.0f / g, 0.0f), 1.0f);
    EXPECT_NEAR(rk_paraboloid_clip_distance(edge * 10.0f, 1.0f, g), 0.0, 1e-5);
    EXPECT_NEAR(rk_paraboloid_clip_distance(vec3(1.0f, 0.0f, 0.0f), 1.0f, 1.0f), 0.0, 0.0);  // g = 1: the plane z = 0
    EXPECT_EQ(rk_paraboloid_project(vec3(0.0f), zn, zf, 1.0f, g).z, -2.0f);
}

TEST(Paraboloid, ProjectionAndDepthAgainstFloat64)
{
    // rk_paraboloid_project against float64 from Brabec's formulas written here: xy = g (x, y) /
    // (|p| + hemi z) (the paraboloid coordinates of p / |p|), z = 2 (|p| - near) / (far - near) - 1;
    // positions at 1e-3..1e4 from the centre in the half's hemisphere, near in [0.01, 1], far in
    // [near + 1, 1e4]. And rk_paraboloid_depth_decode against near + depth (far - near).
    DirGen gen(62);
    std::mt19937 rng(63);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    ErrorStats xy, zs, dec;
    for (int i = 0; i < 100000; ++i) {
        const float hemi = i % 2 ? 1.0f : -1.0f;
        vec3 d = gen();
        if (d.z * hemi < 0.0f) d.z = -d.z;
        const vec3 p = d * std::exp2(-10.0f + 23.3f * u01(rng));
        const float zn = 0.01f + 0.99f * u01(rng), zf = zn + 1.0f + 1e4f * u01(rng);
        const float g = 0.5f + 0.5f * u01(rng);
        const vec4 c = rk_paraboloid_project(p, zn, zf, hemi, g);
        const double L = std::sqrt(static_cast<double>(p.x) * p.x + static_cast<double>(p.y) * p.y +
                                   static_cast<double>(p.z) * p.z);
        const double den = L + static_cast<double>(hemi) * p.z;
        const std::string where = fmt("p", p.x, p.y, p.z, "hemi", hemi, "g", g, "near far", zn, zf);
        xy.add(std::hypot(c.x - static_cast<double>(g) * p.x / den, c.y - static_cast<double>(g) * p.y / den), 0.0,
               where);
        const double zw = 2.0 * (L - zn) / (static_cast<double>(zf) - zn) - 1.0;  // beyond far: > 1
        zs.add(std::abs(c.z - zw) / std::max(1.0, std::abs(zw)), 0.0, where);
        const float depth = -0.5f + 2.0f * u01(rng);
        const double want = zn + static_cast<double>(depth) * (static_cast<double>(zf) - zn);
        dec.add(std::abs(rk_paraboloid_depth_decode(depth, zn, zf) - want) / zf, 0.0, fmt("depth", depth, zn, zf));
    }
    std::printf(
        "Brabec projection vs float64: |xy error| %s\n                              |z error| / max(1, |z|) %s\n"
        "depth decode vs float64, |err| / far: %s\n",
        xy.str().c_str(), zs.str().c_str(), dec.str().c_str());
    EXPECT_LT(xy.max_abs, 3e-7) << xy.worst;
    EXPECT_LT(zs.max_abs, 4e-7) << zs.worst;
    EXPECT_LT(dec.max_abs, 2e-7) << dec.worst;
}

TEST(DualParaboloid, UvDifferentialAgainstComplexStep)
{
    // rk_dual_paraboloid_uv_differential against the float64 derivative of the documented atlas
    // coordinates u = (0.5 + 0.5 g s) / 2 (+ 0.5), v = 0.5 + 0.5 g t, st = (x, y) / (|w| + hemi z) of
    // w = dir, hemi by the sign of dir.z: the complex-step derivative Im f(w + i h dw) / h, exact to
    // float64 rounding (no subtraction, so no truncation/cancellation trade-off), with no Jacobian
    // written by hand. Random directions over the whole sphere at scales 2^-20..2^20.
    DirGen gen(64);
    std::mt19937 rng(65);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    using cd = std::complex<double>;
    ErrorStats rel, norm;
    for (int i = 0; i < 100000; ++i) {
        const vec3 d = gen();
        const double scale = std::exp2(u(rng) * 20.0);
        const vec3 w = d * static_cast<float>(scale);
        const vec3 dw(static_cast<float>(u(rng) * scale), static_cast<float>(u(rng) * scale),
                      static_cast<float>(u(rng) * scale));
        const float g = 0.5f + 0.5f * static_cast<float>(std::abs(u(rng)));
        const vec2 got = rk_dual_paraboloid_uv_differential(w, dw, g);
        const double hemi = w.z > 0.0f ? 1.0 : -1.0;
        const double h = 1e-40;
        const cd x(w.x, h * dw.x), y(w.y, h * dw.y), z(w.z, h * dw.z);
        const cd len = std::sqrt(x * x + y * y + z * z);
        const cd s = x / (len + hemi * z), t = y / (len + hemi * z);
        const double du = 0.25 * g * s.imag() / h, dv = 0.5 * g * t.imag() / h;
        const double err = std::hypot(got.x - du, got.y - dv);
        const std::string where = fmt("w", w.x, w.y, w.z, "dw", dw.x, dw.y, dw.z, "g", g);
        rel.add(err / std::max(std::hypot(du, dv), 1e-300), 0.0, where);
        // Relative to the largest the derivative can be for this |dw|: the stereographic projection
        // scales angles by (1 + s^2 + t^2) / 2 <= 1 in the hemisphere, so |d st| <= |dw| / |w|,
        // and |d uv| <= 0.5 g |d st|. The plain relative error above grows where dw is nearly
        // parallel to w (only its small perpendicular part moves the direction).
        const double wl = std::sqrt(static_cast<double>(glm::dot(w, w)));
        const double dl = std::sqrt(static_cast<double>(glm::dot(dw, dw)));
        norm.add(err / (0.5 * static_cast<double>(g) * dl / wl), 0.0, where);
        ASSERT_LE(std::hypot(du, dv), 0.5 * static_cast<double>(g) * dl / wl * (1.0 + 1e-12)) << where;
    }
    std::printf(
        "atlas uv differential vs float64 complex step: |err| / (0.5 g |dw| / |w|) %s\n"
        "                                               |err| / |d uv| %s\n",
        norm.str().c_str(), rel.str().c_str());
    EXPECT_LT(norm.max_abs, 1e-6) << norm.worst;
    // Relative to |d uv| the error has no bound (d_dir parallel to dir): a regression check on
    // these samples only.
    EXPECT_LT(rel.max_abs, 1e-4) << rel.worst;
}

namespace {
/// Float64 octahedral encoding of Cigolle et al. 2014 (their listing; signNotZero(0) = +1):
/// p = (x, y) / (|x| + |y| + |z|), and for z < 0 the folded ((1 - |p.y|) sgn p.x, (1 - |p.x|) sgn p.y).
std::pair<double, double> oct_encode_ref(D3 d)
{
    const double l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    double px = d.x / l1, py = d.y / l1;
    if (d.z < 0.0) {
        const double fx = (1.0 - std::abs(py)) * (px >= 0.0 ? 1.0 : -1.0);
        const double fy = (1.0 - std::abs(px)) * (py >= 0.0 ? 1.0 : -1.0);
        px = fx;
        py = fy;
    }
    return {px, py};
}
/// Its inverse: v = (p.x, p.y, 1 - |p.x| - |p.y|), unfolded for v.z < 0, normalised.
D3 oct_decode_ref(double px, double py)
{
    double x = px, y = py;
    const double z = 1.0 - std::abs(px) - std::abs(py);
    if (z < 0.0) {
        x = (1.0 - std::abs(py)) * (px >= 0.0 ? 1.0 : -1.0);
        y = (1.0 - std::abs(px)) * (py >= 0.0 ? 1.0 : -1.0);
    }
    const double l = std::sqrt(x * x + y * y + z * z);
    return {x / l, y / l, z / l};
}
/// A direction on a GL cube face (GL 4.6 table 8.19 inverted) at face coordinates sc, tc in [-1, 1].
D3 cube_dir_ref(int face, double sc, double tc)
{
    const D3 v = face == 0 ? D3{1, -tc, -sc}
                 : face == 1 ? D3{-1, -tc, sc}
                 : face == 2 ? D3{sc, 1, tc}
                 : face == 3 ? D3{sc, -1, -tc}
                 : face == 4 ? D3{sc, -tc, 1}
                             : D3{-sc, -tc, -1};
    const double l = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return {v.x / l, v.y / l, v.z / l};
}
}  // namespace

TEST(Octahedral, EncodeDecodeAgainstFloat64)
{
    DirGen gen(66);
    std::mt19937 rng(67);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    ErrorStats enc, dec, rt;
    for (int i = 0; i < 200000; ++i) {
        const vec3 d = gen();
        const vec2 p = octahedral_encode(d);
        const auto want = oct_encode_ref(to_d(d));
        enc.add(std::max(std::abs(p.x - want.first), std::abs(p.y - want.second)), 0.0, fmt(d.x, d.y, d.z));
        rt.add(angle_between(octahedral_decode(p), to_d(d)), 0.0, fmt(d.x, d.y, d.z));
        const vec2 q(u(rng), u(rng));
        dec.add(angle_between(octahedral_decode(q), oct_decode_ref(q.x, q.y)), 0.0, fmt(q.x, q.y));
    }
    std::printf(
        "octahedral vs float64: encode max |dp| %s\n                       decode angle %s\n"
        "                       dir -> p -> dir angle %s\n",
        enc.str().c_str(), dec.str().c_str(), rt.str().c_str());
    EXPECT_LT(enc.max_abs, 3e-7) << enc.worst;
    EXPECT_LT(dec.max_abs, 3e-7) << dec.worst;
    EXPECT_LT(rt.max_abs, 5e-7) << rt.worst;
    // Hand values: +z at the centre, -z at the corners (folded), +x at (1, 0), (1, 1, 0) / sqrt 2 at
    // (0.5, 0.5), (1, 1, -1) / sqrt 3: p = (1/3, 1/3) folds to (2/3, 2/3).
    EXPECT_EQ(octahedral_encode(vec3(0.0f, 0.0f, 1.0f)), vec2(0.0f, 0.0f));
    EXPECT_EQ(octahedral_encode(vec3(0.0f, 0.0f, -1.0f)), vec2(1.0f, 1.0f));
    EXPECT_EQ(octahedral_encode(vec3(1.0f, 0.0f, 0.0f)), vec2(1.0f, 0.0f));
    const vec2 h = octahedral_encode(vec3(1.0f, 1.0f, 0.0f));
    EXPECT_NEAR(h.x, 0.5, 1e-7);
    EXPECT_NEAR(h.y, 0.5, 1e-7);
    const vec2 f = octahedral_encode(vec3(1.0f, 1.0f, -1.0f));
    EXPECT_NEAR(f.x, 2.0 / 3.0, 1e-7);
    EXPECT_NEAR(f.y, 2.0 / 3.0, 1e-7);
    EXPECT_EQ(octahedral_encode(vec3(0.0f)), vec2(0.0f, 0.0f));  // zero: the +z pole
    // Outside [-1, 1]^2 decode clamps.
    EXPECT_LT(angle_between(octahedral_decode(vec2(5.0f, 0.0f)), D3{1, 0, 0}), 1e-7);
}

TEST(Bake, BilinearAgainstFloat64)
{
    // sample_image_bilinear against float64 bilinear interpolation written from GL's GL_LINEAR
    // (texel centres at (i + 0.5) / size, clamp to edge) on a random 128 x 64 image in [0, 1], uv in
    // [-0.1, 1.1]^2 (edges and beyond included). uv * size is exact for these power-of-two sizes;
    // for other sizes its rounding (an ulp of x) moves the weights by as much, times the local
    // texel difference.
    std::mt19937 rng(68);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f), uu(-0.1f, 1.1f);
    EnvImage img(128, 64);
    for (float& c : img.rgb) c = u01(rng);
    ErrorStats bil;
    for (int i = 0; i < 200000; ++i) {
        const vec2 uv(uu(rng), uu(rng));
        const vec3 got = sample_image_bilinear(img, uv);
        const double x = static_cast<double>(uv.x) * 128.0 - 0.5, y = static_cast<double>(uv.y) * 64.0 - 0.5;
        const double fx = std::floor(x), fy = std::floor(y), ax = x - fx, ay = y - fy;
        const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
        auto at = [&](int a, int b, int c) {
            return static_cast<double>(img.texel(std::clamp(a, 0, 127), std::clamp(b, 0, 63))[c]);
        };
        for (int c = 0; c < 3; ++c) {
            const double want = (1 - ay) * ((1 - ax) * at(x0, y0, c) + ax * at(x0 + 1, y0, c)) +
                                ay * ((1 - ax) * at(x0, y0 + 1, c) + ax * at(x0 + 1, y0 + 1, c));
            bil.add(got[c], want, fmt(uv.x, uv.y));
        }
    }
    std::printf("bilinear (128 x 64, values in [0, 1]) vs float64: %s\n", bil.str().c_str());
    EXPECT_LT(bil.max_abs, 1e-5) << bil.worst;
    // Texel centres return the texel exactly.
    EXPECT_EQ(sample_image_bilinear(img, vec2(10.5f / 128.0f, 20.5f / 64.0f)), img.texel(10, 20));
}

// The cube helpers select faces by shadow.glsl's rk_sh_cube_face_uv (one rule for shaders and CPU):
// the same face, sc = 2 s - 1 and tc = 2 t - 1, on random directions and on every kind of exact tie
// (edges and corners, both signs, +-0), where the rule takes x before y before z; at a tie the face
// coordinates still name the point of d (cube_face_direction of them is parallel to d). The zero
// vector selects +Z's centre, and an all-denormal vector the face of its direction.
TEST(Cube, FaceSelectionIsTheShadowRule)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    int ties = 0;
    auto check = [&](vec3 d) {
        float sc = 0.0f, tc = 0.0f;
        const int face = cube_face_select(d, sc, tc);
        const vec3 r = rk_sh_cube_face_uv(d);
        ASSERT_EQ(face, static_cast<int>(r.z)) << fmt(d.x, d.y, d.z);
        EXPECT_EQ(sc, 2.0f * r.x - 1.0f) << fmt(d.x, d.y, d.z);
        EXPECT_EQ(tc, 2.0f * r.y - 1.0f) << fmt(d.x, d.y, d.z);
        const glm::dvec3 back = glm::normalize(glm::dvec3(cube_face_direction(face, sc, tc)));
        EXPECT_LT(glm::length(back - glm::normalize(glm::dvec3(d))), 3e-7) << fmt(d.x, d.y, d.z);
    };
    for (int i = 0; i < 100000; ++i) check(vec3(u(rng), u(rng), u(rng)));
    for (int i = 0; i < 20000; ++i) {
        const float m = std::max(std::abs(u(rng)), 1e-3f), c = u(rng) * m;
        const float a = u(rng) < 0.0f ? -m : m, b = u(rng) < 0.0f ? -m : m, e = u(rng) < 0.0f ? -m : m;
        const vec3 edge_xy(a, b, c), edge_xz(a, c, b), edge_yz(c, a, b), corner(a, b, e);
        for (const vec3& d : {edge_xy, edge_xz, edge_yz, corner}) {
            check(d);
            ++ties;
        }
        // Which face: the first of the tied axes in x, y, z order.
        float sc = 0.0f, tc = 0.0f;
        EXPECT_EQ(cube_face_select(edge_xy, sc, tc), a < 0.0f ? 1 : 0);
        EXPECT_EQ(cube_face_select(edge_yz, sc, tc), a < 0.0f ? 3 : 2);
        EXPECT_EQ(cube_face_select(corner, sc, tc), a < 0.0f ? 1 : 0);
    }
    for (const vec3& d : {vec3(1.0f, -0.0f, 1.0f), vec3(-0.0f, 1.0f, -1.0f), vec3(0.0f, -0.0f, 1.0f)}) check(d);
    EXPECT_EQ(ties, 80000);
    float sc = 1.0f, tc = 1.0f;
    EXPECT_EQ(cube_face_select(vec3(0.0f), sc, tc), 4);
    EXPECT_EQ(sc, 0.0f);
    EXPECT_EQ(tc, 0.0f);
    const vec3 tiny(1e-40f, 3e-41f, -2e-40f);
    float sc2 = 0.0f, tc2 = 0.0f;
    EXPECT_EQ(cube_face_select(tiny, sc, tc), cube_face_select(tiny * 1e30f, sc2, tc2));
    EXPECT_NEAR(sc, sc2, 1e-6f);
    EXPECT_NEAR(tc, tc2, 1e-6f);
    EXPECT_EQ(cube_face_select(tiny, sc, tc), 5);
}

TEST(Bake, SelfDirectionMapsTexelsAndLookups)
{
    // Each baker with env(d) = d: with one sample per texel every texel holds the float64 direction
    // of its centre from the documented layout (the bakers' only error is float rounding); with
    // 4 x 4 supersampling the box filter's mean of unit vectors is slightly shorter and off-centre.
    // Then each lookup of such a map against the looked-up direction (bilinear interpolation of
    // unit vectors: a second-order error), max over random directions, in radians and in the map's
    // texels (the largest angle between neighbouring texel centres, see below).
    const int n = 64;
    double worst[6] = {0, 0, 0, 0, 0, 0};  // cube ss1, cube ss4, paraboloid ss1, ss4, octahedral ss1, ss4
    for (int ssi = 0; ssi < 2; ++ssi) {
        const int ss = ssi == 0 ? 1 : 4;
        const EnvCubeMap cube = bake_cube_map(n, identity_env, ss);
        const EnvImage para = bake_paraboloid_fn(identity_env, n, mat3(1.0f), -1.0f, 1.0f, ss);
        const OctahedralMap oct = bake_octahedral_fn(n, identity_env, ss);
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const double sc = 2.0 * (i + 0.5) / n - 1.0, tc = 2.0 * (j + 0.5) / n - 1.0;
                for (int face = 0; face < 6; ++face) {
                    worst[ssi] = std::max(worst[ssi], angle_between(cube.faces[static_cast<size_t>(face)].texel(i, j),
                                                                    cube_dir_ref(face, sc, tc)));
                }
                // Single paraboloid, hemi = -1, g = 1: st = 2 uv - 1, dir = (2s, 2t, -(1 - s^2 - t^2)) / q.
                const double q = 1.0 + sc * sc + tc * tc;
                const D3 pd{2 * sc / q, 2 * tc / q, -(1 - sc * sc - tc * tc) / q};
                worst[2 + ssi] = std::max(worst[2 + ssi], angle_between(para.texel(i, j), pd));
                worst[4 + ssi] = std::max(worst[4 + ssi], angle_between(oct.image.texel(i, j), oct_decode_ref(sc, tc)));
            }
        }
    }
    // The dual atlas from the function, one sample per texel: the float64 layout exactly.
    DualParaboloidBakeOptions o;
    o.half_size = n;
    o.supersample = 1;
    const DualParaboloidMap dual = bake_dual_paraboloid_fn(identity_env, o);
    double worst_dual = 0;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < 2 * n; ++i) {
            worst_dual = std::max(worst_dual, angle_between(dual.levels[0].texel(i, j),
                                                            atlas_dir_ref((i + 0.5) / (2.0 * n), (j + 0.5) / n,
                                                                          static_cast<double>(dual.guard_scale))));
        }
    }
    std::printf(
        "self-direction bakes (%d texels) vs float64 texel-centre directions, max angle (rad):\n"
        "  cube ss1 %.3g, ss4 %.3g; paraboloid ss1 %.3g, ss4 %.3g; octahedral ss1 %.3g, ss4 %.3g; "
        "dual atlas ss1 %.3g\n",
        n, worst[0], worst[1], worst[2], worst[3], worst[4], worst[5], worst_dual);
    EXPECT_LT(worst[0], 1e-6);
    EXPECT_LT(worst[2], 1e-6);
    EXPECT_LT(worst[4], 1e-6);
    EXPECT_LT(worst_dual, 1e-6);
    // The largest angle between neighbouring texel centres (float64), the maps' "texel" below:
    // 2 / n on a cube face (at its centre), 4 / n for the single paraboloid with g = 1 (at its
    // centre, 4 / ((1 + s^2 + t^2) g n)), 4 / (g H) for the atlas, and for the octahedral map
    // measured here (largest next to the folds).
    double t_oct = 0;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i + 1 < n; ++i) {
            const D3 a = oct_decode_ref(2.0 * (i + 0.5) / n - 1.0, 2.0 * (j + 0.5) / n - 1.0);
            const D3 b = oct_decode_ref(2.0 * (i + 1.5) / n - 1.0, 2.0 * (j + 0.5) / n - 1.0);
            const D3 c = oct_decode_ref(2.0 * (j + 0.5) / n - 1.0, 2.0 * (i + 0.5) / n - 1.0);
            const D3 e = oct_decode_ref(2.0 * (j + 0.5) / n - 1.0, 2.0 * (i + 1.5) / n - 1.0);
            t_oct = std::max({t_oct, std::acos(std::min(1.0, a.x * b.x + a.y * b.y + a.z * b.z)),
                              std::acos(std::min(1.0, c.x * e.x + c.y * e.y + c.z * e.z))});
        }
    }
    const double t_cube = 2.0 / n, t_para = 4.0 / n, t_dual = 4.0 / (static_cast<double>(dual.guard_scale) * n);
    std::printf("  in texels: cube ss4 %.3g, paraboloid ss4 %.3g, octahedral ss4 %.3g (octahedral texel %.3g rad)\n",
                worst[1] / t_cube, worst[3] / t_para, worst[5] / t_oct, t_oct);
    EXPECT_LT(worst[1] / t_cube, 0.002);  // the box filter's bias: small fractions of a texel
    EXPECT_LT(worst[3] / t_para, 0.0001);
    EXPECT_LT(worst[5] / t_oct, 0.1);  // texels straddling a fold, where the mapping has a kink

    // Lookups of the one-sample-per-texel maps.
    const EnvCubeMap cube = bake_cube_map(n, identity_env, 1);
    const EnvImage para = bake_paraboloid_fn(identity_env, n, mat3(1.0f), -1.0f, 1.0f, 1);
    const OctahedralMap oct = bake_octahedral_fn(n, identity_env, 1);
    DirGen gen(69);
    double e_cube = 0, e_para = 0, e_oct = 0, e_dual = 0;
    for (int i = 0; i < 200000; ++i) {
        const vec3 d = gen();
        e_cube = std::max(e_cube, angle_between(sample_cube_map(cube, d), to_d(d)));
        e_oct = std::max(e_oct, angle_between(sample_octahedral(oct, d), to_d(d)));
        e_dual = std::max(e_dual, angle_between(sample_dual_paraboloid(dual, d), to_d(d)));
        if (d.z < 0.0f) e_para = std::max(e_para, angle_between(sample_paraboloid(para, d, -1.0f), to_d(d)));
    }
    std::printf(
        "lookups of those maps (%d texels, ss1) vs the direction, max angle: cube %.3g rad (%.3g texels), "
        "single paraboloid %.3g (%.3g), dual atlas %.3g (%.3g), octahedral %.3g (%.3g)\n",
        n, e_cube, e_cube / t_cube, e_para, e_para / t_para, e_dual, e_dual / t_dual, e_oct, e_oct / t_oct);
    // Bilinear interpolation of a smooth map errs to second order (the atlas); first order where
    // the map has a kink or an edge: the octahedral folds, the cube's corners (the seamless fetch
    // takes the nearest texel of the next face), the single paraboloid's rim with g = 1 (the rim
    // touches the image edge: clamp to edge, half a rim texel, 1 / n rad).
    EXPECT_LT(e_cube / t_cube, 0.15);
    EXPECT_LT(e_para / t_para, 0.3);
    EXPECT_LT(e_dual / t_dual, 0.01);
    EXPECT_LT(e_oct / t_oct, 0.3);
}

// ---------------------------------------------------------------------------------------------
// Totality: every shared function, adversarial inputs, finite outputs.

TEST(Paraboloid, FiniteForEveryFiniteInput)
{
    const float adv[] = {0.0f,  -0.0f,  1e-45f, -1e-45f, 1e-40f,        1.17549435e-38f,
                         1.0f,  -1.0f,  0.5f,   2.0f,    1e-20f,        -1e-20f,
                         1e20f, -1e20f, 1e30f,  -1e30f,  3.4028235e38f, -3.4028235e38f};
    auto finite2 = [](vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); };
    auto finite3 = [](vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    long checked = 0;
    for (float a : adv) {
        for (float b : adv) {
            for (float c : adv) {
                const vec3 v(a, b, c);
                for (float h : {1.0f, -1.0f, 0.0f, -0.0f}) {
                    ASSERT_TRUE(finite2(rk_paraboloid_encode(v, h))) << fmt(a, b, c, h);
                    ASSERT_TRUE(finite3(rk_paraboloid_decode(vec2(a, b), h))) << fmt(a, b, h);
                    ASSERT_TRUE(finite2(rk_paraboloid_encode_differential(v, vec3(c, a, b), h))) << fmt(a, b, c, h);
                    const mat3 m = rk_paraboloid_frame(v, vec3(c, b, a), h);
                    ASSERT_TRUE(finite3(m[0]) && finite3(m[1]) && finite3(m[2])) << fmt(a, b, c, h);
                    ASSERT_TRUE(std::isfinite(rk_paraboloid_clip_distance(v, h, a)));
                    const vec4 p = rk_paraboloid_project(v, a, b, h, c);
                    ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << fmt(a, b, c, h);
                }
                ASSERT_TRUE(std::isfinite(rk_paraboloid_frame_angle(v)));
                ASSERT_TRUE(finite2(rk_dual_paraboloid_uv(v, a)));
                ASSERT_TRUE(finite2(rk_dual_paraboloid_uv_differential(v, vec3(b, c, a), c)));
                ASSERT_TRUE(finite3(rk_dual_paraboloid_dir(vec2(a, b), c)));
                ASSERT_TRUE(std::isfinite(rk_paraboloid_solid_angle_density(vec2(a, b))));
                ASSERT_TRUE(finite2(rk_paraboloid_uv(vec2(a, b), c)));
                ASSERT_TRUE(std::isfinite(rk_paraboloid_texel_angle(vec2(a, b), c, a)));
                ASSERT_TRUE(std::isfinite(rk_paraboloid_lod_for_cone(vec2(a, b), c, a, b, c)));
                ASSERT_TRUE(std::isfinite(rk_paraboloid_lod_from_incidence(a, b)));
                ASSERT_TRUE(std::isfinite(rk_dual_paraboloid_guard_scale(a, b)));
                ASSERT_TRUE(std::isfinite(rk_paraboloid_filter_footprint(a)));
                ASSERT_TRUE(std::isfinite(rk_paraboloid_depth_encode(a, b, c)));
                ASSERT_TRUE(std::isfinite(rk_paraboloid_depth_decode(a, b, c)));
                const mat3 mv = rk_paraboloid_frame_vertical(rk_paraboloid_frame_angle(v));
                ASSERT_TRUE(finite3(mv[0]) && finite3(mv[2]));
                const vec3 nrm = rk_paraboloid_normalize(v, vec3(0.0f, 0.0f, 1.0f));
                ASSERT_TRUE(finite3(nrm));
                ASSERT_NEAR(glm::length(nrm), 1.0, 1e-6) << fmt(a, b, c);
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 5000);
}

// ---------------------------------------------------------------------------------------------
// Issue 5 item 6: accuracy at equal texel budgets (dual paraboloid vs octahedral vs cube).

namespace {
struct Timed {
    ColourError err;
    double ns_per_lookup = 0;
};

template <class Lookup, class Truth>
Timed measure(const std::vector<vec3>& dirs, Lookup&& lookup, Truth&& truth)
{
    Timed t;
    std::vector<vec3> got(dirs.size());
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t i = 0; i < dirs.size(); ++i) got[i] = lookup(dirs[i]);
    const auto t1 = std::chrono::steady_clock::now();
    t.ns_per_lookup = std::chrono::duration<double, std::nano>(t1 - t0).count() / static_cast<double>(dirs.size());
    for (size_t i = 0; i < dirs.size(); ++i) t.err.add(got[i], truth(dirs[i]));
    return t;
}
}  // namespace

TEST(Accuracy, EqualTexelBudgetsDualParaboloidVsOctahedral)
{
    DirGen gen(71);
    std::vector<vec3> dirs(200000);
    for (vec3& d : dirs) d = gen();
    std::printf(
        "\n== Issue 5 item 6: lookups over %zu random directions, bilinear on the CPU, RGB in [0, 1], "
        "PSNR for peak 1 ==\n",
        dirs.size());
    for (int f : {64, 128}) {
        const int h = static_cast<int>(std::lround(f * std::sqrt(3.0)));  // 2 h^2 ~ 6 f^2
        const int m = static_cast<int>(std::lround(f * std::sqrt(6.0)));  // m^2 ~ 6 f^2
        const long cube_texels = 6L * f * f, dp_texels = 2L * h * h, oct_texels = 1L * m * m;
        const EnvCubeMap cube = bake_cube_map(f, city_env, 4);
        DualParaboloidBakeOptions o;
        o.half_size = h;
        const DualParaboloidMap dp = bake_dual_paraboloid(cube, o);
        const OctahedralMap oct = bake_octahedral(cube, m);
        auto cube_lookup = [&](vec3 d) { return sample_cube_map(cube, d); };
        auto dp_lookup = [&](vec3 d) { return sample_dual_paraboloid(dp, d); };
        auto oct_lookup = [&](vec3 d) { return sample_octahedral(oct, d); };
        const Timed tc = measure(dirs, cube_lookup, city_env);
        const Timed td = measure(dirs, dp_lookup, cube_lookup);
        const Timed to = measure(dirs, oct_lookup, cube_lookup);
        std::printf(
            "source cube %dx%dx6 (%ld texels); resampled at equal budget, error against the source cube's lookups:\n",
            f, f, cube_texels);
        std::printf("  %-34s texels %7ld  PSNR %6.2f dB  max abs %.4f  CPU %.1f ns/lookup\n",
                    fmt("dual paraboloid 2x", h, "x", h, "g", dp.guard_scale).c_str(), dp_texels, td.err.psnr(),
                    td.err.max_abs, td.ns_per_lookup);
        std::printf("  %-34s texels %7ld  PSNR %6.2f dB  max abs %.4f  CPU %.1f ns/lookup\n",
                    fmt("octahedral", m, "x", m).c_str(), oct_texels, to.err.psnr(), to.err.max_abs, to.ns_per_lookup);
        std::printf(
            "  %-34s texels %7ld  (cube vs the analytic scene: PSNR %.2f dB, max abs %.4f, CPU %.1f ns/lookup)\n",
            "cube (reference)", cube_texels, tc.err.psnr(), tc.err.max_abs, tc.ns_per_lookup);
        // Each baked straight from the analytic scene at the same budget: the parameterisations
        // themselves, against the scene.
        const DualParaboloidMap dp_a = bake_dual_paraboloid_fn(city_env, o);
        const OctahedralMap oct_a = bake_octahedral_fn(m, city_env, 4);
        const Timed tda = measure(
            dirs, [&](vec3 d) { return sample_dual_paraboloid(dp_a, d); }, city_env);
        const Timed toa = measure(
            dirs, [&](vec3 d) { return sample_octahedral(oct_a, d); }, city_env);
        std::printf("baked from the analytic scene (4x4 supersampled), error against the scene:\n");
        std::printf("  %-34s texels %7ld  PSNR %6.2f dB  max abs %.4f\n", "cube", cube_texels, tc.err.psnr(),
                    tc.err.max_abs);
        std::printf("  %-34s texels %7ld  PSNR %6.2f dB  max abs %.4f\n", "dual paraboloid", dp_texels, tda.err.psnr(),
                    tda.err.max_abs);
        std::printf("  %-34s texels %7ld  PSNR %6.2f dB  max abs %.4f\n", "octahedral", oct_texels, toa.err.psnr(),
                    toa.err.max_abs);
        // Sanity bounds (the numbers themselves go to docs/benchmarks.md).
        EXPECT_GT(td.err.psnr(), 30.0);
        EXPECT_GT(to.err.psnr(), 30.0);
        EXPECT_GT(tda.err.psnr(), 30.0);
        EXPECT_NEAR(static_cast<double>(dp_texels) / static_cast<double>(cube_texels), 1.0, 0.01);
        EXPECT_NEAR(static_cast<double>(oct_texels) / static_cast<double>(cube_texels), 1.0, 0.01);
    }
}
