// raykit — shadow_filter.glsl: shadow-map filtering (Fahlén, "Illumination for Real-Time Rendering
// of Large Architectural Environments", §5.3): the thesis's percentage-closer filter (8 taps, each a
// hardware 2x2 compare), Poisson and Vogel disks rotated per pixel, and percentage-closer soft
// shadows (PCSS: blocker search, penumbra by similar triangles, a filter of that width).
//
// Shared GLSL/C++ source (include/raykit/shadow_filter.hpp is the C++ build). The map is read
// through two functions: rk_sh_compare(map, uv, ref), the lit fraction of a depth comparison with
// the texture's compare mode and linear filtering (a hardware 2x2 PCF), and rk_sh_depth(map, uv),
// the stored depth. In GLSL they are texture() on a sampler2DShadow and textureLod() on a sampler2D
// of the same depth texture (defined below); in C++ they are the CPU twin of shadow_filter.hpp
// (bilinear weights of the four compares, clamp to edge), which the driver parity test checks.
// Depth convention: the map holds the light's window depth, usual (near 0; compare LEQUAL: lit
// where ref <= stored) unless RK_SH_REVERSED_Z is 1 (near 1; compare GEQUAL). Apply the bias to
// ref before the call (rk_sh_slope_bias, or move the point with rk_sh_normal_offset).
//
// Features (compile time):
//   RK_SH_REVERSED_Z (default 0): 1 = the map is reversed-Z (blockers have larger depth).
//   RK_SH_MAX_TAPS (default 64, a plain integer): the loop bound of the disk filters (n is clamped).
//
// @rk-variants RK_SH_REVERSED_Z=0 | RK_SH_REVERSED_Z=1 | RK_SH_MAX_TAPS=16
// @rk-es 310
#ifndef RK_SHADOW_FILTER_GLSL
#define RK_SHADOW_FILTER_GLSL

#ifdef __cplusplus
#define RK_NS_SHADOW_FILTER RK_PP_CAT(RK_PP_CAT(shadow_filter_reversed, RK_SH_REVERSED_Z), RK_PP_CAT(_taps, RK_SH_MAX_TAPS))
#endif

#include "common.glsl"
#include "shadow.glsl"

#ifndef RK_SH_REVERSED_Z
#define RK_SH_REVERSED_Z 0
#endif
#if RK_SH_REVERSED_Z < 0 || RK_SH_REVERSED_Z > 1
#error "RK_SH_REVERSED_Z must be 0 or 1"
#endif
RK_OPTION_CHECK(rk_option_sh_reversed_z, RK_SH_REVERSED_Z);
#ifndef RK_SH_MAX_TAPS
#define RK_SH_MAX_TAPS 64
#endif
#if RK_SH_MAX_TAPS < 1 || RK_SH_MAX_TAPS > 1024
#error "RK_SH_MAX_TAPS must be in 1..1024"
#endif
RK_OPTION_CHECK(rk_option_sh_max_taps, RK_SH_MAX_TAPS);

#ifndef __cplusplus
#ifdef GL_ES
precision highp sampler2DShadow;
precision highp sampler2D;
#endif
#define RK_SH_MAP sampler2DShadow
#define RK_SH_DEPTH_MAP sampler2D
/// rk_sh_compare: the lit fraction at uv for reference depth ref (GLSL: the texture's compare mode,
/// linear filtering = a hardware 2x2 PCF). rk_sh_depth: the stored depth (nearest texel).
RK_INLINE float rk_sh_compare(sampler2DShadow m, vec2 uv, float ref) { return texture(m, vec3(uv.x, uv.y, ref)); }
RK_INLINE float rk_sh_depth(sampler2D m, vec2 uv) { return textureLod(m, uv, 0.0f).x; }
#endif

RK_CONFIGURED_BEGIN(RK_NS_SHADOW_FILTER)

/// rk_sh_blocks: whether stored depth s is nearer the light than reference ref (a blocker).
RK_INLINE bool rk_sh_blocks(float s, float ref)
{
#if RK_SH_REVERSED_Z
    return s > ref;
#else
    return s < ref;
#endif
}

