// raykit — luminance_reduce.glsl: GPU reduction of an HDR image to its log-average luminance
// (thesis §3.3.1, Eq. 3.14), with an optional log2-luminance histogram, and a finish pass that
// derives the percentile-trimmed average, robust min/max, Reinhard 2002 key and white point, eye
// adaptation and EV100 exposure without a read-back.
//
// GLSL-only: compute kernels using shared memory and buffers (the stage and binding plumbing can
// not be C++). All per-pixel and per-value math is the shared code of exposure.glsl, so the CPU
// references in raykit/exposure.hpp (log_average_luminance, luminance_histogram,
// histogram_stats) compute the same terms; tests/gpu/parity_exposure.cpp checks the chain against
// them (3840x2160 with zeros, denormals, 1e6-bright and NaN/Inf/negative pixels: 1e-4 relative).
// The GL 4.5 host that compiles and dispatches the chain is samples/common/rk_luminance_gl.hpp.
//
// The chain (a pass plan is raykit::reduction_chain(width, height, RK_LUMINANCE_REDUCE_TILE)):
//   1. rk_luminance_reduce_image: one workgroup per RK_LUMINANCE_REDUCE_TILE^2 pixel tile (64x64 by
//      default: 16x16 invocations, each summing a 4x4 interleaved sub-tile serially). Each pixel's
//      term rk_log2_luminance(rgb, delta) is summed by a pairwise tree in shared memory and the
//      tile's SUM is written to the scratch buffer; optionally the terms are binned into a shared
//      histogram, flushed with one atomicAdd per non-empty bin.
//   2. rk_luminance_reduce_partials: the same tree over the previous level's sums, 64x64 at a time,
//      until one sum is left (3840x2160: 60x34 sums, then 1).
//   3. rk_luminance_reduce_finish (one invocation): mean = sum / pixel count, log-average, histogram
//      scan, key/white, adaptation, exposure -> the RK_LUM_RESULT_* floats of the result buffer.
// Sums, not means, travel between passes: pixels outside the image contribute nothing, so sizes
// that are not multiples of the tile need no edge weights (a mean-of-blocks chain does; see
// rk_reduce_cover and raykit::reduce_chain_mean). Accuracy: a tree over <= 2^12 values per pass,
// 16-term serial sums per invocation; the rounding error on the mean is ~log2(N) * 2^-24 * mean|term|
// (a bound of 1.4e-6 * 60 stops even for 8.3 M pixels, i.e. < 1e-4 relative on the log-average in
// the worst case). Measured on llvmpipe at 3840x2160 (parity_exposure.cpp): the mean log2 differs
// from the float64-accumulated CPU reference by 5.7e-8 stops, the float log-averages are identical.
//
// Feature macros:
//   RK_LUMINANCE_REDUCE_SOURCE       0: the image is a sampler2D (any float format; texelFetch),
//                                    1: a float SSBO with 1, 3 or 4 floats per pixel (default 0)
//   RK_LUMINANCE_REDUCE_GROUP        invocations per workgroup side, a power of two (default 16)
//   RK_LUMINANCE_REDUCE_THREAD_TILE  pixels per invocation side (default 4; tile = group * this)
//   RK_LUMINANCE_HISTOGRAM_BINS      histogram bins (default 256)
//   RK_LUMINANCE_REDUCE_BINDING_*    image (sampler unit or SSBO), scratch, histogram, result
//                                    bindings (default 0, 1, 2, 3; at most 4 SSBOs, the ES 3.10 minimum)
// Declare the workgroup size in the entry point as
//   layout(local_size_x = RK_LUMINANCE_REDUCE_GROUP, local_size_y = RK_LUMINANCE_REDUCE_GROUP) in;
// (the finish pass may use local_size 1).
//
// @rk-stages comp
// @rk-es 310
// @rk-variants RK_LUMINANCE_REDUCE_SOURCE=1 | RK_LUMINANCE_REDUCE_GROUP=8 RK_LUMINANCE_REDUCE_THREAD_TILE=2 RK_LUMINANCE_HISTOGRAM_BINS=64
#ifndef RK_LUMINANCE_REDUCE_GLSL
#define RK_LUMINANCE_REDUCE_GLSL

