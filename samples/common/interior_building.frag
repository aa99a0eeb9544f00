#version 450 core
#extension GL_GOOGLE_include_directive : require
// raykit — interior_building.frag: a complete interior-mapped building material for OpenGL 4.5
// (vertex stage: interior_building.vert). Copy both files; compile with glslang (include path:
// raykit's shaders/) or at run time with raykit::load_shader_file(path, {shader_dir}, defines),
// defines from raykit::interior_defines(InteriorSceneDesc) (raykit/interior_features.hpp).
//
// FEATURE MACROS (host-settable; defaults in brackets; off = compiled out):
//   RK_IM_SHADING [1]           room textures: 0 four textures (the thesis's), 1 array (RECOMMENDED,
//                               one fetch, no sampler branch), 2 padded atlas, 3 cube per room
//   RK_IM_ROOM_LIGHTS [0]       per-room on/off, colour, level
//   RK_IM_FURNITURE_LAYERS [0]  0..4 sprite planes
//   RK_IM_FURNITURE_FLIPBOOK [1] 1: per-room flipbook frame (u_flipbook, u_flipbook_fps, u_time);
//                               0: each sprite sheet is one image (cheaper: no room hash per layer)
//   RK_IM_VARYING_WALLS [0]     walls displaced per wall index
//   RK_IM_REFLECTION [0]        0: flat u_sky_color in the panes; 1: dual-paraboloid environment
//   RK_IM_FADE [0]              distant interiors fade to a flat colour (trace skipped beyond)
//   RK_IM_COMPOSE_MODE [0]      0 Fresnel glass, 1 the thesis's additive window
//   RK_WINDOW_GLASS_FRESNEL [0] pane reflectance (window_glass.glsl): 0 exact, 1 fast (no sqrt;
//                               measured: no gain on llvmpipe, see docs/benchmarks_interior.md)
//   RK_IM_BUILDING_FACADE [0]   0 procedural facade (a window centred in every room face),
//                               1 facade texture u_facade (RGB albedo, A = window mask, 1 = window)
//   RK_IM_BUILDING_BLOCK [0]    0 loose uniforms with defaults (OpenGL run-time GLSL), 1 the same
//                               values in std140 blocks (binding 8 here, 9 in the vertex stage),
//                               for SPIR-V (Vulkan, OpenGL) and HLSL / MSL through SPIRV-Cross;
//                               fill them with raykit::gpu_pack (docs/integration.md)
//   RK_IM_BUILDING_OUTPUT [0]   0 linear HDR (times u_exposure), 1 rk_tonemap (RK_TONEMAP_OPERATOR)
//                               then sRGB encoding, for an RGBA8 (non-sRGB) target
// MINIMAL VARIANT (benchmark baseline): every macro 0, or RK_IM_BUILDING_FACADE=1 with everything
// else 0: the thesis's material (four interior textures, diffuse facade whose alpha marks windows,
// one reflection colour), with raykit's fixes (nudged on-grid facades, textureGrad, Fresnel glass).
//
// TEXTURE BINDINGS (layout(binding) below; the host binds textures to these units):
//   0 u_facade          sampler2D        RK_IM_BUILDING_FACADE 1
//   1 u_ceiling         sampler2D        RK_IM_SHADING 0 (uv = (x, z) in room units, GL_REPEAT)
//   2 u_floor           sampler2D        RK_IM_SHADING 0
//   3 u_wall_x          sampler2D        RK_IM_SHADING 0, walls of constant x (uv = (z, y))
//   4 u_wall_z          sampler2D        RK_IM_SHADING 0, walls of constant z (uv = (x, y))
//   5 u_rooms           sampler2DArray   RK_IM_SHADING 1 (3 V layers: ceilings, floors, walls)
//   5 u_room_atlas      sampler2D        RK_IM_SHADING 2 (padded atlas, see interior_shading.glsl)
//   5 u_room_cubes      samplerCubeArray RK_IM_SHADING 3
//   6 u_sprites         sampler2DArray   RK_IM_FURNITURE_LAYERS > 0 (layer l: sheet of layer l)
//   7 u_environment     sampler2D        RK_IM_REFLECTION 1 (dual-paraboloid atlas, paraboloid.glsl)
// UNIFORMS (initialised to usable defaults; set what you need by name):
//   grid:      vec3 u_room_size (object units per room: x pitch, storey height, z pitch) [4, 3, 4],
//              vec3 u_grid_origin [0], uint u_seed [1], vec3 u_wall_jitter [0.4, 0, 0.4]
//   facade:    vec3 u_facade_color [0.55, 0.5, 0.45], vec3 u_frame_color [0.12], vec2 u_window_size
//              (window extent as a fraction of the room face) [0.55, 0.5]; the light (u_sun_dir,
//              u_sun_color, u_ambient) is the vertex stage's
//   glass:     vec3 u_glass_tint [0.9, 0.95, 0.95], float u_glass_eta [1.52], float u_glass_panes [1]
//   reflection: vec3 u_sky_color [0.35, 0.45, 0.6] (RK_IM_REFLECTION 0), float u_env_guard_scale [1],
//              float u_env_lod_bias [0] (RK_IM_REFLECTION 1)
//   lights:    float u_lit_probability [0.6], vec3 u_light_warm [1.0, 0.85, 0.65], vec3 u_light_cool
//              [0.85, 0.9, 1.0], vec2 u_light_level [0.6, 1.6], float u_unlit [0.06]
//   furniture: vec4 u_furniture_depth (object units behind the facade, per layer) [0.6, 1.4, 2.2, 3.0],
//              ivec3 u_flipbook (columns, rows, frames) [1, 1, 1], float u_flipbook_fps [8],
//              float u_time [0], float u_alpha_threshold [0.5]
//   fade:      vec2 u_fade_range (world units from the camera) [200, 400], vec3 u_room_average
//              [0.45, 0.4, 0.35]
//   shading:   float u_variants [4] (V, or the cube count N), vec4 u_atlas (grid, cell texels, pad
//              texels, max_lod) [4, 272, 8, 4], float u_tint_amount [0.35]
//   output:    float u_exposure [1], float u_reinhard_white [4]
// Also the vertex stage's u_world_from_object, u_clip_from_world, u_camera_world, u_uv_scale.

