#version 450 core
// raykit sample city — city_building.frag: the city's building material. The window texel is
// raykit's rk_im_shade_window (shaders/raykit/interior_shading.glsl: interior trace, room texture
// array, furniture sprite planes, per-room lights, distance fade, Fresnel glass, composition), the
// same core as samples/common/interior_building.frag; around it, what a whole city needs and that
// copyable material does not do: one draw for every building (per-building grid, seed, lit
// probability, facade from an SSBO instead of uniforms), facades from a texture array with
// analytic derivatives (round towers included), the shadowed sun and sky light of the scene, the
// window reflection from a dual-paraboloid map with the ray-plane correction of
// envmap_correction.glsl, and a second output the host checks.
//
// Macros set by main.cpp: RK_IM_SHADING 1, RK_IM_ROOM_LIGHTS 1, RK_IM_FURNITURE_LAYERS 2,
// RK_IM_FADE 1; CITY_AUX 1 writes output 1.
// Output 1 (CITY_AUX): x = 4 (building + 1) + lit + 2 (facade faces z), yzw = the room's cell,
// for texels with window mask > 0.5 and a valid interior trace; 0 elsewhere.
#extension GL_GOOGLE_include_directive : require
#include "city_common.glsl"
#include "raykit/interior_shading.glsl"
#include "raykit/paraboloid_sample.glsl"
#include "raykit/envmap_correction.glsl"

layout(binding = 0) uniform sampler2DArray u_facades;
layout(binding = 3) uniform sampler2D u_env;       // dual-paraboloid atlas (world directions)
layout(binding = 5) uniform sampler2DArray u_rooms;
layout(binding = 7) uniform sampler2DArray u_sprites;

layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) flat in int v_id;
layout(location = 0) out vec4 o_color;
layout(location = 1) out vec4 o_aux;

// The environment seen in a pane at world point p (normal n) along the reflection r: the city map
// looked up towards where r meets a plane `street` metres in front of the window (the facades
// across the street), or the sky alone while the map itself is being rendered.
vec3 city_reflection(vec3 p, vec3 n, vec3 r, float cos_i)
{
    if (u_env_center.w < 0.5) return city_sky(r);
    float d = max(dot(p - u_env_center.xyz, n) + u_env_params.z, 1.0);
    vec3 rc = rk_reflect_correct_plane(r, p, u_env_center.xyz, n, d);
    float lod = rk_paraboloid_lod_from_incidence(cos_i, u_env_params.y);
    return rk_dual_paraboloid_sample_lod(u_env, rc, u_env_params.x, lod, u_env_params.y).rgb;
}

