// raykit — interior_furniture.glsl: furniture / character planes inside interior-mapped rooms: a
// virtual plane parallel to the facade at a chosen depth behind it, its ray fraction, UV per room,
// room index, screen-space UV derivatives, visibility against the room hit, several layers
// (nearest visible wins) and flipbook animation with a per-room phase.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/interior_furniture.hpp.
// Source: van Dongen 2009, "Using raycasting in GPU shaders to enhance real-time graphics",
// §5.2.4 (furniture plane, alpha test, animated textures); the plane equation, UVs and guards are
// derived here (the thesis gives no formula); layers and flipbooks are extensions beyond the thesis.
//
// Conventions (those of interior_mapping.glsl, same object space):
//   p    the shaded surface point, cam the camera, both in object space; the ray is
//        X(t) = cam + t (p - cam), t = 1 at the surface and t > 1 behind it (rk_im_hit.t).
//   n    the facade's outward normal (any length; normalised here), tangent and bitangent the
//        facade's frame (any length; normalised here), e.g. (1,0,0) and (0,1,0) for a +z facade.
//   depth  D >= 0, the plane's distance behind the surface along -n, in object units.
// The furniture plane is { X : dot(n, X - p) = -D }. With d = dot(n, p - cam) < 0 (camera outside):
//   t_f = 1 - D / d = 1 + D / |d|            (derived here; not in the thesis)
// The UV of the hit is its position on the facade frame in room units,
//   u = dot(X - origin, tangent) / dot(|tangent|, room_size),  v likewise with the bitangent,
// wrapped to [0, 1) so every room shows the sprite once (one tile per room when the frame is
// grid-aligned, which is the case for axis-aligned facades). The room is the grid cell of X.
// Domain (that of interior_mapping.glsl): coordinates and depth are clamped to +-RK_IM_COORD_MAX
// (1e15), room sizes to [RK_IM_ROOM_MIN, RK_IM_ROOM_MAX] (abs taken); every output is finite for every
// finite input. Planes farther than RK_IM_FURNITURE_Q_MAX times the camera-to-surface distance
// (grazing rays: d -> 0) are reported as not hit (valid = false, t = RK_IM_FURNITURE_T_NONE).
// Errors below are against the float64 ray-plane intersection in tests/test_interior_furniture.cpp.
//
// Feature macros:
//   RK_IM_FURNITURE_LAYERS  0..4 (default 0): how many furniture planes interior_shading.glsl's
//                           rk_im_shade_window() intersects and samples (0: the feature is compiled
//                           out). The functions below exist whatever its value.
//   RK_IM_FURNITURE_FLIPBOOK 0/1 (default 1): whether rk_im_shade_window() picks a flipbook frame
//                           per room (rk_im_flipbook_room_uv: 1 room hash, integer div/mod and
//                           ~20 flops per layer). 0: every sprite sheet is a single image (the
//                           sheet UV is the plane's uv; rk_im_window_params.flipbook, flipbook_fps
//                           and time are not read): set it when the sprites are not animated and
//                           have one cell; raykit::interior_defines emits it from
//                           InteriorSceneDesc::furniture_flipbook.
//
// @rk-es 310
// @rk-es300
// @rk-variants RK_IM_FURNITURE_LAYERS=0 | RK_IM_FURNITURE_LAYERS=1 | RK_IM_FURNITURE_LAYERS=4 | RK_IM_FURNITURE_LAYERS=2 RK_IM_FURNITURE_FLIPBOOK=0
#ifndef RK_INTERIOR_FURNITURE_GLSL
#define RK_INTERIOR_FURNITURE_GLSL

#include "common.glsl"
#include "interior_mapping.glsl"

#ifndef RK_IM_FURNITURE_LAYERS
#define RK_IM_FURNITURE_LAYERS 0
#endif
#if RK_IM_FURNITURE_LAYERS < 0 || RK_IM_FURNITURE_LAYERS > 4
#error "RK_IM_FURNITURE_LAYERS must be 0 (no furniture) or 1..4 (sprite planes)"
#endif
RK_OPTION_CHECK(rk_option_im_furniture_layers, RK_IM_FURNITURE_LAYERS);
#ifndef RK_IM_FURNITURE_FLIPBOOK
#define RK_IM_FURNITURE_FLIPBOOK 1
#endif
#if RK_IM_FURNITURE_FLIPBOOK < 0 || RK_IM_FURNITURE_FLIPBOOK > 1
#error "RK_IM_FURNITURE_FLIPBOOK must be 0 (one image per sprite sheet) or 1 (flipbooks)"
#endif
RK_OPTION_CHECK(rk_option_im_furniture_flipbook, RK_IM_FURNITURE_FLIPBOOK);

