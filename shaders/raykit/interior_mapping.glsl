// raykit — interior_mapping.glsl: interior mapping (van Dongen 2008/2009): perspective-correct
// rooms behind a building's windows, by casting the view ray against virtual, regularly spaced,
// infinite planes (floors/ceilings of constant y, walls of constant x and of constant z) in the
// pixel shader of the building's exterior. Constant time per pixel, no interior geometry.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/interior_mapping.hpp, which
// adds CPU helpers (camera_to_object_space, room_grid_for_building, room_at, lit_fraction).
// Source: van Dongen, "Using raycasting in GPU shaders to enhance real-time graphics" (Master's
// thesis, Utrecht University, 2009), ch. 5 + appendix; the thesis's bugs fixed here are listed below.
//
// THE MODEL. All work is in the building's object space. A grid (rk_im_grid) places planes of
// axis i at origin_i + k * room_size_i, k integer; "grid units" below are room units,
// q = (x - origin) / room_size. The ray is X(t) = cam + t (p - cam): p is the shaded point on
// the exterior surface (t = 1), n its outward normal. The hit is the nearest of the three
// "next planes" beyond p, one per axis, found in constant time.
//
// WHAT IS FIXED RELATIVE TO THE THESIS (errata of its appendix shader, and what §5.4 leaves unstated):
//  * Facade exactly on a grid plane (a unit cube with integer rooms per unit): the thesis's
//    floor+step rule returns the plane AT the surface (t = 1, a flat wall that flickers with
//    interpolation jitter). Here the next plane is chosen from a nudged point q' and is always
//    strictly beyond it: q'_i = q_i + RK_IM_NUDGE * s_i on every axis i where the ray moves into
//    the building (s_i = sign of the ray's axis-i component, and the normalised normal has a
//    component n_i * s_i < -1e-6), q'_i = q_i on the others. Rule: a plane that lies within
//    RK_IM_NUDGE room units (default 2^-10 = 0.00098) behind the facade along its normal counts as
//    the facade itself and is skipped; the room seen is the one behind it. Then t > 1 strictly:
//    the result is additionally floored at t = 1 + 2^-23.
//  * Rays parallel to a family (a direction component that is 0, denormal, or below 2^-50 of the
//    largest component): that family's ray distance is the finite sentinel RK_IM_T_SENTINEL, so
//    it is never chosen (some other axis always has a plane within 1 + RK_IM_NUDGE room units).
//    No field is ever Inf or NaN, for any finite input (see the domains).
//  * Camera on the inner side of the surface (dot(n, p - cam) >= 0), a zero normal (max |n_i| <
//    1e-30), or a camera within 1e-20 room units of p: valid = false, and the documented defaults
//    t = 1, depth = 0, family = 1, side = -1, room = rk_im_room_at(p), uv = uv_dx = uv_dy = 0,
//    pos = p.
//  * Room index from the chosen next-plane index per axis (not given in §5.4): room_i = plane_i - 1
//    when the ray travels toward +i, plane_i otherwise. It is the cell the ray segment from p to
//    the hit lies in, so a corner room seen through two facades is the same room.
//  * Analytic UV derivatives (rk_im_trace_grad): the derivative of the hit point on the chosen
//    plane with respect to p, applied to dp/dx and dp/dy: d(hit) = t (dp - dir dp_i / dir_i)
//    (i the chosen axis). They do not contain the cell index, so they are continuous across room
//    seams of one family (a naive dFdx(fract(uv)) jumps by ~1 there); use them with textureGrad.
//  * Precision, the LOCAL-ORIGIN RULE: give each building its own object space centred near the
//    building (|p| within a few hundred room sizes of 0) and put the grid phase in
//    rk_im_grid.origin. Measured (tests/test_interior_mapping.cpp, FarFromOriginNeedsALocalOrigin:
//    30 x 60 x 30 building, 3 m rooms, translated by 1e5 in x and z, 1e5 rays, camera held in
//    float world coordinates): with a local origin (camera through camera_to_object_space)
//    0 rays differ from the float64 reference in family/room and uv is within 1.6e-4 rooms;
//    with object space = world space, 192 rays get the wrong room/family and uv is off by up
//    to 0.136 rooms (float32 spacing at 1e5 is 0.0078 units).
//
// VARYING ROOM SIZES (rk_im_trace_varying, thesis §5.4.3): the wall of index k on axis i is
// displaced to k + delta_i(k) room units, delta_i(k) = jitter_i * rk_u32_to_unit(hash(k, i, seed))
// in [0, 1): "one wall per cell", so walls keep their order and every room has a positive size
// (up to rounding). Then the next wall from q' is wall m = floor(q') if it lies beyond q' along
// the ray, else wall m + s: exact (two candidates), verified against a brute
// force search in the test. The thesis's literal previous/next pair is wrong for about one ray in
// four (the test ports it and prints the count). The room index is that of the cell between
// walls k and k+1; uv is normalised across the displaced room, [0, 1) over its actual width.
//
// Feature macros:
//   RK_IM_VARYING_WALLS  0 (default): rk_im_trace_auto() is rk_im_trace_grad() (regular grid,
//       jitter and seed unused: zero cost). 1: rk_im_trace_auto() is rk_im_trace_varying_grad()
//       (walls displaced per wall index; 12 single-word hashes as four uvec3 hashes, 3
//       divisions: about 80 SPIR-V instructions more).
//       rk_im_trace_varying() and rk_im_trace_grad() themselves are always available.
//   RK_IM_NUDGE  the facade-nudge distance in room units (default 2^-10). Larger values skip
//       planes further behind a facade; it must exceed the interpolation jitter of p in room units
//       (a few ulps of |q|) and stay far below 1.
//
// Domains: |p|, |cam|, |origin| components <= 1e15 (RK_IM_COORD_MAX); room_size components in
// [1e-4, 1e6] (abs taken, clamped); exact plane/room selection needs |q| < 2^22 rooms. Outside the
// domain every field stays finite (no Inf/NaN for any finite input), with the fewest clamps that
// guarantee it, each protecting all later uses: room size (clamped), grid coordinates (clamped to
// +-2^30, which also absorbs an overflow of p - origin), p - cam (clamped to +-1e18, so the
// direction, its length and the facing test cannot overflow), the normal's scale (1 / max|n_i|,
// clamped to [1e-30, 1e30]), dp_dx/dp_dy in room units (clamped to +-1e10), derivative outputs
// (clamped to +-1e30). Within the domain none of these clamps changes a result.
//
// COST: the trace is straight-line vec3 code with selects, no branches. SPIR-V instructions in
// function bodies (glslangValidator -G, spirv-opt -O; the counting rule of
// scripts/bench_interior.sh) of a fragment shader that calls the trace and writes uv, uv_dx,
// uv_dy, family, side, room and valid (scripts/im_trace_spirv.sh): rk_im_trace_grad 184 (118
// ALU), rk_im_trace 138, rk_im_trace_varying_grad 269. The facing test and grid coordinates that
// agree with GPUs flushing subnormals cost 20 to 22 of them (164 / 118 / 247 before, same
// script); before the vectorised rewrite: 293 / 204 / 571, with 23 to 26 conditional branches.
// Divisions: rk_im_trace_grad 11 scalar (grid coordinates 3, the room-size reciprocal 3, the
// direction reciprocal per axis 3, normal and p - cam scales 1 each), was 32.
//
// @rk-es 310
// @rk-es300
// @rk-variants RK_IM_VARYING_WALLS=0 | RK_IM_VARYING_WALLS=1 | RK_IM_VARYING_WALLS=1 RK_IM_NUDGE=0.001f
#ifndef RK_INTERIOR_MAPPING_GLSL
#define RK_INTERIOR_MAPPING_GLSL

