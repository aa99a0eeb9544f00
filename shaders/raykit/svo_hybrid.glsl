// raykit — svo_hybrid.glsl: voxel objects in a rasterised frame (Gritzner, "3D graphics rendering
// using a polygon-voxel-hybrid approach"): the pixel's ray in the octree's object space, and the
// depth value a rasteriser would have written for a point, so ray-cast voxels and triangles share
// one depth buffer and occlude each other both ways.
//
// Shared GLSL/C++ source (include/raykit/svo_hybrid.hpp is the C++ build, with svo_hybrid_view(),
// which fills the uniforms from model, view and projection matrices). Conventions, all through the
// same functions:
//   OpenGL default, NDC z in [-1, 1]: z_near_ndc = -1, depth_range = (0.5, 0.5);
//   Vulkan, or OpenGL with glClipControl(.., GL_ZERO_TO_ONE): z_near_ndc = 0, depth_range = (1, 0);
//   reversed-Z (zero-to-one, near plane at 1, depth test GREATER): z_near_ndc = 1, depth_range = (1, 0).
// Where depth_range maps NDC z to the window depth: depth = z_ndc * depth_range.x + depth_range.y.
//
// The thesis's method, kept: the point whose depth is written is the ray's entry point into the
// voxel (the hit distance of rk_svo_trace), projected "as if it was a vertex", i.e. through the
// same object-to-clip matrix and perspective division as the rasteriser, so a voxel face and a
// triangle in the same plane get the same depth up to float rounding, provided the rasteriser
// projects with the same float matrix (svo_hybrid_view composes P·V·M in double once; an engine that
// multiplies the matrices in float, or in the vertex shader, differs by that product's rounding,
// a few more 2^-24). Not kept: the per-iteration
// depth comparison; instead rk_svo_depth_to_t turns the depth already in the buffer into the ray's
// t_max, so the traversal never descends into anything behind it.
//
// @rk-es 310
// @rk-es300
#ifndef RK_SVO_HYBRID_GLSL
#define RK_SVO_HYBRID_GLSL

#include "common.glsl"

/// rk_svo_pixel_ray: the ray of NDC position `ndc` (x, y in [-1, 1]) in object space:
/// origin on the near plane, dir towards a point further along the pixel's line (not normalised;
/// t = 0 at the near plane). clip_to_obj = inverse(projection * view * model). z_near_ndc is the
/// near plane's NDC z (-1 OpenGL, 0 zero-to-one, 1 reversed-Z). Works for perspective and
/// orthographic projections, and infinite far planes (the second point is at NDC z 0.8, or 0.1
/// for reversed-Z, never at infinity). Cost: 2 mat4 * vec4, 2 divisions.
RK_INLINE void rk_svo_pixel_ray(mat4 clip_to_obj, vec2 ndc, float z_near_ndc, RK_OUT(vec3) origin, RK_OUT(vec3) dir)
{
    vec4 a = clip_to_obj * vec4(ndc.x, ndc.y, z_near_ndc, 1.0f);
    // The second point at NDC z 0.8 (0.1 for reversed-Z): about ten near distances away for usual
    // projections, so the direction's rounding is small against its length.
    vec4 b = clip_to_obj * vec4(ndc.x, ndc.y, z_near_ndc > 0.5f ? 0.1f : 0.8f, 1.0f);
    float wa = abs(a.w) >= RK_FLT_MIN ? a.w : RK_FLT_MIN;
    float wb = abs(b.w) >= RK_FLT_MIN ? b.w : RK_FLT_MIN;
    origin = vec3(a.x, a.y, a.z) / wa;
    dir = vec3(b.x, b.y, b.z) / wb - origin;
}

/// rk_svo_window_depth: the depth a rasteriser writes for object-space point `p`:
/// clamp(z_clip / w_clip * depth_range.x + depth_range.y, 0, 1), obj_to_clip = projection * view *
/// model. Exact up to float rounding of the matrix product (the rasteriser's own rounding may
/// differ by a few ULPs: it interpolates z/w over the triangle). Cost: 1 mat4 * vec4, 1 division.
RK_INLINE float rk_svo_window_depth(mat4 obj_to_clip, vec3 p, vec2 depth_range)
{
    vec4 c = obj_to_clip * vec4(p.x, p.y, p.z, 1.0f);
    float w = abs(c.w) >= RK_FLT_MIN ? c.w : RK_FLT_MIN;
    return clamp(c.z / w * depth_range.x + depth_range.y, 0.0f, 1.0f);
}

/// rk_svo_depth_to_t: the parameter t on the pixel's ray (origin, dir from rk_svo_pixel_ray at the
/// same `ndc`) where the window depth `depth` lies: pass it as rk_svo_trace's t_max so the ray stops
/// at whatever the rasteriser already drew. A depth at an infinite far plane (w = 0) gives
/// RK_FLT_MAX. Cost: 1 mat4 * vec4, 1 division, 2 dots.
RK_INLINE float rk_svo_depth_to_t(mat4 clip_to_obj, vec2 ndc, float depth, vec2 depth_range, vec3 origin, vec3 dir)
{
    float z_ndc = (depth - depth_range.y) / depth_range.x;
    vec4 q = clip_to_obj * vec4(ndc.x, ndc.y, z_ndc, 1.0f);
    if (abs(q.w) < RK_FLT_MIN) return RK_FLT_MAX;
    vec3 p = vec3(q.x, q.y, q.z) / q.w;
    float t = dot(p - origin, dir) / max(dot(dir, dir), RK_FLT_MIN);
    return t >= 0.0f ? min(t, RK_FLT_MAX) : (t < 0.0f ? 0.0f : RK_FLT_MAX);  // NaN (inf - inf) -> no limit
}

#endif  // RK_SVO_HYBRID_GLSL
