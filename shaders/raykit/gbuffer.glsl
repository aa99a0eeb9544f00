// raykit — gbuffer.glsl: what a deferred renderer stores per pixel and how it reads it back
// (Fahlén, "Illumination for Real-Time Rendering of Large Architectural Environments", ch. 2):
// unit vectors in two components, view position and linear distance from a depth buffer, and two
// scalars in one 32-bit word.
//
// Shared GLSL/C++ source (include/raykit/gbuffer.hpp is the C++ build, with the layout descriptor,
// its presets and the depth-parameter helpers). Measured errors and costs: docs/deferred.md.
//
// Unit vectors (every encoder takes any finite vector, normalises it robustly and maps the zero
// vector, NaN and all-denormal input to +z):
//   octahedral (Cigolle et al. 2014, "A Survey of Efficient Representations for Independent Unit
//     Vectors"): the whole sphere in [-1, 1]^2, folded over the diagonals for z < 0;
//   hemisphere remapping (the thesis, after Green): store (x, y) and rebuild z = sqrt(1 - x² - y²).
//     Only the z >= 0 hemisphere survives: a vector with z < 0 decodes as its mirror image (x, y, -z),
//     2 asin(|z|) away. Fine for tangent-space normals, wrong for view-space normals at grazing
//     angles of a perspective view (they can face away from the axis);
//   Lambert azimuthal equal-area (the "spheremap transform"): the whole sphere in the unit disk,
//     equal areas in equal areas; -z is the disk's rim (a singular point: every rim point decodes to
//     -z, so quantisation error grows towards -z).
// Quantisation: rk_gb_pack_snorm2 / rk_gb_pack_unorm2 store a point of [-1, 1]^2 in two b-bit
// fields of a uint (b in 1..16) with the rounding a render target applies (round to nearest);
// rk_gb_quantize_snorm2 / rk_gb_quantize_unorm2 return the value such a target stores, for shaders
// that write floats into RG8/RG16 SNORM or UNORM targets. rk_gb_oct_pack_snorm_precise tries the
// four codes around the point and keeps the one that decodes closest (Cigolle's "P" variants).
//
// Depth (window depth d in [0, 1] as stored by the depth buffer; perspective projections):
//   rk_gb_linear_depth gives the distance along the view axis for every convention (OpenGL's
//   [-1, 1] NDC and Vulkan's [0, 1] give the same window depth; reversed-Z and infinite far planes
//   only change k: rk_gb_depth_params, in C++ gbuffer_depth_params in double).
//   rk_gb_view_pos rebuilds the view-space position from NDC x, y and that distance.
//
// NaN handling (NaN inputs read as documented per function) relies on IEEE comparisons, which
// GLSL ES 3.00 does not require and a driver may fold away: on such drivers only finite inputs are
// covered.
//
// @rk-es 310
// @rk-es300
#ifndef RK_GBUFFER_GLSL
#define RK_GBUFFER_GLSL

#include "common.glsl"

/// rk_gb_clamp_unit: x clamped to [-1, 1], NaN -> 0 (clamp leaves NaN undefined). Cost: 2 selects.
RK_INLINE float rk_gb_clamp_unit(float x) { return x >= -1.0f ? min(x, 1.0f) : (x < -1.0f ? -1.0f : 0.0f); }

// ---------------------------------------------------------------------------------------------
// Octahedral

