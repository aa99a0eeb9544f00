// raykit — volume.hpp: the CPU build of shaders/raykit/volume.glsl (raytraced volumes: spans,
// visible length against the depth buffer, thickness -> opacity, the sphere's two pitfalls and
// their fixes, the slice uv correction and alpha) and the CPU side of the thesis's slices: the
// spherical slice layout (van Dongen, "Interior Mapping: A new technique for rendering realistic
// buildings", §6.3.2).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_volume.cpp checks that both builds agree on a real driver.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "raykit/common.hpp"
#include "raykit/gbuffer.hpp"
#include "raykit/ray.hpp"

namespace raykit {
#include "raykit/volume.glsl"

/// One slice of a slice stack: its offset from the centre along the view axis (towards the eye
/// positive), the half-size of its square, and its alpha.
struct VolumeSlice {
    float offset = 0.0f, half_size = 0.0f, alpha = 0.0f;
};

/// volume_slices: the thesis's slices laid out as a sphere of radius r: n camera-facing squares at
/// offsets z_i = r ((2 i + 1) / n - 1) (i = 0..n-1, evenly spaced, none on the rim), each with
/// half-size sqrt(r² - z_i²) (the sphere's cross-section), and the alpha rk_vol_slice_alpha(a, n)
/// that makes the n slices along the centre line compose to opacity a. n in 0..1024, r >= 0.
inline std::vector<VolumeSlice> volume_slices(int n, float r, float a)
{
    const int nn = std::min(std::max(n, 0), 1024);
    const double rr = std::max(static_cast<double>(r), 0.0);
    std::vector<VolumeSlice> out;
    const float alpha = rk_vol_slice_alpha(a, static_cast<uint>(nn));
    for (int i = 0; i < nn; ++i) {
        const double z = rr * ((2.0 * i + 1.0) / nn - 1.0);
        VolumeSlice s;
        s.offset = static_cast<float>(z);
        s.half_size = static_cast<float>(std::sqrt(std::max(rr * rr - z * z, 0.0)));
        s.alpha = alpha;
        out.push_back(s);
    }
    return out;
}

}  // namespace raykit