/// rk_sh_pcf_taps: the average lit fraction of n taps (n <= 16, clamped) at uv + radius · o[i],
/// each turned by phi: the thesis's scheme with its 8 stratified offsets (pcf_jittered_grid, 2 x 4)
/// and phi = 0, or a Poisson disk (poisson_disk) turned per pixel (rk_sh_rotation). radius in uv
/// units (texels / map size). Cost: n compares (each a hardware 2x2), n rotations when phi != 0.
RK_INLINE float rk_sh_pcf_taps(RK_SH_MAP m, vec3 uvz, float radius, vec2 o[16], uint n, float phi)
{
    uint nn = min(n, 16u);
    float c = cos(phi);
    float s = sin(phi);
    float sum = 0.0f;
    for (uint i = 0u; i < 16u; ++i) {
        if (i >= nn) break;
        vec2 r = vec2(c * o[i].x - s * o[i].y, s * o[i].x + c * o[i].y);
        sum += rk_sh_compare(m, vec2(uvz.x + radius * r.x, uvz.y + radius * r.y), uvz.z);
    }
    return nn > 0u ? sum / float(nn) : rk_sh_compare(m, vec2(uvz.x, uvz.y), uvz.z);
}

/// rk_sh_pcf_vogel: the average lit fraction of n taps (1..RK_SH_MAX_TAPS) on Vogel's spiral of
/// radius `radius` (uv units) turned by phi (rk_sh_rotation per pixel). No table; any n.
/// Cost: n compares, n sin/cos pairs.
RK_INLINE float rk_sh_pcf_vogel(RK_SH_MAP m, vec3 uvz, float radius, uint n, float phi)
{
    uint nn = clamp(n, 1u, uint(RK_SH_MAX_TAPS));
    float sum = 0.0f;
    for (uint i = 0u; i < uint(RK_SH_MAX_TAPS); ++i) {
        if (i >= nn) break;
        vec2 v = rk_sh_vogel_disk(i, nn, phi);
        sum += rk_sh_compare(m, vec2(uvz.x + radius * v.x, uvz.y + radius * v.y), uvz.z);
    }
    return sum / float(nn);
}

/// rk_sh_pcss: percentage-closer soft shadows (Fernando 2005) for a light of width w_light:
/// 1. blocker search: n Vogel taps within `search` (uv units) average the depths that block uvz.z;
///    none blocks: fully lit (1);
/// 2. penumbra: rk_sh_pcss_penumbra in the light's distance units: the map's depths d are turned
///    into distances from the light by dist = d_near + d · d_range (an orthographic map:
///    d_near, d_range of its projection; for a perspective map pass linearised depths instead);
/// 3. filter: rk_sh_pcf_vogel with radius = penumbra / 2 · uv_per_unit (the map's uv per world unit
///    across), at least min_radius (uv).
/// Returns the lit fraction. Cost: 2 n lookups (n in 1..RK_SH_MAX_TAPS), 2 n sin/cos pairs.
RK_INLINE float rk_sh_pcss(RK_SH_MAP m, RK_SH_DEPTH_MAP dm, vec3 uvz, float search, float w_light, float d_near, float d_range,
                           float uv_per_unit, float min_radius, uint n, float phi)
{
    uint nn = clamp(n, 1u, uint(RK_SH_MAX_TAPS));
    float sum = 0.0f;
    float count = 0.0f;
    for (uint i = 0u; i < uint(RK_SH_MAX_TAPS); ++i) {
        if (i >= nn) break;
        vec2 v = rk_sh_vogel_disk(i, nn, phi);
        float s = rk_sh_depth(dm, vec2(uvz.x + search * v.x, uvz.y + search * v.y));
        if (rk_sh_blocks(s, uvz.z)) {
            sum += s;
            count += 1.0f;
        }
    }
    if (count < 0.5f) return 1.0f;
    float d_blocker = sum / count;
#if RK_SH_REVERSED_Z
    // Reversed: depth 1 is the near plane; distances grow as depth falls.
    float dist_r = d_near + (1.0f - uvz.z) * d_range;
    float dist_b = d_near + (1.0f - d_blocker) * d_range;
#else
    float dist_r = d_near + uvz.z * d_range;
    float dist_b = d_near + d_blocker * d_range;
#endif
    float w = rk_sh_pcss_penumbra(dist_r, dist_b, w_light);
    float radius = max(0.5f * w * uv_per_unit, min_radius);
    return rk_sh_pcf_vogel(m, uvz, radius, nn, phi);
}

RK_CONFIGURED_END

#endif  // RK_SHADOW_FILTER_GLSL
