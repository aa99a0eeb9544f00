// Float64 references for raykit's tone mapping, written from the published formulas (the papers,
// blog posts and specification named in shaders/raykit/tonemap.glsl), not from raykit's code.
// Matrices are written row-major here, as the sources print them.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace ref {

using d3 = std::array<double, 3>;
using m3 = std::array<d3, 3>;  // rows

inline d3 mul(const m3& m, const d3& v)
{
    d3 r{};
    for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    return r;
}
inline d3 clamp01(d3 v)
{
    for (double& x : v) x = std::min(1.0, std::max(0.0, x));
    return v;
}
inline double luminance709(const d3& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

// sRGB, IEC 61966-2-1.
inline double srgb_encode(double x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055; }
inline double srgb_decode(double x) { return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4); }

// Reinhard et al. 2002, Eq. 3 and 4.
inline double reinhard(double l) { return l / (1.0 + l); }
inline double reinhard_ext(double l, double w) { return std::min(1.0, l * (1.0 + l / (w * w)) / (1.0 + l)); }

// Narkowicz 2015.
inline double aces_narkowicz(double x) { return std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

// Hill (BakingLab ACES.hlsl): ACESInputMat, RRTAndODTFit, ACESOutputMat (rows as printed there).
inline d3 aces_hill(const d3& c)
{
    const m3 in{{{0.59719, 0.35458, 0.04823}, {0.07600, 0.90834, 0.01566}, {0.02840, 0.13383, 0.83777}}};
    const m3 out{{{1.60475, -0.53108, -0.07367}, {-0.10208, 1.10813, -0.00605}, {-0.00327, -0.07276, 1.07602}}};
    d3 v = mul(in, c);
    for (double& x : v) x = (x * (x + 0.0245786) - 0.000090537) / (x * (0.983729 * x + 0.4329510) + 0.238081);
    return clamp01(mul(out, v));
}

// Minimal AgX (Wrensch; Sobotka's inset/outset), looks as in Blender/Filament (ASC CDL).
inline d3 agx(const d3& c, int look)
{
    // Rows = the GLSL source's columns.
    const m3 inset{{{0.842479062253094, 0.0784335999999992, 0.0792237451477643},
                    {0.0423282422610123, 0.878468636469772, 0.0791661274605434},
                    {0.0423756549057051, 0.0784336, 0.879142973793104}}};
    const m3 outset{{{1.19687900512017, -0.0980208811401368, -0.0990297440797205},
                     {-0.0528968517574562, 1.15190312990417, -0.0989611768448433},
                     {-0.0529716355144438, -0.0980434501171241, 1.15107367264116}}};
    const double lo = -12.47393, hi = 4.026069;
    d3 v = mul(inset, c);
    for (double& x : v) {
        x = std::clamp(std::log2(std::max(x, 1e-10)), lo, hi);
        x = (x - lo) / (hi - lo);
        x = 15.5 * std::pow(x, 6) - 40.14 * std::pow(x, 5) + 31.96 * std::pow(x, 4) - 6.868 * std::pow(x, 3) +
            0.4298 * x * x + 0.1191 * x - 0.00232;
    }
    if (look != 0) {
        const d3 slope = look == 1 ? d3{1.0, 0.9, 0.5} : d3{1.0, 1.0, 1.0};
        const double power = look == 1 ? 0.8 : 1.35, sat = look == 1 ? 1.3 : 1.4;
        const double l = luminance709(v);
        for (int i = 0; i < 3; ++i) v[i] = l + sat * (std::pow(std::max(v[i] * slope[i], 0.0), power) - l);
    }
    v = clamp01(mul(outset, v));
    for (double& x : v) x = std::pow(x, 2.2);
    return v;
}

// Khronos PBR Neutral, PBR_Neutral/README.md. `to_white` = the first published GLSL's final mix
// toward vec3(1) instead of the spec's vec3(newPeak).
inline d3 pbr_neutral(d3 c, bool to_white = false)
{
    const double start = 0.8 - 0.04, desat = 0.15;
    const double x = std::min({c[0], c[1], c[2]});
    const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    for (double& v : c) v -= offset;
    const double peak = std::max({c[0], c[1], c[2]});
    if (peak < start) return c;
    const double d = 1.0 - start;
    const double np = 1.0 - d * d / (peak + d - start);
    for (double& v : c) v *= np / peak;
    const double g = 1.0 - 1.0 / (desat * (peak - np) + 1.0);
    for (double& v : c) v = (1.0 - g) * v + g * (to_white ? 1.0 : np);
    return c;
}

// Hable 2010.
inline double hable_curve(double x)
{
    const double A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
    return ((x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F)) - E / F;
}
inline double hable(double x) { return std::clamp(hable_curve(x) / hable_curve(11.2), 0.0, 1.0); }

// Lottes 2016 (GDC), constants contrast 1.6, shoulder 0.977, hdrMax 8, midIn 0.18, midOut 0.267.
inline double lottes(double x)
{
    const double a = 1.6, d = 0.977, hdr = 8.0, mi = 0.18, mo = 0.267;
    const double b = (-std::pow(mi, a) + std::pow(hdr, a) * mo) / ((std::pow(hdr, a * d) - std::pow(mi, a * d)) * mo);
    const double c = (std::pow(hdr, a * d) * std::pow(mi, a) - std::pow(hdr, a) * std::pow(mi, a * d) * mo) /
                     ((std::pow(hdr, a * d) - std::pow(mi, a * d)) * mo);
    return std::clamp(std::pow(x, a) / (std::pow(x, a * d) * b + c), 0.0, 1.0);
}

// Uchimura 2017 (GT), defaults P 1, a 1, m 0.22, l 0.4, c 1.33, b 0.
inline double uchimura(double x)
{
    const double P = 1, a = 1, m = 0.22, l = 0.4, c = 1.33, b = 0;
    const double l0 = ((P - m) * l) / a, S0 = m + l0, S1 = m + a * l0, C2 = (a * P) / (P - S1), CP = -C2 / P;
    const double t = std::clamp(x / m, 0.0, 1.0);
    const double w0 = 1.0 - t * t * (3.0 - 2.0 * t);
    const double w2 = x >= m + l0 ? 1.0 : 0.0;
    const double w1 = 1.0 - w0 - w2;
    const double T = m * std::pow(x / m, c) + b;
    const double S = P - (P - S1) * std::exp(CP * (x - S0));
    const double L = m + a * (x - m);
    return std::clamp(T * w0 + L * w1 + S * w2, 0.0, 1.0);
}

}  // namespace ref
