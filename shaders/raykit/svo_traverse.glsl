// raykit — svo_traverse.glsl: ray casting through a packed sparse voxel octree.
//
// Shared GLSL/C++ source (include/raykit/svo_traverse.hpp is the C++ build). rk_svo_trace casts one
// ray through the words of docs/svo-format.md and returns the first non-empty voxel it enters (or,
// with level of detail, the first node whose size falls below the ray's footprint).
//
// The method is the parametric, stack-based traversal of Laine and Karras ("Efficient Sparse Voxel
// Octrees"), which Wilks ("Real-time GPU Ray Tracing with Volumetric Effects") ports to CUDA:
// the root is mapped to [1, 2)^3, where every coordinate has the same float exponent and its
// mantissa is a fixed-point cell address; the ray is mirrored so that every direction component
// is negative (the exit corner of a cell is then its minimum corner); plane distances are one
// multiply-add each (t = x * coef - bias); the ray pops back up to the level given by the highest
// bit in which the old and new cell addresses differ (findMSB), so it restarts from the deepest
// common ancestor. Unlike Gritzner's thesis ("3D graphics rendering using a polygon-voxel-hybrid
// approach"), whose restart flipped one axis and could loop, every axis whose exit plane ties
// steps at once (rays through edges and corners), and the loop has a hard bound.
//
// Before traversal the ray is clipped to the root in cube space and its origin moved to the entry
// point, so cell distances are computed near 1 even for an origin far away. Direction components
// below 2^-21 (after normalising) are replaced by 2^-21 of the same sign (no division by zero; a
// ray lying in a cell's face plane belongs to the cells on the side of its direction's sign bit;
// -0 counts as negative).
//
// Features (compile time; the variants line below lists what validation compiles):
//   RK_SVO_TRAVERSE_LOD (default 0): 1 = stop at the first non-empty node whose edge is no larger than
//       the ray's footprint cone.x + cone.y * distance (object units; rk_svo_pixel_cone gives the
//       cone of a pixel). 0 = the cone is ignored and costs nothing.
//   RK_SVO_TRAVERSE_MAX_ITER (default 0, a plain integer): the hard bound on loop iterations (one
//       iteration is one push, advance or pop; rk_svo_trace_iteration_bound). 0 = derived from the
//       tree: 16 x 2^depth, more than any ray through a valid tree takes (it enters at most
//       3 x 2^L - 2 cells of each level L, each once, and pops at most once per node entered:
//       under 12 x 2^depth iterations), so no ray reaches it. A positive value is a fixed cap
//       instead (a latency budget): a ray that reaches it reports no hit with iterations equal to
//       it. Primary rays take ~13 on average at depth 10; the costliest rays slide just above a
//       flat surface: ~2 per leaf cell along an axis, ~4 along a diagonal (8,174 at depth 11,
//       ~131,000 along an axis at depth 16). The value must be a plain literal (it is pasted into
//       the C++ namespace name).
//
// @rk-variants RK_SVO_TRAVERSE_LOD=0 | RK_SVO_TRAVERSE_LOD=1 | RK_SVO_TRAVERSE_LOD=1 RK_SVO_BUFFER_TEXTURE=1 | RK_SVO_TRAVERSE_MAX_ITER=64 | RK_SVO_TRAVERSE_LOD=1 RK_SVO_TRAVERSE_MAX_ITER=4096
// @rk-es 310
// @rk-es300 RK_SVO_BUFFER_TEXTURE=1
#ifndef RK_SVO_TRAVERSE_GLSL
#define RK_SVO_TRAVERSE_GLSL

#include "common.glsl"
#include "svo_format.glsl"

#ifndef RK_SVO_TRAVERSE_LOD
#define RK_SVO_TRAVERSE_LOD 0
#endif
#if RK_SVO_TRAVERSE_LOD < 0 || RK_SVO_TRAVERSE_LOD > 1
#error "RK_SVO_TRAVERSE_LOD must be 0 (full detail) or 1 (level-of-detail stop)"
#endif
RK_OPTION_CHECK(rk_option_svo_traverse_lod, RK_SVO_TRAVERSE_LOD);
#ifndef RK_SVO_TRAVERSE_MAX_ITER
#define RK_SVO_TRAVERSE_MAX_ITER 0
#endif
#if RK_SVO_TRAVERSE_MAX_ITER < 0 || RK_SVO_TRAVERSE_MAX_ITER > 16777216
#error "RK_SVO_TRAVERSE_MAX_ITER must be 0 (derived from the tree's depth) or in 1..2^24"
#endif
RK_OPTION_CHECK(rk_option_svo_traverse_max_iter, RK_SVO_TRAVERSE_MAX_ITER);

