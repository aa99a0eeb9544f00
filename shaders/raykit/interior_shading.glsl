// raykit — interior_shading.glsl: the GLSL-only (texture-sampling) half of interior mapping: room
// surfaces from four textures, a texture array, a padded atlas or a cube map per room; furniture
// sprite layers; and rk_im_shade_window(), which puts trace + shading + furniture + room lights +
// fade + glass + composition together under the feature macros.
// The maths is in the shared files (interior_mapping.glsl, interior_furniture.glsl,
// interior_compose.glsl, interior_surface.glsl), tested on the CPU and for GPU parity; this file
// only samples.
// samples/common/interior_building.frag is a complete material built on it.
//
// Every fetch is a textureGrad with the analytic derivatives of the trace (rk_im_hit.uv_dx/uv_dy,
// rk_im_furniture_hit.uv_dx/uv_dy), which are continuous across room seams and exact on both
// sides of a plane-family change (no neighbour differences): no mip seams, and fetches are legal in non-uniform control flow (rk_im_shade_window
// may be called inside `if (rk_im_needs_interior(mask))`). No dFdx/dFdy is evaluated here: the
// caller passes dp_dx = dFdx(p), dp_dy = dFdy(p) computed in uniform control flow.
//
// Feature macros (each off value compiles the feature out entirely):
//   RK_IM_SHADING  room textures (default 1, the RECOMMENDED mode; 0 is the thesis's):
//     0  four sampler2D: ceiling, floor, wall_x (walls of constant x, family 0, uv = (z, y)),
//        wall_z (walls of constant z, family 2, uv = (x, y)); the thesis's variant, kept for
//        compatibility. It branches over four samplers: one fetch per pixel on a GPU (the branch
//        is coherent inside a room), but a SIMD CPU rasteriser (llvmpipe) runs all four fetches
//        (docs/benchmarks_interior.md: the dearest mode there, ~1.4 plain frames above mode 1).
//     1  one sampler2DArray of 3 V layers: [0, V) ceilings, [V, 2V) floors, [2V, 3V) walls; each
//        face of each room picks variant floor(rk_im_face_random(room, family, side, seed) V).
//        Recommended: one fetch and no sampler branch on every device, and V = 1 gives the
//        thesis's look from a 3-layer array.
//     2  one sampler2D atlas of grid x grid padded cells holding the same 3 V tiles in row-major
//        order (cell k at column k mod grid, row k / grid). PADDING RULE: each cell is tile + 2 pad
//        texels, the gutter filled with the tile's own texels wrapped around (what GL_REPEAT would
//        read); mip levels 0..max_lod never mix tiles when the cell is a multiple of 2^max_lod texels
//        and pad >= max(1, 2^(max_lod - 1)). The shader clamps the LOD to max_lod by scaling the
//        gradients down (isotropic filtering assumed: no anisotropy on the atlas sampler).
//        raykit::interior_atlas_layout / interior_atlas_mip_safe (raykit/interior_features.hpp)
//        compute and check the layout.
//     3  one samplerCubeArray of N room cube maps (GL 4.0 / ARB_texture_cube_map_array): each room
//        picks a cube and a rotation (a multiple of 90° about y) and looks it up along the hit
//        point in the room's own [-1, 1]^3 coordinates (rk_im_cube_lookup in interior_surface.glsl;
//        exact for displaced walls too), tinted by rk_im_room_tint.
//   RK_IM_FURNITURE_LAYERS 0..4 (interior_furniture.glsl): sprite planes from a sampler2DArray,
//        layer l = sprite sheet l (flipbook of flipbook.x columns by flipbook.y rows, flipbook.z frames).
//   RK_IM_FURNITURE_FLIPBOOK 0/1 (interior_furniture.glsl, default 1): 0 compiles the flipbook out
//        (each layer is one sprite image; flipbook, flipbook_fps and time are not read).
//   RK_IM_ROOM_LIGHTS, RK_IM_FADE, RK_IM_COMPOSE_MODE (interior_compose.glsl).
//   RK_IM_VARYING_WALLS (interior_mapping.glsl): rk_im_trace_auto picks the varying-walls trace.
//
// @rk-stages frag
// @rk-variants RK_IM_SHADING=1 | RK_IM_SHADING=2 | RK_IM_SHADING=3 | RK_IM_ROOM_LIGHTS=1 | RK_IM_FURNITURE_LAYERS=1 | RK_IM_FURNITURE_LAYERS=4 | RK_IM_FURNITURE_LAYERS=2 RK_IM_FURNITURE_FLIPBOOK=0 | RK_IM_FADE=1 | RK_IM_VARYING_WALLS=1 | RK_IM_COMPOSE_MODE=1 | RK_IM_SHADING=2 RK_IM_ROOM_LIGHTS=1 RK_IM_FURNITURE_LAYERS=2 RK_IM_FADE=1 | RK_IM_SHADING=3 RK_IM_ROOM_LIGHTS=1 RK_IM_FURNITURE_LAYERS=4 RK_IM_FADE=1 RK_IM_VARYING_WALLS=1
#ifndef RK_INTERIOR_SHADING_GLSL
#define RK_INTERIOR_SHADING_GLSL

