// Float64 Fresnel references for raykit's tests and benchmarks, written independently of
// shaders/raykit/fresnel.glsl from the textbook complex-amplitude form (Born & Wolf; the same form
// pbrt-v4 uses): cos_t = sqrt(1 - sin_i^2 / eta^2) over the complex numbers, then
//   r_s = (cos_i - eta cos_t) / (cos_i + eta cos_t),  r_p = (eta cos_i - cos_t) / (eta cos_i + cos_t).
// Total internal reflection and absorbing media (complex eta) need no special case here: |r| = 1
// falls out of the complex arithmetic. Nothing from raykit is included.
#pragma once

#include <cmath>
#include <complex>
#include <utility>

namespace ref {

using cd = std::complex<double>;

/// (Rs, Rp) for complex relative index eta = n + i k at incidence cosine c in [0, 1].
inline std::pair<double, double> fresnel_sp(double c, cd eta)
{
    const double s2 = 1.0 - c * c;
    const cd cos_t = std::sqrt(1.0 - s2 / (eta * eta));
    const cd rs = (c - eta * cos_t) / (c + eta * cos_t);
    const cd rp = (eta * c - cos_t) / (eta * c + cos_t);
    return {std::norm(rs), std::norm(rp)};
}

/// Unpolarised dielectric reflectance; eta == 1 is an absent interface (0), which the complex form
/// leaves as 0/0 at grazing incidence.
inline double fresnel(double c, double eta)
{
    if (eta == 1.0) return 0.0;
    auto sp = fresnel_sp(c, cd(eta, 0.0));
    return 0.5 * (sp.first + sp.second);
}

inline double conductor(double c, double n, double k)
{
    if (n == 1.0 && k == 0.0) return 0.0;
    auto sp = fresnel_sp(c, cd(n, k));
    return 0.5 * (sp.first + sp.second);
}

/// The thesis's angle form (Eq. 3.2-3.4), valid away from normal incidence and TIR.
inline std::pair<double, double> fresnel_sp_angles(double theta_i, double eta)
{
    const double theta_t = std::asin(std::sin(theta_i) / eta);
    const double rs = std::sin(theta_i - theta_t) / std::sin(theta_i + theta_t);
    const double rp = std::tan(theta_i - theta_t) / std::tan(theta_i + theta_t);
    return {rs * rs, rp * rp};
}

inline double schlick(double c, double f0) { return f0 + (1.0 - f0) * std::pow(1.0 - c, 5.0); }

/// A pane: the geometric series R + T^2 R + T^2 R^3 + ... summed term by term (`terms` terms).
inline double slab_series(double r, int terms)
{
    double sum = r, t2 = (1.0 - r) * (1.0 - r), p = r;
    for (int i = 1; i < terms; ++i) {
        sum += t2 * p;
        p *= r * r;
    }
    return sum;
}

/// N panes (2N surfaces of reflectance r) stacked by the adding rule for incoherent layers:
/// R_ab = R_a + T_a^2 R_b / (1 - R_a R_b), T_ab = T_a T_b / (1 - R_a R_b).
inline double stack_surfaces(double r, int surfaces)
{
    double R = 0.0, T = 1.0;
    for (int i = 0; i < surfaces; ++i) {
        const double d = 1.0 - R * r;
        if (d <= 0.0) {  // two perfect mirrors: everything is reflected
            R = 1.0;
            T = 0.0;
            continue;
        }
        const double nr = R + T * T * r / d;
        T = T * (1.0 - r) / d;
        R = nr;
    }
    return R;
}

}  // namespace ref
