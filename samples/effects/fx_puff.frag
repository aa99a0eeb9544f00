#version 450 core
// raykit sample effects — fx_puff.frag: a smoke puff's colour and opacity (premultiplied):
//   FX_PUFF_MODE 0  billboard: the texture's alpha (hard line where it meets geometry);
//   FX_PUFF_MODE 1  slices: rk_vol_slice_alpha so that FX_SLICES slices compose to the texture's alpha;
//   FX_PUFF_MODE 2  raytraced (soft particle): the visible length of the primitive FX_PUFF_PRIM
//                   (0 constant thickness, 1 linearly decreasing, 2 thickness from the texture's
//                   alpha, 3 true sphere with rk_vol_sphere_edge_fade) in front of the scene depth,
//                   through the opacity function FX_PUFF_OPACITY (0 linear, 1 log, 2 sqrt).
#extension GL_GOOGLE_include_directive : require
#include "fx_common.glsl"
#include "raykit/volume.glsl"
struct FxPuff {
    vec4 centre_radius;
    vec4 colour_opacity;
};
layout(std430, binding = 2) readonly buffer FxPuffs { FxPuff u_puffs[]; };
layout(binding = 5) uniform sampler2D u_smoke;
layout(binding = 0) uniform sampler2D u_depth;
layout(location = 0) in vec2 v_uv;
layout(location = 1) in vec3 v_view;
layout(location = 2) in vec2 v_q;
layout(location = 3) flat in int v_puff;
layout(location = 0) out vec4 o_color;

float fx_opacity(float l, float l_full)
{
#if FX_PUFF_OPACITY == 0
    return rk_vol_opacity_linear(l, l_full);
#elif FX_PUFF_OPACITY == 1
    return rk_vol_opacity_log(l, l_full);
#else
    return rk_vol_opacity_sqrt(l, l_full);
#endif
}

void main()
{
    vec4 tex = texture(u_smoke, v_uv);
    FxPuff P = u_puffs[v_puff];
    float r = P.centre_radius.w;
    float A = P.colour_opacity.w;
#if FX_PUFF_MODE == 0
    float a = tex.a * A;
#elif FX_PUFF_MODE == 1
    float a = rk_vol_slice_alpha(tex.a * A, uint(FX_SLICES));
#else
    vec3 dir = normalize(v_view);
    float ts = rk_vol_scene_distance(texelFetch(u_depth, ivec2(gl_FragCoord.xy), 0).x, u_depth_k.xyz, dir);
    float tn = rk_vol_near_distance(u_depth_k.w, dir);
    float t_bb = length(v_view);
#if FX_PUFF_PRIM == 0
    vec2 span = rk_vol_span_slab(t_bb, 2.0 * r);
#elif FX_PUFF_PRIM == 1
    vec2 span = rk_vol_span_pyramid(t_bb, 2.0 * r, v_q);
#elif FX_PUFF_PRIM == 2
    vec2 span = rk_vol_span_slab(t_bb, 2.0 * r * tex.a);
#else
    vec3 c_view = (u_view * vec4(P.centre_radius.xyz, 1.0)).xyz;
    vec2 span = rk_ray_sphere(vec3(0.0), dir, c_view, r);
#endif
    float l = rk_vol_visible_length(span, ts, tn);
    float a = fx_opacity(l, 2.0 * r) * A;
#if FX_PUFF_PRIM == 3
    a *= rk_vol_sphere_edge_fade(span, r) * tex.a;
#elif FX_PUFF_PRIM != 2
    a *= tex.a;
#endif
#endif
    vec3 light = u_sky.rgb * 1.2 + u_sun_color.rgb * 0.35 * u_sun_view.w;
    vec3 col = P.colour_opacity.rgb * tex.rgb * light;
    o_color = vec4(col * a, a);
}