// Largest t - 1 of a reported hit: planes farther than 1e6 camera-to-surface distances are not hit.
#define RK_IM_FURNITURE_Q_MAX 1.0e6f
// t of a plane that is not hit (larger than any valid t).
#define RK_IM_FURNITURE_T_NONE 1.0e30f
// Largest |uv derivative| reported (room units per pixel).
#define RK_IM_FURNITURE_DUV_MAX 1.0e6f
// Largest flipbook sheet side (frames per row / rows) and frame count handled.
#define RK_IM_FLIPBOOK_SIDE_MAX 4096
#define RK_IM_FLIPBOOK_FRAMES_MAX 65536

/// The intersection of a view ray with one furniture plane (rk_im_furniture_plane*).
/// When valid is false (camera on the inner side of the facade, a ray parallel to it, or a plane
/// beyond RK_IM_FURNITURE_Q_MAX): t = RK_IM_FURNITURE_T_NONE, pos = p (clamped), uv = uv_dx =
/// uv_dy = 0, room = the cell of p.
struct rk_im_furniture_hit {
    float t;      // ray fraction of the hit, same convention as rk_im_hit.t (>= 1 when valid)
    vec2 uv;      // sprite UV in [0, 1): the hit's position on the facade frame in room units, wrapped
    vec2 uv_dx;   // screen-space derivatives of uv (analytic; continuous across room seams)
    vec2 uv_dy;
    ivec3 room;   // grid cell containing the hit (for per-room variation)
    vec3 pos;     // the hit point, object space
    bool valid;
};

/// rk_im_furniture_unit: v / |v| computed without overflow or underflow (scaled by its largest
/// component first); `fallback` when every component is below RK_FLT_MIN in magnitude.
/// Max error: 2 ulp per component. Branch-free (a select at the end: SIMD rasterisers run both
/// sides of a branch). Cost: 3 abs, 3 max, 3 div, 1 dot, 1 inversesqrt, 1 select.
RK_INLINE vec3 rk_im_furniture_unit(vec3 v, vec3 fallback)
{
    float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    vec3 s = rk_div3(v, max(m, RK_FLT_MIN));  // rk_div3: m may exceed 2^126
    // With m >= RK_FLT_MIN the largest |s_i| is exactly 1, so dot(s, s) is in [1, 3]; the floor
    // only keeps the unused side finite for the zero vector.
    vec3 u = s * inversesqrt(max(dot(s, s), 1.0f));
    return m >= RK_FLT_MIN ? u : fallback;
}

/// rk_im_furniture_clamp_coord: each component clamped to +-RK_IM_COORD_MAX (1e15, the domain of
/// interior_mapping.glsl). Exact.
RK_INLINE vec3 rk_im_furniture_clamp_coord(vec3 v)
{
    return clamp(v, vec3(-RK_IM_COORD_MAX), vec3(RK_IM_COORD_MAX));
}

/// rk_im_furniture_wrap: x - floor(x) kept inside [0, 1) (x - floor(x) rounds to 1.0 for tiny
/// negative x; that case returns the largest float below 1). Exact otherwise. Cost: 1 floor, 1 min.
RK_INLINE float rk_im_furniture_wrap(float x) { return min(x - floor(x), 0.99999994f); }

/// The per-pixel part of the furniture-plane intersection, shared by every plane (layer) of one
/// pixel: only the plane depth differs between layers (rk_im_furniture_setup builds it once,
/// rk_im_furniture_layer intersects one plane). Fields (all finite for finite inputs):
struct rk_im_furniture_ray {
    vec3 p;         // the surface point, clamped to +-RK_IM_COORD_MAX
    vec3 v;         // p - cam (both clamped), |components| <= 2e15
    vec3 n;         // unit facade normal (0 for a zero normal: no plane is then hit)
    vec3 tangent;   // unit frame
    vec3 bitangent;
    vec3 origin;    // the grid origin, clamped
    vec2 width;     // room widths along tangent and bitangent, dot(|frame|, room_size), >= RK_IM_ROOM_MIN
    float e;        // -dot(n, ray): |d| of the file header, > 0 when the camera is outside
    float inv_e;    // 1 / e when e > 1e-30, else 0
    vec2 ray_tb;    // (dot(v, tangent), dot(v, bitangent))
    vec2 dx_tb;     // (dot(dp_dx, tangent), dot(dp_dx, bitangent)), dp_dx clamped to +-RK_IM_COORD_MAX
    vec2 dy_tb;
    vec2 n_dxy;     // (dot(n, dp_dx), dot(n, dp_dy))
};

