// raykit — svo_trace_packet.hpp: rk_svo_trace for coherent packets of up to 8 rays (primary rays of
// a pixel tile) that share ONE traversal of the packed octree, the rays on the 8 lanes of AVX2
// registers, as Embree traces coherent packets. svo_trace_rays (svo_trace_simd.hpp) runs one
// traversal per lane instead; rk_svo_trace one per call.
//
// A C++ twin of rk_svo_trace, not shared text (GLSL has no lanes to program). The set-up is a lanes
// twin of rk_svo_trace_begin_ (the same float operations in the same order) and the hit is
// rk_svo_trace_finish_ itself. Rays of one direction octant share the mirroring, so every node has
// the same mirrored coordinates for all of them and visiting children in decreasing mirrored slot
// is front to back for each ray. The packet walks the tree depth first; at a node, each ray's
// interval in each child is [max(entry planes, t_start), min(exit planes)), with rk_svo_trace's
// plane expressions. These half-open intervals tile a ray's path, so a ray is answered at the first
// voxel it reaches, which is rk_svo_trace's.
//
// Contract: the answers (hit, t, level, cell, normal, node and brick fields) are rk_svo_trace's,
// except at exact lattice ties (a ray in a face plane, through an edge or corner, or with
// near-parallel components, where rk_svo_trace's "never backwards" clamp acts): both answers are
// then accepted by the float64 dense-grid DDA (tests/test_svo_trace_packet.cpp). `iterations` is
// the number of nodes the packet expanded until that ray was answered, not rk_svo_trace's count.
// Rays of different octants in one packet are traced as one packet per octant. A packet that
// expands more than RK_SVO_TRAVERSE_MAX_ITER nodes hands its remaining rays to rk_svo_trace. LOD
// builds (RK_SVO_TRAVERSE_LOD=1), CPUs without AVX2 and POPCNT, trees of 2^31 words or more and
// max_level 0 use rk_svo_trace per ray. The MSVC path (/arch:AVX2) is written but not compiled yet.
// Cost: it pays where the 8 rays of a tile stay in the same nodes, i.e. where a pixel's footprint
// is not much smaller than a voxel; measured speed-ups by depth are in docs/svo-traverse.md.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raykit/svo_trace_simd.hpp"
#include "raykit/svo_traverse.hpp"

