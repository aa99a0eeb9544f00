// raykit — interior_compose.glsl: putting an interior-mapped window together: the window mask
// convention, the glass (Fresnel-weighted reflection over the tinted interior, or the thesis's
// plain addition), per-room lights, and the distance fade to a flat interior.
//
// Shared GLSL/C++ source (docs/dialect.md); the C++ build is raykit/interior_compose.hpp.
// Source: van Dongen 2009, "Using raycasting in GPU shaders to enhance real-time graphics",
// §5.2.3 (combining with the exterior, reflections in the windows), §5.4.1 (varying lighting per
// room) and its appendix shader (mask convention); beyond the thesis: Fresnel instead of addition,
// per-room light colour and intensity; Fahlén 2005, "Illumination for Real-Time Rendering of Large
// Architectural Environments", §3.2 via window_glass.glsl.
//
// WINDOW MASK CONVENTION: mask = 1 means window (show the interior behind glass), mask = 0 means
// opaque facade. The exterior texture's alpha is the mask. The thesis disagrees with itself here:
// its prose (§5.2.3) says alpha = 1 shows the diffuse exterior and alpha = 0 the interior, while its
// appendix shader does lerp(wall, window, diffuse.a), i.e. alpha = 1 is the window. raykit follows
// the code: alpha = 1 window. A texture authored for the prose convention is
// used with mask = 1 - alpha. Fractional masks (filtered edges) blend linearly; masks at or below
// RK_IM_MASK_MIN (half an 8-bit step) count as opaque so those texels can skip the trace
// (rk_im_needs_interior), and then the result is exactly the exterior.
//
// THE GLASS (RK_IM_COMPOSE_MODE 0, default): window = R reflection + (1 - R) tint interior,
// R the pane's reflectance at the viewing angle with its internal multiple reflections
// (rk_window_glass_reflectance, i.e. RK_WINDOW_GLASS_FRESNEL / RK_FRESNEL_WINDOW_MODE). Energy
// conserving: each channel is at most max(reflection, interior). The thesis's appendix instead
// adds the cube-map reflection to the interior (window = reflection + interior, no Fresnel):
// RK_IM_COMPOSE_MODE 1 gives it for comparison. It is brighter everywhere (up to twice the
// brightest input) and shows the same reflection at normal incidence as at grazing, where real
// glass reflects 8 % and 100 % of the environment.
//
// Feature macros:
//   RK_IM_COMPOSE_MODE  rk_im_window(): 0 Fresnel glass (default), 1 thesis additive.
//   RK_IM_ROOM_LIGHTS   0/1 (default 0): whether interior_shading.glsl's rk_im_shade_window()
//                       applies rk_im_room_light (per-room on/off, colour, intensity).
//   RK_IM_FADE          0/1 (default 0): whether rk_im_shade_window() fades distant interiors to
//                       rk_im_fade_flat (and skips the trace beyond the fade band).
// The functions below exist whatever the macros; a function nobody calls costs nothing.
//
// @rk-es 310
// @rk-es300
// @rk-variants RK_IM_COMPOSE_MODE=0 | RK_IM_COMPOSE_MODE=1 | RK_IM_ROOM_LIGHTS=1 RK_IM_FADE=1 | RK_WINDOW_GLASS_FRESNEL=1 RK_IM_COMPOSE_MODE=0
#ifndef RK_INTERIOR_COMPOSE_GLSL
#define RK_INTERIOR_COMPOSE_GLSL

#ifdef __cplusplus
#define RK_NS_IM_WINDOW RK_PP_CAT(RK_PP_CAT(RK_PP_CAT(im_window_compose, RK_IM_COMPOSE_MODE), RK_PP_CAT(_glass, RK_WINDOW_GLASS_FRESNEL)), \
                                 RK_PP_CAT(_mode, RK_FRESNEL_WINDOW_MODE))
#endif

#include "common.glsl"
#include "interior_mapping.glsl"
#include "window_glass.glsl"

#ifndef RK_IM_COMPOSE_MODE
#define RK_IM_COMPOSE_MODE 0
#endif
#if RK_IM_COMPOSE_MODE < 0 || RK_IM_COMPOSE_MODE > 1
#error "RK_IM_COMPOSE_MODE must be 0 (Fresnel glass) or 1 (thesis additive)"
#endif
RK_OPTION_CHECK(rk_option_im_compose_mode, RK_IM_COMPOSE_MODE);
#ifndef RK_IM_ROOM_LIGHTS
#define RK_IM_ROOM_LIGHTS 0
#endif
#if RK_IM_ROOM_LIGHTS < 0 || RK_IM_ROOM_LIGHTS > 1
#error "RK_IM_ROOM_LIGHTS must be 0 (off) or 1 (per-room lights)"
#endif
RK_OPTION_CHECK(rk_option_im_room_lights, RK_IM_ROOM_LIGHTS);
#ifndef RK_IM_FADE
#define RK_IM_FADE 0
#endif
#if RK_IM_FADE < 0 || RK_IM_FADE > 1
#error "RK_IM_FADE must be 0 (off) or 1 (distance fade)"
#endif
RK_OPTION_CHECK(rk_option_im_fade, RK_IM_FADE);

