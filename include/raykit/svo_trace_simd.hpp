// raykit — svo_trace_simd.hpp: rk_svo_trace for many rays at once on the CPU. The set-up and the
// hit of every ray are svo_traverse.glsl's own (rk_svo_trace_begin_, rk_svo_trace_finish_); the
// traversal loop between them runs on 8 SIMD lanes (AVX2), each lane taking the next ray as soon as
// its own finishes, so that lanes stay busy whatever the rays' lengths.
//
// This loop is a C++ twin of rk_svo_trace's, not shared text: GLSL has no lanes to program. It
// performs the same float operations in the same order, so its answers are bit for bit those of
// rk_svo_trace (hit, t, level, cell, normal, node, brick fields, iterations) as long as neither is
// compiled with floating-point contraction into fused multiply-adds (GCC and Clang contract only
// with an FMA target such as -march=haswell and without -ffp-contract=off); test_svo_trace_simd
// checks it on random, adversarial and camera rays at several depths, with and without LOD.
//
// The lanes need x86-64 and a CPU with AVX2: with GCC and Clang the code is compiled for AVX2 and
// chosen at run time (__builtin_cpu_supports), with MSVC when the translation unit is built with
// /arch:AVX2. Elsewhere (other CPUs, other compilers) svo_trace_rays calls rk_svo_trace per ray.
// clang-cl takes the Clang path, whose __builtin_cpu_supports needs LLVM's compiler-rt builtins
// library at link time on Windows (not linked by default); it is not built or tested here.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raykit/svo_traverse.hpp"

#if (defined(__x86_64__) || defined(_M_X64)) && (defined(__GNUC__) || defined(__clang__))
#define RK_SVO_RAYS_SIMD 1
#define RK_SVO_RAYS_TARGET __attribute__((target("avx2")))
#elif defined(_M_X64) && defined(_MSC_VER) && defined(__AVX2__)
#define RK_SVO_RAYS_SIMD 1
#define RK_SVO_RAYS_TARGET
#else
#define RK_SVO_RAYS_SIMD 0
#define RK_SVO_RAYS_TARGET
#endif
#if RK_SVO_RAYS_SIMD
#include <immintrin.h>
#endif

// The namespace spells the lanes' availability too: an MSVC build with /arch:AVX2 and one without
// are different functions.
#define RK_SVO_RAYS_NS_CAT_(s) svo_rays_simd##s
#define RK_SVO_RAYS_NS_CAT(s) RK_SVO_RAYS_NS_CAT_(s)

