// raykit — svo_trace_packet.hpp: rk_svo_trace for coherent packets of up to 8 rays (a 4x2 pixel
// tile, on the 8 lanes of AVX2 registers), 16 rays (a 4x4 tile, on AVX-512 lanes or two AVX2
// registers per lane value) or 32 rays (an 8x4 tile, two AVX-512 registers per lane value) that
// share ONE traversal of the packed octree, as Embree traces coherent packets. svo_trace_rays
// (svo_trace_simd.hpp) runs one traversal per lane instead; rk_svo_trace one per call.
//
// A C++ twin of rk_svo_trace, not shared text (GLSL has no lanes to program). The set-up is a lanes
// twin of rk_svo_trace_begin_ (the same float operations in the same order) and the hit is
// rk_svo_trace_finish_'s shared part (rk_svo_trace_hit_fields_) with the face normal computed on
// lanes without branches (entry_normal8, L::entry_normal: rk_svo_trace_entry_normal_'s
// comparisons). Rays of one direction octant share the mirroring, so every node has the same
// mirrored coordinates for all of them and visiting children in decreasing mirrored slot is front
// to back for each ray. The packet walks the tree depth first; at a node, each ray's
// interval in each child is [max(entry planes, t_start), min(exit planes)), with rk_svo_trace's
// plane expressions. These half-open intervals tile a ray's path, so a ray is answered at the first
// voxel it reaches, which is rk_svo_trace's.
//
// Contract: the answers (hit, t, level, cell, normal, node and brick fields) are rk_svo_trace's,
// except at exact lattice ties (a ray in a face plane, through an edge or corner, or with
// near-parallel components, where rk_svo_trace's "never backwards" clamp acts): both answers are
// then accepted by the float64 dense-grid DDA (tests/test_svo_trace_packet.cpp). `iterations` is
// the number of nodes the packet expanded until that ray was answered, not rk_svo_trace's count, so
// where rk_svo_trace stops at its iteration bound and reports a miss (a fixed
// RK_SVO_TRAVERSE_MAX_ITER cap) a packet may still find the hit. Bit for bit only without
// fused multiply-adds: x86-64's default target or -ffp-contract=off (an FMA target such as
// -march=native contracts rk_svo_trace's planes, not the AVX-512 walk's). Rays of different
// octants in one packet are traced as one packet per octant. A packet that expands more than
// rk_svo_trace_iteration_bound(tree) nodes hands its remaining rays to rk_svo_trace. In a
// LOD build (RK_SVO_TRAVERSE_LOD=1) each lane tests rk_svo_trace's footprint stop on the children
// it enters; a ray stopped at a child is answered when the walk reaches that child (front to back),
// or at once, at the first child it enters, when its footprint is a child wide at the node's entry.
// CPUs without AVX2 and POPCNT, trees of 2^31 words or more and max_level 0 use rk_svo_trace per
// ray; CPUs without AVX-512F (and MSVC) trace a 16-ray packet on two AVX2 registers per value and
// a 32-ray one as two 16-ray ones, with the same answers. The MSVC path (/arch:AVX2) is written but
// not compiled yet.
// Cost: it pays where the rays of a tile stay in the same nodes, i.e. where a pixel's footprint is
// not much smaller than a voxel (a pixel cone in a LOD build keeps it so at any depth); the
// secondary rays of a tile's hits (shadow rays, mirror reflections), in their pixels' places, share
// nodes as well; 32-ray
// packets share the levels above the rays' parting, and expand a node on 16 lanes where its rays
// lie in one half of the packet. Where few
// rays reach a 4^3 brick, the 16-lane walk finds each one's first voxel among the brick's 64 at
// once (Lanes16::brick_hit, full-detail builds), a ray alone above the bricks takes them in order
// without the stack, and a node reached by one ray tests its 8 children for it at once (children8,
// both widths). A node's children are fetched into the cache as soon as it is read (and, in trees
// beyond 1 MiB, the next stacked node's too). Measured speed-ups by depth and tile are in
// docs/svo-traverse.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "raykit/svo_trace_simd.hpp"
#include "raykit/svo_traverse.hpp"

