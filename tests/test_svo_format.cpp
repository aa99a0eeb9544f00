// The packed octree format against independent float64 / brute-force references:
// - the codecs of shaders/raykit/svo_format.glsl (C++ build): octahedral normals (max angular
//   round-trip error over 10^6 random and adversarial vectors vs the documented 6.5e-5 rad), sRGB
//   colour words vs the IEC 61966-2-1 formula in double, the builder's table fast path
//   (svo_detail::SrgbTables) bit for bit vs rk_svo_pack_color, snorm16 / unorm8, and the brick and
//   descriptor helpers vs bit loops;
// - trees from raykit::build_svo: texture filtering on quads with known textures (a gradient whose
//   voxel average is its centre value, a checker of half-voxel cells whose average is the mean),
//   inner-node colours / normals / materials recomputed from the leaves at every level, forced far
//   pointers, hand-checked depth 1..3 trees, depth 16, bytes per voxel, the memory estimate and
//   budget, progress and cancellation, invalid options, and custom parallel_for determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <thread>
#include <utility>
#include <random>
#include <vector>

#include "raykit/svo_build.hpp"
#include "raykit/svo_file.hpp"
#include "reference/svo_meshes.hpp"

using namespace raykit;

namespace {

// ---- float64 references and helpers ---------------------------------------------------------

uint32_t bits_of(float x)
{
    uint32_t u;
    std::memcpy(&u, &x, 4);
    return u;
}
float float_of(uint32_t u)
{
    float x;
    std::memcpy(&x, &u, 4);
    return x;
}

/// IEC 61966-2-1 sRGB encode / decode in double.
double srgb_enc64(double x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055; }
double srgb_dec64(double s) { return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4); }

/// Clamp to [0, 1] with NaN -> 0 (the codecs' documented sanitising).
double clamp01_nan0(double x) { return x > 0.0 ? (x < 1.0 ? x : 1.0) : 0.0; }

/// Angle between two non-zero vectors, accurate near 0 (atan2 of |cross| and dot).
double angle64(glm::dvec3 a, glm::dvec3 b)
{
    a = glm::normalize(a);
    b = glm::normalize(b);
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

uint32_t popcount64(uint64_t m)
{
    uint32_t c = 0;
    for (int i = 0; i < 64; ++i) c += static_cast<uint32_t>((m >> i) & 1u);
    return c;
}

/// Channel k (0..3) of a colour word.
uint32_t chan(uint32_t w, int k) { return (w >> (8 * k)) & 0xFFu; }

// ---- codecs: normals ------------------------------------------------------------------------

struct NormalErr {
    double max_err = 0.0;
    glm::dvec3 worst{0.0};
    size_t count = 0;
    void check(glm::vec3 n)
    {
        const glm::dvec3 d(n);
        const double l = glm::length(d);
        if (!(l > 0.0) || !std::isfinite(l)) return;
        const glm::vec3 r = rk_svo_unpack_normal(rk_svo_pack_normal(n));
        const glm::dvec3 rd(r);
        ASSERT_TRUE(std::isfinite(rd.x) && std::isfinite(rd.y) && std::isfinite(rd.z));
        ASSERT_NEAR(glm::length(rd), 1.0, 1e-6);
        const double e = angle64(d, rd);
        ++count;
        if (e > max_err) { max_err = e; worst = d; }
    }
};

TEST(SvoCodec, NormalRoundTripMaxAngularErrorIsWithinTheDocumentedBound)
{
    NormalErr E;
    rkmesh::Rng rng(12345);
    // 10^6 random unit vectors (uniform on the sphere, in double, rounded to float).
    for (int i = 0; i < 1000000; ++i) {
        const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * rkmesh::kPi);
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        E.check(rkmesh::to_vec3(r * std::cos(phi), r * std::sin(phi), z));
        if (::testing::Test::HasFatalFailure()) return;
    }
    // Octant seams: one component +-0, the others random (10^4 each).
    for (int axis = 0; axis < 3; ++axis)
        for (int i = 0; i < 20000; ++i) {
            glm::vec3 v = rkmesh::to_vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
            v[axis] = (i & 1) ? -0.0f : 0.0f;
            E.check(v);
        }
    // Near the seams: one component a few float steps off zero.
    for (int axis = 0; axis < 3; ++axis)
        for (int i = 0; i < 20000; ++i) {
            glm::vec3 v = rkmesh::to_vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
            v[axis] = static_cast<float>(((i & 1) ? -1.0 : 1.0) * std::pow(10.0, rng.uniform(-44.0, -3.0)));
            E.check(v);
        }
    // Every triple of special component values: axes, +-0, diagonals, tiny (denormal) and huge.
    const float specials[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.75f, 1e-40f, -1e-40f, 1.4e-45f, -1.4e-45f,
                              std::numeric_limits<float>::min(), 1e-20f, 1e38f, -1e38f, 1e30f, -3e37f, 1e-7f, -1e-7f};
    for (float a : specials)
        for (float b : specials)
            for (float c : specials) {
                E.check(glm::vec3(a, b, c));
                if (::testing::Test::HasFatalFailure()) return;
            }
    // Diagonals and edge midpoints of the octahedron at several magnitudes.
    for (double s : {1e-40, 1e-30, 1e-3, 1.0, 1e10, 1e30, 1e38})
        for (int sg = 0; sg < 8; ++sg) {
            const double x = (sg & 1) ? -s : s, y = (sg & 2) ? -s : s, z = (sg & 4) ? -s : s;
            E.check(rkmesh::to_vec3(x, y, z));
            E.check(rkmesh::to_vec3(x, y, 0.0));
            E.check(rkmesh::to_vec3(x, 0.0, z));
            E.check(rkmesh::to_vec3(0.0, y, z));
        }
    std::printf("[ normals  ] max angular round-trip error %.4g rad over %zu vectors (documented 6.5e-5), worst (%g, %g, %g)\n",
                E.max_err, E.count, E.worst.x, E.worst.y, E.worst.z);
    EXPECT_GT(E.count, 1000000u);
    EXPECT_LT(E.max_err, 6.5e-5);
    // The quantisation is real: the error is not orders of magnitude below the bound either.
    EXPECT_GT(E.max_err, 1e-5);
}

TEST(SvoCodec, NormalOfHugeFiniteVectorsKeepsItsDirection)
{
    // "Any finite vector": L1 norms above FLT_MAX must not fall back to +z.
    const glm::vec3 cases[] = {{3e38f, -3e38f, 2e38f}, {-3.4e38f, 0.0f, 3.4e38f}, {2e38f, 2e38f, -2e38f}};
    for (const glm::vec3& v : cases) {
        const glm::vec3 r = rk_svo_unpack_normal(rk_svo_pack_normal(v));
        EXPECT_LT(angle64(glm::dvec3(v), glm::dvec3(r)), 6.5e-5) << "v = (" << v.x << ", " << v.y << ", " << v.z << ") decodes to ("
                                                                  << r.x << ", " << r.y << ", " << r.z << ")";
    }
}

TEST(SvoCodec, NormalZeroAndNanEncodePlusZ)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const glm::vec3 cases[] = {{0.0f, 0.0f, 0.0f}, {-0.0f, -0.0f, -0.0f}, {nan, 0.0f, 0.0f}, {0.0f, nan, 1.0f},
                               {1.0f, 1.0f, nan}, {nan, nan, nan}, {-1.0f, nan, -1.0f}};
    for (const glm::vec3& v : cases) {
        const uint32_t w = rk_svo_pack_normal(v);
        const glm::vec3 r = rk_svo_unpack_normal(w);
        EXPECT_EQ(r.x, 0.0f);
        EXPECT_EQ(r.y, 0.0f);
        EXPECT_EQ(r.z, 1.0f);
    }
}

TEST(SvoCodec, NormalUnpackOfEveryEdgeCodeIsAFiniteUnitVector)
{
    const uint32_t edges[] = {0x0000u, 0x0001u, 0x0002u, 0x3FFFu, 0x4000u, 0x4001u, 0x7FFEu, 0x7FFFu,
                              0x8000u, 0x8001u, 0x8002u, 0xBFFFu, 0xC000u, 0xC001u, 0xFFFEu, 0xFFFFu};
    auto check = [](uint32_t w) {
        const glm::vec3 r = rk_svo_unpack_normal(w);
        const bool finite = std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z);
        EXPECT_TRUE(finite) << std::hex << w;
        EXPECT_NEAR(glm::length(glm::dvec3(r)), 1.0, 1e-6) << std::hex << w;
    };
    for (uint32_t u : edges)
        for (uint32_t v : edges) check(u | (v << 16));
    rkmesh::Rng rng(99);
    for (int i = 0; i < 200000; ++i) check(static_cast<uint32_t>(rng.next()));
}

// ---- codecs: snorm16 / unorm8 ---------------------------------------------------------------