/// rk_im_furniture_setup: the frame normalisations, clamps and projections of
/// rk_im_furniture_plane_grad that do not depend on the plane depth, computed once per pixel for
/// any number of planes (arguments as in rk_im_furniture_plane_grad; n, tangent, bitangent of any
/// length). Exact up to the roundings of the normalisations (2 ulp per component) and of the dot
/// products. Cost: 3 normalisations (rk_im_furniture_unit), 1 div, ~50 flops.
RK_INLINE rk_im_furniture_ray rk_im_furniture_setup(vec3 p, vec3 cam, vec3 n, vec3 tangent, vec3 bitangent, vec3 dp_dx,
                                                   vec3 dp_dy, rk_im_grid g)
{
    rk_im_furniture_ray r;
    r.p = rk_im_furniture_clamp_coord(p);
    r.v = r.p - rk_im_furniture_clamp_coord(cam);
    r.n = rk_im_furniture_unit(n, vec3(0.0f));
    r.tangent = rk_im_furniture_unit(tangent, vec3(1.0f, 0.0f, 0.0f));
    r.bitangent = rk_im_furniture_unit(bitangent, vec3(0.0f, 1.0f, 0.0f));
    vec3 size = clamp(abs(g.room_size), vec3(RK_IM_ROOM_MIN), vec3(RK_IM_ROOM_MAX));
    r.origin = rk_im_furniture_clamp_coord(g.origin);
    r.width = vec2(max(dot(abs(r.tangent), size), RK_IM_ROOM_MIN), max(dot(abs(r.bitangent), size), RK_IM_ROOM_MIN));
    r.e = -dot(r.n, r.v);
    r.inv_e = r.e > 1.0e-30f ? 1.0f / r.e : 0.0f;   // <= 1e30
    vec3 dx = rk_im_furniture_clamp_coord(dp_dx);
    vec3 dy = rk_im_furniture_clamp_coord(dp_dy);
    r.ray_tb = vec2(dot(r.v, r.tangent), dot(r.v, r.bitangent));
    r.dx_tb = vec2(dot(dx, r.tangent), dot(dx, r.bitangent));
    r.dy_tb = vec2(dot(dy, r.tangent), dot(dy, r.bitangent));
    r.n_dxy = vec2(dot(r.n, dx), dot(r.n, dy));
    return r;
}

/// rk_im_furniture_layer: the plane `depth` object units behind the facade for the pixel of
/// rk_im_furniture_setup (the per-layer part of rk_im_furniture_plane_grad; same results, same
/// errors, same not-hit rules). The uv derivatives are combined from the per-pixel projections:
/// dot(d(pos), frame) = (1 + q) dot(dp, frame) + dq dot(p - cam, frame).
/// Cost: 1 div, 1 room lookup (rk_im_room_at: 3 div), ~30 flops.
RK_INLINE rk_im_furniture_hit rk_im_furniture_layer(rk_im_furniture_ray r, float depth, rk_im_grid g)
{
    float D = clamp(depth, 0.0f, RK_IM_COORD_MAX);
    bool valid = r.e > max(D * (1.0f / RK_IM_FURNITURE_Q_MAX), 1.0e-30f);
    float q = valid ? D / r.e : 0.0f;      // in [0, 1e6]

    rk_im_furniture_hit h;
    h.valid = valid;
    h.t = valid ? 1.0f + q : RK_IM_FURNITURE_T_NONE;
    h.pos = r.p + q * r.v;
    vec3 rel = h.pos - r.origin;
    h.uv = valid ? vec2(rk_im_furniture_wrap(dot(rel, r.tangent) / r.width.x),
                        rk_im_furniture_wrap(dot(rel, r.bitangent) / r.width.y))
                 : vec2(0.0f);
    h.room = rk_im_room_at(h.pos, g);

    // Derivatives: every intermediate clamped so that no finite input overflows.
    float qe = min(q * r.inv_e, 1.0e20f);  // q / |d| <= 1e36, capped so dot * qe <= 2e35
    float dqx = clamp(r.n_dxy.x * qe, -RK_IM_COORD_MAX, RK_IM_COORD_MAX);
    float dqy = clamp(r.n_dxy.y * qe, -RK_IM_COORD_MAX, RK_IM_COORD_MAX);
    // |(1 + q) dot(dp, frame)| <= 2e21, |dq dot(ray, frame)| <= 3.5e30; clamp to DUV_MAX room
    // widths before dividing by the width.
    vec2 lim = RK_IM_FURNITURE_DUV_MAX * r.width;
    vec2 gx = (1.0f + q) * r.dx_tb + dqx * r.ray_tb;
    vec2 gy = (1.0f + q) * r.dy_tb + dqy * r.ray_tb;
    h.uv_dx = valid ? clamp(gx, -lim, lim) / r.width : vec2(0.0f);
    h.uv_dy = valid ? clamp(gy, -lim, lim) / r.width : vec2(0.0f);
    return h;
}