namespace raykit {
inline namespace RK_SVO_TRAVERSE_NS {
inline namespace RK_SVO_RAYS_NS_CAT(RK_SVO_RAYS_SIMD) {

namespace svo_packet_detail {

#if RK_SVO_RAYS_SIMD
#define RK_SVO_PACKET_SIMD 1
#else
#define RK_SVO_PACKET_SIMD 0
#endif

#if RK_SVO_PACKET_SIMD
// Clang contracts a product and a sum written in one scalar expression into a fused multiply-add
// where the target has FMA (the AVX-512 walk): the planes must round as rk_svo_trace's do. First
// statement of the functions that compute them (GCC: the walk's optimize attribute, below).
#if defined(__clang__)
#define RK_SVO_PACKET_NO_CONTRACT _Pragma("clang fp contract(off)")
#else
#define RK_SVO_PACKET_NO_CONTRACT
#endif
#if defined(__GNUC__) || defined(__clang__)
#define RK_SVO_PACKET_TARGET __attribute__((target("avx2,popcnt")))
inline bool packet_cpu_ok() { return svo_trace_simd_available() && __builtin_cpu_supports("popcnt") != 0; }
#else
#define RK_SVO_PACKET_TARGET
inline bool packet_cpu_ok() { return svo_trace_simd_available(); }
#endif

// The set-up of rk_svo_trace_begin_ for N rays (8 at a time, setup8), the same float operations in
// the same order (so the same bits), one array per field; `valid` has the rays that enter the root.
template <int N>
struct alignas(64) SetupLanes {
    float cx[N], cy[N], cz[N], bx[N], by[N], bz[N];
    float ux[N], uy[N], uz[N];
    float t_min[N], t_hi[N], t_enter[N], t_scale[N];
    int32_t flip[N];
    unsigned valid;
    float lod_bias, lod_slope;  // rk_svo_trace_begin_'s, in a LOD build (set by trace_set_up)
};
using Setup = SetupLanes<8>;

// Writes lanes off..off+7 of S (Setup, or a half of Setup16) for the rays rp[0..n) (n <= 8) and
// returns their `valid` bits (bit i: lane off + i).
template <class SetupT>
RK_SVO_PACKET_TARGET inline unsigned setup8(const rk_svo_tree& tree, const SvoRay* const* rp, unsigned n, SetupT& S, int off)
{
    using svo_rays_detail::glm_max;
    using svo_rays_detail::glm_min;
    // The rays' fields lane by lane, in registers (8 scalar stores read back as one vector would wait
    // for the stores to reach the cache).
    const SvoRay* r[8];
    for (unsigned i = 0; i < 8; ++i) r[i] = rp[i < n ? i : 0u];
#define RK_SVO_PACKET_LANES_OF(f) _mm256_setr_ps(r[0]->f, r[1]->f, r[2]->f, r[3]->f, r[4]->f, r[5]->f, r[6]->f, r[7]->f)
    const __m256 OX = RK_SVO_PACKET_LANES_OF(origin.x), OY = RK_SVO_PACKET_LANES_OF(origin.y), OZ = RK_SVO_PACKET_LANES_OF(origin.z);
    const __m256 Dx = RK_SVO_PACKET_LANES_OF(dir.x), Dy = RK_SVO_PACKET_LANES_OF(dir.y), Dz = RK_SVO_PACKET_LANES_OF(dir.z);
    // Lanes n..7 get t_max -1 (invalid).
    const __m256 TM = _mm256_blendv_ps(_mm256_set1_ps(-1.0f), RK_SVO_PACKET_LANES_OF(t_max),
                                       _mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(int(n)), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7))));
#undef RK_SVO_PACKET_LANES_OF
    const __m256 sgn = _mm256_set1_ps(-0.0f);
    const __m256 one = _mm256_set1_ps(1.0f), two = _mm256_set1_ps(2.0f), three = _mm256_set1_ps(3.0f), zero = _mm256_setzero_ps();
    const __m256 fmax = _mm256_set1_ps(RK_FLT_MAX);
    const __m256 m = glm_max(glm_max(_mm256_andnot_ps(sgn, Dx), _mm256_andnot_ps(sgn, Dy)), _mm256_andnot_ps(sgn, Dz));
    __m256 ok = _mm256_and_ps(_mm256_cmp_ps(m, _mm256_set1_ps(RK_FLT_MIN), _CMP_GE_OQ), _mm256_cmp_ps(TM, zero, _CMP_GE_OQ));
    const __m256 nx = _mm256_div_ps(Dx, m), ny = _mm256_div_ps(Dy, m), nz = _mm256_div_ps(Dz, m);
    const __m256 len = _mm256_sqrt_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(nx, nx), _mm256_mul_ps(ny, ny)), _mm256_mul_ps(nz, nz)));
    __m256 ux = _mm256_div_ps(nx, len), uy = _mm256_div_ps(ny, len), uz = _mm256_div_ps(nz, len);
    const __m256 rs = _mm256_set1_ps(tree.root_size);
    _mm256_store_ps(S.t_scale + off, glm_min(_mm256_div_ps(_mm256_div_ps(rs, m), len), fmax));
    const __m256 inv_size = _mm256_set1_ps(1.0f / tree.root_size);
    __m256 Ox = _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(OX, _mm256_set1_ps(tree.root_min.x)), inv_size), one);
    __m256 Oy = _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(OY, _mm256_set1_ps(tree.root_min.y)), inv_size), one);
    __m256 Oz = _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(OZ, _mm256_set1_ps(tree.root_min.z)), inv_size), one);
    // Tiny components: +-2^-21 by the sign bit.
    const __m256 eps = _mm256_set1_ps(RK_SVO_TRAVERSE_DIR_EPS);
    ux = _mm256_blendv_ps(ux, _mm256_or_ps(eps, _mm256_and_ps(sgn, ux)), _mm256_cmp_ps(_mm256_andnot_ps(sgn, ux), eps, _CMP_LT_OQ));
    uy = _mm256_blendv_ps(uy, _mm256_or_ps(eps, _mm256_and_ps(sgn, uy)), _mm256_cmp_ps(_mm256_andnot_ps(sgn, uy), eps, _CMP_LT_OQ));
    uz = _mm256_blendv_ps(uz, _mm256_or_ps(eps, _mm256_and_ps(sgn, uz)), _mm256_cmp_ps(_mm256_andnot_ps(sgn, uz), eps, _CMP_LT_OQ));
    _mm256_store_ps(S.ux + off, ux);
    _mm256_store_ps(S.uy + off, uy);
    _mm256_store_ps(S.uz + off, uz);
    const __m256 ix = _mm256_div_ps(one, ux), iy = _mm256_div_ps(one, uy), iz = _mm256_div_ps(one, uz);
    const __m256 tax = _mm256_mul_ps(_mm256_sub_ps(one, Ox), ix), tbx = _mm256_mul_ps(_mm256_sub_ps(two, Ox), ix);
    const __m256 tay = _mm256_mul_ps(_mm256_sub_ps(one, Oy), iy), tby = _mm256_mul_ps(_mm256_sub_ps(two, Oy), iy);
    const __m256 taz = _mm256_mul_ps(_mm256_sub_ps(one, Oz), iz), tbz = _mm256_mul_ps(_mm256_sub_ps(two, Oz), iz);
    const __m256 t_enter = glm_max(glm_max(glm_max(glm_min(tax, tbx), glm_min(tay, tby)), glm_min(taz, tbz)), zero);
    const __m256 t_leave = glm_min(glm_min(glm_max(tax, tbx), glm_max(tay, tby)), glm_max(taz, tbz));
    __m256 t_lim = _mm256_and_ps(_mm256_cmp_ps(TM, zero, _CMP_GT_OQ),
                                 glm_min(_mm256_mul_ps(_mm256_mul_ps(TM, _mm256_div_ps(m, rs)), len), fmax));
    ok = _mm256_and_ps(ok, _mm256_and_ps(_mm256_cmp_ps(t_enter, t_leave, _CMP_LE_OQ), _mm256_cmp_ps(t_enter, t_lim, _CMP_LE_OQ)));
    const unsigned valid = static_cast<unsigned>(_mm256_movemask_ps(ok)) & ((1u << n) - 1u);
    _mm256_store_ps(S.t_enter + off, t_enter);
    Ox = _mm256_add_ps(Ox, _mm256_mul_ps(ux, t_enter));
    Oy = _mm256_add_ps(Oy, _mm256_mul_ps(uy, t_enter));
    Oz = _mm256_add_ps(Oz, _mm256_mul_ps(uz, t_enter));
    t_lim = _mm256_sub_ps(t_lim, t_enter);
    const __m256 cx = _mm256_or_ps(ix, sgn), cy = _mm256_or_ps(iy, sgn), cz = _mm256_or_ps(iz, sgn);  // -|1/u|
    __m256 bx = _mm256_mul_ps(cx, Ox), by = _mm256_mul_ps(cy, Oy), bz = _mm256_mul_ps(cz, Oz);
    const __m256 px = _mm256_cmp_ps(ux, zero, _CMP_GT_OQ), py = _mm256_cmp_ps(uy, zero, _CMP_GT_OQ), pz = _mm256_cmp_ps(uz, zero, _CMP_GT_OQ);
    bx = _mm256_blendv_ps(bx, _mm256_sub_ps(_mm256_mul_ps(three, cx), bx), px);
    by = _mm256_blendv_ps(by, _mm256_sub_ps(_mm256_mul_ps(three, cy), by), py);
    bz = _mm256_blendv_ps(bz, _mm256_sub_ps(_mm256_mul_ps(three, cz), bz), pz);
    const __m256i fl = _mm256_or_si256(
        _mm256_and_si256(_mm256_castps_si256(px), _mm256_set1_epi32(1)),
        _mm256_or_si256(_mm256_and_si256(_mm256_castps_si256(py), _mm256_set1_epi32(2)), _mm256_and_si256(_mm256_castps_si256(pz), _mm256_set1_epi32(4))));
    _mm256_store_si256(reinterpret_cast<__m256i*>(S.flip + off), fl);
    _mm256_store_ps(S.cx + off, cx);
    _mm256_store_ps(S.cy + off, cy);
    _mm256_store_ps(S.cz + off, cz);
    _mm256_store_ps(S.bx + off, bx);
    _mm256_store_ps(S.by + off, by);
    _mm256_store_ps(S.bz + off, bz);
    const __m256 t_min = glm_max(glm_max(glm_max(_mm256_sub_ps(_mm256_mul_ps(two, cx), bx), _mm256_sub_ps(_mm256_mul_ps(two, cy), by)),
                                         _mm256_sub_ps(_mm256_mul_ps(two, cz), bz)),
                                 zero);
    _mm256_store_ps(S.t_min + off, t_min);
    _mm256_store_ps(S.t_hi + off, glm_min(glm_min(glm_min(_mm256_sub_ps(cx, bx), _mm256_sub_ps(cy, by)), _mm256_sub_ps(cz, bz)), t_lim));
    return valid;
}

// A node to visit: its mirrored minimum corner, level, handle (descriptor or brick ordinal, or the
// sub-node's slot inside the current brick) and the rays that reach it. In a LOD build also the rays
// whose footprint stops them at this node, and the parent's handle: their hit's parent descriptor,
// child mask and slot are found again from it and the corner (24 + 8 bytes).
struct Entry {
    float px, py, pz;
    uint32_t level;
    uint32_t handle;
    uint32_t rays;
#if RK_SVO_TRAVERSE_LOD
    uint32_t stops;
    uint32_t phandle;
#endif
};
static_assert(offsetof(Entry, level) == 12u && offsetof(Entry, handle) == 16u && offsetof(Entry, rays) == 20u,
              "set_child writes px..level and handle, rays as two blocks");
#if RK_SVO_TRAVERSE_LOD
static_assert(offsetof(Entry, stops) == 24u && offsetof(Entry, phandle) == 28u && sizeof(Entry) == 32u,
              "push_child writes a LOD entry as one 32-byte block");
#endif

// Child mask in mirrored slots: bit k = bit (k ^ flip) of m.
inline uint32_t mirror_mask(uint32_t m, uint32_t flip)
{
    const uint32_t m1 = ((m & 0x55u) << 1) | ((m >> 1) & 0x55u);
    m = (flip & 1u) ? m1 : m;
    const uint32_t m2 = ((m & 0x33u) << 2) | ((m >> 2) & 0x33u);
    m = (flip & 2u) ? m2 : m;
    const uint32_t m4 = ((m & 0x0Fu) << 4) | ((m >> 4) & 0x0Fu);
    return (flip & 4u) ? m4 : m;
}

// A brick's 64-bit mask by mirrored index: bit m = bit (m ^ (flip | flip << 3)) of `m`.
inline uint64_t mirror64(uint64_t m, uint32_t flip)
{
    const uint32_t f = flip | (flip << 3u);
    const uint64_t keep[6] = {0x5555555555555555ull, 0x3333333333333333ull, 0x0F0F0F0F0F0F0F0Full,
                              0x00FF00FF00FF00FFull, 0x0000FFFF0000FFFFull, 0x00000000FFFFFFFFull};
    for (uint32_t j = 0; j < 6u; ++j) {
        const uint32_t sh = 1u << j;
        const uint64_t swapped = ((m & keep[j]) << sh) | ((m >> sh) & keep[j]);
        m = ((f >> j) & 1u) != 0u ? swapped : m;
    }
    return m;
}