namespace raykit {
inline namespace RK_SVO_TRAVERSE_NS {
inline namespace RK_SVO_RAYS_NS_CAT(RK_SVO_RAYS_SIMD) {

/// One ray of svo_trace_rays: rk_svo_trace(words, tree, origin, dir, t_max, cone).
struct SvoRay {
    glm::vec3 origin{0.0f};
    glm::vec3 dir{0.0f, 0.0f, 1.0f};
    float t_max = RK_FLT_MAX;
};

/// How svo_trace_rays runs: `best` uses the SIMD lanes where the CPU has them, `scalar` calls
/// rk_svo_trace per ray (the same answers; for comparisons).
enum class SvoTraceMode { best, scalar };

/// svo_trace_simd_available: whether svo_trace_rays(..., SvoTraceMode::best) runs on SIMD lanes on
/// this CPU with this build.
inline bool svo_trace_simd_available()
{
#if RK_SVO_RAYS_SIMD && (defined(__GNUC__) || defined(__clang__))
    return __builtin_cpu_supports("avx2") != 0;
#else
    return RK_SVO_RAYS_SIMD != 0;
#endif
}

namespace svo_rays_detail {

#if RK_SVO_RAYS_SIMD
constexpr int kLanes = 8;

// The loop state of 8 lanes, one array per field (the fields of rk_svo_trace_state_ that the loop
// reads or writes), and each lane's stack as stk_*[level][lane].
struct alignas(32) Lanes {
    float px[kLanes], py[kLanes], pz[kLanes];
    float cx[kLanes], cy[kLanes], cz[kLanes];
    float bx[kLanes], by[kLanes], bz[kLanes];
    float size[kLanes], t_min[kLanes], t_hi[kLanes], t_end[kLanes], t_enter[kLanes];
    int32_t flip[kLanes], scale[kLanes], idx[kLanes], iter[kLanes];
    uint32_t handle[kLanes], pdesc[kLanes], bmx[kLanes], bmy[kLanes], bsub[kLanes], brick[kLanes], pmask[kLanes];
    // One row more than the levels: the lanes that do not push write there (no branch per lane).
    uint32_t stk_node[RK_SVO_TRAVERSE_STACK + 1][kLanes];
    float stk_tmax[RK_SVO_TRAVERSE_STACK + 1][kLanes];
};

inline void lane_in(Lanes& L, int i, const rk_svo_trace_state_& s)
{
    L.px[i] = s.pos.x;
    L.py[i] = s.pos.y;
    L.pz[i] = s.pos.z;
    L.cx[i] = s.coef.x;
    L.cy[i] = s.coef.y;
    L.cz[i] = s.coef.z;
    L.bx[i] = s.bias.x;
    L.by[i] = s.bias.y;
    L.bz[i] = s.bias.z;
    L.size[i] = s.size;
    L.t_min[i] = s.t_min;
    L.t_end[i] = s.t_end;
    L.t_hi[i] = s.t_hi;
    L.t_enter[i] = s.t_enter;
    L.flip[i] = static_cast<int32_t>(s.flip);
    L.scale[i] = s.scale;
    L.idx[i] = static_cast<int32_t>(s.idx);
    L.iter[i] = 0;
    L.handle[i] = s.handle;
    L.pdesc[i] = s.pdesc;
    L.bmx[i] = s.bmask.x;
    L.bmy[i] = s.bmask.y;
    L.bsub[i] = s.bsub;
    L.brick[i] = s.brick;
    L.pmask[i] = s.pmask;
}

inline void lane_out(const Lanes& L, int i, rk_svo_trace_state_& s)
{
    s.pos = glm::vec3(L.px[i], L.py[i], L.pz[i]);
    s.size = L.size[i];
    s.t_min = L.t_min[i];
    s.t_hi = L.t_hi[i];
    s.scale = L.scale[i];
    s.idx = static_cast<uint32_t>(L.idx[i]);
    s.handle = L.handle[i];
    s.pdesc = L.pdesc[i];
    s.bmask = glm::uvec2(L.bmx[i], L.bmy[i]);
    s.bsub = L.bsub[i];
    s.brick = L.brick[i];
    s.pmask = L.pmask[i];
}

// GLM's min(x, y) is (y < x) ? y : x and max(x, y) is (x < y) ? y : x; _mm256_min_ps(a, b) is
// (a < b) ? a : b and _mm256_max_ps(a, b) is (a > b) ? a : b: the same choices, signed zeros
// included, with the operands swapped.
RK_SVO_RAYS_TARGET inline __m256 glm_min(__m256 x, __m256 y) { return _mm256_min_ps(y, x); }
RK_SVO_RAYS_TARGET inline __m256 glm_max(__m256 x, __m256 y) { return _mm256_max_ps(y, x); }
RK_SVO_RAYS_TARGET inline __m256i bits(__m256 v) { return _mm256_castps_si256(v); }
RK_SVO_RAYS_TARGET inline __m256 flt(__m256i v) { return _mm256_castsi256_ps(v); }
RK_SVO_RAYS_TARGET inline __m256i ne0(__m256i v)  // all ones where v != 0
{
    return _mm256_xor_si256(_mm256_cmpeq_epi32(v, _mm256_setzero_si256()), _mm256_set1_epi32(-1));
}
RK_SVO_RAYS_TARGET inline __m256i sel(__m256i m, __m256i a, __m256i b) { return _mm256_blendv_epi8(b, a, m); }
RK_SVO_RAYS_TARGET inline __m256 self(__m256i m, __m256 a, __m256 b) { return _mm256_blendv_ps(b, a, _mm256_castsi256_ps(m)); }
inline int lowest_bit(unsigned m)
{
#if defined(_MSC_VER) && !defined(__clang__)
    unsigned long i;
    _BitScanForward(&i, m);
    return static_cast<int>(i);
#else
    return __builtin_ctz(m);
#endif
}

// Masked gather: src in the lanes outside `mask`.
RK_SVO_RAYS_TARGET inline __m256i gather(const uint32_t* base, __m256i index, __m256i mask, __m256i src)
{
    return _mm256_mask_i32gather_epi32(src, reinterpret_cast<const int*>(base), index, mask, 4);
}
// The same, skipped when no lane needs a load: for the rare ones (far slots, bricks), whose branch
// is then predicted well.
RK_SVO_RAYS_TARGET inline __m256i gather_rare(const uint32_t* base, __m256i index, __m256i mask, __m256i src)
{
    if (_mm256_testz_si256(mask, mask)) return src;
    return gather(base, index, mask, src);
}

RK_SVO_RAYS_TARGET inline __m256 cle(__m256 a, __m256 b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
RK_SVO_RAYS_TARGET inline __m256i cmask(__m256 m) { return _mm256_castps_si256(m); }

// bitCount of values below 256, per lane.
RK_SVO_RAYS_TARGET inline __m256i popcount8(__m256i x)
{
    const __m256i lut = _mm256_setr_epi8(0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4, 0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2,
                                         3, 3, 4);
    const __m256i lo = _mm256_and_si256(x, _mm256_set1_epi32(15));
    const __m256i hi = _mm256_srli_epi32(x, 4);
    return _mm256_add_epi32(_mm256_shuffle_epi8(lut, lo), _mm256_shuffle_epi8(lut, hi));
}

// rk_svo_brick_nonzero_bytes_ per lane: bit k where byte k of w is non-zero.
RK_SVO_RAYS_TARGET inline __m256i nonzero_bytes(__m256i w)
{
    const __m256i z = _mm256_cmpeq_epi8(w, _mm256_setzero_si256());
    const __m256i nz = _mm256_andnot_si256(z, _mm256_set1_epi32(0x08040201));
    return _mm256_srli_epi32(_mm256_mullo_epi32(nz, _mm256_set1_epi32(0x01010101)), 24);
}

// rk_svo_trace_child_mask_ per lane (levels as small non-negative ints).
RK_SVO_RAYS_TARGET inline __m256i child_mask(__m256i lp, __m256i top, __m256i pdesc, __m256i bmx, __m256i bmy, __m256i bsub,
                                             __m256i handle)
{
    const __m256i ff = _mm256_set1_epi32(0xFF);
    const __m256i w = sel(_mm256_cmpgt_epi32(_mm256_set1_epi32(4), handle), bmx, bmy);
    const __m256i sh = _mm256_slli_epi32(_mm256_and_si256(handle, _mm256_set1_epi32(3)), 3);
    const __m256i in_brick = _mm256_and_si256(_mm256_srlv_epi32(w, sh), ff);
    const __m256i r = sel(_mm256_cmpeq_epi32(lp, top), bsub, in_brick);
    return sel(_mm256_cmpgt_epi32(top, lp), _mm256_and_si256(pdesc, ff), r);
}

// What the lanes of one call share: the tree, the rays, and the loop's constants (computed once per
// call, as rk_svo_trace_begin_ computes them per ray).
struct Batch {
    const uint32_t* words;
    rk_svo_tree tree;
    const SvoRay* rays;
    std::size_t n;
    std::size_t next;
    glm::vec2 cone;
    rk_svo_trace_hit* hits;
    bool sub_masks;  // brick levels b == 2: a brick's sub-node mask is its non-zero bytes
    __m256i top, leaf, desc_words, bound;  // bound: rk_svo_trace_iteration_bound
#if RK_SVO_TRAVERSE_LOD
    __m256 lod_bias, lod_slope;
#endif
};

// A group of 8 lanes: their loop state, each lane's full rk_svo_trace_state_ (the set-up's fields
// the loop does not touch, for the finish) and ray index, and which lanes hold a ray.
struct Group {
    Lanes L{};
    rk_svo_trace_state_ st[kLanes];
    std::size_t ray_of[kLanes] = {};
    unsigned active = 0;  // lanes holding a ray
};

// Gives lane i of g the next ray that needs the loop (rays answered by the set-up are done at once).
inline void refill(Batch& c, Group& g, int i)
{
    while (c.next < c.n) {
        const std::size_t r = c.next++;
        if (rk_svo_trace_begin_(c.words, c.tree, c.rays[r].origin, c.rays[r].dir, c.rays[r].t_max, c.cone, c.hits[r], g.st[i])) {
            lane_in(g.L, i, g.st[i]);
            g.ray_of[i] = r;
            g.active |= 1u << i;
            return;
        }
    }
    g.active &= ~(1u << i);
}

#if defined(_MSC_VER) && !defined(__clang__)
#define RK_SVO_RAYS_FORCE_INLINE __forceinline
#else
#define RK_SVO_RAYS_FORCE_INLINE __attribute__((always_inline)) inline
#endif

// One loop iteration of the 8 lanes of g; lanes that finish are answered and refilled.
RK_SVO_RAYS_TARGET RK_SVO_RAYS_FORCE_INLINE void step(Batch& k, Group& g)
{
    const __m256i top = k.top, leaf = k.leaf, desc_words = k.desc_words;
    const __m256i one = _mm256_set1_epi32(1), two = _mm256_set1_epi32(2), four = _mm256_set1_epi32(4);
    const __m256i lane_id = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256 half = _mm256_set1_ps(0.5f);
    const __m256i act = ne0(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(g.active)), _mm256_sllv_epi32(one, lane_id)));
    const __m256 px = _mm256_load_ps(g.L.px), py = _mm256_load_ps(g.L.py), pz = _mm256_load_ps(g.L.pz);
    const __m256 cx = _mm256_load_ps(g.L.cx), cy = _mm256_load_ps(g.L.cy), cz = _mm256_load_ps(g.L.cz);
    const __m256 bx = _mm256_load_ps(g.L.bx), by = _mm256_load_ps(g.L.by), bz = _mm256_load_ps(g.L.bz);
    const __m256 size = _mm256_load_ps(g.L.size), t_min = _mm256_load_ps(g.L.t_min), t_hi = _mm256_load_ps(g.L.t_hi);
    const __m256i flip = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.flip));
    const __m256i scale = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.scale));
    const __m256i idx = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.idx));
    const __m256i handle = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.handle));
    const __m256i pdesc = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.pdesc));
    const __m256i bmx = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.bmx));
    const __m256i bmy = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.bmy));
    const __m256i bsub = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.bsub));
    const __m256i brick = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.brick));
    const __m256i pmask = _mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.pmask));

    const __m256i lc = _mm256_sub_epi32(_mm256_set1_epi32(23), scale);
    const __m256 tcx = _mm256_sub_ps(_mm256_mul_ps(px, cx), bx);
    const __m256 tcy = _mm256_sub_ps(_mm256_mul_ps(py, cy), by);
    const __m256 tcz = _mm256_sub_ps(_mm256_mul_ps(pz, cz), bz);
    const __m256 tc_max = glm_min(glm_min(tcx, tcy), tcz);
    const __m256i c = _mm256_xor_si256(idx, flip);
    const __m256i child = ne0(_mm256_and_si256(_mm256_srlv_epi32(pmask, c), one));
    const __m256 tv_max = glm_min(t_hi, tc_max);
    const __m256i in_parent = _mm256_and_si256(child, cmask(cle(t_min, t_hi)));
    const __m256i enter = _mm256_and_si256(_mm256_and_si256(in_parent, cmask(cle(t_min, tv_max))), act);
    __m256i stop = _mm256_or_si256(_mm256_cmpgt_epi32(lc, leaf), _mm256_cmpeq_epi32(lc, leaf));
