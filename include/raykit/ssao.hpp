// raykit — ssao.hpp: the CPU build of shaders/raykit/ssao.glsl (screen-space ambient occlusion:
// the thesis's depth-only counting, the normal-oriented hemisphere with a range check, the
// depth-aware blur) over AoMapCpu, whose read function is the C++ twin of the GLSL texture read
// (rk_ao_read: the nearest texel, clamp to edge, as textureLod on a NEAREST-filtered texture), and
// the CPU side: deterministic, stratified kernels and a rotation-noise tile.
//
// Like every header with option macros, the functions that depend on RK_AO_MAX_SAMPLES live in an
// inline namespace named after it (docs/dialect.md), so two translation units may choose
// differently. tests/gpu/parity_ssao.cpp checks both builds against each other on a real driver.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "raykit/common.hpp"
#include "raykit/gbuffer.hpp"

namespace raykit {

/// A float image on the CPU (a depth buffer's window depths or an AO buffer): width x height values,
/// row-major, row 0 at v = 0 (GL's upload order).
struct AoMapCpu {
    int width = 0, height = 0;
    std::vector<float> v;
};

/// rk_ao_read (C++ twin of textureLod(sampler2D, uv, 0).x with NEAREST filtering and clamp to
/// edge): the texel under uv. An empty map reads 0; NaN coordinates read texel 0.
inline float rk_ao_read(const AoMapCpu& m, vec2 uv)
{
    if (m.width <= 0 || m.height <= 0 || m.v.size() < static_cast<size_t>(m.width) * static_cast<size_t>(m.height)) return 0.0f;
    const double fx = static_cast<double>(uv.x) * m.width, fy = static_cast<double>(uv.y) * m.height;
    const int x = std::isfinite(fx) ? static_cast<int>(std::floor(std::min(std::max(fx, 0.0), m.width - 1.0))) : 0;
    const int y = std::isfinite(fy) ? static_cast<int>(std::floor(std::min(std::max(fy, 0.0), m.height - 1.0))) : 0;
    return m.v[static_cast<size_t>(y) * static_cast<size_t>(m.width) + static_cast<size_t>(x)];
}

#define RK_AO_MAP const AoMapCpu&
#include "raykit/ssao.glsl"

/// ao_kernel_hemisphere: n points in the unit hemisphere around +z for rk_ao_hemisphere,
/// deterministic for `seed`: directions stratified over the hemisphere (a jittered grid of about
/// sqrt(n) x sqrt(n) cells mapped by the concentric disk map and lifted to z = sqrt(1 - x² - y²),
/// which distributes them by cos theta), lengths stratified in (0, 1] and scaled by
/// 0.1 + 0.9 t² (more samples near the point, where occlusion matters most), the two
/// stratifications paired by a seeded shuffle. Every point has z > 0 and length <= 1. n in 0..4096.
inline std::vector<vec3> ao_kernel_hemisphere(int n, uint32_t seed)
{
    const int nn = std::min(std::max(n, 0), 4096);
    std::vector<vec3> out;
    if (nn == 0) return out;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int cols = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(nn)))));
    const int rows = (nn + cols - 1) / cols;
    std::vector<int> order(static_cast<size_t>(nn));
    for (int i = 0; i < nn; ++i) order[static_cast<size_t>(i)] = i;
    std::shuffle(order.begin(), order.end(), rng);
    for (int i = 0; i < nn; ++i) {
        // Cell i of the grid (the last row may be partial: its cells stretch over the row).
        const int row = i / cols, col = i % cols;
        const int in_row = row == rows - 1 ? nn - row * cols : cols;
        const double sx = (col + u(rng)) / in_row, sy = (row + u(rng)) / rows;
        const double a = 2.0 * sx - 1.0, b = 2.0 * sy - 1.0;
        // Concentric map (Shirley and Chiu) of (a, b) onto the unit disk.
        double r, phi;
        const double pi4 = 0.78539816339744830962;
        if (a == 0.0 && b == 0.0) {
            r = 0.0;
            phi = 0.0;
        } else if (std::abs(a) > std::abs(b)) {
            r = a;
            phi = pi4 * (b / a);
        } else {
            r = b;
            phi = 2.0 * pi4 - pi4 * (a / b);
        }
        const double x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(1e-6, 1.0 - x * x - y * y));
        const double t = (order[static_cast<size_t>(i)] + u(rng)) / nn, len = 0.1 + 0.9 * t * t;
        const double inv = len / std::sqrt(x * x + y * y + z * z);
        out.push_back(vec3(static_cast<float>(x * inv), static_cast<float>(y * inv), static_cast<float>(z * inv)));
    }
    return out;
}

/// ao_kernel_sphere: n points in the unit ball for rk_ao_sphere_count (the thesis's Crytek
/// counting), deterministic for `seed`: directions stratified in z and azimuth (uniform on the
/// sphere), lengths as ao_kernel_hemisphere's. Length <= 1. n in 0..4096.
inline std::vector<vec3> ao_kernel_sphere(int n, uint32_t seed)
{
    const int nn = std::min(std::max(n, 0), 4096);
    std::vector<vec3> out;
    if (nn == 0) return out;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<int> order(static_cast<size_t>(nn));
    for (int i = 0; i < nn; ++i) order[static_cast<size_t>(i)] = i;
    std::shuffle(order.begin(), order.end(), rng);
    const double pi = 3.14159265358979323846, golden = pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < nn; ++i) {
        const double z = 1.0 - 2.0 * (i + u(rng)) / nn, rho = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = golden * i + 2.0 * pi * u(rng) / nn;
        const double t = (order[static_cast<size_t>(i)] + u(rng)) / nn, len = 0.1 + 0.9 * t * t;
        out.push_back(vec3(static_cast<float>(len * rho * std::cos(phi)), static_cast<float>(len * rho * std::sin(phi)),
                           static_cast<float>(len * z)));
    }
    return out;
}

/// ao_rotation_noise: a size x size tile (row-major) of unit 2-D vectors for rk_ao_hemisphere's
/// `rot` (and, as (x, y, 0) normalised, rk_ao_sphere_count's `plane`): the size² angles stratified
/// over [0, 2 pi) (one per stratum, jittered) and shuffled, deterministic for `seed`. Tile it over
/// the screen (GL_REPEAT, texel = pixel mod size) and blur over the same size. size in 1..64.
inline std::vector<vec2> ao_rotation_noise(int size, uint32_t seed)
{
    const int s = std::min(std::max(size, 1), 64), n = s * s;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<vec2> out;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * 3.14159265358979323846 * (i + u(rng)) / n;
        out.push_back(vec2(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a))));
    }
    std::shuffle(out.begin(), out.end(), rng);
    return out;
}

}  // namespace raykit