inline int highest_bit(uint32_t m)
{
#if defined(_MSC_VER) && !defined(__clang__)
    unsigned long i;
    _BitScanReverse(&i, m);
    return static_cast<int>(i);
#else
    return 31 - __builtin_clz(m);
#endif
}


// What the walk keeps of the tree and the brick it is in.
struct WalkCtx {
    uint32_t b, top, leaf;
    uint32_t brick, bmx, bmy;
};

// A packet's lane values that every node's expansion reads: its planes' coefficients and biases,
// t_start, t_hi and next_up(t_hi), and the footprint's bias, slope and t_enter (LOD builds).
template <class L>
struct NodePlanes {
    typename L::V Cx, Cy, Cz, Bx, By, Bz, T0, TH, TL, LB, LS, TE;
};

inline WalkCtx walk_ctx(const rk_svo_tree& tree)
{
    const uint32_t b = rk_svo_brick_levels(tree.depth);
    return WalkCtx{b, tree.depth - b, tree.max_level < tree.depth ? tree.max_level : tree.depth, 0u, 0u, 0u};
}

// The child mask (format slots) of the node `e`; loads its descriptor (pdesc) or brick masks.
inline uint32_t node_mask(const uint32_t* words, const rk_svo_tree& tree, const Entry& e, WalkCtx& w, uint32_t& pdesc)
{
    pdesc = 0u;
    if (e.level < w.top) {
        pdesc = words[e.handle];
        return pdesc & RK_SVO_CHILD_MASK;
    }
    if (e.level == w.top) {
        const uint32_t wd = rk_svo_word_of(e.handle, tree.desc_words);
        w.bmx = words[wd];
        w.bmy = words[wd + 1u];
        w.brick = e.handle;
        return w.b == 2u ? rk_svo_brick_submask(glm::uvec2(w.bmx, w.bmy)) : (w.bmx & 0xFFu);
    }
    return ((e.handle < 4u ? w.bmx : w.bmy) >> (8u * (e.handle & 3u))) & 0xFFu;
}

// rk_svo_trace_entry_normal_ on 8 lanes, without its branches (the same comparisons): the face of
// the entry plane crossed last (tx, ty, tz), ties to the axis of the larger |u|; -sign(u) on that
// axis, +0 on the others. Written to nx, ny, nz.
RK_SVO_PACKET_TARGET inline void entry_normal8(__m256 tx, __m256 ty, __m256 tz, __m256 ux, __m256 uy, __m256 uz, float* nx, float* ny,
                                               float* nz)
{
    const __m256 sg = _mm256_set1_ps(-0.0f), z = _mm256_setzero_ps();
    const __m256 ax = _mm256_andnot_ps(sg, ux), ay = _mm256_andnot_ps(sg, uy), az = _mm256_andnot_ps(sg, uz);
    const __m256 c1 = _mm256_or_ps(_mm256_cmp_ps(ty, tx, _CMP_GT_OQ), _mm256_and_ps(_mm256_cmp_ps(ty, tx, _CMP_EQ_OQ), _mm256_cmp_ps(ay, ax, _CMP_GT_OQ)));
    const __m256 tb = _mm256_blendv_ps(tx, ty, c1), ub = _mm256_blendv_ps(ax, ay, c1);
    const __m256 c2 = _mm256_or_ps(_mm256_cmp_ps(tz, tb, _CMP_GT_OQ), _mm256_and_ps(_mm256_cmp_ps(tz, tb, _CMP_EQ_OQ), _mm256_cmp_ps(az, ub, _CMP_GT_OQ)));
    const __m256 one = _mm256_set1_ps(1.0f), m_one = _mm256_set1_ps(-1.0f);
    // -sign(u): -1 above 0, 1 below, -0 at 0.
    const __m256 sx = _mm256_blendv_ps(_mm256_blendv_ps(sg, one, _mm256_cmp_ps(ux, z, _CMP_LT_OQ)), m_one, _mm256_cmp_ps(ux, z, _CMP_GT_OQ));
    const __m256 sy = _mm256_blendv_ps(_mm256_blendv_ps(sg, one, _mm256_cmp_ps(uy, z, _CMP_LT_OQ)), m_one, _mm256_cmp_ps(uy, z, _CMP_GT_OQ));
    const __m256 sz = _mm256_blendv_ps(_mm256_blendv_ps(sg, one, _mm256_cmp_ps(uz, z, _CMP_LT_OQ)), m_one, _mm256_cmp_ps(uz, z, _CMP_GT_OQ));
    _mm256_store_ps(nx, _mm256_andnot_ps(_mm256_or_ps(c1, c2), sx));
    _mm256_store_ps(ny, _mm256_and_ps(_mm256_andnot_ps(c2, c1), sy));
    _mm256_store_ps(nz, _mm256_and_ps(c2, sz));
}

// The hits of the lanes `hm` of set-up `S` (Setup or Setup16) in the children of node `e`: lane i
// entered mirrored child k_out[i] at lo_out[i]. nx, ny, nz: the lanes' face normals where the walk
// has them (L::entry_normal), else null: entry_normal8 on this lane's scalars.
template <class SetupT>
RK_SVO_PACKET_TARGET inline void finish_hits(const uint32_t* words, const rk_svo_tree& tree, const SetupT& S, unsigned hm,
                                             const int32_t* k_out, const float* lo_out, const Entry& e, uint32_t flip, uint32_t pdesc,
                                             uint32_t m8, const WalkCtx& w, uint32_t iter, rk_svo_trace_hit* const* hits,
                                             const float* nx = nullptr, const float* ny = nullptr, const float* nz = nullptr)
{
    RK_SVO_PACKET_NO_CONTRACT
    for (unsigned m = hm; m != 0u; m &= m - 1u) {
        const int i = svo_rays_detail::lowest_bit(m);
        const int k = k_out[i];
        const uint32_t Lc = e.level + 1u;
        const float half = uintBitsToFloat((126u - e.level) << 23u);  // 2^-(L+1)
        rk_svo_trace_state_ s;
        s.u = glm::vec3(S.ux[i], S.uy[i], S.uz[i]);
        s.coef = glm::vec3(S.cx[i], S.cy[i], S.cz[i]);
        s.bias = glm::vec3(S.bx[i], S.by[i], S.bz[i]);
        s.flip = flip;
        s.t_enter = S.t_enter[i];
        s.t_scale = S.t_scale[i];
        s.b = w.b;
        s.top = w.top;
        s.leaf = w.leaf;
        s.pos = glm::vec3(e.px + half * float(k & 1), e.py + half * float((k >> 1) & 1), e.pz + half * float((k >> 2) & 1));
        s.size = half;
        s.scale = 23 - int(Lc);
        s.idx = uint32_t(k);
        s.t_min = lo_out[i];
        s.pdesc = pdesc;
        s.pmask = m8;
        s.handle = e.handle;
        s.bmask = glm::uvec2(w.bmx, w.bmy);
        s.brick = w.brick;
        // rk_svo_trace_finish_ with the normal on lanes.
        rk_svo_trace_hit& h = *hits[i];
        h.iterations = iter;
        rk_svo_trace_hit_fields_(words, tree, s, h);
        if (nx != nullptr) {
            h.normal = glm::vec3(nx[i], ny[i], nz[i]);
        } else {
            const glm::vec3 te = (s.pos + glm::vec3(s.size)) * s.coef - s.bias;  // the entry planes of the cell
            alignas(32) float n1[3][8];
            entry_normal8(_mm256_set1_ps(te.x), _mm256_set1_ps(te.y), _mm256_set1_ps(te.z), _mm256_set1_ps(s.u.x), _mm256_set1_ps(s.u.y),
                          _mm256_set1_ps(s.u.z), n1[0], n1[1], n1[2]);
            h.normal = glm::vec3(n1[0][0], n1[1][0], n1[2][0]);
        }
    }
}

// The end of a walk: the unanswered rays get the node count; returns those the node bound stopped.
inline unsigned end_walk(unsigned active, uint32_t iter, bool bounded, rk_svo_trace_hit* const* hits)
{
    for (unsigned m = active; m != 0u; m &= m - 1u) hits[svo_rays_detail::lowest_bit(m)]->iterations = iter;
    return bounded ? active : 0u;
}

