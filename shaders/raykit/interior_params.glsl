// raykit — interior_params.glsl: rk_im_window_params, the per-building parameters of
// rk_im_window_shade (interior_shading.glsl), and its defaults. Shared dialect (docs/dialect.md):
// raykit/interior_params.hpp compiles this text as C++, and raykit::gpu_pack (raykit/gpu_layout.hpp)
// writes it into a std140 uniform block or a std430 buffer at the offsets glslang gives it
// (tests/test_gpu_layout.cpp), for engines that upload it as a block rather than as loose uniforms.
//
// @rk-es 310
// @rk-es300
#ifndef RK_INTERIOR_PARAMS_GLSL
#define RK_INTERIOR_PARAMS_GLSL

#include "interior_mapping.glsl"

/// Everything rk_im_shade_window needs besides the samplers. Fields of features that are compiled
/// out are not read. Units: object space unless stated.
struct rk_im_window_params {
    rk_im_grid grid;
    vec3 normal;            // facade outward normal (object space, UNIT length: rk_im_furniture_unit)
    vec3 tangent;           // facade frame for the furniture UVs (see interior_furniture.glsl)
    vec3 bitangent;
    uint seed;              // per building: all per-room randomness derives from it
    vec3 jitter;            // RK_IM_VARYING_WALLS: wall displacement per axis, room units in [0, 1)
    float variants;         // RK_IM_SHADING 1/2: variants V per surface kind; 3: number of cube maps N
    vec4 atlas;             // RK_IM_SHADING 2: (grid, cell texels, pad texels, max_lod)
    float tint_amount;      // RK_IM_SHADING 3: per-room tint strength in [0, 1]
    float lit_probability;  // RK_IM_ROOM_LIGHTS: c of rk_im_room_light
    vec3 light_warm;
    vec3 light_cool;
    vec2 light_level;
    float unlit;            // light multiplier of unlit rooms (RK_IM_UNLIT_DEFAULT)
    vec3 glass_tint;        // transmission tint of the glass, [0, 1]
    float glass_eta;        // 1.52 for window glass
    float glass_panes;      // read by RK_WINDOW_GLASS_FRESNEL 1 / RK_FRESNEL_WINDOW_MODE 3
    vec4 furniture_depth;   // RK_IM_FURNITURE_LAYERS: plane depth behind the facade per layer
    ivec4 flipbook;         // (columns, rows, frame count, unused) of every sprite sheet
    float flipbook_fps;
    float time;             // seconds
    float alpha_threshold;  // sprite alpha test
    vec2 fade_range;        // RK_IM_FADE: (start, end) of the fade band, in the units of view_distance
    vec3 average_colour;    // RK_IM_FADE: the flat stand-in colour (also used when the trace is invalid)
};

/// rk_im_window_params_default: the sample material's defaults (samples/common/interior_building.frag):
/// rooms 4 x 3 x 4 from the origin, a facade facing +z (tangent +x, bitangent +y), seed 1, walls
/// jittered by 0.4 in x and z, 4 variants, the atlas of interior_atlas_layout(256, 4, 4), 60 % of
/// rooms lit between levels 0.6 and 1.6, unlit rooms at RK_IM_UNLIT_DEFAULT, glass of index 1.52
/// (one pane, tint (0.9, 0.95, 0.95)), furniture planes at 0.6, 1.4, 2.2 and 3.0, single-frame
/// sprites, alpha test 0.5, fade from 200 to 400. Cost: field stores only.
RK_INLINE rk_im_window_params rk_im_window_params_default()
{
    rk_im_window_params p;
    p.grid.room_size = vec3(4.0f, 3.0f, 4.0f);
    p.grid.origin = vec3(0.0f);
    p.normal = vec3(0.0f, 0.0f, 1.0f);
    p.tangent = vec3(1.0f, 0.0f, 0.0f);
    p.bitangent = vec3(0.0f, 1.0f, 0.0f);
    p.seed = 1u;
    p.jitter = vec3(0.4f, 0.0f, 0.4f);
    p.variants = 4.0f;
    p.atlas = vec4(4.0f, 272.0f, 8.0f, 4.0f);
    p.tint_amount = 0.35f;
    p.lit_probability = 0.6f;
    p.light_warm = vec3(1.0f, 0.85f, 0.65f);
    p.light_cool = vec3(0.85f, 0.9f, 1.0f);
    p.light_level = vec2(0.6f, 1.6f);
    p.unlit = 0.06f;
    p.glass_tint = vec3(0.9f, 0.95f, 0.95f);
    p.glass_eta = 1.52f;
    p.glass_panes = 1.0f;
    p.furniture_depth = vec4(0.6f, 1.4f, 2.2f, 3.0f);
    p.flipbook = ivec4(1, 1, 1, 0);
    p.flipbook_fps = 8.0f;
    p.time = 0.0f;
    p.alpha_threshold = 0.5f;
    p.fade_range = vec2(200.0f, 400.0f);
    p.average_colour = vec3(0.45f, 0.4f, 0.35f);
    return p;
}