/// rk_gb_oct_encode: a direction -> p in [-1, 1]^2: p = (x, y) / (|x| + |y| + |z|), folded over
/// the diagonals for z < 0 (z = -0 is not folded; on a fold, x = 0 or y = 0 goes to the + side,
/// and so does an x or y whose share of |x| + |y| + |z| is below RK_FLT_MIN, as on a GPU that
/// flushes subnormals).
/// Domain: any finite vector (see rk_normalize_safe in common.glsl). Max error: dir -> p -> dir through
/// rk_gb_oct_decode within 3.5e-7 rad (10^7 random directions + rings through the poles, folds
/// and equator: docs/deferred.md). Cost: 1 div, ~17 flops.
RK_INLINE vec2 rk_gb_oct_encode(vec3 n)
{
    float m = max(max(abs(n.x), abs(n.y)), abs(n.z));
    if (!(m >= RK_FLT_MIN) || !(abs(n.x) <= RK_FLT_MAX) || !(abs(n.y) <= RK_FLT_MAX) || !(abs(n.z) <= RK_FLT_MAX))
        return vec2(0.0f);
    if (m > 1.2676506e30f) {
        n *= 7.8886091e-31f;
        m *= 7.8886091e-31f;
    }
    vec3 p = n / m;
    float l1 = abs(p.x) + abs(p.y) + abs(p.z);
    // A subnormal u or v counts as 0 (a GPU flushes it to a zero of either sign, which the fold
    // would send to the + side while the CPU sends the negative value to the - side).
    float u = p.x / l1;
    float v = p.y / l1;
    u = abs(u) >= RK_FLT_MIN ? u : 0.0f;
    v = abs(v) >= RK_FLT_MIN ? v : 0.0f;
    if (p.z < 0.0f) {
        vec2 f = rk_oct_fold(u, v);
        u = f.x;
        v = f.y;
    }
    return vec2(u, v);
}

/// rk_gb_oct_decode: p in [-1, 1]^2 (clamped) -> unit direction. (0, 0) is +z, the four corners
/// are -z. Max error: 1.5e-7 rad against the float64 map (tests/test_gbuffer.cpp). Cost: ~10
/// flops, 1 rsqrt.
RK_INLINE vec3 rk_gb_oct_decode(vec2 p)
{
    float u = rk_gb_clamp_unit(p.x);
    float v = rk_gb_clamp_unit(p.y);
    float z = 1.0f - abs(u) - abs(v);
    if (z < 0.0f) {
        vec2 f = rk_oct_fold(u, v);
        u = f.x;
        v = f.y;
    }
    vec3 d = vec3(u, v, z);
    return d * inversesqrt(max(dot(d, d), RK_FLT_MIN));
}

// ---------------------------------------------------------------------------------------------
// Hemisphere remapping (the thesis's)

/// rk_gb_hemi_encode: a direction -> its unit (x, y). Domain: any finite vector (zero -> +z, so
/// (0, 0)). The sign of z is dropped: see the file comment. Cost: rk_normalize_safe.
RK_INLINE vec2 rk_gb_hemi_encode(vec3 n)
{
    vec3 u = rk_normalize_safe(n, vec3(0.0f, 0.0f, 1.0f));
    return vec2(u.x, u.y);
}

/// rk_gb_hemi_decode: (x, y) -> (x, y, sqrt(1 - x² - y²)), renormalised; outside the unit disk
/// (quantisation) z = 0 and (x, y) is scaled back onto the circle. Always z >= 0.
/// Max error of the round trip for z >= 0: 2.9e-6 rad for z >= 0.05, 5.5e-4 rad at the equator
/// (z comes from the square root of a rounding error there; docs/deferred.md). Cost: ~6 flops,
/// 1 sqrt, 1 rsqrt.
RK_INLINE vec3 rk_gb_hemi_decode(vec2 e)
{
    float x = rk_gb_clamp_unit(e.x);
    float y = rk_gb_clamp_unit(e.y);
    vec3 d = vec3(x, y, sqrt(max(1.0f - x * x - y * y, 0.0f)));
    return d * inversesqrt(max(dot(d, d), RK_FLT_MIN));
}

// ---------------------------------------------------------------------------------------------
// Lambert azimuthal equal-area

