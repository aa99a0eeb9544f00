#version 450
// raykit bench — raykit_building.frag: the benchmark's own building material built from raykit's
// interior-mapping includes (interior_mapping.glsl, interior_furniture.glsl,
// interior_compose.glsl, paraboloid_sample.glsl). bench_interior_gl uses it for the rk_* variants
// when samples/common/interior_building.frag is absent (and labels them rkb_* otherwise), so
// that the library's cost is measured whatever the state of the sample material.
//
// Feature macros (defaults: all off = "minimal", the thesis's four textures without reflection):
//   RK_IM_SHADING         0 four textures (one textureGrad of the chosen family's texture),
//                         1 texture array, layer = family * 4 + per-room/per-face random variant,
//                         2 padded atlas (4 x 4 tiles), same choice
//   RK_IM_ROOM_LIGHTS     0/1 per-room light on/off, colour and level (rk_im_room_light)
//   RK_IM_FURNITURE_LAYERS 0..4 furniture planes (rk_im_furniture_setup/_layer + alpha test)
//   RK_IM_REFLECTION      0 none, 1 dual-paraboloid environment (rk_dual_paraboloid_sample_grad)
//                         over the interior with Fresnel glass (rk_im_window, RK_IM_COMPOSE_MODE 0)
//   RK_IM_FADE            0/1 beyond u_fade_end the interior is a flat colour and the trace skipped
//   RK_IM_VARYING_WALLS   0/1 (interior_mapping.glsl) walls displaced per wall index
//   BENCH_SKIP_OPAQUE     1 (default): the trace and interior fetches are skipped for opaque
//                         facade texels (rk_im_needs_interior); 0: computed for every pixel.
//   BENCH_IMPLICIT_LOD    0 (default): interior and furniture fetches use textureGrad with the
//                         analytic derivatives; 1: texture() with implicit derivatives, to measure
//                         what the explicit gradients cost (seams at room edges, and implicit
//                         derivatives in non-uniform control flow are undefined in GLSL: a
//                         measurement variant only, not a way to ship it).
//   BENCH_REFLECTION_LOD  0 (default): the reflection uses rk_dual_paraboloid_sample_grad;
//                         1: rk_dual_paraboloid_sample_lod at LOD 0 (no derivatives; aliasing).
#extension GL_GOOGLE_include_directive : require

#ifndef BENCH_REFLECTION_LOD
#define BENCH_REFLECTION_LOD 0
#endif

#ifndef BENCH_IMPLICIT_LOD
#define BENCH_IMPLICIT_LOD 0
#endif
#if BENCH_IMPLICIT_LOD
#define BENCH_SAMPLE(s, c, dx, dy) texture(s, c)
#else
#define BENCH_SAMPLE(s, c, dx, dy) textureGrad(s, c, dx, dy)
#endif

#ifndef RK_IM_SHADING
#define RK_IM_SHADING 0
#endif
#ifndef RK_IM_REFLECTION
#define RK_IM_REFLECTION 0
#endif
#ifndef BENCH_SKIP_OPAQUE
#define BENCH_SKIP_OPAQUE 1
#endif

#include "raykit/interior_mapping.glsl"
#include "raykit/interior_furniture.glsl"
#include "raykit/interior_compose.glsl"
#if RK_IM_REFLECTION
#include "raykit/paraboloid_sample.glsl"
#endif

layout(binding = 0) uniform sampler2D u_facade;          // RGB exterior, A = window mask (1 = window)
layout(binding = 1) uniform sampler2D u_ceiling;
layout(binding = 2) uniform sampler2D u_floor;
layout(binding = 3) uniform sampler2D u_wall_xy;         // walls of constant z (family 2)
layout(binding = 4) uniform sampler2D u_wall_zy;         // walls of constant x (family 0)
layout(binding = 6) uniform sampler2DArray u_interior_array;   // layer = family slot * 4 + variant
layout(binding = 7) uniform sampler2D u_atlas;           // 4 x 4 tiles of (256 + 2 * 8) texels
layout(binding = 8) uniform sampler2DArray u_furniture;  // RGBA sprites, one layer per plane
layout(binding = 9) uniform sampler2D u_env_dp;          // dual-paraboloid environment atlas

uniform vec3 u_cam_obj;
uniform vec3 u_cam_world;
uniform vec3 u_room_size;
uniform vec3 u_grid_origin;
uniform vec3 u_wall_jitter;
uniform uint u_seed;
uniform float u_lit_probability;
uniform float u_fade_start;
uniform float u_fade_end;
uniform vec3 u_interior_average;
uniform float u_dp_guard;

in vec2 v_uv;
in vec3 v_obj_pos;
in vec3 v_obj_normal;
in vec3 v_world_pos;
in vec3 v_lighting;
layout(location = 0) out vec4 o_color;

// Texture slot of a hit: 0 ceiling, 1 floor, 2 wall of constant z, 3 wall of constant x.
int face_slot(rk_im_hit h)
{
    return h.family == 1 ? (h.side > 0 ? 0 : 1) : (h.family == 2 ? 2 : 3);
}