#include "interior_mapping.glsl"
#include "interior_furniture.glsl"
#include "interior_compose.glsl"
#include "interior_surface.glsl"
#include "interior_params.glsl"

#ifndef RK_IM_SHADING
#define RK_IM_SHADING 1
#endif
#if RK_IM_SHADING < 0 || RK_IM_SHADING > 3
#error "RK_IM_SHADING must be 0 (four textures), 1 (texture array, recommended), 2 (padded atlas) or 3 (cube map per room)"
#endif
RK_OPTION_CHECK(rk_option_im_shading, RK_IM_SHADING);

#if RK_IM_SHADING == 0
/// rk_im_shade_four: the thesis's four textures, one textureGrad of the hit's family and side.
/// Cost: 1 fetch (the branches are uniform inside a room).
RK_INLINE vec4 rk_im_shade_four(rk_im_hit h, sampler2D ceiling, sampler2D floor_tex, sampler2D wall_x, sampler2D wall_z)
{
    if (h.family == 1) {
        return h.side > 0 ? textureGrad(ceiling, h.uv, h.uv_dx, h.uv_dy) : textureGrad(floor_tex, h.uv, h.uv_dx, h.uv_dy);
    }
    return h.family == 0 ? textureGrad(wall_x, h.uv, h.uv_dx, h.uv_dy) : textureGrad(wall_z, h.uv, h.uv_dx, h.uv_dy);
}
#elif RK_IM_SHADING == 1
/// rk_im_shade_array: layer rk_im_array_layer (kind V + variant) of a sampler2DArray (see the file
/// header). Cost: 1 face hash + 1 fetch.
RK_INLINE vec4 rk_im_shade_array(rk_im_hit h, sampler2DArray rooms, float variants, uint seed)
{
    return textureGrad(rooms, vec3(h.uv, rk_im_array_layer(h, variants, seed)), h.uv_dx, h.uv_dy);
}
#elif RK_IM_SHADING == 2
/// rk_im_shade_atlas: tile rk_im_array_layer (kind V + variant) of the padded atlas at
/// rk_im_atlas_uv, with the LOD clamped to max_lod by scaling both gradients by
/// rk_im_atlas_grad_scale. Cost: 1 face hash, ~30 flops, 1 fetch.
RK_INLINE vec4 rk_im_shade_atlas(rk_im_hit h, sampler2D atlas_tex, float variants, vec4 atlas, uint seed)
{
    float s;
    vec2 uv = rk_im_atlas_uv(h.uv, rk_im_array_layer(h, variants, seed), atlas, s);
    vec2 dx = h.uv_dx * s;
    vec2 dy = h.uv_dy * s;
    float k = rk_im_atlas_grad_scale(dx, dy, atlas);
    return textureGrad(atlas_tex, uv, dx * k, dy * k);
}
#elif RK_IM_SHADING == 3
/// rk_im_shade_cube: the room's cube map at rk_im_cube_lookup (the hit in the room's own
/// [-1, 1]^3 coordinates, exact for displaced walls too, rotated per room by a multiple of 90°
/// about y; a cube per room), tinted per room by rk_im_room_tint. Cost: 2 room hashes (the
/// lookup's and the tint's), ~25 flops, 1 fetch.
RK_INLINE vec4 rk_im_shade_cube(rk_im_hit h, samplerCubeArray cubes, float count, float tint_amount, uint seed)
{
    rk_im_cube_coord c = rk_im_cube_lookup(h, count, seed);
    vec4 t = textureGrad(cubes, vec4(c.dir, c.layer), c.dx, c.dy);
    return vec4(vec3(t.x, t.y, t.z) * rk_im_room_tint(h.room, seed, tint_amount), t.w);
}
#endif