/// rk_gb_lambert_encode: a direction -> p in the unit disk: p = (x, y) / sqrt(2 (1 + z)) for the
/// unit vector; below the equator, as |p| = sqrt((1 - z) / 2) along (x, y) (no cancellation near
/// -z); -z itself maps to (1, 0) on the rim. Domain: any finite vector (zero -> +z). Max error:
/// dir -> p -> dir within 6e-6 rad for z > -0.99, 1.3e-3 rad near -z (float cannot resolve |p|
/// near the rim: directions within ~1e-3 rad of -z share few values; docs/deferred.md).
/// Cost: rk_normalize_safe + 1 div, 1 rsqrt.
RK_INLINE vec2 rk_gb_lambert_encode(vec3 n)
{
    vec3 u = rk_normalize_safe(n, vec3(0.0f, 0.0f, 1.0f));
    if (u.z >= 0.0f) {
        float k = inversesqrt(2.0f + 2.0f * u.z);
        return vec2(u.x * k, u.y * k);
    }
    // Below the equator: radius sqrt((1 - z) / 2) (no cancellation) along the direction of (x, y),
    // scaled by its larger component first (x, y may be denormal near -z).
    float rho = min(sqrt((1.0f - u.z) * 0.5f), 1.0f);
    float mxy = max(abs(u.x), abs(u.y));
    if (!(mxy >= RK_FLT_MIN)) return vec2(rho, 0.0f);
    vec2 q = vec2(u.x / mxy, u.y / mxy);
    return q * (rho * inversesqrt(dot(q, q)));
}

/// rk_gb_lambert_decode: p (clamped to the unit disk) -> unit direction: z = 1 - 2 |p|²,
/// (x, y) = 2 sqrt(1 - |p|²) p. Cost: ~10 flops, 1 sqrt, 1 rsqrt.
RK_INLINE vec3 rk_gb_lambert_decode(vec2 p)
{
    float x = rk_gb_clamp_unit(p.x);
    float y = rk_gb_clamp_unit(p.y);
    float r2 = x * x + y * y;
    if (r2 > 1.0f) {
        float k = inversesqrt(r2);
        x *= k;
        y *= k;
        r2 = 1.0f;
    }
    float g = 2.0f * sqrt(max(1.0f - r2, 0.0f));
    vec3 d = vec3(x * g, y * g, 1.0f - 2.0f * r2);
    return d * inversesqrt(max(dot(d, d), RK_FLT_MIN));
}

// ---------------------------------------------------------------------------------------------
// Quantisation of a point of [-1, 1]^2 (any of the maps above)

/// rk_gb_pack_snorm2: p (clamped to [-1, 1]^2) -> two b-bit signed fields (x in bits 0..b-1, y in
/// bits b..2b-1, two's complement), q = round(p * (2^(b-1) - 1)) to the nearest code, ties away from
/// zero (D3D rounds to nearest; OpenGL and Vulkan leave ties to the implementation). bits in 2..16
/// (clamped). NaN stores the code of 0. Exact for the float product p * (2^(b-1) - 1).
/// Cost: ~16 ops.
RK_INLINE uint rk_gb_pack_snorm2(vec2 p, uint bits)
{
    uint b = clamp(bits, 2u, 16u);
    float s = float((1u << (b - 1u)) - 1u);
    RK_PRECISE float x = rk_gb_clamp_unit(p.x) * s;
    RK_PRECISE float y = rk_gb_clamp_unit(p.y) * s;
    // Round half away from zero with an exact tie test (x + 0.5 would round twice).
    float ax = abs(x);
    float ay = abs(y);
    float fx = floor(ax);
    float fy = floor(ay);
    int qx = int(fx + (ax - fx >= 0.5f ? 1.0f : 0.0f)) * (x < 0.0f ? -1 : 1);
    int qy = int(fy + (ay - fy >= 0.5f ? 1.0f : 0.0f)) * (y < 0.0f ? -1 : 1);
    uint mask = (1u << b) - 1u;
    return (uint(qx) & mask) | ((uint(qy) & mask) << b);
}

