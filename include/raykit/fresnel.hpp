// raykit — fresnel.hpp: the CPU build of shaders/raykit/fresnel.glsl plus CPU-only helpers.
//
// Every rk_* function below is compiled from the very same text the GPU runs (see
// docs/dialect.md); tests/gpu_parity_test.cpp checks both builds agree on a real driver.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
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
/// adds 4.9e-4 relative rounding). Linear-interpolation error for n = 1.52, slab_polarised: 2.3e-2
/// at 64 texels, 1.2e-2 at 128, 5.7e-3 at 256 (every 4th cos float + refinement), all from the
/// steep grazing end (cos < 0.1; see test_fresnel). Use the analytic rk_fresnel_window where
/// grazing views matter.
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

/// Per-material constants of rk_fresnel_dielectric_poly, and the fit's measured quality.
struct FresnelPolyParams {
    vec4 p0{0.0f};               ///< (f0, q0, q1, q2)
    vec2 p1{0.0f};               ///< (q3, q4)
    float max_abs_error = 0.0f;  ///< max |poly - exact| over 4097 evenly spaced cosines (float evaluation)
};

/// rk_fresnel_poly_params (C++ only: a CPU helper that computes uniforms; the fit is an iterative
/// float64 solve a shader should not run): the constants of rk_fresnel_dielectric_poly for relative
/// index eta, clamped to [1 + 2^-10, 64] (at 1 the reflectance is 0/0 at grazing). q is the minimax fit (Lawson's iteratively reweighted least
/// squares, 120 rounds over 401 Chebyshev points of [0, 1]) of (F(cos) - f0) / (1 - cos) weighted
/// by (1 - cos), so f0 stays exact. Deterministic; cost about 1 ms per material. Near eta = 1 the
/// reflectance jumps from ~0 to 1 at grazing and no quartic follows it: check max_abs_error
/// (2.7e-2 at eta 1.05, 1.2e-2 at 1.1; above 2.05 the error grows too: 1.1e-2 at 3).
inline FresnelPolyParams rk_fresnel_poly_params(float eta)
{
    const double lo = 1.0 + 1.0 / 1024.0, in = static_cast<double>(eta);
    const double e = in >= lo ? std::min(in, 64.0) : lo;  // NaN -> the lower end
    auto exact = [e](double c) {  // unpolarised dielectric reflectance, external (e >= 1)
        const double g = std::sqrt(e * e - 1.0 + c * c);
        const double rs = (c - g) / (c + g), rp = (e * e * c - g) / (e * e * c + g);
        return 0.5 * (rs * rs + rp * rp);
    };
    const double f0 = exact(1.0);
    constexpr int kN = 5, kPts = 401;
    double ys[kPts], w[kPts], basis[kPts][kN];
    for (int i = 0; i < kPts; ++i) {
        const double x = 0.5 - 0.5 * std::cos(3.14159265358979323846 * i / (kPts - 1));
        ys[i] = exact(x) - f0;
        w[i] = 1.0;
        double ck = 1.0;
        for (int k = 0; k < kN; ++k, ck *= x) basis[i][k] = (1.0 - x) * ck;
    }
    double a[kN] = {0.0, 0.0, 0.0, 0.0, 0.0};
    for (int round = 0; round < 120; ++round) {
        double m[kN][kN + 1] = {};
        for (int i = 0; i < kPts; ++i) {
            for (int j = 0; j < kN; ++j) {
                for (int k = 0; k < kN; ++k) m[j][k] += w[i] * basis[i][j] * basis[i][k];
                m[j][kN] += w[i] * basis[i][j] * ys[i];
            }
        }
        for (int col = 0; col < kN; ++col) {  // Gauss-Jordan with partial pivoting (SPD system)
            int piv = col;
            for (int r = col + 1; r < kN; ++r) {
                if (std::abs(m[r][col]) > std::abs(m[piv][col])) piv = r;
            }
            for (int k = 0; k <= kN; ++k) std::swap(m[col][k], m[piv][k]);
            if (m[col][col] == 0.0) break;
            for (int r = 0; r < kN; ++r) {
                if (r == col) continue;
                const double f = m[r][col] / m[col][col];
                for (int k = col; k <= kN; ++k) m[r][k] -= f * m[col][k];
            }
        }
        for (int k = 0; k < kN; ++k) a[k] = m[k][kN] / m[k][k];
        double sum = 0.0;
        for (int i = 0; i < kPts; ++i) {
            double p = 0.0;
            for (int k = 0; k < kN; ++k) p += a[k] * basis[i][k];
            w[i] *= std::abs(p - ys[i]);
            sum += w[i];
        }
        if (!(sum > 0.0)) break;  // an exact fit: nothing left to reweight
        for (int i = 0; i < kPts; ++i) w[i] = w[i] * kPts / sum;
    }
    FresnelPolyParams out;
    out.p0 = vec4(static_cast<float>(f0), static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2]));
    out.p1 = vec2(static_cast<float>(a[3]), static_cast<float>(a[4]));
    double worst = 0.0;
    for (int i = 0; i <= 4096; ++i) {
        const float c = static_cast<float>(i) / 4096.0f;
        worst = std::max(worst, std::abs(static_cast<double>(rk_fresnel_dielectric_poly(c, out.p0, out.p1)) -
                                         exact(static_cast<double>(c))));
    }
    out.max_abs_error = static_cast<float>(worst);
    return out;
}

}  // namespace raykit
