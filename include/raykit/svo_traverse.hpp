// raykit — svo_traverse.hpp: the CPU build of shaders/raykit/svo_traverse.glsl (octree ray casting)
// and the CPU-side helpers that fill its uniforms.
//
// Feature macros (RK_SVO_TRAVERSE_LOD, RK_SVO_TRAVERSE_MAX_ITER; documented in the .glsl) may differ
// between translation units: the functions are compiled into an inline namespace whose name spells
// the macro values, so each translation unit calls the build it configured (raykit::rk_svo_trace
// resolves to it) and the linker never merges two different builds under one name.
#pragma once

#include "raykit/svo_format.hpp"

// The .glsl's defaults, needed here to name the namespace before the text is included (the .glsl
// keeps its own #ifndef defaults for shaders; test_svo_traverse checks both agree).
#ifndef RK_SVO_TRAVERSE_LOD
#define RK_SVO_TRAVERSE_LOD 0
#endif
#ifndef RK_SVO_TRAVERSE_MAX_ITER
#define RK_SVO_TRAVERSE_MAX_ITER 0
#endif

#define RK_SVO_TRAVERSE_NS_CAT_(lod, it) svo_traverse_lod##lod##_iter##it
#define RK_SVO_TRAVERSE_NS_CAT(lod, it) RK_SVO_TRAVERSE_NS_CAT_(lod, it)
#define RK_SVO_TRAVERSE_NS RK_SVO_TRAVERSE_NS_CAT(RK_SVO_TRAVERSE_LOD, RK_SVO_TRAVERSE_MAX_ITER)

namespace raykit {
inline namespace RK_SVO_TRAVERSE_NS {
#include "raykit/svo_traverse.glsl"

/// svo_trace_tree: the rk_svo_tree uniforms of a packed tree, for buffers laid out as
/// SvoTree::gpu_words() (geometry words, then brick_base). `max_level` is clamped to the depth;
/// pass ~0u (the default) for full detail.
inline rk_svo_tree svo_trace_tree(const SvoTree& t, uint32_t max_level = ~0u)
{
    rk_svo_tree r;
    r.depth = t.depth;
    r.max_level = max_level < t.depth ? max_level : t.depth;
    r.desc_words = t.desc_words;
    r.brick_base_word = t.gpu_brick_base_word();
    r.root_min = t.root_min;
    r.root_size = t.root_size;
    return r;
}

/// The fields of rk_svo_tree for gpu_pack (raykit/gpu_layout.hpp): to upload it as a uniform block.
template <class V>
void rk_gpu_fields(V& v, const rk_svo_tree& s)
{
    v("depth", s.depth);
    v("max_level", s.max_level);
    v("desc_words", s.desc_words);
    v("brick_base_word", s.brick_base_word);
    v("root_min", s.root_min);
    v("root_size", s.root_size);
}
}  // namespace RK_SVO_TRAVERSE_NS
}  // namespace raykit