// The documented contract: c * 32767 in float32, then +-0.5 in float32, truncated toward zero.
uint32_t snorm16_ref(double x)
{
    const double c = std::isnan(x) ? 0.0 : std::min(1.0, std::max(-1.0, x));
    const float r = static_cast<float>(c) * 32767.0f;
    const double q = r >= 0.0f ? std::floor(static_cast<double>(r + 0.5f)) : -std::floor(static_cast<double>(0.5f - r));
    return static_cast<uint32_t>(static_cast<int32_t>(q)) & 0xFFFFu;
}

// The documented contract: c * 255 + 0.5 in float32 (two roundings), truncated.
uint32_t unorm8_ref(double x)
{
    const double c = clamp01_nan0(x);
    const float p = static_cast<float>(c) * 255.0f;
    return static_cast<uint32_t>(std::floor(static_cast<double>(p + 0.5f)));
}

TEST(SvoCodec, Snorm16MatchesTheFloat64Reference)
{
    size_t n = 0;
    auto check = [&](float x) {
        ++n;
        const uint32_t got = rk_svo_pack_snorm16(x), want = snorm16_ref(static_cast<double>(x));
        EXPECT_EQ(got, want) << "x = " << x << " (bits 0x" << std::hex << bits_of(x) << ")";
        return got == want;
    };
    // Every rounding boundary (k + 1/2) / 32767 and its float neighbours, both signs.
    for (int k = 0; k < 32767; ++k) {
        const float b = static_cast<float>((k + 0.5) / 32767.0);
        uint32_t u = bits_of(b);
        for (int d = -3; d <= 3; ++d) {
            const float x = float_of(u + static_cast<uint32_t>(d));
            if (!check(x) || !check(-x)) return;
        }
    }
    rkmesh::Rng rng(7);
    for (int i = 0; i < 300000; ++i)
        if (!check(static_cast<float>(rng.uniform(-1.2, 1.2)))) return;
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (float x : {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, -2.0f, inf, -inf, nan, 1e-45f, -1e-45f}) check(x);
    EXPECT_EQ(rk_svo_pack_snorm16(1.0f), 0x7FFFu);
    EXPECT_EQ(rk_svo_pack_snorm16(-1.0f), 0x8001u);
    EXPECT_EQ(rk_svo_pack_snorm16(nan), 0u);
    // Unpack: every code, against float(i / 32767) in double (-32768 -> -1).
    for (uint32_t f = 0; f < 65536u; ++f) {
        const int i = f >= 0x8000u ? static_cast<int>(f) - 65536 : static_cast<int>(f);
        const float want = static_cast<float>(std::max(-1.0, i / 32767.0));
        ASSERT_EQ(rk_svo_unpack_snorm16(f), want) << f;
        ASSERT_EQ(rk_svo_unpack_snorm16(f | 0xABCD0000u), want) << "high bits must be ignored";
    }
    EXPECT_GT(n, 500000u);
}

TEST(SvoCodec, Unorm8MatchesTheFloat64Reference)
{
    size_t bad = 0;
    auto check = [&](float x) {
        const uint32_t got = rk_svo_pack_unorm8(x), want = unorm8_ref(static_cast<double>(x));
        if (got != want && bad++ < 5) ADD_FAILURE() << "x = " << x << " (bits 0x" << std::hex << bits_of(x) << ") -> " << std::dec << got << ", want " << want;
    };
    for (int k = 0; k < 255; ++k) {
        const uint32_t u = bits_of(static_cast<float>((k + 0.5) / 255.0));
        for (int d = -64; d <= 64; ++d) check(float_of(u + static_cast<uint32_t>(d)));
    }
    rkmesh::Rng rng(8);
    for (int i = 0; i < 300000; ++i) check(static_cast<float>(rng.uniform(-0.1, 1.1)));
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (float x : {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, inf, -inf, nan, 1e-45f}) check(x);
    EXPECT_EQ(bad, 0u);
}

// ---- codecs: colour -------------------------------------------------------------------------

TEST(SvoCodec, ColorPackIsTheFloat64NearestSrgbCode)
{
    size_t checked = 0, near_boundary = 0, bad = 0;
    auto check_channel = [&](float x, uint32_t got) {
        const double t = srgb_enc64(clamp01_nan0(static_cast<double>(x))) * 255.0;
        const double r = std::floor(t + 0.5);
        if (std::fabs(t + 0.5 - std::nearbyint(t + 0.5)) < 1e-4) { ++near_boundary; return; }
        ++checked;
        if (static_cast<double>(got) != r && bad++ < 5)
            ADD_FAILURE() << "x = " << x << " encodes to " << got << ", float64 nearest " << r << " (t = " << t << ")";
    };
    auto check = [&](glm::vec4 c) {
        const uint32_t w = rk_svo_pack_color(c);
        for (int k = 0; k < 3; ++k) check_channel(c[k], chan(w, k));
        EXPECT_EQ(chan(w, 3), unorm8_ref(static_cast<double>(c.w))) << "alpha is linear";
    };
    rkmesh::Rng rng(21);
    for (int i = 0; i < 300000; ++i)
        check(glm::vec4(static_cast<float>(rng.uniform()), static_cast<float>(std::pow(10.0, rng.uniform(-8.0, 0.0))),
                        static_cast<float>(rng.uniform(0.0, 0.01)), static_cast<float>(rng.uniform())));
    // Around every float64 code boundary: decode((k - 1/2) / 255) and its float neighbours.
    for (int k = 1; k < 256; ++k) {
        const uint32_t u = bits_of(static_cast<float>(srgb_dec64((k - 0.5) / 255.0)));
        for (int d = -16; d <= 16; ++d) {
            const float x = float_of(u + static_cast<uint32_t>(d));
            check(glm::vec4(x, x, x, x));
        }
    }
    // Clamping: NaN and negative -> 0, > 1 -> 255 (every channel, alpha included).
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(nan)), 0u);
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(-0.5f)), 0u);
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(-inf)), 0u);
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(-0.0f)), 0u);
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(1.5f)), 0xFFFFFFFFu);
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(inf)), 0xFFFFFFFFu);
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(1.0f)), 0xFFFFFFFFu);
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(nan, 2.0f, -1.0f, 0.5f)), 0x8000FF00u);
    // Channel order: R in bits 0..7.
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(1.0f, 0.0f, 0.0f, 0.0f)), 0x000000FFu);
    EXPECT_EQ(rk_svo_pack_color(glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)), 0x00FF0000u);
    // (Most skipped channels are the deliberate boundary neighbours above.)
    std::printf("[ colour   ] %zu channels equal the float64-nearest code, %zu within 1e-4 of a boundary skipped\n", checked, near_boundary);
    EXPECT_EQ(bad, 0u);
    EXPECT_GT(checked, 800000u);
}

TEST(SvoCodec, ColorUnpackAndRoundTripError)
{
    // Unpack of every code vs the float64 decode (documented 1.9e-7 abs); alpha k / 255.
    double max_dec = 0.0;
    for (uint32_t k = 0; k < 256; ++k) {
        const glm::vec4 c = rk_svo_unpack_color(k | ((255u - k) << 8) | (((k * 7u) & 255u) << 16) | (k << 24));
        const double want[4] = {srgb_dec64(k / 255.0), srgb_dec64((255u - k) / 255.0), srgb_dec64(((k * 7u) & 255u) / 255.0), k / 255.0};
        for (int i = 0; i < 4; ++i) max_dec = std::max(max_dec, std::fabs(static_cast<double>(c[i]) - want[i]));
    }
    EXPECT_LE(max_dec, 1.9e-7);
    // Round trip: within half an sRGB step (in the encoded domain) per channel, alpha 1/510.
    rkmesh::Rng rng(5);
    double max_rt = 0.0, max_a = 0.0;
    for (int i = 0; i < 200000; ++i) {
        const glm::vec4 c(static_cast<float>(rng.uniform()), static_cast<float>(std::pow(10.0, rng.uniform(-6.0, 0.0))),
                          static_cast<float>(rng.uniform(0.0, 0.02)), static_cast<float>(rng.uniform()));
        const glm::vec4 r = rk_svo_unpack_color(rk_svo_pack_color(c));
        for (int k = 0; k < 3; ++k)
            max_rt = std::max(max_rt, std::fabs(srgb_enc64(static_cast<double>(r[k])) - srgb_enc64(static_cast<double>(c[k]))));
        max_a = std::max(max_a, std::fabs(static_cast<double>(r.w) - static_cast<double>(c.w)));
    }
    std::printf("[ colour   ] decode max abs error %.3g, round trip max %.5f sRGB steps, alpha %.5f steps\n", max_dec, max_rt * 255.0,
                max_a * 255.0);
    EXPECT_LE(max_rt, 0.5 / 255.0 + 1e-6);
    EXPECT_LE(max_a, 0.5 / 255.0 + 1e-7);
}

