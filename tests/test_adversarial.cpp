// Adversarial sweeps of every public function of color, tonemap, fresnel, exposure, bloom,
// paraboloid, envmap_correction and window_glass (shaders/raykit/<name>.glsl and the C++-only
// helpers of include/raykit/<name>.hpp): each gets >= 1e5 inputs from tests/adversarial.hpp
// (edge values, documented domain ends, seams and poles, magnitudes up to ±FLT_MAX, NaN/±Inf
// where sanitising is promised, seeded log-uniform and random draws), and every input inside the
// documented domain must give a finite output inside the documented range. A failure prints the
// function, the broken assertion, the output and the exact arguments. `RK_ADV_SCALE=10
// RK_ADV_SEED=n ./test_adversarial` runs a longer, different search (about a minute per 10x).
// The functions built from option macros (rk_tonemap, rk_fresnel_window,
// rk_window_glass_reflectance, rk_window_glass_shade) are swept in the default build here and in
// three other builds by tests/parts/test_adversarial/*.cpp (tests/adversarial_checks.hpp); the
// tone operators of RK_TONEMAP_OPERATOR are also reached through tonemap(). A sample of the same
// stream runs on the driver in tests/gpu/parity_tonemap.cpp and parity_fresnel.cpp.
//
// Inputs: "all" = every float, NaN and ±Inf included (the doc promises to sanitise them);
// "finite" = every finite float (docs/dialect.md rule 11); otherwise the documented domain.
// "x N" = inputs a row feeds (pixels, lookups, texels); rows = 1e5 unless stated.
// "(finite only)": the doc states no range, so only finiteness is asserted.
//
// function (overloads)                       inputs                        asserted
// ---- color.glsl (8) ---------------------------------------------------------------------------
// rk_luminance, rk_luminance_thesis          finite                         finite only
// rk_hdr_sanitize (float, vec3)              all                            == x > 0 ? min(x, 1e18) : 0
// rk_srgb_encode, rk_srgb_decode (f, vec3)   all                            [0, 1]; <= 0 and NaN -> 0; vec3 = scalar
// ---- tonemap.glsl (23) / tonemap.hpp (3) ------------------------------------------------------
// rk_reinhard_scale                          all                            [0, RK_HDR_MAX]
// rk_reinhard, rk_reinhard_extended          all                            [0, 1]
// rk_tonemap_reinhard, rk_aces_narkowicz,    all                            [0, 1]^3
//   rk_aces_hill, rk_agx (looks 0-2, bad),
//   rk_pbr_neutral, rk_hable, rk_lottes,
//   rk_uchimura, rk_tonemap (4 builds)
// rk_aces_hill_curve                         finite                         [-3.81e-4, 1.0165403]
// rk_agx_contrast, rk_agx_look (0-2, bad)    [0, 1]^3                       finite only
// rk_pbr_neutral_inverse                     all                            finite, >= 0 (never negative: doc)
// rk_hable_curve                             finite                         [0, 1 - E/F]
// rk_lottes_params                           finite                         finite only (b, c)
// rk_uchimura_curve                          x in [0, FLT_MAX], parameters  finite only
//                                            in the documented domain
// tonemap (9 operators, AgX looks 0-3)       all                            [0, 1]^3
// tonemap_operator_name, tonemap_defines     operators 0-8 and bad          a name ("?" when bad); the macros
// ---- fresnel.glsl (25) / fresnel.hpp (4) ------------------------------------------------------
// rk_fresnel_clamp_eta                       finite                         [1/4096, 4096]
// rk_f0_from_ior, rk_f0_from_eta             finite                         [0, 1] (a reflectance)
// rk_eta_from_f0                             finite                         [1, 4.1e6] (eta >= 1, ~4e6 at f0 -> 1)
// rk_fresnel_schlick (4 overloads)           finite                         [0, 1]
// rk_fresnel_dielectric_sp, _dielectric      finite                         [0, 1]
// rk_fresnel_fast_params                     finite                         finite only
// rk_fresnel_dielectric_fast (2 overloads)   finite cos; params of any eta  [0, 1]
// rk_fresnel_dielectric_poly                 finite cos, finite p0, p1      [0, 1]
// rk_fresnel_conductor (vec3, float)         finite                         [0, 1]
// rk_critical_cos, rk_critical_angle,        finite                         [0, 1], [0, pi/2], [0, pi/2]
//   rk_brewster_angle
// rk_refract                                 |c| <= 1e15; unit vectors with finite; unit output within 4 ulp for
//                                            dot(i, n) <= 0                 eta >= 1/1.52, 2 ulp / eta^2 below
// rk_fresnel_slab, _slab_sp, _glazing,       finite                         [0, 1]
//   _glazing_sp, rk_fresnel_window (4 builds)
// fresnel_lut_value (4 modes)                finite                         [0, 1]
// bake_fresnel_lut_1d                        sizes -2..70000, finite; x 8   empty outside [2, 65536], else [0, 1]
// sample_fresnel_lut_1d                      baked and empty LUTs, finite   within the LUT's values; empty -> 0
// rk_fresnel_poly_params                     all; 256 fits (1 ms each)      finite p0, p1; error in [0, 1]; the poly
//                                            x 400 cosines                  of those params in [0, 1]
// ---- exposure.glsl (22) / exposure.hpp (9) ----------------------------------------------------
// rk_exposure_clamp                          x all; lo <= hi finite         [lo, hi]; NaN -> lo
// rk_log2_luminance (float, vec3)            all                            [-126, 60.8]
// rk_log_average_from_sum                    all                            [RK_FLT_MIN, 1e18]
// rk_reinhard_auto_key, _auto_white          all                            [0.045, 0.72], [0.046875, 8.65e17]
// rk_ev100_from_luminance                    all                            [-123, 62.8]
// rk_ev100_from_camera                       all                            finite only
// rk_exposure_from_ev100, _from_luminance    all                            [4.5e-20, 1.54e19]
// rk_adapt_exponent, _retain, _factor        all                            [0, 100], [0, 1], [0, 1]; dt <= 0 and
//                                                                          NaN -> 0, 1, 0
// rk_adapt_log2                              all                            between the clamped x and target;
//                                                                          dt <= 0 -> x
// rk_adapt_luminance                         all                            [RK_FLT_MIN, RK_HDR_MAX]; dt <= 0 -> x
// rk_adapt_luminance_linear                  all                            between the sanitised x and target
// rk_reduce_cover                            uints, index * span < 2^32     == the 64-bit definition
// rk_histogram_bin                           all, any bins                  [0, bins - 1]; NaN -> 0
// rk_histogram_bin_edge                      all, any bins                  [lo, hi] of the clamped range
// rk_histogram_scan_init                     -                              every field 0
// rk_histogram_rank_in_bin                   all                            between the clamped edges (3.1 ulp)
// rk_histogram_scan_bin                      all; scans of 1-8 bins         finite state, flags 0/1; an empty bin
//                                                                          changes nothing
// rk_histogram_scan_average                  scanned and arbitrary states   [RK_FLT_MIN, 1e18]
// log_average_luminance (pointer, vector)    images of all floats, bad      finite, clamped; bad input or
//                                            channels / sizes; x 20         empty image -> the documented result
// reinhard_auto_params (floats, stats)       all                            key [0.045, 0.72], white as above
// luminance_histogram                        images of all floats; x 20     counts sum to the pixels; bins 0 -> empty
// histogram_stats                            uint counts, finite; x 20      [RK_FLT_MIN, 1e18]; window <= total
// reduction_chain                            ints (blocks up to 2^31 - 1)   out = ceil(in / block), ends at 1x1
// reduction_texel_weight                     chains of sizes <= 64; x 50    a level's weights sum to w h
// reduce_chain_mean                          |v| <= FLT_MAX / (2 max(w h,   within [min, max] of the values
//                                            block^2)); x 200
// ---- bloom.glsl (25) / bloom.hpp (15) ---------------------------------------------------------
// rk_bloom_sanitize (float, vec3)            all                            == x >= FLT_MIN ? min(x, 1e18) : 0
// rk_bloom_luminance                         all                            0 or [RK_FLT_MIN, RK_HDR_MAX]
// rk_bloom_knee, rk_bloom_cutoff             all, modes 0-2 and bad         [0, sanitised T]
// rk_bloom_weight_hard                       all                            {0, 1}
// rk_bloom_weight_soft_knee                  all                            [0, 1]; 0 at or below T - K, 1 at or
//                                                                          above T + K (above T - K)
// rk_bloom_weight_subtract, rk_bloom_weight  all, modes 0-2 and bad         [0, 1]; 0 at or below the cutoff
// rk_bloom_bright_pass (+ _hard, _soft_knee, all, modes 0-2 and bad         [0, sanitised input]; 0 at or
//   _subtract)                                                             below the cutoff
// rk_bloom_karis_weight                      all                            [1e-18, 1]
// rk_bloom_weighted_average,                 all                            within the range of the colours with
//   rk_bloom_karis_average                                                 a positive weight (1e-6 relative,
//                                                                          RK_FLT_MIN absolute); equal colours
//                                                                          average to themselves (Karis)
// rk_bloom_source_texel                      all                            [-0.5, clamped src - 0.5]
// rk_bloom_bilinear_weights                  all                            each [0, 1], sum 1 within 2.4e-7
// rk_bloom_sum_levels, rk_bloom_composite    all, modes 0-2 and bad         [0, RK_HDR_MAX]^3
//   (+ _add, _mix, _conserve)
// gaussian_weights                           all sigma, radius ints; x 2    valid: w >= 0, w0 + 2 sum = 1; else empty
// linear_sampled_taps, linear_tap_fetches    gaussian and [0, 1e30]; x 8    finite; offsets in [i, i + 1]; 2n - 1
// bloom_chain                                ints                           sizes >= 1, halved up; bad -> empty
// validate_bloom_params, BloomParams::       all floats, ints               the documented rules; presets valid
//   thesis, ::recommended
// bloom_level_weights                        all                            [0, 1e6], 0 past levels; MIX,
//                                                                          CONSERVE: sum 1 (or 0)
// BloomImage(w, h), at                       sizes -3..5                    empty for bad sizes; at reads back
// bloom_texel, sample_bilinear               images |c| <= 1e18; x 10       the texel or 0 / within [min, max]
// bloom_reduce                               images of all floats; x 10     max in [0, 1e18]; count <= pixels
// bloom_blur_discrete                        images |c| <= 1e18; x 10       within [min, max] x sum of weights
// bloom_reference                            images of all floats, params;  [0, RK_HDR_MAX]^3; bad params ->
//                                            x 25                           empty result
// ---- paraboloid.glsl (28) / paraboloid.hpp (25) -----------------------------------------------
// rk_paraboloid_hemi_sign, _max_abs,         finite                         {-1, 1}; max |c|; {1, 2^-100} with a
//   _prescale                                                              normal reciprocal
// rk_paraboloid_normalize                    finite                         within 3.8 ulp per component (denormal
//                                                                          components in and out 0), or the fallback
// rk_paraboloid_encode                       finite                         |st| <= 1e30; <= 1 in the hemisphere
// rk_paraboloid_decode                       finite                         unit within 2 ulp
// rk_paraboloid_encode_differential          finite                         within ±4e30
// rk_paraboloid_solid_angle_density          finite                         [0, 4]
// rk_paraboloid_sweet_circle                 finite                         {0, 1}
// rk_paraboloid_uv                           finite                         |uv - 0.5| <= 0.5 g min(|st|, 1e6)
// rk_paraboloid_frame_angle                  finite                         (-pi, pi]
// rk_paraboloid_frame_vertical               finite                         entries in [-1, 1]
// rk_paraboloid_frame                        finite                         orthonormal right-handed within 4 ulp;
//                                                                          Z = hemi normalise(n)
// rk_paraboloid_filter_footprint             finite                         [0.5, 32768]
// rk_dual_paraboloid_guard_scale             finite                         [1/1024, 1]
// rk_dual_paraboloid_hemi                    finite                         the sign rule
// rk_dual_paraboloid_uv_half                 finite                         finite only
// rk_dual_paraboloid_uv                      finite                         inside the half's disk box (2.4e-7)
// rk_dual_paraboloid_seam_weight             finite dir, all band           [0, 1]
// rk_dual_paraboloid_uv_differential         finite                         |result| <= 0.5 g |d_dir| / |dir|
// rk_dual_paraboloid_dir                     finite                         unit within 2 ulp
// rk_paraboloid_lod_from_incidence           finite                         [0, 16]
// rk_paraboloid_texel_angle                  finite                         (0, 4096]
// rk_paraboloid_lod_for_cone                 finite                         [0, clamped max_lod]
// rk_paraboloid_depth_encode, _decode        finite                         [-1e6, 1e6], finite only
// rk_paraboloid_project                      finite                         finite, w = 1; p = 0 -> (0, 0, -2, 1)
// rk_paraboloid_clip_distance                finite                         finite only
// EnvImage(w, h), texel, set                 sizes -3..5, all               empty for bad sizes; set reads back
// env_cube_valid                             valid and broken cubes         the documented rule
// sample_image_bilinear                      images |c| <= 1e30; x 10       within [min, max]
// downsample_box, generate_env_mips          finite images, odd sizes;      every texel within its sources'
//                                            x 16, x 32                     [min, max]; bad sizes -> empty
// cube_face_direction, cube_face_select      faces 0-5, finite              finite; face 0-5, sc, tc in [-1, 1];
//                                                                          zero -> +Z centre
// cube_texel_direction                       valid texels                   unit within 4 ulp
// sample_cube_map                            cubes |c| <= 1e30; x 20        within the cube's [min, max]
// bake_cube_map, bake_dual_paraboloid(_fn),  sizes / supersampling / guard  bad -> empty with a Status; texels
//   bake_paraboloid(_fn), bake_octahedral    / lod, bad ones included;      within the source's range (the
//   (_fn), cube_from_dual_paraboloid         x baked samples or texels      self-direction [-1, 1] or the cube's)
// dual_paraboloid_guard_scale                any options                    [1/1024, 1]
// dual_paraboloid_auto_supersample           the bakes' size limits         [2, 16]
// sample_dual_paraboloid                     finite dirs, all lod; x 20     within [min, max]; empty map -> 0
// sample_paraboloid                          finite                         within [min, max]; behind the map it
//                                                                          reads the rim (|uv - 0.5| = g / 2)
// octahedral_encode, octahedral_decode       finite                         [-1, 1]^2, unit within 4 ulp
// sample_octahedral                          finite dirs; x 20              within [min, max]
// ---- envmap_correction.glsl (11) --------------------------------------------------------------
// rk_envmap_clamp_pos                        finite                         within ±1e18; identity inside
// rk_envmap_normalize                        finite                         within 3.8 ulp (denormal results 0), or
//                                                                          the fallback
// rk_envmap_angle                            finite                         [0, pi]
// rk_envmap_sigmoid, rk_envmap_fahlen_weight finite                         [1.8e-35, 1]
// rk_reflect_correct_sphere, _plane,         finite                         finite only
//   _box
// rk_reflect_correct_plane_cos               finite                         finite; N.R <= 0 or CP = 0 -> R
// rk_reflect_correct_fahlen (6, 3 args)      finite                         finite; CP = 0 -> R
// ---- window_glass.glsl (8) ---------------------------------------------------------------------
// rk_window_glass_cos                        finite                         [0, 1]
// rk_window_glass_reflectance_exact, _fast   finite (fast: params of any    [0, 1]
//                                            eta)
// rk_window_glass_reflectance (4 builds)     finite                         [0, 1]; grazing -> 1 (eta != 1 and
//                                                                          panes >= RK_FLT_MIN where read)
// rk_window_glass_combine                    colours all, rest finite       finite, >= 0 (terms >= 0: doc)
// rk_window_glass_shade (4 builds)           colours all, rest finite       finite, >= 0
// rk_window_glass_slab_absorbing             finite                         R, T in [0, 1]
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "adversarial_checks.hpp"
#include "raykit/bloom.hpp"
#include "raykit/color.hpp"
#include "raykit/envmap_correction.hpp"
#include "raykit/exposure.hpp"
#include "raykit/fresnel.hpp"
#include "raykit/paraboloid.hpp"
#include "raykit/tonemap.hpp"
#include "raykit/window_glass.hpp"