#ifndef RK_IM_REFLECTION
#define RK_IM_REFLECTION 0
#endif
#ifndef RK_IM_BUILDING_FACADE
#define RK_IM_BUILDING_FACADE 0
#endif
#ifndef RK_IM_BUILDING_OUTPUT
#define RK_IM_BUILDING_OUTPUT 0
#endif
#ifndef RK_IM_BUILDING_BLOCK
#define RK_IM_BUILDING_BLOCK 0
#endif
#if RK_IM_BUILDING_BLOCK < 0 || RK_IM_BUILDING_BLOCK > 1
#error "RK_IM_BUILDING_BLOCK must be 0 (loose uniforms with defaults: OpenGL run-time GLSL) or 1 (std140 blocks: SPIR-V, Vulkan, HLSL/MSL)"
#endif

#include "raykit/interior_shading.glsl"
#if RK_IM_BUILDING_BLOCK
#include "raykit/interior_params.glsl"
#endif
#if RK_IM_REFLECTION
#include "raykit/paraboloid_sample.glsl"
#endif
#if RK_IM_BUILDING_OUTPUT
#include "raykit/tonemap.glsl"
#endif

layout(location = 0) in vec3 v_pos_object;
layout(location = 1) in vec3 v_normal_object;
layout(location = 2) in vec3 v_pos_world;
layout(location = 3) in vec3 v_normal_world;
layout(location = 4) in vec2 v_uv;
layout(location = 5) flat in vec3 v_camera_object;
layout(location = 6) in vec3 v_tangent_object;
layout(location = 7) in vec3 v_light;

layout(location = 0) out vec4 o_color;