TEST(SvoCodec, SrgbTablesEqualTheShaderCodecBitForBit)
{
    const svo_detail::SrgbTables& T = svo_detail::SrgbTables::get();
    size_t n = 0, bad = 0;
    auto check = [&](float x) {
        ++n;
        const glm::vec4 c(x, x, x, x);
        const uint32_t a = T.pack(c), b = rk_svo_pack_color(c);
        if (a != b && bad++ < 5)
            ADD_FAILURE() << "x = " << x << " (bits 0x" << std::hex << bits_of(x) << "): tables 0x" << a << ", rk_svo_pack_color 0x" << b;
    };
    // The tables' own thresholds and my float64 boundaries, 1000 / 16 float steps either way
    // (which also checks that the encoder is monotone where the bisection assumed it).
    for (int k = 1; k < 256; ++k) {
        const uint32_t t = bits_of(T.threshold[k]);
        for (int d = -1000; d <= 1000; ++d) {
            const int64_t u = static_cast<int64_t>(t) + d;
            if (u >= 0 && u <= 0x3F800000) check(float_of(static_cast<uint32_t>(u)));
        }
        check(std::nextafter(T.threshold[k], 0.0f));
        check(std::nextafter(T.threshold[k], 2.0f));
        const uint32_t f = bits_of(static_cast<float>(srgb_dec64((k - 0.5) / 255.0)));
        for (int d = -16; d <= 16; ++d) check(float_of(f + static_cast<uint32_t>(d)));
    }
    rkmesh::Rng rng(77);
    for (int i = 0; i < 1000000; ++i)
        check(static_cast<float>((i & 1) ? rng.uniform() : std::pow(10.0, rng.uniform(-12.0, 0.0))));
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (float x : {0.0f, -0.0f, nan, -nan, 1.0f, std::nextafter(1.0f, 0.0f), 1.0000001f, 2.0f, inf, -inf, -1.0f, 1e-45f,
                    std::numeric_limits<float>::min(), std::numeric_limits<float>::max()})
        check(x);
    // Mixed channels.
    for (int i = 0; i < 100000; ++i) {
        const glm::vec4 c(static_cast<float>(rng.uniform(-0.1, 1.1)), static_cast<float>(rng.uniform()),
                          static_cast<float>(rng.uniform(0.0, 0.005)), static_cast<float>(rng.uniform(-0.1, 1.1)));
        if (T.pack(c) != rk_svo_pack_color(c) && bad++ < 5) ADD_FAILURE() << "mixed channels differ";
    }
    EXPECT_EQ(bad, 0u) << "of " << n;
    // Unpack: every code in every channel.
    for (uint32_t k = 0; k < 256; ++k)
        for (uint32_t w : {k * 0x01010101u, k | ((255u - k) << 8) | (((k * 37u) & 255u) << 16) | (((k * 11u) & 255u) << 24)}) {
            const glm::vec4 a = T.unpack(w), b = rk_svo_unpack_color(w);
            for (int i = 0; i < 4; ++i) ASSERT_EQ(bits_of(a[i]), bits_of(b[i])) << "word 0x" << std::hex << w << " channel " << i;
        }
}

// ---- codecs: brick and descriptor helpers ---------------------------------------------------

/// Morton brick bit by bit loops: bit 3l + a = bit l of cell[a], for l < brick_levels.
uint32_t brick_bit_ref(glm::uvec3 cell, uint32_t b)
{
    uint32_t bit = 0;
    for (uint32_t l = 0; l < b; ++l)
        for (uint32_t a = 0; a < 3; ++a) bit |= ((cell[static_cast<int>(a)] >> l) & 1u) << (3u * l + a);
    return bit;
}

TEST(SvoCodec, BrickAndDescriptorHelpersMatchBitLoops)
{
    // rk_svo_brick_bit: every cell of an 8^3 block (high bits must not matter) plus random cells.
    rkmesh::Rng rng(3);
    for (uint32_t z = 0; z < 8; ++z)
        for (uint32_t y = 0; y < 8; ++y)
            for (uint32_t x = 0; x < 8; ++x) {
                const uint32_t hi = static_cast<uint32_t>(rng.next()) & ~3u;
                const glm::uvec3 c(x, y, z), c2(x | hi, y | ((hi >> 1) & ~3u), z | ((hi >> 2) & ~3u));
                ASSERT_EQ(rk_svo_brick_bit(c, 2u), brick_bit_ref(c, 2u));
                ASSERT_EQ(rk_svo_brick_bit(c2, 2u), brick_bit_ref(c, 2u));
                ASSERT_EQ(rk_svo_brick_bit(c2, 1u), brick_bit_ref(c, 1u));
            }
    // Masks: random of varied density, single bits, empty, full.
    std::vector<uint64_t> masks = {0ull, ~0ull, 1ull, 1ull << 63, 0xFFull, 0xFF00000000000000ull, 0x0101010101010101ull, 0x8000000080000000ull};
    for (int i = 0; i < 64; ++i) masks.push_back(1ull << i);
    for (int i = 0; i < 6000; ++i) {
        uint64_t m = rng.next();
        for (int k = 0; k < (i % 4); ++k) m &= rng.next();
        if (i % 5 == 0) m |= rng.next();
        masks.push_back(m);
    }
    for (uint64_t m : masks) {
        const glm::uvec2 mv(static_cast<uint32_t>(m), static_cast<uint32_t>(m >> 32));
        uint32_t sub_ref = 0;
        for (uint32_t s = 0; s < 8; ++s)
            if ((m >> (8 * s)) & 0xFFull) sub_ref |= 1u << s;
        ASSERT_EQ(rk_svo_brick_submask(mv), sub_ref);
        ASSERT_EQ(rk_svo_brick_voxel_count(mv), popcount64(m));
        const uint32_t base = static_cast<uint32_t>(rng.next() >> 34);
        for (uint32_t bit = 0; bit < 64; ++bit) {
            ASSERT_EQ(rk_svo_brick_has(mv, bit), ((m >> bit) & 1ull) != 0);
            uint32_t rank = 0;
            for (uint32_t j = 0; j < bit; ++j) rank += static_cast<uint32_t>((m >> j) & 1ull);
            ASSERT_EQ(rk_svo_brick_rank(mv, bit), rank);
            ASSERT_EQ(rk_svo_brick_voxel_attr(base, mv, bit, 2u), base + popcount64(sub_ref) + rank);
            ASSERT_EQ(rk_svo_brick_voxel_attr(base | RK_SVO_BRICK_SHARED_SUB, mv, bit, 2u), base + rank);
            if (bit < 8) {
                // 2^3 bricks (depth 1): bits 0..7, no sub-nodes.
                const glm::uvec2 m8(mv.x & 0xFFu, 0u);
                uint32_t r8 = 0;
                for (uint32_t j = 0; j < bit; ++j) r8 += (m8.x >> j) & 1u;
                ASSERT_EQ(rk_svo_brick_voxel_attr(base, m8, bit, 1u), base + r8);
                uint32_t sub_before = 0;
                for (uint32_t s = 0; s < bit; ++s) sub_before += (sub_ref >> s) & 1u;
                ASSERT_EQ(rk_svo_brick_sub_attr(base, mv, bit, 77u), base + sub_before);
                // Shared sub-node attributes: the brick's own index, and voxels right at base.
                ASSERT_EQ(rk_svo_brick_sub_attr(base | RK_SVO_BRICK_SHARED_SUB, mv, bit, 77u), 77u);
            }
        }
    }
    // rk_svo_child_rank: exhaustive.
    for (uint32_t mask = 0; mask < 256; ++mask)
        for (uint32_t c = 0; c < 8; ++c) {
            uint32_t r = 0;
            for (uint32_t j = 0; j < c; ++j) r += (mask >> j) & 1u;
            ASSERT_EQ(rk_svo_child_rank(mask, c), r);
            ASSERT_EQ(rk_svo_child_rank(mask | 0xABCD00u, c), r) << "bits above bit 7 are not children";
        }
    // rk_svo_child_index: random cells at every depth and level.
    for (uint32_t depth = 1; depth <= RK_SVO_MAX_DEPTH; ++depth)
        for (int i = 0; i < 200; ++i) {
            const uint32_t side_mask = (1u << depth) - 1u;
            const glm::uvec3 cell(static_cast<uint32_t>(rng.next()) & side_mask, static_cast<uint32_t>(rng.next()) & side_mask,
                                  static_cast<uint32_t>(rng.next()) & side_mask);
            for (uint32_t level = 0; level < depth; ++level) {
                // The octant at level + 1: bit (depth - level - 1) of each coordinate.
                const uint32_t s = depth - level - 1u;
                uint32_t c = 0;
                for (uint32_t a = 0; a < 3; ++a) c |= ((cell[static_cast<int>(a)] >> s) & 1u) << a;
                ASSERT_EQ(rk_svo_child_index(cell, level, depth), c);
            }
        }
    // rk_svo_word_of: descriptors map to themselves, bricks to 2 words each after desc_words.
    for (int i = 0; i < 100000; ++i) {
        const uint32_t D = static_cast<uint32_t>(rng.next() >> 36);
        const uint64_t ord = rng.next() % (uint64_t(D) + (uint64_t(1) << 31) - uint64_t(D) / 2 + 1);
        const uint64_t want = ord < D ? ord : 2 * ord - D;
        if (want >= (uint64_t(1) << 32)) continue;
        ASSERT_EQ(rk_svo_word_of(static_cast<uint32_t>(ord), D), static_cast<uint32_t>(want)) << ord << " " << D;
    }
    EXPECT_EQ(rk_svo_word_of(0u, 0u), 0u);
    EXPECT_EQ(rk_svo_word_of(5u, 5u), 5u);
    EXPECT_EQ(rk_svo_word_of(6u, 5u), 7u);
    // rk_svo_first_child and the descriptor fields.
    for (int i = 0; i < 100000; ++i) {
        const uint32_t ord = static_cast<uint32_t>(rng.next() >> 34), desc = static_cast<uint32_t>(rng.next());
        const uint32_t far_word = static_cast<uint32_t>(rng.next() >> 34);
        const bool far = (desc >> 8) & 1u;
        ASSERT_EQ(rk_svo_is_far(desc), far);
        ASSERT_EQ(rk_svo_child_mask(desc), desc & 0xFFu);
        ASSERT_EQ(rk_svo_rel_ptr(desc), desc >> 9);
        ASSERT_EQ(rk_svo_first_child(ord, desc, far_word), ord + (far ? far_word : (desc >> 9)));
    }
    for (uint32_t d = 1; d <= RK_SVO_MAX_DEPTH; ++d) EXPECT_EQ(rk_svo_brick_levels(d), d < 2 ? d : 2u);
}