// Stack entries: one per parent level 0 .. RK_SVO_MAX_DEPTH - 1.
#define RK_SVO_TRAVERSE_STACK 20
// Direction components are at least this large after normalisation (2^-21).
#define RK_SVO_TRAVERSE_DIR_EPS 4.76837158203125e-7f

/// The uniforms of one octree, as rk_svo_trace reads them (svo_trace_tree() fills it from an
/// SvoTree in C++). `max_level` (<= depth) is the deepest level the ray descends to: depth for
/// full detail, less to render a coarser tree from the same words.
struct rk_svo_tree {
    uint depth;
    uint max_level;
    uint desc_words;
    uint brick_base_word;
    vec3 root_min;
    float root_size;
};

/// What rk_svo_trace found.
///   hit: a non-empty node was entered within [0, t_max].
///   t: distance along the caller's ray (origin + t * dir, in units of dir) where it is entered; 0
///      when the origin is inside it. Accurate to a few float32 ULPs of the root size, plus the
///      origin's own rounding when it is far away (see rk_svo_trace).
///   level, cell: the node's level (depth, or less at a level-of-detail stop or max_level) and
///      integer coordinates at that level.
///   normal: unit axis vector of the face the ray entered through, facing the ray (through an edge
///      or a corner: the face crossed last, the steepest one on an exact tie); for an origin inside
///      the node, the face behind the origin.
///   node, brick_bit, brick_mask: where the node's attributes are (rk_svo_trace_attr): the ordinal
///      of the descriptor, or of the brick holding the node; inside a brick, the sub-node index
///      (level depth-1) or mask bit (level depth), and the brick's mask.
///   iterations: loop iterations used.
struct rk_svo_trace_hit {
    bool hit;
    float t;
    uint level;
    uvec3 cell;
    vec3 normal;
    uint node;
    uint brick_bit;
    uvec2 brick_mask;
    uint iterations;
};

/// rk_svo_pixel_cone: the footprint cone of a pixel for RK_SVO_TRAVERSE_LOD: a pinhole camera with
/// vertical field of view `fov_y` (radians) rendering `height` pixels sees a pixel that is
/// cone.x + cone.y * distance wide (cone.x = 0). `scale` > 1 stops earlier (coarser, faster).
/// Domain: fov_y in (0, pi), height >= 1. Cost: 1 tan, 1 div.
RK_INLINE vec2 rk_svo_pixel_cone(float fov_y, float height, float scale)
{
    return vec2(0.0f, scale * 2.0f * tan(0.5f * fov_y) / max(height, 1.0f));
}

/// rk_svo_trace_child_mask_: internal. The child mask of the current parent: its descriptor's mask
/// above the bricks, the brick's sub-node mask `bsub` (computed once per brick), or the byte of the
/// sub-node `handle` in the brick.
RK_INLINE uint rk_svo_trace_child_mask_(uint lp, uint top, uint pdesc, uvec2 bmask, uint bsub, uint handle)
{
    if (lp < top) return pdesc & RK_SVO_CHILD_MASK;
    if (lp == top) return bsub;
    uint w = handle < 4u ? bmask.x : bmask.y;
    return (w >> (8u * (handle & 3u))) & 0xFFu;
}

/// rk_svo_trace_entry_normal_: internal. The face normal of the entry plane that the ray crosses
/// last (largest te); on an exact tie (an edge or corner, or a ray lying in a face plane) the axis
/// the ray crosses most steeply (largest |u|), never one it runs parallel to.
RK_INLINE vec3 rk_svo_trace_entry_normal_(vec3 te, vec3 u)
{
    uint ax = (te.y > te.x || (te.y == te.x && abs(u.y) > abs(u.x))) ? 1u : 0u;
    float tb = ax == 0u ? te.x : te.y;
    float ub = ax == 0u ? abs(u.x) : abs(u.y);
    if (te.z > tb || (te.z == tb && abs(u.z) > ub)) ax = 2u;
    return vec3(ax == 0u ? -sign(u.x) : 0.0f, ax == 1u ? -sign(u.y) : 0.0f, ax == 2u ? -sign(u.z) : 0.0f);
}

