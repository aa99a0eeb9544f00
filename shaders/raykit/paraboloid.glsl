// raykit — paraboloid.glsl: (dual-)paraboloid environment maps: direction <-> map coordinates for
// either hemisphere convention, solid-angle density, the window frame, a 2:1 dual-paraboloid atlas
// with a seam guard derived from the texel size and the filter footprint, LOD selection, and the
// Brabec-style vertex projection for rendering into a paraboloid map.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/paraboloid.hpp, which adds the
// CPU baking (cube -> dual paraboloid with supersampling and mips, the inverse, an octahedral map
// for comparison). Texture lookups (GLSL only) are in paraboloid_sample.glsl.
// Sources: Fahlén 2005, "Illumination for Real-Time Rendering of Large Architectural Environments",
// §3.2.3 (Eq. 3.9-3.12: thesis convention, front d0 = -z, the window frame rotation about y),
// Heidrich & Seidel 1998 / Blythe SIGGRAPH '99 notes, Brabec et al. 2002 (dual-paraboloid shadow
// maps, d0 = +z, linear-distance depth). The map is the stereographic projection from the opposite
// pole; density 4 / (1 + s^2 + t^2)^2.
//
// Conventions, used by every function here:
//   hemi   which hemisphere a paraboloid covers, as the sign of its axis d0 = (0, 0, hemi):
//          +1 Heidrich/Brabec (d0 = +z), -1 the thesis (d0 = -z). Any value <= -RK_FLT_MIN means
//          -1, anything else (±0 and negative denormals included) +1.
//   st     paraboloid coordinates: st = (x, y) / (1 + hemi z) for the unit direction (x, y, z).
//          The hemisphere (hemi z >= 0) maps onto the unit disk (the "sweet circle"), its pole to
//          (0, 0), the rim hemi z = 0 to |st| = 1. Directions of the other hemisphere continue the
//          same stereographic projection outside the disk (|st| > 1, the antipode at infinity); the
//          atlas's guard band stores exactly that continuation, so no tap near the seam reads a
//          wrong texel (the error next to the seam is below that a texel further in; what remains is
//          a jump of about h^2/4 rad between the two halves' bilinear errors, h the LOD's texel in
//          st: raykit::sample_dual_paraboloid's comment gives the measured numbers).
//          Handedness, seen from the map centre looking along d0 with +y up: the +z map (hemi = +1)
//          is mirrored left-right (s grows with x, which points left), the -z map is not.
//   uv     texture coordinates, 0.5 + 0.5 st for a single map (v = 0 is the first row of the
//          image, GL's convention), or the dual atlas below.
//   dir    directions need not be unit length (they are normalised internally, robustly for any
//          finite vector: components are first scaled by the largest); the zero vector (and vectors
//          whose components are all denormal) counts as d0.
//
// Dual-paraboloid atlas (rk_dual_paraboloid_uv): a 2H x H texture, left half the +z hemisphere
// (hemi = +1), right half the -z hemisphere (hemi = -1); a direction with z > -RK_FLT_MIN (-0 and
// negative denormals included, so that flushing GPUs agree) uses the left half. Inside a half,
// uv_half = 0.5 + 0.5 g st with the guard scale g < 1: the unit disk covers the central g of the
// half and the rest is a guard ring that the baker fills with the continuation of the projection
// (directions just past the rim). g comes from the texel size and
// the filter footprint (rk_dual_paraboloid_guard_scale): every bilinear tap of every lookup up to
// the largest LOD used stays in its own half, and the taps past the rim read correct data, so both
// halves interpolate the same signal at the seam. H must be a multiple of 2^ceil(max_lod) so the
// 2x2 box mips never mix the halves (raykit::bake_dual_paraboloid checks).
//
// Every function returns finite values for every finite input (denormals, ±0, huge values).
// Errors are against float64 evaluations, measured by tests/test_paraboloid.cpp.
//
// @rk-es 310
// @rk-es300
#ifndef RK_PARABOLOID_GLSL
#define RK_PARABOLOID_GLSL

#include "common.glsl"

// Largest |s|, |t| accepted by the decoders: beyond it the direction is the antipode to float
// precision (|st| = 1e6 is 2e-6 rad from it).
#define RK_PARABOLOID_ST_MAX 1.0e6f
// Largest coordinate magnitude accepted by the projection helpers (positions, depth range).
#define RK_PARABOLOID_POS_MAX 1.0e18f
// Smallest guard scale: below it the guard band would be larger than the map itself.
#define RK_PARABOLOID_GUARD_MIN 0.0009765625f

/// rk_paraboloid_hemi_sign: the hemisphere sign from any float: -1 for hemi <= -RK_FLT_MIN, else
/// +1 (±0 and negative denormals give +1 on every backend, flushing or not). Exact.
/// Cost: 1 compare, 1 select.
RK_INLINE float rk_paraboloid_hemi_sign(float hemi) { return hemi <= -RK_FLT_MIN ? -1.0f : 1.0f; }

