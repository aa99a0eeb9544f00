#version 450 core
// raykit sample city — city_post.frag: CITY_POST_MODE 0 scales the HDR image by the exposure
// (before the bloom, so its threshold is in display-referred units); 1 tone-maps with
// shaders/raykit/tonemap.glsl's default operator and encodes sRGB.
#extension GL_GOOGLE_include_directive : require
#include "raykit/color.glsl"
#include "raykit/tonemap.glsl"
layout(binding = 0) uniform sampler2D u_src;
layout(location = 0) uniform float u_exposure;
layout(location = 0) out vec4 o_color;
void main()
{
    vec3 c = rk_hdr_sanitize(texelFetch(u_src, ivec2(gl_FragCoord.xy), 0).rgb);
#if CITY_POST_MODE == 0
    o_color = vec4(c * u_exposure, 1.0);
#else
    o_color = vec4(rk_srgb_encode(rk_tonemap(c, RK_HDR_MAX)), 1.0);
#endif
}
