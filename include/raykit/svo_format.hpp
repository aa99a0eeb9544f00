// raykit — svo_format.hpp: the CPU build of shaders/raykit/svo_format.glsl, and the in-memory
// packed octree (SvoTree) that the builder (svo_build.hpp) fills, the file loader (svo_file.hpp)
// reads back and an application uploads to the GPU. The layout is documented in
// docs/svo-format.md.
//
// No exceptions: functions that can fail take an SvoStatus& (raykit::Status, status.hpp) and return
// false (or an empty result) with a message.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "raykit/color.hpp"
#include "raykit/common.hpp"
#include "raykit/status.hpp"

namespace raykit {
#include "raykit/svo_format.glsl"

/// The octree's names for raykit's error type (status.hpp): SvoStatus is a Status.
using SvoError = Error;
using SvoStatus = Status;
inline const char* svo_error_name(SvoError e) { return error_name(e); }

/// Per-material values carried by the material table of a tree (RK_SVO_ATTR_MATERIAL): what a
/// traversal needs for secondary rays. A voxel stores the index into this table.
struct SvoMaterial {
    glm::vec4 base_color{1.0f};   ///< linear RGBA factor (multiplies the base-colour texture)
    float reflectance = 0.0f;     ///< mirror reflection weight in [0, 1]
    float ior = 1.5f;             ///< refractive index (> 0)
    glm::vec3 absorption{0.0f};   ///< Beer–Lambert absorption coefficient per unit of object space
};

/// A packed sparse voxel octree (docs/svo-format.md). `words` (geometry) is what a traversal
/// reads; everything else is attributes. The root cube is [root_min, root_min + root_size]^3 in
/// the mesh's object space, split into 2^depth voxels per axis.
struct SvoTree {
    uint32_t depth = 0;           ///< levels below the root: voxels are root_size / 2^depth
    uint32_t brick_levels = 0;    ///< rk_svo_brick_levels(depth)
    glm::vec3 root_min{0.0f};
    float root_size = 0.0f;
    uint32_t attributes = 0;      ///< RK_SVO_ATTR_* bits: which attribute streams are present
    uint32_t pointer_bits = 23;   ///< near pointers the packer used (4..23); larger offsets went far
    uint32_t desc_words = 0;      ///< descriptor region: descriptors and far slots
    uint32_t far_slots = 0;       ///< how many of desc_words are far slots
    uint32_t brick_count = 0;     ///< bricks, at level depth - brick_levels
    uint64_t voxel_count = 0;     ///< occupied voxels at level depth
    std::vector<uint64_t> level_nodes;  ///< occupied nodes per level 0..depth
    std::vector<uint32_t> words;        ///< geometry: desc_words + 2 * brick_count words
    std::vector<uint32_t> brick_base;   ///< per brick: first attribute index of its inner levels
    uint64_t attr_count = 0;            ///< entries of each attribute stream
    std::vector<uint32_t> color;        ///< rk_svo_pack_color words (RK_SVO_ATTR_COLOR)
    std::vector<uint32_t> normal;       ///< rk_svo_pack_normal words (RK_SVO_ATTR_NORMAL)
    std::vector<uint32_t> material;     ///< rk_svo_material_id words (RK_SVO_ATTR_MATERIAL)
    std::vector<SvoMaterial> materials; ///< the material table (RK_SVO_ATTR_MATERIAL)