namespace raykit {
inline namespace RK_SVO_TRAVERSE_NS {
inline namespace RK_SVO_RAYS_NS_CAT(RK_SVO_RAYS_SIMD) {

namespace svo_packet_detail {

#if RK_SVO_RAYS_SIMD && !RK_SVO_TRAVERSE_LOD
#define RK_SVO_PACKET_SIMD 1
#else
#define RK_SVO_PACKET_SIMD 0
#endif

#if RK_SVO_PACKET_SIMD
#if defined(__GNUC__) || defined(__clang__)
#define RK_SVO_PACKET_TARGET __attribute__((target("avx2,popcnt")))
inline bool packet_cpu_ok() { return svo_trace_simd_available() && __builtin_cpu_supports("popcnt") != 0; }
#else
#define RK_SVO_PACKET_TARGET
inline bool packet_cpu_ok() { return svo_trace_simd_available(); }
#endif

// The set-up of rk_svo_trace_begin_ for 8 rays at once, the same float operations in the same
// order (so the same bits), one array per field; `valid` has the rays that enter the root.
struct alignas(32) Setup {
    float cx[8], cy[8], cz[8], bx[8], by[8], bz[8];
    float ux[8], uy[8], uz[8];
    float t_min[8], t_hi[8], t_enter[8], t_scale[8];
    int32_t flip[8];
    unsigned valid;
};

RK_SVO_PACKET_TARGET inline void setup8(const rk_svo_tree& tree, const SvoRay* rays, unsigned n, Setup& S)
{
    using svo_rays_detail::glm_max;
    using svo_rays_detail::glm_min;
    alignas(32) float ox[8], oy[8], oz[8], dx[8], dy[8], dz[8], tm[8];
    for (unsigned i = 0; i < 8; ++i) {
        const SvoRay& r = rays[i < n ? i : 0u];
        ox[i] = r.origin.x;
        oy[i] = r.origin.y;
        oz[i] = r.origin.z;
        dx[i] = r.dir.x;
        dy[i] = r.dir.y;
        dz[i] = r.dir.z;
        tm[i] = i < n ? r.t_max : -1.0f;
    }
    const __m256 sgn = _mm256_set1_ps(-0.0f);
    const __m256 one = _mm256_set1_ps(1.0f), two = _mm256_set1_ps(2.0f), three = _mm256_set1_ps(3.0f), zero = _mm256_setzero_ps();
    const __m256 fmax = _mm256_set1_ps(RK_FLT_MAX);
    const __m256 Dx = _mm256_load_ps(dx), Dy = _mm256_load_ps(dy), Dz = _mm256_load_ps(dz), TM = _mm256_load_ps(tm);
    const __m256 m = glm_max(glm_max(_mm256_andnot_ps(sgn, Dx), _mm256_andnot_ps(sgn, Dy)), _mm256_andnot_ps(sgn, Dz));
    __m256 ok = _mm256_and_ps(_mm256_cmp_ps(m, _mm256_set1_ps(RK_FLT_MIN), _CMP_GE_OQ), _mm256_cmp_ps(TM, zero, _CMP_GE_OQ));
    const __m256 nx = _mm256_div_ps(Dx, m), ny = _mm256_div_ps(Dy, m), nz = _mm256_div_ps(Dz, m);
    const __m256 len = _mm256_sqrt_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(nx, nx), _mm256_mul_ps(ny, ny)), _mm256_mul_ps(nz, nz)));
    __m256 ux = _mm256_div_ps(nx, len), uy = _mm256_div_ps(ny, len), uz = _mm256_div_ps(nz, len);
    const __m256 rs = _mm256_set1_ps(tree.root_size);
    _mm256_store_ps(S.t_scale, glm_min(_mm256_div_ps(_mm256_div_ps(rs, m), len), fmax));
    const __m256 inv_size = _mm256_set1_ps(1.0f / tree.root_size);
    __m256 Ox = _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(ox), _mm256_set1_ps(tree.root_min.x)), inv_size), one);
    __m256 Oy = _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(oy), _mm256_set1_ps(tree.root_min.y)), inv_size), one);
    __m256 Oz = _mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(oz), _mm256_set1_ps(tree.root_min.z)), inv_size), one);
    // Tiny components: +-2^-21 by the sign bit.
    const __m256 eps = _mm256_set1_ps(RK_SVO_TRAVERSE_DIR_EPS);
    ux = _mm256_blendv_ps(ux, _mm256_or_ps(eps, _mm256_and_ps(sgn, ux)), _mm256_cmp_ps(_mm256_andnot_ps(sgn, ux), eps, _CMP_LT_OQ));
    uy = _mm256_blendv_ps(uy, _mm256_or_ps(eps, _mm256_and_ps(sgn, uy)), _mm256_cmp_ps(_mm256_andnot_ps(sgn, uy), eps, _CMP_LT_OQ));
    uz = _mm256_blendv_ps(uz, _mm256_or_ps(eps, _mm256_and_ps(sgn, uz)), _mm256_cmp_ps(_mm256_andnot_ps(sgn, uz), eps, _CMP_LT_OQ));
    _mm256_store_ps(S.ux, ux);
    _mm256_store_ps(S.uy, uy);
    _mm256_store_ps(S.uz, uz);
    const __m256 ix = _mm256_div_ps(one, ux), iy = _mm256_div_ps(one, uy), iz = _mm256_div_ps(one, uz);
    const __m256 tax = _mm256_mul_ps(_mm256_sub_ps(one, Ox), ix), tbx = _mm256_mul_ps(_mm256_sub_ps(two, Ox), ix);
    const __m256 tay = _mm256_mul_ps(_mm256_sub_ps(one, Oy), iy), tby = _mm256_mul_ps(_mm256_sub_ps(two, Oy), iy);
    const __m256 taz = _mm256_mul_ps(_mm256_sub_ps(one, Oz), iz), tbz = _mm256_mul_ps(_mm256_sub_ps(two, Oz), iz);
    const __m256 t_enter = glm_max(glm_max(glm_max(glm_min(tax, tbx), glm_min(tay, tby)), glm_min(taz, tbz)), zero);
    const __m256 t_leave = glm_min(glm_min(glm_max(tax, tbx), glm_max(tay, tby)), glm_max(taz, tbz));
    __m256 t_lim = _mm256_and_ps(_mm256_cmp_ps(TM, zero, _CMP_GT_OQ),
                                 glm_min(_mm256_mul_ps(_mm256_mul_ps(TM, _mm256_div_ps(m, rs)), len), fmax));
    ok = _mm256_and_ps(ok, _mm256_and_ps(_mm256_cmp_ps(t_enter, t_leave, _CMP_LE_OQ), _mm256_cmp_ps(t_enter, t_lim, _CMP_LE_OQ)));
    S.valid = static_cast<unsigned>(_mm256_movemask_ps(ok)) & ((1u << n) - 1u);
    _mm256_store_ps(S.t_enter, t_enter);
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
    _mm256_store_si256(reinterpret_cast<__m256i*>(S.flip), fl);
    _mm256_store_ps(S.cx, cx);
    _mm256_store_ps(S.cy, cy);
    _mm256_store_ps(S.cz, cz);
    _mm256_store_ps(S.bx, bx);
    _mm256_store_ps(S.by, by);
    _mm256_store_ps(S.bz, bz);
    const __m256 t_min = glm_max(glm_max(glm_max(_mm256_sub_ps(_mm256_mul_ps(two, cx), bx), _mm256_sub_ps(_mm256_mul_ps(two, cy), by)),
                                         _mm256_sub_ps(_mm256_mul_ps(two, cz), bz)),
                                 zero);
    _mm256_store_ps(S.t_min, t_min);
    _mm256_store_ps(S.t_hi, glm_min(glm_min(glm_min(_mm256_sub_ps(cx, bx), _mm256_sub_ps(cy, by)), _mm256_sub_ps(cz, bz)), t_lim));
}

