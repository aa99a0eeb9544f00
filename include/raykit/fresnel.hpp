// raykit — fresnel.hpp: the CPU build of shaders/raykit/fresnel.glsl plus CPU-only helpers.
//
// Every rk_* function below is compiled from the very same text the GPU runs (see
// docs/dialect.md); tests/gpu_parity_test.cpp checks both builds agree on a real driver.
#pragma once

#include <vector>

#include "raykit/common.hpp"

namespace raykit {
#include "raykit/fresnel.glsl"

/// Which reflectance a baked Fresnel lookup table holds.
enum class FresnelLutMode {
    single_surface,     ///< rk_fresnel_dielectric: one interface
    slab_thesis,        ///< rk_fresnel_slab of the polarisation average (thesis Eq. 3.8)
    slab_polarised,     ///< rk_fresnel_slab_sp: slab summed per polarisation
    glazing_polarised,  ///< rk_fresnel_glazing_sp with `panes` panes
};

/// Evaluates the reflectance that a Fresnel LUT of `mode` stores, at one cosine.
inline float fresnel_lut_value(float cos_i, float eta, FresnelLutMode mode, float panes = 1.0f)
{
    vec2 sp = rk_fresnel_dielectric_sp(cos_i, eta);
    switch (mode) {
    case FresnelLutMode::single_surface: return 0.5f * (sp.x + sp.y);
    case FresnelLutMode::slab_thesis: return rk_fresnel_slab(0.5f * (sp.x + sp.y));
    case FresnelLutMode::slab_polarised: return rk_fresnel_slab_sp(sp);
    case FresnelLutMode::glazing_polarised: return rk_fresnel_glazing_sp(sp, panes);
    }
    return 0.0f;
}

/// bake_fresnel_lut_1d: the thesis's 1-D texture of window reflectance, indexed by cos = N·E
/// (environment) or N·L (highlight). Texel i holds the value at its centre, cos = (i + 0.5) / size,
/// so a GL_LINEAR, CLAMP_TO_EDGE texture sampled at u = cos_i reproduces the analytic value
/// exactly at texel centres and interpolates linearly between them. Upload as R32F (or R16F:
/// adds 4.9e-4 relative rounding). Linear-interpolation error for n = 1.52, slab_polarised:
/// 2.3e-2 at 64 texels, 1.1e-2 at 128, 5.7e-3 at 256, all from the steep grazing end (cos < 0.1;
/// see test_fresnel). Use the analytic rk_fresnel_window where grazing views matter.
/// Returns an empty vector for size < 2 or size > 65536 (no exception: engines build with
/// -fno-exceptions). Cost: one exact evaluation per texel.
inline std::vector<float> bake_fresnel_lut_1d(int size, float eta, FresnelLutMode mode, float panes = 1.0f)
{
    if (size < 2 || size > 65536) return {};
    std::vector<float> lut(static_cast<size_t>(size));
    for (int i = 0; i < size; ++i) {
        float c = (static_cast<float>(i) + 0.5f) / static_cast<float>(size);
        lut[static_cast<size_t>(i)] = fresnel_lut_value(c, eta, mode, panes);
    }
    return lut;
}

/// Samples a LUT from bake_fresnel_lut_1d as GL_LINEAR + CLAMP_TO_EDGE would at u = cos_i:
/// the CPU mirror of a texture(lut, cos_i) fetch, for tests and CPU renderers.
inline float sample_fresnel_lut_1d(const std::vector<float>& lut, float cos_i)
{
    if (lut.empty()) return 0.0f;
    const float size = static_cast<float>(lut.size());
    float x = rk_saturate(cos_i) * size - 0.5f;
    x = glm::clamp(x, 0.0f, size - 1.0f);
    const size_t i0 = static_cast<size_t>(x);
    const size_t i1 = glm::min(i0 + 1, lut.size() - 1);
    const float t = x - static_cast<float>(i0);
    return lut[i0] + (lut[i1] - lut[i0]) * t;
}

}  // namespace raykit
