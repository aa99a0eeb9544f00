#version 450 core
// raykit sample effects — fx_puff.vert: smoke puffs as camera-facing quads (6 vertices an instance):
//   FX_PUFF_MODE 0  a plain billboard of half-size r;
//   FX_PUFF_MODE 1  FX_SLICES slices laid out as a sphere (volume_slices' layout), each with the
//                   thesis's uv correction (rk_vol_slice_uv), one instance per slice;
//   FX_PUFF_MODE 2  a raytraced volume's proxy, sized by rk_vol_billboard_half_size so that it never
//                   clips the sphere.
#extension GL_GOOGLE_include_directive : require
#include "fx_common.glsl"
#include "raykit/volume.glsl"
struct FxPuff {
    vec4 centre_radius;
    vec4 colour_opacity;
};
layout(std430, binding = 2) readonly buffer FxPuffs { FxPuff u_puffs[]; };
layout(location = 0) out vec2 v_uv;
layout(location = 1) out vec3 v_view;
layout(location = 2) out vec2 v_q;
layout(location = 3) flat out int v_puff;
void main()
{
    const vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
    vec2 q = corners[gl_VertexID % 6];
    int puff = gl_InstanceID / FX_SLICES;
    int slice = gl_InstanceID % FX_SLICES;
    vec3 c = u_puffs[puff].centre_radius.xyz;
    float r = u_puffs[puff].centre_radius.w;
    vec3 eye = u_eye.xyz;
    vec3 n = rk_normalize_safe(eye - c, vec3(0.0, 0.0, 1.0));
    vec3 au = rk_normalize_safe(cross(vec3(0.0, 1.0, 0.0), n), vec3(1.0, 0.0, 0.0));
    vec3 av = cross(n, au);
    vec3 centre = c;
    float half_size = r;
#if FX_PUFF_MODE == 1
    float z = r * ((2.0 * float(slice) + 1.0) / float(FX_SLICES) - 1.0);
    centre = c + n * z;
    half_size = sqrt(max(r * r - z * z, 0.0));
#elif FX_PUFF_MODE == 2
    half_size = min(rk_vol_billboard_half_size(r, length(eye - c)), 1.0e4 * r);
#endif
    vec3 p = centre + (au * q.x + av * q.y) * half_size;
#if FX_PUFF_MODE == 1
    v_uv = rk_vol_slice_uv(p, eye, c, n, au, av, vec2(r));
#else
    v_uv = q * (half_size / (2.0 * r)) + 0.5;
#endif
    v_q = q * (half_size / r);
    v_puff = puff;
    v_view = (u_view * vec4(p, 1.0)).xyz;
    gl_Position = u_view_proj * vec4(p, 1.0);
}
