// raykit — interior_mapping.glsl: interior mapping (van Dongen 2008/2009): perspective-correct
// rooms behind a building's windows, by casting the view ray against virtual, regularly spaced,
// infinite planes (floors/ceilings of constant y, walls of constant x and of constant z) in the
// pixel shader of the building's exterior. Constant time per pixel, no interior geometry.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/interior_mapping.hpp, which
// adds CPU helpers (camera_to_object_space, room_grid_for_building, room_at, lit_fraction).
// Source: van Dongen's thesis ch. 5 + appendix; seed000.md §2 lists the thesis's bugs fixed here.
//
// THE MODEL. All work is in the building's object space. A grid (rk_im_grid) places planes of
// axis i at origin_i + k * room_size_i, k integer; "grid units" below are room units,
// q = (x - origin) / room_size. The ray is X(t) = cam + t (p - cam): p is the shaded point on
// the exterior surface (t = 1), n its outward normal. The hit is the nearest of the three
// "next planes" beyond p, one per axis, found in constant time.
//
// WHAT IS FIXED RELATIVE TO THE THESIS (seed000.md §2.9-2.10):
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
//    No field is ever Inf or NaN, for any finite input (inputs are clamped, see the domains).
//  * Camera on the inner side of the surface (dot(n, p - cam) >= 0), a zero normal (max |n_i| <
//    1e-30), or a camera within 1e-20 room units of p: valid = false, and the documented defaults
//    t = 1, depth = 0, family = 1, side = -1, room = rk_im_room_at(p), uv = uv_dx = uv_dy = 0,
//    pos = p.
//  * Room index from the chosen next-plane index per axis (seed000.md §2.9): room_i = plane_i - 1
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
// the ray, else wall m + s: exact (two candidates, seed000.md §2.8c), verified against a brute
// force search in the test. The thesis's literal previous/next pair is wrong for about one ray in
// four (the test ports it and prints the count). The room index is that of the cell between
// walls k and k+1; uv is normalised across the displaced room, [0, 1) over its actual width.
//
// Feature macros:
//   RK_IM_VARYING_WALLS  0 (default): rk_im_trace_auto() is rk_im_trace_grad() (regular grid,
//       jitter and seed unused: zero cost). 1: rk_im_trace_auto() is rk_im_trace_varying_grad()
//       (walls displaced per wall index; 3 single-word hashes per axis, ~30 integer ops more).
//       rk_im_trace_varying() and rk_im_trace_grad() themselves are always available.
//   RK_IM_NUDGE  the facade-nudge distance in room units (default 2^-10). Larger values skip
//       planes further behind a facade; it must exceed the interpolation jitter of p in room units
//       (a few ulps of |q|) and stay far below 1.
//
// Domains (inputs are clamped into them, so no finite input produces Inf/NaN): |p|, |cam|,
// |origin| components <= 1e15; room_size components in [1e-4, 1e6] (abs taken); grid coordinates
// clamped to +-2^30 (exact plane/room selection needs |q| < 2^22 rooms); dp_dx/dp_dy components
// clamped to +-1e10 room units; derivative outputs clamped to +-1e30.
//
// @rk-es 310
// @rk-variants RK_IM_VARYING_WALLS=0 | RK_IM_VARYING_WALLS=1 | RK_IM_VARYING_WALLS=1 RK_IM_NUDGE=0.001f
#ifndef RK_INTERIOR_MAPPING_GLSL
#define RK_INTERIOR_MAPPING_GLSL

#include "common.glsl"
#include "hash.glsl"

#ifndef RK_IM_VARYING_WALLS
#define RK_IM_VARYING_WALLS 0
#endif
#ifndef RK_IM_NUDGE
#define RK_IM_NUDGE 0.0009765625f
#endif

