// raykit — svo_format.glsl: the packed sparse-voxel-octree format (docs/svo-format.md), decoded.
//
// Shared GLSL/C++ source (include/raykit/svo_format.hpp is the C++ build). What a shader needs to
// walk the words that raykit's builder packs (include/raykit/svo_build.hpp): descriptor fields,
// child ordinals, the ordinal -> word mapping, brick bits, attribute indices and the attribute
// codecs, plus rk_svo_lookup, a point query from the root to a voxel. svo_traverse.glsl casts rays
// through the same functions.
//
// The format in one breath (little-endian uint words, one stream; attributes in other streams):
// levels 0 .. depth-b-1 hold descriptors (1 word: child mask, far bit, 23-bit relative pointer),
// level depth-b holds bricks (2 words: a 64-bit occupancy mask of the 4^3, or 2^3 when depth is 1,
// voxels below, in Morton order), b = min(2, depth). Nodes are numbered by ordinal in
// breadth-first order, children of a node consecutive in ascending child index
// c = x | y << 1 | z << 2; descriptors (and the far slots that follow their sibling group) occupy
// ordinal = word, bricks follow at word = 2 * ordinal - desc_words. Attribute streams are indexed
// by ordinal for descriptors and bricks, and by brick_base[brick] + rank for the levels inside a
// brick.
//
// Buffer access: functions that read words take an RK_SVO_BUF parameter. In C++ it is a
// `const uint*` to the words. In GLSL it is a dummy uint and words come from RK_SVO_LOAD(i). Unless
// the including shader defines RK_SVO_LOAD itself, this file declares the buffer (GLSL only):
//   RK_SVO_BUFFER_TEXTURE=0 (default): layout(std430, binding = RK_SVO_WORDS_BINDING) readonly
//       buffer RkSvoWords { uint rk_svo_words[]; };
//   RK_SVO_BUFFER_TEXTURE=1: layout(binding = RK_SVO_WORDS_BINDING) uniform highp usampler2D
//       rk_svo_words_tex; an R32UI texture RK_SVO_TEXTURE_WIDTH (default 4096) words wide, word i at
//       texel (i % width, i / width) (svo_texture_extent() in C++). For GLSL ES 3.0 / WebGL 2, which
//       have no buffer textures, and ES 3.1 drivers without fragment-stage SSBOs.
// RK_SVO_WORDS_BINDING defaults to 0.
//
// @rk-variants RK_SVO_BUFFER_TEXTURE=0 | RK_SVO_BUFFER_TEXTURE=1
// @rk-es 310
// @rk-es300 RK_SVO_BUFFER_TEXTURE=1
#ifndef RK_SVO_FORMAT_GLSL
#define RK_SVO_FORMAT_GLSL

#include "color.glsl"
#include "common.glsl"

#ifndef RK_SVO_BUFFER_TEXTURE
#define RK_SVO_BUFFER_TEXTURE 0
#endif
#if RK_SVO_BUFFER_TEXTURE < 0 || RK_SVO_BUFFER_TEXTURE > 1
#error "RK_SVO_BUFFER_TEXTURE must be 0 (SSBO) or 1 (R32UI texture)"
#endif
RK_OPTION_CHECK(rk_option_svo_buffer_texture, RK_SVO_BUFFER_TEXTURE);

// Format constants (docs/svo-format.md).
#define RK_SVO_VERSION 1u
#define RK_SVO_MAX_DEPTH 20u
#define RK_SVO_CHILD_MASK 0xFFu
#define RK_SVO_FAR_BIT 0x100u
#define RK_SVO_PTR_SHIFT 9u
#define RK_SVO_PTR_MAX 0x7FFFFFu
// Attribute-set bits (the file header's `attributes` field; one stream each).
#define RK_SVO_ATTR_COLOR 1u
#define RK_SVO_ATTR_NORMAL 2u
#define RK_SVO_ATTR_MATERIAL 4u
// Not a stream: the trees's level-(depth-1) nodes inside bricks store no attributes of their own (a
// lookup or trace stopping there gets its brick's, one level coarser), which saves about a quarter
// of every stream on surfaces. Every brick_base entry then carries RK_SVO_BRICK_SHARED_SUB.
#define RK_SVO_ATTR_SHARED_SUB 8u
// brick_base top bit: this brick's level-(depth-1) nodes share the brick's attributes.
#define RK_SVO_BRICK_SHARED_SUB 0x80000000u