/// rk_svo_trace_state_: internal. What rk_svo_trace carries from its set-up through its loop to its
/// hit: the ray in mirrored cube space and the traversal's current cell and parent. Shared with the
/// C++ twin svo_trace_rays (include/raykit/svo_trace_simd.hpp), which runs the loop on SIMD lanes
/// between the same set-up and finish.
struct rk_svo_trace_state_ {
    vec3 u;         // unit direction, tiny components replaced (for the entry normal)
    vec3 coef;      // plane distance t = x * coef - bias on each mirrored axis
    vec3 bias;
    uint flip;      // bit a set: axis a mirrored (x -> 3 - x)
    float t_enter;  // cube-space distance from the caller's origin to the root entry
    float t_scale;  // caller distance per cube-space distance
    float t_min;    // the ray's current position (cube space, from the entry point)
    float t_hi;     // where it leaves the current parent (or t_max)
    float t_end;    // where it leaves the root, or t_max: nothing beyond can be hit
    uint top;       // levels above the bricks
    uint leaf;      // deepest level descended to
    uint b;         // brick levels
#if RK_SVO_TRAVERSE_LOD
    float lod_bias;  // footprint in cube units: lod_bias + lod_slope * (t_enter + t_min)
    float lod_slope;
#endif
    uint handle;    // the parent: descriptor ordinal, or sub-node index inside a brick
    uint pdesc;     // the parent's descriptor (above the bricks)
    uvec2 bmask;    // the current brick's mask words
    uint bsub;      // the current brick's level-(depth-1) mask
    uint brick;     // the current brick's ordinal
    uint pmask;     // the parent's child mask
    int scale;      // 23 - level of the current cell
    float size;     // its edge, 2^(scale - 23)
    vec3 pos;       // its minimum corner (mirrored)
    uint idx;       // its child slot (mirrored; the format's index is idx ^ flip)
};

