#version 450 core
// raykit sample effects — fx_ssao.frag: ssao.glsl's normal-oriented hemisphere (FX_SSAO_PASS 0) and
// its depth-aware blur (pass 1: horizontal, 2: vertical).
#extension GL_GOOGLE_include_directive : require
#include "fx_common.glsl"
#include "raykit/ssao.glsl"
layout(binding = 0) uniform sampler2D u_depth;   // NEAREST
layout(binding = 1) uniform sampler2D u_normal;  // view-space geometric normal
layout(binding = 2) uniform sampler2D u_ao_in;   // blur input
layout(std140, binding = 1) uniform FxKernel { vec4 u_kernel[RK_AO_MAX_SAMPLES]; vec4 u_noise[16]; };
layout(location = 0) out vec4 o_ao;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec2 uv = gl_FragCoord.xy * u_viewport.zw;
#if FX_SSAO_PASS == 0
    if (texelFetch(u_depth, px, 0).x <= 0.0) { o_ao = vec4(0.0); return; }
    vec3 k[RK_AO_MAX_SAMPLES];
    for (int i = 0; i < RK_AO_MAX_SAMPLES; ++i) k[i] = u_kernel[i].xyz;
    vec3 p = rk_ao_view_pos(u_depth, uv, u_depth_k.xyz, u_view_ray);
    vec3 n = texelFetch(u_normal, px, 0).xyz;
    vec2 rot = u_noise[(px.y & 3) * 4 + (px.x & 3)].xy;
    o_ao = vec4(rk_ao_hemisphere(u_depth, p, n, 0.8, k, 16u, rot, 0.02, u_viewport.zw, u_depth_k.xyz, u_view_ray, u_proj));
#else
    vec2 step = FX_SSAO_PASS == 1 ? vec2(u_viewport.z, 0.0) : vec2(0.0, u_viewport.w);
    o_ao = vec4(rk_ao_blur(u_ao_in, u_depth, uv, step, 2, 20.0, u_depth_k.xyz));
#endif
}