#ifndef RK_SVO_WORDS_BINDING
#define RK_SVO_WORDS_BINDING 0
#endif
#if RK_SVO_WORDS_BINDING < 0 || RK_SVO_WORDS_BINDING > 95
#error "RK_SVO_WORDS_BINDING must be a binding in 0..95"
#endif
RK_OPTION_CHECK(rk_option_svo_words_binding, RK_SVO_WORDS_BINDING);
#ifndef RK_SVO_TEXTURE_WIDTH
#define RK_SVO_TEXTURE_WIDTH 4096
#endif
#if RK_SVO_TEXTURE_WIDTH < 1 || RK_SVO_TEXTURE_WIDTH > 65536
#error "RK_SVO_TEXTURE_WIDTH must be in 1..65536 (texels per row)"
#endif
RK_OPTION_CHECK(rk_option_svo_texture_width, RK_SVO_TEXTURE_WIDTH);

#ifdef __cplusplus
#define RK_SVO_BUF const uint*
#define RK_SVO_READ(buf, i) (buf)[(i)]
#else
#define RK_SVO_BUF uint
#ifndef RK_SVO_LOAD
#if RK_SVO_BUFFER_TEXTURE
#if defined(GL_ES) && __VERSION__ < 310
// GLSL ES 3.00 / WebGL 2 have no binding qualifier: set the texture unit with glUniform1i.
uniform highp usampler2D rk_svo_words_tex;
#elif defined(GL_ES)
layout(binding = RK_SVO_WORDS_BINDING) uniform highp usampler2D rk_svo_words_tex;
#else
layout(binding = RK_SVO_WORDS_BINDING) uniform usampler2D rk_svo_words_tex;
#endif
#define RK_SVO_LOAD(i) texelFetch(rk_svo_words_tex, ivec2(int((i) % uint(RK_SVO_TEXTURE_WIDTH)), int((i) / uint(RK_SVO_TEXTURE_WIDTH))), 0).x
#else
layout(std430, binding = RK_SVO_WORDS_BINDING) readonly buffer RkSvoWords { uint rk_svo_words[]; };
#define RK_SVO_LOAD(i) rk_svo_words[(i)]
#endif
#endif
#define RK_SVO_READ(buf, i) RK_SVO_LOAD(i)
#endif

/// rk_svo_brick_levels: levels a brick spans, b = min(2, depth) (4^3 bricks; 2^3 at depth 1).
/// Domain: depth 1..RK_SVO_MAX_DEPTH. Exact. Cost: 1 min.
RK_INLINE uint rk_svo_brick_levels(uint depth) { return min(depth, 2u); }

/// rk_svo_child_mask / rk_svo_is_far / rk_svo_rel_ptr: the fields of a descriptor word.
/// Exact. Cost: 1 and/shift each.
RK_INLINE uint rk_svo_child_mask(uint desc) { return desc & RK_SVO_CHILD_MASK; }
RK_INLINE bool rk_svo_is_far(uint desc) { return (desc & RK_SVO_FAR_BIT) != 0u; }
RK_INLINE uint rk_svo_rel_ptr(uint desc) { return desc >> RK_SVO_PTR_SHIFT; }

/// rk_svo_child_rank: how many of the children present in `mask` come before child c (c in 0..7).
/// Exact. Cost: 1 shift, 1 and, 1 bitCount.
RK_INLINE uint rk_svo_child_rank(uint mask, uint c) { return uint(bitCount(mask & ((1u << c) - 1u))); }