// ---- trees: helpers -------------------------------------------------------------------------

struct Voxel {
    glm::uvec3 cell;
    uint64_t attr;
};

std::vector<Voxel> voxels_of(const SvoTree& t)
{
    std::vector<Voxel> v;
    svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t a) { v.push_back({c, a}); });
    return v;
}

SvoBuildOptions fixed_unit_cube(int depth)
{
    SvoBuildOptions o;
    o.depth = depth;
    o.fixed_bounds = true;
    o.bounds_min = glm::vec3(0.0f);
    o.bounds_size = 1.0f;
    o.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL;
    return o;
}

/// Axis quad z = z0 over [x0, x1] x [y0, y1] with uv = (x, y), +z, material `mat`.
rkmesh::SvoMeshData z_quad(double z0, double x0, double x1, double y0, double y1, uint16_t mat = 0)
{
    rkmesh::SvoMeshData m = rkmesh::axis_quad(2, z0, {x0, y0}, {x1, y1});
    for (const glm::vec3& p : m.positions) m.uvs.emplace_back(p.x, p.y);
    m.material_ids.assign(2, mat);
    return m;
}

bool build(const rkmesh::SvoMeshData& m, const SvoBuildOptions& o, SvoTree& t, SvoBuildStats* stats = nullptr)
{
    SvoStatus st;
    const bool ok = build_svo(m.view(), o, t, st, stats);
    EXPECT_TRUE(ok) << st.message;
    if (!ok) return false;
    SvoStatus vs;
    EXPECT_TRUE(svo_validate(t, vs)) << vs.message;
    return vs.ok();
}

/// Largest |code - float64 sRGB code| over the RGB channels (alpha: linear).
double code_error(uint32_t w, const glm::dvec4& want)
{
    double e = 0.0;
    for (int k = 0; k < 3; ++k) e = std::max(e, std::fabs(static_cast<double>(chan(w, k)) - srgb_enc64(clamp01_nan0(want[k])) * 255.0));
    return std::max(e, std::fabs(static_cast<double>(chan(w, 3)) - clamp01_nan0(want[3]) * 255.0));
}

/// The texture as the builder is documented to see it at level 0: bilinear between texel centres
/// (clamp), in linear space; averaged over [u0, u1] along one axis of a 1-D ramp `vals`.
double ramp_average(const std::vector<double>& vals, double u0, double u1)
{
    const int n = static_cast<int>(vals.size());
    auto f = [&](double u) {
        const double x = u * n - 0.5;
        if (x <= 0.0) return vals[0];
        if (x >= n - 1) return vals[static_cast<size_t>(n - 1)];
        const int i = static_cast<int>(std::floor(x));
        const double t = x - i;
        return vals[static_cast<size_t>(i)] * (1.0 - t) + vals[static_cast<size_t>(i + 1)] * t;
    };
    const int steps = 4096;  // midpoint rule: exact for the linear pieces up to the kinks
    double s = 0.0;
    for (int k = 0; k < steps; ++k) s += f(u0 + (u1 - u0) * (k + 0.5) / steps);
    return s / steps;
}

// ---- trees: attribute filtering -------------------------------------------------------------

/// A 256 x 256 RGB gradient: R = column (u), G = row (v), B = 128; quad [0,1]^2 at z = 0.53125
/// (the middle of voxel layer 8 at depth 4), fixed unit root. Each voxel covers 16 x 16 texels.
void gradient_case(bool srgb)
{
    rkmesh::SvoMeshData m = z_quad(0.53125, 0.0, 1.0, 0.0, 1.0);
    const int W = 256;
    std::vector<uint8_t> img(static_cast<size_t>(W * W * 3));
    for (int y = 0; y < W; ++y)
        for (int x = 0; x < W; ++x) {
            uint8_t* p = &img[static_cast<size_t>((y * W + x) * 3)];
            p[0] = static_cast<uint8_t>(x);
            p[1] = static_cast<uint8_t>(y);
            p[2] = 128;
        }
    m.images.push_back(std::move(img));
    SvoImageView tex;
    tex.pixels = m.images[0].data();
    tex.width = tex.height = W;
    tex.channels = 3;
    tex.srgb = srgb;
    tex.wrap_s = tex.wrap_t = SvoWrap::clamp;
    m.textures.push_back(tex);
    SvoMeshMaterial mat;
    mat.base_color_texture = 0;
    m.materials.push_back(mat);
    SvoTree t;
    const int depth = 4;
    if (!build(m, fixed_unit_cube(depth), t)) return;
    std::vector<double> lin(static_cast<size_t>(W));
    for (int i = 0; i < W; ++i) lin[static_cast<size_t>(i)] = srgb ? srgb_dec64(i / 255.0) : i / 255.0;
    const double b128 = srgb ? srgb_dec64(128.0 / 255.0) : 128.0 / 255.0;
    const std::vector<Voxel> vox = voxels_of(t);
    ASSERT_EQ(vox.size(), 256u);
    double max_err = 0.0, max_err_interior = 0.0;
    int bad = 0;
    for (const Voxel& v : vox) {
        ASSERT_EQ(v.cell.z, 8u);
        const double u0 = v.cell.x / 16.0, w0 = v.cell.y / 16.0;
        glm::dvec4 want(ramp_average(lin, u0, u0 + 1.0 / 16), ramp_average(lin, w0, w0 + 1.0 / 16), b128, 1.0);
        if (!srgb) {
            // The ramp is linear, so the average is the centre value.
            EXPECT_NEAR(want.x, (16.0 * v.cell.x + 7.5) / 255.0, 1e-4);
        }
        const uint32_t w = t.color[v.attr];
        const double e = code_error(w, want);
        max_err = std::max(max_err, e);
        const bool edge = v.cell.x == 0 || v.cell.y == 0 || v.cell.x == 15 || v.cell.y == 15;
        if (!edge) max_err_interior = std::max(max_err_interior, e);
        if (e > 1.0 && bad++ < 4)
            ADD_FAILURE() << "voxel (" << v.cell.x << ", " << v.cell.y << "): code (" << chan(w, 0) << ", " << chan(w, 1) << ", "
                          << chan(w, 2) << "), float64 (" << srgb_enc64(want.x) * 255 << ", " << srgb_enc64(want.y) * 255 << ", "
                          << srgb_enc64(want.z) * 255 << ")";
        // Flat quad: normal +z exactly, material 0.
        const glm::vec3 n = rk_svo_unpack_normal(t.normal[v.attr]);
        EXPECT_LT(angle64(glm::dvec3(n), glm::dvec3(0, 0, 1)), 1e-6);
        EXPECT_EQ(t.material[v.attr], 0u);
    }
    std::printf("[ filter   ] gradient (sRGB %d): max |code - float64 code| %.3f (interior voxels %.3f)\n", srgb ? 1 : 0, max_err,
                max_err_interior);
    EXPECT_EQ(bad, 0) << "voxels more than one sRGB step from the float64 area average";
}

TEST(SvoBuildFilter, LinearGradientAveragesToTheVoxelCentreValue) { gradient_case(false); }
TEST(SvoBuildFilter, SrgbGradientAveragesInLinearSpace) { gradient_case(true); }

