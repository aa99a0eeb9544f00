// raykit — bench_tonemap.cpp: speed AND accuracy of the tone-mapping operators of
// shaders/raykit/tonemap.glsl and the colour helpers of color.glsl (CPU builds), for
// docs/benchmarks.md (scripts/bench.sh runs raykit_bench and scripts/bench_report.py).
//
// Suite "tonemap", one family "tonemap": every benchmark is BM_tonemap/<variant>/<parameters>; the
// counters, label and registration are described in bench_common.hpp.
//   - Speed: one RGB pixel per call over kInputs pre-generated pixels (hdr_pixel below: peak channel
//     log-uniform in [1e-3, 1e4], a quarter of them saturated primaries or secondaries). The sRGB
//     transfer functions take display values in [0, 1] instead (their domain: HDR input would
//     clamp most channels to 1), and the PBR Neutral inverse takes rk_pbr_neutral's outputs.
//   - Error: worst channel, against the float64 evaluation of each operator's OWN published
//     formula (tests/reference/tonemap_ref.hpp) at the same float input, over a grey ramp of kSweep
//     points log-spaced over [1e-3, 1e4] and kSweep pixels drawn like the timing inputs.
//   - The ACES fits are ALSO compared with the transform they fit, the ACES 1.0 RRT + sRGB 100-nit
//     ODT in float64 (ref::aces_rrt_odt_srgb, written from the Academy's CTL; tests/test_tonemap.cpp
//     checks it against published values): rows "<fit>_vs_aces", flagged "cross", on the grey ramp and
//     on the colours separately, Narkowicz at the 0.6 input scale his post suggests and at 0.5, where
//     it matches best. The older rows comparing Narkowicz with Hill's fit (ref::aces_hill) are kept.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "raykit/tonemap.hpp"
#include "reference/tonemap_ref.hpp"

