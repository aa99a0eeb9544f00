#version 450 core
#ifndef RK_IM_BUILDING_BLOCK
#define RK_IM_BUILDING_BLOCK 0
#endif
#if RK_IM_BUILDING_BLOCK
#extension GL_GOOGLE_include_directive : require
#endif
// raykit — interior_building.vert: vertex stage of the interior-mapped building material
// (samples/common/interior_building.frag documents the whole material). Copy both files freely.
//
// Attributes:
//   location 0  vec3 a_position   object-space position
//   location 1  vec3 a_normal     object-space outward normal (need not be unit length)
//   location 2  vec2 a_uv         facade texture coordinate (RK_IM_BUILDING_FACADE 1)
// Uniforms:
//   mat4 u_world_from_object   model matrix (any affine transform, non-uniform scale included)
//   mat4 u_clip_from_world     view-projection matrix
//   vec3 u_camera_world        camera position in world space
//   vec2 u_uv_scale            facade uv multiplier (the thesis's uvMultiplier; (1, 1) for none)
//   vec3 u_sun_dir             world, towards the sun [0.5, 0.33166, 0.8] (any length)
//   vec3 u_sun_color [1, 1, 0.9], vec3 u_ambient [0.3, 0.3, 0.4]   (the thesis's light)
// Outputs: the object-space position (interior mapping runs in object space, so rooms stay fixed
// to the building); the facade frame, computed here once per vertex instead of per pixel: the unit
// object-space normal, a unit horizontal tangent (cross(up, n); (1, 0, 0) on roofs) and the
// facade's diffuse light (ambient + sun * max(N.L, 0), world space); the world-space position and
// unit normal (the normal through the inverse transpose, so reflections are right under
// non-uniform scale, unlike the appendix vertex program of van Dongen, "Using raycasting in GPU
// shaders to enhance real-time graphics", 2009), the camera in object space (flat), the facade uv.
// The frame and the light are per-face constants on the planar facades interior mapping models,
// so interpolating them is exact there (the fragment stage does not renormalise them).

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;

#if RK_IM_BUILDING_BLOCK
// The uniform-block form (see interior_building.frag): rk_im_building_vertex written with
// raykit::gpu_pack (raykit/interior_params.hpp).
#include "raykit/common.glsl"
#include "raykit/interior_params.glsl"
layout(std140, binding = 9) uniform RkBuildingVertex { rk_im_building_vertex u_vertex; };
#define u_world_from_object u_vertex.world_from_object
#define u_clip_from_world u_vertex.clip_from_world
#define u_camera_world u_vertex.camera_world
#define u_uv_scale u_vertex.uv_scale
#define u_sun_dir u_vertex.sun_dir
#define u_sun_color u_vertex.sun_color
#define u_ambient u_vertex.ambient
#else
uniform mat4 u_world_from_object;
uniform mat4 u_clip_from_world;
uniform vec3 u_camera_world;
uniform vec2 u_uv_scale = vec2(1.0);
uniform vec3 u_sun_dir = vec3(0.5, 0.33166, 0.8);
uniform vec3 u_sun_color = vec3(1.0, 1.0, 0.9);
uniform vec3 u_ambient = vec3(0.3, 0.3, 0.4);
#endif

layout(location = 0) out vec3 v_pos_object;
layout(location = 1) out vec3 v_normal_object;
layout(location = 2) out vec3 v_pos_world;
layout(location = 3) out vec3 v_normal_world;
layout(location = 4) out vec2 v_uv;
layout(location = 5) flat out vec3 v_camera_object;
layout(location = 6) out vec3 v_tangent_object;
layout(location = 7) out vec3 v_light;

// v / |v| without overflow or underflow; `fallback` for a (near-)zero vector.
vec3 unit_or(vec3 v, vec3 fallback)
{
    float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    if (!(m >= 1.175494351e-38)) return fallback;
    vec3 s = v / m;
    return s * inversesqrt(dot(s, s));
}

void main()
{
    vec4 world = u_world_from_object * vec4(a_position, 1.0);
    gl_Position = u_clip_from_world * world;
    v_pos_object = a_position;
    vec3 n = unit_or(a_normal, vec3(0.0, 0.0, 1.0));
    v_normal_object = n;
    // Facade frame: horizontal tangent (roofs: any frame, they have no windows).
    v_tangent_object = abs(n.y) > 0.999 ? vec3(1.0, 0.0, 0.0) : normalize(cross(vec3(0.0, 1.0, 0.0), n));
    v_pos_world = world.xyz;
    // Inverse transpose of the upper 3x3.
    vec3 n_world = unit_or(transpose(inverse(mat3(u_world_from_object))) * a_normal, vec3(0.0, 0.0, 1.0));
    v_normal_world = n_world;
    v_light = u_ambient + u_sun_color * max(dot(n_world, unit_or(u_sun_dir, vec3(0.0, 1.0, 0.0))), 0.0);
    v_uv = a_uv * u_uv_scale;
    v_camera_object = (inverse(u_world_from_object) * vec4(u_camera_world, 1.0)).xyz;
}
