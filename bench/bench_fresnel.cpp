// raykit — bench_fresnel.cpp: speed AND accuracy of every function in shaders/raykit/fresnel.glsl
// (CPU build), for docs/benchmarks.md (scripts/bench.sh runs raykit_bench and scripts/bench_report.py).
//
// Suite "fresnel": every benchmark is named BM_fresnel/<variant>/<parameters>; the counters, the
// label and the registration machinery are described in bench_common.hpp. Errors are taken against
// the float64 references of tests/reference/fresnel_ref.hpp over a dense sweep of kSweep inputs;
// worst_at is the swept input (cos, eta, R...) where max_abs_err occurs.
//
// Approximations (Schlick, the fast dielectric, LUTs, the thesis's pane model) are measured against
// the EXACT quantity they stand in for, which is the speed-vs-error trade-off the report plots.
// CPU timings are only meaningful as ratios between variants; GPU costs differ (e.g. a LUT is a
// texture fetch there, and sqrt/div/asin have different relative costs).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "raykit/fresnel.hpp"
#include "reference/fresnel_ref.hpp"

namespace rkbench {
namespace {

using raykit::vec2;
using raykit::vec3;

// Gold's complex index per RGB channel (as quoted in fresnel.glsl).
const vec3 kGoldN(0.143f, 0.374f, 1.442f);
const vec3 kGoldK(3.983f, 2.385f, 1.603f);

double stack(double r, int surfaces) { return ref::stack_surfaces(r, surfaces); }

std::string eta_tag(float eta)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "eta:%.2f", static_cast<double>(eta));
    return buf;
}

// ---------------------------------------------------------------------------------------------
// Dielectric reflectance for one eta: the exact functions and everything that approximates them.

