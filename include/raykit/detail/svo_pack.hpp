// raykit — detail/svo_pack.hpp: the second half of svo_build.hpp (include that instead): packing
// Morton-sorted leaves into the format of docs/svo-format.md, and build_svo itself.
#pragma once

#include "raykit/svo_build.hpp"

namespace raykit {
namespace svo_detail {

/// Float attribute sums of a node: area-weighted colour and normal, the unweighted means for
/// nodes with no area below them (touch-only and interior voxels), the material of largest area.
struct Sum {
    float w = 0, n = 0;
    glm::vec4 col{0.0f}, ucol{0.0f};
    glm::vec3 nrm{0.0f}, unrm{0.0f};
    // Material histogram: the (up to) 4 heaviest materials below the node with their area (a leaf
    // with no area counts 1e-6). Exact majority by area with <= 4 materials in a subtree; beyond,
    // the lightest are dropped when merging.
    uint16_t mat[4] = {0, 0, 0, 0};
    float mw[4] = {-1.0f, -1.0f, -1.0f, -1.0f};
    uint16_t best_mat = 0;
    uint8_t best = 0;  // slot of best_mat: the first of the heaviest
    // The normal of the heaviest leaf below (the first of equals), for nodes whose normals cancel
    // (the two sides of a thin part), as a leaf takes the normal of its largest contribution.
    float heavy_w = -1.0f;
    glm::vec3 heavy_n{0.0f};