void main()
{
    // Screen-space derivatives first, before any branch: llvmpipe drops the helper lanes of a
    // 2x2 quad from the execution mask after a divergent return, and derivatives taken later
    // along a triangle's edges are garbage there.
    vec3 dp_dx = dFdx(v_world), dp_dy = dFdy(v_world);
    CityBuilding b = u_buildings[v_id];
    vec3 n = normalize(v_normal);
    vec3 centre = vec3(b.c.z, 0.0, b.c.w);
    vec3 p = v_world - centre;           // object space
    vec3 cam = u_cam.xyz - centre;
    o_aux = vec4(0.0);

    // Roofs: gravel, no windows.
    if (n.y > 0.5) {
        float g = 0.8 + 0.4 * city_hash12(v_world.xz * 4.0);
        o_color = vec4(vec3(0.16, 0.155, 0.15) * g * city_outdoor_light(v_world, n, 1.0), 1.0);
        return;
    }

    rk_im_grid grid;
    grid.origin = b.a.xyz;
    grid.room_size = b.b.xyz;
    uint seed = uint(b.b.w);

    // Facade coordinates: u along the wall in window bays, v up in storeys (a tile is one bay of
    // one storey), with derivatives from dp (no seam where atan wraps on the round towers).
    vec3 tangent;
    float bay;
    float u;
    if (b.c.x > 0.5) {
        float radius = length(p.xz);
        bay = b.d.x;
        u = atan(p.z, p.x) * radius / bay;
        tangent = vec3(-p.z, 0.0, p.x) / max(radius, 1e-3);
    } else if (abs(n.x) > 0.5) {
        bay = b.d.y;
        u = (p.z - grid.origin.z) / bay;
        tangent = vec3(0.0, 0.0, 1.0);
    } else {
        bay = b.d.x;
        u = (p.x - grid.origin.x) / bay;
        tangent = vec3(1.0, 0.0, 0.0);
    }
    float v = (p.y - grid.origin.y) / grid.room_size.y;
    vec2 duv_dx = vec2(dot(dp_dx, tangent) / bay, dp_dx.y / grid.room_size.y);
    vec2 duv_dy = vec2(dot(dp_dy, tangent) / bay, dp_dy.y / grid.room_size.y);
    vec4 facade = textureGrad(u_facades, vec3(u, v, b.c.y), duv_dx, duv_dy);
    vec3 albedo = facade.rgb * mix(vec3(0.85, 0.9, 1.0), vec3(1.1, 1.0, 0.85), b.d.w);
    float ao = 0.55 + 0.45 * clamp(v_world.y / 6.0, 0.0, 1.0);
    vec4 exterior = vec4(albedo * city_outdoor_light(v_world, n, ao), facade.a);

    vec3 to_eye = u_cam.xyz - v_world;
    float dist = length(to_eye);
    vec3 colour = exterior.rgb;
    if (rk_im_needs_interior(exterior.a)) {
        vec3 e = to_eye / max(dist, 1e-6);
        float cos_i = rk_window_glass_cos(n, e);
        vec3 reflection = city_reflection(v_world, n, reflect(-e, n), cos_i);

        rk_im_window_params prm;
        prm.grid = grid;
        prm.normal = n;
        prm.tangent = normalize(cross(vec3(0.0, 1.0, 0.0), n));
        prm.bitangent = cross(n, prm.tangent);
        prm.seed = seed;
        prm.jitter = vec3(0.0);
        prm.variants = float(CITY_ROOM_VARIANTS);
        prm.atlas = vec4(0.0);
        prm.tint_amount = 0.0;
        prm.lit_probability = b.a.w;
        prm.light_warm = vec3(1.0, 0.68, 0.38) * u_sun_color.w;
        prm.light_cool = vec3(0.80, 0.90, 1.05) * u_sun_color.w;
        prm.light_level = vec2(0.5, 1.5);
        prm.unlit = u_env_params.w;           // daylight reaching an unlit room
        prm.glass_tint = vec3(0.80, 0.86, 0.84);
        prm.glass_eta = 1.52;
        prm.glass_panes = 2.0;
        float depth = dot(abs(n), grid.room_size);
        prm.furniture_depth = vec4(0.3, 0.8, 0.0, 0.0) * depth;
        prm.flipbook = ivec4(4, 4, CITY_SHEET_CELLS, 0);
        prm.flipbook_fps = 0.0;               // a fixed cell per room (the sheets mix objects)
        prm.time = u_cam.w;
        prm.alpha_threshold = 0.5;
        prm.fade_range = vec2(250.0, 450.0);
        prm.average_colour = vec3(0.30, 0.25, 0.20);
        colour = rk_im_shade_window(exterior, p, cam, dp_dx, dp_dy, dist, reflection, prm, u_rooms, u_sprites);

#if CITY_AUX
        if (exterior.a > 0.5) {
            rk_im_hit h = rk_im_trace_grad(p, cam, n, dp_dx, dp_dy, grid);
            if (h.valid) {
                float lit = rk_im_room_lit(h.room, b.a.w, seed) ? 1.0 : 0.0;
                float axis = abs(n.z) > abs(n.x) ? 1.0 : 0.0;
                o_aux = vec4(4.0 * float(v_id + 1) + lit + 2.0 * axis, vec3(h.room));
            }
        }
#endif
    }
    o_color = vec4(colour, 1.0);
}