// The first child's handle of an inner node above the bricks (0 inside a brick).
inline uint32_t first_child(const uint32_t* words, const Entry& e, uint32_t pdesc, const WalkCtx& w)
{
    if (e.level >= w.top) return 0u;
    const uint32_t far_word = rk_svo_is_far(pdesc) ? words[e.handle + rk_svo_rel_ptr(pdesc)] : 0u;
    return rk_svo_first_child(e.handle, pdesc, far_word);
}

// Ray i of set-up S in the brick `b` (its masks loaded into w by node_mask): its first voxel of the
// 64 at once (L::brick_hit); if there is one, answers *hits[i] and returns true. tl: next_up(t_hi).
template <class L, class SetupT>
RK_SVO_RAYS_FORCE_INLINE bool brick_ray(const uint32_t* words, const rk_svo_tree& tree, const SetupT& S, const Entry& b, int i, float tl,
                                        uint32_t flip, WalkCtx& w, uint32_t iter, rk_svo_trace_hit* const* hits)
{
    const float q = 0.25f * uintBitsToFloat((127u - b.level) << 23u);
    const uint64_t occ = mirror64(uint64_t(w.bmx) | (uint64_t(w.bmy) << 32u), flip);
    float lo = 0.0f;
    const int m = L::brick_hit(glm::vec3(b.px, b.py, b.pz), q, glm::vec3(S.cx[i], S.cy[i], S.cz[i]), glm::vec3(S.bx[i], S.by[i], S.bz[i]),
                               S.t_min[i], S.t_hi[i], tl, occ, lo);
    if (m < 0) return false;
    const int ks = m >> 3;
    Entry sub = Entry();
    sub.px = b.px + 2.0f * q * float(ks & 1);
    sub.py = b.py + 2.0f * q * float((ks >> 1) & 1);
    sub.pz = b.pz + 2.0f * q * float((ks >> 2) & 1);
    sub.level = b.level + 1u;
    sub.handle = uint32_t(ks) ^ flip;
    int32_t k_out[L::N];
    float lo_out[L::N];
    k_out[i] = m & 7;
    lo_out[i] = lo;
    uint32_t no_desc;
    const uint32_t m8s = node_mask(words, tree, sub, w, no_desc);  // the sub-node's byte of the brick
    finish_hits(words, tree, S, 1u << i, k_out, lo_out, sub, flip, no_desc, m8s, w, iter, hits);
    return true;
}

// Asks the cache for the children of a node above the bricks (first: the first child's handle;
// bricks: they are bricks, whose masks are two words each).
inline void prefetch_children(const uint32_t* words, const rk_svo_tree& tree, uint32_t first, bool bricks)
{
    const uint32_t* p = words + (bricks ? rk_svo_word_of(first, tree.desc_words) : first);
    _mm_prefetch(reinterpret_cast<const char*>(p), _MM_HINT_T0);
    _mm_prefetch(reinterpret_cast<const char*>(p + (bricks ? 15 : 7)), _MM_HINT_T0);
}

// The corner and level of mirrored child k of `e` (an Entry's first 16 bytes) and its handle (m8:
// e's child mask in format slots; first: its first child's handle, above the bricks). A corner of a
// level-L node in [1, 2) has no mantissa bit below 2^-L, so adding the child's half edge 2^-(L+1) is
// setting bit 22 - L: the same float as e.px + half * bit, on integers.
inline __m128i child_corner(const Entry& e, int k)
{
    const uint32_t s = 22u - e.level;
    return _mm_setr_epi32(int(floatBitsToUint(e.px) | ((uint32_t(k) & 1u) << s)), int(floatBitsToUint(e.py) | (((uint32_t(k) >> 1u) & 1u) << s)),
                          int(floatBitsToUint(e.pz) | (((uint32_t(k) >> 2u) & 1u) << s)), int(e.level + 1u));
}
inline uint32_t child_handle(const Entry& e, int k, uint32_t flip, uint32_t m8, uint32_t first, const WalkCtx& w)
{
    const uint32_t c = uint32_t(k) ^ flip;
    return e.level < w.top ? first + rk_svo_child_rank(m8, c) : c;
}

// Writes the corner, level, handle and rays of mirrored child k of `e` into `ch`. The walk's pop
// reads a 24-byte entry as 16 bytes and 8, which is how it is written here (a read that spans
// several smaller writes waits for them to reach the cache instead of taking them from the store
// buffer).
inline void set_child(Entry& ch, const Entry& e, int k, uint32_t flip, uint32_t m8, uint32_t first, const WalkCtx& w, uint32_t rays)
{
    _mm_storeu_si128(reinterpret_cast<__m128i*>(&ch.px), child_corner(e, k));
    const uint64_t hr = uint64_t(child_handle(e, k, flip, m8, first, w)) | (uint64_t(rays) << 32u);
    std::memcpy(&ch.handle, &hr, sizeof hr);
}

// Writes mirrored child k of `e` on top of the stack; keeps it when some ray (cm) reaches it (no
// branch per child). `stops`: the rays of cm whose footprint stops them there (LOD builds, whose
// 32-byte entries the pop reads in one piece and which are written so).
RK_SVO_PACKET_TARGET inline void push_child(Entry* stack, int& sp, const Entry& e, int k, uint32_t flip, uint32_t m8, uint32_t first,
                                            const WalkCtx& w, unsigned cm, unsigned stops)
{
    Entry& ch = stack[sp];
#if RK_SVO_TRAVERSE_LOD
    const __m128i rest = _mm_setr_epi32(int(child_handle(e, k, flip, m8, first, w)), int(cm), int(stops), int(e.handle));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(&ch), _mm256_set_m128i(rest, child_corner(e, k)));
#else
    set_child(ch, e, k, flip, m8, first, w, cm);
    (void)stops;
#endif
    sp += cm != 0u ? 1 : 0;
}

// One ray's 8 children at once, a lane each (lane k: mirrored child k), without a branch per
// child: X0, Mi, E1 are the ray's exit, middle and entry plane distances of the node per axis;
// child k's entry plane is E1 or Mi and its exit plane Mi or X0 by bit a of k; returns the
// children whose interval [lo, hi) is not empty (the walk's expressions; t0, th, tl as there)
// and writes their lo to lo8[k].
RK_SVO_PACKET_TARGET inline unsigned children8(const float* X0, const float* Mi, const float* E1, float t0, float th, float tl, float* lo8)
{
    const __m256 bx = _mm256_castsi256_ps(_mm256_setr_epi32(0, -1, 0, -1, 0, -1, 0, -1));
    const __m256 by = _mm256_castsi256_ps(_mm256_setr_epi32(0, 0, -1, -1, 0, 0, -1, -1));
    const __m256 bz = _mm256_castsi256_ps(_mm256_setr_epi32(0, 0, 0, 0, -1, -1, -1, -1));
    const __m256 mx = _mm256_set1_ps(Mi[0]), my = _mm256_set1_ps(Mi[1]), mz = _mm256_set1_ps(Mi[2]);
    const __m256 ex = _mm256_blendv_ps(mx, _mm256_set1_ps(E1[0]), bx), xx = _mm256_blendv_ps(_mm256_set1_ps(X0[0]), mx, bx);
    const __m256 ey = _mm256_blendv_ps(my, _mm256_set1_ps(E1[1]), by), xy = _mm256_blendv_ps(_mm256_set1_ps(X0[1]), my, by);
    const __m256 ez = _mm256_blendv_ps(mz, _mm256_set1_ps(E1[2]), bz), xz = _mm256_blendv_ps(_mm256_set1_ps(X0[2]), mz, bz);
    const __m256 TLv = _mm256_set1_ps(tl);
    const __m256 lo = _mm256_max_ps(_mm256_max_ps(ex, ey), _mm256_max_ps(ez, _mm256_set1_ps(t0)));
    __m256 hi = _mm256_min_ps(_mm256_min_ps(xx, xy), _mm256_min_ps(xz, TLv));
    hi = _mm256_blendv_ps(hi, TLv, _mm256_cmp_ps(hi, _mm256_set1_ps(th), _CMP_GE_OQ));
    _mm256_storeu_ps(lo8, lo);
    return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(lo, hi, _CMP_LT_OQ)));
}