/// rk_paraboloid_max_abs: the largest |component| of v. Exact. Cost: 3 abs, 2 max.
RK_INLINE float rk_paraboloid_max_abs(vec3 v) { return max(max(abs(v.x), abs(v.y)), abs(v.z)); }

/// rk_paraboloid_prescale: a power-of-two factor (1 or 2^-100 = 7.9e-31) that brings a magnitude
/// m <= FLT_MAX below 2.7e8 so that 1 / (m * factor) is a normal float: GPUs may evaluate a / m as
/// a * (1 / m) and flush the denormal reciprocal of a huge m to zero. A power of two scales
/// without rounding (down to the denormal range). Exact. Cost: 1 compare, 1 select.
RK_INLINE float rk_paraboloid_prescale(float m) { return m > 1.0e30f ? 7.8886090522101181e-31f : 1.0f; }

/// rk_paraboloid_normalize: v / |v| computed without overflow or underflow for every finite v
/// (components first divided by the largest |component|); returns `fallback` unchanged when every
/// component is below RK_FLT_MIN in magnitude (zero, or denormal, which GPUs flush to zero).
/// Denormal components count as zero on every backend: beside a component near RK_FLT_MIN a
/// denormal one would otherwise tilt the direction by up to 45 degrees, across the hemisphere
/// that the raw sign test (rk_dual_paraboloid_hemi) chose. Result components below RK_FLT_MIN
/// (a component over 2^126 times smaller than the largest) are 0 on every backend as well.
/// Max error: 3.8 ulp per component against float64 of that vector (4e7 random + refinement),
/// plus the flush of results below RK_FLT_MIN.
/// Cost: 7 max/abs, 6 select, 1 div, 1 dot, 1 rsqrt.
RK_INLINE vec3 rk_paraboloid_normalize(vec3 v, vec3 fallback)
{
    vec3 w = rk_flush_subnormal(v);
    float m = rk_paraboloid_max_abs(w);
    if (m < RK_FLT_MIN) {
        return fallback;
    }
    float pre = rk_paraboloid_prescale(m);
    vec3 q = (w * pre) / (m * pre);  // largest component +-1, dot(q, q) in [1, 3]
    // Result components below RK_FLT_MIN (from one much smaller than the largest) are 0 too: a GPU
    // flushes them, and a frame or a seam weight built on them would differ.
    return rk_flush_subnormal(q * inversesqrt(dot(q, q)));
}

/// rk_paraboloid_encode: paraboloid coordinates st = (x, y) / (1 + hemi z) of the direction `dir`
/// (normalised internally) on the paraboloid with axis d0 = (0, 0, hemi). Thesis Eq. 3.12 for
/// hemi = -1; Heidrich/Brabec for +1. The hemisphere maps onto the unit disk; directions past the
/// rim continue outside it (used by the atlas guard band). The exact antipode -d0 has no image and
/// returns (0, 0); its neighbourhood returns large finite values (|st| <= 2e15).
/// Past the rim (hemi z < 0) 1 + hemi z cancels towards the antipode (it loses ulp(z) / (1 + hemi z)
/// relative, and is 0 within ~2.4e-4 rad of it), so there it is taken as (x^2 + y^2) / (1 - hemi z),
/// the same value for a unit vector, and st keeps its relative accuracy.
/// Max error vs float64 (unit dir in the hemisphere): 2.4e-7; the round trip dir -> st -> dir
/// through rk_paraboloid_decode is within 2.7e-7, st -> dir -> st within 2.6e-7 (2e7 random +
/// refinement each; tests/test_paraboloid.cpp prints them; the issue asks for 1e-6). Past the rim:
/// 2.8e-7 relative to |st|, up to 1e-13 rad from the antipode (8e5 random, any length).
/// Cost: rk_paraboloid_normalize + 1 compare, 2 select, 3 add, 1 div (shared), 4 mul.
RK_INLINE vec2 rk_paraboloid_encode(vec3 dir, float hemi)
{
    float h = rk_paraboloid_hemi_sign(hemi);
    vec3 n = rk_paraboloid_normalize(dir, vec3(0.0f, 0.0f, h));
    float hz = h * n.z;
    // In the hemisphere: 1 / (1 + hz), as written. Past the rim: (1 - hz) / (x^2 + y^2).
    bool past = hz < 0.0f;
    float num = past ? 1.0f - hz : 1.0f;
    float den = past ? n.x * n.x + n.y * n.y : 1.0f + hz;
    float inv = num / max(den, 1.0e-30f);
    return vec2(n.x * inv, n.y * inv);
}