#if RK_SVO_TRAVERSE_LOD
    const __m256 foot = _mm256_add_ps(k.lod_bias, _mm256_mul_ps(k.lod_slope, _mm256_add_ps(_mm256_load_ps(g.L.t_enter), t_min)));
    stop = _mm256_or_si256(stop, cmask(cle(size, foot)));
#endif
    const __m256i found = _mm256_and_si256(enter, stop);
    const __m256i push = _mm256_andnot_si256(stop, enter);
    const __m256i adv = _mm256_andnot_si256(enter, act);

    // Push: the stack entries first (from the old state), then the child's descriptor or brick.
    {
        alignas(32) int32_t row[kLanes];
        _mm256_store_si256(reinterpret_cast<__m256i*>(row),
                           sel(push, _mm256_sub_epi32(lc, one), _mm256_set1_epi32(RK_SVO_TRAVERSE_STACK)));
        for (int i = 0; i < kLanes; ++i) {
            g.L.stk_node[row[i]][i] = g.L.handle[i];
            g.L.stk_tmax[row[i]][i] = g.L.t_hi[i];
        }
    }
    const __m256i lp = _mm256_sub_epi32(lc, one);
    const __m256i desc_push = _mm256_and_si256(push, _mm256_cmpgt_epi32(top, lp));
    const __m256i is_far = ne0(_mm256_and_si256(pdesc, _mm256_set1_epi32(static_cast<int>(RK_SVO_FAR_BIT))));
    const __m256i rel = _mm256_srli_epi32(pdesc, static_cast<int>(RK_SVO_PTR_SHIFT));
    const __m256i far_word =
        gather_rare(k.words, _mm256_add_epi32(handle, rel), _mm256_and_si256(desc_push, is_far), _mm256_setzero_si256());
    const __m256i first = _mm256_add_epi32(handle, sel(is_far, far_word, rel));
    const __m256i below = _mm256_sub_epi32(_mm256_sllv_epi32(one, c), one);
    const __m256i nh = _mm256_add_epi32(first, popcount8(_mm256_and_si256(pmask, below)));
    const __m256i to_desc = _mm256_and_si256(desc_push, _mm256_cmpgt_epi32(top, lc));
    const __m256i to_brick = _mm256_andnot_si256(to_desc, desc_push);
    const __m256i pdesc_push = gather(k.words, nh, to_desc, pdesc);
    const __m256i bw = sel(_mm256_cmpgt_epi32(desc_words, nh), nh, _mm256_sub_epi32(_mm256_slli_epi32(nh, 1), desc_words));
    const __m256i bmx_push = gather_rare(k.words, bw, to_brick, bmx);
    const __m256i bmy_push = gather_rare(k.words, _mm256_add_epi32(bw, one), to_brick, bmy);
    const __m256i bsub_brick = k.sub_masks ? _mm256_or_si256(nonzero_bytes(bmx_push), _mm256_slli_epi32(nonzero_bytes(bmy_push), 4))
                                       : _mm256_and_si256(bmx_push, _mm256_set1_epi32(0xFF));
    const __m256i bsub_push = sel(to_brick, bsub_brick, bsub);
    const __m256i brick_push = sel(to_brick, nh, brick);
    const __m256i handle_push = sel(desc_push, nh, c);
    const __m256i pmask_push = child_mask(lc, top, pdesc_push, bmx_push, bmy_push, bsub_push, handle_push);
    const __m256 size_push = _mm256_mul_ps(size, half);
    const __m256 tmx = _mm256_add_ps(_mm256_mul_ps(size_push, cx), tcx);
    const __m256 tmy = _mm256_add_ps(_mm256_mul_ps(size_push, cy), tcy);
    const __m256 tmz = _mm256_add_ps(_mm256_mul_ps(size_push, cz), tcz);
    const __m256 gx = _mm256_cmp_ps(tmx, t_min, _CMP_GT_OQ), gy = _mm256_cmp_ps(tmy, t_min, _CMP_GT_OQ),
                 gz = _mm256_cmp_ps(tmz, t_min, _CMP_GT_OQ);
    const __m256i idx_push = _mm256_or_si256(_mm256_and_si256(cmask(gx), one),
                                             _mm256_or_si256(_mm256_and_si256(cmask(gy), two), _mm256_and_si256(cmask(gz), four)));
    const __m256 pxp = _mm256_blendv_ps(px, _mm256_add_ps(px, size_push), gx);
    const __m256 pyp = _mm256_blendv_ps(py, _mm256_add_ps(py, size_push), gy);
    const __m256 pzp = _mm256_blendv_ps(pz, _mm256_add_ps(pz, size_push), gz);

    // Advance: every axis whose exit plane ties steps.
    const __m256 sx = cle(tcx, tc_max), sy = cle(tcy, tc_max), sz = cle(tcz, tc_max);
    const __m256 pxa = _mm256_blendv_ps(px, _mm256_sub_ps(px, size), sx);
    const __m256 pya = _mm256_blendv_ps(py, _mm256_sub_ps(py, size), sy);
    const __m256 pza = _mm256_blendv_ps(pz, _mm256_sub_ps(pz, size), sz);
    const __m256i stp = _mm256_or_si256(_mm256_and_si256(cmask(sx), one),
                                        _mm256_or_si256(_mm256_and_si256(cmask(sy), two), _mm256_and_si256(cmask(sz), four)));
    const __m256 t_min_adv = glm_max(t_min, tc_max);
    const __m256i idx_adv = _mm256_xor_si256(idx, stp);
    const __m256i pop = _mm256_and_si256(adv, ne0(_mm256_and_si256(idx_adv, stp)));

    // Pop: the level of the highest differing address bit (exact as a float below 2^23; from
    // 2^23 up the ray has left the root).
    const __m256i dx = _mm256_and_si256(cmask(sx), _mm256_xor_si256(bits(pxa), bits(_mm256_add_ps(pxa, size))));
    const __m256i dy = _mm256_and_si256(cmask(sy), _mm256_xor_si256(bits(pya), bits(_mm256_add_ps(pya, size))));
    const __m256i dz = _mm256_and_si256(cmask(sz), _mm256_xor_si256(bits(pza), bits(_mm256_add_ps(pza, size))));
    const __m256i diff = _mm256_or_si256(dx, _mm256_or_si256(dy, dz));
    const __m256i big = _mm256_cmpgt_epi32(diff, _mm256_set1_epi32(0x7FFFFF));
    const __m256i msb =
        _mm256_sub_epi32(_mm256_srli_epi32(bits(_mm256_cvtepi32_ps(_mm256_andnot_si256(big, diff))), 23), _mm256_set1_epi32(127));
    const __m256i below_leaf = _mm256_cmpgt_epi32(_mm256_sub_epi32(_mm256_set1_epi32(23), leaf), msb);
    // Leaving at a pop: past t_max or the root's exit (rk_svo_trace's t_end test), out of the root,
    // or below the leaf level.
    const __m256i past_end = cmask(_mm256_cmp_ps(t_min_adv, _mm256_load_ps(g.L.t_end), _CMP_GT_OQ));
    const __m256i leave = _mm256_and_si256(pop, _mm256_or_si256(past_end, _mm256_or_si256(big, below_leaf)));
    const __m256i popped = _mm256_andnot_si256(leave, pop);
    const __m256 size_pop = flt(_mm256_slli_epi32(_mm256_add_epi32(msb, _mm256_set1_epi32(104)), 23));
    const __m256i lpp = _mm256_sub_epi32(_mm256_set1_epi32(22), msb);
    const __m256i slot = _mm256_add_epi32(_mm256_slli_epi32(lpp, 3), lane_id);
    const __m256i handle_pop = gather(&g.L.stk_node[0][0], slot, popped, handle);
    const __m256 t_hi_pop = flt(gather(reinterpret_cast<const uint32_t*>(&g.L.stk_tmax[0][0]), slot, popped, bits(t_hi)));
    const __m256i pdesc_pop = gather(k.words, handle_pop, _mm256_and_si256(popped, _mm256_cmpgt_epi32(top, lpp)), pdesc);
    const __m256i pmask_pop = child_mask(lpp, top, pdesc_pop, bmx, bmy, bsub, handle_pop);
    const __m256i ax = _mm256_srlv_epi32(bits(pxa), msb), ay = _mm256_srlv_epi32(bits(pya), msb),
                  az = _mm256_srlv_epi32(bits(pza), msb);
    const __m256 pxo = flt(_mm256_sllv_epi32(ax, msb)), pyo = flt(_mm256_sllv_epi32(ay, msb)), pzo = flt(_mm256_sllv_epi32(az, msb));
    const __m256i idx_pop = _mm256_or_si256(_mm256_and_si256(ax, one),
                                            _mm256_or_si256(_mm256_slli_epi32(_mm256_and_si256(ay, one), 1),
                                                            _mm256_slli_epi32(_mm256_and_si256(az, one), 2)));

    // The new state: push, pop, plain advance, or unchanged (found, leaving, idle lanes).
    const __m256i moved = _mm256_andnot_si256(pop, adv);  // advanced within the parent
    const __m256 fpush = _mm256_castsi256_ps(push), fpop = _mm256_castsi256_ps(popped), fadv = _mm256_castsi256_ps(adv);
    _mm256_store_ps(g.L.px, _mm256_blendv_ps(_mm256_blendv_ps(_mm256_blendv_ps(px, pxa, fadv), pxo, fpop), pxp, fpush));
    _mm256_store_ps(g.L.py, _mm256_blendv_ps(_mm256_blendv_ps(_mm256_blendv_ps(py, pya, fadv), pyo, fpop), pyp, fpush));
    _mm256_store_ps(g.L.pz, _mm256_blendv_ps(_mm256_blendv_ps(_mm256_blendv_ps(pz, pza, fadv), pzo, fpop), pzp, fpush));
    _mm256_store_ps(g.L.size, self(push, size_push, self(popped, size_pop, size)));
    _mm256_store_ps(g.L.t_min, _mm256_blendv_ps(t_min, t_min_adv, fadv));
    _mm256_store_ps(g.L.t_hi, self(push, tv_max, self(popped, t_hi_pop, t_hi)));
    const __m256i scale_new = sel(push, _mm256_sub_epi32(scale, one), sel(popped, msb, scale));
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.scale), scale_new);
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.idx), sel(push, idx_push, sel(popped, idx_pop, sel(moved, idx_adv, idx))));
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.handle), sel(push, handle_push, sel(popped, handle_pop, handle)));
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.pdesc), sel(push, pdesc_push, sel(popped, pdesc_pop, pdesc)));
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.pmask), sel(push, pmask_push, sel(popped, pmask_pop, pmask)));
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.bmx), sel(push, bmx_push, bmx));
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.bmy), sel(push, bmy_push, bmy));
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.bsub), sel(push, bsub_push, bsub));
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.brick), sel(push, brick_push, brick));

    // Lanes that finished: found a node, left the root, or reached the iteration bound.
    const unsigned found_bits = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(found)));
    const unsigned leave_bits = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(leave)));
    const __m256i iter = _mm256_add_epi32(_mm256_load_si256(reinterpret_cast<const __m256i*>(g.L.iter)), _mm256_andnot_si256(
                                                                                                             _mm256_or_si256(found, leave), _mm256_and_si256(act, one)));
    _mm256_store_si256(reinterpret_cast<__m256i*>(g.L.iter), iter);
    const unsigned bound_bits = static_cast<unsigned>(_mm256_movemask_ps(
        _mm256_castsi256_ps(_mm256_and_si256(act, _mm256_cmpeq_epi32(iter, k.bound)))));
    for (unsigned m = (found_bits | leave_bits | bound_bits) & g.active; m != 0u; m &= m - 1u) {
        const int i = lowest_bit(m);
        lane_out(g.L, i, g.st[i]);
        rk_svo_trace_finish_(k.words, k.tree, g.st[i], ((found_bits >> i) & 1u) != 0u, static_cast<uint32_t>(g.L.iter[i]),
                             k.hits[g.ray_of[i]]);
        refill(k, g, i);
    }
}