// The lanes of a packet, as the walk (detail/svo_packet_walk.inl) uses them: V the planes, M a
// lane mask, I the lanes' child slots. 8 lanes on AVX2, masks as vectors.
struct Lanes8 {
    using V = __m256;
    using M = __m256i;
    using I = __m256i;
    static constexpr int N = 8;
    RK_SVO_PACKET_TARGET static V load(const float* p) { return _mm256_load_ps(p); }
    RK_SVO_PACKET_TARGET static V set1(float x) { return _mm256_set1_ps(x); }
    RK_SVO_PACKET_TARGET static V zero() { return _mm256_setzero_ps(); }
    RK_SVO_PACKET_TARGET static I zero_i() { return _mm256_setzero_si256(); }
    RK_SVO_PACKET_TARGET static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
    RK_SVO_PACKET_TARGET static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
    RK_SVO_PACKET_TARGET static V max(V a, V b) { return _mm256_max_ps(a, b); }  // a > b ? a : b
    RK_SVO_PACKET_TARGET static V min(V a, V b) { return _mm256_min_ps(a, b); }  // a < b ? a : b
    // hi >= t_hi becomes t_hi_up.
    RK_SVO_PACKET_TARGET static V close_end(V hi, V t_hi, V t_hi_up) { return _mm256_blendv_ps(hi, t_hi_up, _mm256_cmp_ps(hi, t_hi, _CMP_GE_OQ)); }
    // The next float up; +-0 gives the smallest normal float, not the smallest denormal, so that a
    // cell entered at 0 by a ray with t_hi 0 passes lo < next_up(t_hi) under denormals-are-zero too
    // (no plane distance lies in (0, FLT_MIN): the same answers).
    RK_SVO_PACKET_TARGET static V next_up(V x)
    {
        const V z = _mm256_setzero_ps();
        const __m256i up = _mm256_add_epi32(_mm256_castps_si256(x), _mm256_blendv_epi8(_mm256_set1_epi32(-1), _mm256_set1_epi32(1),
                                                                                      _mm256_castps_si256(_mm256_cmp_ps(x, z, _CMP_GT_OQ))));
        return _mm256_blendv_ps(_mm256_castsi256_ps(up), _mm256_castsi256_ps(_mm256_set1_epi32(0x00800000)), _mm256_cmp_ps(x, z, _CMP_EQ_OQ));
    }
    RK_SVO_PACKET_TARGET static M mask_of(unsigned m)
    {
        return svo_rays_detail::ne0(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(m)), _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128)));
    }
    RK_SVO_PACKET_TARGET static M lt_and(V a, V b, M m) { return _mm256_and_si256(_mm256_castps_si256(_mm256_cmp_ps(a, b, _CMP_LT_OQ)), m); }
    RK_SVO_PACKET_TARGET static unsigned lt_bits(V a, V b) { return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LT_OQ))); }
    RK_SVO_PACKET_TARGET static unsigned le_bits(V a, V b) { return static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(a, b, _CMP_LE_OQ))); }
    RK_SVO_PACKET_TARGET static V add(V a, V b) { return _mm256_add_ps(a, b); }
    RK_SVO_PACKET_TARGET static M and_not(M a, M b) { return _mm256_andnot_si256(a, b); }  // b & ~a
    RK_SVO_PACKET_TARGET static unsigned bits(M m) { return static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(m))); }
    RK_SVO_PACKET_TARGET static I blend_k(M m, I a, int k) { return _mm256_blendv_epi8(a, _mm256_set1_epi32(k), m); }
    RK_SVO_PACKET_TARGET static V blend(M m, V a, V b) { return _mm256_blendv_ps(a, b, _mm256_castsi256_ps(m)); }
    RK_SVO_PACKET_TARGET static void store(float* p, V v) { _mm256_store_ps(p, v); }
    RK_SVO_PACKET_TARGET static void store_i(int32_t* p, I v) { _mm256_store_si256(reinterpret_cast<__m256i*>(p), v); }
    // Lane by lane: bit `bit` of k set ? b : a.
    RK_SVO_PACKET_TARGET static V pick(I k, int bit, V a, V b)
    {
        const __m256i bv = _mm256_set1_epi32(bit);
        return _mm256_blendv_ps(a, b, _mm256_castsi256_ps(_mm256_cmpeq_epi32(_mm256_and_si256(k, bv), bv)));
    }
    RK_SVO_PACKET_TARGET static void entry_normal(V tx, V ty, V tz, V ux, V uy, V uz, float* nx, float* ny, float* nz)
    {
        entry_normal8(tx, ty, tz, ux, uy, uz, nx, ny, nz);
    }
    // No brick_hit on 8 lanes: eight groups of 8 voxels are slower than the walk's own brick
    // expansions there (docs/svo-traverse.md).
    static constexpr bool kBrickHit = false;
    static int brick_hit(const glm::vec3&, float, const glm::vec3&, const glm::vec3&, float, float, float, uint64_t, float&) { return -1; }
};

#define RK_SVO_PW_NAME walk
#define RK_SVO_PW_EXPAND expand8
#define RK_SVO_PW_TARGET RK_SVO_PACKET_TARGET
#define RK_SVO_PW_LANES Lanes8
#define RK_SVO_PW_SETUP Setup
#include "raykit/detail/svo_packet_walk.inl"

// 16-ray packets (4x4 tiles) on AVX2 where the CPU has no AVX-512F: two 8-lane registers per lane
// value (rays 0-7 and 8-15), a node whose rays lie in one half expanded on that half's lanes
// alone (RK_SVO_PW_HALVES): 1.06-1.27x two 4x2 packets (docs/svo-traverse.md).
#define RK_SVO_LP_NAME Lanes8x2
#define RK_SVO_LP_HALF Lanes8
#define RK_SVO_LP_TARGET RK_SVO_PACKET_TARGET
#include "raykit/detail/svo_packet_pair.inl"

#define RK_SVO_PW_NAME walk8x2
#define RK_SVO_PW_EXPAND expand8x2
#define RK_SVO_PW_HALVES 1
#define RK_SVO_PW_TARGET RK_SVO_PACKET_TARGET
#define RK_SVO_PW_LANES Lanes8x2
#define RK_SVO_PW_SETUP SetupLanes<16>
#include "raykit/detail/svo_packet_walk.inl"

// 16-ray packets (4x4 tiles) on AVX-512 lanes, GCC and Clang: the same walk on one 16-lane register
// (the same expressions per lane, so the same answers).
#if defined(__GNUC__) || defined(__clang__)
#define RK_SVO_PACKET16 1
#if defined(__clang__)
#define RK_SVO_PACKET16_TARGET __attribute__((target("avx512f,avx2,popcnt")))
#else
// GCC contracts a product and a difference of intrinsics into a fused multiply-add where FMA is
// enabled (AVX-512 implies it); the planes must round as rk_svo_trace's do.
#define RK_SVO_PACKET16_TARGET __attribute__((target("avx512f,avx2,popcnt"), optimize("fp-contract=off")))
#endif
inline bool packet16_cpu_ok() { return packet_cpu_ok() && __builtin_cpu_supports("avx512f") != 0; }

using Setup16 = SetupLanes<16>;

// N / 8 set-ups of 8 rays side by side (Setup16, Setup32), written in place (lanes of an absent
// group of 8 are invalid).
template <unsigned N, class SetupT>
inline void setup_wide(const rk_svo_tree& tree, const SvoRay* const* rp, unsigned n, SetupT& S)
{
    unsigned valid = 0u;
    for (unsigned q = 0; q < N; q += 8u) {
        const unsigned k = n > q ? (n - q < 8u ? n - q : 8u) : 0u;
        valid |= setup8(tree, k != 0u ? rp + q : rp, k, S, int(q)) << q;
    }
    S.valid = valid;
}