// Per-family ray distance (room units) of a family the ray runs parallel to.
#define RK_IM_T_SENTINEL 1e30f
// |normalised direction component| below this (2^-50) counts as parallel.
#define RK_IM_PARALLEL 8.8817841970012523e-16f
// Camera closer than this to p (room units, max-norm): degenerate ray, valid = false.
#define RK_IM_DIR_MIN 1e-20f
#define RK_IM_COORD_MAX 1e15f
#define RK_IM_GRID_MAX 1073741824.0f
#define RK_IM_ROOM_MIN 1e-4f
#define RK_IM_ROOM_MAX 1e6f
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
/// room_size with the documented clamps (|x| <= 1e15, room_size in [1e-4, 1e6], result within
/// +-2^30). Exact up to one rounding of the subtraction and one of the division. Cost: 3 sub,
/// 3 div, clamps.
RK_INLINE vec3 rk_im_grid_coord(vec3 x, rk_im_grid g)
{
    vec3 rs = clamp(abs(g.room_size), vec3(RK_IM_ROOM_MIN), vec3(RK_IM_ROOM_MAX));
    vec3 o = clamp(g.origin, vec3(-RK_IM_COORD_MAX), vec3(RK_IM_COORD_MAX));
    vec3 xc = clamp(x, vec3(-RK_IM_COORD_MAX), vec3(RK_IM_COORD_MAX));
    return clamp((xc - o) / rs, vec3(-RK_IM_GRID_MAX), vec3(RK_IM_GRID_MAX));
}

/// rk_im_room_at: the grid cell containing the object-space point p: floor of its grid
/// coordinates (a point exactly on a plane belongs to the cell on the plane's + side). Domain:
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

/// rk_im_wall_offset: the displacement, in room units in [0, 1), of wall k of axis (0 x, 1 y,
/// 2 z) in the varying-walls model: clamp(jitter, 0, 1) * rk_u32_to_unit(rk_hash_u32(uint(k) ^
/// key(axis, seed))). A function of the wall index only, so each wall plane moves as a whole.
/// Exact (bit-identical on CPU/GPU). Cost: 2 rk_hash_u32 (the key is shared between calls after
/// common-subexpression elimination).
RK_INLINE float rk_im_wall_offset(int axis, int k, float jitter, uint seed)
{
    uint key = rk_hash_u32(seed + uint(axis) * 2654435769u);
    return clamp(jitter, 0.0f, 1.0f) * rk_u32_to_unit(rk_hash_u32(uint(k) ^ key));
}

/// rk_im_room_at_varying: the cell containing p when walls are displaced (rk_im_trace_varying's
/// model): per axis m = floor(q), then m - 1 if q lies before wall m (q < m + delta(m)).
/// Cost: rk_im_grid_coord + 3 rk_im_wall_offset.
RK_INLINE ivec3 rk_im_room_at_varying(vec3 p, rk_im_grid g, vec3 jitter, uint seed)
{
    vec3 q = rk_im_grid_coord(p, g);
    vec3 m = floor(q);
    ivec3 r = ivec3(m);
    if (q.x < m.x + rk_im_wall_offset(0, r.x, jitter.x, seed)) r.x -= 1;
    if (q.y < m.y + rk_im_wall_offset(1, r.y, jitter.y, seed)) r.y -= 1;
    if (q.z < m.z + rk_im_wall_offset(2, r.z, jitter.z, seed)) r.z -= 1;
    return r;
}

// ---- implementation details (not part of the API) ----------------------------------------------

/// Whether the ray counts as travelling toward +axis: d >= -2^-50, so a parallel component (0,
/// -0, denormal, flushed or not) always counts as +, identically on every backend.
RK_INLINE bool rk_im_detail_up(float d) { return d >= -RK_IM_PARALLEL; }