/// rk_im_furniture_plane_grad: the furniture plane `depth` object units behind the facade (outward
/// normal n, frame tangent/bitangent) hit by the ray from cam through p, with analytic screen-space
/// derivatives of its UV from dp_dx, dp_dy (dFdx/dFdy of the object-space position p):
///   t = 1 + q, q = D / |d|, d = dot(n, p - cam) < 0;  pos = p + q (p - cam);
///   d(pos) = (1 + q) dp + q dot(n, dp) / |d| (p - cam)    (q depends on p through d).
/// uv derivatives are those of the unwrapped (continuous) coordinates, so textureGrad with them
/// has no seam at room boundaries; clamped to +-RK_IM_FURNITURE_DUV_MAX.
/// Not hit (valid = false): d >= 0 (camera inside or exactly grazing), |d| <= 1e-30, or
/// q > RK_IM_FURNITURE_Q_MAX (see struct). D = 0 is the plane of the facade itself: t = 1.
/// It is rk_im_furniture_layer(rk_im_furniture_setup(...), depth, g): for several planes per pixel
/// call those two directly (the setup once), as rk_im_shade_window does.
/// Max error vs float64 (200,000 random rays, |p| <= 70, camera 0.5 to 200 units away, rotated and
/// axis-aligned facades): t 3.6 ulp, pos 5.4e-6 object units, uv 3.2e-6 room units, uv
/// derivatives 3.2e-7 relative (tests/test_interior_furniture.cpp).
/// Cost: 3 normalisations, 2 div + 3 in the room lookup, ~80 flops (of which ~30 per extra plane
/// through rk_im_furniture_layer).
RK_INLINE rk_im_furniture_hit rk_im_furniture_plane_grad(vec3 p, vec3 cam, vec3 n, vec3 tangent, vec3 bitangent,
                                                         float depth, vec3 dp_dx, vec3 dp_dy, rk_im_grid g)
{
    return rk_im_furniture_layer(rk_im_furniture_setup(p, cam, n, tangent, bitangent, dp_dx, dp_dy, g), depth, g);
}

/// rk_im_furniture_plane: rk_im_furniture_plane_grad without derivatives (uv_dx = uv_dy = 0).
/// Same domain and errors.
RK_INLINE rk_im_furniture_hit rk_im_furniture_plane(vec3 p, vec3 cam, vec3 n, vec3 tangent, vec3 bitangent, float depth,
                                                    rk_im_grid g)
{
    rk_im_furniture_hit h = rk_im_furniture_plane_grad(p, cam, n, tangent, bitangent, depth, vec3(0.0f), vec3(0.0f), g);
    h.uv_dx = vec2(0.0f);
    h.uv_dy = vec2(0.0f);
    return h;
}

/// rk_im_furniture_visible: whether a furniture sample is drawn in front of the room: the plane is
/// hit, strictly nearer than the room surface (t < room_t, room_t = rk_im_hit.t; a room wall in
/// front of the plane hides it) and the sprite's alpha exceeds the threshold (alpha test, thesis
/// §5.2.4). Exact. Cost: 3 compares.
RK_INLINE bool rk_im_furniture_visible(rk_im_furniture_hit f, float room_t, float alpha, float threshold)
{
    return f.valid && f.t < room_t && alpha > threshold;
}

