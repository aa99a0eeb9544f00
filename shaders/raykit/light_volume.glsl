// raykit — light_volume.glsl: deferred lighting with light volumes (Fahlén, "Illumination for
// Real-Time Rendering of Large Architectural Environments", §2.3): each light shades only the pixels
// its bounding volume covers (a sphere for a point light, a cone for a spot light, a screen
// rectangle for a directional light), drawn with back faces culled, or front faces when the camera
// is inside the volume. This file has the parts a shader or a GPU culling pass needs: a windowed
// inverse-square falloff that reaches exactly zero at the volume's radius (so the volume bounds the
// light exactly), the spot cone's angular factor, and a sphere's tight screen rectangle and depth
// range (scissor, tiled or clustered light lists, depth-bounds test).
//
// Shared GLSL/C++ source (include/raykit/light_volume.hpp is the C++ build, with the volume meshes,
// the culling rule and the radius helpers).
//
// @rk-es 310
// @rk-es300
#ifndef RK_LIGHT_VOLUME_GLSL
#define RK_LIGHT_VOLUME_GLSL

#include "common.glsl"
#include "gbuffer.glsl"

/// rk_lv_window: the window (1 - (d/r)^4)^2 on [0, r], 0 beyond, of x = d² / r² (Karis, "Real
/// Shading in Unreal Engine 4", 2013): 1 at the light, C¹ at the radius. Domain: any float (NaN and
/// negative read as 0). Exact to float rounding. Cost: 3 mul, 1 clamp.
RK_INLINE float rk_lv_window(float x)
{
    float xc = x > 0.0f ? min(x, 1.0f) : 0.0f;
    float w = 1.0f - xc * xc;
    return w * w;
}

/// rk_lv_point_falloff: the windowed inverse-square falloff of a point light at squared distance
/// dist2: rk_lv_window(dist2 / radius²) / max(dist2, min_dist²). Never above the unwindowed
/// 1 / max(dist2, min_dist²), exactly 0 from `radius` on. inv_radius2 = 1 / radius²; min_dist (> 0,
/// e.g. 1 cm) keeps the light finite at its centre. Domain: dist2 >= 0, inv_radius2 >= 0, any
/// finite min_dist2 (floored at RK_FLT_MIN). Cost: 1 div, ~6 flops.
RK_INLINE float rk_lv_point_falloff(float dist2, float inv_radius2, float min_dist2)
{
    float d2 = max(dist2, max(min_dist2, RK_FLT_MIN));
    return rk_lv_window(dist2 * inv_radius2) / d2;
}

/// rk_lv_spot_factor: the angular factor of a spot light: 0 outside the outer cone, 1 inside the
/// inner cone, smooth (squared linear ramp in the cosine) between. cos_angle = dot(-L, spot axis)
/// for the unit vector L towards the light; cos_outer < cos_inner (equal cones give a hard edge at
/// the outer angle). Domain: any finite floats. Cost: 1 div, ~4 flops.
RK_INLINE float rk_lv_spot_factor(float cos_angle, float cos_outer, float cos_inner)
{
    float span = max(cos_inner - cos_outer, RK_FLT_MIN);
    float t = rk_saturate((cos_angle - cos_outer) / span);
    return cos_angle >= cos_outer ? t * t : 0.0f;
}

/// rk_lv_circle_ndc_range_: internal. The range of (p_aa * a + p_za * z) / -z over the part of the
/// disk (centre (ca, cz), radius r) in the (a, z) plane with z <= -near: its tangent points from the
/// origin where they lie beyond the near plane, and the ends of its chord on the near plane.
/// Returns (min, max); (1, -1) (empty) when nothing of the disk is beyond the near plane.
RK_INLINE vec2 rk_lv_circle_ndc_range_(float ca, float cz, float r, float p_aa, float p_za, float near)
{
    float lo = RK_FLT_MAX;
    float hi = -RK_FLT_MAX;
    if (!(cz - r < -near)) return vec2(1.0f, -1.0f);
    float d2 = ca * ca + cz * cz;
    float l2 = d2 - r * r;
    if (l2 > 0.0f) {
        // Tangent points T = (L C ± r C_perp) L / |C|², C_perp = (-cz, ca), L = sqrt(|C|² - r²).
        float l = sqrt(l2);
        float s = l / d2;
        for (int k = 0; k < 2; ++k) {
            float sg = k == 0 ? 1.0f : -1.0f;
            float ta = s * (l * ca - sg * r * cz);
            float tz = s * (l * cz + sg * r * ca);
            if (tz <= -near) {
                float v = (p_aa * ta + p_za * tz) / -tz;
                lo = min(lo, v);
                hi = max(hi, v);
            }
        }
    }
    float h2 = r * r - (cz + near) * (cz + near);
    if (h2 >= 0.0f) {
        // The chord on the near plane z = -near.
        float h = sqrt(h2);
        float v0 = (p_aa * (ca - h) - p_za * near) / near;
        float v1 = (p_aa * (ca + h) - p_za * near) / near;
        lo = min(lo, min(v0, v1));
        hi = max(hi, max(v0, v1));
    }
    return vec2(lo, hi);
}

