#version 450 core
// raykit sample deferred_city — dc_light.frag: one point light on the pixels its volume covers,
// added to the HDR target (blend ONE, ONE).
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"
#include "dc_gbuffer_read.glsl"
layout(location = 0) flat in int v_light;
layout(location = 0) out vec4 o_color;
void main()
{
    DcSurface s;
    float dist;
    vec3 v;
    if (!dc_read_gbuffer(ivec2(gl_FragCoord.xy), s, dist, v)) discard;
    o_color = vec4(dc_point_light(s, v, u_lights[v_light]), 0.0);
}