/// rk_svo_trace_begin_: internal. rk_svo_trace's set-up: clips the ray to the root and fills `s`
/// for the loop (true), or writes the final answer to `h` (false: a miss, or a stop at the root).
RK_INLINE bool rk_svo_trace_begin_(RK_SVO_BUF buf, rk_svo_tree tree, vec3 origin, vec3 dir, float t_max, vec2 cone,
                                   RK_INOUT(rk_svo_trace_hit) h, RK_INOUT(rk_svo_trace_state_) s)
{
    h.hit = false;
    h.t = 0.0f;
    h.level = 0u;
    h.cell = uvec3(0u);
    h.normal = vec3(0.0f);
    h.node = 0u;
    h.brick_bit = 0u;
    h.brick_mask = uvec2(0u);
    h.iterations = 0u;

    // Normalise the direction (scaled first so that no component overflows or underflows).
    float m = max(max(abs(dir.x), abs(dir.y)), abs(dir.z));
    if (!(m >= RK_FLT_MIN) || !(t_max >= 0.0f) || !(tree.root_size > 0.0f) || tree.depth == 0u ||
        tree.depth > RK_SVO_MAX_DEPTH)
        return false;
    vec3 dn = dir / m;
    float len = length(dn);  // in [1, sqrt(3)]
    vec3 u = dn / len;
    // t (caller) = t_cube * t_scale, where t_cube is the distance in root-size units.
    // (Divided step by step: m * len overflows for |dir| near FLT_MAX; t then underflows towards 0,
    // which is the true distance to float precision.)
    s.t_scale = min((tree.root_size / m) / len, RK_FLT_MAX);
    float inv_size = 1.0f / tree.root_size;
    vec3 o = (origin - tree.root_min) * inv_size + vec3(1.0f);

    // Tiny components get a tiny value of the same sign (sign bit: -0 is negative).
    if (abs(u.x) < RK_SVO_TRAVERSE_DIR_EPS) u.x = (floatBitsToUint(u.x) & 0x80000000u) != 0u ? -RK_SVO_TRAVERSE_DIR_EPS : RK_SVO_TRAVERSE_DIR_EPS;
    if (abs(u.y) < RK_SVO_TRAVERSE_DIR_EPS) u.y = (floatBitsToUint(u.y) & 0x80000000u) != 0u ? -RK_SVO_TRAVERSE_DIR_EPS : RK_SVO_TRAVERSE_DIR_EPS;
    if (abs(u.z) < RK_SVO_TRAVERSE_DIR_EPS) u.z = (floatBitsToUint(u.z) & 0x80000000u) != 0u ? -RK_SVO_TRAVERSE_DIR_EPS : RK_SVO_TRAVERSE_DIR_EPS;
    s.u = u;

    // Clip to the root [1, 2]^3 and move the origin to the entry point.
    vec3 inv_u = vec3(1.0f) / u;
    vec3 ta = (vec3(1.0f) - o) * inv_u;
    vec3 tb = (vec3(2.0f) - o) * inv_u;
    vec3 tlo = min(ta, tb);
    vec3 thi = max(ta, tb);
    float t_enter = max(max(max(tlo.x, tlo.y), tlo.z), 0.0f);
    float t_leave = min(min(thi.x, thi.y), thi.z);
    float t_lim = t_max > 0.0f ? min(t_max * (m / tree.root_size) * len, RK_FLT_MAX) : 0.0f;
    if (!(t_enter <= t_leave) || !(t_enter <= t_lim)) return false;
    s.t_enter = t_enter;
    o = o + u * t_enter;
    t_lim = t_lim - t_enter;

    // Mirror to negative directions: t(x) = x * coef - bias on the mirrored axis.
    vec3 coef = -abs(inv_u);  // -1 / |u|, exactly (IEEE division is sign-symmetric)
    vec3 bias = coef * o;
    uint flip = 0u;
    if (u.x > 0.0f) { flip |= 1u; bias.x = 3.0f * coef.x - bias.x; }
    if (u.y > 0.0f) { flip |= 2u; bias.y = 3.0f * coef.y - bias.y; }
    if (u.z > 0.0f) { flip |= 4u; bias.z = 3.0f * coef.z - bias.z; }
    s.coef = coef;
    s.bias = bias;
    s.flip = flip;

    float t_min = max(max(max(2.0f * coef.x - bias.x, 2.0f * coef.y - bias.y), 2.0f * coef.z - bias.z), 0.0f);
    s.t_min = t_min;
    s.t_hi = min(min(min(coef.x - bias.x, coef.y - bias.y), coef.z - bias.z), t_lim);
    s.t_end = s.t_hi;

    s.b = rk_svo_brick_levels(tree.depth);
    s.top = tree.depth - s.b;
    s.leaf = min(tree.max_level, tree.depth);
#if RK_SVO_TRAVERSE_LOD
    // Footprint in cube units: cone.x / root_size + cone.y * t_cube * root_size / root_size.
    s.lod_bias = max(cone.x, 0.0f) * inv_size;
    s.lod_slope = max(cone.y, 0.0f);
#else
    RK_UNUSED(cone);
#endif

    // The root (parent at level 0).
    s.handle = 0u;
    s.pdesc = 0u;
    s.bmask = uvec2(0u);
    s.bsub = 0u;
    s.brick = 0u;
    if (s.top > 0u) {
        s.pdesc = RK_SVO_READ(buf, 0u);
    } else {
        uint w0 = rk_svo_word_of(0u, tree.desc_words);
        s.bmask = uvec2(RK_SVO_READ(buf, w0), RK_SVO_READ(buf, w0 + 1u));
        s.bsub = s.b == 2u ? rk_svo_brick_submask(s.bmask) : (s.bmask.x & 0xFFu);
    }
    s.pmask = rk_svo_trace_child_mask_(0u, s.top, s.pdesc, s.bmask, s.bsub, 0u);
    bool root_stop = s.leaf == 0u;
#if RK_SVO_TRAVERSE_LOD
    root_stop = root_stop || 1.0f <= s.lod_bias + s.lod_slope * (t_enter + t_min);
#endif
    if (root_stop) {
        h.hit = s.pmask != 0u && t_min <= s.t_hi;
        // Face: the axis whose entry plane is furthest along the ray.
        h.normal = rk_svo_trace_entry_normal_(2.0f * coef - bias, u);
        h.t = min((t_enter + t_min) * s.t_scale, RK_FLT_MAX);
        if (!h.hit) h.normal = vec3(0.0f);
        return false;
    }

    // The first cell: the root's child the ray starts in.
    s.scale = 22;
    s.size = 0.5f;
    s.pos = vec3(1.0f);
    s.idx = 0u;
    if (1.5f * coef.x - bias.x > t_min) { s.idx |= 1u; s.pos.x = 1.5f; }
    if (1.5f * coef.y - bias.y > t_min) { s.idx |= 2u; s.pos.y = 1.5f; }
    if (1.5f * coef.z - bias.z > t_min) { s.idx |= 4u; s.pos.z = 1.5f; }
    return true;
}