/// rk_svo_first_child: ordinal of the first child of the descriptor at `ordinal`. For a far
/// descriptor the pointer field addresses a far slot, whose word `far_word` holds the 32-bit
/// relative offset; pass any value for a near one. Exact (uint wrap-around never occurs in a
/// validated tree). Cost: 1 select, 1 add.
RK_INLINE uint rk_svo_first_child(uint ordinal, uint desc, uint far_word)
{
    return ordinal + (rk_svo_is_far(desc) ? far_word : rk_svo_rel_ptr(desc));
}

/// rk_svo_word_of: word index of a node's first word. Descriptors and far slots: word = ordinal;
/// bricks (ordinal >= desc_words): 2 words each after the descriptor region. Exact whenever the
/// result is below 2^32 (the format's limit; uint wrap-around cancels). Cost: 1 compare, 1 mad.
RK_INLINE uint rk_svo_word_of(uint ordinal, uint desc_words)
{
    return ordinal < desc_words ? ordinal : 2u * ordinal - desc_words;
}

/// rk_svo_child_index: child index c = x | y << 1 | z << 2 of the octant of `cell` (integer voxel
/// coordinates at `depth`) below a node of level `level` (< depth). Exact. Cost: 3 shifts, 3 and.
RK_INLINE uint rk_svo_child_index(uvec3 cell, uint level, uint depth)
{
    uint s = depth - level - 1u;
    return ((cell.x >> s) & 1u) | (((cell.y >> s) & 1u) << 1u) | (((cell.z >> s) & 1u) << 2u);
}

/// rk_svo_brick_bit: bit (0..63) of a voxel in its brick's mask: Morton order, the voxel's child
/// index in its level-(depth-1) node in bits 0..2, that node's child index in the brick in bits
/// 3..5 (b = 2); the child index alone (b = 1). `cell` are voxel coordinates at `depth`.
/// Exact. Cost: ~12 integer ops.
RK_INLINE uint rk_svo_brick_bit(uvec3 cell, uint brick_levels)
{
    uint fine = (cell.x & 1u) | ((cell.y & 1u) << 1u) | ((cell.z & 1u) << 2u);
    uint coarse = ((cell.x >> 1u) & 1u) | (((cell.y >> 1u) & 1u) << 1u) | (((cell.z >> 1u) & 1u) << 2u);
    return brick_levels == 2u ? (fine | (coarse << 3u)) : fine;
}

/// rk_svo_brick_has: whether bit `bit` of the 64-bit brick mask (lo = bits 0..31) is set. Exact.
RK_INLINE bool rk_svo_brick_has(uvec2 mask, uint bit)
{
    uint w = bit < 32u ? mask.x : mask.y;
    return ((w >> (bit & 31u)) & 1u) != 0u;
}

/// rk_svo_brick_rank: set bits of the brick mask below `bit` (0..63). Exact. Cost: 2 bitCount.
RK_INLINE uint rk_svo_brick_rank(uvec2 mask, uint bit)
{
    uint below_lo = bit >= 32u ? mask.x : (mask.x & ((1u << (bit & 31u)) - 1u));
    uint below_hi = bit >= 32u ? (mask.y & ((1u << (bit & 31u)) - 1u)) : 0u;
    return uint(bitCount(below_lo)) + uint(bitCount(below_hi));
}

/// rk_svo_brick_nonzero_bytes_: internal. Bit k (0..3) set where byte k of w is non-zero: each
/// byte's bits are ORed into its lowest bit, and one multiply gathers those four bits into the top
/// byte (bit 8k lands on bit 24 + k; no other product term reaches bits 24..27, and none carries).
RK_INLINE uint rk_svo_brick_nonzero_bytes_(uint w)
{
    uint t = w | (w >> 4u);
    t = t | (t >> 2u);
    t = t | (t >> 1u);
    return (((t & 0x01010101u) * 0x01020408u) >> 24u) & 0xFu;
}