#if RK_IM_BUILDING_BLOCK
// The uniform-block form: the same values in two std140 blocks (binding 8 here; the vertex stage's
// block is binding 9), written on the host with raykit::gpu_pack from rk_im_window_params and
// rk_im_building_frame (raykit/interior_params.hpp). The per-fragment fields of u_params (normal,
// tangent, bitangent) are not read.
layout(std140, binding = 8) uniform RkBuildingFragment {
    rk_im_window_params u_params;
    rk_im_building_frame u_frame;
};
#define u_camera_world u_frame.camera_world
#define u_room_size u_params.grid.room_size
#define u_grid_origin u_params.grid.origin
#define u_seed u_params.seed
#define u_wall_jitter u_params.jitter
#define u_facade_color u_frame.facade_color
#define u_frame_color u_frame.frame_color
#define u_window_size u_frame.window_size
#define u_glass_tint u_params.glass_tint
#define u_glass_eta u_params.glass_eta
#define u_glass_panes u_params.glass_panes
#define u_sky_color u_frame.sky_color
#define u_env_guard_scale u_frame.env_guard_scale
#define u_env_lod_bias u_frame.env_lod_bias
#define u_lit_probability u_params.lit_probability
#define u_light_warm u_params.light_warm
#define u_light_cool u_params.light_cool
#define u_light_level u_params.light_level
#define u_unlit u_params.unlit
#define u_furniture_depth u_params.furniture_depth
#define u_flipbook u_params.flipbook.xyz
#define u_flipbook_fps u_params.flipbook_fps
#define u_time u_params.time
#define u_alpha_threshold u_params.alpha_threshold
#define u_fade_range u_params.fade_range
#define u_room_average u_params.average_colour
#define u_variants u_params.variants
#define u_atlas u_params.atlas
#define u_tint_amount u_params.tint_amount
#define u_exposure u_frame.exposure
#define u_reinhard_white u_frame.reinhard_white
#else
uniform vec3 u_camera_world;
uniform vec3 u_room_size = vec3(4.0, 3.0, 4.0);
uniform vec3 u_grid_origin = vec3(0.0);
uniform uint u_seed = 1u;
uniform vec3 u_wall_jitter = vec3(0.4, 0.0, 0.4);
uniform vec3 u_facade_color = vec3(0.55, 0.5, 0.45);
uniform vec3 u_frame_color = vec3(0.12);
uniform vec2 u_window_size = vec2(0.55, 0.5);
uniform vec3 u_glass_tint = vec3(0.9, 0.95, 0.95);
uniform float u_glass_eta = 1.52;
uniform float u_glass_panes = 1.0;
uniform vec3 u_sky_color = vec3(0.35, 0.45, 0.6);
uniform float u_env_guard_scale = 1.0;
uniform float u_env_lod_bias = 0.0;
uniform float u_lit_probability = 0.6;
uniform vec3 u_light_warm = vec3(1.0, 0.85, 0.65);
uniform vec3 u_light_cool = vec3(0.85, 0.9, 1.0);
uniform vec2 u_light_level = vec2(0.6, 1.6);
uniform float u_unlit = 0.06;
uniform vec4 u_furniture_depth = vec4(0.6, 1.4, 2.2, 3.0);
uniform ivec3 u_flipbook = ivec3(1, 1, 1);
uniform float u_flipbook_fps = 8.0;
uniform float u_time = 0.0;
uniform float u_alpha_threshold = 0.5;
uniform vec2 u_fade_range = vec2(200.0, 400.0);
uniform vec3 u_room_average = vec3(0.45, 0.4, 0.35);
uniform float u_variants = 4.0;
uniform vec4 u_atlas = vec4(4.0, 272.0, 8.0, 4.0);
uniform float u_tint_amount = 0.35;
uniform float u_exposure = 1.0;
uniform float u_reinhard_white = 4.0;
#endif

#if RK_IM_BUILDING_FACADE
layout(binding = 0) uniform sampler2D u_facade;
#endif
#if RK_IM_SHADING == 0
layout(binding = 1) uniform sampler2D u_ceiling;
layout(binding = 2) uniform sampler2D u_floor;
layout(binding = 3) uniform sampler2D u_wall_x;
layout(binding = 4) uniform sampler2D u_wall_z;
#elif RK_IM_SHADING == 1
layout(binding = 5) uniform sampler2DArray u_rooms;
#elif RK_IM_SHADING == 2
layout(binding = 5) uniform sampler2D u_room_atlas;
#else
layout(binding = 5) uniform samplerCubeArray u_room_cubes;
#endif
#if RK_IM_FURNITURE_LAYERS > 0
layout(binding = 6) uniform sampler2DArray u_sprites;
#endif
#if RK_IM_REFLECTION
layout(binding = 7) uniform sampler2D u_environment;
#endif

