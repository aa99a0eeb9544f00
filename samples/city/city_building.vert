#version 450 core
// raykit sample city — city_building.vert: buildings and ground (world-space vertices).
#extension GL_GOOGLE_include_directive : require
#include "city_common.glsl"
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in float a_id;
layout(location = 0) out vec3 v_world;
layout(location = 1) out vec3 v_normal;
layout(location = 2) flat out int v_id;
void main()
{
    v_world = a_pos;
    v_normal = a_normal;
    v_id = int(a_id + 0.5);
#ifdef CITY_SHADOW_PASS
    gl_Position = u_shadow_mat * vec4(a_pos, 1.0);
    gl_Position.xyz = gl_Position.xyz * 2.0 - gl_Position.w;  // [0,1] -> clip
#else
    gl_Position = u_view_proj * vec4(a_pos, 1.0);
#endif
}