TEST(SvoBuildFilter, HalfVoxelCheckerAveragesToTheMeanOfItsColours)
{
    // 32 x 32 checker on [0,1]^2 at depth 4: every voxel covers exactly 2 x 2 cells, so its area
    // average is the mean of the two colours (a single point sample would give one of them).
    const glm::u8vec4 A(230, 40, 20, 255), B(20, 90, 240, 255);
    rkmesh::SvoMeshData m = rkmesh::textured_quad(32, A, B);  // sRGB, repeat
    m = rkmesh::transformed(m, 1.0, {0.0, 0.0, 0.53125});
    SvoTree t;
    if (!build(m, fixed_unit_cube(4), t)) return;
    glm::dvec4 want;
    for (int k = 0; k < 3; ++k) want[k] = 0.5 * (srgb_dec64(A[k] / 255.0) + srgb_dec64(B[k] / 255.0));
    want[3] = 1.0;
    const std::vector<Voxel> vox = voxels_of(t);
    ASSERT_EQ(vox.size(), 256u);
    double max_err = 0.0;
    int bad = 0;
    for (const Voxel& v : vox) {
        const uint32_t w = t.color[v.attr];
        const double e = code_error(w, want);
        max_err = std::max(max_err, e);
        if (e > 1.0 && bad++ < 4)
            ADD_FAILURE() << "voxel (" << v.cell.x << ", " << v.cell.y << "): code (" << chan(w, 0) << ", " << chan(w, 1) << ", " << chan(w, 2)
                          << "), area average (float64) (" << srgb_enc64(want.x) * 255 << ", " << srgb_enc64(want.y) * 255 << ", "
                          << srgb_enc64(want.z) * 255 << ")";
    }
    std::printf("[ filter   ] half-voxel checker: max |code - float64 mean code| %.3f sRGB steps\n", max_err);
    EXPECT_EQ(bad, 0);
}

// ---- trees: inner nodes ---------------------------------------------------------------------

/// Recomputes every node of every level from the leaves (equal leaf areas: unweighted means) and
/// compares with what rk_svo_lookup(..., level) finds: colour (float64-nearest code of the mean of
/// the decoded leaf colours), normal (the normalised mean of the leaf normals), material (the
/// strict majority of leaves, or one of the tied ones).
void check_inner_nodes(const SvoTree& t, const char* what)
{
    const std::vector<Voxel> vox = voxels_of(t);
    const std::vector<uint32_t> gw = t.gpu_words();
    const uint32_t bbw = t.gpu_brick_base_word();
    double max_col = 0.0, max_nrm = 0.0;
    int material_mismatch = 0;
    for (uint32_t L = 0; L <= t.depth; ++L) {
        struct Node { glm::dvec4 col{0.0}; glm::dvec3 nrm{0.0}; size_t n = 0; std::map<uint32_t, size_t> mats; glm::uvec3 any; };
        std::map<uint64_t, Node> nodes;
        const uint32_t s = t.depth - L;
        for (const Voxel& v : vox) {
            const glm::uvec3 c = v.cell >> s;
            Node& N = nodes[svo_morton(c)];
            N.col += glm::dvec4(rk_svo_unpack_color(t.color[v.attr]));
            N.nrm += glm::dvec3(rk_svo_unpack_normal(t.normal[v.attr]));
            N.mats[t.material[v.attr]]++;
            N.n++;
            N.any = v.cell;
        }
        ASSERT_EQ(nodes.size(), t.level_nodes[L]) << what << " level " << L;
        for (const auto& kv : nodes) {
            const Node& N = kv.second;
            const rk_svo_hit h = rk_svo_lookup(gw.data(), t.desc_words, bbw, t.depth, N.any, L);
            ASSERT_TRUE(h.found) << what << " level " << L;
            ASSERT_EQ(h.level, L) << what;
            ASSERT_LT(h.attr, t.attr_count);
            const glm::dvec4 mean = N.col / static_cast<double>(N.n);
            const double e = code_error(t.color[h.attr], mean);
            max_col = std::max(max_col, e);
            EXPECT_LE(e, 0.5 + 2e-3) << what << " level " << L << " node (" << (N.any >> s).x << ", " << (N.any >> s).y << ", " << (N.any >> s).z
                                     << ") of " << N.n << " leaves: code (" << chan(t.color[h.attr], 0) << ", " << chan(t.color[h.attr], 1) << ", "
                                     << chan(t.color[h.attr], 2) << "), leaf mean (" << srgb_enc64(mean.x) * 255 << ", "
                                     << srgb_enc64(mean.y) * 255 << ", " << srgb_enc64(mean.z) * 255 << ")";
            const double ne = angle64(N.nrm, glm::dvec3(rk_svo_unpack_normal(t.normal[h.attr])));
            max_nrm = std::max(max_nrm, ne);
            EXPECT_LT(ne, 6.5e-5) << what << " level " << L;
            size_t best = 0;
            for (const auto& mc : N.mats) best = std::max(best, mc.second);
            const uint32_t got = t.material[h.attr];
            const bool ok = N.mats.count(got) && N.mats.at(got) == best;
            if (!ok && material_mismatch++ < 4) {
                std::string counts;
                for (const auto& mc : N.mats) counts += " m" + std::to_string(mc.first) + ":" + std::to_string(mc.second);
                ADD_FAILURE() << what << " level " << L << " node (" << (N.any >> s).x << ", " << (N.any >> s).y << ", " << (N.any >> s).z
                              << "): material " << got << ", leaf counts" << counts << " (equal leaf areas)";
            }
        }
    }
    std::printf("[ inner    ] %s: max node colour error %.4f codes, normal %.3g rad\n", what, max_col, max_nrm);
    EXPECT_EQ(material_mismatch, 0) << what;
}

TEST(SvoBuildFilter, InnerNodesAreTheMeansOfTheirLeaves)
{
    // Two materials on whole-voxel quads at depth 4 (every leaf area 1): material 0 (red) on the
    // columns x < 6, material 1 (blue) on x >= 6, so the root holds 6 : 10 and nodes straddling
    // x = 6 mix the colours; flat +z everywhere.
    rkmesh::SvoMeshData m = z_quad(0.53125, 0.0, 6.0 / 16, 0.0, 1.0, 0);
    rkmesh::SvoMeshData q1 = z_quad(0.53125, 6.0 / 16, 1.0, 0.0, 1.0, 1);
    rkmesh::append(m, q1);
    m.material_ids = {0, 0, 1, 1};
    m.materials.resize(2);
    m.materials[0].values.base_color = glm::vec4(0.8f, 0.1f, 0.05f, 1.0f);
    m.materials[1].values.base_color = glm::vec4(0.05f, 0.2f, 0.9f, 0.5f);
    SvoTree t;
    if (!build(m, fixed_unit_cube(4), t)) return;
    const std::vector<Voxel> vox = voxels_of(t);
    ASSERT_EQ(vox.size(), 256u);
    for (const Voxel& v : vox) {
        const int mat = v.cell.x < 6 ? 0 : 1;
        const glm::vec4 bc = m.materials[static_cast<size_t>(mat)].values.base_color;
        EXPECT_LE(code_error(t.color[v.attr], glm::dvec4(bc)), 0.5 + 1e-3);
        EXPECT_EQ(t.material[v.attr], static_cast<uint32_t>(mat)) << v.cell.x;
        EXPECT_EQ(rk_svo_unpack_normal(t.normal[v.attr]), glm::vec3(0, 0, 1));
    }
    check_inner_nodes(t, "two materials");
    // The root by hand: 6/16 of red, 10/16 of blue (linear means of the quantised leaf colours).
    const glm::dvec4 r(rk_svo_unpack_color(rk_svo_pack_color(m.materials[0].values.base_color)));
    const glm::dvec4 b(rk_svo_unpack_color(rk_svo_pack_color(m.materials[1].values.base_color)));
    EXPECT_LE(code_error(t.color[0], (6.0 * r + 10.0 * b) / 16.0), 0.5 + 1e-3);
    EXPECT_EQ(t.material[0], 1u) << "the root's majority material (10 of 16 columns)";
    EXPECT_EQ(rk_svo_unpack_normal(t.normal[0]), glm::vec3(0, 0, 1));
}

/// Two unit squares across [0,1]^2 in y and z, at x = x_plus facing +x and at x = x_minus facing
/// -x (one material).
rkmesh::SvoMeshData facing_x_walls(float x_plus, float x_minus)
{
    rkmesh::SvoMeshData m;
    const float xs[2] = {x_plus, x_minus};
    for (int side = 0; side < 2; ++side) {
        const uint32_t b = static_cast<uint32_t>(m.positions.size());
        m.positions.push_back({xs[side], 0.0f, 0.0f});
        m.positions.push_back({xs[side], 1.0f, 0.0f});
        m.positions.push_back({xs[side], 1.0f, 1.0f});
        m.positions.push_back({xs[side], 0.0f, 1.0f});
        if (side == 0) m.indices.insert(m.indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});   // (e1 x e2).x > 0: +x
        else m.indices.insert(m.indices.end(), {b, b + 2, b + 1, b, b + 3, b + 2});             // -x
    }
    m.material_ids.assign(4, 0);
    m.materials.resize(1);
    return m;
}