/// Common setup: clamped inputs, grid coordinates q, the nudged q', the direction d normalised
/// to max |d_i| = 1 (grid units), its scale D (so p - cam = D d room_size) and validity.
RK_INLINE void rk_im_detail_setup(vec3 p, vec3 cam, vec3 n, rk_im_grid g, RK_OUT(vec3) q, RK_OUT(vec3) qn,
                                  RK_OUT(vec3) d, RK_OUT(float) dscale, RK_OUT(bool) valid)
{
    vec3 rs = clamp(abs(g.room_size), vec3(RK_IM_ROOM_MIN), vec3(RK_IM_ROOM_MAX));
    vec3 pc = clamp(p, vec3(-RK_IM_COORD_MAX), vec3(RK_IM_COORD_MAX));
    vec3 cc = clamp(cam, vec3(-RK_IM_COORD_MAX), vec3(RK_IM_COORD_MAX));
    q = rk_im_grid_coord(p, g);
    vec3 e = (pc - cc) / rs;
    float dmax = max(max(abs(e.x), abs(e.y)), abs(e.z));
    dscale = dmax;
    d = e / max(dmax, RK_IM_DIR_MIN);
    float nmax = max(max(abs(n.x), abs(n.y)), abs(n.z));
    vec3 nn = n / max(nmax, 1e-30f);
    valid = nmax >= 1e-30f && dmax >= RK_IM_DIR_MIN && dot(nn, pc - cc) < 0.0f;
    vec3 s = vec3(rk_im_detail_up(d.x) ? 1.0f : -1.0f, rk_im_detail_up(d.y) ? 1.0f : -1.0f,
                  rk_im_detail_up(d.z) ? 1.0f : -1.0f);
    vec3 inward = vec3(nn.x * s.x < -1e-6f ? 1.0f : 0.0f, nn.y * s.y < -1e-6f ? 1.0f : 0.0f,
                       nn.z * s.z < -1e-6f ? 1.0f : 0.0f);
    qn = q + (RK_IM_NUDGE * s) * inward;
}

/// Regular grid, one axis: the cell the ray is in after q' and the next plane strictly beyond q'.
RK_INLINE void rk_im_detail_axis(float qn, float d, RK_OUT(float) room, RK_OUT(float) plane, RK_OUT(float) lo,
                                 RK_OUT(float) width)
{
    bool up = rk_im_detail_up(d);
    room = up ? floor(qn) : ceil(qn) - 1.0f;
    plane = up ? room + 1.0f : room;
    lo = room;
    width = 1.0f;
}

/// Displaced walls, one axis: the two-candidate rule {m, m + s}, m = floor(q') (exact for
/// offsets in [0, 1)); lo/width: the displaced room's lower wall and width along the axis.
RK_INLINE void rk_im_detail_axis_varying(float qn, float d, int axis, float jitter, uint seed, RK_OUT(float) room,
                                         RK_OUT(float) plane, RK_OUT(float) lo, RK_OUT(float) width)
{
    float m = floor(qn);
    int mi = int(m);
    float w_prev = (m - 1.0f) + rk_im_wall_offset(axis, mi - 1, jitter, seed);
    float w_m = m + rk_im_wall_offset(axis, mi, jitter, seed);
    float w_next = (m + 1.0f) + rk_im_wall_offset(axis, mi + 1, jitter, seed);
    bool up = rk_im_detail_up(d);
    float s = up ? 1.0f : -1.0f;
    bool take_m = (w_m - qn) * s > 0.0f;
    bool lower = take_m == up;  // the ray is in cell m - 1
    room = lower ? m - 1.0f : m;
    plane = take_m ? w_m : (up ? w_next : w_prev);
    lo = lower ? w_prev : w_m;
    float hi = lower ? w_m : w_next;
    width = max(hi - lo, 1.0e-6f);
}