using namespace raykit;
using rktest::adv::finite;
using rktest::adv::Floats;
using rktest::adv::kRows;
using rktest::adv::S;
using rktest::adv::Vecs;
using rktest::adv::within;

namespace {

const Floats kAll = Floats::all();
const Floats kAny = Floats::any();
const Floats kUnit = Floats::range(0.0f, 1.0f);
const Floats kCos = Floats::any().mark({0.0f, 1.0f, 0.7597469f, 0.5f, -1.0f});
const Floats kEta =
    Floats::any().mark({1.0f, 1.52f, 1.0f / 1.52f, 1.33f, RK_FRESNEL_ETA_MIN, RK_FRESNEL_ETA_MAX, 1e30f});
const Floats kHdr = Floats::all().mark({0.18f, 0.76f, 0.08f, 11.2f, 8.0f, RK_HDR_MAX, 1e9f, 1.9e6f});
const Vecs kHdr3 = Vecs::of(kHdr);

double len(vec3 v) { return std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z); }
double len(vec2 v) { return std::sqrt(double(v.x) * v.x + double(v.y) * v.y); }
float max_abs(vec3 v) { return std::max(std::max(std::abs(v.x), std::abs(v.y)), std::abs(v.z)); }
constexpr double kUlp1 = 1.1920928955078125e-7;  // 1 ulp of 1 (2^-23)

/// Normalisation promise shared by rk_paraboloid_normalize and rk_envmap_normalize: the fallback
/// (bit for bit) when every |component| is below RK_FLT_MIN, else each component within 3.8 ulp of
/// the float64 v / |v| (ulp of that component, at least of a normal float), or 0 where that
/// component is below RK_FLT_MIN (to within those 3.8 ulp: both flush such results, as a GPU
/// would). `flush`: denormal input components count as zero (rk_paraboloid_normalize).
std::string normalize_error(vec3 v, vec3 fb, vec3 r, bool flush)
{
    if (max_abs(v) < RK_FLT_MIN) {
        return std::memcmp(&r, &fb, sizeof r) == 0 ? "" : "not the fallback " + S(r);
    }
    if (flush) {
        for (int i = 0; i < 3; ++i) v[i] = std::abs(v[i]) < RK_FLT_MIN ? 0.0f : v[i];
    }
    const double m = max_abs(v), x = v.x / m, y = v.y / m, z = v.z / m, l = std::sqrt(x * x + y * y + z * z);
    for (int i = 0; i < 3; ++i) {
        const double ref = (double(v[i]) / m) / l;
        const float fe = std::abs(static_cast<float>(ref));
        const double ulp = std::max(double(std::nextafter(fe, RK_FLT_MAX)) - fe, 1.1754943508222875e-38 * kUlp1);
        if (r[i] == 0.0f && std::abs(ref) < 1.1754943508222875e-38 + 3.8 * ulp) continue;
        if (!(std::abs(double(r[i]) - ref) <= 3.8 * ulp)) return "component " + std::to_string(i) + " " + S(r);
    }
    return "";
}

// ---------------------------------------------------------------------------------------------
TEST(Adversarial, Color)
{
    ADV("rk_luminance", {
        const float y = rk_luminance(G.v3(Vecs::any()));
        CHECK(finite(y), S(y));
    });
    ADV("rk_luminance_thesis", {
        const float y = rk_luminance_thesis(G.v3(Vecs::any()));
        CHECK(finite(y), S(y));
    });
    ADV("rk_hdr_sanitize(float)", {
        const float x = G.f(kHdr);
        const float r = rk_hdr_sanitize(x);
        const float want = x > 0.0f ? std::min(x, RK_HDR_MAX) : 0.0f;
        CHECK(r == want && within(r, 0.0f, RK_HDR_MAX), S(r));
    });
    ADV("rk_hdr_sanitize(vec3)", {
        const vec3 c = G.v3(kHdr3);
        const vec3 r = rk_hdr_sanitize(c);
        CHECK(r.x == rk_hdr_sanitize(c.x) && r.y == rk_hdr_sanitize(c.y) && r.z == rk_hdr_sanitize(c.z), S(r));
    });
    const Floats srgb = Floats::all().mark({0.0031308f, 0.04045f, 1.0f, 0.0f});
    ADV("rk_srgb_encode(float)", {
        const float x = G.f(srgb);
        const float r = rk_srgb_encode(x);
        CHECK(within(r, 0.0f, 1.0f), S(r));
        CHECK(x > 0.0f || r == 0.0f, S(r));
    });
    const Vecs srgb3 = Vecs::of(srgb);
    ADV("rk_srgb_encode(vec3)", {
        const vec3 c = G.v3(srgb3);
        const vec3 r = rk_srgb_encode(c);
        CHECK(within(r, 0.0f, 1.0f) && r.x == rk_srgb_encode(c.x) && r.z == rk_srgb_encode(c.z), S(r));
    });
    ADV("rk_srgb_decode(float)", {
        const float x = G.f(srgb);
        const float r = rk_srgb_decode(x);
        CHECK(within(r, 0.0f, 1.0f), S(r));
        CHECK(x > 0.0f || r == 0.0f, S(r));
    });
    ADV("rk_srgb_decode(vec3)", {
        const vec3 c = G.v3(srgb3);
        const vec3 r = rk_srgb_decode(c);
        CHECK(within(r, 0.0f, 1.0f) && r.y == rk_srgb_decode(c.y), S(r));
    });
}