// The lanes of one call: 8 rays in flight until every ray is answered.
RK_SVO_RAYS_TARGET inline void trace_lanes(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, std::size_t n,
                                           glm::vec2 cone, rk_svo_trace_hit* hits)
{
    Batch c;
    c.words = words;
    c.tree = tree;
    c.rays = rays;
    c.n = n;
    c.next = 0;
    c.cone = cone;
    c.hits = hits;
    const uint32_t b = rk_svo_brick_levels(tree.depth);
    c.sub_masks = b == 2u;
    c.top = _mm256_set1_epi32(static_cast<int>(tree.depth - b));
    c.leaf = _mm256_set1_epi32(static_cast<int>(tree.max_level < tree.depth ? tree.max_level : tree.depth));
    c.desc_words = _mm256_set1_epi32(static_cast<int>(tree.desc_words));
    c.bound = _mm256_set1_epi32(static_cast<int>(rk_svo_trace_iteration_bound(tree)));
#if RK_SVO_TRAVERSE_LOD
    c.lod_bias = _mm256_set1_ps(glm::max(cone.x, 0.0f) * (1.0f / tree.root_size));
    c.lod_slope = _mm256_set1_ps(glm::max(cone.y, 0.0f));
#endif
    Group g;
    for (int i = 0; i < kLanes; ++i) refill(c, g, i);
    while (g.active != 0u) step(c, g);
}
#endif

}  // namespace svo_rays_detail

