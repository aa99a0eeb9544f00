// raykit sample deferred_city — dc_common.glsl: what every pass of the deferred city shares: the
// frame's uniform block, the light list, the surface a G-buffer texel holds, and the lighting
// itself (sun with cascaded shadow maps, windowed point lights, sky, emission). The forward path
// (dc_forward.frag) and the deferred passes (dc_sun.frag, dc_light.frag) call the same functions
// here, so the two images differ only by what the G-buffer stores.
#extension GL_GOOGLE_include_directive : require
#include "raykit/gbuffer.glsl"
#include "raykit/light_volume.glsl"
#include "raykit/shadow_filter.glsl"

layout(std140, binding = 0) uniform DcFrame {
    mat4 u_view_proj;      // world -> clip (reversed-Z, [0, 1] depth)
    mat4 u_inv_view;       // view -> world
    mat4 u_shadow_mat[4];  // world -> (u, v, depth) of each cascade (Eq. 5.1, [0, 1] depth)
    vec4 u_splits;         // far end of each cascade (view distance)
    vec4 u_cascade_texel;  // one shadow texel's width in world units, per cascade
    vec4 u_view_ray;       // gbuffer_view_ray(P)
    vec4 u_depth_k;        // xyz: gbuffer_depth_params(n, f, reversed = true)
    vec4 u_sun_dir;        // xyz: towards the sun (unit); w: 1 = shadows
    vec4 u_sun_color;      // rgb: sun irradiance; w: cascade blend band (view units)
    vec4 u_ambient;        // rgb: sky light on an upward surface; w: window emission scale
    vec4 u_eye;            // xyz: camera position (world); w: point lights (forward path)
    vec4 u_viewport;       // width, height, 1 / width, 1 / height
    vec4 u_layout;         // city grid: pitch, block, boulevard - street, blocks_x
    vec4 u_layout2;        // blocks_z, shadow map size, show cascades (0/1), PCF taps
};

struct DcLight {
    vec4 pos_radius;  // xyz position, w radius (the windowed falloff is 0 from there on)
    vec4 color;       // rgb intensity (I / d² at distance d), w unused
};
layout(std430, binding = 1) readonly buffer DcLights { DcLight u_lights[]; };

layout(binding = 4) uniform sampler2DShadow u_cascade0;
layout(binding = 5) uniform sampler2DShadow u_cascade1;
layout(binding = 6) uniform sampler2DShadow u_cascade2;
layout(binding = 7) uniform sampler2DShadow u_cascade3;

#define DC_PI 3.14159265358979f

/// The surface a pixel shows, from the material textures (forward) or the G-buffer (deferred).
struct DcSurface {
    vec3 p;         // world position
    vec3 n;         // shading normal (unit)
    vec3 albedo;    // linear
    float gloss;    // Blinn-Phong exponent / 512, in [0, 1]
    float spec;     // specular weight
    float emission; // emitted radiance (times albedo)
};

float dc_exponent(float gloss) { return 2.0 + 510.0 * gloss; }

/// One cascade's lit fraction at uvz: Vogel PCF turned per pixel, radius 1.5 texels.
float dc_cascade_pcf(uint c, vec3 uvz, float phi)
{
    float radius = 1.5 / u_layout2.y;
    uint taps = uint(u_layout2.w);
    if (c == 0u) return rk_sh_pcf_vogel(u_cascade0, uvz, radius, taps, phi);
    if (c == 1u) return rk_sh_pcf_vogel(u_cascade1, uvz, radius, taps, phi);
    if (c == 2u) return rk_sh_pcf_vogel(u_cascade2, uvz, radius, taps, phi);
    return rk_sh_pcf_vogel(u_cascade3, uvz, radius, taps, phi);
}

/// The sun's lit fraction for surface s at view distance `dist`: normal-offset and slope-scaled
/// bias, the cascade of that distance, blended with the next one near its far end.
float dc_cascade_lookup(uint c, DcSurface s, float ndl, float phi)
{
    vec3 p = rk_sh_normal_offset(s.p, s.n, ndl, u_cascade_texel[c], 1.5);
    vec3 uvz = rk_sh_project(u_shadow_mat[c], p);
    uvz.z -= rk_sh_slope_bias(ndl, 2.0e-5, 1.0e-4, 2.0e-3);
    return dc_cascade_pcf(c, uvz, phi);
}