/// rk_gb_unpack_snorm2: inverse of rk_gb_pack_snorm2: q / (2^(b-1) - 1), the most negative code
/// decodes as -1 (as SNORM targets do). Exact to float rounding. Cost: ~12 integer ops, 2 div.
RK_INLINE vec2 rk_gb_unpack_snorm2(uint w, uint bits)
{
    uint b = clamp(bits, 2u, 16u);
    uint mask = (1u << b) - 1u;
    uint sign = 1u << (b - 1u);
    uint ux = w & mask;
    uint uy = (w >> b) & mask;
    int qx = int(ux) - ((ux & sign) != 0u ? int(1u << b) : 0);
    int qy = int(uy) - ((uy & sign) != 0u ? int(1u << b) : 0);
    float s = float(sign - 1u);
    return vec2(max(float(qx) / s, -1.0f), max(float(qy) / s, -1.0f));
}

/// rk_gb_pack_unorm2: p (clamped to [-1, 1]^2) mapped to u = 0.5 p + 0.5 -> two b-bit unsigned
/// fields, q = round(u * (2^b - 1)) to the nearest code (UNORM render targets), ties up, exact for
/// the float value u * (2^b - 1). bits in 1..16 (clamped). NaN stores the code of 0.
/// Note: 0 (the octahedral +z, the hemisphere pole) has no exact UNORM code. Cost: ~10 ops.
RK_INLINE uint rk_gb_pack_unorm2(vec2 p, uint bits)
{
    uint b = clamp(bits, 1u, 16u);
    float s = float((1u << b) - 1u);
    RK_PRECISE float x = (rk_gb_clamp_unit(p.x) * 0.5f + 0.5f) * s;
    RK_PRECISE float y = (rk_gb_clamp_unit(p.y) * 0.5f + 0.5f) * s;
    float fx = floor(x);
    float fy = floor(y);
    uint qx = uint(fx + (x - fx >= 0.5f ? 1.0f : 0.0f));  // exact tie test, ties up
    uint qy = uint(fy + (y - fy >= 0.5f ? 1.0f : 0.0f));
    return qx | (qy << b);
}

/// rk_gb_unpack_unorm2: inverse of rk_gb_pack_unorm2, back in [-1, 1]^2. Cost: ~8 ops, 2 div.
RK_INLINE vec2 rk_gb_unpack_unorm2(uint w, uint bits)
{
    uint b = clamp(bits, 1u, 16u);
    uint mask = (1u << b) - 1u;
    float s = float(mask);
    return vec2(float(w & mask) / s * 2.0f - 1.0f, float((w >> b) & mask) / s * 2.0f - 1.0f);
}

/// rk_gb_quantize_snorm2 / rk_gb_quantize_unorm2: the value an RG SNORM (resp. UNORM, as
/// 0.5 p + 0.5) target of b bits per channel stores for p when it rounds to nearest (a code value:
/// written back, every target stores it unchanged, which is how a code chosen by
/// rk_gb_oct_pack_snorm_precise is written). Cost: pack + unpack.
RK_INLINE vec2 rk_gb_quantize_snorm2(vec2 p, uint bits) { return rk_gb_unpack_snorm2(rk_gb_pack_snorm2(p, bits), bits); }
RK_INLINE vec2 rk_gb_quantize_unorm2(vec2 p, uint bits)
{
    vec2 q = rk_gb_unpack_unorm2(rk_gb_pack_unorm2(p, bits), bits);
    return vec2(q.x * 0.5f + 0.5f, q.y * 0.5f + 0.5f);
}

/// rk_gb_oct_pack_snorm / rk_gb_oct_unpack_snorm: octahedral in two b-bit SNORM fields, rounded to
/// the nearest code (Cigolle's octN with N = 2b). Max error: 3 sqrt(2) / (2 (2^(b-1) - 1)) rad, half
/// a step on both fields at an octant face centre: 1.67e-2, 4.15e-3, 1.04e-3, 6.47e-5 for b = 8,
/// 10, 12, 16 (10^7 directions measure 1.664e-2 ... 6.46e-5). Cost: encode + pack, unpack + decode.
RK_INLINE uint rk_gb_oct_pack_snorm(vec3 n, uint bits) { return rk_gb_pack_snorm2(rk_gb_oct_encode(n), bits); }
RK_INLINE vec3 rk_gb_oct_unpack_snorm(uint w, uint bits) { return rk_gb_oct_decode(rk_gb_unpack_snorm2(w, bits)); }