#ifdef __cplusplus
#define RK_NS_IM_TRACE RK_PP_CAT(RK_PP_CAT(im_trace_varying_walls, RK_IM_VARYING_WALLS), RK_PP_CAT(_nudge_, RK_IM_NUDGE_TAG))
#endif

#include "common.glsl"
#include "hash.glsl"

#ifndef RK_IM_VARYING_WALLS
#define RK_IM_VARYING_WALLS 0
#endif
#if RK_IM_VARYING_WALLS < 0 || RK_IM_VARYING_WALLS > 1
#error "RK_IM_VARYING_WALLS must be 0 (regular walls) or 1 (walls displaced per wall index)"
#endif
RK_OPTION_CHECK(rk_option_im_varying_walls, RK_IM_VARYING_WALLS);
#ifdef __cplusplus
// A float cannot name a namespace: the C++ build of the functions that read RK_IM_NUDGE is named
// after RK_IM_NUDGE_TAG, which a non-default nudge must come with.
#if defined(RK_IM_NUDGE) && !defined(RK_IM_NUDGE_TAG)
#error "C++ build: a non-default RK_IM_NUDGE needs RK_IM_NUDGE_TAG, an identifier naming its value (e.g. 2em12), which names the C++ functions built with it"
#endif
#ifndef RK_IM_NUDGE_TAG
#define RK_IM_NUDGE_TAG default_2em10
#endif
#endif
#ifndef RK_IM_NUDGE
#define RK_IM_NUDGE 0.0009765625f
#endif