// A node to visit: its mirrored minimum corner, level, handle (descriptor or brick ordinal, or the
// sub-node's slot inside the current brick) and the rays that reach it.
struct Entry {
    float px, py, pz;
    uint32_t level;
    uint32_t handle;
    uint32_t rays;
};

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


// A cell's interval [lo, hi) is closed at the ray's end (rk_svo_trace enters a cell at t <= t_hi,
// its root exit or t limit): an exit at or beyond t_hi becomes next_up(t_hi).
RK_SVO_PACKET_TARGET inline __m256 close_end(__m256 hi, __m256 t_hi, __m256 t_hi_up)
{
    return _mm256_blendv_ps(hi, t_hi_up, _mm256_cmp_ps(hi, t_hi, _CMP_GE_OQ));
}

// The walk of one packet: `lanes` are rays whose st[i] came out of rk_svo_trace_begin_ with one
// and the same `flip`. Answers hits[i] for them; returns the lanes still unanswered when the node
// bound was reached (0 normally).
RK_SVO_PACKET_TARGET inline unsigned walk(const uint32_t* words, const rk_svo_tree& tree, const Setup& S, unsigned lanes,
                                          uint32_t flip, rk_svo_trace_hit* hits)
{
    // Lanes outside `lanes` get planes that no cell interval reaches (and their bits are masked).
    const __m256 lm = _mm256_castsi256_ps(svo_rays_detail::ne0(
        _mm256_and_si256(_mm256_set1_epi32(static_cast<int>(lanes)), _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128))));
    const __m256 m1 = _mm256_set1_ps(-1.0f), z = _mm256_setzero_ps();
    const __m256 Cx = _mm256_blendv_ps(m1, _mm256_load_ps(S.cx), lm), Cy = _mm256_blendv_ps(m1, _mm256_load_ps(S.cy), lm),
                 Cz = _mm256_blendv_ps(m1, _mm256_load_ps(S.cz), lm);
    const __m256 Bx = _mm256_blendv_ps(z, _mm256_load_ps(S.bx), lm), By = _mm256_blendv_ps(z, _mm256_load_ps(S.by), lm),
                 Bz = _mm256_blendv_ps(z, _mm256_load_ps(S.bz), lm);
    const __m256 T0 = _mm256_blendv_ps(_mm256_set1_ps(1.0f), _mm256_load_ps(S.t_min), lm);
    const __m256 TH = _mm256_blendv_ps(z, _mm256_load_ps(S.t_hi), lm);
    // lo <= t_hi  <=>  lo < next_up(t_hi): the next float up (t_hi may be slightly negative for a
    // ray that only touches the root; +-0 goes to the smallest denormal).
    const __m256i thb = _mm256_castps_si256(TH);
    const __m256i up = _mm256_add_epi32(thb, _mm256_blendv_epi8(_mm256_set1_epi32(-1), _mm256_set1_epi32(1),
                                                                 _mm256_castps_si256(_mm256_cmp_ps(TH, z, _CMP_GT_OQ))));
    const __m256 TL = _mm256_blendv_ps(
        z, _mm256_blendv_ps(_mm256_castsi256_ps(up), _mm256_castsi256_ps(_mm256_set1_epi32(1)), _mm256_cmp_ps(TH, z, _CMP_EQ_OQ)), lm);

    const uint32_t b = rk_svo_brick_levels(tree.depth);
    const uint32_t top = tree.depth - b;
    const uint32_t leaf = tree.max_level < tree.depth ? tree.max_level : tree.depth;

    Entry stack[8 * (RK_SVO_MAX_DEPTH + 2)];
    int sp = 0;
    stack[sp++] = Entry{1.0f, 1.0f, 1.0f, 0u, 0u, lanes};
    unsigned active = lanes;
    uint32_t brick = 0u, bmx = 0u, bmy = 0u;
    uint32_t iter = 0u;
    alignas(32) float lo_out[8];
    bool bounded = false;
    while (sp > 0) {
        const Entry e = stack[--sp];
        unsigned R = e.rays & active;
        if (R == 0u) continue;
        if (iter >= uint32_t(RK_SVO_TRAVERSE_MAX_ITER)) {
            bounded = true;
            break;
        }
        ++iter;
        // The node's child mask (format slots) and what the hit of a child needs.
        const uint32_t L = e.level;
        uint32_t m8, pdesc = 0u;
        if (L < top) {
            pdesc = words[e.handle];
            m8 = pdesc & RK_SVO_CHILD_MASK;
        } else if (L == top) {
            const uint32_t w = rk_svo_word_of(e.handle, tree.desc_words);
            bmx = words[w];
            bmy = words[w + 1u];
            brick = e.handle;
            m8 = b == 2u ? rk_svo_brick_submask(glm::uvec2(bmx, bmy)) : (bmx & 0xFFu);
        } else {
            m8 = ((e.handle < 4u ? bmx : bmy) >> (8u * (e.handle & 3u))) & 0xFFu;
        }
        const uint32_t mm = mirror_mask(m8, flip);
        // Plane distances of the node's exit (min corner), middle and entry (max corner) planes.
        const float size = uintBitsToFloat((127u - L) << 23u);  // 2^-L
        const float half = 0.5f * size;
        const __m256 Px = _mm256_set1_ps(e.px), Py = _mm256_set1_ps(e.py), Pz = _mm256_set1_ps(e.pz);
        const __m256 Xx0 = _mm256_sub_ps(_mm256_mul_ps(Px, Cx), Bx);
        const __m256 Xy0 = _mm256_sub_ps(_mm256_mul_ps(Py, Cy), By);
        const __m256 Xz0 = _mm256_sub_ps(_mm256_mul_ps(Pz, Cz), Bz);
        const __m256 Mx = _mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(e.px + half), Cx), Bx);
        const __m256 My = _mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(e.py + half), Cy), By);
        const __m256 Mz = _mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(e.pz + half), Cz), Bz);
        const __m256 Ex1 = _mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(e.px + size), Cx), Bx);
        const __m256 Ey1 = _mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(e.py + size), Cy), By);
        const __m256 Ez1 = _mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(e.pz + size), Cz), Bz);
        // Child slot k (mirrored; bit set = upper half): entry planes E_a = k_a ? entry : middle,
        // exit planes X_a = k_a ? middle : exit. lo = max(A[k & 3], B[k >> 2]), hi = min(C[k & 3], D[k >> 2]).
        __m256 A[4], Bk[2], C[4], D[2];
        A[0] = _mm256_max_ps(Mx, My);
        A[1] = _mm256_max_ps(Ex1, My);
        A[2] = _mm256_max_ps(Mx, Ey1);
        A[3] = _mm256_max_ps(Ex1, Ey1);
        Bk[0] = _mm256_max_ps(Mz, T0);
        Bk[1] = _mm256_max_ps(Ez1, T0);
        C[0] = _mm256_min_ps(Xx0, Xy0);
        C[1] = _mm256_min_ps(Mx, Xy0);
        C[2] = _mm256_min_ps(Xx0, My);
        C[3] = _mm256_min_ps(Mx, My);
        D[0] = _mm256_min_ps(Xz0, TL);
        D[1] = _mm256_min_ps(Mz, TL);
        const uint32_t Lc = L + 1u;
        if (Lc >= leaf) {
            // The children are answers: the first a ray reaches in front-to-back order is its hit
            // (chosen on the lanes, no branch per child; then one finish per ray that hit).
            const __m256i lane_bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
            __m256i left = svo_rays_detail::ne0(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(R)), lane_bit));
            __m256i hk = _mm256_setzero_si256();
            __m256 hlo = _mm256_setzero_ps();
            for (uint32_t rest = mm; rest != 0u;) {
                const int k = highest_bit(rest);
                rest &= ~(1u << k);
                const __m256 lo = _mm256_max_ps(A[k & 3], Bk[k >> 2]);
                const __m256 hi = close_end(_mm256_min_ps(C[k & 3], D[k >> 2]), TH, TL);
                const __m256i in = _mm256_and_si256(_mm256_castps_si256(_mm256_cmp_ps(lo, hi, _CMP_LT_OQ)), left);
                hk = _mm256_blendv_epi8(hk, _mm256_set1_epi32(k), in);
                hlo = _mm256_blendv_ps(hlo, lo, _mm256_castsi256_ps(in));
                left = _mm256_andnot_si256(in, left);
            }
            const unsigned hm = R & ~static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(left)));
            if (hm == 0u) continue;
            alignas(32) int32_t k_out[8];
            _mm256_store_si256(reinterpret_cast<__m256i*>(k_out), hk);
            _mm256_store_ps(lo_out, hlo);
            for (unsigned m = hm; m != 0u; m &= m - 1u) {
                const int i = svo_rays_detail::lowest_bit(m);
                const int k = k_out[i];
                rk_svo_trace_state_ s;
                s.u = glm::vec3(S.ux[i], S.uy[i], S.uz[i]);
                s.coef = glm::vec3(S.cx[i], S.cy[i], S.cz[i]);
                s.bias = glm::vec3(S.bx[i], S.by[i], S.bz[i]);
                s.flip = flip;
                s.t_enter = S.t_enter[i];
                s.t_scale = S.t_scale[i];
                s.b = b;
                s.top = top;
                s.leaf = leaf;
                s.pos = glm::vec3(e.px + half * float(k & 1), e.py + half * float((k >> 1) & 1), e.pz + half * float((k >> 2) & 1));
                s.size = half;
                s.scale = 23 - int(Lc);
                s.idx = uint32_t(k);
                s.t_min = lo_out[i];
                s.pdesc = pdesc;
                s.pmask = m8;
                s.handle = e.handle;
                s.bmask = glm::uvec2(bmx, bmy);
                s.brick = brick;
                rk_svo_trace_finish_(words, tree, s, true, iter, hits[i]);
            }
            active &= ~hm;
            continue;
        }
        // Inner children: pushed back to front (the first to visit on top).
        uint32_t first = 0u;
        if (L < top) {
            const uint32_t far_word = rk_svo_is_far(pdesc) ? words[e.handle + rk_svo_rel_ptr(pdesc)] : 0u;
            first = rk_svo_first_child(e.handle, pdesc, far_word);
        }
        for (uint32_t rest = mm; rest != 0u; rest &= rest - 1u) {
            const int k = svo_rays_detail::lowest_bit(rest);
            const __m256 lo = _mm256_max_ps(A[k & 3], Bk[k >> 2]);
            const __m256 hi = close_end(_mm256_min_ps(C[k & 3], D[k >> 2]), TH, TL);
            const unsigned cm = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(lo, hi, _CMP_LT_OQ))) & R;
            // Written whatever cm is, kept only when some ray reaches it (no branch per child).
            const uint32_t c = uint32_t(k) ^ flip;
            Entry& ch = stack[sp];
            ch.px = e.px + half * float(k & 1);
            ch.py = e.py + half * float((k >> 1) & 1);
            ch.pz = e.pz + half * float((k >> 2) & 1);
            ch.level = Lc;
            ch.handle = L < top ? first + rk_svo_child_rank(m8, c) : c;
            ch.rays = cm;
            sp += cm != 0u ? 1 : 0;
        }
    }
    for (unsigned m = active; m != 0u; m &= m - 1u) hits[svo_rays_detail::lowest_bit(m)].iterations = iter;
    return bounded ? active : 0u;
}
#endif

}  // namespace svo_packet_detail

