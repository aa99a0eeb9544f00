// raykit sample deferred_city — dc_gbuffer_read.glsl: a G-buffer texel back to a DcSurface
// (position from the reversed-Z depth: rk_gb_linear_depth, rk_gb_view_pos, the inverse view).
layout(binding = 0) uniform sampler2D u_gb_albedo;
layout(binding = 1) uniform usampler2D u_gb_normal;
layout(binding = 2) uniform sampler2D u_gb_material;
layout(binding = 3) uniform usampler2D u_gb_extra;
layout(binding = 8) uniform sampler2D u_gb_depth;

/// False for sky pixels (depth 0: reversed-Z's far plane, the clear value).
bool dc_read_gbuffer(ivec2 px, out DcSurface s, out float dist, out vec3 view_dir)
{
    float d = texelFetch(u_gb_depth, px, 0).x;
    vec2 ndc = (vec2(px) + 0.5) * u_viewport.zw * 2.0 - 1.0;
    vec3 ray = mat3(u_inv_view) * rk_gb_view_pos(ndc, 1.0, u_view_ray);
    view_dir = -ray;
    if (d <= 0.0) return false;
    dist = rk_gb_linear_depth(d, u_depth_k.xyz);
    s.p = (u_inv_view * vec4(rk_gb_view_pos(ndc, dist, u_view_ray), 1.0)).xyz;
    s.n = rk_gb_oct_unpack_snorm(texelFetch(u_gb_normal, px, 0).x, 16u);
    s.albedo = texelFetch(u_gb_albedo, px, 0).rgb;
    vec4 m = texelFetch(u_gb_material, px, 0);
    s.gloss = m.x;
    vec2 se = rk_gb_unpack_half2(texelFetch(u_gb_extra, px, 0).x);
    s.spec = se.x;
    s.emission = se.y;
    view_dir = rk_normalize_safe(u_eye.xyz - s.p, s.n);
    return true;
}