#include "common.glsl"
#include "exposure.glsl"

#ifndef RK_LUMINANCE_REDUCE_SOURCE
#define RK_LUMINANCE_REDUCE_SOURCE 0
#endif
#if RK_LUMINANCE_REDUCE_SOURCE < 0 || RK_LUMINANCE_REDUCE_SOURCE > 1
#error "RK_LUMINANCE_REDUCE_SOURCE must be 0 (sampler2D) or 1 (float SSBO)"
#endif
RK_OPTION_CHECK(rk_option_luminance_reduce_source, RK_LUMINANCE_REDUCE_SOURCE);
#ifndef RK_LUMINANCE_REDUCE_GROUP
#define RK_LUMINANCE_REDUCE_GROUP 16
#endif
#if RK_LUMINANCE_REDUCE_GROUP < 1 || RK_LUMINANCE_REDUCE_GROUP > 32 || (RK_LUMINANCE_REDUCE_GROUP & (RK_LUMINANCE_REDUCE_GROUP - 1)) != 0
#error "RK_LUMINANCE_REDUCE_GROUP must be 1, 2, 4, 8, 16 or 32"
#endif
RK_OPTION_CHECK(rk_option_luminance_reduce_group, RK_LUMINANCE_REDUCE_GROUP);
#ifndef RK_LUMINANCE_REDUCE_THREAD_TILE
#define RK_LUMINANCE_REDUCE_THREAD_TILE 4
#endif
#if RK_LUMINANCE_REDUCE_THREAD_TILE < 1 || RK_LUMINANCE_REDUCE_THREAD_TILE > 64
#error "RK_LUMINANCE_REDUCE_THREAD_TILE must be in 1..64"
#endif
RK_OPTION_CHECK(rk_option_luminance_reduce_thread_tile, RK_LUMINANCE_REDUCE_THREAD_TILE);
#ifndef RK_LUMINANCE_HISTOGRAM_BINS
#define RK_LUMINANCE_HISTOGRAM_BINS 256
#endif
#if RK_LUMINANCE_HISTOGRAM_BINS < 1 || RK_LUMINANCE_HISTOGRAM_BINS > 4096
#error "RK_LUMINANCE_HISTOGRAM_BINS must be in 1..4096"
#endif
RK_OPTION_CHECK(rk_option_luminance_histogram_bins, RK_LUMINANCE_HISTOGRAM_BINS);
#ifndef RK_LUMINANCE_REDUCE_BINDING_IMAGE
#define RK_LUMINANCE_REDUCE_BINDING_IMAGE 0
#endif
#if RK_LUMINANCE_REDUCE_BINDING_IMAGE < 0 || RK_LUMINANCE_REDUCE_BINDING_IMAGE > 95
#error "RK_LUMINANCE_REDUCE_BINDING_IMAGE must be a binding in 0..95"
#endif
RK_OPTION_CHECK(rk_option_luminance_reduce_binding_image, RK_LUMINANCE_REDUCE_BINDING_IMAGE);
#ifndef RK_LUMINANCE_REDUCE_BINDING_SCRATCH
#define RK_LUMINANCE_REDUCE_BINDING_SCRATCH 1
#endif
#if RK_LUMINANCE_REDUCE_BINDING_SCRATCH < 0 || RK_LUMINANCE_REDUCE_BINDING_SCRATCH > 95
#error "RK_LUMINANCE_REDUCE_BINDING_SCRATCH must be a binding in 0..95"
#endif
RK_OPTION_CHECK(rk_option_luminance_reduce_binding_scratch, RK_LUMINANCE_REDUCE_BINDING_SCRATCH);
#ifndef RK_LUMINANCE_REDUCE_BINDING_HISTOGRAM
#define RK_LUMINANCE_REDUCE_BINDING_HISTOGRAM 2
#endif
#if RK_LUMINANCE_REDUCE_BINDING_HISTOGRAM < 0 || RK_LUMINANCE_REDUCE_BINDING_HISTOGRAM > 95
#error "RK_LUMINANCE_REDUCE_BINDING_HISTOGRAM must be a binding in 0..95"
#endif
RK_OPTION_CHECK(rk_option_luminance_reduce_binding_histogram, RK_LUMINANCE_REDUCE_BINDING_HISTOGRAM);
#ifndef RK_LUMINANCE_REDUCE_BINDING_RESULT
#define RK_LUMINANCE_REDUCE_BINDING_RESULT 3
#endif
#if RK_LUMINANCE_REDUCE_BINDING_RESULT < 0 || RK_LUMINANCE_REDUCE_BINDING_RESULT > 95
#error "RK_LUMINANCE_REDUCE_BINDING_RESULT must be a binding in 0..95"
#endif
RK_OPTION_CHECK(rk_option_luminance_reduce_binding_result, RK_LUMINANCE_REDUCE_BINDING_RESULT);

