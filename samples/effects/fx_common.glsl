// raykit sample effects — fx_common.glsl: the frame's uniform block of every pass.
#extension GL_GOOGLE_include_directive : require
#include "raykit/gbuffer.glsl"

layout(std140, binding = 0) uniform FxFrame {
    mat4 u_view_proj;  // world -> clip (reversed-Z, [0, 1] depth)
    mat4 u_view;       // world -> view
    mat4 u_inv_view;   // view -> world
    vec4 u_view_ray;   // gbuffer_view_ray(P)
    vec4 u_depth_k;    // xyz: gbuffer_depth_params(n, f, reversed = true); w: near plane
    vec4 u_proj;       // P[0][0], P[1][1], P[2][0], P[2][1]
    vec4 u_viewport;   // width, height, 1 / width, 1 / height
    vec4 u_sun_view;   // xyz: towards the sun, view space; w: 1 if the sun is above the horizon
    vec4 u_sun_color;  // rgb: sun irradiance
    vec4 u_sky;        // rgb: sky light on an upward surface; w: SSAO on (1) / off (0)
    vec4 u_light_uv;   // xy: the sun's screen position; z: rk_ls_fade; w: shaft strength
    vec4 u_eye;        // xyz: camera position (world)
};

/// The view-space position of the pixel at integer coordinates px (depth from the depth buffer).
vec3 fx_view_pos(sampler2D depth, ivec2 px)
{
    float d = texelFetch(depth, px, 0).x;
    vec2 ndc = (vec2(px) + 0.5) * u_viewport.zw * 2.0 - 1.0;
    return rk_gb_view_pos(ndc, rk_gb_linear_depth(d, u_depth_k.xyz), u_view_ray);
}

/// Sky radiance in view-space direction d (a sunset gradient and the sun's disk).
vec3 fx_sky(vec3 d_view)
{
    vec3 d = mat3(u_inv_view) * d_view;
    float up = clamp(d.y, 0.0, 1.0);
    vec3 c = mix(u_sky.rgb * 2.2 + vec3(0.05, 0.03, 0.01), u_sky.rgb * 0.8, sqrt(up));
    float s = max(dot(d_view, u_sun_view.xyz), 0.0);
    return c + u_sun_color.rgb * (0.05 * pow(s, 16.0) + 4.0 * smoothstep(0.9995, 0.9998, s));
}