float dc_sun_shadow(DcSurface s, float dist, float ndl, uvec2 pixel)
{
    if (u_sun_dir.w < 0.5) return 1.0;
    uint c = rk_sh_cascade_index(dist, u_splits);
    if (c >= 4u) return 1.0;
    float phi = rk_sh_rotation(pixel);
    float lit = dc_cascade_lookup(c, s, ndl, phi);
    float w = rk_sh_cascade_blend(dist, u_splits[c], u_sun_color.w * (c + 1u));
    if (w > 0.0) {
        float next = c < 3u ? dc_cascade_lookup(c + 1u, s, ndl, phi) : 1.0;
        lit = mix(lit, next, w);
    }
    return lit;
}

/// Blinn-Phong, normalised ((e + 8) / 8 pi), over a Lambert base.
vec3 dc_brdf(DcSurface s, vec3 l, vec3 v)
{
    vec3 h = rk_normalize_safe(l + v, s.n);
    float e = dc_exponent(s.gloss);
    float sp = s.spec * (e + 8.0) / (8.0 * DC_PI) * pow(max(dot(s.n, h), 0.0), e);
    return s.albedo / DC_PI + vec3(sp);
}

/// A point light's contribution: windowed inverse-square falloff (rk_lv_point_falloff, exactly 0
/// from the radius on, so a light volume drawn at that radius loses nothing).
vec3 dc_point_light(DcSurface s, vec3 v, DcLight L)
{
    vec3 d = L.pos_radius.xyz - s.p;
    float d2 = dot(d, d);
    float r = L.pos_radius.w;
    float f = rk_lv_point_falloff(d2, 1.0 / (r * r), 0.25);
    if (f <= 0.0) return vec3(0.0);
    vec3 l = d * inversesqrt(max(d2, 1e-12));
    float ndl = dot(s.n, l);
    if (ndl <= 0.0) return vec3(0.0);
    return L.color.rgb * (f * ndl) * dc_brdf(s, l, v);
}

/// Sky radiance in direction d (the background of both paths).
vec3 dc_sky(vec3 d)
{
    float up = clamp(d.y, 0.0, 1.0);
    vec3 horizon = u_ambient.rgb * 1.6 + vec3(0.002, 0.002, 0.003);
    vec3 zenith = u_ambient.rgb * 0.7 + vec3(0.0005, 0.0008, 0.002);
    vec3 c = mix(horizon, zenith, sqrt(up));
    float sun = max(dot(d, u_sun_dir.xyz), 0.0);
    return c + u_sun_color.rgb * (0.02 * pow(sun, 8.0) + 2.0 * pow(sun, 2000.0));
}

/// Sun, sky light and emission of surface s seen from the eye (no point lights).
vec3 dc_shade_sun(DcSurface s, vec3 v, float dist, uvec2 pixel)
{
    vec3 c = s.albedo * u_ambient.rgb * (0.6 + 0.4 * s.n.y) + s.albedo * (s.emission * u_ambient.w);
    float ndl = dot(s.n, u_sun_dir.xyz);
    if (ndl > 0.0 && dot(u_sun_color.rgb, vec3(1.0)) > 0.0) {
        float lit = dc_sun_shadow(s, dist, ndl, pixel);
        c += u_sun_color.rgb * (lit * ndl) * dc_brdf(s, u_sun_dir.xyz, v);
    }
    if (u_layout2.z > 0.5) {
        uint k = rk_sh_cascade_index(dist, u_splits);
        vec3 tint = k == 0u ? vec3(1.0, 0.35, 0.35) : k == 1u ? vec3(0.35, 1.0, 0.35) : k == 2u ? vec3(0.4, 0.5, 1.0)
                  : k == 3u ? vec3(1.0, 1.0, 0.3) : vec3(1.0);
        c *= tint;
    }
    return c;
}

/// 1 on the paved blocks of the city grid, 0 on the streets (city_gen.hpp's layout).
float dc_block_mask(vec3 p)
{
    float pitch = u_layout.x, block = u_layout.y, extra = 0.5 * u_layout.z;
    float nx = u_layout.w, nz = u_layout2.x;
    float ix = floor(p.x / pitch + 0.5 * (nx - 1.0) + 0.5);
    float cx = (ix - 0.5 * (nx - 1.0)) * pitch;
    float zz = abs(p.z) - extra;  // blocks are pushed away from the boulevard by `extra`
    float iz = floor((zz * sign(p.z)) / pitch + 0.5 * (nz - 1.0) + 0.5);
    float cz = (iz - 0.5 * (nz - 1.0)) * pitch;
    float inx = step(abs(p.x - cx), 0.5 * block) * step(0.0, ix) * step(ix, nx - 1.0);
    float inz = step(extra, abs(p.z)) * step(abs(zz * sign(p.z) - cz), 0.5 * block) * step(0.0, iz) * step(iz, nz - 1.0);
    return inx * inz;
}