/// rk_gb_oct_pack_snorm_precise: of the four codes around the octahedral point (floor and ceil on
/// each axis), the one whose decoded direction is closest to n (Cigolle's octNP); ties keep the
/// first in the order (floor, floor), (ceil, floor), (floor, ceil), (ceil, ceil). Never worse than
/// rk_gb_oct_pack_snorm beyond the float rounding of the distances it compares (the nearest code
/// is one of the four; at 16 bits 7e-8 rad in 181 of 2e6 directions). Max error: 1.12e-2, 2.77e-3,
/// 6.9e-4, 4.31e-5 rad for b = 8, 10, 12, 16 (10^7 directions), two thirds of the nearest code's.
/// Cost: 4 decodes (7-9x a round trip on a CPU).
RK_INLINE uint rk_gb_oct_pack_snorm_precise(vec3 n, uint bits)
{
    uint b = clamp(bits, 2u, 16u);
    vec3 u = rk_normalize_safe(n, vec3(0.0f, 0.0f, 1.0f));
    vec2 p = rk_gb_oct_encode(u);
    float s = float((1u << (b - 1u)) - 1u);
    float fx = floor(rk_gb_clamp_unit(p.x) * s);
    float fy = floor(rk_gb_clamp_unit(p.y) * s);
    // Closeness as the squared distance of the unit vectors, not their dot product: at 16 bits the
    // candidates' cosines differ by less than float's resolution near 1.
    uint best = 0u;
    float best_d2 = 8.0f;
    for (uint k = 0u; k < 4u; ++k) {
        float cx = min(fx + float(k & 1u), s);
        float cy = min(fy + float(k >> 1u), s);
        uint w = rk_gb_pack_snorm2(vec2(cx / s, cy / s), b);
        vec3 e = rk_gb_oct_unpack_snorm(w, b) - u;
        RK_PRECISE float d2 = dot(e, e);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = w;
        }
    }
    return best;
}

/// rk_gb_oct_pack_unorm / rk_gb_oct_unpack_unorm: octahedral in two b-bit UNORM fields (RG8 /
/// RG16 UNORM targets). UNORM has no code for 0, so +z and the fold lines are half a step off:
/// prefer SNORM where the format exists. Cost: encode + pack, unpack + decode.
RK_INLINE uint rk_gb_oct_pack_unorm(vec3 n, uint bits) { return rk_gb_pack_unorm2(rk_gb_oct_encode(n), bits); }
RK_INLINE vec3 rk_gb_oct_unpack_unorm(uint w, uint bits) { return rk_gb_oct_decode(rk_gb_unpack_unorm2(w, bits)); }

// ---------------------------------------------------------------------------------------------
// Depth

/// rk_gb_depth_params: the k of rk_gb_linear_depth for a perspective projection with near plane n
/// and far plane f (f <= n or not finite: an infinite far plane), `reversed` false for the usual
/// depth (near at 0, far at 1: OpenGL's [-1, 1] NDC and Vulkan's [0, 1] give the same window depth)
/// and true for reversed-Z (near at 1): k = (1 / n, 1 / f or 0, reversed ? 0 : 1).
/// Domain: n > 0 (below RK_FLT_MIN, n and f read as RK_FLT_MIN, so k stays finite). In float;
/// gbuffer_depth_params (C++) computes the same in double for finite n > 0. Cost: 2 div.
RK_INLINE vec3 rk_gb_depth_params(float n, float f, bool reversed)
{
    bool inf = !(f > n) || !(f <= RK_FLT_MAX);
    return vec3(1.0f / max(n, RK_FLT_MIN), inf ? 0.0f : 1.0f / max(f, RK_FLT_MIN), reversed ? 0.0f : 1.0f);
}