// Lanes8's operations on 16 lanes of AVX-512 registers, masks in mask registers. max and min take
// the zero-masking forms: GCC 12's plain _mm512_max_ps passes an undefined source that
// -Wmaybe-uninitialized reports in users' builds (the same instruction either way).
struct Lanes16 {
    using V = __m512;
    using M = __mmask16;
    using I = __m512i;
    static constexpr int N = 16;
    RK_SVO_PACKET16_TARGET static V load(const float* p) { return _mm512_load_ps(p); }
    RK_SVO_PACKET16_TARGET static V set1(float x) { return _mm512_set1_ps(x); }
    RK_SVO_PACKET16_TARGET static V zero() { return _mm512_setzero_ps(); }
    RK_SVO_PACKET16_TARGET static I zero_i() { return _mm512_setzero_si512(); }
    RK_SVO_PACKET16_TARGET static V mul(V a, V b) { return _mm512_mul_ps(a, b); }
    RK_SVO_PACKET16_TARGET static V sub(V a, V b) { return _mm512_sub_ps(a, b); }
    RK_SVO_PACKET16_TARGET static V max(V a, V b) { return _mm512_maskz_max_ps(static_cast<__mmask16>(0xFFFFu), a, b); }
    RK_SVO_PACKET16_TARGET static V min(V a, V b) { return _mm512_maskz_min_ps(static_cast<__mmask16>(0xFFFFu), a, b); }
    RK_SVO_PACKET16_TARGET static V close_end(V hi, V t_hi, V t_hi_up)
    {
        return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(hi, t_hi, _CMP_GE_OQ), hi, t_hi_up);
    }
    RK_SVO_PACKET16_TARGET static V next_up(V x)
    {
        const V z = _mm512_setzero_ps();
        const __m512i up = _mm512_add_epi32(_mm512_castps_si512(x), _mm512_mask_blend_epi32(_mm512_cmp_ps_mask(x, z, _CMP_GT_OQ),
                                                                                            _mm512_set1_epi32(-1), _mm512_set1_epi32(1)));
        return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(x, z, _CMP_EQ_OQ), _mm512_castsi512_ps(up), _mm512_castsi512_ps(_mm512_set1_epi32(0x00800000)));
    }
    static M mask_of(unsigned m) { return static_cast<__mmask16>(m); }
    RK_SVO_PACKET16_TARGET static M lt_and(V a, V b, M m) { return static_cast<__mmask16>(_mm512_cmp_ps_mask(a, b, _CMP_LT_OQ) & m); }
    RK_SVO_PACKET16_TARGET static unsigned lt_bits(V a, V b) { return static_cast<unsigned>(_mm512_cmp_ps_mask(a, b, _CMP_LT_OQ)); }
    RK_SVO_PACKET16_TARGET static unsigned le_bits(V a, V b) { return static_cast<unsigned>(_mm512_cmp_ps_mask(a, b, _CMP_LE_OQ)); }
    RK_SVO_PACKET16_TARGET static V add(V a, V b) { return _mm512_add_ps(a, b); }
    static M and_not(M a, M b) { return static_cast<__mmask16>(b & ~a); }
    static unsigned bits(M m) { return static_cast<unsigned>(m); }
    RK_SVO_PACKET16_TARGET static I blend_k(M m, I a, int k) { return _mm512_mask_blend_epi32(m, a, _mm512_set1_epi32(k)); }
    RK_SVO_PACKET16_TARGET static V blend(M m, V a, V b) { return _mm512_mask_blend_ps(m, a, b); }
    RK_SVO_PACKET16_TARGET static void store(float* p, V v) { _mm512_store_ps(p, v); }
    RK_SVO_PACKET16_TARGET static void store_i(int32_t* p, I v) { _mm512_store_si512(p, v); }
    RK_SVO_PACKET16_TARGET static V pick(I k, int bit, V a, V b) { return _mm512_mask_blend_ps(_mm512_test_epi32_mask(k, _mm512_set1_epi32(bit)), a, b); }
    // entry_normal8 on 16 lanes.
    RK_SVO_PACKET16_TARGET static void entry_normal(V tx, V ty, V tz, V ux, V uy, V uz, float* nx, float* ny, float* nz)
    {
        // |u| by the zero-masking and-not (GCC 12's plain one passes an undefined source, see max).
        const __mmask16 all = static_cast<__mmask16>(0xFFFFu);
        const __m512i sgn = _mm512_set1_epi32(int(0x80000000u));
        const V sg = _mm512_castsi512_ps(sgn), z = _mm512_setzero_ps();
        const V ax = _mm512_castsi512_ps(_mm512_maskz_andnot_epi32(all, sgn, _mm512_castps_si512(ux)));
        const V ay = _mm512_castsi512_ps(_mm512_maskz_andnot_epi32(all, sgn, _mm512_castps_si512(uy)));
        const V az = _mm512_castsi512_ps(_mm512_maskz_andnot_epi32(all, sgn, _mm512_castps_si512(uz)));
        const __mmask16 c1 = static_cast<__mmask16>(_mm512_cmp_ps_mask(ty, tx, _CMP_GT_OQ) |
                                                    (_mm512_cmp_ps_mask(ty, tx, _CMP_EQ_OQ) & _mm512_cmp_ps_mask(ay, ax, _CMP_GT_OQ)));
        const V tb = _mm512_mask_blend_ps(c1, tx, ty), ub = _mm512_mask_blend_ps(c1, ax, ay);
        const __mmask16 c2 = static_cast<__mmask16>(_mm512_cmp_ps_mask(tz, tb, _CMP_GT_OQ) |
                                                    (_mm512_cmp_ps_mask(tz, tb, _CMP_EQ_OQ) & _mm512_cmp_ps_mask(az, ub, _CMP_GT_OQ)));
        const V one = _mm512_set1_ps(1.0f), m_one = _mm512_set1_ps(-1.0f);
        const V sx = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(ux, z, _CMP_GT_OQ), _mm512_mask_blend_ps(_mm512_cmp_ps_mask(ux, z, _CMP_LT_OQ), sg, one), m_one);
        const V sy = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(uy, z, _CMP_GT_OQ), _mm512_mask_blend_ps(_mm512_cmp_ps_mask(uy, z, _CMP_LT_OQ), sg, one), m_one);
        const V sz = _mm512_mask_blend_ps(_mm512_cmp_ps_mask(uz, z, _CMP_GT_OQ), _mm512_mask_blend_ps(_mm512_cmp_ps_mask(uz, z, _CMP_LT_OQ), sg, one), m_one);
        _mm512_store_ps(nx, _mm512_maskz_mov_ps(static_cast<__mmask16>(~(c1 | c2)), sx));
        _mm512_store_ps(ny, _mm512_maskz_mov_ps(static_cast<__mmask16>(c1 & ~c2), sy));
        _mm512_store_ps(nz, _mm512_maskz_mov_ps(c2, sz));
    }
    // One ray in a 4^3 brick, all 64 voxels at once: the brick's mirrored minimum corner p, its
    // voxels' edge q and the ray's plane coefficients c, b give the 5 plane distances
    // (p + j q) c - b of each mirrored axis (the walk's, in the same operations), occ the occupied
    // voxels by mirrored index (mirror64). Voxel m = (mirrored sub-node << 3) | mirrored slot spans
    // planes i..i+1 on each axis (i = 2 * sub bit + slot bit); its interval is the walk's [lo, hi).
    // Returns the voxel the ray enters first (its lo in `lo_out`), -1 if none: the intervals of one
    // ray are disjoint, so that is the walk's two-level answer, without its branches (ties: the
    // highest m, the walk's order).
    static constexpr bool kBrickHit = true;
    RK_SVO_PACKET16_TARGET static V perm(__m512i idx, V table) { return _mm512_maskz_permutexvar_ps(static_cast<__mmask16>(0xFFFFu), idx, table); }
    RK_SVO_PACKET16_TARGET static int brick_hit(const glm::vec3& p, float q, const glm::vec3& c, const glm::vec3& b, float t0, float th,
                                                float tl, uint64_t occ, float& lo_out)
    {
        const __m512 J = _mm512_setr_ps(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
        const __m512 Q = _mm512_mul_ps(_mm512_set1_ps(q), J);
        const __m512 Tx = _mm512_sub_ps(_mm512_mul_ps(_mm512_add_ps(_mm512_set1_ps(p.x), Q), _mm512_set1_ps(c.x)), _mm512_set1_ps(b.x));
        const __m512 Ty = _mm512_sub_ps(_mm512_mul_ps(_mm512_add_ps(_mm512_set1_ps(p.y), Q), _mm512_set1_ps(c.y)), _mm512_set1_ps(b.y));
        const __m512 Tz = _mm512_sub_ps(_mm512_mul_ps(_mm512_add_ps(_mm512_set1_ps(p.z), Q), _mm512_set1_ps(c.z)), _mm512_set1_ps(b.z));
        const __m512 T0 = _mm512_set1_ps(t0), TH = _mm512_set1_ps(th), TLv = _mm512_set1_ps(tl);
        const __m512 inf = _mm512_castsi512_ps(_mm512_set1_epi32(0x7F800000));
        const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
        const __m512i one = _mm512_set1_epi32(1);
        __m512 L[4];
        for (int g = 0; g < 4; ++g) {
            const __m512i m = _mm512_add_epi32(lane, _mm512_set1_epi32(16 * g));
            // i = 2 * bit(3 + a) + bit(a) of m, for axis a = 0, 1, 2.
            const __m512i ix = _mm512_or_si512(_mm512_and_si512(_mm512_srli_epi32(m, 2), _mm512_set1_epi32(2)), _mm512_and_si512(m, one));
            const __m512i iy = _mm512_or_si512(_mm512_and_si512(_mm512_srli_epi32(m, 3), _mm512_set1_epi32(2)),
                                               _mm512_and_si512(_mm512_srli_epi32(m, 1), one));
            const __m512i iz = _mm512_or_si512(_mm512_and_si512(_mm512_srli_epi32(m, 4), _mm512_set1_epi32(2)),
                                               _mm512_and_si512(_mm512_srli_epi32(m, 2), one));
            const __m512 ex = perm(_mm512_add_epi32(ix, one), Tx), xx = perm(ix, Tx);
            const __m512 ey = perm(_mm512_add_epi32(iy, one), Ty), xy = perm(iy, Ty);
            const __m512 ez = perm(_mm512_add_epi32(iz, one), Tz), xz = perm(iz, Tz);
            const __m512 lo = max(max(ex, ey), max(ez, T0));
            const __m512 hi = close_end(min(min(xx, xy), min(xz, TLv)), TH, TLv);
            const __mmask16 in = static_cast<__mmask16>(_mm512_cmp_ps_mask(lo, hi, _CMP_LT_OQ) & static_cast<unsigned>(occ >> (16 * g)));
            L[g] = _mm512_mask_blend_ps(in, inf, lo);
        }
        // The minimum in every lane (zero-masking shuffles: see max and min).
        const __mmask16 all = static_cast<__mmask16>(0xFFFFu);
        __m512 m4 = min(min(L[0], L[1]), min(L[2], L[3]));
        m4 = min(m4, _mm512_maskz_shuffle_f32x4(all, m4, m4, 0x4E));
        m4 = min(m4, _mm512_maskz_shuffle_f32x4(all, m4, m4, 0xB1));
        m4 = min(m4, _mm512_maskz_permute_ps(all, m4, 0x4E));
        m4 = min(m4, _mm512_maskz_permute_ps(all, m4, 0xB1));
        const float best = _mm512_cvtss_f32(m4);
        if (!(best < uintBitsToFloat(0x7F800000u))) return -1;
        // The highest voxel with that distance, from the four groups' masks at once (no branch per group).
        const __m512 bv = _mm512_set1_ps(best);
        const uint64_t eq = uint64_t(_mm512_cmp_ps_mask(L[0], bv, _CMP_EQ_OQ)) | (uint64_t(_mm512_cmp_ps_mask(L[1], bv, _CMP_EQ_OQ)) << 16u) |
                            (uint64_t(_mm512_cmp_ps_mask(L[2], bv, _CMP_EQ_OQ)) << 32u) | (uint64_t(_mm512_cmp_ps_mask(L[3], bv, _CMP_EQ_OQ)) << 48u);
        lo_out = best;
        return 63 - __builtin_clzll(eq);
    }
};

