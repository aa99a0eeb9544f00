// GPU parity for shaders/raykit/gbuffer.glsl (see parity.hpp): every shared function on the driver
// against its C++ build, over random and adversarial inputs (±0, denormals, FLT_MAX, NaN-free
// extremes). The half conversions and the packing of given points must match bit for bit (except
// at exact ties, which the rounding rule settles the same way on both); the octahedral words go
// through a division and a normalisation, whose last-ulp differences between builds may move a
// point across a code boundary, so they are compared as values (one code apart at most).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/gbuffer.hpp"

using namespace raykit;
namespace dom = parity::dom;

// A uint output as two exactly representable floats; a word from two inputs in [0, 1].
#define RK_GB_EMIT_U(k, v) o[k] = float((v) & 65535u); o[k + 1] = float((v) >> 16u);
#define RK_PARITY_X(...) RK_PARITY(__VA_ARGS__)
#define RK_GB_WORD(i, j) (uint(clamp(a[i], 0.0f, 1.0f) * 65535.0f) | (uint(clamp(a[j], 0.0f, 1.0f) * 65535.0f) << 16u))

namespace {

parity::Domain any() { return {-4.0f, 4.0f, false, {1.0f, -1.0f, 0.5f, -0.5f, 1e-3f, -1e-3f}}; }
parity::Domain bits() { return {1.0f, 17.0f, false, {8.0f, 10.0f, 12.0f, 16.0f, 2.0f}}; }
parity::Domain depth() { return {0.0f, 1.0f, false, {0.0f, 1.0f, 0.5f, 0.99999994f, 1e-7f}}; }
parity::Domain planes() { return {0.01f, 1e5f, true, {0.1f, 1000.0f}}; }
parity::Domain wide() { return {-70000.0f, 70000.0f, false, {65504.0f, 65520.0f, 6.1035156e-5f, 5.9604645e-8f, 2.9802322e-8f, 1234.5f}}; }

}  // namespace