#if RK_IM_FURNITURE_LAYERS > 0
/// rk_im_shade_furniture: intersects the RK_IM_FURNITURE_LAYERS planes, samples each one nearer
/// than the current nearest (initially the room hit at room_t) from layer l of `sprites` (with
/// RK_IM_FURNITURE_FLIPBOOK 1 the flipbook frame of `room`, the room hit's room), alpha-tests it,
/// and keeps the nearest visible one in `colour`. Returns whether any layer won. `room` is not
/// changed: a plane in front of the room surface lies in the room hit's room (the cell the ray
/// segment from p to the hit lies in), so that is the room of the furniture, for the flipbook
/// and the room light alike (up to rounding where the plane hit lies within an ulp of a cell
/// boundary). The frame and ray terms are computed once (rk_im_furniture_setup), only the plane
/// depth differs per layer.
/// Cost: setup (3 normalisations, ~50 flops) + per layer: the plane (1 div, ~25 flops; no room
/// lookup), 1 fetch, and with RK_IM_FURNITURE_FLIPBOOK 1 a room hash and the frame arithmetic.
RK_INLINE bool rk_im_shade_furniture(vec3 p, vec3 cam, vec3 dp_dx, vec3 dp_dy, float room_t, rk_im_window_params prm,
                           sampler2DArray sprites, inout vec3 colour, ivec3 room)
{
    float nearest = room_t;
    bool any = false;
    rk_im_furniture_ray fr = rk_im_furniture_setup(p, cam, prm.normal, prm.tangent, prm.bitangent, dp_dx, dp_dy,
                                                   prm.grid);
#if RK_IM_FURNITURE_FLIPBOOK
    int cols = clamp(prm.flipbook.x, 1, RK_IM_FLIPBOOK_SIDE_MAX);
    int rows = clamp(prm.flipbook.y, 1, RK_IM_FLIPBOOK_SIDE_MAX);
    vec2 sheet = vec2(1.0f / float(cols), 1.0f / float(rows));
#endif
    for (int l = 0; l < RK_IM_FURNITURE_LAYERS; ++l) {
        rk_im_furniture_hit f = rk_im_furniture_layer(fr, prm.furniture_depth[l], prm.grid);
        if (!f.valid || !(f.t < nearest)) continue;
#if RK_IM_FURNITURE_FLIPBOOK
        vec2 suv = rk_im_flipbook_room_uv(f.uv, room, prm.time, prm.flipbook_fps, prm.flipbook.z, cols, rows,
                                          prm.seed + uint(l));
        vec4 texel = textureGrad(sprites, vec3(suv, float(l)), f.uv_dx * sheet, f.uv_dy * sheet);
#else
        vec4 texel = textureGrad(sprites, vec3(f.uv, float(l)), f.uv_dx, f.uv_dy);
#endif
        // A visible plane lies on the ray segment from p to the room hit, i.e. inside the room
        // hit's room (rk_im_hit.room is the cell that segment lies in): `room` stays that room,
        // and no per-layer room lookup is needed (f.room is not read, so it is not computed).
        if (rk_im_furniture_take(f, texel.w, prm.alpha_threshold, nearest)) {
            colour = vec3(texel.x, texel.y, texel.z);
            any = true;
        }
    }
    return any;
}
#endif

