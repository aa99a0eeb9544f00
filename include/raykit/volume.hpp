// raykit — volume.hpp: the CPU build of shaders/raykit/volume.glsl (raytraced volumes: spans,
// visible length against the depth buffer, thickness -> opacity, the sphere's two pitfalls and
// their fixes, the slice uv correction and alpha) and the CPU side of the thesis's slices: the
// spherical slice layout (van Dongen, "Interior Mapping: A new technique for rendering realistic
// buildings", §6.3.2).
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_volume.cpp checks that both builds agree on a real driver. rk_vol_density is
// the C++ twin of the density texture read (trilinear, clamp to edge); rk_vol_march_box lives in an
// inline namespace named after RK_VOL_MAX_STEPS, so two translation units may choose differently.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "raykit/common.hpp"
#include "raykit/gbuffer.hpp"
#include "raykit/ray.hpp"

namespace raykit {

/// A density volume on the CPU: w x h x d values, x fastest, slice z = 0 first (GL's 3-D upload
/// order).
struct VolDensityCpu {
    int w = 0, h = 0, d = 0;
    std::vector<float> v;
    float at(int x, int y, int z) const
    {
        x = std::min(std::max(x, 0), w - 1);
        y = std::min(std::max(y, 0), h - 1);
        z = std::min(std::max(z, 0), d - 1);
        return v[(static_cast<size_t>(z) * static_cast<size_t>(h) + static_cast<size_t>(y)) * static_cast<size_t>(w) + static_cast<size_t>(x)];
    }
};

/// rk_vol_density (C++ twin of textureLod(sampler3D, uvw, 0).x with LINEAR filtering and clamp to
/// edge): the trilinear blend of the 8 texels around uvw, texel centres at (i + 0.5) / size. An
/// empty volume and NaN coordinates read 0.
inline float rk_vol_density(const VolDensityCpu& m, vec3 uvw)
{
    if (m.w <= 0 || m.h <= 0 || m.d <= 0 || m.v.size() < static_cast<size_t>(m.w) * static_cast<size_t>(m.h) * static_cast<size_t>(m.d))
        return 0.0f;
    const double f[3] = {static_cast<double>(uvw.x) * m.w - 0.5, static_cast<double>(uvw.y) * m.h - 0.5, static_cast<double>(uvw.z) * m.d - 0.5};
    const int size[3] = {m.w, m.h, m.d};
    int i0[3];
    float a[3];
    for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(f[k])) return 0.0f;
        const double c = std::min(std::max(f[k], -1.0), static_cast<double>(size[k]));
        i0[k] = static_cast<int>(std::floor(c));
        a[k] = static_cast<float>(c - i0[k]);
    }
    float r = 0.0f;
    for (int c = 0; c < 8; ++c) {
        const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
        const float wgt = (dx ? a[0] : 1.0f - a[0]) * (dy ? a[1] : 1.0f - a[1]) * (dz ? a[2] : 1.0f - a[2]);
        r += wgt * m.at(i0[0] + dx, i0[1] + dy, i0[2] + dz);
    }
    return r;
}

#define RK_VOL_DENSITY_MAP const VolDensityCpu&
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