/// svo_trace_packet8: hits[i] = the answer of rk_svo_trace(words, tree, rays[i].origin, rays[i].dir,
/// rays[i].t_max, no cone) for i < n (n <= 8), the rays traced as one packet (see the file
/// comment): hit, t, level, cell, normal, node and brick fields as rk_svo_trace (up to its
/// near-parallel clamp; ties in edges and corners as rk_svo_trace's); `iterations` counts the
/// packet's node expansions. Coherent rays (a 2x4 pixel tile) make it pay: the packet expands each
/// node once for all its rays. `words` as SvoTree::gpu_words().
inline void svo_trace_packet8(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, rk_svo_trace_hit* hits,
                              unsigned n = 8u)
{
    if (n > 8u) n = 8u;
#if RK_SVO_PACKET_SIMD
    if (n > 0u && tree.brick_base_word < 0x80000000u && tree.root_size > 0.0f && tree.depth >= 1u && tree.depth <= RK_SVO_MAX_DEPTH &&
        tree.max_level >= 1u && svo_packet_detail::packet_cpu_ok()) {
        svo_packet_detail::Setup S;
        svo_packet_detail::setup8(tree, rays, n, S);
        for (unsigned i = 0; i < n; ++i) hits[i] = rk_svo_trace_hit{false, 0.0f, 0u, glm::uvec3(0u), glm::vec3(0.0f), 0u, 0u, glm::uvec2(0u), 0u};
        unsigned pending = S.valid;
        while (pending != 0u) {
            const int32_t flip = S.flip[svo_rays_detail::lowest_bit(pending)];
            unsigned group = 0u;
            for (unsigned m = pending; m != 0u; m &= m - 1u) {
                const int i = svo_rays_detail::lowest_bit(m);
                if (S.flip[i] == flip) group |= 1u << i;
            }
            pending &= ~group;
            const unsigned left = svo_packet_detail::walk(words, tree, S, group, uint32_t(flip), hits);
            for (unsigned m = left; m != 0u; m &= m - 1u) {
                const int i = svo_rays_detail::lowest_bit(m);
                hits[i] = rk_svo_trace(words, tree, rays[i].origin, rays[i].dir, rays[i].t_max, glm::vec2(0.0f));
            }
        }
        return;
    }
#endif
    for (unsigned i = 0; i < n; ++i) hits[i] = rk_svo_trace(words, tree, rays[i].origin, rays[i].dir, rays[i].t_max, glm::vec2(0.0f));
}

