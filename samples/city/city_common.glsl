// raykit sample city — city_common.glsl: what every pass of the city shares: the frame uniforms,
// the building table, the procedural sky, the street pattern, the sun's shadow map and the outdoor
// lighting. Sample code (GLSL only), not part of the shared GLSL/C++ dialect.
#ifndef CITY_COMMON_GLSL
#define CITY_COMMON_GLSL

layout(std140, binding = 0) uniform CityFrame {
    mat4 u_view_proj;
    mat4 u_inv_view_proj;
    mat4 u_shadow_mat;     // world -> shadow map [0, 1]^3
    vec4 u_cam;            // xyz camera position, w time (s)
    vec4 u_sun_dir;        // xyz unit vector towards the sun, w sun illuminance scale
    vec4 u_sun_color;      // rgb, w interior light intensity
    vec4 u_sky_zenith;     // rgb, w dusk amount (0 day .. 1 dusk)
    vec4 u_sky_horizon;    // rgb, w street-light intensity
    vec4 u_env_center;     // xyz capture point of the reflection map, w 1 = reflections on
    vec4 u_env_params;     // x guard scale, y max lod, z distance to the facades across the street, w unlit-room light
    vec4 u_layout0;        // blocks x, blocks z, block size, street width
    vec4 u_layout1;        // boulevard width, sidewalk width, city half extent, -
};

struct CityBuilding {
    vec4 a;  // origin.xyz, lit probability c
    vec4 b;  // room size.xyz, seed (exact float)
    vec4 c;  // kind (0 box, 1 cylinder), facade layer, centre x, centre z
    vec4 d;  // half x, half z (cylinder: radius), height, tint
};
layout(std430, binding = 1) readonly buffer CityBuildings { CityBuilding u_buildings[]; };

layout(binding = 6) uniform sampler2DShadow u_shadow_map;

// ---------------------------------------------------------------------------------------------
// Sky

vec3 city_sky(vec3 dir)
{
    dir = normalize(dir);
    vec3 sun = u_sun_dir.xyz;
    float mu = max(dot(dir, sun), 0.0);
    float e = dir.y;
    float up = max(e, 0.0);
    vec3 sky = mix(u_sky_horizon.rgb, u_sky_zenith.rgb, pow(up, 0.45));
    // Horizon glow towards the sun (stronger at dusk), and a bright aureole.
    float towards = clamp(0.5 + 0.5 * dot(normalize(vec2(dir.x, dir.z) + 1e-6), normalize(vec2(sun.x, sun.z) + 1e-6)), 0.0, 1.0);
    sky += u_sun_color.rgb * (0.25 + 0.8 * u_sky_zenith.w) * pow(towards, 6.0) * exp(-up * 6.0) * 0.6;
    sky += u_sun_color.rgb * (pow(mu, 12.0) * 0.35 + pow(mu, 200.0) * 2.0);
    // Sun disk (0.27 deg radius, limb-darkened), kept finite and moderate for the bloom.
    float disk = smoothstep(0.999975, 0.999990, mu);
    sky += u_sun_color.rgb * disk * 400.0;
    // Below the horizon: the haze over a distant ground.
    if (e < 0.0) sky = u_sky_horizon.rgb;  // the haze the far ground fades into
    return sky;
}

// Average sky radiance seen by a surface of normal n (a cheap hemisphere integral).
vec3 city_sky_ambient(vec3 n)
{
    vec3 top = mix(u_sky_horizon.rgb, u_sky_zenith.rgb, 0.6);
    vec3 ground = u_sky_horizon.rgb * 0.25 + u_sun_color.rgb * max(u_sun_dir.y, 0.0) * 0.08;
    return mix(ground, top, 0.5 + 0.5 * n.y);
}

// ---------------------------------------------------------------------------------------------
// Sun and shadows

float city_shadow(vec3 world, vec3 n)
{
    vec4 s = u_shadow_mat * vec4(world + n * 0.25, 1.0);
    vec3 p = s.xyz / s.w;
    if (p.x <= 0.0 || p.x >= 1.0 || p.y <= 0.0 || p.y >= 1.0 || p.z >= 1.0) return 1.0;
    vec2 texel = 1.0 / vec2(textureSize(u_shadow_map, 0));
    float sum = 0.0;
    for (int i = 0; i < 4; ++i) {
        vec2 o = vec2(float(i & 1) - 0.5, float(i >> 1) - 0.5) * texel * 1.5;
        sum += texture(u_shadow_map, vec3(p.xy + o, p.z - 0.0015));
    }
    return sum * 0.25;
}

// Outdoor light on a diffuse surface: sun (shadowed) + sky + a little street light at night.
vec3 city_outdoor_light(vec3 world, vec3 n, float ao)
{
    float ndl = max(dot(n, u_sun_dir.xyz), 0.0);
    float sh = ndl > 0.0 ? city_shadow(world, n) : 0.0;
    vec3 l = u_sun_color.rgb * u_sun_dir.w * ndl * sh;
    l += city_sky_ambient(n) * ao;
    return l;
}