void main()
{
    rk_im_grid grid;
    grid.room_size = u_room_size;
    grid.origin = u_grid_origin;
    vec3 p = v_pos_object;
    // The facade frame from the vertex stage (unit, per-face constants on planar facades).
    vec3 n_obj = v_normal_object;
    vec3 tangent = v_tangent_object;
    vec3 bitangent = cross(n_obj, tangent);
    // Derivatives in uniform control flow (the interior's fetches use them inside the branch below).
    vec3 dp_dx = dFdx(p);
    vec3 dp_dy = dFdy(p);

    // Exterior: albedo + window mask, lit by the sun (the vertex stage's diffuse light).
    vec3 light = v_light;
#if RK_IM_BUILDING_FACADE
    vec4 facade = texture(u_facade, v_uv);
    vec4 exterior = vec4(facade.rgb * light, facade.a);
#else
    // A window centred in every room face, antialiased over one pixel (fwidth of the unwrapped
    // room coordinate), with a dark frame around it; roofs (|n.y| > 0.5) are opaque.
    vec2 cell = vec2(dot(p - u_grid_origin, tangent) / max(dot(abs(tangent), u_room_size), 1e-4),
                     dot(p - u_grid_origin, bitangent) / max(dot(abs(bitangent), u_room_size), 1e-4));
    vec2 px = max(fwidth(cell), vec2(1e-6));
    vec2 dist = abs(fract(cell) - 0.5) - 0.5 * u_window_size;
    float window = clamp(0.5 - max(dist.x / px.x, dist.y / px.y), 0.0, 1.0);
    float frame = clamp(0.5 - max((dist.x - 0.03) / px.x, (dist.y - 0.03) / px.y), 0.0, 1.0);
    float wall = abs(n_obj.y) > 0.5 ? 0.0 : 1.0;
    vec3 albedo = mix(u_facade_color, u_frame_color, frame * wall);
    vec4 exterior = vec4(albedo * light, window * wall);
#endif

    // Reflection direction (world space) and its derivatives, also in uniform control flow.
    vec3 to_eye_world = u_camera_world - v_pos_world;
#if RK_IM_REFLECTION
    vec3 r = reflect(-to_eye_world, v_normal_world);
    vec3 r_dx = dFdx(r);
    vec3 r_dy = dFdy(r);
#endif

    vec3 colour = exterior.rgb;
    if (rk_im_needs_interior(exterior.a)) {
#if RK_IM_REFLECTION
        float lod_scale = exp2(clamp(u_env_lod_bias, -16.0, 16.0));
        vec3 reflection = textureGrad(u_environment, rk_dual_paraboloid_uv(r, u_env_guard_scale),
                                      lod_scale * rk_dual_paraboloid_uv_differential(r, r_dx, u_env_guard_scale),
                                      lod_scale * rk_dual_paraboloid_uv_differential(r, r_dy, u_env_guard_scale)).rgb;
#else
        vec3 reflection = u_sky_color;
#endif
        rk_im_window_params prm;
        prm.grid = grid;
        prm.normal = n_obj;
        prm.tangent = tangent;
        prm.bitangent = bitangent;
        prm.seed = u_seed;
        prm.jitter = u_wall_jitter;
        prm.variants = u_variants;
        prm.atlas = u_atlas;
        prm.tint_amount = u_tint_amount;
        prm.lit_probability = u_lit_probability;
        prm.light_warm = u_light_warm;
        prm.light_cool = u_light_cool;
        prm.light_level = u_light_level;
        prm.unlit = u_unlit;
        prm.glass_tint = u_glass_tint;
        prm.glass_eta = u_glass_eta;
        prm.glass_panes = u_glass_panes;
        prm.furniture_depth = u_furniture_depth;
        prm.flipbook = ivec4(u_flipbook, 0);
        prm.flipbook_fps = u_flipbook_fps;
        prm.time = u_time;
        prm.alpha_threshold = u_alpha_threshold;
        prm.fade_range = u_fade_range;
        prm.average_colour = u_room_average;
        colour = rk_im_shade_window(exterior, p, v_camera_object, dp_dx, dp_dy, length(to_eye_world), reflection, prm
#if RK_IM_SHADING == 0
                                    , u_ceiling, u_floor, u_wall_x, u_wall_z
#elif RK_IM_SHADING == 1
                                    , u_rooms
#elif RK_IM_SHADING == 2
                                    , u_room_atlas
#else
                                    , u_room_cubes
#endif
#if RK_IM_FURNITURE_LAYERS > 0
                                    , u_sprites
#endif
        );
    }

    colour *= u_exposure;
#if RK_IM_BUILDING_OUTPUT
    o_color = vec4(rk_srgb_encode(rk_tonemap(colour, u_reinhard_white)), 1.0);
#else
    o_color = vec4(colour, 1.0);
#endif
}
