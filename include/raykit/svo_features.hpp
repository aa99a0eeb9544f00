// raykit — svo_features.hpp: what an octree scene uses, turned into the minimal set of feature
// macros for shaders/raykit/svo_traverse.glsl, svo_secondary.glsl and the sample voxel pass
// (samples/common/rk_svo_gl.hpp) (C++ only). Pass the result to raykit::inject_shader_defines /
// load_shader_file (raykit/shader_source.hpp) or to raykit_compile_shaders(DEFINES ...).
//
// Every macro is emitted with an explicit value (a feature the scene does not use is set to its
// "off" value rather than left to the file's default), so one description always gives the same
// shader, and a feature that is off is compiled out (zero instructions).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "raykit/shader_define.hpp"
#include "raykit/status.hpp"
#include "raykit/svo_format.hpp"

namespace raykit {

/// What an octree scene asks of its shaders. Reflection, refraction and absorption follow from the
/// materials (svo_defines); the rest are choices.
struct SvoSceneDesc {
    bool lod = false;              ///< level-of-detail stops at a pixel footprint (RK_SVO_TRAVERSE_LOD)
    uint32_t max_iterations = 0;   ///< fixed iteration cap, or 0: derived from the depth (RK_SVO_TRAVERSE_MAX_ITER)
    bool shadows = false;          ///< shadow rays towards the light (RK_SVO_PASS_SHADOWS)
    bool fast_fresnel = false;     ///< the fast Fresnel form for external reflection (RK_SVO_SECONDARY_FRESNEL_FAST)
    uint32_t max_march_steps = 4096;  ///< voxels one medium march may cross (RK_SVO_SECONDARY_MAX_STEPS)
};

/// What a set of materials needs: a mirror (reflectance > 0), a transparent material
/// (base_color.a < 1: refracts with its ior), and absorption: some material with an absorption
/// component > 0 where something refracts (a refracted ray marches through every voxel it meets,
/// an opaque one touching the glass included; without refraction no ray marches).
struct SvoMaterialNeeds {
    bool reflection = false;
    bool refraction = false;
    bool absorption = false;
};

/// svo_material_needs: see SvoMaterialNeeds. Exact; cost O(materials).
inline SvoMaterialNeeds svo_material_needs(const std::vector<SvoMaterial>& materials)
{
    SvoMaterialNeeds n;
    bool absorbs = false;
    for (const SvoMaterial& m : materials) {
        n.reflection = n.reflection || m.reflectance > 0.0f;
        n.refraction = n.refraction || m.base_color.a < 1.0f;
        absorbs = absorbs || m.absorption.x > 0.0f || m.absorption.y > 0.0f || m.absorption.z > 0.0f;
    }
    n.absorption = n.refraction && absorbs;
    return n;
}

/// svo_defines: the macro set of a scene with `materials` (SvoTree::materials; empty: none), in a
/// fixed order: RK_SVO_TRAVERSE_LOD, RK_SVO_TRAVERSE_MAX_ITER, RK_SVO_SECONDARY_FRESNEL_FAST,
/// RK_SVO_SECONDARY_ABSORPTION, RK_SVO_SECONDARY_MAX_STEPS, RK_SVO_PASS_SHADOWS,
/// RK_SVO_PASS_REFLECTION, RK_SVO_PASS_REFRACTION (the last three are the sample pass's; the
/// library files ignore them). Fresnel and absorption are on only where a material refracts (and
/// absorbs). A material with a non-finite or negative field, an ior <= 0, max_iterations or
/// max_march_steps above 2^24, or max_march_steps 0: an empty set, described in *st (status.hpp).
/// Exact (a table); cost O(materials) and 8 small strings.
inline std::vector<ShaderDefine> svo_defines(const SvoSceneDesc& d, const std::vector<SvoMaterial>& materials,
                                             Status* st = nullptr)
{
    detail::reset(st);
    if (d.max_iterations > (1u << 24)) {
        detail::report(st, "raykit::svo_defines: max_iterations must be 0 (derived from the depth) or in 1..2^24");
        return {};
    }
    if (d.max_march_steps < 1u || d.max_march_steps > (1u << 24)) {
        detail::report(st, "raykit::svo_defines: max_march_steps must be in 1..2^24");
        return {};
    }
    for (const SvoMaterial& m : materials) {
        const float f[] = {m.base_color.r, m.base_color.g, m.base_color.b, m.base_color.a, m.reflectance,
                           m.ior, m.absorption.x, m.absorption.y, m.absorption.z};
        bool ok = m.ior > 0.0f;
        for (float v : f) ok = ok && std::isfinite(v) && v >= 0.0f;
        if (!ok) {
            detail::report(st, "raykit::svo_defines: a material has a negative or non-finite field, or ior <= 0");
            return {};
        }
    }
    const SvoMaterialNeeds n = svo_material_needs(materials);
    auto b = [](bool on) { return std::string(on ? "1" : "0"); };
    return {
        {"RK_SVO_TRAVERSE_LOD", b(d.lod)},
        {"RK_SVO_TRAVERSE_MAX_ITER", std::to_string(d.max_iterations)},
        {"RK_SVO_SECONDARY_FRESNEL_FAST", b(n.refraction && d.fast_fresnel)},
        {"RK_SVO_SECONDARY_ABSORPTION", b(n.absorption)},
        {"RK_SVO_SECONDARY_MAX_STEPS", std::to_string(d.max_march_steps)},
        {"RK_SVO_PASS_SHADOWS", b(d.shadows)},
        {"RK_SVO_PASS_REFLECTION", b(n.reflection)},
        {"RK_SVO_PASS_REFRACTION", b(n.refraction)},
    };
}

}  // namespace raykit
