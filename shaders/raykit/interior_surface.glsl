// raykit — interior_surface.glsl: which texel a room hit samples, for each room-texture mode of
// interior_shading.glsl (RK_IM_SHADING): the surface kind (ceiling, floor, wall), the per-face
// variant, the texture-array layer, the padded-atlas coordinate and its LOD clamp, and the per-room
// cube map (layer, rotation, direction and its screen derivatives).
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/interior_surface.hpp. Tested
// against float64 brute force in tests/test_interior_surface.cpp (the cube direction against the
// hit face of a brute-force tracer of displaced rooms) and for GPU parity in
// tests/gpu/parity_interior.cpp. interior_shading.glsl only adds the texture fetches.
//
// Every function here is exact selection arithmetic (integer choices, or a few float operations
// whose rounding is stated); none has a NaN/Inf output for any finite input: the choices clamp
// their ranges and the atlas LOD clamp guards its division.
//
// @rk-es 310
// @rk-es300
#ifndef RK_INTERIOR_SURFACE_GLSL
#define RK_INTERIOR_SURFACE_GLSL

#include "interior_mapping.glsl"
#include "interior_compose.glsl"

// Seed XORed into the caller's seed for the per-room choices of the cube mode (cube: lane x,
// rotation: lane y of rk_im_room_lanes).
#define RK_IM_CUBE_SEED 0x7F4A7C15u

/// rk_im_surface_kind: the texture group of a hit: 0 ceiling (family 1, ray going up), 1 floor
/// (family 1, ray going down), 2 wall (families 0 and 2). Exact. Cost: 2 compares.
RK_INLINE int rk_im_surface_kind(rk_im_hit h) { return h.family == 1 ? (h.side > 0 ? 0 : 1) : 2; }

/// rk_im_variant: the variant index in [0, V) of a hit's face, V = max(floor(variants), 1):
/// floor(rk_im_face_random(room, family, side, seed) V), clamped to V - 1. Each face of each room
/// (a wall seen from its two rooms counts twice) draws independently and uniformly (to 2^-24).
/// Exact (bit-identical on CPU and GPU). Cost: 1 PCG3D hash, ~5 flops.
RK_INLINE float rk_im_variant(rk_im_hit h, float variants, uint seed)
{
    float v = max(floor(variants), 1.0f);
    return min(floor(rk_im_face_random(h.room, h.family, h.side, seed) * v), v - 1.0f);
}

/// rk_im_array_layer: the layer of a sampler2DArray of 3 V layers laid out [0, V) ceilings,
/// [V, 2V) floors, [2V, 3V) walls: kind V + variant, an integer in [0, 3V). Exact. Cost:
/// rk_im_variant + 2 flops.
RK_INLINE float rk_im_array_layer(rk_im_hit h, float variants, uint seed)
{
    float v = max(floor(variants), 1.0f);
    return float(rk_im_surface_kind(h)) * v + rk_im_variant(h, v, seed);
}

/// rk_im_atlas_uv: the atlas coordinate of uv in [0, 1) inside tile `index` of a padded atlas,
/// atlas = (grid, cell, pad, max_lod): grid x grid cells of `cell` texels, tile k in column
/// k mod grid, row floor(k / grid), its tile proper inset by `pad` texels on every side (pad
/// clamped to [0, cell / 2 - 1/2], grid and cell to >= 1). deriv_scale receives the factor that
/// maps uv derivatives to atlas derivatives, (cell - 2 pad) / (cell grid). Error: a few float
/// roundings (<= 2 ulp of the result for grid <= 64, tests/test_interior_surface.cpp). Cost: 1
/// div, 2 floor, ~12 flops.
RK_INLINE vec2 rk_im_atlas_uv(vec2 uv, float index, vec4 atlas, RK_OUT(float) deriv_scale)
{
    float grid = max(atlas.x, 1.0f);
    float cell = max(atlas.y, 1.0f);
    float pad = clamp(atlas.z, 0.0f, 0.5f * cell - 0.5f);
    float inner = (cell - 2.0f * pad) / cell;  // the tile proper's share of its cell
    float row = floor(index / grid);
    float col = index - grid * row;
    deriv_scale = inner / grid;
    return (vec2(col, row) + vec2(pad / cell) + inner * uv) / grid;
}