/// rk_paraboloid_decode: the unit direction of paraboloid coordinates st, the inverse of
/// rk_paraboloid_encode: (2s, 2t, hemi (1 - s^2 - t^2)) / (1 + s^2 + t^2) (thesis Eq. 3.10 for
/// hemi = -1). |st| <= 1 gives the hemisphere, (0, 0) gives d0, the unit circle the rim
/// hemi z = 0; points outside the disk decode to the other hemisphere (the guard band's content).
/// Domain: s, t clamped to [-RK_PARABOLOID_ST_MAX, RK_PARABOLOID_ST_MAX]. The result is unit
/// length within 2 ulp. Max error vs float64: 1.8e-7 absolute per component, 1.5e-7 in the unit
/// disk (4e7 random + refinement; z near the rim is absolute-accurate only: 1 - s^2 - t^2 cancels
/// there). Cost: 1 div, ~9 flops.
RK_INLINE vec3 rk_paraboloid_decode(vec2 st, float hemi)
{
    float h = rk_paraboloid_hemi_sign(hemi);
    float s = clamp(st.x, -RK_PARABOLOID_ST_MAX, RK_PARABOLOID_ST_MAX);
    float t = clamp(st.y, -RK_PARABOLOID_ST_MAX, RK_PARABOLOID_ST_MAX);
    float r2 = s * s + t * t;
    float inv = 1.0f / (1.0f + r2);
    return vec3(2.0f * s * inv, 2.0f * t * inv, h * (1.0f - r2) * inv);
}

/// rk_paraboloid_encode_differential: the change d(st) of rk_paraboloid_encode(v, hemi) for a
/// change dv of its (not necessarily unit) argument v: the exact Jacobian of the normalised
/// projection, s = x / (|v| + hemi z), applied to dv. Used to give textureGrad derivatives that
/// stay continuous across the atlas seam (paraboloid_sample.glsl): pass dFdx(dir) and dFdy(dir).
/// Both v and dv are scaled by the largest |component| of v first (the result is invariant under
/// that), so any finite input is safe; dv is then clamped to ±RK_PARABOLOID_POS_MAX. Denormal
/// components of v count as zero (as in rk_paraboloid_normalize). v = 0 returns (0, 0); within
/// 1e-6 of the antipode the divisor is floored (|result| <= 4e30).
/// Accuracy: agrees with central differences of the float64 encode to 2e-5 relative (the
/// differences' own truncation error) over random directions and scales 2^-20..2^20.
/// Cost: 3 div, 1 sqrt, 3 select, ~25 flops.
RK_INLINE vec2 rk_paraboloid_encode_differential(vec3 v, vec3 dv, float hemi)
{
    float h = rk_paraboloid_hemi_sign(hemi);
    vec3 w = rk_flush_subnormal(v);
    float m = rk_paraboloid_max_abs(w);
    if (m < RK_FLT_MIN) {
        return vec2(0.0f);
    }
    float pre = rk_paraboloid_prescale(m);
    float inv_m = 1.0f / (m * pre);
    vec3 q = (w * pre) * inv_m;
    vec3 dq = clamp((dv * pre) * inv_m, vec3(-RK_PARABOLOID_POS_MAX), vec3(RK_PARABOLOID_POS_MAX));
    float len = sqrt(dot(q, q));                // in [1, sqrt(3)]
    float dlen = dot(q, dq) / len;              // d|q|
    float den = max(len + h * q.z, 1.0e-6f);    // >= len in the hemisphere; 0 only at the antipode
    float dden = dlen + h * dq.z;
    float inv = 1.0f / den;
    return vec2((dq.x - q.x * dden * inv) * inv, (dq.y - q.y * dden * inv) * inv);
}

/// rk_paraboloid_solid_angle_density: dω/dA = 4 / (1 + s^2 + t^2)^2, the solid angle per unit
/// area of st (the Jacobian of the decode): 4 at the centre, 1 on the rim (the factor-4 sampling
/// variation of thesis §5.2.5); its integral over the unit disk is 2π. Domain: any finite st
/// (s^2 + t^2 is clamped to 1e18; the far outside tends to 0). Max error: 7.4 ulp (4e7 random +
/// refinement). Cost: 1 div, 5 flops.
RK_INLINE float rk_paraboloid_solid_angle_density(vec2 st)
{
    float r2 = min(st.x * st.x + st.y * st.y, 1.0e18f);
    float d = 1.0f + r2;
    return 4.0f / (d * d);
}

/// rk_paraboloid_sweet_circle: 1 inside the unit disk s^2 + t^2 <= 1 (the part of a square
/// single-paraboloid map that holds the hemisphere, π/4 = 78.54% of it), else 0.
/// Exact. Cost: 1 dot, 1 step.
RK_INLINE float rk_paraboloid_sweet_circle(vec2 st)
{
    return step(st.x * st.x + st.y * st.y, 1.0f);
}

/// rk_paraboloid_uv: texture coordinates 0.5 + 0.5 st of a single (square) paraboloid map, scaled
/// about the centre by guard_scale (1 for the thesis's plain layout; see the atlas for the guard).
/// Domain: st clamped to ±RK_PARABOLOID_ST_MAX, guard_scale to [RK_PARABOLOID_GUARD_MIN, 1].
/// Max error: 9.0e-8 absolute (0.75 ulp of 1; not in ulps of a result near 0). Cost: 2 fma.
RK_INLINE vec2 rk_paraboloid_uv(vec2 st, float guard_scale)
{
    float g = 0.5f * clamp(guard_scale, RK_PARABOLOID_GUARD_MIN, 1.0f);
    vec2 c = clamp(st, vec2(-RK_PARABOLOID_ST_MAX), vec2(RK_PARABOLOID_ST_MAX));
    return vec2(0.5f + g * c.x, 0.5f + g * c.y);
}