/// svo_trace_rays: hits[i] = rk_svo_trace(words, tree, rays[i].origin, rays[i].dir, rays[i].t_max,
/// cone) for i < n, bit for bit (see the file comment), the traversal loops of 8 rays at a time on
/// SIMD lanes where the CPU has AVX2 (mode `best`). `words` is the tree as SvoTree::gpu_words();
/// trees of 2^31 words or more take the per-ray path. Cost: the set-up and hit of each ray as
/// rk_svo_trace; per loop iteration of 8 lanes ~250 AVX2 instructions (spills included) and up to
/// 7 gathers: 0.9-1.5x the per-ray speed on 512^2 primary rays at depth 10 (docs/svo-traverse.md).
inline void svo_trace_rays(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, std::size_t n,
                           rk_svo_trace_hit* hits, glm::vec2 cone = glm::vec2(0.0f), SvoTraceMode mode = SvoTraceMode::best)
{
#if RK_SVO_RAYS_SIMD
    if (mode == SvoTraceMode::best && tree.brick_base_word < 0x80000000u && svo_trace_simd_available()) {
        svo_rays_detail::trace_lanes(words, tree, rays, n, cone, hits);
        return;
    }
#endif
    (void)mode;
    for (std::size_t i = 0; i < n; ++i) hits[i] = rk_svo_trace(words, tree, rays[i].origin, rays[i].dir, rays[i].t_max, cone);
}

}  // namespace RK_SVO_RAYS_NS_CAT(RK_SVO_RAYS_SIMD)
}  // namespace RK_SVO_TRAVERSE_NS
}  // namespace raykit
