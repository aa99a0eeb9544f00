#version 450 core
// raykit sample effects — fx_light.frag: sun and sky light (sky light times 1 - AO), the sky where
// nothing was drawn, and the light shafts added on top.
#extension GL_GOOGLE_include_directive : require
#include "fx_common.glsl"
layout(binding = 0) uniform sampler2D u_depth;
layout(binding = 1) uniform sampler2D u_normal;
layout(binding = 2) uniform sampler2D u_ao;
layout(binding = 3) uniform sampler2D u_albedo;
layout(binding = 4) uniform sampler2D u_shafts;  // half resolution, LINEAR
layout(location = 0) out vec4 o_color;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec2 uv = gl_FragCoord.xy * u_viewport.zw;
    vec3 shafts = texture(u_shafts, uv).rgb * (u_light_uv.z * u_light_uv.w);
    float d = texelFetch(u_depth, px, 0).x;
    vec2 ndc = uv * 2.0 - 1.0;
    if (d <= 0.0) {
        o_color = vec4(fx_sky(normalize(rk_gb_view_pos(ndc, 1.0, u_view_ray))) + shafts, 1.0);
        return;
    }
    vec3 n = texelFetch(u_normal, px, 0).xyz;
    vec4 alb = texelFetch(u_albedo, px, 0);
    vec3 albedo = alb.rgb;  // alpha: the relief's self-shadowing
    float ao = u_sky.w > 0.5 ? texelFetch(u_ao, px, 0).x : 0.0;
    float up = dot(n, mat3(u_view) * vec3(0.0, 1.0, 0.0));
    vec3 c = albedo * u_sky.rgb * (0.65 + 0.35 * up) * (1.0 - ao);
    c += albedo / 3.14159265 * u_sun_color.rgb * max(dot(n, u_sun_view.xyz), 0.0) * u_sun_view.w * alb.a;
    o_color = vec4(c + shafts, 1.0);
}