TEST(SvoBuildFilter, OppositeFacesInOneVoxelKeepTheirAxis)
{
    // Both sides of a thin wall inside one layer of voxels: x = 0.53125 facing +x and x = 0.546875
    // facing -x (depth 4: voxels 1/16 wide, both in layer x = 8). Their area-weighted normals cancel
    // exactly; the voxel then takes the normal of its largest contribution (+x or -x), not the
    // direction the zero vector encodes (+z).
    const rkmesh::SvoMeshData m = facing_x_walls(0.53125f, 0.546875f);
    SvoTree t;
    if (!build(m, fixed_unit_cube(4), t)) return;
    const std::vector<Voxel> vox = voxels_of(t);
    ASSERT_EQ(vox.size(), 256u);
    for (const Voxel& v : vox) {
        ASSERT_EQ(v.cell.x, 8u);
        const glm::vec3 n = rk_svo_unpack_normal(t.normal[v.attr]);
        EXPECT_GT(std::abs(n.x), 0.999f) << "voxel (" << v.cell.y << ", " << v.cell.z << "): normal " << n.x << " " << n.y << " " << n.z;
    }
}

TEST(SvoBuildFilter, InnerNodesWhoseNormalsCancelKeepAnAxis)
{
    // Two walls facing each other in neighbouring voxels (depth 4: x = 8.5/16 facing +x in voxel 8,
    // x = 9.5/16 facing -x in voxel 9), of equal area: every node above both holds normals that
    // cancel exactly. Like a leaf, such a node takes the normal of its heaviest part (+x or -x),
    // not the direction the zero vector encodes (+z).
    const rkmesh::SvoMeshData m = facing_x_walls(8.5f / 16.0f, 9.5f / 16.0f);
    SvoTree t;
    if (!build(m, fixed_unit_cube(4), t)) return;
    const std::vector<Voxel> vox = voxels_of(t);
    ASSERT_EQ(vox.size(), 512u);
    const std::vector<uint32_t> gw = t.gpu_words();
    const uint32_t bbw = t.gpu_brick_base_word();
    for (uint32_t L = 0; L <= t.depth; ++L)
        for (const Voxel& v : vox) {
            const rk_svo_hit h = rk_svo_lookup(gw.data(), t.desc_words, bbw, t.depth, v.cell, L);
            ASSERT_TRUE(h.found);
            const glm::vec3 n = rk_svo_unpack_normal(t.normal[h.attr]);
            ASSERT_GT(std::abs(n.x), 0.999f) << "level " << L << ", voxel (" << v.cell.x << ", " << v.cell.y << ", " << v.cell.z
                                             << "): normal " << n.x << " " << n.y << " " << n.z;
            if (L == t.depth) {
                EXPECT_EQ(n.x > 0.0f, v.cell.x == 8u) << "a leaf keeps its own wall's normal";
            }
        }
}

TEST(SvoBuildFilter, InnerNodesOfTheGradientQuad)
{
    rkmesh::SvoMeshData m = z_quad(0.53125, 0.0, 1.0, 0.0, 1.0);
    const int W = 64;
    std::vector<uint8_t> img(static_cast<size_t>(W * W * 4));
    for (int y = 0; y < W; ++y)
        for (int x = 0; x < W; ++x) {
            uint8_t* p = &img[static_cast<size_t>((y * W + x) * 4)];
            p[0] = static_cast<uint8_t>(4 * x);
            p[1] = static_cast<uint8_t>(255 - 4 * y);
            p[2] = static_cast<uint8_t>((x * y) & 255);
            p[3] = static_cast<uint8_t>(255 - x);
        }
    m.images.push_back(std::move(img));
    SvoImageView tex;
    tex.pixels = m.images[0].data();
    tex.width = tex.height = W;
    m.textures.push_back(tex);
    m.materials.resize(1);
    m.materials[0].base_color_texture = 0;
    for (int depth : {3, 4, 5}) {
        SvoTree t;
        if (!build(m, fixed_unit_cube(depth), t)) return;
        check_inner_nodes(t, ("gradient depth " + std::to_string(depth)).c_str());
    }
}

// ---- trees: far pointers ----------------------------------------------------------------------

TEST(SvoBuildTree, ForcedFarPointersGiveTheSameTree)
{
    const rkmesh::SvoMeshData m = rkmesh::icosphere(3);
    SvoBuildOptions o;
    o.depth = 7;
    o.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL;
    SvoTree ref;
    if (!build(m, o, ref)) return;
    EXPECT_EQ(ref.far_slots, 0u);
    const std::vector<Voxel> rv = voxels_of(ref);
    const std::vector<uint32_t> rg = ref.gpu_words();
    for (uint32_t bits : {4u, 5u, 8u}) {
        o.pointer_bits = bits;
        SvoTree t;
        if (!build(m, o, t)) return;
        std::printf("[ far      ] pointer_bits %u: %u far slots of %u descriptor words\n", bits, t.far_slots, t.desc_words);
        if (bits <= 5) { EXPECT_GT(t.far_slots, 0u); }
        EXPECT_EQ(t.pointer_bits, bits);
        EXPECT_EQ(t.desc_words, ref.desc_words + t.far_slots);
        EXPECT_EQ(t.level_nodes, ref.level_nodes);
        EXPECT_EQ(t.voxel_count, ref.voxel_count);
        const std::vector<Voxel> tv = voxels_of(t);
        ASSERT_EQ(tv.size(), rv.size());
        for (size_t i = 0; i < tv.size(); ++i) {
            ASSERT_EQ(tv[i].cell, rv[i].cell);
            ASSERT_EQ(t.color[tv[i].attr], ref.color[rv[i].attr]);
            ASSERT_EQ(t.normal[tv[i].attr], ref.normal[rv[i].attr]);
            ASSERT_EQ(t.material[tv[i].attr], ref.material[rv[i].attr]);
        }
        // Every node of every level: the same attributes through rk_svo_lookup.
        const std::vector<uint32_t> g = t.gpu_words();
        for (uint32_t L = 0; L <= t.depth; ++L)
            for (size_t i = 0; i < rv.size(); i += 3) {
                const rk_svo_hit a = rk_svo_lookup(rg.data(), ref.desc_words, ref.gpu_brick_base_word(), ref.depth, rv[i].cell, L);
                const rk_svo_hit b = rk_svo_lookup(g.data(), t.desc_words, t.gpu_brick_base_word(), t.depth, rv[i].cell, L);
                ASSERT_TRUE(a.found && b.found);
                ASSERT_EQ(a.level, b.level);
                ASSERT_EQ(ref.color[a.attr], t.color[b.attr]);
                ASSERT_EQ(ref.normal[a.attr], t.normal[b.attr]);
                ASSERT_EQ(ref.material[a.attr], t.material[b.attr]);
            }
    }
}

// ---- trees: small depths by hand, depth 16 --------------------------------------------------

rkmesh::SvoMeshData corner_triangle()
{
    rkmesh::SvoMeshData m;
    m.positions = {{0.1f, 0.1f, 0.1f}, {0.3f, 0.1f, 0.1f}, {0.1f, 0.3f, 0.1f}};
    m.indices = {0, 1, 2};
    return m;
}

TEST(SvoBuildTree, Depth1TreeByHand)
{
    SvoTree t;
    if (!build(corner_triangle(), fixed_unit_cube(1), t)) return;
    EXPECT_EQ(t.depth, 1u);
    EXPECT_EQ(t.brick_levels, 1u);
    EXPECT_EQ(t.desc_words, 0u);
    EXPECT_EQ(t.far_slots, 0u);
    EXPECT_EQ(t.brick_count, 1u);
    EXPECT_EQ(t.words, (std::vector<uint32_t>{1u, 0u}));  // voxel (0,0,0): bit 0 of a 2^3 brick
    EXPECT_EQ(t.level_nodes, (std::vector<uint64_t>{1u, 1u}));
    EXPECT_EQ(t.voxel_count, 1u);
    EXPECT_EQ(t.brick_base, (std::vector<uint32_t>{1u}));
    EXPECT_EQ(t.attr_count, 2u);  // the brick (root), its voxel
    EXPECT_EQ(t.color, (std::vector<uint32_t>{0xFFFFFFFFu, 0xFFFFFFFFu}));  // default white material
    EXPECT_EQ(t.normal, (std::vector<uint32_t>{0u, 0u}));                   // +z: u = v = 0
    EXPECT_EQ(t.material, (std::vector<uint32_t>{0u, 0u}));
    EXPECT_EQ(t.root_min, glm::vec3(0.0f));
    EXPECT_EQ(t.root_size, 1.0f);
}