#define RK_SVO_PW_NAME walk16
#define RK_SVO_PW_EXPAND expand16
#define RK_SVO_PW_TARGET RK_SVO_PACKET16_TARGET
#define RK_SVO_PW_LANES Lanes16
#define RK_SVO_PW_SETUP Setup16
#include "raykit/detail/svo_packet_walk.inl"

// 32-ray packets (8x4 tiles): the same walk with every lane value in two AVX-512 registers (rays
// 0-15 and 16-31), Lanes16's operations on each; a node whose rays all lie in one half is expanded
// on that half alone (RK_SVO_PW_HALVES). Two 4x4 packets walk the levels above their rays' parting
// twice; one 8x4 packet walks them once.
using Setup32 = SetupLanes<32>;

#define RK_SVO_LP_NAME Lanes32
#define RK_SVO_LP_HALF Lanes16
#define RK_SVO_LP_TARGET RK_SVO_PACKET16_TARGET
#include "raykit/detail/svo_packet_pair.inl"

#define RK_SVO_PW_NAME walk32
#define RK_SVO_PW_EXPAND expand32
#define RK_SVO_PW_HALVES 1
#define RK_SVO_PW_TARGET RK_SVO_PACKET16_TARGET
#define RK_SVO_PW_LANES Lanes32
#define RK_SVO_PW_SETUP Setup32
#include "raykit/detail/svo_packet_walk.inl"
#else
#define RK_SVO_PACKET16 0
#endif
#endif

}  // namespace svo_packet_detail

namespace svo_packet_detail {
#if RK_SVO_PACKET_SIMD
// Whether the packet walk applies to this tree (else rk_svo_trace per ray).
inline bool packet_tree_ok(const rk_svo_tree& tree)
{
    return tree.brick_base_word < 0x80000000u && tree.root_size > 0.0f && tree.depth >= 1u && tree.depth <= RK_SVO_MAX_DEPTH &&
           tree.max_level >= 1u;
}

// Traces the set-up rays as one packet per direction octant present, with `walk_fn` (walk or
// walk16); rays the node bound stops go to rk_svo_trace, and so do (LOD builds) rays whose footprint
// stops them at the root (rk_svo_trace_begin_ answers those).
template <class SetupT, class WalkFn>
inline void trace_set_up(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* const* rp, SetupT& S, unsigned n,
                         rk_svo_trace_hit* const* hits, glm::vec2 cone, WalkFn walk_fn)
{
    for (unsigned i = 0; i < n; ++i) *hits[i] = rk_svo_trace_hit{false, 0.0f, 0u, glm::uvec3(0u), glm::vec3(0.0f), 0u, 0u, glm::uvec2(0u), 0u};
    unsigned pending = S.valid;
#if RK_SVO_TRAVERSE_LOD
    // rk_svo_trace_begin_'s footprint, from the same expressions.
    S.lod_bias = glm::max(cone.x, 0.0f) * (1.0f / tree.root_size);
    S.lod_slope = glm::max(cone.y, 0.0f);
    for (unsigned m = pending; m != 0u; m &= m - 1u) {
        const int i = svo_rays_detail::lowest_bit(m);
        if (1.0f <= S.lod_bias + S.lod_slope * (S.t_enter[i] + S.t_min[i])) {
            *hits[i] = rk_svo_trace(words, tree, rp[i]->origin, rp[i]->dir, rp[i]->t_max, cone);
            pending &= ~(1u << i);
        }
    }
#else
    S.lod_bias = 0.0f;
    S.lod_slope = 0.0f;
#endif
    while (pending != 0u) {
        const int32_t flip = S.flip[svo_rays_detail::lowest_bit(pending)];
        unsigned group = 0u;
        for (unsigned m = pending; m != 0u; m &= m - 1u) {
            const int i = svo_rays_detail::lowest_bit(m);
            if (S.flip[i] == flip) group |= 1u << i;
        }
        pending &= ~group;
        const unsigned left = walk_fn(words, tree, S, group, uint32_t(flip), hits);
        for (unsigned m = left; m != 0u; m &= m - 1u) {
            const int i = svo_rays_detail::lowest_bit(m);
            *hits[i] = rk_svo_trace(words, tree, rp[i]->origin, rp[i]->dir, rp[i]->t_max, cone);
        }
    }
}
#endif
}  // namespace svo_packet_detail