void register_reflectance(float eta)
{
    using namespace raykit;
    const std::string fam = "reflectance_" + eta_tag(eta);
    const std::string tag = eta_tag(eta);
    char title[160];
    std::snprintf(title, sizeof title,
                  "Dielectric reflectance, external (eta = %.2f): exact forms and their approximations, "
                  "errors against the exact unpolarised float64 reflectance",
                  static_cast<double>(eta));
    add_family(fam, title);
    const double e = d(eta);
    const std::string vs_exact = "exact unpolarised dielectric (ref::fresnel)";
    auto exact = [e](float c) { return ref::fresnel(d(c), e); };
    auto random_cos = [](Rng& r, std::size_t) { return r.uniform(0.0f, 1.0f); };

    struct CosEta {
        float c, eta;
    };
    auto cos_eta = [eta](Rng& r, std::size_t) { return CosEta{r.uniform(0.0f, 1.0f), eta}; };

    // Schlick with F0 from eta (the per-material constant), scalar and with f90 = 1.
    {
        const float f0 = rk_f0_from_eta(eta);
        struct In {
            float c, f0;
        };
        add_bench({"schlick", tag, fam, "rk_fresnel_schlick(cos, f0)", vs_exact},
                  sweep(0, 1, [&](float c, Accuracy& a) { a.add(d(rk_fresnel_schlick(c, f0)), exact(c), d(c)); }),
                  make_inputs<In>([f0](Rng& r, std::size_t) { return In{r.uniform(0.0f, 1.0f), f0}; }),
                  [](const In& x) { return rk_fresnel_schlick(x.c, x.f0); });
        struct In90 {
            float c, f0, f90;
        };
        add_bench({"schlick_f90", tag, fam, "rk_fresnel_schlick(cos, f0, f90 = 1)", vs_exact},
                  sweep(0, 1, [&](float c, Accuracy& a) { a.add(d(rk_fresnel_schlick(c, f0, 1.0f)), exact(c), d(c)); }),
                  make_inputs<In90>([f0](Rng& r, std::size_t) { return In90{r.uniform(0.0f, 1.0f), f0, 1.0f}; }),
                  [](const In90& x) { return rk_fresnel_schlick(x.c, x.f0, x.f90); });
    }
    // The fast dielectric: precomputed params, and params built per call from eta.
    {
        const vec3 p = rk_fresnel_fast_params(eta);
        struct In {
            float c;
            vec3 p;
        };
        const Accuracy acc =
            sweep(0, 1, [&](float c, Accuracy& a) { a.add(d(rk_fresnel_dielectric_fast(c, p)), exact(c), d(c)); });
        add_bench({"fast", tag, fam, "rk_fresnel_dielectric_fast(cos, params)", vs_exact}, acc,
                  make_inputs<In>([p](Rng& r, std::size_t) { return In{r.uniform(0.0f, 1.0f), p}; }),
                  [](const In& x) { return rk_fresnel_dielectric_fast(x.c, x.p); });
        const Accuracy acc_eta =
            sweep(0, 1, [&](float c, Accuracy& a) { a.add(d(rk_fresnel_dielectric_fast(c, eta)), exact(c), d(c)); });
        add_bench({"fast_eta", tag, fam, "rk_fresnel_dielectric_fast(cos, eta)", vs_exact}, acc_eta,
                  make_inputs<CosEta>(cos_eta), [](const CosEta& x) { return rk_fresnel_dielectric_fast(x.c, x.eta); });
    }
    // The per-material polynomial (constants fitted on the CPU, loaded per call like the others).
    {
        const raykit::FresnelPolyParams pp = raykit::rk_fresnel_poly_params(eta);
        struct In {
            float c;
            vec4 p0;
            vec2 p1;
        };
        add_bench({"poly", tag, fam, "rk_fresnel_dielectric_poly(cos, p0, p1)", vs_exact},
                  sweep(0, 1, [&](float c, Accuracy& a) { a.add(d(rk_fresnel_dielectric_poly(c, pp.p0, pp.p1)), exact(c), d(c)); }),
                  make_inputs<In>([pp](Rng& r, std::size_t) { return In{r.uniform(0.0f, 1.0f), pp.p0, pp.p1}; }),
                  [](const In& x) { return rk_fresnel_dielectric_poly(x.c, x.p0, x.p1); });
    }
    // The exact forms.
    add_bench({"dielectric", tag, fam, "rk_fresnel_dielectric(cos, eta)", vs_exact},
              sweep(0, 1, [&](float c, Accuracy& a) { a.add_ulp(rk_fresnel_dielectric(c, eta), exact(c), d(c)); }),
              make_inputs<CosEta>(cos_eta), [](const CosEta& x) { return rk_fresnel_dielectric(x.c, x.eta); });
    add_bench({"dielectric_sp", tag, fam, "rk_fresnel_dielectric_sp(cos, eta)", "exact Rs and Rp (ref::fresnel_sp), worse of the two"},
              sweep(0, 1,
                    [&](float c, Accuracy& a) {
                        const vec2 r = rk_fresnel_dielectric_sp(c, eta);
                        const auto x = ref::fresnel_sp(d(c), ref::cd(e, 0.0));
                        a.add(d(r.x), x.first, d(c));
                        a.add(d(r.y), x.second, d(c));
                    }),
              make_inputs<CosEta>(cos_eta), [](const CosEta& x) { return rk_fresnel_dielectric_sp(x.c, x.eta); });
    // The conductor form with k = 0 computes the same reflectance (3 sqrt instead of 1).
    {
        struct In {
            float c, n, k;
        };
        add_bench({"conductor_k0", tag, fam, "rk_fresnel_conductor(cos, eta, k = 0)", vs_exact},
                  sweep(0, 1, [&](float c, Accuracy& a) { a.add_ulp(rk_fresnel_conductor(c, eta, 0.0f), exact(c), d(c)); }),
                  make_inputs<In>([eta](Rng& r, std::size_t) { return In{r.uniform(0.0f, 1.0f), eta, 0.0f}; }),
                  [](const In& x) { return rk_fresnel_conductor(x.c, x.n, x.k); });
    }
    // Baked 1-D LUTs of the single-surface reflectance, sampled as GL_LINEAR would.
    for (int size : {64, 256}) {
        const std::vector<float> lut = raykit::bake_fresnel_lut_1d(size, eta, raykit::FresnelLutMode::single_surface);
        add_bench({"lut" + std::to_string(size), tag, fam,
                   "sample_fresnel_lut_1d(lut" + std::to_string(size) + ", cos) [single_surface]", vs_exact},
                  sweep(0, 1, [&](float c, Accuracy& a) { a.add(d(raykit::sample_fresnel_lut_1d(lut, c)), exact(c), d(c)); }),
                  make_inputs<float>(random_cos), [lut](float c) { return raykit::sample_fresnel_lut_1d(lut, c); });
    }
}