#define RK_LUMINANCE_REDUCE_THREADS (RK_LUMINANCE_REDUCE_GROUP * RK_LUMINANCE_REDUCE_GROUP)
#define RK_LUMINANCE_REDUCE_TILE (RK_LUMINANCE_REDUCE_GROUP * RK_LUMINANCE_REDUCE_THREAD_TILE)

#if RK_LUMINANCE_REDUCE_SOURCE == 0
layout(binding = RK_LUMINANCE_REDUCE_BINDING_IMAGE) uniform highp sampler2D rk_lr_image;
#else
layout(std430, binding = RK_LUMINANCE_REDUCE_BINDING_IMAGE) readonly buffer RkLumImage { float rk_lr_image[]; };
#endif
/// Partial sums of every level, one after the other (offsets chosen by the host).
layout(std430, binding = RK_LUMINANCE_REDUCE_BINDING_SCRATCH) buffer RkLumScratch { float rk_lr_scratch[]; };
/// RK_LUMINANCE_HISTOGRAM_BINS counts; the host clears it before the image pass.
layout(std430, binding = RK_LUMINANCE_REDUCE_BINDING_HISTOGRAM) buffer RkLumHistogram { uint rk_lr_histogram[]; };
/// RK_LUM_RESULT_COUNT floats (exposure.glsl); RK_LUM_RESULT_ADAPTED is also the adaptation state.
layout(std430, binding = RK_LUMINANCE_REDUCE_BINDING_RESULT) buffer RkLumResult { float rk_lr_result[]; };

shared float rk_lr_sum[RK_LUMINANCE_REDUCE_THREADS];
shared uint rk_lr_bins[RK_LUMINANCE_HISTOGRAM_BINS];

/// rk_lr_pixel_log2: the term rk_log2_luminance of pixel p (inside the image). channels: 1 reads
/// the first component as luminance; 3 or 4 read linear Rec.709 RGB. Error: that of
/// rk_log2_luminance (exposure.glsl). Cost: 1 texelFetch (source 0) or 1 / 3 SSBO loads (source 1,
/// plus 2 integer mads for the address), then rk_log2_luminance (1 dot for RGB, sanitise, 1 add,
/// 1 max, 1 log2).
RK_INLINE float rk_lr_pixel_log2(ivec2 p, ivec2 size, int channels, float delta)
{
#if RK_LUMINANCE_REDUCE_SOURCE == 0
    RK_UNUSED(size);
    vec4 t = texelFetch(rk_lr_image, p, 0);
    return channels == 1 ? rk_log2_luminance(t.x, delta) : rk_log2_luminance(vec3(t.x, t.y, t.z), delta);
#else
    uint c = uint(channels);
    uint base = (uint(p.y) * uint(size.x) + uint(p.x)) * c;
    if (c == 1u) {
        return rk_log2_luminance(rk_lr_image[base], delta);
    }
    return rk_log2_luminance(vec3(rk_lr_image[base], rk_lr_image[base + 1u], rk_lr_image[base + 2u]), delta);
#endif
}