// Per-family ray distance of a family the ray runs parallel to (never the nearest: see above).
#define RK_IM_T_SENTINEL 1e30f
// |direction component| below this (2^-50) times the largest component counts as parallel.
#define RK_IM_PARALLEL 8.8817841970012523e-16f
// Camera closer than this to p (room units, max-norm): degenerate ray, valid = false.
#define RK_IM_DIR_MIN 1e-20f
// The documented coordinate domain (|p|, |cam|, |origin| components), also used by the other
// interior files.
#define RK_IM_COORD_MAX 1e15f
#define RK_IM_GRID_MAX 1073741824.0f
#define RK_IM_ROOM_MIN 1e-4f
#define RK_IM_ROOM_MAX 1e6f
// p - cam is clamped to this per component (2 RK_IM_COORD_MAX fits: no effect in the domain).
#define RK_IM_DIFF_MAX 1e18f
#define RK_IM_DQ_MAX 1e10f
#define RK_IM_DERIV_MAX 1e30f
// Largest float below 1: uv is clamped to [0, RK_IM_UV_MAX].
#define RK_IM_UV_MAX 0.99999994f
// 1 + 2^-23: the smallest t returned (strictly behind the surface).
#define RK_IM_T_MIN 1.00000012f

/// The room grid of one building, in its object space: planes of axis i at
/// origin_i + k * room_size_i (k integer). room_size = (wall pitch in x, storey height, wall
/// pitch in z). Keep origin near the building (see the local-origin rule above).
struct rk_im_grid {
    vec3 room_size;
    vec3 origin;
};

/// The result of an interior-mapping trace. See the file header for conventions and defaults.
struct rk_im_hit {
    float t;      // ray fraction: hit = cam + t (p - cam); > 1 (strictly) when valid, 1 otherwise
    float depth;  // object-space distance from p to the hit (>= 0)
    int family;   // 0: wall of constant x, 1: floor/ceiling (constant y), 2: wall of constant z
    int side;     // +1: the ray travels toward +axis (family 1: ceiling), -1: toward -axis (floor)
    ivec3 room;   // the grid cell (room) the ray is in when it hits
    vec2 uv;      // face uv in [0, 1): family 0 (z, y), 1 (x, z), 2 (x, y)
    vec2 uv_dx;   // d uv / d screen x (analytic, continuous across room seams); 0 from rk_im_trace
    vec2 uv_dy;   // d uv / d screen y
    vec3 pos;     // hit point in object space (exactly on the chosen plane's coordinate)
    bool valid;   // false: camera on the inner side, zero normal or degenerate ray
};

/// rk_im_grid_coord: grid (room-unit) coordinates of an object-space point, (x - origin) /
/// room_size, room_size taken as clamp(|room_size|, 1e-4, 1e6) and the result clamped to
/// +-2^30 (x - origin may overflow to +-Inf only for components beyond 1.7e38, far outside the
/// domain; the clamp maps that to +-2^30, never NaN). A coordinate below RK_FLT_MIN in magnitude
/// is 0 (a GPU that flushes subnormals makes it so; otherwise a point 1e-38 below the origin's
/// planes would be in room -1 on one build and 0 on the other). Exact up to one rounding of the
/// subtraction and one of the division. Cost: 3 sub, 3 div, 1 abs + 2 clamps, 3 selects (vec3).
RK_INLINE vec3 rk_im_grid_coord(vec3 x, rk_im_grid g)
{
    vec3 rs = clamp(abs(g.room_size), vec3(RK_IM_ROOM_MIN), vec3(RK_IM_ROOM_MAX));
    vec3 q = clamp((x - g.origin) / rs, vec3(-RK_IM_GRID_MAX), vec3(RK_IM_GRID_MAX));
    return rk_flush_subnormal(q);
}

/// rk_im_room_at: the grid cell containing the object-space point p: floor of its grid
/// coordinates (a point exactly on a plane belongs to the cell on the plane's + side, and so does
/// one within a subnormal grid distance of the origin's planes). Domain:
/// any finite p; exact for |q| < 2^22 rooms. For gameplay queries (which room is lit?). Regular
/// grid only (rk_im_room_at_varying for displaced walls). Cost: rk_im_grid_coord + 3 floor.
RK_INLINE ivec3 rk_im_room_at(vec3 p, rk_im_grid g) { return ivec3(floor(rk_im_grid_coord(p, g))); }

/// rk_im_room_random: a per-room random number in [0, 1) (multiples of 2^-24), from rk_pcg3d of
/// the room index with the seed mixed into z: rk_u32_to_unit(rk_pcg3d(uvec3(x, y, z ^
/// rk_hash_u32(seed))).x). Different seeds give unrelated sequences. Exact: bit-identical on CPU
/// and GPU. Cost: 1 rk_hash_u32 + 1 rk_pcg3d.
RK_INLINE float rk_im_room_random(ivec3 room, uint seed)
{
    uvec3 h = rk_pcg3d(uvec3(uint(room.x), uint(room.y), uint(room.z) ^ rk_hash_u32(seed)));
    return rk_u32_to_unit(h.x);
}

