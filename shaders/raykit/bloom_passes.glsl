// raykit — bloom_passes.glsl: the GLSL-only (texture-sampling) half of bloom: one function per pass
// of the chain. The math is in bloom.glsl (shared with C++); the CPU mirror of these passes is
// raykit::bloom_reference in raykit/bloom.hpp, and samples/common/rk_bloom_gl.hpp is a GL 4.5 host
// that runs them (its fragment shaders are a few lines of uniforms plus a call to one function here).
//
// The chain (Fahlén, "Illumination for Real-Time Rendering of Large Architectural Environments"
// (2005), §3.4.2: Kawase's downsampling followed by a Gaussian):
//   1. rk_bloom_prefilter:  full-size HDR -> 1/2: bright pass of 4 texels (texelFetch, clamped to
//      the edge), then their bilinear-weighted average (the 2x2 box for even sizes), optionally
//      Karis-weighted.
//   2. rk_bloom_downsample: 1/2 -> 1/4 -> 1/8 -> ... one GL_LINEAR fetch at the target texel's
//      centre (a 2x2 box for even sizes), sampler CLAMP_TO_EDGE.
//   3. rk_bloom_blur: on each of the last `levels` (1/8 .. 1/64), a separable Gaussian with the
//      merged linear-sampling taps of raykit::linear_sampled_taps as uniforms (sigma 3, radius 9:
//      11 fetches instead of 19), sampler CLAMP_TO_BORDER with a black border so nothing wraps
//      around and the image behaves as zero outside (the thesis's setting).
//   4. rk_bloom_gather_levels + rk_bloom_composite: magnify every blurred level bilinearly
//      (CLAMP_TO_EDGE) at the full-size pixel, weight, sum and composite with the HDR image.
// Fragment stage only (texture() with implicit derivatives).
//
// @rk-stages frag
#ifndef RK_BLOOM_PASSES_GLSL
#define RK_BLOOM_PASSES_GLSL

#include "bloom.glsl"

/// rk_bloom_fetch_edge: texelFetch of level 0 with the coordinate clamped to the texture
/// (CLAMP_TO_EDGE for texelFetch, which has no wrap mode); returns the RGB channels unsanitised.
/// Cost: 1 fetch.
RK_INLINE vec3 rk_bloom_fetch_edge(sampler2D tex, ivec2 p, ivec2 size)
{
    vec4 t = texelFetch(tex, clamp(p, ivec2(0), max(size - ivec2(1), ivec2(0))), 0);
    return vec3(t.x, t.y, t.z);
}

/// rk_bloom_prefilter: the first downsample. `frag` is gl_FragCoord.xy of a `dst_size` target
/// (1/2 of the source, rounded up); the four source texels around its centre are bright-passed
/// (rk_bloom_bright_pass, `mode` = RK_BLOOM_MODE_*) and averaged with their bilinear weights, times
/// the Karis weights when `karis` is true. Cost: 4 texelFetch + 4 bright passes + 1 average.
RK_INLINE vec3 rk_bloom_prefilter(sampler2D hdr, vec2 frag, vec2 dst_size, float threshold, float knee, int mode,
                                  bool karis)
{
    ivec2 size = textureSize(hdr, 0);
    vec2 p = vec2(rk_bloom_source_texel(frag.x, dst_size.x, float(size.x)),
                  rk_bloom_source_texel(frag.y, dst_size.y, float(size.y)));
    vec4 w = rk_bloom_bilinear_weights(p);
    ivec2 i = ivec2(floor(p));
    vec3 c0 = rk_bloom_bright_pass(rk_bloom_fetch_edge(hdr, i, size), threshold, knee, mode);
    vec3 c1 = rk_bloom_bright_pass(rk_bloom_fetch_edge(hdr, i + ivec2(1, 0), size), threshold, knee, mode);
    vec3 c2 = rk_bloom_bright_pass(rk_bloom_fetch_edge(hdr, i + ivec2(0, 1), size), threshold, knee, mode);
    vec3 c3 = rk_bloom_bright_pass(rk_bloom_fetch_edge(hdr, i + ivec2(1, 1), size), threshold, knee, mode);
    return karis ? rk_bloom_karis_average(c0, c1, c2, c3, w) : rk_bloom_weighted_average(c0, c1, c2, c3, w);
}

