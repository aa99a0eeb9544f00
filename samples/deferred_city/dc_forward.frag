#version 450 core
// raykit sample deferred_city — dc_forward.frag: the forward path: the same surface and lighting
// as the deferred passes, from the exact attributes, every point light looped per pixel.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"
#include "dc_material.glsl"
layout(location = 0) out vec4 o_color;
void main()
{
    DcSurface s = dc_material();
    vec3 v = rk_normalize_safe(u_eye.xyz - s.p, s.n);
    float dist = dot(s.p - u_eye.xyz, -u_inv_view[2].xyz);
    vec3 c = dc_shade_sun(s, v, dist, uvec2(gl_FragCoord.xy));
    int n = int(u_eye.w);
    for (int i = 0; i < n; ++i) c += dc_point_light(s, v, u_lights[i]);
    o_color = vec4(c, 1.0);
}