/// rk_im_face_random: a random number in [0, 1) per face of a room (6 faces: family 0..2 x side
/// -1/+1), independent of rk_im_room_random for the same room and seed (it uses another lane of
/// PCG3D and a face-dependent key): e.g. a texture-array layer per wall. family is clamped to
/// [0, 2], side > 0 means +1. Exact (integer only). Cost: 2 rk_hash_u32 + 1 rk_pcg3d.
RK_INLINE float rk_im_face_random(ivec3 room, int family, int side, uint seed)
{
    uint face = uint(clamp(family, 0, 2) * 2 + (side > 0 ? 1 : 0));
    uint key = rk_hash_u32(seed ^ rk_hash_u32(face + 0x6a09e667u));
    uvec3 h = rk_pcg3d(uvec3(uint(room.x) ^ key, uint(room.y), uint(room.z) ^ rk_hash_u32(seed)));
    return rk_u32_to_unit(h.y);
}

/// rk_im_room_lit: whether a room's light is on, for the building's probability c (thesis
/// §5.4.1): rk_im_room_random(room, seed) < c. The lit set is monotone in c (a room lit at c is
/// lit at every c' > c); c <= 0: none, c >= 1: all. The expected lit fraction is c to 2^-24.
/// Cost: that of rk_im_room_random.
RK_INLINE bool rk_im_room_lit(ivec3 room, float c, uint seed) { return rk_im_room_random(room, seed) < c; }

/// rk_im_jitter: the wall jitter the varying-walls model uses: clamped to [0, 1], and 0 below 2^-64,
/// where jitter * hash (rk_im_wall_offset) could be subnormal, which a GPU flushes: the room of a
/// point 1e-38 from a wall would then differ between builds. Exact. Cost: 1 clamp, 1 select.
RK_INLINE vec3 rk_im_jitter(vec3 jitter)
{
    vec3 j = clamp(jitter, vec3(0.0f), vec3(1.0f));
    return mix(j, vec3(0.0f), lessThan(j, vec3(5.421010862427522e-20f)));
}

/// rk_im_wall_offset: the displacement, in room units in [0, 1), of wall k of axis (0 x, 1 y,
/// 2 z) in the varying-walls model: rk_im_jitter(jitter) * rk_u32_to_unit(rk_hash_u32(uint(k) ^
/// key(axis, seed))), key(axis, seed) = rk_hash_u32(seed + axis * 2654435769u). A function of the
/// wall index only, so each wall plane moves as a whole. Exact (bit-identical on CPU/GPU). Cost:
/// 2 rk_hash_u32 (the key is shared between calls after common-subexpression elimination).
RK_INLINE float rk_im_wall_offset(int axis, int k, float jitter, uint seed)
{
    uint key = rk_hash_u32(seed + uint(axis) * 2654435769u);
    return rk_im_jitter(vec3(jitter)).x * rk_u32_to_unit(rk_hash_u32(uint(k) ^ key));
}

// ---- implementation details (not part of the API) ----------------------------------------------