/// rk_gb_linear_depth: the distance along the view axis (positive, view units) of window depth d
/// (clamped to [0, 1]; NaN reads as the near plane), k from rk_gb_depth_params.
/// Window depth is d = (1/n - 1/dist) / (1/n - 1/f) (usual; reversed-Z: 1 - that), so with
/// t = |k.z - d| (1 - d usual, d reversed; exact for d >= 0.5), 1 / dist = t / n + (1 - t) / f:
/// two non-negative terms, no cancellation, unlike the textbook n f / (f - d (f - n)), which loses
/// f / n ulps near the far plane. The far plane of an infinite projection gives RK_FLT_MAX, and so
/// does any depth whose 1 / dist is below RK_FLT_MIN (dist beyond 8.5e37, where 1 / dist would be
/// subnormal and a GPU flushes it to 0).
/// Max error (relative, against float64 at the same stored d): 2e-7 (tests/test_gbuffer.cpp: every
/// 64th float in [0, 1], every float near 0 and 1, five conventions); what the
/// stored d itself carries depends on the convention (the usual one keeps ~dist / n ulps, reversed-Z
/// float depth ~1e-7 everywhere). Cost: 1 abs, 2 fma, 1 div.
RK_INLINE float rk_gb_linear_depth(float d, vec3 k)
{
    // NaN reads as the near plane: 0 usual (k.z = 1), 1 reversed (k.z = 0).
    float dc = d >= 0.0f ? min(d, 1.0f) : (d < 0.0f ? 0.0f : 1.0f - k.z);
    float t = abs(k.z - dc);
    float q = t * k.x + (1.0f - t) * k.y;
    return q >= RK_FLT_MIN ? clamp(1.0f / q, RK_FLT_MIN, RK_FLT_MAX) : RK_FLT_MAX;
}

/// rk_gb_window_depth: the window depth of view distance `dist` (> 0) for k from
/// rk_gb_depth_params (the inverse of rk_gb_linear_depth): t = (1/dist - 1/f) / (1/n - 1/f), d = 1 - t
/// (usual) or t (reversed-Z), clamped to [0, 1]. Cost: 2 div, ~4 flops.
RK_INLINE float rk_gb_window_depth(float dist, vec3 k)
{
    float inv = 1.0f / max(dist, RK_FLT_MIN);
    float t = rk_saturate((inv - k.y) / max(k.x - k.y, RK_FLT_MIN));
    return abs(k.z - t);
}

/// rk_gb_view_pos: the view-space position (camera at the origin looking down -z) of the pixel at
/// NDC (x, y) in [-1, 1]^2 whose distance along the view axis is `dist` (rk_gb_linear_depth):
/// (dist (x + P[2][0]) / P[0][0], dist (y + P[2][1]) / P[1][1], -dist), with `ray` =
/// (1 / P[0][0], 1 / P[1][1], P[2][0] / P[0][0], P[2][1] / P[1][1]) of the column-major
/// projection P (off-centre frusta and a negative P[1][1] for Vulkan's y-flip included;
/// gbuffer_view_ray in C++). Domain: ndc in [-1, 1]^2 (a guard band beyond works), dist >= 0;
/// any finite input gives a finite result (overflow is held at +-RK_FLT_MAX). The same result on a
/// GPU that flushes subnormals needs ndc components 0 or of magnitude >= 2^-40 and ray components
/// 0 or >= 2^-20 (any projection up to P[0][0] = 2^20): the products then stay normal.
/// Cost: 2 fma, 3 mul, 3 clamps.
RK_INLINE vec3 rk_gb_view_pos(vec2 ndc, float dist, vec4 ray)
{
    float sx = clamp(ndc.x * ray.x + ray.z, -RK_FLT_MAX, RK_FLT_MAX);
    float sy = clamp(ndc.y * ray.y + ray.w, -RK_FLT_MAX, RK_FLT_MAX);
    return clamp(vec3(dist * sx, dist * sy, -dist), vec3(-RK_FLT_MAX), vec3(RK_FLT_MAX));
}