/// rk_lr_group_sum: the workgroup-wide sum of one float per invocation, by a pairwise tree in
/// shared memory (error ~log2(threads) ulp instead of the serial sum's ~threads ulp). Every
/// invocation must call it (uniform control flow); every invocation gets the sum.
/// Cost: 1 shared store, then log2(RK_LUMINANCE_REDUCE_THREADS) rounds (8 at the default 16x16) of
/// one shared load + add + store by the lower half of the active invocations and one barrier each
/// (THREADS - 1 adds per workgroup in all; 1 + log2(THREADS) barriers), then 1 shared load.
RK_INLINE float rk_lr_group_sum(float v)
{
    uint i = gl_LocalInvocationIndex;
    rk_lr_sum[i] = v;
    memoryBarrierShared();
    barrier();
    for (uint s = uint(RK_LUMINANCE_REDUCE_THREADS) / 2u; s > 0u; s /= 2u) {
        if (i < s) {
            rk_lr_sum[i] += rk_lr_sum[i + s];
        }
        memoryBarrierShared();
        barrier();
    }
    return rk_lr_sum[0];
}

/// rk_lr_tile_origin: the first pixel this invocation reads in its workgroup's tile; it then reads
/// RK_LUMINANCE_REDUCE_THREAD_TILE^2 pixels RK_LUMINANCE_REDUCE_GROUP apart (neighbouring
/// invocations read neighbouring pixels: coalesced loads). Exact (integers). Cost: 2 integer mads.
RK_INLINE ivec2 rk_lr_tile_origin()
{
    return ivec2(int(gl_WorkGroupID.x), int(gl_WorkGroupID.y)) * RK_LUMINANCE_REDUCE_TILE +
           ivec2(int(gl_LocalInvocationID.x), int(gl_LocalInvocationID.y));
}