// ---------------------------------------------------------------------------------------------
// Window frame (thesis Eq. 3.11, generalised)

/// rk_paraboloid_frame_angle: the thesis's rotation angle about y for a vertical window of unit
/// normal n, θ = atan2(-n.x, -n.z): the branch-free form of Eq. 3.11 (θ = ±arccos(N·d0) with the
/// sign of (N x d0).y, d0 = -z), satisfying R_y(θ) d0 = N for the standard right-handed
/// R_y(θ) = [[cos θ, 0, sin θ], [0, 1, 0], [-sin θ, 0, cos θ]]. Only n.x, n.z are read (a tilted
/// normal gives the angle of its horizontal projection); n.x = n.z = 0 (below RK_FLT_MIN) gives 0.
/// Result in (-π, π]: N = +z gives +π whatever the sign of a zero n.x. Max error: that of the
/// driver's atan (3.3e-6 rad on llvmpipe; 2.7e-7 against Eq. 3.11 in float64 on the CPU, every 4th
/// float phi in [-π, π] + refinement).
/// Cost: 1 atan.
RK_INLINE float rk_paraboloid_frame_angle(vec3 n)
{
    float m = max(abs(n.x), abs(n.z));
    if (m < RK_FLT_MIN) {
        return 0.0f;
    }
    float pre = rk_paraboloid_prescale(m);
    float inv = 1.0f / (m * pre);  // atan(y, x) of huge arguments may divide them on a GPU
    float y = -(n.x * pre) * inv;
    float x = -(n.z * pre) * inv;
    // A zero (or denormal) y of either sign gives +π, not -π, on every backend.
    float a = atan(abs(y) < RK_FLT_MIN ? 0.0f : y, abs(x) < RK_FLT_MIN ? 0.0f : x);
    // A tiny negative y (n near +z, n.x > 0) gives -π + ε, which float rounds to the float
    // nearest -π (below -π): the same rotation as +π, which keeps the result in (-π, π].
    return a < -3.1415925f ? RK_PI : a;
}

/// rk_paraboloid_frame_vertical: R_y(θ) as a mat3 (columns: the window frame's x, y, z axes in
/// world space), the thesis's window frame: world = M * local, local = world * M (GLSL's
/// row-vector product is the transpose). With θ = rk_paraboloid_frame_angle(N), M maps the thesis
/// axis d0 = -z onto N. Exact up to the driver's sin/cos. Cost: 1 sin, 1 cos.
RK_INLINE mat3 rk_paraboloid_frame_vertical(float theta)
{
    float c = cos(theta);
    float s = sin(theta);
    return mat3(vec3(c, 0.0f, -s), vec3(0.0f, 1.0f, 0.0f), vec3(s, 0.0f, c));
}

/// rk_paraboloid_frame: the window frame for any normal, as an orthonormal right-handed basis
/// M = (X, Y, Z) (columns, world space) such that the map axis d0 = (0, 0, hemi) maps onto n:
/// Z = hemi n, Y = `up` made orthogonal to n, X = Y x Z. For a vertical window, up = +y and
/// hemi = -1 this is exactly rk_paraboloid_frame_vertical(rk_paraboloid_frame_angle(n)) (Eq. 3.11).
/// world = M * local, local = world * M. n and up are normalised internally; when up is (nearly)
/// parallel to n (|cross| < 1e-4 after normalisation) the least aligned world axis replaces it, so
/// horizontal windows (skylights) get a valid frame. n = 0 counts as -z. Orthonormal within 4 ulp
/// (X is rebuilt as Y x Z: the first X, the normalised cross product of nearly parallel vectors,
/// can be ~1e3 ulp off orthogonal to Z). Cost: 4 normalisations, 3 cross, ~10 flops.
RK_INLINE mat3 rk_paraboloid_frame(vec3 n, vec3 up, float hemi)
{
    float h = rk_paraboloid_hemi_sign(hemi);
    vec3 nn = rk_paraboloid_normalize(n, vec3(0.0f, 0.0f, -1.0f));
    vec3 z = h * nn;
    vec3 u = rk_paraboloid_normalize(up, vec3(0.0f, 1.0f, 0.0f));
    vec3 x = cross(u, z);
    if (dot(x, x) < 1.0e-8f) {
        // Up parallel to the normal: use the world axis least aligned with it.
        vec3 a = abs(nn);
        u = (a.x <= a.y && a.x <= a.z) ? vec3(1.0f, 0.0f, 0.0f)
                                       : (a.y <= a.z ? vec3(0.0f, 1.0f, 0.0f) : vec3(0.0f, 0.0f, 1.0f));
        x = cross(u, z);
    }
    x = rk_paraboloid_normalize(x, vec3(1.0f, 0.0f, 0.0f));
    vec3 y = rk_paraboloid_normalize(cross(z, x), vec3(0.0f, 1.0f, 0.0f));
    return mat3(cross(y, z), y, z);
}

