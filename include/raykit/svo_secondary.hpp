// raykit — svo_secondary.hpp: the CPU build of shaders/raykit/svo_secondary.glsl (shadow rays,
// reflection and refraction with Fresnel and total internal reflection, heterogeneous media
// through octrees) and svo_media_table(), which packs a tree's materials for it.
//
// Feature macros (RK_SVO_SECONDARY_FRESNEL_FAST, RK_SVO_SECONDARY_ABSORPTION, RK_SVO_SECONDARY_MAX_STEPS) may differ
// between translation units: like svo_traverse.hpp, the functions live in an inline namespace
// named after the macro values.
#pragma once

#include <vector>

#include "raykit/fresnel.hpp"
#include "raykit/svo_traverse.hpp"

// The .glsl's defaults (they name the namespace before the text is included).
#ifndef RK_SVO_SECONDARY_FRESNEL_FAST
#define RK_SVO_SECONDARY_FRESNEL_FAST 0
#endif
#ifndef RK_SVO_SECONDARY_ABSORPTION
#define RK_SVO_SECONDARY_ABSORPTION 1
#endif
#ifndef RK_SVO_SECONDARY_MAX_STEPS
#define RK_SVO_SECONDARY_MAX_STEPS 4096
#endif

#define RK_SVO_SECONDARY_NS_CAT_(f, a, s) svo_secondary_fast##f##_abs##a##_steps##s
#define RK_SVO_SECONDARY_NS_CAT(f, a, s) RK_SVO_SECONDARY_NS_CAT_(f, a, s)
#define RK_SVO_SECONDARY_NS RK_SVO_SECONDARY_NS_CAT(RK_SVO_SECONDARY_FRESNEL_FAST, RK_SVO_SECONDARY_ABSORPTION, RK_SVO_SECONDARY_MAX_STEPS)

namespace raykit {
inline namespace RK_SVO_SECONDARY_NS {
#include "raykit/svo_secondary.glsl"

/// svo_media_table: the media of a tree's materials, one vec4(ior, absorption rgb) per material
/// (the table RK_SVO_MEDIUM reads; upload it as the RkSvoMedia SSBO). A tree without materials
/// gets one entry (index 1.5, no absorption), matching SvoMaterial's defaults.
inline std::vector<vec4> svo_media_table(const SvoTree& t)
{
    std::vector<vec4> m;
    for (const SvoMaterial& s : t.materials) m.push_back(vec4(s.ior, s.absorption.x, s.absorption.y, s.absorption.z));
    if (m.empty()) m.push_back(vec4(SvoMaterial().ior, 0.0f, 0.0f, 0.0f));
    return m;
}
}  // namespace RK_SVO_SECONDARY_NS
}  // namespace raykit