// Masks at or below this count as opaque facade (half a step of an 8-bit alpha channel).
#define RK_IM_MASK_MIN 0.001953125f
// Suggested darkening of unlit rooms (the thesis gives no value): 6 % of the lit colour, enough
// to keep furniture silhouettes readable against a night sky without looking lit.
#define RK_IM_UNLIT_DEFAULT 0.06f
// Seed (XORed into the caller's seed) of the per-room tint hash, so that the tint is independent
// of the other per-room draws made with the caller's seed.
#define RK_IM_TINT_SEED 0x165667B1u

/// rk_im_needs_interior: whether a texel with this window mask shows any interior (mask >
/// RK_IM_MASK_MIN): branch on it to skip the trace for opaque facade texels. Exact. Cost: 1 compare.
RK_INLINE bool rk_im_needs_interior(float mask) { return mask > RK_IM_MASK_MIN; }

/// rk_im_window_weight: the window's weight in the composition: 0 at or below RK_IM_MASK_MIN, else
/// min(mask, 1). Exact. Cost: 1 compare, 1 min.
RK_INLINE float rk_im_window_weight(float mask) { return rk_im_needs_interior(mask) ? min(mask, 1.0f) : 0.0f; }

// C++: the functions below depend on RK_IM_COMPOSE_MODE, RK_WINDOW_GLASS_FRESNEL and
// RK_FRESNEL_WINDOW_MODE; their C++ build lives in an inline namespace named after the values
// (docs/dialect.md), so translation units with other values never share it.
RK_CONFIGURED_BEGIN(RK_NS_IM_WINDOW)
/// rk_im_window_fresnel: the pane over the interior: R reflection + (1 - R) tint interior with
/// R = rk_window_glass_reflectance(cos_view, eta, panes) (macros of window_glass.glsl), inputs
/// sanitised as in rk_window_glass_combine. cos_view = |N.V| (rk_window_glass_cos).
/// Each channel <= max(reflection, interior). Max error: that of the reflectance (1e-6 exact mode)
/// + 3 ulp. Cost: reflectance + ~10 flops.
RK_INLINE vec3 rk_im_window_fresnel(vec3 interior, vec3 reflection, float cos_view, vec3 tint, float eta, float panes)
{
    return rk_window_glass_combine(reflection, interior, rk_window_glass_reflectance(cos_view, eta, panes), tint);
}

/// rk_im_window_additive: the thesis's window colour (appendix): reflection + interior, each
/// sanitised (rk_hdr_sanitize). No Fresnel, no tint; for comparison only (see the file header).
/// Exact up to 1 rounding. Cost: 1 add x3 + sanitising.
RK_INLINE vec3 rk_im_window_additive(vec3 interior, vec3 reflection)
{
    return rk_hdr_sanitize(interior) + rk_hdr_sanitize(reflection);
}

/// rk_im_window: the window colour of RK_IM_COMPOSE_MODE (0 rk_im_window_fresnel, 1
/// rk_im_window_additive, which ignores cos_view, tint, eta, panes).
RK_INLINE vec3 rk_im_window(vec3 interior, vec3 reflection, float cos_view, vec3 tint, float eta, float panes)
{
#if RK_IM_COMPOSE_MODE == 1
    RK_UNUSED(cos_view);
    RK_UNUSED(tint);
    RK_UNUSED(eta);
    RK_UNUSED(panes);
    return rk_im_window_additive(interior, reflection);
#else
    return rk_im_window_fresnel(interior, reflection, cos_view, tint, eta, panes);
#endif
}
RK_CONFIGURED_END

/// rk_im_compose: the facade texel: exterior (1 - w) + window w with w = rk_im_window_weight(mask).
/// mask <= RK_IM_MASK_MIN gives exactly `exterior`, mask >= 1 exactly `window` (finite inputs).
/// Each channel lies between the two inputs (up to 1 ulp). Cost: 1 compare, ~7 flops.
RK_INLINE vec3 rk_im_compose(vec3 exterior, float mask, vec3 window)
{
    float w = rk_im_window_weight(mask);
    return exterior * (1.0f - w) + window * w;
}

/// rk_im_compose (RGBA exterior): the exterior's alpha is the window mask (1 = window).
RK_INLINE vec3 rk_im_compose(vec4 exterior_rgba, vec3 window)
{
    return rk_im_compose(vec3(exterior_rgba.x, exterior_rgba.y, exterior_rgba.z), exterior_rgba.w, window);
}