// ---------------------------------------------------------------------------------------------
// Internal reflection (glass -> air): the exact forms with their total-internal-reflection branch.

void register_internal()
{
    using namespace raykit;
    const float eta = 1.0f / 1.52f;
    const double e = d(eta);
    const std::string fam = "internal";
    const std::string tag = "eta:0.66";
    add_family(fam,
               "Dielectric reflectance, internal (glass -> air, eta = 1/1.52): exact forms; random cos takes the "
               "total-internal-reflection branch 75% of the time (branch mispredictions on a CPU, divergence on a "
               "GPU); the error peaks at the critical angle, where R has infinite slope");
    struct In {
        float c, eta;
    };
    auto inputs = make_inputs<In>([eta](Rng& r, std::size_t) { return In{r.uniform(0.0f, 1.0f), eta}; });
    add_bench({"dielectric", tag, fam, "rk_fresnel_dielectric(cos, eta)", "exact unpolarised dielectric (ref::fresnel)"},
              sweep(0, 1, [&](float c, Accuracy& a) { a.add_ulp(rk_fresnel_dielectric(c, eta), ref::fresnel(d(c), e), d(c)); }),
              inputs, [](const In& x) { return rk_fresnel_dielectric(x.c, x.eta); });
    add_bench({"dielectric_sp", tag, fam, "rk_fresnel_dielectric_sp(cos, eta)", "exact Rs and Rp (ref::fresnel_sp), worse of the two"},
              sweep(0, 1,
                    [&](float c, Accuracy& a) {
                        const vec2 r = rk_fresnel_dielectric_sp(c, eta);
                        const auto x = ref::fresnel_sp(d(c), ref::cd(e, 0.0));
                        a.add(d(r.x), x.first, d(c));
                        a.add(d(r.y), x.second, d(c));
                    }),
              inputs, [](const In& x) { return rk_fresnel_dielectric_sp(x.c, x.eta); });
}

// ---------------------------------------------------------------------------------------------
// Conductors (gold): the exact complex-index form and Schlick with gold's F0.

void register_conductor()
{
    using namespace raykit;
    const std::string fam = "conductor";
    const std::string tag = "metal:gold";
    add_family(fam,
               "Conductor reflectance, gold (n + ik per RGB channel): exact form and Schlick with gold's F0, errors "
               "against the exact float64 conductor reflectance, worst channel");
    const std::string vs = "exact conductor per channel (ref::conductor)";
    auto exact = [](float c, int ch) { return ref::conductor(d(c), d(kGoldN[ch]), d(kGoldK[ch])); };
    vec3 f0;
    for (int ch = 0; ch < 3; ++ch) f0[ch] = static_cast<float>(ref::conductor(1.0, d(kGoldN[ch]), d(kGoldK[ch])));

    struct InNK {
        float c;
        vec3 n, k;
    };
    add_bench({"conductor_rgb", tag, fam, "rk_fresnel_conductor(cos, vec3 eta, vec3 k)", vs},
              sweep(0, 1,
                    [&](float c, Accuracy& a) {
                        const vec3 r = rk_fresnel_conductor(c, kGoldN, kGoldK);
                        for (int ch = 0; ch < 3; ++ch) a.add_ulp(r[ch], exact(c, ch), d(c));
                    }),
              make_inputs<InNK>([](Rng& r, std::size_t) { return InNK{r.uniform(0.0f, 1.0f), kGoldN, kGoldK}; }),
              [](const InNK& x) { return rk_fresnel_conductor(x.c, x.n, x.k); });
    struct In1 {
        float c, n, k;
    };
    add_bench({"conductor", tag, fam, "rk_fresnel_conductor(cos, float eta, float k)", vs},
              sweep(0, 1,
                    [&](float c, Accuracy& a) {
                        for (int ch = 0; ch < 3; ++ch) a.add_ulp(rk_fresnel_conductor(c, kGoldN[ch], kGoldK[ch]), exact(c, ch), d(c));
                    }),
              make_inputs<In1>([](Rng& r, std::size_t i) {
                  const int ch = static_cast<int>(i % 3);
                  return In1{r.uniform(0.0f, 1.0f), kGoldN[ch], kGoldK[ch]};
              }),
              [](const In1& x) { return rk_fresnel_conductor(x.c, x.n, x.k); });
    struct InRgb {
        float c;
        vec3 f0;
    };
    add_bench({"schlick_rgb", tag, fam, "rk_fresnel_schlick(cos, vec3 f0)", vs},
              sweep(0, 1,
                    [&](float c, Accuracy& a) {
                        const vec3 r = rk_fresnel_schlick(c, f0);
                        for (int ch = 0; ch < 3; ++ch) a.add(d(r[ch]), exact(c, ch), d(c));
                    }),
              make_inputs<InRgb>([f0](Rng& r, std::size_t) { return InRgb{r.uniform(0.0f, 1.0f), f0}; }),
              [](const InRgb& x) { return rk_fresnel_schlick(x.c, x.f0); });
    struct InRgb90 {
        float c;
        vec3 f0, f90;
    };
    add_bench({"schlick_rgb_f90", tag, fam, "rk_fresnel_schlick(cos, vec3 f0, vec3 f90 = 1)", vs},
              sweep(0, 1,
                    [&](float c, Accuracy& a) {
                        const vec3 r = rk_fresnel_schlick(c, f0, vec3(1.0f));
                        for (int ch = 0; ch < 3; ++ch) a.add(d(r[ch]), exact(c, ch), d(c));
                    }),
              make_inputs<InRgb90>([f0](Rng& r, std::size_t) { return InRgb90{r.uniform(0.0f, 1.0f), f0, vec3(1.0f)}; }),
              [](const InRgb90& x) { return rk_fresnel_schlick(x.c, x.f0, x.f90); });
}