TEST(GpuParity, Gbuffer)
{
    const char* G = "raykit/gbuffer.glsl";
    struct Entry {
        parity::Case c;
        std::vector<int> exact;
    };
    std::vector<Entry> cases;
    cases.push_back({RK_PARITY_X("rk_gb_oct_encode / decode", G, (any(), any(), any()), 5,
                               vec2 p = rk_gb_oct_encode(vec3(a[0], a[1], a[2]));
                               vec3 d = rk_gb_oct_decode(p);
                               o[0] = p.x; o[1] = p.y; o[2] = d.x; o[3] = d.y; o[4] = d.z;),
                     {}});
    cases.push_back({RK_PARITY_X("rk_oct_fold (common.glsl)", G, (any(), any()), 2,
                                 vec2 f = rk_oct_fold(a[0], a[1]);
                                 o[0] = f.x; o[1] = f.y;),
                     {0, 1}});
    cases.push_back({RK_PARITY_X("rk_gb_oct_decode (any p)", G, (any(), any()), 3,
                               vec3 d = rk_gb_oct_decode(vec2(a[0], a[1]));
                               o[0] = d.x; o[1] = d.y; o[2] = d.z;),
                     {}});
    cases.push_back({RK_PARITY_X("rk_gb_hemi_encode / decode", G, (any(), any(), any()), 5,
                               vec2 p = rk_gb_hemi_encode(vec3(a[0], a[1], a[2]));
                               vec3 d = rk_gb_hemi_decode(p);
                               o[0] = p.x; o[1] = p.y; o[2] = d.x; o[3] = d.y; o[4] = d.z;),
                     {}});
    cases.push_back({RK_PARITY_X("rk_gb_lambert_encode / decode", G, (any(), any(), any()), 5,
                               vec2 p = rk_gb_lambert_encode(vec3(a[0], a[1], a[2]));
                               vec3 d = rk_gb_lambert_decode(p);
                               o[0] = p.x; o[1] = p.y; o[2] = d.x; o[3] = d.y; o[4] = d.z;),
                     {}});
    // Packed words: the codes must agree exactly, except where the float product p * (2^b - 1) sits
    // within rounding of a tie (a tie rule below accepts neighbouring codes only then).
    cases.push_back({RK_PARITY_X("rk_gb_pack_snorm2 / unorm2 and unpack", G, (any(), any(), bits()), 8,
                               uint b = uint(clamp(a[2], 1.0f, 17.0f));
                               uint ws = rk_gb_pack_snorm2(vec2(a[0], a[1]), b);
                               uint wu = rk_gb_pack_unorm2(vec2(a[0], a[1]), b);
                               RK_GB_EMIT_U(0, ws) RK_GB_EMIT_U(2, wu)
                               vec2 s = rk_gb_unpack_snorm2(ws, b);
                               vec2 u = rk_gb_unpack_unorm2(wu, b);
                               o[4] = s.x; o[5] = s.y; o[6] = u.x; o[7] = u.y;),
                     {0, 1, 2, 3}});
    cases.push_back({RK_PARITY_X("rk_gb_oct_pack_snorm / precise / unorm", G, (any(), any(), any(), bits()), 9,
                               vec3 n = vec3(a[0], a[1], a[2]);
                               uint b = uint(clamp(a[3], 1.0f, 17.0f));
                               uint ws = rk_gb_oct_pack_snorm(n, b);
                               uint wp = rk_gb_oct_pack_snorm_precise(n, b);
                               uint wu = rk_gb_oct_pack_unorm(n, b);
                               RK_GB_EMIT_U(0, ws) RK_GB_EMIT_U(2, wp) RK_GB_EMIT_U(4, wu)
                               vec3 d = rk_gb_oct_unpack_snorm(wp, b);
                               o[6] = d.x; o[7] = d.y; o[8] = d.z;),
                     {}});
    cases.push_back({RK_PARITY_X("rk_gb_oct_unpack_snorm / unorm (any word)", G, (dom::unit(), dom::unit(), bits()), 6,
                               uint b = uint(clamp(a[2], 1.0f, 17.0f));
                               vec3 s = rk_gb_oct_unpack_snorm(RK_GB_WORD(0, 1), b);
                               vec3 u = rk_gb_oct_unpack_unorm(RK_GB_WORD(0, 1), b);
                               o[0] = s.x; o[1] = s.y; o[2] = s.z; o[3] = u.x; o[4] = u.y; o[5] = u.z;),
                     {}});
    cases.push_back({RK_PARITY_X("rk_gb_quantize_snorm2 / unorm2", G, (any(), any(), bits()), 4,
                               uint b = uint(clamp(a[2], 1.0f, 17.0f));
                               vec2 s = rk_gb_quantize_snorm2(vec2(a[0], a[1]), b);
                               vec2 u = rk_gb_quantize_unorm2(vec2(a[0], a[1]), b);
                               o[0] = s.x; o[1] = s.y; o[2] = u.x; o[3] = u.y;),
                     {}});
    cases.push_back({RK_PARITY_X("rk_gb_half_bits / value, pack / unpack_half2", G, (wide(), wide()), 6,
                               uint w = rk_gb_pack_half2(a[0], a[1]);
                               RK_GB_EMIT_U(0, w)
                               vec2 v = rk_gb_unpack_half2(w);
                               o[2] = v.x; o[3] = v.y;
                               o[4] = float(rk_gb_half_bits(a[0]));
                               o[5] = rk_gb_half_value(RK_GB_WORD(1, 1) & 65535u);),
                     {0, 1, 2, 3, 4, 5}});
    cases.push_back({RK_PARITY_X("rk_gb_depth_params / linear_depth", G, (planes(), planes(), depth(), dom::unit()), 4,
                               vec3 k = rk_gb_depth_params(a[0], a[1], a[3] > 0.5f);
                               o[0] = k.x; o[1] = k.y; o[2] = k.z;
                               o[3] = rk_gb_linear_depth(a[2], k);),
                     {}});
    // The ray's scale is bounded in the body (the harness's extremes would overflow 1.5 * a there).
    // Offsets beyond the NDC range keep ndc * ray.x + ray.z away from cancellation, where a driver
    // that fuses the multiply-add (allowed by GLSL) rounds differently.
    cases.push_back({RK_PARITY_X("rk_gb_view_pos", G, (dom::signed_unit(), dom::signed_unit(), planes(), any(), any()), 3,
                               float rx = clamp(a[3], -4.0f, 4.0f); float ry = clamp(a[4], -4.0f, 4.0f);
                               // The documented domain: ray and NDC components 0 or of magnitude
                               // >= 2^-20 and 2^-40 (products then stay normal on flushing drivers).
                               rx = abs(rx) >= 9.5367431640625e-7f ? rx : 0.0f;
                               ry = abs(ry) >= 9.5367431640625e-7f ? ry : 0.0f;
                               float nx = abs(a[0]) >= 9.094947017729282e-13f ? a[0] : 0.0f;
                               float ny = abs(a[1]) >= 9.094947017729282e-13f ? a[1] : 0.0f;
                               vec3 p = rk_gb_view_pos(vec2(nx, ny), a[2], vec4(rx, ry, 1.5f * rx, -1.5f * ry));
                               o[0] = p.x; o[1] = p.y; o[2] = p.z;),
                     {}});
    // Near the maps' singular points (the hemisphere's equator, Lambert's rim at -z) the decode
    // turns ulp differences of sqrt / inversesqrt into angles of up to the documented bounds
    // (5.5e-4 and 1.3e-3 rad): there, rows whose encodings agree within 4 ulp and whose directions agree
    // within those bounds are ties.
    auto near_singular = [](double bound) {
        return [bound](const float*, const float* g, const float* h) {
            const glm::dvec3 a(g[2], g[3], g[4]), b(h[2], h[3], h[4]);
            const double ang = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
            return std::abs(double(g[0]) - h[0]) <= 5e-7 && std::abs(double(g[1]) - h[1]) <= 5e-7 && ang <= bound;
        };
    };
    for (Entry& e : cases) {
        if (e.c.name == "rk_gb_hemi_encode / decode") e.c.tie = near_singular(6e-4);
        if (e.c.name == "rk_gb_lambert_encode / decode") e.c.tie = near_singular(1.5e-3);
        // The word columns of the pack case: a tie is a row whose codes differ by one step on one
        // axis, the float product being within rounding of a half-way point.
        if (e.c.name == "rk_gb_pack_snorm2 / unorm2 and unpack") {
            // A tie only where an input's product lies within a few ulps of a half-way point (a
            // driver may round the product itself differently) and the codes are neighbours.
            e.c.tie = [](const float* in, const float* g, const float* h) {
                const uint32_t b = std::min(std::max(static_cast<uint32_t>(std::min(std::max(in[2], 1.0f), 17.0f)), 1u), 16u);
                const uint32_t bs = std::max(b, 2u);
                const double s = double((1u << (bs - 1u)) - 1u), su = double((1u << b) - 1u);
                bool near_half = false;
                for (int a = 0; a < 2; ++a) {
                    const double c = std::min(std::max(double(in[a]), -1.0), 1.0);
                    for (double x : {std::abs(c * s), (c * 0.5 + 0.5) * su})
                        near_half = near_half || std::abs(x - std::floor(x) - 0.5) <= 8.0 * x * 1.2e-7;
                }
                const uint32_t wg = uint32_t(g[0]) | (uint32_t(g[1]) << 16), wh = uint32_t(h[0]) | (uint32_t(h[1]) << 16);
                const uint32_t ug = uint32_t(g[2]) | (uint32_t(g[3]) << 16), uh = uint32_t(h[2]) | (uint32_t(h[3]) << 16);
                const double step = 2.0 / su;
                const bool neighbours = glm::length(glm::dvec2(rk_gb_unpack_snorm2(wg, b)) - glm::dvec2(rk_gb_unpack_snorm2(wh, b))) <= 2.1 / s &&
                                        glm::length(glm::dvec2(rk_gb_unpack_unorm2(ug, b)) - glm::dvec2(rk_gb_unpack_unorm2(uh, b))) <= 1.01 * step;
                return near_half && neighbours;
            };
        }
        const parity::Result r = parity::run(e.c, parity::shader_dir(), 8192, e.exact);
        EXPECT_TRUE(r.ok) << e.c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << e.c.name;
    }
}
