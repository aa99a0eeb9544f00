#version 450 core
// raykit sample effects — fx_occlusion.frag: the light shafts' occlusion buffer (half resolution):
// the sun's disk where the sky is seen (rk_ls_disk), black where geometry is.
#extension GL_GOOGLE_include_directive : require
#include "fx_common.glsl"
#include "raykit/lightshafts.glsl"
layout(binding = 0) uniform sampler2D u_depth;  // full resolution, NEAREST
layout(location = 0) out vec4 o_occ;
void main()
{
    vec2 uv = gl_FragCoord.xy / vec2(textureSize(u_depth, 0) / 2);
    float d = textureLod(u_depth, uv, 0.0).x;
    float disk = d <= 0.0 ? rk_ls_disk(uv, u_light_uv.xy, 0.22, u_viewport.x / u_viewport.y) : 0.0;
    o_occ = vec4(u_sun_color.rgb * disk, 1.0);
}