// ---------------------------------------------------------------------------------------------
// Window panes: slab / glazing from a reflectance, the window models end to end, and pane LUTs.

void register_panes()
{
    using namespace raykit;
    const float eta = 1.52f;
    const double e = d(eta);
    const std::string fam = "pane";
    add_family(fam,
               "Window panes (non-absorbing, incoherent multiple reflections): errors against float64 stacking of "
               "layers (ref::stack_surfaces) on float64 Rs, Rp, except the R-to-pane helpers, whose float inputs "
               "are exact by definition");
    // Exact pane reflectance at cos, summed per polarisation, with `panes` panes.
    auto exact_pane = [e](float c, int panes) {
        const auto sp = ref::fresnel_sp(d(c), ref::cd(e, 0.0));
        return 0.5 * (stack(sp.first, 2 * panes) + stack(sp.second, 2 * panes));
    };
    const std::string vs_pane = "exact pane per polarisation (ref::fresnel_sp + ref::stack_surfaces)";

    add_bench({"slab", "R:0..1", fam, "rk_fresnel_slab(R)", "ref::stack_surfaces(R, 2)"},
              sweep(0, 1, [&](float r, Accuracy& a) { a.add_ulp(rk_fresnel_slab(r), stack(d(r), 2), d(r)); }),
              make_inputs<float>([](Rng& r, std::size_t) { return r.uniform(0.0f, 1.0f); }),
              [](float r) { return rk_fresnel_slab(r); });
    add_bench({"slab_sp", eta_tag(eta), fam, "rk_fresnel_slab_sp(vec2 rsp)", "ref::stack_surfaces per polarisation of the same float Rs, Rp"},
              sweep(0, 1,
                    [&](float c, Accuracy& a) {
                        const vec2 sp = rk_fresnel_dielectric_sp(c, eta);
                        a.add_ulp(rk_fresnel_slab_sp(sp),
                                  0.5 * (stack(d(sp.x), 2) + stack(d(sp.y), 2)), d(c));
                    }),
              make_inputs<vec2>([eta](Rng& r, std::size_t) { return rk_fresnel_dielectric_sp(r.uniform(0.0f, 1.0f), eta); }),
              [](const vec2& sp) { return rk_fresnel_slab_sp(sp); });
    struct InRP {
        float r, panes;
    };
    add_bench({"glazing", "R:0..1/panes:2", fam, "rk_fresnel_glazing(R, panes)", "ref::stack_surfaces(R, 2 panes)"},
              sweep(0, 1, [&](float r, Accuracy& a) { a.add_ulp(rk_fresnel_glazing(r, 2.0f), stack(d(r), 4), d(r)); }),
              make_inputs<InRP>([](Rng& r, std::size_t) { return InRP{r.uniform(0.0f, 1.0f), 2.0f}; }),
              [](const InRP& x) { return rk_fresnel_glazing(x.r, x.panes); });
    struct InSpP {
        vec2 sp;
        float panes;
    };
    add_bench({"glazing_sp", eta_tag(eta) + "/panes:2", fam, "rk_fresnel_glazing_sp(vec2 rsp, panes)",
               "ref::stack_surfaces per polarisation of the same float Rs, Rp"},
              sweep(0, 1,
                    [&](float c, Accuracy& a) {
                        const vec2 sp = rk_fresnel_dielectric_sp(c, eta);
                        a.add_ulp(rk_fresnel_glazing_sp(sp, 2.0f),
                                  0.5 * (stack(d(sp.x), 4) + stack(d(sp.y), 4)), d(c));
                    }),
              make_inputs<InSpP>([eta](Rng& r, std::size_t) {
                  return InSpP{rk_fresnel_dielectric_sp(r.uniform(0.0f, 1.0f), eta), 2.0f};
              }),
              [](const InSpP& x) { return rk_fresnel_glazing_sp(x.sp, x.panes); });

    // The window models from cos: the default (RK_FRESNEL_WINDOW_MODE 2, per polarisation) and the
    // thesis's slab of the average (mode 1), an approximation of the former.
    struct In {
        float c, eta, panes;
    };
    auto window_inputs = make_inputs<In>([eta](Rng& r, std::size_t) { return In{r.uniform(0.0f, 1.0f), eta, 1.0f}; });
    add_bench({"window", eta_tag(eta), fam, "rk_fresnel_window(cos, eta, 1) [RK_FRESNEL_WINDOW_MODE 2]", vs_pane},
              sweep(0, 1, [&](float c, Accuracy& a) { a.add_ulp(rk_fresnel_window(c, eta, 1.0f), exact_pane(c, 1), d(c)); }),
              window_inputs, [](const In& x) { return rk_fresnel_window(x.c, x.eta, x.panes); });
    add_bench({"window_thesis", eta_tag(eta), fam, "rk_fresnel_slab(rk_fresnel_dielectric(cos, eta)) [mode 1, thesis Eq. 3.8]",
               vs_pane},
              sweep(0, 1,
                    [&](float c, Accuracy& a) { a.add(d(rk_fresnel_slab(rk_fresnel_dielectric(c, eta))), exact_pane(c, 1), d(c)); }),
              window_inputs, [](const In& x) { return rk_fresnel_slab(rk_fresnel_dielectric(x.c, x.eta)); });
    for (int size : {64, 256}) {
        const std::vector<float> lut = raykit::bake_fresnel_lut_1d(size, eta, raykit::FresnelLutMode::slab_polarised);
        add_bench({"window_lut" + std::to_string(size), eta_tag(eta), fam,
                   "sample_fresnel_lut_1d(lut" + std::to_string(size) + ", cos) [slab_polarised]", vs_pane},
                  sweep(0, 1, [&](float c, Accuracy& a) { a.add(d(raykit::sample_fresnel_lut_1d(lut, c)), exact_pane(c, 1), d(c)); }),
                  make_inputs<float>([](Rng& r, std::size_t) { return r.uniform(0.0f, 1.0f); }),
                  [lut](float c) { return raykit::sample_fresnel_lut_1d(lut, c); });
    }
}