// ---------------------------------------------------------------------------------------------
// Streets

// Nearest block centre along one axis and the distance to it; along z the blocks are pushed apart
// to open the boulevard at z = 0 (city_gen.hpp's block_span).
float city_block_offset(float x, float count, float pitch, float extra)
{
    float shifted = x > 0.0 ? x - extra : x + extra;
    float i = clamp(floor(shifted / pitch + 0.5 * (count - 1.0) + 0.5), 0.0, count - 1.0);
    float c = (i - 0.5 * (count - 1.0)) * pitch;
    c += c > 0.0 ? extra : -extra;
    return x - c;
}

float city_hash12(vec2 p)
{
    uvec2 q = uvec2(ivec2(floor(p))) * uvec2(1597334673u, 3812015801u);
    uint n = (q.x ^ q.y) * 1597334673u;
    return float(n >> 8u) * (1.0 / 16777216.0);
}

// Ground albedo at world xz and whether it is road (1), sidewalk (0.5) or block interior (0).
vec3 city_ground_albedo(vec2 xz, out float kind)
{
    float pitch = u_layout0.z + u_layout0.w;
    float half_block = 0.5 * u_layout0.z;
    float extra = 0.5 * (u_layout1.x - u_layout0.w);
    float ox = city_block_offset(xz.x, u_layout0.x, pitch, 0.0);
    float oz = city_block_offset(xz.y, u_layout0.y, pitch, extra);
    float dx = abs(ox) - half_block, dz = abs(oz) - half_block;  // > 0: outside the block (street)
    float n = city_hash12(xz * 3.0) * 0.5 + city_hash12(xz * 0.7) * 0.5;
    float beyond = max(abs(xz.x), abs(xz.y)) - (u_layout1.z + u_layout0.w);
    if (beyond > 0.0) {  // outside the city: fields, crossed by the continuing boulevard
        kind = 0.0;
        if (abs(xz.y) < 0.5 * u_layout1.x && abs(xz.x) > abs(xz.y)) {
            kind = 1.0;
            return vec3(0.055, 0.055, 0.06) * (0.8 + 0.4 * n);
        }
        float patchy = city_hash12(floor(xz / 40.0) + 0.5);
        return mix(vec3(0.07, 0.09, 0.04), vec3(0.12, 0.10, 0.06), patchy) * (0.8 + 0.4 * n);
    }
    vec3 asphalt = vec3(0.055, 0.055, 0.06) * (0.8 + 0.4 * n);
    vec3 sidewalk = vec3(0.30, 0.29, 0.27) * (0.85 + 0.3 * n);
    vec3 court = vec3(0.10, 0.14, 0.07) * (0.7 + 0.6 * n);
    if (dx > 0.0 || dz > 0.0) {
        kind = 1.0;
        vec3 c = asphalt;
        // Dashed centre lines: the street's middle is where the offset to the block is half a pitch.
        float street_x = abs(abs(ox) - 0.5 * pitch);  // distance to the middle of an x street (const x)
        bool boulevard = abs(xz.y) < 0.5 * u_layout1.x;
        float street_z = boulevard ? abs(xz.y) : abs(abs(oz) - 0.5 * pitch);
        if (dx > 0.0 && dz <= 0.0 && street_x < 0.08 && fract(xz.y / 6.0) < 0.5) c = vec3(0.55);
        if (dz > 0.0 && dx <= 0.0 && street_z < 0.08 && fract(xz.x / 6.0) < 0.5) c = vec3(0.55);
        if (boulevard && dx <= 0.0 && abs(abs(xz.y) - 4.0) < 0.06) c = vec3(0.6, 0.5, 0.2);
        // Zebra crossings at the corners.
        if (dx > 0.0 && dz > 0.0) {
            bool stripes = fract((xz.x + xz.y) * 0.5) < 0.5;
            if (dx < 3.0 && stripes || dz < 3.0 && stripes) c = vec3(0.5);
        }
        return c;
    }
    float sw = u_layout1.y;
    if (dx > -sw || dz > -sw) {
        kind = 0.5;
        float tiles = step(0.05, fract(xz.x * 0.5)) * step(0.05, fract(xz.y * 0.5));
        return sidewalk * (0.8 + 0.2 * tiles);
    }
    kind = 0.0;
    return court;
}

// Night-time street lighting: warm pools of light along the sidewalks (no extra geometry).
vec3 city_street_light(vec3 world)
{
    if (u_sky_horizon.w <= 0.0) return vec3(0.0);
    float spacing = 18.0;
    vec2 cell = floor(world.xz / spacing + 0.5) * spacing;
    float d = length(world.xz - cell);
    return vec3(1.0, 0.62, 0.3) * u_sky_horizon.w * exp(-d * d / 40.0);
}

#endif