TEST(SvoBuildTree, Depth2And3TreesByHand)
{
    {
        // Voxels of 0.25: the triangle (x + y <= 0.4 in [0.1, 0.3]^2, z = 0.1) covers (0,0), (1,0), (0,1).
        SvoTree t;
        if (!build(corner_triangle(), fixed_unit_cube(2), t)) return;
        EXPECT_EQ(t.brick_levels, 2u);
        EXPECT_EQ(t.desc_words, 0u);
        EXPECT_EQ(t.brick_count, 1u);
        EXPECT_EQ(t.words, (std::vector<uint32_t>{0x7u, 0u}));
        EXPECT_EQ(t.level_nodes, (std::vector<uint64_t>{1u, 1u, 3u}));
        EXPECT_EQ(t.brick_base, (std::vector<uint32_t>{1u}));
        EXPECT_EQ(t.attr_count, 5u);  // brick, 1 sub-node, 3 voxels
        EXPECT_EQ(t.voxel_count, 3u);
    }
    {
        // Voxels of 0.125: cells (i, j, 0), i, j <= 2, i + j <= 3 (8 voxels), all in child 0.
        SvoTree t;
        if (!build(corner_triangle(), fixed_unit_cube(3), t)) return;
        EXPECT_EQ(t.desc_words, 1u);
        EXPECT_EQ(t.brick_count, 1u);
        uint64_t mask = 0;
        for (uint32_t j = 0; j <= 2; ++j)
            for (uint32_t i = 0; i <= 2; ++i)
                if (i + j <= 3) mask |= 1ull << brick_bit_ref(glm::uvec3(i, j, 0), 2);
        EXPECT_EQ(mask, 0x3050Full);
        // Root: child 0, near pointer +1 to the brick (ordinal 1, words 1..2).
        EXPECT_EQ(t.words, (std::vector<uint32_t>{1u | (1u << 9), 0x3050Fu, 0u}));
        EXPECT_EQ(t.level_nodes, (std::vector<uint64_t>{1u, 1u, 3u, 8u}));
        EXPECT_EQ(t.brick_base, (std::vector<uint32_t>{2u}));
        EXPECT_EQ(t.attr_count, 13u);  // root, brick, 3 sub-nodes, 8 voxels
    }
}

TEST(SvoBuildTree, Depth16SmallTriangleIsValidAndEveryVoxelIsFound)
{
    rkmesh::SvoMeshData m;
    const glm::dvec3 p0(0.30001, 0.40002, 0.50003);
    m.positions = {rkmesh::to_vec3(p0.x, p0.y, p0.z), rkmesh::to_vec3(p0.x + 4e-4, p0.y + 1e-4, p0.z),
                   rkmesh::to_vec3(p0.x, p0.y + 3e-4, p0.z + 2e-4)};
    m.indices = {0, 1, 2};
    SvoBuildOptions o = fixed_unit_cube(16);
    SvoTree t;
    if (!build(m, o, t)) return;
    EXPECT_EQ(t.depth, 16u);
    const std::vector<Voxel> vox = voxels_of(t);
    ASSERT_GT(vox.size(), 100u);
    EXPECT_EQ(vox.size(), t.voxel_count);
    EXPECT_EQ(t.level_nodes[0], 1u);
    for (uint32_t L = 0; L + 1 < t.level_nodes.size(); ++L) EXPECT_LE(t.level_nodes[L], t.level_nodes[L + 1]);
    const std::vector<uint32_t> g = t.gpu_words();
    std::map<uint64_t, uint64_t> set;
    glm::uvec3 lo(~0u), hi(0u);
    for (const Voxel& v : vox) {
        set[svo_morton(v.cell)] = v.attr;
        lo = glm::min(lo, v.cell);
        hi = glm::max(hi, v.cell);
        const rk_svo_hit h = rk_svo_lookup(g.data(), t.desc_words, t.gpu_brick_base_word(), 16u, v.cell, 16u);
        ASSERT_TRUE(h.found);
        ASSERT_EQ(h.level, 16u);
        ASSERT_EQ(h.attr, v.attr);
    }
    // The voxel set vs the public exact predicate on the snapped triangle, over its bounding box + 1.
    int64_t tv[3][3];
    for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) tv[k][a] = svo_snap_coordinate(m.positions[static_cast<size_t>(k)][a], 0.0f, 1.0f, 16u);
    size_t cells = 0;
    for (uint32_t z = lo.z - 1; z <= hi.z + 1; ++z)
        for (uint32_t y = lo.y - 1; y <= hi.y + 1; ++y)
            for (uint32_t x = lo.x - 1; x <= hi.x + 1; ++x) {
                const int64_t S = int64_t(1) << kSvoSubvoxelBits;
                const int64_t bmin[3] = {int64_t(x) * S, int64_t(y) * S, int64_t(z) * S};
                const bool want = svo_triangle_box_overlap(tv, bmin, S);
                const bool have = set.count(svo_morton(glm::uvec3(x, y, z))) != 0;
                ASSERT_EQ(have, want) << x << " " << y << " " << z;
                const rk_svo_hit h = rk_svo_lookup(g.data(), t.desc_words, t.gpu_brick_base_word(), 16u, glm::uvec3(x, y, z), 16u);
                ASSERT_EQ(h.found, want);
                ++cells;
            }
    std::printf("[ depth 16 ] %zu voxels, %zu cells checked, %zu words\n", vox.size(), cells, t.words.size());
}

// ---- trees: size, memory, progress, options -----------------------------------------------

TEST(SvoBuildTree, SurfaceStructureIsAtMostOneBytePerVoxel)
{
    const rkmesh::SvoMeshData m = rkmesh::icosphere(3);
    SvoBuildOptions o;
    o.depth = 10;
    o.attributes = 0;
    SvoTree t;
    SvoBuildStats stats;
    if (!build(m, o, t, &stats)) return;
    const double bpv = static_cast<double>(t.structure_bytes()) / static_cast<double>(t.voxel_count);
    std::printf("[ size     ] icosphere(3) depth 10: %llu voxels, %llu structure bytes = %.4f bytes/voxel (%.2f s)\n",
                static_cast<unsigned long long>(t.voxel_count), static_cast<unsigned long long>(t.structure_bytes()), bpv,
                stats.seconds_total);
    EXPECT_GT(t.voxel_count, 1000000u);
    EXPECT_LE(bpv, 1.0);
}

TEST(SvoBuildOptionsTest, EstimateBoundsThePeakAndTheBudgetIsEnforced)
{
    struct Case { const char* name; rkmesh::SvoMeshData mesh; int depth; SvoFill fill; };
    std::vector<Case> cases;
    cases.push_back({"icosphere(3) d6", rkmesh::icosphere(3), 6, SvoFill::surface});
    cases.push_back({"icosphere(3) d8", rkmesh::icosphere(3), 8, SvoFill::surface});
    cases.push_back({"torus solid d7", rkmesh::torus(48, 24), 7, SvoFill::solid});
    cases.push_back({"menger(2) solid d6", rkmesh::menger_sponge(2), 6, SvoFill::solid});
    cases.push_back({"textured quad d6", rkmesh::textured_quad(64), 6, SvoFill::surface});
    cases.push_back({"soup d7", rkmesh::random_soup(300), 7, SvoFill::surface});
    for (const Case& c : cases) {
        SvoBuildOptions o;
        o.depth = c.depth;
        o.fill = c.fill;
        o.threads = 2;
        SvoStatus st;
        const uint64_t est = estimate_svo_memory(c.mesh.view(), o, st);
        ASSERT_TRUE(st.ok()) << st.message;
        SvoTree t;
        SvoBuildStats stats;
        ASSERT_TRUE(build_svo(c.mesh.view(), o, t, st, &stats)) << st.message;
        std::printf("[ memory   ] %-20s estimate %10llu  peak %10llu  (%.1fx)\n", c.name, static_cast<unsigned long long>(est),
                    static_cast<unsigned long long>(stats.peak_bytes), static_cast<double>(est) / static_cast<double>(std::max<uint64_t>(stats.peak_bytes, 1)));
        EXPECT_GE(est, stats.peak_bytes) << c.name;
        EXPECT_GT(stats.peak_bytes, 0u) << c.name;
        EXPECT_EQ(stats.estimated_peak_bytes, est) << c.name;
        // A budget of exactly the estimate passes; one byte less fails before building.
        o.memory_budget = est;
        SvoTree t2;
        EXPECT_TRUE(build_svo(c.mesh.view(), o, t2, st)) << c.name << ": " << st.message;
        EXPECT_EQ(t2.words, t.words);
        o.memory_budget = est - 1;
        SvoTree t3;
        EXPECT_FALSE(build_svo(c.mesh.view(), o, t3, st));
        EXPECT_EQ(st.code, SvoError::budget_exceeded) << c.name;
        EXPECT_FALSE(st.message.empty());
    }
}