namespace rkbench {
namespace {

using raykit::vec3;

constexpr double kHdrLo = 1e-3, kHdrHi = 1e4;  // range of the peak channel (grey ramp: of all three)
const char* const kFam = "tonemap";

// ---------------------------------------------------------------------------------------------
// Inputs.

/// An HDR pixel: peak channel log-uniform in [kHdrLo, kHdrHi]; 6 in 8 mildly coloured (the other
/// channels 0.1..1 x the peak, log-uniform), 1 in 8 a saturated primary and 1 in 8 a saturated
/// secondary (the remaining channels 0..1% of the peak).
vec3 hdr_pixel(Rng& r, std::size_t i)
{
    const float peak = std::pow(10.0f, r.uniform(static_cast<float>(std::log10(kHdrLo)), static_cast<float>(std::log10(kHdrHi))));
    const int k = r.index(3);  // the peak channel
    vec3 c;
    for (int ch = 0; ch < 3; ++ch) {  // one statement per draw: argument evaluation order is unspecified
        switch (i % 8) {
        case 0: c[ch] = peak * r.uniform(0.0f, 0.01f); break;                  // primary
        case 1: c[ch] = ch == k ? peak * r.uniform(0.0f, 0.01f) : peak; break;  // secondary
        default: c[ch] = peak * std::pow(10.0f, r.uniform(-1.0f, 0.0f)); break;
        }
    }
    if (i % 8 != 1) c[k] = peak;
    return c;
}

vec3 display_pixel(Rng& r, std::size_t)
{
    const float x = r.uniform(0.0f, 1.0f);
    const float y = r.uniform(0.0f, 1.0f);
    const float z = r.uniform(0.0f, 1.0f);
    return vec3(x, y, z);
}

using Set = std::vector<vec3>;

/// Accuracy inputs: the grey ramp, and colours drawn like the timing inputs (other seed).
const Set& grey_ramp()
{
    static const Set s = [] {
        Set v;
        for (int i = 0; i < kSweep; ++i) v.push_back(vec3(log_sweep_point(i, kHdrLo, kHdrHi)));
        return v;
    }();
    return s;
}
const Set& hdr_colours()
{
    static const Set s = [] {
        Rng rng(7u);
        Set v;
        for (int i = 0; i < kSweep; ++i) v.push_back(hdr_pixel(rng, static_cast<std::size_t>(i)));
        return v;
    }();
    return s;
}
/// Display-referred inputs (sRGB): a grey ramp over [0, 1] and random pixels in [0, 1]^3.
const Set& display_values()
{
    static const Set s = [] {
        Rng rng(11u);
        Set v;
        for (int i = 0; i < kSweep; ++i) v.push_back(vec3(sweep_point(i, 0.0, 1.0)));
        for (int i = 0; i < kSweep; ++i) v.push_back(display_pixel(rng, 0));
        return v;
    }();
    return s;
}

// ---------------------------------------------------------------------------------------------
// Float64 references.

ref::d3 d3of(const vec3& v) { return {d(v.x), d(v.y), d(v.z)}; }

ref::d3 per_channel(double (*f)(double), const ref::d3& c) { return {f(c[0]), f(c[1]), f(c[2])}; }

/// Reinhard on BT.709 luminance with the colour ratio kept, clamped (white <= 0: simple, Eq. 3.16).
ref::d3 reinhard_rgb(const ref::d3& c, double white)
{
    const double l = ref::luminance709(c);
    const double ld = white > 0.0 ? ref::reinhard_ext(l, white) : ref::reinhard(l);
    const double s = ld / std::max(l, 1e-300);
    return ref::clamp01({c[0] * s, c[1] * s, c[2] * s});
}

/// The analytic inverse of the Khronos PBR Neutral forward formula (ref::pbr_neutral), in float64,
/// with rk_pbr_neutral_inverse's documented domain handling (input clamped to [0, 1 - 2^-20],
/// colours outside the forward map's image clamped to the grey axis' foot). tests/reference/ has
/// no inverse; this one is checked against ref::pbr_neutral at start-up (check_pbr_inverse).
ref::d3 pbr_neutral_inverse(ref::d3 c)
{
    const double start = 0.8 - 0.04, desat = 0.15, dd = 1.0 - start;
    for (double& v : c) v = std::min(std::max(v, 0.0), 1.0 - 9.5367431640625e-7);
    const double new_peak = std::max({c[0], c[1], c[2]});
    if (new_peak >= start) {
        const double peak = dd * dd / (1.0 - new_peak) - dd + start;
        const double g = 1.0 - 1.0 / (desat * (peak - new_peak) + 1.0);
        for (double& v : c) v = std::max(v - g * new_peak, 0.0) / (1.0 - g) * (peak / new_peak);
    }
    const double y = std::max(std::min({c[0], c[1], c[2]}), 0.0);
    const double x = y < 0.04 ? 0.4 * std::sqrt(y) : y + 0.04;
    for (double& v : c) v += x - y;
    return c;
}

// ---------------------------------------------------------------------------------------------
// Error sweeps.

/// Worst-channel absolute error of f (vec3 -> vec3) against `reference` (d3 -> d3) over `sets`.
template <class F, class R>
Accuracy rgb_error(const std::vector<const Set*>& sets, F f, R reference)
{
    Accuracy acc;
    for (const Set* set : sets) {
        for (const vec3& c : *set) {
            const vec3 got = f(c);
            const ref::d3 want = reference(d3of(c));
            for (int k = 0; k < 3; ++k) acc.add(d(got[k]), want[static_cast<std::size_t>(k)], c);
        }
    }
    return acc;
}

/// As rgb_error, also tracking ulps (exact functions whose results stay away from zero).
template <class F, class R>
Accuracy rgb_error_ulp(const std::vector<const Set*>& sets, F f, R reference)
{
    Accuracy acc;
    for (const Set* set : sets) {
        for (const vec3& c : *set) {
            const vec3 got = f(c);
            const ref::d3 want = reference(d3of(c));
            for (int k = 0; k < 3; ++k) {
                acc.add(d(got[k]), want[static_cast<std::size_t>(k)], c);
                acc.note_ulp(got[k], want[static_cast<std::size_t>(k)]);
            }
        }
    }
    return acc;
}

const std::vector<const Set*>& hdr_sets()
{
    static const std::vector<const Set*> s{&grey_ramp(), &hdr_colours()};
    return s;
}

std::vector<vec3> hdr_inputs() { return make_inputs<vec3>(hdr_pixel); }

// ---------------------------------------------------------------------------------------------
// Registration.

void register_operators()
{
    using namespace raykit;
    add_family(kFam,
               "Tone-mapping operators: CPU time per RGB pixel, error vs float64 of each published formula "
               "(tests/reference/tonemap_ref.hpp), worst channel, display-linear output; relative cost vs the "
               "clamp (no tone mapping). Rows marked vs ACES measure the two ACES fits against the ACES 1.0 RRT + sRGB "
               "100-nit ODT itself (float64, from the Academy's CTL); rows marked vs Hill measure Narkowicz's fit "
               "against Hill's fit");
    const std::string hdr = "hdr";

    // Baseline: RK_TONEMAP_OPERATOR 0, what a pixel costs without tone mapping.
    add_bench({"clamp", hdr, kFam, "clamp(rk_hdr_sanitize(rgb), 0, 1) [RK_TONEMAP_OPERATOR 0, baseline]",
               "clamp to [0, 1] in float64 (exact)"},
              rgb_error_ulp(hdr_sets(), [](const vec3& c) { return glm::clamp(rk_hdr_sanitize(c), vec3(0.0f), vec3(1.0f)); },
                            [](const ref::d3& c) { return ref::clamp01(c); }),
              hdr_inputs(), [](const vec3& c) { return glm::clamp(rk_hdr_sanitize(c), vec3(0.0f), vec3(1.0f)); });

    // Reinhard on luminance; white loaded per call (a uniform on a GPU).
    struct InW {
        vec3 c;
        float white;
    };
    const std::string vs_reinhard = "Reinhard 2002 on BT.709 luminance (ref::luminance709, ref::reinhard";
    add_bench({"reinhard", "white:max/" + hdr, kFam, "rk_tonemap_reinhard(rgb, RK_HDR_MAX) [simple, Eq. 3.16]",
               vs_reinhard + "), colour ratio kept, clamped"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_tonemap_reinhard(c, RK_HDR_MAX); },
                        [](const ref::d3& c) { return reinhard_rgb(c, 0.0); }),
              make_inputs<InW>([](Rng& r, std::size_t i) { return InW{hdr_pixel(r, i), RK_HDR_MAX}; }),
              [](const InW& x) { return rk_tonemap_reinhard(x.c, x.white); });
    add_bench({"reinhard", "white:4/" + hdr, kFam, "rk_tonemap_reinhard(rgb, 4) [extended, Eq. 3.17, white 4]",
               vs_reinhard + "_ext(L, 4)), colour ratio kept, clamped"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_tonemap_reinhard(c, 4.0f); },
                        [](const ref::d3& c) { return reinhard_rgb(c, 4.0); }),
              make_inputs<InW>([](Rng& r, std::size_t i) { return InW{hdr_pixel(r, i), 4.0f}; }),
              [](const InW& x) { return rk_tonemap_reinhard(x.c, x.white); });