/// rk_im_furniture_take: the layer loop's step for several planes (RK_IM_FURNITURE_LAYERS): when
/// layer f with sprite alpha `alpha` is visible in front of `nearest_t` (initialise it with the
/// room hit's t), sets nearest_t = f.t and returns true (the caller then keeps this layer's
/// colour). After all layers, the nearest visible layer has won, whatever the order of the loop.
/// Exact. Cost: 4 compares.
RK_INLINE bool rk_im_furniture_take(rk_im_furniture_hit f, float alpha, float threshold, RK_INOUT(float) nearest_t)
{
    bool take = rk_im_furniture_visible(f, nearest_t, alpha, threshold);
    nearest_t = take ? f.t : nearest_t;
    return take;
}

/// rk_im_flipbook_frame: the frame shown at `time` (seconds) of a `frame_count`-frame loop played
/// at `fps` frames per second, offset by `phase` in [0, 1) of the loop (e.g. rk_im_room_random so
/// rooms do not animate in lockstep):
///   frame = (floor(time fps) mod count + floor(phase count)) mod count, in [0, count).
/// The mod is the floored one, so negative time loops backwards continuously (time = -1/fps shows
/// frame count - 1). Exact for |time fps| < 2^24; beyond, float time has no frame resolution left
/// and the result is some frame in range. frame_count clamped to [1, 65536], time to +-1e30, fps
/// to [0, 1e6], phase to [0, 1]; a product time * fps below RK_FLT_MIN in magnitude counts as 0
/// (frame 0 of the loop), as on drivers that flush denormals. Cost: 2 floor, 1 div, ~12 ops.
RK_INLINE int rk_im_flipbook_frame(float time, float fps, int frame_count, float phase)
{
    int count = clamp(frame_count, 1, RK_IM_FLIPBOOK_FRAMES_MAX);
    float fc = float(count);
    float x = clamp(time, -1.0e30f, 1.0e30f) * clamp(fps, 0.0f, 1.0e6f);
    float f = floor(abs(x) < RK_FLT_MIN ? 0.0f : x);
    float m = f - fc * floor(f / fc);
    // The division may round across an integer (and GPUs divide to 2.5 ulp): fix by one period.
    m = m < 0.0f ? m + fc : m;
    m = m >= fc ? m - fc : m;
    int frame = int(clamp(m, 0.0f, fc - 1.0f));
    int offset = int(clamp(floor(rk_saturate(phase) * fc), 0.0f, fc - 1.0f));
    return (frame + offset) % count;
}

/// rk_im_flipbook_uv: the sheet UV of `uv` (in [0, 1), clamped) inside frame `frame` of a sheet of
/// cols x rows frames, frames in row-major order starting at texture coordinate (0, 0): frame k is
/// in column k mod cols, row k / cols, rows counted along +v. (An image uploaded top row first, as
/// stb_image loads it, has its top row at v = 0, so frame 0 is its top-left cell.)
/// cols, rows clamped to [1, 4096], frame to [0, cols rows - 1]. Max error: 1 ulp (one division).
/// Cost: 2 int div/mod, 2 div.
RK_INLINE vec2 rk_im_flipbook_uv(vec2 uv, int frame, int cols, int rows)
{
    int c = clamp(cols, 1, RK_IM_FLIPBOOK_SIDE_MAX);
    int r = clamp(rows, 1, RK_IM_FLIPBOOK_SIDE_MAX);
    int k = clamp(frame, 0, c * r - 1);
    int col = k % c;
    int row = k / c;
    return vec2((float(col) + rk_saturate(uv.x)) / float(c), (float(row) + rk_saturate(uv.y)) / float(r));
}

/// rk_im_flipbook_room_uv: the sprite-sheet UV of a furniture hit in room `room`: the frame of
/// rk_im_flipbook_frame(time, fps, frame_count, rk_im_room_random(room, seed)) then
/// rk_im_flipbook_uv. Derivatives for textureGrad: the hit's uv_dx / uv_dy divided by (cols, rows).
/// Cost: 1 room hash + the two above.
RK_INLINE vec2 rk_im_flipbook_room_uv(vec2 uv, ivec3 room, float time, float fps, int frame_count, int cols, int rows,
                                      uint seed)
{
    int frame = rk_im_flipbook_frame(time, fps, frame_count, rk_im_room_random(room, seed));
    return rk_im_flipbook_uv(uv, frame, cols, rows);
}

#endif  // RK_INTERIOR_FURNITURE_GLSL
