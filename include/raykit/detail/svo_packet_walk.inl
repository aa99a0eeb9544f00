// raykit — detail/svo_packet_walk.inl: the walk of one packet of svo_trace_packet.hpp, one text
// for every lane width. svo_trace_packet.hpp includes it once per width, with
//   RK_SVO_PW_NAME    the function's name,
//   RK_SVO_PW_TARGET  its target attribute (the lanes' instruction set),
//   RK_SVO_PW_LANES   the lane traits (Lanes8: AVX2, Lanes16: AVX-512, and pairs of them:
//                     Lanes8x2, Lanes32; see svo_trace_packet.hpp),
//   RK_SVO_PW_SETUP   the set-up type (SetupLanes<N> for N lanes),
//   RK_SVO_PW_EXPAND  the name of its node expansion (a function template on the lane traits),
//   RK_SVO_PW_HALVES  (lane pairs only, svo_packet_pair.inl) expand a node whose rays lie in one
//                     half on that half's lanes,
// defined, and undefines them after. Not a header of its own: no include guard on purpose.

// The expansion of node `e` for its rays R (ray bits; more than one ray, or children at the leaf
// level) on the lanes of LL, which hold rays sh .. sh + LL::N - 1 (sh > 0: the upper half of a
// lane pair whose rays at this node all lie there; P: the packet's planes on those lanes).
// Answers the rays that hit among its children; pushes the inner children each ray enters, back
// to front.
template <class LL>
RK_SVO_PW_TARGET RK_SVO_RAYS_FORCE_INLINE void RK_SVO_PW_EXPAND(const uint32_t* words, const rk_svo_tree& tree, const RK_SVO_PW_SETUP& S,
                                                                const NodePlanes<LL>& P, int sh, const Entry& e, unsigned R, uint32_t mm,
                                                                uint32_t m8, uint32_t first, uint32_t pdesc, const WalkCtx& w,
                                                                uint32_t flip, uint32_t iter, rk_svo_trace_hit* const* hits,
                                                                Entry* stack, int& sp, unsigned& active, int32_t* k_out, float* lo_out,
                                                                float* nx, float* ny, float* nz)
{
    RK_SVO_PACKET_NO_CONTRACT
    using V = typename LL::V;
    using M = typename LL::M;
    using I = typename LL::I;
    const float size = uintBitsToFloat((127u - e.level) << 23u);  // 2^-level
    const float half = 0.5f * size;
    R >>= sh;  // lane bits from here on
    const V Xx0 = LL::sub(LL::mul(LL::set1(e.px), P.Cx), P.Bx);
    const V Xy0 = LL::sub(LL::mul(LL::set1(e.py), P.Cy), P.By);
    const V Xz0 = LL::sub(LL::mul(LL::set1(e.pz), P.Cz), P.Bz);
    const V Mx = LL::sub(LL::mul(LL::set1(e.px + half), P.Cx), P.Bx);
    const V My = LL::sub(LL::mul(LL::set1(e.py + half), P.Cy), P.By);
    const V Mz = LL::sub(LL::mul(LL::set1(e.pz + half), P.Cz), P.Bz);
    const V Ex1 = LL::sub(LL::mul(LL::set1(e.px + size), P.Cx), P.Bx);
    const V Ey1 = LL::sub(LL::mul(LL::set1(e.py + size), P.Cy), P.By);
    const V Ez1 = LL::sub(LL::mul(LL::set1(e.pz + size), P.Cz), P.Bz);
    // Child slot k (mirrored; bit set = upper half): entry planes E_a = k_a ? entry : middle,
    // exit planes X_a = k_a ? middle : exit. lo = max(A[k & 3], B[k >> 2]), hi = min(C[k & 3], D[k >> 2]).
    V A[4], Bk[2], C[4], D[2];
    A[0] = LL::max(Mx, My);
    A[1] = LL::max(Ex1, My);
    A[2] = LL::max(Mx, Ey1);
    A[3] = LL::max(Ex1, Ey1);
    Bk[0] = LL::max(Mz, P.T0);
    Bk[1] = LL::max(Ez1, P.T0);
    C[0] = LL::min(Xx0, Xy0);
    C[1] = LL::min(Mx, Xy0);
    C[2] = LL::min(Xx0, My);
    C[3] = LL::min(Mx, My);
    D[0] = LL::min(Xz0, P.TL);
    D[1] = LL::min(Mz, P.TL);
    // Rays answered among the children: all of them at the leaf level; in a LOD build also those
    // whose footprint stops them at every child they enter (at the node's entry, where a child's
    // entry is at the earliest, it is already a child wide, and it only widens along the ray).
    unsigned now = e.level + 1u >= w.leaf ? R : 0u;
#if RK_SVO_TRAVERSE_LOD
    const V half_v = LL::set1(half);
    if (now == 0u) {
        const V entry = LL::max(LL::max(Ex1, Ey1), LL::max(Ez1, P.T0));
        now = LL::le_bits(half_v, LL::add(P.LB, LL::mul(P.LS, LL::add(P.TE, entry)))) & R;
    }
#endif
    if (now != 0u) {
        // The first child a ray reaches in front-to-back order is its hit (chosen on the lanes,
        // no branch per child; then one finish per ray that hit).
        M left = LL::mask_of(now);
        I hk = LL::zero_i();
        V hlo = LL::zero();
        for (uint32_t rest = mm; rest != 0u;) {
            const int k = highest_bit(rest);
            rest &= ~(1u << k);
            const V lo = LL::max(A[k & 3], Bk[k >> 2]);
            const V hi = LL::close_end(LL::min(C[k & 3], D[k >> 2]), P.TH, P.TL);
            const M in = LL::lt_and(lo, hi, left);
            hk = LL::blend_k(in, hk, k);
            hlo = LL::blend(in, hlo, lo);
            left = LL::and_not(in, left);
        }
        const unsigned hm = now & ~LL::bits(left);
        if (hm != 0u) {
            LL::store_i(k_out + sh, hk);
            LL::store(lo_out + sh, hlo);
            // The face normals on the lanes: a child's entry planes are the node's middle or
            // entry planes by the bits of its slot.
            LL::entry_normal(LL::pick(hk, 1, Mx, Ex1), LL::pick(hk, 2, My, Ey1), LL::pick(hk, 4, Mz, Ez1), LL::load(S.ux + sh),
                             LL::load(S.uy + sh), LL::load(S.uz + sh), nx + sh, ny + sh, nz + sh);
            finish_hits(words, tree, S, hm << sh, k_out, lo_out, e, flip, pdesc, m8, w, iter, hits, nx, ny, nz);
            active &= ~(hm << sh);
        }
        R &= ~now;
        if (R == 0u) return;
    }
    // Inner children: pushed back to front (the first to visit on top).
    for (uint32_t rest = mm; rest != 0u; rest &= rest - 1u) {
        const int k = svo_rays_detail::lowest_bit(rest);
        const V lo = LL::max(A[k & 3], Bk[k >> 2]);
        const V hi = LL::close_end(LL::min(C[k & 3], D[k >> 2]), P.TH, P.TL);
        const unsigned cm = LL::lt_bits(lo, hi) & R;
#if RK_SVO_TRAVERSE_LOD
        const unsigned stops = LL::le_bits(half_v, LL::add(P.LB, LL::mul(P.LS, LL::add(P.TE, lo)))) & cm;
#else
        const unsigned stops = 0u;
#endif
        push_child(stack, sp, e, k, flip, m8, first, w, cm << sh, stops << sh);
    }
}