/// rk_bloom_downsample: one bilinear fetch at uv = gl_FragCoord.xy / target size (bind a
/// GL_LINEAR, CLAMP_TO_EDGE sampler): the 2x2 box of a 2:1 reduction. Cost: 1 fetch.
RK_INLINE vec3 rk_bloom_downsample(sampler2D src, vec2 uv)
{
    vec4 t = texture(src, uv);
    return vec3(t.x, t.y, t.z);
}

/// rk_bloom_blur: one direction of the separable Gaussian with merged linear-sampling taps.
/// taps[k] = (offset in texels, weight), one-sided, taps[0] = (0, w0) the centre; `count` taps used
/// (clamped to [1, RK_BLOOM_MAX_TAPS]); `texel_step` = direction / source size in uv, e.g.
/// vec2(1 / width, 0). Sum of taps[0].y * f(uv) + taps[k].y * (f(uv + o step) + f(uv - o step)).
/// Bind a GL_LINEAR, CLAMP_TO_BORDER (black) sampler. Cost: 2 count - 1 fetches (11 for sigma 3).
RK_INLINE vec3 rk_bloom_blur(sampler2D src, vec2 uv, vec2 texel_step, vec2 taps[RK_BLOOM_MAX_TAPS], int count)
{
    vec4 c = texture(src, uv);
    vec3 sum = taps[0].y * vec3(c.x, c.y, c.z);
    for (int k = 1; k < RK_BLOOM_MAX_TAPS; ++k) {
        if (k >= count) {
            break;
        }
        vec2 d = taps[k].x * texel_step;
        vec4 a = texture(src, uv + d);
        vec4 b = texture(src, uv - d);
        sum += taps[k].y * vec3(a.x + b.x, a.y + b.y, a.z + b.z);
    }
    return sum;
}

/// rk_bloom_gather_levels: the four blurred levels magnified to the full-size pixel at `uv`
/// (bilinear, bind CLAMP_TO_EDGE samplers) and summed with rk_bloom_sum_levels weights `w` (give
/// unused levels weight 0). Cost: 4 fetches + 4 madd.
RK_INLINE vec3 rk_bloom_gather_levels(sampler2D l0, sampler2D l1, sampler2D l2, sampler2D l3, vec2 uv, vec4 w)
{
    vec4 a = texture(l0, uv);
    vec4 b = texture(l1, uv);
    vec4 c = texture(l2, uv);
    vec4 d = texture(l3, uv);
    return rk_bloom_sum_levels(vec3(a.x, a.y, a.z), vec3(b.x, b.y, b.z), vec3(c.x, c.y, c.z), vec3(d.x, d.y, d.z), w);
}

/// rk_bloom_composite_pixel: the final pass at integer pixel `pixel` of the full-size HDR image:
/// rk_bloom_composite of the texel, its bright pass (for RK_BLOOM_COMPOSITE_CONSERVE) and `bloom`.
/// Cost: 1 texelFetch + 1 bright pass + 1 composite.
RK_INLINE vec3 rk_bloom_composite_pixel(sampler2D hdr, ivec2 pixel, vec3 bloom, float threshold, float knee,
                                        int bright_mode, float strength, int composite_mode)
{
    vec3 h = rk_bloom_fetch_edge(hdr, pixel, textureSize(hdr, 0));
    vec3 bright = rk_bloom_bright_pass(h, threshold, knee, bright_mode);
    return rk_bloom_composite(h, bright, bloom, strength, composite_mode);
}

#endif  // RK_BLOOM_PASSES_GLSL