    // ACES fits, each against its own formula.
    add_bench({"aces_narkowicz", hdr, kFam, "rk_aces_narkowicz(rgb)", "Narkowicz 2015 per channel (ref::aces_narkowicz)"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_aces_narkowicz(c); },
                        [](const ref::d3& c) { return per_channel(ref::aces_narkowicz, c); }),
              hdr_inputs(), [](const vec3& c) { return rk_aces_narkowicz(c); });
    add_bench({"aces_hill", hdr, kFam, "rk_aces_hill(rgb)",
               "Hill's fit: BakingLab ACES.hlsl matrices and RRTAndODTFit (ref::aces_hill)"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_aces_hill(c); },
                        [](const ref::d3& c) { return ref::aces_hill(c); }),
              hdr_inputs(), [](const vec3& c) { return rk_aces_hill(c); });

    // Both ACES fits against the transform they approximate: the ACES 1.0 RRT + sRGB ODT in float64.
    {
        const std::string vs_aces =
            "ACES 1.0 RRT + sRGB 100-nit ODT in float64, display-linear (ref::aces_rrt_odt_srgb, from the Academy's CTL)";
        // The reference is costly (glow, red modifier, two splines, xyY round trip): evaluate it once per set.
        struct Cached {
            const Set* set;
            std::vector<ref::d3> want;
        };
        static const std::vector<Cached> cached = [] {
            std::vector<Cached> v;
            for (const Set* set : {&grey_ramp(), &hdr_colours()}) {
                Cached c{set, {}};
                for (const vec3& x : *set) c.want.push_back(ref::aces_rrt_odt_srgb(d3of(x)));
                v.push_back(std::move(c));
            }
            return v;
        }();
        auto error_vs_aces = [](const Cached& c, float scale, bool hill) {
            Accuracy acc;
            for (std::size_t i = 0; i < c.set->size(); ++i) {
                const vec3& x = (*c.set)[i];
                const vec3 got = hill ? rk_aces_hill(x) : rk_aces_narkowicz(scale * x);
                for (int k = 0; k < 3; ++k) acc.add(d(got[k]), c.want[i][static_cast<std::size_t>(k)], x);
            }
            return acc;
        };
        for (const Cached& c : cached) {
            const bool grey = c.set == &grey_ramp();
            const std::string where = grey ? "grey" : "colours";
            const std::string range = grey ? "; grey ramp 1e-3..1e4" : "; HDR colours";
            add_bench({"aces_hill_vs_aces", where, kFam, "rk_aces_hill(rgb) [vs ACES RRT+ODT]", vs_aces + range, "cross"},
                      error_vs_aces(c, 1.0f, true), hdr_inputs(), [](const vec3& x) { return rk_aces_hill(x); });
            add_bench({"aces_narkowicz_vs_aces", "scale:0.6/" + where, kFam,
                       "rk_aces_narkowicz(0.6 * rgb) [vs ACES RRT+ODT, Narkowicz's suggested 0.6 input scale]", vs_aces + range,
                       "cross"},
                      error_vs_aces(c, 0.6f, false), hdr_inputs(), [](const vec3& x) { return rk_aces_narkowicz(0.6f * x); });
            add_bench({"aces_narkowicz_vs_aces", "scale:0.5/" + where, kFam,
                       "rk_aces_narkowicz(0.5 * rgb) [vs ACES RRT+ODT, input scale 0.5: the best match on grey]",
                       vs_aces + range, "cross"},
                      error_vs_aces(c, 0.5f, false), hdr_inputs(), [](const vec3& x) { return rk_aces_narkowicz(0.5f * x); });
        }
    }

    // Narkowicz against Hill's fit (both fits of the same transform; kept from before the ACES reference).
    {
        const std::string vs_hill =
            "Hill's ACES RRT+ODT fit in float64 (ref::aces_hill), itself a fit (the rows vs ACES compare with the "
            "RRT+ODT itself)";
        struct Case {
            const char* params;
            const char* function;
            const Set* set;
            const char* where;
            bool scaled;
        };
        const Case cases[] = {
            {"scale:1.0/grey", "rk_aces_narkowicz(rgb) [vs Hill, input scale 1]", &grey_ramp(), "grey ramp 1e-3..1e4", false},
            {"scale:1.0/colours", "rk_aces_narkowicz(rgb) [vs Hill, input scale 1]", &hdr_colours(), "HDR colours", false},
            {"scale:0.6/grey", "rk_aces_narkowicz(0.6 * rgb) [vs Hill, Narkowicz's suggested 0.6 input scale]",
             &grey_ramp(), "grey ramp 1e-3..1e4", true},
            {"scale:0.6/colours", "rk_aces_narkowicz(0.6 * rgb) [vs Hill, Narkowicz's suggested 0.6 input scale]",
             &hdr_colours(), "HDR colours", true},
        };
        for (const Case& k : cases) {
            const Info info{"narkowicz_vs_hill", k.params, kFam, k.function, vs_hill + "; " + k.where, "cross"};
            if (k.scaled) {
                add_bench(info,
                          rgb_error({k.set}, [](const vec3& c) { return rk_aces_narkowicz(0.6f * c); },
                                    [](const ref::d3& c) { return ref::aces_hill(c); }),
                          hdr_inputs(), [](const vec3& c) { return rk_aces_narkowicz(0.6f * c); });
            } else {
                add_bench(info,
                          rgb_error({k.set}, [](const vec3& c) { return rk_aces_narkowicz(c); },
                                    [](const ref::d3& c) { return ref::aces_hill(c); }),
                          hdr_inputs(), [](const vec3& c) { return rk_aces_narkowicz(c); });
            }
        }
    }

    // AgX; the look is a compile-time constant (RK_AGX_LOOK), as in a shader.
    const std::string vs_agx = "Wrensch's minimal AgX, Blender/Filament CDL looks (ref::agx, look ";
    add_bench({"agx", "look:default/" + hdr, kFam, "rk_agx(rgb, 0) [default look]", vs_agx + "0)"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_agx(c, 0); }, [](const ref::d3& c) { return ref::agx(c, 0); }),
              hdr_inputs(), [](const vec3& c) { return rk_agx(c, 0); });
    add_bench({"agx", "look:golden/" + hdr, kFam, "rk_agx(rgb, 1) [golden look]", vs_agx + "1)"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_agx(c, 1); }, [](const ref::d3& c) { return ref::agx(c, 1); }),
              hdr_inputs(), [](const vec3& c) { return rk_agx(c, 1); });
    add_bench({"agx", "look:punchy/" + hdr, kFam, "rk_agx(rgb, 2) [punchy look]", vs_agx + "2)"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_agx(c, 2); }, [](const ref::d3& c) { return ref::agx(c, 2); }),
              hdr_inputs(), [](const vec3& c) { return rk_agx(c, 2); });

    // Khronos PBR Neutral and its inverse.
    add_bench({"pbr_neutral", hdr, kFam, "rk_pbr_neutral(rgb)", "Khronos PBR Neutral specification (ref::pbr_neutral)"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_pbr_neutral(c); },
                        [](const ref::d3& c) { return ref::pbr_neutral(c); }),
              hdr_inputs(), [](const vec3& c) { return rk_pbr_neutral(c); });
    {
        // Display inputs: the forward map's float outputs of the HDR sets. The output is
        // scene-referred (up to ~1e4 here), so the error is divided by max(1, exact peak channel).
        Set display;
        for (const Set* s : hdr_sets()) {
            for (const vec3& c : *s) display.push_back(rk_pbr_neutral(c));
        }
        Accuracy acc;
        for (const vec3& y : display) {
            const vec3 got = rk_pbr_neutral_inverse(y);
            const ref::d3 want = pbr_neutral_inverse(d3of(y));
            const double scale = std::max({1.0, want[0], want[1], want[2]});
            for (int k = 0; k < 3; ++k) acc.add(d(got[k]) / scale, want[static_cast<std::size_t>(k)] / scale, y);
        }
        // The float64 inverse must undo the float64 forward formula. (Checked on float64 forward
        // outputs: float ones can lie just outside the forward map's image, where the clamp engages.)
        double round_trip = 0.0;
        for (const Set* s : hdr_sets()) {
            for (const vec3& c : *s) {
                const ref::d3 y = ref::pbr_neutral(d3of(c));
                const ref::d3 back = ref::pbr_neutral(pbr_neutral_inverse(y));
                for (std::size_t k = 0; k < 3; ++k) round_trip = std::max(round_trip, std::abs(back[k] - y[k]));
            }
        }
        if (!(round_trip < 1e-9)) {
            std::fprintf(stderr, "bench_tonemap: warning: float64 PBR Neutral inverse off by %.3g (ref::pbr_neutral round trip)\n",
                         round_trip);
        }
        add_bench({"pbr_neutral_inverse", "display", kFam, "rk_pbr_neutral_inverse(display)",
                   "analytic inverse of the spec formula in float64 (bench_tonemap.cpp, checked against ref::pbr_neutral), "
                   "on rk_pbr_neutral's outputs; error / max(1, peak channel) as the result is scene-referred"},
                  acc, make_inputs<vec3>([](Rng& r, std::size_t i) { return rk_pbr_neutral(hdr_pixel(r, i)); }),
                  [](const vec3& c) { return rk_pbr_neutral_inverse(c); });
    }

    // Filmic curves, per channel.
    add_bench({"hable", hdr, kFam, "rk_hable(rgb)", "Hable 2010, white 11.2, per channel (ref::hable)"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_hable(c); },
                        [](const ref::d3& c) { return per_channel(ref::hable, c); }),
              hdr_inputs(), [](const vec3& c) { return rk_hable(c); });
    add_bench({"lottes", hdr, kFam, "rk_lottes(rgb)", "Lottes 2016 with its published constants, per channel (ref::lottes)"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_lottes(c); },
                        [](const ref::d3& c) { return per_channel(ref::lottes, c); }),
              hdr_inputs(), [](const vec3& c) { return rk_lottes(c); });
    add_bench({"uchimura", hdr, kFam, "rk_uchimura(rgb)", "Uchimura 2017 (GT) with its published defaults, per channel (ref::uchimura)"},
              rgb_error(hdr_sets(), [](const vec3& c) { return rk_uchimura(c); },
                        [](const ref::d3& c) { return per_channel(ref::uchimura, c); }),
              hdr_inputs(), [](const vec3& c) { return rk_uchimura(c); });

    // color.glsl: sRGB transfer (display values) and luminance (HDR values).
    const std::vector<const Set*> display_sets{&display_values()};
    add_bench({"srgb_encode", "display", kFam, "rk_srgb_encode(rgb)", "IEC 61966-2-1 (ref::srgb_encode), inputs in [0, 1]"},
              rgb_error_ulp(display_sets, [](const vec3& c) { return rk_srgb_encode(c); },
                            [](const ref::d3& c) { return per_channel(ref::srgb_encode, c); }),
              make_inputs<vec3>(display_pixel), [](const vec3& c) { return rk_srgb_encode(c); });
    add_bench({"srgb_decode", "display", kFam, "rk_srgb_decode(rgb)", "IEC 61966-2-1 (ref::srgb_decode), inputs in [0, 1]"},
              rgb_error_ulp(display_sets, [](const vec3& c) { return rk_srgb_decode(c); },
                            [](const ref::d3& c) { return per_channel(ref::srgb_decode, c); }),
              make_inputs<vec3>(display_pixel), [](const vec3& c) { return rk_srgb_decode(c); });
    {
        Accuracy acc;
        for (const Set* s : hdr_sets()) {
            for (const vec3& c : *s) {
                const float got = rk_luminance(c);
                const double want = ref::luminance709(d3of(c));
                const double scale = std::max(1.0, want);
                acc.add(d(got) / scale, want / scale, c);
                acc.note_ulp(got, want);
            }
        }
        add_bench({"luminance", hdr, kFam, "rk_luminance(rgb)",
                   "BT.709 Y (ref::luminance709); error / max(1, Y) as Y is scene-referred"},
                  acc, hdr_inputs(), [](const vec3& c) { return rk_luminance(c); });
    }
}