vec3 shade_room(rk_im_hit h)
{
    int slot = face_slot(h);
#if RK_IM_SHADING == 0
    vec3 c;
    if (slot == 0) c = BENCH_SAMPLE(u_ceiling, h.uv, h.uv_dx, h.uv_dy).rgb;
    else if (slot == 1) c = BENCH_SAMPLE(u_floor, h.uv, h.uv_dx, h.uv_dy).rgb;
    else if (slot == 2) c = BENCH_SAMPLE(u_wall_xy, h.uv, h.uv_dx, h.uv_dy).rgb;
    else c = BENCH_SAMPLE(u_wall_zy, h.uv, h.uv_dx, h.uv_dy).rgb;
    return c;
#else
    int variant = min(int(rk_im_face_random(h.room, h.family, h.side, u_seed) * 4.0), 3);
    int layer = slot * 4 + variant;
#if RK_IM_SHADING == 1
    return BENCH_SAMPLE(u_interior_array, vec3(h.uv, float(layer)), h.uv_dx, h.uv_dy).rgb;
#else
    const float tile = 1.0 / 4.0, pad = 8.0 / 272.0, inner = 256.0 / 272.0;
    vec2 cell = vec2(float(layer % 4), float(layer / 4));
    vec2 uv = (cell + pad + h.uv * inner) * tile;
    return BENCH_SAMPLE(u_atlas, uv, h.uv_dx * (inner * tile), h.uv_dy * (inner * tile)).rgb;
#endif
#endif
}

void main()
{
    vec4 ext = texture(u_facade, v_uv);
    vec3 exterior = ext.rgb * v_lighting;
    vec3 p = v_obj_pos;
    vec3 n = v_obj_normal;
    vec3 dp_dx = dFdx(p);   // outside any branch: derivatives need uniform control flow
    vec3 dp_dy = dFdy(p);
    rk_im_grid g;
    g.room_size = u_room_size;
    g.origin = u_grid_origin;

    vec3 window = vec3(0.0);
#if BENCH_SKIP_OPAQUE
    if (rk_im_needs_interior(ext.a)) {
#endif
        vec3 interior = u_interior_average;
#if RK_IM_FADE
        float fade = rk_im_fade_weight(length(v_world_pos - u_cam_world), u_fade_start, u_fade_end);
        if (fade < 1.0) {
#endif
            rk_im_hit h = rk_im_trace_auto(p, u_cam_obj, n, dp_dx, dp_dy, g, u_wall_jitter, u_seed);
            interior = shade_room(h);
#if RK_IM_FURNITURE_LAYERS > 0
            vec3 tangent = vec3(n.z, 0.0, -n.x);
            float nearest = h.t;
            // The per-pixel part once, then one plane per layer (interior_furniture.glsl).
            rk_im_furniture_ray fr = rk_im_furniture_setup(p, u_cam_obj, n, tangent, vec3(0.0, 1.0, 0.0), dp_dx, dp_dy, g);
            for (int i = 0; i < RK_IM_FURNITURE_LAYERS; ++i) {
                float depth = (0.2 + 0.25 * float(i)) * min(u_room_size.x, u_room_size.z);
                rk_im_furniture_hit f = rk_im_furniture_layer(fr, depth, g);
                vec4 s = BENCH_SAMPLE(u_furniture, vec3(f.uv, float(i)), f.uv_dx, f.uv_dy);
                if (rk_im_furniture_take(f, s.a, 0.5, nearest)) interior = s.rgb;
            }
#endif
#if RK_IM_ROOM_LIGHTS
            interior *= rk_im_room_light(h.room, u_lit_probability, u_seed, vec3(1.0, 0.85, 0.6), vec3(0.8, 0.9, 1.0),
                                         vec2(0.8, 1.4), RK_IM_UNLIT_DEFAULT);
#endif
#if RK_IM_FADE
        }
        if (fade > 0.0) {
            vec3 light = vec3(1.0);
#if RK_IM_ROOM_LIGHTS
            light = rk_im_room_light(rk_im_room_at(p - n * (0.5 * u_room_size), g), u_lit_probability, u_seed,
                                     vec3(1.0, 0.85, 0.6), vec3(0.8, 0.9, 1.0), vec2(0.8, 1.4), RK_IM_UNLIT_DEFAULT);
#endif
            interior = rk_im_fade(interior, rk_im_fade_flat(u_interior_average, light), fade);
        }
#endif
#if RK_IM_REFLECTION
        vec3 to_eye = normalize(u_cam_world - v_world_pos);
#if BENCH_REFLECTION_LOD
        vec3 refl = rk_dual_paraboloid_sample_lod(u_env_dp, reflect(-to_eye, n), u_dp_guard, 0.0, 0.0).rgb;
#else
        vec3 refl = rk_dual_paraboloid_sample_grad(u_env_dp, reflect(-to_eye, n), u_dp_guard, 0.0).rgb;
#endif
        window = rk_im_window(interior, refl, rk_window_glass_cos(n, to_eye), vec3(1.0), RK_WINDOW_GLASS_ETA, 1.0);
#else
        window = interior;
#endif
#if BENCH_SKIP_OPAQUE
    }
#endif
    o_color = vec4(rk_im_compose(vec4(exterior, ext.a), window), 1.0);
}