/// rk_im_room_lanes: the three 24-bit random lanes of a room, each in [0, 1): rk_u32_to_unit of
/// the three words of rk_pcg3d(uvec3(room.x, room.y, room.z ^ rk_hash_u32(seed))). Lane x is
/// rk_im_room_random(room, seed) bit for bit (so rk_im_room_lit(room, c, seed) is lanes.x < c);
/// PCG3D's lanes are mutually independent, so y and z are two more per-room draws at no extra
/// hash. Exact (integer only; bit-identical on CPU and GPU). Cost: 1 rk_hash_u32 + 1 rk_pcg3d.
RK_INLINE vec3 rk_im_room_lanes(ivec3 room, uint seed)
{
    uvec3 h = rk_pcg3d(uvec3(uint(room.x), uint(room.y), uint(room.z) ^ rk_hash_u32(seed)));
    return vec3(rk_u32_to_unit(h.x), rk_u32_to_unit(h.y), rk_u32_to_unit(h.z));
}

/// rk_im_room_light: the light multiplier of a room (thesis §5.4.1 plus colour and level), from
/// one hash (rk_im_room_lanes(room, seed) = (x, h, k)): lit iff x < lit_probability, i.e. exactly
/// rk_im_room_lit(room, lit_probability, seed) (monotone in lit_probability: raising it only
/// switches lights on); a lit room gets mix(warm, cool, h) * mix(level.x, level.y, k), h and k the
/// other two lanes (independent of x and of each other); an unlit room gets vec3(unlit)
/// (suggested RK_IM_UNLIT_DEFAULT). warm and cool are sanitised, level clamped to [0, 65504],
/// unlit to [0, 1]. Deterministic: the same on CPU and GPU (integer hashes). Multiply the interior
/// colour (not the reflection) by it. Max error vs the float64 formula: 4e-7 relative.
/// Cost: 1 rk_hash_u32 + 1 rk_pcg3d, ~15 flops.
RK_INLINE vec3 rk_im_room_light(ivec3 room, float lit_probability, uint seed, vec3 warm, vec3 cool, vec2 level, float unlit)
{
    vec3 lanes = rk_im_room_lanes(room, seed);
    bool lit = lanes.x < lit_probability;
    vec2 lv = clamp(level, vec2(0.0f), vec2(65504.0f));
    vec3 a = rk_hdr_sanitize(warm);
    vec3 b = rk_hdr_sanitize(cool);
    vec3 colour = (a + (b - a) * lanes.y) * (lv.x + (lv.y - lv.x) * lanes.z);
    return lit ? rk_hdr_sanitize(colour) : vec3(rk_saturate(unlit));
}

/// rk_im_room_tint: a per-room colour tint, 1 - amount * (r, g, b) with (r, g, b) =
/// rk_im_room_lanes(room, seed ^ RK_IM_TINT_SEED) (three independent lanes, independent of the
/// draws made with `seed` itself; amount clamped to [0, 1]): each channel in (1 - amount, 1]. Used
/// by the cube-map interiors (RK_IM_SHADING 3) to vary one cube map across rooms.
/// Cost: 1 rk_hash_u32 + 1 rk_pcg3d.
RK_INLINE vec3 rk_im_room_tint(ivec3 room, uint seed, float amount)
{
    float a = rk_saturate(amount);
    return vec3(1.0f) - a * rk_im_room_lanes(room, seed ^ RK_IM_TINT_SEED);
}

/// rk_im_fade_weight: the weight of the flat interior at distance `dist`: 0 up to `start`, 1 from
/// `end` on, smoothstep 3x^2 - 2x^3 between (C1: continuous value and slope). Unlike GLSL's
/// smoothstep it is defined for end <= start (a hard switch at start). Inputs clamped to
/// [0, 1e30]. Max error: 4 ulp. Cost: 1 div, ~8 flops.
RK_INLINE float rk_im_fade_weight(float dist, float start, float end)
{
    float d = clamp(dist, 0.0f, 1.0e30f);
    float s = clamp(start, 0.0f, 1.0e30f);
    float band = max(clamp(end, 0.0f, 1.0e30f) - s, 0.0f);
    float x = d <= s ? 0.0f : (d - s >= band ? 1.0f : (d - s) / max(band, RK_FLT_MIN));
    x = rk_saturate(x);
    return x * x * (3.0f - 2.0f * x);
}

/// rk_im_fade_flat: the flat stand-in for a distant interior: the room's average colour times its
/// light (rk_im_room_light, or vec3(1) without room lights). Sanitised. Cost: 3 mul.
RK_INLINE vec3 rk_im_fade_flat(vec3 average_colour, vec3 light)
{
    return rk_hdr_sanitize(rk_hdr_sanitize(average_colour) * rk_hdr_sanitize(light));
}

/// rk_im_fade: interior (1 - w) + flat w with w from rk_im_fade_weight; w <= 0 gives exactly
/// `interior`, w >= 1 exactly `flat_colour`. Cost: ~7 flops.
RK_INLINE vec3 rk_im_fade(vec3 interior, vec3 flat_colour, float w)
{
    float x = rk_saturate(w);
    return interior * (1.0f - x) + flat_colour * x;
}

#endif  // RK_INTERIOR_COMPOSE_GLSL