    /// Bytes a traversal reads (geometry words).
    uint64_t structure_bytes() const { return 4ull * words.size(); }
    /// Bytes of attributes: the streams, the brick bases and the material table.
    uint64_t attribute_bytes() const
    {
        return 4ull * (brick_base.size() + color.size() + normal.size() + material.size()) +
               sizeof(SvoMaterial) * materials.size();
    }
    /// One buffer for a shader: the geometry words, then brick_base (at word gpu_brick_base_word()),
    /// as rk_svo_lookup and svo_traverse.glsl expect. Attribute streams go to buffers of their own.
    std::vector<uint32_t> gpu_words() const
    {
        std::vector<uint32_t> g(words);
        g.insert(g.end(), brick_base.begin(), brick_base.end());
        return g;
    }
    uint32_t gpu_brick_base_word() const { return static_cast<uint32_t>(words.size()); }
};

/// svo_texture_extent: width and height of the R32UI 2D texture holding `words` words
/// (RK_SVO_BUFFER_TEXTURE=1 in svo_format.glsl): `width` (without it, this translation unit's
/// RK_SVO_TEXTURE_WIDTH, which the shader must agree with) by ceil(words / width); pad the words
/// with zeros to width * height.
inline glm::uvec2 svo_texture_extent(size_t words, uint32_t width)
{
    return glm::uvec2(width, static_cast<uint32_t>((words + width - 1) / width));
}
// The one-argument form reads the macro, so it lives in a namespace named after its value (as
// RK_CONFIGURED_BEGIN does for the shared functions).
RK_CONFIGURED_BEGIN(RK_PP_CAT(svo_texture_width, RK_SVO_TEXTURE_WIDTH))
inline glm::uvec2 svo_texture_extent(size_t words) { return raykit::svo_texture_extent(words, RK_SVO_TEXTURE_WIDTH); }
RK_CONFIGURED_END

/// svo_for_each_voxel: calls f(cell, attr) for every occupied voxel of a valid tree, in Morton
/// (breadth-first then brick-bit) order: cell = integer coordinates at tree.depth, attr = the
/// voxel's attribute index. The CPU reference for "unpack". Cost: O(nodes).
template <class F>
void svo_for_each_voxel(const SvoTree& t, F&& f)
{
    if (t.depth == 0 || t.words.empty()) return;
    const uint32_t b = t.brick_levels;
    const uint32_t top = t.depth - b;
    // Breadth-first over descriptor levels, carrying each node's ordinal and cell origin.
    struct Node { uint32_t ord; glm::uvec3 org; };
    std::vector<Node> cur{{0u, glm::uvec3(0u)}}, next;
    for (uint32_t level = 0; level < top; ++level) {
        next.clear();
        const uint32_t half = 1u << (t.depth - level - 1u);
        for (const Node& n : cur) {
            const uint32_t desc = t.words[n.ord];
            const uint32_t mask = rk_svo_child_mask(desc);
            const uint32_t far_word = rk_svo_is_far(desc) ? t.words[n.ord + rk_svo_rel_ptr(desc)] : 0u;
            const uint32_t first = rk_svo_first_child(n.ord, desc, far_word);
            for (uint32_t c = 0; c < 8; ++c) {
                if (!(mask & (1u << c))) continue;
                const glm::uvec3 o = n.org + glm::uvec3(c & 1u, (c >> 1) & 1u, (c >> 2) & 1u) * half;
                next.push_back({first + rk_svo_child_rank(mask, c), o});
            }
        }
        cur.swap(next);
    }
    for (const Node& n : cur) {
        const uint32_t w = rk_svo_word_of(n.ord, t.desc_words);
        const glm::uvec2 mask(t.words[w], t.words[w + 1]);
        const uint32_t base = t.brick_base[n.ord - t.desc_words];
        for (uint32_t bit = 0; bit < (b == 2u ? 64u : 8u); ++bit) {
            if (!rk_svo_brick_has(mask, bit)) continue;
            const uint32_t fine = bit & 7u, coarse = bit >> 3;
            glm::uvec3 cell = n.org + glm::uvec3(fine & 1u, (fine >> 1) & 1u, (fine >> 2) & 1u);
            if (b == 2u) cell += 2u * glm::uvec3(coarse & 1u, (coarse >> 1) & 1u, (coarse >> 2) & 1u);
            f(cell, static_cast<uint64_t>(rk_svo_brick_voxel_attr(base, mask, bit, b)));
        }
    }
}

}  // namespace raykit