// ---------------------------------------------------------------------------------------------
// Helpers: index/F0 conversions, special angles, refraction.

void register_helpers()
{
    using namespace raykit;
    const std::string fam = "helpers";
    add_family(fam, "Helpers: F0/index conversions, special angles, refraction; errors against the same formula in float64");

    auto eta_inputs = [](float lo, float hi) {
        return make_inputs<float>([lo, hi](Rng& r, std::size_t) { return r.uniform(lo, hi); });
    };
    add_bench({"clamp_eta", "eta:0.25..4", fam, "rk_fresnel_clamp_eta(eta) [~ loop overhead]", "the input (exact)"},
              sweep(0.25, 4, [&](float x, Accuracy& a) { a.add_ulp(rk_fresnel_clamp_eta(x), d(x), d(x)); }), eta_inputs(0.25f, 4.0f),
              [](float x) { return rk_fresnel_clamp_eta(x); });
    add_bench({"f0_from_eta", "eta:0.25..4", fam, "rk_f0_from_eta(eta)", "((eta - 1) / (eta + 1))^2"},
              sweep(0.25, 4,
                    [&](float x, Accuracy& a) {
                        const double q = (d(x) - 1.0) / (d(x) + 1.0);
                        a.add_ulp(rk_f0_from_eta(x), q * q, d(x));
                    }),
              eta_inputs(0.25f, 4.0f), [](float x) { return rk_f0_from_eta(x); });
    struct Ior {
        float n1, n2;
    };
    add_bench({"f0_from_ior", "n1:1.33/n2:1..4", fam, "rk_f0_from_ior(n1, n2)", "((n1 - n2) / (n1 + n2))^2"},
              sweep(1, 4,
                    [&](float x, Accuracy& a) {
                        const double q = (d(1.33f) - d(x)) / (d(1.33f) + d(x));
                        a.add_ulp(rk_f0_from_ior(1.33f, x), q * q, d(x));
                    }),
              make_inputs<Ior>([](Rng& r, std::size_t) { return Ior{1.33f, r.uniform(1.0f, 4.0f)}; }),
              [](const Ior& x) { return rk_f0_from_ior(x.n1, x.n2); });
    add_bench({"eta_from_f0", "f0:0..0.5", fam, "rk_eta_from_f0(f0)", "(1 + sqrt(f0)) / (1 - sqrt(f0))"},
              sweep(0, 0.5,
                    [&](float x, Accuracy& a) {
                        const double s = std::sqrt(d(x));
                        a.add_ulp(rk_eta_from_f0(x), (1.0 + s) / (1.0 - s), d(x));
                    }),
              eta_inputs(0.0f, 0.5f), [](float x) { return rk_eta_from_f0(x); });
    add_bench({"fast_params", "eta:1..4", fam, "rk_fresnel_fast_params(eta)", "(eta^2, g0 = sqrt(eta^2 - 1), eta - g0), worst component"},
              sweep(1, 4,
                    [&](float x, Accuracy& a) {
                        const vec3 p = rk_fresnel_fast_params(x);
                        const double g0 = std::sqrt(d(x) * d(x) - 1.0);
                        a.add_ulp(p.x, d(x) * d(x), d(x));
                        a.add_ulp(p.y, g0, d(x));
                        a.add_ulp(p.z, d(x) - g0, d(x));
                    }),
              eta_inputs(1.0f, 4.0f), [](float x) { return rk_fresnel_fast_params(x); });
    add_bench({"critical_cos", "eta:0..1", fam, "rk_critical_cos(eta)", "sqrt(1 - eta^2)"},
              sweep(0, 1, [&](float x, Accuracy& a) { a.add_ulp(rk_critical_cos(x), std::sqrt(1.0 - d(x) * d(x)), d(x)); }),
              eta_inputs(0.0f, 1.0f), [](float x) { return rk_critical_cos(x); });
    add_bench({"critical_angle", "eta:0..1", fam, "rk_critical_angle(eta)", "std::asin (float64), radians"},
              sweep(0, 1, [&](float x, Accuracy& a) { a.add_ulp(rk_critical_angle(x), std::asin(d(x)), d(x)); }),
              eta_inputs(0.0f, 1.0f), [](float x) { return rk_critical_angle(x); });
    add_bench({"brewster_angle", "eta:0.25..4", fam, "rk_brewster_angle(eta)", "std::atan (float64), radians"},
              sweep(0.25, 4, [&](float x, Accuracy& a) { a.add_ulp(rk_brewster_angle(x), std::atan(d(x)), d(x)); }),
              eta_inputs(0.25f, 4.0f), [](float x) { return rk_brewster_angle(x); });

    // Refraction: incident directions over the whole hemisphere of cos in the sweep, normal +z.
    const float eta = 1.52f;
    struct Refr {
        vec3 i, n;
        float eta;
    };
    struct RefrOut {
        vec3 t;
        bool ok;
    };
    add_bench({"refract", eta_tag(eta), fam, "rk_refract(incident, normal, eta, out t)",
               "Snell's law in float64 (t = i/eta + (cos_i/eta - cos_t) n), worst component"},
              sweep(0, 1,
                    [&](float c, Accuracy& a) {
                        const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
                        const vec3 i(s, 0.0f, -c), n(0.0f, 0.0f, 1.0f);
                        vec3 t;
                        rk_refract(i, n, eta, t);
                        const double ci = -d(i.z), ed = d(eta);
                        const double ct = std::sqrt(1.0 - (1.0 - ci * ci) / (ed * ed));
                        const double tx = d(i.x) / ed, tz = d(i.z) / ed + (ci / ed - ct);
                        a.add(d(t.x), tx, d(c));
                        a.add(d(t.y), 0.0, d(c));
                        a.add(d(t.z), tz, d(c));
                    }),
              make_inputs<Refr>([eta](Rng& r, std::size_t) {
                  const vec3 n = r.unit_vector();
                  vec3 i = r.unit_vector();
                  if (glm::dot(i, n) > 0.0f) i = -i;
                  return Refr{i, n, eta};
              }),
              [](const Refr& x) {
                  RefrOut o{};
                  o.ok = rk_refract(x.i, x.n, x.eta, o.t);
                  return o;
              });
}


