#version 450 core
// raykit sample deferred_city — dc_sun.frag: the deferred pass of everything but the point lights
// (sun with cascaded shadows, sky light, emission; the sky where nothing was drawn), full screen.
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"
#include "dc_gbuffer_read.glsl"
layout(location = 0) out vec4 o_color;
void main()
{
    DcSurface s;
    float dist;
    vec3 v;
    ivec2 px = ivec2(gl_FragCoord.xy);
    if (!dc_read_gbuffer(px, s, dist, v)) {
        o_color = vec4(dc_sky(normalize(-v)), 1.0);
        return;
    }
    o_color = vec4(dc_shade_sun(s, v, dist, uvec2(px)), 1.0);
}