    void add_material(uint16_t m, float weight)
    {
        // Most leaves of a node share its heaviest material: it only grows, so it stays the first
        // of the heaviest.
        if (mw[best] >= 0.0f && mat[best] == m) {
            mw[best] += weight;
            return;
        }
        int slot = -1, lightest = 0;
        for (int i = 0; i < 4; ++i) {
            if (mw[i] >= 0.0f && mat[i] == m) slot = i;
            if (mw[i] < mw[lightest]) lightest = i;
        }
        if (slot >= 0) {
            mw[slot] += weight;
        } else if (weight > mw[lightest]) {
            mat[lightest] = m;
            mw[lightest] = weight;
        }
        int b = 0;
        for (int i = 1; i < 4; ++i)
            if (mw[i] > mw[b]) b = i;
        best = static_cast<uint8_t>(b);
        best_mat = mat[b];
    }
    /// Adds leaf l whose colour and normal words decode to c and nn.
    void add_leaf(const Leaf& l, const glm::vec4& c, const glm::vec3& nn)
    {
        col += c * l.weight;
        ucol += c;
        nrm += nn * l.weight;
        unrm += nn;
        w += l.weight;
        n += 1.0f;
        if (l.weight > heavy_w) { heavy_w = l.weight; heavy_n = nn; }
        add_material(l.material, l.weight > 0.0f ? l.weight : 1e-6f);
    }
    void add(const Sum& s)
    {
        w += s.w; n += s.n; col += s.col; ucol += s.ucol; nrm += s.nrm; unrm += s.unrm;
        if (s.heavy_w > heavy_w) { heavy_w = s.heavy_w; heavy_n = s.heavy_n; }
        for (int i = 0; i < 4; ++i)
            if (s.mw[i] >= 0.0f) add_material(s.mat[i], s.mw[i]);
    }
    uint32_t color() const { return SrgbTables::get().pack(w > 0.0f ? col / w : ucol / std::max(n, 1.0f)); }
    uint32_t normal() const
    {
        const glm::vec3 sum = w > 0.0f ? nrm : unrm;
        const float scale = w > 0.0f ? w : n;  // |sum| <= scale: the same cancellation test as a leaf's
        return rk_svo_pack_normal(glm::length(sum) > 1e-3f * scale ? sum : heavy_n);
    }
};

/// Writes one node's attributes at index i of the present streams.
inline void put_attr(SvoTree& t, uint64_t i, const Sum& s)
{
    if (!t.color.empty()) t.color[i] = s.color();
    if (!t.normal.empty()) t.normal[i] = s.normal();
    if (!t.material.empty()) t.material[i] = s.best_mat;
}
inline void put_leaf_attr(SvoTree& t, uint64_t i, const Leaf& l)
{
    if (!t.color.empty()) t.color[i] = l.color;
    if (!t.normal.empty()) t.normal[i] = l.normal;
    if (!t.material.empty()) t.material[i] = l.material;
}

/// A run of Morton-sorted leaves holding whole bricks (a chunk's output, or all leaves).
struct LeafSpan {
    const Leaf* p;
    size_t n;
};

/// Packs Morton-sorted, unique leaves (keys at `depth`), given as consecutive spans that each hold
/// whole bricks, into `t`.
inline bool pack(const SvoBuildOptions& opt, const std::vector<LeafSpan>& spans, uint32_t depth, uint32_t attributes, uint32_t pointer_bits,
                 const std::vector<SvoMaterial>& materials, SvoTree& t, Memory& mem, SvoStatus& st)
{
    const uint32_t b = rk_svo_brick_levels(depth);
    const uint32_t top = depth - b;  // brick level
    t = SvoTree{};
    t.depth = depth;
    t.brick_levels = b;
    const bool shared = opt.shared_sub_attributes && b == 2u;
    t.attributes = attributes;
    t.pointer_bits = pointer_bits;
    t.level_nodes.assign(depth + 1u, 0u);
    size_t nleaves = 0;
    for (const LeafSpan& sp : spans) nleaves += sp.n;
    t.voxel_count = nleaves;
    // Structure, bottom-up: bricks (key, first leaf) then descriptor levels (key, mask, first child).
    // Bricks are the runs of leaves with one key >> bs, found in parallel over blocks of each span
    // (a block owns the bricks that start in it), each with its voxel mask.
    std::vector<uint64_t> brick_key;
    std::vector<const Leaf*> brick_leaf;  // the brick's first leaf
    std::vector<uint64_t> brick_mask;     // bit i: voxel i of the brick
    const uint32_t bs = 3u * b;
    {
        const size_t lblock = size_t(1) << 16;
        struct Task { const Leaf* p; size_t n, s, e; };  // span p[0..n), block [s, e)
        std::vector<Task> tasks;
        for (const LeafSpan& sp : spans)
            for (size_t s0 = 0; s0 < sp.n; s0 += lblock) tasks.push_back({sp.p, sp.n, s0, std::min(sp.n, s0 + lblock)});
        struct Run { std::vector<uint64_t> key, mask; std::vector<const Leaf*> leaf; };
        std::vector<Run> runs(tasks.size());
        parallel_for(opt, tasks.size(), [&](size_t k) {
            const Task& T = tasks[k];
            const Leaf* L = T.p;
            size_t i = T.s;
            while (i < T.e && i > 0 && (L[i].key >> bs) == (L[i - 1].key >> bs)) ++i;  // an earlier block's brick
            Run& R = runs[k];
            while (i < T.e) {
                const uint64_t bk = L[i].key >> bs;
                const size_t first = i;
                uint64_t m = 0;
                for (; i < T.n && (L[i].key >> bs) == bk; ++i) m |= uint64_t(1) << (L[i].key & ((uint64_t(1) << bs) - 1));
                R.key.push_back(bk);
                R.leaf.push_back(L + first);
                R.mask.push_back(m);
            }
        });
        size_t total = 0;
        for (const Run& R : runs) total += R.key.size();
        brick_key.reserve(total);
        brick_leaf.reserve(total);
        brick_mask.reserve(total);
        for (Run& R : runs) {
            brick_key.insert(brick_key.end(), R.key.begin(), R.key.end());
            brick_leaf.insert(brick_leaf.end(), R.leaf.begin(), R.leaf.end());
            brick_mask.insert(brick_mask.end(), R.mask.begin(), R.mask.end());
            R = Run{};
        }
    }
    const uint64_t nb = brick_key.size();
    if (nb >= (1ull << 31)) return st.fail(SvoError::too_large, "more than 2^31 bricks");
    struct Level {
        std::vector<uint64_t> key;
        std::vector<uint8_t> mask;
        std::vector<uint32_t> first;  // index of the first child in the level below
    };
    std::vector<Level> lv(top);
    {
        const std::vector<uint64_t>* child = &brick_key;
        for (uint32_t L = top; L-- > 0;) {
            Level& P = lv[L];
            for (size_t i = 0; i < child->size(); ++i) {
                const uint64_t k = (*child)[i] >> 3;
                if (P.key.empty() || P.key.back() != k) {
                    P.key.push_back(k);
                    P.mask.push_back(0);
                    P.first.push_back(static_cast<uint32_t>(i));
                }
                P.mask.back() = static_cast<uint8_t>(P.mask.back() | (1u << ((*child)[i] & 7u)));
            }
            child = &P.key;
        }
    }
    // An empty tree (no leaf) is a root with an empty mask: a descriptor, or a brick when depth <= 2.
    if (nleaves == 0) {
        t.level_nodes[0] = 1;
        if (top > 0) {
            t.words.assign(1, 0u);
            t.desc_words = 1;
        } else {
            t.words.assign(2, 0u);
            t.brick_count = 1;
            t.brick_base.assign(1, 1u);
        }
        t.attr_count = t.desc_words + t.brick_count;
        if (attributes & RK_SVO_ATTR_COLOR) t.color.assign(t.attr_count, 0u);
        if (attributes & RK_SVO_ATTR_NORMAL) t.normal.assign(t.attr_count, 0u);
        if (attributes & RK_SVO_ATTR_MATERIAL) { t.material.assign(t.attr_count, 0u); t.materials = materials; }
        return true;
    }
    // Ordinal layout with far slots (fixpoint: a far slot shifts later nodes, which may make more
    // pointers far; far flags only ever turn on, so it converges).
    const uint32_t maxrel = (1u << pointer_bits) - 1u;
    std::vector<std::vector<uint32_t>> pos(top), slot(top);
    std::vector<std::vector<uint8_t>> far(top);
    for (uint32_t L = 0; L < top; ++L) {
        far[L].assign(lv[L].key.size(), 0);
        pos[L].assign(lv[L].key.size(), 0);
        slot[L].assign(lv[L].key.size(), 0);
    }
    uint64_t desc_words = 0;
    {
        for (int iter = 0;; ++iter) {
            if (iter > 64) return st.fail(SvoError::too_large, "far-pointer layout did not converge");
            uint64_t cur = 0;
            for (uint32_t L = 0; L < top; ++L) {
                const size_t n = lv[L].key.size();
                // Sibling groups: children of consecutive level-(L-1) parents; the root alone at L = 0.
                size_t g = 0;
                while (g < n) {
                    size_t e = n;
                    if (L > 0) {
                        // The parent of node g is the level-(L-1) node whose key is key >> 3.
                        const uint64_t pk = lv[L].key[g] >> 3;
                        e = g;
                        while (e < n && (lv[L].key[e] >> 3) == pk) ++e;
                    }
                    for (size_t i = g; i < e; ++i) pos[L][i] = static_cast<uint32_t>(cur++);
                    for (size_t i = g; i < e; ++i)
                        if (far[L][i]) slot[L][i] = static_cast<uint32_t>(cur++);
                    if (cur >= (1ull << 31)) return st.fail(SvoError::too_large, "more than 2^31 descriptors");
                    g = e;
                }
            }
            desc_words = cur;
            // gpu_words() (geometry + brick_base) must be indexable by a uint.
            if (desc_words + 3 * nb > (1ull << 32)) return st.fail(SvoError::too_large, "more than 2^32 words of geometry and brick bases");
            bool changed = false;
            for (uint32_t L = 0; L < top; ++L)
                for (size_t i = 0; i < lv[L].key.size(); ++i) {
                    const uint64_t first = (L + 1 < top) ? pos[L + 1][lv[L].first[i]] : desc_words + lv[L].first[i];
                    if (!far[L][i] && first - pos[L][i] > maxrel) { far[L][i] = 1; changed = true; }
                }
            if (!changed) break;
        }
        t.desc_words = static_cast<uint32_t>(desc_words);
        t.brick_count = static_cast<uint32_t>(nb);
        t.words.assign(desc_words + 2 * nb, 0u);
        if (!mem.add(4ull * t.words.size(), st, "packing the structure")) return false;
        for (uint32_t L = 0; L < top; ++L) {
            t.level_nodes[L] = lv[L].key.size();
            for (size_t i = 0; i < lv[L].key.size(); ++i) {
                const uint64_t first = (L + 1 < top) ? pos[L + 1][lv[L].first[i]] : desc_words + lv[L].first[i];
                uint32_t w = lv[L].mask[i];
                if (far[L][i]) {
                    w |= RK_SVO_FAR_BIT | ((slot[L][i] - pos[L][i]) << RK_SVO_PTR_SHIFT);
                    t.words[slot[L][i]] = static_cast<uint32_t>(first - pos[L][i]);
                    ++t.far_slots;
                } else {
                    w |= static_cast<uint32_t>(first - pos[L][i]) << RK_SVO_PTR_SHIFT;
                }
                t.words[pos[L][i]] = w;
            }
        }
        t.level_nodes[top] = nb;
    }
    // Bricks: masks, brick bases; sub-node counts; attribute count.
    if (shared) t.attributes |= RK_SVO_ATTR_SHARED_SUB;
    const uint64_t attr_limit = 1ull << 31;  // the top bit of brick_base is the shared-sub flag
    uint64_t attr = desc_words + nb;
    {
        t.brick_base.resize(nb);
        for (uint64_t j = 0; j < nb; ++j) {
            const uint32_t lo = static_cast<uint32_t>(brick_mask[j]), hi = static_cast<uint32_t>(brick_mask[j] >> 32);
            t.words[desc_words + 2 * j] = lo;
            t.words[desc_words + 2 * j + 1] = hi;
            t.brick_base[j] = static_cast<uint32_t>(attr) | (shared ? RK_SVO_BRICK_SHARED_SUB : 0u);
            const uint32_t subs = b == 2 ? static_cast<uint32_t>(bitCount(rk_svo_brick_submask(glm::uvec2(lo, hi)))) : 0u;
            if (b == 2) t.level_nodes[top + 1] += subs;
            attr += (shared ? 0u : subs) + static_cast<uint32_t>(bitCount(lo) + bitCount(hi));  // its leaves
            if (attr > attr_limit) return st.fail(SvoError::too_large, "more than 2^31 attribute entries");
        }
        t.level_nodes[depth] = nleaves;
    }
    t.attr_count = attr;
    const uint32_t streams = static_cast<uint32_t>(bitCount(attributes & (RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL)));
    if (!mem.add(4ull * (streams * attr + nb), st, "packing the attributes")) return false;
    if (attributes & RK_SVO_ATTR_COLOR) t.color.assign(attr, 0u);
    if (attributes & RK_SVO_ATTR_NORMAL) t.normal.assign(attr, 0u);
    if (attributes & RK_SVO_ATTR_MATERIAL) { t.material.assign(attr, 0u); t.materials = materials; }
    // Attributes, bottom-up: voxels, sub-nodes and the brick itself (in parallel over blocks of
    // bricks), then each descriptor level.
    // The bricks' sums: raw storage each brick's task constructs its element in (a value-initialised
    // vector would construct all of them on this thread first).
    struct SumBuffer {
        Sum* p;
        explicit SumBuffer(size_t n) : p(static_cast<Sum*>(::operator new(std::max<size_t>(n, 1) * sizeof(Sum)))) {}
        ~SumBuffer() { ::operator delete(p); }
        SumBuffer(const SumBuffer&) = delete;
        SumBuffer& operator=(const SumBuffer&) = delete;
    };
    static_assert(std::is_trivially_destructible<Sum>::value, "SumBuffer does not destroy its elements");
    SumBuffer brick_sums(nb);
    const Sum* child = brick_sums.p;
    std::vector<Sum> parent, upper;
    const uint64_t block = 4096;
    parallel_for(opt, static_cast<size_t>((nb + block - 1) / block), [&](size_t blk) {
        const uint64_t j_end = std::min<uint64_t>(nb, (blk + 1) * block);
        const SrgbTables& srgb = SrgbTables::get();
        uint32_t last_code = 0;
        glm::vec3 last_normal(0.0f);
        bool have_last = false;
        for (uint64_t j = blk * block; j < j_end; ++j) {
            const glm::uvec2 m(t.words[desc_words + 2 * j], t.words[desc_words + 2 * j + 1]);
            const uint64_t base = t.brick_base[j] & ~RK_SVO_BRICK_SHARED_SUB;
            const uint32_t subs = b == 2 && !shared ? static_cast<uint32_t>(bitCount(rk_svo_brick_submask(m))) : 0u;
            // Sums of the brick's level-(depth-1) nodes (b = 2; each over up to 8 voxels) or of its
            // voxels (b = 1), then the brick.
            Sum brick;
            uint32_t np = 0;
            const Leaf* const bl = brick_leaf[j];
            const uint32_t bn = static_cast<uint32_t>(bitCount(m.x) + bitCount(m.y));  // the brick's leaves
            for (uint32_t i = 0; i < bn;) {
                const uint64_t part = b == 2 ? (bl[i].key >> 3) : bl[i].key;
                Sum p;
                for (; i < bn && (b == 2 ? (bl[i].key >> 3) : bl[i].key) == part; ++i) {
                    const Leaf& l = bl[i];
                    put_leaf_attr(t, base + subs + i, l);
                    if (l.normal != last_code || !have_last) {  // neighbours on one face share a normal word
                        last_code = l.normal;
                        last_normal = rk_svo_unpack_normal(l.normal);
                        have_last = true;
                    }
                    p.add_leaf(l, srgb.unpack(l.color), last_normal);
                }
                if (b == 2 && !shared) put_attr(t, base + np, p);
                ++np;
                brick.add(p);
            }
            put_attr(t, desc_words + j, brick);
            new (&brick_sums.p[j]) Sum(brick);
        }
    });
    for (uint32_t L = top; L-- > 0;) {
        parent.assign(lv[L].key.size(), Sum{});
        parallel_for(opt, (parent.size() + block - 1) / block, [&](size_t blk) {
            const size_t i_end = std::min<size_t>(parent.size(), (blk + 1) * block);
            for (size_t i = blk * block; i < i_end; ++i) {
                const uint32_t cnt = static_cast<uint32_t>(bitCount(static_cast<uint32_t>(lv[L].mask[i])));
                for (uint32_t c = 0; c < cnt; ++c) parent[i].add(child[lv[L].first[i] + c]);
                put_attr(t, pos[L][i], parent[i]);
            }
        });
        upper.swap(parent);
        child = upper.data();
    }
    return true;
}

}  // namespace svo_detail

inline bool build_svo(const SvoMesh& mesh, const SvoBuildOptions& opt, SvoTree& out, SvoStatus& st, SvoBuildStats* stats_out)
{
    using namespace svo_detail;
    const Clock::time_point t0 = Clock::now();
    st = SvoStatus{};
    SvoBuildStats stats;
    Prepared P;
    if (!prepare(mesh, opt, P, stats, st, true)) {
        if (stats_out) *stats_out = stats;
        return false;
    }
    stats.estimated_peak_bytes = estimate(P, opt, mesh);
    if (opt.memory_budget && stats.estimated_peak_bytes > opt.memory_budget) {
        if (stats_out) *stats_out = stats;
        char msg[200];
        std::snprintf(msg, sizeof msg, "estimated peak memory %.1f MiB exceeds the budget of %.1f MiB at depth %u (try depth %u or a larger budget)",
                      static_cast<double>(stats.estimated_peak_bytes) / 1048576.0, static_cast<double>(opt.memory_budget) / 1048576.0, P.depth,
                      P.depth > 1 ? P.depth - 1 : 1u);
        return st.fail(SvoError::budget_exceeded, msg);
    }
    Memory mem;
    mem.budget = opt.memory_budget;
    std::mutex progress_mutex;
    std::atomic<bool> cancelled{false};
    float last_fraction = 0.0f;
    auto report = [&](float f, const char* stage) {
        if (!opt.progress) return true;
        std::lock_guard<std::mutex> lock(progress_mutex);
        if (cancelled) return false;
        f = std::max(f, last_fraction);  // workers may report out of order
        last_fraction = f;
        if (!opt.progress(f, stage)) cancelled = true;
        return !cancelled.load();
    };
    auto finish = [&](bool ok) {
        stats.peak_bytes = mem.peak;
        stats.seconds_total = seconds_since(t0);
        if (stats_out) *stats_out = stats;
        return ok;
    };
    if (!mem.add(P.tris.size() * sizeof(Tri), st, "snapping triangles")) return finish(false);
    // Textures used by some material, filtered once.
    P.textures.resize(mesh.texture_count);
    {
        std::vector<uint8_t> used(mesh.texture_count, 0);
        for (int tex : P.material_texture)
            if (tex >= 0) used[static_cast<size_t>(tex)] = 1;
        parallel_for(opt, mesh.texture_count, [&](size_t i) {
            if (used[i]) P.textures[i].prepare(mesh.textures[i]);
        });
        uint64_t tb = 0;
        for (const Texture& tx : P.textures) tb += tx.bytes();
        if (!mem.add(tb, st, "filtering textures")) return finish(false);
    }
    if (!report(0.0f, "binning")) return finish(st.fail(SvoError::cancelled, "cancelled"));
    // Bin triangles into chunks of 2^cs voxels per side (exact overlap at chunk size).
    const Clock::time_point tv0 = Clock::now();
    const uint32_t cs = std::min<uint32_t>(P.depth, 5u);
    const uint32_t chunk_level = P.depth - cs;
    const int64_t chunks_side = int64_t(1) << chunk_level;
    std::vector<std::vector<uint64_t>> bins(P.tris.size());
    std::atomic<uint64_t> nbinned{0};
    parallel_for(opt, P.tris.size(), [&](size_t t) {
        const int64_t lo[3] = {0, 0, 0}, hi[3] = {chunks_side - 1, chunks_side - 1, chunks_side - 1};
        std::vector<uint64_t>& out_bins = bins[t];
        for_each_overlap(P.tris[t].v, kSvoSubvoxelBits + cs, lo, hi, [&](const int64_t c[3]) {
            out_bins.push_back(morton(static_cast<uint32_t>(c[0]), static_cast<uint32_t>(c[1]), static_cast<uint32_t>(c[2])));
        });
        nbinned += out_bins.size();
    });
    std::vector<std::pair<uint64_t, uint32_t>> pairs;
    if (!mem.add(nbinned * (sizeof(pairs[0]) + 8), st, "binning triangles")) return finish(false);
    pairs.reserve(nbinned);
    for (size_t t = 0; t < bins.size(); ++t) {
        for (uint64_t k : bins[t]) pairs.emplace_back(k, static_cast<uint32_t>(t));
        std::vector<uint64_t>().swap(bins[t]);
    }
    std::sort(pairs.begin(), pairs.end());
    std::vector<size_t> chunk_start;
    for (size_t i = 0; i < pairs.size(); ++i)
        if (i == 0 || pairs[i].first != pairs[i - 1].first) chunk_start.push_back(i);
    chunk_start.push_back(pairs.size());
    const size_t nchunks = chunk_start.size() - 1;
    std::vector<uint32_t> tri_ids(pairs.size());
    for (size_t i = 0; i < pairs.size(); ++i) tri_ids[i] = pairs[i].second;
    // Voxelise the chunks in parallel, in batches (for the memory budget's checks). Each chunk's
    // leaves stay in their own vector: the chunks are in Morton order, so together they are the
    // sorted leaves, and the packer reads them in place (no copy into one array).
    std::vector<std::vector<Leaf>> chunk_leaves(nchunks);
    std::vector<std::unique_ptr<ChunkWork>> work_pool;
    size_t work_created = 0;
    std::mutex pool_mutex;
    std::atomic<size_t> done{0};
    std::atomic<bool> over_budget{false};
    const size_t batch = 8192;
    uint64_t nleaves = 0;
    for (size_t b0 = 0; b0 < nchunks && !cancelled && !over_budget; b0 += batch) {
        const size_t nb_chunks = std::min(batch, nchunks - b0);
        std::atomic<uint64_t> batch_leaves{0};
        parallel_for(opt, nb_chunks, [&](size_t ci) {
            if (cancelled || over_budget) return;
            const size_t c = b0 + ci;
            std::unique_ptr<ChunkWork> W;
            {
                std::lock_guard<std::mutex> lock(pool_mutex);
                if (!work_pool.empty()) { W = std::move(work_pool.back()); work_pool.pop_back(); }
                else ++work_created;
            }
            if (!W) W.reset(new ChunkWork);
            const uint64_t key = pairs[chunk_start[c]].first;
            uint32_t org[3] = {0, 0, 0};
            for (uint32_t l = 0; l < chunk_level; ++l)
                for (int a = 0; a < 3; ++a) org[a] |= static_cast<uint32_t>((key >> (3 * l + static_cast<uint32_t>(a))) & 1u) << l;
            for (int a = 0; a < 3; ++a) org[a] <<= cs;
            voxelize_chunk(P, tri_ids.data() + chunk_start[c], chunk_start[c + 1] - chunk_start[c], org, cs, *W, chunk_leaves[c]);
            const uint64_t tot = (batch_leaves += chunk_leaves[c].size());
            if (opt.memory_budget && mem.live + tot * sizeof(Leaf) > opt.memory_budget) over_budget = true;
            {
                std::lock_guard<std::mutex> lock(pool_mutex);
                work_pool.push_back(std::move(W));
            }
            const size_t d = ++done;
            if ((d & 63u) == 0 || d == nchunks) report(0.05f + 0.75f * static_cast<float>(d) / static_cast<float>(nchunks), "voxelizing");
        });
        const uint64_t pool_bytes = work_created * (uint64_t(1) << (3 * cs)) * sizeof(Accum);
        // Peak of this batch: the leaves so far (counted already), the batch's and the accumulators.
        nleaves += batch_leaves;
        if (!mem.add(pool_bytes + batch_leaves * sizeof(Leaf), st, "voxelizing")) return finish(false);
        mem.sub(pool_bytes);
    }
    work_pool.clear();
    if (cancelled) return finish(st.fail(SvoError::cancelled, "cancelled while voxelizing"));
    if (over_budget) return finish(st.fail(SvoError::budget_exceeded, "memory budget exceeded while voxelizing"));
    std::vector<std::pair<uint64_t, uint32_t>>().swap(pairs);
    std::vector<uint32_t>().swap(tri_ids);
    mem.sub(nbinned * (sizeof(std::pair<uint64_t, uint32_t>) + 8));
    stats.surface_voxels = nleaves;
    stats.seconds_voxelize = seconds_since(tv0);
    std::vector<LeafSpan> spans;
    std::vector<Leaf> leaves;  // solid fill: all leaves in one array
    if (opt.fill == SvoFill::solid) {
        const Clock::time_point tf0 = Clock::now();
        if (!report(0.8f, "filling")) return finish(st.fail(SvoError::cancelled, "cancelled"));
        if (!mem.add(nleaves * sizeof(Leaf), st, "collecting voxels")) return finish(false);
        leaves.reserve(nleaves);
        for (std::vector<Leaf>& v : chunk_leaves) {
            leaves.insert(leaves.end(), v.begin(), v.end());
            std::vector<Leaf>().swap(v);
        }
        mem.sub(nleaves * sizeof(Leaf));
        std::vector<Leaf> interior;
        if (!solid_fill(P, opt, leaves, interior, mem, st)) return finish(false);
        stats.interior_voxels = interior.size();
        if (!interior.empty()) {
            if (!mem.add(interior.size() * sizeof(Leaf) * 2, st, "merging the interior")) return finish(false);
            std::vector<Leaf> merged;
            merged.reserve(leaves.size() + interior.size());
            std::merge(leaves.begin(), leaves.end(), interior.begin(), interior.end(), std::back_inserter(merged),
                       [](const Leaf& a, const Leaf& b2) { return a.key < b2.key; });
            leaves.swap(merged);
        }
        spans.push_back({leaves.data(), leaves.size()});
        stats.seconds_fill = seconds_since(tf0);
    } else {
        for (const std::vector<Leaf>& v : chunk_leaves)
            if (!v.empty()) spans.push_back({v.data(), v.size()});
    }
    // Pack.
    const Clock::time_point tp0 = Clock::now();
    if (!report(0.9f, "packing")) return finish(st.fail(SvoError::cancelled, "cancelled"));
    if (!pack(opt, spans, P.depth, opt.attributes, opt.pointer_bits, P.materials, out, mem, st)) return finish(false);
    out.root_min = glm::vec3(P.root_min[0], P.root_min[1], P.root_min[2]);
    out.root_size = P.root_size;
    stats.seconds_pack = seconds_since(tp0);
    report(1.0f, "done");
    return finish(true);
}

}  // namespace raykit
