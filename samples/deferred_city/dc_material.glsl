// raykit sample deferred_city — dc_material.glsl: the surface of a building or ground fragment
// from its textures: albedo (sRGB, alpha = window glass), a two-channel normal map in the frame of
// the vertex tangent (raykit's normalmap.glsl: rk_nm_tbn, rk_nm_unpack_rg, rk_nm_perturb), street
// or paving from the city grid, and the night's lit windows. Both paths call dc_material().
#include "raykit/normalmap.glsl"
#include "raykit/hash.glsl"

layout(binding = 0) uniform sampler2DArray u_albedo;     // layer 0 ground, 1.. facades
layout(binding = 1) uniform sampler2DArray u_normalmap;  // RG8: tangent-space x, y in [0, 1]

layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec4 v_tangent;
layout(location = 3) in vec2 v_uv;
layout(location = 4) flat in vec2 v_mat;

DcSurface dc_material()
{
    DcSurface s;
    s.p = v_world;
    float layer = v_mat.x;
    vec4 a = texture(u_albedo, vec3(v_uv, layer));
    vec3 n_ts = rk_nm_unpack_rg(texture(u_normalmap, vec3(v_uv, layer)).rg);
    s.albedo = a.rgb;
    s.gloss = 0.05;
    s.spec = 0.04;
    s.emission = 0.0;
    if (layer < 0.5) {
        // Ground: the paving texture on the blocks, darker and flatter asphalt on the streets.
        float block = dc_block_mask(v_world);
        s.albedo = mix(s.albedo * vec3(0.28, 0.28, 0.3), s.albedo, block);
        n_ts = normalize(mix(vec3(0.35 * n_ts.x, 0.35 * n_ts.y, n_ts.z), n_ts, block));
        s.gloss = mix(0.12, 0.05, block);
    } else {
        // Facades: alpha marks window glass, glossy; at night a window bay may be lit.
        float glass = smoothstep(0.3, 0.7, a.a);
        s.gloss = mix(0.04, 0.8, glass);
        s.spec = mix(0.03, 0.5, glass);
        uint bay = uint(floor(v_uv.x) + 4096.0) * 4099u + uint(floor(v_uv.y) + 64.0);
        uint h = rk_hash_u32(bay ^ (uint(v_mat.y) * 2654435761u));
        if (u_ambient.w > 0.0 && glass > 0.5 && rk_u32_to_unit(h) < 0.3) {
            s.emission = glass * (0.5 + rk_u32_to_unit(rk_hash_u32(h)));
            s.albedo = mix(s.albedo, vec3(1.0, 0.62, 0.3), 0.85);
        }
    }
    s.n = rk_nm_perturb(rk_nm_tbn(v_normal, v_tangent), n_ts);
    return s;
}
