// A test-only octree packer, written from docs/svo-format.md independently of
// include/raykit/svo_build.hpp: voxel cells -> SvoTree, so the file and format tests have small
// hand-made trees (with far pointers forced by pointer_bits, empty trees, every attribute stream)
// whose contents they know. Simple and slow (sorting Morton keys, re-laying out until the far
// pointer choice is stable); meant for trees of at most a few thousand voxels.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "raykit/svo_format.hpp"

namespace svotest {

/// Morton key of a cell: bit 3i of the key is bit i of x, 3i+1 of y, 3i+2 of z.
inline uint64_t morton3(glm::uvec3 c)
{
    uint64_t k = 0;
    for (uint32_t i = 0; i < 21; ++i)
        k |= (uint64_t((c.x >> i) & 1u) << (3 * i)) | (uint64_t((c.y >> i) & 1u) << (3 * i + 1)) |
             (uint64_t((c.z >> i) & 1u) << (3 * i + 2));
    return k;
}

inline glm::uvec3 demorton3(uint64_t k)
{
    glm::uvec3 c(0u);
    for (uint32_t i = 0; i < 21; ++i) {
        c.x |= uint32_t((k >> (3 * i)) & 1u) << i;
        c.y |= uint32_t((k >> (3 * i + 1)) & 1u) << i;
        c.z |= uint32_t((k >> (3 * i + 2)) & 1u) << i;
    }
    return c;
}

inline uint32_t test_hash(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return uint32_t(x ^ (x >> 31));
}

struct PackOptions {
    uint32_t pointer_bits = 23;
    uint32_t attributes = 0;   ///< RK_SVO_ATTR_* streams, filled with hashes of the attribute index
    uint32_t materials = 1;    ///< material table size when RK_SVO_ATTR_MATERIAL
    glm::vec3 root_min{-1.0f, 0.5f, 2.0f};
    float root_size = 3.0f;
};

/// Packs the voxel cells (each < 2^depth per axis; duplicates allowed) into a tree of `depth`.
inline raykit::SvoTree pack_cells(uint32_t depth, const std::vector<glm::uvec3>& cells, const PackOptions& o = {})
{
    raykit::SvoTree t;
    const uint32_t b = depth < 2 ? depth : 2, top = depth - b;
    t.depth = depth;
    t.brick_levels = b;
    t.root_min = o.root_min;
    t.root_size = o.root_size;
    t.attributes = o.attributes;
    t.pointer_bits = o.pointer_bits;
    t.level_nodes.assign(depth + 1, 0);
    // Sorted unique keys per level: breadth-first order with children in ascending child index is
    // Morton order at each level.
    std::vector<std::vector<uint64_t>> keys(depth + 1);
    for (const glm::uvec3& c : cells) keys[depth].push_back(morton3(c));
    for (uint32_t l = depth + 1; l-- > 0;) {
        if (l < depth)
            for (uint64_t k : keys[l + 1]) keys[l].push_back(k >> 3);
        std::sort(keys[l].begin(), keys[l].end());
        keys[l].erase(std::unique(keys[l].begin(), keys[l].end()), keys[l].end());
        t.level_nodes[l] = keys[l].size();
    }
    const uint64_t bc = keys[top].size();
    if (cells.empty()) {
        // The empty tree: a zero root descriptor, or a zero root brick when the root is a brick.
        t.desc_words = top == 0 ? 0u : 1u;
        t.brick_count = top == 0 ? 1u : 0u;
        t.words.assign(t.desc_words + 2u * t.brick_count, 0u);
        t.brick_base.assign(t.brick_count, t.desc_words + t.brick_count);
        t.level_nodes[0] = 1;  // the root is stored (and counted) even when empty
    } else {
        // far[l][i]: descriptor i of level l uses a far slot. Lay out, find near offsets that do not
        // fit pointer_bits, make those far, repeat until stable (far only grows, so this ends).
        std::vector<std::vector<char>> far(top);
        for (uint32_t l = 0; l < top; ++l) far[l].assign(keys[l].size(), 0);
        std::vector<std::vector<uint64_t>> ord(top), slot(top);
        uint64_t D = 0;
        for (bool changed = true; changed;) {
            changed = false;
            uint64_t next = 0;
            for (uint32_t l = 0; l < top; ++l) {
                ord[l].assign(keys[l].size(), 0);
                slot[l].assign(keys[l].size(), 0);
                for (size_t i = 0; i < keys[l].size();) {
                    size_t e = i + 1;  // sibling group [i, e): same parent key
                    while (e < keys[l].size() && (keys[l][e] >> 3) == (keys[l][i] >> 3) && l > 0) ++e;
                    for (size_t j = i; j < e; ++j) ord[l][j] = next++;
                    for (size_t j = i; j < e; ++j)
                        if (far[l][j]) slot[l][j] = next++;
                    i = e;
                }
            }
            D = next;
            for (uint32_t l = 0; l < top; ++l) {
                size_t c = 0;  // first child index at level l + 1
                for (size_t i = 0; i < keys[l].size(); ++i) {
                    while (c < keys[l + 1].size() && (keys[l + 1][c] >> 3) < keys[l][i]) ++c;
                    const uint64_t first = l + 1 < top ? ord[l + 1][c] : D + c;
                    if (!far[l][i] && first - ord[l][i] >= (uint64_t(1) << o.pointer_bits)) {
                        far[l][i] = 1;
                        changed = true;
                    }
                }
            }
        }
        t.desc_words = uint32_t(D);
        t.brick_count = uint32_t(bc);
        t.words.assign(D + 2 * bc, 0u);
        for (uint32_t l = 0; l < top; ++l) {
            size_t c = 0;
            for (size_t i = 0; i < keys[l].size(); ++i) {
                while (c < keys[l + 1].size() && (keys[l + 1][c] >> 3) < keys[l][i]) ++c;
                uint32_t mask = 0;
                for (size_t k = c; k < keys[l + 1].size() && (keys[l + 1][k] >> 3) == keys[l][i]; ++k)
                    mask |= 1u << (keys[l + 1][k] & 7u);
                const uint64_t first = l + 1 < top ? ord[l + 1][c] : D + c;
                const uint64_t o_ = ord[l][i];
                if (far[l][i]) {
                    t.words[o_] = mask | RK_SVO_FAR_BIT | uint32_t((slot[l][i] - o_) << RK_SVO_PTR_SHIFT);
                    t.words[slot[l][i]] = uint32_t(first - o_);
                    ++t.far_slots;
                } else {
                    t.words[o_] = mask | uint32_t((first - o_) << RK_SVO_PTR_SHIFT);
                }
            }
        }
        // Bricks: bit = the voxel key's low 3b bits (Morton order inside the brick).
        uint64_t run = D + bc;
        size_t v = 0;
        for (size_t j = 0; j < bc; ++j) {
            uint64_t m = 0;
            for (; v < keys[depth].size() && (keys[depth][v] >> (3 * b)) == keys[top][j]; ++v)
                m |= uint64_t(1) << (keys[depth][v] & ((uint64_t(1) << (3 * b)) - 1u));
            t.words[D + 2 * j] = uint32_t(m);
            t.words[D + 2 * j + 1] = uint32_t(m >> 32);
            t.brick_base.push_back(uint32_t(run));
            uint64_t subs = 0;
            if (b == 2)
                for (uint32_t s = 0; s < 8; ++s) subs += ((m >> (8 * s)) & 0xFFu) ? 1u : 0u;
            run += subs + uint64_t(__builtin_popcountll(m));
        }
    }
    t.voxel_count = t.level_nodes[depth];
    t.attr_count = t.desc_words + uint64_t(t.brick_count);
    for (size_t j = 0; j < t.brick_count; ++j) {
        const uint64_t m = t.words[t.desc_words + 2 * j] | (uint64_t(t.words[t.desc_words + 2 * j + 1]) << 32);
        uint64_t subs = 0;
        if (b == 2)
            for (uint32_t s = 0; s < 8; ++s) subs += ((m >> (8 * s)) & 0xFFu) ? 1u : 0u;
        t.attr_count += subs + uint64_t(__builtin_popcountll(m));
    }
    // Far-slot ordinals carry zero attributes.
    std::vector<char> is_slot(t.desc_words, 0);
    // (A far slot follows its descriptor, so it is marked before the loop reaches it and skipped:
    // its word is an offset, not a descriptor.)
    for (uint32_t w = 0; w < t.desc_words; ++w)
        if (!is_slot[w] && raykit::rk_svo_is_far(t.words[w])) is_slot[w + raykit::rk_svo_rel_ptr(t.words[w])] = 1;
    auto stream = [&](uint32_t bit, uint32_t salt, std::vector<uint32_t>& s) {
        if (!(o.attributes & bit)) return;
        s.resize(t.attr_count);
        for (uint64_t i = 0; i < t.attr_count; ++i) {
            const uint32_t h = test_hash(i * 7 + salt);
            s[i] = i < t.desc_words && is_slot[i] ? 0u : bit == RK_SVO_ATTR_MATERIAL ? h % o.materials : h;
        }
    };
    stream(RK_SVO_ATTR_COLOR, 1, t.color);
    stream(RK_SVO_ATTR_NORMAL, 2, t.normal);
    stream(RK_SVO_ATTR_MATERIAL, 3, t.material);
    if (o.attributes & RK_SVO_ATTR_MATERIAL)
        for (uint32_t i = 0; i < o.materials; ++i) {
            raykit::SvoMaterial m;
            m.base_color = glm::vec4(0.1f * float(i), 0.5f, 1.0f - 0.05f * float(i), 0.75f);
            m.reflectance = 0.125f * float(i % 8);
            m.ior = 1.0f + 0.25f * float(i);
            m.absorption = glm::vec3(0.0f, -0.0f, 3.5f * float(i));
            t.materials.push_back(m);
        }
    return t;
}

/// `count` distinct random cells of a 2^depth grid (all cells when count exceeds them).
inline std::vector<glm::uvec3> random_cells(uint32_t depth, size_t count, uint64_t seed)
{
    const uint64_t side = uint64_t(1) << depth, total = side * side * side;
    std::vector<glm::uvec3> cells;
    if (count >= total) {
        for (uint64_t k = 0; k < total; ++k) cells.push_back(demorton3(k));
        return cells;
    }
    std::vector<uint64_t> keys;
    for (uint64_t i = 0; keys.size() < count; ++i) {
        keys.push_back(test_hash(seed * 1000003u + i) % total);
        if (keys.size() == count) {
            std::sort(keys.begin(), keys.end());
            keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
        }
    }
    for (uint64_t k : keys) cells.push_back(demorton3(k));
    return cells;
}

}  // namespace svotest
