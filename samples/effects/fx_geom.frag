#version 450 core
// raykit sample effects — fx_geom.frag: albedo (alpha: the sun's self-shadowing visibility) and
// view-space normal. Relief materials (relief.glsl) displace the surface in the pixel shader: cone
// stepping (rk_relief_cone) on a conservative cone map, the normal from the depth map around the
// hit, self-shadowing towards the sun (rk_relief_shadow). SSAO gets the geometric normal: the
// depth buffer holds the flat surface, and a bumped normal would lean its hemisphere into it.
#extension GL_GOOGLE_include_directive : require
#include "fx_common.glsl"
#include "raykit/relief.glsl"
layout(binding = 6) uniform sampler2D u_bricks;  // RG32F: depth, cone ratio (REPEAT, LINEAR)
layout(binding = 7) uniform sampler2D u_paving;
layout(location = 0) uniform int u_relief;       // 0: relief materials drawn flat
layout(location = 0) in vec3 v_normal;
layout(location = 1) in vec3 v_albedo;
layout(location = 2) in vec3 v_world;
layout(location = 3) flat in int v_material;
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;      // the shading normal (relief-mapped)
layout(location = 2) out vec4 o_geo_normal;  // the geometric normal, for SSAO (it matches the depth)

float fx_hash(vec2 c) { return fract(sin(dot(c, vec2(12.9898, 78.233))) * 43758.5453); }

void main()
{
    vec3 n = normalize(v_normal);
    vec3 albedo = v_albedo;
    float sun_vis = 1.0;
    if (v_material != 0 && u_relief != 0) {
        bool bricks = v_material == 1;
        vec3 t = abs(n.y) > 0.5 ? vec3(1.0, 0.0, 0.0) : normalize(cross(vec3(0.0, 1.0, 0.0), n));
        vec3 b = cross(n, t);
        float tile = bricks ? 1.0 : 2.0;   // metres per texture repeat
        float depth = bricks ? 0.035 : 0.02; // metres at depth 1
        float s = depth / tile;             // in uv units
        vec2 uv = vec2(dot(v_world, t), dot(v_world, b)) / tile;
        vec3 vw = normalize(u_eye.xyz - v_world);
        vec3 v_ts = vec3(dot(vw, t), dot(vw, b), dot(vw, n));
        vec3 hit = bricks ? rk_relief_cone(u_bricks, uv, v_ts, s, 32u) : rk_relief_cone(u_paving, uv, v_ts, s, 32u);
        vec2 huv = vec2(hit.x, hit.y);
        // The normal of the displaced surface: depth differences around the hit.
        float e = 1.0 / 256.0;
        float du = bricks ? rk_relief_depth_at(u_bricks, huv + vec2(e, 0.0)) - rk_relief_depth_at(u_bricks, huv - vec2(e, 0.0))
                          : rk_relief_depth_at(u_paving, huv + vec2(e, 0.0)) - rk_relief_depth_at(u_paving, huv - vec2(e, 0.0));
        float dv = bricks ? rk_relief_depth_at(u_bricks, huv + vec2(0.0, e)) - rk_relief_depth_at(u_bricks, huv - vec2(0.0, e))
                          : rk_relief_depth_at(u_paving, huv + vec2(0.0, e)) - rk_relief_depth_at(u_paving, huv - vec2(0.0, e));
        vec3 n_ts = normalize(vec3(du * s / (2.0 * e), dv * s / (2.0 * e), 1.0));
        n = normalize(t * n_ts.x + b * n_ts.y + n * n_ts.z);
        // Mortar (deep) against brick or stone faces, each face its own shade.
        vec2 cells = bricks ? vec2(4.0, 8.0) : vec2(2.0, 2.0);
        vec2 cell = floor(vec2(huv.x * cells.x + (bricks ? 0.5 * mod(floor(huv.y * cells.y), 2.0) : 0.0), huv.y * cells.y));
        float shade = 0.8 + 0.35 * fx_hash(cell);
        vec3 face = bricks ? vec3(0.52, 0.25, 0.16) * shade : vec3(0.5, 0.48, 0.44) * shade;
        albedo = mix(face, vec3(0.62, 0.6, 0.56), smoothstep(0.45, 0.75, hit.z));
        vec3 lw = mat3(u_inv_view) * u_sun_view.xyz;
        vec3 l_ts = vec3(dot(lw, t), dot(lw, b), dot(lw, normalize(v_normal)));
        if (l_ts.z > 0.0)
            sun_vis = bricks ? rk_relief_shadow(u_bricks, hit, l_ts, s, 16u, 0.02) : rk_relief_shadow(u_paving, hit, l_ts, s, 16u, 0.02);
    }
    o_albedo = vec4(albedo, sun_vis);
    o_normal = vec4(mat3(u_view) * n, 0.0);
    o_geo_normal = vec4(mat3(u_view) * normalize(v_normal), 0.0);
}