// ---------------------------------------------------------------------------------------------
// Dual-paraboloid atlas

/// rk_paraboloid_filter_footprint: how far, in level-0 texels, a filtered lookup at LOD up to
/// max_lod reaches from its sample point: half a texel of level ceil(max_lod), 0.5 * 2^ceil(lod)
/// (bilinear reads the texels whose centres are within one texel; trilinear also reads the
/// coarser level). max_lod clamped to [0, 16]. Anisotropic filtering reaches further (by up to the
/// anisotropy ratio along the major axis): pass the LOD of the major axis then. Exact. Cost: 1 ceil,
/// 1 exp2.
RK_INLINE float rk_paraboloid_filter_footprint(float max_lod)
{
    return 0.5f * exp2(ceil(clamp(max_lod, 0.0f, 16.0f)));
}

/// rk_dual_paraboloid_guard_scale: the guard scale g of a dual-paraboloid atlas whose halves are
/// half_size x half_size texels (the atlas is 2 half_size x half_size), for lookups whose filter
/// reaches `footprint` level-0 texels (rk_paraboloid_filter_footprint): g = 1 - 2 footprint /
/// half_size, the largest scale that keeps every tap of a lookup anywhere in the unit disk inside
/// its own half. This replaces magic shrink factors such as Torque3D's 0.997. Examples: 256 texels,
/// bilinear level 0 (footprint 0.5): g = 0.99609; up to LOD 3 (footprint 4): g = 0.96875.
/// Domain: half_size clamped to [1, 2^24], footprint to [0, 2^24]; the result is clamped to
/// [RK_PARABOLOID_GUARD_MIN, 1] (a result at the floor means the footprint is too large for the
/// map). Exact (2 roundings). Cost: 1 div, 2 flops.
RK_INLINE float rk_dual_paraboloid_guard_scale(float half_size, float footprint)
{
    float n = clamp(half_size, 1.0f, 16777216.0f);
    float f = clamp(footprint, 0.0f, 16777216.0f);
    return clamp(1.0f - 2.0f * f / n, RK_PARABOLOID_GUARD_MIN, 1.0f);
}

/// rk_dual_paraboloid_hemi: the half of the atlas a direction uses: +1 (left, +z) for
/// z > -RK_FLT_MIN (±0 and negative denormals, which lie on the seam, included), -1 (right, -z)
/// otherwise. Exact. Cost: 1 select.
RK_INLINE float rk_dual_paraboloid_hemi(vec3 dir) { return rk_paraboloid_hemi_sign(dir.z); }

/// rk_dual_paraboloid_uv_half: atlas coordinates of `dir` in a given half (hemi > -RK_FLT_MIN: the
/// left, +z half; else the right one), whatever the sign of dir.z: a direction just across the seam
/// lands in that half's guard band (|st| slightly above 1). The seam cross-fade reads both halves
/// with it; rk_dual_paraboloid_uv is it with hemi = rk_dual_paraboloid_hemi(dir).
/// Max error: 2.5e-7 in uv within the half's guard band for g >= 0.5 (2e7 random + refinement);
/// deeper into the other hemisphere |st| grows as 1 / (1 - |z|), its error relative to |st| staying
/// that of rk_paraboloid_encode past the rim (2.8e-7).
/// Cost: rk_paraboloid_encode + 4 flops.
RK_INLINE vec2 rk_dual_paraboloid_uv_half(vec3 dir, float guard_scale, float hemi)
{
    float h = rk_paraboloid_hemi_sign(hemi);
    vec2 uv = rk_paraboloid_uv(rk_paraboloid_encode(dir, h), guard_scale);
    return vec2(0.5f * uv.x + (h > 0.0f ? 0.0f : 0.5f), uv.y);
}

/// rk_dual_paraboloid_uv: atlas texture coordinates of `dir` (normalised internally): the
/// hemisphere by the sign of z, then u = (0.5 + 0.5 g s) / 2 (+ 0.5 for the right half),
/// v = 0.5 + 0.5 g t, with g from rk_dual_paraboloid_guard_scale. |st| <= 1 always (the chosen
/// hemisphere contains dir), so u stays in [0.25 (1 - g), 0.25 (1 + g)] (+ 0.5) and the filter taps
/// never cross into the other half (tests/test_paraboloid.cpp checks every tap up to the LOD, on
/// and beside the seam). Max error: 1.6e-7 in uv (2e7 random + refinement).
/// Cost: rk_paraboloid_encode + 4 flops.
RK_INLINE vec2 rk_dual_paraboloid_uv(vec3 dir, float guard_scale)
{
    return rk_dual_paraboloid_uv_half(dir, guard_scale, rk_dual_paraboloid_hemi(dir));
}