// ---------------------------------------------------------------------------------------------
TEST(Adversarial, Tonemap)
{
    const Floats log_avg = kHdr.mark({1e-20f});
    ADV("rk_reinhard_scale", {
        const float r = CALL(rk_reinhard_scale, G.f(kHdr), G.f(kHdr), G.f(log_avg));
        CHECK(within(r, 0.0f, RK_HDR_MAX), S(r));
    });
    ADV("rk_reinhard", {
        const float r = rk_reinhard(G.f(kHdr));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    const Floats white = kHdr.mark({1e-9f, 1e9f});
    ADV("rk_reinhard_extended", {
        const float r = CALL(rk_reinhard_extended, G.f(kHdr), G.f(white));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_tonemap_reinhard", {
        const vec3 r = CALL(rk_tonemap_reinhard, G.v3(kHdr3), G.f(white));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_aces_narkowicz", {
        const vec3 r = rk_aces_narkowicz(G.v3(kHdr3));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    const Vecs hill = Vecs::of(kAny.mark({0.00325f, 1e9f}));
    ADV("rk_aces_hill_curve", {
        const vec3 r = rk_aces_hill_curve(G.v3(hill));
        CHECK(within(r, -3.81e-4f, 1.0165403f), S(r));
    });
    ADV("rk_aces_hill", {
        const vec3 r = rk_aces_hill(G.v3(kHdr3));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    const Vecs unit3 = Vecs::of(kUnit);
    ADV("rk_agx_contrast", {
        const vec3 r = rk_agx_contrast(G.v3(unit3));
        CHECK(finite(r), S(r));
    });
    ADV("rk_agx_look", {
        const vec3 r = CALL(rk_agx_look, G.v3(unit3), G.i({0, 1, 2}));
        CHECK(finite(r), S(r));
    });
    ADV("rk_agx", {
        const vec3 r = CALL(rk_agx, G.v3(kHdr3), G.i({0, 1, 2}));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_pbr_neutral", {
        const vec3 r = rk_pbr_neutral(G.v3(kHdr3));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    const Vecs display = Vecs::of(kHdr.mark({0.76f, 1.0f - 9.5367431640625e-7f, 0.04f}));
    ADV("rk_pbr_neutral_inverse", {
        const vec3 r = rk_pbr_neutral_inverse(G.v3(display));
        CHECK(finite(r) && within(r, 0.0f, RK_FLT_MAX), S(r));
    });
    const Vecs hable = Vecs::of(kAny.mark({1e9f}));
    ADV("rk_hable_curve", {
        const vec3 r = rk_hable_curve(G.v3(hable));
        CHECK(within(r, 0.0f, 1.0f - 0.02f / 0.30f), S(r));
    });
    ADV("rk_hable", {
        const vec3 r = rk_hable(G.v3(kHdr3));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    const Floats la = kAny.mark({0.1f, 4.0f}), ld = kAny.mark({0.1f}), lh = kAny.mark({1e4f}), lmi = kAny.mark({1e-4f}),
                 lmo = kAny.mark({1e-4f, 0.9999f});
    ADV("rk_lottes_params", {
        const vec2 r = CALL(rk_lottes_params, G.f(la), G.f(ld), G.f(lh), G.f(lmi), G.f(lmo));
        CHECK(finite(r), S(r));
    });
    ADV("rk_lottes", {
        const vec3 r = rk_lottes(G.v3(kHdr3));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    // The documented parameter domain (rk_uchimura_curve's comment), ends and interior.
    const Floats uch_p = Floats::range(1e-3f, 1e3f).mark({1.0f, 1.5f}),
                 uch_mf = Floats::range(1e-4f, 0.999f).mark({0.22f});
    const Floats uch_l = Floats::range(0.0f, 0.999f).mark({0.4f}), uch_a = Floats::range(1e-3f, 1e3f).mark({1.0f});
    const Floats uch_c = Floats::range(0.01f, 100.0f).mark({1.33f}), uch_b = Floats::range(-1.0f, 1.0f);
    const Vecs uch_x = Vecs::of(Floats::range(0.0f, RK_FLT_MAX));
    ADV("rk_uchimura_curve", {
        const vec3 x = G.v3(uch_x);
        const float P = G.f(uch_p), m = P * G.f(uch_mf), a = G.f(uch_a), l = G.f(uch_l), c = G.f(uch_c),
                    b = P * G.f(uch_b);
        const vec3 r = rk_uchimura_curve(x, P, a, m, l, c, b);
        CHECK(finite(r), S(r));
    });
    ADV("rk_uchimura", {
        const vec3 r = rk_uchimura(G.v3(kHdr3));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    for (int op = 0; op <= 8; ++op) {
        for (int look = 0; look <= (op == 4 ? 3 : 0); ++look) {
            ADV("tonemap(" + std::string(tonemap_operator_name(static_cast<ToneOperator>(op))) + ", look " +
                    std::to_string(look) + ")",
                {
                    const vec3 r = CALL(tonemap, static_cast<ToneOperator>(op), G.v3(kHdr3), look, G.f(white));
                    CHECK(within(r, 0.0f, 1.0f), S(r));
                });
        }
    }
    ADV("tonemap_operator_name", {
        const int op = G.i({0, 1, 2, 3, 4, 5, 6, 7, 8});
        const char* n = tonemap_operator_name(static_cast<ToneOperator>(op));
        CHECK(n != nullptr && (op < 0 || op > 8 ? std::strcmp(n, "?") == 0 : std::strcmp(n, "?") != 0), std::string(n));
    });
    ADV("tonemap_defines", {
        const int op = static_cast<int>(G.index(9));
        const int look = G.i({0, 1, 2});
        const std::vector<ShaderDefine> d = tonemap_defines(static_cast<ToneOperator>(op), look);
        CHECK(!d.empty() && d[0].name == "RK_TONEMAP_OPERATOR" && d[0].value == std::to_string(op) &&
                  d.size() == (op == 4 ? 2u : 1u),
              std::to_string(d.size()));
    });
}

// ---------------------------------------------------------------------------------------------
TEST(Adversarial, Fresnel)
{
    ADV("rk_fresnel_clamp_eta", {
        const float r = rk_fresnel_clamp_eta(G.f(kEta));
        CHECK(within(r, RK_FRESNEL_ETA_MIN, RK_FRESNEL_ETA_MAX), S(r));
    });
    ADV("rk_f0_from_ior", {
        const float r = CALL(rk_f0_from_ior, G.f(kEta), G.f(kEta));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_f0_from_eta", {
        const float r = rk_f0_from_eta(G.f(kEta));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    const Floats f0 = kAny.mark({0.9999990f, 0.04f});
    ADV("rk_eta_from_f0", {
        const float r = rk_eta_from_f0(G.f(f0));
        CHECK(within(r, 1.0f, 4.1e6f), S(r));
    });
    ADV("rk_fresnel_schlick(float, float)", {
        const float r = CALL(rk_fresnel_schlick, G.f(kCos), G.f(kAny));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_schlick(float, vec3)", {
        const vec3 r = CALL(rk_fresnel_schlick, G.f(kCos), G.v3(Vecs::any()));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_schlick(float, float, float)", {
        const float r = CALL(rk_fresnel_schlick, G.f(kCos), G.f(kAny), G.f(kAny));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_schlick(float, vec3, vec3)", {
        const vec3 r = CALL(rk_fresnel_schlick, G.f(kCos), G.v3(Vecs::any()), G.v3(Vecs::any()));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_dielectric_sp", {
        const vec2 r = CALL(rk_fresnel_dielectric_sp, G.f(kCos), G.f(kEta));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_dielectric", {
        const float r = CALL(rk_fresnel_dielectric, G.f(kCos), G.f(kEta));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_fast_params", {
        const vec3 r = rk_fresnel_fast_params(G.f(kEta));
        CHECK(finite(r), S(r));
    });
    ADV("rk_fresnel_dielectric_fast(float, vec3)", {
        const float r = CALL(rk_fresnel_dielectric_fast, G.f(kCos), rk_fresnel_fast_params(G.f(kEta)));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_dielectric_fast(float, float)", {
        const float r = CALL(rk_fresnel_dielectric_fast, G.f(kCos), G.f(kEta));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    const Floats kappa = kEta.mark({0.0f});
    const Vecs eta3 = Vecs::of(kEta), kappa3 = Vecs::of(kappa);
    ADV("rk_fresnel_dielectric_poly", {
        const float c = G.f(kCos);
        const vec4 p0 = G.v4(Vecs::any());
        const vec2 p1 = G.v2(Vecs::any());
        const float r = rk_fresnel_dielectric_poly(c, p0, p1);
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    // A fit takes ~1 ms: 256 materials (etas of every float), each checked over 400 cosines.
    const Floats poly_eta = kAll.mark({1.0f + 1.0f / 1024.0f, 64.0f, 1.52f, 1.05f});
    ADV_N("rk_fresnel_poly_params (+ rk_fresnel_dielectric_poly)", 256, 400, {
        const FresnelPolyParams p = rk_fresnel_poly_params(G.f(poly_eta));
        CHECK(finite(p.p0) && finite(p.p1) && within(p.max_abs_error, 0.0f, 1.0f),
              S(p.p0) + S(p.p1) + S(p.max_abs_error));
        for (int k = 0; k < 400; ++k) {
            const float r = rk_fresnel_dielectric_poly(G.f(kCos), p.p0, p.p1);
            CHECK(within(r, 0.0f, 1.0f), S(r));
        }
    });
    ADV("rk_fresnel_conductor(float, vec3, vec3)", {
        const vec3 r = CALL(rk_fresnel_conductor, G.f(kCos), G.v3(eta3), G.v3(kappa3));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_conductor(float, float, float)", {
        const float r = CALL(rk_fresnel_conductor, G.f(kCos), G.f(kEta), G.f(kappa));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_critical_cos", {
        const float r = rk_critical_cos(G.f(kEta));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_critical_angle", {
        const float r = rk_critical_angle(G.f(kEta));
        CHECK(within(r, 0.0f, RK_HALF_PI), S(r));
    });
    ADV("rk_brewster_angle", {
        const float r = rk_brewster_angle(G.f(kEta));
        CHECK(within(r, 0.0f, RK_HALF_PI), S(r));
    });
    const Vecs lim = Vecs::of(Floats::range(-1e15f, 1e15f));
    ADV("rk_refract (any vectors)", {
        vec3 t(0.0f);
        const vec3 i = G.v3(lim), n = G.v3(lim);
        rk_refract(i, n, G.f(kEta), t);
        CHECK(finite(t), S(t));
    });
    ADV("rk_refract (unit vectors)", {
        vec3 i = G.v3(Vecs::units()), n = G.v3(Vecs::units());
        if (dot(i, n) > 0.0f) i = -i;
        const float e = G.f(kEta);
        vec3 t(0.0f);
        rk_refract(i, n, e, t);
        CHECK(finite(t), S(t));
        // "Unit inputs give a unit output within 4 ulp for eta >= 1/1.52; below, within 2 ulp / eta^2".
        const double ec = rk_fresnel_clamp_eta(e);
        CHECK(std::abs(len(t) - 1.0) <= (ec >= 1.0 / 1.52 ? 4.0 : 2.0 / (ec * ec)) * kUlp1, S(t));
    });
    ADV("rk_fresnel_slab", {
        const float r = rk_fresnel_slab(G.f(kAny));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_slab_sp", {
        const float r = rk_fresnel_slab_sp(G.v2(Vecs::any()));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    const Floats panes = kAny.mark({0.0f, 1.0f, 2.0f, 1e6f});
    ADV("rk_fresnel_glazing", {
        const float r = CALL(rk_fresnel_glazing, G.f(kAny), G.f(panes));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_glazing_sp", {
        const float r = CALL(rk_fresnel_glazing_sp, G.v2(Vecs::any()), G.f(panes));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("fresnel_lut_value", {
        const float r =
            CALL(fresnel_lut_value, G.f(kCos), G.f(kEta), static_cast<FresnelLutMode>(G.index(4)), G.f(panes));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    // Every LUT value is an input; sizes mostly small, with the documented limits and beyond.
    ADV_N("bake_fresnel_lut_1d", 20000, 8, {
        const int sizes[] = {-2, 0, 1, 2, 3, 5, 8, 17, 64, 65536, 65537, 70000};
        const int size = G.uniform() < 0.98 ? sizes[G.index(9)] : sizes[9 + G.index(3)];
        const float e = G.f(kEta);
        const FresnelLutMode mode = static_cast<FresnelLutMode>(G.index(4));
        const std::vector<float> lut = bake_fresnel_lut_1d(size, e, mode, G.f(panes));
        CHECK((size < 2 || size > 65536) ? lut.empty() : lut.size() == static_cast<size_t>(size),
              std::to_string(lut.size()));
        for (float v : lut) CHECK(within(v, 0.0f, 1.0f), S(v));
    });
    std::vector<std::vector<float>> luts = {{}, {0.25f}};
    for (int m = 0; m < 4; ++m)
        luts.push_back(bake_fresnel_lut_1d(2 + 7 * m, 1.52f, static_cast<FresnelLutMode>(m), 2.0f));
    ADV("sample_fresnel_lut_1d", {
        const std::vector<float>& lut = luts[G.index(luts.size())];
        const float r = sample_fresnel_lut_1d(lut, G.f(kCos));
        if (lut.empty()) {
            CHECK(r == 0.0f, S(r));
        } else {
            CHECK(within(r, *std::min_element(lut.begin(), lut.end()), *std::max_element(lut.begin(), lut.end())),
                  S(r));
        }
    });
}

// ---------------------------------------------------------------------------------------------
TEST(Adversarial, Exposure)
{
    const Floats ev = kAll.mark({-64.0f, 64.0f, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX});
    ADV("rk_exposure_clamp", {
        const float x = G.f(kAll);
        float lo = G.f(kAny), hi = G.f(kAny);
        if (lo > hi) std::swap(lo, hi);
        const float r = rk_exposure_clamp(x, lo, hi);
        CHECK(within(r, lo, hi) && (!std::isnan(x) || r == lo), S(r));
    });
    const Floats delta = kHdr.mark({RK_LOG_LUM_DELTA});
    ADV("rk_log2_luminance(float, float)", {
        const float r = CALL(rk_log2_luminance, G.f(kHdr), G.f(delta));
        CHECK(within(r, -126.0f, 60.8f), S(r));
    });
    ADV("rk_log2_luminance(vec3, float)", {
        const float r = CALL(rk_log2_luminance, G.v3(kHdr3), G.f(kHdr));
        CHECK(within(r, -126.0f, 60.8f), S(r));
    });
    ADV("rk_log_average_from_sum", {
        const float r = CALL(rk_log_average_from_sum, G.f(ev), G.f(kAll));
        CHECK(within(r, RK_FLT_MIN, 1e18f), S(r));
    });
    const Floats lum = kAll.mark({RK_REINHARD_LUM_MIN, 0.01f, 100.0f});
    ADV("rk_reinhard_auto_key", {
        const float r = CALL(rk_reinhard_auto_key, G.f(lum), G.f(lum), G.f(lum));
        CHECK(within(r, 0.045f * (1.0f - 1e-6f), 0.72f * (1.0f + 1e-6f)), S(r));
    });
    ADV("rk_reinhard_auto_white", {
        const float r = CALL(rk_reinhard_auto_white, G.f(lum), G.f(lum));
        CHECK(within(r, 0.046875f, 8.65e17f), S(r));
    });
    ADV("rk_ev100_from_luminance", {
        const float r = rk_ev100_from_luminance(G.f(kHdr));
        CHECK(within(r, -123.0f, 62.8f), S(r));
    });
    const Floats cam = kAll.mark({1e-6f, 1e6f});
    ADV("rk_ev100_from_camera", {
        const float r = CALL(rk_ev100_from_camera, G.f(cam), G.f(cam), G.f(cam));
        CHECK(finite(r), S(r));
    });
    ADV("rk_exposure_from_ev100", {
        const float r = rk_exposure_from_ev100(G.f(ev));
        CHECK(within(r, 4.5e-20f, 1.54e19f), S(r));
    });
    ADV("rk_exposure_from_luminance", {
        const float r = CALL(rk_exposure_from_luminance, G.f(kHdr), G.f(ev));
        CHECK(within(r, 4.5e-20f, 1.54e19f), S(r));
    });
    const Floats dt = kAll.mark({RK_ADAPT_TAU_MIN, RK_ADAPT_TIME_MAX, 1.0f / 60.0f});
    ADV("rk_adapt_exponent", {
        const float d = G.f(dt);
        const float r = rk_adapt_exponent(d, G.f(dt));
        CHECK(within(r, 0.0f, 100.0f) && (d > 0.0f || r == 0.0f), S(r));
    });
    ADV("rk_adapt_retain", {
        const float d = G.f(dt);
        const float r = rk_adapt_retain(d, G.f(dt));
        CHECK(within(r, 0.0f, 1.0f) && (d > 0.0f || r == 1.0f), S(r));
    });
    ADV("rk_adapt_factor", {
        const float d = G.f(dt);
        const float r = rk_adapt_factor(d, G.f(dt));
        CHECK(within(r, 0.0f, 1.0f) && (d > 0.0f || r == 0.0f), S(r));
    });
    ADV("rk_adapt_log2", {
        const float x = G.f(ev), target = G.f(ev), d = G.f(dt);
        const float r = CALL(rk_adapt_log2, x, target, d, G.f(dt), G.f(dt));
        const float c = rk_exposure_clamp(x, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX);
        const float t = rk_exposure_clamp(target, RK_LOG2_LUM_MIN, RK_LOG2_LUM_MAX);
        CHECK(within(r, std::min(c, t), std::max(c, t)) && (d > 0.0f || r == c), S(r));
    });
    ADV("rk_adapt_luminance", {
        const float x = G.f(kHdr), d = G.f(dt);
        const float r = CALL(rk_adapt_luminance, x, G.f(kHdr), d, G.f(dt), G.f(dt));
        CHECK(within(r, RK_FLT_MIN, RK_HDR_MAX) && (d > 0.0f || r == std::max(rk_hdr_sanitize(x), RK_FLT_MIN)), S(r));
    });
    ADV("rk_adapt_luminance_linear", {
        const float x = G.f(kHdr), target = G.f(kHdr), d = G.f(dt);
        const float r = CALL(rk_adapt_luminance_linear, x, target, d, G.f(dt), G.f(dt));
        const float c = rk_hdr_sanitize(x), t = rk_hdr_sanitize(target);
        CHECK(within(r, std::min(c, t), std::max(c, t)) && (d > 0.0f || r == c), S(r));
    });
    ADV("rk_reduce_cover", {
        const uint span = G.u();
        const uint index = G.u(0u, span == 0u ? 0xFFFFFFFFu : 0xFFFFFFFFu / span);
        const uint size = G.u();
        const std::uint64_t start = std::uint64_t(index) * span;
        const std::uint64_t want = start < size ? std::min<std::uint64_t>(span, size - start) : 0u;
        const uint r = rk_reduce_cover(index, span, size);
        CHECK(r == want, std::to_string(r));
    });
    const Floats range_log2 = kAll.mark({-256.0f, 256.0f, 512.0f, -8.0f, 8.0f});
    ADV("rk_histogram_bin", {
        const float x = G.f(kAll);
        const uint bins = G.u();
        const uint r = CALL(rk_histogram_bin, x, G.f(range_log2), G.f(range_log2), bins);
        const uint n = std::min(std::max(bins, 1u), 16777216u);
        CHECK(r <= n - 1u && (!std::isnan(x) || r == 0u), std::to_string(r));
    });
    ADV("rk_histogram_bin_edge", {
        const float lo_in = G.f(range_log2), hi_in = G.f(range_log2);
        const float r = CALL(rk_histogram_bin_edge, G.f(kAll), lo_in, hi_in, G.u());
        const float lo = rk_exposure_clamp(lo_in, -256.0f, 256.0f), hi = rk_exposure_clamp(hi_in, lo + 1.0e-3f, 512.0f);
        CHECK(within(r, lo, hi), S(r));
    });
    ADV("rk_histogram_scan_init", {
        (void)G;
        const rk_histogram_scan s = rk_histogram_scan_init();
        CHECK(s.below == 0.0f && s.weight == 0.0f && s.weighted_log2 == 0.0f && s.low_log2 == 0.0f &&
                  s.high_log2 == 0.0f && s.low_found == 0.0f && s.high_found == 0.0f,
              "");
    });
    const Floats edge = kAll.mark({-1024.0f, 1024.0f});
    ADV("rk_histogram_rank_in_bin", {
        const float rank = G.f(kAll), below = G.f(kAll), count = G.f(kAll), e0 = G.f(edge), e1 = G.f(edge);
        const float r = rk_histogram_rank_in_bin(rank, below, count, e0, e1);
        const float c0 = rk_exposure_clamp(e0, -1024.0f, 1024.0f), c1 = rk_exposure_clamp(e1, -1024.0f, 1024.0f);
        // Between the clamped edges, within the documented 3.1 ulp of the edges.
        const float ulps = 3.1f * std::max(std::abs(c0), std::abs(c1)) * FLT_EPSILON;
        CHECK(within(r, std::min(c0, c1) - ulps, std::max(c0, c1) + ulps), S(r));
    });
    // Scans of 1-8 bins with adversarial counts, edges, windows and ranks; every call is an input.
    const Floats count = kAll.mark({1e30f, 16777216.0f});
    auto scan_ok = [](const rk_histogram_scan& s) {
        return within(s.below, 0.0f, RK_FLT_MAX) && within(s.weight, 0.0f, RK_FLT_MAX) && finite(s.weighted_log2) &&
               within(s.low_log2, -1024.001f, 1024.001f) && within(s.high_log2, -1024.001f, 1024.001f) &&
               (s.low_found == 0.0f || s.low_found == 1.0f) && (s.high_found == 0.0f || s.high_found == 1.0f);
    };
    auto scan_str = [](const rk_histogram_scan& s) {
        return S(vec4(s.below, s.weight, s.weighted_log2, s.low_log2)) +
               S(vec3(s.high_log2, s.low_found, s.high_found));
    };
    std::vector<rk_histogram_scan> finished;
    ADV_N("rk_histogram_scan_bin", kRows / 4, 4.5, {
        rk_histogram_scan s = rk_histogram_scan_init();
        const float wl = G.f(count), wh = G.f(count), lr = G.f(count), hr = G.f(count);
        const int bins = 1 + static_cast<int>(G.index(8));
        for (int b = 0; b < bins; ++b) {
            const rk_histogram_scan before = s;
            const float c = G.f(count);
            const float e0 = G.f(edge), e1 = G.f(edge);
            rk_histogram_scan_bin(s, c, e0, e1, wl, wh, lr, hr);
            CHECK(scan_ok(s), scan_str(s));
            // An empty bin changes nothing ("but below", which it leaves as it is).
            CHECK(c > 0.0f || std::memcmp(&s, &before, sizeof s) == 0, scan_str(s));
        }
        if (finished.size() < 4096) finished.push_back(s);
    });
    ADV("rk_histogram_scan_average", {
        rk_histogram_scan s;
        if (G.uniform() < 0.5) {
            s = finished[G.index(finished.size())];
        } else {
            s.below = G.f(kAll);
            s.weight = G.f(kAll);
            s.weighted_log2 = G.f(kAll);
            s.low_log2 = G.f(kAll);
            s.high_log2 = G.f(kAll);
            s.low_found = G.f(kAll);
            s.high_found = G.f(kAll);
        }
        const float r = rk_histogram_scan_average(s);
        CHECK(within(r, RK_FLT_MIN, 1e18f), S(r));
    });
}

// ---------------------------------------------------------------------------------------------
// C++ helpers of exposure.hpp. Images: 0-64 pixels of every float (NaN and ±Inf included).
std::vector<float> adversarial_image(rktest::adv::Gen& G, size_t floats, const Floats& values)
{
    std::vector<float> v(floats);
    for (float& x : v) x = G.f(values);
    return v;
}

TEST(Adversarial, ExposureHpp)
{
    const Floats pct = kUnit.mark({0.01f, 0.99f});
    ADV_N("log_average_luminance", kRows / 10, 20, {
        const size_t w = G.index(9), h = G.index(9);
        const int ch = G.i({1, 3, 4});
        const std::vector<float> px =
            adversarial_image(G, w * h * static_cast<size_t>(std::min(std::max(ch, 1), 4)) + 1, kHdr);
        LogAverageOptions o;
        o.delta = G.f(kHdr);
        o.low_percentile = G.f(pct);
        o.high_percentile = G.f(pct);
        Status st;
        const LuminanceStats s = log_average_luminance(px.data(), w, h, ch, o, &st);
        const bool valid = ch == 1 || ch == 3 || ch == 4;
        CHECK(st.ok() == valid, st.message);
        // Extremes of delta + L are exp2 of terms in [-126, 60.8]; an empty image keeps the defaults.
        CHECK(s.count == 0 || (within(s.log_average, RK_FLT_MIN, 1e18f) && std::isfinite(s.mean_log2) &&
                               std::isfinite(s.sum_log2) && within(s.min, RK_FLT_MIN, 2e18f) &&
                               within(s.max, RK_FLT_MIN, 2e18f) && within(s.robust_min, RK_FLT_MIN, 1e18f) &&
                               within(s.robust_max, RK_FLT_MIN, 1e18f) && s.sanitized <= s.count),
              S(vec4(s.log_average, s.min, s.max, s.robust_min)));
        CHECK(s.count == (valid ? w * h : 0u) && (s.count > 0 || s.log_average == 1.0f), std::to_string(s.count));
        // The vector overload: a size mismatch gives the empty image's result.
        const LuminanceStats v = log_average_luminance(px, w, h, ch, o, &st);
        CHECK(!st.ok() && v.count == 0 && v.log_average == 1.0f, st.message);
    });
    const Floats lum = kAll.mark({RK_REINHARD_LUM_MIN, 0.01f, 100.0f});
    ADV("reinhard_auto_params(float, float, float)", {
        const ReinhardParams p = CALL(reinhard_auto_params, G.f(lum), G.f(lum), G.f(lum));
        CHECK(within(p.key, 0.045f * (1.0f - 1e-6f), 0.72f * (1.0f + 1e-6f)) && within(p.white, 0.046875f, 8.65e17f),
              S(vec2(p.key, p.white)));
    });
    ADV("reinhard_auto_params(LuminanceStats)", {
        LuminanceStats s;
        s.log_average = G.f(lum);
        s.robust_min = G.f(lum);
        s.robust_max = G.f(lum);
        const ReinhardParams p = reinhard_auto_params(s);
        CHECK(within(p.key, 0.045f * (1.0f - 1e-6f), 0.72f * (1.0f + 1e-6f)) && within(p.white, 0.046875f, 8.65e17f),
              S(vec2(p.key, p.white)));
    });
    const Floats range_log2 = kAll.mark({-256.0f, 256.0f, -20.0f, 20.0f});
    ADV_N("luminance_histogram", kRows / 10, 20, {
        const size_t w = G.index(9), h = G.index(9);
        const int ch = G.i({1, 3, 4});
        const std::vector<float> px =
            adversarial_image(G, w * h * static_cast<size_t>(std::min(std::max(ch, 1), 4)), kHdr);
        const uint bins = G.uniform() < 0.1 ? 0u : static_cast<uint>(1 + G.index(300));
        Status st;
        const std::vector<std::uint32_t> c =
            CALL(luminance_histogram, px.data(), w, h, ch, bins, G.f(range_log2), G.f(range_log2), G.f(kHdr), &st);
        const bool valid = (ch == 1 || ch == 3 || ch == 4) && bins > 0;
        std::uint64_t sum = 0;
        for (std::uint32_t k : c) sum += k;
        CHECK(st.ok() == valid && c.size() == (valid ? bins : 0u) && sum == (valid ? w * h : 0u), st.message);
    });
    const Floats frac = kAny.mark({0.0f, 1.0f, 0.05f, 0.95f});
    ADV_N("histogram_stats", kRows / 10, 20, {
        std::vector<std::uint32_t> counts(G.index(40));
        for (std::uint32_t& k : counts) k = G.uniform() < 0.5 ? 0u : G.u();
        const HistogramStats h =
            CALL(histogram_stats, counts, G.f(range_log2), G.f(range_log2), G.f(frac), G.f(frac), G.f(frac), G.f(frac));
        double total = 0.0;
        for (std::uint32_t k : counts) total += k;
        CHECK(within(h.average, RK_FLT_MIN, 1e18f) && within(h.low, RK_FLT_MIN, 1e18f) &&
                  within(h.high, RK_FLT_MIN, 1e18f) &&
                  within(h.window_pixels, 0.0f, static_cast<float>(total) * (1.0f + 1e-6f)) && h.total == total,
              S(vec4(h.average, h.low, h.high, h.window_pixels)));
    });
    ADV("reduction_chain", {
        const int w = static_cast<int>(G.u(0u, 0x7FFFFFFFu)) * (G.uniform() < 0.1 ? -1 : 1);
        const int h = G.uniform() < 0.5 ? static_cast<int>(G.index(5000)) : static_cast<int>(G.u(0u, 0x7FFFFFFFu));
        const int block = G.uniform() < 0.5 ? static_cast<int>(G.index(70)) : static_cast<int>(G.u(0u, 0x7FFFFFFFu));
        Status st;
        const std::vector<ReductionPass> c = reduction_chain(w, h, block, &st);
        const bool valid = w >= 1 && h >= 1 && w <= (1 << 30) && h <= (1 << 30) && block >= 2;
        CHECK(st.ok() == valid && c.empty() == !valid, st.message);
        std::int64_t iw = w, ih = h;
        for (const ReductionPass& p : c) {
            CHECK(p.in_width == iw && p.in_height == ih && p.out_width == (iw + block - 1) / block &&
                      p.out_height == (ih + block - 1) / block && p.last_cover_x >= 1 && p.last_cover_y >= 1,
                  std::to_string(p.out_width) + " " + std::to_string(p.out_height));
            iw = p.out_width;
            ih = p.out_height;
        }
        CHECK(!valid || (c.back().out_width == 1 && c.back().out_height == 1), std::to_string(c.size()));
    });
    // Every texel weight of a chain is an input.
    ADV_N("reduction_texel_weight", kRows / 20, 50, {
        const int w = 1 + static_cast<int>(G.index(64)), h = 1 + static_cast<int>(G.index(64)),
                  block = 2 + static_cast<int>(G.index(7));
        for (const ReductionPass& p : reduction_chain(w, h, block)) {
            double sum = 0.0;
            for (int j = 0; j < p.out_height; ++j) {
                for (int i = 0; i < p.out_width; ++i) sum += reduction_texel_weight(p, i, j, w, h);
            }
            CHECK(sum == double(w) * h, std::to_string(sum));
        }
    });
    ADV_N("reduce_chain_mean", kRows / 50, 200, {
        const int w = 1 + static_cast<int>(G.index(32)), h = 1 + static_cast<int>(G.index(32)),
                  block = 2 + static_cast<int>(G.index(5));
        // The documented domain: no block sum overflows.
        const float lim = RK_FLT_MAX / static_cast<float>(2 * std::max(w * h, block * block));
        const Floats values = Floats::range(-lim, lim);
        std::vector<float> v(static_cast<size_t>(w * h));
        const float shared = G.f(kAny);
        for (float& x : v) x = G.uniform() < 0.3 ? std::min(std::max(shared, -lim), lim) : G.f(values);
        const float lo = *std::min_element(v.begin(), v.end()), hi = *std::max_element(v.begin(), v.end());
        const float slack = 1e-5f * std::max(std::abs(lo), std::abs(hi));
        for (bool weighted : {true, false}) {
            const float m = reduce_chain_mean(v, w, h, block, weighted);
            CHECK(within(m, lo - slack, hi + slack), S(m));
        }
    });
}

// ---------------------------------------------------------------------------------------------
float bloom_ref_sanitize(float x) { return x >= RK_FLT_MIN ? std::min(x, RK_HDR_MAX) : 0.0f; }

/// The range promise of the weighted averages: each channel within [min, max] of the sanitised
/// colours whose (sanitised) weight is positive, up to rounding (1e-6 relative, RK_FLT_MIN
/// absolute); black when no weight is.
std::string weighted_average_error(const vec3 c[4], const float w[4], vec3 r)
{
    vec3 lo(RK_FLT_MAX), hi(0.0f);
    bool any = false;
    for (int i = 0; i < 4; ++i) {
        if (bloom_ref_sanitize(w[i]) > 0.0f) {
            const vec3 sc = rk_bloom_sanitize(c[i]);
            lo = min(lo, sc);
            hi = max(hi, sc);
            any = true;
        }
    }
    if (!any) return r == vec3(0.0f) ? "" : "not black " + S(r);
    for (int k = 0; k < 3; ++k) {
        if (!within(r[k], lo[k] * (1.0f - 1e-6f) - RK_FLT_MIN, hi[k] * (1.0f + 1e-6f) + RK_FLT_MIN)) {
            return S(r) + " outside " + S(lo) + ".." + S(hi);
        }
    }
    return "";
}

TEST(Adversarial, Bloom)
{
    const Floats thr = kAll.mark({RK_BLOOM_THRESHOLD, 0.5f, 2.0f});
    const Vecs w4 = Vecs::of(kAll.mark({0.25f, 1.0f}));
    ADV("rk_bloom_sanitize(float)", {
        const float x = G.f(kHdr);
        const float r = rk_bloom_sanitize(x);
        CHECK(r == bloom_ref_sanitize(x), S(r));
    });
    ADV("rk_bloom_sanitize(vec3)", {
        const vec3 c = G.v3(kHdr3);
        const vec3 r = rk_bloom_sanitize(c);
        CHECK(r.x == bloom_ref_sanitize(c.x) && r.y == bloom_ref_sanitize(c.y) && r.z == bloom_ref_sanitize(c.z), S(r));
    });
    ADV("rk_bloom_luminance", {
        const float r = rk_bloom_luminance(G.v3(kHdr3));
        CHECK(within(r, 0.0f, RK_HDR_MAX) && (r == 0.0f || r >= RK_FLT_MIN), S(r));
    });
    ADV("rk_bloom_knee", {
        const float t = G.f(thr);
        const float r = rk_bloom_knee(t, G.f(thr));
        CHECK(within(r, 0.0f, bloom_ref_sanitize(t)), S(r));
    });
    ADV("rk_bloom_cutoff", {
        const float t = G.f(thr);
        const float r = CALL(rk_bloom_cutoff, t, G.f(thr), G.i({0, 1, 2}));
        CHECK(within(r, 0.0f, bloom_ref_sanitize(t)), S(r));
    });
    ADV("rk_bloom_weight_hard", {
        const float r = CALL(rk_bloom_weight_hard, G.f(kHdr), G.f(thr));
        CHECK(r == 0.0f || r == 1.0f, S(r));
    });
    ADV("rk_bloom_weight_soft_knee", {
        const float y = G.f(kHdr), t = G.f(thr), k = G.f(thr);
        const float r = rk_bloom_weight_soft_knee(y, t, k);
        const float ys = bloom_ref_sanitize(y), ts = bloom_ref_sanitize(t), ks = std::min(bloom_ref_sanitize(k), ts);
        // 0 at or below T - K; 1 at or above T + K (when above T - K: at K = 0, y = T is the hard step's 0).
        CHECK(within(r, 0.0f, 1.0f) && (ys > ts - ks || r == 0.0f) && (ys < ts + ks || ys <= ts - ks || r == 1.0f),
              S(r));
    });
    ADV("rk_bloom_weight_subtract", {
        const float y = G.f(kHdr), t = G.f(thr), k = G.f(thr);
        const float r = rk_bloom_weight_subtract(y, t, k);
        CHECK(within(r, 0.0f, 1.0f) &&
                  (bloom_ref_sanitize(y) > rk_bloom_cutoff(t, k, RK_BLOOM_MODE_SUBTRACT) || r == 0.0f),
              S(r));
    });
    ADV("rk_bloom_weight", {
        const float y = G.f(kHdr), t = G.f(thr), k = G.f(thr);
        const int mode = G.i({0, 1, 2});
        const float r = rk_bloom_weight(y, t, k, mode);
        CHECK(within(r, 0.0f, 1.0f) && (bloom_ref_sanitize(y) > rk_bloom_cutoff(t, k, mode) || r == 0.0f), S(r));
    });
    // Bright passes: never brighter than the sanitised input; 0 at or below the cutoff.
    auto bright_ok = [](vec3 c, vec3 r, float cutoff) {
        const vec3 sc = rk_bloom_sanitize(c);
        return within(r, 0.0f, RK_HDR_MAX) && r.x <= sc.x && r.y <= sc.y && r.z <= sc.z &&
               (rk_bloom_luminance(c) > cutoff || r == vec3(0.0f));
    };
    ADV("rk_bloom_bright_pass_hard", {
        const vec3 c = G.v3(kHdr3);
        const float t = G.f(thr);
        const vec3 r = rk_bloom_bright_pass_hard(c, t);
        CHECK(bright_ok(c, r, rk_bloom_cutoff(t, 0.0f, RK_BLOOM_MODE_HARD)), S(r));
    });
    ADV("rk_bloom_bright_pass_soft_knee", {
        const vec3 c = G.v3(kHdr3);
        const float t = G.f(thr), k = G.f(thr);
        const vec3 r = rk_bloom_bright_pass_soft_knee(c, t, k);
        CHECK(bright_ok(c, r, rk_bloom_cutoff(t, k, RK_BLOOM_MODE_SOFT_KNEE)), S(r));
    });
    ADV("rk_bloom_bright_pass_subtract", {
        const vec3 c = G.v3(kHdr3);
        const float t = G.f(thr), k = G.f(thr);
        const vec3 r = rk_bloom_bright_pass_subtract(c, t, k);
        CHECK(bright_ok(c, r, rk_bloom_cutoff(t, k, RK_BLOOM_MODE_SUBTRACT)), S(r));
    });
    ADV("rk_bloom_bright_pass", {
        const vec3 c = G.v3(kHdr3);
        const float t = G.f(thr), k = G.f(thr);
        const int mode = G.i({0, 1, 2});
        const vec3 r = rk_bloom_bright_pass(c, t, k, mode);
        CHECK(bright_ok(c, r, rk_bloom_cutoff(t, k, mode)), S(r));
    });
    ADV("rk_bloom_karis_weight", {
        const float r = rk_bloom_karis_weight(G.v3(kHdr3));
        CHECK(within(r, 9.99e-19f, 1.0f), S(r));
    });
    ADV("rk_bloom_weighted_average", {
        const vec3 c[4] = {G.v3(kHdr3), G.v3(kHdr3), G.v3(kHdr3), G.v3(kHdr3)};
        const vec4 w = G.v4(w4);
        const float wf[4] = {std::min(w.x, 1.0f), std::min(w.y, 1.0f), std::min(w.z, 1.0f), std::min(w.w, 1.0f)};
        const vec3 r = rk_bloom_weighted_average(c[0], c[1], c[2], c[3], w);
        const std::string e = weighted_average_error(c, wf, r);
        CHECK(e.empty(), e);
    });
    ADV("rk_bloom_karis_average", {
        const vec3 c[4] = {G.v3(kHdr3), G.v3(kHdr3), G.v3(kHdr3), G.v3(kHdr3)};
        const vec4 w = G.v4(w4);
        const float wf[4] = {w.x, w.y, w.z, w.w};  // the colours with a positive filter weight count
        const vec3 r = rk_bloom_karis_average(c[0], c[1], c[2], c[3], w);
        const std::string e = weighted_average_error(c, wf, r);
        CHECK(e.empty(), e);
    });
    ADV("rk_bloom_karis_average (equal colours)", {
        const vec3 c = G.v3(kHdr3);
        const vec4 w = G.v4(w4);
        const vec3 r = rk_bloom_karis_average(c, c, c, c, w);
        const vec3 sc = rk_bloom_sanitize(c);
        const bool weighted =
            bloom_ref_sanitize(w.x) + bloom_ref_sanitize(w.y) + bloom_ref_sanitize(w.z) + bloom_ref_sanitize(w.w) >
            0.0f;
        const vec3 lo = sc * (1.0f - 1e-6f) - vec3(RK_FLT_MIN), hi = sc * (1.0f + 1e-6f) + vec3(RK_FLT_MIN);
        CHECK(!weighted || (within(r.x, lo.x, hi.x) && within(r.y, lo.y, hi.y) && within(r.z, lo.z, hi.z)), S(r));
    });
    const Floats sizes = kAll.mark({1.0f, 65536.0f, 2.0f, 4096.0f});
    ADV("rk_bloom_source_texel", {
        const float src = G.f(sizes);
        const float r = CALL(rk_bloom_source_texel, G.f(kAll), G.f(sizes), src);
        const float sc = src > 1.0f ? std::min(src, 65536.0f) : 1.0f;
        CHECK(within(r, -0.5f, sc - 0.5f), S(r));
    });
    ADV("rk_bloom_bilinear_weights", {
        const vec4 r = rk_bloom_bilinear_weights(G.v2(Vecs::all()));
        CHECK(within(r, 0.0f, 1.0f) && std::abs(double(r.x) + r.y + r.z + r.w - 1.0) <= 2.4e-7, S(r));
    });
    ADV("rk_bloom_sum_levels", {
        const vec3 r = CALL(rk_bloom_sum_levels, G.v3(kHdr3), G.v3(kHdr3), G.v3(kHdr3), G.v3(kHdr3), G.v4(w4));
        CHECK(within(r, 0.0f, RK_HDR_MAX), S(r));
    });
    ADV("rk_bloom_composite_add", {
        const vec3 r = CALL(rk_bloom_composite_add, G.v3(kHdr3), G.v3(kHdr3), G.f(thr));
        CHECK(within(r, 0.0f, RK_HDR_MAX), S(r));
    });
    ADV("rk_bloom_composite_mix", {
        const vec3 r = CALL(rk_bloom_composite_mix, G.v3(kHdr3), G.v3(kHdr3), G.f(thr));
        CHECK(within(r, 0.0f, RK_HDR_MAX), S(r));
    });
    ADV("rk_bloom_composite_conserve", {
        const vec3 r = CALL(rk_bloom_composite_conserve, G.v3(kHdr3), G.v3(kHdr3), G.v3(kHdr3), G.f(thr));
        CHECK(within(r, 0.0f, RK_HDR_MAX), S(r));
    });
    ADV("rk_bloom_composite", {
        const vec3 r = CALL(rk_bloom_composite, G.v3(kHdr3), G.v3(kHdr3), G.v3(kHdr3), G.f(thr), G.i({0, 1, 2}));
        CHECK(within(r, 0.0f, RK_HDR_MAX), S(r));
    });
}

// ---------------------------------------------------------------------------------------------
// C++ helpers of bloom.hpp.
BloomImage bloom_image(rktest::adv::Gen& G, int w, int h, const Vecs& values)
{
    BloomImage img(w, h);
    for (vec3& p : img.pixels) p = G.v3(values);
    return img;
}

TEST(Adversarial, BloomHpp)
{
    const Floats sigma = kAll.mark({3.0f, 1e4f, 1e-20f});
    ADV_N("gaussian_weights", kRows / 2, 2, {
        const float s = G.f(sigma);
        const int r = G.uniform() < 0.99 ? static_cast<int>(G.index(40)) - 2 : G.i({4096, 4097, 0});
        Status st;
        const std::vector<float> w = gaussian_weights(s, r, &st);
        const bool valid = s > 0.0f && s <= 1e4f && r >= 0 && r <= 4096;
        CHECK(st.ok() == valid && w.size() == (valid ? static_cast<size_t>(r) + 1 : 0u), st.message);
        double sum = 0.0;
        bool ok = true;
        for (size_t i = 0; i < w.size(); ++i) {
            sum += (i == 0 ? 1.0 : 2.0) * w[i];
            ok = ok && within(w[i], 0.0f, 1.0f);
        }
        CHECK(ok && (w.empty() || std::abs(sum - 1.0) <= 1e-6), std::to_string(sum));
    });
    const Floats tapw = Floats::range(0.0f, 1e30f).mark({1.0f});
    const Floats sigmas = Floats::range(0.01f, 100.0f);
    ADV_N("linear_sampled_taps", kRows / 8, 8, {
        std::vector<float> w = G.uniform() < 0.5 ? gaussian_weights(G.f(sigmas), static_cast<int>(G.index(30)))
                                                 : std::vector<float>(G.index(17));
        for (float& x : w) {
            if (G.uniform() < 0.5) x = G.f(tapw);
        }
        const std::vector<BloomTap> t = linear_sampled_taps(w);
        CHECK(linear_tap_fetches(t) == (t.empty() ? 0 : 2 * static_cast<int>(t.size()) - 1), std::to_string(t.size()));
        for (size_t i = 1; i < t.size(); ++i) {
            const float base = static_cast<float>(2 * i - 1);
            CHECK(within(t[i].offset, base, base + 1.0f) && finite(t[i].weight) && t[i].weight >= 0.0f,
                  S(vec2(t[i].offset, t[i].weight)));
        }
    });
    ADV("bloom_chain", {
        const int w = G.uniform() < 0.9 ? static_cast<int>(G.index(70000)) - 2 : G.i({65536, 65537});
        const int h = G.uniform() < 0.9 ? static_cast<int>(G.index(70000)) - 2 : G.i({1, 65536});
        const int div = G.uniform() < 0.8 ? 1 << G.index(16) : G.i({1, 8, 32768});
        const int levels = G.uniform() < 0.9 ? static_cast<int>(G.index(18)) : G.i({1, 4, 16});
        Status st;
        const BloomChain c = bloom_chain(w, h, div, levels, &st);
        const bool valid = w >= 1 && h >= 1 && w <= 65536 && h <= 65536 && div >= 1 && div <= 32768 &&
                           (div & (div - 1)) == 0 && levels >= 1 && levels <= 16;
        CHECK(st.ok() == valid && c.levels.size() == (valid ? static_cast<size_t>(levels) : 0u), st.message);
        ivec2 prev(w, h);
        for (size_t i = 0; i < c.downsamples.size(); ++i) {
            const ivec2 d = c.downsamples[i];
            const bool same = i == 0 && div == 1;
            CHECK(d.x >= 1 && d.y >= 1 && (same ? d == prev : d == ivec2((prev.x + 1) / 2, (prev.y + 1) / 2)),
                  std::to_string(d.x) + "x" + std::to_string(d.y));
            prev = d;
        }
    });
    auto random_params = [&](rktest::adv::Gen& G) {
        BloomParams p;
        p.threshold = G.f(kAll);
        p.knee = G.f(kAll);
        p.mode = G.i({0, 1, 2});
        p.karis = G.uniform() < 0.5;
        p.sigma = G.f(sigma);
        p.radius = G.i({0, 3, 9, 30, 31});
        p.first_div = G.i({1, 2, 4, 8, 6});
        p.levels = G.i({1, 2, 3, 4});
        p.composite = G.i({0, 1, 2});
        p.strength = G.f(kAll);
        p.level_weights = G.v4(Vecs::all());
        return p;
    };
    ADV("validate_bloom_params", {
        const BloomParams p = random_params(G);
        Status st;
        const bool ok = validate_bloom_params(p, &st);
        const bool want = p.sigma > 0.0f && p.sigma <= 1e4f && p.radius >= 0 && p.radius <= 30 && p.first_div >= 1 &&
                          p.first_div <= 32768 && (p.first_div & (p.first_div - 1)) == 0 && p.levels >= 1 &&
                          p.levels <= 4 && p.mode >= 0 && p.mode <= 2 && p.composite >= 0 && p.composite <= 2;
        CHECK(ok == want && st.ok() == want, st.message);
    });
    ADV("BloomParams::thesis, ::recommended", {
        (void)G;
        CHECK(validate_bloom_params(BloomParams::thesis()) && validate_bloom_params(BloomParams::recommended()), "");
    });
    ADV("bloom_level_weights", {
        const BloomParams p = random_params(G);
        const vec4 w = bloom_level_weights(p);
        const float sum = w.x + w.y + w.z + w.w;
        bool zero_beyond = true;
        for (int i = std::max(p.levels, 0); i < 4; ++i) zero_beyond = zero_beyond && w[i] == 0.0f;
        CHECK(within(w, 0.0f, RK_BLOOM_WEIGHT_MAX) && zero_beyond &&
                  (p.composite == RK_BLOOM_COMPOSITE_ADD || sum == 0.0f || std::abs(sum - 1.0f) <= 1e-6f),
              S(w));
    });
    const Vecs finite_px = Vecs::of(Floats::range(-RK_HDR_MAX, RK_HDR_MAX));
    ADV("BloomImage(w, h), at", {
        const int w = G.one_of({-3, -1, 0, 1, 2, 5}), h = G.one_of({-3, -1, 0, 1, 2, 5});
        BloomImage img(w, h);
        const bool empty = w < 1 || h < 1;
        CHECK(img.width == (empty ? 0 : w) && img.height == (empty ? 0 : h) &&
                  img.pixels.size() == static_cast<size_t>(img.width * img.height),
              std::to_string(img.width));
        if (!empty) {
            const vec3 c = G.v3(Vecs::all());
            img.at(img.width - 1, img.height - 1) = c;
            const vec3 r = static_cast<const BloomImage&>(img).at(img.width - 1, img.height - 1);
            CHECK(std::memcmp(&r, &c, sizeof r) == 0, S(r));
        }
    });
    ADV_N("bloom_texel", kRows / 10, 10, {
        const BloomImage img =
            bloom_image(G, 1 + static_cast<int>(G.index(4)), 1 + static_cast<int>(G.index(4)), finite_px);
        for (int k = 0; k < 10; ++k) {
            const int x = G.i({-1, 0, 1, 2, 3, 4}), y = G.i({-1, 0, 1, 2, 3, 4});
            const bool border = G.uniform() < 0.5;
            const vec3 r = bloom_texel(img, x, y, border ? BloomWrap::border_black : BloomWrap::clamp_to_edge);
            const bool inside = x >= 0 && y >= 0 && x < img.width && y < img.height;
            const vec3 want = inside   ? img.at(x, y)
                              : border ? vec3(0.0f)
                                       : img.at(std::clamp(x, 0, img.width - 1), std::clamp(y, 0, img.height - 1));
            CHECK(r == want, S(r));
        }
    });
    const Vecs uv = Vecs::of(Floats::range(-1e6f, 1e6f).mark({0.0f, 1.0f, 0.5f}));
    ADV_N("sample_bilinear", kRows / 10, 10, {
        const BloomImage img =
            bloom_image(G, 1 + static_cast<int>(G.index(5)), 1 + static_cast<int>(G.index(5)), finite_px);
        vec3 lo(RK_FLT_MAX), hi(-RK_FLT_MAX);
        for (const vec3& p : img.pixels) {
            lo = min(lo, p);
            hi = max(hi, p);
        }
        for (int k = 0; k < 10; ++k) {
            const bool border = G.uniform() < 0.5;
            if (border) {
                lo = min(lo, vec3(0.0f));
                hi = max(hi, vec3(0.0f));
            }
            const vec3 r = sample_bilinear(img, G.v2(uv), border ? BloomWrap::border_black : BloomWrap::clamp_to_edge);
            // Rounding: 1e-6 relative, and the denormal grid's spacing for tiny values.
            const vec3 slack = 1e-6f * max(abs(lo), abs(hi)) + vec3(1e-44f);
            CHECK(finite(r) && r.x >= lo.x - slack.x && r.y >= lo.y - slack.y && r.z >= lo.z - slack.z &&
                      r.x <= hi.x + slack.x && r.y <= hi.y + slack.y && r.z <= hi.z + slack.z,
                  S(r));
        }
    });
    ADV_N("bloom_reduce", kRows / 10, 10, {
        const BloomImage img =
            bloom_image(G, 1 + static_cast<int>(G.index(4)), 1 + static_cast<int>(G.index(4)), kHdr3);
        const BloomReduction r = bloom_reduce(img, G.f(kAll));
        CHECK(within(r.max_luminance, 0.0f, RK_HDR_MAX) && r.count_above <= img.pixels.size(), S(r.max_luminance));
    });
    const Floats blur_sigmas = Floats::range(0.1f, 10.0f);
    ADV_N("bloom_blur_discrete", kRows / 10, 10, {
        const BloomImage img =
            bloom_image(G, 1 + static_cast<int>(G.index(5)), 1 + static_cast<int>(G.index(5)), finite_px);
        const std::vector<float> w = gaussian_weights(G.f(blur_sigmas), static_cast<int>(G.index(6)));
        const BloomImage out = bloom_blur_discrete(img, w, G.uniform() < 0.5);
        double wsum = w[0];
        for (size_t i = 1; i < w.size(); ++i) wsum += 2.0 * w[i];
        float lo = 0.0f, hi = 0.0f;
        for (const vec3& p : img.pixels) {
            lo = std::min(lo, std::min(std::min(p.x, p.y), p.z));
            hi = std::max(hi, std::max(std::max(p.x, p.y), p.z));
        }
        for (const vec3& p : out.pixels) {
            CHECK(within(p, static_cast<float>(lo * wsum * (1.0 + 1e-6)), static_cast<float>(hi * wsum * (1.0 + 1e-6))),
                  S(p));
        }
    });
    // Whole blooms of tiny images; every input pixel counts.
    ADV_N("bloom_reference", kRows / 25, 25, {
        const BloomImage img =
            bloom_image(G, 1 + static_cast<int>(G.index(9)), 1 + static_cast<int>(G.index(9)), kHdr3);
        BloomParams p = random_params(G);
        if (G.uniform() < 0.7) {
            p.sigma = 1.5f;
            p.radius = static_cast<int>(G.index(4));
        }
        Status st;
        const BloomResult r = bloom_reference(img, p, &st);
        CHECK(st.ok() == validate_bloom_params(p) && (st.ok() ? r.output.width == img.width : r.output.width == 0),
              st.message);
        for (const vec3& o : r.output.pixels) {
            if (r.composited) {
                CHECK(within(o, 0.0f, RK_HDR_MAX), S(o));
            }
        }
    });
}

// ---------------------------------------------------------------------------------------------
/// Orthonormal right-handed within `ulps` ulp: unit columns, pairwise dot products, det = +1.
bool orthonormal(const mat3& m, double ulps)
{
    const double tol = ulps * kUlp1;
    for (int i = 0; i < 3; ++i) {
        if (!finite(m[i]) || std::abs(len(m[i]) - 1.0) > tol) return false;
        const vec3 a = m[i], b = m[(i + 1) % 3];
        if (std::abs(double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z) > tol) return false;
    }
    const vec3 c = cross(m[0], m[1]);
    return double(c.x) * m[2].x + double(c.y) * m[2].y + double(c.z) * m[2].z > 0.0;
}

TEST(Adversarial, Paraboloid)
{
    const Floats hemi = kAny.mark({0.0f, -RK_FLT_MIN, 1.0f, -1.0f});
    const Floats guard = kAny.mark({RK_PARABOLOID_GUARD_MIN, 1.0f, 0.96875f});
    const Floats half = kAny.mark({1.0f, 16777216.0f, 256.0f});
    const Vecs dirs = Vecs::any();
    const Vecs st2 = Vecs::of(kAny.mark({RK_PARABOLOID_ST_MAX, 1.0f}));
    ADV("rk_paraboloid_hemi_sign", {
        const float h = G.f(hemi);
        const float r = rk_paraboloid_hemi_sign(h);
        CHECK(r == (h <= -RK_FLT_MIN ? -1.0f : 1.0f), S(r));
    });
    ADV("rk_paraboloid_max_abs", {
        const vec3 v = G.v3(dirs);
        const float r = rk_paraboloid_max_abs(v);
        CHECK(r == max_abs(v), S(r));
    });
    ADV("rk_paraboloid_prescale", {
        const float m = std::abs(G.f(kAny));
        const float r = rk_paraboloid_prescale(m);
        CHECK((r == 1.0f || r == 0x1p-100f) && m * r <= 1e30f && (m < RK_FLT_MIN || 1.0f / (m * r) >= RK_FLT_MIN),
              S(r));
    });
    ADV("rk_paraboloid_normalize", {
        const vec3 v = G.v3(dirs), fb = G.v3(dirs);
        const vec3 r = rk_paraboloid_normalize(v, fb);
        const std::string e = normalize_error(v, fb, r, true);
        CHECK(e.empty(), e);
    });
    ADV("rk_paraboloid_encode", {
        const vec3 d = G.v3(dirs);
        const float h = G.f(hemi);
        const vec2 r = rk_paraboloid_encode(d, h);
        CHECK(within(r, -1e30f, 1e30f), S(r));
        // The hemisphere maps into the unit disk.
        const vec3 n = rk_paraboloid_normalize(d, vec3(0.0f, 0.0f, rk_paraboloid_hemi_sign(h)));
        CHECK(rk_paraboloid_hemi_sign(h) * n.z < 0.0f || len(r) <= 1.0 + 2.0 * kUlp1, S(r));
    });
    ADV("rk_paraboloid_decode", {
        const vec3 r = CALL(rk_paraboloid_decode, G.v2(st2), G.f(hemi));
        CHECK(std::abs(len(r) - 1.0) <= 2.0 * kUlp1, S(r));
    });
    ADV("rk_paraboloid_encode_differential", {
        const vec2 r = CALL(rk_paraboloid_encode_differential, G.v3(dirs), G.v3(dirs), G.f(hemi));
        CHECK(within(r, -4e30f, 4e30f), S(r));
    });
    ADV("rk_paraboloid_solid_angle_density", {
        const float r = rk_paraboloid_solid_angle_density(G.v2(st2));
        CHECK(within(r, 0.0f, 4.0f), S(r));
    });
    ADV("rk_paraboloid_sweet_circle", {
        const float r = rk_paraboloid_sweet_circle(G.v2(st2));
        CHECK(r == 0.0f || r == 1.0f, S(r));
    });
    ADV("rk_paraboloid_uv", {
        const vec2 st = G.v2(st2);
        const float g = G.f(guard);
        const vec2 r = rk_paraboloid_uv(st, g);
        const float gc = 0.5f * clamp(g, RK_PARABOLOID_GUARD_MIN, 1.0f);
        const float bx = gc * std::min(std::abs(st.x), RK_PARABOLOID_ST_MAX),
                    by = gc * std::min(std::abs(st.y), RK_PARABOLOID_ST_MAX);
        CHECK(
            std::abs(r.x - 0.5f) <= bx * (1.0f + 1e-6f) + 3e-8f && std::abs(r.y - 0.5f) <= by * (1.0f + 1e-6f) + 3e-8f,
            S(r));
    });
    ADV("rk_paraboloid_frame_angle", {
        const float r = rk_paraboloid_frame_angle(G.v3(dirs));
        CHECK(r > -RK_PI && r <= RK_PI, S(r));
    });
    const Floats theta = kAny.mark({RK_PI, -RK_PI});
    ADV("rk_paraboloid_frame_vertical", {
        const mat3 m = rk_paraboloid_frame_vertical(G.f(theta));
        CHECK(within(m[0], -1.0f, 1.0f) && within(m[1], -1.0f, 1.0f) && within(m[2], -1.0f, 1.0f), S(m[0]) + S(m[2]));
    });
    ADV("rk_paraboloid_frame", {
        const vec3 n = G.v3(dirs), up = G.v3(dirs);
        const float h = G.f(hemi);
        const mat3 m = rk_paraboloid_frame(n, up, h);
        CHECK(orthonormal(m, 4.0), S(m[0]) + S(m[1]) + S(m[2]));
        // Z = hemi n (normalised; n = 0 counts as -z).
        const vec3 z = rk_paraboloid_hemi_sign(h) * rk_paraboloid_normalize(n, vec3(0.0f, 0.0f, -1.0f));
        CHECK(m[2] == z, S(m[2]));
    });
    const Floats lod = kAny.mark({16.0f, 0.0f, 2.5f});
    ADV("rk_paraboloid_filter_footprint", {
        const float r = rk_paraboloid_filter_footprint(G.f(lod));
        CHECK(within(r, 0.5f, 32768.0f), S(r));
    });
    const Floats footprint = kAny.mark({0.5f, 16777216.0f});
    ADV("rk_dual_paraboloid_guard_scale", {
        const float r = CALL(rk_dual_paraboloid_guard_scale, G.f(half), G.f(footprint));
        CHECK(within(r, RK_PARABOLOID_GUARD_MIN, 1.0f), S(r));
    });
    ADV("rk_dual_paraboloid_hemi", {
        const vec3 d = G.v3(dirs);
        const float r = rk_dual_paraboloid_hemi(d);
        CHECK(r == (d.z > -RK_FLT_MIN ? 1.0f : -1.0f), S(r));
    });
    ADV("rk_dual_paraboloid_uv_half", {
        const vec2 r = CALL(rk_dual_paraboloid_uv_half, G.v3(dirs), G.f(guard), G.f(hemi));
        CHECK(finite(r), S(r));
    });
    ADV("rk_dual_paraboloid_uv", {
        const vec3 d = G.v3(dirs);
        const float g = G.f(guard);
        const vec2 r = rk_dual_paraboloid_uv(d, g);
        // |st| <= 1: u in [0.25 (1 - g), 0.25 (1 + g)] (+ 0.5 for the -z half), v in [0.5 (1 - g), 0.5 (1 + g)].
        const float gc = clamp(g, RK_PARABOLOID_GUARD_MIN, 1.0f), off = rk_dual_paraboloid_hemi(d) > 0.0f ? 0.0f : 0.5f;
        const float e = 2.4e-7f;
        CHECK(within(r.x, off + 0.25f * (1.0f - gc) - e, off + 0.25f * (1.0f + gc) + e) &&
                  within(r.y, 0.5f * (1.0f - gc) - e, 0.5f * (1.0f + gc) + e),
              S(r));
    });
    const Floats band = kAll.mark({0.0f, 1.0f, 0.01f});
    ADV("rk_dual_paraboloid_seam_weight", {
        const float r = CALL(rk_dual_paraboloid_seam_weight, G.v3(dirs), G.f(band));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_dual_paraboloid_uv_differential", {
        vec3 d = G.v3(dirs);
        const vec3 dd = G.v3(dirs);
        const float g = G.f(guard);
        const vec2 r = rk_dual_paraboloid_uv_differential(d, dd, g);
        for (int i = 0; i < 3; ++i) d[i] = std::abs(d[i]) < RK_FLT_MIN ? 0.0f : d[i];  // denormals count as 0
        // |result| <= 0.5 g |d_dir| / |dir| (d_dir / max|dir| is clamped to 1e18 first).
        const double m = max_abs(d);
        const double bound =
            m < RK_FLT_MIN ? 0.0 : 0.5 * clamp(g, RK_PARABOLOID_GUARD_MIN, 1.0f) * len(dd) / m / (len(d) / m);
        CHECK(finite(r) && len(r) <= bound * (1.0 + 1e-5) + 1e-30, S(r));
    });
    const Vecs atlas_uv = Vecs::of(kAny.mark({0.5f, 0.25f, 0.75f, 0.0f, 1.0f}));
    ADV("rk_dual_paraboloid_dir", {
        const vec3 r = CALL(rk_dual_paraboloid_dir, G.v2(atlas_uv), G.f(guard));
        CHECK(std::abs(len(r) - 1.0) <= 2.0 * kUlp1, S(r));
    });
    const Floats lod16 = kAny.mark({16.0f});
    ADV("rk_paraboloid_lod_from_incidence", {
        const float r = CALL(rk_paraboloid_lod_from_incidence, G.f(kCos), G.f(lod16));
        CHECK(within(r, 0.0f, 16.0f), S(r));
    });
    ADV("rk_paraboloid_texel_angle", {
        const float r = CALL(rk_paraboloid_texel_angle, G.v2(st2), G.f(half), G.f(guard));
        CHECK(r > 0.0f && r <= 4096.0f, S(r));
    });
    const Floats lod_hi = kAny.mark({16.0f});
    const Floats cone = kAny.mark({1e-20f, 1e20f});
    ADV("rk_paraboloid_lod_for_cone", {
        const float lod_max = G.f(lod_hi);
        const float r = CALL(rk_paraboloid_lod_for_cone, G.v2(st2), G.f(cone), G.f(half), G.f(guard), lod_max);
        CHECK(within(r, 0.0f, clamp(lod_max, 0.0f, 16.0f)), S(r));
    });
    const Floats depth = kAny.mark({RK_PARABOLOID_POS_MAX, 1e6f, 1e-18f});
    ADV("rk_paraboloid_depth_encode", {
        const float r = CALL(rk_paraboloid_depth_encode, G.f(depth), G.f(depth), G.f(depth));
        CHECK(within(r, -1e6f, 1e6f), S(r));
    });
    ADV("rk_paraboloid_depth_decode", {
        const float r = CALL(rk_paraboloid_depth_decode, G.f(depth), G.f(depth), G.f(depth));
        CHECK(finite(r), S(r));
    });
    ADV("rk_paraboloid_project", {
        const vec3 p = G.v3(dirs);
        const vec4 r = CALL(rk_paraboloid_project, p, G.f(depth), G.f(depth), G.f(hemi), G.f(guard));
        CHECK(finite(r) && r.w == 1.0f, S(r));
        CHECK(p != vec3(0.0f) || r == vec4(0.0f, 0.0f, -2.0f, 1.0f), S(r));
    });
    ADV("rk_paraboloid_clip_distance", {
        const float r = CALL(rk_paraboloid_clip_distance, G.v3(dirs), G.f(hemi), G.f(guard));
        CHECK(finite(r), S(r));
    });
}

// ---------------------------------------------------------------------------------------------
TEST(Adversarial, EnvmapCorrection)
{
    const Vecs vecs = Vecs::of(kAny.mark({RK_ENVMAP_POS_MAX, 8.0f}));
    const Floats radius = kAny.mark({1e-18f, 1e18f, RK_ENVMAP_FAHLEN_D});
    const Floats sig_a = kAny.mark({RK_ENVMAP_FAHLEN_A, 1e6f, -1e6f}), sig_k = kAny.mark({RK_ENVMAP_FAHLEN_K});
    ADV("rk_envmap_clamp_pos", {
        const vec3 v = G.v3(vecs);
        const vec3 r = rk_envmap_clamp_pos(v);
        bool ok = within(r, -RK_ENVMAP_POS_MAX, RK_ENVMAP_POS_MAX);
        for (int i = 0; i < 3; ++i) ok = ok && (std::abs(v[i]) > RK_ENVMAP_POS_MAX || r[i] == v[i]);
        CHECK(ok, S(r));
    });
    ADV("rk_envmap_normalize", {
        const vec3 v = G.v3(Vecs::any()), fb = G.v3(Vecs::any());
        const vec3 r = rk_envmap_normalize(v, fb);
        const std::string e = normalize_error(v, fb, r, false);
        CHECK(e.empty(), e);
    });
    ADV("rk_envmap_angle", {
        const float r = rk_envmap_angle(G.f(kCos));
        CHECK(within(r, 0.0f, RK_PI), S(r));
    });
    const Floats angle = kAny.mark({0.0f, RK_HALF_PI, RK_PI, 0.9f});
    ADV("rk_envmap_sigmoid", {
        const float r = CALL(rk_envmap_sigmoid, G.f(angle), G.f(sig_a), G.f(sig_k));
        CHECK(within(r, 1.8e-35f, 1.0f), S(r));
    });
    ADV("rk_envmap_fahlen_weight", {
        const float r = CALL(rk_envmap_fahlen_weight, G.f(kCos), G.f(sig_a), G.f(sig_k));
        CHECK(within(r, 1.8e-35f, 1.0f), S(r));
    });
    ADV("rk_reflect_correct_sphere", {
        const vec3 r = CALL(rk_reflect_correct_sphere, G.v3(vecs), G.v3(vecs), G.f(radius));
        CHECK(finite(r), S(r));
    });
    ADV("rk_reflect_correct_plane_cos", {
        const vec3 rd = G.v3(vecs), n = G.v3(vecs), cp = G.v3(vecs);
        const vec3 r = CALL(rk_reflect_correct_plane_cos, rd, n, cp, G.f(radius));
        CHECK(finite(r), S(r));
        // N.R <= 0 (the clamped vectors' dot) or CP = 0: R itself.
        const vec3 rc = rk_envmap_clamp_pos(rd);
        const bool plain = dot(rk_envmap_clamp_pos(n), rc) <= 0.0f || cp == vec3(0.0f);
        CHECK(!plain || r == rc, S(r));
    });
    ADV("rk_reflect_correct_fahlen (6 arguments)", {
        const vec3 rd = G.v3(vecs), n = G.v3(vecs), cp = G.v3(vecs);
        const vec3 r = CALL(rk_reflect_correct_fahlen, rd, n, cp, G.f(radius), G.f(sig_a), G.f(sig_k));
        CHECK(finite(r) && (cp != vec3(0.0f) || r == rk_envmap_clamp_pos(rd)), S(r));
    });
    ADV("rk_reflect_correct_fahlen (thesis constants)", {
        const vec3 rd = G.v3(vecs), n = G.v3(vecs), cp = G.v3(vecs);
        const vec3 r = rk_reflect_correct_fahlen(rd, n, cp);
        CHECK(finite(r) && (cp != vec3(0.0f) || r == rk_envmap_clamp_pos(rd)), S(r));
    });
    ADV("rk_reflect_correct_plane", {
        const vec3 r = CALL(rk_reflect_correct_plane, G.v3(vecs), G.v3(vecs), G.v3(vecs), G.v3(vecs), G.f(radius));
        CHECK(finite(r), S(r));
    });
    ADV("rk_reflect_correct_box", {
        const vec3 r = CALL(rk_reflect_correct_box, G.v3(vecs), G.v3(vecs), G.v3(vecs), G.v3(vecs), G.v3(vecs));
        CHECK(finite(r), S(r));
    });
}

// ---------------------------------------------------------------------------------------------
TEST(Adversarial, WindowGlass)
{
    const Floats panes = kAny.mark({0.0f, 1.0f, 2.0f, 1e6f});
    ADV("rk_window_glass_cos", {
        const float r = CALL(rk_window_glass_cos, G.v3(Vecs::any()), G.v3(Vecs::any()));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_window_glass_reflectance_exact", {
        const float r = CALL(rk_window_glass_reflectance_exact, G.f(kCos), G.f(kEta), G.f(panes));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_window_glass_reflectance_fast", {
        const float c = G.f(kCos);
        const vec3 params = rk_fresnel_fast_params(G.f(kEta));
        const float r = rk_window_glass_reflectance_fast(c, params, G.f(panes));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_window_glass_combine", {
        const vec3 r = CALL(rk_window_glass_combine, G.v3(kHdr3), G.v3(kHdr3), G.f(kAny), G.v3(Vecs::any()));
        CHECK(finite(r) && within(r, 0.0f, RK_FLT_MAX), S(r));
    });
    const Vecs taus = Vecs::of(kAny.mark({0.0f, 1.0f}));
    ADV("rk_window_glass_slab_absorbing", {
        const vec2 rsp = G.v2(Vecs::any());
        const vec3 tau = G.v3(taus);
        vec3 refl(0.0f), trans(0.0f);
        rk_window_glass_slab_absorbing(rsp, tau, refl, trans);
        CHECK(within(refl, 0.0f, 1.0f) && within(trans, 0.0f, 1.0f), S(refl) + S(trans));
    });
}

// ---------------------------------------------------------------------------------------------
// C++ helpers of paraboloid.hpp: small images, cubes and maps of adversarial texels; every
// lookup, texel read or baked texel counts as an input.
EnvImage env_image(rktest::adv::Gen& G, int w, int h, const Vecs& values)
{
    EnvImage img(w, h);
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) img.set(x, y, G.v3(values));
    }
    return img;
}

/// [min, max] over the channels of an image (a channel-agnostic bound is enough for convexity).
vec2 value_range(const std::vector<float>& v)
{
    if (v.empty()) return vec2(0.0f);
    return vec2(*std::min_element(v.begin(), v.end()), *std::max_element(v.begin(), v.end()));
}

bool in_range(vec3 c, vec2 range)
{
    const float slack = 1e-6f * std::max(std::abs(range.x), std::abs(range.y)) + 1e-44f;
    return within(c, range.x - slack, range.y + slack);
}

EnvCubeMap env_cube(rktest::adv::Gen& G, int size, const Vecs& values)
{
    EnvCubeMap cube;
    cube.size = size;
    for (EnvImage& f : cube.faces) f = env_image(G, size, size, values);
    return cube;
}

vec2 cube_range(const EnvCubeMap& cube)
{
    vec2 r(RK_FLT_MAX, -RK_FLT_MAX);
    for (const EnvImage& f : cube.faces) {
        const vec2 fr = value_range(f.rgb);
        r = vec2(std::min(r.x, fr.x), std::max(r.y, fr.y));
    }
    return r;
}

TEST(Adversarial, ParaboloidHpp)
{
    const Vecs texels = Vecs::of(Floats::range(-1e30f, 1e30f));
    const Floats guards = Floats::range(RK_PARABOLOID_GUARD_MIN, 1.0f);
    ADV("EnvImage(w, h), texel, set", {
        const int w = G.one_of({-3, -1, 0, 1, 2, 5}), h = G.one_of({-3, -1, 0, 1, 2, 5});
        EnvImage img(w, h);
        const bool empty = w < 1 || h < 1;
        CHECK(img.width == (empty ? 0 : w) && img.height == (empty ? 0 : h) &&
                  img.rgb.size() == static_cast<size_t>(img.width * img.height) * 3u,
              std::to_string(img.width));
        if (!empty) {
            const vec3 c = G.v3(Vecs::all());
            img.set(img.width - 1, img.height - 1, c);
            const vec3 r = img.texel(img.width - 1, img.height - 1);
            CHECK(std::memcmp(&r, &c, sizeof r) == 0, S(r));
        }
    });
    const Vecs dirs = Vecs::any();
    const Vecs uv = Vecs::of(Floats::range(-1e6f, 1e6f).mark({0.0f, 1.0f, 0.5f}));
    ADV_N("sample_image_bilinear", kRows / 10, 10, {
        const EnvImage img = env_image(G, 1 + static_cast<int>(G.index(5)), 1 + static_cast<int>(G.index(5)), texels);
        const vec2 range = value_range(img.rgb);
        for (int k = 0; k < 10; ++k) {
            const vec3 r = sample_image_bilinear(img, G.v2(uv));
            CHECK(finite(r) && in_range(r, range), S(r));
        }
    });
    const Vecs any_texels = Vecs::of(Floats::any());
    ADV_N("downsample_box", kRows / 10, 16, {
        const int w = static_cast<int>(G.index(9)), h = static_cast<int>(G.index(9));
        const EnvImage img = env_image(G, w, h, any_texels);
        Status st;
        const EnvImage d = downsample_box(img, &st);
        const bool valid = w >= 2 && h >= 2 && w % 2 == 0 && h % 2 == 0;
        CHECK(st.ok() == valid && d.width == (valid ? w / 2 : 0) && d.height == (valid ? h / 2 : 0), st.message);
        for (int y = 0; y < d.height; ++y) {
            for (int x = 0; x < d.width; ++x) {
                for (int c = 0; c < 3; ++c) {
                    const float a = img.texel(2 * x, 2 * y)[c], b = img.texel(2 * x + 1, 2 * y)[c];
                    const float e = img.texel(2 * x, 2 * y + 1)[c], f = img.texel(2 * x + 1, 2 * y + 1)[c];
                    const float lo = std::min(std::min(a, b), std::min(e, f)),
                                hi = std::max(std::max(a, b), std::max(e, f));
                    const float v = d.texel(x, y)[c];
                    CHECK(finite(v) && in_range(vec3(v), vec2(lo, hi)), S(v));
                }
            }
        }
    });
    ADV_N("generate_env_mips", kRows / 20, 32, {
        const int w = 1 << G.index(4), h = 1 << G.index(4), levels = G.one_of({-1, 0, 1, 2, 3, 4});
        const EnvImage img = env_image(G, w, h, any_texels);
        Status st;
        const std::vector<EnvImage> mips = generate_env_mips(img, levels, &st);
        bool fits = levels >= 1;
        for (int l = 1; l < levels; ++l)
            fits = fits && (w >> (l - 1)) % 2 == 0 && (h >> (l - 1)) % 2 == 0 && (w >> l) >= 1 && (h >> l) >= 1;
        CHECK(st.ok() == fits && mips.size() == (fits ? static_cast<size_t>(levels) : 0u), st.message);
        const vec2 range = value_range(img.rgb);
        for (const EnvImage& m : mips) {
            for (float v : m.rgb) CHECK(finite(v) && in_range(vec3(v), range), S(v));
        }
    });
    ADV("env_cube_valid", {
        EnvCubeMap cube;
        cube.size = G.one_of({-1, 0, 1, 2, 3});
        const int broken = static_cast<int>(G.index(8));
        for (int f = 0; f < 6; ++f)
            cube.faces[static_cast<size_t>(f)] = EnvImage(f == broken ? cube.size + 1 : cube.size, cube.size);
        CHECK(env_cube_valid(cube) == (cube.size >= 1 && broken >= 6), std::to_string(cube.size));
    });
    const Floats sc = kAny.mark({1.0f, -1.0f});
    ADV("cube_face_direction", {
        const int face = static_cast<int>(G.index(6));
        const float a = G.f(sc), b = G.f(sc);
        const vec3 r = cube_face_direction(face, a, b);
        CHECK(finite(r) && max_abs(r) == std::max(1.0f, std::max(std::abs(a), std::abs(b))), S(r));
    });
    ADV("cube_face_select", {
        const vec3 d = G.v3(dirs);
        float s_ = 0.0f, t_ = 0.0f;
        const int face = cube_face_select(d, s_, t_);
        CHECK(face >= 0 && face <= 5 && within(s_, -1.0f, 1.0f) && within(t_, -1.0f, 1.0f), S(vec2(s_, t_)));
        CHECK(max_abs(d) > 0.0f || (face == 4 && s_ == 0.0f && t_ == 0.0f), std::to_string(face));
    });
    ADV("cube_texel_direction", {
        const int size = 1 + static_cast<int>(G.u(0u, 65535u));
        const int i = static_cast<int>(G.u(0u, static_cast<uint>(size - 1))),
                  j = static_cast<int>(G.u(0u, static_cast<uint>(size - 1)));
        const vec3 r = cube_texel_direction(static_cast<int>(G.index(6)), i, j, size);
        CHECK(std::abs(len(r) - 1.0) <= 4.0 * kUlp1, S(r));
    });
    // Small cubes of finite texels; lookups along adversarial directions.
    ADV_N("sample_cube_map", kRows / 20, 20, {
        const EnvCubeMap cube = env_cube(G, 1 + static_cast<int>(G.index(4)), texels);
        const vec2 range = cube_range(cube);
        for (int k = 0; k < 20; ++k) {
            const vec3 r = sample_cube_map(cube, G.v3(dirs));
            CHECK(finite(r) && in_range(r, range), S(r));
        }
    });
    auto self = [](vec3 d) { return d; };
    ADV_N("bake_cube_map", 2500, 1, {
        const int size = G.one_of({-1, 0, 1, 2, 3, 4, 65537});
        const int ss = G.one_of({-1, 0, 1, 2, 3, 65});
        Status st;
        const EnvCubeMap cube = bake_cube_map(size, self, ss, &st);
        const bool valid = size >= 1 && size <= 65536 && ss >= 1 && ss <= 64;
        CHECK(st.ok() == valid && cube.size == (valid ? size : 0) && (!valid || env_cube_valid(cube)), st.message);
        for (const EnvImage& f : cube.faces) {
            for (float v : f.rgb) CHECK(within(v, -1.0f, 1.0f), S(v));
        }
        TL.rows += 6L * cube.size * cube.size * ss * ss - 1;  // every evaluation of env is an input
    });
    const Floats max_lods = kAny.mark({0.0f, 16.0f});
    const Floats fades = kAll.mark({0.0f, 65536.0f});
    ADV("dual_paraboloid_guard_scale", {
        DualParaboloidBakeOptions o;
        o.half_size = static_cast<int>(G.u(0u, 0x7FFFFFFFu)) * (G.uniform() < 0.1 ? -1 : 1);
        o.max_lod = G.f(max_lods);
        o.seam_fade = G.f(fades);
        const float r = dual_paraboloid_guard_scale(o);
        CHECK(within(r, RK_PARABOLOID_GUARD_MIN, 1.0f), S(r));
    });
    ADV("dual_paraboloid_auto_supersample", {
        const int cube = 1 + static_cast<int>(G.u(0u, 65535u)), half = 1 + static_cast<int>(G.u(0u, 32767u));
        const int r = dual_paraboloid_auto_supersample(cube, half, G.f(guards));
        CHECK(r >= 2 && r <= 16, std::to_string(r));
    });
    auto random_options = [&](rktest::adv::Gen& G) {
        DualParaboloidBakeOptions o;
        o.half_size = G.one_of({-2, 0, 1, 2, 4, 8, 16, 3, 6, 32770});
        o.max_lod = G.uniform() < 0.9 ? static_cast<float>(G.index(4)) * 0.75f : G.f(kAll);
        o.supersample = G.one_of({-1, 0, 1, 2, 65});
        o.seam_fade = G.uniform() < 0.5 ? 0.0f : G.f(Floats::range(0.0f, 4.0f));
        if (G.uniform() < 0.3) o.frame = rk_paraboloid_frame(G.v3(dirs), G.v3(dirs), 1.0f);
        return o;
    };
    auto options_valid = [](const DualParaboloidBakeOptions& o) {
        if (!(o.max_lod >= 0.0f && o.max_lod <= 16.0f) || o.supersample < 0 || o.supersample > 64) return false;
        const int extra = static_cast<int>(std::ceil(o.max_lod));
        return o.half_size >= 2 && o.half_size <= 32768 && o.half_size % (1 << extra) == 0 &&
               dual_paraboloid_guard_scale(o) >= 0.25f;
    };
    ADV_N("bake_dual_paraboloid_fn", 600, 1, {
        const DualParaboloidBakeOptions o = random_options(G);
        Status st;
        const DualParaboloidMap map = bake_dual_paraboloid_fn(self, o, &st);
        const bool valid = options_valid(o);
        CHECK(st.ok() == valid && (map.half_size == (valid ? o.half_size : 0)), st.message);
        CHECK(!valid || (within(map.guard_scale, 0.25f, 1.0f) && within(map.seam_band, 0.0f, 1.0f)),
              S(map.guard_scale));
        for (const EnvImage& l : map.levels) {
            for (float v : l.rgb) CHECK(within(v, -1.0f - 1e-6f, 1.0f + 1e-6f), S(v));
        }
        if (valid)
            TL.rows += 2L * o.half_size * o.half_size * (o.supersample == 0 ? 16 : o.supersample * o.supersample) - 1;
    });
    ADV_N("bake_dual_paraboloid", 1000, 1, {
        const EnvCubeMap cube = env_cube(G, 1 + static_cast<int>(G.index(3)), texels);
        const DualParaboloidBakeOptions o = random_options(G);
        Status st;
        const DualParaboloidMap map = bake_dual_paraboloid(cube, o, &st);
        CHECK(st.ok() == options_valid(o), st.message);
        const vec2 range = cube_range(cube);
        for (const EnvImage& l : map.levels) {
            for (int y = 0; y < l.height; ++y) {
                for (int x = 0; x < l.width; ++x) CHECK(in_range(l.texel(x, y), range), S(l.texel(x, y)));
            }
        }
        TL.rows += static_cast<long>(map.levels.empty() ? 0 : map.levels[0].rgb.size()) - 1;
    });
    const Floats lods = kAll.mark({0.0f, 0.5f, 1.0f, 16.0f});
    ADV_N("sample_dual_paraboloid", kRows / 20, 20, {
        DualParaboloidBakeOptions o;
        o.half_size = 4;
        o.max_lod = static_cast<float>(G.index(3));
        o.seam_fade = G.uniform() < 0.5 ? 0.0f : 1.0f;
        const bool empty = G.uniform() < 0.05;
        DualParaboloidMap map;
        if (!empty) {
            const EnvCubeMap cube = env_cube(G, 1, texels);
            o.supersample = 1;
            map = bake_dual_paraboloid(cube, o);
        }
        vec2 range(0.0f);
        if (!map.levels.empty()) range = value_range(map.levels[0].rgb);
        for (int k = 0; k < 20; ++k) {
            const vec3 r = CALL(sample_dual_paraboloid, map, G.v3(dirs), G.f(lods));
            CHECK(finite(r) && in_range(r, range) && (!empty || r == vec3(0.0f)), S(r));
        }
    });
    ADV_N("bake_paraboloid_fn", 3200, 1, {
        const int size = G.one_of({-1, 0, 1, 2, 3, 8, 65537});
        const float g = G.uniform() < 0.9 ? G.f(guards) : G.f(kAll);
        const int ss = G.one_of({-1, 0, 1, 2, 4, 65});
        const mat3 frame = G.uniform() < 0.5 ? mat3(1.0f) : rk_paraboloid_frame(G.v3(dirs), G.v3(dirs), G.f(kAny));
        Status st;
        const EnvImage img = bake_paraboloid_fn(self, size, frame, G.f(kAny), g, ss, &st);
        const bool valid =
            size >= 1 && size <= 65536 && ss >= 1 && ss <= 64 && g >= RK_PARABOLOID_GUARD_MIN && g <= 1.0f;
        CHECK(st.ok() == valid && img.width == (valid ? size : 0), st.message);
        for (float v : img.rgb) CHECK(within(v, -1.0f - 1e-6f, 1.0f + 1e-6f), S(v));
        TL.rows += static_cast<long>(img.rgb.size() / 3) * ss * ss - 1;
    });
    ADV_N("bake_paraboloid", 7000, 1, {
        const EnvCubeMap cube = env_cube(G, 1 + static_cast<int>(G.index(3)), texels);
        const int size = G.one_of({-1, 0, 1, 2, 4, 8});
        Status st;
        const EnvImage img =
            CALL(bake_paraboloid, cube, size, mat3(1.0f), G.f(kAny), G.f(guards), G.one_of({0, 1, 2}), &st);
        CHECK(st.ok() == (size >= 1), st.message);
        const vec2 range = cube_range(cube);
        for (int y = 0; y < img.height; ++y) {
            for (int x = 0; x < img.width; ++x) CHECK(in_range(img.texel(x, y), range), S(img.texel(x, y)));
        }
        TL.rows += static_cast<long>(img.rgb.size() / 3) - 1;
    });
    // sample_paraboloid: within the map's range; behind the map (|st| > 1, not the exact antipode)
    // it reads the rim. The map stores its own uv, so the sample returns the uv it read.
    const int n = 16;
    EnvImage uv_map(n, n);
    for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x)
            uv_map.set(x, y, vec3((static_cast<float>(x) + 0.5f) / n, (static_cast<float>(y) + 0.5f) / n, 0.0f));
    }
    const Floats hemi = kAny.mark({1.0f, -1.0f, 0.0f});
    const Floats inner_guards = Floats::range(RK_PARABOLOID_GUARD_MIN, 0.9f);
    ADV("sample_paraboloid", {
        const vec3 d = G.v3(dirs);
        const float h = G.f(hemi), g = G.f(inner_guards);
        const vec3 r = sample_paraboloid(uv_map, d, h, g);
        CHECK(finite(r) && in_range(r, vec2(0.0f, 1.0f)), S(r));
        const vec2 st = rk_paraboloid_encode(d, h);
        const bool behind = len(st) > 1.0;
        CHECK(!behind || std::abs(len(vec2(r.x - 0.5f, r.y - 0.5f)) - 0.5 * g) <= 1e-5, S(r));
    });
    ADV_N("cube_from_dual_paraboloid", 4500, 1, {
        DualParaboloidBakeOptions o;
        o.half_size = 2 * (1 + static_cast<int>(G.index(3)));
        o.supersample = 1;
        const DualParaboloidMap map = G.uniform() < 0.1 ? DualParaboloidMap{} : bake_dual_paraboloid_fn(self, o);
        const int size = G.one_of({1, 2, 3});
        Status st;
        const EnvCubeMap cube = CALL(cube_from_dual_paraboloid, map, size, G.one_of({1, 2}), &st);
        CHECK(st.ok() == !map.levels.empty(), st.message);
        for (const EnvImage& f : cube.faces) {
            for (float v : f.rgb) CHECK(within(v, -1.0f - 1e-6f, 1.0f + 1e-6f), S(v));
        }
        TL.rows += 6L * cube.size * cube.size - 1;
    });
    ADV("octahedral_encode", {
        const vec2 r = octahedral_encode(G.v3(dirs));
        CHECK(within(r, -1.0f, 1.0f), S(r));
    });
    const Vecs oct = Vecs::of(kAny.mark({1.0f, -1.0f, 0.0f}));
    ADV("octahedral_decode", {
        const vec3 r = octahedral_decode(G.v2(oct));
        CHECK(std::abs(len(r) - 1.0) <= 4.0 * kUlp1, S(r));
    });
    ADV_N("bake_octahedral_fn", 4000, 1, {
        const int size = G.one_of({-1, 0, 1, 2, 3, 4, 8, 65537}), ss = G.one_of({-1, 0, 1, 2, 3, 65});
        Status st;
        const OctahedralMap m = bake_octahedral_fn(size, self, ss, &st);
        const bool valid = size >= 2 && size <= 65536 && ss >= 1 && ss <= 64;
        CHECK(st.ok() == valid && m.size == (valid ? size : 0), st.message);
        for (float v : m.image.rgb) CHECK(within(v, -1.0f - 1e-6f, 1.0f + 1e-6f), S(v));
        if (valid) TL.rows += static_cast<long>(size) * size * ss * ss - 1;
    });
    ADV_N("bake_octahedral", 6000, 1, {
        const EnvCubeMap cube = env_cube(G, 1 + static_cast<int>(G.index(3)), texels);
        const int size = G.one_of({1, 2, 3, 4, 8});
        Status st;
        const OctahedralMap m = CALL(bake_octahedral, cube, size, G.one_of({0, 1, 2}), &st);
        CHECK(st.ok() == (size >= 2), st.message);
        const vec2 range = cube_range(cube);
        for (int y = 0; y < m.image.height; ++y) {
            for (int x = 0; x < m.image.width; ++x) CHECK(in_range(m.image.texel(x, y), range), S(m.image.texel(x, y)));
        }
        TL.rows += static_cast<long>(m.image.rgb.size() / 3) - 1;
    });
    ADV_N("sample_octahedral", kRows / 20, 20, {
        const OctahedralMap m =
            bake_octahedral(env_cube(G, 1 + static_cast<int>(G.index(2)), texels), 2 + static_cast<int>(G.index(4)), 1);
        const vec2 range = value_range(m.image.rgb);
        for (int k = 0; k < 20; ++k) {
            const vec3 r = sample_octahedral(m, G.v3(dirs));
            CHECK(finite(r) && in_range(r, range), S(r));
        }
    });
}

TEST(AdversarialConfigured, Default) { check_configured_functions("defaults"); }

/// Prints every sweep (inputs, time) once all tests, those of tests/parts/test_adversarial included, ran.
class SweepSummary : public ::testing::Environment {
public:
    void TearDown() override
    {
        double total = 0.0;
        long inputs = 0;
        for (const rktest::adv::Tally& t : rktest::adv::registry()) {
            std::printf("[adversarial] %-60s inputs %8ld  %6.3f s\n", t.name.c_str(), t.rows, t.seconds);
            total += t.seconds;
            inputs += t.rows;
        }
        std::printf("[adversarial] %zu sweeps, %ld inputs, %.2f s\n", rktest::adv::registry().size(), inputs, total);
    }
};
[[maybe_unused]] ::testing::Environment* const sweep_summary = ::testing::AddGlobalTestEnvironment(new SweepSummary);

}  // namespace
