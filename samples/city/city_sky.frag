#version 450 core
// raykit sample city — city_sky.frag: the procedural sky behind everything (drawn last, at depth 1).
#extension GL_GOOGLE_include_directive : require
#include "city_common.glsl"
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_aux;
layout(location = 0) uniform vec2 u_size;
void main()
{
    vec2 ndc = gl_FragCoord.xy / u_size * 2.0 - 1.0;
    vec4 far = u_inv_view_proj * vec4(ndc, 1.0, 1.0);
    vec4 near = u_inv_view_proj * vec4(ndc, -1.0, 1.0);
    vec3 dir = far.xyz / far.w - near.xyz / near.w;
    o_color = vec4(city_sky(dir), 1.0);
    o_aux = vec4(0.0);
}
