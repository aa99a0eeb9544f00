// raykit — normalmap.glsl: normal mapping (Fahlén, "Illumination for Real-Time Rendering of Large
// Architectural Environments", §6.2-6.3): the tangent frame from a per-vertex tangent with its
// handedness (Eq. 6.5, B = w · N × T), or from screen-space derivatives when no tangents are stored
// (Schüler's cotangent frame), two-channel normal-map unpacking with z rebuilt, and parallax offset
// mapping with offset limiting (Welsh 2004).
//
// Shared GLSL/C++ source (include/raykit/normalmap.hpp is the C++ build; include/raykit/tangents.hpp
// generates the per-vertex tangents on the CPU). The derivative-based frame takes dFdx / dFdy as
// arguments, so the same text runs on the CPU with analytic derivatives; a fragment shader passes
// dFdx(p), dFdy(p), dFdx(uv), dFdy(uv).
//
// Conventions: tangent space is (T, B, N) with T along increasing u and B along increasing v of the
// normal map (OpenGL's convention: v up; a DirectX-convention map has its green channel flipped:
// negate y after rk_nm_unpack_rg). The thesis's Eq. 6.4 prints Q1 = s1 T − t1 B; the derivation needs
// Q1 = s1 T + t1 B, which is what tangents.hpp solves.
//
// @rk-es 310
// @rk-es300
#ifndef RK_NORMALMAP_GLSL
#define RK_NORMALMAP_GLSL

#include "common.glsl"

/// rk_nm_basis_tangent: a unit tangent perpendicular to unit n, continuous except where n.z's sign
/// bit flips (Duff et al., "Building an Orthonormal Basis, Revisited", 2017; -0 is on the negative
/// side, so a subnormal n.z that a GPU flushes to a zero of the same sign picks the same side). The
/// fallback when a mesh gives no usable tangent. Exact to float rounding for unit n.
/// Cost: ~10 flops, 1 div.
RK_INLINE vec3 rk_nm_basis_tangent(vec3 n)
{
    float s = (floatBitsToUint(n.z) & 0x80000000u) != 0u ? -1.0f : 1.0f;
    float a = -1.0f / (s + n.z);
    float b = n.x * n.y * a;
    return vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
}

/// rk_nm_tbn: the tangent frame (columns T, B, N) from an interpolated normal and a tangent
/// (xyz, w = handedness ±1, as tangents.hpp and glTF store it): N normalised, T made perpendicular
/// to N (Gram–Schmidt) and normalised, B = sign(w) · N × T (Eq. 6.5). A zero or NaN normal gives
/// +z; a tangent within 0.26 degrees of N, zero or NaN gives rk_nm_basis_tangent(N). w = 0 counts
/// as +1. Orthonormal to 2e-6 (two Gram-Schmidt steps). Cost: ~35 flops, 4 rsqrt.
RK_INLINE mat3 rk_nm_tbn(vec3 n, vec4 t)
{
    vec3 nn = rk_normalize_safe(n, vec3(0.0f, 0.0f, 1.0f));
    // Normalised before Gram-Schmidt: the projection of a tiny tangent onto N would be subnormal.
    vec3 tt = rk_normalize_safe(vec3(t.x, t.y, t.z), vec3(0.0f));
    vec3 tp = rk_normalize_safe(tt - nn * dot(nn, tt), vec3(0.0f));
    // Within 0.26 degrees of n the tangent carries no usable direction: use the basis instead.
    if (dot(tp, tp) == 0.0f || abs(dot(nn, tt)) > 0.99999f) tp = rk_nm_basis_tangent(nn);
    // A second Gram-Schmidt step: the first leaves a residue of rounding / sin(angle(t, n)).
    tp = rk_normalize_safe(tp - nn * dot(nn, tp), rk_nm_basis_tangent(nn));
    float w = t.w < 0.0f ? -1.0f : 1.0f;
    vec3 b = cross(nn, tp) * w;
    return mat3(tp, b, nn);
}

/// rk_nm_perturb: the shading normal of tangent-space normal `n_ts` (from a normal map) in the frame
/// `tbn` (rk_nm_tbn or rk_nm_cotangent_frame), normalised; a zero n_ts gives the frame's N.
/// Cost: 1 mat3 * vec3, 1 rsqrt.
RK_INLINE vec3 rk_nm_perturb(mat3 tbn, vec3 n_ts) { return rk_normalize_safe(tbn * n_ts, tbn[2]); }