/// rk_im_building_frame: the per-frame values of the sample building material
/// (samples/common/interior_building.frag) besides rk_im_window_params, for its uniform-block form
/// (RK_IM_BUILDING_BLOCK 1: Vulkan, OpenGL SPIR-V, and HLSL / MSL through SPIRV-Cross). The
/// loose-uniform form reads the same values from u_camera_world, u_facade_color and so on.
struct rk_im_building_frame {
    vec3 camera_world;      // camera position, world space
    float env_guard_scale;  // RK_IM_REFLECTION 1: the atlas's guard scale (rk_dual_paraboloid_guard_scale)
    vec3 facade_color;      // procedural facade albedo (RK_IM_BUILDING_FACADE 0)
    float env_lod_bias;     // RK_IM_REFLECTION 1: LOD bias of the environment lookup
    vec3 frame_color;       // window frames (RK_IM_BUILDING_FACADE 0)
    float exposure;         // multiplies the output colour
    vec3 sky_color;         // RK_IM_REFLECTION 0: the colour the glass reflects
    float reinhard_white;   // RK_IM_BUILDING_OUTPUT 1 with RK_TONEMAP_OPERATOR 1
    vec2 window_size;       // window extent as a fraction of the room face (RK_IM_BUILDING_FACADE 0)
};

/// rk_im_building_vertex: the vertex stage's values (samples/common/interior_building.vert) in its
/// uniform-block form: the model and view-projection matrices, the camera, the facade uv scale
/// and the sun light of the facade.
struct rk_im_building_vertex {
    mat4 world_from_object;
    mat4 clip_from_world;
    vec3 camera_world;
    vec3 sun_dir;           // world, towards the sun (any length)
    vec3 sun_color;
    vec3 ambient;
    vec2 uv_scale;          // facade uv multiplier (the thesis's uvMultiplier)
};

/// rk_im_building_frame_default: the loose uniforms' defaults of interior_building.frag (camera at
/// the origin, sky colour (0.35, 0.45, 0.6), exposure 1, Reinhard white 4). Cost: field stores.
RK_INLINE rk_im_building_frame rk_im_building_frame_default()
{
    rk_im_building_frame f;
    f.camera_world = vec3(0.0f);
    f.env_guard_scale = 1.0f;
    f.facade_color = vec3(0.55f, 0.5f, 0.45f);
    f.env_lod_bias = 0.0f;
    f.frame_color = vec3(0.12f);
    f.exposure = 1.0f;
    f.sky_color = vec3(0.35f, 0.45f, 0.6f);
    f.reinhard_white = 4.0f;
    f.window_size = vec2(0.55f, 0.5f);
    return f;
}

/// rk_im_building_vertex_default: the loose uniforms' defaults of interior_building.vert (identity
/// matrices, camera at the origin, sun (0.5, 0.33166, 0.8) of colour (1, 1, 0.9), ambient
/// (0.3, 0.3, 0.4), uv scale 1). Cost: field stores.
RK_INLINE rk_im_building_vertex rk_im_building_vertex_default()
{
    rk_im_building_vertex v;
    v.world_from_object = mat4(1.0f);
    v.clip_from_world = mat4(1.0f);
    v.camera_world = vec3(0.0f);
    v.sun_dir = vec3(0.5f, 0.33166f, 0.8f);
    v.sun_color = vec3(1.0f, 1.0f, 0.9f);
    v.ambient = vec3(0.3f, 0.3f, 0.4f);
    v.uv_scale = vec2(1.0f);
    return v;
}

#endif  // RK_INTERIOR_PARAMS_GLSL
