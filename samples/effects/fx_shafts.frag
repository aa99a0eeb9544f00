#version 450 core
// raykit sample effects — fx_shafts.frag: lightshafts.glsl's radial accumulation (half resolution).
#extension GL_GOOGLE_include_directive : require
#include "fx_common.glsl"
#include "raykit/lightshafts.glsl"
layout(binding = 0) uniform sampler2D u_occ;  // LINEAR, CLAMP_TO_EDGE
layout(location = 0) out vec4 o_shafts;
void main()
{
    vec2 uv = gl_FragCoord.xy / vec2(textureSize(u_occ, 0));
    o_shafts = vec4(rk_ls_accumulate(u_occ, uv, u_light_uv.xy, 64u, 0.9, 1.0 / 64.0, 0.975, 1.2), 1.0);
}