void register_all()
{
    register_reflectance(1.52f);
    register_reflectance(1.33f);
    register_internal();
    register_conductor();
    register_panes();
    register_helpers();
}

const SuiteRegistrar registrar(
    {"fresnel", 10, "Fresnel: shaders/raykit/fresnel.glsl", "bench/bench_fresnel.cpp", "call",
     "BM_fresnel/schlick/eta:1.52",
     {"reflectance_eta:1.52", "reflectance_eta:1.33", "pane", "conductor"},
     "- **ns/call**: each call's arguments, material constants included, are loaded per call from the "
     "pre-generated array, so nothing per-material is hoisted out of the loop.\n"
     "- **max / mean abs err**: against float64 references (`tests/reference/fresnel_ref.hpp`, or the "
     "formula named in the last column) over a dense sweep of the input range. Approximations (Schlick, "
     "the fast dielectric, LUTs, the thesis's pane model) are measured against the *exact* quantity they "
     "stand in for.\n"
     "- **worst at**: the swept input (cos, eta, R or F0, see the parameters in the name) where the max "
     "abs error occurs.\n"
     "- **The 1.3x goal on a CPU.** Schlick, the fast dielectric and the polynomial each take 4 to 6 cycles "
     "per call here, and the compiled clamps are branches, so where the timed loop lands in memory moves "
     "them by a cycle: a build with 32-byte loop alignment (`-falign-loops=32` in bench/CMakeLists.txt) timed "
     "the two identical Schlick rows at 1.63 and 1.36 ns/call and put the fast dielectric at 1.45x and 1.81x, "
     "the polynomial at 1.69x. The verdicts above hold for this build only. GPU instruction counts, which "
     "do not move: Schlick 5 (1 add, 3 mul, 1 multiply-add), the polynomial 6 (1 add, 5 multiply-adds), the "
     "fast dielectric about 16 plus a division.",
     "On a GPU, `sqrt`, division and `asin`/`atan` have different relative costs, a LUT is a texture fetch "
     "through the texture unit rather than two loads and a lerp, and the total-internal-reflection branch "
     "costs divergence rather than mispredictions. The error columns, on the other hand, carry over (same "
     "source, IEEE float32), up to the driver's `sqrt`/division/`asin` precision.",
     "BM_fresnel/poly/eta:1.52|0.005|1.3|the per-material polynomial, glass;"
     "BM_fresnel/fast/eta:1.52|0.005|1.3|the fast dielectric, glass;"
     "BM_fresnel/poly/eta:1.33|0.005|1.3|the per-material polynomial, water;"
     "BM_fresnel/fast/eta:1.33|0.005|1.3|the fast dielectric, water"},
    &register_all);

}  // namespace
}  // namespace rkbench