/// rk_svo_brick_submask: the 8-bit mask of a 4^3 brick's non-empty level-(depth-1) nodes (one per
/// mask byte). Exact. Cost: ~14 integer ops, no branch.
RK_INLINE uint rk_svo_brick_submask(uvec2 mask)
{
    return rk_svo_brick_nonzero_bytes_(mask.x) | (rk_svo_brick_nonzero_bytes_(mask.y) << 4u);
}

/// rk_svo_brick_voxel_count: voxels of a brick. Exact. Cost: 2 bitCount.
RK_INLINE uint rk_svo_brick_voxel_count(uvec2 mask) { return uint(bitCount(mask.x)) + uint(bitCount(mask.y)); }

/// rk_svo_brick_sub_attr: attribute index of level-(depth-1) node `sub` (0..7) of a 4^3 brick whose
/// brick_base entry is `base` and whose ordinal is `brick`. Sub-nodes come first, in ascending sub
/// index, then voxels; a brick with RK_SVO_BRICK_SHARED_SUB has no sub-node entries and returns
/// `brick` (its own attributes). Exact. Cost: rk_svo_brick_submask + 1 bitCount.
RK_INLINE uint rk_svo_brick_sub_attr(uint base, uvec2 mask, uint sub, uint brick)
{
    if ((base & RK_SVO_BRICK_SHARED_SUB) != 0u) return brick;
    return base + rk_svo_child_rank(rk_svo_brick_submask(mask), sub);
}

/// rk_svo_brick_voxel_attr: attribute index of the voxel at brick bit `bit`: after the brick's
/// sub-node attributes (none when brick_levels is 1 or the brick has RK_SVO_BRICK_SHARED_SUB), in
/// mask-bit order. Exact.
RK_INLINE uint rk_svo_brick_voxel_attr(uint base, uvec2 mask, uint bit, uint brick_levels)
{
    bool own_subs = brick_levels == 2u && (base & RK_SVO_BRICK_SHARED_SUB) == 0u;
    uint subs = own_subs ? uint(bitCount(rk_svo_brick_submask(mask))) : 0u;
    return (base & ~RK_SVO_BRICK_SHARED_SUB) + subs + rk_svo_brick_rank(mask, bit);
}

/// rk_svo_pack_unorm8: x in [0, 1] to 0..255: x * 255 + 0.5 in float32, truncated (round half up,
/// up to the float32 roundings: within 2^-24 relative of a half code the code can be one higher
/// than exact rounding, and a backend that fuses the multiply-add into one fma may differ there by
/// one); NaN -> 0. Cost: 1 clamp, 1 mad, 1 convert.
RK_INLINE uint rk_svo_pack_unorm8(float x)
{
    float c = x > 0.0f ? min(x, 1.0f) : 0.0f;
    return uint(c * 255.0f + 0.5f);
}

/// rk_svo_pack_color: linear RGBA -> one word, RGB sRGB-encoded, alpha linear, 8 bits each, R in
/// bits 0..7. NaN and out-of-range channels are clamped to [0, 1]. Max error of the round trip:
/// half an sRGB step per channel (rk_srgb_encode's error + 1/510). Cost: 3 sRGB encodes + 4 packs.
RK_INLINE uint rk_svo_pack_color(vec4 c)
{
    vec3 s = rk_srgb_encode(clamp(vec3(c.x > 0.0f ? c.x : 0.0f, c.y > 0.0f ? c.y : 0.0f, c.z > 0.0f ? c.z : 0.0f),
                                  vec3(0.0f), vec3(1.0f)));
    return rk_svo_pack_unorm8(s.x) | (rk_svo_pack_unorm8(s.y) << 8u) | (rk_svo_pack_unorm8(s.z) << 16u) |
           (rk_svo_pack_unorm8(c.w) << 24u);
}

