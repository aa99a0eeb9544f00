// raykit — paraboloid_sample.glsl: the GLSL-only (texture-sampling) half of paraboloid.glsl:
// lookups of a dual-paraboloid atlas and of a single paraboloid map. The coordinate maths is in
// paraboloid.glsl (shared with C++); raykit::sample_dual_paraboloid in raykit/paraboloid.hpp is the
// CPU mirror of these lookups (bilinear / trilinear, as GL_LINEAR_MIPMAP_LINEAR would).
//
// Sampler setup for the atlas: GL_LINEAR_MIPMAP_LINEAR (or GL_LINEAR for one level),
// GL_CLAMP_TO_EDGE, no anisotropy unless the guard accounts for it (see
// rk_paraboloid_filter_footprint), GL_TEXTURE_MAX_LEVEL (or the lod clamp below) at most the
// max_lod the guard scale was computed for. The halves must be a multiple of 2^ceil(max_lod)
// texels wide so that the mips never mix them (raykit::bake_dual_paraboloid ensures it).
//
// Why not texture(atlas, uv): the implicit derivatives of uv jump by half the atlas where a 2x2
// pixel quad straddles the seam, and the GPU then picks the coarsest mip along the seam (a visible
// line). rk_dual_paraboloid_sample_grad passes analytic derivatives instead
// (rk_dual_paraboloid_uv_differential), continuous across the seam; rk_dual_paraboloid_sample_lod
// needs none. Fragment stage only (dFdx/dFdy).
//
// @rk-stages frag
// @rk-es 310
// @rk-es300
#ifndef RK_PARABOLOID_SAMPLE_GLSL
#define RK_PARABOLOID_SAMPLE_GLSL

#include "paraboloid.glsl"

/// rk_dual_paraboloid_sample_lod: the atlas at direction dir (any length) and an explicit LOD
/// (e.g. rk_paraboloid_lod_from_incidence or rk_paraboloid_lod_for_cone), clamped to
/// [0, max_lod], the LOD the guard scale g was made for. Cost: rk_dual_paraboloid_uv + 1 textureLod.
RK_INLINE vec4 rk_dual_paraboloid_sample_lod(sampler2D atlas, vec3 dir, float guard_scale, float lod, float max_lod)
{
    return textureLod(atlas, rk_dual_paraboloid_uv(dir, guard_scale), clamp(lod, 0.0f, max(max_lod, 0.0f)));
}

/// rk_dual_paraboloid_sample_lod_seamless: rk_dual_paraboloid_sample_lod with the seam cross-faded
/// over |z| < band (rk_dual_paraboloid_seam_weight; DualParaboloidMap::seam_band for an atlas
/// baked with DualParaboloidBakeOptions::seam_fade): inside the band both halves are read and
/// mixed, so the lookup is continuous across z = 0 instead of jumping by about h^2 / 4 rad.
/// band <= 0 is rk_dual_paraboloid_sample_lod. Cost: 1 textureLod, 2 inside the band (a branch).
RK_INLINE vec4 rk_dual_paraboloid_sample_lod_seamless(sampler2D atlas, vec3 dir, float guard_scale, float lod,
                                                      float max_lod, float band)
{
    float l = clamp(lod, 0.0f, max(max_lod, 0.0f));
    float w = rk_dual_paraboloid_seam_weight(dir, band);
    if (w >= 1.0f || w <= 0.0f) {
        return textureLod(atlas, rk_dual_paraboloid_uv_half(dir, guard_scale, w > 0.0f ? 1.0f : -1.0f), l);
    }
    vec4 plus = textureLod(atlas, rk_dual_paraboloid_uv_half(dir, guard_scale, 1.0f), l);
    vec4 minus = textureLod(atlas, rk_dual_paraboloid_uv_half(dir, guard_scale, -1.0f), l);
    return minus * (1.0f - w) + plus * w;
}

/// rk_dual_paraboloid_sample_grad: the atlas at direction dir with the LOD the hardware derives
/// from the screen-space change of dir (dFdx/dFdy of dir through the exact Jacobian), plus
/// lod_bias levels (the thesis's per-pixel bias from the angle of incidence: the gradients are
/// scaled by 2^bias, which is what a bias does to an isotropic LOD). The caller keeps the
/// resulting LOD within the guard's max_lod with GL_TEXTURE_MAX_LEVEL. Continuous across the seam.
/// Cost: rk_dual_paraboloid_uv + 2 differentials + 1 exp2 + 1 textureGrad.
RK_INLINE vec4 rk_dual_paraboloid_sample_grad(sampler2D atlas, vec3 dir, float guard_scale, float lod_bias)
{
    vec2 uv = rk_dual_paraboloid_uv(dir, guard_scale);
    float scale = exp2(clamp(lod_bias, -16.0f, 16.0f));
    vec2 dx = scale * rk_dual_paraboloid_uv_differential(dir, dFdx(dir), guard_scale);
    vec2 dy = scale * rk_dual_paraboloid_uv_differential(dir, dFdy(dir), guard_scale);
    return textureGrad(atlas, uv, dx, dy);
}

/// rk_paraboloid_sample_biased: the thesis's lookup of one square paraboloid map (the half-space a
/// window reflects; dir in the map's frame, e.g. world * rk_paraboloid_frame(N, up, -1)), with a
/// per-pixel LOD bias: texture(map, uv, bias). A single map has no seam, so the implicit
/// derivatives are fine; directions behind the window are clamped to the rim (|st| <= 1).
/// guard_scale as used when baking the map (1 for the thesis's layout, where the rim touches the
/// edge: sample it with GL_CLAMP_TO_EDGE). llvmpipe within 2.4e-6 (values in [0, 1]) of the CPU
/// sampling of the same map at the same LOD (raykit::sample_paraboloid at LOD 0, trilinear at
/// LOD = bias where uv steps one texel per pixel), biases -1..9, directions behind the window
/// included (tests/gpu/parity_paraboloid.cpp ParaboloidSampleBiased asserts 1e-5).
/// Cost: rk_paraboloid_encode + 1 texture.
RK_INLINE vec4 rk_paraboloid_sample_biased(sampler2D map, vec3 dir, float hemi, float guard_scale, float lod_bias)
{
    vec2 st = rk_paraboloid_encode(dir, hemi);
    float r2 = dot(st, st);
    st = r2 > 1.0f ? st * inversesqrt(r2) : st;
    return texture(map, rk_paraboloid_uv(st, guard_scale), clamp(lod_bias, -16.0f, 16.0f));
}

#endif  // RK_PARABOLOID_SAMPLE_GLSL