namespace svo_packet_detail {
// svo_trace_packet8/16 on rays and answers reached through pointers (*rp[i] is answered in *hp[i]),
// so that svo_trace_packets traces a tile of an image in place.
inline void packet8(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* const* rp, rk_svo_trace_hit* const* hp,
                    unsigned n, glm::vec2 cone)
{
#if RK_SVO_PACKET_SIMD
    if (n > 0u && packet_tree_ok(tree) && packet_cpu_ok()) {
        Setup S;
        S.valid = setup8(tree, rp, n, S, 0);
        trace_set_up(words, tree, rp, S, n, hp, cone, walk);
        return;
    }
#endif
    for (unsigned i = 0; i < n; ++i) *hp[i] = rk_svo_trace(words, tree, rp[i]->origin, rp[i]->dir, rp[i]->t_max, cone);
}

#if RK_SVO_PACKET_SIMD
// n <= N rays as one packet of N lanes (walk_fn: walk8x2 on AVX2, walk16 or walk32 on AVX-512; ok:
// the CPU has its instructions); false where it does not apply (no rays, a tree the walk does not
// take, a CPU without them).
template <unsigned N, class SetupT, class WalkFn>
inline bool packet_wide(bool ok, const uint32_t* words, const rk_svo_tree& tree, const SvoRay* const* rp, rk_svo_trace_hit* const* hp,
                        unsigned n, glm::vec2 cone, WalkFn walk_fn)
{
    if (!ok || n == 0u || !packet_tree_ok(tree)) return false;
    SetupT S;
    setup_wide<N>(tree, rp, n, S);
    trace_set_up(words, tree, rp, S, n, hp, cone, walk_fn);
    return true;
}
#endif

// n <= 16 rays as one packet on AVX2 lanes, two 8-lane registers per value (where the CPU has no
// AVX-512F; tests call it directly); false where it does not apply.
inline bool packet16_avx2(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* const* rp, rk_svo_trace_hit* const* hp,
                          unsigned n, glm::vec2 cone)
{
#if RK_SVO_PACKET_SIMD
    return packet_wide<16, SetupLanes<16>>(packet_cpu_ok(), words, tree, rp, hp, n, cone, walk8x2);
#else
    (void)words, (void)tree, (void)rp, (void)hp, (void)n, (void)cone;
    return false;
#endif
}

// n rays as packets of up to `w` rays by `fn` (packet8, packet16), in order.
template <class PacketFn>
inline void packets_of(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* const* rp, rk_svo_trace_hit* const* hp,
                       unsigned n, glm::vec2 cone, unsigned w, PacketFn fn)
{
    for (unsigned i = 0; i < n; i += w) fn(words, tree, rp + i, hp + i, n - i < w ? n - i : w, cone);
}

// Else as two packets of half the width.
inline void packet16(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* const* rp, rk_svo_trace_hit* const* hp,
                     unsigned n, glm::vec2 cone)
{
#if RK_SVO_PACKET_SIMD && RK_SVO_PACKET16
    if (packet_wide<16, Setup16>(packet16_cpu_ok(), words, tree, rp, hp, n, cone, walk16)) return;
#endif
    if (packet16_avx2(words, tree, rp, hp, n, cone)) return;
    packets_of(words, tree, rp, hp, n, cone, 8u, packet8);
}

inline void packet32(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* const* rp, rk_svo_trace_hit* const* hp,
                     unsigned n, glm::vec2 cone)
{
#if RK_SVO_PACKET_SIMD && RK_SVO_PACKET16
    if (packet_wide<32, Setup32>(packet16_cpu_ok(), words, tree, rp, hp, n, cone, walk32)) return;
#endif
    packets_of(words, tree, rp, hp, n, cone, 16u, packet16);
}

// The rays of a row-major block `width` wide (n rays, partial last row allowed) in tiles of
// tile_w x tile_h (tile_w * tile_h <= 32; partial at the right and bottom edges), each traced by
// `fn` (packet8, packet16, packet32 or a test's own) on pointers to its rays and answers.
template <class PacketFn>
inline void trace_tiles(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, std::size_t n, std::size_t width,
                        rk_svo_trace_hit* hits, unsigned tile_w, unsigned tile_h, glm::vec2 cone, PacketFn fn)
{
    const std::size_t rows = (n + width - 1u) / width;
    const SvoRay* rp[32];
    rk_svo_trace_hit* hp[32];
    for (std::size_t y0 = 0; y0 < rows; y0 += tile_h)
        for (std::size_t x0 = 0; x0 < width; x0 += tile_w) {
            unsigned k = 0;
            for (std::size_t y = y0; y < y0 + tile_h && y < rows; ++y)
                for (std::size_t x = x0; x < x0 + tile_w && x < width; ++x) {
                    const std::size_t i = y * width + x;
                    if (i >= n) continue;
                    rp[k] = rays + i;
                    hp[k++] = hits + i;
                }
            if (k != 0u) fn(words, tree, rp, hp, k, cone);
        }
}

// packet8, packet16 or packet32 (`fn`) on n <= N contiguous rays and answers.
template <unsigned N, class PacketFn>
inline void packet_contiguous(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, rk_svo_trace_hit* hits, unsigned n,
                              glm::vec2 cone, PacketFn fn)
{
    const SvoRay* rp[N];
    rk_svo_trace_hit* hp[N];
    for (unsigned i = 0; i < n; ++i) rp[i] = rays + i, hp[i] = hits + i;
    fn(words, tree, rp, hp, n, cone);
}
}  // namespace svo_packet_detail

/// svo_trace_packet8: hits[i] = the answer of rk_svo_trace(words, tree, rays[i].origin, rays[i].dir,
/// rays[i].t_max, cone) for i < n (n <= 8), the rays traced as one packet (see the file comment):
/// hit, t, level, cell, normal, node and brick fields as rk_svo_trace (up to its near-parallel
/// clamp; ties in edges and corners as rk_svo_trace's); `iterations` counts the packet's node
/// expansions. Coherent rays (a 2x4 pixel tile) make it pay: the packet expands each node once for
/// all its rays. `words` as SvoTree::gpu_words(). `cone` is every ray's footprint in a
/// RK_SVO_TRAVERSE_LOD=1 build (rk_svo_pixel_cone), ignored otherwise.
inline void svo_trace_packet8(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, rk_svo_trace_hit* hits,
                              unsigned n = 8u, glm::vec2 cone = glm::vec2(0.0f))
{
    svo_packet_detail::packet_contiguous<8>(words, tree, rays, hits, n < 8u ? n : 8u, cone, svo_packet_detail::packet8);
}

/// svo_trace_packet16: svo_trace_packet8 for up to 16 rays (a 4x4 pixel tile) sharing one traversal
/// on AVX-512 lanes, where the CPU has AVX-512F (GCC, Clang), else on two 8-lane AVX2 registers per
/// value; without AVX2, rays 0-7 and 8-15 go to svo_trace_packet8. The same answers either way (the
/// same expressions per lane). Where the rays are coherent a 4x4 packet shares more nodes than two
/// 4x2 ones (docs/svo-traverse.md).
inline void svo_trace_packet16(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, rk_svo_trace_hit* hits,
                               unsigned n = 16u, glm::vec2 cone = glm::vec2(0.0f))
{
    svo_packet_detail::packet_contiguous<16>(words, tree, rays, hits, n < 16u ? n : 16u, cone, svo_packet_detail::packet16);
}

/// svo_trace_packet32: svo_trace_packet16 for up to 32 rays (an 8x4 pixel tile) sharing one traversal,
/// each lane value in two AVX-512 registers, where the CPU has AVX-512F (GCC, Clang); elsewhere rays
/// 0-15 and 16-31 go to svo_trace_packet16. The same answers either way. A node whose rays all lie
/// in one half is expanded on that half's 16 lanes.
inline void svo_trace_packet32(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, rk_svo_trace_hit* hits,
                               unsigned n = 32u, glm::vec2 cone = glm::vec2(0.0f))
{
    svo_packet_detail::packet_contiguous<32>(words, tree, rays, hits, n < 32u ? n : 32u, cone, svo_packet_detail::packet32);
}

/// svo_trace_packet_best_tile: the tile svo_trace_packets uses by default on this CPU: 8 x 4 where
/// the packets run on AVX-512 lanes (svo_trace_packet32; one packet walks the upper levels once for
/// 32 rays, and a node whose rays lie in one half of it is expanded on 16 lanes: 1.06-1.18x the 4x4
/// tiles at depths 8-12), else 4 x 4 (svo_trace_packet16 on two 8-lane AVX2 registers per value:
/// 1.06-1.27x the 4x2 tiles; docs/svo-traverse.md).
inline void svo_trace_packet_best_tile(unsigned& tile_w, unsigned& tile_h)
{
    tile_w = 4u;
    tile_h = 4u;
#if RK_SVO_PACKET_SIMD && RK_SVO_PACKET16
    if (svo_packet_detail::packet16_cpu_ok()) tile_w = 8u;
#endif
}

/// svo_trace_packets: the rays of a row-major image block `width` rays wide (n = width * rows,
/// partial last row allowed), traced in packets of tile_w x tile_h pixels (tile_w * tile_h <= 32;
/// 0 x 0, the default: svo_trace_packet_best_tile; more than 8 rays go to
/// svo_trace_packet16, more than 16 to svo_trace_packet32; tiles at the right and bottom edges are
/// partial; a larger tile traces 8 rays at a time in order). hits[i] answers rays[i]; `cone` as
/// svo_trace_packet8.
inline void svo_trace_packets(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, std::size_t n, std::size_t width,
                              rk_svo_trace_hit* hits, unsigned tile_w = 0u, unsigned tile_h = 0u, glm::vec2 cone = glm::vec2(0.0f))
{
    if (tile_w == 0u && tile_h == 0u) svo_trace_packet_best_tile(tile_w, tile_h);
    if (width == 0u || tile_w == 0u || tile_h == 0u || tile_w > 32u || tile_h > 32u || tile_w * tile_h > 32u) {
        for (std::size_t i = 0; i < n; i += 8) svo_trace_packet8(words, tree, rays + i, hits + i, unsigned(n - i < 8 ? n - i : 8), cone);
        return;
    }
    const unsigned lanes = tile_w * tile_h;
    const auto fn = lanes > 16u ? svo_packet_detail::packet32 : lanes > 8u ? svo_packet_detail::packet16 : svo_packet_detail::packet8;
    svo_packet_detail::trace_tiles(words, tree, rays, n, width, hits, tile_w, tile_h, cone, fn);
}

}  // namespace RK_SVO_RAYS_NS_CAT(RK_SVO_RAYS_SIMD)
}  // namespace RK_SVO_TRAVERSE_NS
}  // namespace raykit