/// Picks the nearest family and fills the hit. All per-axis inputs in grid units.
RK_INLINE rk_im_hit rk_im_detail_finish(vec3 p, vec3 cam, rk_im_grid g, vec3 dp_dx, vec3 dp_dy, vec3 q, vec3 d,
                                        float dscale, bool valid, vec3 room, vec3 plane, vec3 lo, vec3 width)
{
    vec3 rs = clamp(abs(g.room_size), vec3(RK_IM_ROOM_MIN), vec3(RK_IM_ROOM_MAX));
    vec3 o = clamp(g.origin, vec3(-RK_IM_COORD_MAX), vec3(RK_IM_COORD_MAX));
    vec3 pc = clamp(p, vec3(-RK_IM_COORD_MAX), vec3(RK_IM_COORD_MAX));
    RK_UNUSED(cam);
    vec3 delta = plane - q;
    vec3 f = vec3(abs(d.x) >= RK_IM_PARALLEL ? max(delta.x / d.x, 0.0f) : RK_IM_T_SENTINEL,
                  abs(d.y) >= RK_IM_PARALLEL ? max(delta.y / d.y, 0.0f) : RK_IM_T_SENTINEL,
                  abs(d.z) >= RK_IM_PARALLEL ? max(delta.z / d.z, 0.0f) : RK_IM_T_SENTINEL);
    // Nearest family; ties go to the x wall over the z wall over the floor/ceiling (thesis).
    int fam = 0;
    float fd = f.x;
    if (f.z < fd) {
        fam = 2;
        fd = f.z;
    }
    if (f.y < fd) {
        fam = 1;
        fd = f.y;
    }
    vec3 qh = q + fd * d;
    float dfam = fam == 0 ? d.x : (fam == 1 ? d.y : d.z);
    float t = max(1.0f + fd / max(dscale, RK_IM_DIR_MIN), RK_IM_T_MIN);

    rk_im_hit h;
    h.valid = valid;
    h.t = t;
    h.depth = fd * length(d * rs);
    h.family = fam;
    h.side = dfam >= 0.0f ? 1 : -1;
    h.room = ivec3(room);
    vec3 pos = pc + (fd * d) * rs;
    if (fam == 0) pos.x = o.x + plane.x * rs.x;
    if (fam == 1) pos.y = o.y + plane.y * rs.y;
    if (fam == 2) pos.z = o.z + plane.z * rs.z;
    h.pos = pos;
    vec3 uvw = (qh - lo) / width;
    vec2 uv = fam == 0 ? vec2(uvw.z, uvw.y) : (fam == 1 ? vec2(uvw.x, uvw.z) : vec2(uvw.x, uvw.y));
    h.uv = clamp(uv, vec2(0.0f), vec2(RK_IM_UV_MAX));
    // d(hit) = t (dq - d dq_i / d_i) on the chosen plane i (grid units), then / width.
    vec3 dqx = clamp(dp_dx / rs, vec3(-RK_IM_DQ_MAX), vec3(RK_IM_DQ_MAX));
    vec3 dqy = clamp(dp_dy / rs, vec3(-RK_IM_DQ_MAX), vec3(RK_IM_DQ_MAX));
    float inv_di = 1.0f / (dfam >= 0.0f ? max(dfam, RK_IM_PARALLEL) : min(dfam, -RK_IM_PARALLEL));
    float kx = (fam == 0 ? dqx.x : (fam == 1 ? dqx.y : dqx.z)) * inv_di;
    float ky = (fam == 0 ? dqy.x : (fam == 1 ? dqy.y : dqy.z)) * inv_di;
    float tt = min(t, 1e12f);
    vec3 hx = (tt * (dqx - d * kx)) / width;
    vec3 hy = (tt * (dqy - d * ky)) / width;
    vec2 ux = fam == 0 ? vec2(hx.z, hx.y) : (fam == 1 ? vec2(hx.x, hx.z) : vec2(hx.x, hx.y));
    vec2 uy = fam == 0 ? vec2(hy.z, hy.y) : (fam == 1 ? vec2(hy.x, hy.z) : vec2(hy.x, hy.y));
    h.uv_dx = clamp(ux, vec2(-RK_IM_DERIV_MAX), vec2(RK_IM_DERIV_MAX));
    h.uv_dy = clamp(uy, vec2(-RK_IM_DERIV_MAX), vec2(RK_IM_DERIV_MAX));
    if (!valid) {
        h.t = 1.0f;
        h.depth = 0.0f;
        h.family = 1;
        h.side = -1;
        h.room = ivec3(floor(q));
        h.uv = vec2(0.0f);
        h.uv_dx = vec2(0.0f);
        h.uv_dy = vec2(0.0f);
        h.pos = pc;
    }
    return h;
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
/// analytic derivatives within 1.2e-6 relative of finite differences. GPU parity (llvmpipe):
/// 2 ulp. Cost: 3 + 6 (derivatives) divisions, ~60 ALU, no loops, no texture; constant
/// whatever the number of rooms.
RK_INLINE rk_im_hit rk_im_trace_grad(vec3 p, vec3 cam, vec3 n, vec3 dp_dx, vec3 dp_dy, rk_im_grid g)
{
    vec3 q, qn, d;
    float dscale;
    bool valid;
    rk_im_detail_setup(p, cam, n, g, q, qn, d, dscale, valid);
    vec3 room, plane, lo, width;
    rk_im_detail_axis(qn.x, d.x, room.x, plane.x, lo.x, width.x);
    rk_im_detail_axis(qn.y, d.y, room.y, plane.y, lo.y, width.y);
    rk_im_detail_axis(qn.z, d.z, room.z, plane.z, lo.z, width.z);
    return rk_im_detail_finish(p, cam, g, dp_dx, dp_dy, q, d, dscale, valid, room, plane, lo, width);
}

/// rk_im_trace: rk_im_trace_grad without derivatives (uv_dx = uv_dy = 0; the compiler drops
/// their arithmetic). Use with textureLod or when the interior is not mip-mapped.
RK_INLINE rk_im_hit rk_im_trace(vec3 p, vec3 cam, vec3 n, rk_im_grid g)
{
    return rk_im_trace_grad(p, cam, n, vec3(0.0f), vec3(0.0f), g);
}

/// rk_im_trace_varying_grad: the trace with walls (and floors, jitter.y) displaced per wall
/// index: wall k of axis i at k + rk_im_wall_offset(i, k, jitter_i, seed) room units, jitter in
/// [0, 1] (clamped; 0 gives the regular grid up to the uv/room conventions). Exact two-candidate
/// rule (file header); room = the cell between the displaced walls; uv normalised across the
/// displaced room's actual width, [0, 1); derivatives as rk_im_trace_grad divided by that width.
/// Max error vs brute force over the displaced planes: as rk_im_trace_grad. Cost:
/// rk_im_trace_grad + 9 wall offsets (each one rk_hash_u32 once the per-axis keys are shared).
RK_INLINE rk_im_hit rk_im_trace_varying_grad(vec3 p, vec3 cam, vec3 n, vec3 dp_dx, vec3 dp_dy, rk_im_grid g,
                                             vec3 jitter, uint seed)
{
    vec3 q, qn, d;
    float dscale;
    bool valid;
    rk_im_detail_setup(p, cam, n, g, q, qn, d, dscale, valid);
    vec3 room, plane, lo, width;
    rk_im_detail_axis_varying(qn.x, d.x, 0, jitter.x, seed, room.x, plane.x, lo.x, width.x);
    rk_im_detail_axis_varying(qn.y, d.y, 1, jitter.y, seed, room.y, plane.y, lo.y, width.y);
    rk_im_detail_axis_varying(qn.z, d.z, 2, jitter.z, seed, room.z, plane.z, lo.z, width.z);
    rk_im_hit h = rk_im_detail_finish(p, cam, g, dp_dx, dp_dy, q, d, dscale, valid, room, plane, lo, width);
    if (!valid) h.room = rk_im_room_at_varying(p, g, jitter, seed);
    return h;
}

/// rk_im_trace_varying: rk_im_trace_varying_grad without derivatives (uv_dx = uv_dy = 0).
RK_INLINE rk_im_hit rk_im_trace_varying(vec3 p, vec3 cam, vec3 n, rk_im_grid g, vec3 jitter, uint seed)
{
    return rk_im_trace_varying_grad(p, cam, n, vec3(0.0f), vec3(0.0f), g, jitter, seed);
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

#endif  // RK_INTERIOR_MAPPING_GLSL
