// raykit — shadow_filter.hpp: the CPU build of shaders/raykit/shadow_filter.glsl (the thesis's PCF,
// Poisson and Vogel PCF, PCSS) over a CPU shadow map, ShadowMapCpu, whose two read functions are
// the C++ twins of the GLSL texture reads: rk_sh_compare (a depth compare with linear filtering:
// the four texels around uv compared and weighted bilinearly, clamp to edge, texel centres at
// (i + 0.5) / size, as OpenGL's LINEAR filter on a depth-compare texture) and rk_sh_depth (the
// nearest texel). C++ only, because GLSL reads the map through the texture unit;
// tests/gpu/parity_shadow_filter.cpp checks the twins against the driver.
//
// Like every header with option macros, the filter functions live in an inline namespace named
// after RK_SH_REVERSED_Z and RK_SH_MAX_TAPS (docs/dialect.md), so two translation units may choose
// differently.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "raykit/shadow.hpp"

namespace raykit {

/// A shadow map on the CPU: width x height depths, row-major, row 0 at v = 0 (GL's upload order).
/// `reversed`: compare as reversed-Z (GEQUAL) instead of LEQUAL; it must match RK_SH_REVERSED_Z of
/// the translation unit that filters it.
struct ShadowMapCpu {
    int width = 0, height = 0;
    std::vector<float> depth;
    bool reversed = false;
    float at(int x, int y) const
    {
        x = std::min(std::max(x, 0), width - 1);
        y = std::min(std::max(y, 0), height - 1);
        return depth[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
    }
};

/// rk_sh_compare (C++ twin of GLSL's texture(sampler2DShadow, vec3(uv, ref)) with LINEAR filtering):
/// the bilinear average of the four texels' compares (lit: ref <= stored, or >= reversed). An empty
/// map is lit.
inline float rk_sh_compare(const ShadowMapCpu& m, vec2 uv, float ref)
{
    if (m.width <= 0 || m.height <= 0 || m.depth.size() < static_cast<size_t>(m.width) * static_cast<size_t>(m.height)) return 1.0f;
    const double fx = static_cast<double>(uv.x) * m.width - 0.5, fy = static_cast<double>(uv.y) * m.height - 0.5;
    if (!std::isfinite(fx) || !std::isfinite(fy)) return 1.0f;
    const double cx = std::min(std::max(fx, -1.0), static_cast<double>(m.width)), cy = std::min(std::max(fy, -1.0), static_cast<double>(m.height));
    const int x0 = static_cast<int>(std::floor(cx)), y0 = static_cast<int>(std::floor(cy));
    const float ax = static_cast<float>(cx - x0), ay = static_cast<float>(cy - y0);
    auto lit = [&](int x, int y) { return (m.reversed ? ref >= m.at(x, y) : ref <= m.at(x, y)) ? 1.0f : 0.0f; };
    const float top = lit(x0, y0) * (1.0f - ax) + lit(x0 + 1, y0) * ax, bottom = lit(x0, y0 + 1) * (1.0f - ax) + lit(x0 + 1, y0 + 1) * ax;
    return top * (1.0f - ay) + bottom * ay;
}

/// rk_sh_depth (C++ twin of textureLod(sampler2D, uv, 0) with NEAREST filtering): the stored depth
/// of the texel under uv (clamp to edge). An empty map reads as the far plane.
inline float rk_sh_depth(const ShadowMapCpu& m, vec2 uv)
{
    if (m.width <= 0 || m.height <= 0 || m.depth.size() < static_cast<size_t>(m.width) * static_cast<size_t>(m.height))
        return m.reversed ? 0.0f : 1.0f;
    const double fx = static_cast<double>(uv.x) * m.width, fy = static_cast<double>(uv.y) * m.height;
    if (!std::isfinite(fx) || !std::isfinite(fy)) return m.reversed ? 0.0f : 1.0f;
    const int x = static_cast<int>(std::floor(std::min(std::max(fx, -1.0), static_cast<double>(m.width))));
    const int y = static_cast<int>(std::floor(std::min(std::max(fy, -1.0), static_cast<double>(m.height))));
    return m.at(x, y);
}

#define RK_SH_MAP const ShadowMapCpu&
#define RK_SH_DEPTH_MAP const ShadowMapCpu&
#include "raykit/shadow_filter.glsl"

}  // namespace raykit
