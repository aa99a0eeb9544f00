// raykit — svo_hybrid.hpp: the CPU build of shaders/raykit/svo_hybrid.glsl (pixel rays and
// rasteriser-compatible depth for ray-cast voxel objects) and the CPU helper that computes its
// uniforms from an object's model matrix and the camera's view and projection.
#pragma once

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/common.hpp"

namespace raykit {
#include "raykit/svo_hybrid.glsl"

/// The depth conventions a hybrid pass must match (docs: svo_hybrid.glsl's header).
enum class SvoDepthConvention {
    gl_minus_one_to_one,  ///< OpenGL default: NDC z in [-1, 1], window depth = z * 0.5 + 0.5, test LESS
    zero_to_one,          ///< Vulkan, D3D, glClipControl(GL_ZERO_TO_ONE): NDC z in [0, 1], test LESS
    reversed_zero_to_one, ///< reversed-Z: near at 1, far at 0, test GREATER (float depth buffers)
};

/// The uniforms of a hybrid pass for one voxel object.
struct SvoHybridView {
    glm::mat4 obj_to_clip{1.0f};  ///< projection * view * model: rk_svo_window_depth
    glm::mat4 clip_to_obj{1.0f};  ///< its inverse: rk_svo_pixel_ray, rk_svo_depth_to_t
    float z_near_ndc = -1.0f;     ///< the near plane's NDC z
    glm::vec2 depth_range{0.5f, 0.5f};  ///< window depth = z_ndc * x + y
};

/// svo_hybrid_view: the uniforms for an object drawn with `model` (object to world) by a camera
/// with `view` (world to eye) and `projection` (eye to clip, built for `convention`). The product
/// is formed in double and inverted in double, so the ray and the depth agree with what a
/// rasteriser computes from the same float matrices to float rounding.
inline SvoHybridView svo_hybrid_view(const glm::mat4& model, const glm::mat4& view, const glm::mat4& projection,
                                     SvoDepthConvention convention)
{
    const glm::dmat4 m = glm::dmat4(projection) * glm::dmat4(view) * glm::dmat4(model);
    SvoHybridView v;
    v.obj_to_clip = glm::mat4(m);
    v.clip_to_obj = glm::mat4(glm::inverse(m));
    switch (convention) {
    case SvoDepthConvention::gl_minus_one_to_one: v.z_near_ndc = -1.0f; v.depth_range = glm::vec2(0.5f, 0.5f); break;
    case SvoDepthConvention::zero_to_one: v.z_near_ndc = 0.0f; v.depth_range = glm::vec2(1.0f, 0.0f); break;
    case SvoDepthConvention::reversed_zero_to_one: v.z_near_ndc = 1.0f; v.depth_range = glm::vec2(1.0f, 0.0f); break;
    }
    return v;
}

/// svo_perspective: a right-handed perspective projection (camera looking down -z) for
/// `convention`; `far_plane` may be +infinity for reversed_zero_to_one (the usual pairing).
/// Vertical field of view `fov_y` in radians.
inline glm::mat4 svo_perspective(float fov_y, float aspect, float near_plane, float far_plane, SvoDepthConvention convention)
{
    switch (convention) {
    case SvoDepthConvention::gl_minus_one_to_one: return glm::perspectiveRH_NO(fov_y, aspect, near_plane, far_plane);
    case SvoDepthConvention::zero_to_one: return glm::perspectiveRH_ZO(fov_y, aspect, near_plane, far_plane);
    case SvoDepthConvention::reversed_zero_to_one: break;
    }
    // Reversed: z_ndc = near / z_eye-distance for an infinite far plane, else the ZO matrix with
    // near and far swapped.
    if (!(far_plane < 3.0e38f)) {
        const float f = 1.0f / std::tan(0.5f * fov_y);
        glm::mat4 p(0.0f);
        p[0][0] = f / aspect;
        p[1][1] = f;
        p[2][3] = -1.0f;
        p[3][2] = near_plane;
        return p;
    }
    return glm::perspectiveRH_ZO(fov_y, aspect, far_plane, near_plane);
}

}  // namespace raykit