/// rk_im_atlas_grad_scale: the factor k in (0, 1] by which an atlas lookup's gradients dx, dy
/// (atlas uv units per pixel) are scaled so that the LOD the hardware picks (log2 of rho, the
/// larger gradient length in texels, isotropic filtering) stays <= max_lod = atlas.w (clamped to
/// [0, 16]): k = min(1, 2^max_lod / rho); k = 1 when rho <= 2^max_lod (then nothing changes).
/// Beyond max_lod the padded cells would mix tiles (interior_features.hpp's padding rule). Error:
/// log2(rho k) <= max_lod + 1e-6. Cost: 2 dot, 1 sqrt, 1 exp2, 1 div (only when clamping).
RK_INLINE float rk_im_atlas_grad_scale(vec2 dx, vec2 dy, vec4 atlas)
{
    float texels = max(atlas.x, 1.0f) * max(atlas.y, 1.0f);
    float rho = texels * sqrt(max(dot(dx, dx), dot(dy, dy)));
    float limit = exp2(clamp(atlas.w, 0.0f, 16.0f));
    return rho > limit ? limit / rho : 1.0f;
}

/// rk_im_cube_rotate: v rotated about +y by k * 90° (k in 0..3; other values: no rotation),
/// right-handed: k = 1 maps +z to +x and +x to -z. Exact (component swaps and negations).
/// Cost: 3 compares, selects.
RK_INLINE vec3 rk_im_cube_rotate(vec3 v, int k)
{
    if (k == 1) return vec3(v.z, v.y, -v.x);
    if (k == 2) return vec3(-v.x, v.y, -v.z);
    if (k == 3) return vec3(-v.z, v.y, v.x);
    return v;
}

/// A per-room cube-map lookup: direction and its screen derivatives (already rotated) and the
/// cube-array layer.
struct rk_im_cube_coord {
    vec3 dir;     // direction to sample: the hit in the room's own [-1, 1]^3 coordinates, rotated
    vec3 dx;      // d(dir)/dx, d(dir)/dy for textureGrad (samplerCubeArray takes vec3 gradients)
    vec3 dy;
    float layer;  // cube index in [0, N)
};

/// rk_im_cube_lookup: the lookup of the room's cube map for a hit: the hit point in the room's
/// normalised coordinates [-1, 1]^3, built from the hit face itself: the family's component is
/// the side (+1: the face toward +axis), the other two are 2 uv - 1 along the face's uv axes
/// (family 0: uv = (z, y); 1: (x, z); 2: (x, y)). Since uv spans the room actually hit, this is
/// exact for the regular grid and for displaced walls (RK_IM_VARYING_WALLS) alike, and the major
/// axis of dir is always the face hit (ties only on the room's edges). Derivatives: 2 uv_dx,
/// 2 uv_dy on the same axes (0 along the family). Then rotated per room about y by k * 90° and a
/// cube chosen per room: (layer, k) from rk_im_room_lanes(room, seed ^ RK_IM_CUBE_SEED) lanes x
/// and y (N = max(floor(count), 1) cubes). Error: dir within 1 ulp of 2 uv - 1 (uv's own error:
/// interior_mapping.glsl). Cost: 1 PCG3D hash, ~20 flops and selects.
RK_INLINE rk_im_cube_coord rk_im_cube_lookup(rk_im_hit h, float count, uint seed)
{
    float s = h.side > 0 ? 1.0f : -1.0f;
    vec2 a = 2.0f * h.uv - vec2(1.0f);
    vec2 gx = 2.0f * h.uv_dx;
    vec2 gy = 2.0f * h.uv_dy;
    vec3 dir = h.family == 0 ? vec3(s, a.y, a.x) : (h.family == 1 ? vec3(a.x, s, a.y) : vec3(a.x, a.y, s));
    vec3 dx = h.family == 0 ? vec3(0.0f, gx.y, gx.x) : (h.family == 1 ? vec3(gx.x, 0.0f, gx.y) : vec3(gx.x, gx.y, 0.0f));
    vec3 dy = h.family == 0 ? vec3(0.0f, gy.y, gy.x) : (h.family == 1 ? vec3(gy.x, 0.0f, gy.y) : vec3(gy.x, gy.y, 0.0f));
    vec3 lanes = rk_im_room_lanes(h.room, seed ^ RK_IM_CUBE_SEED);
    int k = int(min(floor(lanes.y * 4.0f), 3.0f));
    float n = max(floor(count), 1.0f);
    rk_im_cube_coord c;
    c.dir = rk_im_cube_rotate(dir, k);
    c.dx = rk_im_cube_rotate(dx, k);
    c.dy = rk_im_cube_rotate(dy, k);
    c.layer = min(floor(lanes.x * n), n - 1.0f);
    return c;
}

#endif  // RK_INTERIOR_SURFACE_GLSL
