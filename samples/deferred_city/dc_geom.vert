#version 450 core
// raykit sample deferred_city — dc_geom.vert: buildings and ground (world-space vertices with
// tangents from raykit::compute_tangents), for the G-buffer, the forward path and (DC_SHADOW) the
// cascades' depth-only passes.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_tangent;
layout(location = 3) in vec2 a_uv;
layout(location = 4) in vec2 a_mat;  // x: texture layer (0 ground, 1.. facades), y: building index
layout(location = 0) out vec3 v_world;
layout(location = 1) out vec3 v_normal;
layout(location = 2) out vec4 v_tangent;
layout(location = 3) out vec2 v_uv;
layout(location = 4) flat out vec2 v_mat;
#ifdef DC_SHADOW
layout(location = 0) uniform mat4 u_light_view_proj;
#endif
void main()
{
    v_world = a_pos;
    v_normal = a_normal;
    v_tangent = a_tangent;
    v_uv = a_uv;
    v_mat = a_mat;
#ifdef DC_SHADOW
    gl_Position = u_light_view_proj * vec4(a_pos, 1.0);
#else
    gl_Position = u_view_proj * vec4(a_pos, 1.0);
#endif
}
