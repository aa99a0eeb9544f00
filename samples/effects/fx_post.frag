#version 450 core
// raykit sample effects — fx_post.frag: exposure, tone mapping, sRGB (or the AO buffer shown).
#extension GL_GOOGLE_include_directive : require
#include "raykit/tonemap.glsl"
layout(binding = 0) uniform sampler2D u_hdr;
layout(binding = 1) uniform sampler2D u_ao;
layout(location = 0) uniform float u_exposure;
layout(location = 1) uniform int u_show_ao;
layout(location = 0) out vec4 o_color;
void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    if (u_show_ao != 0) {
        o_color = vec4(vec3(1.0 - texelFetch(u_ao, px, 0).x), 1.0);
        return;
    }
    o_color = vec4(rk_srgb_encode(rk_tonemap(rk_hdr_sanitize(texelFetch(u_hdr, px, 0).rgb * u_exposure), 4.0)), 1.0);
}