/// rk_svo_unpack_color: one colour word -> linear RGBA (rk_srgb_decode of RGB). Max error vs a
/// float64 decode of the code: 1.9e-7 abs (measured over all codes, tests/test_svo_format.cpp).
/// Cost: 3 sRGB decodes.
RK_INLINE vec4 rk_svo_unpack_color(uint w)
{
    vec3 s = vec3(float(w & 0xFFu), float((w >> 8u) & 0xFFu), float((w >> 16u) & 0xFFu)) / 255.0f;
    return vec4(rk_srgb_decode(s), float(w >> 24u) / 255.0f);
}

/// rk_svo_pack_snorm16: x in [-1, 1] to a 16-bit two's-complement field: x * 32767 in float32,
/// rounded half away from zero by adding 0.5 in float32 (the same float32 caveats as
/// rk_svo_pack_unorm8); NaN -> 0. Cost: ~6 ops.
RK_INLINE uint rk_svo_pack_snorm16(float x)
{
    float c = clamp(x == x ? x : 0.0f, -1.0f, 1.0f) * 32767.0f;
    int i = c >= 0.0f ? int(c + 0.5f) : -int(0.5f - c);
    return uint(i) & 0xFFFFu;
}

/// rk_svo_unpack_snorm16: inverse of rk_svo_pack_snorm16 (−32768 decodes as −1). Exact.
RK_INLINE float rk_svo_unpack_snorm16(uint f)
{
    int i = int(f & 0xFFFFu) - ((f & 0x8000u) != 0u ? 65536 : 0);
    return max(float(i) / 32767.0f, -1.0f);
}

/// rk_svo_pack_normal: a direction -> one word, octahedral map with 16-bit snorm u (bits 0..15)
/// and v (bits 16..31). Any finite vector, normalised by its L1 norm (not unit length needed);
/// the zero vector and NaN encode +z. Max angular error of the round trip: 6.5e-5 rad (half a
/// snorm16 step on both u and v at an octant face centre: 3 sqrt(2) / (2 * 32767) = 6.47e-5; 6.41e-5
/// measured over 1.1e6 vectors in tests/test_svo_format.cpp). Cost: ~20 ops.
RK_INLINE uint rk_svo_pack_normal(vec3 n)
{
    vec3 a = abs(n);
    // Scale the largest component to 1 first so that the L1 norm neither overflows nor underflows.
    float m = max(a.x, max(a.y, a.z));
    if (!(m > 0.0f) || !(m <= RK_FLT_MAX)) return rk_svo_pack_snorm16(0.0f) | (rk_svo_pack_snorm16(0.0f) << 16u);
    // Above 2^100 scale by 2^-100 first (exact): GLSL's division is only specified for divisors up
    // to 2^126, and a GPU that divides by multiplying with a reciprocal flushes 1/m to 0 there
    // (NVIDIA: every normal with a component near FLT_MAX packed as +z).
    if (m > 1.2676506e30f) {
        n *= 7.8886091e-31f;
        m *= 7.8886091e-31f;
    }
    vec3 p = n / m;
    float s = abs(p.x) + abs(p.y) + abs(p.z);
    float u = p.x / s;
    float v = p.y / s;
    if (p.z < 0.0f) {
        vec2 f = rk_oct_fold(u, v);
        u = f.x;
        v = f.y;
    }
    return rk_svo_pack_snorm16(u) | (rk_svo_pack_snorm16(v) << 16u);
}

/// rk_svo_unpack_normal: one normal word -> unit vector (octahedral decode, then normalised).
/// Exact inverse of the map up to the quantisation (see rk_svo_pack_normal). Cost: ~20 ops +
/// inversesqrt.
RK_INLINE vec3 rk_svo_unpack_normal(uint w)
{
    float u = rk_svo_unpack_snorm16(w);
    float v = rk_svo_unpack_snorm16(w >> 16u);
    float z = 1.0f - abs(u) - abs(v);
    if (z < 0.0f) {
        vec2 f = rk_oct_fold(u, v);
        u = f.x;
        v = f.y;
    }
    vec3 d = vec3(u, v, z);
    return d * inversesqrt(max(dot(d, d), RK_FLT_MIN));
}