const SuiteRegistrar registrar(
    {"tonemap", 20, "Tone mapping: shaders/raykit/tonemap.glsl, color.glsl", "bench/bench_tonemap.cpp", "RGB pixel",
     "BM_tonemap/clamp/hdr", {"tonemap"},
     "- **ns/pixel**: one RGB pixel per call over 4096 pre-generated pixels: the peak channel log-uniform in "
     "[1e-3, 1e4], three quarters mildly coloured (other channels 0.1 to 1 times the peak), a quarter saturated "
     "primaries and secondaries (other channels 0 to 1% of the peak). `rk_srgb_encode`/`rk_srgb_decode` take "
     "display values uniform in [0, 1] (their domain), `rk_pbr_neutral_inverse` takes `rk_pbr_neutral`'s outputs. "
     "Reinhard's white is loaded per call (a uniform on a GPU); the AgX look is a compile-time constant "
     "(`RK_AGX_LOOK`), as in a shader.\n"
     "- **relative cost**: against `clamp(rk_hdr_sanitize(rgb), 0, 1)`, i.e. `RK_TONEMAP_OPERATOR 0`: what a "
     "pixel costs without tone mapping (sanitising, clamping, loads and stores), so an operator's relative cost "
     "reads as that many untone-mapped pixels.\n"
     "- **max / mean abs err**: worst channel, against a float64 evaluation of each function's *own* published "
     "formula (`tests/reference/tonemap_ref.hpp`) at the same float input, over a grey ramp of 20001 values "
     "log-spaced over [1e-3, 1e4] and 20001 pixels drawn like the timing inputs (sRGB: a ramp and random "
     "pixels over [0, 1]). These columns measure the float32 implementation, not how good an operator is. "
     "`rk_luminance` and `rk_pbr_neutral_inverse` return scene-referred values: their error is divided by "
     "max(1, exact value) (absolute up to 1, relative above).\n"
     "- **vs ACES** (flagged *cross*; orange on the plot): both ACES curves are fits of the ACES 1.0 RRT + ODT, so "
     "their error against that transform matters too: `ref::aces_rrt_odt_srgb` evaluates the RRT (glow, red "
     "modifier, RRT_SAT, segmented spline) and the sRGB 100-nit ODT (48-nit spline, dim surround, ODT_SAT, D60->D65) "
     "in float64 from the Academy's CTL, display-linear (before the sRGB encoding); tests/test_tonemap.cpp checks it "
     "against published values (Hill's matrices, 1.0 -> sRGB 0.812, white at 16.292). Hill's fit takes the input "
     "as is; Narkowicz suggests scaling it by 0.6, but 0.5 is where his curve matches best on grey (max 0.0138, the "
     "fit error his post states), hence both. Grey ramp and colours separately: the colour rows add the "
     "hue/saturation differences (Hill omits the glow, red modifier and surround steps; Narkowicz all matrices, so "
     "bright saturated colours stay saturated where ACES goes to white).\n"
     "- **vs Hill** (flagged *cross*): Narkowicz's fit against Hill's fit in float64 (`ref::aces_hill`, BakingLab's "
     "ACES.hlsl), at input scales 1 and 0.6.\n"
     "- **worst at**: the RGB input (display input for the inverse) where the max abs error occurs.",
     "On a GPU, `pow`, `exp2` and `log2` are native approximations and divisions are cheap, so the operators built "
     "on them (AgX: 3 log2 + 3 pow, Lottes: 6 pow, Uchimura, sRGB) cost relatively less than on this CPU, and "
     "the matrices are plain mads. Errors carry over where only +, *, / are used; for `pow`/`log2`/`exp` GLSL "
     "leaves the precision to the driver (tests/gpu/parity_tonemap.cpp measures the CPU/GPU agreement)."},
    &register_operators);

}  // namespace
}  // namespace rkbench
