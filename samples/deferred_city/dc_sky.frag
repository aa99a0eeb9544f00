#version 450 core
// raykit sample deferred_city — dc_sky.frag: the forward path's background (the deferred path
// draws the same sky in dc_sun.frag where the depth buffer holds the far plane).
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"
layout(location = 0) out vec4 o_color;
void main()
{
    vec2 ndc = gl_FragCoord.xy * u_viewport.zw * 2.0 - 1.0;
    o_color = vec4(dc_sky(normalize(mat3(u_inv_view) * rk_gb_view_pos(ndc, 1.0, u_view_ray))), 1.0);
}