/// rk_dual_paraboloid_seam_weight: the weight of the +z half in the seam cross-fade: with z the
/// normalised direction's z, 1 for z >= band, 0 for z <= -band, 0.5 + 0.5 z / band between (near
/// the rim |d st| = |d z|, so band is the fade's half-width in st too). band <= 0 (or NaN): the
/// hard switch of rk_dual_paraboloid_uv (1 for z > -RK_FLT_MIN, else 0). Mixing the two halves'
/// lookups with it removes the jump at the seam, where the halves' bilinear errors have opposite
/// signs; the atlas's guard must then cover band beyond the rim at every LOD used (bake with
/// DualParaboloidBakeOptions::seam_fade). Exact up to 2 roundings. Cost: a normalisation, 2 flops.
RK_INLINE float rk_dual_paraboloid_seam_weight(vec3 dir, float band)
{
    if (!(band > 0.0f)) {
        return rk_dual_paraboloid_hemi(dir) > 0.0f ? 1.0f : 0.0f;
    }
    vec3 n = rk_paraboloid_normalize(dir, vec3(0.0f, 0.0f, 1.0f));
    // Divided first: 0.5 * n.z can be subnormal (flushed on a GPU) where n.z / band is not.
    return clamp(0.5f + 0.5f * (n.z / min(band, 1.0f)), 0.0f, 1.0f);
}

/// rk_dual_paraboloid_uv_differential: the change of rk_dual_paraboloid_uv for a change d_dir of
/// dir, with the hemisphere fixed by dir: the derivative a textureGrad lookup needs. Continuous
/// across the seam (both halves have the same texel density at the rim), unlike dFdx(uv), which
/// jumps by half the atlas there and makes the GPU pick the coarsest mip along the seam.
/// Domain: any finite dir and d_dir (both scaled by the largest |component| of dir, then d_dir
/// clamped, as rk_paraboloid_encode_differential); guard_scale clamped to
/// [RK_PARABOLOID_GUARD_MIN, 1]. Edge cases: dir = 0 (or all-denormal) returns (0, 0); on the seam
/// (z = ±0) the hemisphere is +z, as for rk_dual_paraboloid_uv; d_dir parallel to dir returns ~0.
/// |result| <= 0.5 g |d_dir| / |dir| (the projection scales angles by (1 + |st|^2) / 2 <= 1).
/// Max error vs the float64 complex-step derivative of the documented atlas uv: 7.5e-7 of that
/// bound (1e7 random directions, scales 2^-20..2^20, + refinement); relative to |result| it is
/// unbounded as d_dir turns parallel to dir (the result goes to 0). llvmpipe: within 6e-7 of
/// the CPU.
/// Cost: rk_paraboloid_encode_differential (3 div, 1 sqrt, ~25 flops) + 4 mul, 1 clamp.
RK_INLINE vec2 rk_dual_paraboloid_uv_differential(vec3 dir, vec3 d_dir, float guard_scale)
{
    float g = clamp(guard_scale, RK_PARABOLOID_GUARD_MIN, 1.0f);
    vec2 d = rk_paraboloid_encode_differential(dir, d_dir, rk_dual_paraboloid_hemi(dir));
    return vec2(0.25f * g * d.x, 0.5f * g * d.y);
}

/// rk_dual_paraboloid_dir: the unit direction stored at atlas coordinates uv (the inverse of
/// rk_dual_paraboloid_uv): u < 0.5 is the left (+z) half. Inside a half st = (2 uv_half - 1) / g;
/// points of the guard band (|st| > 1) return the continuation directions of the other
/// hemisphere, which is what a baker must store there. Give texel centres to bake a texel.
/// Domain: uv clamped to [0, 1]^2, g to [RK_PARABOLOID_GUARD_MIN, 1].
/// Max error: the uv -> dir -> uv round trip with rk_dual_paraboloid_uv is within 4.3e-7 inside
/// the disks (a uv on the rim of the right half comes back in the left half, 0.5 away).
/// Cost: 1 div + rk_paraboloid_decode.
RK_INLINE vec3 rk_dual_paraboloid_dir(vec2 uv, float guard_scale)
{
    float g = clamp(guard_scale, RK_PARABOLOID_GUARD_MIN, 1.0f);
    float u = rk_saturate(uv.x);
    float v = rk_saturate(uv.y);
    float h = u < 0.5f ? 1.0f : -1.0f;
    float uh = h > 0.0f ? 2.0f * u : 2.0f * u - 1.0f;
    vec2 st = vec2(2.0f * uh - 1.0f, 2.0f * v - 1.0f) / g;
    return rk_paraboloid_decode(st, h);
}

// ---------------------------------------------------------------------------------------------
// LOD selection (thesis §3.3: a per-pixel LOD bias from the angle of incidence)

