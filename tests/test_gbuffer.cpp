// Tests of shaders/raykit/gbuffer.glsl (C++ build) and include/raykit/gbuffer.hpp against float64
// references written here (the octahedral, hemisphere and Lambert maps, round-to-nearest codes,
// correctly rounded halves, the depth maps of each convention), on random and adversarial inputs:
// poles, the octahedron's folds, the equator, ±0, denormals, unnormalised and huge vectors, NaN.
// The bounds asserted are the doc comments' (docs/deferred.md has the dense sweeps they come from).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "adversarial_checks.hpp"
#include "raykit/gbuffer.hpp"
#include "raykit/svo_hybrid.hpp"

using namespace raykit;
using glm::dvec2;
using glm::dvec3;
using rktest::adv::finite;
using rktest::adv::Floats;
using rktest::adv::S;
using rktest::adv::Vecs;

namespace {

// ---------------------------------------------------------------------------------------------
// float64 references

double angle(dvec3 a, dvec3 b)
{
    a = glm::normalize(a);
    b = glm::normalize(b);
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

dvec2 oct_encode_d(dvec3 n)
{
    const double l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    dvec2 p(n.x / l1, n.y / l1);
    if (n.z < 0.0) p = dvec2((1.0 - std::abs(p.y)) * (p.x >= 0.0 ? 1.0 : -1.0), (1.0 - std::abs(p.x)) * (p.y >= 0.0 ? 1.0 : -1.0));
    return p;
}

dvec3 oct_decode_d(dvec2 p)
{
    dvec3 v(p.x, p.y, 1.0 - std::abs(p.x) - std::abs(p.y));
    if (v.z < 0.0) v = dvec3((1.0 - std::abs(p.y)) * (p.x >= 0.0 ? 1.0 : -1.0), (1.0 - std::abs(p.x)) * (p.y >= 0.0 ? 1.0 : -1.0), v.z);
    return glm::normalize(v);
}

dvec3 lambert_decode_d(dvec2 p)
{
    const double r2 = p.x * p.x + p.y * p.y, g = 2.0 * std::sqrt(std::max(1.0 - r2, 0.0));
    return dvec3(p.x * g, p.y * g, 1.0 - 2.0 * r2);
}

/// Round half away from zero (what the SNORM conversion does), in double.
double round_away(double x) { return x >= 0.0 ? std::floor(x + 0.5) : -std::floor(-x + 0.5); }

/// The correctly rounded half of x (round to nearest even), saturated at 65504, NaN -> 0: the
/// documented result of rk_gb_half_bits, from float64 arithmetic only.
double half_round_d(float xf)
{
    if (std::isnan(xf)) return 0.0;
    const double x = xf, a = std::abs(x);
    if (a == 0.0) return x;
    int e;
    std::frexp(a, &e);                          // a in [2^(e-1), 2^e)
    const double ulp = std::ldexp(1.0, std::max(e - 1, -14) - 10);  // half ulp at that binade
    double q = std::nearbyint(a / ulp) * ulp;   // FE_TONEAREST: ties to even
    if (q > 65504.0) q = 65504.0;
    return x < 0.0 ? -q : q;
}

std::vector<dvec3> test_directions(int random, unsigned seed)
{
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::vector<dvec3> d;
    for (int i = 0; i < random; ++i) d.push_back(glm::normalize(dvec3(g(rng), g(rng), g(rng))));
    // Poles, axes, the octahedron's folds and edges, the equator, near -z (Lambert's rim).
    for (int i = 0; i < 4000; ++i) {
        const double t = 2.0 * 3.14159265358979323846 * i / 4000.0;
        d.push_back(dvec3(std::cos(t), std::sin(t), 0.0));
        d.push_back(glm::normalize(dvec3(std::cos(t), std::sin(t), 1e-3)));
        d.push_back(glm::normalize(dvec3(std::cos(t), std::sin(t), -1e-3)));
        d.push_back(glm::normalize(dvec3(1e-4 * std::cos(t), 1e-4 * std::sin(t), -1.0)));
        d.push_back(glm::normalize(dvec3(1e-4 * std::cos(t), 1e-4 * std::sin(t), 1.0)));
        d.push_back(glm::normalize(dvec3(std::cos(t), 0.0, std::sin(t))));
        d.push_back(glm::normalize(dvec3(0.0, std::cos(t), std::sin(t))));
    }
    for (int a = 0; a < 3; ++a)
        for (double s : {1.0, -1.0}) {
            dvec3 v(0.0);
            v[a] = s;
            d.push_back(v);
        }
    return d;
}

const std::vector<dvec3>& dirs()
{
    static const std::vector<dvec3> d = test_directions(200000, 11u);
    return d;
}

float ufloat(uint32_t b)
{
    float f;
    std::memcpy(&f, &b, 4);
    return f;
}

// ---------------------------------------------------------------------------------------------
// Unit vectors: float maps

TEST(GbufferOct, RoundTripAndMapAgainstFloat64)
{
    double max_rt = 0.0, max_p = 0.0, max_dec = 0.0;
    for (const dvec3& v : dirs()) {
        const vec3 f(v);
        const vec2 p = rk_gb_oct_encode(f);
        max_p = std::max(max_p, glm::length(dvec2(p) - oct_encode_d(dvec3(f))));
        max_rt = std::max(max_rt, angle(dvec3(rk_gb_oct_decode(p)), dvec3(f)));
        max_dec = std::max(max_dec, angle(dvec3(rk_gb_oct_decode(p)), oct_decode_d(dvec2(p))));
    }
    EXPECT_LE(max_rt, 3.5e-7) << "dir -> p -> dir";
    EXPECT_LE(max_p, 2.5e-7) << "encode vs the float64 map";
    EXPECT_LE(max_dec, 1.5e-7) << "decode vs the float64 map";
}

TEST(GbufferOct, EdgeCases)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(rk_gb_oct_encode(vec3(0.0f)), vec2(0.0f));
    EXPECT_EQ(rk_gb_oct_encode(vec3(nan, 1.0f, 0.0f)), vec2(0.0f));
    EXPECT_EQ(rk_gb_oct_encode(vec3(1e-40f, -1e-41f, 1e-45f)), vec2(0.0f)) << "all-denormal counts as zero";
    EXPECT_EQ(rk_gb_oct_decode(vec2(0.0f)), vec3(0.0f, 0.0f, 1.0f));
    // -z: the corner (+1, +1) (fold of x = y = 0 goes to the + side); every corner decodes to -z.
    EXPECT_EQ(rk_gb_oct_encode(vec3(0.0f, 0.0f, -1.0f)), vec2(1.0f, 1.0f));
    for (vec2 c : {vec2(1, 1), vec2(-1, 1), vec2(1, -1), vec2(-1, -1)}) EXPECT_EQ(rk_gb_oct_decode(c), vec3(0.0f, 0.0f, -1.0f));
    // z = -0 is not folded: (1, 0, -0) stays (1, 0).
    EXPECT_EQ(rk_gb_oct_encode(vec3(1.0f, 0.0f, -0.0f)), vec2(1.0f, 0.0f));
    // Unnormalised and extreme magnitudes encode the same point as the unit vector.
    const vec3 u = glm::normalize(vec3(0.3f, -0.5f, -0.8f));
    const vec2 pu = rk_gb_oct_encode(u);
    for (float s : {1e-30f, 1e-20f, 7.0f, 1e20f, 1e30f, 3e38f}) {
        const vec2 p = rk_gb_oct_encode(u * s);
        EXPECT_LE(glm::length(dvec2(p) - dvec2(pu)), 3e-7) << s;
    }
    EXPECT_EQ(rk_gb_oct_encode(vec3(3.4028235e38f, -3.4028235e38f, 3.4028235e38f)), rk_gb_oct_encode(vec3(1, -1, 1)));
    // Outside [-1, 1]^2 and NaN decode to unit vectors.
    for (vec2 p : {vec2(5.0f, -7.0f), vec2(nan, 0.25f), vec2(1e30f, -1e30f)}) {
        const vec3 r = rk_gb_oct_decode(p);
        EXPECT_NEAR(glm::length(dvec3(r)), 1.0, 1e-6) << S(p);
    }
}

TEST(GbufferHemisphere, UpperHalfRoundTripsAndLowerHalfMirrors)
{
    double max_up = 0.0, max_up_eq = 0.0;
    for (const dvec3& v : dirs()) {
        const vec3 f(v);
        const vec3 r = rk_gb_hemi_decode(rk_gb_hemi_encode(f));
        EXPECT_GE(r.z, 0.0f);
        const dvec3 fd(f);
        if (fd.z >= 0.0) {
            const double e = angle(dvec3(r), fd);
            (fd.z >= 0.05 ? max_up : max_up_eq) = std::max(fd.z >= 0.05 ? max_up : max_up_eq, e);
        } else {
            // The documented failure: z < 0 decodes as the mirror image (x, y, -z), 2 asin(|z|) away.
            const double e = angle(dvec3(r), fd), want = 2.0 * std::asin(std::min(-fd.z / glm::length(fd), 1.0));
            ASSERT_NEAR(e, want, 1e-3) << S(f);
            ASSERT_LE(angle(dvec3(r), dvec3(fd.x, fd.y, -fd.z)), 5e-4) << S(f);
        }
    }
    EXPECT_LE(max_up, 3e-6) << "z >= 0.05";
    EXPECT_LE(max_up_eq, 6e-4) << "z in [0, 0.05): sqrt of a rounding error";
}

TEST(GbufferLambert, RoundTripAgainstFloat64)
{
    double max_far = 0.0, max_near = 0.0, max_dec = 0.0;
    for (const dvec3& v : dirs()) {
        const vec3 f(v);
        const vec2 p = rk_gb_lambert_encode(f);
        ASSERT_LE(glm::length(dvec2(p)), 1.0 + 2e-7) << S(f);
        const double e = angle(dvec3(rk_gb_lambert_decode(p)), dvec3(f));
        (dvec3(f).z > -0.99 ? max_far : max_near) = std::max(dvec3(f).z > -0.99 ? max_far : max_near, e);
        max_dec = std::max(max_dec, angle(dvec3(rk_gb_lambert_decode(p)), lambert_decode_d(dvec2(p))));
    }
    EXPECT_LE(max_far, 7e-6) << "z > -0.99";
    EXPECT_LE(max_near, 1.5e-3) << "near -z: float cannot resolve |p| near the rim";
    EXPECT_LE(max_dec, 1.5e-3);
    EXPECT_EQ(rk_gb_lambert_encode(vec3(0.0f, 0.0f, -1.0f)), vec2(1.0f, 0.0f));
    EXPECT_EQ(rk_gb_lambert_decode(vec2(1.0f, 0.0f)), vec3(0.0f, 0.0f, -1.0f));
    EXPECT_EQ(rk_gb_lambert_encode(vec3(0.0f)), vec2(0.0f)) << "zero -> +z";
}

// ---------------------------------------------------------------------------------------------
// Quantisation

TEST(GbufferQuantise, SnormAndUnormCodesAreTheNearest)
{
    std::mt19937 rng(5u);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    for (uint32_t b : {2u, 5u, 8u, 10u, 12u, 16u}) {
        const double s = double((1u << (b - 1u)) - 1u), su = double((1u << b) - 1u);
        for (int i = 0; i < 20000; ++i) {
            const vec2 p(u(rng), u(rng));
            // The codes are the nearest to the float products the functions form (ties away from
            // zero for SNORM, up for UNORM), exactly: the reference rounds those floats in double.
            const uint32_t w = rk_gb_pack_snorm2(p, b), wu = rk_gb_pack_unorm2(p, b);
            const vec2 q = rk_gb_unpack_snorm2(w, b);
            for (int a = 0; a < 2; ++a) {
                const float c = std::clamp(p[a], -1.0f, 1.0f);
                const float xs = c * static_cast<float>(s);
                ASSERT_EQ(double(q[a]), double(float(round_away(double(xs)) / s))) << "snorm" << b << " " << S(p);
                const float xu = (c * 0.5f + 0.5f) * static_cast<float>(su);
                const double code = double((wu >> (uint32_t(a) * b)) & ((1u << b) - 1u));
                ASSERT_EQ(code, std::floor(double(xu) + 0.5)) << "unorm" << b << " " << S(p);
            }
        }
        // Every code decodes and re-encodes to itself (x field; y = x), the most negative SNORM
        // code to -1 (and back to the code of -1).
        for (uint32_t c = 0; c < (1u << b); ++c) {
            const uint32_t wc = c | (c << b);
            const uint32_t back = rk_gb_pack_snorm2(rk_gb_unpack_snorm2(wc, b), b);
            if (c == (1u << (b - 1u))) {
                EXPECT_EQ(rk_gb_unpack_snorm2(wc, b).x, -1.0f);
                continue;
            }
            ASSERT_EQ(back, wc) << "snorm" << b << " code " << c;
            ASSERT_EQ(rk_gb_pack_unorm2(rk_gb_unpack_unorm2(wc, b), b), wc) << "unorm" << b << " code " << c;
        }
    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(rk_gb_pack_snorm2(vec2(nan, nan), 8u), 0u);
    EXPECT_EQ(rk_gb_pack_unorm2(vec2(nan, -1.0f), 8u), rk_gb_pack_unorm2(vec2(0.0f, -1.0f), 8u));
    EXPECT_EQ(rk_gb_pack_snorm2(vec2(7.0f, -1e30f), 8u), rk_gb_pack_snorm2(vec2(1.0f, -1.0f), 8u));
    // The quantize helpers give exactly what the packed word decodes to.
    EXPECT_EQ(rk_gb_quantize_snorm2(vec2(0.3f, -0.7f), 8u), rk_gb_unpack_snorm2(rk_gb_pack_snorm2(vec2(0.3f, -0.7f), 8u), 8u));
    const vec2 qu = rk_gb_quantize_unorm2(vec2(0.3f, -0.7f), 8u);
    EXPECT_EQ(qu.x * 255.0f, std::round(qu.x * 255.0f));
    EXPECT_NEAR(qu.x, 0.65f, 0.5f / 255.0f);
}

struct OctBound {
    uint32_t bits;
    double snorm, precise, unorm;  // max angle, rad (docs/deferred.md)
};

TEST(GbufferQuantise, OctahedralAngularErrorBounds)
{
    // The documented maxima (dense sweep, docs/deferred.md), and the mean.
    const OctBound bounds[] = {{8u, 1.7e-2, 1.15e-2, 1.7e-2}, {10u, 4.2e-3, 2.9e-3, 4.2e-3}, {12u, 1.05e-3, 7.2e-4, 1.05e-3},
                               {16u, 6.5e-5, 4.5e-5, 6.6e-5}};
    for (const OctBound& ob : bounds) {
        double m_s = 0.0, m_p = 0.0, m_u = 0.0, sum_s = 0.0, sum_p = 0.0;
        for (const dvec3& v : dirs()) {
            const vec3 f(v);
            const uint32_t ws = rk_gb_oct_pack_snorm(f, ob.bits), wp = rk_gb_oct_pack_snorm_precise(f, ob.bits);
            const double es = angle(dvec3(rk_gb_oct_unpack_snorm(ws, ob.bits)), dvec3(f));
            const double ep = angle(dvec3(rk_gb_oct_unpack_snorm(wp, ob.bits)), dvec3(f));
            const double eu = angle(dvec3(rk_gb_oct_unpack_unorm(rk_gb_oct_pack_unorm(f, ob.bits), ob.bits)), dvec3(f));
            // Never worse than the nearest code (which is one of its four candidates), up to the
            // float rounding of the distance it compares.
            ASSERT_LE(ep, es + 1e-7) << ob.bits << " " << S(f);
            m_s = std::max(m_s, es);
            m_p = std::max(m_p, ep);
            m_u = std::max(m_u, eu);
            sum_s += es;
            sum_p += ep;
        }
        EXPECT_LE(m_s, ob.snorm) << "oct snorm" << ob.bits;
        EXPECT_LE(m_p, ob.precise) << "oct snorm" << ob.bits << " precise";
        EXPECT_LE(m_u, ob.unorm) << "oct unorm" << ob.bits;
        EXPECT_LT(sum_p, sum_s) << ob.bits << ": the precise encoder lowers the mean error";
        EXPECT_LT(m_p, 0.8 * m_s) << ob.bits << ": and the maximum";
    }
}

// ---------------------------------------------------------------------------------------------
// Halves

TEST(GbufferHalf, CorrectlyRoundedAgainstFloat64)
{
    long checked = 0;
    auto check = [&](float x) {
        const uint32_t h = rk_gb_half_bits(x);
        ASSERT_LE(h, 0xFFFFu);
        const double got = rk_gb_half_value(h), want = half_round_d(x);
        if (!(got == want) || (got == 0.0 && std::signbit(got) != std::signbit(want) && !std::isnan(x)))
            FAIL() << "x " << S(x) << " half " << std::hex << h << std::dec << " -> " << got << ", want " << want;
        ++checked;
    };
    // Every 251st float pattern (both signs, all exponents, NaNs, infinities) ...
    for (uint64_t b = 0; b <= 0xFFFFFFFFull; b += 251) check(ufloat(static_cast<uint32_t>(b)));
    // ... and every float around the thresholds: the largest half, the rounding limit 65520, the
    // smallest normal half, the smallest denormal and half of it, ties in each binade.
    for (float c : {65504.0f, 65520.0f, 6.103515625e-5f, 5.9604644775390625e-8f, 2.98023223876953125e-8f, 1.0f, 2049.0f,
                    1.00048828125f, 3.0517578125e-5f}) {
        uint32_t b;
        std::memcpy(&b, &c, 4);
        for (int64_t d = -4096; d <= 4096; ++d) {
            check(ufloat(static_cast<uint32_t>(int64_t(b) + d)));
            check(-ufloat(static_cast<uint32_t>(int64_t(b) + d)));
        }
    }
    EXPECT_GT(checked, 17000000);
    EXPECT_EQ(rk_gb_half_bits(std::numeric_limits<float>::infinity()), 0x7BFFu) << "saturates, never inf";
    EXPECT_EQ(rk_gb_half_bits(-1e30f), 0xFBFFu);
    EXPECT_EQ(rk_gb_half_bits(std::numeric_limits<float>::quiet_NaN()), 0u);
}

TEST(GbufferHalf, EveryHalfDecodesExactly)
{
    for (uint32_t h = 0; h < 65536u; ++h) {
        const uint32_t e = (h >> 10) & 31u, m = h & 1023u;
        double want = e == 0 ? std::ldexp(double(m), -24) : std::ldexp(double(m | 1024u), int(e) - 25);
        if (e == 31u) want = m != 0 ? 0.0 : 65504.0;  // never made by rk_gb_half_bits (documented)
        if (h & 0x8000u) want = -want;
        const float got = rk_gb_half_value(h);
        ASSERT_EQ(double(got), want) << std::hex << h;
        if (e != 31u) {
            ASSERT_EQ(rk_gb_half_bits(got), h) << std::hex << h << ": every half round-trips";
        }
    }
    const uint32_t w = rk_gb_pack_half2(0.25f, -1234.5f);  // -1234.5 is a tie: to even, -1234
    EXPECT_EQ(rk_gb_unpack_half2(w), vec2(0.25f, -1234.0f));
    EXPECT_EQ(w & 0xFFFFu, rk_gb_half_bits(0.25f));
}

// ---------------------------------------------------------------------------------------------
// Depth

struct DepthCase {
    const char* name;
    SvoDepthConvention conv;
    float far_plane;
    bool reversed;
};

const DepthCase kDepthCases[] = {
    {"OpenGL [-1, 1]", SvoDepthConvention::gl_minus_one_to_one, 1e4f, false},
    {"zero-to-one", SvoDepthConvention::zero_to_one, 1e4f, false},
    {"zero-to-one, infinite far", SvoDepthConvention::zero_to_one, INFINITY, false},
    {"reversed-Z", SvoDepthConvention::reversed_zero_to_one, 1e4f, true},
    {"reversed-Z, infinite far", SvoDepthConvention::reversed_zero_to_one, INFINITY, true},
};

/// Window depth of view distance `dist` as a float pipeline makes it (clip = P v in float, z / w,
/// then OpenGL's 0.5 z + 0.5).
float window_depth(const mat4& P, SvoDepthConvention conv, double dist)
{
    const vec4 c = P * vec4(0.3f, -0.2f, static_cast<float>(-dist), 1.0f);
    const float z = c.z / c.w;
    return conv == SvoDepthConvention::gl_minus_one_to_one ? z * 0.5f + 0.5f : z;
}

mat4 projection(const DepthCase& c, float n)
{
    if (std::isinf(c.far_plane) && !c.reversed) {
        // glm has no infinite zero-to-one RH projection: d = 1 - n / dist.
        mat4 p(0.0f);
        const float f = 1.0f / std::tan(0.5f);
        p[0][0] = f / 1.5f;
        p[1][1] = f;
        p[2][2] = -1.0f;
        p[2][3] = -1.0f;
        p[3][2] = -n;
        return p;
    }
    return svo_perspective(1.0f, 1.5f, n, c.far_plane, c.conv);
}

TEST(GbufferDepth, LinearDepthAgainstFloat64AtTheStoredValue)
{
    const double n = 0.1;
    for (const DepthCase& c : kDepthCases) {
        const vec3 k = gbuffer_depth_params(n, c.far_plane, c.reversed);
        const double F = c.far_plane;
        // d = a + b / dist for the exact map of this convention.
        double a, b;
        if (c.reversed) {
            a = std::isfinite(F) ? -n / (F - n) : 0.0;
            b = std::isfinite(F) ? n * F / (F - n) : n;
        } else {
            a = std::isfinite(F) ? F / (F - n) : 1.0;
            b = std::isfinite(F) ? -n * F / (F - n) : -n;
        }
        double worst = 0.0, worst_textbook = 0.0;
        const float nf = static_cast<float>(n), ff = c.far_plane;
        // Every 64th float in [0, 1] and every float in the last 2^16 below 1 and above 0.
        auto visit = [&](float d) {
            const double exact = b / (double(d) - a);
            if (!(exact > 0.0) || !std::isfinite(exact) || exact > 3e38) return;
            const float got = rk_gb_linear_depth(d, k);
            // Documented: where 1 / dist would be subnormal (dist beyond 1 / RK_FLT_MIN = 8.5e37),
            // the result is RK_FLT_MAX, as on a GPU that flushes it.
            if (got == RK_FLT_MAX && exact * 1.1754943508222875e-38 >= 1.0 - 1e-6) return;
            worst = std::max(worst, std::abs(double(got) - exact) / exact);
            // The textbook form n f / (f - d (f - n)), in float, for the usual finite convention.
            if (!c.reversed && std::isfinite(F)) {
                const float tb = nf * ff / (ff - d * (ff - nf));
                worst_textbook = std::max(worst_textbook, std::abs(double(tb) - exact) / exact);
            }
        };
        for (uint32_t bits = 0; bits <= 0x3F800000u; bits += 64) visit(ufloat(bits));
        for (uint32_t bits = 0x3F800000u - 65536u; bits <= 0x3F800000u; ++bits) visit(ufloat(bits));
        for (uint32_t bits = 0; bits < 65536u; ++bits) visit(ufloat(bits));
        EXPECT_LE(worst, 2.0e-7) << c.name;
        if (!c.reversed && std::isfinite(F)) {
            std::printf("%-28s rk_gb_linear_depth %.2g, textbook n f / (f - d (f - n)) %.2g\n", c.name, worst, worst_textbook);
            EXPECT_GT(worst_textbook, 1e-3) << c.name << ": the cancellation this form avoids";
        }
        // The ends of the range.
        EXPECT_NEAR(rk_gb_linear_depth(c.reversed ? 1.0f : 0.0f, k), n, 1e-7) << c.name;
        if (std::isfinite(F)) {
            EXPECT_NEAR(rk_gb_linear_depth(c.reversed ? 0.0f : 1.0f, k), F, F * 2e-7) << c.name;
        } else {
            EXPECT_EQ(rk_gb_linear_depth(c.reversed ? 0.0f : 1.0f, k), RK_FLT_MAX) << c.name;
        }
        EXPECT_NEAR(rk_gb_linear_depth(std::numeric_limits<float>::quiet_NaN(), k), n, n * 1e-6) << c.name << ": NaN reads as the near plane";
        // Outside [0, 1] and NaN are clamped.
        for (float d : {-1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN(), -0.0f, 1e-45f, 3e38f}) {
            const float r = rk_gb_linear_depth(d, k);
            EXPECT_TRUE(std::isfinite(r) && r >= float(n) * 0.999999f) << c.name << " d " << S(d) << " -> " << S(r);
        }
    }
}

TEST(GbufferDepth, EndToEndErrorByConvention)
{
    // The distance rebuilt from the depth a float pipeline stores (D32F): reversed-Z keeps ~1e-7
    // relative at every distance; the usual convention loses ~dist / n ulps (the stored d, not the
    // formula). The rows printed are the table of docs/deferred.md.
    const float n = 0.1f;
    for (const DepthCase& c : kDepthCases) {
        const mat4 P = projection(c, n);
        const vec3 k = gbuffer_depth_params(n, c.far_plane, c.reversed);
        // An infinite far plane: reversed-Z to 1e7 (10^8 near distances); the usual convention only
        // resolves distances up to about n 2^24 (beyond, 1 - n / dist rounds to 1).
        const double fmax = std::isfinite(c.far_plane) ? c.far_plane : (c.reversed ? 1e7 : 1e5);
        std::printf("%-28s", c.name);
        for (double lo = n; lo < fmax * 0.999; lo *= 10.0) {
            double worst = 0.0;
            for (int i = 0; i < 4000; ++i) {
                const double dist = std::min(lo * std::pow(10.0, i / 4000.0), fmax);
                const float got = rk_gb_linear_depth(window_depth(P, c.conv, dist), k);
                worst = std::max(worst, std::abs(double(got) - dist) / dist);
            }
            std::printf(" %9.2g", worst);
            if (c.reversed) {
                EXPECT_LE(worst, 4e-7) << c.name << " at distances from " << lo;
            } else {
                // d's own resolution: ~1.2e-7 * dist / n (twice for margin), and 1e-6 near the plane.
                EXPECT_LE(worst, std::max(2.4e-7 * (10.0 * lo) / n, 2e-6)) << c.name << " at distances from " << lo;
                EXPECT_GE(worst, 1.2e-8 * lo / n) << c.name << ": the usual convention's loss is real";
            }
        }
        std::printf("\n");
    }
}

TEST(GbufferDepth, ViewRayOfADegenerateMatrixStaysFinite)
{
    mat4 P(0.0f);
    P[0][0] = 1e-39f;
    P[1][1] = 1e-20f;
    P[2][0] = 1e20f;
    const vec4 ray = gbuffer_view_ray(P);
    EXPECT_TRUE(std::isfinite(ray.x) && std::isfinite(ray.y) && std::isfinite(ray.z) && std::isfinite(ray.w));
    const vec3 p = rk_gb_view_pos(vec2(0.0f), 1.0f, ray);
    EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
}

TEST(GbufferDepth, ViewPositionAgainstFloat64)
{
    const float n = 0.05f;
    std::mt19937 rng(9u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    struct Proj {
        const char* name;
        mat4 P;
        bool reversed;
        float far_plane;
    };
    mat4 vk = svo_perspective(0.9f, 1.7f, n, INFINITY, SvoDepthConvention::reversed_zero_to_one);
    vk[1][1] = -vk[1][1];  // Vulkan's y-flip
    const Proj projs[] = {
        {"reversed infinite", svo_perspective(0.9f, 1.7f, n, INFINITY, SvoDepthConvention::reversed_zero_to_one), true, INFINITY},
        {"reversed infinite, Vulkan y-flip", vk, true, INFINITY},
        {"off-centre frustum (GL)", glm::frustum(-0.03f, 0.05f, -0.02f, 0.035f, n, 500.0f), false, 500.0f},
        {"zero-to-one", svo_perspective(1.2f, 1.0f, n, 500.0f, SvoDepthConvention::zero_to_one), false, 500.0f},
    };
    for (const Proj& p : projs) {
        const vec4 ray = gbuffer_view_ray(p.P);
        const vec3 k = gbuffer_depth_params(n, p.far_plane, p.reversed);
        double worst = 0.0;
        for (int i = 0; i < 20000; ++i) {
            const double dist = n * std::pow(400.0 / n, 0.5 * (u(rng) + 1.0));
            const dvec3 v(u(rng) * dist, u(rng) * dist, -dist);
            // NDC of v (float64), and the depth stored as a float.
            const glm::dvec4 c = glm::dmat4(p.P) * glm::dvec4(v, 1.0);
            const dvec2 ndc(c.x / c.w, c.y / c.w);
            const double zn = c.z / c.w;
            const float d = static_cast<float>(p.name[0] == 'o' ? zn * 0.5 + 0.5 : zn);
            const vec3 got = rk_gb_view_pos(vec2(ndc), rk_gb_linear_depth(d, k), ray);
            worst = std::max(worst, glm::length(dvec3(got) - v) / dist);
        }
        if (p.reversed) {
            EXPECT_LE(worst, 1e-6) << p.name;
        } else {
            EXPECT_LE(worst, 2e-7 * 400.0 / n) << p.name;  // the stored d's resolution at 400
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Layouts

TEST(GbufferLayout, PresetsAndValidation)
{
    Status st;
    std::string warn;
    const GbLayout thesis = gbuffer_layout_thesis();
    GbLayoutRules r2005;
    r2005.max_targets = 4;
    r2005.equal_bits = true;
    r2005.warn_targets = 4;
    EXPECT_TRUE(validate_gbuffer_layout(thesis, r2005, st, &warn)) << st.message;
    EXPECT_NE(warn.find("4 targets"), std::string::npos) << warn;
    EXPECT_EQ(gbuffer_bits_per_pixel(thesis), 4 * 64 + 24);
    const GbLayout compact = gbuffer_layout_compact();
    EXPECT_TRUE(validate_gbuffer_layout(compact, GbLayoutRules{}, st)) << st.message;
    EXPECT_EQ(gbuffer_bits_per_pixel(compact), 160);
    GbLayout mixed = compact;
    mixed.targets[1].format = GbFormat::rgba16f;
    EXPECT_TRUE(validate_gbuffer_layout(mixed, GbLayoutRules{}, st)) << st.message;
    EXPECT_FALSE(validate_gbuffer_layout(mixed, r2005, st)) << "mixed bits under the 2005 rule";
    EXPECT_NE(st.message.find("equal_bits"), std::string::npos) << st.message;

    GbLayout bad = compact;
    const GbTarget first = bad.targets[0];
    bad.targets.resize(9, first);
    for (size_t i = 1; i < bad.targets.size(); ++i) bad.targets[i].channels.clear();
    EXPECT_FALSE(validate_gbuffer_layout(bad, GbLayoutRules{}, st));
    EXPECT_NE(st.message.find("9 targets"), std::string::npos) << st.message;
    bad = compact;
    bad.targets[1].channels.push_back("extra");
    EXPECT_FALSE(validate_gbuffer_layout(bad, GbLayoutRules{}, st));
    EXPECT_NE(st.message.find("names 3 channels"), std::string::npos) << st.message;
    bad = compact;
    bad.targets[2].channels[0] = "albedo.r";
    EXPECT_FALSE(validate_gbuffer_layout(bad, GbLayoutRules{}, st));
    EXPECT_NE(st.message.find("stored twice"), std::string::npos) << st.message;
    bad = compact;
    bad.depth_bits = 20;
    EXPECT_FALSE(validate_gbuffer_layout(bad, GbLayoutRules{}, st));
    bad.targets.clear();
    bad.depth_bits = 32;
    EXPECT_FALSE(validate_gbuffer_layout(bad, GbLayoutRules{}, st));
    EXPECT_EQ(st.code, Error::invalid_argument);
    for (int f = 0; f <= static_cast<int>(GbFormat::rgba32ui); ++f) {
        const GbFormat g = static_cast<GbFormat>(f);
        EXPECT_GT(gb_format_bits(g), 0);
        EXPECT_EQ(gb_format_bits(g) % gb_format_channels(g) == 0 || g == GbFormat::rgb10a2 || g == GbFormat::r11g11b10f, true)
            << gb_format_name(g);
    }
}

// ---------------------------------------------------------------------------------------------
// Bad input: every function, adversarial arguments (±0, denormals, FLT_MAX, NaN, ±Inf).

TEST(GbufferAdversarial, EveryFunctionStaysFiniteAndInRange)
{
    const Floats all = Floats::all();
    const Vecs v3 = Vecs::all();
    auto unit = [](vec3 r) { return finite(r) && std::abs(glm::length(dvec3(r)) - 1.0) <= 1e-6; };
    ADV("rk_gb_oct_encode/decode", {
        const vec3 v = G.v3(v3);
        const vec2 p = rk_gb_oct_encode(v);
        CHECK(finite(p) && std::abs(p.x) <= 1.0f && std::abs(p.y) <= 1.0f, S(p));
        CHECK(unit(rk_gb_oct_decode(p)), S(p));
        CHECK(unit(rk_gb_oct_decode(G.v2(v3))), "decode");
    });
    ADV("rk_gb_hemi_encode/decode", {
        const vec3 v = G.v3(v3);
        const vec2 p = rk_gb_hemi_encode(v);
        CHECK(finite(p) && glm::length(dvec2(p)) <= 1.0 + 3e-7, S(p));
        const vec3 r = rk_gb_hemi_decode(G.v2(v3));
        CHECK(unit(r) && r.z >= 0.0f, S(r));
    });
    ADV("rk_gb_lambert_encode/decode", {
        const vec3 v = G.v3(v3);
        const vec2 p = rk_gb_lambert_encode(v);
        CHECK(finite(p) && glm::length(dvec2(p)) <= 1.0 + 3e-7, S(p));
        CHECK(unit(rk_gb_lambert_decode(G.v2(v3))), "decode");
    });
    ADV("rk_gb_oct_pack/unpack (snorm, precise, unorm)", {
        const vec3 v = G.v3(v3);
        const uint32_t b = G.u(0u, 40u);
        const uint32_t bc = std::min(std::max(b, 2u), 16u);
        const uint32_t ws = rk_gb_oct_pack_snorm(v, b), wp = rk_gb_oct_pack_snorm_precise(v, b), wu = rk_gb_oct_pack_unorm(v, b);
        CHECK(ws < (1ull << (2 * bc)) && wp < (1ull << (2 * bc)) && wu < (1ull << (2 * std::max(std::min(b, 16u), 1u))), "word");
        CHECK(unit(rk_gb_oct_unpack_snorm(ws, b)) && unit(rk_gb_oct_unpack_snorm(wp, b)) && unit(rk_gb_oct_unpack_unorm(wu, b)),
              "unpack");
        CHECK(unit(rk_gb_oct_unpack_snorm(G.u(), b)) && unit(rk_gb_oct_unpack_unorm(G.u(), b)), "unpack any word");
    });
    ADV("rk_gb_pack/unpack snorm2/unorm2, quantize", {
        const vec2 p = G.v2(v3);
        const uint32_t b = G.u(0u, 40u);
        const vec2 qs = rk_gb_quantize_snorm2(p, b), qu = rk_gb_quantize_unorm2(p, b);
        CHECK(finite(qs) && std::abs(qs.x) <= 1.0f && std::abs(qs.y) <= 1.0f, S(qs));
        CHECK(finite(qu) && qu.x >= 0.0f && qu.x <= 1.0f && qu.y >= 0.0f && qu.y <= 1.0f, S(qu));
        const vec2 us = rk_gb_unpack_snorm2(G.u(), b), uu = rk_gb_unpack_unorm2(G.u(), b);
        CHECK(finite(us) && std::abs(us.x) <= 1.0f && finite(uu) && std::abs(uu.y) <= 1.0f, S(us) + S(uu));
    });
    ADV("rk_gb_half_bits/value, pack/unpack_half2", {
        const float a = G.f(all), b = G.f(all);
        const vec2 r = rk_gb_unpack_half2(rk_gb_pack_half2(a, b));
        CHECK(finite(r) && std::abs(r.x) <= 65504.0f && std::abs(r.y) <= 65504.0f, S(r));
        CHECK(std::isfinite(rk_gb_half_value(G.u())), "value");
    });
    ADV("rk_gb_depth_params/linear_depth/view_pos", {
        const float n = G.f(all), f = G.f(all), d = G.f(all);
        const vec3 k = rk_gb_depth_params(n, f, G.uniform() < 0.5);
        const float r = rk_gb_linear_depth(d, k);
        const vec3 kd = gbuffer_depth_params(n, f, G.uniform() < 0.5);
        CHECK(std::isfinite(rk_gb_linear_depth(d, kd)) && rk_gb_linear_depth(d, kd) > 0.0f, "double params");
        // Finite k (a finite positive near plane) gives a finite positive distance.
        if (n >= RK_FLT_MIN && std::isfinite(k.x)) CHECK(std::isfinite(r) && r > 0.0f, S(r));
        const vec3 pos = rk_gb_view_pos(G.v2(Vecs::of(Floats::range(-1.0f, 1.0f))), std::min(r, 1e30f),
                                        vec4(G.f(Floats::range(-10.0f, 10.0f)), G.f(Floats::range(-10.0f, 10.0f)),
                                             G.f(Floats::range(-10.0f, 10.0f)), G.f(Floats::range(-10.0f, 10.0f))));
        CHECK(finite(pos), S(pos));
    });
}

}  // namespace
