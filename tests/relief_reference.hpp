// Reference for relief.glsl's tests and bench: the exact first intersection of a ray with the
// bilinear surface of a depth map, written independently of include/raykit/relief.hpp (its own
// double-precision bilinear read, its own wrap). A fine march (at most 1/32 texel and 1/2048 of the
// depth range per step) finds the first sample at or below the surface, then 60 bisections.
// Along a ray the bilinear surface is a quadratic per cell, so a crossing that opens and closes
// within one step (a graze under 1/32 texel) is the only thing it can miss.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace relief_ref {

struct Map {
    int w = 0, h = 0;
    bool wrap = true;
    std::vector<double> d;  // depth, row-major
    double texel(int x, int y) const
    {
        if (wrap) {
            x = ((x % w) + w) % w;
            y = ((y % h) + h) % h;
        } else {
            x = std::clamp(x, 0, w - 1);
            y = std::clamp(y, 0, h - 1);
        }
        return d[size_t(y) * size_t(w) + size_t(x)];
    }
    double at(double u, double v) const
    {
        double fx = u * w - 0.5, fy = v * h - 0.5;
        if (!wrap) {
            fx = std::clamp(fx, 0.0, double(w - 1));
            fy = std::clamp(fy, 0.0, double(h - 1));
        }
        const double x0 = std::floor(fx), y0 = std::floor(fy), ax = fx - x0, ay = fy - y0;
        const int ix = int(std::fmod(x0, double(w)) + (x0 < 0 ? w : 0)), iy = int(std::fmod(y0, double(h)) + (y0 < 0 ? h : 0));
        const double a = texel(ix, iy), b = texel(ix + 1, iy), c = texel(ix, iy + 1), e = texel(ix + 1, iy + 1);
        return (a * (1 - ax) + b * ax) * (1 - ay) + (c * (1 - ax) + e * ax) * ay;
    }
};

struct Hit {
    double u, v, t;
};

/// The first point p(t) = uv + t delta, t in [0, 1], with t >= d(p(t)).
inline Hit trace(const Map& m, double u, double v, double du, double dv)
{
    const double len_texels = std::sqrt(du * du * m.w * m.w + dv * dv * m.h * m.h);
    const int n = std::max(2048, int(std::ceil(len_texels * 32.0)));
    auto f = [&](double t) { return t - m.at(u + du * t, v + dv * t); };
    double ta = 0.0;
    if (f(0.0) >= 0.0) return {u, v, 0.0};
    for (int k = 1; k <= n; ++k) {
        const double tb = double(k) / n;
        if (f(tb) >= 0.0) {
            double a = ta, b = tb;
            for (int i = 0; i < 60; ++i) {
                const double mid = 0.5 * (a + b);
                (f(mid) >= 0.0 ? b : a) = mid;
            }
            return {u + du * b, v + dv * b, b};
        }
        ta = tb;
    }
    return {u + du, v + dv, 1.0};
}

/// Whether the segment from hit point (u, v, t) towards a light reaching the polygon after
/// lu, lv uv per unit of depth rise is blocked (the surface above it by more than `bias`), sampled
/// at 1/32 texel.
inline bool shadowed(const Map& m, double u, double v, double t, double lu, double lv, double bias)
{
    const double len = std::sqrt(lu * lu * m.w * m.w + lv * lv * m.h * m.h) * t;
    const int n = std::max(1024, int(std::ceil(len * 32.0)));
    for (int k = 1; k < n; ++k) {
        const double e = t * (1.0 - double(k) / n);
        if (m.at(u + lu * (t - e), v + lv * (t - e)) < e - bias) return true;
    }
    return false;
}

/// A smooth tiling test surface (sines and bumps) with a few sharp ridges, depth in [0, 1].
inline std::vector<double> test_depths(int w, int h, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    std::vector<double> d(size_t(w) * size_t(h));
    const double kTau = 6.283185307179586;
    double ph[6];
    for (double& p : ph) p = U(rng) * kTau;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double u = (x + 0.5) / w, v = (y + 0.5) / h;
            double z = 0.5 + 0.2 * std::sin(kTau * (2 * u) + ph[0]) * std::cos(kTau * (1 * v) + ph[1]) + 0.12 * std::sin(kTau * (3 * u + 2 * v) + ph[2]) +
                       0.08 * std::cos(kTau * (5 * v) + ph[3]);
            // Bricks: a mortar groove every quarter.
            if ((x % (w / 4)) == 0 || (y % (h / 4)) == 0) z += 0.3;
            d[size_t(y) * size_t(w) + size_t(x)] = std::clamp(z, 0.0, 1.0);
        }
    return d;
}

}  // namespace relief_ref
