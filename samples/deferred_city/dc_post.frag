#version 450 core
// raykit sample deferred_city — dc_post.frag: edge anti-aliasing for deferred shading (Fahlén
// §2.4; raykit's edge_aa.glsl: depth kinks and normal creases from the G-buffer, a 4-tap blur),
// then exposure, tone mapping (rk_tonemap) and sRGB encoding.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"
#include "raykit/edge_aa.glsl"
#include "raykit/tonemap.glsl"
layout(binding = 9) uniform sampler2D u_hdr;
layout(binding = 1) uniform usampler2D u_gb_normal;
layout(binding = 8) uniform sampler2D u_gb_depth;
layout(location = 0) uniform float u_exposure;
layout(location = 1) uniform int u_edge_aa;  // 0 off, 1 on, 2 show the edge weight
layout(location = 0) out vec4 o_color;

float dc_depth(ivec2 p) { return texelFetch(u_gb_depth, clamp(p, ivec2(0), ivec2(u_viewport.xy) - 1), 0).x; }
vec3 dc_normal(ivec2 p)
{
    return rk_gb_oct_unpack_snorm(texelFetch(u_gb_normal, clamp(p, ivec2(0), ivec2(u_viewport.xy) - 1), 0).x, 16u);
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec2 uv = gl_FragCoord.xy * u_viewport.zw;
    vec3 hdr;
    float edge = 0.0;
    if (u_edge_aa != 0) {
        float d[9];
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) d[j * 3 + i] = dc_depth(px + ivec2(i - 1, j - 1));
        float de = rk_aa_depth_edge(d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8], 0.2, 1.0e-5);
        float ne = rk_aa_normal_edge(dc_normal(px), dc_normal(px + ivec2(-1, 0)), dc_normal(px + ivec2(1, 0)),
                                     dc_normal(px + ivec2(0, 1)), dc_normal(px + ivec2(0, -1)), 0.1);
        edge = rk_aa_combine(de, ne, 0u);
        hdr = vec3(0.0);
        for (uint k = 0u; k < 4u; ++k) hdr += texture(u_hdr, uv + rk_aa_blur_offset(k, edge) * u_viewport.zw).rgb;
        hdr *= 0.25;
    } else {
        hdr = texelFetch(u_hdr, px, 0).rgb;
    }
    vec3 c = rk_srgb_encode(rk_tonemap(rk_hdr_sanitize(hdr * u_exposure), 4.0));
    if (u_edge_aa == 2) c = mix(c * 0.4, vec3(1.0, 0.2, 0.1), edge);
    o_color = vec4(c, 1.0);
}