// ---------------------------------------------------------------------------------------------
// Two scalars in one 32-bit word

/// rk_gb_half_bits: float -> IEEE half bits, round to nearest even; beyond the largest half
/// (65504) saturates to +-65504 (never an infinity), NaN -> 0, results below the smallest half
/// denormal round to +-0. Exact (the correctly rounded half). Cost: ~20 integer ops.
RK_INLINE uint rk_gb_half_bits(float x)
{
    uint f = floatBitsToUint(x);
    uint sign = (f >> 16u) & 0x8000u;
    uint a = f & 0x7FFFFFFFu;
    if (a > 0x7F800000u) return 0u;                 // NaN
    if (a >= 0x477FF000u) return sign | 0x7BFFu;    // rounds to >= 65520: saturate to 65504
    if (a >= 0x38800000u) {                          // normal half (>= 2^-14)
        uint m = a - 0x38000000u;                    // rebias the exponent (127 -> 15)
        uint r = (m >> 13u) + (((m >> 12u) & 1u) & (((m & 0xFFFu) != 0u ? 1u : 0u) | ((m >> 13u) & 1u)));
        return sign | r;
    }
    if (a < 0x33000000u) return sign;                // below half the smallest denormal: +-0
    // Denormal half: the value in units of 2^-24, rounded to nearest even.
    uint e = a >> 23u;                               // 102 .. 112
    uint mant = (a & 0x7FFFFFu) | 0x800000u;
    uint shift = 126u - e;                           // 14 .. 24
    uint q = mant >> shift;
    uint rem = mant & ((1u << shift) - 1u);
    uint halfway = 1u << (shift - 1u);
    if (rem > halfway || (rem == halfway && (q & 1u) != 0u)) q += 1u;
    return sign | q;
}

/// rk_gb_half_value: IEEE half bits (low 16 bits of h) -> float, exactly (denormals included;
/// infinities and NaN, which rk_gb_half_bits never makes, decode as +-65504 and 0). Cost: ~12 ops.
RK_INLINE float rk_gb_half_value(uint h)
{
    uint sign = (h & 0x8000u) << 16u;
    uint e = (h >> 10u) & 0x1Fu;
    uint m = h & 0x3FFu;
    if (e == 31u) return m != 0u ? 0.0f : uintBitsToFloat(sign | 0x477FE000u);
    if (e == 0u) return uintBitsToFloat(sign) + (sign != 0u ? -1.0f : 1.0f) * float(m) * 5.9604644775390625e-8f;
    return uintBitsToFloat(sign | ((e + 112u) << 23u) | (m << 13u));
}

/// rk_gb_pack_half2: two scalars -> one uint (a in bits 0..15, b in 16..31), each the correctly
/// rounded half (saturating at +-65504, NaN -> 0): what the thesis proposed for specular and emission.
/// Store it in an R32UI channel (a float channel could turn some bit patterns into NaN). Relative
/// error <= 2^-11 for |v| in [6.1e-5, 65504]; absolute <= 2^-25 below. Cost: 2 rk_gb_half_bits.
RK_INLINE uint rk_gb_pack_half2(float a, float b) { return rk_gb_half_bits(a) | (rk_gb_half_bits(b) << 16u); }

/// rk_gb_unpack_half2: inverse of rk_gb_pack_half2 (exact for every word it makes). Cost: 2
/// rk_gb_half_value.
RK_INLINE vec2 rk_gb_unpack_half2(uint w) { return vec2(rk_gb_half_value(w & 0xFFFFu), rk_gb_half_value(w >> 16u)); }

#endif  // RK_GBUFFER_GLSL