/// svo_trace_packets: the rays of a row-major image block `width` rays wide (n = width * rows,
/// partial last row allowed), traced in packets of tile_w x tile_h pixels (tile_w * tile_h <= 8;
/// default 4 x 2; tiles at the right and bottom edges are partial). hits[i] answers rays[i].
inline void svo_trace_packets(const uint32_t* words, const rk_svo_tree& tree, const SvoRay* rays, std::size_t n, std::size_t width,
                              rk_svo_trace_hit* hits, unsigned tile_w = 4u, unsigned tile_h = 2u)
{
    if (width == 0u || tile_w == 0u || tile_h == 0u || tile_w * tile_h > 8u) {
        for (std::size_t i = 0; i < n; i += 8) svo_trace_packet8(words, tree, rays + i, hits + i, unsigned(n - i < 8 ? n - i : 8));
        return;
    }
    const std::size_t rows = (n + width - 1u) / width;
    SvoRay in[8];
    rk_svo_trace_hit out[8];
    std::size_t at[8];
    for (std::size_t y0 = 0; y0 < rows; y0 += tile_h)
        for (std::size_t x0 = 0; x0 < width; x0 += tile_w) {
            unsigned k = 0;
            for (std::size_t y = y0; y < y0 + tile_h && y < rows; ++y)
                for (std::size_t x = x0; x < x0 + tile_w && x < width; ++x) {
                    const std::size_t i = y * width + x;
                    if (i >= n) continue;
                    in[k] = rays[i];
                    at[k++] = i;
                }
            if (k == 0u) continue;
            svo_trace_packet8(words, tree, in, out, k);
            for (unsigned j = 0; j < k; ++j) hits[at[j]] = out[j];
        }
}

}  // namespace RK_SVO_RAYS_NS_CAT(RK_SVO_RAYS_SIMD)
}  // namespace RK_SVO_TRAVERSE_NS
}  // namespace raykit