/// rk_svo_material_id: the material index of a material word (bits 0..15; bits 16..31 reserved, 0).
RK_INLINE uint rk_svo_material_id(uint w) { return w & 0xFFFFu; }

/// What rk_svo_lookup found: `level` is the deepest level reached (0 = root); `found` is true when
/// the query cell is occupied at that level. `ordinal` is that node's ordinal (for a voxel inside a
/// brick: the brick's), `attr` the attribute index of the node or voxel found.
struct rk_svo_hit {
    bool found;
    uint level;
    uint ordinal;
    uint attr;
};

/// rk_svo_lookup: descends from the root towards voxel `cell` (integer coordinates at `depth`,
/// each < 2^depth) and stops at level `max_level` (<= depth), or where the octree is empty.
/// `desc_words` is the header's descriptor-region size; `brick_base` is the start word of the
/// brick_base stream inside `buf` (the loader's buffers place it after the geometry words; pass
/// the offset you uploaded it at). Cells outside the grid report found = false at level 0.
/// Cost: one word per descriptor level, 2 words for the brick, 1 more for a far pointer or the
/// brick's attribute base; at most depth + 3 loads. Exact (integer only).
RK_INLINE rk_svo_hit rk_svo_lookup(RK_SVO_BUF buf, uint desc_words, uint brick_base_word, uint depth, uvec3 cell,
                                   uint max_level)
{
    rk_svo_hit h;
    h.found = false;
    h.level = 0u;
    h.ordinal = 0u;
    h.attr = 0u;
    uint b = rk_svo_brick_levels(depth);
    uint top = depth - b;  // level of the bricks
    uint lim = min(max_level, depth);
    uint side = 1u << depth;
    if (cell.x >= side || cell.y >= side || cell.z >= side) return h;
    uint ord = 0u;
    for (uint level = 0u; level < RK_SVO_MAX_DEPTH; ++level) {
        if (level >= top) break;
        uint desc = RK_SVO_READ(buf, ord);
        if (level == lim) {
            h.found = rk_svo_child_mask(desc) != 0u;
            h.level = level;
            h.ordinal = ord;
            h.attr = ord;
            return h;
        }
        uint c = rk_svo_child_index(cell, level, depth);
        uint mask = rk_svo_child_mask(desc);
        if ((mask & (1u << c)) == 0u) {
            h.level = level;
            h.ordinal = ord;
            h.attr = ord;
            return h;
        }
        uint far_word = rk_svo_is_far(desc) ? RK_SVO_READ(buf, ord + rk_svo_rel_ptr(desc)) : 0u;
        ord = rk_svo_first_child(ord, desc, far_word) + rk_svo_child_rank(mask, c);
    }
    // ord is a brick at level `top`.
    uint w = rk_svo_word_of(ord, desc_words);
    uvec2 mask = uvec2(RK_SVO_READ(buf, w), RK_SVO_READ(buf, w + 1u));
    h.ordinal = ord;
    h.attr = ord;
    h.level = top;
    if (lim == top) {
        h.found = (mask.x | mask.y) != 0u;
        return h;
    }
    uint bit = rk_svo_brick_bit(cell, b);
    uint base = RK_SVO_READ(buf, brick_base_word + (ord - desc_words));
    if (b == 2u && lim == top + 1u) {
        uint sub = bit >> 3u;
        h.level = top + 1u;
        h.found = ((rk_svo_brick_submask(mask) >> sub) & 1u) != 0u;
        if (h.found) h.attr = rk_svo_brick_sub_attr(base, mask, sub, ord);
        return h;
    }
    h.level = depth;
    h.found = rk_svo_brick_has(mask, bit);
    if (h.found) h.attr = rk_svo_brick_voxel_attr(base, mask, bit, b);
    return h;
}

#endif  // RK_SVO_FORMAT_GLSL
