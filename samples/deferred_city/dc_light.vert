#version 450 core
// raykit sample deferred_city — dc_light.vert: a point light's volume, raykit::light_volume_sphere
// (it contains the unit ball) scaled by the light's radius, one instance per light.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"
layout(location = 0) in vec3 a_pos;
layout(location = 0) uniform int u_first;  // first light of this draw (sorted by cull mode)
layout(location = 0) flat out int v_light;
void main()
{
    v_light = u_first + gl_InstanceID;
    vec4 pr = u_lights[v_light].pos_radius;
    gl_Position = u_view_proj * vec4(pr.xyz + pr.w * a_pos, 1.0);
}