TEST(SvoBuildOptionsTest, ProgressIsMonotoneEndsAtOneAndCancels)
{
    const rkmesh::SvoMeshData m = rkmesh::icosphere(3);
    SvoBuildOptions o;
    o.depth = 8;
    o.threads = 2;
    std::vector<std::pair<float, std::string>> calls;
    o.progress = [&](float f, const char* stage) {
        calls.emplace_back(f, stage ? stage : "");
        return true;
    };
    SvoTree t;
    SvoStatus st;
    ASSERT_TRUE(build_svo(m.view(), o, t, st)) << st.message;
    ASSERT_GE(calls.size(), 3u);
    for (size_t i = 1; i < calls.size(); ++i)
        EXPECT_LE(calls[i - 1].first, calls[i].first) << "call " << i << " (" << calls[i].second << ")";
    EXPECT_GE(calls.front().first, 0.0f);
    EXPECT_EQ(calls.back().first, 1.0f);
    // Returning false at any call but the last cancels.
    const size_t n = calls.size();
    for (size_t k = 0; k + 1 < n; ++k) {
        size_t seen = 0;
        o.progress = [&](float, const char*) { return seen++ != k; };
        SvoTree tc;
        EXPECT_FALSE(build_svo(m.view(), o, tc, st)) << "cancel at call " << k;
        EXPECT_EQ(st.code, SvoError::cancelled) << "cancel at call " << k;
        EXPECT_FALSE(st.message.empty());
    }
}

TEST(SvoBuildOptionsTest, InvalidOptionsFail)
{
    rkmesh::SvoMeshData m = rkmesh::icosphere(1);
    auto expect_invalid = [&](const SvoBuildOptions& o, const rkmesh::SvoMeshData& mesh, const char* what) {
        SvoTree t;
        SvoStatus st;
        EXPECT_FALSE(build_svo(mesh.view(), o, t, st)) << what;
        EXPECT_EQ(st.code, SvoError::invalid_argument) << what << ": " << st.message;
        EXPECT_FALSE(st.message.empty()) << what;
        SvoStatus es;
        EXPECT_EQ(estimate_svo_memory(mesh.view(), o, es), 0u) << what;
        EXPECT_EQ(es.code, SvoError::invalid_argument) << what;
    };
    SvoBuildOptions o;
    o.depth = 0;
    expect_invalid(o, m, "depth 0");
    o.depth = 21;
    expect_invalid(o, m, "depth 21");
    o.depth = -3;
    expect_invalid(o, m, "depth -3");
    o = SvoBuildOptions{};
    o.depth = 5;
    o.pointer_bits = 3;
    expect_invalid(o, m, "pointer_bits 3");
    o.pointer_bits = 24;
    expect_invalid(o, m, "pointer_bits 24");
    o = SvoBuildOptions{};
    o.depth = 5;
    o.voxel_size = std::numeric_limits<float>::quiet_NaN();
    expect_invalid(o, m, "NaN voxel_size");
    o.voxel_size = std::numeric_limits<float>::infinity();
    expect_invalid(o, m, "infinite voxel_size");
    o.voxel_size = 1e-9f;  // would need more than 20 levels for a size-2 root
    expect_invalid(o, m, "voxel_size too small");
    o = SvoBuildOptions{};
    o.depth = 5;
    o.attributes = 8;
    expect_invalid(o, m, "unknown attribute bit");
    o = SvoBuildOptions{};
    o.depth = 5;
    for (float ior : {0.0f, -1.5f, std::numeric_limits<float>::quiet_NaN()}) {
        rkmesh::SvoMeshData mm = m;
        mm.materials.resize(1);
        mm.materials[0].values.ior = ior;
        expect_invalid(o, mm, ("material ior " + std::to_string(ior)).c_str());
    }
    // voxel_size picks the depth: root 2 (icosphere radius 1), 2 / 2^5 = 0.0625.
    o = SvoBuildOptions{};
    o.voxel_size = 0.0625f;
    SvoTree t;
    SvoStatus st;
    ASSERT_TRUE(build_svo(m.view(), o, t, st)) << st.message;
    EXPECT_EQ(t.depth, 5u);
}

void expect_same_tree(const SvoTree& a, const SvoTree& b, const char* what)
{
    EXPECT_EQ(a.depth, b.depth) << what;
    EXPECT_EQ(a.desc_words, b.desc_words) << what;
    EXPECT_EQ(a.far_slots, b.far_slots) << what;
    EXPECT_EQ(a.brick_count, b.brick_count) << what;
    EXPECT_EQ(a.voxel_count, b.voxel_count) << what;
    EXPECT_EQ(a.attr_count, b.attr_count) << what;
    EXPECT_EQ(a.level_nodes, b.level_nodes) << what;
    EXPECT_TRUE(a.words == b.words) << what << ": words differ";
    EXPECT_TRUE(a.brick_base == b.brick_base) << what << ": brick_base differs";
    EXPECT_TRUE(a.color == b.color) << what << ": color stream differs";
    EXPECT_TRUE(a.normal == b.normal) << what << ": normal stream differs";
    EXPECT_TRUE(a.material == b.material) << what << ": material stream differs";
    EXPECT_EQ(bits_of(a.root_size), bits_of(b.root_size)) << what;
    EXPECT_EQ(a.root_min, b.root_min) << what;
}

TEST(SvoBuildOptionsTest, CustomParallelForGivesTheSameTreeAsThePool)
{
    rkmesh::SvoMeshData sphere = rkmesh::icosphere(3);
    // Vertex normals (perturbed) so that the normal sums are not trivially equal.
    for (const glm::vec3& p : sphere.positions) sphere.normals.push_back(glm::normalize(p + glm::vec3(0.1f, -0.2f, 0.05f)));
    const rkmesh::SvoMeshData quad = rkmesh::transformed(rkmesh::textured_quad(16), 1.0, {0.013, 0.021, 0.37});
    struct Case { const char* name; const rkmesh::SvoMeshData* mesh; int depth; SvoFill fill; };
    const Case cases[] = {{"icosphere d7", &sphere, 7, SvoFill::surface}, {"icosphere solid d6", &sphere, 6, SvoFill::solid},
                          {"textured quad d7", &quad, 7, SvoFill::surface}};
    for (const Case& c : cases) {
        SvoBuildOptions o;
        o.depth = c.depth;
        o.fill = c.fill;
        o.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL;
        o.threads = 1;
        SvoTree t1, t2, tr, tt;
        if (!build(*c.mesh, o, t1)) { return; }
        o.threads = 2;
        if (!build(*c.mesh, o, t2)) { return; }
        // Serial, in reverse order.
        std::atomic<size_t> calls{0};
        o.parallel_for = [&](size_t n, const std::function<void(size_t)>& body) {
            ++calls;
            for (size_t i = n; i-- > 0;) body(i);
        };
        if (!build(*c.mesh, o, tr)) { return; }
        EXPECT_GT(calls.load(), 0u);
        // Three threads, strided.
        o.parallel_for = [](size_t n, const std::function<void(size_t)>& body) {
            std::vector<std::thread> th;
            for (size_t k = 0; k < 3; ++k)
                th.emplace_back([&, k]() {
                    for (size_t i = k; i < n; i += 3) body(i);
                });
            for (std::thread& x : th) x.join();
        };
        if (!build(*c.mesh, o, tt)) { return; }
        expect_same_tree(t1, t2, (std::string(c.name) + ": 1 vs 2 threads").c_str());
        expect_same_tree(t1, tr, (std::string(c.name) + ": 1 thread vs custom reverse").c_str());
        expect_same_tree(t1, tt, (std::string(c.name) + ": 1 thread vs custom 3 threads").c_str());
    }
}

}  // namespace

// The portable bitCount / findMSB of common.glsl (GLSL ES 3.00 has no built-ins) against glm's,
// over every single-bit and all-ones-below pattern, their neighbours, and 2^22 random words.
TEST(CommonGlsl, PortableBitCountAndFindMsbMatchTheBuiltins)
{
    std::vector<uint32_t> v = {0u, 1u, 2u, 3u, 0xFFFFFFFFu, 0x80000000u, 0x7FFFFFFFu, 0x55555555u, 0xAAAAAAAAu};
    for (int b = 0; b < 32; ++b) {
        const uint32_t p = 1u << b;
        for (uint32_t x : {p, p - 1u, p + 1u, ~p, p | (p >> 1)}) v.push_back(x);
    }
    std::mt19937 rng(11);
    for (int i = 0; i < (1 << 22); ++i) v.push_back(static_cast<uint32_t>(rng()));
    for (uint32_t x : v) {
        ASSERT_EQ(raykit::rk_bit_count_portable(x), glm::bitCount(x)) << x;
        ASSERT_EQ(raykit::rk_find_msb_portable(x), glm::findMSB(x)) << x;
    }
}