/// rk_nm_unpack_rg: a two-channel normal map texel (BC5 / RG8, values in [0, 1]) -> unit tangent-
/// space normal: xy = 2 rg - 1, z = sqrt(1 - x² - y²) >= 0 (outside the unit disk, after filtering
/// or compression, xy is scaled back onto the circle and z = 0). Max error: float rounding (2 ulp)
/// inside the disk. Cost: ~8 flops, 1 sqrt, 1 rsqrt.
RK_INLINE vec3 rk_nm_unpack_rg(vec2 rg)
{
    float x = clamp(rg.x * 2.0f - 1.0f, -1.0f, 1.0f);
    float y = clamp(rg.y * 2.0f - 1.0f, -1.0f, 1.0f);
    vec3 v = vec3(x, y, sqrt(max(1.0f - x * x - y * y, 0.0f)));
    return v * inversesqrt(max(dot(v, v), RK_FLT_MIN));
}

/// rk_nm_cotangent_frame: a tangent frame without stored tangents (Schüler, "Normal Mapping Without
/// Precomputed Tangents", 2013), from the unit normal n and the screen-space derivatives of the
/// position (dp_dx, dp_dy) and of the normal map's uv (duv_dx, duv_dy): T and B solve the
/// derivatives' 2x2 system projected on the tangent plane, scaled by one common factor
/// (1 / max(|T|, |B|): the map's aspect ratio is kept, as Schüler does). For rk_nm_perturb, whose
/// result it normalises. Mirrored uv comes out as a left-handed frame by itself. Degenerate
/// derivatives (zero area in uv or on screen, NaN, overflow) give the frame of rk_nm_tbn(n, basis
/// tangent).
/// Cost: 2 cross, ~20 flops, 1 rsqrt.
RK_INLINE mat3 rk_nm_cotangent_frame(vec3 n, vec3 dp_dx, vec3 dp_dy, vec2 duv_dx, vec2 duv_dy)
{
    vec3 nn = rk_normalize_safe(n, vec3(0.0f, 0.0f, 1.0f));
    vec3 dp2perp = cross(dp_dy, nn);
    vec3 dp1perp = cross(nn, dp_dx);
    vec3 t = dp2perp * duv_dx.x + dp1perp * duv_dy.x;
    vec3 b = dp2perp * duv_dx.y + dp1perp * duv_dy.y;
    float tt = dot(t, t);
    float bb = dot(b, b);
    float m = max(tt, bb);
    // Each length checked (max() may drop a NaN): NaN, infinite or vanishing derivatives fall back.
    if (!(m >= 1e-36f) || !(tt <= 1e36f) || !(bb <= 1e36f)) return rk_nm_tbn(nn, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    float k = inversesqrt(m);
    return mat3(t * k, b * k, nn);
}

/// rk_nm_parallax_offset: parallax mapping with offset limiting (Welsh, "Parallax Mapping with
/// Offset Limiting", 2004): uv + (h · scale + bias) · v_ts.xy, where h in [0, 1] is the height-map
/// texel and v_ts the unit tangent-space vector from the surface towards the eye. Offset limiting
/// drops the division by v_ts.z, so the offset never exceeds |h · scale + bias| at grazing angles.
/// Welsh's typical scale and bias: 0.04 and -0.02 (the offset's range is then ±0.02 uv). Returns
/// uv unchanged when h · scale + bias = 0 or the view is along the normal. h is clamped to [0, 1]
/// (NaN reads as 0) and the result to ±RK_FLT_MAX, so any finite input gives a finite uv.
/// Cost: 2 fma, 3 clamps.
RK_INLINE vec2 rk_nm_parallax_offset(vec2 uv, float h, vec3 v_ts, float scale, float bias)
{
    float hc = h > 0.0f ? min(h, 1.0f) : 0.0f;
    float o = clamp(hc * scale + bias, -RK_FLT_MAX, RK_FLT_MAX);
    return clamp(vec2(uv.x + o * v_ts.x, uv.y + o * v_ts.y), vec2(-RK_FLT_MAX), vec2(RK_FLT_MAX));
}

#endif  // RK_NORMALMAP_GLSL