/// rk_hash_u32 on each component (bit-identical to it; tests/test_interior_mapping.cpp checks).
RK_INLINE uvec3 rk_im_detail_hash3(uvec3 x)
{
    uvec3 state = x * 747796405u + 2891336453u;
    uvec3 word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/// The three per-axis keys of rk_im_wall_offset: rk_hash_u32(seed + axis * 2654435769u)
/// (2 * 2654435769 mod 2^32 = 1013904242).
RK_INLINE uvec3 rk_im_detail_wall_keys(uint seed)
{
    return rk_im_detail_hash3(uvec3(seed) + uvec3(0u, 2654435769u, 1013904242u));
}

/// rk_im_wall_offset of wall k_i of axis i, for the three axes at once; k holds integers
/// (|k| < 2^31), jit the clamped jitter. Bit-identical to three rk_im_wall_offset calls.
RK_INLINE vec3 rk_im_detail_wall_offset3(vec3 k, uvec3 key, vec3 jit)
{
    uvec3 h = rk_im_detail_hash3(uvec3(ivec3(k)) ^ key);
    return jit * (vec3(h >> 8u) * 5.9604644775390625e-8f);
}

/// rk_im_room_at_varying: the cell containing p when walls are displaced (rk_im_trace_varying's
/// model): per axis m = floor(q), then m - 1 if q lies before wall m (q < m + delta(m)).
/// Cost: rk_im_grid_coord + 6 single-word hashes (3 keys, 3 walls; vec3 integer ops).
RK_INLINE ivec3 rk_im_room_at_varying(vec3 p, rk_im_grid g, vec3 jitter, uint seed)
{
    vec3 q = rk_im_grid_coord(p, g);
    vec3 m = floor(q);
    vec3 wm = m + rk_im_detail_wall_offset3(m, rk_im_detail_wall_keys(seed), rk_im_jitter(jitter));
    // q < wm  <=>  not (q >= wm) = 1 - step(wm, q)
    return ivec3(m - (vec3(1.0f) - step(wm, q)));
}

/// The ray of one trace, shared by the regular and the varying-walls traces (all vec3 work).
struct rk_im_detail_ray {
    vec3 rs;     // room size, clamp(|room_size|, RK_IM_ROOM_MIN, RK_IM_ROOM_MAX)
    vec3 irs;    // 1 / rs
    vec3 q;      // grid coordinates of p (rk_im_grid_coord)
    vec3 qn;     // q' = q nudged past the facade (q itself when invalid)
    vec3 v;      // p - cam in object units, clamped to +-RK_IM_DIFF_MAX
    vec3 e;      // v / rs: the ray in grid units, unnormalised: q(t) = q + (t - 1) e
    vec3 ie;     // 1 / e per axis (1 for components below 2^-50 RK_IM_DIR_MIN), |ie| <= 1.2e35
    bvec3 np;    // non-parallel components: |e_i| >= 2^-50 max(max_j |e_j|, RK_IM_DIR_MIN)
    vec3 up;     // 1 where the ray counts as travelling toward +axis (e_i >= -that bound), else 0;
                 // all 1 when invalid
    vec3 s;      // 2 up - 1
    bool valid;
};

// C++: the functions below depend on RK_IM_VARYING_WALLS and RK_IM_NUDGE (RK_IM_NUDGE_TAG); their C++ build lives in an
// inline namespace named after the values (docs/dialect.md), so translation units with other
// values never share it.
RK_CONFIGURED_BEGIN(RK_NS_IM_TRACE)
/// Common setup: clamps, grid coordinates, direction, validity, travel direction and the nudge.
/// When invalid, up = 1 and q' = q, so that both axis rules return the documented default room
/// (rk_im_room_at, rk_im_room_at_varying) with no extra work.
RK_INLINE rk_im_detail_ray rk_im_detail_setup(vec3 p, vec3 cam, vec3 n, rk_im_grid g)
{
    rk_im_detail_ray r;
    r.rs = clamp(abs(g.room_size), vec3(RK_IM_ROOM_MIN), vec3(RK_IM_ROOM_MAX));
    r.irs = vec3(1.0f) / r.rs;
    r.q = rk_im_grid_coord(p, g);
    r.v = clamp(p - cam, vec3(-RK_IM_DIFF_MAX), vec3(RK_IM_DIFF_MAX));
    r.e = r.v * r.irs;
    vec3 ae = abs(r.e);
    float emax = max(max(ae.x, ae.y), ae.z);
    float thr = RK_IM_PARALLEL * max(emax, RK_IM_DIR_MIN);
    r.np = bvec3(step(vec3(thr), ae));
    // The divisor does not wait for thr: components below 2^-50 RK_IM_DIR_MIN (always parallel)
    // are replaced by 1; the others between that and thr are parallel too and get the sentinel.
    r.ie = vec3(1.0f) / mix(vec3(1.0f), r.e, bvec3(step(vec3(RK_IM_PARALLEL * RK_IM_DIR_MIN), ae)));
    float nmax = max(max(abs(n.x), abs(n.y)), abs(n.z));
    // Only the sign of dot(n, v) matters: n and v scaled by their largest components (clamped so
    // that the scales are normal floats and the dot cannot overflow), components below 2^-60 of
    // those dropped and a dot below RK_FLT_MIN read as 0, so that no product or sum is subnormal
    // (a GPU that flushes subnormals then decides as the CPU does).
    vec3 nn = n * (1.0f / clamp(nmax, 1e-30f, 1e30f));
    float vmax = max(max(abs(r.v.x), abs(r.v.y)), abs(r.v.z));
    vec3 vn = r.v * (1.0f / clamp(vmax, 1e-30f, 1e30f));
    nn = mix(nn, vec3(0.0f), lessThan(abs(nn), vec3(8.673617379884035e-19f)));
    vn = mix(vn, vec3(0.0f), lessThan(abs(vn), vec3(8.673617379884035e-19f)));
    bool facing = dot(nn, vn) <= -RK_FLT_MIN;  // (a separate bool: && of plain values needs no branch)
    r.valid = nmax >= 1e-30f && emax >= RK_IM_DIR_MIN && facing;
    vec3 up_ray = step(vec3(-thr), r.e);
    vec3 ones = vec3(1.0f);
    r.up = r.valid ? up_ray : ones;
    r.s = 2.0f * r.up - vec3(1.0f);
    // Nudge on every axis where the ray moves into the building: n_i s_i < -1e-6 max|n|.
    vec3 inward = vec3(1.0f) - step(vec3(-1e-6f * nmax), n * r.s);
    vec3 qn = r.q + (RK_IM_NUDGE * r.s) * inward;
    r.qn = r.valid ? qn : r.q;
    return r;
}

/// Picks the nearest family and fills the hit. room, plane, lo (the room's lower wall) and
/// inv_width (1 / the room's width) per axis, in grid units. with_grad is a compile-time constant
/// at every call: false drops the derivative work.
RK_INLINE rk_im_hit rk_im_detail_finish(vec3 p, rk_im_grid g, vec3 dp_dx, vec3 dp_dy, bool with_grad,
                                        rk_im_detail_ray r, vec3 room, vec3 plane, vec3 lo, vec3 inv_width)
{
    // Ray fraction beyond p (t - 1) to each family's next plane; the sentinel when parallel. No
    // max(., 0) needed: the plane lies beyond q' (so beyond q) along s, and a non-parallel e has
    // the sign s, so the product is >= 0 (or -0).
    vec3 f = mix(vec3(RK_IM_T_SENTINEL), (plane - r.q) * r.ie, r.np);
    // Nearest family; ties go to the x wall over the z wall over the floor/ceiling (thesis).
    bool bz = f.z < f.x;
    float fxz = min(f.x, f.z);
    bool by = f.y < fxz;
    float fd = min(fxz, f.y);
    bool b0 = !(bz || by);
    bvec2 sel_uv = bvec2(b0, by);  // uv axes: family 0 (z, y), 1 (x, z), 2 (x, y)
    int fam_xz = bz ? 2 : 0;
    int fam = by ? 1 : fam_xz;
    float ief = mix(mix(r.ie.x, r.ie.z, bz), r.ie.y, by);  // 1 / e of the chosen family (non-parallel)
    int side = ief >= 0.0f ? 1 : -1;
    float t = max(1.0f + fd, RK_IM_T_MIN);
    vec3 dv = fd * r.v;  // p -> hit, object units
    float depth = length(dv);
    vec3 pos = mix(p + dv, g.origin + plane * r.rs, bvec3(b0, by, bz && !by));
    vec3 w = (r.q + fd * r.e - lo) * inv_width;
    vec2 uv = clamp(mix(vec2(w.x, w.y), vec2(w.z, w.z), sel_uv), vec2(0.0f), vec2(RK_IM_UV_MAX));
    vec2 ux = vec2(0.0f);
    vec2 uy = vec2(0.0f);
    if (with_grad) {
        // d(hit) = t (dq - (e / e_i) dq_i) on the chosen plane i (grid units), times inv_width.
        // |e / e_i| <= 2^50 (e_i is not parallel) and |dq| <= 1e10: no overflow before t.
        vec3 dqx = clamp(dp_dx * r.irs, vec3(-RK_IM_DQ_MAX), vec3(RK_IM_DQ_MAX));
        vec3 dqy = clamp(dp_dy * r.irs, vec3(-RK_IM_DQ_MAX), vec3(RK_IM_DQ_MAX));
        vec2 ratio = mix(vec2(r.e.x, r.e.y), vec2(r.e.z, r.e.z), sel_uv) * ief;
        vec2 iw_uv = mix(vec2(inv_width.x, inv_width.y), vec2(inv_width.z, inv_width.z), sel_uv);
        vec2 dqx_uv = mix(vec2(dqx.x, dqx.y), vec2(dqx.z, dqx.z), sel_uv);
        vec2 dqy_uv = mix(vec2(dqy.x, dqy.y), vec2(dqy.z, dqy.z), sel_uv);
        float dqx_i = mix(mix(dqx.x, dqx.z, bz), dqx.y, by);
        float dqy_i = mix(mix(dqy.x, dqy.z, bz), dqy.y, by);
        ux = clamp((t * (dqx_uv - ratio * dqx_i)) * iw_uv, vec2(-RK_IM_DERIV_MAX), vec2(RK_IM_DERIV_MAX));
        uy = clamp((t * (dqy_uv - ratio * dqy_i)) * iw_uv, vec2(-RK_IM_DERIV_MAX), vec2(RK_IM_DERIV_MAX));
    }
    // The documented defaults when invalid (selects; the room is already the default one).
    vec2 zero2 = vec2(0.0f);
    rk_im_hit h;
    h.valid = r.valid;
    h.t = r.valid ? t : 1.0f;
    h.depth = r.valid ? depth : 0.0f;
    h.family = r.valid ? fam : 1;
    h.side = r.valid ? side : -1;
    h.room = ivec3(room);
    h.uv = r.valid ? uv : zero2;
    h.uv_dx = r.valid ? ux : zero2;
    h.uv_dy = r.valid ? uy : zero2;
    h.pos = r.valid ? pos : p;
    return h;
}

/// Regular grid, the three axes at once: the cell the ray is in after q' and the next plane
/// strictly beyond q' (toward +axis: floor(q') + 1, toward -axis: ceil(q') - 1, i.e.
/// s (floor(s q') + 1)); room = plane - 1 toward +axis, plane toward -axis.
RK_INLINE rk_im_hit rk_im_detail_trace(vec3 p, vec3 cam, vec3 n, vec3 dp_dx, vec3 dp_dy, bool with_grad, rk_im_grid g)
{
    rk_im_detail_ray r = rk_im_detail_setup(p, cam, n, g);
    vec3 plane = r.s * (floor(r.s * r.qn) + vec3(1.0f));
    vec3 room = plane - r.up;
    return rk_im_detail_finish(p, g, dp_dx, dp_dy, with_grad, r, room, plane, room, vec3(1.0f));
}

/// Displaced walls, the three axes at once: the two-candidate rule {m, m + s}, m = floor(q')
/// (exact for offsets in [0, 1)): the ray is in cell m - 1 when wall m lies beyond q' and the
/// ray travels toward +axis, or when it does not and the ray travels toward -axis; that cell's
/// other wall is m - 1 or m + 1 (all three wall offsets per axis are hashed, as one uvec3 hash each).
RK_INLINE rk_im_hit rk_im_detail_trace_varying(vec3 p, vec3 cam, vec3 n, vec3 dp_dx, vec3 dp_dy, bool with_grad,
                                               rk_im_grid g, vec3 jitter, uint seed)
{
    rk_im_detail_ray r = rk_im_detail_setup(p, cam, n, g);
    uvec3 key = rk_im_detail_wall_keys(seed);
    vec3 jit = rk_im_jitter(jitter);
    vec3 m = floor(r.qn);
    vec3 wm = m + rk_im_detail_wall_offset3(m, key, jit);
    vec3 not_m = step((wm - r.qn) * r.s, vec3(0.0f));  // 1: wall m is not beyond q' along the ray
    vec3 lower = abs(not_m - r.up);                     // 1: the ray is in cell m - 1
    // The cell's other wall, m - 1 or m + 1: both are hashed (independent of the test above, so
    // the three hashes run in parallel; a dependent second hash is slower on latency-bound SIMD).
    vec3 wp = (m - vec3(1.0f)) + rk_im_detail_wall_offset3(m - vec3(1.0f), key, jit);
    vec3 wn = (m + vec3(1.0f)) + rk_im_detail_wall_offset3(m + vec3(1.0f), key, jit);
    vec3 wk = mix(wn, wp, bvec3(lower));
    vec3 lo = min(wm, wk);                              // walls keep their order
    vec3 inv_width = vec3(1.0f) / max(max(wm, wk) - lo, vec3(1.0e-6f));
    vec3 plane = mix(wm, wk, bvec3(not_m));
    return rk_im_detail_finish(p, g, dp_dx, dp_dy, with_grad, r, m - lower, plane, lo, inv_width);
}

// ---- traces ------------------------------------------------------------------------------------

/// rk_im_trace_grad: the interior-mapping trace with analytic uv derivatives. p: the shaded
/// point of the exterior surface, cam: the camera, n: the surface's outward normal (any length),
/// all in the building's object space; dp_dx/dp_dy: screen derivatives of p (dFdx(p), dFdy(p)).
/// Returns the nearest of the next floor/ceiling plane and the next wall of each family beyond p
/// (the file header gives the rules, fixes and defaults). Max error vs a float64 brute-force
/// tracer over explicit room planes (tests/test_interior_mapping.cpp, 1.02e6 random and
/// adversarial rays): 0 wrong families/rooms (2,753 rays lying exactly on a wall plane they run
/// along are boundary-ambiguous and counted separately); hit position error <= 1.9 * 2^-24 *
/// (4 + |q|) room units times 1/|d_family| (the conditioning of the hit), uv within 1.6e-6;
/// analytic derivatives within 1.2e-6 relative of finite differences. GPU parity (llvmpipe,
/// tests/gpu/parity_interior.cpp): family, side, room and valid bit-identical; t, uv and pos
/// within 1 ulp on the exact domain; on grazing scene rays, whose derivatives reach 1e6, within
/// 1e-4 relative (up to 1.5e3 ulp, 1e-3 absolute). Cost: 11 scalar divisions (3 grid
/// coordinates, 3 room-size reciprocals, 3 direction reciprocals reused by the plane distances and
/// the derivatives, the normal's and p - cam's scales), about 270 scalar ALU ops, all selects (no branches), no loops, no texture; constant whatever the number
/// of rooms. SPIR-V (spirv-opt -O): 184 instructions with every field used.
RK_INLINE rk_im_hit rk_im_trace_grad(vec3 p, vec3 cam, vec3 n, vec3 dp_dx, vec3 dp_dy, rk_im_grid g)
{
    return rk_im_detail_trace(p, cam, n, dp_dx, dp_dy, true, g);
}

/// rk_im_trace: rk_im_trace_grad without derivatives (uv_dx = uv_dy = 0, their work skipped).
/// Use with textureLod or when the interior is not mip-mapped. Domain, edge cases and max error:
/// those of rk_im_trace_grad; every other field is bit-identical to it (tests/
/// test_interior_mapping.cpp TraceWithoutDerivativesIsTheGradTrace). Cost: rk_im_trace_grad less
/// the derivative work: 138 SPIR-V instructions (spirv-opt -O), 11 scalar divisions.
RK_INLINE rk_im_hit rk_im_trace(vec3 p, vec3 cam, vec3 n, rk_im_grid g)
{
    return rk_im_detail_trace(p, cam, n, vec3(0.0f), vec3(0.0f), false, g);
}

/// rk_im_trace_varying_grad: the trace with walls (and floors, jitter.y) displaced per wall
/// index: wall k of axis i at k + rk_im_wall_offset(i, k, jitter_i, seed) room units, jitter in
/// [0, 1] (rk_im_jitter; 0 gives the regular grid up to the uv/room conventions). Exact two-candidate
/// rule (file header); room = the cell between the displaced walls; uv normalised across the
/// displaced room's actual width, [0, 1); derivatives as rk_im_trace_grad divided by that width.
/// Max error vs brute force over the displaced planes (200,000 random and adversarial rays,
/// tests/test_interior_mapping.cpp): 0 wrong families/rooms; hit position <= 6.1 * 2^-24 *
/// (4 + |q|) room units times 1/|d_family|, uv within 4.9e-6 (the displaced widths add a
/// subtraction and a division: about 3x rk_im_trace_grad's); derivatives within 2.9e-6 relative
/// of float64 finite differences across the displaced room. GPU parity as rk_im_trace_grad (up to
/// 4e3 ulp on the derivatives of grazing rays). Cost:
/// rk_im_trace_grad + 12 single-word hashes as 4 uvec3 hashes (the 3 keys, walls m - 1, m, m + 1:
/// hashing both neighbours keeps the hashes independent, which is faster on latency-bound SIMD
/// such as llvmpipe than hashing only the needed one after the test) and 3 divisions (the room
/// widths). SPIR-V (spirv-opt -O): 269 instructions.
RK_INLINE rk_im_hit rk_im_trace_varying_grad(vec3 p, vec3 cam, vec3 n, vec3 dp_dx, vec3 dp_dy, rk_im_grid g,
                                             vec3 jitter, uint seed)
{
    return rk_im_detail_trace_varying(p, cam, n, dp_dx, dp_dy, true, g, jitter, seed);
}

/// rk_im_trace_varying: rk_im_trace_varying_grad without derivatives (uv_dx = uv_dy = 0). Domain,
/// edge cases and max error: those of rk_im_trace_varying_grad, every other field bit-identical
/// to it (TraceWithoutDerivativesIsTheGradTrace). Cost: rk_im_trace_varying_grad less the
/// derivative work (the 12 hashes and 3 width divisions remain).
RK_INLINE rk_im_hit rk_im_trace_varying(vec3 p, vec3 cam, vec3 n, rk_im_grid g, vec3 jitter, uint seed)
{
    return rk_im_detail_trace_varying(p, cam, n, vec3(0.0f), vec3(0.0f), false, g, jitter, seed);
}

/// rk_im_trace_auto: the trace selected by RK_IM_VARYING_WALLS: 0 (default) rk_im_trace_grad
/// (jitter and seed unused, zero cost), 1 rk_im_trace_varying_grad. Shading code calls this one
/// so that varying room sizes are a compile-time switch.
RK_INLINE rk_im_hit rk_im_trace_auto(vec3 p, vec3 cam, vec3 n, vec3 dp_dx, vec3 dp_dy, rk_im_grid g, vec3 jitter,
                                     uint seed)
{
#if RK_IM_VARYING_WALLS
    return rk_im_trace_varying_grad(p, cam, n, dp_dx, dp_dy, g, jitter, seed);
#else
    RK_UNUSED(jitter);
    RK_UNUSED(seed);
    return rk_im_trace_grad(p, cam, n, dp_dx, dp_dy, g);
#endif
}
RK_CONFIGURED_END

#endif  // RK_INTERIOR_MAPPING_GLSL