// The walk of one packet: `lanes` are rays whose set-up came out of rk_svo_trace_begin_'s twin with
// one and the same `flip`. Answers *hits[i] for them; returns the lanes still unanswered when the node
// bound was reached (0 normally).
RK_SVO_PW_TARGET inline unsigned RK_SVO_PW_NAME(const uint32_t* words, const rk_svo_tree& tree, const RK_SVO_PW_SETUP& S,
                                                unsigned lanes, uint32_t flip, rk_svo_trace_hit* const* hits)
{
    RK_SVO_PACKET_NO_CONTRACT
    using L = RK_SVO_PW_LANES;
    using V = typename L::V;
    using M = typename L::M;
    // Lanes outside `lanes` get planes that no cell interval reaches (and their bits are masked).
    // A cell's interval [lo, hi) is closed at the ray's end (rk_svo_trace enters a cell at
    // t <= t_hi, its root exit or t limit): lo <= t_hi <=> lo < next_up(t_hi), the next float up
    // (t_hi may be slightly negative for a ray that only touches the root; +-0 goes to the smallest
    // normal float), and an exit at or beyond t_hi becomes next_up(t_hi) (L::close_end).
    const M lm = L::mask_of(lanes);
    const V m1 = L::set1(-1.0f), z = L::zero();
    const V Cx = L::blend(lm, m1, L::load(S.cx)), Cy = L::blend(lm, m1, L::load(S.cy)), Cz = L::blend(lm, m1, L::load(S.cz));
    const V Bx = L::blend(lm, z, L::load(S.bx)), By = L::blend(lm, z, L::load(S.by)), Bz = L::blend(lm, z, L::load(S.bz));
    const V T0 = L::blend(lm, L::set1(1.0f), L::load(S.t_min));
    const V TH = L::blend(lm, z, L::load(S.t_hi));
    const V TL = L::blend(lm, z, L::next_up(TH));
    alignas(64) float tl_lane[L::N];  // TL's lanes, for a ray alone (children8, L::brick_hit)
    L::store(tl_lane, TL);
    // The footprint lod_bias + lod_slope * (t_enter + t) at a cell entered at t (rk_svo_trace's stop;
    // read in LOD builds only).
    const V LB = L::set1(S.lod_bias), LS = L::set1(S.lod_slope), TE = L::load(S.t_enter);
    const NodePlanes<L> P{Cx, Cy, Cz, Bx, By, Bz, T0, TH, TL, LB, LS, TE};
#ifdef RK_SVO_PW_HALVES
    using HL = typename L::H;
    const NodePlanes<HL> P_lo{Cx.a, Cy.a, Cz.a, Bx.a, By.a, Bz.a, T0.a, TH.a, TL.a, LB.a, LS.a, TE.a};
    const NodePlanes<HL> P_hi{Cx.b, Cy.b, Cz.b, Bx.b, By.b, Bz.b, T0.b, TH.b, TL.b, LB.b, LS.b, TE.b};
#endif

    WalkCtx w = walk_ctx(tree);
    // A tree larger than a core's cache (1 MiB of geometry) gains from fetching a node ahead; a
    // smaller one only pays for it.
    const bool far_tree = tree.brick_base_word > (1u << 18u);
    Entry stack[8 * (RK_SVO_MAX_DEPTH + 2)];
    int sp = 0;
    Entry root = Entry();
    root.px = root.py = root.pz = 1.0f;
    root.rays = lanes;
    stack[sp++] = root;
    unsigned active = lanes;
    uint32_t iter = 0u;
    const uint32_t iter_bound = rk_svo_trace_iteration_bound(tree);  // node expansions before handing over
    alignas(64) float lo_out[L::N];
    alignas(64) int32_t k_out[L::N];
    alignas(64) float nx[L::N], ny[L::N], nz[L::N];  // hits' face normals (L::entry_normal)
    bool bounded = false;
    while (sp > 0) {
        const Entry e = stack[--sp];
        unsigned R = e.rays & active;
        if (R == 0u) continue;
        if (far_tree && sp > 0 && stack[sp - 1].level < w.top) {
            // The node after this one's subtree: its children are fetched now (its descriptor was
            // fetched with its siblings'), so that two nodes' misses overlap.
            const uint32_t nh = stack[sp - 1].handle;
            const uint32_t nd = words[nh];
            if (!rk_svo_is_far(nd)) prefetch_children(words, tree, nh + rk_svo_rel_ptr(nd), stack[sp - 1].level + 1u == w.top);
        }
#if RK_SVO_TRAVERSE_LOD
        if ((e.stops & R) != 0u) {
            // Rays whose footprint stopped them at this node when it was pushed: it is the first
            // non-empty node they reach that is not wider than their footprint, so their hit. lo as
            // the parent computed it (the same planes, the same order of max).
            const unsigned hm = e.stops & R;
            const float sz = uintBitsToFloat((127u - e.level) << 23u);
            const V ex = L::sub(L::mul(L::set1(e.px + sz), Cx), Bx), ey = L::sub(L::mul(L::set1(e.py + sz), Cy), By);
            const V ez = L::sub(L::mul(L::set1(e.pz + sz), Cz), Bz);
            L::store(lo_out, L::max(L::max(ex, ey), L::max(ez, T0)));
            L::entry_normal(ex, ey, ez, L::load(S.ux), L::load(S.uy), L::load(S.uz), nx, ny, nz);
            // The node's mirrored slot k is bit (23 - level) of its corner's coordinates (in [1, 2));
            // the parent's descriptor and child mask are read again (a brick's: the one in w).
            const uint32_t bit = 23u - e.level;
            const int k = int(((floatBitsToUint(e.px) >> bit) & 1u) | (((floatBitsToUint(e.py) >> bit) & 1u) << 1u) |
                              (((floatBitsToUint(e.pz) >> bit) & 1u) << 2u));
            for (int i = 0; i < L::N; ++i) k_out[i] = k;
            const Entry parent{(k & 1) ? e.px - sz : e.px, (k & 2) ? e.py - sz : e.py, (k & 4) ? e.pz - sz : e.pz, e.level - 1u,
                               e.phandle, 0u, 0u, 0u};
            uint32_t ppdesc;
            const uint32_t pm8 = node_mask(words, tree, parent, w, ppdesc);
            finish_hits(words, tree, S, hm, k_out, lo_out, parent, flip, ppdesc, pm8, w, iter, hits, nx, ny, nz);
            active &= ~hm;
            R &= ~hm;
            if (R == 0u) continue;
        }
#endif
        if (iter >= iter_bound) {
            bounded = true;
            break;
        }
        ++iter;
        // The node's child mask (format slots) and what the hit of a child needs.
        uint32_t pdesc;
        const uint32_t m8 = node_mask(words, tree, e, w, pdesc);
        // Above the bricks, the children's descriptors or brick masks are fetched now, while the
        // planes are computed (they are contiguous: one or two cache lines).
        const uint32_t first = first_child(words, e, pdesc, w);
        if (e.level < w.top) prefetch_children(words, tree, first, e.level + 1u == w.top);
#if !RK_SVO_TRAVERSE_LOD
        if constexpr (L::kBrickHit) {
            if (e.level == w.top && w.b == 2u && w.leaf == tree.depth && bitCount(R) <= 4) {
                // A brick reached by at most four rays: each ray's first voxel of the 64 at once
                // (L::brick_hit) instead of expanding the brick and its sub-nodes.
                for (unsigned rest = R; rest != 0u; rest &= rest - 1u) {
                    const int i = svo_rays_detail::lowest_bit(rest);
                    if (brick_ray<L>(words, tree, S, e, i, tl_lane[i], flip, w, iter, hits)) active &= ~(1u << i);
                }
                continue;
            }
        }
#endif
        const uint32_t mm = mirror_mask(m8, flip);
        // Plane distances of the node's exit (min corner), middle and entry (max corner) planes.
        const float size = uintBitsToFloat((127u - e.level) << 23u);  // 2^-level
        const float half = 0.5f * size;
        if ((R & (R - 1u)) == 0u && e.level + 1u < w.leaf) {
            // One ray in an inner node: the children it enters, all 8 at once on scalars' plane
            // distances (the walk's expressions and order of max and min).
            const int i = svo_rays_detail::lowest_bit(R);
            const float cx = S.cx[i], cy = S.cy[i], cz = S.cz[i], bx = S.bx[i], by = S.by[i], bz = S.bz[i];
            const float X0[3] = {e.px * cx - bx, e.py * cy - by, e.pz * cz - bz};
            const float Mi[3] = {(e.px + half) * cx - bx, (e.py + half) * cy - by, (e.pz + half) * cz - bz};
            const float E1[3] = {(e.px + size) * cx - bx, (e.py + size) * cy - by, (e.pz + size) * cz - bz};
            const float t0 = S.t_min[i], tl = tl_lane[i];
            float lo8[8];
            const uint32_t cm = mm & children8(X0, Mi, E1, t0, S.t_hi[i], tl, lo8);
#if !RK_SVO_TRAVERSE_LOD
            if constexpr (L::kBrickHit) {
                if (e.level + 1u == w.top && w.b == 2u && w.leaf == tree.depth) {
                    // Its children are bricks: each one it enters, front to back, resolved by
                    // brick_ray until one has its voxel; no pushes.
                    for (uint32_t rest = cm; rest != 0u;) {
                        const int k = highest_bit(rest);
                        rest &= ~(1u << k);
                        if (iter >= iter_bound) {
                            bounded = true;
                            break;
                        }
                        ++iter;
                        Entry br = Entry();
                        set_child(br, e, k, flip, m8, first, w, R);
                        uint32_t no_desc;
                        node_mask(words, tree, br, w, no_desc);  // the brick's masks
                        if (brick_ray<L>(words, tree, S, br, i, tl, flip, w, iter, hits)) {
                            active &= ~R;
                            break;
                        }
                    }
                    if (bounded) break;
                    continue;
                }
            }
#endif
            // Pushed back to front.
#if RK_SVO_TRAVERSE_LOD
            // The lanes' footprint tests, on this ray's scalars (the same operations).
            const float ea = E1[0] > E1[1] ? E1[0] : E1[1], eb = E1[2] > t0 ? E1[2] : t0;
            if (half <= S.lod_bias + S.lod_slope * (S.t_enter[i] + (ea > eb ? ea : eb))) {
                // A child wide at the node's entry: the first child it enters is its hit.
                if (cm != 0u) {
                    const int k = highest_bit(cm);
                    k_out[i] = k;
                    lo_out[i] = lo8[k];
                    finish_hits(words, tree, S, R, k_out, lo_out, e, flip, pdesc, m8, w, iter, hits);
                    active &= ~R;
                }
                continue;
            }
            for (uint32_t rest = cm; rest != 0u; rest &= rest - 1u) {
                const int k = svo_rays_detail::lowest_bit(rest);
                const bool stop = half <= S.lod_bias + S.lod_slope * (S.t_enter[i] + lo8[k]);
                push_child(stack, sp, e, k, flip, m8, first, w, R, stop ? R : 0u);
            }
#else
            for (uint32_t rest = cm; rest != 0u; rest &= rest - 1u)
                push_child(stack, sp, e, svo_rays_detail::lowest_bit(rest), flip, m8, first, w, R, 0u);
#endif
            continue;
        }
        // Several rays (or children at the leaf level): on the lanes, or on one half's lanes when
        // they all lie in it (RK_SVO_PW_HALVES).
#ifdef RK_SVO_PW_HALVES
        if ((R >> HL::N) == 0u) {
            RK_SVO_PW_EXPAND<HL>(words, tree, S, P_lo, 0, e, R, mm, m8, first, pdesc, w, flip, iter, hits, stack, sp, active, k_out, lo_out,
                                      nx, ny, nz);
            continue;
        }
        if ((R & L::kHalf) == 0u) {
            RK_SVO_PW_EXPAND<HL>(words, tree, S, P_hi, HL::N, e, R, mm, m8, first, pdesc, w, flip, iter, hits, stack, sp, active, k_out,
                                      lo_out, nx, ny, nz);
            continue;
        }
#endif
        RK_SVO_PW_EXPAND<L>(words, tree, S, P, 0, e, R, mm, m8, first, pdesc, w, flip, iter, hits, stack, sp, active, k_out, lo_out, nx, ny, nz);
    }
    return end_walk(active, iter, bounded, hits);
}

#undef RK_SVO_PW_NAME
#undef RK_SVO_PW_TARGET
#undef RK_SVO_PW_LANES
#undef RK_SVO_PW_SETUP
#undef RK_SVO_PW_EXPAND
#undef RK_SVO_PW_HALVES
