// raykit — lightshafts.hpp: the CPU build of shaders/raykit/lightshafts.glsl (screen-space light
// shafts) over LsMapCpu, whose read function is the C++ twin of the GLSL texture read
// (rk_ls_read: LINEAR filtering, clamp to edge, texel centres at (i + 0.5) / size).
//
// Like every header with option macros, rk_ls_accumulate lives in an inline namespace named after
// RK_LS_MAX_SAMPLES (docs/dialect.md). tests/gpu/parity_lightshafts.cpp checks both builds against
// each other on a real driver.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "raykit/common.hpp"

namespace raykit {

/// An RGB image on the CPU (the occlusion buffer): width x height texels, row-major, row 0 at v = 0.
struct LsMapCpu {
    int width = 0, height = 0;
    std::vector<vec3> v;
    vec3 at(int x, int y) const
    {
        x = std::min(std::max(x, 0), width - 1);
        y = std::min(std::max(y, 0), height - 1);
        return v[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
    }
};

/// rk_ls_read (C++ twin of textureLod(sampler2D, uv, 0).rgb with LINEAR filtering and clamp to
/// edge): the bilinear blend of the four texels around uv. An empty map and NaN coordinates read 0.
inline vec3 rk_ls_read(const LsMapCpu& m, vec2 uv)
{
    if (m.width <= 0 || m.height <= 0 || m.v.size() < static_cast<size_t>(m.width) * static_cast<size_t>(m.height)) return vec3(0.0f);
    const double fx = static_cast<double>(uv.x) * m.width - 0.5, fy = static_cast<double>(uv.y) * m.height - 0.5;
    if (!std::isfinite(fx) || !std::isfinite(fy)) return vec3(0.0f);
    const double cx = std::min(std::max(fx, -1.0), static_cast<double>(m.width)), cy = std::min(std::max(fy, -1.0), static_cast<double>(m.height));
    const int x0 = static_cast<int>(std::floor(cx)), y0 = static_cast<int>(std::floor(cy));
    const float ax = static_cast<float>(cx - x0), ay = static_cast<float>(cy - y0);
    const vec3 top = m.at(x0, y0) * (1.0f - ax) + m.at(x0 + 1, y0) * ax, bottom = m.at(x0, y0 + 1) * (1.0f - ax) + m.at(x0 + 1, y0 + 1) * ax;
    return top * (1.0f - ay) + bottom * ay;
}

#define RK_LS_MAP const LsMapCpu&
#include "raykit/lightshafts.glsl"

}  // namespace raykit