/// rk_paraboloid_lod_from_incidence: the thesis's blur of window reflections as a LOD (or bias)
/// that grows with the angle of incidence: lod_at_grazing * (1 - cos_i). The thesis gives no
/// function; linear in (1 - cos) is 0 at normal incidence, lod_at_grazing at grazing incidence and
/// grows fastest where the ghost images of the pane's internal reflections separate most.
/// cos_i clamped to [0, 1], lod_at_grazing to [0, 16]. 2 roundings (1.5 ulp). Cost: 2 flops.
RK_INLINE float rk_paraboloid_lod_from_incidence(float cos_i, float lod_at_grazing)
{
    return clamp(lod_at_grazing, 0.0f, 16.0f) * (1.0f - rk_saturate(cos_i));
}

/// rk_paraboloid_texel_angle: the angle (radians) one level-0 texel spans at st in an atlas with
/// halves of half_size texels and guard scale g: one texel spans 2 / (g half_size) of st and one
/// unit of st spans 2 / (1 + s^2 + t^2) radians, so the texel angle is
/// 4 / ((1 + s^2 + t^2) g half_size): largest at the centre, half of it on the rim. For a single
/// square map of n texels pass half_size = n. Domain: st as rk_paraboloid_solid_angle_density,
/// half_size clamped to [1, 2^24], guard_scale to [RK_PARABOLOID_GUARD_MIN, 1]. Max error: 4.2 ulp
/// (2e7 random + refinement). Cost: 1 div, 5 flops.
RK_INLINE float rk_paraboloid_texel_angle(vec2 st, float half_size, float guard_scale)
{
    float r2 = min(st.x * st.x + st.y * st.y, 1.0e18f);
    float n = clamp(half_size, 1.0f, 16777216.0f);
    float g = clamp(guard_scale, RK_PARABOLOID_GUARD_MIN, 1.0f);
    return 4.0f / ((1.0f + r2) * g * n);
}

/// rk_paraboloid_lod_for_cone: the mip level whose texels span `cone_angle` radians at st:
/// log2(cone_angle / rk_paraboloid_texel_angle(st, ...)), clamped to [0, max_lod] (max_lod to
/// [0, 16]). Converts a physical blur (e.g. a roughness or the spread of the pane's ghost images)
/// into an explicit LOD for textureLod; a cone of one texel gives 0, twice that 1.
/// cone_angle clamped to [1e-20, 1e20]. Max error: that of log2 (GLSL: 3 ulp). Cost: 2 log2 + texel
/// angle.
RK_INLINE float rk_paraboloid_lod_for_cone(vec2 st, float cone_angle, float half_size, float guard_scale,
                                           float max_lod)
{
    float a = clamp(cone_angle, 1.0e-20f, 1.0e20f);
    float lod = log2(a) - log2(rk_paraboloid_texel_angle(st, half_size, guard_scale));
    return clamp(lod, 0.0f, clamp(max_lod, 0.0f, 16.0f));
}

// ---------------------------------------------------------------------------------------------
// Rendering into a paraboloid map (Brabec et al. 2002)
//
// TESSELLATION CAVEAT: the projection below is non-linear and is applied per vertex, but the
// rasteriser interpolates linearly between the projected vertices, so a straight edge that should
// map to a curve stays straight and long triangles land in the wrong texels (thesis Fig. 3.10);
// triangles spanning both hemispheres are mangled (their far vertex projects outside the disk)
// and must be clipped (rk_paraboloid_clip_distance) and rendered again into the other half.
// Either tessellate so that every edge subtends a few texels at most, or do as the thesis does
// for environment maps: render a cube map and resample it (raykit::bake_dual_paraboloid). The
// direct projection suits well-tessellated occluders in dual-paraboloid shadow maps.

/// rk_paraboloid_depth_encode: linear-distance depth (dist - z_near) / (z_far - z_near) in [0, 1]
/// (Brabec: the distance to the centre, not a projective z). Domain: all three clamped to
/// [0, RK_PARABOLOID_POS_MAX]; z_far - z_near floored at 1e-18; the result clamped to
/// [-1e6, 1e6]. Max error: 2.5 ulp (2e7 random + refinement). Cost: 1 div, 2 flops.
RK_INLINE float rk_paraboloid_depth_encode(float dist, float z_near, float z_far)
{
    float d = clamp(dist, 0.0f, RK_PARABOLOID_POS_MAX);
    float n = clamp(z_near, 0.0f, RK_PARABOLOID_POS_MAX);
    float f = clamp(z_far, 0.0f, RK_PARABOLOID_POS_MAX);
    return clamp((d - n) / max(f - n, 1.0e-18f), -1.0e6f, 1.0e6f);
}

