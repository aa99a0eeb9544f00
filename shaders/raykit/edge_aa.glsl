// raykit — edge_aa.glsl: edge anti-aliasing for a deferred renderer (Fahlén, "Illumination for
// Real-Time Rendering of Large Architectural Environments", §2.4, after Shishkovtsov, "Deferred
// Shading in S.T.A.L.K.E.R.", GPU Gems 2 ch. 9): a G-buffer has no multisampling, so edges are
// found from depth and normal discontinuities in a 3x3 neighbourhood and the final image is blurred
// there by four lookups offset by the edge strength.
//
// Shared GLSL/C++ source (include/raykit/edge_aa.hpp is the C++ build). The texture reads belong to
// the application's pass: it reads the nine depths and five normals and calls these functions.
// Depths must be affine in 1/distance, which window depth is in every convention
// (rk_gb_linear_depth's input, not its output): a plane then has zero second difference across the
// screen, so flat surfaces never count as edges however steep they are.
//
// @rk-es 310
// @rk-es300
#ifndef RK_EDGE_AA_GLSL
#define RK_EDGE_AA_GLSL

#include "common.glsl"

/// rk_aa_kink: how far the centre c of three collinear depth samples a, c, b (window depth) is
/// from the straight line through a and b, relative to the steps: |a + b - 2c| / (|a - c| + |b - c|),
/// 0 on a plane, 1 at a step (one side flat, the other jumps) or a crease of opposite slopes.
/// Cost: 5 flops, 1 div.
RK_INLINE float rk_aa_kink(float a, float c, float b)
{
    float s = abs(a - c) + abs(b - c);
    return s > 1e-7f ? min(abs(a + b - 2.0f * c) / s, 1.0f) : 0.0f;
}

/// rk_aa_depth_edge: the depth discontinuity at a pixel from its 3x3 window depths (row by row:
/// d00 d10 d20 / d01 d11 d21 / d02 d12 d22, d11 the centre): the largest rk_aa_kink over the
/// horizontal, vertical and two diagonal lines through the centre, mapped to [0, 1] by a
/// smoothstep from `threshold` to 2 · threshold (threshold in (0, 0.5], e.g. 0.2: a kink ratio
/// under it is a curved surface, not an edge). A line whose two steps sum to less than
/// min_step · |d11| (relative, e.g. 1e-5) does not count: along a plane's iso-depth direction the
/// steps vanish and the ratio would measure rounding (a few ulps of the depth: 1e-5 keeps that
/// below 0.04). Cost: ~40 flops, 4 div.
RK_INLINE float rk_aa_depth_edge(float d00, float d10, float d20, float d01, float d11, float d21, float d02, float d12,
                                 float d22, float threshold, float min_step)
{
    float k = 0.0f;
    float ms = max(min_step, 0.0f) * abs(d11);
    if (abs(d01 - d11) + abs(d21 - d11) > ms) k = max(k, rk_aa_kink(d01, d11, d21));
    if (abs(d10 - d11) + abs(d12 - d11) > ms) k = max(k, rk_aa_kink(d10, d11, d12));
    if (abs(d00 - d11) + abs(d22 - d11) > ms) k = max(k, rk_aa_kink(d00, d11, d22));
    if (abs(d20 - d11) + abs(d02 - d11) > ms) k = max(k, rk_aa_kink(d20, d11, d02));
    float t = clamp(threshold, 1e-3f, 0.5f);
    return smoothstep(t, 2.0f * t, k);
}

/// rk_aa_normal_edge: the normal discontinuity at a pixel: 1 - the smallest cosine between the
/// centre's unit normal and its four edge neighbours', mapped by a smoothstep from `threshold` to
/// 2 · threshold (e.g. 0.1: about 25 to 37 degrees). Catches creases that depth alone misses (a wall
/// meeting a floor seen so that the depth kink is slight). Cost: 4 dot, ~10 flops.
RK_INLINE float rk_aa_normal_edge(vec3 nc, vec3 nl, vec3 nr, vec3 nu, vec3 nd, float threshold)
{
    float c = min(min(dot(nc, nl), dot(nc, nr)), min(dot(nc, nu), dot(nc, nd)));
    float t = clamp(threshold, 1e-3f, 1.0f);
    return smoothstep(t, 2.0f * t, 1.0f - clamp(c, -1.0f, 1.0f));
}

/// rk_aa_combine: the edge weight from the two terms: the thesis multiplies them (an edge must show
/// in both: robust against noise in either, blind to creases whose depth kink is slight), raykit
/// defaults to their maximum (either suffices). mode 0: max, 1: product (the thesis).
/// Cost: 1 select.
RK_INLINE float rk_aa_combine(float depth_edge, float normal_edge, uint mode)
{
    return mode == 1u ? depth_edge * normal_edge : max(depth_edge, normal_edge);
}

/// rk_aa_blur_offset: the k-th (0..3) of the four lookup offsets (in texels) of the edge blur: the
/// diagonals (±0.5, ±0.5) scaled by the edge weight, so weight 0 reads the pixel itself four times
/// and weight 1 averages the 2x2 neighbourhoods around it with bilinear filtering (a small box blur).
/// Cost: 2 selects, 2 mul.
RK_INLINE vec2 rk_aa_blur_offset(uint k, float edge)
{
    float e = edge > 0.0f ? min(edge, 1.0f) * 0.5f : 0.0f;  // NaN reads the pixel itself
    return vec2((k & 1u) != 0u ? e : -e, (k & 2u) != 0u ? e : -e);
}

#endif  // RK_EDGE_AA_GLSL