/// rk_svo_trace_hit_fields_: internal. The answer for the node the loop stopped at, all but the face
/// normal (svo_trace_packet.hpp computes that on its lanes): un-mirrored cell, level, distance and
/// where its attributes are. Exact but for t, (t_enter + t_min) * t_scale in two roundings (bounded
/// by rk_svo_trace's Accuracy line). Cost: ~20 ALU, one word load where the parent has a far pointer.
RK_INLINE void rk_svo_trace_hit_fields_(RK_SVO_BUF buf, rk_svo_tree tree, rk_svo_trace_state_ s, RK_INOUT(rk_svo_trace_hit) h)
{
    uint lvl = uint(23 - s.scale);
    uint c = s.idx ^ s.flip;
    float px = (s.flip & 1u) != 0u ? 3.0f - s.size - s.pos.x : s.pos.x;
    float py = (s.flip & 2u) != 0u ? 3.0f - s.size - s.pos.y : s.pos.y;
    float pz = (s.flip & 4u) != 0u ? 3.0f - s.size - s.pos.z : s.pos.z;
    uint sh = uint(s.scale);
    h.cell = uvec3((floatBitsToUint(px) & 0x7FFFFFu) >> sh, (floatBitsToUint(py) & 0x7FFFFFu) >> sh,
                   (floatBitsToUint(pz) & 0x7FFFFFu) >> sh);
    h.hit = true;
    h.level = lvl;
    h.t = min((s.t_enter + s.t_min) * s.t_scale, RK_FLT_MAX);
    uint lp = lvl - 1u;
    if (lp < s.top) {
        uint far_word = rk_svo_is_far(s.pdesc) ? RK_SVO_READ(buf, s.handle + rk_svo_rel_ptr(s.pdesc)) : 0u;
        h.node = rk_svo_first_child(s.handle, s.pdesc, far_word) + rk_svo_child_rank(s.pmask, c);
    } else {
        h.node = s.brick;
        h.brick_mask = s.bmask;
        h.brick_bit = lvl == tree.depth && s.b == 2u ? (c | (s.handle << 3u)) : c;
    }
}

/// rk_svo_trace_finish_: internal. rk_svo_trace's answer after the loop: `found` (the loop stopped
/// at a node) or a miss, with `iterations` loop iterations.
RK_INLINE void rk_svo_trace_finish_(RK_SVO_BUF buf, rk_svo_tree tree, rk_svo_trace_state_ s, bool found, uint iterations,
                                    RK_INOUT(rk_svo_trace_hit) h)
{
    h.iterations = iterations;
    if (!found) return;
    rk_svo_trace_hit_fields_(buf, tree, s, h);
    h.normal = rk_svo_trace_entry_normal_((s.pos + vec3(s.size)) * s.coef - s.bias, s.u);  // entry planes of the cell
}

/// rk_svo_trace_iteration_bound: the bound on rk_svo_trace's loop iterations for `tree`:
/// RK_SVO_TRAVERSE_MAX_ITER, or where that is 0 (the default) 16 x 2^depth (depth clamped to
/// RK_SVO_MAX_DEPTH), which no ray through a valid tree reaches. Exact. Cost: 1 min, 1 shift.
RK_INLINE uint rk_svo_trace_iteration_bound(rk_svo_tree tree)
{
    return RK_SVO_TRAVERSE_MAX_ITER > 0 ? uint(RK_SVO_TRAVERSE_MAX_ITER) : (16u << min(tree.depth, RK_SVO_MAX_DEPTH));
}

