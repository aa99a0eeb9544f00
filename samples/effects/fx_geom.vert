#version 450 core
// raykit sample effects — fx_geom.vert: the static scene (world-space positions, normals, albedo,
// material: 0 plain, 1 relief-mapped bricks, 2 relief-mapped paving).
#extension GL_GOOGLE_include_directive : require
#include "fx_common.glsl"
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_albedo;
layout(location = 3) in float a_material;
layout(location = 0) out vec3 v_normal;
layout(location = 1) out vec3 v_albedo;
layout(location = 2) out vec3 v_world;
layout(location = 3) flat out int v_material;
void main()
{
    v_normal = a_normal;
    v_albedo = a_albedo;
    v_world = a_pos;
    v_material = int(a_material + 0.5);
    gl_Position = u_view_proj * vec4(a_pos, 1.0);
}