/// rk_im_shade_window: the whole window texel: trace (rk_im_trace_auto), room texture
/// (RK_IM_SHADING), furniture layers, room light, distance fade, glass (rk_im_window) and
/// composition with the exterior (rk_im_compose; exterior.w is the window mask, 1 = window).
///   p, dp_dx, dp_dy  object-space surface point and its dFdx/dFdy (computed by the caller in
///                    uniform control flow); cam the camera in object space;
///   view_distance    the distance used by RK_IM_FADE (any unit, that of prm.fade_range);
///   reflection       the environment colour seen in the pane (0 for none).
/// Call it only where rk_im_needs_interior(exterior.w) (the result for other texels is correct but
/// the trace is wasted). When the trace is invalid (camera behind the facade) the interior is
/// prm.average_colour. Samplers by RK_IM_SHADING: 0 (ceiling, floor_tex, wall_x, wall_z),
/// 1 (sampler2DArray rooms), 2 (sampler2D atlas), 3 (samplerCubeArray cubes); then, with
/// RK_IM_FURNITURE_LAYERS > 0, sampler2DArray sprites.
/// Domain: that of the trace (interior_mapping.glsl); any finite input gives a finite colour for
/// finite textures (every part is NaN/Inf-free; tests/gpu/parity_interior_shading.cpp renders
/// every macro combination and checks it). Error: the parts' (trace, glass, fade); the texel
/// chosen is exactly the CPU build's (GpuRender.InteriorRoomTexturesFetchTheSelectedTexel).
/// Cost: the sum of the enabled parts: trace (166 SPIR-V instructions, 10 divisions; +83 with
/// varying walls), 1 room fetch (+ 1 face hash in modes 1/2, 2 room hashes in mode 3), per
/// furniture layer 1 division and 1 fetch, room light 1 hash, fade 1 hash and the flat colour,
/// glass 1 sqrt; measured frame costs per feature in docs/benchmarks_interior.md.
RK_INLINE vec3 rk_im_shade_window(vec4 exterior, vec3 p, vec3 cam, vec3 dp_dx, vec3 dp_dy, float view_distance, vec3 reflection,
                        rk_im_window_params prm
#if RK_IM_SHADING == 0
                        , sampler2D ceiling, sampler2D floor_tex, sampler2D wall_x, sampler2D wall_z
#elif RK_IM_SHADING == 1
                        , sampler2DArray rooms
#elif RK_IM_SHADING == 2
                        , sampler2D atlas_tex
#else
                        , samplerCubeArray cubes
#endif
#if RK_IM_FURNITURE_LAYERS > 0
                        , sampler2DArray sprites
#endif
)
{
    vec3 nn = prm.normal;
    vec3 interior = prm.average_colour;
#if RK_IM_FADE
    // The flat stand-in: the average colour in the light of the room half a room behind p.
    ivec3 flat_room = rk_im_room_at(p - nn * (0.5f * dot(abs(nn), prm.grid.room_size)), prm.grid);
#if RK_IM_ROOM_LIGHTS
    vec3 flat_light = rk_im_room_light(flat_room, prm.lit_probability, prm.seed, prm.light_warm, prm.light_cool,
                                       prm.light_level, prm.unlit);
#else
    vec3 flat_light = vec3(1.0f);
#endif
    vec3 flat_colour = rk_im_fade_flat(prm.average_colour, flat_light);
    float fade = rk_im_fade_weight(view_distance, prm.fade_range.x, prm.fade_range.y);
    interior = flat_colour;
    if (fade < 1.0f) {
#else
    RK_UNUSED(view_distance);
    {
#endif
        rk_im_hit h = rk_im_trace_auto(p, cam, prm.normal, dp_dx, dp_dy, prm.grid, prm.jitter, prm.seed);
        if (h.valid) {
#if RK_IM_SHADING == 0
            vec4 room_colour = rk_im_shade_four(h, ceiling, floor_tex, wall_x, wall_z);
#elif RK_IM_SHADING == 1
            vec4 room_colour = rk_im_shade_array(h, rooms, prm.variants, prm.seed);
#elif RK_IM_SHADING == 2
            vec4 room_colour = rk_im_shade_atlas(h, atlas_tex, prm.variants, prm.atlas, prm.seed);
#else
            vec4 room_colour = rk_im_shade_cube(h, cubes, prm.variants, prm.tint_amount, prm.seed);
#endif
            vec3 c = vec3(room_colour.x, room_colour.y, room_colour.z);
            ivec3 room = h.room;
#if RK_IM_FURNITURE_LAYERS > 0
            rk_im_shade_furniture(p, cam, dp_dx, dp_dy, h.t, prm, sprites, c, room);
#endif
#if RK_IM_ROOM_LIGHTS
            c *= rk_im_room_light(room, prm.lit_probability, prm.seed, prm.light_warm, prm.light_cool, prm.light_level,
                                  prm.unlit);
#endif
            interior = c;
        }
#if RK_IM_FADE
        interior = rk_im_fade(interior, flat_colour, fade);
#endif
    }
    // |cos| of the viewing angle without normalising the eye vector: |n.v| / |v| (n is unit; |v|
    // <= 3.5e15 after the clamps, so |v|^2 cannot overflow; the floor keeps cam = p finite).
    vec3 to_eye = rk_im_furniture_clamp_coord(cam) - rk_im_furniture_clamp_coord(p);
    float cos_view = min(abs(dot(nn, to_eye)) * inversesqrt(max(dot(to_eye, to_eye), 1.0e-30f)), 1.0f);
    vec3 window = rk_im_window(interior, reflection, cos_view, prm.glass_tint, prm.glass_eta, prm.glass_panes);
    return rk_im_compose(exterior, window);
}

#endif  // RK_INTERIOR_SHADING_GLSL