/// rk_lv_sphere_ndc_rect: the NDC rectangle (x_min, y_min, x_max, y_max), clamped to [-1, 1]², that
/// a sphere (view-space centre c, camera at the origin looking down -z, radius r) covers after
/// clipping at the near plane z = -near, for a perspective projection with `proj` = (P[0][0],
/// P[1][1], P[2][0], P[2][1]) of the column-major matrix P (off-centre frusta and Vulkan's negative
/// P[1][1] included). Tight: bounded by the sphere's tangent planes through the eye and, where the
/// sphere crosses the near plane, by the circle it cuts there (Mara and McGuire, "2D Polyhedral
/// Bounds of a Clipped, Perspective-Projected 3D Sphere", 2013). A sphere entirely in front of the
/// near plane gives the empty rectangle (1, 1, -1, -1): x_min > x_max. The camera inside the sphere
/// gives the whole screen. Domain: finite c with |c| < 1e18, r >= 0, near > 0. Conservative: each
/// bound is pushed out by 3e-5 (1 + |bound|), more than its float rounding (5.1e-6 measured), so
/// every projected point of the clipped sphere is inside (tests/test_light_volume.cpp, 1,800
/// spheres against 10^4 projected samples each, three projections). Cost: ~65 flops, 4 sqrt, 10 div.
RK_INLINE vec4 rk_lv_sphere_ndc_rect(vec3 c, float r, vec4 proj, float near)
{
    float rr = max(r, 0.0f);
    float n = max(near, RK_FLT_MIN);
    // The eye is inside when |c| <= r, compared in units of c's largest component so that neither
    // squares overflow nor tiny ones underflow (to zero on drivers that flush denormals).
    float mc = max(max(abs(c.x), abs(c.y)), abs(c.z));
    vec3 sc = c / max(mc, RK_FLT_MIN);
    float q = min(rr / max(mc, RK_FLT_MIN), 4.0f);
    if (mc <= 0.0f || dot(sc, sc) <= q * q) return vec4(-1.0f, -1.0f, 1.0f, 1.0f);
    vec2 x = rk_lv_circle_ndc_range_(c.x, c.z, rr, proj.x, proj.z, n);
    vec2 y = rk_lv_circle_ndc_range_(c.y, c.z, rr, proj.y, proj.w, n);
    if (!(x.x <= x.y) || !(y.x <= y.y)) return vec4(1.0f, 1.0f, -1.0f, -1.0f);
    // Outward by 3e-5 (1 + |bound|): float rounding of the tangent points moves a bound by up to
    // 5.1e-6 (measured), so the rectangle stays conservative (3e-5 is 1/17 of a 4K pixel).
    float ex = 3e-5f;
    vec4 b = vec4(x.x - ex * (1.0f + abs(x.x)), y.x - ex * (1.0f + abs(y.x)), x.y + ex * (1.0f + abs(x.y)),
                  y.y + ex * (1.0f + abs(y.y)));
    return clamp(b, vec4(-1.0f), vec4(1.0f));
}

/// rk_lv_sphere_depth_range: the window-depth range (min, max) a sphere (view-space centre z `cz`,
/// radius r) can occupy between the near and far planes of k (rk_gb_depth_params), for a
/// depth-bounds test or conservative depth: its view distances [-(cz + r), -(cz - r)] clamped to
/// [n, f]. A sphere behind the camera gives the near plane's depth twice. Cost: 2
/// rk_gb_window_depth.
RK_INLINE vec2 rk_lv_sphere_depth_range(float cz, float r, vec3 k)
{
    float dn = max(-(cz + max(r, 0.0f)), 0.0f);
    float df = max(-(cz - max(r, 0.0f)), 0.0f);
    float a = rk_gb_window_depth(dn, k);
    float b = rk_gb_window_depth(df, k);
    return vec2(min(a, b), max(a, b));
}

#endif  // RK_LIGHT_VOLUME_GLSL