/// rk_luminance_reduce_image: pass 1. Dispatch ceil(size / RK_LUMINANCE_REDUCE_TILE) workgroups;
/// workgroup (x, y) writes the sum of its tile's terms to
/// rk_lr_scratch[out_offset + y * gl_NumWorkGroups.x + x]. With `histogram`, also adds every term's
/// rk_histogram_bin over [hist_min_log2, hist_max_log2] to rk_lr_histogram (cleared by the host).
/// `histogram` must be dynamically uniform.
/// Cost per invocation: RK_LUMINANCE_REDUCE_THREAD_TILE^2 (16 by default) rk_lr_pixel_log2 calls and
/// adds, one rk_lr_group_sum, 1 SSBO store by invocation 0; with `histogram` also, per pixel,
/// rk_histogram_bin (1 div) and 1 shared atomicAdd, plus a shared clear (1 barrier) and at most
/// BINS / THREADS global atomicAdds (one per non-empty bin per workgroup). Per workgroup:
/// RK_LUMINANCE_REDUCE_TILE^2 = 4096 pixels for one stored float (3840x2160: 60x34 workgroups).
RK_INLINE void rk_luminance_reduce_image(ivec2 size, int channels, float delta, bool histogram, float hist_min_log2,
                                         float hist_max_log2, uint out_offset)
{
    uint li = gl_LocalInvocationIndex;
    if (histogram) {
        for (uint b = li; b < uint(RK_LUMINANCE_HISTOGRAM_BINS); b += uint(RK_LUMINANCE_REDUCE_THREADS)) {
            rk_lr_bins[b] = 0u;
        }
        memoryBarrierShared();
        barrier();
    }
    ivec2 origin = rk_lr_tile_origin();
    float s = 0.0f;
    for (int ty = 0; ty < RK_LUMINANCE_REDUCE_THREAD_TILE; ++ty) {
        for (int tx = 0; tx < RK_LUMINANCE_REDUCE_THREAD_TILE; ++tx) {
            ivec2 p = origin + ivec2(tx, ty) * RK_LUMINANCE_REDUCE_GROUP;
            if (p.x < size.x && p.y < size.y) {
                float v = rk_lr_pixel_log2(p, size, channels, delta);
                s += v;
                if (histogram) {
                    uint bin = rk_histogram_bin(v, hist_min_log2, hist_max_log2, uint(RK_LUMINANCE_HISTOGRAM_BINS));
                    atomicAdd(rk_lr_bins[bin], 1u);
                }
            }
        }
    }
    // The tree's barriers also order the shared histogram's atomics before the flush below.
    float total = rk_lr_group_sum(s);
    if (li == 0u) {
        rk_lr_scratch[out_offset + gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = total;
    }
    if (histogram) {
        for (uint b = li; b < uint(RK_LUMINANCE_HISTOGRAM_BINS); b += uint(RK_LUMINANCE_REDUCE_THREADS)) {
            uint c = rk_lr_bins[b];
            if (c != 0u) {
                atomicAdd(rk_lr_histogram[b], c);
            }
        }
    }
}

/// rk_luminance_reduce_partials: passes 2..n. Reads the in_size grid of sums at
/// rk_lr_scratch[in_offset + y * in_size.x + x] and writes one sum per
/// RK_LUMINANCE_REDUCE_TILE^2 block, as rk_luminance_reduce_image does. Dispatch
/// ceil(in_size / RK_LUMINANCE_REDUCE_TILE) workgroups; the regions must not overlap.
/// Cost per invocation: RK_LUMINANCE_REDUCE_THREAD_TILE^2 SSBO loads and adds, one
/// rk_lr_group_sum, 1 SSBO store by invocation 0. Each pass divides the number of sums by
/// RK_LUMINANCE_REDUCE_TILE^2 (4096 by default).
RK_INLINE void rk_luminance_reduce_partials(ivec2 in_size, uint in_offset, uint out_offset)
{
    ivec2 origin = rk_lr_tile_origin();
    float s = 0.0f;
    for (int ty = 0; ty < RK_LUMINANCE_REDUCE_THREAD_TILE; ++ty) {
        for (int tx = 0; tx < RK_LUMINANCE_REDUCE_THREAD_TILE; ++tx) {
            ivec2 p = origin + ivec2(tx, ty) * RK_LUMINANCE_REDUCE_GROUP;
            if (p.x < in_size.x && p.y < in_size.y) {
                s += rk_lr_scratch[in_offset + uint(p.y) * uint(in_size.x) + uint(p.x)];
            }
        }
    }
    float total = rk_lr_group_sum(s);
    if (gl_LocalInvocationIndex == 0u) {
        rk_lr_scratch[out_offset + gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = total;
    }
}

/// rk_luminance_reduce_finish: the last step, run by one invocation. Reads the total at
/// rk_lr_scratch[in_offset] and writes the RK_LUM_RESULT_* values:
///   log-average = rk_log_average_from_sum(total, pixel_count) and its mean log2;
///   with `histogram`: one rk_histogram_scan over the bins (edges from [hist_min_log2, hist_max_log2])
///   giving the average over the percentile window [window.x, window.y], the robust min/max at the
///   percentiles robust.x / robust.y, and rk_reinhard_auto_key / rk_reinhard_auto_white from the
///   log-average and those; without it key 0.18, white RK_HDR_MAX (Eq. 3.17 without burn-out) and 0s;
///   adaptation: the state rk_lr_result[RK_LUM_RESULT_ADAPTED] moves towards the target (the
///   histogram average when `adapt_to_histogram`, else the log-average) by rk_adapt_luminance; it
///   is set to the target when `reset` or when the state is not a positive number (first frame);
///   EV100 and exposure (rk_exposure_from_luminance with ev_compensation) of the adapted value.
/// This is the same arithmetic as raykit::histogram_stats and the rk_ functions on the CPU.
/// Cost (serial, one invocation): without `histogram` the log-average, adaptation, EV100 and
/// exposure functions (a few div, log2, exp2/exp) and 12 buffer accesses (2 loads, 10 stores); with
/// it, 2 passes over the RK_LUMINANCE_HISTOGRAM_BINS counts (256 by default): a sum, then per bin 2
/// rk_histogram_bin_edge (1 div each) and rk_histogram_scan_bin (~25 flops), plus 2 exp2 and the
/// key/white functions: O(bins) latency in one invocation.
RK_INLINE void rk_luminance_reduce_finish(uint in_offset, float pixel_count, bool histogram, float hist_min_log2,
                                          float hist_max_log2, vec2 window, vec2 robust, bool adapt_to_histogram,
                                          float dt, float tau_up, float tau_down, float ev_compensation, bool reset)
{
    float sum = rk_lr_scratch[in_offset];
    float n = rk_exposure_clamp(pixel_count, 1.0f, RK_FLT_MAX);
    float mean = rk_exposure_clamp(sum / n, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX);
    float lavg = rk_log_average_from_sum(sum, pixel_count);
    float hist_avg = 0.0f;
    float rmin = 0.0f;
    float rmax = 0.0f;
    float key = RK_EXPOSURE_MIDDLE_GREY;
    float white = RK_HDR_MAX;
    if (histogram) {
        uint bins = uint(RK_LUMINANCE_HISTOGRAM_BINS);
        float total = 0.0f;
        for (uint b = 0u; b < bins; ++b) {
            total += float(rk_lr_histogram[b]);
        }
        rk_histogram_scan s = rk_histogram_scan_init();
        for (uint b = 0u; b < bins; ++b) {
            float e0 = rk_histogram_bin_edge(float(b), hist_min_log2, hist_max_log2, bins);
            float e1 = rk_histogram_bin_edge(float(b + 1u), hist_min_log2, hist_max_log2, bins);
            rk_histogram_scan_bin(s, float(rk_lr_histogram[b]), e0, e1, rk_saturate(window.x) * total,
                                  rk_saturate(window.y) * total, rk_saturate(robust.x) * total,
                                  rk_saturate(robust.y) * total);
        }
        hist_avg = rk_histogram_scan_average(s);
        rmin = exp2(rk_exposure_clamp(s.low_log2, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX));
        rmax = exp2(rk_exposure_clamp(s.high_log2, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX));
        key = rk_reinhard_auto_key(lavg, rmin, rmax);
        white = rk_reinhard_auto_white(rmin, rmax);
    }
    float target = (histogram && adapt_to_histogram) ? hist_avg : lavg;
    float prev = rk_lr_result[RK_LUM_RESULT_ADAPTED];
    float adapted = (reset || !(prev > 0.0f)) ? target : rk_adapt_luminance(prev, target, dt, tau_up, tau_down);
    rk_lr_result[RK_LUM_RESULT_LOG_AVERAGE] = lavg;
    rk_lr_result[RK_LUM_RESULT_MEAN_LOG2] = mean;
    rk_lr_result[RK_LUM_RESULT_HIST_AVERAGE] = hist_avg;
    rk_lr_result[RK_LUM_RESULT_ROBUST_MIN] = rmin;
    rk_lr_result[RK_LUM_RESULT_ROBUST_MAX] = rmax;
    rk_lr_result[RK_LUM_RESULT_KEY] = key;
    rk_lr_result[RK_LUM_RESULT_WHITE] = white;
    rk_lr_result[RK_LUM_RESULT_ADAPTED] = adapted;
    rk_lr_result[RK_LUM_RESULT_EV100] = rk_ev100_from_luminance(adapted);
    rk_lr_result[RK_LUM_RESULT_EXPOSURE] = rk_exposure_from_luminance(adapted, ev_compensation);
}

#endif  // RK_LUMINANCE_REDUCE_GLSL
