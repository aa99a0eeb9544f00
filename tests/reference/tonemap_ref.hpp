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

/// Hill's RRTAndODTFit alone (BakingLab ACES.hlsl), unclamped: the rational curve in AP1.
inline double aces_hill_fit(double v) { return (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081); }

/// The ASC CDL looks of AgX (Blender/Filament): slope, power, then saturation about BT.709 luma.
/// look 1 golden (slope 1, 0.9, 0.5; power 0.8; saturation 1.3), 2 punchy (power 1.35, sat 1.4).
inline d3 agx_look(d3 v, int look)
{
    if (look != 1 && look != 2) return v;
    const d3 slope = look == 1 ? d3{1.0, 0.9, 0.5} : d3{1.0, 1.0, 1.0};
    const double power = look == 1 ? 0.8 : 1.35, sat = look == 1 ? 1.3 : 1.4;
    const double l = luminance709(v);
    for (int i = 0; i < 3; ++i) v[i] = l + sat * (std::pow(std::max(v[i] * slope[i], 0.0), power) - l);
    return v;
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

// Lottes 2016: the (b, c) that map mid_in -> mid_out and hdr_max -> 1 for contrast a, shoulder d.
inline std::array<double, 2> lottes_params(double a, double d, double hdr, double mi, double mo)
{
    const double den = (std::pow(hdr, a * d) - std::pow(mi, a * d)) * mo;
    return {(-std::pow(mi, a) + std::pow(hdr, a) * mo) / den,
            (std::pow(hdr, a * d) * std::pow(mi, a) - std::pow(hdr, a) * std::pow(mi, a * d) * mo) / den};
}

// Uchimura 2017 (GT) with all six parameters, unclamped: toe m (x/m)^c + b below m (blended by
// smoothstep(0, m, x)), linear m + a (x - m), shoulder P - (P - S1) e^(-C2/P (x - S0)) from S0 on.
inline double uchimura_curve(double x, double P, double a, double m, double l, double c, double b)
{
    const double l0 = ((P - m) * l) / a, S0 = m + l0, S1 = m + a * l0, C2 = (a * P) / (P - S1), CP = -C2 / P;
    const double t = std::clamp(x / m, 0.0, 1.0);
    const double w0 = 1.0 - t * t * (3.0 - 2.0 * t);
    const double w2 = x >= m + l0 ? 1.0 : 0.0;
    const double w1 = 1.0 - w0 - w2;
    return (m * std::pow(x / m, c) + b) * w0 + (m + a * (x - m)) * w1 + (P - (P - S1) * std::exp(CP * (x - S0))) * w2;
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


// ---------------------------------------------------------------------------------------------
// ACES 1.0 RRT + ODT (sRGB / Rec.709 primaries, 100 nits, dim surround), the transform the
// Narkowicz and Hill fits approximate. Written from the structure and constants of the Academy's
// CTL (ampas/aces-dev, transforms/ctl: rrt/RRT.ctl, odt/sRGB/ODT.Academy.sRGB_100nits_dim.ctl and
// lib/ACESlib.{Tonescales,RRT_Common,ODT_Common,Transform_Common,Utilities_Color}.ctl, v1.0.x),
// evaluated in float64 (the CTL runs in float32). The matrices are not typed in: they are derived
// here from the published chromaticities (AP0, AP1, Rec.709, D60 = (0.32168, 0.33767),
// D65 = (0.3127, 0.329)) and the Bradford cone matrix, as the CTL does at load time.
// Input: scene-linear Rec.709 RGB (converted to ACES2065-1 by Rec.709 -> XYZ -> Bradford D65->D60
// -> AP0, the same path as Hill's ACESInputMat). Output: display-linear Rec.709 in [0, 1], i.e. the
// ODT's code value before its sRGB encoding (moncurve_r 2.4 / 0.055 = the sRGB OETF).
// Column-vector convention throughout (M * v); the CTL multiplies row vectors by transposed matrices.

namespace aces {

inline m3 mmul(const m3& a, const m3& b)
{
    m3 r{};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
    }
    return r;
}

inline m3 inverse(const m3& m)
{
    const double a = m[0][0], b = m[0][1], c = m[0][2], d = m[1][0], e = m[1][1], f = m[1][2], g = m[2][0],
                 h = m[2][1], i = m[2][2];
    const double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
    const double det = a * A + b * B + c * C;
    return {{{A / det, -(b * i - c * h) / det, (b * f - c * e) / det},
             {B / det, (a * i - c * g) / det, -(a * f - c * d) / det},
             {C / det, -(a * h - b * g) / det, (a * e - b * d) / det}}};
}

struct Primaries {
    double rx, ry, gx, gy, bx, by, wx, wy;
};
constexpr Primaries kAP0{0.7347, 0.2653, 0.0, 1.0, 0.0001, -0.0770, 0.32168, 0.33767};
constexpr Primaries kAP1{0.713, 0.293, 0.165, 0.830, 0.128, 0.044, 0.32168, 0.33767};
constexpr Primaries kRec709{0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290};

inline d3 xy_to_XYZ(double x, double y) { return {x / y, 1.0, (1.0 - x - y) / y}; }

/// RGB -> XYZ for the primaries, normalised so RGB (1, 1, 1) is the white with Y = 1 (SMPTE RP 177).
inline m3 rgb_to_xyz(const Primaries& p)
{
    const d3 r = xy_to_XYZ(p.rx, p.ry), g = xy_to_XYZ(p.gx, p.gy), b = xy_to_XYZ(p.bx, p.by);
    const m3 cols{{{r[0], g[0], b[0]}, {r[1], g[1], b[1]}, {r[2], g[2], b[2]}}};
    const d3 s = mul(inverse(cols), xy_to_XYZ(p.wx, p.wy));
    m3 m = cols;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m[i][j] *= s[j];
    }
    return m;
}

/// Von Kries adaptation in the Bradford cone space from white (sx, sy) to white (dx, dy).
inline m3 bradford(double sx, double sy, double dx, double dy)
{
    const m3 B{{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
    const d3 s = mul(B, xy_to_XYZ(sx, sy)), d = mul(B, xy_to_XYZ(dx, dy));
    const m3 D{{{d[0] / s[0], 0.0, 0.0}, {0.0, d[1] / s[1], 0.0}, {0.0, 0.0, d[2] / s[2]}}};
    return mmul(inverse(B), mmul(D, B));
}

/// calc_sat_adjust_matrix: out = sat * in + (1 - sat) * Y(in), Y with the AP1 luminance weights.
inline m3 saturation_matrix(double sat)
{
    const m3 ap1 = rgb_to_xyz(kAP1);
    m3 m{};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m[i][j] = (1.0 - sat) * ap1[1][j] + (i == j ? sat : 0.0);
    }
    return m;
}

struct Matrices {
    m3 rec709_to_ap0, ap0_to_ap1, ap1_to_ap0, ap1_to_xyz, xyz_to_ap1, rrt_sat, odt_sat, d60_to_d65, xyz_to_rec709;
};

inline const Matrices& matrices()
{
    static const Matrices m = [] {
        Matrices r;
        const m3 ap0 = rgb_to_xyz(kAP0), rec = rgb_to_xyz(kRec709);
        r.ap1_to_xyz = rgb_to_xyz(kAP1);
        r.xyz_to_ap1 = inverse(r.ap1_to_xyz);
        r.ap0_to_ap1 = mmul(r.xyz_to_ap1, ap0);
        r.ap1_to_ap0 = mmul(inverse(ap0), r.ap1_to_xyz);
        r.rec709_to_ap0 = mmul(inverse(ap0), mmul(bradford(kRec709.wx, kRec709.wy, kAP0.wx, kAP0.wy), rec));
        r.rrt_sat = saturation_matrix(0.96);
        r.odt_sat = saturation_matrix(0.93);
        r.d60_to_d65 = bradford(kAP0.wx, kAP0.wy, kRec709.wx, kRec709.wy);
        r.xyz_to_rec709 = inverse(rec);
        return r;
    }();
    return m;
}

/// Quadratic B-spline segment through three coefficients (the CTL's M = {{.5,-1,.5},{-1,1,.5},{.5,0,0}}).
inline double bspline2(double c0, double c1, double c2, double t)
{
    return 0.5 * (c0 - 2.0 * c1 + c2) * t * t + (c1 - c0) * t + 0.5 * (c0 + c1);
}

/// The segmented log-log spline of ACESlib.Tonescales: `n` knots per half (4 for c5, 8 for c9),
/// linear extensions with slopes sl/sh (log-log) outside [min, max].
inline double segmented_spline(double x, const double* lo, const double* hi, int n, double minx, double miny,
                               double midx, double maxx, double maxy, double sl, double sh)
{
    const double half_min = 5.9604644775390625e-8;  // HALF_MIN (smallest positive half)
    const double lx = std::log10(std::max(x, half_min));
    const double lmin = std::log10(minx), lmid = std::log10(midx), lmax = std::log10(maxx);
    double ly;
    if (lx <= lmin) {
        ly = lx * sl + (std::log10(miny) - sl * lmin);
    } else if (lx < lmid) {
        const double k = (n - 1) * (lx - lmin) / (lmid - lmin);
        const int j = static_cast<int>(k);
        ly = bspline2(lo[j], lo[j + 1], lo[j + 2], k - j);
    } else if (lx < lmax) {
        const double k = (n - 1) * (lx - lmid) / (lmax - lmid);
        const int j = static_cast<int>(k);
        ly = bspline2(hi[j], hi[j + 1], hi[j + 2], k - j);
    } else {
        ly = lx * sh + (std::log10(maxy) - sh * lmax);
    }
    return std::pow(10.0, ly);
}

/// RRT tone scale (segmented_spline_c5_fwd with RRT_PARAMS): 0.18 -> 4.8 (cd/m^2, OCES).
inline double rrt_tonescale(double x)
{
    static const double lo[6] = {-4.0, -4.0, -3.1573765773, -0.4852499958, 1.8477324706, 1.8477324706};
    static const double hi[6] = {-0.7185482425, 2.0810307172, 3.6681241237, 4.0, 4.0, 4.0};
    return segmented_spline(x, lo, hi, 4, 0.18 * std::pow(2.0, -15.0), 1e-4, 0.18, 0.18 * std::pow(2.0, 18.0), 1e4, 0.0,
                            0.0);
}

/// ODT tone scale (segmented_spline_c9_fwd with ODT_48nits): OCES -> cinema luminance 0.02..48.
inline double odt_tonescale_48nits(double x)
{
    static const double lo[10] = {-1.6989700043, -1.6989700043, -1.4779, -1.2291, -0.8648, -0.448, 0.00518,
                                  0.4511080334,  0.9113744414,  0.9113744414};
    static const double hi[10] = {0.5154386965, 0.8470437783, 1.1358, 1.3802, 1.5197, 1.5985, 1.6467,
                                  1.6746091357, 1.6878733390, 1.6878733390};
    static const double minx = rrt_tonescale(0.18 * std::pow(2.0, -6.5)), midx = rrt_tonescale(0.18),
                        maxx = rrt_tonescale(0.18 * std::pow(2.0, 6.5));
    return segmented_spline(x, lo, hi, 8, minx, 0.02, midx, maxx, 48.0, 0.0, 0.04);
}

/// RRT: ACES2065-1 (AP0) -> OCES (AP0). Glow module, red modifier, AP1 with RRT_SAT, tone scale.
inline d3 rrt(d3 aces)
{
    const Matrices& M = matrices();
    const double tiny = 1e-10;
    const double mx = std::max({aces[0], aces[1], aces[2]}), mn = std::min({aces[0], aces[1], aces[2]});
    const double saturation = (std::max(mx, tiny) - std::max(mn, tiny)) / std::max(mx, 1e-2);
    // Glow: lifts dark saturated colours; yc is a luminance proxy (Y + 1.75 chroma) / 3.
    const double r = aces[0], g = aces[1], b = aces[2];
    const double yc = (r + g + b + 1.75 * std::sqrt(std::max(0.0, b * (b - g) + g * (g - r) + r * (r - b)))) / 3.0;
    const double sx = (saturation - 0.4) / 0.2, st = std::max(1.0 - std::abs(sx / 2.0), 0.0);
    const double shaper = (1.0 + (sx > 0 ? 1.0 : sx < 0 ? -1.0 : 0.0) * (1.0 - st * st)) / 2.0;
    const double gain = 0.05 * shaper, mid = 0.08;
    const double glow = yc <= 2.0 / 3.0 * mid ? gain : yc >= 2.0 * mid ? 0.0 : gain * (mid / yc - 0.5);
    for (double& v : aces) v *= 1.0 + glow;
    // Red modifier: pulls reds with hue near 0° (±67.5°, cubic B-spline weight) toward 0.03.
    double weight = 0.0;
    if (!(aces[0] == aces[1] && aces[1] == aces[2])) {  // neutral: hue undefined, weight 0
        double hue = std::atan2(std::sqrt(3.0) * (aces[1] - aces[2]), 2.0 * aces[0] - aces[1] - aces[2]) *
                     (180.0 / 3.14159265358979323846);
        if (hue < 0.0) hue += 360.0;
        if (hue > 180.0) hue -= 360.0;  // centred on RRT_RED_HUE = 0
        const double w = 135.0;
        if (hue > -w / 2.0 && hue < w / 2.0) {
            const double k = (hue + w / 2.0) * 4.0 / w;
            const int j = static_cast<int>(k);
            const double t = k - j;
            const double y = j == 0   ? t * t * t / 6.0
                             : j == 1 ? (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0
                             : j == 2 ? (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0
                                      : (1.0 - t) * (1.0 - t) * (1.0 - t) / 6.0;
            weight = 1.5 * y;
        }
    }
    aces[0] += weight * saturation * (0.03 - aces[0]) * (1.0 - 0.82);
    for (double& v : aces) v = std::max(v, 0.0);
    d3 rgb = mul(M.ap0_to_ap1, aces);
    for (double& v : rgb) v = std::min(std::max(v, 0.0), 65504.0);  // HALF_MAX
    rgb = mul(M.rrt_sat, rgb);
    for (double& v : rgb) v = rrt_tonescale(v);
    return mul(M.ap1_to_ap0, rgb);
}

/// ODT.Academy.sRGB_100nits_dim up to (not including) the sRGB encoding: display-linear Rec.709.
inline d3 odt_srgb_100nits_linear(const d3& oces)
{
    const Matrices& M = matrices();
    d3 rgb = mul(M.ap0_to_ap1, oces);
    for (double& v : rgb) v = (odt_tonescale_48nits(v) - 0.02) / (48.0 - 0.02);  // Y_2_linCV
    // Dark -> dim surround: Y^0.9811 at constant xy.
    d3 xyz = mul(M.ap1_to_xyz, rgb);
    double sum = xyz[0] + xyz[1] + xyz[2];
    if (sum == 0.0) sum = 1e-10;
    const double x = xyz[0] / sum, y = xyz[1] / sum;
    const double Y = std::pow(std::max(xyz[1], 0.0), 0.9811);
    xyz = {x * Y / std::max(y, 1e-10), Y, (1.0 - x - y) * Y / std::max(y, 1e-10)};
    rgb = mul(M.odt_sat, mul(M.xyz_to_ap1, xyz));
    return clamp01(mul(M.xyz_to_rec709, mul(M.d60_to_d65, mul(M.ap1_to_xyz, rgb))));
}

}  // namespace aces

/// ACES 1.0 RRT + sRGB 100-nit ODT of scene-linear Rec.709 RGB, display-linear output in [0, 1].
inline d3 aces_rrt_odt_srgb(const d3& rec709)
{
    return aces::odt_srgb_100nits_linear(aces::rrt(mul(aces::matrices().rec709_to_ap0, rec709)));
}

}  // namespace ref