/// rk_svo_trace: casts the ray origin + t * dir, t in [0, t_max], through `tree` and returns the
/// first non-empty voxel (or level-of-detail node) it enters.
/// Domain: finite origin and dir (dir may have zero or tiny components; a dir below 1.2e-38 in
/// every component misses), t_max >= 0 (negative misses), a tree that passed svo_validate.
/// Ties: a ray that only touches a voxel along an edge or corner, or runs in a face plane, may or
/// may not report it (the tests compare with a float64 dense-grid DDA that brackets the answer).
/// Accuracy: the hit point lies within 2e-6 root sizes of the node's surface (plus ~8 ULPs of the
/// origin's distance for far origins); at depth >= 18 a direction component below 2^-21 (tilted,
/// see above) can move the ray by up to a voxel over the root.
/// Cost: per iteration ~30 ALU and at most one word load (a descriptor on push or pop, a far slot,
/// 2 words for a brick); a brick's 4^3 voxels cost no further load. Loop bounded by
/// rk_svo_trace_iteration_bound. No attribute is read (rk_svo_trace_attr gives their index).
RK_INLINE rk_svo_trace_hit rk_svo_trace(RK_SVO_BUF buf, rk_svo_tree tree, vec3 origin, vec3 dir, float t_max, vec2 cone)
{
    rk_svo_trace_hit h;
    rk_svo_trace_state_ s;
    if (!rk_svo_trace_begin_(buf, tree, origin, dir, t_max, cone, h, s)) return h;

    uint stk_node[RK_SVO_TRAVERSE_STACK];
    float stk_tmax[RK_SVO_TRAVERSE_STACK];

    uint iter = 0u;
    bool found = false;
    uint bound = rk_svo_trace_iteration_bound(tree);
    for (; iter < bound; ++iter) {
        uint lc = uint(23 - s.scale);  // level of the current cell
        vec3 tc = s.pos * s.coef - s.bias;  // exit planes of the current cell
        float tc_max = min(min(tc.x, tc.y), tc.z);
        uint c = s.idx ^ s.flip;
        if (((s.pmask >> c) & 1u) != 0u && s.t_min <= s.t_hi) {
            float tv_max = min(s.t_hi, tc_max);
            if (s.t_min <= tv_max) {
                bool stop = lc >= s.leaf;
#if RK_SVO_TRAVERSE_LOD
                stop = stop || s.size <= s.lod_bias + s.lod_slope * (s.t_enter + s.t_min);
#endif
                if (stop) {
                    found = true;
                    break;
                }
                // Push: the child becomes the parent.
                uint lp = lc - 1u;
                stk_node[lp] = s.handle;
                stk_tmax[lp] = s.t_hi;
                if (lp < s.top) {
                    uint far_word = rk_svo_is_far(s.pdesc) ? RK_SVO_READ(buf, s.handle + rk_svo_rel_ptr(s.pdesc)) : 0u;
                    s.handle = rk_svo_first_child(s.handle, s.pdesc, far_word) + rk_svo_child_rank(s.pmask, c);
                    if (lc < s.top) {
                        s.pdesc = RK_SVO_READ(buf, s.handle);
                    } else {
                        uint w = rk_svo_word_of(s.handle, tree.desc_words);
                        s.bmask = uvec2(RK_SVO_READ(buf, w), RK_SVO_READ(buf, w + 1u));
                        s.bsub = s.b == 2u ? rk_svo_brick_submask(s.bmask) : (s.bmask.x & 0xFFu);
                        s.brick = s.handle;
                    }
                } else {
                    s.handle = c;  // a level-(depth-1) node inside the brick
                }
                s.pmask = rk_svo_trace_child_mask_(lc, s.top, s.pdesc, s.bmask, s.bsub, s.handle);
                s.scale -= 1;
                s.size *= 0.5f;
                s.idx = 0u;
                vec3 tmid = s.size * s.coef + tc;  // the child's centre planes
                if (tmid.x > s.t_min) { s.idx |= 1u; s.pos.x += s.size; }
                if (tmid.y > s.t_min) { s.idx |= 2u; s.pos.y += s.size; }
                if (tmid.z > s.t_min) { s.idx |= 4u; s.pos.z += s.size; }
                s.t_hi = tv_max;
                continue;
            }
        }
        // Advance to the next cell along the ray; every axis whose exit plane ties steps.
        uint stp = 0u;
        if (tc.x <= tc_max) { stp |= 1u; s.pos.x -= s.size; }
        if (tc.y <= tc_max) { stp |= 2u; s.pos.y -= s.size; }
        if (tc.z <= tc_max) { stp |= 4u; s.pos.z -= s.size; }
        // Never backwards: for an axis almost parallel to the ray, plane distances carry rounding
        // of ~2^-22 / |dir| (a position error of ~2^-22), which can put tc_max below t_min.
        s.t_min = max(s.t_min, tc_max);
        s.idx ^= stp;
        if ((s.idx & stp) != 0u) {
            // Left the parent. Past t_max (or the root's exit) nothing more can be entered: stop
            // rather than pop and walk on to the root's exit.
            if (s.t_min > s.t_end) break;
            // Pop to the level of the highest differing address bit.
            uint diff = 0u;
            if ((stp & 1u) != 0u) diff |= floatBitsToUint(s.pos.x) ^ floatBitsToUint(s.pos.x + s.size);
            if ((stp & 2u) != 0u) diff |= floatBitsToUint(s.pos.y) ^ floatBitsToUint(s.pos.y + s.size);
            if ((stp & 4u) != 0u) diff |= floatBitsToUint(s.pos.z) ^ floatBitsToUint(s.pos.z + s.size);
            s.scale = findMSB(diff);
            if (s.scale >= 23 || s.scale < 23 - int(s.leaf)) break;  // left the root
            s.size = uintBitsToFloat(uint(s.scale + 104) << 23u);  // 2^(scale - 23)
            uint lp = uint(22 - s.scale);
            s.handle = stk_node[lp];
            s.t_hi = stk_tmax[lp];
            if (lp < s.top) s.pdesc = RK_SVO_READ(buf, s.handle);
            s.pmask = rk_svo_trace_child_mask_(lp, s.top, s.pdesc, s.bmask, s.bsub, s.handle);
            uint sx = floatBitsToUint(s.pos.x) >> uint(s.scale);
            uint sy = floatBitsToUint(s.pos.y) >> uint(s.scale);
            uint sz = floatBitsToUint(s.pos.z) >> uint(s.scale);
            s.pos = vec3(uintBitsToFloat(sx << uint(s.scale)), uintBitsToFloat(sy << uint(s.scale)), uintBitsToFloat(sz << uint(s.scale)));
            s.idx = (sx & 1u) | ((sz & 1u) << 2u) | ((sy & 1u) << 1u);
        }
    }
    rk_svo_trace_finish_(buf, tree, s, found, iter, h);
    return h;
}

/// rk_svo_trace_attr: the attribute index (into the color / normal / material streams) of what
/// rk_svo_trace hit: the node's ordinal above the bricks, else brick_base[brick] plus its rank in
/// the brick (rk_svo_brick_sub_attr, rk_svo_brick_voxel_attr; a level-(depth-1) stop in a tree built
/// with shared sub-node attributes gets the brick's). Domain: hit.hit is true.
/// Cost: 1 word load inside a brick, none above.
RK_INLINE uint rk_svo_trace_attr(RK_SVO_BUF buf, rk_svo_tree tree, rk_svo_trace_hit hit)
{
    uint b = rk_svo_brick_levels(tree.depth);
    uint top = tree.depth - b;
    if (hit.level <= top) return hit.node;
    uint base = RK_SVO_READ(buf, tree.brick_base_word + (hit.node - tree.desc_words));
    if (hit.level == tree.depth) return rk_svo_brick_voxel_attr(base, hit.brick_mask, hit.brick_bit, b);
    return rk_svo_brick_sub_attr(base, hit.brick_mask, hit.brick_bit, hit.node);
}

#endif  // RK_SVO_TRAVERSE_GLSL