/// rk_paraboloid_depth_decode: the distance of a depth from rk_paraboloid_depth_encode,
/// z_near + depth (z_far - z_near). Domain: depth clamped to [-1e6, 1e6], z_near and z_far to
/// [0, RK_PARABOLOID_POS_MAX]. Edge cases: depth 0 gives z_near, 1 z_far, outside [0, 1] the
/// linear continuation; it inverts rk_paraboloid_depth_encode only for z_far > z_near (encode
/// floors the range at 1e-18, decode does not reorder it).
/// Max error vs float64: 2.0e-7 of z_far (depth in [-0.5, 1.5], z_near in [0.01, 1], z_far up to
/// 1e4; 2e7 random + refinement; tests/test_paraboloid.cpp ProjectionAndDepthAgainstFloat64); the
/// same bits on llvmpipe (GPU parity). Cost: 1 sub, 1 mul, 1 add (or 1 fma), 3 clamps.
RK_INLINE float rk_paraboloid_depth_decode(float depth, float z_near, float z_far)
{
    float n = clamp(z_near, 0.0f, RK_PARABOLOID_POS_MAX);
    float f = clamp(z_far, 0.0f, RK_PARABOLOID_POS_MAX);
    return n + clamp(depth, -1.0e6f, 1.0e6f) * (f - n);
}

/// rk_paraboloid_project: Brabec-style clip-space position of a vertex at p (in the map's frame,
/// relative to its centre) for the half hemi, when rendering straight into one half of the atlas
/// (glViewport on that half, so NDC [-1, 1] covers it): xy = guard_scale * rk_paraboloid_encode(p),
/// z = 2 depth - 1 with the linear-distance depth (GL's default depth range; with
/// glClipControl(GL_ZERO_TO_ONE) or Vulkan use rk_paraboloid_depth_encode instead), w = 1 (no
/// perspective division: the caveat above). Pair with rk_paraboloid_clip_distance. Domain: p
/// clamped to ±RK_PARABOLOID_POS_MAX, z_near/z_far as rk_paraboloid_depth_encode, guard_scale to
/// [RK_PARABOLOID_GUARD_MIN, 1], hemi as everywhere here. Edge cases: p = 0 (each component below
/// RK_FLT_MIN) returns (0, 0, -2, 1) (clipped); p in the other hemisphere gives |xy| > g (outside
/// the half's disk, culled by rk_paraboloid_clip_distance); the exact antipode of d0 gives xy = (0,
/// 0); distances beyond z_far give z > 1 and below z_near z < -1 (clipped by the depth range). Max
/// error vs float64 g (x, y) / (|p| + hemi z) and 2 (|p| - z_near) / (z_far - z_near) - 1: 2.6e-7
/// in xy, 4.9e-7 of max(1, |z|) in z (|p| in 1e-3..1e4 in the half's hemisphere, z_far up to 1e4;
/// 2e7 random + refinement; tests/test_paraboloid.cpp ProjectionAndDepthAgainstFloat64); llvmpipe
/// within 48 ulp of the CPU (GPU parity). Cost: 1 sqrt, 1 rsqrt, 4 div, ~35 flops, 6 clamps.
RK_INLINE vec4 rk_paraboloid_project(vec3 p, float z_near, float z_far, float hemi, float guard_scale)
{
    vec3 q = clamp(p, vec3(-RK_PARABOLOID_POS_MAX), vec3(RK_PARABOLOID_POS_MAX));
    float m = rk_paraboloid_max_abs(q);
    if (m < RK_FLT_MIN) {
        return vec4(0.0f, 0.0f, -2.0f, 1.0f);
    }
    // |q| scaled by its largest component: the squares of a tiny q would be subnormal (flushed on
    // a GPU, which would then see p = 0).
    float dist = m * length(q / m);  // <= 1.8e18, no overflow
    float g = clamp(guard_scale, RK_PARABOLOID_GUARD_MIN, 1.0f);
    vec2 st = rk_paraboloid_encode(q, hemi);
    float z = 2.0f * rk_paraboloid_depth_encode(dist, z_near, z_far) - 1.0f;
    return vec4(g * st.x, g * st.y, z, 1.0f);
}

/// rk_paraboloid_clip_distance: a gl_ClipDistance value that is >= 0 for the directions one half
/// of the atlas covers up to its edge (|st| <= 1 / guard_scale, the hemisphere plus the guard
/// band): hemi p.z - z_min |p| with z_min = (g^2 - 1) / (g^2 + 1) <= 0, the cone of the edge
/// (the plane hemi z = 0 when g = 1, Brabec's hemisphere cull). The rasteriser interpolates it
/// linearly, so for large triangles the clip edge is approximate (the tessellation caveat).
/// p clamped to ±RK_PARABOLOID_POS_MAX. Max error: 3.7 ulp of |p| (2e7 random + refinement).
/// Cost: 1 sqrt, 1 div, 4 flops.
RK_INLINE float rk_paraboloid_clip_distance(vec3 p, float hemi, float guard_scale)
{
    float h = rk_paraboloid_hemi_sign(hemi);
    vec3 q = clamp(p, vec3(-RK_PARABOLOID_POS_MAX), vec3(RK_PARABOLOID_POS_MAX));
    float g = clamp(guard_scale, RK_PARABOLOID_GUARD_MIN, 1.0f);
    float g2 = g * g;
    float z_min = (g2 - 1.0f) / (g2 + 1.0f);
    return h * q.z - z_min * length(q);
}

#endif  // RK_PARABOLOID_GLSL
